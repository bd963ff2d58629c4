//! Motion that the shutter's keys alone would get wrong, against coverage worked out by
//! hand: an instance that moves while its mesh's vertices move too (the product of the
//! two at each time, not a straight line between keys), and a zero-length shutter
//! (`shutter t t`), which shows the scene at motion time `t`. An orthographic camera looks
//! at the right edge of a large quad; a pixel's alpha is the fraction of the shutter
//! during which the quad covers it. Both engines, both acceleration backends.

mod support;

use std::sync::atomic::AtomicBool;

use render::{Backend, EngineKind, Settings};

/// Image width and height (pixels): 16 columns over x ∈ [−2, 2], a quarter unit each.
const W: usize = 16;
const H: usize = 4;

/// A 16×4 orthographic view of x ∈ [−2, 2] and a white quad over x ∈ [−10, 0] at
/// z = −5 whose four vertices all carry the motion vector `vector` (or none when empty);
/// `options` go into the options, `quad` into the quad's instance, `camera` into the
/// camera's instance.
fn scene(options: &str, quad: &str, camera: &str, vector: &str) -> String {
    let m = if vector.is_empty() { String::new() } else { " m 4".to_string() };
    let vectors = if vector.is_empty() { String::new() } else { vector.to_string() };
    format!(
        r#"
options "opt" filter box 1 1 {options} end options
camera "cam" focal infinity aperture 4 aspect 4 resolution {W} {H} end camera
instance "cam_inst" "cam" {camera} end instance
material "m" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 1 1 1, "diffuse" 0 0 0) end material
object "quad" group
    -10 -10 -5  0 -10 -5  0 10 -5  -10 10 -5
    {vectors}
    v 0{m} v 1{m} v 2{m} v 3{m}
    c "m" 0 1 2 3
end group end object
instance "quad_inst" "quad" material "m" {quad} end instance
instgroup "root" "cam_inst" "quad_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The alpha of each pixel (rows from the top) of `text` rendered with `engine` on
/// `backend` at 64 samples per pixel.
fn alpha(text: &str, engine: EngineKind, backend: Backend) -> Vec<f32> {
    let c = support::compile(text);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let world = render::World::from_scene_shaded(&c.scene, Some(&c.shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    let accel = render::accel::build(&world, backend);
    let settings = Settings { engine, spp: Some(64), ..Settings::default() };
    let (film, _) =
        render::render(&world, accel.as_ref(), Some(&c.shading), &settings, &AtomicBool::new(false), &|_| {});
    film.rgba().iter().map(|p| p[3]).collect()
}

/// Every engine on every backend compiled in.
fn each_renderer(mut check: impl FnMut(EngineKind, Backend)) {
    for engine in [EngineKind::Path, EngineKind::Classic] {
        for backend in [Backend::Rust, Backend::Embree].into_iter().filter(|b| b.available()) {
            check(engine, backend);
        }
    }
}

/// Checks that each column's alpha, averaged over the rows, is `expect(x0, x1)` (the
/// coverage's mean over the column's span `[x0, x1]`) within `tolerance`.
fn assert_profile(a: &[f32], expect: impl Fn(f32, f32) -> f32, tolerance: f32, what: &str) {
    for i in 0..W {
        let mean = (0..H).map(|y| a[y * W + i]).sum::<f32>() / H as f32;
        let (x0, x1) = (-2.0 + i as f32 * 0.25, -2.0 + (i + 1) as f32 * 0.25);
        let want = expect(x0, x1);
        assert!((mean - want).abs() < tolerance, "{what}: column {i} ([{x0}, {x1}]): {mean} vs {want}");
    }
}

/// The mean over `[x0, x1]` of `f` (midpoint rule, 256 points).
fn mean_over(x0: f32, x1: f32, f: impl Fn(f32) -> f32) -> f32 {
    (0..256).map(|k| f(x0 + (k as f32 + 0.5) / 256.0 * (x1 - x0))).sum::<f32>() / 256.0
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
