//! Tests of the Maya highlight and translucence lobes (`MayaGlossy`, `MayaBsdf`).

use super::*;
use crate::{testing, Bsdf};
use std::f32::consts::{PI, TAU};

fn shapes() -> [Shape; 6] {
    [
        Shape::Blinn { eccentricity: 0.3, rolloff: 0.7 },
        Shape::RampBlinn { eccentricity: 0.3 },
        Shape::Blinn { eccentricity: 0.8, rolloff: 0.7 },
        Shape::Phong { power: 20.0 },
        Shape::PhongE { roughness: 0.5, size: 0.5 },
        Shape::Anisotropic { alpha_x: 0.2, alpha_y: 0.4, ior: 6.0 },
    ]
}

/// ∫ H/π dω over the hemisphere by a midpoint rule in (cos θ, φ), 1000 × 1000.
fn albedo_by_quadrature(shape: Shape, mu: f32) -> f32 {
    let v = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
    let n = 1000;
    let mut sum = 0.0f64;
    for i in 0..n {
        let c = (i as f32 + 0.5) / n as f32;
        let s = (1.0 - c * c).sqrt();
        for j in 0..n {
            let phi = (j as f32 + 0.5) / n as f32 * TAU;
            let l = Vec3A::new(s * phi.cos(), s * phi.sin(), c);
            sum += f64::from(shape.value(v, l));
        }
    }
    (sum * f64::from(TAU) / f64::from(n * n) / f64::from(PI)) as f32
}

/// The refraction bends by Snell's law (sin θt = sin θo / η, η = `refractiveIndex`
/// entering, its inverse leaving, 1 past `refractionLimit`), reflects under total
/// internal reflection, and weighs T per channel (no Fresnel).
#[test]
fn the_refraction_bends_by_snell_and_weighs_the_transparency() {
    let t = Rgb::new(0.9, 0.5, 0.2);
    let g = MayaGlossy::new(Shape::Phong { power: 20.0 }, Rgb::ZERO).with_refraction(t, 1.5, 1);
    let wo = Vec3A::new(0.6, 0.0, 0.8);
    for (inside, made, eta) in [(false, 0, 1.5), (true, 0, 1.0 / 1.5), (false, 1, 1.0), (true, 3, 1.0)] {
        let mut b = g.bsdf(Rgb::ZERO, wo);
        b.refract_at(inside, made);
        let s = b.sample(wo, Vec2::splat(0.5), 0.5).expect("a refraction");
        assert!(s.delta && s.wi.z < 0.0, "{s:?}");
        let sin_t = (s.wi.x * s.wi.x + s.wi.y * s.wi.y).sqrt();
        assert!((sin_t - 0.6 / eta).abs() < 1e-5 && s.wi.x < 0.0, "{inside} {made}: {s:?}");
        assert!((s.weight() - t).abs().max_element() < 1e-5, "{}", s.weight());
    }
    // Leaving at sin θ = 0.8 > 1/1.5: the mirror direction, same weight.
    let wo = Vec3A::new(0.8, 0.0, 0.6);
    let mut b = g.bsdf(Rgb::ZERO, wo);
    b.refract_at(true, 0);
    let s = b.sample(wo, Vec2::splat(0.5), 0.5).expect("a reflection");
    assert!((s.wi - Vec3A::new(-0.8, 0.0, 0.6)).length() < 1e-6, "{s:?}");
    assert!((s.weight() - t).abs().max_element() < 1e-5);
    // Beside a diffuse lobe the delta is chosen by its share: its weight × share is T.
    let b = g.bsdf(Rgb::splat(0.3), wo);
    let s = b.sample(wo, Vec2::splat(0.5), 0.999).expect("a refraction");
    assert!(s.delta && s.pdf < 1.0 && (s.weight() * s.pdf - t).abs().max_element() < 1e-5, "{s:?}");
}

#[test]
fn the_evaluation_gives_the_classic_highlight_under_a_light_of_pi_times_its_colour() {
    // A light of colour C from l: the classic material adds s·C·H(v, l); the path
    // engine's light brings π·C·cos θ of irradiance, reflected by f.
    let v = Vec3A::new(0.3, -0.1, 0.9).normalize();
    let l = Vec3A::new(-0.35, 0.05, 0.8).normalize();
    for shape in shapes() {
        let g = MayaGlossy::new(shape, Rgb::new(0.5, 0.4, 0.3));
        let b = g.bsdf(Rgb::new(0.4, 0.2, 0.1), v);
        let path = b.eval(v, l) * (PI * l.z);
        let classic = Rgb::new(0.4, 0.2, 0.1) * l.z + Rgb::new(0.5, 0.4, 0.3) * shape.value(v, l);
        assert!((path - classic).abs().max_element() < 1e-5, "{shape:?}: {path} vs {classic}");
        // Both sides alike.
        let flip = |w: Vec3A| Vec3A::new(w.x, w.y, -w.z);
        assert!((b.eval(flip(v), flip(l)) - b.eval(v, l)).abs().max_element() < 1e-6);
        assert_eq!(b.eval(v, flip(l)), Rgb::ZERO);
    }
}

#[test]
fn the_tabulated_albedo_matches_quadrature_and_sampling_matches_the_density() {
    for shape in shapes() {
        for mu in [1.0, 0.6, 0.25] {
            let (table, exact) = (shape.albedo(mu), albedo_by_quadrature(shape, mu));
            assert!((table - exact).abs() < 0.03 * exact + 1e-3, "{shape:?} at {mu}: {table} vs {exact}");
        }
        let b = Bsdf::Maya(MayaGlossy::new(shape, Rgb::splat(0.5)).bsdf(Rgb::splat(0.3), testing::incidences()[1]));
        for wo in testing::incidences() {
            testing::chi_square(&b, wo);
        }
    }
}

#[test]
fn a_highlight_that_would_reflect_more_than_it_receives_is_bounded_to_one() {
    // Blinn of eccentricity 0.8 and specularColor 1: its unit albedo exceeds 1 at
    // grazing views (1.9 at μ = 0.05 by quadrature).
    let wide = Shape::Blinn { eccentricity: 0.8, rolloff: 0.7 };
    assert!(albedo_by_quadrature(wide, 0.1) > 1.3);
    let g = MayaGlossy::new(wide, Rgb::ONE);
    for mu in [1.0f32, 0.5, 0.2, 0.1, 0.03] {
        let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        // The highlight alone (no diffuse): its white-furnace albedo.
        let a = testing::albedo(&Bsdf::Maya(g.bsdf(Rgb::ZERO, wo)), wo, 100_000);
        assert!(a.max_element() <= 1.03, "albedo {a} at μ = {mu}");
    }
    // A default blinn is not touched: its tint stays specularColor at every view.
    let default = MayaGlossy::new(Shape::Blinn { eccentricity: 0.3, rolloff: 0.7 }, Rgb::splat(0.5));
    for mu in [1.0f32, 0.5, 0.1, 0.0] {
        let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu.max(1e-3));
        assert_eq!(default.bsdf(Rgb::splat(0.4), wo).tint, Rgb::splat(0.5));
    }
}

#[test]
fn the_mirror_reflects_its_weight_beside_the_other_lobes() {
    // Blinn's default with reflectivity 0.5 · specularColor (0.5, 0.4, 0.2) and
    // reflectionRolloff: the mirror reflects its weight × schlick(0.7, N·V); the
    // furnace albedo is diffuse + highlight + mirror.
    let shape = Shape::Blinn { eccentricity: 0.3, rolloff: 0.7 };
    let tint = Rgb::new(0.5, 0.4, 0.2);
    let g = MayaGlossy::new(shape, tint).with_mirror(tint * 0.5, Some(0.7));
    for mu in [1.0f32, 0.5] {
        let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        let b = g.bsdf(Rgb::splat(0.3), wo);
        let mirror = tint * 0.5 * schlick(0.7, mu);
        assert!((b.mirror - mirror).abs().max_element() < 1e-6);
        let s = b.sample(wo, Vec2::new(0.3, 0.6), 0.9999).expect("the mirror");
        assert!(s.delta && (s.wi - Vec3A::new(-wo.x, 0.0, wo.z)).length() < 1e-6);
        assert!((s.weight() - mirror / b.mirror_share).abs().max_element() < 1e-5);
        let want = Rgb::splat(0.3) + tint * g.unit_albedo(mu) + mirror;
        let a = testing::albedo(&Bsdf::Maya(b), wo, 200_000);
        assert!((a - want).abs().max_element() < 0.01, "μ = {mu}: {a} vs {want}");
    }
}

#[test]
fn reflected_colour_is_emitted_by_the_mirror_weight_and_the_limit_drops_the_mirror() {
    // Blinn with reflectivity 0.5 · specularColor, Schlick's roll-off of 0.3,
    // reflectedColor R, on a surface of coverage ½: emitted r·s·F(N·V) ⊙ R / ½; past
    // the reflection limit the mirror is gone and the rest keeps its albedo.
    let tint = Rgb::new(0.5, 0.4, 0.2);
    let reflected = Rgb::new(0.3, 0.2, 0.1);
    let g = MayaGlossy::new(Shape::Blinn { eccentricity: 0.3, rolloff: 0.7 }, tint)
        .with_mirror(tint * 0.5, Some(0.3))
        .with_reflected(reflected)
        .with_coverage(0.5);
    for mu in [1.0f32, 0.4, 0.1] {
        let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        let b = g.bsdf(Rgb::splat(0.3), wo);
        let want = reflected * tint * 0.5 * schlick(0.3, mu) / 0.5;
        assert!((b.emitted - want).abs().max_element() < 1e-6, "μ = {mu}: {} vs {want}", b.emitted);
        let mut c = b;
        c.without_mirror();
        assert_eq!((c.mirror, c.emitted), (Rgb::ZERO, b.emitted));
        for u in [0.0, 0.5, 0.9999] {
            assert!(c.sample(wo, Vec2::new(0.3, 0.6), u).is_none_or(|s| !s.delta));
        }
        let a = testing::albedo(&Bsdf::Maya(c), wo, 100_000);
        let want = Rgb::splat(0.3) + tint * g.unit_albedo(mu) / 0.5;
        assert!((a - want).abs().max_element() < 0.01, "μ = {mu}: {a} vs {want}");
    }
    // A mirror alone, dropped: nothing to sample.
    let mut m =
        MayaGlossy::new(Shape::Phong { power: 20.0 }, Rgb::ZERO).with_mirror(Rgb::ONE, None).bsdf(Rgb::ZERO, Vec3A::Z);
    m.without_mirror();
    assert!(m.sample(Vec3A::Z, Vec2::new(0.3, 0.6), 0.5).is_none());
}

#[test]
fn view_ramps_scale_the_highlight_and_the_mirror_and_colour_them() {
    // rampShader's roll-off 1 − ¾f and reflectivity 0.8 − 0.6f over the facing ratio
    // f, environment (y, 0, 1 − y) over the reflection's height y = (1 + R_z)/2
    // (no frame: local z is up), specular colour (h, h, 1 − h) over the highlight H.
    let ramps = ViewRamps::tabulate(|f| 1.0 - 0.75 * f, |f| 0.8 - 0.6 * f, |y| Rgb::new(y, 0.0, 1.0 - y));
    let g = MayaGlossy::new(Shape::RampBlinn { eccentricity: 0.3 }, Rgb::splat(0.8))
        .with_mirror(Rgb::ONE, None)
        .with_view_ramps(ramps)
        .with_specular_ramp(|h| Rgb::new(h, h, 1.0 - h));
    let wo = Vec3A::new(0.6, 0.0, 0.8);
    let b = g.bsdf(Rgb::ZERO, wo);
    let r = 0.8 - 0.6 * 0.8;
    assert!((b.mirror - Rgb::splat(r)).abs().max_element() < 1e-5, "{}", b.mirror);
    let env = Rgb::new(0.9, 0.0, 0.1);
    assert!((b.emitted - env * r).abs().max_element() < 1e-5, "{}", b.emitted);
    for l in [Vec3A::new(-0.6, 0.0, 0.8), Vec3A::new(-0.3, 0.2, 0.9).normalize()] {
        let h = ramp_blinn(Vec3A::Z, wo, l, 0.3);
        let want = 0.8 * (1.0 - 0.75 * 0.8) * Rgb::new(h, h, 1.0 - h) * h;
        let got = b.eval(wo, l) * (PI * l.z);
        assert!((got - want).abs().max_element() < 1e-5, "{l}: {got} vs {want}");
    }
    // In a frame the height is the world's y.
    let frame = Frame::from_normal(Vec3A::X);
    let world_y = frame.to_world(Vec3A::new(-0.6, 0.0, 0.8)).y;
    let b = g.bsdf_seen(Rgb::ZERO, wo, Some(&frame));
    let y = 0.5 * (1.0 + world_y);
    assert!((b.emitted - Rgb::new(y, 0.0, 1.0 - y) * r).abs().max_element() < 1e-5, "{}", b.emitted);
}

#[test]
fn the_peak_is_the_formula_over_pi() {
    // Seen and lit head-on, blinn's highlight is the roll-off, phong's and
    // anisotropic's 1, phongE's its size: f = diffuse/π + tint·H/π.
    let n = Vec3A::Z;
    let cases = [
        (Shape::Blinn { eccentricity: 0.3, rolloff: 0.7 }, 0.7),
        (Shape::Phong { power: 20.0 }, 1.0),
        (Shape::PhongE { roughness: 0.5, size: 0.6 }, 0.6),
        (Shape::RampBlinn { eccentricity: 0.4 }, 1.0),
        (Shape::Anisotropic { alpha_x: 0.2, alpha_y: 0.4, ior: 6.0 }, 1.0),
    ];
    for (shape, peak) in cases {
        let b = MayaGlossy::new(shape, Rgb::splat(0.5)).bsdf(Rgb::splat(0.2), n);
        let want = (0.2 + 0.5 * peak) / PI;
        assert!((b.eval(n, n).x - want).abs() < 1e-6, "{shape:?}");
    }
}

/// Directions spread over the sphere (an R2 sequence), local frame.
fn sphere(n: u32) -> Vec<Vec3A> {
    (0..n)
        .map(|i| {
            let u = testing::r2(i + 1);
            let z = 1.0 - 2.0 * u.x;
            let r = (1.0 - z * z).max(0.0).sqrt();
            Vec3A::new(r * (TAU * u.y).cos(), r * (TAU * u.y).sin(), z)
        })
        .collect()
}

/// A layeredShader's two translucent layers of `translucenceFocus` 0 and 0.5 at shares w
/// and 1 − w (w = 0.3; albedo c = (0.5, 0.4, 0.3) and (0.9, 0.8, 0.7)), added in either
/// order: the stack's lobe is w · f(0) + (1 − w) · f(0.5) of the two single lobes within
/// 1e-5 over 64 × 64 pairs of directions; its sampling passes the chi-square test at the
/// standard incidences, and its albedo by sampling (50 000 samples) is the sum of the
/// two single lobes' sampled albedos within 1 %. Furnace: with white layers (c = 1) the
/// stack passes 1 at normal incidence within 1 % and at most 1.01 at the other
/// incidences. Before, the stack took the first translucent layer's focus for both.
#[test]
fn a_stack_of_translucent_layers_keeps_each_layers_focus() {
    let w = 0.3;
    let (n0, n5) = (translucence::focus_exponent(0.0), translucence::focus_exponent(0.5));
    let plain = MayaGlossy::new(Shape::Phong { power: 1.0 }, Rgb::ZERO);
    for (ca, cb) in [(Rgb::new(0.5, 0.4, 0.3), Rgb::new(0.9, 0.8, 0.7)), (Rgb::ONE, Rgb::ONE)] {
        let (a, b) = (plain.with_translucence(ca * w, n0), plain.with_translucence(cb * (1.0 - w), n5));
        for (first, second) in [(a, b), (b, a)] {
            let mut stack = first;
            assert_eq!(stack.add_translucence(second.translucence, second.focus, None), Ok(()));
            assert_eq!(stack.focus, 0.0, "the focus-0 lobe goes first");
            for wo in sphere(64) {
                let (sa, sb, s) = (a.bsdf(Rgb::ZERO, wo), b.bsdf(Rgb::ZERO, wo), stack.bsdf(Rgb::ZERO, wo));
                for wi in sphere(64) {
                    let want = sa.eval(wo, wi) + sb.eval(wo, wi);
                    let got = s.eval(wo, wi);
                    assert!((got - want).abs().max_element() < 1e-5, "{wo} {wi}: {got} vs {want}");
                }
            }
            for wo in testing::incidences() {
                let bsdf = Bsdf::Maya(stack.bsdf(Rgb::ZERO, wo));
                testing::chi_square(&bsdf, wo);
                let albedo = testing::albedo(&bsdf, wo, 50_000);
                let single = |g: &MayaGlossy| testing::albedo(&Bsdf::Maya(g.bsdf(Rgb::ZERO, wo)), wo, 50_000);
                let want = single(&a) + single(&b);
                assert!(((albedo / want) - 1.0).abs().max_element() < 0.01, "{wo}: {albedo} vs {want}");
                if ca == Rgb::ONE {
                    assert!(albedo.max_element() < 1.01, "furnace at {wo}: {albedo}");
                    if wo == Vec3A::Z {
                        assert!((albedo - Rgb::ONE).abs().max_element() < 0.01, "furnace head-on: {albedo}");
                    }
                }
            }
        }
    }
}

/// A stack carries four distinct foci exactly (a lobe each: the stack's f is their sum
/// within 1e-5); a fifth is merged into the further lobe of the nearest exponent, which
/// keeps its own (`add_translucence` says so, naming both exponents), and a layer of a
/// focus already carried joins its lobe.
#[test]
fn a_stack_carries_four_foci_and_merges_a_fifth_into_the_nearest() {
    let plain = MayaGlossy::new(Shape::Phong { power: 1.0 }, Rgb::ZERO);
    let foci = [0.0f32, 2.0, 8.0, 18.0];
    let lobes: Vec<MayaGlossy> = foci.iter().map(|&n| plain.with_translucence(Rgb::splat(0.2), n)).collect();
    let mut stack = plain;
    for l in &lobes {
        assert_eq!(stack.add_translucence(l.translucence, l.focus, None), Ok(()));
    }
    assert_eq!(stack.add_translucence(Rgb::splat(0.1), 2.0, None), Ok(()), "a focus already carried");
    for wo in sphere(16) {
        for wi in sphere(16) {
            let want = lobes.iter().fold(Rgb::ZERO, |s, l| s + l.bsdf(Rgb::ZERO, wo).eval(wo, wi))
                + plain.with_translucence(Rgb::splat(0.1), 2.0).bsdf(Rgb::ZERO, wo).eval(wo, wi);
            let got = stack.bsdf(Rgb::ZERO, wo).eval(wo, wi);
            assert!((got - want).abs().max_element() < 1e-5, "{got} vs {want}");
        }
    }
    let merged = stack.add_translucence(Rgb::splat(0.1), 10.0, None);
    assert_eq!(merged, Err(crate::Merged { exponent: 10.0, into: 8.0 }), "a fifth focus has no lobe of its own");
    assert_eq!(stack.translucence_lobes().count(), 4);
    let (a, n) = stack.translucence_lobes().find(|(_, n)| *n == 8.0).expect("the lobe of exponent 8");
    assert!((a - Rgb::splat(0.3)).abs().max_element() < 1e-6 && n == 8.0, "{a} {n}");
}
