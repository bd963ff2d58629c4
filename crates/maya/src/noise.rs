//! Maya's noise texture: fractal gradient noise over the 2D texture coordinate (and
//! `time` as a third coordinate).
//!
//! Parameters (see `mayabase.mi`): `threshold` (0), `amplitude` (1), `ratio` (0.707),
//! `frequencyRatio` (2), `depthMax` (3), `inflection` (off), `time` (0), `frequency` (8),
//! `implode` (not read), `noiseType` (0 Perlin, 1 billow; the wave, wispy and space-time
//! types read as Perlin).
//!
//! ```text
//! F = Σ_{i<depthMax} ratio^i · n(p · frequency · frequencyRatio^i) / Σ ratio^i
//! Perlin:  value = threshold + 0.5 + 0.5 · amplitude · F
//! billow (or inflection): n → |n|, value = threshold + amplitude · F
//! ```
//!
//! clipped to [0, 1], with n gradient noise in [−1, 1] that is 0 on the integer lattice
//! (Perlin's improved noise, with mira's own lattice hash: the pattern is not Maya's, its
//! statistics are). Maya documents the attributes' effects — threshold added and
//! clipped, amplitude scaling about the mean, ratio and frequency ratio between the
//! octaves — not its noise function.

use glam::{Vec2, Vec3A};
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;

/// A 32-bit hash of a lattice point.
pub fn lattice(i: i32, j: i32, k: i32) -> u32 {
    let mut h = (i as u32).wrapping_mul(0x8da6_b343)
        ^ (j as u32).wrapping_mul(0xd816_3841)
        ^ (k as u32).wrapping_mul(0xcb1a_b31f);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297a_2d39);
    h ^ (h >> 15)
}

/// The dot product of one of the 12 cube-edge gradients (chosen by `h`) with (x, y, z).
fn gradient(h: u32, x: f32, y: f32, z: f32) -> f32 {
    match h % 12 {
        0 => x + y,
        1 => -x + y,
        2 => x - y,
        3 => -x - y,
        4 => x + z,
        5 => -x + z,
        6 => x - z,
        7 => -x - z,
        8 => y + z,
        9 => -y + z,
        10 => y - z,
        _ => -y - z,
    }
}

fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// Gradient noise at `p`, in [−1, 1], zero at integer points (and at infinity).
pub fn gradient_noise(p: Vec3A) -> f32 {
    if !p.is_finite() {
        return 0.0;
    }
    let f = p.floor();
    let (i, j, k) = (f.x as i32, f.y as i32, f.z as i32);
    let d = p - f;
    let (u, v, w) = (fade(d.x), fade(d.y), fade(d.z));
    let corner = |a: i32, b: i32, c: i32| {
        // Wrapping: a hostile frequency puts the lattice at the edge of i32.
        let h = lattice(i.wrapping_add(a), j.wrapping_add(b), k.wrapping_add(c));
        gradient(h, d.x - a as f32, d.y - b as f32, d.z - c as f32)
    };
    let lerp = |t: f32, a: f32, b: f32| a + t * (b - a);
    let x00 = lerp(u, corner(0, 0, 0), corner(1, 0, 0));
    let x10 = lerp(u, corner(0, 1, 0), corner(1, 1, 0));
    let x01 = lerp(u, corner(0, 0, 1), corner(1, 0, 1));
    let x11 = lerp(u, corner(0, 1, 1), corner(1, 1, 1));
    // The 12-gradient noise peaks below 1 in magnitude; clamp for safety.
    lerp(w, lerp(v, x00, x10), lerp(v, x01, x11)).clamp(-1.0, 1.0)
}

/// The settings of a noise texture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Noise {
    /// `threshold`.
    pub threshold: f32,
    /// `amplitude`.
    pub amplitude: f32,
    /// `ratio`: the weight of each octave relative to the one before.
    pub ratio: f32,
    /// `frequencyRatio`: the frequency of each octave relative to the one before.
    pub frequency_ratio: f32,
    /// `depthMax`: the number of octaves.
    pub depth: u32,
    /// `inflection` or the billow type: absolute noise.
    pub billow: bool,
    /// `frequency` of the first octave, per UV unit.
    pub frequency: f32,
    /// `time`, the third coordinate.
    pub time: f32,
}

impl Noise {
    /// The settings of node `n`, whose parameters from index `first` are `threshold`,
    /// `amplitude`, `ratio`, `frequencyRatio`, `depthMax`, `inflection`, `time` and
    /// `frequency` in that order, and whose `noiseType` (1: billow) is at index
    /// `noise_type` (the 2D and 3D textures declare it at different places).
    pub fn read(ctx: &mut Ctx, n: NodeId, first: usize, noise_type: usize) -> Noise {
        let e = first;
        Noise {
            threshold: ctx.scalar(n, e),
            amplitude: ctx.scalar(n, e + 1),
            ratio: ctx.scalar(n, e + 2),
            frequency_ratio: ctx.scalar(n, e + 3),
            depth: ctx.int(n, e + 4).max(1) as u32,
            billow: ctx.bool(n, e + 5) || ctx.int(n, noise_type) == 1,
            time: ctx.scalar(n, e + 6),
            frequency: ctx.scalar(n, e + 7),
        }
    }

    /// The texture's value at `uv`, in [0, 1].
    pub fn value(&self, uv: Vec2) -> f32 {
        self.value_with(|f| Vec3A::new(uv.x * f, uv.y * f, self.time))
    }

    /// The same fractal over 3D space (Maya's volumeNoise): the value at the point `q`,
    /// in [0, 1], each octave's noise read at q · f shifted by `time` along the diagonal
    /// (1, 1, 1) (mira's reading: Maya says only that `time` animates the texture).
    pub fn value3(&self, q: Vec3A) -> f32 {
        self.value_with(|f| q * f + Vec3A::splat(self.time))
    }

    /// The value with octave noise read at `at(f)`, f the octave's frequency.
    fn value_with(&self, at: impl Fn(f32) -> Vec3A) -> f32 {
        let (mut sum, mut weights, mut w, mut f) = (0.0, 0.0, 1.0, self.frequency);
        for _ in 0..self.depth.clamp(1, 16) {
            let n = gradient_noise(at(f));
            sum += w * if self.billow { n.abs() } else { n };
            weights += w;
            w *= self.ratio;
            f *= self.frequency_ratio;
        }
        let fractal = if weights > 0.0 { sum / weights } else { 0.0 };
        let v = if self.billow {
            self.threshold + self.amplitude * fractal
        } else {
            self.threshold + 0.5 + 0.5 * self.amplitude * fractal
        };
        v.clamp(0.0, 1.0)
    }
}

maya_shader!(
    /// Maya's noise texture ([`Noise`]), grey, through the colour balance.
    NOISE,
    ADSK_NOISE,
    "maya_noise",
    "adskMayaNoise",
    &[
        "uvCoord",
        "invert",
        "alphaIsLuminance",
        "colorGain",
        "colorOffset",
        "alphaGain",
        "alphaOffset",
        "defaultColor",
        "threshold",
        "amplitude",
        "ratio",
        "frequencyRatio",
        "depthMax",
        "inflection",
        "time",
        "frequency",
        "noiseType"
    ],
    noise
);

fn noise(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = crate::texture::texture_uv(ctx, n) else { return crate::texture::outside(ctx, n, out) };
    let settings = Noise::read(ctx, n, 8, 16);
    let v = settings.value(uv);
    crate::texture::balance(ctx, n, Vec3A::splat(v), v, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn maya_default() -> Noise {
        Noise {
            threshold: 0.0,
            amplitude: 1.0,
            ratio: 0.707,
            frequency_ratio: 2.0,
            depth: 3,
            billow: false,
            frequency: 8.0,
            time: 0.0,
        }
    }

    #[test]
    fn lattice_points_give_the_mean_and_values_stay_in_range() {
        let n = maya_default();
        // uv · 8 · 2^i integer: every octave is 0 there.
        for uv in [Vec2::new(0.25, 0.5), Vec2::new(0.125, 0.875)] {
            assert!((n.value(uv) - 0.5).abs() < 1e-6);
            assert!((Noise { threshold: 0.2, ..n }.value(uv) - 0.7).abs() < 1e-6);
            assert!(Noise { billow: true, ..n }.value(uv).abs() < 1e-6);
        }
        // Over many points: within [0, 1], mean near 0.5, not constant, continuous.
        let (mut sum, mut min, mut max) = (0.0f64, 1f32, 0f32);
        let count = 4096;
        for i in 0..count {
            let uv = Vec2::new((i % 64) as f32 / 64.0 + 0.003, (i / 64) as f32 / 64.0 + 0.007);
            let v = n.value(uv);
            assert!((0.0..=1.0).contains(&v));
            let near = n.value(uv + Vec2::splat(1e-4));
            assert!((near - v).abs() < 0.01, "jump at {uv}");
            sum += f64::from(v);
            (min, max) = (min.min(v), max.max(v));
        }
        let mean = sum / f64::from(count);
        assert!((mean - 0.5).abs() < 0.05, "mean {mean}");
        assert!(max - min > 0.3, "range {min}..{max}");
        // Hostile settings stay finite and in range (no lattice overflow).
        for f in [1e30f32, -1e30, f32::INFINITY] {
            let v = Noise { frequency: f, ..n }.value(Vec2::new(0.3, 0.6));
            assert!((0.0..=1.0).contains(&v), "frequency {f}: {v}");
        }
        // Amplitude 0: the constant threshold + 0.5.
        assert!((Noise { amplitude: 0.0, ..n }.value(Vec2::new(0.3, 0.6)) - 0.5).abs() < 1e-6);
    }
}
