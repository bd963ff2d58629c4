//! Maya's 3D textures, place3dTexture, projection, envSphere and bump3d in compiled
//! scenes, read through a surfaceShader (unlit: the texture's colour is the pixel's) or a
//! lambert. The shading point is the world origin, normal +y (see `support::maya::point`).

use crate::support;

use support::maya::{assert_rgb, compile, point, run, Compiled};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";
/// A 2×2 texture: red, green (bottom row), blue, white (top row).
const QUAD: &str = r#"color texture "quad" [ 2 2 ] 'ff0000' '00ff00' '0000ff' 'ffffff'"#;

fn scene(body: &str) -> Compiled {
    let c = compile("", &format!("{LIBS}{QUAD}\n{body}"), &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    c
}

/// A surfaceShader material showing `source` (a shader's colour output).
fn show(source: &str) -> String {
    format!(
        r#"shader "flat" "maya_surfaceshader" ("outColor" = "{source}")
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material"#
    )
}

fn shade(c: &Compiled, state: shader::State) -> glam::Vec4 {
    run(c, &Empty::default(), c.material("m"), state).color()
}

#[test]
fn planar_projection_through_a_place3d_texture() {
    // The placement object moved by t: the origin is at −t in placement space, so the
    // planar projection reads the quad at ((1 − t_x)/2, (1 − t_y)/2) whatever the
    // surface's own coordinate (0.75, 0.25: green) is.
    for (t, want) in [([0.5, 0.5], [1.0, 0.0, 0.0]), ([-0.5, -0.5], [1.0, 1.0, 1.0]), ([-0.5, 0.5], [0.0, 1.0, 0.0])] {
        let c = scene(&format!(
            r#"shader "p3d" "maya_place3dtexture" ("matrix" 1 0 0 0  0 1 0 0  0 0 1 0  {} {} 0 1)
            shader "file1" "maya_file" ("fileTextureName" "quad")
            shader "proj" "maya_projection" ("projType" 1, "image" = "file1.outColor",
                "placementMatrix" = "p3d.worldInverseMatrix")
            {}"#,
            t[0],
            t[1],
            show("proj.outColor")
        ));
        assert_rgb(shade(&c, point([0.75, 0.25])), want, 1e-4);
    }
}

#[test]
fn env_sphere_reads_the_image_along_the_ray() {
    // Looking along (1, −1, 0)/√2: u = ½ + ¼, v = ½ − ¼ → the quad's green texel.
    let c = scene(&format!(
        r#"shader "file1" "adskMayaFile" ("fileTextureName" "quad")
        shader "env" "adskMayaEnvSphere" ("image" = "file1.outColor")
        {}"#,
        show("env.outColor")
    ));
    let mut s = point([0.25, 0.75]);
    s.dir = glam::Vec3A::new(1.0, -1.0, 0.0).normalize();
    assert_rgb(shade(&c, s), [0.0, 1.0, 0.0], 1e-4);
    // Flipped: u = ¼ → red.
    let c = scene(&format!(
        r#"shader "file1" "maya_file" ("fileTextureName" "quad")
        shader "env" "maya_envsphere" ("image" = "file1.outColor", "flip" on)
        {}"#,
        show("env.outColor")
    ));
    let mut s = point([0.25, 0.75]);
    s.dir = glam::Vec3A::new(1.0, -1.0, 0.0).normalize();
    assert_rgb(shade(&c, s), [1.0, 0.0, 0.0], 1e-4);
}

#[test]
fn solid_fractal_threshold_colour_balance_and_wrap() {
    // Amplitude 0: the value is threshold + 0.5 everywhere; colour gain tints it.
    let body = |extra: &str| {
        format!(
            r#"shader "sf" "maya_solidfractal" ("amplitude" 0, "threshold" 0.2, "colorGain" 1 0.5 0.25,
                "defaultColor" 0 0 1 {extra})
            {}"#,
            show("sf.outColor")
        )
    };
    let c = scene(&body(""));
    assert_rgb(shade(&c, point([0.0, 0.0])), [0.7, 0.35, 0.175], 1e-6);
    // The placement scaled by 4 puts the origin moved by (1, 0, 0) outside the cube
    // [−1, 1]³: with wrap off, the default colour; with wrap on, the texture.
    let m = r#", "placementMatrix" 4 0 0 0  0 4 0 0  0 0 4 0  0 0 0 1"#;
    let mut s = point([0.0, 0.0]);
    s.point = glam::Vec3A::new(1.0, 0.0, 0.0);
    let c = scene(&body(&format!(r#"{m}, "wrap" off"#)));
    assert_rgb(shade(&c, s.clone()), [0.0, 0.0, 1.0], 1e-6);
    let c = scene(&body(m));
    assert_rgb(shade(&c, s), [0.7, 0.35, 0.175], 1e-6);
}

#[test]
fn marble_and_wood_stay_between_their_colours() {
    for (shader, params) in [
        ("maya_marble", r#""fillerColor" 1 1 1, "veinColor" 0 0 0"#),
        ("adskMayaWood", r#""fillerColor" 1 1 1, "veinColor" 0 0 0, "grainContrast" 0"#),
    ] {
        let c = scene(&format!(r#"shader "t" "{shader}" ({params}) {}"#, show("t.outColor")));
        let (mut lo, mut hi) = (f32::MAX, f32::MIN);
        for i in 0..64 {
            let mut s = point([0.0, 0.0]);
            s.point = glam::Vec3A::new(i as f32 * 0.031 - 1.0, 0.3, (i % 7) as f32 * 0.05);
            let got = shade(&c, s);
            assert!(got.x == got.y && got.y == got.z, "{shader}: grey between white and black, got {got}");
            lo = lo.min(got.x);
            hi = hi.max(got.x);
        }
        assert!(lo >= 0.0 && hi <= 1.0, "{shader}: {lo}..{hi}");
        assert!(hi - lo > 0.5, "{shader}: both veins and filler appear ({lo}..{hi})");
    }
}

#[test]
fn bump3d_tilts_the_normal_against_the_gradient() {
    // bumpValue = u of a planar projection of a U ramp: b = (x + 1)/2, ∇b = (½, 0, 0);
    // depth 2 tilts the +y normal to (−1, 1, 0)/√2, so a lambert lit straight from above
    // shows c·d·cos 45°.
    let c = scene(
        r#"light "sun" "maya_directionallight" ("intensity" 1) direction 0 -1 0 end light
        instance "sun_inst" "sun" end instance
        shader "ramp1" "maya_ramp" ("type" 1, "interpolation" 1,
            "colorEntryList" [ { "position" 0, "color" 0 0 0 }, { "position" 1, "color" 1 1 1 } ])
        shader "proj" "maya_projection" ("projType" 1, "image" = "ramp1.outColor", "alphaIsLuminance" on)
        shader "b3" "maya_bump3d" ("bumpValue" = "proj.outAlpha", "bumpDepth" 2)
        shader "lam" "maya_lambert" ("color" 1 1 1, "diffuse" 1, "normalCamera" = "b3.outNormal")
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#,
    );
    assert_rgb(shade(&c, point([0.0, 0.0])), [std::f32::consts::FRAC_1_SQRT_2; 3], 2e-3);
}

/// The perspective projection through a linked camera 4 above (−1, 0, 0.5) looking down
/// (focal 35 mm, Maya's 35 mm film gate 1.417 × 0.945 in: the image plane's half width
/// h = 1.417 · 25.4 / 70 at distance 1), of U and V ramps (their colour is the
/// coordinate they are read at), for an image of aspect 1.25: the origin lies at
/// camera-space (1, 0.5, −4), screen position s = (1, 0.5)/(4h), and each fit scales it
/// as the projection's module doc says, worked out here by hand. With no focal length
/// the render camera is used, its frame filled as before.
#[test]
fn the_perspective_projection_looks_through_the_linked_camera_with_its_fit() {
    let coordinate = |ramp_type: i32, camera: &str| {
        let c = scene(&format!(
            r#"shader "ramp1" "maya_ramp" ("type" {ramp_type}, "interpolation" 1,
                "colorEntryList" [ {{ "position" 0, "color" 0 0 0 }}, {{ "position" 1, "color" 1 1 1 }} ])
            shader "proj" "maya_projection" ("projType" 8, "image" = "ramp1.outColor", "imageAspect" 1.25{camera})
            {}"#,
            show("proj.outColor")
        ));
        let resolution = c.shading.resolution;
        (shade(&c, point([0.0, 0.0])).x, resolution.0 as f32 / resolution.1 as f32, c)
    };
    let linked = r#", "linkedCamera" 1 0 0 0  0 0 1 0  0 -1 0 0  1 0.5 -4 1, "cameraFocalLength" 35,
        "cameraHorizontalFilmAperture" 1.417, "cameraVerticalFilmAperture" 0.945"#;
    let h = 1.417 * 25.4 / 70.0;
    let s = glam::Vec2::new(1.0, 0.5) / (4.0 * h);
    let film = 1.417 / 0.945;
    let (_, resolution_aspect, _) = coordinate(1, "");
    for (fit_type, fit_fill, scale) in [
        (0, 0, glam::Vec2::ONE),
        (1, 0, glam::Vec2::new(1.0, film)),
        (1, 1, glam::Vec2::new(1.0, 1.25)),
        (1, 2, glam::Vec2::new(film / 1.25, film)),
        (2, 0, glam::Vec2::new(1.0, resolution_aspect)),
    ] {
        let camera = format!(r#"{linked}, "fitType" {fit_type}, "fitFill" {fit_fill}"#);
        let want = glam::Vec2::splat(0.5) + 0.5 * s * scale;
        let (u, v) = (coordinate(1, &camera).0, coordinate(0, &camera).0);
        assert!(
            (u - want.x).abs() < 1e-4 && (v - want.y).abs() < 1e-4,
            "fit {fit_type}/{fit_fill}: {u}, {v} vs {want}"
        );
    }
    // No linked camera: the render camera's frame, filled (its aspect from its image plane).
    let (u, _, c) = coordinate(1, "");
    let (v, _, _) = coordinate(0, "");
    let shading = &c.shading;
    let p = shading.world_to_camera.transform_point3a(glam::Vec3A::ZERO);
    let want = glam::Vec2::splat(0.5) + 0.5 * glam::Vec2::new(p.x, p.y) / -p.z / shading.image_plane;
    assert!((u - want.x).abs() < 1e-4 && (v - want.y).abs() < 1e-4, "render camera: {u}, {v} vs {want}");
}

/// The perspective projection through an orthographic linked camera (`cameraOrthographic`
/// on, `cameraOrthographicWidth` 8: the view's half width 4) placed as in the test above:
/// the origin at camera-space (1, 0.5, −4) lies at s = (1, 0.5)/4 = (0.25, 0.125) whatever
/// its depth, and the four fits (film gate 1.417 × 0.945 in, aspect 1.49947; image aspect
/// 1.25) give by hand: none (0.625, 0.5625); fill (0.625, 0.5 + 0.0625 · 1.49947 =
/// 0.593717); horizontal (0.625, 0.5 + 0.0625 · 1.25 = 0.578125); vertical (0.5 + 0.125 ·
/// 1.49947/1.25 = 0.649947, 0.593717). Within 1e-4; the focal length is not read.
#[test]
fn the_perspective_projection_through_an_orthographic_linked_camera() {
    let coordinate = |ramp_type: i32, camera: &str| {
        let c = scene(&format!(
            r#"shader "ramp1" "maya_ramp" ("type" {ramp_type}, "interpolation" 1,
                "colorEntryList" [ {{ "position" 0, "color" 0 0 0 }}, {{ "position" 1, "color" 1 1 1 }} ])
            shader "proj" "maya_projection" ("projType" 8, "image" = "ramp1.outColor", "imageAspect" 1.25{camera})
            {}"#,
            show("proj.outColor")
        ));
        shade(&c, point([0.0, 0.0])).x
    };
    let linked = r#", "linkedCamera" 1 0 0 0  0 0 1 0  0 -1 0 0  1 0.5 -4 1, "cameraOrthographic" on,
        "cameraOrthographicWidth" 8, "cameraFocalLength" 35,
        "cameraHorizontalFilmAperture" 1.417, "cameraVerticalFilmAperture" 0.945"#;
    for (fit_type, fit_fill, want) in
        [(0, 0, [0.625, 0.5625]), (1, 0, [0.625, 0.593717]), (1, 1, [0.625, 0.578125]), (1, 2, [0.649947, 0.593717])]
    {
        let camera = format!(r#"{linked}, "fitType" {fit_type}, "fitFill" {fit_fill}"#);
        let (u, v) = (coordinate(1, &camera), coordinate(0, &camera));
        assert!(
            (u - want[0]).abs() < 1e-4 && (v - want[1]).abs() < 1e-4,
            "fit {fit_type}/{fit_fill}: {u}, {v} vs {want:?}"
        );
    }
    // Half the width: twice the offset from the centre (fit none).
    let camera = linked.replace("\"cameraOrthographicWidth\" 8", "\"cameraOrthographicWidth\" 4");
    let (u, v) =
        (coordinate(1, &format!("{camera}, \"fitType\" 0")), coordinate(0, &format!("{camera}, \"fitType\" 0")));
    assert!((u - 0.75).abs() < 1e-4 && (v - 0.625).abs() < 1e-4, "{u}, {v}");
}

/// Crater's and stucco's `outNormal` drive a lambert's `normalCamera` (both families):
/// lit straight from above, depth 0 leaves the normal (c·d·cos 0 = 1, 1e-5); with deep
/// craters the lambert never brightens (the tilted normal's cosine ≤ 1) and darkens on the
/// walls at some of 60 placements of the texture.
#[test]
fn crater_and_stucco_out_normals_bump_a_lambert() {
    for (tex, depth) in [
        ("maya_crater", "normDepth"),
        ("adskMayaCrater", "normDepth"),
        ("maya_stucco", "normalDepth"),
        ("adskMayaStucco", "normalDepth"),
    ] {
        let lit = |params: &str, tx: f32| {
            let c = scene(&format!(
                r#"light "sun" "maya_directionallight" ("intensity" 1) direction 0 -1 0 end light
                instance "sun_inst" "sun" end instance
                shader "tex" "{tex}" ("placementMatrix" 1 0 0 0  0 1 0 0  0 0 1 0  {tx} 0 {tz} 1{params})
                shader "lam" "maya_lambert" ("color" 1 1 1, "diffuse" 1, "normalCamera" = "tex.outNormal")
                material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#,
                tz = 0.37 * tx
            ));
            shade(&c, point([0.0, 0.0])).x
        };
        assert!((lit(&format!(r#", "{depth}" 0"#), 0.3) - 1.0).abs() < 1e-5, "{tex}");
        let mut darkest = 1.0f32;
        for i in 0..60 {
            let v = lit(&format!(r#", "{depth}" 40"#), i as f32 * 0.0371);
            assert!(v <= 1.0 + 1e-5, "{tex}: {v}");
            darkest = darkest.min(v);
        }
        assert!(darkest < 0.95, "{tex}: the walls tilt the normal ({darkest})");
    }
}
