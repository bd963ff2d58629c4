//! The moving-quad scene the motion-blur tests measure coverage on: a 16×4 orthographic
//! view of x ∈ [−2, 2] (a quarter unit per column) and a white, self-lit quad over
//! x ∈ [−10, 0] at z = −5. A pixel's alpha is the fraction of the (shape-weighted) shutter
//! during which the quad covers it, so a moving edge gives a coverage profile worked out
//! by hand.

use std::sync::atomic::AtomicBool;

use render::{Backend, EngineKind, Settings};

/// Image width (pixels): 16 columns over x ∈ [−2, 2].
pub const W: usize = 16;
/// Image height (pixels).
pub const H: usize = 4;

/// The scene: `options` go into the options block, `quad` into the quad's instance,
/// `camera` into the camera's instance, `vertex_motion[k]` after the quad's vertex `k`
/// (e.g. `"m 4"`), and `extra_vectors` after its four corner points (vectors 4, 5, …).
pub fn scene(options: &str, quad: &str, camera: &str, vertex_motion: [&str; 4], extra_vectors: &str) -> String {
    let [m0, m1, m2, m3] = vertex_motion;
    format!(
        r#"
options "opt" filter box 1 1 {options} end options
camera "cam" focal infinity aperture 4 aspect 4 resolution {W} {H} end camera
instance "cam_inst" "cam" {camera} end instance
material "m" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 1 1 1, "diffuse" 0 0 0) end material
object "quad" group
    -10 -10 -5  0 -10 -5  0 10 -5  -10 10 -5
    {extra_vectors}
    v 0 {m0} v 1 {m1} v 2 {m2} v 3 {m3}
    c "m" 0 1 2 3
end group end object
instance "quad_inst" "quad" material "m" {quad} end instance
instgroup "root" "cam_inst" "quad_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Renders `text` with `engine` on `backend` at `spp` samples per pixel, asserting that
/// reading and compiling it said nothing: the alpha of each pixel (rows from the top) and
/// the world's translation warnings.
pub fn render_alpha(text: &str, engine: EngineKind, backend: Backend, spp: u32) -> (Vec<f32>, Vec<String>) {
    let c = super::compile(text);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let world = render::World::from_scene_shaded(&c.scene, Some(&c.shading));
    let accel = render::accel::build(&world, backend);
    let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
    let (film, _) =
        render::render(&world, accel.as_ref(), Some(&c.shading), &settings, &AtomicBool::new(false), &|_| {});
    (film.rgba().iter().map(|p| p[3]).collect(), world.warnings.clone())
}

/// [`render_alpha`] at 64 samples per pixel, asserting that the world's translation gave
/// no warning either: the alpha of each pixel.
pub fn alpha(text: &str, engine: EngineKind, backend: Backend) -> Vec<f32> {
    let (alpha, warnings) = render_alpha(text, engine, backend, 64);
    assert!(warnings.is_empty(), "{warnings:?}");
    alpha
}

/// The acceleration backends compiled in.
pub fn backends() -> Vec<Backend> {
    [Backend::Rust, Backend::Embree].into_iter().filter(|b| b.available()).collect()
}

/// Calls `check` for both engines on every backend compiled in.
pub fn each_renderer(mut check: impl FnMut(EngineKind, Backend)) {
    for engine in [EngineKind::Path, EngineKind::Classic] {
        for backend in backends() {
            check(engine, backend);
        }
    }
}

/// The span `[x0, x1]` of pixel column `i` (scene units).
pub fn column_span(i: usize) -> (f32, f32) {
    let width = 4.0 / W as f32;
    (-2.0 + i as f32 * width, -2.0 + (i + 1) as f32 * width)
}

/// Checks that each column's alpha, averaged over the rows, is `expect(x0, x1)` (the
/// coverage's mean over the column's span) within `tolerance`.
pub fn assert_columns(alpha: &[f32], expect: impl Fn(f32, f32) -> f32, tolerance: f32, what: &str) {
    for i in 0..W {
        let mean = (0..H).map(|y| alpha[y * W + i]).sum::<f32>() / H as f32;
        let (x0, x1) = column_span(i);
        let want = expect(x0, x1);
        assert!((mean - want).abs() < tolerance, "{what}: column {i} ([{x0}, {x1}]): {mean} vs {want}");
    }
}

/// The mean over `[x0, x1]` of `f` (midpoint rule, 256 points).
pub fn mean_over(x0: f32, x1: f32, f: impl Fn(f32) -> f32) -> f32 {
    (0..256).map(|k| f(x0 + (k as f32 + 0.5) / 256.0 * (x1 - x0))).sum::<f32>() / 256.0
}

/// Coverage of a quad edge that moves from x = 0 to x = 2 at constant speed over a box
/// shutter: 1 left of 0, then falling linearly to 0 at x = 2.
pub fn box_ramp(x: f32) -> f32 {
    if x <= 0.0 {
        1.0
    } else {
        (1.0 - x / 2.0).max(0.0)
    }
}
