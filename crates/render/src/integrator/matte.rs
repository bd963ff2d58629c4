//! Maya's useBackground in the path engine: a shadow-catching matte
//! ([`material::maya::MayaMatte`]).
//!
//! Every ray that stops at the matte (camera, reflected, scattered: as the classic shader
//! shades every ray but light and shadow rays alike) finds
//!
//! ```text
//! background ⊙ (1 − m · shadow) + (r s) ⊙ mirror reflection
//! shadow = Σ_lights (N·L) (1 − f_L) / Σ_lights (N·L)
//! ```
//!
//! the background the environment along the ray (for a camera ray only when the camera
//! sees the environment), m `shadowMask`, the sum over the lights linked to the instance
//! that lie in front of the point (portals left out), f_L the luminance of the share of
//! light L's shadow ray that occluders let through (1 for lights without shadows;
//! `shadowColor` plays no part, as Maya's reference says), r s `reflectivity` ×
//! `specularColor` while the path has made fewer than `reflectionLimit` mirror
//! reflections. The camera ray's alpha is m · shadow, as the classic shader's.

use bsdf::Rgb;
use glam::{Vec2, Vec3A};
use material::maya::MayaMatte;
use shader::Shading;

use super::cutout::shadow_passed;
use super::Surface;
use crate::accel::Accel;
use crate::environment::Environment;
use crate::ray::{mask, Ray, RayCounts};
use crate::world::World;

/// What a ray finds at the matte.
pub(super) struct MatteHit {
    /// The radiance it sends back along the ray besides its reflection.
    pub color: Rgb,
    /// m · shadow (the classic shader's alpha).
    pub alpha: f32,
    /// The mirror reflection: its weight and the reflected ray; `None` when it does not
    /// reflect.
    pub mirror: Option<(Rgb, Ray)>,
}

/// Where and how a ray reached the matte.
pub(super) struct Arrival<'a> {
    /// The ray (its direction unit).
    pub ray: &'a Ray,
    /// The surface it stopped at.
    pub surface: &'a Surface,
    /// The instance hit (light linking).
    pub instance: u32,
    /// Whether it is the camera ray.
    pub camera: bool,
    /// The mirror reflections the path has made before.
    pub reflections: u32,
}

/// The matte `matte` as the ray of `at` finds it; `u` picks the lights' shadow rays (soft
/// shadows), `seed` the cut-out choices along them.
#[allow(clippy::too_many_arguments)]
pub(super) fn shade(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    env: Option<&Environment>,
    matte: &MayaMatte,
    at: &Arrival,
    u: Vec2,
    seed: u32,
    counts: &mut RayCounts,
) -> MatteHit {
    let (ray, s) = (at.ray, at.surface);
    // The normals turned towards the ray.
    let (ng, ns) = if s.ng.dot(ray.dir) <= 0.0 { (s.ng, s.ns) } else { (-s.ng, -s.ns) };
    let background = match env {
        Some(env) if !at.camera || env.camera_visible => env.radiance(ray.dir),
        _ => Rgb::ZERO,
    };
    let shadow = if matte.shadow_mask > 0.0 {
        matte.shadow_mask * blocked_share(world, accel, shading, at, (ng, ns), u, seed, counts)
    } else {
        0.0
    };
    let mirror = (matte.mirror != Rgb::ZERO && at.reflections < matte.reflection_limit).then(|| {
        let dir = ray.dir - 2.0 * ray.dir.dot(ns) * ns;
        let dir = if dir.dot(ng) > 0.0 { dir } else { (dir - 2.0 * dir.dot(ng) * ng).normalize_or(ng) };
        let next = Ray {
            mask: mask::SECONDARY,
            origin: s.leave(ng, dir),
            dir,
            tmin: 0.0,
            tmax: f32::INFINITY,
            time: ray.time,
        };
        (matte.mirror, next)
    });
    MatteHit { color: background * (1.0 - shadow), alpha: shadow, mirror }
}

/// Σ (N·L)(1 − f_L) / Σ (N·L) over the lights in front of the point (see the module
/// doc); 0 without any.
#[allow(clippy::too_many_arguments)]
fn blocked_share(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    at: &Arrival,
    (ng, ns): (Vec3A, Vec3A),
    u: Vec2,
    seed: u32,
    counts: &mut RayCounts,
) -> f32 {
    let (p, time) = (at.surface.p, at.ray.time);
    let (mut blocked, mut total) = (0.0f32, 0.0f32);
    for (k, light) in world.lights.iter().enumerate() {
        if light.is_portal() || !world.lights_instance(k, at.instance) {
            continue;
        }
        let Some(ls) = light.sample_at(p, u, time) else { continue };
        let cos = ns.dot(ls.wi);
        if !(cos > 0.0 && ls.wi.dot(ng) > 0.0) {
            continue;
        }
        total += cos;
        if !light.shadow {
            continue;
        }
        let (dir, dist) = light.shadow_ray_at(p, &ls, u, time);
        let tmax = if dist.is_finite() { dist * (1.0 - 1e-4) } else { f32::INFINITY };
        counts.shadow_rays += 1;
        let shadow = Ray { mask: mask::SHADOW, origin: at.surface.leave(ng, dir), dir, tmin: 0.0, tmax, time };
        let through =
            bsdf::luminance(shadow_passed(world, accel, shading, &shadow, seed, Some(at.instance))).clamp(0.0, 1.0);
        blocked += cos * (1.0 - through);
    }
    if total > 0.0 {
        blocked / total
    } else {
        0.0
    }
}
