//! Maya's crater and stucco 3D textures: colours mixed by "shaken" noise, and an
//! `outNormal` that bumps the surface into plateaus and craters.
//!
//! Both share the 3D textures' placement, `wrap` and colour balance
//! ([`crate::texture3d`]). Maya's node reference gives their attributes, defaults and
//! what each does, not formulas; the formulas below are mira's reading of those
//! descriptions, the noise mira's gradient noise ([`crate::noise::gradient_noise`], g
//! below, in [−1, 1]), not Maya's pattern. p is the point in placement space.
//!
//! - crater: `shaker` s (1.5: how "shaken up", perturbed, the texture is), `channel1`
//!   (red), `channel2` (green), `channel3` (blue: the three colours it mixes), `melt` m
//!   (0: the softness of the borders between the colours), `balance` b (0: the ratio in
//!   which the three colours show), `frequency` f (2: the frequency of the
//!   perturbation), and for `outNormal` `normDepth` (5), `normMelt` (0), `normBalance`
//!   (1), `normFrequency` (1), `normalCamera` (the normal to perturb; the surface normal
//!   when unconnected). The colours: the point is shaken, q = f·p + s·W(p) with W three
//!   gradient noises of p; each channel k has a noise n_k = g(q + o_k) (o_k fixed
//!   offsets), channel 1's raised by b and channel 3's lowered by b (so a large positive
//!   balance shows channel 1 only, a large negative one channel 3 only); channel k's
//!   weight is max(0, 1 − (max_j n_j − n_k)/m) — with `melt` 0 only the largest shows
//!   (hard borders), a growing melt widens the blends until, without bound, the three
//!   average — and `outColor` is the weighted mean of the channels.
//! - stucco: `shaker` s (20: the mix of the two colours — low, mostly `channel2` with
//!   bits of `channel1` peeking through; higher, `channel1`'s areas more solid and spread
//!   out), `channel1` (red), `channel2` (blue), and for `outNormal` `normalDepth` (1),
//!   `normalMelt` (0.1), `normalCamera`. With the stain noise v = ½ + ½·F(4p) (F the
//!   fractal of four octaves of doubling frequency and halving amplitude, normalised, so
//!   v ∈ [0, 1]) and channel 1's cover c = s/(s + 20) (½ at the default; 0 for s = 0, 1
//!   as s grows without bound), channel 1's share is the smoothstep of
//!   (v − t)/0.1 + ½, t = 1.1 − 1.2·c: 0 everywhere for s = 0 and 1 everywhere as s → ∞,
//!   a border 0.1 wide in v between (t = ½ at the default). `outColor` = channel2 + share·(channel1 −
//!   channel2), `outAlpha` the share.
//! - outNormal (both): a height field h ∈ [0, 1], plateaus (1) and crater floors (0)
//!   joined by walls, h = smoothstep((n + w)/(2w)) with the wall's half width
//!   w = 0.05 + melt (`normMelt`, `normalMelt`: softer edges as it grows) and a noise n:
//!   crater's n = (g(ν p) + β g(4ν p + o))/(1 + β), ν = `normFrequency` (rougher, finer
//!   detail as it grows), β = `normBalance` ≥ 0 (the ratio of the high-frequency
//!   disturbance to the low); stucco's n = 2v − 1, its craters where its stains are.
//!   The surface is raised by H = `depth`·h/100 world units (depth = `normDepth` or
//!   `normalDepth`; h of the point's placement), and `outNormal` is the base normal tilted against the
//!   gradient of that height, found by central differences of the world point along two
//!   tangents over [`BUMP_STEP`]: N' = normalize(N − ∇H + N (N·∇H)). Depth 0 (or a point
//!   on a plateau or a crater floor) leaves the normal as it is. crater's `outAlpha` is h.

use glam::{Mat4, Vec3A};
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::noise::gradient_noise;
use crate::texture::{balance, bump_base_normal, outside};
use crate::texture3d::{fractal, placement_matrix, placement_point, texture3d_params, EXTRA};
use crate::values::{rgb, write_struct};

/// The step (world units) the bumped normals are differentiated over.
pub const BUMP_STEP: f32 = 1e-3;

/// The offsets of crater's three shaking noises and three channel noises (placement
/// units; away from the lattice so that no two noises coincide).
const SHAKE: [Vec3A; 3] = [Vec3A::new(0.37, 7.13, 3.71), Vec3A::new(5.29, 1.91, 8.47), Vec3A::new(2.63, 9.59, 0.83)];
const CHANNEL: [Vec3A; 3] =
    [Vec3A::new(11.17, 4.43, 6.31), Vec3A::new(3.07, 13.73, 9.11), Vec3A::new(7.79, 2.27, 15.53)];
/// The offset of crater's high-frequency normal noise.
const HIGH: Vec3A = Vec3A::new(19.41, 5.87, 12.29);

/// Crater's channel weights (summing to 1) at placement-space point `p` for `shaker`,
/// `frequency`, `balance` and `melt` (see the module doc).
pub fn crater_weights(p: Vec3A, shaker: f32, frequency: f32, balance: f32, melt: f32) -> [f32; 3] {
    let shake = Vec3A::new(gradient_noise(p + SHAKE[0]), gradient_noise(p + SHAKE[1]), gradient_noise(p + SHAKE[2]));
    let q = p * frequency + shake * shaker;
    let mut n = CHANNEL.map(|o| gradient_noise(q + o));
    n[0] += balance;
    n[2] -= balance;
    if !n.iter().all(|v| v.is_finite()) {
        return [1.0 / 3.0; 3];
    }
    let top = n[0].max(n[1]).max(n[2]);
    let w = if melt > 0.0 {
        n.map(|v| (1.0 - (top - v) / melt).max(0.0))
    } else {
        // The largest alone (the first of equals).
        let k = n.iter().position(|&v| v == top).unwrap_or(0);
        std::array::from_fn(|i| f32::from(i == k))
    };
    let sum = w[0] + w[1] + w[2];
    w.map(|v| v / sum)
}

/// Stucco's stain noise v ∈ [0, 1] at placement-space point `p`.
pub fn stucco_noise(p: Vec3A) -> f32 {
    let v = 0.5 + 0.5 * fractal(p * 4.0, 4.0, 0.5, 2.0, false);
    if v.is_finite() {
        v.clamp(0.0, 1.0)
    } else {
        0.5
    }
}

/// Stucco's share of `channel1` for the stain noise `v` and `shaker` (see the module doc).
pub fn stucco_share(v: f32, shaker: f32) -> f32 {
    const BAND: f32 = 0.1;
    let s = shaker.max(0.0);
    let cover = if s.is_finite() { s / (s + 20.0) } else { 1.0 };
    let t = 1.0 + BAND - cover * (1.0 + 2.0 * BAND);
    smoothstep((v - t) / BAND + 0.5)
}

/// 3x² − 2x³ on x clamped to [0, 1] (NaN: 0).
fn smoothstep(x: f32) -> f32 {
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    x * x * (3.0 - 2.0 * x)
}

/// The plateau height h ∈ [0, 1] of the noise `n` with the wall softness `melt`.
pub fn plateau(n: f32, melt: f32) -> f32 {
    let w = 0.05 + melt.max(0.0);
    smoothstep((n + w) / (2.0 * w))
}

/// Crater's normal noise at placement-space point `p` (see the module doc).
pub fn crater_normal_noise(p: Vec3A, frequency: f32, balance: f32) -> f32 {
    let b = balance.max(0.0);
    let n = (gradient_noise(p * frequency) + b * gradient_noise(p * (4.0 * frequency) + HIGH)) / (1.0 + b);
    if n.is_finite() {
        n
    } else {
        0.0
    }
}

/// `base` tilted against the gradient of the world height `height` (a function of the
/// world point) about `point`, by central differences over [`BUMP_STEP`].
pub fn bumped_normal(base: Vec3A, point: Vec3A, height: impl Fn(Vec3A) -> f32) -> Vec3A {
    let t1 = base.any_orthonormal_vector();
    let t2 = base.cross(t1);
    let mut gradient = Vec3A::ZERO;
    for t in [t1, t2] {
        let d = height(point + t * BUMP_STEP) - height(point - t * BUMP_STEP);
        gradient += t * (d / (2.0 * BUMP_STEP));
    }
    let n = base - gradient;
    if n.is_finite() {
        n.try_normalize().unwrap_or(base)
    } else {
        base
    }
}

/// The placement-space point of world point `w` through `m` (the texture's
/// `placementMatrix`).
fn to_placement(m: &Mat4, w: Vec3A) -> Vec3A {
    Vec3A::from(m.transform_point3(w.into()))
}

/// Writes `outNormal`: the base normal (parameter `normal_camera`) bumped by `depth`/100
/// world units × the height `h` of the placement-space point.
fn write_normal(ctx: &mut Ctx, n: NodeId, normal_camera: usize, depth: f32, h: impl Fn(Vec3A) -> f32, out: &mut Value) {
    let base = bump_base_normal(ctx, n, normal_camera);
    let normal = if depth != 0.0 && depth.is_finite() {
        let m = placement_matrix(&ctx.eval(n, 0));
        let scale = depth / 100.0;
        bumped_normal(base, ctx.state.point, |w| scale * h(to_placement(&m, w)))
    } else {
        base
    };
    write_struct(out, &[("outNormal", Value::Vector(normal))]);
}

maya_shader!(
    /// Maya's crater (see the module doc).
    CRATER,
    ADSK_CRATER,
    "maya_crater",
    "adskMayaCrater",
    texture3d_params!(
        "shaker",
        "channel1",
        "channel2",
        "channel3",
        "melt",
        "balance",
        "frequency",
        "normDepth",
        "normMelt",
        "normBalance",
        "normFrequency",
        "normalCamera"
    ),
    crater
);

fn crater(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let e = EXTRA;
    let Some(p) = placement_point(ctx, n) else {
        outside(ctx, n, out);
        let base = bump_base_normal(ctx, n, e + 11);
        write_struct(out, &[("outNormal", Value::Vector(base))]);
        return true;
    };
    let channels = [rgb(ctx.color(n, e + 1)), rgb(ctx.color(n, e + 2)), rgb(ctx.color(n, e + 3))];
    let w = crater_weights(p, ctx.scalar(n, e), ctx.scalar(n, e + 6), ctx.scalar(n, e + 5), ctx.scalar(n, e + 4));
    let color = channels[0] * w[0] + channels[1] * w[1] + channels[2] * w[2];
    let (depth, melt) = (ctx.scalar(n, e + 7), ctx.scalar(n, e + 8));
    let (nb, nf) = (ctx.scalar(n, e + 9), ctx.scalar(n, e + 10));
    let h = move |q: Vec3A| plateau(crater_normal_noise(q, nf, nb), melt);
    balance(ctx, n, color, h(p), out);
    write_normal(ctx, n, e + 11, depth, h, out);
    true
}

maya_shader!(
    /// Maya's stucco (see the module doc).
    STUCCO,
    ADSK_STUCCO,
    "maya_stucco",
    "adskMayaStucco",
    texture3d_params!("shaker", "channel1", "channel2", "normalDepth", "normalMelt", "normalCamera"),
    stucco
);

fn stucco(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let e = EXTRA;
    let Some(p) = placement_point(ctx, n) else {
        outside(ctx, n, out);
        let base = bump_base_normal(ctx, n, e + 5);
        write_struct(out, &[("outNormal", Value::Vector(base))]);
        return true;
    };
    let (c1, c2) = (rgb(ctx.color(n, e + 1)), rgb(ctx.color(n, e + 2)));
    let share = stucco_share(stucco_noise(p), ctx.scalar(n, e));
    balance(ctx, n, c2 + (c1 - c2) * share, share, out);
    let (depth, melt) = (ctx.scalar(n, e + 3), ctx.scalar(n, e + 4));
    write_normal(ctx, n, e + 5, depth, move |q| plateau(2.0 * stucco_noise(q) - 1.0, melt), out);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points spread over a few units of space.
    fn points() -> impl Iterator<Item = Vec3A> {
        (0..3000).map(|i| Vec3A::new(i as f32 * 0.0173, (i % 41) as f32 * 0.029, (i % 13) as f32 * 0.047))
    }

    /// The index of the channel that wins a hard-edged crater.
    fn winner(w: [f32; 3]) -> usize {
        w.iter().position(|&v| v == 1.0).expect("one channel alone")
    }

    #[test]
    fn crater_defaults_show_each_channel_alone_in_comparable_shares() {
        // Defaults: shaker 1.5, frequency 2, balance 0, melt 0: hard borders, every point
        // one channel exactly, each channel a fair share of the points.
        let mut count = [0usize; 3];
        for p in points() {
            let w = crater_weights(p, 1.5, 2.0, 0.0, 0.0);
            count[winner(w)] += 1;
            assert_eq!(w, crater_weights(p, 1.5, 2.0, 0.0, 0.0), "deterministic");
        }
        let total = count.iter().sum::<usize>() as f32;
        for c in count {
            let share = c as f32 / total;
            assert!((0.15..0.55).contains(&share), "shares {count:?}");
        }
    }

    #[test]
    fn crater_balance_and_melt_at_their_extremes() {
        for p in points().take(500) {
            // A balance beyond the noise's range: channel 1 alone, or channel 3 alone.
            assert_eq!(crater_weights(p, 1.5, 2.0, 2.5, 0.0), [1.0, 0.0, 0.0]);
            assert_eq!(crater_weights(p, 1.5, 2.0, -2.5, 0.0), [0.0, 0.0, 1.0]);
            // Melt: the weights sum to 1 and tend to the average as melt grows (the
            // noises differ by at most 2: with melt 1e4 each weight is within 1e-4 of ⅓).
            let w = crater_weights(p, 1.5, 2.0, 0.0, 0.3);
            assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-5 && w.iter().all(|v| (0.0..=1.0).contains(v)));
            for v in crater_weights(p, 1.5, 2.0, 0.0, 1e4) {
                assert!((v - 1.0 / 3.0).abs() < 1e-4, "{v}");
            }
            // A small melt keeps the largest channel the heaviest.
            let hard = winner(crater_weights(p, 1.5, 2.0, 0.0, 0.0));
            let soft = crater_weights(p, 1.5, 2.0, 0.0, 0.3);
            assert!(soft.iter().all(|&v| v <= soft[hard]));
        }
        // Melt softens: the share of points showing more than one channel grows with it.
        let mixed =
            |melt: f32| points().filter(|&p| crater_weights(p, 1.5, 2.0, 0.0, melt).iter().all(|&v| v < 1.0)).count();
        assert!(mixed(0.0) == 0 && mixed(0.05) < mixed(0.5), "{} {}", mixed(0.05), mixed(0.5));
        // A point the noise cannot place (NaN) still gives weights that sum to 1.
        assert_eq!(crater_weights(Vec3A::splat(f32::NAN), 1.5, 2.0, 0.0, 0.0).iter().sum::<f32>(), 1.0);
        assert_eq!(crater_weights(Vec3A::ZERO, 1.5, 2.0, f32::NAN, 0.0), [1.0 / 3.0; 3]);
    }

    #[test]
    fn crater_shaker_and_frequency_perturb_the_pattern() {
        // Without shaking the pattern at p is the unshaken noise at f·p: doubling the
        // frequency equals evaluating at 2p.
        for p in points().take(300) {
            assert_eq!(crater_weights(p, 0.0, 4.0, 0.0, 0.2), crater_weights(p * 2.0, 0.0, 2.0, 0.0, 0.2));
        }
        // Shaking changes which channel shows at a good share of the points.
        let changed = points().filter(|&p| {
            winner(crater_weights(p, 0.0, 2.0, 0.0, 0.0)) != winner(crater_weights(p, 1.5, 2.0, 0.0, 0.0))
        });
        assert!(changed.count() > 300);
    }

    #[test]
    fn stucco_shaker_sets_channel1s_cover() {
        // Shaker 0: channel 2 everywhere; a huge shaker: channel 1 everywhere; in between
        // channel 1's cover grows with shaker; the default (20) about half.
        let cover = |s: f32| points().map(|p| stucco_share(stucco_noise(p), s)).sum::<f32>() / 3000.0;
        for p in points().take(500) {
            let v = stucco_noise(p);
            assert!((0.0..=1.0).contains(&v));
            assert_eq!(v, stucco_noise(p), "deterministic");
            assert_eq!(stucco_share(v, 0.0), 0.0);
            assert_eq!(stucco_share(v, f32::INFINITY), 1.0);
            assert_eq!(stucco_share(v, 1e9), 1.0);
        }
        let (low, mid, high) = (cover(5.0), cover(20.0), cover(80.0));
        assert!(low < mid && mid < high, "{low} {mid} {high}");
        assert!((0.3..0.7).contains(&mid), "{mid}");
        // Where the noise is exactly at the threshold of the default the share is ½.
        assert!((stucco_share(0.5, 20.0) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn plateaus_are_flat_and_walls_bump_the_normal() {
        // The height: 0 on crater floors, 1 on plateaus, ½ in the wall's middle.
        assert_eq!(plateau(-0.5, 0.0), 0.0);
        assert_eq!(plateau(0.5, 0.0), 1.0);
        assert!((plateau(0.0, 0.3) - 0.5).abs() < 1e-6);
        // A larger melt: a gentler wall (the height at n = 0.04 nearer ½).
        assert!(plateau(0.04, 0.5) < plateau(0.04, 0.0));
        // A height ramp of slope k along x tilts +y towards −x by atan(k).
        let n = bumped_normal(Vec3A::Y, Vec3A::ZERO, |w| 0.5 * w.x);
        assert!((n - Vec3A::new(-0.5, 1.0, 0.0).normalize()).length() < 1e-4, "{n}");
        // A flat height leaves the normal.
        assert_eq!(bumped_normal(Vec3A::Y, Vec3A::ZERO, |_| 0.3), Vec3A::Y);
        // Crater's normal noise with normBalance 0 is the low-frequency noise alone.
        let p = Vec3A::new(0.3, 0.7, 0.1);
        assert_eq!(crater_normal_noise(p, 1.0, 0.0), gradient_noise(p));
        assert_eq!(crater_normal_noise(p * 0.5, 2.0, 0.0), gradient_noise(p));
    }
}
