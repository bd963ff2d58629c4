//! Motion that the shutter's keys alone would get wrong, against coverage worked out by
//! hand: an instance that moves while its mesh's vertices move too (the product of the
//! two at each time, not a straight line between keys), and a zero-length shutter
//! (`shutter t t`), which shows the scene at motion time `t`. An orthographic camera looks
//! at the right edge of a large quad; a pixel's alpha is the fraction of the shutter
//! during which the quad covers it. Both engines, both acceleration backends.

use crate::support;

use support::moving_quad::{alpha, assert_columns as assert_profile, each_renderer, mean_over};

/// The moving-quad scene ([`support::moving_quad::scene`]) whose four vertices all carry
/// the motion vector `vector` (or none when empty).
fn scene(options: &str, quad: &str, camera: &str, vector: &str) -> String {
    let motion = if vector.is_empty() { "" } else { "m 4" };
    support::moving_quad::scene(options, quad, camera, [motion; 4], vector)
}

/// An instance sliding one unit right (`motion transform`) while its vertices slide one
/// unit right too (`m 1 0 0`): the edge moves 2 units at the summed speed, so the
/// coverage falls linearly from 1 at x = 0 to 0 at x = 2. Within 0.03 per column.
#[test]
fn instance_and_vertex_motion_add_up() {
    let text = scene("motion on shutter 0 1", "motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1", "", "1 0 0");
    each_renderer(|engine, backend| {
        let a = alpha(&text, engine, backend);
        let ramp = |x: f32| if x <= 0.0 { 1.0 } else { (1.0 - x / 2.0).max(0.0) };
        assert_profile(&a, |x0, x1| mean_over(x0, x1, ramp), 0.03, &format!("{engine:?} {backend:?}"));
    });
}

/// An instance stretching from scale 1 to 3 along x (about its origin) while its
/// vertices slide one unit right: at time t the edge is at (1 + 2t)·t — the product of
/// the instance's transform and the vertex position at that time, a parabola — so a
/// point x in [0, 3] is covered while t > (√(1 + 8x) − 1)/4. Keys of the product at the
/// shutter's ends (a straight line from 0 to 3) would give 1 − x/3 instead: at x = 1.5,
/// 0.50 where the product gives 0.35. Within 0.03 per column.
#[test]
fn a_stretching_instance_of_a_moving_mesh_follows_the_product() {
    let text =
        scene("motion on shutter 0 1", "motion transform 0.3333333333 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1", "", "1 0 0");
    let covered = |x: f32| if x <= 0.0 { 1.0 } else { (1.0 - ((1.0 + 8.0 * x).sqrt() - 1.0) / 4.0).max(0.0) };
    // The straight line between the keys is far enough off to fail the tolerance.
    let straight = |x: f32| if x <= 0.0 { 1.0 } else { (1.0 - x / 3.0).max(0.0) };
    assert!((mean_over(1.5, 1.75, covered) - mean_over(1.5, 1.75, straight)).abs() > 0.1);
    each_renderer(|engine, backend| {
        let a = alpha(&text, engine, backend);
        assert_profile(&a, |x0, x1| mean_over(x0, x1, covered), 0.03, &format!("{engine:?} {backend:?}"));
    });
}

/// `shutter 0.5 0.5` with `motion on`: no blur, and everything where it is at motion time
/// ½ — a quad whose instance moves 2 units right over the motion interval has its edge at
/// x = 1 (columns left of it fully covered, right of it empty: exactly, the edge is a
/// column boundary), the same for vertex motion and, with the quad still, for a camera
/// moving 2 units left. `shutter 0 0` (and no shutter) keeps the edge at x = 0.
#[test]
fn a_zero_length_shutter_shows_the_scene_at_its_time() {
    let at = |edge: f32| move |x0: f32, x1: f32| mean_over(x0, x1, |x| if x < edge { 1.0 } else { 0.0 });
    let moving_instance = "motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -2 0 0 1";
    let moving_camera =
        "transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1  motion transform 1 0 0 0  0 1 0 0  0 0 1 0  2 0 0 1";
    for (options, edge) in [("motion on shutter 0.5 0.5", 1.0), ("motion on shutter 0 0", 0.0), ("motion on", 0.0)] {
        for text in [
            scene(options, moving_instance, "", ""),
            scene(options, "", "", "2 0 0"),
            scene(options, "", moving_camera, ""),
        ] {
            each_renderer(|engine, backend| {
                let a = alpha(&text, engine, backend);
                assert_profile(&a, at(edge), 1e-4, &format!("{options}: {engine:?} {backend:?}"));
            });
        }
    }
}
