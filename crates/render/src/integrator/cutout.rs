//! Cut-out surfaces (materials with opacity below 1) that rays pass through. Interface:
//! [`MAX_CUTOUT_CROSSINGS`] (most cut-outs a ray crosses before it stops at the next),
//! [`cutout_number`] (the number in [0, 1) a pass-or-stop choice at a point is made with,
//! decorrelated from the path's sampler) and [`shadow_passed`] (the fraction of light a
//! shadow ray lets through past cut-outs); used by the path tracer and by
//! [`super::media`]'s shadow walk.

use bsdf::Rgb;
use glam::Vec3A;
use shader::Shading;

use super::hit_material::material_at;
use super::own_stretch::{passage, OwnStretch};
use super::surface;
use crate::accel::Accel;
use crate::ray::Ray;
use crate::world::World;

/// Most cutout surfaces a ray passes through before it stops at the next one.
pub(super) const MAX_CUTOUT_CROSSINGS: u32 = 64;

/// A number in [0, 1) for a cutout decision at `p`, decorrelated from the path's sampler.
pub(super) fn cutout_number(sampler_seed: u32, p: Vec3A, depth: u32) -> f32 {
    // Each word goes through a full 64-bit avalanche (SplitMix64's finaliser) before the
    // next is added, so nearby points and seeds give independent numbers.
    let mix = |mut z: u64| {
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    };
    let h = [p.x.to_bits(), p.y.to_bits(), p.z.to_bits(), sampler_seed, depth]
        .iter()
        .fold(0x9e37_79b9_7f4a_7c15u64, |h, &w| mix(h.wrapping_add(u64::from(w)).wrapping_mul(0x9e37_79b9_7f4a_7c15)));
    (h >> 40) as f32 / (1u64 << 24) as f32
}

/// The fraction of light (per channel) the shadow ray lets through: 0 when blocked by any
/// surface, or with cutout materials by a surface that does not let it pass (one marked
/// `opaque`, [`World::blocks_shadows`]; else a stochastic choice by its opacity); the
/// product of the cut-out tints of the surfaces it
/// passes ([`material::SurfaceMaterial::cutout_tint`]) otherwise. Where the ray leaves
/// `own` (the receiving point's instance) through a surface with a translucence depth,
/// that surface passes its translucent share instead (`own_stretch`).
pub(super) fn shadow_passed(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    shadow: &Ray,
    seed: u32,
    own: Option<u32>,
) -> Rgb {
    if !world.has_cutouts {
        return if accel.occluded(shadow) { Rgb::ZERO } else { Rgb::ONE };
    }
    let mut ray = *shadow;
    let mut tint = Rgb::ONE;
    let mut stretch = OwnStretch::new(own);
    for crossing in 0..MAX_CUTOUT_CROSSINGS {
        let Some(hit) = accel.intersect(&ray) else { return tint };
        let s = surface(world, &ray, &hit);
        let inside = stretch.step(&hit, &s, ray.dir);
        if world.blocks_shadows(s.material) {
            return Rgb::ZERO;
        }
        let m = material_at(world, accel, shading, &ray, &hit, s.material);
        match passage(world, &m, &s, ray.dir, inside) {
            Some(through) => tint *= through,
            None if m.opacity >= 1.0 || cutout_number(seed, s.p, crossing + 100) < m.opacity => return Rgb::ZERO,
            None => tint *= m.cutout_tint,
        }
        if tint == Rgb::ZERO {
            return Rgb::ZERO;
        }
        let travelled = hit.t;
        ray.origin = s.leave(s.ng, ray.dir);
        ray.tmax = (ray.tmax - travelled).max(0.0);
    }
    Rgb::ZERO
}

/// [`shadow_passed`] (from a point of instance `own`) for light `light` (an index into
/// [`World::lights`]) in a world with
/// shadow links ([`World::casts_shadow_for`]): surfaces of instances that cast no shadow
/// for the light let the ray through untouched; the others stop or filter it as there.
/// (Scenes with media walk them in `media::light_transmittance`.)
pub(super) fn linked_shadow_passed(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    shadow: &Ray,
    seed: u32,
    (light, own): (usize, Option<u32>),
) -> Rgb {
    let mut ray = *shadow;
    let mut tint = Rgb::ONE;
    let mut crossing = 0;
    let mut stretch = OwnStretch::new(own);
    // Surfaces passed for the link count against the same limit as cut-outs, twice over.
    for _ in 0..2 * MAX_CUTOUT_CROSSINGS {
        let Some(hit) = accel.intersect(&ray) else { return tint };
        let s = surface(world, &ray, &hit);
        let inside = stretch.step(&hit, &s, ray.dir);
        if world.casts_shadow_for(light, hit.instance) {
            if !world.has_cutouts || world.blocks_shadows(s.material) {
                return Rgb::ZERO;
            }
            let m = material_at(world, accel, shading, &ray, &hit, s.material);
            match passage(world, &m, &s, ray.dir, inside) {
                Some(through) => tint *= through,
                None if m.opacity >= 1.0 || cutout_number(seed, s.p, crossing + 100) < m.opacity => return Rgb::ZERO,
                None => tint *= m.cutout_tint,
            }
            if tint == Rgb::ZERO {
                return Rgb::ZERO;
            }
            crossing += 1;
        }
        let travelled = hit.t;
        ray.origin = s.leave(s.ng, ray.dir);
        ray.tmax = (ray.tmax - travelled).max(0.0);
    }
    Rgb::ZERO
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cutout numbers of neighbouring points and seeds are uniform: the mean of 40 000
    /// is ½ and each tenth of [0, 1) holds a tenth of them (chi-square below 30, 9 degrees
    /// of freedom; 99.95 % quantile 29.7).
    #[test]
    fn cutout_numbers_are_uniform() {
        let mut cells = [0u32; 10];
        let mut sum = 0.0f64;
        let n = 40_000;
        for i in 0..n {
            let p = Vec3A::new((i % 200) as f32 * 1e-3, (i / 200) as f32 * 1e-3, 1.0);
            let u = cutout_number(i % 7, p, i % 3);
            assert!((0.0..1.0).contains(&u));
            sum += f64::from(u);
            cells[(u * 10.0) as usize] += 1;
        }
        assert!((sum / f64::from(n) - 0.5).abs() < 0.005, "mean {}", sum / f64::from(n));
        let expect = f64::from(n) / 10.0;
        let chi2: f64 = cells.iter().map(|&c| (f64::from(c) - expect).powi(2) / expect).sum();
        assert!(chi2 < 30.0, "chi-square {chi2}: {cells:?}");
    }
}
