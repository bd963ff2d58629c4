//! Maya's fractal, mountain and water 2D textures: height fields over the UV tile that
//! exports use as bump or displacement maps (their alpha is the height) and as colour
//! maps, read through the shared 2D texture parameters and colour balance.
//!
//! Maya's node reference names their attributes, defaults and effects but gives no
//! formulas: the formulas here are mira's readings, stated on each item. The noise is
//! mira's gradient noise (`crate::noise`), so the patterns have Maya's parameters, not
//! Maya's exact pattern.

use glam::{Vec2, Vec3A};
use shader::{Ctx, NodeId, Value};

use crate::lattice_hash::lattice;
use crate::maya_shader;
use crate::noise::gradient_noise;
use crate::pattern_textures::{params2d, EXTRA};
use crate::texture::{balance, outside, texture_uv};
use crate::texture3d::solid_fractal_value;
use crate::values::rgb;

/// The most octaves a fractal here sums (2^16 cycles per tile is far below a pixel).
const MAX_OCTAVES: f32 = 16.0;

/// A fractal of gradient noise over the tile: octaves i from `level_min` to `level_max`
/// (a fractional last one weighted by its fraction), octave i read at `uv` × `step`^i
/// (one noise cell per tile at i = 0) and `z`(i) as third coordinate, weighted `ratio`^i
/// and normalised by the sum of the weights; with `inflection` each octave is |n|. No
/// octaves give 0. In [−1, 1] ([0, 1] with inflection).
pub fn fractal2d(
    uv: Vec2,
    level_min: f32,
    level_max: f32,
    ratio: f32,
    step: f32,
    inflection: bool,
    z: impl Fn(i32) -> f32,
) -> f32 {
    let lo = level_min.clamp(0.0, MAX_OCTAVES).floor();
    let hi = level_max.clamp(0.0, MAX_OCTAVES);
    let (mut sum, mut norm) = (0.0, 0.0);
    let mut i = lo;
    while i < hi {
        let w = (hi - i).min(1.0) * ratio.powf(i);
        let f = step.powf(i);
        let n = gradient_noise(Vec3A::new(uv.x * f, uv.y * f, z(i as i32)));
        sum += w * if inflection { n.abs() } else { n };
        norm += w;
        i += 1.0;
    }
    if norm > 0.0 {
        sum / norm
    } else {
        0.0
    }
}

maya_shader!(
    /// Maya's fractal: grey v with the same alpha, through the colour balance, where
    /// F = [`fractal2d`] over octaves `levelMin`..`levelMax` (0, 9) with `ratio` (0.707)
    /// and `frequencyRatio` (2), the third coordinate `time` × `timeRatio`^i when
    /// `animated` (else 0), and v = `threshold` + ½ + ½·`amplitude`·F (with
    /// `inflection`: `threshold` + `amplitude`·F), moved by ½·`bias` and clipped to
    /// [0, 1] — the same reading as solidFractal's.
    FRACTAL,
    ADSK_FRACTAL,
    "maya_fractal",
    "adskMayaFractal",
    params2d!(
        "amplitude",
        "threshold",
        "ratio",
        "frequencyRatio",
        "levelMin",
        "levelMax",
        "bias",
        "inflection",
        "animated",
        "time",
        "timeRatio"
    ),
    fractal
);

fn fractal(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = texture_uv(ctx, n) else { return outside(ctx, n, out) };
    let e = EXTRA;
    let (amplitude, threshold, ratio, step) =
        (ctx.scalar(n, e), ctx.scalar(n, e + 1), ctx.scalar(n, e + 2), ctx.scalar(n, e + 3));
    let (level_min, level_max, bias, inflection) =
        (ctx.scalar(n, e + 4), ctx.scalar(n, e + 5), ctx.scalar(n, e + 6), ctx.bool(n, e + 7));
    let (animated, time, time_ratio) = (ctx.bool(n, e + 8), ctx.scalar(n, e + 9), ctx.scalar(n, e + 10));
    let z = |i: i32| if animated { time * time_ratio.powi(i) } else { 0.0 };
    let f = fractal2d(uv, level_min, level_max, ratio, step, inflection, z);
    let v = solid_fractal_value(f, threshold, amplitude, bias, inflection);
    balance(ctx, n, Vec3A::splat(v), v, out)
}

/// The settings of a mountain texture (Maya's attributes; defaults in brackets).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mountain {
    /// `snowColor` (white).
    pub snow: Vec3A,
    /// `rockColor` (0.262, 0.102, 0).
    pub rock: Vec3A,
    /// `amplitude` (1): scales the height about ½.
    pub amplitude: f32,
    /// `snowRoughness` (0.4): the ratio of the snow line's fractal.
    pub snow_roughness: f32,
    /// `rockRoughness` (0.707): the ratio of the height's fractal.
    pub rock_roughness: f32,
    /// `boundary` (1): how far the snow line wanders (± ¼ × boundary in height).
    pub boundary: f32,
    /// `snowAltitude` (0.5): the height of the snow line.
    pub snow_altitude: f32,
    /// `snowDropoff` (2): how suddenly the snow ends below the line.
    pub snow_dropoff: f32,
    /// `snowSlope` (0.8): the steepest slope (height per tile) snow stays on.
    pub snow_slope: f32,
    /// `depthMax` (20): the octaves of both fractals.
    pub depth: f32,
}

/// The offset of the snow line's fractal from the height's (an independent pattern).
const SNOW_SALT: Vec2 = Vec2::new(17.31, 5.77);

impl Mountain {
    /// The height at `uv`: ½ + ½·`amplitude`·F, F the fractal of `depthMax` octaves with
    /// ratio `rockRoughness`, clipped to [0, 1].
    pub fn height(&self, uv: Vec2) -> f32 {
        let f = fractal2d(uv, 0.0, self.depth, self.rock_roughness, 2.0, false, |_| 0.0);
        (0.5 + 0.5 * self.amplitude * f).clamp(0.0, 1.0)
    }

    /// The colour and the height (its alpha) at `uv`. Snow covers a point with the share
    /// s = clamp((h − a)·(1 + 10·`snowDropoff`), 0, 1) of its height h above the snow line
    /// a = `snowAltitude` + ¼·`boundary`·F_s (F_s a fractal of ratio `snowRoughness`:
    /// the ragged boundary), and none where the height's slope |∇h| (per tile, finite
    /// differences) reaches `snowSlope` (Maya: "snow only sticks to the elevated areas
    /// of the texture, and areas where it is not too steep"); colour = rock + (snow −
    /// rock)·s.
    pub fn at(&self, uv: Vec2) -> (Vec3A, f32) {
        let h = self.height(uv);
        const STEP: f32 = 1e-3;
        let grad = Vec2::new(
            self.height(uv + Vec2::X * STEP) - self.height(uv - Vec2::X * STEP),
            self.height(uv + Vec2::Y * STEP) - self.height(uv - Vec2::Y * STEP),
        ) / (2.0 * STEP);
        let line = if self.boundary != 0.0 {
            let f = fractal2d(uv + SNOW_SALT, 0.0, self.depth, self.snow_roughness, 2.0, false, |_| 0.0);
            self.snow_altitude + 0.25 * self.boundary * f
        } else {
            self.snow_altitude
        };
        let share = if grad.length() < self.snow_slope {
            ((h - line) * (1.0 + 10.0 * self.snow_dropoff.max(0.0))).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (self.rock + (self.snow - self.rock) * share, h)
    }
}

maya_shader!(
    /// Maya's mountain ([`Mountain::at`]) through the colour balance: parameters
    /// `snowColor`, `rockColor`, `amplitude`, `snowRoughness`, `rockRoughness`,
    /// `boundary`, `snowAltitude`, `snowDropoff`, `snowSlope`, `depthMax`.
    MOUNTAIN,
    ADSK_MOUNTAIN,
    "maya_mountain",
    "adskMayaMountain",
    params2d!(
        "snowColor",
        "rockColor",
        "amplitude",
        "snowRoughness",
        "rockRoughness",
        "boundary",
        "snowAltitude",
        "snowDropoff",
        "snowSlope",
        "depthMax"
    ),
    mountain
);

fn mountain(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = texture_uv(ctx, n) else { return outside(ctx, n, out) };
    let e = EXTRA;
    let m = Mountain {
        snow: rgb(ctx.color(n, e)),
        rock: rgb(ctx.color(n, e + 1)),
        amplitude: ctx.scalar(n, e + 2),
        snow_roughness: ctx.scalar(n, e + 3),
        rock_roughness: ctx.scalar(n, e + 4),
        boundary: ctx.scalar(n, e + 5),
        snow_altitude: ctx.scalar(n, e + 6),
        snow_dropoff: ctx.scalar(n, e + 7),
        snow_slope: ctx.scalar(n, e + 8),
        depth: ctx.scalar(n, e + 9),
    };
    let (colour, h) = m.at(uv);
    balance(ctx, n, colour, h, out)
}

/// The settings of a water texture (Maya's attributes; defaults in brackets).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Water {
    /// `numberOfWaves` (8): linear waves.
    pub waves: i32,
    /// `waveTime` (0).
    pub wave_time: f32,
    /// `waveVelocity` (1): tiles per unit of wave time.
    pub wave_velocity: f32,
    /// `waveAmplitude` (0.05): the first wave's height.
    pub wave_amplitude: f32,
    /// `waveFrequency` (4): the first wave's cycles per tile.
    pub wave_frequency: f32,
    /// `subWaveFrequency` (0.125): each further wave's frequency step, a share of the first's.
    pub sub_wave_frequency: f32,
    /// `smoothness` (2): how fast the amplitude falls with frequency.
    pub smoothness: f32,
    /// `windU`, `windV` (1, 0): the waves' overall direction.
    pub wind: Vec2,
    /// `rippleTime` (0): ripples appear after 0.
    pub ripple_time: f32,
    /// `rippleFrequency` (25): the ripples' cycles per tile.
    pub ripple_frequency: f32,
    /// `rippleAmplitude` (0.05).
    pub ripple_amplitude: f32,
    /// `dropSize` (0.3): the drop's mass; 0 makes no ripple.
    pub drop_size: f32,
    /// `rippleOriginU`, `rippleOriginV` (0.5, 0.5).
    pub ripple_origin: Vec2,
    /// `groupVelocity` (1): the speed of the rings' envelope.
    pub group_velocity: f32,
    /// `phaseVelocity` (2.5): the speed of the wave under the envelope.
    pub phase_velocity: f32,
    /// `spreadStart` (0.005): the envelope's width at time 0.
    pub spread_start: f32,
    /// `spreadRate` (0.3): its growth per unit of ripple time.
    pub spread_rate: f32,
}

/// The direction turn (radians) and phase of linear wave `k` > 0: hashed, within ±π/4 of
/// the wind and anywhere in the period.
fn wave_spread(k: i32) -> (f32, f32) {
    let h = lattice(k, 0x3a7, 11);
    let a = (h >> 8) as f32 / (1u32 << 24) as f32;
    let p = (lattice(k, 0x3a7, 12) >> 8) as f32 / (1u32 << 24) as f32;
    ((a - 0.5) * std::f32::consts::FRAC_PI_2, p * std::f32::consts::TAU)
}

impl Water {
    /// The height at `uv`, ½ + W + R clipped to [0, 1]:
    /// - W = Σ_{k<N} a_k cos(2π f_k (d_k·uv − `waveVelocity`·`waveTime`) + φ_k), the
    ///   linear waves: f_k = `waveFrequency`·(1 + k·`subWaveFrequency`), a_k =
    ///   `waveAmplitude`·(1 + k·`subWaveFrequency`)^−`smoothness`, d_k the wind's
    ///   direction (+u without wind) turned by a hashed angle within ±45° and φ_k a hashed
    ///   phase, both 0 for the first wave;
    /// - R = `rippleAmplitude`·(`dropSize`/0.3)·exp(−½((r − r₀)/σ)²)·cos(2π
    ///   `rippleFrequency` (r − `phaseVelocity`·t)), the concentric ripple at distance r
    ///   from `rippleOrigin`: its envelope's radius r₀ = `groupVelocity`·t and width σ =
    ///   `spreadStart` + `spreadRate`·t at t = `rippleTime`, none for t ≤ 0 (the drop has
    ///   not touched the water).
    ///
    /// The attributes and their meaning are Maya's (and Alias's, whose water texture Maya
    /// took over: "frequency increment for successive waves", "rate of dropoff of
    /// amplitude with frequency", "envelope velocity", "velocity of modulated sinewave");
    /// the formulas are mira's. `fast` and the reflection box are not read.
    pub fn height(&self, uv: Vec2) -> f32 {
        let wind = self.wind.try_normalize().unwrap_or(Vec2::X);
        let mut h = 0.5;
        for k in 0..self.waves.clamp(0, 100) {
            let step = 1.0 + k as f32 * self.sub_wave_frequency;
            let (turn, phase) = if k == 0 { (0.0, 0.0) } else { wave_spread(k) };
            let d = Vec2::from_angle(turn).rotate(wind);
            let f = self.wave_frequency * step;
            let x = d.dot(uv) - self.wave_velocity * self.wave_time;
            h += self.wave_amplitude * step.powf(-self.smoothness) * (std::f32::consts::TAU * f * x + phase).cos();
        }
        let t = self.ripple_time;
        if t > 0.0 && self.drop_size > 0.0 && self.ripple_amplitude != 0.0 {
            let r = (uv - self.ripple_origin).length();
            let sigma = (self.spread_start + self.spread_rate * t).max(1e-6);
            let envelope = (-0.5 * ((r - self.group_velocity * t) / sigma).powi(2)).exp();
            let carrier = (std::f32::consts::TAU * self.ripple_frequency * (r - self.phase_velocity * t)).cos();
            h += self.ripple_amplitude * (self.drop_size / 0.3) * envelope * carrier;
        }
        h.clamp(0.0, 1.0)
    }
}

maya_shader!(
    /// Maya's water: grey [`Water::height`] with the same alpha, through the colour
    /// balance.
    WATER,
    ADSK_WATER,
    "maya_water",
    "adskMayaWater",
    params2d!(
        "numberOfWaves",
        "waveTime",
        "waveVelocity",
        "waveAmplitude",
        "waveFrequency",
        "subWaveFrequency",
        "smoothness",
        "windU",
        "windV",
        "rippleTime",
        "rippleFrequency",
        "rippleAmplitude",
        "dropSize",
        "rippleOriginU",
        "rippleOriginV",
        "groupVelocity",
        "phaseVelocity",
        "spreadStart",
        "spreadRate"
    ),
    water
);

fn water(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(uv) = texture_uv(ctx, n) else { return outside(ctx, n, out) };
    let e = EXTRA;
    let s = |ctx: &mut Ctx, i: usize| ctx.scalar(n, e + i);
    let w = Water {
        waves: ctx.int(n, e),
        wave_time: s(ctx, 1),
        wave_velocity: s(ctx, 2),
        wave_amplitude: s(ctx, 3),
        wave_frequency: s(ctx, 4),
        sub_wave_frequency: s(ctx, 5),
        smoothness: s(ctx, 6),
        wind: Vec2::new(s(ctx, 7), s(ctx, 8)),
        ripple_time: s(ctx, 9),
        ripple_frequency: s(ctx, 10),
        ripple_amplitude: s(ctx, 11),
        drop_size: s(ctx, 12),
        ripple_origin: Vec2::new(s(ctx, 13), s(ctx, 14)),
        group_velocity: s(ctx, 15),
        phase_velocity: s(ctx, 16),
        spread_start: s(ctx, 17),
        spread_rate: s(ctx, 18),
    };
    let h = w.height(uv);
    balance(ctx, n, Vec3A::splat(h), h, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fractal_is_zero_on_the_lattice_normalised_and_stops_at_its_levels() {
        let flat = |_| 0.0;
        // Every octave's lattice holds the tile's corners: 0 there.
        assert_eq!(fractal2d(Vec2::ZERO, 0.0, 9.0, 0.707, 2.0, false, flat), 0.0);
        assert_eq!(fractal2d(Vec2::new(0.3, 0.7), 4.0, 4.0, 0.707, 2.0, false, flat), 0.0);
        let mut spread = (1.0f32, -1.0f32);
        for i in 0..200 {
            let uv = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 * 0.414_213).fract());
            let f = fractal2d(uv, 0.0, 9.0, 0.707, 2.0, false, flat);
            assert!((-1.0..=1.0).contains(&f));
            assert!((0.0..=1.0).contains(&fractal2d(uv, 0.0, 9.0, 0.707, 2.0, true, flat)));
            spread = (spread.0.min(f), spread.1.max(f));
            // Level min above 0 leaves the coarse octaves out.
            let fine = fractal2d(uv, 3.0, 9.0, 0.707, 2.0, false, flat);
            assert!((-1.0..=1.0).contains(&fine));
        }
        assert!(spread.1 - spread.0 > 0.3, "{spread:?}");
        // Time moves an animated fractal.
        let uv = Vec2::new(0.3, 0.6);
        let a = fractal2d(uv, 0.0, 4.0, 0.707, 2.0, false, |_| 0.0);
        let b = fractal2d(uv, 0.0, 4.0, 0.707, 2.0, false, |i| 0.4 * 2f32.powi(i));
        assert!((a - b).abs() > 1e-4);
    }

    fn mountain() -> Mountain {
        Mountain {
            snow: Vec3A::ONE,
            rock: Vec3A::new(0.262, 0.102, 0.0),
            amplitude: 1.0,
            snow_roughness: 0.4,
            rock_roughness: 0.707,
            boundary: 1.0,
            snow_altitude: 0.5,
            snow_dropoff: 2.0,
            snow_slope: 0.8,
            depth: 20.0,
        }
    }

    #[test]
    fn mountain_snow_lies_above_its_altitude_where_flat_enough() {
        // Amplitude 0: level ground at height ½.
        let flat = Mountain { amplitude: 0.0, boundary: 0.0, ..mountain() };
        let uv = Vec2::new(0.3, 0.6);
        let at = |m: Mountain| m.at(uv);
        let near = |a: Vec3A, b: Vec3A| (a - b).abs().max_element() < 1e-5;
        let (c, h) = at(Mountain { snow_altitude: 0.3, ..flat });
        assert!(near(c, Vec3A::ONE) && h == 0.5, "{c} {h}");
        assert_eq!(at(Mountain { snow_altitude: 0.7, ..flat }).0, flat.rock);
        // 0.02 above the line with dropoff 2: share 0.02 × 21.
        let (c, _) = at(Mountain { snow_altitude: 0.48, ..flat });
        let want = flat.rock + (Vec3A::ONE - flat.rock) * 0.42;
        assert!((c - want).abs().max_element() < 1e-5, "{c}");
        // No slope is gentle enough for a snow slope of 0.
        assert_eq!(at(Mountain { snow_altitude: 0.3, snow_slope: 0.0, ..flat }).0, flat.rock);
        // Defaults: heights in range and colours between rock and snow; both appear.
        let m = mountain();
        let (mut snow, mut rock) = (0, 0);
        for i in 0..400 {
            let uv = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 * 0.414_213).fract());
            let (c, h) = Mountain { depth: 6.0, snow_altitude: 0.45, snow_slope: 1e3, ..m }.at(uv);
            assert!((0.0..=1.0).contains(&h));
            assert!(c.cmpge(m.rock - 1e-6).all() && c.cmple(Vec3A::ONE + 1e-6).all(), "{c}");
            snow += near(c, Vec3A::ONE) as u32;
            rock += near(c, m.rock) as u32;
        }
        assert!(snow > 0 && rock > 0, "{snow} {rock}");
    }

    fn calm() -> Water {
        Water {
            waves: 0,
            wave_time: 0.0,
            wave_velocity: 1.0,
            wave_amplitude: 0.1,
            wave_frequency: 4.0,
            sub_wave_frequency: 0.125,
            smoothness: 2.0,
            wind: Vec2::X,
            ripple_time: 0.0,
            ripple_frequency: 25.0,
            ripple_amplitude: 0.05,
            drop_size: 0.3,
            ripple_origin: Vec2::splat(0.5),
            group_velocity: 1.0,
            phase_velocity: 0.0,
            spread_start: 0.005,
            spread_rate: 0.3,
        }
    }

    #[test]
    fn water_waves_and_ripples_follow_their_formulas() {
        let close = |a: f32, b: f32| assert!((a - b).abs() < 1e-5, "{a} vs {b}");
        // No waves and no ripple yet: still water at ½.
        for uv in [Vec2::ZERO, Vec2::new(0.3, 0.8), Vec2::splat(0.5)] {
            close(calm().height(uv), 0.5);
        }
        // One wave along +u: ½ + 0.1 cos(2π·4·u).
        let one = Water { waves: 1, ..calm() };
        close(one.height(Vec2::new(0.0, 0.3)), 0.6);
        close(one.height(Vec2::new(0.0625, 0.9)), 0.5);
        close(one.height(Vec2::new(0.125, 0.1)), 0.4);
        // A quarter of wave time at velocity 1 is a whole period at frequency 4.
        close(Water { wave_time: 0.25, ..one }.height(Vec2::new(0.0, 0.3)), 0.6);
        close(Water { wave_time: 0.125, ..one }.height(Vec2::new(0.0, 0.3)), 0.4);
        // Wind along +v turns the wave.
        close(Water { wind: Vec2::new(0.0, 2.0), ..one }.height(Vec2::new(0.3, 0.125)), 0.4);
        // A ripple at t = 0.2: the ring at r = 0.2 peaks at ½ + 0.05 (cos(2π·25·0.2) = 1),
        // far from it the water is still; a drop of size 0 makes none.
        let ripple = Water { ripple_time: 0.2, ..calm() };
        close(ripple.height(Vec2::new(0.7, 0.5)), 0.55);
        close(ripple.height(Vec2::new(0.5, 1.0 - 1e-6)), 0.5);
        close(Water { drop_size: 0.0, ..ripple }.height(Vec2::new(0.7, 0.5)), 0.5);
        // Eight default waves stay in range.
        let eight = Water { waves: 8, wave_amplitude: 0.05, ..calm() };
        let mut spread = (1.0f32, 0.0f32);
        for i in 0..100 {
            let h = eight.height(Vec2::new(i as f32 * 0.01, 0.37));
            spread = (spread.0.min(h), spread.1.max(h));
        }
        assert!(spread.0 >= 0.0 && spread.1 <= 1.0 && spread.1 - spread.0 > 0.05, "{spread:?}");
    }
}
