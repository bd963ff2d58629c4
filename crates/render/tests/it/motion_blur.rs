//! Motion blur against coverage worked out by hand: an orthographic camera looks at the
//! edge of a large quad that moves across the view while the shutter is open; a pixel's
//! alpha is then the fraction of the (shape-weighted) shutter time during which the quad
//! covers it. Both engines, both acceleration backends, moving objects and a moving
//! camera, vertex motion over two motion steps, box and triangle shutters.

use crate::support;

use std::sync::atomic::AtomicBool;

use render::{Backend, EngineKind, Settings};
use support::moving_quad::{alpha, assert_columns, backends, box_ramp, render_alpha, scene};

/// Checks that each column's alpha, averaged over the rows, is `expect(x)` at the column's
/// centre x within 0.03 (the coverage is linear across each pixel, so its mean over the
/// pixel is its value at the centre).
fn assert_profile(a: &[f32], expect: impl Fn(f32) -> f32, what: &str) {
    assert_columns(a, |x0, x1| expect(0.5 * (x0 + x1)), 0.03, what);
}

const MOVE_RIGHT_2: &str = "motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -2 0 0 1";

#[test]
fn a_moving_quad_covers_each_pixel_for_its_share_of_the_shutter() {
    let text = scene("motion on shutter 0 1", MOVE_RIGHT_2, "", [""; 4], "");
    for engine in [EngineKind::Path, EngineKind::Classic] {
        for backend in backends() {
            let a = alpha(&text, engine, backend);
            assert_profile(&a, box_ramp, &format!("{engine:?} {backend:?}"));
        }
    }
}

/// The same quad instanced twice (the second far behind the camera): the acceleration
/// structures keep the shared mesh once and move the instance (or the mesh's vertices)
/// instead of flattening it.
#[test]
fn a_moving_shared_mesh_blurs_the_same() {
    let moving_instance = scene("motion on shutter 0 1", MOVE_RIGHT_2, "", [""; 4], "");
    let moving_vertices = scene("motion on shutter 0 1", "", "", ["m 4", "m 5", "m 5", "m 4"], "0 0 0  2 0 0");
    for text in [moving_instance, moving_vertices] {
        let text = text.replace(
            r#"instgroup "root" "cam_inst" "quad_inst" end instgroup"#,
            r#"instance "far" "quad" material "m" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -100 1 end instance
instgroup "root" "cam_inst" "quad_inst" "far" end instgroup"#,
        );
        for backend in backends() {
            let a = alpha(&text, EngineKind::Path, backend);
            assert_profile(&a, box_ramp, &format!("shared {backend:?}"));
        }
    }
}

/// A camera moving 2 units to the left over the shutter sees the static quad move 2 units
/// to the right: the same ramp.
#[test]
fn a_moving_camera_blurs_the_static_quad() {
    let text = scene("motion on shutter 0 1", "", "motion transform 1 0 0 0  0 1 0 0  0 0 1 0  2 0 0 1", [""; 4], "");
    for engine in [EngineKind::Path, EngineKind::Classic] {
        for backend in backends() {
            let a = alpha(&text, engine, backend);
            assert_profile(&a, box_ramp, &format!("camera {engine:?} {backend:?}"));
        }
    }
}

/// A shutter from 0.25 to 0.75 of the motion interval (`shutter 0.25 0.75`) sees half
/// the motion: the edge goes from x = 0.5 to x = 1.5.
#[test]
fn a_shorter_shutter_makes_a_shorter_trail() {
    let text = scene("motion on shutter 0.25 0.75", MOVE_RIGHT_2, "", [""; 4], "");
    let a = alpha(&text, EngineKind::Path, Backend::default_available());
    assert_profile(&a, |x| (1.5 - x).clamp(0.0, 1.0), "shutter 0.25 0.75");
}

/// The triangle shutter (`"shutter full open" 0.5`, `"shutter full close" 0.5`): the
/// coverage at x is the chance that the time s ≥ x/2 under the triangle density, 1 − F(x/2)
/// with F(s) = 2s² below ½ and 1 − 2(1 − s)² above.
#[test]
fn a_triangle_shutter_weights_the_middle_of_the_interval() {
    let text = scene(
        r#"motion on shutter 0 1 "shutter full open" 0.5 "shutter full close" 0.5"#,
        MOVE_RIGHT_2,
        "",
        [""; 4],
        "",
    );
    let cdf = |s: f32| if s < 0.5 { 2.0 * s * s } else { 1.0 - 2.0 * (1.0 - s) * (1.0 - s) };
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let a = alpha(&text, engine, Backend::default_available());
        assert_profile(&a, |x| if x <= 0.0 { 1.0 } else { 1.0 - cdf((x / 2.0).min(1.0)) }, &format!("{engine:?}"));
    }
}

/// Per-vertex motion vectors (`m`) instead of an instance motion: the right edge's
/// vertices move +2 in x, the left edge's stay, so the quad stretches; the coverage of the
/// moving edge is the same ramp.
#[test]
fn vertex_motion_vectors_blur_like_instance_motion() {
    let text = scene("motion on shutter 0 1", "", "", ["m 4", "m 5", "m 5", "m 4"], "0 0 0  2 0 0");
    for engine in [EngineKind::Path, EngineKind::Classic] {
        for backend in backends() {
            let a = alpha(&text, engine, backend);
            assert_profile(&a, box_ramp, &format!("vertex motion {engine:?} {backend:?}"));
        }
    }
}

/// A scene where nothing moves renders bit for bit the same with `motion on` and a
/// shutter as without: no time is drawn, nothing is interpolated.
#[test]
fn a_static_scene_is_the_same_with_motion_on() {
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let still = support::render_text(&scene("", "", "", [""; 4], ""), engine, Some(16)).0;
        let on = support::render_text(&scene("motion on shutter 0 1", "", "", [""; 4], ""), engine, Some(16)).0;
        assert!(still.iter().any(|p| p[3] > 0.0) && still.iter().any(|p| p[3] == 0.0));
        assert_eq!(still, on, "{engine:?}");
    }
}

/// With `motion off` on the instance, its motion transform is ignored: a sharp edge.
#[test]
fn motion_off_keeps_an_instance_still() {
    let text = scene("motion on shutter 0 1", &format!("{MOVE_RIGHT_2} motion off"), "", [""; 4], "");
    let a = alpha(&text, EngineKind::Path, Backend::default_available());
    assert_profile(&a, |x| if x <= 0.0 { 1.0 } else { 0.0 }, "motion off");
}

/// Two motion steps (two `m` vectors per vertex, `motion steps 2`): the right edge moves
/// along a bent path, 1.5 right and 1 up by the middle of the interval, then to 2 right and
/// back down by its end. The edge's x runs at 3 units per interval, then at 1, so the
/// coverage falls as 1 − x/3 up to x = 1.5 and as 2 − x beyond (one step would give
/// 1 − x/2: 0.25 more at x = 1.5).
#[test]
fn two_motion_steps_follow_a_bent_path() {
    let text = scene(
        "motion on motion steps 2 shutter 0 1",
        "",
        "",
        ["m 6 m 6", "m 4 m 5", "m 4 m 5", "m 6 m 6"],
        "1.5 1 0  2 0 0  0 0 0",
    );
    let expect = |x: f32| {
        if x <= 0.0 {
            1.0
        } else if x <= 1.5 {
            1.0 - x / 3.0
        } else {
            (2.0 - x).max(0.0)
        }
    };
    for engine in [EngineKind::Path, EngineKind::Classic] {
        for backend in backends() {
            let a = alpha(&text, engine, backend);
            assert_profile(&a, expect, &format!("two steps {engine:?} {backend:?}"));
        }
    }
}

/// A point light at height h = 1 that moves from x = −a to x = a (a = 1) over the shutter
/// lights the point below its path's middle with the time average of its irradiance there.
/// `mib_light_point` without attenuation does not fall off with distance (mental ray's
/// non-physical light), so the irradiance is I·cos θ = I·h/d and its average over the path
/// is I·(h/a)·asinh(a/h): asinh(1) = 0.88137 of what the light standing at x = 0 gives.
/// Path engine, both backends; the view is a 0.02-wide patch of the lit plane.
#[test]
fn a_moving_light_lights_with_its_time_average() {
    let text = |light: &str| {
        format!(
            r#"
options "opt" filter box 1 1 motion on shutter 0 1 end options
camera "cam" focal infinity aperture 0.02 aspect 1 resolution 4 4 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
light "l" "mib_light_point" ("color" 1 1 1) origin 0 0 0 end light
instance "l_inst" "l" {light} end instance
material "m" "mib_illum_lambert" ("diffuse" 0.6 0.6 0.6, "lights" ["l_inst"]) end material
object "plane" group
    -10 -10 0  10 -10 0  10 10 0  -10 10 0
    v 0 v 1 v 2 v 3
    c "m" 0 1 2 3
end group end object
instance "plane_inst" "plane" material "m" end instance
instgroup "root" "cam_inst" "l_inst" "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#
        )
    };
    let mean_red = |text: &str, backend: Backend| {
        let c = support::compile(text);
        let world = render::World::from_scene_shaded(&c.scene, Some(&c.shading));
        let accel = render::accel::build(&world, backend);
        let settings = Settings { engine: EngineKind::Path, spp: Some(64), ..Settings::default() };
        let (film, _) =
            render::render(&world, accel.as_ref(), Some(&c.shading), &settings, &AtomicBool::new(false), &|_| {});
        film.rgba().iter().map(|p| p[0]).sum::<f32>() / 16.0
    };
    for backend in backends() {
        let still = mean_red(&text("transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -1 1"), backend);
        let moving = mean_red(
            &text(
                "transform 1 0 0 0  0 1 0 0  0 0 1 0  1 0 -1 1  motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 -1 1",
            ),
            backend,
        );
        assert!(still > 0.0, "{still}");
        let ratio = moving / still;
        assert!((ratio - 1.0f32.asinh()).abs() < 0.005, "{backend:?}: {ratio}");
    }
}

/// A shutter that carries a moving quad beyond single precision (`shutter 0 1e30`) does
/// not break the render: the quad is kept still, with a warning that says so.
#[test]
fn motion_beyond_single_precision_is_kept_still_with_a_warning() {
    let text = scene("motion on shutter 0 1e30", MOVE_RIGHT_2, "", [""; 4], "");
    for backend in backends() {
        let (a, warnings) = render_alpha(&text, EngineKind::Path, backend, 64);
        assert!(warnings.iter().any(|w| w.contains("beyond single precision")), "{warnings:?}");
        assert_profile(&a, |x| if x <= 0.0 { 1.0 } else { 0.0 }, &format!("{backend:?}"));
    }
}

/// The same seed gives the same blurred image bit for bit on one thread and on three (the
/// time is drawn from each pixel sample's own numbers), in both engines.
#[test]
fn blurred_images_do_not_depend_on_the_thread_count() {
    let text = scene("motion on shutter 0 1", MOVE_RIGHT_2, "", ["m 4", "m 5", "m 5", "m 4"], "0 0 0  0.5 0.3 0");
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a thread pool");
            pool.install(|| alpha(&text, engine, Backend::Rust))
        };
        let (one, three) = (on(1), on(3));
        assert!(one.iter().any(|a| *a > 0.0 && *a < 1.0), "{engine:?}: no blur");
        assert_eq!(
            one.iter().map(|a| a.to_bits()).collect::<Vec<_>>(),
            three.iter().map(|a| a.to_bits()).collect::<Vec<_>>()
        );
    }
}

/// A thin bar (x ∈ [0, 1.9], |y| ≤ 0.1 in its object space, z = −5) turning 90° about the
/// z axis through its end over a `shutter 0 1`, seen in a 16×16 orthographic view of
/// [−2, 2]²: each pixel's alpha is the share of its area and of the shutter during which
/// the turning bar covers it. The reference integrates that with the exact rotation
/// (8×8 points per pixel × 64 times). The bar keeps its area 0.38 all along, so the image's
/// total coverage is 0.38 / 0.0625 = 6.08 pixels within 2 %; with the two matrices
/// interpolated linearly the bar would shrink by (1 − s)² + s² and cover 2/3 of that.
/// Each pixel matches within 0.06 and the pixels' mean absolute error is below 0.005 at
/// 256 samples per pixel (measured: total 6.023, worst pixel 0.030, mean 0.0015 in both
/// engines on both backends).
#[test]
fn a_turning_bar_sweeps_a_quarter_disc_at_its_size() {
    const N: usize = 16;
    const PIXEL: f32 = 4.0 / N as f32;
    let (length, half_width) = (1.9f32, 0.1f32);
    let text = format!(
        r#"
options "opt" filter box 1 1 motion on shutter 0 1 end options
camera "cam" focal infinity aperture 4 aspect 1 resolution {N} {N} end camera
instance "cam_inst" "cam" end instance
material "m" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 1 1 1, "diffuse" 0 0 0) end material
object "bar" group
    0 {nw} -5  {length} {nw} -5  {length} {half_width} -5  0 {half_width} -5
    v 0 v 1 v 2 v 3
    c "m" 0 1 2 3
end group end object
instance "bar_inst" "bar" material "m" motion transform 0 -1 0 0  1 0 0 0  0 0 1 0  0 0 0 1 end instance
instgroup "root" "cam_inst" "bar_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        nw = -half_width
    );
    // The bar covers (x, y) at shutter time s when the point turned back by 90°·s lies on it.
    let covered = |x: f32, y: f32, s: f32, rotation: bool| {
        let (u, v) = if rotation {
            let (sin, cos) = (std::f32::consts::FRAC_PI_2 * s).sin_cos();
            (cos * x + sin * y, -sin * x + cos * y)
        } else {
            // Linear matrices: object → world is [[1 − s, −s], [s, 1 − s]]; invert it.
            let det = (1.0 - s) * (1.0 - s) + s * s;
            (((1.0 - s) * x + s * y) / det, (-s * x + (1.0 - s) * y) / det)
        };
        (0.0..=length).contains(&u) && v.abs() <= half_width
    };
    let reference = |rotation: bool| -> Vec<f32> {
        let (points, times) = (8, 64);
        let mut out = vec![0.0; N * N];
        for (k, value) in out.iter_mut().enumerate() {
            let (col, row) = (k % N, k / N);
            let mut hits = 0u32;
            for i in 0..points * points {
                let x = -2.0 + (col as f32 + ((i % points) as f32 + 0.5) / points as f32) * PIXEL;
                let y = 2.0 - (row as f32 + ((i / points) as f32 + 0.5) / points as f32) * PIXEL;
                hits += (0..times).filter(|t| covered(x, y, (*t as f32 + 0.5) / times as f32, rotation)).count() as u32;
            }
            *value = hits as f32 / (points * points * times) as f32;
        }
        out
    };
    let expect = reference(true);
    let area_pixels = 2.0 * length * half_width / (PIXEL * PIXEL);
    let total: f32 = expect.iter().sum();
    assert!((total / area_pixels - 1.0).abs() < 0.02, "reference covers {total} pixels, not {area_pixels}");
    let shrunk: f32 = reference(false).iter().sum();
    assert!((shrunk / area_pixels - 2.0 / 3.0).abs() < 0.02, "linear matrices cover {shrunk}");
    for engine in [EngineKind::Path, EngineKind::Classic] {
        for backend in backends() {
            let (a, _) = render_alpha(&text, engine, backend, 256);
            let what = format!("{engine:?} {backend:?}");
            let sum: f32 = a.iter().sum();
            assert!((sum / area_pixels - 1.0).abs() < 0.02, "{what}: covers {sum} pixels, not {area_pixels}");
            let errors: Vec<f32> = a.iter().zip(&expect).map(|(a, e)| (a - e).abs()).collect();
            let worst = errors.iter().cloned().fold(0.0, f32::max);
            let mean = errors.iter().sum::<f32>() / errors.len() as f32;
            eprintln!("{what}: total {sum} vs {area_pixels}, worst pixel {worst}, mean error {mean}");
            assert!(worst < 0.06 && mean < 0.005, "{what}: worst pixel off by {worst}, mean {mean}");
        }
    }
}
