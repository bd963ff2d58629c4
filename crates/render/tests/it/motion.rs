//! The classic engine's motion buffer: raster-space motion of each pixel's first hit over
//! the shutter interval, from instance `motion transform`s.

use std::sync::atomic::AtomicBool;

use render::{EngineKind, Settings};
use shader::{Shading, ShadingOptions};

/// An orthographic 2×2 view at 8×8 pixels (4 pixels per unit) onto a quad at z = −5 whose
/// instance carries `motion`.
fn motion_buffer(motion: &str) -> Vec<[f32; 2]> {
    motion_buffer_with(motion, "")
}

/// [`motion_buffer`] with more `options` statements.
fn motion_buffer_with(motion: &str, options: &str) -> Vec<[f32; 2]> {
    let text = format!(
        r#"
options "opt" filter box 1 1 shutter 0 1 {options} end options
camera "cam" focal infinity aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
material "m" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 0.5 0.5 0.5) end material
object "quad" group
    -2 -2 -5  2 -2 -5  2 2 -5  -2 2 -5
    v 0 v 1 v 2 v 3
    c "m" 0 1 2 3
end group end object
instance "quad_inst" "quad" {motion} end instance
instgroup "root" "cam_inst" "quad_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    );
    let parsed = mi::parse_str("t.mi", &text);
    assert!(parsed.diagnostics.list.is_empty(), "parse diagnostics");
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    let (shading, _) = Shading::build(&scene, &ShadingOptions::default(), &material::registry());
    let world = render::World::from_scene(&scene);
    let accel = render::accel::build(&world, render::Backend::default_available());
    let settings = Settings { engine: EngineKind::Classic, spp: Some(1), ..Settings::default() };
    let (film, _) = render::render(&world, accel.as_ref(), Some(&shading), &settings, &AtomicBool::new(false), &|_| {});
    film.motion()
}

#[test]
fn a_quad_moving_one_unit_right_moves_four_pixels() {
    // `motion transform` is world → object at the shutter's close: +1 in x in the world.
    let m = motion_buffer("motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1");
    assert_eq!(m.len(), 64);
    for (i, v) in m.iter().enumerate() {
        assert!((v[0] - 4.0).abs() < 1e-4 && v[1].abs() < 1e-4, "pixel {i}: {v:?}");
    }
    // Upwards by 0.5: two pixels up (mental ray's raster y points up).
    let m = motion_buffer("motion transform 1 0 0 0  0 1 0 0  0 0 1 0  0 -0.5 0 1");
    assert!(m.iter().all(|v| v[0].abs() < 1e-4 && (v[1] - 2.0).abs() < 1e-4), "{:?}", m[0]);
}

#[test]
fn a_static_quad_has_no_motion() {
    let m = motion_buffer("");
    assert!(m.iter().all(|v| *v == [0.0, 0.0]));
}

/// With motion blur on (`motion on`), the quad is hit where it is at each sample's time,
/// and the motion buffer still holds the motion over the whole interval: 4 pixels right
/// wherever the first sample hit it (the quad covers the whole view all the time).
#[test]
fn the_motion_buffer_is_the_same_with_motion_blur() {
    let m = motion_buffer_with("motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1", "motion on");
    for (i, v) in m.iter().enumerate() {
        assert!((v[0] - 4.0).abs() < 1e-3 && v[1].abs() < 1e-3, "pixel {i}: {v:?}");
    }
}
