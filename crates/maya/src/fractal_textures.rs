//! Maya's brownian and cloud 3D textures: fractal noise over the placement space.
//!
//! Both share the 3D textures' placement, `wrap` and colour balance
//! ([`crate::texture3d`]). Maya's node reference documents their attributes' meanings and
//! most defaults; the formulas are mira's reading of those descriptions, the noise mira's
//! gradient noise ([`crate::texture3d::fractal`]), not Maya's pattern.
//!
//! - brownian: `lacunarity` L (4: the gap between the frequencies added), `increment` g
//!   (0.1: the ratio of each octave's amplitude to the one before — larger blends light
//!   and dark more), `octaves` (3, fractional allowed; mira's default, the reference's
//!   table does not give it), `weight3d` w (1 1 1: the texture's frequency along each
//!   placement axis; mira's reading and default). The value is
//!   v = ½ + ½·F(p ⊙ w), F the normalised fractal sum of `octaves` octaves of frequency
//!   L^i and amplitude g^i, in [0, 1]; `outColor` is v as grey (Maya's brownian is
//!   black and white, tinted by the colour balance), `outAlpha` v.
//! - cloud: `color1` (white), `color2` (black; mira's defaults), `contrast` c (0.5),
//!   `amplitude` a (1), `depthMin`/`depthMax` (0, 8: the first and last octave),
//!   `ripples` r (1 1 1: the frequency along each axis), `ratio` (0.707: each octave's
//!   amplitude over the one before), `softEdges` (on), `centerThresh` (0),
//!   `edgeThresh` (1), `transpRange` (0.5). The noise f = a·F(p ⊙ r · 2^depthMin) over
//!   depthMax − depthMin octaves of doubling frequency; color2's share
//!   w = clamp(½ + c·f, 0, 1) (c = 0: the two colours averaged everywhere, c = −1:
//!   reversed, as Maya describes the contrast); `outColor` = color1 + w (color2 − color1).
//!   With `softEdges` the cloud fades as the surface turns from the viewer: with
//!   e = 1 − |N·V| (0 facing the viewer, 1 edge-on) moved by the noise, e' = e +
//!   transpRange · f, the opacity is α = 1 − smoothstep(centerThresh, edgeThresh, e')
//!   (a low centre and high edge threshold: a dense ball; the reverse: wisps);
//!   `outAlpha` = α (1 without soft edges).

use glam::Vec3A;
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::texture::{balance, outside};
use crate::texture3d::{fractal, placement_point, texture3d_params, EXTRA};
use crate::values::rgb;

/// Brownian's value at placement-space point `p` (see the module doc), in [0, 1].
pub fn brownian(p: Vec3A, lacunarity: f32, increment: f32, octaves: f32, weight: Vec3A) -> f32 {
    let v = 0.5 + 0.5 * fractal(p * weight, octaves, increment, lacunarity, false);
    if v.is_finite() {
        v.clamp(0.0, 1.0)
    } else {
        0.5
    }
}

/// Cloud's noise f at placement-space point `p`: `amplitude` × the fractal of octaves
/// `depth_min` to `depth_max` (doubling frequency, amplitude × `ratio` each) at p ⊙
/// `ripples`.
pub fn cloud_noise(p: Vec3A, ripples: Vec3A, depth_min: f32, depth_max: f32, ratio: f32, amplitude: f32) -> f32 {
    let first = depth_min.clamp(0.0, 30.0);
    let f = amplitude * fractal(p * ripples * 2f32.powf(first), depth_max - first, ratio, 2.0, false);
    if f.is_finite() {
        f
    } else {
        0.0
    }
}

/// Cloud's share of `color2` for the noise `f` and `contrast` (see the module doc).
pub fn cloud_share(f: f32, contrast: f32) -> f32 {
    (0.5 + contrast * f).clamp(0.0, 1.0)
}

/// Cloud's opacity with soft edges, for the cosine `facing` between the normal and the
/// view direction and the noise `f` (see the module doc).
pub fn cloud_opacity(facing: f32, f: f32, center: f32, edge: f32, range: f32) -> f32 {
    let e = 1.0 - facing.abs().min(1.0) + range * f;
    let t = if edge > center { ((e - center) / (edge - center)).clamp(0.0, 1.0) } else { f32::from(e >= edge) };
    let s = t * t * (3.0 - 2.0 * t);
    if s.is_finite() {
        1.0 - s
    } else {
        1.0
    }
}

maya_shader!(
    /// Maya's brownian (see the module doc).
    BROWNIAN,
    ADSK_BROWNIAN,
    "maya_brownian",
    "adskMayaBrownian",
    texture3d_params!("lacunarity", "increment", "octaves", "weight3d"),
    brownian_shader
);

fn brownian_shader(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(p) = placement_point(ctx, n) else { return outside(ctx, n, out) };
    let v =
        brownian(p, ctx.scalar(n, EXTRA), ctx.scalar(n, EXTRA + 1), ctx.scalar(n, EXTRA + 2), ctx.vector(n, EXTRA + 3));
    balance(ctx, n, Vec3A::splat(v), v, out)
}

maya_shader!(
    /// Maya's cloud (see the module doc).
    CLOUD,
    ADSK_CLOUD,
    "maya_cloud",
    "adskMayaCloud",
    texture3d_params!(
        "color1",
        "color2",
        "contrast",
        "amplitude",
        "depthMin",
        "depthMax",
        "ripples",
        "ratio",
        "softEdges",
        "centerThresh",
        "edgeThresh",
        "transpRange"
    ),
    cloud_shader
);

fn cloud_shader(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(p) = placement_point(ctx, n) else { return outside(ctx, n, out) };
    let e = EXTRA;
    let (c1, c2) = (rgb(ctx.color(n, e)), rgb(ctx.color(n, e + 1)));
    let f = cloud_noise(
        p,
        ctx.vector(n, e + 6),
        ctx.scalar(n, e + 4),
        ctx.scalar(n, e + 5),
        ctx.scalar(n, e + 7),
        ctx.scalar(n, e + 3),
    );
    let w = cloud_share(f, ctx.scalar(n, e + 2));
    let alpha = if ctx.bool(n, e + 8) {
        let facing = ctx.state.normal.dot(ctx.state.dir);
        cloud_opacity(facing, f, ctx.scalar(n, e + 9), ctx.scalar(n, e + 10), ctx.scalar(n, e + 11))
    } else {
        1.0
    };
    balance(ctx, n, c1 + (c2 - c1) * w, alpha, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points spread over a few units of space.
    fn points() -> impl Iterator<Item = Vec3A> {
        (0..2000).map(|i| Vec3A::new(i as f32 * 0.0137, (i % 37) as f32 * 0.021, (i % 11) as f32 * 0.043))
    }

    #[test]
    fn brownian_lies_in_the_unit_range_varies_and_repeats() {
        let (mut lo, mut hi) = (1.0f32, 0.0f32);
        for p in points() {
            // Defaults: lacunarity 4, increment 0.1, octaves 3, weight3d 1 1 1.
            let v = brownian(p, 4.0, 0.1, 3.0, Vec3A::ONE);
            assert!((0.0..=1.0).contains(&v));
            assert_eq!(v, brownian(p, 4.0, 0.1, 3.0, Vec3A::ONE), "deterministic");
            // weight3d scales the space per axis (powers of two: exact).
            assert_eq!(
                brownian(p, 4.0, 0.1, 3.0, Vec3A::new(2.0, 0.5, 1.0)),
                brownian(p * Vec3A::new(2.0, 0.5, 1.0), 4.0, 0.1, 3.0, Vec3A::ONE)
            );
            (lo, hi) = (lo.min(v), hi.max(v));
        }
        assert!(hi - lo > 0.3, "it varies: {lo}..{hi}");
        // No octaves: ½ everywhere; on the lattice every octave is 0: ½.
        assert_eq!(brownian(Vec3A::new(0.3, 0.2, 0.1), 4.0, 0.1, 0.0, Vec3A::ONE), 0.5);
        assert_eq!(brownian(Vec3A::new(1.0, 2.0, 3.0), 4.0, 0.1, 3.0, Vec3A::ONE), 0.5);
        assert_eq!(brownian(Vec3A::splat(f32::NAN), 4.0, 0.1, 3.0, Vec3A::ONE), 0.5);
    }

    #[test]
    fn cloud_contrast_blends_and_reverses_the_colours() {
        for p in points().take(500) {
            let f = cloud_noise(p, Vec3A::ONE, 0.0, 8.0, 0.707, 1.0);
            assert!((-1.0..=1.0).contains(&f));
            assert_eq!(f, cloud_noise(p, Vec3A::ONE, 0.0, 8.0, 0.707, 1.0), "deterministic");
            // Contrast 0: the average everywhere; −c mirrors c about ½.
            assert_eq!(cloud_share(f, 0.0), 0.5);
            assert!((cloud_share(f, -0.5) - (1.0 - cloud_share(f, 0.5))).abs() < 1e-6);
            // Amplitude 0: no noise.
            assert_eq!(cloud_noise(p, Vec3A::ONE, 0.0, 8.0, 0.707, 0.0), 0.0);
        }
        // At the threshold: noise 0.3 with contrast 0.5 gives colour2 a share of 0.65.
        assert!((cloud_share(0.3, 0.5) - 0.65).abs() < 1e-6);
        assert_eq!(cloud_share(0.9, 2.0), 1.0);
    }

    #[test]
    fn cloud_soft_edges_fade_towards_the_silhouette() {
        // Defaults: centre 0, edge 1, range 0.5. Facing the viewer without noise: opaque;
        // edge-on: clear; halfway (e = ½): ½.
        assert_eq!(cloud_opacity(-1.0, 0.0, 0.0, 1.0, 0.5), 1.0);
        assert_eq!(cloud_opacity(0.0, 0.0, 0.0, 1.0, 0.5), 0.0);
        assert!((cloud_opacity(0.5, 0.0, 0.0, 1.0, 0.5) - 0.5).abs() < 1e-6);
        // The noise moves the edge by transpRange · f.
        assert!(cloud_opacity(0.5, 0.4, 0.0, 1.0, 0.5) < cloud_opacity(0.5, 0.0, 0.0, 1.0, 0.5));
        assert_eq!(cloud_opacity(0.5, 0.4, 0.0, 1.0, 0.0), cloud_opacity(0.5, 0.0, 0.0, 1.0, 0.0));
        // Equal thresholds: a hard edge.
        assert_eq!(cloud_opacity(0.9, 0.0, 0.5, 0.5, 0.0), 1.0);
        assert_eq!(cloud_opacity(0.1, 0.0, 0.5, 0.5, 0.0), 0.0);
        assert_eq!(cloud_opacity(f32::NAN, 0.0, 0.0, 1.0, 0.5), 1.0);
    }
}
