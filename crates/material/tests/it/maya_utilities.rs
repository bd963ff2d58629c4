//! Maya utilities, the grid texture, the file texture's alpha balance and the materials'
//! `ambientColor` in compiled scenes under both name families, each against the node
//! reference's documented behaviour (closed forms, 1e-5). The shading point is the world
//! origin, normal +y, seen from straight above, at the uv given to
//! `support::maya::point`.

use crate::support;

use support::maya::{assert_rgb, compile, point, run};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";

/// The colour of material "m" whose surfaceShader (of the family `adsk` names) shows
/// `member` of the shader "u" that `shaders` declare, at `uv`.
fn shows(shaders: &str, member: &str, adsk: bool, uv: [f32; 2]) -> glam::Vec4 {
    let (surface, engine) = if adsk {
        ("adskMayaSurfaceShader", "adskMayaShadingEngine")
    } else {
        ("maya_surfaceshader", "maya_shadingengine")
    };
    let c = compile(
        "",
        &format!(
            r#"{LIBS}{shaders}
            shader "flat" "{surface}" ("outColor" = "u.{member}")
            material "m" opaque "{engine}" ("surfaceShader" = "flat.outColor") end material"#
        ),
        &["m"],
        "",
    );
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    run(&c, &Empty::default(), c.material("m"), point(uv)).color()
}

fn name(adsk: bool, maya: &str, camel: &str) -> String {
    if adsk {
        format!("adskMaya{camel}")
    } else {
        format!("maya_{maya}")
    }
}

/// reverse is 1 − input; gammaCorrect value^(1/gamma) per channel; vectorProduct's dot
/// product (in every channel), cross product and normalised output.
#[test]
fn reverse_gamma_correct_and_vector_product() {
    for adsk in [false, true] {
        let rev = name(adsk, "reverse", "Reverse");
        assert_rgb(
            shows(&format!(r#"shader "u" "{rev}" ("input" 0.2 0.5 1.25)"#), "output", adsk, [0.3, 0.6]),
            [0.8, 0.5, -0.25],
            1e-6,
        );
        let gc = name(adsk, "gammacorrect", "GammaCorrect");
        let g = shows(
            &format!(r#"shader "u" "{gc}" ("value" 0.25 0.5 0.64, "gamma" 2 1 0.5)"#),
            "outValue",
            adsk,
            [0.3, 0.6],
        );
        assert_rgb(g, [0.5, 0.5, 0.4096], 1e-5);
        let vp = name(adsk, "vectorproduct", "VectorProduct");
        let dot = format!(r#"shader "u" "{vp}" ("operation" 1, "input1" 1 2 3, "input2" 0.5 0.25 0.1)"#);
        assert_rgb(shows(&dot, "output", adsk, [0.3, 0.6]), [1.3; 3], 1e-5);
        let cross = format!(r#"shader "u" "{vp}" ("operation" 2, "input1" 1 0 0, "input2" 0 1 0)"#);
        assert_rgb(shows(&cross, "output", adsk, [0.3, 0.6]), [0.0, 0.0, 1.0], 1e-6);
        let unit =
            format!(r#"shader "u" "{vp}" ("operation" 2, "input1" 2 0 0, "input2" 0 0 3, "normalizeOutput" on)"#);
        assert_rgb(shows(&unit, "output", adsk, [0.3, 0.6]), [0.0, -1.0, 0.0], 1e-6);
    }
}

/// samplerInfo's `uvCoord` is the hit's first texture coordinate (z 0) and `pointWorld`
/// the hit point (the origin here); `facingRatio` 1 seen head-on feeds a blendColors to
/// its first colour.
#[test]
fn sampler_info_gives_the_hit_facts() {
    for adsk in [false, true] {
        let si = name(adsk, "samplerinfo", "SamplerInfo");
        assert_rgb(shows(&format!(r#"shader "u" "{si}" ()"#), "uvCoord", adsk, [0.3, 0.6]), [0.3, 0.6, 0.0], 1e-6);
        assert_rgb(shows(&format!(r#"shader "u" "{si}" ()"#), "pointWorld", adsk, [0.3, 0.6]), [0.0; 3], 1e-6);
        let bc = name(adsk, "blendcolors", "BlendColors");
        let blend = format!(
            r#"shader "si" "{si}" ()
            shader "u" "{bc}" ("blender" = "si.facingRatio", "color1" 0.9 0.1 0.2, "color2" 0 0 1)"#
        );
        assert_rgb(shows(&blend, "output", adsk, [0.3, 0.6]), [0.9, 0.1, 0.2], 1e-6);
    }
}

/// Grid: `lineColor` on lines `uWidth`/`vWidth` wide centred on the tile's edges,
/// `fillerColor` between (contrast 1).
#[test]
fn grid_draws_lines_on_the_tile_edges() {
    for adsk in [false, true] {
        let g = name(adsk, "grid", "Grid");
        let tex = format!(
            r#"shader "u" "{g}" ("lineColor" 0.9 0.8 0.7, "fillerColor" 0.1 0.2 0.3, "uWidth" 0.2, "vWidth" 0.1)"#
        );
        assert_rgb(shows(&tex, "outColor", adsk, [0.5, 0.5]), [0.1, 0.2, 0.3], 1e-6);
        assert_rgb(shows(&tex, "outColor", adsk, [0.05, 0.5]), [0.9, 0.8, 0.7], 1e-6);
        assert_rgb(shows(&tex, "outColor", adsk, [0.5, 0.97]), [0.9, 0.8, 0.7], 1e-6);
        // 0.12 from the left edge is past half the u line (0.1) but within no v line.
        assert_rgb(shows(&tex, "outColor", adsk, [0.12, 0.5]), [0.1, 0.2, 0.3], 1e-6);
    }
}

/// A file texture's colour balance: `outColor` = c ⊙ `colorGain` + `colorOffset`, and
/// `outAlpha` = α·`alphaGain` + `alphaOffset` (a colour image's α is 1; `invert` first
/// turns it into 1 − α), read through a blendColors whose blender is the alpha.
#[test]
fn file_colour_and_alpha_balance() {
    let image = r#"color texture "quad" [ 2 2 ] 'ff0000' '00ff00' '0000ff' 'ffffff'"#;
    for adsk in [false, true] {
        let file = name(adsk, "file", "File");
        let bc = name(adsk, "blendcolors", "BlendColors");
        let colour = |params: &str| {
            let shaders = format!(
                r#"{image}
                shader "u" "{file}" ("fileTextureName" "quad"{params})"#
            );
            shows(&shaders, "outColor", adsk, [0.25, 0.25])
        };
        assert_rgb(colour(""), [1.0, 0.0, 0.0], 1e-3);
        assert_rgb(colour(r#", "colorGain" 0.5 0.5 0.5, "colorOffset" 0.1 0.1 0.1"#), [0.6, 0.1, 0.1], 1e-3);
        let alpha = |params: &str| {
            let shaders = format!(
                r#"{image}
                shader "f" "{file}" ("fileTextureName" "quad"{params})
                shader "u" "{bc}" ("blender" = "f.outAlpha", "color1" 1 1 1, "color2" 0 0 0)"#
            );
            shows(&shaders, "output", adsk, [0.25, 0.25])
        };
        assert_rgb(alpha(""), [1.0; 3], 1e-5);
        assert_rgb(alpha(r#", "alphaGain" 0.5, "alphaOffset" 0.1"#), [0.6; 3], 1e-5);
        assert_rgb(alpha(r#", "alphaGain" 0.5, "alphaOffset" 0.1, "invert" on"#), [0.1; 3], 1e-5);
    }
}

/// A lambert's `ambientColor` a adds c ⊙ a whatever the lights (none here: exactly
/// c ⊙ a), and with a unit light straight above c ⊙ (a + d).
#[test]
fn ambient_color_adds_the_colour_times_itself_without_lights() {
    let sun = r#"light "sun" "maya_directionallight" ("intensity" 1) direction 0 -1 0 end light
        instance "sun_inst" "sun" end instance"#;
    for adsk in [false, true] {
        let lambert = name(adsk, "lambert", "Lambert");
        for (lights, want) in [("", [0.12, 0.1, 0.04]), (sun, [0.12 + 0.36, 0.1 + 0.3, 0.04 + 0.24])] {
            let engine = if adsk { "adskMayaShadingEngine" } else { "maya_shadingengine" };
            let c = compile(
                "",
                &format!(
                    r#"{LIBS}{lights}
                    shader "lam" "{lambert}" ("color" 0.6 0.5 0.4, "diffuse" 0.6, "ambientColor" 0.2 0.2 0.1)
                    material "m" opaque "{engine}" ("surfaceShader" = "lam.outColor") end material"#
                ),
                &["m"],
                "",
            );
            assert!(c.messages.is_empty(), "{:#?}", c.messages);
            assert_rgb(run(&c, &Empty::default(), c.material("m"), point([0.3, 0.6])).color(), want, 1e-5);
        }
    }
}

/// rgbToHsv: red is (0°, 1, 1), teal (180°, 1, ½); hsvToRgb turns (120°, 1, ½) into
/// green at ½.
#[test]
fn rgb_to_hsv_and_back() {
    for adsk in [false, true] {
        let to_hsv = name(adsk, "rgbtohsv", "RgbToHsv");
        assert_rgb(
            shows(&format!(r#"shader "u" "{to_hsv}" ("inRgb" 1 0 0)"#), "outHsv", adsk, [0.3, 0.6]),
            [0.0, 1.0, 1.0],
            1e-5,
        );
        assert_rgb(
            shows(&format!(r#"shader "u" "{to_hsv}" ("inRgb" 0 0.5 0.5)"#), "outHsv", adsk, [0.3, 0.6]),
            [180.0, 1.0, 0.5],
            1e-4,
        );
        let to_rgb = name(adsk, "hsvtorgb", "HsvToRgb");
        assert_rgb(
            shows(&format!(r#"shader "u" "{to_rgb}" ("inHsv" 120 1 0.5)"#), "outRgb", adsk, [0.3, 0.6]),
            [0.0, 0.5, 0.0],
            1e-5,
        );
    }
}

/// samplerInfo's `rayDirection` is the eye ray's direction in world space (straight
/// down here).
#[test]
fn sampler_info_ray_direction() {
    for adsk in [false, true] {
        let si = name(adsk, "samplerinfo", "SamplerInfo");
        assert_rgb(
            shows(&format!(r#"shader "u" "{si}" ()"#), "rayDirection", adsk, [0.3, 0.6]),
            [0.0, -1.0, 0.0],
            1e-6,
        );
    }
}

/// Translucence t lets a light behind the surface through as c·t·I·|cos θ| · K (a unit
/// light straight below a lambert of translucence 0.5 seen from straight above, along the
/// light's straight-through direction), none without it: K = 1 for `translucenceFocus`
/// 0 (diffuse translucence, c·0.5), K = (n + 2)/2 = 2 for the default focus 0.5 (n = 2:
/// c·1), within 1e-5.
#[test]
fn translucence_passes_light_from_behind() {
    let below = r#"light "sun" "maya_directionallight" ("intensity" 1) direction 0 1 0 end light
        instance "sun_inst" "sun" end instance"#;
    for adsk in [false, true] {
        let lambert = name(adsk, "lambert", "Lambert");
        let engine = if adsk { "adskMayaShadingEngine" } else { "maya_shadingengine" };
        for (t, focus, want) in
            [(0.5, "0", [0.3, 0.25, 0.2]), (0.5, "0.5", [0.6, 0.5, 0.4]), (0.0, "0", [0.0; 3]), (0.0, "0.5", [0.0; 3])]
        {
            let c = compile(
                "",
                &format!(
                    r#"{LIBS}{below}
                    shader "lam" "{lambert}" ("color" 0.6 0.5 0.4, "translucence" {t}, "translucenceFocus" {focus})
                    material "m" opaque "{engine}" ("surfaceShader" = "lam.outColor") end material"#
                ),
                &["m"],
                "",
            );
            assert!(c.messages.is_empty(), "{:#?}", c.messages);
            assert_rgb(run(&c, &Empty::default(), c.material("m"), point([0.3, 0.6])).color(), want, 1e-5);
        }
    }
}

/// A file texture placed by a place2dTexture (repeat 2 × 3, offset, rotate UV 90°) on a
/// lambert's colour: the path engine's translation reads the same colour per hit as the
/// classic shader (1e-5) at points of different quadrants of the image.
#[test]
fn the_path_engine_reads_a_placed_file_texture_per_hit() {
    let sun = r#"light "sun" "maya_directionallight" ("intensity" 1) direction 0 -1 0 end light
        instance "sun_inst" "sun" end instance"#;
    let c = compile(
        "",
        &format!(
            r#"{LIBS}{sun}
            color texture "quad" [ 2 2 ] 'ff0000' '00ff00' '0000ff' 'ffffff'
            shader "place" "maya_place2dtexture" ("repeatU" 2, "repeatV" 3, "offsetU" 0.1, "offsetV" 0.2, "rotateUV" 1.5707963)
            shader "f" "maya_file" ("fileTextureName" "quad", "uvCoord" = "place.outUV")
            shader "lam" "maya_lambert" ("color" = "f.outColor", "diffuse" 0.5)
            material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#
        ),
        &["m"],
        "",
    );
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    let (s, warnings) = material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("Maya");
    assert!(warnings.is_empty(), "{warnings:?}");
    let tracer = Empty::default();
    let mut seen = Vec::new();
    for uv in [[0.05, 0.05], [0.3, 0.6], [0.7, 0.2], [0.9, 0.85], [0.45, 0.4]] {
        let mut ctx = shader::Ctx::new(&c.shading, &tracer, point(uv));
        let hit = s.at(&mut ctx);
        let classic = run(&c, &tracer, c.material("m"), point(uv)).color();
        for i in 0..3 {
            assert!((hit.diffuse[i] - classic[i]).abs() < 1e-5, "{uv:?}: path {} classic {classic}", hit.diffuse);
        }
        seen.push(classic);
    }
    // The placement moves the lookup across the image's texels: not one colour everywhere.
    assert!(seen.iter().any(|c| (*c - seen[0]).abs().max_element() > 0.1), "{seen:?}");
}

/// Shadow shaders under both names: an occluder whose shadow shader is `maya_shadow` /
/// `adskMayaShadow` over a material of transparency (0.5, 0.25, 1) filters a unit light
/// per channel, through `surfaceShader` or (older translators' form) `transparency`
/// connected to the material's `outTransparency`; one whose shadow shader is
/// `maya_transparent` / `adskMayaTransparent`
/// (particles' shadow) lets it all through, whatever the material's transparency (1e-5).
#[test]
fn shadow_shaders_filter_or_pass_the_light() {
    let light = r#"light "sun" "maya_directionallight" ("intensity" 1, "useRayTraceShadows" on) direction 0 -1 0 end light
        instance "sun_inst" "sun" end instance"#;
    for adsk in [false, true] {
        let (shadow, transparent) =
            if adsk { ("adskMayaShadow", "adskMayaTransparent") } else { ("maya_shadow", "maya_transparent") };
        for (shader, params, want) in [
            (shadow, r#""surfaceShader" = "occ.outColor""#, [0.6 * 0.5, 0.5 * 0.25, 0.4]),
            // The older translators' form (mrLiquid's): the material's transparency by member.
            (
                shadow,
                r#""transparency" = "occ.outTransparency", "shadowAttenuation" 0.5, "translucenceDepth" 1"#,
                [0.6 * 0.5, 0.5 * 0.25, 0.4],
            ),
            (transparent, "", [0.6, 0.5, 0.4]),
        ] {
            let c = compile(
                "",
                &format!(
                    r#"{LIBS}{light}
                    shader "lam" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 1)
                    material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
                    shader "occ" "maya_lambert" ("transparency" 0.5 0.25 1)
                    material "g" "maya_shadingengine" ("surfaceShader" = "occ.outColor")
                        shadow "{shader}" ({params}) end material"#
                ),
                &["m", "g"],
                "",
            );
            assert!(c.messages.is_empty(), "{shader}: {:#?}", c.messages);
            let tracer = support::maya::Occluder { material: c.material_index("g") };
            assert_rgb(run(&c, &tracer, c.material("m"), point([0.0, 0.0])).color(), want, 1e-5);
        }
    }
}
