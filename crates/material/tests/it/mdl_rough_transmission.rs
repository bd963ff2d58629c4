//! Rough transmission outside a lone glass lobe (tests/mdl/rough_transmission.mdl; issue
//! 12): a transmit-only GGX or Beckmann lobe under a weighted layer, rough glass in a
//! normalized mix with a Lambertian, under a Fresnel-layered coat and under a thin film
//! compile to the general lobe sum's rough dielectric lobe ([`bsdf::Lobe::Glass`]) instead
//! of their diffuse part, and pass the standard checks: the white furnace counted in
//! n²-weighted radiance (what crosses into index n carries n² times less radiance for the
//! same flux), the generalised reciprocity of refraction and χ² sampling.

use crate::mdl_support;

use bsdf::rough_glass::Halves;
use bsdf::testing::{chi_square, incidences, r3};
use bsdf::{Bsdf, Lobe, Rgb};
use glam::Vec3A;
use material::{SurfaceMaterial, SurfaceModel};
use mdl_support::{compile_text, get};

/// The materials of the module.
const MATERIALS: [&str; 5] =
    ["weighted_transmit", "weighted_transmit_beckmann", "glass_and_diffuse", "coated_glass", "film_over_glass"];

/// Roughnesses compiled.
const ROUGHNESS: [f32; 4] = [0.05, 0.1, 0.3, 0.7];

/// The shader name of `material` at roughness `r`, solid or thin-walled.
fn shader(material: &str, r: f32, thin: bool) -> String {
    format!("{material}-{r}-{}", if thin { "thin" } else { "solid" })
}

/// Every material at every roughness, solid and thin, compiled; no diagnostic.
fn compiled() -> (material::mdl_modules::MdlMaterials, scene::Library) {
    let mut text = String::new();
    for m in MATERIALS {
        for r in ROUGHNESS {
            for thin in [false, true] {
                let on = if thin { "on" } else { "off" };
                text += &format!(
                    "shader \"{}\" \"mdl::rough_transmission::{m}\" (\"r\" {r}, \"thin\" {on})\n",
                    shader(m, r, thin)
                );
            }
        }
    }
    text += "shader \"lone\" \"mdl::furnace::rough_glass\" ()\n";
    let (mdl, lib, diags) = compile_text(&text);
    assert!(diags.is_empty(), "{diags:#?}");
    (mdl, lib)
}

/// The index on `w`'s side: 1.5 inside a solid, 1 outside and on both sides of a thin
/// sheet.
fn index(thin: bool, w: Vec3A) -> f32 {
    if w.z < 0.0 && !thin {
        1.5
    } else {
        1.0
    }
}

/// What `m` scatters from ωo in n²-weighted radiance: the mean of weight · n(ωi)²/n(ωo)²
/// over 20 000 samples.
fn energy(m: &SurfaceMaterial, thin: bool, wo: Vec3A) -> Rgb {
    let b = m.bsdf(wo);
    let n = 20_000;
    let mut sum = Rgb::ZERO;
    for k in 0..n {
        let (u, c) = r3(k);
        if let Some(s) = b.sample(wo, u, c) {
            sum += s.weight() * (index(thin, s.wi) / index(thin, wo)).powi(2);
        }
    }
    sum / n as f32
}

/// The lobes of a compiled material.
fn lobes(m: &SurfaceMaterial) -> Vec<(Rgb, Lobe)> {
    match &m.model {
        SurfaceModel::MdlLobes(l) => l.parts().collect(),
        SurfaceModel::MdlWide(l) => l.parts().collect(),
        other => panic!("not a lobe sum: {other:?}"),
    }
}

/// Each compiles, without a warning, to a lobe sum with one rough dielectric lobe of the
/// material's index 1.5, the tree's roughness, mode and thin-walledness (and the film's
/// curve for the film), weighted as the tree says (exactly, 1e-6): ½ for the weighted
/// layer and the mix, 1 for the film; a solid one has an inside. The lone rough glass
/// lobe stays the unified material's glass (unchanged).
#[test]
fn rough_transmission_compiles_to_a_glass_lobe() {
    let (mdl, lib) = compiled();
    for m in MATERIALS {
        for r in ROUGHNESS {
            for thin in [false, true] {
                let name = shader(m, r, thin);
                let got = get(&mdl, &lib, &name);
                let glass: Vec<_> = lobes(got)
                    .into_iter()
                    .filter_map(|(w, l)| match l {
                        Lobe::Glass(g) => Some((w, g)),
                        _ => None,
                    })
                    .collect();
                assert_eq!(glass.len(), 1, "{name}: {:?}", lobes(got));
                let (w, g) = glass[0];
                assert!((g.eta - 1.5).abs() < 1e-6 && g.thin == thin, "{name}: {g:?}");
                assert!((g.alpha_x - r).abs() < 1e-6 && (g.alpha_y - r).abs() < 1e-6, "{name}: {g:?}");
                let halves = if m.starts_with("weighted_transmit") { Halves::Transmit } else { Halves::Both };
                assert_eq!(g.halves, halves, "{name}");
                assert_eq!(g.micro.is_beckmann(), m.ends_with("beckmann"), "{name}");
                assert_eq!(g.film > 0, m == "film_over_glass", "{name}");
                let want = match m {
                    "coated_glass" | "film_over_glass" => 1.0,
                    _ => 0.5,
                };
                assert!((w - Rgb::splat(want)).abs().max_element() < 1e-6, "{name}: weight {w:?}");
                assert_eq!(got.has_inside(), !thin, "{name}");
            }
        }
    }
    assert!(matches!(get(&mdl, &lib, "lone").model, SurfaceModel::Unified(_)));
}

/// The white furnace in n²-weighted radiance: every material at every roughness, solid and
/// thin, from outside at 0°, 37° and 72° and from inside at the same angles, scatters at
/// most what it receives (≤ 1 + 1 %). At roughness 0.05 the lossless ones — glass and a
/// Lambertian, glass under a film — keep all of it (1 ± 1 %, from outside at 0° and 37°),
/// and half a transmit-only lobe over half a Lambertian scatters ½ + ½ (1 − F(0°)) =
/// 0.98 head-on (1 %).
#[test]
fn rough_transmission_passes_the_white_furnace_in_radiance_units() {
    let (mdl, lib) = compiled();
    for m in MATERIALS {
        for r in ROUGHNESS {
            for thin in [false, true] {
                let name = shader(m, r, thin);
                let got = get(&mdl, &lib, &name);
                for wo in incidences() {
                    for wo in [wo, -wo] {
                        let e = energy(got, thin, wo);
                        assert!(e.max_element() <= 1.01 && e.min_element() >= 0.0, "{name} at {wo}: {e}");
                        let lossless = r == 0.05 && (m == "glass_and_diffuse" || m == "film_over_glass");
                        if lossless && wo.z > 0.5 {
                            assert!((e - Rgb::ONE).abs().max_element() <= 0.01, "{name} at {wo}: {e}");
                        }
                        if r == 0.05 && m.starts_with("weighted_transmit") && wo == Vec3A::Z {
                            assert!((e - Rgb::splat(0.98)).abs().max_element() <= 0.01, "{name}: {e}");
                        }
                    }
                }
            }
        }
    }
}

/// Generalised reciprocity, f(ωo, ωi)/n(ωo)² = f(ωi, ωo)/n(ωi)² (reflection: plain
/// reciprocity), within 1e-3 relative (values under 0.01 within 1e-5 absolute) over
/// 40 × 40 pairs of directions, every material at roughness 0.1, 0.3 and 0.7, solid and
/// thin.
#[test]
fn rough_transmission_is_reciprocal_in_radiance_units() {
    let (mdl, lib) = compiled();
    let sphere = |i: u32| {
        let u = bsdf::testing::r2(i);
        let z = 1.0 - 2.0 * u.x;
        let s = (1.0 - z * z).max(0.0).sqrt();
        Vec3A::new(s * (std::f32::consts::TAU * u.y).cos(), s * (std::f32::consts::TAU * u.y).sin(), z)
    };
    for m in MATERIALS {
        for r in [0.1, 0.3, 0.7] {
            for thin in [false, true] {
                let name = shader(m, r, thin);
                let b: Bsdf = get(&mdl, &lib, &name).bsdf(Vec3A::Z);
                for i in 0..40 {
                    for j in 0..40 {
                        let (a, c) = (sphere(i + 1), sphere(j + 301));
                        let f1 = b.eval(a, c) / index(thin, a).powi(2);
                        let f2 = b.eval(c, a) / index(thin, c).powi(2);
                        let scale = f1.max_element().max(f2.max_element()).max(1e-2);
                        assert!((f1 - f2).abs().max_element() <= 1e-3 * scale, "{name}: f({a}, {c}) {f1} vs {f2}");
                    }
                }
            }
        }
    }
}

/// Sampling matches the density (χ² at 1 %, 200 000 samples): glass and a Lambertian and
/// the Beckmann transmit-only layer at roughness 0.1, 0.3 and 0.7, the others at 0.3, solid
/// and thin, from outside at 37° and from inside.
#[test]
fn rough_transmission_samples_its_density() {
    let (mdl, lib) = compiled();
    for m in MATERIALS {
        for r in [0.1, 0.3, 0.7] {
            if r != 0.3 && m != "glass_and_diffuse" && m != "weighted_transmit_beckmann" {
                continue;
            }
            for thin in [false, true] {
                let name = shader(m, r, thin);
                let got = get(&mdl, &lib, &name);
                for wo in [Vec3A::new(0.562, 0.174, 0.808).normalize(), Vec3A::new(-0.3, 0.5, -0.81).normalize()] {
                    chi_square(&got.bsdf(wo), wo);
                }
            }
        }
    }
}

/// Smooth glass (`specular_bsdf(scatter_reflect_transmit)`) in a normalized mix with a
/// white Lambertian and under a thin film compiles, without a warning, to the sum's smooth
/// glass lobe (two Dirac lobes; the film's curve on its Fresnel term) and keeps all it
/// receives in n²-weighted radiance (1 ± 1 % from outside and inside at 0°, 37° and 72°,
/// solid and thin); head-on the film reflects its Airy reflectance R(1) per channel
/// (`bsdf::layer_curve::airy_reflectance` averaged over each channel's three wavelengths,
/// within 1 %).
#[test]
fn smooth_glass_in_sums_and_under_films_is_lossless() {
    let mut text = String::new();
    for m in ["smooth_glass_and_diffuse", "film_over_smooth_glass"] {
        for thin in [false, true] {
            let on = if thin { "on" } else { "off" };
            text += &format!("shader \"{}\" \"mdl::rough_transmission::{m}\" (\"thin\" {on})\n", shader(m, 0.0, thin));
        }
    }
    let (mdl, lib, diags) = compile_text(&text);
    assert!(diags.is_empty(), "{diags:#?}");
    for m in ["smooth_glass_and_diffuse", "film_over_smooth_glass"] {
        for thin in [false, true] {
            let name = shader(m, 0.0, thin);
            let got = get(&mdl, &lib, &name);
            let glass: Vec<_> = lobes(got)
                .into_iter()
                .filter_map(|(_, l)| match l {
                    Lobe::Glass(g) => Some(g),
                    _ => None,
                })
                .collect();
            assert!(glass.len() == 1 && glass[0].is_smooth() && glass[0].thin == thin, "{name}: {glass:?}");
            assert_eq!(glass[0].film > 0, m.starts_with("film"), "{name}");
            for wo in incidences() {
                for wo in [wo, -wo] {
                    let e = energy(got, thin, wo);
                    assert!((e - Rgb::ONE).abs().max_element() <= 0.01, "{name} at {wo}: {e}");
                }
            }
        }
    }
    let film = bsdf::CurveKind::ThinFilm { ior: 1.5, film_ior: Rgb::new(1.3, 1.4, 1.8), thickness_nm: 400.0 };
    let b = get(&mdl, &lib, &shader("film_over_smooth_glass", 0.0, false)).bsdf(Vec3A::Z);
    let mut reflected = Rgb::ZERO;
    for k in 0..20_000 {
        let (u, c) = r3(k);
        if let Some(s) = b.sample(Vec3A::Z, u, c) {
            if s.wi.z > 0.0 {
                reflected += s.weight();
            }
        }
    }
    let (got, want) = (reflected / 20_000.0, film.eval(1.0));
    assert!((got - want).abs().max_element() <= 0.01 * want.max_element(), "{got} vs {want}");
}

/// A lone glass lobe beyond the unified glass compiles, without a warning, to the lobe
/// sum's glass lobe: anisotropic GGX (roughness 0.1 along u, 0.4 along v, kept apart) and
/// transmit-only Beckmann (reflecting nothing). Both pass the n²-weighted furnace (≤ 1 + 1 %
/// from both sides, solid and thin; the transmit-only lobe at α 0.05 scatters 1 − F(0°)
/// = 0.96 head-on within 1 %), generalised reciprocity (1e-3; values under 0.01 within
/// 1e-5; pairs within 0.6° of grazing left out: there the refracted direction lies at the
/// critical angle, where the Fresnel term's infinite slope turns f32 rounding into
/// differences of 0.6 %) and χ² sampling.
#[test]
fn lone_anisotropic_and_transmit_only_glass_are_glass_lobes() {
    let mut text = String::new();
    for m in ["anisotropic_glass", "transmit_only"] {
        for thin in [false, true] {
            let on = if thin { "on" } else { "off" };
            text += &format!("shader \"{}\" \"mdl::rough_transmission::{m}\" (\"thin\" {on})\n", shader(m, 0.0, thin));
        }
    }
    text += "shader \"transmit_only-0.3\" \"mdl::rough_transmission::transmit_only\" (\"r\" 0.3)\n";
    let (mdl, lib, diags) = compile_text(&text);
    assert!(diags.is_empty(), "{diags:#?}");
    for m in ["anisotropic_glass", "transmit_only"] {
        for thin in [false, true] {
            let name = shader(m, 0.0, thin);
            let got = get(&mdl, &lib, &name);
            let parts = lobes(got);
            let [(w, Lobe::Glass(g))] = parts[..] else { panic!("{name}: {parts:?}") };
            assert!((w - Rgb::ONE).abs().max_element() < 1e-6, "{name}: {w:?}");
            let want = if m == "transmit_only" {
                (0.05, 0.05, Halves::Transmit, true)
            } else {
                (0.1, 0.4, Halves::Both, false)
            };
            assert_eq!((g.alpha_x, g.alpha_y, g.halves, g.micro.is_beckmann()), want, "{name}");
            assert_eq!(g.thin, thin, "{name}");
            for wo in incidences() {
                for wo in [wo, -wo] {
                    let e = energy(got, thin, wo);
                    assert!(e.max_element() <= 1.01, "{name} at {wo}: {e}");
                }
            }
            if m == "transmit_only" {
                let e = energy(got, thin, Vec3A::Z);
                assert!((e - Rgb::splat(0.96)).abs().max_element() <= 0.01, "{name} head-on: {e}");
            }
            let b = got.bsdf(Vec3A::Z);
            for i in 0..30 {
                for j in 0..30 {
                    let u = (bsdf::testing::r2(i + 1), bsdf::testing::r2(j + 501));
                    let dir = |u: glam::Vec2| {
                        let z = 1.0 - 2.0 * u.x;
                        let s = (1.0 - z * z).max(0.0).sqrt();
                        Vec3A::new(s * (std::f32::consts::TAU * u.y).cos(), s * (std::f32::consts::TAU * u.y).sin(), z)
                    };
                    let (a, c) = (dir(u.0), dir(u.1));
                    if a.z.abs().min(c.z.abs()) < 0.01 {
                        continue;
                    }
                    let f1 = b.eval(a, c) / index(thin, a).powi(2);
                    let f2 = b.eval(c, a) / index(thin, c).powi(2);
                    let scale = f1.max_element().max(f2.max_element()).max(1e-2);
                    assert!((f1 - f2).abs().max_element() <= 1e-3 * scale, "{name}: f({a}, {c}) {f1} vs {f2}");
                }
            }
            // Solid transmit-only glass sampled at α 0.3: at α 0.05 its refracted lobe is
            // narrower than the χ² test's integration of the density resolves.
            let sampled = if m == "transmit_only" && !thin { get(&mdl, &lib, "transmit_only-0.3") } else { got };
            for wo in [Vec3A::new(0.562, 0.174, 0.808).normalize(), Vec3A::new(-0.3, 0.5, -0.81).normalize()] {
                chi_square(&sampled.bsdf(wo), wo);
            }
        }
    }
}
