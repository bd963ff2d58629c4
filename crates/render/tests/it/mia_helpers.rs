//! The Architectural library's helpers in the classic engine, end to end: `mia_roundcorners`
//! on a box's edge, `mia_lens_bokeh`'s focus and circle of confusion, and `mia_envblur` at
//! blur 0 against its input.

use crate::support;

use render::{EngineKind, Settings};

/// Renders `text` with the classic engine at `spp` samples per pixel: RGBA pixels (rows
/// from the top) and every diagnostic.
fn render(text: &str, spp: u32) -> (Vec<[f32; 4]>, Vec<String>) {
    let support::Compiled { scene, shading, messages, .. } = support::compile(text);
    let world = render::World::from_scene(&scene);
    let settings = Settings { engine: EngineKind::Classic, spp: Some(spp), ..Settings::default() };
    (support::render_world(&world, &shading, &settings).0.rgba(), messages)
}

/// A camera at the origin looking down −Z (`focal` "infinity" for orthographic), `res`²
/// pixels, a one-pixel box filter, black background; `lens` and `env` go into the camera.
fn scene(camera: &str, res: u32, body: &str, instances: &[&str]) -> String {
    let names: String = instances.iter().map(|n| format!(" \"{n}\"")).collect();
    format!(
        r#"
options "opt" filter box 1 1 samples 0 2 end options
camera "cam" {camera} aspect 1 resolution {res} {res} end camera
instance "cam_inst" "cam" end instance
{body}
instgroup "root" "cam_inst"{names} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// A constant-colour material: a light-less Lambert whose ambient term is `c`.
fn constant(name: &str, c: f32) -> String {
    format!(
        "material \"{name}\" \"mib_illum_lambert\" (\"ambience\" {c} {c} {c} 1, \"ambient\" 1 1 1 1, \"diffuse\" 0 0 0 1, \"mode\" 0) end material\n"
    )
}

#[test]
fn roundcorners_turns_the_normal_at_a_box_edge_and_leaves_it_elsewhere() {
    // The box's top face (z = −5, facing the camera) ends at x = 0.5; the material shows
    // the rounded normal (set mode, world space) as its colour.
    let radius = 0.25;
    let body = format!(
        "shader \"rc\" \"mia_roundcorners\" (\"radius\" {radius}, \"bump_mode\" 6)\n\
         material \"normal_mtl\" \"mib_color_mix\" (\"num\" 0, \"color_base\" = \"rc\") end material\n{}",
        support::box_object("cube", "normal_mtl", [-3.0, -3.0, -7.0], [0.5, 3.0, -5.0], "")
    );
    let res = 32;
    let (pixels, messages) = render(&scene("focal infinity aperture 2", res, &body, &["cube_inst"]), 16);
    assert!(messages.is_empty(), "{messages:?}");
    let px = |col: u32, row: u32| pixels[(row * res + col) as usize];
    let width = 2.0 / res as f32;
    for row in [4, 16, 27] {
        // Far from the edge (more than the radius): exactly the face normal.
        for col in 0..14 {
            assert_eq!(&px(col, row)[..3], &[0.0, 0.0, 1.0], "pixel ({col}, {row})");
        }
        // The pixels within the radius: the pixel's mean of the fillet profile
        // α(d) = 45° − asin(d/r · sin 45°), d the distance to the edge.
        for col in 17..24 {
            let (x0, x1) = (-1.0 + col as f32 * width, -1.0 + (col + 1) as f32 * width);
            let mut want = [0.0f32; 2];
            let steps = 64;
            for k in 0..steps {
                let x = x0 + (k as f32 + 0.5) / steps as f32 * (x1 - x0);
                let d = 0.5 - x;
                let alpha = if d >= radius {
                    0.0
                } else {
                    45f32.to_radians() - ((d / radius) * 45f32.to_radians().sin()).asin()
                };
                want[0] += alpha.sin() / steps as f32;
                want[1] += alpha.cos() / steps as f32;
            }
            let p = px(col, row);
            assert!(
                (p[0] - want[0]).abs() < 0.02 && (p[2] - want[1]).abs() < 0.02,
                "pixel ({col}, {row}): {p:?} want {want:?}"
            );
            assert!(p[1].abs() < 1e-5 && p[2] > 0.0);
        }
        // Next to the edge the normal is close to the bisector (the pixel spans d ∈ [0, 1/16]).
        let edge = px(23, row);
        assert!(edge[0] > 0.5 && (edge[0] - edge[2]).abs() < 0.25, "{edge:?}");
    }
}

/// A bright square of side `side` (a thin box) centred at (`x`, `y`, −`z`), the rest black.
fn dot_scene(lens: &str, res: u32, x: f32, y: f32, z: f32, side: f32) -> String {
    let h = side / 2.0;
    let body = format!(
        "{}{}",
        constant("white", 1.0),
        support::box_object("dot", "white", [x - h, y - h, -z - 1e-3], [x + h, y + h, -z], "")
    );
    scene(&format!("focal 1 aperture 2 {lens}"), res, &body, &["dot_inst"])
}

#[test]
fn bokeh_keeps_the_focal_plane_sharp_and_radius_zero_is_the_pinhole() {
    // At distance 10 a pixel is 20/32 wide: the square covers pixels 16–17 × 14–15 exactly.
    let res = 32;
    let w = 20.0 / res as f32;
    let pinhole = render(&dot_scene("", res, w, w, 10.0, 2.0 * w), 16).0;
    let lens = "lens \"mia_lens_bokeh\" (\"plane\" 10, \"radius\" 0.8, \"samples\" 8)";
    let (focused, messages) = render(&dot_scene(lens, res, w, w, 10.0, 2.0 * w), 16);
    assert!(messages.is_empty(), "{messages:?}");
    let lit: Vec<usize> = pinhole.iter().enumerate().filter(|(_, p)| p[0] > 0.0).map(|(i, _)| i).collect();
    assert_eq!(lit.len(), 4, "the square covers four pixels");
    for (i, (a, b)) in pinhole.iter().zip(&focused).enumerate() {
        assert!((a[0] - b[0]).abs() < 1e-3, "pixel {i}: {} vs {}", a[0], b[0]);
    }
    let zero = "lens \"mia_lens_bokeh\" (\"plane\" 10, \"radius\" 0, \"samples\" 8)";
    assert_eq!(render(&dot_scene(zero, res, w, w, 10.0, 2.0 * w), 16).0, pinhole, "radius 0: the pinhole image");
}

#[test]
fn bokeh_circle_of_confusion_has_the_thin_lens_diameter() {
    // Focus at 10, a small square at 5: on the focal plane the aperture's disc scaled by
    // |1 − 10/5| = 1, i.e. radius R = 1.5, which at distance 10 is 1.5 / (20/48) = 3.6 px.
    let res = 48;
    let radius: f64 = 1.5;
    let lens = format!("lens \"mia_lens_bokeh\" (\"plane\" 10, \"radius\" {radius}, \"samples\" 32)");
    let (img, messages) = render(&dot_scene(&lens, res, 0.0, 0.0, 5.0, 0.05), 64);
    assert!(messages.is_empty(), "{messages:?}");
    let (mut e, mut cx, mut cy) = (0.0f64, 0.0f64, 0.0f64);
    for (i, p) in img.iter().enumerate() {
        let (x, y) = ((i as u32 % res) as f64 + 0.5, (i as u32 / res) as f64 + 0.5);
        e += p[0] as f64;
        cx += p[0] as f64 * x;
        cy += p[0] as f64 * y;
    }
    let (cx, cy) = (cx / e, cy / e);
    let m2: f64 = img
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let (x, y) = ((i as u32 % res) as f64 + 0.5 - cx, (i as u32 / res) as f64 + 0.5 - cy);
            p[0] as f64 * (x * x + y * y)
        })
        .sum::<f64>()
        / e;
    // A uniform disc of radius ρ has ⟨r²⟩ = ρ²/2; the pixel's box filter adds 1/6 px², the
    // square itself (0.05 wide at 5 units: 0.24 px on the image) about 0.01 px².
    let rho = (2.0 * (m2 - 1.0 / 6.0 - 0.01)).sqrt();
    let want = radius * (1.0 - 10.0 / 5.0f64).abs() / (20.0 / res as f64);
    assert!((rho - want).abs() / want < 0.04, "circle of confusion radius {rho} px, thin lens {want} px");
    assert!((cx - 24.0).abs() < 0.2 && (cy - 24.0).abs() < 0.2, "centred: {cx} {cy}");
}

#[test]
fn envblur_at_blur_zero_is_its_input_and_blurred_keeps_a_constant() {
    // Only the environment is in view (a box behind the camera gives the scene geometry).
    let behind = format!(
        "{}{}",
        constant("white", 1.0),
        support::box_object("behind", "white", [-1.0, -1.0, 10.0], [1.0, 1.0, 11.0], "")
    );
    let cases = [
        ("mia_physicalsky", "\"y_is_up\" on, \"sun_direction\" 0.3 0.4 -0.8", 0.0),
        ("mib_color_mix", "\"num\" 0, \"color_base\" 0.2 0.4 0.8 1", 0.3),
    ];
    for (shader, params, blur) in cases {
        let direct_env = format!("focal 1 aperture 2 environment \"{shader}\" ({params})");
        let direct = render(&scene(&direct_env, 8, &behind, &["behind_inst"]), 4).0;
        let body = format!("shader \"env\" \"{shader}\" ({params})\n{behind}");
        let env = format!(
            "focal 1 aperture 2 environment \"mia_envblur\" (\"environment\" \"env\", \"blur\" {blur}, \"resolution\" 32)"
        );
        let (img, messages) = render(&scene(&env, 8, &body, &["behind_inst"]), 4);
        assert!(messages.is_empty(), "{messages:?}");
        assert!(direct.iter().any(|p| p[0] != direct[0][0]) || blur > 0.0, "the sky varies over the image");
        for (a, b) in img.iter().zip(&direct) {
            for k in 0..4 {
                assert!((a[k] - b[k]).abs() <= 1e-4 * b[k].abs().max(1.0), "{shader} blur {blur}: {a:?} vs {b:?}");
            }
        }
    }
}
