//! Lobe sums whose weights depend on direction: layer curves (`custom_curve_layer`,
//! `fresnel_layer`, `thin_film`), directional factors, a sheen over its base, and the
//! backscattering and mirror lobes. Each passes the standard checks (reciprocity 1e-4,
//! albedo bound, chi-square at three incidences); lossless combinations pass a white
//! furnace within 1 %.

use bsdf::layer_curve::{airy_reflectance, CurveKind, LayerCurve};
use bsdf::microfacet::Ggx;
use bsdf::testing::{albedo, incidences, standard_checks};
use bsdf::{Bsdf, Lobe, Lobes, Rgb, Role};
use glam::Vec3A;

fn schlick(normal: f32, grazing: f32, exponent: f32) -> CurveKind {
    CurveKind::Schlick { normal: Rgb::splat(normal), grazing: Rgb::splat(grazing), exponent }
}

/// `layer` (weight 1 inside the layer) of curve `kind` and weight `w` over a base lobe of
/// tint `base_tint`.
fn layered(kind: CurveKind, w: Rgb, layer: Lobe, base: Lobe, base_tint: Rgb) -> Bsdf {
    let mut l = Lobes::default();
    let lambertian = matches!(base, Lobe::Diffuse(s) if s == 0.0);
    let k = l.add_curve(LayerCurve::new(kind, w, lambertian)).unwrap();
    assert!(l.push_with_role(Rgb::ONE, layer, Role { over: 1 << k, ..Role::default() }));
    assert!(l.push_with_role(base_tint, base, Role { under: 1 << k, ..Role::default() }));
    Bsdf::Lobes(l)
}

fn lossless(bsdf: &Bsdf, what: &str) {
    for wo in incidences() {
        let a = albedo(bsdf, wo, 50_000);
        assert!((a - Rgb::ONE).abs().max_element() <= 0.01, "{what}: albedo {a:?} at {wo:?}");
    }
}

#[test]
fn backscattering_glossy_reflects_back_towards_the_viewer_and_passes_the_checks() {
    for g in [Ggx::isotropic(0.3), Ggx { alpha_x: 0.4, alpha_y: 0.15 }] {
        let mut l = Lobes::default();
        assert!(l.push(Rgb::ONE, Lobe::Backscatter(g)));
        let bsdf = Bsdf::Lobes(l);
        standard_checks(&bsdf, 1.005, &format!("backscatter {g:?}"));
        // At 60° the lobe peaks back along ωo, not in the mirror direction.
        let wo = Vec3A::new(0.866, 0.0, 0.5);
        let mirror = Vec3A::new(-0.866, 0.0, 0.5);
        assert!(bsdf.eval(wo, wo).x > 20.0 * bsdf.eval(wo, mirror).x, "{g:?}");
        // It is the GGX reflection turned by π: the same albedo at every incidence.
        let mut ggx = Lobes::default();
        assert!(ggx.push(Rgb::ONE, Lobe::Ggx(g)));
        for wo in incidences() {
            let (a, b) = (albedo(&bsdf, wo, 50_000).x, albedo(&Bsdf::Lobes(ggx), wo, 50_000).x);
            assert!((a - b).abs() < 0.01, "{g:?} at {wo:?}: {a} vs {b}");
        }
    }
}

#[test]
fn a_curve_layered_mirror_takes_its_curve_and_leaves_a_white_base_lossless() {
    let kind = schlick(0.1, 0.9, 5.0);
    let w = Rgb::new(1.0, 0.7, 0.4);
    let white = layered(kind, w, Lobe::Mirror, Lobe::Diffuse(0.0), Rgb::ONE);
    standard_checks(&white, 1.01, "curve layer over white Lambert");
    lossless(&white, "curve layer over white Lambert");
    // Over a black base only the mirror reflects: weight · R(cos θo), exactly.
    let black = layered(kind, w, Lobe::Mirror, Lobe::Diffuse(0.0), Rgb::ZERO);
    for wo in incidences() {
        let a = albedo(&black, wo, 1000);
        let expected = w * kind.eval(wo.z);
        assert!((a - expected).abs().max_element() < 1e-5, "{a:?} vs {expected:?} at {wo:?}");
    }
}

#[test]
fn curve_and_fresnel_layers_of_glossy_lobes_conserve_energy() {
    let ggx = Lobe::Ggx(Ggx::isotropic(0.25));
    for (kind, what) in [(schlick(0.04, 1.0, 5.0), "schlick"), (CurveKind::Fresnel { ior: 1.5 }, "fresnel")] {
        // Glossy over Lambert: at most 1; GGX single scattering loses a little to
        // shadowing, and the layer's min(R(θo), R(θi)) a little at grazing (0.89 at 72°).
        let b = layered(kind, Rgb::ONE, ggx, Lobe::Diffuse(0.0), Rgb::ONE);
        standard_checks(&b, 1.005, &format!("{what}: glossy over Lambert"));
        for wo in incidences() {
            let a = albedo(&b, wo, 50_000);
            assert!(a.min_element() > 0.85, "{what}: {a:?} at {wo:?}");
        }
        // A mirror over a glossy base (no compensation there): at most 1.
        let b = layered(kind, Rgb::ONE, Lobe::Mirror, ggx, Rgb::ONE);
        standard_checks(&b, 1.005, &format!("{what}: mirror over glossy"));
        // Rough Oren–Nayar base.
        let b = layered(kind, Rgb::splat(0.8), ggx, Lobe::Diffuse(0.5), Rgb::ONE);
        standard_checks(&b, 1.005, &format!("{what}: glossy over Oren–Nayar"));
    }
}

#[test]
fn a_thin_film_over_a_fresnel_layer_colours_it_and_stays_lossless() {
    let kind = CurveKind::ThinFilm { ior: 1.5, film_ior: Rgb::splat(1.33), thickness_nm: 400.0 };
    let b = layered(kind, Rgb::ONE, Lobe::Mirror, Lobe::Diffuse(0.0), Rgb::ONE);
    standard_checks(&b, 1.01, "thin film over white Lambert");
    lossless(&b, "thin film over white Lambert");
    // The mirror's reflectance is the film's Airy reflectance averaged over each band,
    // and it is coloured (the channels differ by more than 0.01 at normal incidence).
    let r = kind.eval(1.0);
    let green = (airy_reflectance(1.0, 1.33, 1.5, 400.0, 510.0)
        + airy_reflectance(1.0, 1.33, 1.5, 400.0, 540.0)
        + airy_reflectance(1.0, 1.33, 1.5, 400.0, 570.0))
        / 3.0;
    assert!((r.y - green).abs() < 1e-6);
    assert!(r.max_element() - r.min_element() > 0.01, "{r:?}");
}

#[test]
fn a_directional_factor_scales_by_its_curve_at_the_half_vector() {
    let kind = schlick(0.2, 1.0, 3.0);
    let mut l = Lobes::default();
    let k = l.add_curve(LayerCurve::new(kind, Rgb::ONE, false)).unwrap();
    let role = Role { factor: 1 << k, ..Role::default() };
    assert!(l.push_with_role(Rgb::ONE, Lobe::Ggx(Ggx::isotropic(0.3)), role));
    let b = Bsdf::Lobes(l);
    standard_checks(&b, 1.005, "directional factor");
    let (wo, wi) = (Vec3A::new(0.6, 0.0, 0.8), Vec3A::new(-0.8, 0.0, 0.6));
    let h = (wo + wi).normalize();
    let mut plain = Lobes::default();
    assert!(plain.push(Rgb::ONE, Lobe::Ggx(Ggx::isotropic(0.3))));
    let ratio = b.eval(wo, wi).x / plain.eval(wo, wi).x;
    assert!((ratio - kind.eval(wo.dot(h)).x).abs() < 1e-5, "{ratio}");
}

/// A sheen over a white Lambertian base: without compensation the two add up past 1
/// (the sheen's albedo on top of everything the base reflects); with the base under the
/// sheen's albedo curve the white furnace is 1 within 1 %.
#[test]
fn sheen_over_a_white_base_is_energy_compensated() {
    for r in [0.2, 0.5, 1.0] {
        let mut plain = Lobes::default();
        assert!(plain.push(Rgb::ONE, Lobe::Sheen(r)) && plain.push(Rgb::ONE, Lobe::Diffuse(0.0)));
        let grazing = incidences()[2];
        assert!(albedo(&Bsdf::Lobes(plain), grazing, 50_000).x > 1.05, "sheen {r} uncompensated");
        let b =
            layered(CurveKind::SheenAlbedo { roughness: r }, Rgb::ONE, Lobe::Sheen(r), Lobe::Diffuse(0.0), Rgb::ONE);
        standard_checks(&b, 1.01, &format!("sheen {r} over white Lambert"));
        lossless(&b, &format!("sheen {r} over white Lambert"));
    }
}
