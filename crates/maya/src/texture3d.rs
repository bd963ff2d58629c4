//! Maya's 3D textures and their placement: place3dTexture, solidFractal, marble, wood and
//! bump3d.
//!
//! A 3D texture is a function of the point in its placement space, p = the world point
//! through `placementMatrix` (world → placement, mental ray's row-vector convention; an
//! unset or singular matrix is the identity). Exports connect `placementMatrix` to a
//! place3dTexture's `worldInverseMatrix` or write the matrix itself. With `wrap` off, a
//! point outside the placement cube [−1, 1]³ gets `defaultColor`. The colour balance
//! (`invert`, `alphaIsLuminance`, `colorGain`, `colorOffset`, `alphaGain`,
//! `alphaOffset`) is the 2D textures' (see [`crate::texture`]).
//!
//! Parameters and patterns (F(q) = Σ_{i<depthMax} ratio^i n(q·2^i) / Σ ratio^i, fractal
//! gradient noise in [−1, 1], [`crate::noise::gradient_noise`]; mira's noise, with
//! Maya's statistics but not its pattern):
//!
//! - solidFractal: `threshold` (0), `amplitude` (1), `ratio` (0.707), `frequencyRatio`
//!   (2, the octaves' frequency step), `ripples` (1 1 1, frequency per axis), `depthMax`
//!   (8), `bias` (0), `inflection` (off): value = threshold + 0.5 + 0.5·amplitude·F(p ⊙
//!   ripples) + bias/2 (with inflection |n| per octave and no 0.5 offset), clipped to
//!   [0, 1]; `outColor` is the value as grey, `outAlpha` the value;
//! - marble: `fillerColor`, `veinColor`, `veinWidth` (0.1), `diffusion` (0.5),
//!   `contrast` (0.5), `amplitude` (1.5), `ratio` (0.707), `ripples`, `depthMax` (20):
//!   veins are the planes x = integer of the placement space bent by
//!   amplitude·F(p ⊙ ripples); at distance δ from the nearest one a point is vein for
//!   δ < veinWidth/2 and blends into the filler over `diffusion`·0.5 beyond it, the vein
//!   weight sharpened by `contrast` (w^(1 − contrast)); `outAlpha` is the vein weight;
//! - wood: `fillerColor`, `veinColor`, `veinSpread` (0.25), `layerSize` (0.05),
//!   `randomness` (0.5), `age` (20), `grainColor`, `grainContrast` (1), `grainSpacing`
//!   (0.1), `centerU`/`centerV` (0.5, −0.5, the rings' axis in the placement's XZ plane
//!   as Maya's wood defines it, in [0, 1] units across the cube), `amplitudeX`/`Y` (0.1),
//!   `ratio` (0.35), `ripples`, `depthMax` (8): rings of width `layerSize` about an axis
//!   parallel to the placement's Y through the centre, their radius bent by amplitude·F
//!   and jittered per ring by `randomness`; a ring is vein colour over the fraction
//!   `veinSpread` of its width nearest its outer edge, blending into filler inside; grain
//!   adds `grainColor` where high-frequency noise of period `grainSpacing` exceeds
//!   1 − grainContrast/2; `age` is not read (it only names the ring count in Maya's UI);
//! - bump3d: `bumpValue`, `bumpDepth` (1), `normalCamera`: `outNormal` is the normal
//!   tilted against the gradient of bumpValue in space, found by finite differences of
//!   the world point along two tangents (n − depth·(∇b − n (n·∇b)), normalised).
//!
//! Maya documents these attributes' effects, not the formulas; the formulas are mira's
//! reading of that documentation. `filter`, `filterOffset`, `time`, `depthMin` and the
//! local/blend attributes are not read.

use glam::{Mat4, Vec3A};
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::noise::gradient_noise;
use crate::texture::{balance, bump_base_normal, outside};
use crate::values::{rgb, write_struct};

/// Parameters every 3D texture reads first, in this order (the colour balance at the
/// same indices as the 2D textures').
macro_rules! texture3d_params {
    ($($extra:literal),*) => {
        &["placementMatrix", "invert", "alphaIsLuminance", "colorGain", "colorOffset",
          "alphaGain", "alphaOffset", "defaultColor", "wrap", $($extra),*]
    };
}
pub(crate) use texture3d_params;

/// The first parameter a 3D texture adds to the shared ones.
pub(crate) const EXTRA: usize = 9;

/// The world → placement matrix of a `placementMatrix` value (the identity when unset or
/// singular).
pub fn placement_matrix(v: &Value) -> Mat4 {
    let m = v.transform();
    let det = m.determinant();
    if det.is_finite() && det.abs() > 1e-12 {
        m
    } else {
        Mat4::IDENTITY
    }
}

/// The shading point in the texture's placement space, `None` outside the placement cube
/// when `wrap` is off.
pub(crate) fn placement_point(ctx: &mut Ctx, n: NodeId) -> Option<Vec3A> {
    let m = placement_matrix(&ctx.eval(n, 0));
    let p = Vec3A::from(m.transform_point3(ctx.state.point.into()));
    if !ctx.bool(n, 8) && p.abs().max_element() > 1.0 {
        return None;
    }
    Some(p)
}

/// Fractal gradient noise at `q`: `octaves` octaves (a fractional last one weighted by
/// its fraction), each `step` times the frequency and `ratio` times the amplitude of the
/// one before, normalised by the sum of the amplitudes; with `inflection` each octave is
/// |n| (then the result lies in [0, 1], else in [−1, 1]).
pub fn fractal(q: Vec3A, octaves: f32, ratio: f32, step: f32, inflection: bool) -> f32 {
    let octaves = octaves.clamp(0.0, 30.0);
    let (mut sum, mut norm, mut amp, mut freq) = (0.0, 0.0, 1.0f32, 1.0f32);
    let mut i = 0.0;
    while i < octaves {
        let w = (octaves - i).min(1.0);
        let n = gradient_noise(q * freq);
        sum += w * amp * if inflection { n.abs() } else { n };
        norm += w * amp;
        amp *= ratio;
        freq *= step;
        i += 1.0;
    }
    if norm > 0.0 {
        sum / norm
    } else {
        0.0
    }
}

/// solidFractal's value (see the module doc).
pub fn solid_fractal_value(f: f32, threshold: f32, amplitude: f32, bias: f32, inflection: bool) -> f32 {
    let v = if inflection { threshold + amplitude * f } else { threshold + 0.5 + 0.5 * amplitude * f };
    (v + 0.5 * bias).clamp(0.0, 1.0)
}

/// The vein weight of marble at distance `delta` (0..0.5) from the nearest vein plane.
pub fn marble_vein(delta: f32, width: f32, diffusion: f32, contrast: f32) -> f32 {
    let half = 0.5 * width.max(0.0);
    let spread = 0.5 * diffusion.max(0.0);
    let w = if delta <= half {
        1.0
    } else if spread > 0.0 {
        (1.0 - (delta - half) / spread).max(0.0)
    } else {
        0.0
    };
    w.powf((1.0 - contrast).clamp(0.05, 1.0))
}

/// The vein weight of wood at the fraction `t` (0 inner edge .. 1 outer edge) across a
/// ring: 1 over the outer `spread` of the ring, falling linearly to 0 across the same
/// width inside it.
pub fn wood_vein(t: f32, spread: f32) -> f32 {
    let s = spread.clamp(1e-3, 1.0);
    ((t - (1.0 - 2.0 * s)) / s).clamp(0.0, 1.0)
}

maya_shader!(
    /// place3dTexture: returns `matrix` as `worldMatrix` and its inverse as
    /// `worldInverseMatrix` (the identity when singular).
    PLACE3D,
    ADSK_PLACE3D,
    "maya_place3dtexture",
    "adskMayaPlace3dTexture",
    &["matrix"],
    place3d
);

fn place3d(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let m = placement_matrix(&ctx.eval(n, 0));
    write_struct(out, &[("worldMatrix", Value::Transform(m)), ("worldInverseMatrix", Value::Transform(m.inverse()))]);
    true
}

maya_shader!(
    /// Maya's solidFractal (see the module doc).
    SOLIDFRACTAL,
    ADSK_SOLIDFRACTAL,
    "maya_solidfractal",
    "adskMayaSolidFractal",
    texture3d_params!("threshold", "amplitude", "ratio", "frequencyRatio", "ripples", "depthMax", "bias", "inflection"),
    solid_fractal
);

fn solid_fractal(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(p) = placement_point(ctx, n) else { return outside(ctx, n, out) };
    let (threshold, amplitude, ratio) = (ctx.scalar(n, EXTRA), ctx.scalar(n, EXTRA + 1), ctx.scalar(n, EXTRA + 2));
    let step = ctx.scalar(n, EXTRA + 3);
    let ripples = ctx.vector(n, EXTRA + 4);
    let depth = ctx.scalar(n, EXTRA + 5);
    let (bias, inflection) = (ctx.scalar(n, EXTRA + 6), ctx.bool(n, EXTRA + 7));
    let f = fractal(p * ripples, depth, ratio, step, inflection);
    let v = solid_fractal_value(f, threshold, amplitude, bias, inflection);
    balance(ctx, n, Vec3A::splat(v), v, out)
}

maya_shader!(
    /// Maya's marble (see the module doc).
    MARBLE,
    ADSK_MARBLE,
    "maya_marble",
    "adskMayaMarble",
    texture3d_params!(
        "fillerColor",
        "veinColor",
        "veinWidth",
        "diffusion",
        "contrast",
        "amplitude",
        "ratio",
        "ripples",
        "depthMax"
    ),
    marble
);

fn marble(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(p) = placement_point(ctx, n) else { return outside(ctx, n, out) };
    let (filler, vein) = (rgb(ctx.color(n, EXTRA)), rgb(ctx.color(n, EXTRA + 1)));
    let (width, diffusion, contrast) = (ctx.scalar(n, EXTRA + 2), ctx.scalar(n, EXTRA + 3), ctx.scalar(n, EXTRA + 4));
    let (amplitude, ratio) = (ctx.scalar(n, EXTRA + 5), ctx.scalar(n, EXTRA + 6));
    let ripples = ctx.vector(n, EXTRA + 7);
    let depth = ctx.scalar(n, EXTRA + 8);
    let s = p.x + amplitude * fractal(p * ripples, depth, ratio, 2.0, false);
    let delta = (s - s.round()).abs();
    let w = marble_vein(delta, width, diffusion, contrast);
    balance(ctx, n, filler + (vein - filler) * w, w, out)
}

maya_shader!(
    /// Maya's wood (see the module doc).
    WOOD,
    ADSK_WOOD,
    "maya_wood",
    "adskMayaWood",
    texture3d_params!(
        "fillerColor",
        "veinColor",
        "veinSpread",
        "layerSize",
        "randomness",
        "grainColor",
        "grainContrast",
        "grainSpacing",
        "centerU",
        "centerV",
        "amplitudeX",
        "amplitudeY",
        "ratio",
        "ripples",
        "depthMax"
    ),
    wood
);

fn wood(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(p) = placement_point(ctx, n) else { return outside(ctx, n, out) };
    let s = |ctx: &mut Ctx, i: usize| ctx.scalar(n, EXTRA + i);
    let (filler, vein) = (rgb(ctx.color(n, EXTRA)), rgb(ctx.color(n, EXTRA + 1)));
    let (spread, layer, randomness) = (s(ctx, 2), s(ctx, 3).max(1e-4), s(ctx, 4));
    let grain = rgb(ctx.color(n, EXTRA + 5));
    let (grain_contrast, grain_spacing) = (s(ctx, 6), s(ctx, 7).max(1e-4));
    let (cu, cv) = (s(ctx, 8), s(ctx, 9));
    let (ax, ay, ratio) = (s(ctx, 10), s(ctx, 11), s(ctx, 12));
    let ripples = ctx.vector(n, EXTRA + 13);
    let depth = s(ctx, 14);
    // The axis: (centerU, centerV) of the cube's [0, 1] span → placement x, z.
    let (x0, z0) = (2.0 * cu - 1.0, 2.0 * cv - 1.0);
    let q = p * ripples;
    let bend_x = ax * fractal(q, depth, ratio, 2.0, false);
    let bend_z = ay * fractal(q + Vec3A::splat(17.31), depth, ratio, 2.0, false);
    let r = Vec3A::new(p.x - x0 + bend_x, 0.0, p.z - z0 + bend_z).length();
    let ring = r / layer;
    let jitter = randomness * 0.5 * gradient_noise(Vec3A::new(ring.floor() * 0.731 + 0.5, 0.37, 0.5));
    let t = (ring + jitter).rem_euclid(1.0);
    let w = wood_vein(t, spread);
    let mut c = filler + (vein - filler) * w;
    let g = 0.5 + 0.5 * gradient_noise(p / grain_spacing);
    if g > 1.0 - 0.5 * grain_contrast.clamp(0.0, 2.0) {
        c = grain;
    }
    balance(ctx, n, c, w, out)
}

/// The step (world units) bump3d differentiates over.
const BUMP3D_STEP: f32 = 1e-3;

maya_shader!(
    /// Maya's bump3d (see the module doc).
    BUMP3D,
    ADSK_BUMP3D,
    "maya_bump3d",
    "adskMayaBump3d",
    &["bumpValue", "bumpDepth", "normalCamera"],
    bump3d
);

fn bump3d(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let base = bump_base_normal(ctx, n, 2);
    let depth = ctx.scalar(n, 1);
    let normal = if depth != 0.0 && ctx.is_connected(n, 0) {
        let saved = ctx.state.point;
        let t1 = base.any_orthonormal_vector();
        let t2 = base.cross(t1);
        let b = ctx.scalar(n, 0);
        let mut gradient = Vec3A::ZERO;
        for t in [t1, t2] {
            ctx.flush_cache();
            ctx.state.point = saved + t * BUMP3D_STEP;
            gradient += t * (ctx.scalar(n, 0) - b) / BUMP3D_STEP;
        }
        ctx.flush_cache();
        ctx.state.point = saved;
        (base - depth * gradient).try_normalize().unwrap_or(base)
    } else {
        base
    };
    write_struct(out, &[("outNormal", Value::Vector(normal))]);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fractal_is_bounded_and_normalised() {
        for i in 0..200 {
            let q = Vec3A::new(i as f32 * 0.37, i as f32 * 0.11 - 3.0, 1.7);
            let f = fractal(q, 8.0, 0.707, 2.0, false);
            assert!((-1.0..=1.0).contains(&f), "{f}");
            let g = fractal(q, 8.0, 0.707, 2.0, true);
            assert!((0.0..=1.0).contains(&g), "{g}");
        }
        // One octave is the noise itself; none is 0; the lattice is 0.
        let q = Vec3A::new(0.3, 0.6, 0.2);
        assert_eq!(fractal(q, 1.0, 0.5, 2.0, false), gradient_noise(q));
        assert_eq!(fractal(q, 0.0, 0.5, 2.0, false), 0.0);
        assert_eq!(fractal(Vec3A::new(2.0, -1.0, 5.0), 1.0, 0.5, 2.0, false), 0.0);
    }

    #[test]
    fn solid_fractal_value_threshold_amplitude_and_clip() {
        assert_eq!(solid_fractal_value(0.0, 0.0, 1.0, 0.0, false), 0.5);
        assert!((solid_fractal_value(0.4, 0.1, 0.5, 0.0, false) - 0.7).abs() < 1e-6);
        assert_eq!(solid_fractal_value(1.0, 0.5, 1.0, 0.0, false), 1.0);
        assert!((solid_fractal_value(0.3, 0.0, 2.0, 0.2, true) - 0.7).abs() < 1e-6);
    }

    #[test]
    fn marble_and_wood_veins() {
        // Inside the vein: 1; beyond vein + diffusion: 0; linear between (contrast 0).
        assert_eq!(marble_vein(0.04, 0.1, 0.5, 0.0), 1.0);
        assert_eq!(marble_vein(0.4, 0.1, 0.5, 0.0), 0.0);
        assert!((marble_vein(0.05 + 0.125, 0.1, 0.5, 0.0) - 0.5).abs() < 1e-6);
        // Contrast sharpens the edge: a partial weight grows towards 1.
        assert!(marble_vein(0.175, 0.1, 0.5, 0.5) > 0.5);
        // Wood: vein over the outer quarter, filler inside half, linear between.
        assert_eq!(wood_vein(0.9, 0.25), 1.0);
        assert_eq!(wood_vein(0.3, 0.25), 0.0);
        assert!((wood_vein(0.625, 0.25) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn placement_matrix_falls_back_to_the_identity() {
        assert_eq!(placement_matrix(&Value::Transform(Mat4::ZERO)), Mat4::IDENTITY);
        assert_eq!(placement_matrix(&Value::Null), Mat4::IDENTITY);
        let s = Mat4::from_scale(glam::Vec3::splat(2.0));
        assert_eq!(placement_matrix(&Value::Transform(s)), s);
    }
}
