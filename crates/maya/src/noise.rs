//! Maya's noise texture: fractal gradient noise over the 2D texture coordinate (and
//! `time` as a third coordinate).
//!
//! Parameters (see `mayabase.mi`): `threshold` (0), `amplitude` (1), `ratio` (0.707),
//! `frequencyRatio` (2), `depthMax` (3), `inflection` (off), `time` (0), `frequency` (8),
//! `implode` (0) about `implodeCenterU`/`implodeCenterV` (0.5, 0.5) ([`Implode`]), `noiseType` (1, Billow: Maya's default), `numWaves` (5) and the
//! Billow cells' `density` (1), `spottyness` (0.1), `sizeRand` (0), `randomness` (1) and
//! `falloff` (2, Fast) ([`crate::billow`]).
//!
//! ```text
//! F = Σ_{i<depthMax} ratio^i · n_i(p · frequency · frequencyRatio^i) / Σ ratio^i
//! Perlin:  value = threshold + 0.5 + 0.5 · amplitude · F
//! Billow (or inflection): n → |n|, value = threshold + amplitude · F
//! ```
//!
//! clipped to [0, 1], with p = (u, v, `time`) and n the octave's noise ([`Shape`]), in
//! [−1, 1]. Maya's reference describes the noise types: Perlin (0) "the standard 2D
//! noise", Billow (1) "a puffy, cloudlike effect", Wave (2) "a sum of 2D waves in
//! space", Wispy (3) "a perlin noise that uses a second noise as a smear map … when time
//! is animated the smear noise is moved, causing an undulating effect", SpaceTime (4)
//! "a 3 dimensional version of the 2D perlin noise, where time is the third dimension".
//! mira's readings:
//! - Perlin and SpaceTime: gradient noise g (Perlin's improved noise, with mira's own
//!   lattice hash: the pattern is not Maya's, its statistics are), 0 on the integer
//!   lattice, at (u f, v f, `time`) — mira's Perlin already animates through time as a
//!   third dimension, so the two coincide;
//! - Billow: puffy cells in [0, 1] ([`crate::billow::Cells`]: blobs jittered over the
//!   octave's grid, their presence, size and intensity random, shaped by `falloff`);
//! - Wave: (1/N) Σ_{k<N} cos(2π (d_k · (x, y) + `time`) + φ_k), N = `numWaves` (at least
//!   1), d_k a unit direction in the plane and φ_k a phase, both from a hash of k and the
//!   octave: waves of one period per unit of the octave's coordinate, moving a period per
//!   unit of `time` (periodic in it); over 3D space (volumeNoise) d_k is a unit 3D
//!   direction and `time` shifts the point (as for the other types);
//! - Wispy: g at the point moved by [`WISPY_SMEAR`] × a smear vector of two (3D: three)
//!   gradient noises of half the octave's frequency; in 2D the main noise is read at
//!   depth 0 and the smear noise at depth `time`, so animating time moves the smear alone.

use glam::{Vec2, Vec3A};
use shader::{Ctx, NodeId, Value};

use crate::billow::{Cells, Falloff};
use crate::maya_shader;

pub use crate::lattice_hash::lattice;

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

/// How far Wispy's smear noise moves the point (octave coordinate units).
pub const WISPY_SMEAR: f32 = 0.5;

/// The noise each octave reads (`noiseType`; see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// Perlin (0) and SpaceTime (4): gradient noise.
    Perlin,
    /// Billow (1): puffy cells.
    Billow {
        /// `density`, `spottyness`, `sizeRand`, `randomness` and `falloff`.
        cells: Cells,
    },
    /// Wave (2): a sum of `waves` plane waves.
    Wave {
        /// `numWaves`.
        waves: u32,
    },
    /// Wispy (3): gradient noise smeared by a second noise.
    Wispy,
}

impl Shape {
    /// Maya's `noiseType` with `numWaves` and the Billow `cells` (unknown types read as
    /// Perlin).
    pub fn from_maya(noise_type: i32, waves: i32, cells: Cells) -> Shape {
        match noise_type {
            1 => Shape::Billow { cells },
            2 => Shape::Wave { waves: waves.clamp(1, 256) as u32 },
            3 => Shape::Wispy,
            _ => Shape::Perlin,
        }
    }

    /// The octave's noise at `q` for octave `octave`; `planar`: the 2D texture's (q =
    /// (x, y, time)), else a point in space.
    pub fn at(self, q: Vec3A, octave: u32, planar: bool) -> f32 {
        match self {
            Shape::Perlin => gradient_noise(q),
            // 2D: time moves the point along (1, 1).
            Shape::Billow { cells } if planar => cells.at(Vec3A::new(q.x + q.z, q.y + q.z, 0.0), octave, true),
            Shape::Billow { cells } => cells.at(q, octave, false),
            Shape::Wave { waves } => wave(q, waves, octave, planar),
            Shape::Wispy => {
                let half = q * 0.5;
                if planar {
                    let smear = Vec3A::new(
                        gradient_noise(Vec3A::new(half.x + 17.3, half.y + 5.1, q.z)),
                        gradient_noise(Vec3A::new(half.x + 3.7, half.y + 29.9, q.z)),
                        0.0,
                    );
                    gradient_noise(Vec3A::new(q.x, q.y, 0.0) + WISPY_SMEAR * smear)
                } else {
                    let smear = Vec3A::new(
                        gradient_noise(half + Vec3A::new(17.3, 5.1, 11.7)),
                        gradient_noise(half + Vec3A::new(3.7, 29.9, 7.3)),
                        gradient_noise(half + Vec3A::new(23.1, 13.3, 31.9)),
                    );
                    gradient_noise(q + WISPY_SMEAR * smear)
                }
            }
        }
    }
}

/// A hash of wave `k` of octave `octave`, `salt` choosing one of its numbers, in [0, 1).
fn wave_hash(k: u32, octave: u32, salt: i32) -> f32 {
    (lattice(k as i32, octave as i32, salt) >> 8) as f32 / (1u32 << 24) as f32
}

/// The Wave noise: the mean of `waves` plane waves (see the module doc), in [−1, 1].
pub fn wave(q: Vec3A, waves: u32, octave: u32, planar: bool) -> f32 {
    if !q.is_finite() {
        return 0.0;
    }
    let n = waves.max(1);
    let tau = std::f32::consts::TAU;
    let mut sum = 0.0;
    for k in 0..n {
        let phase = tau * wave_hash(k, octave, 1);
        let azimuth = tau * wave_hash(k, octave, 2);
        let (s, c) = azimuth.sin_cos();
        let along = if planar {
            // time (q.z) moves the wave a period per unit.
            c * q.x + s * q.y + q.z
        } else {
            let z = 2.0 * wave_hash(k, octave, 3) - 1.0;
            let r = (1.0 - z * z).max(0.0).sqrt();
            r * c * q.x + r * s * q.y + z * q.z
        };
        // The fraction of a period only: large coordinates keep their precision.
        sum += (tau * along.rem_euclid(1.0) + phase).cos();
    }
    (sum / n as f32).clamp(-1.0, 1.0)
}

/// Maya's `implode`: the reference says it "warps the noise function in a concentric
/// fashion" about `implodeCenter` (a UV point), no effect at 0, a spherical projection
/// ("starburst") at 1, negative values skewing the noise outward. It gives no formula;
/// mira's: the texture reads the noise at
///
/// ```text
/// uv' = c + d · |d|^(−implode),   d = uv − c   (|d|' = |d|^(1 − implode))
/// ```
///
/// so 0 is the identity, 1 puts every point on the unit circle about c (the noise then
/// varies with the angle alone: the starburst) and negative values pull points towards
/// c (the pattern spreads outward). The centre itself is left where it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Implode {
    /// `implode`.
    pub amount: f32,
    /// `implodeCenterU`, `implodeCenterV`: the centre, in UV.
    pub center: Vec2,
}

impl Implode {
    /// The UV point whose noise the texture shows at `uv`.
    pub fn warp(&self, uv: Vec2) -> Vec2 {
        let d = uv - self.center;
        let r = d.length();
        if self.amount == 0.0 || r == 0.0 || !r.is_finite() {
            return uv;
        }
        self.center + d * r.powf(-self.amount)
    }
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
    /// The octaves' noise (`noiseType`, `numWaves`).
    pub shape: Shape,
}

impl Noise {
    /// The settings of node `n`, whose parameters from index `first` are `threshold`,
    /// `amplitude`, `ratio`, `frequencyRatio`, `depthMax`, `inflection`, `time` and
    /// `frequency` in that order, and whose `noiseType` (1: billow) is at index
    /// `noise_type` (the 2D and 3D textures declare it at different places), followed
    /// by `numWaves`, `density`, `spottyness`, `sizeRand`, `randomness` and `falloff`.
    pub fn read(ctx: &mut Ctx, n: NodeId, first: usize, noise_type: usize) -> Noise {
        let e = first;
        let t = noise_type;
        let cells = Cells {
            density: ctx.scalar(n, t + 2),
            spottyness: ctx.scalar(n, t + 3),
            size_rand: ctx.scalar(n, t + 4),
            randomness: ctx.scalar(n, t + 5),
            falloff: Falloff::from_maya(ctx.int(n, t + 6)),
        };
        let shape = Shape::from_maya(ctx.int(n, t), ctx.int(n, t + 1), cells);
        Noise {
            threshold: ctx.scalar(n, e),
            amplitude: ctx.scalar(n, e + 1),
            ratio: ctx.scalar(n, e + 2),
            frequency_ratio: ctx.scalar(n, e + 3),
            depth: ctx.int(n, e + 4).max(1) as u32,
            billow: ctx.bool(n, e + 5) || ctx.int(n, noise_type) == 1,
            time: ctx.scalar(n, e + 6),
            frequency: ctx.scalar(n, e + 7),
            shape,
        }
    }

    /// The texture's value at `uv`, in [0, 1].
    pub fn value(&self, uv: Vec2) -> f32 {
        self.value_with(true, |f| Vec3A::new(uv.x * f, uv.y * f, self.time))
    }

    /// The same fractal over 3D space (Maya's volumeNoise): the value at the point `q`,
    /// in [0, 1], each octave's noise read at q · f shifted by `time` along the diagonal
    /// (1, 1, 1) (mira's reading: Maya says only that `time` animates the texture).
    pub fn value3(&self, q: Vec3A) -> f32 {
        self.value_with(false, |f| q * f + Vec3A::splat(self.time))
    }

    /// The value with octave noise read at `at(f)`, f the octave's frequency (`planar`:
    /// the 2D texture's coordinate).
    fn value_with(&self, planar: bool, at: impl Fn(f32) -> Vec3A) -> f32 {
        let (mut sum, mut weights, mut w, mut f) = (0.0, 0.0, 1.0, self.frequency);
        for octave in 0..self.depth.clamp(1, 16) {
            let n = self.shape.at(at(f), octave, planar);
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
        "noiseType",
        "numWaves",
        "density",
        "spottyness",
        "sizeRand",
        "randomness",
        "falloff",
        "implode",
        "implodeCenterU",
        "implodeCenterV"
    ],
    noise
);

fn noise(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = crate::texture::texture_uv(ctx, n) else { return crate::texture::outside(ctx, n, out) };
    let settings = Noise::read(ctx, n, 8, 16);
    let implode = Implode { amount: ctx.scalar(n, 23), center: Vec2::new(ctx.scalar(n, 24), ctx.scalar(n, 25)) };
    let v = settings.value(implode.warp(uv));
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
            shape: Shape::Perlin,
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

    /// Billow's cells in the fractal: values in [0, 1] and deterministic over many
    /// points (not constant); density 0 gives the threshold exactly; blobs on the
    /// lattice (randomness 0) of equal peaks (spottyness 0) give every octave its peak
    /// at a point that is a cell centre in all three octaves (uv · 8 · 3^i half-integer:
    /// frequencyRatio 3), so the value is threshold + amplitude · curve(0) (1e-5), also
    /// after `time` 1 moves the point by a whole cell along (1, 1).
    #[test]
    fn billow_is_a_fractal_of_cells() {
        let billow = Noise { billow: true, shape: Shape::Billow { cells: Cells::MAYA_DEFAULT }, ..maya_default() };
        let (mut lo, mut hi) = (1f32, 0f32);
        for i in 0..2000 {
            let uv = Vec2::new((i % 50) as f32 / 50.0 + 0.003, (i / 50) as f32 / 40.0 + 0.007);
            let v = billow.value(uv);
            assert!((0.0..=1.0).contains(&v) && v == billow.value(uv));
            assert!((0.0..=1.0).contains(&billow.value3(Vec3A::new(uv.x, uv.y, 0.3))));
            (lo, hi) = (lo.min(v), hi.max(v));
        }
        assert!(hi - lo > 0.3, "{lo}..{hi}");
        let none = Shape::Billow { cells: Cells { density: 0.0, ..Cells::MAYA_DEFAULT } };
        for uv in [Vec2::new(0.31, 0.77), Vec2::new(-4.2, 0.05)] {
            assert_eq!(Noise { threshold: 0.3, shape: none, ..billow }.value(uv), 0.3);
            assert_eq!(Noise { threshold: 0.3, shape: none, ..billow }.value3(uv.extend(0.5).into()), 0.3);
        }
        for falloff in [Falloff::Linear, Falloff::Smooth, Falloff::Fast, Falloff::Bubble] {
            let cells = Cells { randomness: 0.0, spottyness: 0.0, falloff, ..Cells::MAYA_DEFAULT };
            let n = Noise {
                threshold: 0.1,
                amplitude: 0.8,
                frequency_ratio: 3.0,
                shape: Shape::Billow { cells },
                ..billow
            };
            let peak = 0.1 + 0.8 * falloff.curve(0.0);
            for uv in [Vec2::new(0.0625, 0.1875), Vec2::new(0.3125, -0.4375)] {
                assert!((n.value(uv) - peak).abs() < 1e-5, "{falloff:?} at {uv}: {}", n.value(uv));
                assert!((Noise { time: 1.0, ..n }.value(uv) - peak).abs() < 1e-5);
                assert!((n.value3(uv.extend(0.0625).into()) - peak).abs() < 1e-5);
            }
        }
    }

    /// Wave: the mean of N plane waves, within [−1, 1], periodic in time with period 1
    /// (1e-4), varying and continuous; one wave of a 2D octave is constant across its
    /// crests: moving along the crest (perpendicular to its direction) keeps the value.
    #[test]
    fn wave_noise_is_a_mean_of_plane_waves() {
        let n = Noise { shape: Shape::Wave { waves: 5 }, ..maya_default() };
        let (mut lo, mut hi) = (1f32, 0f32);
        for i in 0..2000 {
            let uv = Vec2::new((i % 50) as f32 / 50.0 + 0.003, (i / 50) as f32 / 40.0 + 0.007);
            let v = n.value(uv);
            assert!((0.0..=1.0).contains(&v));
            assert!((n.value(uv + Vec2::splat(1e-4)) - v).abs() < 0.01, "continuous");
            for t in [0.25f32, 1.5] {
                let a = Noise { time: t, ..n }.value(uv);
                let b = Noise { time: t + 1.0, ..n }.value(uv);
                assert!((a - b).abs() < 1e-4, "periodic in time: {a} {b}");
            }
            (lo, hi) = (lo.min(v), hi.max(v));
        }
        assert!(hi - lo > 0.3, "{lo}..{hi}");
        // One wave: its crest direction is perpendicular to d = (cos a, sin a).
        let a = std::f32::consts::TAU * wave_hash(0, 0, 2);
        let crest = Vec3A::new(-a.sin(), a.cos(), 0.0);
        for i in 0..50 {
            let q = Vec3A::new(i as f32 * 0.173, i as f32 * 0.071, 0.3);
            let (v, w) = (wave(q, 1, 0, true), wave(q + crest * 2.5, 1, 0, true));
            assert!((v - w).abs() < 1e-3, "{v} {w}");
            assert!(wave(q, 7, 3, false).abs() <= 1.0);
        }
        // numWaves below 1 reads as 1; a NaN point gives 0.
        assert_eq!(Shape::from_maya(2, 0, Cells::MAYA_DEFAULT), Shape::Wave { waves: 1 });
        assert_eq!(wave(Vec3A::splat(f32::NAN), 5, 0, true), 0.0);
    }

    /// Wispy: in range, deterministic, not the plain noise; in 2D `time` moves only the
    /// smear noise — at time 0 and time 0.37 the smear differs, so the value does, while
    /// Perlin and SpaceTime (mira: the same noise) share one value.
    #[test]
    fn wispy_smears_the_noise_and_spacetime_is_perlin() {
        let wispy = Noise { shape: Shape::Wispy, ..maya_default() };
        let perlin = maya_default();
        let (mut differ, mut moved) = (0, 0);
        for i in 0..1000 {
            let uv = Vec2::new((i % 40) as f32 / 40.0 + 0.011, (i / 40) as f32 / 25.0 + 0.013);
            let v = wispy.value(uv);
            assert!((0.0..=1.0).contains(&v) && v == wispy.value(uv));
            differ += usize::from((v - perlin.value(uv)).abs() > 1e-3);
            moved += usize::from((v - Noise { time: 0.37, ..wispy }.value(uv)).abs() > 1e-3);
            assert!(wispy.value3(Vec3A::new(uv.x, uv.y, 0.2)) <= 1.0);
        }
        assert!(differ > 500 && moved > 500, "{differ} {moved}");
        let c = Cells::MAYA_DEFAULT;
        assert_eq!(Shape::from_maya(4, 5, c), Shape::Perlin);
        assert_eq!(Shape::from_maya(0, 5, c), Shape::Perlin);
        assert_eq!(Shape::from_maya(3, 5, c), Shape::Wispy);
        assert_eq!(Shape::from_maya(1, 5, c), Shape::Billow { cells: c });
    }

    /// `implode`: 0 leaves every point (so the pattern) bit-identical; the centre keeps
    /// its value; elsewhere the texture shows the unwarped noise at c + d·|d|^(−implode)
    /// computed here by hand (1e-6), and implode 1 makes the value constant along each
    /// ray from the centre (the starburst: 1e-6).
    #[test]
    fn implode_warps_about_its_centre() {
        let n = maya_default();
        let c = Vec2::new(0.5, 0.5);
        let none = Implode { amount: 0.0, center: c };
        for i in 0..400 {
            let uv = Vec2::new((i % 20) as f32 / 20.0 + 0.013, (i / 20) as f32 / 20.0 + 0.029);
            assert_eq!(none.warp(uv), uv);
            assert_eq!(n.value(none.warp(uv)).to_bits(), n.value(uv).to_bits());
        }
        for amount in [0.5f32, 1.0, -0.7, 2.0] {
            let imp = Implode { amount, center: c };
            assert_eq!(imp.warp(c), c);
            assert_eq!(n.value(imp.warp(c)), n.value(c));
        }
        // d = (0.3, 0.4), |d| = 0.5: at implode 0.5 |d|' = 0.5^0.5, along (0.6, 0.8).
        let imp = Implode { amount: 0.5, center: c };
        let uv = c + Vec2::new(0.3, 0.4);
        let by_hand = c + Vec2::new(0.6, 0.8) * 0.5f32.sqrt();
        assert!((imp.warp(uv) - by_hand).length() < 1e-6);
        assert!((n.value(imp.warp(uv)) - n.value(by_hand)).abs() < 1e-6);
        assert!((n.value(imp.warp(uv)) - n.value(uv)).abs() > 1e-4, "the warp changes the value");
        // Implode 1: every point along a ray from c shows the noise at distance 1.
        let star = Implode { amount: 1.0, center: c };
        let dir = Vec2::new(0.8, -0.6);
        let at_one = n.value(c + dir);
        for t in [0.05f32, 0.2, 0.37, 0.9] {
            assert!((n.value(star.warp(c + dir * t)) - at_one).abs() < 1e-6);
        }
    }
}
