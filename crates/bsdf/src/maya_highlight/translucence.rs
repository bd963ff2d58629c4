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

/// How many knots of rampShader's colour ramp [`LightAngle`] holds: the ramp's knots in
/// [0, ½] and the first one after ½ (what the classic shader reads for a light behind).
pub const LIGHT_ANGLE_KNOTS: usize = 4;

/// How a ramp's segment runs from its knot to the next, as Maya's `<ramp>_Interp`
/// (and the classic shaders' `maya::utility::curve_at`) reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Interp {
    /// 0, none: the knot's value up to the next knot.
    Step,
    /// 1, linear.
    Linear,
    /// 2, smooth, and 3, spline (read as smooth, as the classic shaders do): the
    /// smoothstep 3τ² − 2τ³ of the segment's parameter τ.
    Smooth,
}

impl Interp {
    /// Maya's interpolation code: 0 none, 1 linear, anything else smooth.
    pub fn from_maya(code: i32) -> Interp {
        match code {
            0 => Interp::Step,
            1 => Interp::Linear,
            _ => Interp::Smooth,
        }
    }

    /// The segment's blend at its parameter `tau` ∈ [0, 1].
    fn blend(self, tau: f32) -> f32 {
        match self {
            Interp::Step => 0.0,
            Interp::Linear => tau,
            Interp::Smooth => tau * tau * (3.0 - 2.0 * tau),
        }
    }

    /// ∫_0^τ of [`Interp::blend`].
    fn integral(self, tau: f64) -> f64 {
        match self {
            Interp::Step => 0.0,
            Interp::Linear => 0.5 * tau * tau,
            Interp::Smooth => tau * tau * tau - 0.5 * tau * tau * tau * tau,
        }
    }
}

/// rampShader's light-angle translucence (`maya::ramp_shader`): the classic shader adds
/// P(u) ⊙ L for a light of colour L behind the surface at |N·l| = u, P(u) = t · C((1 − u)/2)
/// (C the colour ramp), with no cosine factor. mira's path lobe evaluates the ramp itself
/// — its knots in [0, ½] and the next one, with their interpolation, as the classic shader
/// reads it — in the shape S = P/A, A = 2∫P du its albedo (per channel, in closed form, not
/// capped: where the classic shader passes more light than it receives, so does the lobe;
/// 2∫S du = 1), plus a part b · u that a layeredShader's lambert layers add (diffuse translucence is S(u) = u, [`LightAngle::DIFFUSE`]); f = A/π ⊙ S(u)/u. It
/// depends on the light's direction only, as the classic formula (not reciprocal: the
/// classic shaders evaluate it towards the lights, as the path engine's camera paths
/// do). It is sampled uniformly over the far hemisphere ([`uniform_opposite`]), whose
/// weight f · u/pdf = 2A ⊙ S(u) stays bounded at the factor's pole at the horizon (u is
/// clamped to 1e-4 there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightAngle {
    /// The knots' positions x on the colour ramp (x = (1 − u)/2), sorted.
    at: [f32; LIGHT_ANGLE_KNOTS],
    /// The shape's ramp part at the knots, per channel (t · C / A).
    value: [[f32; 3]; LIGHT_ANGLE_KNOTS],
    /// Each knot's segment's interpolation.
    interp: [Interp; LIGHT_ANGLE_KNOTS],
    /// How many knots there are (0: no ramp part).
    count: u8,
    /// The linear part's slope b per channel (the shape adds b · u).
    linear: [f32; 3],
}

/// The value of the sorted knots `(x, value, interp)` at `x`, as
/// `maya::utility::curve_at` reads a ramp: the first knot's value before it, the last
/// one's after it, each segment by its first knot's interpolation.
fn ramp_at(knots: &[(f32, [f32; 3], Interp)], x: f32) -> [f32; 3] {
    let Some(first) = knots.first() else { return [0.0; 3] };
    if x <= first.0 {
        return first.1;
    }
    for w in knots.windows(2) {
        let ((p0, v0, interp), (p1, v1, _)) = (w[0], w[1]);
        if x < p1 {
            let tau = if p1 > p0 { (x - p0) / (p1 - p0) } else { 1.0 };
            let s = interp.blend(tau);
            return std::array::from_fn(|c| v0[c] + (v1[c] - v0[c]) * s);
        }
    }
    knots[knots.len() - 1].1
}

/// ∫ over x ∈ [0, ½] of the knots' ramp ([`ramp_at`]), per channel, in closed form.
fn ramp_integral(knots: &[(f32, [f32; 3], Interp)]) -> [f64; 3] {
    let mut sum = [0.0f64; 3];
    let Some(first) = knots.first() else { return sum };
    let add = |sum: &mut [f64; 3], len: f64, v: [f32; 3]| {
        for c in 0..3 {
            sum[c] += len * f64::from(v[c]);
        }
    };
    // Before the first knot and after the last: their values.
    add(&mut sum, f64::from(first.0.clamp(0.0, 0.5)), first.1);
    let last = knots[knots.len() - 1];
    add(&mut sum, f64::from(0.5 - last.0.clamp(0.0, 0.5)), last.1);
    for w in knots.windows(2) {
        let ((p0, v0, interp), (p1, v1, _)) = (w[0], w[1]);
        let (a, b) = (f64::from(p0.clamp(0.0, 0.5)), f64::from(p1.clamp(0.0, 0.5)));
        if b <= a {
            continue;
        }
        let (p0, len) = (f64::from(p0), f64::from(p1 - p0));
        let rise = (interp.integral((b - p0) / len) - interp.integral((a - p0) / len)) * len;
        for c in 0..3 {
            sum[c] += (b - a) * f64::from(v0[c]) + f64::from(v1[c] - v0[c]) * rise;
        }
    }
    sum
}

impl LightAngle {
    /// Diffuse translucence, S(u) = u: the factor is 1 at every angle.
    pub const DIFFUSE: LightAngle = LightAngle {
        at: [0.0; LIGHT_ANGLE_KNOTS],
        value: [[0.0; 3]; LIGHT_ANGLE_KNOTS],
        interp: [Interp::Linear; LIGHT_ANGLE_KNOTS],
        count: 0,
        linear: [1.0; 3],
    };

    /// The shape of P(u) = `t` · C((1 − u)/2) for the colour ramp C of sorted `knots`
    /// (position, linear RGB, Maya interpolation code; none: C = `empty`) and its albedo
    /// A = 2∫P du (a channel of albedo 0 or less takes the diffuse shape). `false` when
    /// the ramp has more than [`LIGHT_ANGLE_KNOTS`] − 1 knots in [0, ½]: the shape then
    /// reads the ramp at that many evenly spaced points of [0, ½] and the first knot
    /// after, linearly between (the caller warns).
    pub fn from_ramp(knots: &[(f32, Rgb, i32)], empty: Rgb, t: f32) -> (Rgb, LightAngle, bool) {
        let full: Vec<(f32, [f32; 3], Interp)> = if knots.is_empty() {
            vec![(0.0, empty.into(), Interp::Linear)]
        } else {
            knots.iter().map(|&(x, c, i)| (x, c.into(), Interp::from_maya(i))).collect()
        };
        // The knots the classic shader reads for a light behind: those in [0, ½] and
        // the first after ½.
        let inside = full.iter().filter(|k| k.0 <= 0.5).count();
        let kept: Vec<(f32, [f32; 3], Interp)> = if inside < LIGHT_ANGLE_KNOTS {
            full[..(inside + 1).min(full.len())].to_vec()
        } else {
            let next = full.iter().find(|k| k.0 > 0.5);
            let points = LIGHT_ANGLE_KNOTS - usize::from(next.is_some());
            let step = 0.5 / (points - 1) as f32;
            (0..points)
                .map(|k| (k as f32 * step, ramp_at(&full, k as f32 * step), Interp::Linear))
                .chain(next.map(|&(x, v, _)| (x, v, Interp::Linear)))
                .collect()
        };
        let exact = inside < LIGHT_ANGLE_KNOTS;
        let integral = ramp_integral(&kept);
        let albedo: [f32; 3] = std::array::from_fn(|c| (4.0 * f64::from(t) * integral[c]) as f32);
        let linear = albedo.map(|a| if a > 0.0 { 0.0 } else { 1.0 });
        let mut shape = LightAngle { count: kept.len() as u8, linear, ..LightAngle::DIFFUSE };
        for (k, (x, v, interp)) in kept.iter().enumerate() {
            shape.at[k] = *x;
            shape.interp[k] = *interp;
            shape.value[k] = std::array::from_fn(|c| if albedo[c] > 0.0 { v[c] * t / albedo[c] } else { 0.0 });
        }
        (Rgb::from(albedo).max(Rgb::ZERO), shape, exact)
    }

    /// The knots of the ramp part.
    fn knots(&self) -> Vec<(f32, [f32; 3], Interp)> {
        (0..usize::from(self.count)).map(|k| (self.at[k], self.value[k], self.interp[k])).collect()
    }

    /// Whether [`LightAngle::mixed`] of these two shapes is exact: at most one of them has
    /// a ramp part, or both have theirs at the same knots with the same interpolation.
    pub fn mixes_exactly(&self, other: &LightAngle) -> bool {
        self.count == 0
            || other.count == 0
            || (self.count == other.count && self.at == other.at && self.interp == other.interp)
    }

    /// The shape of the sum of a lobe of albedo `a` and shape `self` and one of albedo
    /// `b` and shape `other` (per channel by their albedos; the sum's albedo is a + b):
    /// exact where [`LightAngle::mixes_exactly`]; otherwise the sum read at the union of
    /// their knots in [0, ½] (or [`LIGHT_ANGLE_KNOTS`] evenly spaced points when they are
    /// more), linearly between.
    pub fn mixed(&self, a: Rgb, other: &LightAngle, b: Rgb) -> LightAngle {
        let (a, b) = (a.max(Rgb::ZERO), b.max(Rgb::ZERO));
        let weights = |c: usize| {
            let total = a[c] + b[c];
            if total > 0.0 {
                (a[c] / total, b[c] / total)
            } else {
                (1.0, 0.0)
            }
        };
        let mut out = *self;
        for c in 0..3 {
            let (wa, wb) = weights(c);
            out.linear[c] = wa * self.linear[c] + wb * other.linear[c];
        }
        if self.mixes_exactly(other) {
            let base = if self.count > 0 { self } else { other };
            (out.count, out.at, out.interp) = (base.count, base.at, base.interp);
            for k in 0..usize::from(base.count) {
                for c in 0..3 {
                    let (wa, wb) = weights(c);
                    let mine = if self.count > 0 { self.value[k][c] } else { 0.0 };
                    let theirs = if other.count > 0 { other.value[k][c] } else { 0.0 };
                    out.value[k][c] = wa * mine + wb * theirs;
                }
            }
            return out;
        }
        let (mine, theirs) = (self.knots(), other.knots());
        let mut at: Vec<f32> = mine.iter().chain(&theirs).map(|k| k.0.clamp(0.0, 0.5)).collect();
        at.sort_by(f32::total_cmp);
        at.dedup();
        if at.len() > LIGHT_ANGLE_KNOTS {
            at = (0..LIGHT_ANGLE_KNOTS).map(|k| 0.5 * k as f32 / (LIGHT_ANGLE_KNOTS - 1) as f32).collect();
        }
        out.count = at.len() as u8;
        for (k, x) in at.iter().enumerate() {
            let (p, q) = (ramp_at(&mine, *x), ramp_at(&theirs, *x));
            out.at[k] = *x;
            out.interp[k] = Interp::Linear;
            out.value[k] = std::array::from_fn(|c| {
                let (wa, wb) = weights(c);
                wa * p[c] + wb * q[c]
            });
        }
        out
    }

    /// S(u) per channel (`u` clamped to [0, 1]).
    pub fn shape_at(&self, u: f32) -> Rgb {
        let u = u.clamp(0.0, 1.0);
        Rgb::from(self.ramp_value(0.5 * (1.0 - u))) + Rgb::from(self.linear) * u
    }

    /// The ramp part at the ramp's position `x`, as [`ramp_at`] of the knots (read in
    /// place: the lobe evaluates it at every light).
    fn ramp_value(&self, x: f32) -> [f32; 3] {
        let n = usize::from(self.count).min(LIGHT_ANGLE_KNOTS);
        if n == 0 {
            return [0.0; 3];
        }
        if x <= self.at[0] {
            return self.value[0];
        }
        for k in 1..n {
            let (p0, p1) = (self.at[k - 1], self.at[k]);
            if x < p1 {
                let tau = if p1 > p0 { (x - p0) / (p1 - p0) } else { 1.0 };
                let s = self.interp[k - 1].blend(tau);
                let (v0, v1) = (self.value[k - 1], self.value[k]);
                return [v0[0] + (v1[0] - v0[0]) * s, v0[1] + (v1[1] - v0[1]) * s, v0[2] + (v1[2] - v0[2]) * s];
            }
        }
        self.value[n - 1]
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
        let (a, shape, exact) = LightAngle::from_ramp(&[(0.0, p0, 1), (0.25, p1, 1), (0.5, p2, 1)], Rgb::ZERO, 1.0);
        assert!(exact);
        let want = (p0 + p1 * 2.0 + p2) * 0.5;
        assert!((a - want).abs().max_element() < 1e-6, "{a} vs {want}");
        assert!(a.x > 1.0);
        for u in [0.05f32, 0.2, 0.4, 0.5, 0.6, 0.93, 1.0] {
            let got = a * shape.factor(u) * u;
            assert!((got - p(u)).abs().max_element() < 1e-6, "u {u}: {got} vs {}", p(u));
            assert!((LightAngle::DIFFUSE.factor(u) - Rgb::ONE).abs().max_element() < 1e-6);
        }
        let steps = 100_000;
        let integral =
            (0..steps).map(|i| shape.shape_at((i as f32 + 0.5) / steps as f32)).fold(Rgb::ZERO, |s, v| s + v)
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
                let w = uniform_opposite(wo, Vec2::new((i as f32 + 0.5) / 100.0, (j as f32 + 0.5) / 100.0));
                assert!(w.z < 0.0 && (w.length() - 1.0).abs() < 1e-4);
                sum += -w.z;
            }
        }
        assert!((sum / 1e4 - 0.5).abs() < 1e-3);
        assert!((UNIFORM_PDF * TAU - 1.0).abs() < 1e-6);
    }

    /// The classic ramp of `knots` (position, colour, Maya interpolation) at `x`, as
    /// `maya::utility::curve_at` reads it (written out here: the bsdf crate does not
    /// depend on the maya crate).
    fn classic_ramp(knots: &[(f32, Rgb, i32)], x: f32) -> Rgb {
        if x <= knots[0].0 {
            return knots[0].1;
        }
        for w in knots.windows(2) {
            let ((p0, v0, interp), (p1, v1, _)) = (w[0], w[1]);
            if x < p1 {
                let t = (x - p0) / (p1 - p0);
                let t = match interp {
                    0 => 0.0,
                    1 => t,
                    _ => t * t * (3.0 - 2.0 * t),
                };
                return v0 + (v1 - v0) * t;
            }
        }
        knots[knots.len() - 1].1
    }

    /// Ramps with knots off the former table's sixteenths (0.1, 0.37 and 0.8) in each
    /// interpolation (none, linear, smooth, spline), t = 0.7: A ⊙ S(u) is t · C((1 − u)/2)
    /// within 1e-5 at 100 light cosines, the albedo is 2∫P du by a midpoint rule (200 000
    /// steps, summed in f64) within 1e-4, and a ramp of four knots in [0, ½] is flagged
    /// inexact.
    #[test]
    fn the_light_angle_shape_reads_the_ramp_in_every_interpolation() {
        for interp in 0..4 {
            let knots = [
                (0.1, Rgb::new(0.9, 0.1, 0.3), interp),
                (0.37, Rgb::new(0.2, 0.8, 0.6), interp),
                (0.8, Rgb::new(0.5, 0.3, 1.2), interp),
            ];
            let t = 0.7;
            let (a, shape, exact) = LightAngle::from_ramp(&knots, Rgb::ZERO, t);
            assert!(exact);
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
        let many: Vec<(f32, Rgb, i32)> = (0..4).map(|k| (k as f32 * 0.1, Rgb::splat(k as f32), 1)).collect();
        assert!(!LightAngle::from_ramp(&many, Rgb::ZERO, 1.0).2);
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
        let (a, shape, _) = LightAngle::from_ramp(&knots, Rgb::ZERO, 1.0);
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
