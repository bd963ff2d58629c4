//! `df::measured_edf` in module materials (tests/mdl/profiles.mdl, its profile
//! tests/mdl/lamp.ies): the radiance towards a direction is the intensity times the
//! multiplier times the profile's tabulated candela, in the surface's frame (axis the
//! normal, horizontal angle 0 along the u tangent) or in a global frame; a power is spread
//! by what the profile emits over the hemisphere; `light_profile_maximum`, `_power` and
//! `_isvalid` read the profile.

use crate::mdl_support;

use std::path::Path;

use bsdf::Rgb;
use glam::Vec3A;
use material::{SurfaceMaterial, Varying};
use mdl_support::{compile_text, get};
use shader::State;

/// A shading state at the origin with normal +Z whose u tangent is turned by `angle`
/// (radians) from +X about the normal.
fn state(angle: f32) -> State {
    let du = Vec3A::new(angle.cos(), angle.sin(), 0.0);
    State {
        normal: Vec3A::Z,
        normal_geom: Vec3A::Z,
        dir: -Vec3A::Z,
        tex_count: 1,
        derivs: [du, Vec3A::Z.cross(du)],
        ..Default::default()
    }
}

/// The radiance material `m` emits towards `dir` from the point of `state`.
fn radiance(m: &SurfaceMaterial, state: &State, dir: Vec3A) -> f32 {
    let mut h = m.constant();
    if let Varying::Evaluated(e) = &m.varying {
        e.0.apply(state, &mut h);
    }
    let shape = h.emission_shape.expect("a measured emission");
    h.emission.x * shape.factor(state.normal, h.tangent, dir).x
}

/// The direction at vertical angle `v` (degrees, from `axis`) and horizontal angle `h`
/// (degrees, from `x` towards `y`).
fn toward(axis: Vec3A, x: Vec3A, y: Vec3A, v: f32, h: f32) -> Vec3A {
    let (v, h) = (v.to_radians(), h.to_radians());
    (axis * v.cos() + (x * h.cos() + y * h.sin()) * v.sin()).normalize()
}

/// In the surface's frame, three tabulated directions (the axis: 1000 cd; 30° towards
/// horizontal 0: 900; 60° towards 90°: 200) give intensity 2 × multiplier × candela within
/// 1e-3, wherever the u tangent points; nothing behind the surface.
#[test]
fn the_radiance_is_the_tabulated_candela_in_the_surface_frame() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "m" "mdl::profiles::measured" ()
shader "half" "mdl::profiles::measured" ("multiplier" 0.5)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    for (name, k) in [("m", 2.0), ("half", 1.0)] {
        let m = get(&mdl, &lib, name);
        for angle in [0.0f32, 0.4, 2.5] {
            let s = state(angle);
            let x = Vec3A::new(angle.cos(), angle.sin(), 0.0);
            // The profile's horizontal 90° lies along x × normal.
            let y = x.cross(Vec3A::Z);
            for (v, h, cd) in [(0.0, 0.0, 1000.0), (30.0, 0.0, 900.0), (60.0, 90.0, 200.0), (60.0, 270.0, 200.0)] {
                let l = radiance(m, &s, toward(Vec3A::Z, x, y, v, h));
                let want = k * cd;
                assert!((l - want).abs() <= 1e-3 * want, "{name}, tangent {angle}, V {v} H {h}: {l} vs {want}");
            }
            assert_eq!(radiance(m, &s, toward(-Vec3A::Z, x, y, 10.0, 0.0)), 0.0, "behind");
        }
    }
}

/// `global_frame` diag(1, 1, −1) (`light_ies`'s): the axis is world −Z and horizontal 0
/// world +X, as for a mental ray light pointing down; the surface's normal only decides
/// which side emits.
#[test]
fn a_global_frame_orients_the_profile_in_world_space() {
    let (mdl, lib, diags) = compile_text(r#"shader "g" "mdl::profiles::measured_global" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let g = get(&mdl, &lib, "g");
    let down = State { normal: -Vec3A::Z, normal_geom: -Vec3A::Z, dir: Vec3A::Z, ..state(0.0) };
    for (v, h, cd) in [(0.0, 0.0, 1000.0), (30.0, 0.0, 900.0), (60.0, 90.0, 200.0)] {
        // Horizontal 90° of a light pointing down is world +Y (LM-63: counter-clockwise
        // seen from above).
        let l = radiance(g, &down, toward(-Vec3A::Z, Vec3A::X, Vec3A::Y, v, h));
        assert!((l - cd).abs() <= 1e-3 * cd, "V {v} H {h}: {l} vs {cd}");
    }
}

/// `intensity_power`: the emission is for the whole surface (divided by its area later),
/// scaled so that the radiance integrated with the cosine over the hemisphere gives the
/// power: checked by an independent midpoint rule in (cos θ, φ), 1e-3.
#[test]
fn a_power_is_spread_by_what_the_profile_emits() {
    let (mdl, lib, diags) = compile_text(r#"shader "p" "mdl::profiles::measured_power" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let p = get(&mdl, &lib, "p");
    assert!(p.emission_over_area);
    let s = state(0.0);
    let (nu, np) = (400, 200);
    let mut sum = 0.0f64;
    for i in 0..nu {
        let mu = (i as f32 + 0.5) / nu as f32;
        for j in 0..np {
            let phi = (j as f32 + 0.5) / np as f32 * std::f32::consts::TAU;
            let st = (1.0 - mu * mu).sqrt();
            let d = Vec3A::new(st * phi.cos(), st * phi.sin(), mu);
            sum += f64::from(radiance(p, &s, d) * mu);
        }
    }
    let power = sum / (nu * np) as f64 * std::f64::consts::TAU;
    assert!((power - 10.0).abs() < 1e-2, "{power}");
}

/// `light_profile_maximum` is the peak (1000 cd), `light_profile_power` the reader's flux,
/// `light_profile_isvalid` true; an invalid profile emits nothing, and a missing file is
/// an error at its module line.
#[test]
fn profile_queries_and_invalid_profiles() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "n" "mdl::profiles::profile_numbers" ()
shader "none" "mdl::profiles::no_profile" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mdl/lamp.ies");
    let (profile, _) = shader::light::ies::Profile::load(&file, false).expect("lamp.ies");
    let want = Rgb::new(1.0, profile.flux() / 10000.0, 1.0);
    let n = get(&mdl, &lib, "n").diffuse;
    assert!((n - want).abs().max_element() < 1e-5, "{n:?} vs {want:?}");
    let none = get(&mdl, &lib, "none");
    assert_eq!(none.emission, Rgb::ZERO);
}

/// A `light_profile` parameter set from the `.mi` file: by a `lightprofile` element's name
/// (its `format ies` file on the search path) or by an IES file's name, the profile read
/// (its maximum, power and validity within 1e-5); a name that is neither is a warning at
/// its `.mi` line and the invalid profile; no parameter, the default (none).
#[test]
fn a_light_profile_parameter_is_set_from_the_mi_file() {
    let (mdl, lib, diags) = compile_text(
        r#"lightprofile "lamp" format ies file "lamp.ies" end lightprofile
shader "element" "mdl::profiles::given_profile" ("profile" "lamp")
shader "file" "mdl::profiles::given_profile" ("profile" "lamp.ies")
shader "missing" "mdl::profiles::given_profile" ("profile" "no_such_lamp")
shader "default" "mdl::profiles::given_profile" ()"#,
    );
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert!(
        diags[0].contains("t.mi:4:") && diags[0].contains("no_such_lamp") && diags[0].contains("invalid light profile"),
        "{}",
        diags[0]
    );
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mdl/lamp.ies");
    let (profile, _) = shader::light::ies::Profile::load(&file, false).expect("lamp.ies");
    let want = Rgb::new(1.0, profile.flux() / 10000.0, 1.0);
    for name in ["element", "file"] {
        let d = get(&mdl, &lib, name).diffuse;
        assert!((d - want).abs().max_element() < 1e-5, "{name}: {d:?} vs {want:?}");
    }
    for name in ["missing", "default"] {
        assert_eq!(get(&mdl, &lib, name).diffuse, Rgb::ZERO, "{name}");
    }
}

/// The radiance (all channels) material `m` emits towards `dir` from the point of
/// `state`, before any division by the area (a power as given).
fn radiance_rgb(m: &SurfaceMaterial, state: &State, dir: Vec3A) -> Rgb {
    let mut h = m.constant();
    if let Varying::Evaluated(e) = &m.varying {
        e.0.apply(state, &mut h);
    }
    match h.emission_shape {
        Some(shape) => h.emission * shape.factor(state.normal, h.tangent, dir),
        // Lambertian: the radiance itself.
        None => h.emission,
    }
}

/// A `measured_edf` inside edf combinators emits the weighted sum of its parts, each as
/// it emits alone (within 1e-4 of the larger value, at six directions and three u
/// tangents): a normalized mix of ½ the profile and ¼ diffuse emission = ½ `measured` +
/// ¼ a lone diffuse emitter; a tint (0.2, 0.5, 1) of the profile along world +Y = the tint
/// × `measured_along_y` (the tangent read inside the tint); an unbounded mix of ½ and ½
/// emitting a power of 10 = ½ `measured_power` + ½ the diffuse emitter of intensity 10
/// (each part normalised to the power it emits alone); the profile under a directional
/// factor (normal (1, 0.5, 0.25), grazing 0.2, exponent 3) = the Schlick curve of the
/// emission angle × `measured`. No diagnostic.
#[test]
fn measured_edfs_in_mixes_tints_and_factors_emit_the_weighted_sum_of_their_parts() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "mix" "mdl::profiles::measured_mix" ()
shader "m" "mdl::profiles::measured" ()
shader "d" "mdl::profiles::diffuse_emitter" ()
shader "tint" "mdl::profiles::measured_tint" ()
shader "y" "mdl::profiles::measured_along_y" ()
shader "pmix" "mdl::profiles::measured_power_mix" ()
shader "p" "mdl::profiles::measured_power" ()
shader "d10" "mdl::profiles::diffuse_emitter" ("intensity" 10 10 10)
shader "factor" "mdl::profiles::measured_factor_edf" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let g = |name: &str| get(&mdl, &lib, name);
    let tint = Rgb::new(0.2, 0.5, 1.0);
    let (normal, grazing) = (Rgb::new(1.0, 0.5, 0.25), Rgb::splat(0.2));
    for angle in [0.0f32, 0.4, 2.5] {
        let s = state(angle);
        let x = Vec3A::new(angle.cos(), angle.sin(), 0.0);
        let y = x.cross(Vec3A::Z);
        for (v, h) in [(0.0, 0.0), (30.0, 0.0), (45.0, 60.0), (60.0, 90.0), (75.0, 200.0), (20.0, 300.0)] {
            let d = toward(Vec3A::Z, x, y, v, h);
            let r = |name: &str| radiance_rgb(g(name), &s, d);
            let schlick = normal + (grazing - normal) * (1.0 - d.z).powi(3);
            let cases = [
                ("mix", r("mix"), r("m") * 0.5 + r("d") * 0.25),
                ("tint", r("tint"), r("y") * tint),
                ("pmix", r("pmix"), r("p") * 0.5 + r("d10") * 0.5),
                ("factor", r("factor"), r("m") * schlick),
            ];
            for (name, got, want) in cases {
                let scale = got.max_element().max(want.max_element());
                assert!(scale > 0.0, "{name}: nothing emitted");
                assert!(
                    (got - want).abs().max_element() <= 1e-4 * scale,
                    "{name}, tangent {angle}, V {v} H {h}: {got:?} vs {want:?}"
                );
            }
        }
    }
}
