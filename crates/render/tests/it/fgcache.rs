//! The classic engine's final gather interpolation cache against brute-force final
//! gathering and the analytic irradiance of a floor beside a black wall under a uniform
//! sky.

use crate::support;

use render::{EngineKind, Settings, Stats};
use shader::ShadingOptions;

/// Resolution of the test images.
const RES: usize = 48;

/// An orthographic camera looking down −Z at x, y ∈ [−1, 1]; a white Lambertian floor at
/// z = −5 (x ∈ [−1, 9], y ∈ [−20, 20]); a black wall of height 1 standing on the floor
/// along its edge x = −1; a white environment (radiance 1).
fn wall_scene(options: &str) -> String {
    format!(
        r#"
options "opt" filter box 1 1 {options} end options
camera "cam" focal infinity aperture 2 aspect 1 resolution {RES} {RES}
    environment "mib_color_mix" ("num" 0, "color_base" 1 1 1 1)
end camera
instance "cam_inst" "cam" end instance
material "floor_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 1 1 1 1) end material
material "black" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0 0 0 1) end material
object "floor" group
    -1 -20 -5  9 -20 -5  9 20 -5  -1 20 -5
    v 0 v 1 v 2 v 3
    c "floor_mtl" 0 1 2 3
end group end object
object "wall" group
    -1 -20 -5  -1 20 -5  -1 20 -4  -1 -20 -4
    v 0 v 1 v 2 v 3
    c "black" 0 1 2 3
end group end object
instance "floor_inst" "floor" end instance
instance "wall_inst" "wall" end instance
instgroup "root" "cam_inst" "floor_inst" "wall_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Builds and renders a scene with the classic engine at `spp` samples per pixel, brute
/// force gathers casting `fg_rays` rays.
fn render(text: &str, spp: u32, fg_rays: Option<u32>) -> (Vec<[f32; 4]>, Stats) {
    let options = ShadingOptions { finalgather_rays: fg_rays, ..ShadingOptions::default() };
    let support::Compiled { scene, shading, messages, read } = support::compile_with(text, &options);
    assert!(!messages[..read].iter().any(|m| m.contains("error:")), "{messages:?}");
    let world = render::World::from_scene(&scene);
    let settings = Settings { engine: EngineKind::Classic, spp: Some(spp), ..Settings::default() };
    let (film, stats) = support::render_world(&world, &shading, &settings);
    (film.rgba(), stats)
}

/// Mean red value of each image column (columns are lines of constant x).
fn columns(px: &[[f32; 4]]) -> Vec<f64> {
    (0..RES).map(|i| (0..RES).map(|j| f64::from(px[j * RES + i][0])).sum::<f64>() / RES as f64).collect()
}

/// Irradiance (not divided by π, as the base shaders use it) at distance `d` from an
/// infinitely long black wall of height 1 under a sky of radiance 1: π (1 − F), F = ½ (1 −
/// d / √(d² + 1)) the view factor of the wall; averaged over column `i`'s width.
fn analytic(i: usize) -> f64 {
    let width = 2.0 / RES as f64;
    let steps = 64;
    (0..steps)
        .map(|k| {
            let d = (i as f64 + (k as f64 + 0.5) / steps as f64) * width;
            std::f64::consts::PI * (1.0 - 0.5 * (1.0 - d / (d * d + 1.0).sqrt()))
        })
        .sum::<f64>()
        / steps as f64
}

/// Mean and largest relative difference of `a` from `b`.
fn errors(a: &[f64], b: &[f64]) -> (f64, f64) {
    let rel: Vec<f64> = a.iter().zip(b).map(|(x, y)| (x - y).abs() / y).collect();
    (rel.iter().sum::<f64>() / rel.len() as f64, rel.iter().cloned().fold(0.0, f64::max))
}

#[test]
fn interpolated_irradiance_matches_brute_force_and_the_analytic_wall() {
    let truth: Vec<f64> = (0..RES).map(analytic).collect();
    let (brute, brute_stats) = render(&wall_scene("finalgather on finalgather points 0"), 16, Some(256));
    assert_eq!(brute_stats.fg_points, 0, "brute force makes no points");
    let brute = columns(&brute);
    let (cached, stats) = render(&wall_scene("finalgather on finalgather accuracy 512 0.5 0.005"), 4, None);
    let cached = columns(&cached);
    let (b_mean, b_max) = errors(&brute, &truth);
    let (c_mean, c_max) = errors(&cached, &truth);
    let (cb_mean, cb_max) = errors(&cached, &brute);
    eprintln!(
        "brute vs analytic {b_mean:.4}/{b_max:.4}, cached vs analytic {c_mean:.4}/{c_max:.4}, \
         cached vs brute {cb_mean:.4}/{cb_max:.4}; {} final gather points for {} shading points, \
         {} rays (brute force {} rays)",
        stats.fg_points,
        stats.samples,
        stats.total_rays(),
        brute_stats.total_rays()
    );
    assert!(b_mean < 0.01 && b_max < 0.03, "brute force vs analytic {b_mean}, {b_max}");
    assert!(cb_mean < 0.02 && cb_max < 0.04, "cached vs brute force {cb_mean}, {cb_max}");
    assert!(c_mean < 0.02 && c_max < 0.04, "cached vs analytic {c_mean}, {c_max}");
    // Far fewer gathers than shading points.
    assert!(stats.fg_points > 0 && stats.fg_points * 10 < stats.samples, "{} points", stats.fg_points);
}

#[test]
fn more_accuracy_gives_less_error() {
    let truth: Vec<f64> = (0..RES).map(analytic).collect();
    let err = |rays: u32| {
        let (px, stats) =
            render(&wall_scene(&format!("finalgather on finalgather accuracy {rays} 0.5 0.005")), 1, None);
        let e = errors(&columns(&px), &truth).0;
        eprintln!("accuracy {rays}: mean error {e:.4}, {} points", stats.fg_points);
        e
    };
    let (low, high) = (err(16), err(512));
    assert!(high < low, "accuracy 512 error {high} not below accuracy 16 error {low}");
}

#[test]
fn open_floor_needs_only_coarse_points_and_is_exact() {
    // No wall (it is hidden): E = π everywhere, with every lookup interpolated.
    let text = wall_scene("finalgather on finalgather accuracy 64")
        .replace(r#"instance "wall_inst" "wall" end instance"#, r#"instance "wall_inst" "wall" hide on end instance"#);
    let (px, stats) = render(&text, 1, None);
    for p in &px {
        assert!((p[0] - std::f32::consts::PI).abs() < 1e-4, "{}", p[0]);
    }
    // The coarsest grid (every 32 pixels) covers the floor: 2 × 2 points at 48².
    assert!(stats.fg_points <= 4, "{} points", stats.fg_points);
}

#[test]
fn automatic_mode_interpolates_the_nearest_points() {
    let truth: Vec<f64> = (0..RES).map(analytic).collect();
    let opts = r#"finalgather on finalgather accuracy 512 "finalgather mode" "automatic" "finalgather points" 8"#;
    let (px, stats) = render(&wall_scene(opts), 1, None);
    let (mean, max) = errors(&columns(&px), &truth);
    eprintln!("automatic: {mean:.4}/{max:.4} with {} points", stats.fg_points);
    assert!(mean < 0.03 && max < 0.06, "automatic vs analytic {mean}, {max}");
}

#[test]
fn the_cache_is_the_same_for_any_thread_count() {
    let text = wall_scene("finalgather on finalgather accuracy 64 0.5 0.005");
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap().install(|| render(&text, 1, None));
    let four = rayon::ThreadPoolBuilder::new().num_threads(4).build().unwrap().install(|| render(&text, 1, None));
    assert_eq!(one.1.fg_points, four.1.fg_points);
    assert!(one.0 == four.0, "images differ between 1 and 4 threads");
}
