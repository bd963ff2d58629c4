//! Tests of the light-angle shape: the ramp read exactly, its albedo, mixes.

use super::*;
use glam::{Vec2, Vec3A};
use std::f32::consts::TAU;

/// The colour ramp C = (0.2, 0.9, 0.5) at x = 0, (1.1, 0.3, 0.5) at ¼, (0.6, 0.6, 0.5) at
/// ½ (linear: P(u) = t · C((1 − u)/2), t = 1, has a knot at u = ½): the shape's albedo
/// is 2∫P du within 1e-6 (uncapped: red's is 1.5), A ⊙ S(u) is P(u) within 1e-6 at
/// u = 0.05 … 1 (the knot followed), 2∫S du is 1 per channel within 1e-3 (midpoint
/// rule, 100 000 steps), the diffuse shape's factor is 1 within 1e-6 at every angle,
/// and a mix with it is the albedo-weighted sum of the two P within 1e-6 (exact: one
/// side has no ramp part). `uniform_opposite` lands on the far side, unit length,
/// with z uniform (mean |z| ½ within 1e-3 over 10 000 stratified samples).
#[test]
fn the_light_angle_shape_follows_the_ramp_and_keeps_its_albedo() {
    let (p0, p1, p2) = (Rgb::new(0.2, 0.9, 0.5), Rgb::new(1.1, 0.3, 0.5), Rgb::new(0.6, 0.6, 0.5));
    // P(u) at u = 1 is C(0), at u = ½ C(¼), at u = 0 C(½).
    let p = |u: f32| if u < 0.5 { p2 + (p1 - p2) * (u / 0.5) } else { p1 + (p0 - p1) * ((u - 0.5) / 0.5) };
    let (a, shape) = LightAngle::from_ramp(&[(0.0, p0, 1), (0.25, p1, 1), (0.5, p2, 1)], Rgb::ZERO, 1.0);
    let want = (p0 + p1 * 2.0 + p2) * 0.5;
    assert!((a - want).abs().max_element() < 1e-6, "{a} vs {want}");
    assert!(a.x > 1.0);
    for u in [0.05f32, 0.2, 0.4, 0.5, 0.6, 0.93, 1.0] {
        let got = a * shape.factor(u) * u;
        assert!((got - p(u)).abs().max_element() < 1e-6, "u {u}: {got} vs {}", p(u));
        assert!((LightAngle::DIFFUSE.factor(u) - Rgb::ONE).abs().max_element() < 1e-6);
    }
    let steps = 100_000;
    let integral = (0..steps).map(|i| shape.shape_at((i as f32 + 0.5) / steps as f32)).fold(Rgb::ZERO, |s, v| s + v)
        * (2.0 / steps as f32);
    assert!((integral - Rgb::ONE).abs().max_element() < 1e-3, "{integral}");
    let b = Rgb::new(0.3, 0.1, 0.7);
    assert!(shape.mixes_exactly(&LightAngle::DIFFUSE));
    let mixed = shape.mixed(a, &LightAngle::DIFFUSE, b);
    for u in [0.1f32, 0.5, 0.8] {
        let got = (a + b) * mixed.shape_at(u);
        let want = p(u) + b * u;
        assert!((got - want).abs().max_element() < 1e-6, "u {u}: {got} vs {want}");
    }
    let wo = Vec3A::new(0.3, 0.1, 0.9).normalize();
    let mut sum = 0.0;
    for i in 0..100 {
        for j in 0..100 {
            let w = crate::maya_highlight::translucence::uniform_opposite(
                wo,
                Vec2::new((i as f32 + 0.5) / 100.0, (j as f32 + 0.5) / 100.0),
            );
            assert!(w.z < 0.0 && (w.length() - 1.0).abs() < 1e-4);
            sum += -w.z;
        }
    }
    assert!((sum / 1e4 - 0.5).abs() < 1e-3);
    assert!((crate::maya_highlight::translucence::UNIFORM_PDF * TAU - 1.0).abs() < 1e-6);
}

/// The classic ramp of `knots` (position, colour, Maya interpolation) at `x`, read
/// over the whole ramp as the classic shaders read it (`ramp_curve::ramp_value`, whose
/// formulas its own tests check); the lobe keeps only the knots the light from behind
/// reads.
fn classic_ramp(knots: &[(f32, Rgb, i32)], x: f32) -> Rgb {
    crate::maya_highlight::ramp_curve::ramp_value(knots, x)
}

/// Ramps with knots off the former table's sixteenths (0.1, 0.37 and 0.8) in each
/// interpolation (none, linear, smooth, spline), t = 0.7: A ⊙ S(u) is t · C((1 − u)/2)
/// within 1e-5 at 100 light cosines, the albedo is 2∫P du by a midpoint rule (200 000
/// steps, summed in f64) within 1e-4.
#[test]
fn the_light_angle_shape_reads_the_ramp_in_every_interpolation() {
    for interp in 0..4 {
        let knots = [
            (0.1, Rgb::new(0.9, 0.1, 0.3), interp),
            (0.37, Rgb::new(0.2, 0.8, 0.6), interp),
            (0.8, Rgb::new(0.5, 0.3, 1.2), interp),
        ];
        let t = 0.7;
        let (a, shape) = LightAngle::from_ramp(&knots, Rgb::ZERO, t);
        for i in 0..100 {
            let u = (i as f32 + 0.5) / 100.0;
            let got = a * shape.factor(u) * u;
            let want = classic_ramp(&knots, 0.5 * (1.0 - u)) * t;
            assert!((got - want).abs().max_element() < 1e-5, "interp {interp}, u {u}: {got} vs {want}");
        }
        let steps = 200_000;
        let sum = (0..steps).fold([0.0f64; 3], |s, i| {
            let p = classic_ramp(&knots, 0.5 * (1.0 - (i as f32 + 0.5) / steps as f32)) * t;
            [s[0] + f64::from(p.x), s[1] + f64::from(p.y), s[2] + f64::from(p.z)]
        });
        let want = Rgb::from(sum.map(|v| (v * 2.0 / f64::from(steps)) as f32));
        assert!((a - want).abs().max_element() < 1e-4, "interp {interp}: {a} vs {want}");
    }
}

/// A Maya BSDF with a light-angle translucence (P from 0.5 · (0.9, 0.6, 0.3) straight
/// behind to 0.5 · (0.2, 0.5, 0.9) at the horizon with a knot (0.8, 0.1, 0.4) · 0.5
/// at u = ½, smooth; diffuse 0.3): its sampling passes the chi-square test of its
/// density at the standard incidences, and its albedo by sampling (50 000 samples) is
/// 0.3 + A within 1 % per channel. It is not reciprocal (the classic formula follows
/// the light's direction only).
#[test]
fn the_light_angle_lobe_samples_its_density_and_keeps_its_albedo() {
    let knots = [
        (0.0, Rgb::new(0.9, 0.6, 0.3) * 0.5, 2),
        (0.25, Rgb::new(0.8, 0.1, 0.4) * 0.5, 2),
        (0.5, Rgb::new(0.2, 0.5, 0.9) * 0.5, 2),
    ];
    let (a, shape) = LightAngle::from_ramp(&knots, Rgb::ZERO, 1.0);
    let g = crate::MayaGlossy::new(crate::maya_highlight::Shape::Phong { power: 1.0 }, Rgb::ZERO)
        .with_translucence(a, 0.0)
        .with_light_angle(shape);
    for wo in crate::testing::incidences() {
        let bsdf = crate::Bsdf::Maya(g.bsdf(Rgb::splat(0.3), wo));
        crate::testing::chi_square(&bsdf, wo);
        let albedo = crate::testing::albedo(&bsdf, wo, 50_000);
        let want = a + 0.3;
        assert!(((albedo / want) - 1.0).abs().max_element() < 0.01, "{wo}: {albedo} vs {want}");
    }
}

/// A 5-knot and a 7-knot colour ramp, knots past ½ and inside, smooth (2) and spline (3)
/// segments (and one of each other kind in the 7-knot ramp), t = 0.6.
fn many_knots() -> [Vec<(f32, Rgb, i32)>; 2] {
    let five = vec![
        (0.05, Rgb::new(0.9, 0.2, 0.4), 2),
        (0.18, Rgb::new(0.1, 0.7, 0.3), 3),
        (0.31, Rgb::new(0.6, 0.1, 0.9), 2),
        (0.47, Rgb::new(0.3, 0.9, 0.2), 3),
        (0.72, Rgb::new(1.1, 0.4, 0.6), 2),
    ];
    let seven = vec![
        (0.0, Rgb::new(0.2, 0.5, 0.8), 3),
        (0.08, Rgb::new(0.9, 0.1, 0.2), 2),
        (0.15, Rgb::new(0.4, 0.8, 0.1), 0),
        (0.26, Rgb::new(0.7, 0.3, 0.5), 1),
        (0.39, Rgb::new(0.1, 0.6, 0.9), 3),
        (0.55, Rgb::new(0.8, 0.8, 0.3), 2),
        (0.9, Rgb::new(0.3, 0.2, 0.7), 3),
    ];
    [five, seven]
}

/// Ramps of 5 and 7 knots (4 and 5 of them in [0, ½], past the former limit of 3): A ⊙ S(u)
/// is t · C((1 − u)/2) within 1e-5 at 200 light cosines, the albedo 2∫P du by a midpoint
/// rule (200 000 steps, f64) within 1e-4.
#[test]
fn ramps_of_many_knots_are_read_exactly() {
    let t = 0.6;
    for knots in many_knots() {
        let (a, shape) = LightAngle::from_ramp(&knots, Rgb::ZERO, t);
        for i in 0..200 {
            let u = (i as f32 + 0.5) / 200.0;
            let got = a * shape.factor(u) * u;
            let want = classic_ramp(&knots, 0.5 * (1.0 - u)) * t;
            assert!((got - want).abs().max_element() < 1e-5, "{} knots, u {u}: {got} vs {want}", knots.len());
        }
        let steps = 200_000;
        let sum = (0..steps).fold([0.0f64; 3], |s, i| {
            let p = classic_ramp(&knots, 0.5 * (1.0 - (i as f32 + 0.5) / steps as f32)) * t;
            [s[0] + f64::from(p.x), s[1] + f64::from(p.y), s[2] + f64::from(p.z)]
        });
        let want = Rgb::from(sum.map(|v| (v * 2.0 / f64::from(steps)) as f32));
        assert!((a - want).abs().max_element() < 1e-4, "{} knots: {a} vs {want}", knots.len());
    }
}

/// Two lobes whose ramps' knots differ (the 5- and 7-knot ramps), mixed by their albedos,
/// and a diffuse third: (a + b) ⊙ S_mix(u) = a ⊙ S_a(u) + b ⊙ S_b(u) within 1e-5 at 50
/// cosines (each keeps its own ramp), mixing is exact, and equal ramps share one part (a
/// ramp mixed with itself is itself within 1e-6). A fifth distinct shape is not exact.
#[test]
fn differing_ramps_mix_as_the_sum_of_each() {
    let [five, seven] = many_knots();
    let (a, sa) = LightAngle::from_ramp(&five, Rgb::ZERO, 0.6);
    let (b, sb) = LightAngle::from_ramp(&seven, Rgb::ZERO, 0.3);
    let d = Rgb::new(0.2, 0.05, 0.4);
    assert!(sa.mixes_exactly(&sb));
    let ab = sa.mixed(a, &sb, b);
    assert!(ab.mixes_exactly(&LightAngle::DIFFUSE));
    let abd = ab.mixed(a + b, &LightAngle::DIFFUSE, d);
    for i in 0..50 {
        let u = (i as f32 + 0.5) / 50.0;
        let want = a * sa.shape_at(u) + b * sb.shape_at(u);
        let got = (a + b) * ab.shape_at(u);
        assert!((got - want).abs().max_element() < 1e-5, "u {u}: {got} vs {want}");
        let got = (a + b + d) * abd.shape_at(u);
        assert!((got - (want + d * u)).abs().max_element() < 1e-5, "u {u}: {got} vs {}", want + d * u);
        let same = sa.mixed(a, &sa, a * 0.5);
        assert!((same.shape_at(u) - sa.shape_at(u)).abs().max_element() < 1e-6);
    }
    assert_eq!(sa.mixed(a, &sa, a).used().count(), 1);
    let more: Vec<LightAngle> = (0..3)
        .map(|k| LightAngle::from_ramp(&[(0.1 * k as f32, Rgb::ONE, 1), (0.45, Rgb::splat(0.2), 1)], Rgb::ZERO, 1.0).1)
        .collect();
    let four = more.iter().fold(sa, |m, s| m.mixed(Rgb::ONE, s, Rgb::ONE));
    assert_eq!(four.used().count(), 4);
    assert!(!four.mixes_exactly(&sb));
}

/// The light-angle shape is a reference and weights, whatever the ramp's knots: at most
/// the 88 bytes its table of 4 knots took, so the BSDF stays at 336 bytes at most (416
/// before maya46).
#[test]
fn the_shape_keeps_the_bsdf_small() {
    assert!(std::mem::size_of::<Option<LightAngle>>() <= 88, "{}", std::mem::size_of::<Option<LightAngle>>());
    assert!(std::mem::size_of::<crate::Bsdf>() <= 336, "{}", std::mem::size_of::<crate::Bsdf>());
}

/// A Maya BSDF whose light-angle translucence sums the 5- and 7-knot ramps (diffuse 0.2):
/// its sampling passes the chi-square test of its density at the standard incidences,
/// and its albedo by sampling (50 000 samples) is 0.2 + A within 1 % per channel.
#[test]
fn a_lobe_of_differing_ramps_samples_its_density_and_keeps_its_albedo() {
    let [five, seven] = many_knots();
    let (a, sa) = LightAngle::from_ramp(&five, Rgb::ZERO, 0.5);
    let (b, sb) = LightAngle::from_ramp(&seven, Rgb::ZERO, 0.3);
    let g = crate::MayaGlossy::new(crate::maya_highlight::Shape::Phong { power: 1.0 }, Rgb::ZERO)
        .with_translucence(a + b, 0.0)
        .with_light_angle(sa.mixed(a, &sb, b));
    for wo in crate::testing::incidences() {
        let bsdf = crate::Bsdf::Maya(g.bsdf(Rgb::splat(0.2), wo));
        crate::testing::chi_square(&bsdf, wo);
        let albedo = crate::testing::albedo(&bsdf, wo, 50_000);
        let want = a + b + 0.2;
        assert!(((albedo / want) - 1.0).abs().max_element() < 0.01, "{wo}: {albedo} vs {want}");
    }
}

/// Six distinct ramp shapes and the diffuse one mixed one by one with
/// `mixed_interned` (albedos 0.1 … 0.7 per part, differing per channel): the mix's
/// (Σ a) ⊙ S(u) is Σ a_i ⊙ S_i(u) within 1e-5 at 50 light cosines, though only
/// LIGHT_ANGLE_PARTS parts fit (composites hold the rest); the same mix again interns
/// nothing new (the same composites, bit for bit equal results); the lossy `mixed` of
/// the same parts differs (it adds past the fourth to the largest).
#[test]
fn an_interned_mix_keeps_every_shape_exactly() {
    let shapes: Vec<(Rgb, LightAngle)> = (0..6)
        .map(|i| {
            let x = 0.1 + 0.07 * i as f32;
            let knots = [
                (0.0, Rgb::new(0.9, 0.2, 0.4), 1),
                (x, Rgb::new(0.1, 0.8 - 0.1 * i as f32, 0.3), if i % 2 == 0 { 1 } else { 3 }),
                (0.7, Rgb::new(0.5, 0.5, 0.9), 2),
            ];
            LightAngle::from_ramp(&knots, Rgb::ZERO, 0.6)
        })
        .chain(std::iter::once((Rgb::splat(0.3), LightAngle::DIFFUSE)))
        .collect();
    let weights: Vec<Rgb> = (0..7).map(|i| Rgb::new(0.1 + 0.1 * i as f32, 0.7 - 0.1 * i as f32, 0.35)).collect();
    let mix = |exact: bool| {
        let (mut total, mut out) = (weights[0], shapes[0].1);
        for (w, (_, s)) in weights.iter().zip(&shapes).skip(1) {
            out = if exact { out.mixed_interned(total, s, *w) } else { out.mixed(total, s, *w) };
            total += *w;
        }
        (total, out)
    };
    let (total, exact) = mix(true);
    let (_, again) = mix(true);
    let (_, lossy) = mix(false);
    let mut lossy_error = 0.0f32;
    for i in 0..50 {
        let u = (i as f32 + 0.5) / 50.0;
        let want: Rgb = weights.iter().zip(&shapes).map(|(w, (_, s))| *w * s.shape_at(u)).sum();
        let got = total * exact.shape_at(u);
        assert!((got - want).abs().max_element() < 1e-5, "u {u}: {got} vs {want}");
        assert_eq!(again.shape_at(u), exact.shape_at(u));
        lossy_error = lossy_error.max((total * lossy.shape_at(u) - want).abs().max_element());
    }
    assert!(lossy_error > 1e-3, "{lossy_error}");
    assert_eq!(again, exact);
}
