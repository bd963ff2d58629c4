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

use crate::Frame;

pub use super::light_angle::{LightAngle, RampShape, LIGHT_ANGLE_PARTS};
pub use super::ramp_curve::Interp;

/// The density of [`uniform_opposite`]'s directions, 1/(2π).
pub const UNIFORM_PDF: f32 = 0.5 * FRAC_1_PI;

/// A direction uniform over the hemisphere opposite `wo` (local frame, +Z the normal),
/// density [`UNIFORM_PDF`], from the unit square `u`.
pub fn uniform_opposite(wo: Vec3A, u: Vec2) -> Vec3A {
    let z = u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = TAU * u.y;
    let side = if wo.z < 0.0 { 1.0 } else { -1.0 };
    Vec3A::new(r * phi.cos(), r * phi.sin(), side * z)
}

/// A translucence [`crate::MayaGlossy::add_translucence`] could not carry as a lobe of its own
/// (every further lobe taken by another focus): its albedo joined the further lobe of
/// the nearest exponent. Both lobes are normalised (albedo kept at normal incidence), so
/// the merged light keeps its total straight through; what changes is its spread: the
/// forward peak (n + 2)/2 of its own exponent n becomes (m + 2)/2, and its value towards
/// any view changes by at most albedo · max((n + 2)/2, (m + 2)/2)/π.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Merged {
    /// The exponent n of the translucence that was merged.
    pub exponent: f32,
    /// The exponent m of the lobe it joined.
    pub into: f32,
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
