//! Maya's snow, rock and volumeNoise 3D textures.
//!
//! Both share the 3D textures' placement, `wrap` and colour balance
//! ([`crate::texture3d`]). Maya's node reference documents their attributes' meanings,
//! ranges and defaults; the formulas below are mira's reading of those descriptions, and
//! rock's grains come from mira's gradient noise ([`crate::noise::gradient_noise`]), not
//! Maya's (its statistics, not its pattern).
//!
//! - snow: `snowColor` (white), `surfaceColor` (0.5 grey), `threshold` (0.5),
//!   `depthDecay` (5), `thickness` (1). Snow lies where the surface faces up the
//!   placement's +Y axis: θ is the angle of the surface normal (placement space) from +Y,
//!   and the steepest slope that holds snow is θ_max = (1 − threshold) · 90° (Maya:
//!   threshold 0 is 90° from horizontal, 1 is 0°, 0.5 is 45°). The snow's share is
//!   w = thickness · clamp(depthDecay · (θ_max − θ) / 90°, 0, 1): none at θ_max, growing
//!   towards flatter ground at the rate `depthDecay` (full snow 90°/depthDecay inside the
//!   limit: 18° by default), `thickness` its opacity. `outColor` = surfaceColor +
//!   w · (snowColor − surfaceColor), `outAlpha` = w;
//! - rock: `color1` (black), `color2` (white), `grainSize` (0.01), `diffusion` (1),
//!   `mixRatio` (0.5). The grain value g = ½ + ½ n(p / grainSize) lies in [0, 1], n the
//!   gradient noise (grainSize 0: g = ½ everywhere, no grains); color2's share is
//!   w = clamp((e − g)/diffusion + ½, 0, 1) with the edge e = mixRatio · (1 + diffusion) −
//!   diffusion/2, so that mixRatio 0 leaves color1 alone and 1 color2 alone (Maya: "0
//!   Color1 totally dominant, 1 Color2 totally dominant"), and `diffusion` is the width
//!   over which one blends into the other (0: a hard edge at g = mixRatio). `outColor` =
//!   color1 + w · (color2 − color1), `outAlpha` = w;
//! - volumeNoise: the noise texture's attributes and formula ([`crate::noise::Noise`]:
//!   `threshold` (0), `amplitude` (1), `ratio` (0.707), `frequencyRatio` (2), `depthMax`
//!   (3), `inflection` (off), `time` (0), `frequency` (8), `noiseType` (1, billow; 0
//!   Perlin, 2 Wave, 3 Wispy, 4 SpaceTime, as the noise texture reads them in space),
//!   `numWaves` (5), the Billow cells' `density`, `spottyness`, `sizeRand`, `randomness`
//!   and `falloff`: [`crate::billow`]) over 3D space ([`crate::noise::Noise::value3`]),
//!   at q = (p − `origin`) ⊘ `scale` (`scale` 1 1 1, `origin` 0 0 0: Maya says scale has
//!   the inverse effect of frequency; the origin's sign is mira's reading); `outColor` is
//!   the value as grey, `outAlpha` the value.

use glam::{Mat4, Vec3A};
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::noise::{gradient_noise, Noise};
use crate::texture::{balance, outside};
use crate::texture3d::{placement_matrix, placement_point, texture3d_params, EXTRA};
use crate::values::rgb;

/// Snow's share at a surface whose unit normal (placement space) is `n` (see the module
/// doc), in [0, 1] for `thickness` in [0, 1].
pub fn snow_share(n: Vec3A, threshold: f32, depth_decay: f32, thickness: f32) -> f32 {
    let right = std::f32::consts::FRAC_PI_2;
    let theta = n.y.clamp(-1.0, 1.0).acos();
    let limit = (1.0 - threshold.clamp(0.0, 1.0)) * right;
    let w = thickness.max(0.0) * (depth_decay.max(0.0) * (limit - theta) / right).clamp(0.0, 1.0);
    if w.is_nan() {
        0.0
    } else {
        w
    }
}

/// Rock's share of `color2` at the grain value `g` (see the module doc).
pub fn rock_share(g: f32, diffusion: f32, mix_ratio: f32) -> f32 {
    let d = diffusion.max(0.0);
    let edge = mix_ratio * (1.0 + d) - 0.5 * d;
    if d == 0.0 {
        return if g < edge || mix_ratio >= 1.0 { 1.0 } else { 0.0 };
    }
    let w = ((edge - g) / d + 0.5).clamp(0.0, 1.0);
    if w.is_nan() {
        0.0
    } else {
        w
    }
}

/// Rock's grain value at placement-space point `p` for `grainSize` `size`, in [0, 1].
pub fn rock_grain(p: Vec3A, size: f32) -> f32 {
    0.5 + 0.5 * gradient_noise(p / size)
}

/// The shading normal in the placement space of `m` (world → placement), unit; +Y when
/// the map flattens it.
fn placement_normal(m: Mat4, normal: Vec3A) -> Vec3A {
    Vec3A::from(m.inverse().transpose().transform_vector3(normal.into())).try_normalize().unwrap_or(Vec3A::Y)
}

maya_shader!(
    /// Maya's snow (see the module doc).
    SNOW,
    ADSK_SNOW,
    "maya_snow",
    "adskMayaSnow",
    texture3d_params!("snowColor", "surfaceColor", "threshold", "depthDecay", "thickness"),
    snow
);

fn snow(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if placement_point(ctx, n).is_none() {
        return outside(ctx, n, out);
    }
    let m = placement_matrix(&ctx.eval(n, 0));
    let normal = placement_normal(m, ctx.state.normal);
    let (snow, surface) = (rgb(ctx.color(n, EXTRA)), rgb(ctx.color(n, EXTRA + 1)));
    let w = snow_share(normal, ctx.scalar(n, EXTRA + 2), ctx.scalar(n, EXTRA + 3), ctx.scalar(n, EXTRA + 4));
    balance(ctx, n, surface + (snow - surface) * w, w, out)
}

maya_shader!(
    /// Maya's rock (see the module doc).
    ROCK,
    ADSK_ROCK,
    "maya_rock",
    "adskMayaRock",
    texture3d_params!("color1", "color2", "grainSize", "diffusion", "mixRatio"),
    rock
);

fn rock(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(p) = placement_point(ctx, n) else { return outside(ctx, n, out) };
    let (c1, c2) = (rgb(ctx.color(n, EXTRA)), rgb(ctx.color(n, EXTRA + 1)));
    let g = rock_grain(p, ctx.scalar(n, EXTRA + 2));
    let w = rock_share(g, ctx.scalar(n, EXTRA + 3), ctx.scalar(n, EXTRA + 4));
    balance(ctx, n, c1 + (c2 - c1) * w, w, out)
}

maya_shader!(
    /// Maya's volumeNoise (see the module doc).
    VOLUME_NOISE,
    ADSK_VOLUME_NOISE,
    "maya_volumenoise",
    "adskMayaVolumeNoise",
    texture3d_params!(
        "threshold",
        "amplitude",
        "ratio",
        "frequencyRatio",
        "depthMax",
        "inflection",
        "time",
        "frequency",
        "scale",
        "origin",
        "noiseType",
        "numWaves",
        "density",
        "spottyness",
        "sizeRand",
        "randomness",
        "falloff"
    ),
    volume_noise
);

fn volume_noise(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(p) = placement_point(ctx, n) else { return outside(ctx, n, out) };
    let e = EXTRA;
    let settings = Noise::read(ctx, n, e, e + 10);
    let (scale, origin) = (ctx.vector(n, e + 8), ctx.vector(n, e + 9));
    let v = settings.value3((p - origin) / scale);
    balance(ctx, n, Vec3A::splat(v), v, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The normal at `deg` degrees from +Y.
    fn tilted(deg: f32) -> Vec3A {
        let (s, c) = deg.to_radians().sin_cos();
        Vec3A::new(s, c, 0.0)
    }

    #[test]
    fn snow_lies_on_ground_flatter_than_the_threshold_slope() {
        // Defaults: threshold 0.5 (45°), depthDecay 5 (full snow 18° inside the limit).
        let w = |deg: f32| snow_share(tilted(deg), 0.5, 5.0, 1.0);
        assert_eq!(w(0.0), 1.0);
        assert_eq!(w(27.0 - 1e-3), 1.0);
        // At the threshold slope: the surface colour; beyond it, too.
        assert!(w(45.0).abs() < 1e-5);
        assert_eq!(w(60.0), 0.0);
        assert_eq!(w(180.0), 0.0);
        // Halfway across the 18° transition: half.
        assert!((w(36.0) - 0.5).abs() < 1e-4, "{}", w(36.0));
        // threshold 1 holds snow only on level ground, 0 up to vertical walls.
        assert!(snow_share(tilted(1.0), 1.0, 5.0, 1.0) == 0.0);
        assert!(snow_share(tilted(80.0), 0.0, 5.0, 1.0) > 0.5);
        // thickness is the snow's opacity.
        assert!((snow_share(Vec3A::Y, 0.5, 5.0, 0.3) - 0.3).abs() < 1e-6);
        // A hostile normal gives no snow rather than NaN.
        assert_eq!(snow_share(Vec3A::splat(f32::NAN), 0.5, 5.0, 1.0), 0.0);
    }

    #[test]
    fn rock_mix_ratio_picks_the_dominant_grain() {
        let grains: Vec<f32> = (0..=100).map(|i| i as f32 / 100.0).collect();
        for d in [0.0, 0.5, 1.0, 3.0] {
            // 0: colour1 alone, 1: colour2 alone, whatever the diffusion.
            assert!(grains.iter().all(|&g| rock_share(g, d, 0.0) == 0.0), "diffusion {d}");
            assert!(grains.iter().all(|&g| rock_share(g, d, 1.0) == 1.0), "diffusion {d}");
            // 0.5: even, symmetric about g = ½.
            assert!((rock_share(0.5, d, 0.5) - if d == 0.0 { 0.0 } else { 0.5 }).abs() < 1e-6);
            for &g in &grains {
                let (a, b) = (rock_share(g, d, 0.5), rock_share(1.0 - g, d, 0.5));
                if (g - 0.5).abs() > 1e-3 {
                    assert!((a + b - 1.0).abs() < 1e-5, "diffusion {d}, g {g}: {a} + {b}");
                }
                // A larger mixRatio never takes colour2 away.
                assert!(rock_share(g, d, 0.7) >= a);
            }
        }
        // Diffusion 1, mixRatio 0.5: color2's share falls linearly across the grains.
        assert!((rock_share(0.25, 1.0, 0.5) - 0.75).abs() < 1e-6);
    }

    #[test]
    fn rock_grains_lie_in_the_unit_range_scale_with_the_grain_size_and_repeat() {
        let mut lo: f32 = 1.0;
        let mut hi: f32 = 0.0;
        for i in 0..2000 {
            let p = Vec3A::new(i as f32 * 0.0137, (i % 37) as f32 * 0.021, (i % 11) as f32 * 0.043);
            let g = rock_grain(p, 0.01);
            (lo, hi) = (lo.min(g), hi.max(g));
            assert_eq!(g, rock_grain(p, 0.01), "deterministic");
            // grainSize scales the whole texture (sizes that are powers of two: exact).
            assert_eq!(rock_grain(p * 2.0, 0.5), rock_grain(p, 0.25));
        }
        assert!((0.0..=1.0).contains(&lo) && (0.0..=1.0).contains(&hi));
        assert!(hi - lo > 0.5, "the grains vary: {lo}..{hi}");
        // No grains at size 0.
        assert_eq!(rock_grain(Vec3A::new(0.3, 0.1, 0.2), 0.0), 0.5);
    }

    fn volume_noise_default() -> Noise {
        Noise {
            threshold: 0.0,
            amplitude: 1.0,
            ratio: 0.707,
            frequency_ratio: 2.0,
            depth: 3,
            billow: false,
            time: 0.0,
            frequency: 8.0,
            shape: crate::noise::Shape::Perlin,
        }
    }

    #[test]
    fn volume_noise_is_the_noise_fractal_over_space() {
        let n = volume_noise_default();
        // q · 8 · 2^i on the lattice: every octave 0, the mean 0.5 (+ threshold).
        for q in [Vec3A::ZERO, Vec3A::new(0.25, -0.5, 0.125)] {
            assert_eq!(n.value3(q), 0.5);
            assert!((Noise { threshold: 0.2, ..n }.value3(q) - 0.7).abs() < 1e-6);
            assert_eq!(Noise { billow: true, ..n }.value3(q), 0.0);
        }
        // In range, varying, continuous and deterministic; amplitude 0 is flat.
        let (mut lo, mut hi) = (1.0f32, 0.0f32);
        for i in 0..3000 {
            let q = Vec3A::new(i as f32 * 0.0131, (i % 17) as f32 * 0.029, (i % 23) as f32 * 0.041);
            let v = n.value3(q);
            assert!((0.0..=1.0).contains(&v));
            assert_eq!(v, n.value3(q));
            assert!((n.value3(q + Vec3A::splat(1e-4)) - v).abs() < 0.01);
            assert_eq!(Noise { amplitude: 0.0, ..n }.value3(q), 0.5);
            // Scale is the inverse of frequency: half the frequency at the point, or the
            // point halved (powers of two: exact).
            assert_eq!(Noise { frequency: 4.0, ..n }.value3(q), n.value3(q * 0.5));
            (lo, hi) = (lo.min(v), hi.max(v));
        }
        assert!(hi - lo > 0.3, "{lo}..{hi}");
    }
}
