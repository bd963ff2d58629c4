//! Maya materials, lights, textures and utilities in compiled scenes, against values
//! worked out by hand from Maya's conventions (no 1/π; decay I/d^rate). The shading
//! point is the origin, normal +y, seen from straight above (see `support::maya::point`).

use crate::support;

use support::maya::{assert_rgb, compile, compile_with_camera, point, run, Compiled, HalfSpace, Occluder};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";

/// Compiles `body` with one material `m` on the scene's triangle; asserts a clean build.
fn scene(body: &str) -> Compiled {
    let c = compile("", &format!("{LIBS}{body}"), &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    assert!(c.attached > 0);
    c
}

/// The colour of material `m` at `uv` with no occluders.
fn shade(c: &Compiled, uv: [f32; 2]) -> glam::Vec4 {
    run(c, &Empty::default(), c.material("m"), point(uv)).color()
}

/// A directional light shining along `dir` (normalised here).
fn directional(name: &str, shader: &str, params: &str, dir: [f32; 3]) -> String {
    let d = glam::Vec3::from_array(dir).normalize();
    format!(
        "light \"{name}\" \"{shader}\" ({params}) direction {} {} {} end light\n\
         instance \"{name}_inst\" \"{name}\" end instance\n",
        d.x, d.y, d.z
    )
}

const LAMBERT: &str = r#"
shader "lambert1" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 0.7)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lambert1.outColor") end material
"#;

#[test]
fn lambert_under_a_directional_light_is_c_d_i_cos_theta() {
    // θ = 60° from the normal: cos θ = 0.5; colour (1, 0.9, 0.8), intensity 1.5.
    let t = 60f32.to_radians();
    let light =
        directional("sun", "maya_directionallight", r#""color" 1 0.9 0.8, "intensity" 1.5"#, [-t.sin(), -t.cos(), 0.0]);
    let c = scene(&format!("{light}{LAMBERT}"));
    let k = 0.7 * 1.5 * 0.5;
    let got = shade(&c, [0.0, 0.0]);
    assert_rgb(got, [0.6 * k, 0.5 * 0.9 * k, 0.4 * 0.8 * k], 1e-5);
    assert!((got.w - 1.0).abs() < 1e-6, "opaque: alpha 1");
}

#[test]
fn adsk_names_shade_the_same() {
    let light = directional("sun", "adskMayaDirectionalLight", r#""intensity" 2"#, [0.0, -1.0, 0.0]);
    let c = scene(&format!(
        r#"{light}
        shader "lambert1" "adskMayaLambert" ("color" 0.5 0.5 0.5, "diffuse" 0.8)
        material "m" opaque "adskMayaShadingEngine" ("surfaceShader" = "lambert1.outColor") end material"#
    ));
    assert_rgb(shade(&c, [0.0, 0.0]), [0.8; 3], 1e-5);
}

#[test]
fn point_light_decay_rates() {
    // The light 2 units above: I / 2^rate.
    for rate in 0..4 {
        let c = scene(&format!(
            r#"light "pt" "maya_pointlight" ("intensity" 3, "decayRate" {rate}) origin 0 0 0 end light
            instance "pt_inst" "pt" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 -2 0 1 end instance
            {LAMBERT}"#
        ));
        let k = 0.7 * 3.0 / 2f32.powi(rate);
        assert_rgb(shade(&c, [0.0, 0.0]), [0.6 * k, 0.5 * k, 0.4 * k], 1e-5);
    }
}

#[test]
fn spot_light_cone_decay_and_dropoff() {
    // A spot 4 units above pointing down, quadratic decay: on the axis I/16; dropoff is
    // cos^d of the angle from the axis, 1 on it.
    let spot = |x: f32, extra: &str| {
        format!(
            r#"light "sp" "maya_spotlight" ("intensity" 8, "decayRate" 2, "coneAngle" 0.6981317{extra})
                origin 0 0 0 direction 0 -1 0 spread 0.9 end light
            instance "sp_inst" "sp" transform 1 0 0 0  0 1 0 0  0 0 1 0  {x} -4 0 1 end instance
            {LAMBERT}"#
        )
    };
    let c = scene(&spot(0.0, ""));
    let k = 0.7 * 8.0 / 16.0;
    assert_rgb(shade(&c, [0.0, 0.0]), [0.6 * k, 0.5 * k, 0.4 * k], 1e-5);
    // Moved 1 unit sideways: 14.04° off the axis, inside the 20° half-cone; with dropoff
    // 4 the light is (I/17)·cos⁴α, times cos θ = cos α at the point.
    let c = scene(&spot(1.0, r#", "dropoff" 4"#));
    let cos_a = 4.0 / 17f32.sqrt();
    let k = 0.7 * 8.0 / 17.0 * cos_a.powi(4) * cos_a;
    assert_rgb(shade(&c, [0.0, 0.0]), [0.6 * k, 0.5 * k, 0.4 * k], 1e-5);
    // 2 units sideways: 26.6°, outside the cone: black.
    let c = scene(&spot(2.0, ""));
    assert_rgb(shade(&c, [0.0, 0.0]), [0.0; 3], 1e-7);
}

#[test]
fn ambient_light_with_ambient_shade() {
    // ambientShade 0: light from all sides (no cosine) and no diffuse coefficient:
    // c · I; ambientShade 1: like a point light, c · I · cos θ (here the light is straight
    // above, cos θ = 1, but it is below the surface in the second case: 0).
    let amb = |shade: f32, y: f32| {
        format!(
            r#"light "amb" "maya_ambientlight" ("intensity" 0.5, "ambientShade" {shade}) origin 0 0 0 end light
            instance "amb_inst" "amb" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 {y} 0 1 end instance
            {LAMBERT}"#
        )
    };
    assert_rgb(shade(&scene(&amb(0.0, -3.0)), [0.0; 2]), [0.3, 0.25, 0.2], 1e-5);
    assert_rgb(shade(&scene(&amb(0.0, 3.0)), [0.0; 2]), [0.3, 0.25, 0.2], 1e-5);
    assert_rgb(shade(&scene(&amb(1.0, -3.0)), [0.0; 2]), [0.3, 0.25, 0.2], 1e-5);
    assert_rgb(shade(&scene(&amb(1.0, 3.0)), [0.0; 2]), [0.0; 3], 1e-6);
}

#[test]
fn emit_diffuse_and_emit_specular() {
    let light = directional("sun", "maya_directionallight", r#""emitDiffuse" off"#, [0.0, -1.0, 0.0]);
    let c = scene(&format!("{light}{LAMBERT}"));
    assert_rgb(shade(&c, [0.0, 0.0]), [0.0; 3], 1e-7);
}

#[test]
fn blinn_highlight_peak() {
    // Viewer and light on the normal: the Blinn term is specularRollOff (D = G = 1, the
    // Fresnel factor at normal incidence is the roll-off), so the colour is the lambert
    // part plus specularColor · rolloff · I.
    let light = directional("sun", "maya_directionallight", r#""intensity" 2"#, [0.0, -1.0, 0.0]);
    let c = scene(&format!(
        r#"{light}
        shader "blinn1" "maya_blinn" ("color" 0.5 0.5 0.5, "diffuse" 0.8, "specularColor" 0.4 0.3 0.2,
            "eccentricity" 0.3, "specularRollOff" 0.7, "reflectivity" 0)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "blinn1.outColor") end material"#
    ));
    let diffuse = 0.5 * 0.8 * 2.0;
    assert_rgb(
        shade(&c, [0.0, 0.0]),
        [diffuse + 0.4 * 0.7 * 2.0, diffuse + 0.3 * 0.7 * 2.0, diffuse + 0.2 * 0.7 * 2.0],
        1e-5,
    );
}

#[test]
fn phong_highlight_off_the_peak() {
    // Light 30° from the normal, viewer on it: R·L = cos 30°, highlight cos^20 30°.
    let t = 30f32.to_radians();
    let light = directional("sun", "maya_directionallight", "", [-t.sin(), -t.cos(), 0.0]);
    let c = scene(&format!(
        r#"{light}
        shader "phong1" "maya_phong" ("color" 0 0 0, "specularColor" 1 1 1, "cosinePower" 20, "reflectivity" 0)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "phong1.outColor") end material"#
    ));
    let want = t.cos().powf(20.0);
    assert_rgb(shade(&c, [0.0, 0.0]), [want; 3], 1e-5);
}

#[test]
fn light_linking_excludes_a_light() {
    // Two lights straight above; the first triangle's instance excludes the second, the
    // second triangle's has no light list.
    let lights = format!(
        "{}{}",
        directional("key", "maya_directionallight", r#""intensity" 1"#, [0.0, -1.0, 0.0]),
        directional("fill", "maya_directionallight", r#""intensity" 3"#, [0.0, -1.0, 0.0]),
    );
    let body = format!("{LIBS}{lights}{LAMBERT}");
    let c = compile("", &body, &["m", "m"], r#"light "exclusive" ["fill_inst"]"#);
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    let mut s = point([0.0, 0.0]);
    s.instance = c.linked_instance();
    let got = run(&c, &Empty::default(), c.material("m"), s).color();
    assert_rgb(got, [0.6 * 0.7, 0.5 * 0.7, 0.4 * 0.7], 1e-5);
    // An instance without a light list sees both lights.
    let mut s = point([0.0, 0.0]);
    s.instance = c.unlinked_instance();
    let got = run(&c, &Empty::default(), c.material("m"), s).color();
    assert_rgb(got, [0.6 * 2.8, 0.5 * 2.8, 0.4 * 2.8], 1e-5);
}

#[test]
fn raytraced_shadow_through_a_transparent_occluder_with_shadow_color() {
    // The occluder lets half the light through (transparency 0.5); the light's
    // shadowColor 0.2 fills the rest: received = 0.5 + 0.5 · 0.2 = 0.6 of the light.
    let light = directional(
        "sun",
        "maya_directionallight",
        r#""useRayTraceShadows" on, "shadowColor" 0.2 0.2 0.2"#,
        [0.0, -1.0, 0.0],
    );
    let body = format!(
        r#"{LIBS}{light}{LAMBERT}
        shader "glass" "maya_lambert" ("transparency" 0.5 0.5 0.5)
        material "g" "maya_shadingengine" ("surfaceShader" = "glass.outColor")
            shadow "maya_shadingengine" ("surfaceShader" = "glass.outColor") end material"#
    );
    let c = compile("", &body, &["m", "g"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    let tracer = Occluder { material: c.material_index("g") };
    let got = run(&c, &tracer, c.material("m"), point([0.0, 0.0])).color();
    assert_rgb(got, [0.6 * 0.7 * 0.6, 0.5 * 0.7 * 0.6, 0.4 * 0.7 * 0.6], 1e-5);
}

/// A 2×2 texture: bottom row red, green; top row blue, white.
const QUAD: &str = r#"color texture "quad" [ 2 2 ] 'ff0000' '00ff00' '0000ff' 'ffffff'"#;

fn file_scene(placement: &str) -> Compiled {
    scene(&format!(
        r#"{QUAD}
        shader "place" "maya_place2dtexture" ({placement})
        shader "file1" "maya_file" ("fileTextureName" "quad", "uvCoord" = "place.outUV")
        shader "flat" "maya_surfaceshader" ("outColor" = "file1.outColor")
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material"#
    ))
}

const RED: [f32; 3] = [1.0, 0.0, 0.0];
const GREEN: [f32; 3] = [0.0, 1.0, 0.0];
const BLUE: [f32; 3] = [0.0, 0.0, 1.0];
const WHITE: [f32; 3] = [1.0, 1.0, 1.0];

#[test]
fn file_lookups_through_place2d_repeat_offset_rotate() {
    let tol = 1e-3;
    let plain = file_scene(r#""repeatU" 1"#);
    assert_rgb(shade(&plain, [0.25, 0.25]), RED, tol);
    assert_rgb(shade(&plain, [0.75, 0.25]), GREEN, tol);
    assert_rgb(shade(&plain, [0.25, 0.75]), BLUE, tol);
    // Repeat 2: (0.375, 0.125) → (0.75, 0.25); (0.625, 0.125) → (1.25, 0.25) ≡ (0.25, 0.25).
    let rep = file_scene(r#""repeatU" 2, "repeatV" 2"#);
    assert_rgb(shade(&rep, [0.375, 0.125]), GREEN, tol);
    assert_rgb(shade(&rep, [0.625, 0.125]), RED, tol);
    assert_rgb(shade(&rep, [0.625, 0.375]), BLUE, tol);
    // Offset 0.5 in u: (0.25, 0.25) → (0.75, 0.25).
    let off = file_scene(r#""offsetU" 0.5"#);
    assert_rgb(shade(&off, [0.25, 0.25]), GREEN, tol);
    // rotateUV 90°: (0.25, 0.25) → (0.25, 0.75); (0.75, 0.75) → (0.75, 0.25).
    let rot = file_scene(r#""rotateUV" 1.5707964"#);
    assert_rgb(shade(&rot, [0.25, 0.25]), BLUE, tol);
    assert_rgb(shade(&rot, [0.75, 0.75]), GREEN, tol);
    assert_rgb(shade(&rot, [0.75, 0.25]), RED, tol);
    // Coverage 0.5 without wrap: outside the frame the file's default colour (0.5 grey).
    let cov = file_scene(r#""coverageU" 0.5, "coverageV" 0.5, "wrapU" off, "wrapV" off"#);
    assert_rgb(shade(&cov, [0.75, 0.25]), [0.5; 3], tol);
    assert_rgb(shade(&cov, [0.375, 0.375]), WHITE, tol);
}

#[test]
fn file_colour_balance() {
    let c = scene(&format!(
        r#"{QUAD}
        shader "file1" "maya_file" ("fileTextureName" "quad", "colorGain" 0.5 0.5 0.5, "colorOffset" 0.1 0.2 0.3,
            "invert" on)
        shader "flat" "maya_surfaceshader" ("outColor" = "file1.outColor")
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material"#
    ));
    // Red inverted is cyan: (0, 1, 1) · 0.5 + offset.
    assert_rgb(shade(&c, [0.25, 0.25]), [0.1, 0.7, 0.8], 1e-3);
}

#[test]
fn checker_and_utilities_feed_a_lambert() {
    // color = multiplyDivide(checker / 2); under a light of intensity 1 straight above
    // with diffuse 1: checker colour1 (0.8, 0.6, 0.4) halves.
    let light = directional("sun", "maya_directionallight", "", [0.0, -1.0, 0.0]);
    let c = scene(&format!(
        r#"{light}
        shader "chk" "maya_checker" ("color1" 0.8 0.6 0.4, "color2" 0.2 0.2 0.2)
        shader "md" "maya_multiplydivide" ("operation" 2, "input1" = "chk.outColor", "input2" 2 2 2)
        shader "lam" "maya_lambert" ("color" = "md.output", "diffuse" 1)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#
    ));
    assert_rgb(shade(&c, [0.25, 0.25]), [0.4, 0.3, 0.2], 1e-5);
    assert_rgb(shade(&c, [0.75, 0.25]), [0.1, 0.1, 0.1], 1e-5);
    assert_rgb(shade(&c, [0.75, 0.75]), [0.4, 0.3, 0.2], 1e-5);
}

#[test]
fn condition_set_range_and_remap_value_in_a_graph() {
    // facing ratio 1 (seen head-on) → setRange [0,1]→[0.2,0.4] = 0.4 → condition
    // (0.4 > 0.3) picks colorIfTrue; remapValue maps 0.4 through a curve 0→0, 1→0.5.
    let c = scene(
        r#"
        shader "si" "maya_samplerinfo" ()
        shader "sr" "maya_setrange" ("value" = "si.facingRatio", "min" 0.2 0.2 0.2, "max" 0.4 0.4 0.4,
            "oldMax" 1 1 1)
        shader "cond" "maya_condition" ("operation" 2, "firstTerm" = "sr.outValue", "secondTerm" 0.3,
            "colorIfTrue" 0 1 0, "colorIfFalse" 1 0 0)
        shader "rv" "maya_remapvalue" ("inputValue" = "sr.outValue",
            "value" [ { "value_Position" 0, "value_FloatValue" 0, "value_Interp" 1 },
                      { "value_Position" 1, "value_FloatValue" 0.5, "value_Interp" 1 } ])
        shader "blend" "maya_blendcolors" ("color1" = "cond.outColor", "color2" 0 0 1, "blender" = "rv.outValue")
        shader "flat" "maya_surfaceshader" ("outColor" = "blend.output")
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material"#,
    );
    // blender = 0.4 · 0.5 = 0.2: 0.2 · green + 0.8 · blue.
    assert_rgb(shade(&c, [0.0, 0.0]), [0.0, 0.2, 0.8], 1e-5);
}

/// Spline and the ramp texture's exponential interpolations through the shader graph:
/// remapValue's curve (0, 0), (0.5, 1), (1, 0.25), all spline, at 0.4 is the Catmull-Rom
/// Hermite cubic with slopes (1 − 0)/(0.5 − (−0.5)) = 1 at the first knot (a phantom knot
/// at −0.5 holding 0) and (0.25 − 0)/(1 − 0) at ½ (τ = 0.8: h10 = 0.032, h01 = 0.896,
/// h11 = −0.128: 0.5 · 1 · 0.032 + 0.896 · 1 + 0.5 · 0.25 · (−0.128) = 0.896); a U ramp from black to white with
/// exponential up (2) at u = 0.4 is 0.4² = 0.16, exponential down (3) 1 − 0.6² = 0.64
/// (1e-5).
#[test]
fn spline_and_exponential_interpolations_in_a_graph() {
    let c = scene(
        r#"
        shader "si" "maya_samplerinfo" ()
        shader "sr" "maya_setrange" ("value" = "si.facingRatio", "min" 0.4 0.4 0.4, "max" 0.4 0.4 0.4,
            "oldMax" 1 1 1)
        shader "rv" "maya_remapvalue" ("inputValue" = "sr.outValue",
            "value" [ { "value_Position" 0, "value_FloatValue" 0, "value_Interp" 3 },
                      { "value_Position" 0.5, "value_FloatValue" 1, "value_Interp" 3 },
                      { "value_Position" 1, "value_FloatValue" 0.25, "value_Interp" 3 } ])
        shader "blend" "maya_blendcolors" ("color1" 0 1 0, "color2" 0 0 1, "blender" = "rv.outValue")
        shader "flat" "maya_surfaceshader" ("outColor" = "blend.output")
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material"#,
    );
    assert_rgb(shade(&c, [0.0, 0.0]), [0.0, 0.896, 0.104], 1e-5);
    for (mode, want) in [(2, 0.16f32), (3, 0.64)] {
        let c = scene(&format!(
            r#"
            shader "rmp" "maya_ramp" ("type" 1, "interpolation" {mode},
                "colorEntryList" [ {{ "position" 0, "color" 0 0 0 }}, {{ "position" 1, "color" 1 1 1 }} ])
            shader "flat" "maya_surfaceshader" ("outColor" = "rmp.outColor")
            material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material"#
        ));
        assert_rgb(shade(&c, [0.4, 0.5]), [want; 3], 1e-5);
    }
}

#[test]
fn bump2d_tilts_the_normal_against_the_slope() {
    // A ramp in u (0 → 1 across the tile) as the bump height with depth 0.1: dh/du = 1,
    // dP/du = +x, so the normal is (−0.1, 1, 0) normalised; a directional light from
    // straight above then gives cos θ = 1/√1.01.
    let light = directional("sun", "maya_directionallight", "", [0.0, -1.0, 0.0]);
    let c = scene(&format!(
        r#"{light}
        shader "rmp" "maya_ramp" ("type" 1, "interpolation" 1,
            "colorEntryList" [ {{ "position" 0, "color" 0 0 0 }}, {{ "position" 1, "color" 1 1 1 }} ])
        shader "lum" "maya_luminance" ("value" = "rmp.outColor")
        shader "bmp" "maya_bump2d" ("bumpValue" = "lum.outValue", "bumpDepth" 0.1)
        shader "lam" "maya_lambert" ("color" 1 1 1, "diffuse" 1, "normalCamera" = "bmp.outNormal")
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#
    ));
    let want = 1.0 / 1.01f32.sqrt();
    assert_rgb(shade(&c, [0.4, 0.5]), [want; 3], 2e-4);
}

#[test]
fn transparency_blends_with_what_lies_behind_and_sets_alpha() {
    // Nothing behind (transparent black): out = c·d·I·(1 − T), alpha 1 − T.
    let light = directional("sun", "maya_directionallight", "", [0.0, -1.0, 0.0]);
    let c = scene(&format!(
        r#"{light}
        shader "lam" "maya_lambert" ("color" 1 1 1, "diffuse" 1, "transparency" 0.25 0.25 0.25)
        material "m" "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#
    ));
    let got = shade(&c, [0.0, 0.0]);
    assert_rgb(got, [0.75; 3], 1e-5);
    assert!((got.w - 0.75).abs() < 1e-5, "alpha {}", got.w);
}

#[test]
fn use_background_shows_the_background_and_catches_a_shadow() {
    // Background (the camera's environment) (0.2, 0.4, 0.6); shadowMask 0.8. Unshadowed:
    // the background, alpha 0. Behind an opaque occluder (no shadow shader): the
    // background darkened by 0.8, alpha 0.8.
    let light = directional("sun", "maya_directionallight", "", [0.0, -1.0, 0.0]);
    let body = format!(
        r#"{LIBS}{light}
        shader "bg" "maya_usebackground" ("shadowMask" 0.8, "reflectivity" 0)
        material "m" "maya_shadingengine" ("surfaceShader" = "bg.outColor") end material
        shader "lam" "maya_lambert" ()
        material "blocker" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#
    );
    let camera = r#"environment "maya_surfaceshader" ("outColor" 0.2 0.4 0.6)"#;
    let c = compile_with_camera(camera, "", &body, &["m", "blocker"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    let clear = run(&c, &Empty::default(), c.material("m"), point([0.0, 0.0])).color();
    assert_rgb(clear, [0.2, 0.4, 0.6], 1e-5);
    assert!(clear.w.abs() < 1e-6, "alpha {}", clear.w);
    let tracer = Occluder { material: c.material_index("blocker") };
    let shadowed = run(&c, &tracer, c.material("m"), point([0.0, 0.0])).color();
    assert_rgb(shadowed, [0.04, 0.08, 0.12], 1e-5);
    assert!((shadowed.w - 0.8).abs() < 1e-5, "alpha {}", shadowed.w);
}

/// The lambert's colour under `light` (with its instance) where shadow rays towards +x
/// are blocked by an opaque occluder.
fn half_shadowed(light: &str) -> glam::Vec4 {
    let body = format!(
        r#"{LIBS}{light}{LAMBERT}
        shader "lam2" "maya_lambert" ()
        material "blocker" opaque "maya_shadingengine" ("surfaceShader" = "lam2.outColor") end material"#
    );
    let c = compile("", &body, &["m", "blocker"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    let tracer = HalfSpace { material: c.material_index("blocker") };
    run(&c, &tracer, c.material("m"), point([0.0, 0.0])).color()
}

#[test]
fn soft_shadows_from_light_radius_and_light_angle() {
    let lit = [0.6 * 0.7, 0.5 * 0.7, 0.4 * 0.7];
    let point_light = |radius: f32| {
        format!(
            r#"light "pt" "maya_pointlight" ("useRayTraceShadows" on, "shadowRays" 64, "lightRadius" {radius})
                origin 0 0 0 end light
            instance "pt_inst" "pt" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 -2 0 1 end instance
            "#
        )
    };
    // A hard shadow ray goes straight up (x = 0): not blocked.
    assert_rgb(half_shadowed(&point_light(0.0)), lit, 1e-5);
    // A sphere of radius 1 seen from below: the rays to its +x half are blocked.
    let soft = half_shadowed(&point_light(1.0));
    assert_rgb(soft, lit.map(|v| 0.5 * v), 0.03 * lit[0]);
    // A directional light of angular diameter 10°: half its cone is blocked.
    let sun = directional(
        "sun",
        "maya_directionallight",
        r#""useRayTraceShadows" on, "shadowRays" 64, "lightAngle" 0.17453"#,
        [0.0, -1.0, 0.0],
    );
    assert_rgb(half_shadowed(&sun), lit.map(|v| 0.5 * v), 0.03 * lit[0]);
}

#[test]
fn area_light_averages_both_cosines_over_its_rectangle() {
    // A 1 × 1 light 2 units above, facing down (its local −z), 8 × 8 samples: the mean
    // over the rectangle of cos θ_surface · cos θ_light = h² / r².
    let c = scene(&format!(
        r#"light "area" "maya_arealight" ("intensity" 1)
            origin 0 0 0
            rectangle 1 0 0 0 1 0 8 8
        end light
        instance "area_inst" "area" transform 1 0 0 0  0 0 1 0  0 -1 0 0  0 0 -2 1 end instance
        {LAMBERT}"#
    ));
    let n = 400;
    let mut mean = 0.0f64;
    for i in 0..n {
        for j in 0..n {
            let (x, z) = ((i as f64 + 0.5) / n as f64 - 0.5, (j as f64 + 0.5) / n as f64 - 0.5);
            mean += 4.0 / (4.0 + x * x + z * z);
        }
    }
    let k = 0.7 * (mean / (n * n) as f64) as f32;
    assert_rgb(shade(&c, [0.0, 0.0]), [0.6 * k, 0.5 * k, 0.4 * k], 2e-3);
}

#[test]
fn cut_away_opacity_removes_nearly_transparent_surfaces() {
    // Transparency 0.8 (opacity 0.2) under a unit light: kept with cutAwayOpacity 0.1
    // (c·(1 − T) = 0.2, alpha 0.2 over nothing), cut away with 0.5 (what lies behind:
    // nothing, transparent black).
    let light = directional("sun", "maya_directionallight", "", [0.0, -1.0, 0.0]);
    let with_cut = |cut: f32| {
        let c = scene(&format!(
            r#"{light}
            shader "lam" "maya_lambert" ("color" 1 1 1, "diffuse" 1, "transparency" 0.8 0.8 0.8)
            material "m" "maya_shadingengine" ("surfaceShader" = "lam.outColor", "cutAwayOpacity" {cut}) end material"#
        ));
        shade(&c, [0.0, 0.0])
    };
    let kept = with_cut(0.1);
    assert_rgb(kept, [0.2; 3], 1e-5);
    assert!((kept.w - 0.2).abs() < 1e-5);
    let cut = with_cut(0.5);
    assert_rgb(cut, [0.0; 3], 1e-7);
    assert!(cut.w.abs() < 1e-7);
}

#[test]
fn maya_shadow_filters_by_the_material_transparency() {
    // The occluder's shadow shader is maya_shadow on a material of transparency
    // (0.5, 0.25, 1): the light arrives filtered per channel.
    let light = directional("sun", "maya_directionallight", r#""useRayTraceShadows" on"#, [0.0, -1.0, 0.0]);
    let body = format!(
        r#"{LIBS}{light}{LAMBERT}
        shader "tinted" "maya_lambert" ("transparency" 0.5 0.25 1)
        material "g" "maya_shadingengine" ("surfaceShader" = "tinted.outColor")
            shadow "maya_shadow" ("surfaceShader" = "tinted.outColor") end material"#
    );
    let c = compile("", &body, &["m", "g"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    let tracer = Occluder { material: c.material_index("g") };
    let got = run(&c, &tracer, c.material("m"), point([0.0, 0.0])).color();
    assert_rgb(got, [0.6 * 0.7 * 0.5, 0.5 * 0.7 * 0.25, 0.4 * 0.7], 1e-5);
}

#[test]
fn layered_texture_blends_a_connected_layer_over_a_constant_one() {
    // A half-transparent checker (red / blue) over opaque grey.
    let c = scene(
        r#"
        shader "chk" "maya_checker" ("color1" 1 0 0, "color2" 0 0 1)
        shader "lt" "maya_layeredtexture" ("inputs" [
            { "color" = "chk.outColor", "alpha" 0.5, "blendMode" 1, "isVisible" on },
            { "color" 0.5 0.5 0.5, "alpha" 1, "blendMode" 1, "isVisible" on },
            { "color" 0 1 0, "alpha" 1, "blendMode" 0, "isVisible" off } ])
        shader "flat" "maya_surfaceshader" ("outColor" = "lt.outColor")
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material"#,
    );
    assert_rgb(shade(&c, [0.25, 0.25]), [0.75, 0.25, 0.25], 1e-5);
    assert_rgb(shade(&c, [0.75, 0.25]), [0.25, 0.25, 0.75], 1e-5);
}

#[test]
fn declared_plug_in_materials_get_a_stand_in_of_their_colour() {
    // Two plug-in shaders the scene declares but mira cannot run: one behind a shading
    // engine (struct result), one as a material's shader (colour result). Under a unit
    // light straight above each shows its colour parameter, with a warning naming it.
    let light = directional("sun", "maya_directionallight", "", [0.0, -1.0, 0.0]);
    let body = format!(
        r#"{LIBS}{light}
        declare shader struct {{ color "outColor", color "outTransparency" }} "vendorMaterial" (
            scalar "rough", color "baseColor") end declare
        declare shader color "vendor_mtl" (color "Diffuse_Color", scalar "gloss") end declare
        shader "vm" "vendorMaterial" ("baseColor" 0.8 0.2 0.1, "rough" 0.3)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "vm.outColor") end material
        material "v" opaque "vendor_mtl" ("Diffuse_Color" 0.1 0.5 0.3) end material"#
    );
    let mut c = compile("", &body, &["m", "v"], "");
    let warnings = maya::standin::attach_stand_ins(&mut c.shading);
    let text: Vec<String> = warnings.iter().map(|d| d.message.clone()).collect();
    assert_eq!(text.len(), 2, "{text:?}");
    assert!(text.iter().any(|w| w.contains("'vendorMaterial'") && w.contains("'baseColor'")), "{text:?}");
    assert!(text.iter().any(|w| w.contains("'vendor_mtl'") && w.contains("'Diffuse_Color'")), "{text:?}");
    assert_rgb(shade(&c, [0.0, 0.0]), [0.8, 0.2, 0.1], 1e-5);
    let v = run(&c, &Empty::default(), c.material("v"), point([0.0, 0.0])).color();
    assert_rgb(v, [0.1, 0.5, 0.3], 1e-5);
}

#[test]
fn remap_color_maps_each_channel_through_its_curve() {
    // Red through 0→0, 1→0.5; green through a step (interp none) 0→0.2, 0.5→0.9; blue
    // unmapped; output range [0, 2].
    let c = scene(
        r#"
        shader "rc" "maya_remapcolor" ("color" 0.4 0.7 0.25, "outputMax" 2,
            "red" [ { "red_Position" 0, "red_FloatValue" 0, "red_Interp" 1 },
                    { "red_Position" 1, "red_FloatValue" 0.5, "red_Interp" 1 } ],
            "green" [ { "green_Position" 0, "green_FloatValue" 0.2, "green_Interp" 0 },
                      { "green_Position" 0.5, "green_FloatValue" 0.9, "green_Interp" 0 } ])
        shader "flat" "maya_surfaceshader" ("outColor" = "rc.outColor")
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material"#,
    );
    assert_rgb(shade(&c, [0.0, 0.0]), [0.4, 1.8, 0.5], 1e-5);
}
