//! `df::measured_bsdf` of `bsdf_measurement("…")` resources: MBSDF files the tests write
//! (beside a module they write, in the target's temporary directory), found relative to
//! the module, read, and compiled to a measured lobe. Each test states its tolerance.

use std::f32::consts::FRAC_PI_2;
use std::path::PathBuf;

use bsdf::measured_bsdf::reader::{encode, Block};
use bsdf::testing::{albedo, incidences, standard_checks};
use bsdf::Rgb;
use glam::Vec3A;

use crate::mdl_support::{compile_text_with, get};

/// The module the tests compile (`measured_test`), with its materials.
const MODULE: &str = r#"mdl 1.7;
import ::df::*;

export material flat(uniform float multiplier = 1.0) = material(surface: material_surface(
    scattering: df::measured_bsdf(measurement: bsdf_measurement("flat.mbsdf"), multiplier: multiplier)));
export material lambert() = material(surface: material_surface(
    scattering: df::diffuse_reflection_bsdf(tint: color(0.2 * 3.14159265358979))));
export material glossy(uniform df::scatter_mode mode = df::scatter_reflect) = material(surface: material_surface(
    scattering: df::measured_bsdf(measurement: bsdf_measurement("./glossy.mbsdf"), mode: mode)));
export material tinted(color r = color(0.9, 0.5, 0.2), color t = color(0.1, 0.6, 0.3), uniform float multiplier = 0.5) =
    material(surface: material_surface(scattering: df::tint(reflection_tint: r, transmission_tint: t,
        base: df::measured_bsdf(measurement: bsdf_measurement("./glossy.mbsdf"), multiplier: multiplier,
            mode: df::scatter_reflect_transmit))));
export material given(uniform bsdf_measurement m = bsdf_measurement()) = material(surface: material_surface(
    scattering: df::measured_bsdf(measurement: m)));
export material invalid() = material(surface: material_surface(
    scattering: df::measured_bsdf(measurement: bsdf_measurement())));
export material truncated() = material(surface: material_surface(
    scattering: df::measured_bsdf(measurement: bsdf_measurement("truncated.mbsdf"))));
export material missing() = material(surface: material_surface(
    scattering: df::measured_bsdf(measurement: bsdf_measurement("nowhere.mbsdf"))));
"#;

/// The directory of the written module and files (written once per test run; each test
/// writes the same bytes, so parallel tests agree).
fn written() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("mdl_measured_bsdf");
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, bytes: &[u8]| {
        // Written under a unique name and renamed: a test reading it never sees half a file.
        let tmp = dir.join(format!("{name}.{:?}", std::thread::current().id()));
        std::fs::write(&tmp, bytes).unwrap();
        std::fs::rename(&tmp, dir.join(name)).unwrap();
    };
    write("measured_test.mdl", MODULE.as_bytes());
    let flat = vec![0.2f32; 6 * 6 * 8];
    write("flat.mbsdf", &encode(Some(Block { channels: 1, res_theta: 6, res_phi: 8, values: &flat }), None));
    let (nt, np) = (12usize, 24usize);
    let mut glossy = Vec::new();
    for a in 0..nt {
        for b in 0..nt {
            for k in 0..np {
                let (ti, to) = (a as f32 * FRAC_PI_2 / nt as f32, b as f32 * FRAC_PI_2 / nt as f32);
                let dphi = k as f32 * std::f32::consts::PI / np as f32;
                let cos_alpha = ti.cos() * to.cos() - ti.sin() * to.sin() * dphi.cos();
                let v = 0.03 + 0.4 * cos_alpha.max(0.0).powi(6);
                glossy.extend([v, 0.5 * v, 0.25 * v]);
            }
        }
    }
    let trans = vec![0.05f32; 4 * 4 * 4];
    let glossy_file = encode(
        Some(Block { channels: 3, res_theta: nt as u32, res_phi: np as u32, values: &glossy }),
        Some(Block { channels: 1, res_theta: 4, res_phi: 4, values: &trans }),
    );
    write("glossy.mbsdf", &glossy_file);
    write("truncated.mbsdf", &glossy_file[..glossy_file.len() / 2]);
    dir
}

/// Compiles `.mi` shaders of the written module.
fn compile(text: &str) -> (material::mdl_modules::MdlMaterials, scene::Library, Vec<String>) {
    compile_text_with(text, &[written()])
}

/// A measurement of constant value c = 0.2 (a file the test writes, named relative to the
/// module) is the Lambertian of albedo π c: f equal to the module's
/// `diffuse_reflection_bsdf(tint: π c)` at pairs of directions (1e-4 relative), albedo π c
/// (1e-4, its sampling is the cosine distribution); `multiplier` 0.5 halves f (1e-6).
#[test]
fn a_constant_measurement_is_a_lambertian_of_albedo_pi_c() {
    let (mdl, lib, diags) = compile(
        r#"shader "m" "mdl::measured_test::flat" ()
shader "h" "mdl::measured_test::flat" ("multiplier" 0.5)
shader "l" "mdl::measured_test::lambert" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let (m, h, l) = (get(&mdl, &lib, "m"), get(&mdl, &lib, "h"), get(&mdl, &lib, "l"));
    let pairs = [(0.0f32, 30.0f32, 1.0f32), (37.0, 72.0, 2.5), (80.0, 10.0, 0.2), (55.0, 55.0, 3.1)];
    let dir = |deg: f32, phi: f32| {
        let t = deg.to_radians();
        Vec3A::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
    };
    for (a, b, phi) in pairs {
        let (wo, wi) = (dir(a, 0.0), dir(b, phi));
        let (fm, fl) = (m.bsdf(wo).eval(wo, wi), l.bsdf(wo).eval(wo, wi));
        assert!((fm - fl).abs().max_element() <= 1e-4 * fl.max_element(), "{fm:?} vs {fl:?}");
        let fh = h.bsdf(wo).eval(wo, wi);
        assert!((fh - 0.5 * fm).abs().max_element() <= 1e-6, "{fh:?} vs {fm:?}");
    }
    let want = 0.2 * std::f32::consts::PI;
    for wo in incidences() {
        let a = albedo(&m.bsdf(wo), wo, 4096);
        assert!((a - Rgb::splat(want)).abs().max_element() <= 1e-4 * want, "{a:?} at {wo:?}");
    }
}

/// An RGB glossy measurement with a transmission part: `scatter_reflect` uses only the
/// reflection (nothing through), `scatter_transmit` only the transmission, and
/// `scatter_reflect_transmit` both; each passes the standard checks (reciprocity 1e-4,
/// albedo ≤ 1, χ² sampling at 0°, 37°, 72°).
#[test]
fn a_glossy_measurement_scatters_as_its_mode_says() {
    let (mdl, lib, diags) = compile(
        r#"shader "r" "mdl::measured_test::glossy" ()
shader "t" "mdl::measured_test::glossy" ("mode" "scatter_transmit")
shader "b" "mdl::measured_test::glossy" ("mode" "scatter_reflect_transmit")"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let wo = Vec3A::new(0.3, 0.1, 0.9).normalize();
    let (up, down) = (Vec3A::new(-0.2, 0.0, 0.8).normalize(), Vec3A::new(-0.2, 0.0, -0.8).normalize());
    for (name, reflects, transmits) in [("r", true, false), ("t", false, true), ("b", true, true)] {
        let m = get(&mdl, &lib, name);
        let b = m.bsdf(wo);
        assert_eq!(b.eval(wo, up) != Rgb::ZERO, reflects, "{name}");
        assert_eq!(b.eval(wo, down) != Rgb::ZERO, transmits, "{name}");
        standard_checks(&b, 1.0, name);
    }
}

/// A `measured_bsdf` that reflects and transmits (the RGB glossy file with transmission,
/// `multiplier` 0.5) under `df::tint` of r = (0.9, 0.5, 0.2) and t = (0.1, 0.6, 0.3) is
/// its reflection part under r and its transmission part under t (once an error): two
/// measured lobes of weights exactly 0.5 r and 0.5 t (1e-6), the first reflecting only,
/// the second transmitting only; f equals 0.5 (r f_R + t f_T) — f_R and f_T the
/// `scatter_reflect` and `scatter_transmit` materials of the same file — at 9 × 9 pairs of
/// directions on both sides (1e-6 of the larger value). No diagnostic; the split passes the
/// standard checks (reciprocity 1e-4, albedo ≤ 1, χ²).
#[test]
fn a_measurement_under_two_tints_is_split_into_its_parts() {
    let (mdl, lib, diags) = compile(
        r#"shader "s" "mdl::measured_test::tinted" ()
shader "r" "mdl::measured_test::glossy" ()
shader "t" "mdl::measured_test::glossy" ("mode" "scatter_transmit")"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let (r, t) = (Rgb::new(0.9, 0.5, 0.2), Rgb::new(0.1, 0.6, 0.3));
    let s = get(&mdl, &lib, "s");
    let material::SurfaceModel::MdlLobes(l) = &s.model else { panic!("not a lobe sum: {:?}", s.model) };
    let parts: Vec<_> = l.parts().collect();
    assert_eq!(parts.len(), 2, "{parts:?}");
    for ((w, lobe), (want, reflects)) in parts.iter().zip([(0.5 * r, true), (0.5 * t, false)]) {
        assert!((*w - want).abs().max_element() <= 1e-6, "{w:?} vs {want:?}");
        let bsdf::Lobe::Measured(m) = lobe else { panic!("{lobe:?}") };
        assert_eq!((m.reflect, m.transmit), (reflects, !reflects), "{m:?}");
    }
    let (fr, ft) = (get(&mdl, &lib, "r"), get(&mdl, &lib, "t"));
    let dirs: Vec<Vec3A> = (1..10)
        .map(|i| {
            let u = bsdf::testing::r2(i);
            let z = 1.0 - 2.0 * u.x;
            let q = (1.0 - z * z).max(0.0).sqrt();
            let phi = std::f32::consts::TAU * u.y;
            Vec3A::new(q * phi.cos(), q * phi.sin(), z)
        })
        .collect();
    for &wo in &dirs {
        for &wi in &dirs {
            let got = s.bsdf(wo).eval(wo, wi);
            let want = 0.5 * (r * fr.bsdf(wo).eval(wo, wi) + t * ft.bsdf(wo).eval(wo, wi));
            let scale = got.max_element().max(want.max_element()).max(1e-6);
            assert!((got - want).abs().max_element() <= 1e-6 * scale, "{wo} → {wi}: {got:?} vs {want:?}");
        }
    }
    standard_checks(&s.bsdf(Vec3A::Z), 1.0, "split measurement");
}

/// The invalid measurement (`bsdf_measurement()`) scatters nothing; a truncated file and a
/// missing one are errors at the module's `file:line:col` of the resource, the truncated
/// one naming the file and the byte offset.
#[test]
fn bad_measurements_are_errors_at_their_module_line() {
    let (mdl, lib, diags) = compile(r#"shader "i" "mdl::measured_test::invalid" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let i = get(&mdl, &lib, "i");
    let wo = Vec3A::Z;
    assert_eq!(i.bsdf(wo).eval(wo, Vec3A::new(0.6, 0.0, 0.8)), Rgb::ZERO);
    let line = |inside: &str| MODULE.lines().position(|l| l.contains(inside)).unwrap() + 1;
    for (shader, file, says) in
        [("truncated", "truncated.mbsdf", "ends inside"), ("missing", "nowhere.mbsdf", "not found")]
    {
        let (_, _, diags) = compile(&format!("shader \"s\" \"mdl::measured_test::{shader}\" ()"));
        assert_eq!(diags.len(), 1, "{diags:#?}");
        let at = format!("measured_test.mdl:{}:", line(file));
        assert!(diags[0].contains(&at) && diags[0].contains(says) && diags[0].contains(file), "{}", diags[0]);
    }
}

/// A `bsdf_measurement` parameter set from the `.mi` file (a string naming the file, found
/// on the search path) is read: `given` with "flat.mbsdf" equals `flat` at pairs of
/// directions (1e-6); a name that is not found is a warning naming the parameter and the
/// file, and the invalid measurement (nothing scattered) is used.
#[test]
fn measurements_set_from_the_mi_file_are_read() {
    let (mdl, lib, diags) = compile(
        r#"shader "g" "mdl::measured_test::given" ("m" "flat.mbsdf")
shader "f" "mdl::measured_test::flat" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let (g, f) = (get(&mdl, &lib, "g"), get(&mdl, &lib, "f"));
    for (wo, wi) in [(Vec3A::Z, Vec3A::new(0.6, 0.0, 0.8)), (Vec3A::new(0.0, 0.8, 0.6), Vec3A::new(-0.28, 0.0, 0.96))] {
        let (a, b) = (g.bsdf(wo).eval(wo, wi), f.bsdf(wo).eval(wo, wi));
        assert!(b.max_element() > 0.0 && (a - b).abs().max_element() <= 1e-6, "{a:?} vs {b:?}");
    }
    let (mdl, lib, diags) = compile(r#"shader "n" "mdl::measured_test::given" ("m" "elsewhere.mbsdf")"#);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert!(diags[0].contains("'m'") && diags[0].contains("elsewhere.mbsdf"), "{}", diags[0]);
    let n = get(&mdl, &lib, "n");
    assert_eq!(n.bsdf(Vec3A::Z).eval(Vec3A::Z, Vec3A::new(0.6, 0.0, 0.8)), Rgb::ZERO);
}
