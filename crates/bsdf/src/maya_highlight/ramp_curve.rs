//! Maya's ramp attributes (`<ramp>_Position`, `<ramp>_Color` or `<ramp>_FloatValue`,
//! `<ramp>_Interp`): the value of sorted knots at a position, and its integral in closed
//! form. The classic shaders (`maya::utility::curve_at`) and the path engine's
//! light-angle lobe ([`super::translucence::LightAngle`]) both read ramps here.
//!
//! Maya's documentation (the "Set attributes using ramps" page and
//! `MRampAttribute`'s kNone 0, kLinear 1, kSmooth 2, kSpline 3) names the interpolations
//! and says each controls "how the ramp value changes between the selected position
//! marker and the next one": a segment runs by its first knot's interpolation. It
//! describes smooth as "along a bell curve, so that each value dominates the
//! surrounding region, then changes quickly to the next value" and spline as "along a
//! spline curve, taking neighboring values into account"; it gives no formula. mira's
//! reading, with τ ∈ [0, 1] the parameter across the segment from knot i to i + 1:
//!
//! ```text
//! none (0):    v_i
//! linear (1):  v_i + (v_{i+1} − v_i) · τ
//! smooth (2):  v_i + (v_{i+1} − v_i) · (3τ² − 2τ³)            (flat at both knots)
//! spline (3):  cubic Hermite: h00(τ) v_i + h10(τ) Δ m_i + h01(τ) v_{i+1} + h11(τ) Δ m_{i+1}
//!              Δ = p_{i+1} − p_i,  m_k = (v_{k+1} − v_{k−1}) / (p_{k+1} − p_{k−1})
//! ```
//!
//! The spline is Catmull-Rom's for knots at any spacing (the slope at a knot is the
//! chord between its neighbours, in value per unit of position): it passes through
//! every knot and is C1 where two spline segments meet. End condition: a phantom knot
//! one end segment's width beyond the first (and the last) knot, holding that knot's
//! value, so the end slope is half the end segment's chord. Maya documents no formula;
//! this is the reading of Arnold for Maya's remap shaders (MtoA's `MayaUtils.cpp`, whose
//! spline was rewritten in 2012 to match Maya, its ticket #713), and Cortex's
//! `FloatSplineParameterHandler` notes Maya's implicit doubling of the end points. The
//! curve therefore meets the constant beyond the ends with a kink. Other codes read as
//! smooth. Outside the knots the ramp is the first knot's value before it and the last
//! one's after it.

use crate::Rgb;

/// A ramp knot: position, value (per channel), Maya interpolation code of the segment
/// that starts at it.
pub type Knot = (f32, Rgb, i32);

/// How a ramp's segment runs from its knot to the next (`<ramp>_Interp`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Interp {
    /// 0, none: the knot's value up to the next knot.
    Step,
    /// 1, linear.
    Linear,
    /// 2, smooth: the smoothstep 3τ² − 2τ³ of the segment's parameter τ (also any code
    /// Maya does not define).
    Smooth,
    /// 3, spline: Catmull-Rom's cubic through the knots (see the module doc).
    Spline,
}

impl Interp {
    /// Maya's interpolation code: 0 none, 1 linear, 3 spline, anything else smooth.
    pub fn from_maya(code: i32) -> Interp {
        match code {
            0 => Interp::Step,
            1 => Interp::Linear,
            3 => Interp::Spline,
            _ => Interp::Smooth,
        }
    }

    /// The blend of a segment's two values at its parameter `tau` ∈ [0, 1] (not for
    /// [`Interp::Spline`], which reads its neighbours too).
    fn blend(self, tau: f32) -> f32 {
        match self {
            Interp::Step => 0.0,
            Interp::Linear => tau,
            Interp::Smooth | Interp::Spline => tau * tau * (3.0 - 2.0 * tau),
        }
    }

    /// ∫_0^τ of [`Interp::blend`].
    fn blend_integral(self, tau: f64) -> f64 {
        match self {
            Interp::Step => 0.0,
            Interp::Linear => 0.5 * tau * tau,
            Interp::Smooth | Interp::Spline => tau * tau * tau - 0.5 * tau * tau * tau * tau,
        }
    }
}

/// The spline's slope (value per unit position) at knot `i` of sorted `knots`: the
/// chord between its neighbours; at the first and the last knot, the chord to a phantom
/// knot one end segment's width outside holding the end's value (half the end segment's
/// chord); 0 for a lone knot or knots at one place.
pub fn spline_slope(knots: &[Knot], i: usize) -> Rgb {
    let n = knots.len();
    if n < 2 || i >= n {
        return Rgb::ZERO;
    }
    let (p0, v0) = if i == 0 {
        // Phantom knot before the first: p_0 − (p_1 − p_0), value v_0.
        (2.0 * knots[0].0 - knots[1].0, knots[0].1)
    } else {
        (knots[i - 1].0, knots[i - 1].1)
    };
    let (p1, v1) = if i + 1 == n {
        // Phantom knot after the last: p_{n−1} + (p_{n−1} − p_{n−2}), value v_{n−1}.
        (2.0 * knots[n - 1].0 - knots[n - 2].0, knots[n - 1].1)
    } else {
        (knots[i + 1].0, knots[i + 1].1)
    };
    if p1 > p0 {
        (v1 - v0) / (p1 - p0)
    } else {
        Rgb::ZERO
    }
}

/// The cubic Hermite basis h00, h10, h01, h11 at `tau`.
fn hermite(tau: f32) -> [f32; 4] {
    let (t2, t3) = (tau * tau, tau * tau * tau);
    [2.0 * t3 - 3.0 * t2 + 1.0, t3 - 2.0 * t2 + tau, 3.0 * t2 - 2.0 * t3, t3 - t2]
}

/// ∫_0^τ of each of [`hermite`]'s basis functions.
fn hermite_integral(tau: f64) -> [f64; 4] {
    let (t2, t3, t4) = (tau * tau, tau * tau * tau, tau * tau * tau * tau);
    [tau - t3 + 0.5 * t4, 0.5 * t2 - 2.0 * t3 / 3.0 + 0.25 * t4, t3 - 0.5 * t4, 0.25 * t4 - t3 / 3.0]
}

/// The value of sorted `knots` at `x` (see the module doc); 0 for no knots.
pub fn ramp_value(knots: &[Knot], x: f32) -> Rgb {
    let Some(first) = knots.first() else { return Rgb::ZERO };
    if x <= first.0 {
        return first.1;
    }
    for (i, w) in knots.windows(2).enumerate() {
        let ((p0, v0, interp), (p1, v1, _)) = (w[0], w[1]);
        if x < p1 {
            let tau = if p1 > p0 { (x - p0) / (p1 - p0) } else { 1.0 };
            let interp = Interp::from_maya(interp);
            if interp == Interp::Spline {
                let len = p1 - p0;
                let h = hermite(tau);
                return v0 * h[0]
                    + spline_slope(knots, i) * (len * h[1])
                    + v1 * h[2]
                    + spline_slope(knots, i + 1) * (len * h[3]);
            }
            return v0 + (v1 - v0) * interp.blend(tau);
        }
    }
    knots[knots.len() - 1].1
}

/// ∫ over x ∈ [`a`, `b`] of [`ramp_value`] per channel, in closed form (f64); 0 for no
/// knots or `b` ≤ `a`.
pub fn ramp_integral(knots: &[Knot], a: f32, b: f32) -> [f64; 3] {
    let mut sum = [0.0f64; 3];
    let Some(first) = knots.first() else { return sum };
    if b <= a {
        return sum;
    }
    let add = |sum: &mut [f64; 3], len: f64, v: Rgb| {
        for c in 0..3 {
            sum[c] += len * f64::from(v[c]);
        }
    };
    // Before the first knot and after the last: their values.
    add(&mut sum, f64::from(first.0.clamp(a, b) - a), first.1);
    let last = knots[knots.len() - 1];
    add(&mut sum, f64::from(b - last.0.clamp(a, b)), last.1);
    for (i, w) in knots.windows(2).enumerate() {
        let ((p0, v0, interp), (p1, v1, _)) = (w[0], w[1]);
        let (lo, hi) = (f64::from(p0.clamp(a, b)), f64::from(p1.clamp(a, b)));
        if hi <= lo {
            continue;
        }
        let (start, len) = (f64::from(p0), f64::from(p1 - p0));
        let (ta, tb) = ((lo - start) / len, (hi - start) / len);
        match Interp::from_maya(interp) {
            Interp::Spline => {
                let (ha, hb) = (hermite_integral(ta), hermite_integral(tb));
                let h: [f64; 4] = std::array::from_fn(|k| (hb[k] - ha[k]) * len);
                let (m0, m1) = (spline_slope(knots, i), spline_slope(knots, i + 1));
                for c in 0..3 {
                    sum[c] += h[0] * f64::from(v0[c])
                        + h[1] * len * f64::from(m0[c])
                        + h[2] * f64::from(v1[c])
                        + h[3] * len * f64::from(m1[c]);
                }
            }
            interp => {
                let rise = (interp.blend_integral(tb) - interp.blend_integral(ta)) * len;
                for c in 0..3 {
                    sum[c] += (hi - lo) * f64::from(v0[c]) + f64::from(v1[c] - v0[c]) * rise;
                }
            }
        }
    }
    sum
}

#[cfg(test)]
#[path = "ramp_curve_tests.rs"]
mod tests;
