//! A module function that calls `base::sun_and_sky` as the scene's environment gets the
//! sun's share of the path engine's environment samples, as the `.mi` shader
//! `mdl::base::sun_and_sky` does: the same sun lobe (direction, cone, share), a Lambert
//! plane under it agrees with the one under the native sky within noise and with albedo/π
//! × (the sun's and the sky's irradiance, from the sky's own model), and at equal samples
//! its mean squared error is far lower than without the share (which misses the sun,
//! half a real sun across, nearly always).

use crate::environment::plane_stats;
use crate::support;

use std::f32::consts::PI;

use glam::Vec3A;
use mdl::sky::SunAndSky;
use render::environment::{sun_lobe_of, Environment};

const MODULE: &str = r#"mdl 1.7;
import ::base::*;
import ::df::*;

// Z up, the sun 60° up, its disk half the real sun's (MDL's default scale).
export color day(float3 sun = float3(0.5, 0.0, 0.8660254)) {
    return base::sun_and_sky(y_is_up: false, sun_direction: sun, sun_disk_scale: 0.5,
        sun_disk_intensity: 1.0, multiplier: 0.1, rgb_unit_conversion: color(0.0001),
        saturation: 1.0).tint;
}
export material matte(color tint = color(0.6)) = material(surface: material_surface(
    scattering: df::diffuse_reflection_bsdf(tint: tint)));
"#;

const NATIVE: &str = r#"shader "sky" "mdl::base::sun_and_sky(bool,float,color,float,float,float,float,float,color,color,float3,float,float,float,bool,int,bool)" ("y_is_up" off, "sun_direction" 0.5 0 0.8660254, "sun_disk_scale" 0.5, "sun_disk_intensity" 1, "multiplier" 0.1, "rgb_unit_conversion" 0.0001 0.0001 0.0001, "saturation" 1)"#;

/// A plane facing +Z (up) filling an 8 × 8 orthographic view, under the environment
/// shader `sky_shader` (named "sky").
fn scene(sky_shader: &str) -> String {
    format!(
        r#"{sky_shader}
shader "mat" "mdl::skies::matte" ()
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
    )
}

#[test]
fn a_sky_called_in_a_module_function_gets_the_suns_share_of_samples() {
    let dir = std::env::temp_dir().join(format!("mira_mdl_sky_share_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("skies.mdl"), MODULE).unwrap();
    let spp = 64;
    let mut results = Vec::new();
    for sky in [NATIVE, "shader \"sky\" \"mdl::skies::day\" ()"] {
        let parsed = mi::parse_str("t.mi", &scene(sky));
        let built = support::build_parsed(&parsed, 8, std::slice::from_ref(&dir));
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        let (world, shading) = (&built.built.world, &built.built.shading);
        let accel = render::accel::build(world, render::Backend::default_available());
        let node = shading.environment.expect("an environment");
        let lobe = sun_lobe_of(world, accel.as_ref(), shading, node).expect("a sun lobe");
        let env = Environment::of_scene(world, accel.as_ref(), shading).expect("an environment");
        let with_share = plane_stats(world, &env, 8, spp);
        let without = plane_stats(world, &env.with_sun(None), 8, spp);
        results.push((lobe, with_share, without));
    }
    let [(native_lobe, native, _), (lobe, module, module_without)] = results[..] else { unreachable!() };
    eprintln!(
        "plane under the sky, {spp} spp: native {native:?}; module {module:?}, without the share {module_without:?}"
    );
    assert!((lobe.direction - native_lobe.direction).abs().max_element() < 1e-6, "{lobe:?} {native_lobe:?}");
    assert!((lobe.cos_max - native_lobe.cos_max).abs() < 1e-7 && (lobe.share - native_lobe.share).abs() < 1e-5);
    // Means within four standard errors of their difference (64 pixels each).
    let error = ((native.1 + module.1) / 64.0).sqrt();
    assert!((module.0 - native.0).abs() < 4.0 * error + 1e-4 * native.0, "{module:?} vs {native:?}");
    // The exact plane: albedo/π × (E_sun cos θ + ∫ L_sky cos θ dω), red channel.
    let mut sky = SunAndSky::default();
    sky.sky.y_is_up = false;
    sky.sky.sun_direction = Vec3A::new(0.5, 0.0, 0.866_025_4);
    sky.sky.sun_disk_scale = 0.5;
    sky.sky.sun_disk_intensity = 1.0;
    sky.sky.multiplier = 0.1;
    sky.sky.rgb_unit_conversion = Vec3A::splat(1e-4);
    sky.sky.saturation = 1.0;
    let sun = sky.sun().expect("a sun");
    let (n, m) = (200, 400);
    let mut e_sky = 0.0f64;
    for i in 0..n {
        let r = ((i as f32 + 0.5) / n as f32).sqrt();
        let z = (1.0 - r * r).max(0.0).sqrt();
        for j in 0..m {
            let phi = 2.0 * PI * (j as f32 + 0.5) / m as f32;
            e_sky += f64::from(sky.sky_radiance(Vec3A::new(r * phi.cos(), r * phi.sin(), z)).x);
        }
    }
    let e_sky = e_sky * std::f64::consts::PI / f64::from(n * m);
    let exact = 0.6 / std::f64::consts::PI * (f64::from(sun.irradiance.x * sun.direction.z) + e_sky);
    let mse = |(mean, var): (f64, f64)| (mean - exact) * (mean - exact) + var / 64.0;
    eprintln!("exact {exact}: mean squared error {} with the share, {} without", mse(module), mse(module_without));
    assert!((module.0 - exact).abs() < 4.0 * (module.1 / 64.0).sqrt() + 0.01 * exact, "{module:?} vs {exact}");
    assert!(mse(module) * 4.0 < mse(module_without), "{} with the share, {} without", mse(module), mse(module_without));
    std::fs::remove_dir_all(&dir).ok();
}
