//! `state::transform_point` to object space in a rendered scene: two instances of one
//! emitting quad placed 2 units apart, whose radiance is the hit point's half-unit cell
//! (crates/material/tests/mdl/object_space.mdl, `cell`), seen by an orthographic camera
//! whose pixels are half a unit wide. In object space both instances' images are the
//! same pixel for pixel (1e-5); in world space they differ by the 4 cells between them.

use std::path::Path;

use crate::support;
use render::{EngineKind, Settings};

const RES: usize = 8;

/// Renders `text` with `engine` at `RES`² pixels, 4 samples: the pixels' RGB and the
/// messages.
fn render_text(text: &str, engine: EngineKind) -> (Vec<[f32; 3]>, Vec<String>) {
    let parsed = mi::parse_str("object_space.mi", text);
    let modules = [Path::new(env!("CARGO_MANIFEST_DIR")).join("../material/tests/mdl")];
    let built = support::build_parsed(&parsed, RES as u32, &modules);
    let settings = Settings { engine, spp: Some(4), ..Settings::default() };
    let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
    (film.rgba().iter().map(|p| [p[0], p[1], p[2]]).collect(), built.messages)
}

/// The quad x ∈ [−1, 1], y ∈ [−2, 2] (object space) of shader `shader`, instanced at
/// x = −1 and x = +1, 5 units in front of an orthographic camera 4 units wide.
fn scene(shader: &str) -> String {
    format!(
        r#"options "opt" filter box 1 1 end options
shader "glow" {shader}
object "quad" group
    -1 -2 0  1 -2 0  1 2 0  -1 2 0
    v 0 v 1 v 2 v 3
    p "glow" 0 1 2 3
end group end object
instance "left" "quad" transform 1 0 0 0  0 1 0 0  0 0 1 0  1 0 5 1 end instance
instance "right" "quad" transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 5 1 end instance
camera "cam" focal infinity aperture 4 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
instgroup "root" "cam_inst" "left" "right" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

#[test]
fn object_space_cells_repeat_across_instances_and_world_cells_do_not() {
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let (object, messages) = render_text(&scene(r#""mdl::object_space::cell" ("offset" 12)"#), engine);
        assert!(messages.is_empty(), "{messages:#?}");
        let (world, messages) = render_text(&scene(r#""mdl::object_space::cell" ("object" off, "offset" 12)"#), engine);
        assert!(messages.is_empty(), "{messages:#?}");
        for j in 0..RES {
            for i in 0..RES {
                // Pixel (i, j): world x = −2 + 0.5 i … (row 0 at the top, y = 2 − 0.5 j …);
                // each instance's object x = world x ± 1.
                let cell_y = 12.0 + 3.0 - j as f32;
                let want_object = [12.0 - 2.0 + (i % 4) as f32, cell_y, 12.0];
                let want_world = [12.0 - 4.0 + i as f32, cell_y, 12.0 - 10.0];
                let (o, w) = (object[j * RES + i], world[j * RES + i]);
                for c in 0..3 {
                    assert!((o[c] - want_object[c]).abs() <= 1e-5, "{engine:?} object ({i}, {j}): {o:?}");
                    assert!((w[c] - want_world[c]).abs() <= 1e-5, "{engine:?} world ({i}, {j}): {w:?}");
                }
                if i < 4 {
                    // The same object point of the two instances.
                    let other = object[j * RES + i + 4];
                    assert!((0..3).all(|c| (o[c] - other[c]).abs() <= 1e-5), "{engine:?} ({i}, {j})");
                    assert!((world[j * RES + i + 4][0] - w[0] - 4.0).abs() <= 1e-5);
                }
            }
        }
    }
}

/// The left instance moving 1 unit towards the camera while the shutter is open (seen
/// orthographically, so the same pixels see it): its object space is read at each ray's
/// time, so the object-space image is the still one exactly (object z stays 0 — the
/// matrices of the shutter's opening would give z up to 1 and cells up to 2 higher),
/// while world z's cell grows over the shutter.
#[test]
fn a_moving_instance_is_read_in_its_object_space_at_the_rays_time() {
    let moving = |text: String| {
        text.replace("filter box 1 1 end", "filter box 1 1 motion on shutter 0 1 end").replace(
            "0 0 1 0  1 0 5 1 end instance",
            "0 0 1 0  1 0 5 1 motion transform 1 0 0 0  0 1 0 0  0 0 1 0  1 0 4 1 end instance",
        )
    };
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let object = scene(r#""mdl::object_space::cell" ("offset" 12)"#);
        let (still, messages) = render_text(&object, engine);
        assert!(messages.is_empty(), "{messages:#?}");
        let (moved, messages) = render_text(&moving(object), engine);
        assert!(messages.is_empty(), "{messages:#?}");
        for (k, (a, b)) in still.iter().zip(&moved).enumerate() {
            assert!((0..3).all(|c| (a[c] - b[c]).abs() <= 1e-5), "{engine:?} pixel {k}: {a:?} vs {b:?}");
        }
        let world = scene(r#""mdl::object_space::cell" ("object" off, "offset" 12)"#);
        let (moved, _) = render_text(&moving(world), engine);
        // Left half: world z from −5 to −4 over the shutter, cells −10 then −9 (+ 12).
        let left: f32 =
            (0..RES).flat_map(|j| (0..4).map(move |i| j * RES + i)).map(|k| moved[k][2]).sum::<f32>() / 32.0;
        assert!(left > 2.2 && left < 2.8, "{engine:?}: mean world z cell {left}");
        assert!((0..RES).all(|j| (moved[j * RES + 6][2] - 2.0).abs() <= 1e-5), "the right one stays");
    }
}
