//! `base::lookup_volume_coefficients` and `base::volume_blackbody_emission` in module
//! materials: volume textures the tests write byte by byte (`mdl_textures3d::volume_file`),
//! read at the shading point's object-space position through the call's `transform`, with
//! `wrap_clip`. Each value is checked against the MDL SDK's definition worked out here from
//! the voxels: the density at voxel centres (and outside the unit cube: 0) scaling the
//! coefficients of the medium a path enters, the temperature as black body emission.

use std::path::PathBuf;

use bsdf::Rgb;
use glam::{Affine3A, Vec3A};
use material::mdl_modules::spectral::blackbody_rgb;
use material::{SurfaceMaterial, Varying};
use shader::State;

use crate::mdl_support::{close, compile_text_with, get};
use crate::mdl_textures3d::volume_file;

const MODULE: &str = r#"mdl 1.7;
import ::df::*;
import ::base::*;
import ::state::*;

// The unit cube of the textures is the object-space cube [-0.5, 1.5]^3: scaled by 1/2,
// moved by 1/4.
const float4x4 HALF = float4x4(0.5, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.25, 0.25, 0.25, 1.0);

export material smoke(uniform bool relative = false) = let {
    base::volume_coefficients c = base::lookup_volume_coefficients(texture_3d("./density.dds"),
        scattering_multiplier: color(2.0, 1.0, 0.5), absorption_multiplier: color(0.1, 0.2, 0.3),
        scattering_offset: color(0.05), absorption_offset: color(0.01, 0.02, 0.03),
        transform: HALF, density_multiplier: 2.0, density_relative_to_size: relative);
} in material(
    surface: material_surface(scattering: df::specular_bsdf(mode: df::scatter_reflect_transmit)),
    ior: color(1.0),
    volume: material_volume(scattering_coefficient: c.scattering_coefficient,
        absorption_coefficient: c.absorption_coefficient));

export material fire(uniform texture_3d density = texture_3d()) = material(
    surface: material_surface(emission: material_emission(emission: df::diffuse_edf(),
        intensity: base::volume_blackbody_emission(texture_3d("./temperature.dds"), density,
            temperature_mult: 1000.0, temperature_offset: 500.0, scale: 2.0, tint: color(1.0, 0.5, 0.25),
            transform: HALF))));

export material glowing_gas() = material(
    surface: material_surface(scattering: df::specular_bsdf(mode: df::scatter_reflect_transmit)),
    ior: color(1.0),
    volume: material_volume(absorption_coefficient: color(1.0),
        emission_intensity: base::volume_blackbody_emission(texture_3d("./temperature.dds"),
            temperature_mult: 1000.0, temperature_offset: 500.0, scale: 2.0, tint: color(1.0, 0.5, 0.25),
            transform: HALF)));
"#;

/// Density voxel (i, j, k) (j = 0 the bottom row): a colour per voxel.
fn density(i: usize, j: usize, k: usize) -> [f32; 4] {
    [0.1 + 0.4 * i as f32, 0.2 + 0.3 * j as f32, 0.05 + 0.6 * k as f32, 1.0]
}

/// Temperature voxel (i, j, k): 1 … 8 (× 1000 + 500 kelvin in `fire`).
fn temperature(i: usize, j: usize, k: usize) -> [f32; 4] {
    let t = 1.0 + (i + 2 * j + 4 * k) as f32;
    [t, 0.0, 0.0, 1.0]
}

/// A 2 × 2 × 2 volume file of `voxel`, in file order (slice k, rows from the top, columns).
fn file(voxel: fn(usize, usize, usize) -> [f32; 4]) -> Vec<u8> {
    let mut voxels = Vec::new();
    for k in 0..2 {
        for j in [1, 0] {
            for i in 0..2 {
                voxels.push(voxel(i, j, k));
            }
        }
    }
    volume_file(2, 2, 2, &voxels)
}

/// A directory of test `test` with the module (`volumes.mdl`) and its two volumes.
fn fixtures(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mira_mdl_volume_textures_{}_{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("volumes.mdl"), MODULE).unwrap();
    std::fs::write(dir.join("density.dds"), file(density)).unwrap();
    std::fs::write(dir.join("temperature.dds"), file(temperature)).unwrap();
    dir
}

/// Compiles `text` with test `test`'s fixtures: the materials and the messages.
fn compiled(test: &str, text: &str) -> (material::mdl_modules::MdlMaterials, scene::Library, Vec<String>) {
    let dir = fixtures(test);
    let out = compile_text_with(text, std::slice::from_ref(&dir));
    std::fs::remove_dir_all(&dir).ok();
    out
}

/// A shading point at world position `p` of an instance scaled by `scale` (object to world).
fn point(p: Vec3A, scale: f32) -> State {
    let object_to_world = Affine3A::from_scale(glam::Vec3::splat(scale));
    State {
        point: p,
        normal: Vec3A::Z,
        normal_geom: Vec3A::Z,
        dir: -Vec3A::Z,
        object_to_world,
        world_to_object: object_to_world.inverse(),
        ..State::default()
    }
}

/// The voxel centres' object-space positions (texture coordinate (i + ½)/2 … through the
/// module's `HALF`) and their voxel indices.
fn centres() -> Vec<(Vec3A, [usize; 3])> {
    (0..8)
        .map(|n| {
            let ijk = [n & 1, n >> 1 & 1, n >> 2 & 1];
            (Vec3A::new(ijk[0] as f32, ijk[1] as f32, ijk[2] as f32), ijk)
        })
        .collect()
}

/// The density's coefficients scale the medium a path enters at each voxel centre by the
/// voxel's colour: σs = (2, 1, 0.5)·d·2 + 0.05·2, σa = (0.1, 0.2, 0.3)·d·2 + (0.01, 0.02,
/// 0.03)·2 (density multiplier 2), within 1e-5; outside the texture's cube the density is 0
/// (wrap_clip) and only the offsets remain; with `density_relative_to_size` an instance
/// scaled by 2 doubles the density.
#[test]
fn density_coefficients_are_the_voxels_at_the_entry_point() {
    let (mdl, lib, diags) = compiled(
        "coefficients",
        r#"shader "s" "mdl::volumes::smoke" ()
shader "r" "mdl::volumes::smoke" ("relative" on)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let smoke = get(&mdl, &lib, "s");
    assert!(smoke.varying_medium.is_some(), "the medium varies with the entry point");
    let want = |d: Rgb, scale: f32| {
        let d = d * 2.0 * scale;
        (Rgb::new(2.0, 1.0, 0.5) * d + 0.1, Rgb::new(0.1, 0.2, 0.3) * d + Rgb::new(0.02, 0.04, 0.06))
    };
    for (p, [i, j, k]) in centres() {
        let v = density(i, j, k);
        let d = Rgb::new(v[0], v[1], v[2]);
        let m = smoke.medium_at(&point(p, 1.0)).expect("a medium");
        let (s, a) = want(d, 1.0);
        assert!(close(m.sigma_s, s, 1e-5) && close(m.sigma_a, a, 1e-5), "{p}: {m:?} vs σs {s:?} σa {a:?}");
        // Relative to size: the same object point on an instance twice as large.
        let m = get(&mdl, &lib, "r").medium_at(&point(p * 2.0, 2.0)).expect("a medium");
        let (s, a) = want(d, 2.0);
        assert!(close(m.sigma_s, s, 1e-5) && close(m.sigma_a, a, 1e-5), "{p} ×2: {m:?} vs σs {s:?} σa {a:?}");
    }
    let outside = smoke.medium_at(&point(Vec3A::new(2.0, 0.5, 0.5), 1.0)).expect("a medium");
    let (s, a) = want(Rgb::ZERO, 1.0);
    assert!(close(outside.sigma_s, s, 1e-6) && close(outside.sigma_a, a, 1e-6), "{outside:?}");
}

/// The MDL SDK's black body emission of temperature sample `sample` (× 1000 + 500 K),
/// scale 2, tint (1, 0.5, 0.25), density `d`: the colour of luminance 1 × exp(rational
/// fit) × 2 / 1000 × d × tint (the fit's coefficients as `base.mdl` gives them).
fn fire(sample: f32, d: f32) -> Rgb {
    let t = (sample * 1000.0 + 500.0).max(500.0) as f64;
    let num = 1.0 + t * (-8.81488646e+02 + t * (-9.73116632e+04 + t * (1.29971736e+02 + t * 4.83600971e-04)));
    let den =
        -3.83985730e-02 + t * (-4.60407613e+03 + t * (1.92388064e+02 + t * (4.00569612e+00 + t * 1.14000081e-05)));
    let intensity = ((num / den).exp() * 2.0 / 1000.0 * f64::from(d)).max(0.0) as f32;
    blackbody_rgb(t as f32) * intensity * Rgb::new(1.0, 0.5, 0.25)
}

/// The emission radiance of `m` at `state` (exitance / π).
fn emission(m: &SurfaceMaterial, state: &State) -> Rgb {
    let Varying::Evaluated(hit) = &m.varying else { panic!("{} is not evaluated per hit", m.name) };
    let mut h = m.constant();
    hit.0.apply(state, &mut h);
    h.emission
}

/// The temperature texture's black body emission at three voxel centres (without a density
/// texture, and with the density's red channel as the particles' density) is the MDL SDK's
/// formula within 1e-4 relative; hotter voxels glow brighter and bluer.
#[test]
fn temperature_texture_glows_as_a_black_body() {
    let (mdl, lib, diags) = compiled(
        "fire",
        r#"shader "f" "mdl::volumes::fire" ()
shader "d" "mdl::volumes::fire" ("density" "density.dds")"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let pi = std::f32::consts::PI;
    let mut seen = Vec::new();
    for (p, [i, j, k]) in [centres()[0], centres()[3], centres()[7]] {
        let sample = temperature(i, j, k)[0];
        let got = emission(get(&mdl, &lib, "f"), &point(p, 1.0)) * pi;
        let want = fire(sample, 1.0);
        assert!(want.max_element() > 0.0 && close(got, want, 1e-4 * want.max_element()), "{p}: {got:?} vs {want:?}");
        let got = emission(get(&mdl, &lib, "d"), &point(p, 1.0)) * pi;
        let want = fire(sample, density(i, j, k)[0]);
        assert!(close(got, want, 1e-4 * want.max_element()), "{p} with density: {got:?} vs {want:?}");
        seen.push(emission(get(&mdl, &lib, "f"), &point(p, 1.0)));
    }
    assert!(seen.windows(2).all(|w| w[1].max_element() > w[0].max_element() && w[1].z / w[1].x > w[0].z / w[0].x));
}

/// A volume's black body emission is the medium's emission (radiance per unit length),
/// evaluated where a path enters: at voxel centres the MDL SDK's formula within 1e-4
/// relative (no factor π: the volume's intensity is not an exitance); the volume still
/// absorbs; no message.
#[test]
fn volume_emission_is_the_media_emission() {
    let (mdl, lib, diags) = compiled("gas", r#"shader "g" "mdl::volumes::glowing_gas" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let m = get(&mdl, &lib, "g");
    for (p, [i, j, k]) in [centres()[0], centres()[5]] {
        let medium = m.medium_at(&point(p, 1.0)).expect("a medium");
        let want = fire(temperature(i, j, k)[0], 1.0);
        assert!(close(medium.sigma_a, Rgb::ONE, 1e-6), "{medium:?}");
        assert!(
            want.max_element() > 0.0 && close(medium.emission, want, 1e-4 * want.max_element()),
            "{p}: {:?} vs {want:?}",
            medium.emission
        );
    }
}
