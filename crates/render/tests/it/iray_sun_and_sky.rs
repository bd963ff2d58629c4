//! Iray's `base::sun_and_sky` as the options' `environment_function` in the path engine: a
//! white-ish Lambertian plane under it shows albedo/π × (the sun's irradiance × cos θ +
//! the sky's irradiance), both computed from the shader's own model.

use crate::support;

use std::f32::consts::PI;

use glam::Vec3A;
use mdl::sky::SunAndSky;
use mia::sky::PhysicalSky;
use render::EngineKind;

/// Z up; the sun 60° up, its disk `scale` × the real sun's.
fn sky_params(scale: f32) -> String {
    format!(
        r#""y_is_up" off, "sun_direction" 0.5 0 0.8660254, "sun_disk_scale" {scale},
    "sun_disk_intensity" 1, "multiplier" 0.1, "rgb_unit_conversion" 0.0001 0.0001 0.0001,
    "saturation" 1"#
    )
}

const ALBEDO: f32 = 0.6;

fn sky(scale: f32) -> SunAndSky {
    let d = SunAndSky::default();
    SunAndSky {
        on: true,
        sky: PhysicalSky {
            y_is_up: false,
            sun_direction: Vec3A::new(0.5, 0.0, 0.866_025_4),
            sun_disk_scale: scale,
            sun_disk_intensity: 1.0,
            multiplier: 0.1,
            rgb_unit_conversion: Vec3A::splat(1e-4),
            saturation: 1.0,
            ..d.sky
        },
    }
}

fn render_plane(spp: u32, scale: f32) -> Vec<[f32; 4]> {
    let sky = sky_params(scale);
    let text = format!(
        r#"
shader "sky" "mdl::base::sun_and_sky(bool,float,color,float,float,float,float,float,color,color,float3,float,float,float,bool,int,bool)" ({sky})
shader "mat" "mdl::nvidia::core_definitions::diffuse" ("diffuse_color" {ALBEDO} {ALBEDO} {ALBEDO})
options "opt" filter box 1 1
    attribute string "environment_function" "sky"
end options
camera "cam" focal infinity aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
object "plane" group
    -500 -500 -1  500 -500 -1  500 500 -1  -500 500 -1
    v 0 v 1 v 2 v 3 c 0 0 1 2 c 0 0 2 3
end group end object
instance "plane_inst" "plane" material "mat" end instance
instgroup "root" "cam_inst" "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    );
    let (pixels, messages) = support::render_text(&text, EngineKind::Path, Some(spp));
    assert!(messages.is_empty(), "{messages:?}");
    pixels
}

/// The sky's irradiance (without the sun) on a plane facing +Z: ∫ L cos θ dω over the
/// upper hemisphere by a 200 × 400 midpoint grid in (cos² θ, φ).
fn sky_irradiance(s: &SunAndSky) -> Vec3A {
    let (n, m) = (200, 400);
    let mut sum = Vec3A::ZERO;
    for i in 0..n {
        let r = ((i as f32 + 0.5) / n as f32).sqrt();
        let z = (1.0 - r * r).max(0.0).sqrt();
        for j in 0..m {
            let phi = 2.0 * PI * (j as f32 + 0.5) / m as f32;
            sum += s.sky_radiance(Vec3A::new(r * phi.cos(), r * phi.sin(), z));
        }
    }
    sum * (PI / (n * m) as f32)
}

/// The plane under a sky whose sun disk is `scale` × the real sun's: albedo/π × (sun +
/// sky irradiance) within 3 % per channel.
fn check_plane(scale: f32) {
    let s = sky(scale);
    let sun = s.sun().expect("a sun");
    let e_sun = sun.irradiance * sun.direction.z;
    let e_sky = sky_irradiance(&s);
    let want = (e_sun + e_sky) * (ALBEDO / PI);
    let pixels = render_plane(256, scale);
    let n = pixels.len() as f32;
    let got = pixels.iter().fold(Vec3A::ZERO, |a, p| a + Vec3A::new(p[0], p[1], p[2])) / n;
    eprintln!("plane (disk × {scale}): rendered {got}, expected {want} (sun {e_sun}, sky {e_sky})");
    // The sun dominates (it is the test's point) …
    assert!(e_sun.y > 2.0 * e_sky.y, "{e_sun} {e_sky}");
    // … and the rendered plane matches within 3 % per channel.
    for k in 0..3 {
        assert!((got[k] / want[k] - 1.0).abs() < 0.03, "disk × {scale}, channel {k}: {got} vs {want}");
    }
}

#[test]
fn a_lambert_plane_under_sun_and_sky_shows_albedo_over_pi_times_the_irradiance() {
    check_plane(4.0);
}

/// At MDL's default disk size (½ × the real sun, a fifth of an importance-map texel) the sun
/// is found by its own sample share.
#[test]
fn the_default_small_sun_lights_the_plane_too() {
    check_plane(0.5);
}
