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

/// How many light cosines rampShader's light-angle table holds ([`LightAngle`]), evenly
/// spaced over [0, 1]: u = k/8, where the classic shader reads the colour ramp at
/// (1 − u)/2 = ½, 7/16, … 0 (every sixteenth of [0, ½]).
pub const LIGHT_ANGLE_STEPS: usize = 9;

/// rampShader's light-angle translucence (`maya::ramp_shader`): the classic shader adds
/// P(u) ⊙ L for a light of colour L behind the surface at |N·l| = u, P(u) = t · C((1 − u)/2)
/// (C the colour ramp), with no cosine factor. mira's path lobe tabulates P at
/// u = k/8 ([`LIGHT_ANGLE_STEPS`]) and reads it linearly between (exact for a linear ramp
/// whose knots lie on sixteenths of [0, ½]): f = P(u)/(π u) = A/π ⊙ S(u)/u, A = 2∫P du its
/// albedo (per channel, not capped: where the classic shader passes more light than it
/// receives, so does the lobe) and S = P/A the shape this table holds (2∫S du = 1).
/// Diffuse translucence is S(u) = u ([`LightAngle::DIFFUSE`]). It depends on the light's
/// direction only, as the classic formula (not reciprocal: the classic shaders evaluate it
/// towards the lights, as the path engine's camera paths do). It is sampled uniformly over
/// the far hemisphere ([`uniform_opposite`]), whose weight f · u/pdf = 2A ⊙ S(u) stays
/// bounded at the factor's pole at the horizon (u is clamped to 1e-4 there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightAngle {
    /// S per channel at u = k/8.
    shape: [[f32; 3]; LIGHT_ANGLE_STEPS],
}

impl LightAngle {
    /// Diffuse translucence, S(u) = u: the factor is 1 at every angle.
    pub const DIFFUSE: LightAngle = LightAngle {
        shape: {
            let mut shape = [[0.0; 3]; LIGHT_ANGLE_STEPS];
            let mut k = 0;
            while k < LIGHT_ANGLE_STEPS {
                let u = k as f32 / (LIGHT_ANGLE_STEPS - 1) as f32;
                shape[k] = [u, u, u];
                k += 1;
            }
            shape
        },
    };

    /// The table of P(u) (per channel, negative values taken as 0) at u = k/8: its albedo
    /// A = 2∫P du (the trapezoid rule, exact for the piecewise linear P the lobe reads)
    /// and its shape P/A (a channel of albedo 0 takes the diffuse shape).
    pub fn tabulate(p: impl Fn(f32) -> Rgb) -> (Rgb, LightAngle) {
        let last = (LIGHT_ANGLE_STEPS - 1) as f32;
        let values: [Rgb; LIGHT_ANGLE_STEPS] = std::array::from_fn(|k| p(k as f32 / last).max(Rgb::ZERO));
        let inner = values[1..LIGHT_ANGLE_STEPS - 1].iter().fold(Rgb::ZERO, |s, v| s + *v);
        let albedo = (inner + (values[0] + values[LIGHT_ANGLE_STEPS - 1]) * 0.5) * (2.0 / last);
        let shape = std::array::from_fn(|k| {
            let diffuse = k as f32 / last;
            let s = |c: usize| if albedo[c] > 0.0 { values[k][c] / albedo[c] } else { diffuse };
            [s(0), s(1), s(2)]
        });
        (albedo, LightAngle { shape })
    }

    /// The shape of the sum of a lobe of albedo `a` and shape `self` and one of albedo
    /// `b` and shape `other` (per channel by their albedos; the sum's albedo is a + b).
    pub fn mixed(&self, a: Rgb, other: &LightAngle, b: Rgb) -> LightAngle {
        let (a, b) = (a.max(Rgb::ZERO), b.max(Rgb::ZERO));
        let shape = std::array::from_fn(|k| {
            let s = |c: usize| {
                let total = a[c] + b[c];
                if total > 0.0 {
                    (a[c] * self.shape[k][c] + b[c] * other.shape[k][c]) / total
                } else {
                    self.shape[k][c]
                }
            };
            [s(0), s(1), s(2)]
        });
        LightAngle { shape }
    }

    /// S(u) per channel, linear between the table's points (`u` clamped to [0, 1]).
    pub fn shape_at(&self, u: f32) -> Rgb {
        let x = u.clamp(0.0, 1.0) * (LIGHT_ANGLE_STEPS - 1) as f32;
        let k = (x as usize).min(LIGHT_ANGLE_STEPS - 2);
        let t = x - k as f32;
        Rgb::from(self.shape[k]) * (1.0 - t) + Rgb::from(self.shape[k + 1]) * t
    }

    /// The factor S(u)/u that multiplies the albedo's A/π at the light's cosine `u`
    /// (clamped to 1e-4, the pole at the horizon).
    pub fn factor(&self, u: f32) -> Rgb {
        let u = u.clamp(1e-4, 1.0);
        self.shape_at(u) / u
    }
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

    /// The light-angle table (rampShader) of a P(u) with a knot at u = ½ (the colour ramp's
    /// at ¼), P = (0.2, 0.9, 0.5) at 0, (1.1, 0.3, 0.5) at ½, (0.6, 0.6, 0.5) at 1: its albedo
    /// is 2∫P du within 1e-6 (uncapped: red's is 1.5), A ⊙ S(u) · π … the lobe's
    /// f · u · π is P(u) within 1e-6 at u = 0.05 … 1 (the knot followed), 2∫S du is 1 per
    /// channel within 1e-3 (midpoint rule, 100 000 steps), the diffuse table's factor is
    /// 1 within 1e-6 at every angle, and a mix of two tables is the albedo-weighted sum
    /// of their P within 1e-6. `uniform_opposite` lands on the far side, unit length,
    /// with z uniform (mean |z| ½ within 1e-3 over 10 000 stratified samples).
    #[test]
    fn the_light_angle_table_follows_the_ramp_and_keeps_its_albedo() {
        let (p0, p1, p2) = (Rgb::new(0.2, 0.9, 0.5), Rgb::new(1.1, 0.3, 0.5), Rgb::new(0.6, 0.6, 0.5));
        let p = |u: f32| if u < 0.5 { p0 + (p1 - p0) * (u / 0.5) } else { p1 + (p2 - p1) * ((u - 0.5) / 0.5) };
        let (a, table) = LightAngle::tabulate(p);
        let want = (p0 + p1 * 2.0 + p2) * 0.5;
        assert!((a - want).abs().max_element() < 1e-6, "{a} vs {want}");
        assert!(a.x > 1.0);
        for u in [0.05f32, 0.2, 0.4, 0.5, 0.6, 0.93, 1.0] {
            let got = a * table.factor(u) * u;
            assert!((got - p(u)).abs().max_element() < 1e-6, "u {u}: {got} vs {}", p(u));
            assert!((LightAngle::DIFFUSE.factor(u) - Rgb::ONE).abs().max_element() < 1e-6);
        }
        let steps = 100_000;
        let integral =
            (0..steps).map(|i| table.shape_at((i as f32 + 0.5) / steps as f32)).fold(Rgb::ZERO, |s, v| s + v)
                * (2.0 / steps as f32);
        assert!((integral - Rgb::ONE).abs().max_element() < 1e-3, "{integral}");
        let b = Rgb::new(0.3, 0.1, 0.7);
        let mixed = table.mixed(a, &LightAngle::DIFFUSE, b);
        for u in [0.1f32, 0.5, 0.8] {
            let got = (a + b) * mixed.shape_at(u);
            let want = p(u) + b * u;
            assert!((got - want).abs().max_element() < 1e-6, "u {u}: {got} vs {want}");
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

    /// A Maya BSDF with a light-angle translucence (P from 0.5 · (0.9, 0.6, 0.3) straight
    /// behind to 0.5 · (0.2, 0.5, 0.9) at the horizon with a knot (0.8, 0.1, 0.4) · 0.5
    /// at u = ½; diffuse 0.3): its sampling passes the chi-square test of its density at
    /// the standard incidences, and its albedo by sampling (50 000 samples) is 0.3 + A
    /// within 1 % per channel. It is not reciprocal (the classic formula follows the
    /// light's direction only).
    #[test]
    fn the_light_angle_lobe_samples_its_density_and_keeps_its_albedo() {
        let (p0, p1, p2) =
            (Rgb::new(0.2, 0.5, 0.9) * 0.5, Rgb::new(0.8, 0.1, 0.4) * 0.5, Rgb::new(0.9, 0.6, 0.3) * 0.5);
        let (a, table) =
            LightAngle::tabulate(
                |u| {
                    if u < 0.5 {
                        p0 + (p1 - p0) * (u / 0.5)
                    } else {
                        p1 + (p2 - p1) * ((u - 0.5) / 0.5)
                    }
                },
            );
        let g = crate::MayaGlossy::new(crate::maya_highlight::Shape::Phong { power: 1.0 }, Rgb::ZERO)
            .with_translucence(a, 0.0)
            .with_light_angle(table);
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
