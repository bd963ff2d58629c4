//! Glossy interpolation of `mia_material` (`refl_interpolate`, `refr_interpolate`).
//!
//! mental ray computed interpolated glossy reflections and refractions at the points of a
//! grid `intr_grid_density` sets (0: twice the image resolution, 1: the resolution, 2 … 5:
//! a half … a fifth of it) in a pre-pass, and blended `intr_refl_samples` of them at each
//! shading point: smoother, cheaper glossy results that are, the manual warns, only right
//! on flat surfaces. mira has no pre-pass; it fills a cache while rendering:
//!
//! - The grid is a 3-D lattice in world space whose spacing is the grid density's pixel
//!   step at the shading point (the eye ray's footprint × 0.5 … 5 pixels), rounded to a
//!   power of two so that neighbouring points agree on the lattice (a lattice level per
//!   power of two; where the level changes with distance, neighbours blend different
//!   levels, a small seam).
//! - The value at a lattice point is the layer's glossy colour computed at the point's
//!   projection onto the surface's tangent plane at the shading point that first needs it,
//!   seen from the eye ray's origin, with the layer's usual ray count and a sample sequence
//!   that depends only on the lattice point; it is computed once per material, layer and
//!   instance and kept for the rest of the render (shared by all threads).
//! - A shading point blends the 8 lattice points around it trilinearly, so the result is
//!   continuous across the surface and neighbouring pixels share their noise.
//!
//! Only eye-ray hits interpolate (deeper hits shade as usual, as in mental ray, whose grid
//! is a screen grid). Not done: `intr_refl_samples` / `intr_refr_samples` (mira always
//! blends the 8 surrounding points), the high-detail distance (`intr_refl_ddist`).

use std::collections::HashMap;
use std::sync::Mutex;

use glam::Vec3A;

use shader::ctx::hash;
use shader::{Ctx, NodeId, RayType};

/// Which glossy layer a cached value belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Layer {
    /// The reflection layer's raw colour.
    Reflection,
    /// The refraction layer's raw colour and the alpha of what it saw.
    Refraction,
}

/// A lattice point: layer, level (log₂ of the spacing), integer coordinates, instance.
type Key = (Layer, i32, [i32; 3], u32);

/// The interpolation cache of one material node for one render.
#[derive(Debug, Default)]
pub struct GlossCache {
    points: Mutex<HashMap<Key, (Vec3A, f32)>>,
}

impl GlossCache {
    /// How many lattice points hold a value.
    pub fn len(&self) -> usize {
        self.points.lock().map_or(0, |p| p.len())
    }

    /// Whether no lattice point holds a value yet.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The grid step in pixels for `intr_grid_density` (0: half a pixel; 1 … 5: that many
/// pixels; beyond: 5).
pub fn grid_pixels(density: i32) -> f32 {
    if density <= 0 {
        0.5
    } else {
        density.min(5) as f32
    }
}

/// The lattice level (log₂ of the spacing, scene units) for a grid step of `step`.
pub fn level(step: f32) -> i32 {
    step.log2().round().clamp(-100.0, 100.0) as i32
}

/// Trilinear weights of the 8 corners of the unit cell for fractional position `f`
/// (corner bit 0: x, 1: y, 2: z).
pub fn trilinear(f: Vec3A) -> [f32; 8] {
    let mut w = [0.0; 8];
    for (c, w) in w.iter_mut().enumerate() {
        let pick = |bit: usize, t: f32| if c >> bit & 1 == 1 { t } else { 1.0 - t };
        *w = pick(0, f.x) * pick(1, f.y) * pick(2, f.z);
    }
    w
}

/// The layer's glossy result at the shading point, interpolated from the cache of node `n`
/// (see the module comment): `compute` shades the layer at the state's point and
/// direction. `None` where interpolation does not apply (not an eye-ray hit, no ray
/// footprint): the caller shades as usual.
pub fn interpolated(
    ctx: &mut Ctx,
    n: NodeId,
    layer: Layer,
    density: i32,
    mut compute: impl FnMut(&mut Ctx) -> (Vec3A, f32),
) -> Option<(Vec3A, f32)> {
    let s = &ctx.state;
    let from_eye =
        s.ray_type == RayType::Eye && s.reflection_level == 0 && s.refraction_level == 0 && s.finalgather_level == 0;
    if !(from_eye && s.footprint > 0.0 && s.footprint.is_finite()) {
        return None;
    }
    let lvl = level(s.footprint * grid_pixels(density));
    let cell = 2f32.powi(lvl);
    let (p, ng, org, instance) = (s.point, s.normal_geom, s.org, s.instance);
    let q = p / cell;
    let base = q.floor();
    let weights = trilinear(q - base);
    let cache = ctx.shading().precomputed.get_or_init(n, GlossCache::default)?;
    let mut sum = (Vec3A::ZERO, 0.0);
    for (c, &w) in weights.iter().enumerate() {
        if w <= 0.0 {
            continue;
        }
        let corner = [(c & 1) as i32, (c >> 1 & 1) as i32, (c >> 2 & 1) as i32];
        let ijk = [base.x as i32 + corner[0], base.y as i32 + corner[1], base.z as i32 + corner[2]];
        let key = (layer, lvl, ijk, instance);
        let known = cache.points.lock().ok().and_then(|m| m.get(&key).copied());
        let value = match known {
            Some(v) => v,
            None => {
                let at = Vec3A::new(ijk[0] as f32, ijk[1] as f32, ijk[2] as f32) * cell;
                let v = at_point(ctx, key, at - ng * (at - p).dot(ng), org, &mut compute);
                if let Ok(mut m) = cache.points.lock() {
                    *m.entry(key).or_insert(v)
                } else {
                    v
                }
            }
        };
        sum.0 += value.0 * w;
        sum.1 += value.1 * w;
    }
    Some(sum)
}

/// Runs `compute` as if the eye ray from `org` hit `point` (same surface frame), with a
/// sample sequence of lattice point `key`.
fn at_point(
    ctx: &mut Ctx,
    key: Key,
    point: Vec3A,
    org: Vec3A,
    compute: &mut impl FnMut(&mut Ctx) -> (Vec3A, f32),
) -> (Vec3A, f32) {
    let saved = (ctx.state.point, ctx.state.dir, ctx.state.dot_nd, ctx.state.pixel, ctx.state.sample_index);
    let dir = (point - org).normalize_or(saved.1);
    ctx.state.point = point;
    ctx.state.dir = dir;
    ctx.state.dot_nd = ctx.state.normal.dot(dir);
    let [i, j, k] = key.2.map(|v| v as u32);
    ctx.state.pixel = [hash(&[i, j, k, key.1 as u32]), hash(&[key.3, key.0 as u32])];
    ctx.state.sample_index = 0;
    let v = compute(ctx);
    (ctx.state.point, ctx.state.dir, ctx.state.dot_nd, ctx.state.pixel, ctx.state.sample_index) = saved;
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trilinear_weights_sum_to_one_and_reproduce_linear_functions() {
        for f in [Vec3A::ZERO, Vec3A::new(0.25, 0.5, 0.75), Vec3A::new(0.9, 0.1, 0.3)] {
            let w = trilinear(f);
            assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-6);
            // A linear function of the corners' positions is reproduced exactly.
            let g = |x: f32, y: f32, z: f32| 2.0 * x - 3.0 * y + 0.5 * z + 1.0;
            let got: f32 = (0..8).map(|c| w[c] * g((c & 1) as f32, (c >> 1 & 1) as f32, (c >> 2 & 1) as f32)).sum();
            assert!((got - g(f.x, f.y, f.z)).abs() < 1e-5);
        }
        // At a corner, that corner alone.
        assert_eq!(trilinear(Vec3A::ZERO)[0], 1.0);
    }

    #[test]
    fn grid_steps_and_levels() {
        assert_eq!(grid_pixels(0), 0.5);
        assert_eq!(grid_pixels(2), 2.0);
        assert_eq!(grid_pixels(9), 5.0);
        assert_eq!(level(1.0), 0);
        assert_eq!(level(0.26), -2);
        assert_eq!(level(3.0), 2); // log₂ 3 = 1.58
    }
}
