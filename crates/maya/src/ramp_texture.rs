//! Maya's ramp texture: the colours of `colorEntryList` along the ramp's `type`, moved
//! by its wave and noise attributes and varied in HSV by its colour noise.
//!
//! Parameters after the shared 2D texture ones ([`crate::texture`]): `type` (0 V, 1 U,
//! 2 diagonal, 3 radial, 4 circular, 5 box; the others read as V), `interpolation` (0
//! none, 1 linear, 4 smooth; the others read as linear), `colorEntryList` (array of
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

/// The colour of sorted ramp entries (position, colour) at `t` with Maya's
/// `interpolation` (0 none, 1 linear, 4 smooth; the others read as linear).
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
            let x = match interpolation {
                0 => 0.0,
                4 => x * x * (3.0 - 2.0 * x),
                _ => x,
            };
            return c0 + (c1 - c0) * x;
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
        assert!((ramp_color(&e, 0.125, 4) - Vec3A::splat(0.15625)).length() < 1e-6);
        assert!((ramp_color(&e, 0.75, 1) - Vec3A::new(1.0, 0.5, 0.5)).length() < 1e-6);
        assert_eq!(ramp_position(0, Vec2::new(0.2, 0.7)), 0.7);
        assert_eq!(ramp_position(1, Vec2::new(0.2, 0.7)), 0.2);
        assert!((ramp_position(5, Vec2::new(0.5, 0.9)) - 0.8).abs() < 1e-6);
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
