//! Tests of a stack's translucence held by the material: its f at a facing ratio is the
//! sum of its layers' lobes by their shares, and its sampling follows its density.

use super::*;
use crate::maya_highlight::{MayaGlossy, Shape};
use crate::{testing, Bsdf};
use std::f32::consts::TAU;

/// Layer i's transparency at facing ratio f: linear in f (so the table's linear reading
/// is exact), the last layer opaque.
fn transparency(i: usize, layers: usize, f: f32) -> Rgb {
    if i + 1 == layers {
        return Rgb::ZERO;
    }
    let k = i as f32;
    Rgb::new(0.7 - 0.5 * f, 0.2 + 0.05 * k + 0.3 * f, 0.5 - 0.04 * k * f).clamp(Rgb::ZERO, Rgb::ONE)
}

/// The classic shares w_i(f) = T_0 ⊙ ⋯ ⊙ T_(i−1) ⊙ (1 − T_i), computed directly.
fn shares(layers: usize, f: f32) -> Vec<Rgb> {
    let mut through = Rgb::ONE;
    (0..layers)
        .map(|i| {
            let t = transparency(i, layers, f);
            let w = through * (Rgb::ONE - t);
            through *= t;
            w
        })
        .collect()
}

/// Six distinct light-angle ramps (knots at 0, 0.1 + 0.05 i and 0.6, interpolations none,
/// linear, smooth, spline in turn): the layers' lobes (albedo, exponent 0, shape).
fn ramp_lobes() -> Vec<StackLobe> {
    (0..6i32)
        .map(|i| {
            let k = i as f32;
            let knots = [
                (0.0, Rgb::new(0.9 - 0.1 * k, 0.2 + 0.1 * k, 0.5), i % 4),
                (0.1 + 0.05 * k, Rgb::new(0.3, 0.8 - 0.1 * k, 0.1 + 0.1 * k), (i + 1) % 4),
                (0.6, Rgb::new(0.1 * k, 0.4, 0.9 - 0.1 * k), 1),
            ];
            let (albedo, shape) = LightAngle::from_ramp(&knots, Rgb::ZERO, 0.6);
            StackLobe { albedo, exponent: 0.0, light_angle: Some(shape) }
        })
        .collect()
}

/// Six distinct foci (exponents 0 … 18), diffuse translucence first.
fn focus_lobes() -> Vec<StackLobe> {
    [0.0f32, 1.0, 2.0, 5.0, 8.0, 18.0]
        .iter()
        .enumerate()
        .map(|(i, &n)| {
            let k = i as f32;
            StackLobe { albedo: Rgb::new(0.2 + 0.1 * k, 0.7 - 0.1 * k, 0.4), exponent: n, light_angle: None }
        })
        .collect()
}

/// A stack of one layer per lobe with [`transparency`] tabulated at k/32.
fn stack_of(lobes: &[StackLobe]) -> &'static TranslucentStack {
    let n = lobes.len();
    TranslucentStack::interned(
        lobes
            .iter()
            .enumerate()
            .map(|(i, l)| StackLayer {
                transparency: (0..33).map(|k| transparency(i, n, k as f32 / 32.0)).collect(),
                lobes: vec![*l],
            })
            .collect(),
    )
}

/// The lobe alone: a Maya model with only this translucence.
fn alone(l: &StackLobe, w: Rgb) -> MayaGlossy {
    let g = MayaGlossy::new(Shape::Phong { power: 1.0 }, Rgb::ZERO).with_translucence(l.albedo * w, l.exponent);
    match l.light_angle {
        Some(shape) => g.with_light_angle(shape),
        None => g,
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

/// A stack of six layers of distinct light-angle ramps, and one of six distinct foci,
/// each layer's transparency following the facing ratio: at f = 0.3, 0.55, 0.8 and 1 the
/// BSDF's translucence is Σ_i w_i(f) ⊙ (layer i's lobe alone), w_i the classic shares at
/// f, within 1e-5 over 48 × 48 direction pairs; the stack's albedo is Σ w_i ⊙ a_i within
/// 1e-6. The same stack interned twice is one; `StackAt` is 16 bytes with its `Option`.
#[test]
fn a_stack_is_the_sum_of_its_layers_by_their_shares_at_the_facing_ratio() {
    assert_eq!(std::mem::size_of::<Option<StackAt>>(), 16);
    let plain = MayaGlossy::new(Shape::Phong { power: 1.0 }, Rgb::ZERO);
    for lobes in [ramp_lobes(), focus_lobes()] {
        let stack = stack_of(&lobes);
        assert!(std::ptr::eq(stack, stack_of(&lobes)), "interned once");
        assert_eq!(stack.len(), 6);
        for f in [0.3f32, 0.55, 0.8, 1.0] {
            let w = shares(lobes.len(), f);
            let mut g = plain.with_translucence_stack(stack);
            g.translucence_stack = Some(StackAt { stack, facing: f, scale: 1.0 });
            let at = g.translucence_stack.expect("a stack");
            let want = lobes.iter().zip(&w).fold(Rgb::ZERO, |s, (l, w)| s + l.albedo * *w);
            assert!((at.albedo() - want).abs().max_element() < 1e-6, "f {f}: {} vs {want}", at.albedo());
            for wo in sphere(48) {
                let b = g.bsdf(Rgb::ZERO, wo);
                let singles: Vec<_> = lobes.iter().zip(&w).map(|(l, w)| alone(l, *w).bsdf(Rgb::ZERO, wo)).collect();
                for wi in sphere(48) {
                    let want = singles.iter().fold(Rgb::ZERO, |s, b| s + b.eval_translucence(wo, wi));
                    let got = b.eval(wo, wi);
                    assert!((got - want).abs().max_element() < 1e-5, "f {f}, {wo} {wi}: {got} vs {want}");
                }
            }
        }
    }
}

/// The stacks of [`a_stack_is_the_sum_of_its_layers_by_their_shares_at_the_facing_ratio`]
/// at f = 0.55 (and the foci's at 0.3 with a scale of 1.5): sampling passes the chi-square
/// test at the standard incidences and the albedo by sampling (50 000 samples) is the sum
/// of the single lobes' sampled albedos within 1 %. Furnace: with white lobes of albedo 1
/// (the ramps' shapes kept) the stack passes 1 at normal incidence within 1 % and at most
/// 1.01 at the other incidences (the shares sum to 1).
#[test]
fn a_stacks_sampling_follows_its_density_and_keeps_its_albedo() {
    let plain = MayaGlossy::new(Shape::Phong { power: 1.0 }, Rgb::ZERO);
    let white = |lobes: Vec<StackLobe>| -> Vec<StackLobe> {
        lobes.into_iter().map(|l| StackLobe { albedo: Rgb::ONE, ..l }).collect()
    };
    let cases = [
        (ramp_lobes(), 0.55, 1.0),
        (focus_lobes(), 0.55, 1.0),
        (focus_lobes(), 0.3, 1.5),
        (white(ramp_lobes()), 0.55, 1.0),
        (white(focus_lobes()), 0.55, 1.0),
    ];
    for (lobes, facing, scale) in cases {
        let stack = stack_of(&lobes);
        let mut g = plain.with_translucence_stack(stack);
        g.translucence_stack = Some(StackAt { stack, facing, scale });
        let w = shares(lobes.len(), facing);
        let furnace = lobes.iter().all(|l| l.albedo == Rgb::ONE);
        for wo in testing::incidences() {
            let bsdf = Bsdf::Maya(g.bsdf(Rgb::ZERO, wo));
            testing::chi_square(&bsdf, wo);
            let albedo = testing::albedo(&bsdf, wo, 50_000);
            let want = lobes.iter().zip(&w).fold(Rgb::ZERO, |s, (l, w)| {
                s + testing::albedo(&Bsdf::Maya(alone(l, *w * scale).bsdf(Rgb::ZERO, wo)), wo, 50_000)
            });
            assert!(((albedo / want) - 1.0).abs().max_element() < 0.01, "{wo}: {albedo} vs {want}");
            if furnace {
                assert!(albedo.max_element() < 1.01, "furnace at {wo}: {albedo}");
                if wo == Vec3A::Z {
                    assert!((albedo - Rgb::ONE).abs().max_element() < 0.01, "furnace head-on: {albedo}");
                }
            }
        }
    }
}
