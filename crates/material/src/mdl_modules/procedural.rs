//! The procedural patterns of MDL's `::base` module as pure functions of a texture-space
//! position: the checker, gradient noise (`perlin_noise_texture`), cellular noise
//! (`worley_noise_texture`), flow noise, flakes, the three-colour gradient and the tile
//! pattern ([`super::tiles`]), plus the height of an image (`file_bump_texture`).
//!
//! The structure of each pattern (what the parameters do: octaves, marble, dents, bands,
//! thresholds, Worley's modes and metrics, the gradient's modes and interpolations) follows
//! the published behaviour of the MDL SDK's `base.mdl`; the noise and hash functions are
//! mira's own, so values are not NVIDIA's bit for bit, but they have the same properties
//! (gradient noise is 0 on the integer lattice and within [−1, 1]; Worley's features are
//! one per unit cell; flakes are constant per cell).

use glam::{Vec3A, Vec4};

use super::hit::Image;
use super::tiles::Tiling;

/// The modifications shared by the noise textures (`apply_marble`, `apply_dent`,
/// `noise_bands`, `noise_threshold_low/high`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoiseShaping {
    /// `apply_marble`: cos(x + 5·value).
    pub marble: bool,
    /// `apply_dent`: value³.
    pub dent: bool,
    /// `noise_bands`: stripes of the fraction of value·bands (1: none).
    pub bands: f32,
    /// `noise_threshold_low`.
    pub low: f32,
    /// `noise_threshold_high` (rescaled and clamped between low and high when low < high).
    pub high: f32,
}

impl NoiseShaping {
    /// `value` shaped; `x` is the scaled position's x (the marble's phase).
    pub fn apply(&self, value: f32, x: f32) -> f32 {
        let mut r = value;
        if self.marble {
            r = (x + r * 5.0).cos();
        }
        if self.dent {
            r = r * r * r;
        }
        if self.bands != 1.0 {
            r *= self.bands;
            r -= r.floor();
            r += (1.0 - r).powf(20.0);
        }
        if self.low < self.high {
            r = ((r - self.low) / (self.high - self.low)).clamp(0.0, 1.0);
        }
        r
    }
}

/// A procedural pattern. [`Pattern::eval`] gives its value at a texture-space position:
/// a number in all four lanes (the blend between `color1` and `color2`, or a height), or,
/// for the gradient, the colour.
#[derive(Clone, Debug, PartialEq)]
pub enum Pattern {
    /// `checker_texture`: 1 in `color1`'s cells, 0 in `color2`'s, blended within `blur` of
    /// an edge (0.5 on it).
    Checker {
        /// `blur`.
        blur: f32,
        /// `checker_position`.
        position: f32,
    },
    /// `perlin_noise_texture`: summed gradient noise of the position / `size`.
    Perlin {
        /// `size`.
        size: f32,
        /// `noise_phase` (the fourth noise coordinate).
        phase: f32,
        /// `noise_levels` (octaves).
        levels: u32,
        /// `absolute_noise`.
        absolute: bool,
        /// `ridged_noise`.
        ridged: bool,
        /// `noise_distortion`.
        distortion: Vec3A,
        /// The shared modifications.
        shaping: NoiseShaping,
    },
    /// `worley_noise_texture`: cellular noise of the position / `size`.
    Worley {
        /// `size`.
        size: f32,
        /// `mode` (0–11, see [`worley_mode`]).
        mode: i32,
        /// `metric`: 0 Euclidean, 1 Manhattan, 2 Chebyshev.
        metric: i32,
        /// `noise_distortion`.
        distortion: Vec3A,
        /// `step_threshold`.
        step_threshold: f32,
        /// The shared modifications.
        shaping: NoiseShaping,
    },
    /// `flow_noise_texture`: octaves of 2D gradient noise whose gradients turn with
    /// `phase`, of the position's (u, v) / `size`.
    Flow {
        /// `size`.
        size: f32,
        /// `phase` (one turn of every gradient per unit).
        phase: f32,
        /// `levels`.
        levels: u32,
        /// `absolute_noise`.
        absolute: bool,
        /// `level_gain`: each octave's weight relative to the one before.
        gain: f32,
        /// `level_scale`: each octave's frequency relative to the one before.
        scale: f32,
        /// `level_progressive_u_scale`: u's extra frequency factor per octave.
        u_scale: f32,
        /// `level_progressive_v_motion`: v's shift per octave.
        v_motion: f32,
    },
    /// `flake_noise_texture`: a reflectivity constant per flake (`intensity` ·
    /// r^(1/`density`) for a random r per flake).
    Flake {
        /// `intensity`.
        intensity: f32,
        /// `scale`: the flakes' size in texture units.
        scale: f32,
        /// `density`.
        density: f32,
        /// `noise_type`: 0 displaced cubes, 1 Worley cells.
        cells: bool,
        /// `maximum_size`: Worley flakes farther than this from their centre are black.
        maximum_size: f32,
        /// `metric` of the Worley cells.
        metric: i32,
    },
    /// `gradient3_texture`: the colour of `position` (by `mode`) on a three-stop gradient.
    Gradient {
        /// `mode` (0–7, `gradient_mode`).
        mode: i32,
        /// `gradient_positions`.
        positions: [f32; 3],
        /// `gradient_colors`.
        colors: [Vec3A; 3],
        /// `interpolation_modes` of the two spans (the third is not used).
        interpolation: [i32; 3],
        /// `distortion`, added to the position.
        distortion: f32,
    },
    /// `gradient3_recolor`: the colour of the number in the position's x on a three-stop
    /// gradient.
    Recolor {
        /// `gradient_positions`.
        positions: [f32; 3],
        /// `gradient_colors`.
        colors: [Vec3A; 3],
        /// `interpolation_modes` of the two spans (the third is not used).
        interpolation: [i32; 3],
    },
    /// `flake_noise_bump_texture`'s random unit vector of the flake at the position /
    /// `scale` (in x, y, z).
    FlakeDirection {
        /// `scale`.
        scale: f32,
        /// `noise_type` 1 (Worley cells), else displaced cubes.
        cells: bool,
        /// `metric` of the cells.
        metric: i32,
    },
    /// The tile pattern of `tile_texture` and `tile_bump_texture` ([`Tiling::eval`]: its
    /// height, whether on a tile, the tile's brightness variation).
    Tiles(Tiling),
    /// The mean of another pattern's first three lanes in all four (the height of a colour
    /// pattern: `gradient3_bump_texture`'s).
    Mean(Box<Pattern>),
    /// An image's height (`file_bump_texture`): its texel by a `mono_mode` (by name).
    ImageHeight {
        /// The image.
        image: Image,
        /// `wrap_u`, `wrap_v` by enumerator name.
        wrap: [&'static str; 2],
        /// `clip`.
        clip: bool,
        /// `bump_source` by enumerator name.
        mono: &'static str,
    },
}

impl Pattern {
    /// The value at texture-space position `p`.
    pub fn eval(&self, p: Vec3A) -> Vec4 {
        match self {
            Pattern::Checker { blur, position } => Vec4::splat(checker(p, *blur, *position)),
            Pattern::Perlin { size, phase, levels, absolute, ridged, distortion, shaping } => {
                let q = p / *size;
                Vec4::splat(shaping.apply(summed_perlin(q, *phase, *levels, *distortion, *absolute, *ridged), q.x))
            }
            Pattern::Worley { size, mode, metric, distortion, step_threshold, shaping } => {
                let q = p / *size;
                let mut v = worley_mode(&worley(q, *metric), *mode, *step_threshold);
                if *distortion != Vec3A::ZERO {
                    v = (q.dot(*distortion) + v).sin();
                }
                Vec4::splat(shaping.apply(v, q.x))
            }
            Pattern::Flow { size, phase, levels, absolute, gain, scale, u_scale, v_motion } => {
                let (u, v) = (p.x / size, p.y / size);
                Vec4::splat(flow(u, v, *phase, *levels, *absolute, *gain, *scale, *u_scale, *v_motion))
            }
            Pattern::Flake { intensity, scale, density, cells, maximum_size, metric } => {
                Vec4::splat(flake(p / *scale, *intensity, *density, *cells, *maximum_size, *metric))
            }
            Pattern::FlakeDirection { scale, cells, metric } => {
                flake_direction(p / *scale, *cells, *metric).extend(0.0)
            }
            Pattern::Gradient { mode, positions, colors, interpolation, distortion } => {
                let t = gradient_position(*mode, p.x, p.y);
                recolor(t, *distortion, positions, colors, interpolation).extend(0.0)
            }
            Pattern::Recolor { positions, colors, interpolation } => {
                recolor(p.x, 0.0, positions, colors, interpolation).extend(0.0)
            }
            Pattern::Tiles(t) => t.eval(p),
            Pattern::Mean(inner) => {
                let c = inner.eval(p);
                Vec4::splat((c.x + c.y + c.z) / 3.0)
            }
            Pattern::ImageHeight { image, wrap, clip, mono } => {
                let texel = image_texel(image, p, *wrap, *clip).unwrap_or(Vec4::ZERO);
                Vec4::splat(mdl::texture::mono(texel, mono))
            }
        }
    }
}

/// The RGBA texel of `image` at `p`'s (u, v) with MDL's wrap modes; `None` where clipped.
pub fn image_texel(image: &Image, p: Vec3A, wrap: [&str; 2], clip: bool) -> Option<Vec4> {
    if clip && !((0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y)) {
        return None;
    }
    let u = mdl::texture::wrap(p.x, wrap[0])?;
    let v = mdl::texture::wrap(p.y, wrap[1])?;
    image.0.lookup(Vec3A::new(u, v, 0.0), 0.0)
}

/// A 32-bit integer hash (an avalanche mix of the bits).
fn hash(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// The hash of a lattice point.
fn hash4(i: [i32; 4]) -> u32 {
    let mut h = 0x9e37_79b9u32;
    for c in i {
        h = hash(h ^ (c as u32).wrapping_mul(0x2c1b_3c6d));
    }
    h
}

/// A number in [0, 1) from a hash.
fn unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Perlin's quintic fade, 6t⁵ − 15t⁴ + 10t³.
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// The gradient of a 4D lattice corner (one of the 32 vectors with one zero coordinate
/// and ±1 in the others) dotted with the offset `d`.
fn grad4(h: u32, d: [f32; 4]) -> f32 {
    let h = h >> 11;
    let zero = (h & 3) as usize;
    let mut sum = 0.0;
    let mut bit = 4;
    for (k, x) in d.iter().enumerate() {
        if k == zero {
            continue;
        }
        sum += if h & bit != 0 { -x } else { *x };
        bit <<= 1;
    }
    sum
}

/// Gradient noise of a 4D point: 0 on the integer lattice, within about [−1, 1].
pub fn perlin4(p: [f32; 4]) -> f32 {
    let cell = p.map(|x| x.floor());
    let f: [f32; 4] = std::array::from_fn(|k| p[k] - cell[k]);
    let i = cell.map(|x| x as i32);
    let w = f.map(fade);
    let mut corners = [0.0f32; 16];
    for (c, value) in corners.iter_mut().enumerate() {
        let bit = |k: usize| ((c >> k) & 1) as i32;
        let corner = std::array::from_fn(|k| i[k].wrapping_add(bit(k)));
        let d = std::array::from_fn(|k| f[k] - bit(k) as f32);
        *value = grad4(hash4(corner), d);
    }
    // Interpolate along x, then y, z, w.
    let mut n = 16;
    for wk in w {
        n /= 2;
        for c in 0..n {
            corners[c] = corners[2 * c] + wk * (corners[2 * c + 1] - corners[2 * c]);
        }
    }
    // The 4D gradients' largest possible value is about 1.5 (three unit components).
    (corners[0] * (2.0 / 3.0)).clamp(-1.0, 1.0)
}

/// Octaves of gradient noise (frequency doubling, weight halving), as
/// `perlin_noise_texture` sums them: ridged octaves (1 − |n|)² weighted by the previous
/// one, or |n|, or plain noise mapped to [0, 1]; a distortion adds sin(p · distortion).
pub fn summed_perlin(p: Vec3A, phase: f32, levels: u32, distortion: Vec3A, absolute: bool, ridged: bool) -> f32 {
    let mut sum = 0.0;
    let mut weight = if ridged { 0.625 } else { 1.0 };
    let mut previous = 1.0;
    let mut q = [p.x, p.y, p.z, phase];
    for _ in 0..levels.min(32) {
        let n = perlin4(q);
        let n = if ridged {
            (1.0 - n.abs()).powi(2)
        } else if absolute {
            n.abs()
        } else {
            n
        };
        sum += weight * previous * n;
        q = q.map(|x| x * 2.0);
        weight *= 0.5;
        if ridged {
            previous = n;
        }
    }
    if distortion != Vec3A::ZERO {
        sum = (p.dot(distortion) + sum).sin();
    }
    if !absolute && !ridged {
        sum = 0.5 * sum + 0.5;
    }
    sum
}

/// The two nearest feature points of a cellular pattern (one per unit cell) and their
/// distances by `metric` (0 Euclidean, 1 Manhattan, 2 Chebyshev).
#[derive(Clone, Copy, Debug)]
pub struct Cells {
    /// The distances to the nearest and second nearest features.
    pub f: [f32; 2],
    /// The nearest and second nearest features.
    pub nearest: [Vec3A; 2],
}

/// The feature point of unit cell `c` (inside it).
fn feature(c: [i32; 3]) -> Vec3A {
    let h = hash4([c[0], c[1], c[2], 0x51ed]);
    let (a, b) = (hash(h ^ 0x68e3_1da4), hash(h ^ 0xb5297a4d));
    Vec3A::new(c[0] as f32, c[1] as f32, c[2] as f32) + Vec3A::new(unit(h), unit(a), unit(b))
}

/// The cellular pattern at `p`.
pub fn worley(p: Vec3A, metric: i32) -> Cells {
    let base = p.floor();
    let mut out = Cells { f: [f32::MAX; 2], nearest: [Vec3A::ZERO; 2] };
    for dx in -1..=1 {
        for dy in -1..=1 {
            for dz in -1..=1 {
                let c = [base.x as i32 + dx, base.y as i32 + dy, base.z as i32 + dz];
                let q = feature(c);
                let d = q - p;
                let dist = match metric {
                    1 => d.abs().element_sum(),
                    2 => d.abs().max_element(),
                    _ => d.length(),
                };
                if dist < out.f[0] {
                    out.f[1] = out.f[0];
                    out.nearest[1] = out.nearest[0];
                    out.f[0] = dist;
                    out.nearest[0] = q;
                } else if dist < out.f[1] {
                    out.f[1] = dist;
                    out.nearest[1] = q;
                }
            }
        }
    }
    out
}

/// The number `worley_noise_texture`'s `mode` makes of the cells: 0 F1, 1 F1², 8 F2,
/// 9 F2², 2 a random value per cell, 3 a hard step of F2 − F1 at `step`, 4 F2 − F1,
/// 5 (F2 − F1)/(F2 + F1), 6 F1·F2, 7 F1 + F2, 10/11 the Manhattan/Chebyshev distance
/// between the two nearest features.
pub fn worley_mode(c: &Cells, mode: i32, step: f32) -> f32 {
    let [f1, f2] = c.f;
    match mode {
        1 => f1 * f1,
        8 => f2,
        9 => f2 * f2,
        2 => {
            let n = c.nearest[0].floor();
            unit(hash4([n.x as i32, n.y as i32, n.z as i32, 0x7a3]))
        }
        3 => {
            if f2 - f1 < step {
                0.0
            } else {
                1.0
            }
        }
        4 => f2 - f1,
        5 => (f2 - f1) / (f2 + f1),
        6 => f1 * f2,
        7 => f1 + f2,
        10 => (c.nearest[1] - c.nearest[0]).abs().element_sum(),
        11 => (c.nearest[1] - c.nearest[0]).abs().max_element(),
        _ => f1,
    }
}

/// 2D gradient noise whose lattice gradients turn by `phase` turns (each corner in its
/// own direction of rotation): 0 on the lattice, within [−1, 1].
fn flow2(x: f32, y: f32, phase: f32) -> f32 {
    let (cx, cy) = (x.floor(), y.floor());
    let (fx, fy) = (x - cx, y - cy);
    let (ix, iy) = (cx as i32, cy as i32);
    let corner = |dx: i32, dy: i32| {
        let h = hash4([ix.wrapping_add(dx), iy.wrapping_add(dy), 0x3f1, 0]);
        let spin = if h & 1 == 0 { 1.0 } else { -1.0 };
        let angle = std::f32::consts::TAU * (unit(h) + spin * phase);
        let (s, c) = angle.sin_cos();
        c * (fx - dx as f32) + s * (fy - dy as f32)
    };
    let (wx, wy) = (fade(fx), fade(fy));
    let bottom = corner(0, 0) + wx * (corner(1, 0) - corner(0, 0));
    let top = corner(0, 1) + wx * (corner(1, 1) - corner(0, 1));
    // A unit gradient's largest value on the unit square is √2/2.
    ((bottom + wy * (top - bottom)) * std::f32::consts::SQRT_2).clamp(-1.0, 1.0)
}

/// `flow_noise_texture`'s value: octaves of `flow2`, each `gain` times the weight and
/// `scale` times the frequency of the one before, u stretched by `u_scale` and v shifted
/// by `v_motion` more per octave; |sum| when `absolute`, else mapped to [0, 1].
#[allow(clippy::too_many_arguments)]
pub fn flow(
    u: f32,
    v: f32,
    phase: f32,
    levels: u32,
    absolute: bool,
    gain: f32,
    scale: f32,
    u_scale: f32,
    v_motion: f32,
) -> f32 {
    let (mut sum, mut weight, mut total) = (0.0, 1.0, 0.0);
    let (mut fu, mut fv) = (1.0, 1.0);
    for level in 0..levels.clamp(1, 32) {
        let n = flow2(u * fu, v * fv + v_motion * level as f32, phase);
        sum += weight * if absolute { n.abs() } else { n };
        total += weight;
        weight *= gain;
        fu *= scale * u_scale;
        fv *= scale;
    }
    let mean = if total > 0.0 { sum / total } else { 0.0 };
    if absolute {
        mean
    } else {
        0.5 * mean + 0.5
    }
}

/// `flake_noise_texture`'s reflectivity at the scaled position `p`.
pub fn flake(p: Vec3A, intensity: f32, density: f32, cells: bool, maximum_size: f32, metric: i32) -> f32 {
    let (cell, distance) = if cells {
        let c = worley(p, metric);
        (c.nearest[0].floor(), c.f[0])
    } else {
        // Cubes of a displaced space: flake edges wander, each flake is one value.
        let n = |o: f32| perlin4([p.x + o, p.y - o, p.z + 0.5 * o, 0.0]);
        ((p + 2.0 * Vec3A::new(n(17.3), n(41.9), n(73.1))).floor(), 0.0)
    };
    if cells && maximum_size < distance {
        return 0.0;
    }
    let r = unit(hash4([cell.x as i32, cell.y as i32, cell.z as i32, 0x0f1a]));
    r.powf(1.0 / density.max(1e-6)) * intensity
}

/// A random unit vector per flake (the cell `flake` picks its value from), for
/// `flake_noise_bump_texture`.
pub fn flake_direction(p: Vec3A, cells: bool, metric: i32) -> Vec3A {
    let cell = if cells {
        worley(p, metric).nearest[0].floor()
    } else {
        let n = |o: f32| perlin4([p.x + o, p.y - o, p.z + 0.5 * o, 0.0]);
        (p + 2.0 * Vec3A::new(n(17.3), n(41.9), n(73.1))).floor()
    };
    let h = hash4([cell.x as i32, cell.y as i32, cell.z as i32, 0x0d1e]);
    let z = 2.0 * unit(h) - 1.0;
    let phi = std::f32::consts::TAU * unit(hash(h));
    let r = (1.0 - z * z).max(0.0).sqrt();
    Vec3A::new(r * phi.cos(), r * phi.sin(), z)
}

/// `gradient_mode`'s position in [0, 1] of the fraction of (u, v).
pub fn gradient_position(mode: i32, u: f32, v: f32) -> f32 {
    let (x, y) = (u - u.floor(), v - v.floor());
    match mode {
        1 => x * x,
        2 => 2.0 * (x - 0.5).abs().max((y - 0.5).abs()),
        3 => std::f32::consts::SQRT_2 * (x - y).abs(),
        4 => {
            if y < x {
                1.0 - 0.5 * (y / x)
            } else if x < y {
                0.5 * (x / y)
            } else {
                0.5
            }
        }
        5 => {
            if y < x {
                y / x
            } else if x < y {
                x / y
            } else {
                1.0
            }
        }
        6 => 2.0 * (x - 0.5).hypot(y - 0.5),
        7 => {
            let (dx, dy) = (x - 0.5, y - 0.5);
            let r = dx.hypot(dy);
            let a = if r > 0.0 { (dy / r).clamp(-1.0, 1.0).acos() * 0.5 / std::f32::consts::PI } else { 0.0 };
            if dx < 0.0 {
                a
            } else {
                1.0 - a
            }
        }
        _ => x,
    }
}

/// `gradient_interpolation_mode`'s easing of t in [0, 1].
fn ease(mode: i32, t: f32) -> f32 {
    const P: f32 = 2.0 / 3.0;
    match mode {
        1 => 0.0,
        2 => 1.0 - (1.0 - t).powf(P),
        3 => t.powf(P),
        4 => {
            if t <= 0.5 {
                0.5 * (2.0 * t).powf(P)
            } else {
                0.5 + 0.5 * (1.0 - (2.0 * (1.0 - t)).powf(P))
            }
        }
        _ => t,
    }
}

/// The colour of `position` + `distortion` on the three-stop gradient.
pub fn recolor(position: f32, distortion: f32, at: &[f32; 3], colors: &[Vec3A; 3], modes: &[i32; 3]) -> Vec3A {
    let p = position + distortion;
    if p <= at[0] {
        return colors[0];
    }
    if at[2] <= p {
        return colors[2];
    }
    let i = if p < at[1] { 0 } else { 1 };
    let span = at[i + 1] - at[i];
    let t = if span > 0.0 { ease(modes[i], (p - at[i]) / span) } else { 1.0 };
    colors[i].lerp(colors[i + 1], t)
}

/// `checker_texture`'s blend weight of `color1` at `p`: a 3D checker of cells split at
/// `position` in each axis (an odd number of axes below it is `color1`), blurred linearly
/// within `blur` of an edge in u or v (0.5 on the edge).
pub fn checker(p: Vec3A, blur: f32, position: f32) -> f32 {
    let t = p - p.floor();
    let rel = t - Vec3A::splat(position);
    let below = (rel.x < 0.0) as u8 + (rel.y < 0.0) as u8 + (rel.z < 0.0) as u8;
    let one = below % 2 == 1;
    let edge = t.min(Vec3A::ONE - t).min(rel.abs());
    let mut amount = 1.0;
    // Blurred along u and v only: texture spaces are mostly flat (z = 0, on an edge in z).
    for e in [edge.x, edge.y] {
        if e < blur {
            amount *= e / blur;
        }
    }
    amount *= 0.5;
    if one {
        0.5 + amount
    } else {
        0.5 - amount
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gradient_noise_is_zero_on_the_lattice_and_bounded() {
        for i in -3..3 {
            assert_eq!(perlin4([i as f32, 2.0, -5.0, 1.0]), 0.0);
        }
        let mut spread = (f32::MAX, f32::MIN);
        for k in 0..4000 {
            let x = k as f32 * 0.0137;
            let n = perlin4([x, x * 1.7 + 0.3, x * 0.31, 0.25]);
            assert!((-1.0..=1.0).contains(&n));
            spread = (spread.0.min(n), spread.1.max(n));
        }
        // It varies: both signs, an amplitude of a noise.
        assert!(spread.0 < -0.2 && spread.1 > 0.2, "{spread:?}");
        // Continuous: a small step is a small change.
        let a = perlin4([0.3, 0.4, 0.5, 0.0]);
        let b = perlin4([0.3001, 0.4, 0.5, 0.0]);
        assert!((a - b).abs() < 1e-3);
    }

    #[test]
    fn worley_features_are_one_per_cell() {
        // A feature point is at distance 0 from itself and lies in its cell.
        let f = feature([2, -1, 0]);
        assert!(f.floor() == Vec3A::new(2.0, -1.0, 0.0));
        let c = worley(f, 0);
        assert!(c.f[0] < 1e-6 && c.f[1] > c.f[0]);
        // F1 is at most the distance to the cell's own feature (√3 in a unit cell).
        for k in 0..200 {
            let p = Vec3A::new(k as f32 * 0.173, k as f32 * 0.071, 0.4);
            let c = worley(p, 0);
            assert!(c.f[0] <= c.f[1] && c.f[0] <= 3f32.sqrt());
        }
    }

    #[test]
    fn checker_cells_and_blur() {
        // z = 0 is below 0.5 in z: (0.75, 0.75) has one axis below → color1.
        assert_eq!(checker(Vec3A::new(0.75, 0.75, 0.0), 0.0, 0.5), 1.0);
        assert_eq!(checker(Vec3A::new(0.25, 0.75, 0.0), 0.0, 0.5), 0.0);
        assert_eq!(checker(Vec3A::new(1.25, 1.25, 0.0), 0.0, 0.5), 1.0);
    }

    #[test]
    fn gradients_and_easings_at_their_ends() {
        let colors = [Vec3A::ZERO, Vec3A::splat(0.5), Vec3A::ONE];
        let at = [0.0, 0.5, 1.0];
        assert_eq!(recolor(0.25, 0.0, &at, &colors, &[0; 3]), Vec3A::splat(0.25));
        assert_eq!(recolor(0.25, 0.0, &at, &colors, &[1; 3]), Vec3A::ZERO);
        assert_eq!(recolor(2.0, 0.0, &at, &colors, &[0; 3]), Vec3A::ONE);
        for m in 0..5 {
            assert!((ease(m, 1.0) - if m == 1 { 0.0 } else { 1.0 }).abs() < 1e-6);
        }
        assert!((gradient_position(2, 0.5, 0.5)).abs() < 1e-6);
        assert!((gradient_position(6, 1.0 - 1e-7, 0.5) - 1.0).abs() < 1e-4);
    }
}
