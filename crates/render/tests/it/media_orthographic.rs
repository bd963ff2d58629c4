//! An orthographic camera's rays start across its image plane, each in the media around
//! its own origin, in both engines: a gel box (σa 0.5, 1, 2) that holds the right quarter
//! of the image plane but not the camera's centre darkens only that quarter's view of a
//! glow inside it (exp(−1.5σa)), and a box that holds the centre but not that quarter
//! leaves the quarter's view clear. Rays that started in the media around the centre would
//! see the glow unattenuated in the first case and attenuated everywhere in the second.

use render::integrator::PathSettings;
use render::EngineKind;

use crate::media::{closed_box, render_by, scene_with, wall, SIGMA_A};

/// The view of a glow of radiance 1 at z = −1.5 through a gel box spanning x from `x0` to
/// `x1` (y ± 5, z ± 4) by an orthographic camera at the origin looking down −z (x and y
/// within ±1 on its image plane, 4 × 4 pixels), rendered by `engine`.
fn view(engine: EngineKind, x0: f32, x1: f32) -> Vec<[f32; 4]> {
    let body = format!(
        "shader \"glow_mtl\" \"mdl::media::glow\" ()\nshader \"box_mtl\" \"mdl::media::tinted_gel\" ()\n{}{}",
        closed_box("box", [x0, -5.0, -4.0], [x1, 5.0, 4.0], "box_mtl"),
        wall("w", -1.5, "glow_mtl")
    );
    let text =
        scene_with(&body, &["box_inst", "w_inst"], 4).replace("focal 1 aperture 0.01", "focal infinity aperture 2");
    let (px, messages) = render_by(engine, &text, 4, 4, PathSettings { max_depth: 16, ..Default::default() });
    assert!(messages.is_empty(), "{messages:#?}");
    px
}

/// Asserts that the pixels of column 3 (x from 0.5 to 1 on the image plane) show
/// `inside` and the others `outside`, per channel within 1e-3 relative.
fn assert_columns(px: &[[f32; 4]], inside: [f32; 3], outside: [f32; 3], what: &str) {
    for (i, p) in px.iter().enumerate() {
        let want = if i % 4 == 3 { inside } else { outside };
        for k in 0..3 {
            assert!((p[k] - want[k]).abs() <= 1e-3 * want[k], "{what}: pixel {i} channel {k}: {} vs {}", p[k], want[k]);
        }
    }
}

#[test]
fn orthographic_rays_start_in_the_media_around_their_own_origin() {
    let through = SIGMA_A.map(|s| (-1.5 * s).exp());
    for engine in [EngineKind::Path, EngineKind::Classic] {
        // The box holds x from 0.5: column 3's rays start in it, the centre is outside.
        let px = view(engine, 0.5, 5.0);
        assert_columns(&px, through, [1.0; 3], &format!("{engine:?}, the box off the centre"));
        // The box holds the centre and x up to 0.5: column 3's rays start outside it.
        let px = view(engine, -5.0, 0.5);
        assert_columns(&px, [1.0; 3], through, &format!("{engine:?}, the box around the centre"));
    }
}
