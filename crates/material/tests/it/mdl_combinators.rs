//! The distribution-function combinators compiled after the others
//! (tests/mdl/combinators.mdl): `unbounded_mix` and `color_unbounded_mix` (weights summed as
//! given), `measured_curve_layer` and its colour form, `fresnel_factor` (a conductor's
//! Fresnel reflectance at the half vector), and the combinators of EDFs (`tint`,
//! `directional_factor`, the mixes). Each test states its tolerance.

use crate::mdl_support;

use bsdf::testing::{albedo, incidences, standard_checks};
use bsdf::Rgb;
use glam::Vec3A;
use material::SurfaceModel;
use mdl_support::per_hit::direction_pairs;
use mdl_support::{close, compile_text, get};

/// `unbounded_mix` sums its weights as given (MDL: no normalisation, no clamp): 0.75 + 0.5
/// of a white Lambertian is a Lambertian of albedo exactly 1.25 (1e-6), which the furnace
/// measures as 1.25 (1e-4: cosine sampling of a Lambertian has no variance) — more than it
/// receives, as MDL defines. The colour form weighs a tinted Lambertian and a grey mirror
/// per channel: lobe weights (0.8, 0.1, 0.5) and (0.3, 0.15, 0.45) (1e-6), a furnace of
/// their sum (1 %), whose red channel passes 1.
#[test]
fn unbounded_mixes_sum_their_weights_as_given() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "u" "mdl::combinators::unbounded" ()
shader "c" "mdl::combinators::color_unbounded" ()
shader "g" "mdl::combinators::unbounded_glossy" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let u = get(&mdl, &lib, "u");
    assert_eq!(u.model, SurfaceModel::Lambert);
    assert!(close(u.diffuse, Rgb::splat(1.25), 1e-6), "{:?}", u.diffuse);
    for wo in incidences() {
        let a = albedo(&u.bsdf(wo), wo, 20_000);
        assert!(close(a, Rgb::splat(1.25), 1e-4), "albedo {a:?} at {wo:?}");
    }
    let c = get(&mdl, &lib, "c");
    let SurfaceModel::Lobes(l) = &c.model else { panic!("{:?}", c.model) };
    assert!(close(l.diffuse.albedo, Rgb::new(0.8, 0.1, 0.5), 1e-6), "{:?}", l.diffuse.albedo);
    assert!(close(l.reflect, Rgb::new(0.3, 0.15, 0.45), 1e-6), "{:?}", l.reflect);
    let want = Rgb::new(1.1, 0.25, 0.95);
    for wo in incidences() {
        let a = albedo(&c.bsdf(wo), wo, 20_000);
        assert!(((a - want) / want).abs().max_element() <= 0.01, "albedo {a:?} at {wo:?}");
    }
    // A general lobe sum keeps the weights as given too: 0.7 + 0.6 + 0.2.
    let g = get(&mdl, &lib, "g");
    let SurfaceModel::MdlLobes(l) = &g.model else { panic!("{:?}", g.model) };
    let weights: Vec<Rgb> = l.parts().map(|p| p.0).collect();
    assert_eq!(weights, vec![Rgb::splat(0.7), Rgb::splat(0.6), Rgb::splat(0.2)]);
}

/// A measured curve equal to the constant w is `weighted_layer(w)` (over a white
/// Lambertian base, whose share the curve layer normalises): equal BSDF values at every
/// pair of directions within 1e-5 of the largest.
#[test]
fn a_constant_measured_curve_is_the_weighted_layer() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "m" "mdl::combinators::measured_constant" ("w" 0.3)
shader "w" "mdl::combinators::weighted_constant" ("w" 0.3)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let (m, w) = (get(&mdl, &lib, "m"), get(&mdl, &lib, "w"));
    assert!(matches!(m.model, SurfaceModel::MdlLobes(_)), "{:?}", m.model);
    for (wo, wi) in direction_pairs() {
        let (a, b) = (m.bsdf(wo).eval(wo, wi), w.bsdf(wo).eval(wo, wi));
        let scale = a.max_element().max(b.max_element()).max(1e-3);
        assert!((a - b).abs().max_element() <= 1e-5 * scale, "{wo} {wi}: {a:?} vs {b:?}");
    }
}

/// A curve of two colours a, b is a + (b − a) θ / (π/2) (MDL: samples at uniform steps of
/// the angle from 0 to π/2, linear between them): a mirror under it with no base reflects
/// exactly that at 0°, 37° and 72° (1e-5).
#[test]
fn a_two_value_measured_curve_is_linear_in_the_angle() {
    let (mdl, lib, diags) = compile_text(r#"shader "l" "mdl::combinators::measured_linear" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let m = get(&mdl, &lib, "l");
    let (a, b) = (Rgb::new(0.2, 0.4, 0.1), Rgb::new(0.8, 0.6, 1.0));
    for wo in incidences() {
        let theta = wo.z.acos();
        let want = a + (b - a) * (theta / std::f32::consts::FRAC_PI_2);
        let got = albedo(&m.bsdf(wo), wo, 16);
        assert!(close(got, want, 1e-5), "θ {theta}: {got:?} vs {want:?}");
    }
}

/// A mirror under a tabulated curve over a white Lambertian is lossless (1 ± 1 %); a
/// tinted rough GGX lobe under one (GGX micro-mirrors lose what they shadow) reflects at
/// most what it receives (≤ 1 + 1 %). Both pass the standard checks (reciprocity 1e-4,
/// albedo ≤ 1 + 1 %, χ² of the sampling at the 1 % level).
#[test]
fn measured_curve_layers_pass_the_furnace_and_the_standard_checks() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "c" "mdl::combinators::measured_coat" ()
shader "r" "mdl::combinators::measured_rough_coat" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    for name in ["c", "r"] {
        let m = get(&mdl, &lib, name);
        assert!(matches!(m.model, SurfaceModel::MdlLobes(_)), "{name}: {:?}", m.model);
        for wo in incidences() {
            let a = albedo(&m.bsdf(wo), wo, 50_000);
            let lossless = name == "c";
            let ok = if lossless { (a - Rgb::ONE).abs().max_element() <= 0.01 } else { a.max_element() <= 1.01 };
            assert!(ok, "{name}: albedo {a:?} at {wo:?}");
        }
        standard_checks(&m.bsdf(Vec3A::Z), 1.01, name);
    }
}

/// `fresnel_factor` scales its base by a conductor's Fresnel reflectance at the half
/// vector: a mirror under it reflects exactly F(θ) of the complex index at 0° and 60°
/// (1e-4, against `bsdf::conductor::fresnel_conductor_rgb`); over a rough GGX lobe it
/// reflects at most what it receives (≤ 1 + 1 %) and passes the standard checks.
#[test]
fn fresnel_factors_reflect_the_conductor_fresnel_term() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "m" "mdl::combinators::fresnel_mirror" ()
shader "r" "mdl::combinators::fresnel_rough" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let (eta, k) = (Rgb::new(0.2, 0.9, 1.1), Rgb::new(3.9, 2.4, 2.2));
    let m = get(&mdl, &lib, "m");
    for deg in [0.0f32, 60.0] {
        let wo = Vec3A::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
        let want = bsdf::conductor::fresnel_conductor_rgb(wo.z, eta, k);
        let got = albedo(&m.bsdf(wo), wo, 16);
        assert!(close(got, want, 1e-4), "{deg}°: {got:?} vs {want:?}");
    }
    let r = get(&mdl, &lib, "r");
    for wo in incidences() {
        let a = albedo(&r.bsdf(wo), wo, 20_000);
        assert!(a.max_element() <= 1.01, "albedo {a:?} at {wo:?}");
    }
    standard_checks(&r.bsdf(Vec3A::Z), 1.01, "fresnel_rough");
}

/// The emitted radiance of a material towards the direction at `deg` degrees from the
/// normal (z), in the x–z plane.
fn radiance(m: &material::SurfaceMaterial, deg: f32) -> Rgb {
    let d = Vec3A::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
    m.emission * m.emission_shape.as_ref().map_or(Rgb::ONE, |s| s.factor(Vec3A::Z, None, d))
}

/// Tints, directional factors and mixes of edfs emit the weighted sum of their
/// components' radiances: a Lambertian's intensity/π, a spot's N · shape (the spot of
/// exponent 4 and spread 2 about the normal) — each as the mixes weigh them (normalised
/// per channel, clamped, or as given) — at 0°, 30°, 55° and 80° (1e-4 relative).
#[test]
fn edf_combinators_emit_the_weighted_sum_of_their_components() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "t" "mdl::combinators::edf_tint" ()
shader "f" "mdl::combinators::edf_factor" ()
shader "n" "mdl::combinators::edf_normalized" ()
shader "c" "mdl::combinators::edf_clamped" ()
shader "u" "mdl::combinators::edf_unbounded" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let spot = material::spot_edf::SpotEdf::new(4.0, 2.0, None);
    let lambert = Rgb::splat(std::f32::consts::FRAC_1_PI);
    for deg in [0.0f32, 30.0, 55.0, 80.0] {
        let d = Vec3A::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
        let s = Rgb::splat(spot.normalization * spot.factor(Vec3A::Z, d));
        let c = d.z;
        let n = Rgb::new(1.0, 0.5, 0.2);
        let (w1, w2) = (Rgb::new(0.5, 0.2, 0.9), Rgb::new(0.7, 0.9, 0.1));
        let total = (w1 + w2).max(Rgb::ONE);
        let want = [
            ("t", Rgb::new(0.5, 1.0, 2.0) * 3.0 * s),
            ("f", (n + (Rgb::ONE - n) * (1.0 - c).powi(3)) * lambert),
            ("n", 2.0 * (w1 / total * lambert + w2 / total * s)),
            ("c", 2.0 * (0.7 * lambert + 0.3 * s)),
            ("u", 2.0 * (0.7 * lambert + 0.6 * Rgb::new(1.0, 0.5, 0.25) * s)),
        ];
        for (name, want) in want {
            let got = radiance(get(&mdl, &lib, name), deg);
            let scale = want.max_element().max(1e-6);
            assert!((got - want).abs().max_element() <= 1e-4 * scale, "{name} at {deg}°: {got:?} vs {want:?}");
        }
    }
}

/// What once was an error compiles without a diagnostic: a tint of a `measured_edf` (mdl36;
/// its radiance: `mdl_measured_edf`), emitting through an edf tree, and `measured_factor`
/// of the invalid texture (see `mdl_measured_factor`).
#[test]
fn tints_of_measured_edfs_and_curve_factors_compile() {
    let (mdl, lib, diags) = compile_text("shader \"m\" \"mdl::combinators::measured_edf_tint\" ()");
    assert!(diags.is_empty(), "{diags:#?}");
    let m = get(&mdl, &lib, "m");
    assert!(matches!(m.emission_shape, Some(material::edf::EmissionShape::Tree(_))), "{:?}", m.emission_shape);
    let (_, _, diags) = compile_text("shader \"m\" \"mdl::combinators::curve_factor\" ()");
    assert!(diags.is_empty(), "{diags:#?}");
}

/// `measured_curve_factor` scales its base by the tabulated curve at the half vector (the
/// MDL SDK reads it so): a mirror under a two-colour curve a, b reflects a + (b − a) θ /
/// (π/2) at 0°, 37° and 72° (1e-5); over a rough GGX lobe it reflects at most what it
/// receives (≤ 1 + 1 %) and passes the standard checks.
#[test]
fn a_measured_curve_factor_scales_its_base_by_the_curve() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "m" "mdl::combinators::curve_factor_mirror" ()
shader "r" "mdl::combinators::curve_factor_rough" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let m = get(&mdl, &lib, "m");
    let (a, b) = (Rgb::new(0.9, 0.5, 0.3), Rgb::new(0.1, 0.7, 1.0));
    for wo in incidences() {
        let theta = wo.z.acos();
        let want = a + (b - a) * (theta / std::f32::consts::FRAC_PI_2);
        let got = albedo(&m.bsdf(wo), wo, 16);
        assert!(close(got, want, 1e-5), "θ {theta}: {got:?} vs {want:?}");
    }
    let r = get(&mdl, &lib, "r");
    for wo in incidences() {
        let a = albedo(&r.bsdf(wo), wo, 20_000);
        assert!(a.max_element() <= 1.01, "albedo {a:?} at {wo:?}");
    }
    standard_checks(&r.bsdf(Vec3A::Z), 1.01, "curve_factor_rough");
}
