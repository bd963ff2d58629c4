//! Maya's `translucence` with `translucenceFocus`: the light a lambert-family material
//! passes from a light behind it, concentrated about the light's straight-through
//! direction.
//!
//! Maya's reference says only that the focus sets how much of the translucent light is
//! scattered forward, in the light's direction (0: scattered alike in all directions, as
//! diffuse translucence), and publishes no formula. mira's reading, shared by the
//! classic shaders (`maya::material`) and the path engine's BSDF: the transmitted light
//! of a light of colour L from direction l (towards the light, behind the surface) seen
//! from v adds
//!
//! ```text
//! c · t · L · |N·l| · K(n, −v·l),   K(n, x) = (n + 2)/2 · max(x, 0)^n,   n = 2φ/(1 − φ)
//! ```
//!
//! φ the focus clamped to [0, 0.99]. For φ = 0, K = 1: diffuse translucence, the classic
//! shader's c · t · L · |N·l| exactly. K is a normalised cosine power about the light's
//! straight-through direction −l: as a BSDF, f = c · t · K/π is symmetric in v and l
//! and its transmitted albedo is c · t at normal incidence and less at others (the lobe
//! is cut by the horizon), never more — energy is conserved for every focus.

use std::f32::consts::{FRAC_1_PI, TAU};

use glam::{Vec2, Vec3A};

use crate::{Frame, Rgb};

/// The density of [`uniform_opposite`]'s directions, 1/(2π).
pub const UNIFORM_PDF: f32 = 0.5 * FRAC_1_PI;

/// rampShader's light-angle translucence (`maya::ramp_shader`): the classic shader adds
/// P(u) ⊙ L for a light of colour L behind the surface at |N·l| = u, P(u) = t · C((1 − u)/2)
/// (C the colour ramp), with no cosine factor. mira's path lobe reads P as the chord
/// A ⊙ ((1 − g) · u + g · (1 − u)) (A = P(1) + P(0) its albedo, g = P(0)/A), exact where
/// the ramp is linear over [0, ½]: f = A/π ⊙ this factor, (1 − g) + g · (1 − u)/u. Its
/// albedo is A whatever g; it depends on the light's direction only, as the classic
/// formula (not reciprocal: the classic shaders evaluate it towards the lights, as the
/// path engine's camera paths do). `u` is clamped to 1e-4 (the factor's pole at the
/// horizon, which [`uniform_opposite`]'s samples keep bounded: f · u/pdf ≤ 2A).
pub fn light_angle_factor(g: Rgb, u: f32) -> Rgb {
    let u = u.clamp(1e-4, 1.0);
    (Rgb::ONE - g) + g * ((1.0 - u) / u)
}

/// A direction uniform over the hemisphere opposite `wo` (local frame, +Z the normal),
/// density [`UNIFORM_PDF`], from the unit square `u`.
pub fn uniform_opposite(wo: Vec3A, u: Vec2) -> Vec3A {
    let z = u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = TAU * u.y;
    let side = if wo.z < 0.0 { 1.0 } else { -1.0 };
    Vec3A::new(r * phi.cos(), r * phi.sin(), side * z)
}

/// The largest focus read: beyond it the lobe's exponent grows without bound.
const MAX_FOCUS: f32 = 0.99;

/// The cosine power n of the forward lobe for `translucenceFocus` φ: 2φ/(1 − φ) (φ
/// clamped to [0, 0.99]); 0 for φ ≤ 0, diffuse translucence.
pub fn focus_exponent(focus: f32) -> f32 {
    let f = focus.clamp(0.0, MAX_FOCUS);
    2.0 * f / (1.0 - f)
}

/// K(n, x) = (n + 2)/2 · max(x, 0)^n, x the cosine between the view direction and the
/// light's straight-through direction (see the module doc); exactly 1 for n = 0.
pub fn forward_lobe(n: f32, x: f32) -> f32 {
    if n <= 0.0 {
        return 1.0;
    }
    0.5 * (n + 2.0) * x.max(0.0).powf(n)
}

/// A direction about `axis` (unit) with density (n + 1)/(2π) · max(cos α, 0)^n over the
/// sphere (α from the axis), from the unit square `u`.
pub fn sample_about(axis: Vec3A, n: f32, u: Vec2) -> Vec3A {
    let cos_a = u.x.powf(1.0 / (n + 1.0));
    let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
    let phi = TAU * u.y;
    Frame::from_normal(axis).to_world(Vec3A::new(sin_a * phi.cos(), sin_a * phi.sin(), cos_a))
}

/// The density of [`sample_about`] at a direction of cosine `x` to the axis.
pub fn pdf_about(n: f32, x: f32) -> f32 {
    if x <= 0.0 {
        return 0.0;
    }
    (n + 1.0) * 0.5 * FRAC_1_PI * x.powf(n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::PI;

    /// ∫ K(n, −v·l)/π |cos θ_l| dω_l over the far hemisphere by a midpoint rule in
    /// (cos θ, φ), 800 × 800: the lobe's transmitted albedo seen from v at cosine `mu`.
    fn albedo(n: f32, mu: f32) -> f32 {
        let v = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        let steps = 800;
        let mut sum = 0.0f64;
        for i in 0..steps {
            let c = (i as f32 + 0.5) / steps as f32;
            let s = (1.0 - c * c).sqrt();
            for j in 0..steps {
                let phi = (j as f32 + 0.5) / steps as f32 * TAU;
                let l = Vec3A::new(s * phi.cos(), s * phi.sin(), -c);
                sum += f64::from(forward_lobe(n, -v.dot(l)) * c);
            }
        }
        (sum * f64::from(TAU) / f64::from(steps * steps) / f64::from(PI)) as f32
    }

    /// Focus 0 is diffuse translucence (K = 1 everywhere); the transmitted albedo is 1 at
    /// normal incidence for every focus (within 2e-3 of the quadrature) and at most 1
    /// (+2e-3) at other views; the focus only ever sharpens the lobe (K at the axis grows).
    #[test]
    fn the_lobe_is_normalised_and_focus_zero_is_diffuse() {
        assert_eq!(focus_exponent(0.0), 0.0);
        for x in [-1.0, -0.2, 0.0, 0.3, 1.0] {
            assert_eq!(forward_lobe(0.0, x), 1.0);
        }
        let mut peak = 0.0;
        for focus in [0.0, 0.25, 0.5, 0.8] {
            let n = focus_exponent(focus);
            let a = albedo(n, 1.0);
            assert!((a - 1.0).abs() < 2e-3, "focus {focus}: albedo {a} head-on");
            for mu in [0.8, 0.5, 0.2] {
                let a = albedo(n, mu);
                assert!(a < 1.0 + 2e-3, "focus {focus}, μ {mu}: albedo {a}");
            }
            assert!(forward_lobe(n, 1.0) >= peak);
            peak = forward_lobe(n, 1.0);
        }
    }

    /// The light-angle factor (rampShader) leaves the albedo at 1 for every share g: the
    /// midpoint rule of 2 ∫ factor · u du over 200 000 steps is 1 within 1e-3; at u the
    /// lobe's f · u · π is the chord (1 − g) · u + g · (1 − u) within 1e-6; and
    /// `uniform_opposite` lands on the far side, unit length, with z uniform (mean |z| ½
    /// within 1e-3 over 10 000 stratified samples).
    #[test]
    fn the_light_angle_lobe_keeps_its_albedo_and_follows_the_chord() {
        for g in [0.0f32, 0.3, 0.5, 1.0] {
            let steps = 200_000;
            let sum: f64 = (0..steps)
                .map(|i| {
                    let u = (i as f32 + 0.5) / steps as f32;
                    f64::from(light_angle_factor(Rgb::splat(g), u).x * u)
                })
                .sum();
            let albedo = 2.0 * sum / f64::from(steps);
            assert!((albedo - 1.0).abs() < 1e-3, "g {g}: {albedo}");
            for u in [0.1f32, 0.5, 0.9, 1.0] {
                let chord = (1.0 - g) * u + g * (1.0 - u);
                assert!((light_angle_factor(Rgb::splat(g), u).x * u - chord).abs() < 1e-6);
            }
        }
        let wo = Vec3A::new(0.3, 0.1, 0.9).normalize();
        let mut sum = 0.0;
        for i in 0..100 {
            for j in 0..100 {
                let w = uniform_opposite(wo, Vec2::new((i as f32 + 0.5) / 100.0, (j as f32 + 0.5) / 100.0));
                assert!(w.z < 0.0 && (w.length() - 1.0).abs() < 1e-4);
                sum += -w.z;
            }
        }
        assert!((sum / 1e4 - 0.5).abs() < 1e-3);
        assert!((UNIFORM_PDF * TAU - 1.0).abs() < 1e-6);
    }

    /// A Maya BSDF with the light-angle translucence (albedo A = (0.5, 0.4, 0.3), shares
    /// g = (0.3, 0.5, 0.7), diffuse 0.3): its sampling passes the chi-square test of its
    /// density at the standard incidences, and its albedo by sampling (50 000 samples) is
    /// 0.3 + A within 1 % per channel (≤ 1: energy). It is not reciprocal (the classic
    /// formula follows the light's direction only).
    #[test]
    fn the_light_angle_lobe_samples_its_density_and_keeps_its_albedo() {
        let a = Rgb::new(0.5, 0.4, 0.3);
        let g = crate::MayaGlossy::new(crate::maya_highlight::Shape::Phong { power: 1.0 }, Rgb::ZERO)
            .with_translucence(a, 0.0)
            .with_translucence_grazing(Rgb::new(0.3, 0.5, 0.7));
        for wo in crate::testing::incidences() {
            let bsdf = crate::Bsdf::Maya(g.bsdf(Rgb::splat(0.3), wo));
            crate::testing::chi_square(&bsdf, wo);
            let albedo = crate::testing::albedo(&bsdf, wo, 50_000);
            let want = a + 0.3;
            assert!(((albedo / want) - 1.0).abs().max_element() < 0.01, "{wo}: {albedo} vs {want}");
        }
    }

    /// The samples about an axis have the density `pdf_about` says: the mean of
    /// cos α over 20 000 stratified samples is (n + 1)/(n + 2) within 1e-3.
    #[test]
    fn sampling_about_the_axis_follows_its_density() {
        let axis = Vec3A::new(0.3, -0.4, 0.5).normalize();
        for n in [0.0, 2.0, 18.0] {
            let k = 200;
            let mut sum = 0.0;
            for i in 0..k {
                for j in 0..100 {
                    let u = Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / 100.0);
                    let w = sample_about(axis, n, u);
                    assert!((w.length() - 1.0).abs() < 1e-4);
                    sum += w.dot(axis);
                }
            }
            let mean = sum / (k * 100) as f32;
            assert!((mean - (n + 1.0) / (n + 2.0)).abs() < 1e-3, "n {n}: {mean}");
        }
        assert!((pdf_about(0.0, 0.5) - 0.5 * FRAC_1_PI).abs() < 1e-7);
    }
}
