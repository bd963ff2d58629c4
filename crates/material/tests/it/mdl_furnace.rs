//! White furnaces for every distribution function issue 12 names (tests/mdl/furnace.mdl):
//! each elemental BSDF of `::df` with a white tint, each mixer and layerer (and their
//! `color_` forms), `tint`, `directional_factor` and `thin_film` over white bases, compiled
//! from MDL text and integrated by importance sampling (`bsdf::testing::albedo`, 20 000
//! samples) at normal incidence, 37° and 72°. Every one reflects and transmits at most what
//! it receives (albedo ≤ 1 + 1 %); the lossless ones — a white Lambertian, diffuse
//! transmission, a mirror, thin glass, mixes and layers whose weights use everything, the
//! normalized curve layers and films over a white Lambertian — give 1 ± 1 %; where the
//! definition gives the albedo in closed form (a tint, a directional factor over a
//! Lambertian, solid glass) it is checked within 1 %.

use crate::mdl_support;

use bsdf::testing::{albedo, incidences};
use bsdf::Rgb;
use glam::Vec3A;
use material::SurfaceMaterial;
use mdl_support::{compile_text, get};

/// Every material of tests/mdl/furnace.mdl, as `.mi` shaders of the same names.
const MATERIALS: [&str; 31] = [
    "diffuse",
    "oren_nayar",
    "transmission",
    "mirror",
    "glass",
    "rough_glass",
    "simple_glossy",
    "backscattering",
    "ggx_smith",
    "ggx_vcavities",
    "beckmann_smith",
    "beckmann_vcavities",
    "sheen",
    "ward",
    "normalized_mix",
    "clamped_mix",
    "color_normalized_mix",
    "color_clamped_mix",
    "weighted_layer",
    "weighted_glossy_layer",
    "color_weighted_layer",
    "fresnel_layer",
    "rough_fresnel_layer",
    "color_fresnel_layer",
    "custom_curve_layer",
    "color_custom_curve_layer",
    "tint",
    "white_tint_of_a_coat",
    "white_directional_factor",
    "directional_factor",
    "thin_film",
];

/// Those that lose nothing: 1 ± 1 % at every incidence.
const LOSSLESS: [&str; 16] = [
    "diffuse",
    "transmission",
    "mirror",
    "clamped_mix",
    "color_normalized_mix",
    "color_clamped_mix",
    "weighted_layer",
    "color_weighted_layer",
    "fresnel_layer",
    "color_fresnel_layer",
    "custom_curve_layer",
    "color_custom_curve_layer",
    "white_tint_of_a_coat",
    "white_directional_factor",
    "thin_film",
    "thin_glass",
];

/// The compiled materials, with no diagnostic.
fn compiled() -> (material::mdl_modules::MdlMaterials, scene::Library) {
    let shaders: String =
        MATERIALS.iter().map(|m| format!("shader \"{m}\" \"mdl::furnace::{m}\" ()\n")).collect::<String>()
            + "shader \"thin_glass\" \"mdl::furnace::glass\" (\"thin\" on)\n";
    let (mdl, lib, diags) = compile_text(&shaders);
    assert!(diags.is_empty(), "{diags:#?}");
    (mdl, lib)
}

/// The albedo of `m` at each of the incidences.
fn albedos(m: &SurfaceMaterial) -> [Rgb; 3] {
    incidences().map(|wo| albedo(&m.bsdf(wo), wo, 20_000))
}

#[test]
fn every_bsdf_and_layerer_reflects_at_most_what_it_receives() {
    let (mdl, lib) = compiled();
    for name in MATERIALS {
        for (wo, a) in incidences().into_iter().zip(albedos(get(&mdl, &lib, name))) {
            assert!(a.max_element() <= 1.01 && a.min_element() >= 0.0, "{name}: albedo {a:?} at {wo:?}");
        }
    }
}

#[test]
fn the_lossless_ones_keep_all_of_it() {
    let (mdl, lib) = compiled();
    for name in LOSSLESS {
        for (wo, a) in incidences().into_iter().zip(albedos(get(&mdl, &lib, name))) {
            assert!((a - Rgb::ONE).abs().max_element() <= 0.01, "{name}: albedo {a:?} at {wo:?}");
        }
    }
}

/// `tint(c, white Lambertian)` reflects c; a directional factor of normal tint n, grazing
/// tint 1 and exponent e over a white Lambertian reflects, at normal incidence,
/// ∫ R(cos θ/2) 2 cos θ sin θ dθ with R(c) = n + (1 − n)(1 − c)^e (the curve at the half
/// vector; Simpson's rule, 2000 intervals).
#[test]
fn tints_and_directional_factors_reflect_their_closed_forms() {
    let (mdl, lib) = compiled();
    for a in albedos(get(&mdl, &lib, "tint")) {
        assert!((a - Rgb::new(0.5, 0.25, 1.0)).abs().max_element() <= 0.01, "tint: {a:?}");
    }
    let n = [0.2f64, 0.5, 1.0];
    let want: Vec<f64> = n
        .iter()
        .map(|&n| {
            let f = |t: f64| (n + (1.0 - n) * (1.0 - (t / 2.0).cos()).powi(3)) * 2.0 * t.cos() * t.sin();
            simpson(f, 0.0, std::f64::consts::FRAC_PI_2, 2000)
        })
        .collect();
    let m = get(&mdl, &lib, "directional_factor");
    let a = albedo(&m.bsdf(Vec3A::Z), Vec3A::Z, 50_000);
    for (k, w) in want.iter().enumerate() {
        assert!((f64::from(a[k]) - w).abs() <= 0.01 * w, "channel {k}: {} vs {w}", a[k]);
    }
}

/// Simpson's rule for ∫ f over [a, b] with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n).map(|i| if i % 2 == 1 { 4.0 } else { 2.0 } * f(a + i as f64 * h)).sum();
    (f(a) + f(b) + inner) * h / 3.0
}

/// `df::tint(reflection_tint, transmission_tint, base)` of a half-and-half diffuse
/// reflector and transmitter reflects ½ r and transmits ½ t (exactly, in the compiled
/// lobes; 1 % in the furnace). A glass lobe under two tints (thin smooth glass under 1 and
/// ½; rough solid GGX glass, α 0.3, index 1.5, under (0.9, 0.6, 0.3) and (0.3, 0.6, 0.9))
/// is its Fresnel-reflected half under the reflection tint and its transmitted half under
/// the transmission tint: two glass lobes of exactly those weights (1e-6), the reflected
/// one reflecting only, the transmitted one transmitting only; the thin smooth glass
/// reflects F(θ) and passes ½ (1 − F(θ)) (the furnace within 1 %, both sides); the rough
/// solid one scatters at most the tints' largest channel of what it receives (n²-weighted
/// radiance, ≤ 1 % over, from both sides) and keeps the generalised reciprocity
/// f(ωo, ωi)/n(ωo)² = f(ωi, ωo)/n(ωi)² (1e-3 relative, values under 0.01 within 1e-5
/// absolute) over 30 × 30 pairs. No diagnostic.
#[test]
fn a_tint_of_two_colours_tints_reflection_and_transmission_apart() {
    use bsdf::rough_glass::Halves;
    let (mdl, lib, diags) = compile_text(
        r#"shader "split" "mdl::furnace::split_tint" ()
shader "glass" "mdl::furnace::split_tint_glass" ()
shader "rough" "mdl::furnace::split_tint_rough_glass" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let (r, t) = (Rgb::new(0.5, 0.25, 1.0), Rgb::new(0.25, 1.0, 0.5));
    let m = get(&mdl, &lib, "split");
    let material::SurfaceModel::Lobes(l) = &m.model else { panic!("{:?}", m.model) };
    assert!((l.diffuse.albedo - r * 0.5).abs().max_element() < 1e-6, "{:?}", l.diffuse.albedo);
    assert!((l.transl - t * 0.5).abs().max_element() < 1e-6, "{:?}", l.transl);
    for a in albedos(m) {
        assert!((a - (r + t) * 0.5).abs().max_element() <= 0.01, "{a:?}");
    }
    let glass_parts = |name: &str| -> Vec<(Rgb, bsdf::rough_glass::RoughGlass)> {
        let parts: Vec<_> = match &get(&mdl, &lib, name).model {
            material::SurfaceModel::MdlLobes(l) => l.parts().collect(),
            other => panic!("{name}: not a lobe sum: {other:?}"),
        };
        parts
            .into_iter()
            .map(|(w, l)| match l {
                bsdf::Lobe::Glass(g) => (w, g),
                other => panic!("{name}: {other:?}"),
            })
            .collect()
    };
    let tints = [("glass", Rgb::ONE, Rgb::splat(0.5)), ("rough", Rgb::new(0.9, 0.6, 0.3), Rgb::new(0.3, 0.6, 0.9))];
    for (name, r, t) in tints {
        let parts = glass_parts(name);
        assert_eq!(parts.len(), 2, "{name}: {parts:?}");
        assert_eq!((parts[0].1.halves, parts[1].1.halves), (Halves::Reflect, Halves::Transmit), "{name}");
        assert!((parts[0].0 - r).abs().max_element() < 1e-6 && (parts[1].0 - t).abs().max_element() < 1e-6, "{name}");
        assert_eq!(parts[0].1.thin, name == "glass");
    }
    let eta = 1.5f32;
    let fresnel = |c: f32| {
        let t = (1.0 - (1.0 - c * c) / (eta * eta)).sqrt();
        let rs = (c - eta * t) / (c + eta * t);
        let rp = (eta * c - t) / (eta * c + t);
        (rs * rs + rp * rp) / 2.0
    };
    let glass = get(&mdl, &lib, "glass");
    for wo in incidences() {
        for wo in [wo, -wo] {
            let f = fresnel(wo.z.abs());
            let want = f + 0.5 * (1.0 - f);
            let a = albedo(&glass.bsdf(wo), wo, 20_000);
            assert!((a - Rgb::splat(want)).abs().max_element() <= 0.01 * want, "glass at {wo:?}: {a:?} vs {want}");
        }
    }
    let rough = get(&mdl, &lib, "rough");
    let index = |w: Vec3A| if w.z < 0.0 { eta } else { 1.0 };
    for wo in incidences() {
        for wo in [wo, -wo] {
            let e = n2_albedo(rough, wo, eta);
            assert!(e.max_element() <= 0.9 * 1.01 && e.min_element() >= 0.0, "rough at {wo:?}: {e:?}");
        }
    }
    let b = rough.bsdf(Vec3A::Z);
    let sphere = |i: u32| {
        let u = bsdf::testing::r2(i);
        let z = 1.0 - 2.0 * u.x;
        let s = (1.0 - z * z).max(0.0).sqrt();
        Vec3A::new(s * (std::f32::consts::TAU * u.y).cos(), s * (std::f32::consts::TAU * u.y).sin(), z)
    };
    for i in 0..30 {
        for j in 0..30 {
            let (a, c) = (sphere(i + 1), sphere(j + 301));
            let (f1, f2) = (b.eval(a, c) / index(a).powi(2), b.eval(c, a) / index(c).powi(2));
            let scale = f1.max_element().max(f2.max_element()).max(1e-2);
            assert!((f1 - f2).abs().max_element() <= 1e-3 * scale, "rough: f({a}, {c}) {f1} vs {f2}");
        }
    }
}

/// A `sheen_bsdf` whose base transmits, under `df::tint` of two tints (r = (0.9, 0.6, 0.3),
/// t = (0.3, 0.6, 0.9)): the sheen is a reflection lobe and takes r, the base's reflected
/// half takes r and its transmitted half t, the base still under the sheen's albedo curve.
/// Over a half-and-half diffuse reflector and transmitter (thin-walled) and over rough
/// solid GGX glass (α 0.3, index 1.5): f equals r times the untinted material's f where ωo
/// and ωi lie on one side and t times it across (1e-5 relative, 1e-7 absolute; 30 × 30
/// pairs over the sphere); the furnace (n²-weighted radiance for the glass, from both
/// sides at 0°, 37° and 72°, 20 000 samples) stays within the largest tint, 0.9 (1 + 1 %),
/// and at most 1 + 1 % untinted; (generalised) reciprocity f(ωo, ωi)/n(ωo)² = f(ωi,
/// ωo)/n(ωi)² within 1e-3 relative (values under 0.01: 1e-5 absolute); χ² sampling at 37°
/// from both sides. No diagnostic.
#[test]
fn a_sheen_over_a_transmitting_base_under_two_tints_tints_its_halves_apart() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "white" "mdl::furnace::sheen_over_half_transmitter" ()
shader "split" "mdl::furnace::split_tint_sheen" ()
shader "white_glass" "mdl::furnace::sheen_over_rough_glass" ()
shader "split_glass" "mdl::furnace::split_tint_sheen_rough_glass" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let (r, t) = (Rgb::new(0.9, 0.6, 0.3), Rgb::new(0.3, 0.6, 0.9));
    let sphere = |i: u32| {
        let u = bsdf::testing::r2(i);
        let z = 1.0 - 2.0 * u.x;
        let s = (1.0 - z * z).max(0.0).sqrt();
        Vec3A::new(s * (std::f32::consts::TAU * u.y).cos(), s * (std::f32::consts::TAU * u.y).sin(), z)
    };
    for (white, split, eta) in [("white", "split", 1.0f32), ("white_glass", "split_glass", 1.5)] {
        let index = |w: Vec3A| if w.z < 0.0 { eta } else { 1.0 };
        let (w, s) = (get(&mdl, &lib, white), get(&mdl, &lib, split));
        let (bw, bs) = (w.bsdf(Vec3A::Z), s.bsdf(Vec3A::Z));
        for i in 0..30 {
            for j in 0..30 {
                let (a, c) = (sphere(i + 1), sphere(j + 301));
                let want = bw.eval(a, c) * if a.z * c.z > 0.0 { r } else { t };
                let got = bs.eval(a, c);
                assert!(
                    (got - want).abs().max_element() <= 1e-5 * want.max_element() + 1e-7,
                    "{split}: f({a}, {c}) {got:?} vs {want:?}"
                );
                let (f1, f2) = (got / index(a).powi(2), bs.eval(c, a) / index(c).powi(2));
                let scale = f1.max_element().max(f2.max_element()).max(1e-2);
                assert!((f1 - f2).abs().max_element() <= 1e-3 * scale, "{split}: f({a}, {c}) {f1} vs {f2}");
            }
        }
        for wo in incidences() {
            for wo in [wo, -wo] {
                for (m, bound) in [(w, 1.01), (s, 0.9 * 1.01)] {
                    let e = n2_albedo(m, wo, eta);
                    assert!(e.max_element() <= bound && e.min_element() >= 0.0, "{split} at {wo:?}: {e:?}");
                }
            }
        }
        let wo = Vec3A::new(0.6, 0.0, 0.8);
        for wo in [wo, -wo] {
            bsdf::testing::chi_square(&s.bsdf(wo), wo);
        }
    }
}

/// Solid glass (`specular_bsdf(scatter_reflect_transmit)`, `ior` 1.5, not thin-walled)
/// reflects the dielectric's Fresnel reflectance F(θ) and transmits 1 − F into the denser
/// medium, where radiance is (1 − F)/η² (the η² a radiance gains by the narrowing of its
/// solid angle; the flux is kept): F + (1 − F)/η² within 1 % — 0.4667 head-on. The same
/// glass rough (GGX, α 0.2) stays at most that plus 1 %.
#[test]
fn solid_glass_reflects_fresnel_and_transmits_the_rest_as_radiance() {
    let (mdl, lib) = compiled();
    let eta = 1.5f32;
    let fresnel = |c: f32| {
        let t = (1.0 - (1.0 - c * c) / (eta * eta)).sqrt();
        let rs = (c - eta * t) / (c + eta * t);
        let rp = (eta * c - t) / (eta * c + t);
        (rs * rs + rp * rp) / 2.0
    };
    let glass = albedos(get(&mdl, &lib, "glass"));
    let rough = albedos(get(&mdl, &lib, "rough_glass"));
    for ((wo, a), r) in incidences().into_iter().zip(glass).zip(rough) {
        let f = fresnel(wo.z);
        let want = f + (1.0 - f) / (eta * eta);
        assert!((a - Rgb::splat(want)).abs().max_element() <= 0.01 * want, "glass at {wo:?}: {a:?} vs {want}");
        assert!(r.max_element() <= want * 1.01, "rough glass at {wo:?}: {r:?} vs {want}");
    }
}

/// The n²-weighted albedo of `m` seen from `wo` (index `eta` below the surface, 1 above)
/// by 20 000 quasi-random samples: what a solid glass conserves.
fn n2_albedo(m: &SurfaceMaterial, wo: Vec3A, eta: f32) -> Rgb {
    let index = |w: Vec3A| if w.z < 0.0 { eta } else { 1.0 };
    let b = m.bsdf(wo);
    let mut sum = Rgb::ZERO;
    for k in 0..20_000 {
        let (u, c) = bsdf::testing::r3(k);
        if let Some(s) = b.sample(wo, u, c) {
            sum += s.weight() * (index(s.wi) / index(wo)).powi(2);
        }
    }
    sum / 20_000.0
}
