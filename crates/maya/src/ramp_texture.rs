//! Maya's ramp texture: the colours of `colorEntryList` along the ramp's `type`, moved
//! by its wave and noise attributes and varied in HSV by its colour noise.
//!
//! Parameters after the shared 2D texture ones ([`crate::texture`]): `type` (0 V, 1 U,
//! 2 diagonal, 3 radial, 4 circular, 5 box; the others read as V), `interpolation` (0
//! none, 1 linear, 2 exponential up, 3 exponential down, 4 smooth, 5 bump, 6 spike; the
//! others read as linear: see [`interpolation_blend`]), `colorEntryList` (array of
//! {position, color}), `uWave`, `vWave`, `noise` (0), `noiseFreq` (0.5), `hueNoise`,
//! `satNoise`, `valNoise` (0), `hueNoiseFreq`, `satNoiseFreq`, `valNoiseFreq` (0.5).
//!
//! Maya's node reference: uWave and vWave control "the amplitude of a sine wave offset
//! of the texture in the U and V directions" (more waves come from the placement's
//! repeat); noise is "the amount that the texture is offset in the U and V directions by
//! two-dimensional noise", noiseFreq its granularity; hue, sat and val noise mottle the
//! colour in HSV space, each at its own frequency. The reference gives no formula.
//! mira's reading (the order and the sine's argument as 3Delight's reimplementation of
//! the Maya ramp has them; the noise is mira's gradient noise g ∈ [−1, 1],
//! [`crate::noise::gradient_noise`], so the pattern is not Maya's, its scale and
//! amplitudes are):
//!
//! ```text
//! (u, v) += noise · (g(p, 0), g(p, 1)),   p = (u, v) · NOISE_CELLS · noiseFreq
//! v += vWave · sin(2π u)
//! u −= uWave · sin(2π v)                  (v already waved)
//! (u, v) ← (u, v) mod 1;  c = the ramp's colour at its position for (u, v)
//! hue += hueNoise · g(q_h, 2)  (hue in turns, wrapped)
//! sat = clamp(sat + satNoise · g(q_s, 3), 0, 1),  val = clamp(val + valNoise · g(q_v, 4), 0, 1)
//! ```
//!
//! with q_x = (u, v) · NOISE_CELLS · xNoiseFreq. All of them 0 (the defaults) leave the
//! plain ramp, bit for bit.

use glam::{Vec2, Vec3A};
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::noise::gradient_noise;
use crate::texture::{balance, outside, texture_params, texture_uv, EXTRA};
use crate::utility::{hsv_to_rgb, rgb_to_hsv};
use crate::values::rgb;

/// The position along a ramp of `type` (Maya's enumeration) at `uv`.
pub fn ramp_position(kind: i32, uv: Vec2) -> f32 {
    let d = uv - Vec2::splat(0.5);
    match kind {
        1 => uv.x,
        2 => 0.5 * (uv.x + uv.y),
        3 => (d.y.atan2(d.x) / std::f32::consts::TAU).rem_euclid(1.0),
        4 => (2.0 * d.length()).min(1.0),
        5 => 2.0 * d.x.abs().max(d.y.abs()),
        _ => uv.y,
    }
}

/// The blend s ∈ [0, 1] from entry colour `c0` to the next one `c1` at the segment's
/// parameter `tau` ∈ [0, 1] under the ramp texture's `interpolation` (colour
/// = c0 + (c1 − c0) · s).
///
/// Maya's node reference names the modes (none, linear, exponential up, exponential
/// down, smooth, bump, spike) and gives no formula; its user guide describes smooth as
/// a bell curve over which each colour dominates its region. The formulas are those of
/// the reimplementations that were fitted to Maya's images (Arnold for Maya's
/// `MayaUtils.cpp`, appleseed's `as_maya_ramp_helpers.h`, both agreeing):
///
/// ```text
/// 0 none:              s = 0
/// 1 linear:            s = τ
/// 2 exponential up:    s = τ²             (leaves c0 slowly, reaches c1 steeply)
/// 3 exponential down:  s = 1 − (1 − τ)²   (leaves c0 steeply, reaches c1 flat)
/// 4 smooth:            s = (1 − cos πτ)/2 (a half cosine: flat at both entries)
/// 5 bump:              flat at the brighter entry, steep at the darker one, a
///                      quarter sine: s = sin(πτ/2) towards a brighter c1,
///                      1 − cos(πτ/2) towards a darker one, "brighter" by the sum of
///                      the channels (Arnold for Maya's choice since 2012, replacing a
///                      luminance that mixed up coloured entries) — rounded crests at
///                      the bright entries, creases at the dark
/// 6 spike:             the opposite: steep at the brighter entry, flat at the darker
///                      one — sharp peaks at the bright entries
/// ```
///
/// Equal brightnesses read as bump's and spike's "towards a brighter c1" branch.
pub fn interpolation_blend(interpolation: i32, tau: f32, c0: Vec3A, c1: Vec3A) -> f32 {
    use std::f32::consts::FRAC_PI_2;
    let rises = || c1.element_sum() >= c0.element_sum();
    match interpolation {
        0 => 0.0,
        2 => tau * tau,
        3 => 1.0 - (1.0 - tau) * (1.0 - tau),
        4 => 0.5 * (1.0 - (std::f32::consts::PI * tau).cos()),
        5 if rises() => (FRAC_PI_2 * tau).sin(),
        5 => 1.0 - (FRAC_PI_2 * tau).cos(),
        6 if rises() => 1.0 - (FRAC_PI_2 * tau).cos(),
        6 => (FRAC_PI_2 * tau).sin(),
        _ => tau,
    }
}

/// The colour of sorted ramp entries (position, colour) at `t` with Maya's
/// `interpolation` ([`interpolation_blend`]).
pub fn ramp_color(entries: &[(f32, Vec3A)], t: f32, interpolation: i32) -> Vec3A {
    let Some(first) = entries.first() else { return Vec3A::ZERO };
    if t <= first.0 {
        return first.1;
    }
    for w in entries.windows(2) {
        let ((p0, c0), (p1, c1)) = (w[0], w[1]);
        if t < p1 {
            let span = p1 - p0;
            let x = if span > 0.0 { (t - p0) / span } else { 1.0 };
            return c0 + (c1 - c0) * interpolation_blend(interpolation, x, c0, c1);
        }
    }
    entries[entries.len() - 1].1
}

/// Noise cells per UV unit at a frequency of 1 (Maya's default 0.5 gives 8 across a
/// tile; Arnold's and 3Delight's translations of the ramp use 16 and 18).
pub const NOISE_CELLS: f32 = 16.0;

/// Gradient noise number `k` (decorrelated by depth) at the 2D point `p`, in [−1, 1].
fn noise2(p: Vec2, k: u32) -> f32 {
    gradient_noise(Vec3A::new(p.x, p.y, k as f32 + 0.5))
}

/// A ramp's wave and noise attributes (see the module doc).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RampWaves {
    /// `uWave`, `vWave`: sine amplitudes (UV units).
    pub wave: Vec2,
    /// `noise`: amplitude of the noise offset (UV units).
    pub noise: f32,
    /// `noiseFreq`.
    pub noise_freq: f32,
    /// `hueNoise` (turns), `satNoise`, `valNoise`.
    pub hsv_noise: Vec3A,
    /// `hueNoiseFreq`, `satNoiseFreq`, `valNoiseFreq`.
    pub hsv_freq: Vec3A,
}

impl RampWaves {
    /// The coordinate the ramp reads for texture coordinate `uv` (in [0, 1)²), in [0, 1)².
    pub fn offset(&self, uv: Vec2) -> Vec2 {
        let mut p = uv;
        if self.noise != 0.0 {
            let q = uv * NOISE_CELLS * self.noise_freq;
            p += self.noise * Vec2::new(noise2(q, 0), noise2(q, 1));
        }
        if self.wave.y != 0.0 {
            p.y += self.wave.y * (std::f32::consts::TAU * p.x).sin();
        }
        if self.wave.x != 0.0 {
            p.x -= self.wave.x * (std::f32::consts::TAU * p.y).sin();
        }
        if p == uv {
            p
        } else {
            p - p.floor()
        }
    }

    /// The colour `c` varied by the HSV noise at the (moved) coordinate `uv`.
    pub fn vary(&self, c: Vec3A, uv: Vec2) -> Vec3A {
        if self.hsv_noise == Vec3A::ZERO {
            return c;
        }
        let g = |k: usize| {
            let amount = self.hsv_noise[k];
            if amount == 0.0 {
                0.0
            } else {
                amount * noise2(uv * NOISE_CELLS * self.hsv_freq[k], 2 + k as u32)
            }
        };
        let hsv = rgb_to_hsv(c);
        let h = hsv.x + 360.0 * g(0);
        let s = (hsv.y + g(1)).clamp(0.0, 1.0);
        let v = (hsv.z + g(2)).clamp(0.0, 1.0);
        hsv_to_rgb(Vec3A::new(h, s, v))
    }
}

maya_shader!(
    /// Maya's ramp (see the module doc).
    RAMP,
    ADSK_RAMP,
    "maya_ramp",
    "adskMayaRamp",
    texture_params!(
        "type",
        "interpolation",
        "colorEntryList",
        "uWave",
        "vWave",
        "noise",
        "noiseFreq",
        "hueNoise",
        "satNoise",
        "valNoise",
        "hueNoiseFreq",
        "satNoiseFreq",
        "valNoiseFreq"
    ),
    ramp
);

fn ramp(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = texture_uv(ctx, n) else { return outside(ctx, n, out) };
    let kind = ctx.int(n, EXTRA);
    let interpolation = ctx.int(n, EXTRA + 1);
    let list = ctx.array(n, EXTRA + 2);
    let mut entries: Vec<(f32, Vec3A)> = list
        .array()
        .iter()
        .map(|e| {
            (e.member("position").map_or(0.0, Value::scalar), e.member("color").map_or(Vec3A::ZERO, |c| rgb(c.color())))
        })
        .collect();
    entries.sort_by(|a, b| a.0.total_cmp(&b.0));
    let s = |ctx: &mut Ctx, i: usize| ctx.scalar(n, EXTRA + i);
    let waves = RampWaves {
        wave: Vec2::new(s(ctx, 3), s(ctx, 4)),
        noise: s(ctx, 5),
        noise_freq: s(ctx, 6),
        hsv_noise: Vec3A::new(s(ctx, 7), s(ctx, 8), s(ctx, 9)),
        hsv_freq: Vec3A::new(s(ctx, 10), s(ctx, 11), s(ctx, 12)),
    };
    let at = waves.offset(uv);
    let c = waves.vary(ramp_color(&entries, ramp_position(kind, at), interpolation), at);
    balance(ctx, n, c, 1.0, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_interpolates_between_sorted_entries() {
        let e = [(0.0, Vec3A::ZERO), (0.5, Vec3A::ONE), (1.0, Vec3A::new(1.0, 0.0, 0.0))];
        assert!((ramp_color(&e, 0.25, 1) - Vec3A::splat(0.5)).length() < 1e-6);
        assert_eq!(ramp_color(&e, 0.25, 0), Vec3A::ZERO);
        assert!((ramp_color(&e, 0.25, 4) - Vec3A::splat(0.5)).length() < 1e-6);
        // Smooth at τ = ¼: (1 − cos(π/4)) / 2.
        let smooth = 0.5 * (1.0 - std::f32::consts::FRAC_PI_4.cos());
        assert!((ramp_color(&e, 0.125, 4) - Vec3A::splat(smooth)).length() < 1e-6);
        assert!((ramp_color(&e, 0.75, 1) - Vec3A::new(1.0, 0.5, 0.5)).length() < 1e-6);
        assert_eq!(ramp_position(0, Vec2::new(0.2, 0.7)), 0.7);
        assert_eq!(ramp_position(1, Vec2::new(0.2, 0.7)), 0.2);
        assert!((ramp_position(5, Vec2::new(0.5, 0.9)) - 0.8).abs() < 1e-6);
    }

    /// Each interpolation at τ = ¼ and ⅔ of the segment from black at 0.2 to white at
    /// 0.6 (rising) and from white to black (falling) against its formula within 1e-5:
    /// none 0, linear τ, exponential up τ², down 1 − (1 − τ)², smooth (1 − cos πτ)/2, bump
    /// sin(πτ/2) rising and 1 − cos(πτ/2) falling, spike the reverse; every mode takes
    /// the entries' own colours at τ = 0 and (but none) τ → 1; an unknown code is linear.
    #[test]
    fn each_interpolation_follows_its_formula() {
        use std::f32::consts::FRAC_PI_2;
        let rising = [(0.2, Vec3A::ZERO), (0.6, Vec3A::ONE)];
        let falling = [(0.2, Vec3A::ONE), (0.6, Vec3A::ZERO)];
        for tau in [0.25f32, 2.0 / 3.0] {
            let (up, down) = ((FRAC_PI_2 * tau).sin(), 1.0 - (FRAC_PI_2 * tau).cos());
            let smooth = 0.5 * (1.0 - (2.0 * FRAC_PI_2 * tau).cos());
            let want: [(i32, f32, f32); 8] = [
                (0, 0.0, 0.0),
                (1, tau, tau),
                (2, tau * tau, tau * tau),
                (3, 1.0 - (1.0 - tau) * (1.0 - tau), 1.0 - (1.0 - tau) * (1.0 - tau)),
                (4, smooth, smooth),
                (5, up, down),
                (6, down, up),
                (9, tau, tau),
            ];
            let t = 0.2 + 0.4 * tau;
            for (mode, s_rise, s_fall) in want {
                let got = ramp_color(&rising, t, mode);
                assert!((got - Vec3A::splat(s_rise)).abs().max_element() < 1e-5, "mode {mode} rising τ {tau}: {got}");
                let got = ramp_color(&falling, t, mode);
                assert!(
                    (got - Vec3A::splat(1.0 - s_fall)).abs().max_element() < 1e-5,
                    "mode {mode} falling τ {tau}: {got}"
                );
            }
        }
        for mode in 0..7 {
            assert_eq!(ramp_color(&rising, 0.2, mode), Vec3A::ZERO);
            assert_eq!(ramp_color(&rising, 0.6, mode), Vec3A::ONE);
            if mode != 0 {
                assert!((ramp_color(&rising, 0.6 - 1e-6, mode) - Vec3A::ONE).abs().max_element() < 1e-4, "mode {mode}");
            }
        }
        // "Brighter" is the channel sum: green (sum 1, luminance 0.587) towards magenta
        // (sum 1.8, luminance 0.373) rises, so bump is sin(πτ/2) there (a luminance test
        // would take the falling branch, 1 − cos(πτ/2)).
        let (green, magenta) = (Vec3A::new(0.0, 1.0, 0.0), Vec3A::new(0.9, 0.0, 0.9));
        let s = interpolation_blend(5, 0.25, green, magenta);
        assert!((s - (FRAC_PI_2 * 0.25).sin()).abs() < 1e-6, "{s}");
        // Bump is flat at the bright entry, spike at the dark one (one-sided slopes).
        let slope =
            |mode: i32, t: f32, h: f32| (ramp_color(&rising, t + h, mode).x - ramp_color(&rising, t, mode).x) / h;
        assert!(slope(5, 0.6 - 1e-3, 1e-3 * 0.5).abs() < 0.05 && slope(5, 0.2, 1e-3) > 3.0);
        assert!(slope(6, 0.2, 1e-3).abs() < 0.05 && slope(6, 0.6 - 1e-3, 1e-3 * 0.5) > 3.0);
    }

    /// uWave alone: a U ramp's position is u − uWave · sin(2π v); vWave alone: a V ramp's
    /// is v + vWave · sin(2π u), wrapped into [0, 1) (1e-5).
    #[test]
    fn waves_move_the_position_by_their_sine() {
        let w = RampWaves { wave: Vec2::new(0.1, 0.0), ..RampWaves::default() };
        for (u, v) in [(0.5, 0.25), (0.3, 0.1), (0.05, 0.8), (0.7, 0.6)] {
            let want = (u - 0.1 * (std::f32::consts::TAU * v).sin()).rem_euclid(1.0);
            let got = ramp_position(1, w.offset(Vec2::new(u, v)));
            assert!((got - want).abs() < 1e-5, "({u}, {v}): {got} vs {want}");
        }
        let w = RampWaves { wave: Vec2::new(0.0, 0.2), ..RampWaves::default() };
        for (u, v) in [(0.25, 0.5), (0.1, 0.3), (0.8, 0.05)] {
            let want = (v + 0.2 * (std::f32::consts::TAU * u).sin()).rem_euclid(1.0);
            let got = ramp_position(0, w.offset(Vec2::new(u, v)));
            assert!((got - want).abs() < 1e-5, "({u}, {v}): {got} vs {want}");
        }
    }

    /// No wave or noise: the coordinate and colour are returned unchanged, bit for bit;
    /// a noise amplitude moves the coordinate by at most the amplitude (per axis) and
    /// does move it somewhere on the tile.
    #[test]
    fn noise_offsets_the_position_within_its_amplitude() {
        let none = RampWaves { noise_freq: 0.5, hsv_freq: Vec3A::splat(0.5), ..RampWaves::default() };
        let uv = Vec2::new(0.31, 0.47);
        assert_eq!(none.offset(uv), uv);
        assert_eq!(none.vary(Vec3A::new(0.2, 0.4, 0.6), uv), Vec3A::new(0.2, 0.4, 0.6));
        let noisy = RampWaves { noise: 0.05, noise_freq: 0.5, ..RampWaves::default() };
        let mut moved = 0.0f32;
        for i in 0..64 {
            let uv = Vec2::new(0.2 + 0.009 * i as f32, 0.3 + 0.007 * i as f32);
            let d = noisy.offset(uv) - uv;
            assert!(d.abs().max_element() <= 0.05 + 1e-6, "{uv}: {d}");
            moved = moved.max(d.abs().max_element());
        }
        assert!(moved > 0.005, "{moved}");
    }
}
