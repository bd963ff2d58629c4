//! Shading that looks at the scene around a hit sees it at the ray's shutter time: hair
//! ribbons turned towards the camera turn with a moving instance or camera, and
//! `mia_roundcorners`' probe rays find the edges of a moving box where they are.

use crate::support;

use std::f32::consts::PI;

use render::{Backend, EngineKind, Settings};

/// Renders `text` with `engine` at `spp` samples per pixel on each backend compiled in:
/// RGBA pixels (rows from the top); also checks that the scene had nothing to report and
/// the world nothing about motion.
fn render(text: &str, engine: EngineKind, spp: u32) -> Vec<(Backend, Vec<[f32; 4]>)> {
    let c = support::compile(text);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let world = render::World::from_scene_shaded(&c.scene, Some(&c.shading));
    assert!(!world.warnings.iter().any(|w| w.contains("move")), "{:?}", world.warnings);
    [Backend::Rust, Backend::Embree]
        .into_iter()
        .filter(|b| b.available())
        .map(|backend| {
            let accel = render::accel::build(&world, backend);
            let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
            let (film, _) = render::render(
                &world,
                accel.as_ref(),
                Some(&c.shading),
                &settings,
                &std::sync::atomic::AtomicBool::new(false),
                &|_| {},
            );
            (backend, film.rgba())
        })
        .collect()
}

/// A world → object transform in `.mi` order: the inverse of object → world `m`.
fn mi_transform(m: glam::Mat4) -> String {
    m.inverse().to_cols_array().map(|v| format!("{v}")).join(" ")
}

/// One straight hair of radius 0.2 up the y axis (y ∈ [−1, 1]) of its object, placed at
/// z = −5 and turning about its own axis by `turn` degrees over the shutter (`shutter 0 1`),
/// seen by a 20×20 orthographic view 2 units wide: an opaque constant material.
fn hair_scene(turn: f32) -> String {
    let place = |deg: f32| {
        mi_transform(
            glam::Mat4::from_translation(glam::Vec3::new(0.0, 0.0, -5.0))
                * glam::Mat4::from_rotation_y(deg.to_radians()),
        )
    };
    format!(
        r#"
options "opt" filter box 1 1 motion on shutter 0 1 end options
camera "cam" focal infinity aperture 2 aspect 1 resolution 20 20 end camera
instance "cam_inst" "cam" end instance
material "m" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 1 1 1, "diffuse" 0 0 0) end material
object "fur" hair
    material "m"
    radius 0.2
    scalar [ 6 ]
    0 -1 0  0 1 0
    hair [ 2 ]
    0 6
end hair end object
instance "fur_inst" "fur" transform {} motion transform {} end instance
instgroup "root" "cam_inst" "fur_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        place(0.0),
        place(turn)
    )
}

/// The hair's mean width seen across rows 4 … 15 (its middle), scene units: the alpha
/// summed over each row times the pixel width (0.1), averaged.
fn seen_width(pixels: &[[f32; 4]]) -> f32 {
    let rows = 4..16;
    let n = rows.len() as f32;
    rows.map(|y| (0..20).map(|x| pixels[y * 20 + x][3]).sum::<f32>() * 0.1).sum::<f32>() / n
}

/// A hair turning 90° about its own axis while the shutter is open keeps showing the
/// camera its full width, 0.4, as mental ray's ray-facing ribbons do: the ribbon facing
/// the camera is turned towards it at each time. Turned only at the shutter's opening it
/// would turn edge-on with the instance and show 0.4 · 2/π = 0.255 on average. The still
/// hair shows 0.4 too. Within 0.02, both engines, both backends.
#[test]
fn camera_facing_hair_keeps_facing_a_turning_instance() {
    for engine in [EngineKind::Classic, EngineKind::Path] {
        for (turn, want) in [(0.0, 0.4), (90.0, 0.4)] {
            for (backend, pixels) in render(&hair_scene(turn), engine, 64) {
                let w = seen_width(&pixels);
                eprintln!("{engine:?} {backend:?} turning {turn}°: width {w}");
                assert!((w - want).abs() < 0.02, "{engine:?} {backend:?} turning {turn}°: {w} vs {want}");
                assert!((w - 0.4 * 2.0 / PI).abs() > 0.1);
            }
        }
    }
}

/// A box whose top face (z = −5, facing the camera) ends at x = 0.5 in its object space,
/// moved by `placement`, its material showing `mia_roundcorners`' rounded normal (radius
/// 0.25, world space) as its colour; a 32×32 orthographic view 2 units wide, `options` in
/// the options.
fn corner_scene(options: &str, placement: &str) -> String {
    format!(
        r#"
options "opt" filter box 1 1 samples 0 2 {options} end options
camera "cam" focal infinity aperture 2 aspect 1 resolution 32 32 end camera
instance "cam_inst" "cam" end instance
shader "rc" "mia_roundcorners" ("radius" 0.25, "bump_mode" 6)
material "normal_mtl" "mib_color_mix" ("num" 0, "color_base" = "rc") end material
{}
instgroup "root" "cam_inst" "cube_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        support::box_object("cube", "normal_mtl", [-3.0, -3.0, -7.0], [0.5, 3.0, -5.0], placement)
    )
}

/// The x component of the rounded normal at distance `d` inside the edge: the fillet
/// profile's turn α(d) = 45° − asin(d/r · sin 45°) within the radius r = 0.25, 0 beyond.
fn rounded_x(d: f32) -> f32 {
    let r = 0.25;
    if d >= r || d < 0.0 {
        return 0.0;
    }
    (45f32.to_radians() - ((d / r) * 45f32.to_radians().sin()).asin()).sin()
}

/// `mia_roundcorners` on a box sliding 0.25 right over the shutter: its probe rays find
/// the edge where it is at each sample's time. With `shutter 1 1` (everything at motion
/// time 1) the image is the still box placed there, within 1e-4 per channel — where the
/// box at time 0 differs by more than 0.3 at the edge. Over a box shutter each column's
/// normal x (its mean over 28 rows at 16 samples per pixel) is the fillet profile averaged
/// over the column and over the edge's positions x_e = 0.5 + 0.25·t, within 0.03.
#[test]
fn roundcorners_probes_see_a_moving_box_where_it_is() {
    let slide = "motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -0.25 0 0 1";
    let there = "transform 1 0 0 0  0 1 0 0  0 0 1 0  -0.25 0 0 1";
    let moved = render(&corner_scene("motion on shutter 1 1", slide), EngineKind::Classic, 16);
    let still = render(&corner_scene("", there), EngineKind::Classic, 16);
    let at_zero = render(&corner_scene("", ""), EngineKind::Classic, 16);
    for (((backend, m), (_, s)), (_, z)) in moved.iter().zip(&still).zip(&at_zero) {
        let worst = m.iter().zip(s).flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs())).fold(0.0, f32::max);
        assert!(worst < 1e-4, "{backend:?}: shutter 1 1 vs the still box there: {worst}");
        let apart = m.iter().zip(z).map(|(a, b)| (a[0] - b[0]).abs()).fold(0.0, f32::max);
        assert!(apart > 0.3, "{backend:?}: time 1 vs time 0 differ by only {apart}");
    }
    let blurred = render(&corner_scene("motion on shutter 0 1", slide), EngineKind::Classic, 16);
    for (backend, pixels) in blurred {
        for col in 14..32 {
            let (x0, x1) = (-1.0 + col as f32 / 16.0, -1.0 + (col + 1) as f32 / 16.0);
            let mut want = 0.0;
            let steps = 64;
            for i in 0..steps {
                for j in 0..steps {
                    let x = x0 + (i as f32 + 0.5) / steps as f32 * (x1 - x0);
                    let edge = 0.5 + 0.25 * (j as f32 + 0.5) / steps as f32;
                    want += rounded_x(edge - x);
                }
            }
            want /= (steps * steps) as f32;
            // The column's mean over rows 2 … 29 (the box spans them all): the colour is
            // premultiplied, so where the face has moved away the pixel counts 0.
            let rows = 2..30;
            let n = rows.len() as f32;
            let got = rows.map(|row| pixels[row * 32 + col][0]).sum::<f32>() / n;
            assert!((got - want).abs() < 0.03, "{backend:?} column {col}: {got} want {want}");
        }
    }
}
