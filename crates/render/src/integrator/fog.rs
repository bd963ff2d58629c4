//! The camera's volume (mental ray's atmosphere, e.g. Maya's environment and light fogs) in
//! the path engine.
//!
//! mental ray runs the camera's volume shader on the colour each eye, reflection,
//! refraction, transparency and final gather ray brings back over its segment, outside
//! the materials a ray has entered. The path engine adds light forward instead (each
//! contribution weighted by the path's throughput), so it applies a volume whose effect is
//! affine in the colour it receives — c ↦ keep ⊙ c + add over the segment, as Maya's fogs
//! are ([`shader::volume::VolumeTerms`]) — exactly: at every segment of a path outside the
//! path engine's media it adds throughput ⊙ add (the fog's own light in front of what lies
//! behind) and multiplies the throughput by keep (what lies behind, the environment and
//! everything found later along the path). The terms come from the same shader code the
//! classic engine runs, on the same volume state (`org`, `dir`, `point`, `dist`; a ray
//! that leaves the scene has an infinite segment), so both engines give the same fog:
//! a camera ray's composite is the classic eye ray's, and rays after a bounce see it as
//! the classic engine's reflection, refraction and final gather rays do. Shadow rays of
//! next-event estimation pass unchanged, as light and shadow rays pass the classic fogs.
//!
//! What differs: the classic engine leaves the atmosphere inside a closed object a ray
//! refracted into (that material's volume, often none, is current there); the path
//! engine keeps the camera's volume on every segment outside its participating media.
//! A camera volume with any shader that tells no affine terms is not applied (a warning
//! at compile time names it).

use glam::Vec3A;
use shader::volume::VolumeTerms;
use shader::{Ctx, NodeId, RayType, Shading, State};

use crate::accel::Accel;
use crate::ray::Ray;
use crate::world::World;

/// The camera's volume shader list when the path engine applies it: every shader in it
/// tells its affine terms ([`shader::volume::is_affine`]).
pub(super) fn camera_fog(shading: Option<&Shading>) -> Option<(&Shading, NodeId)> {
    let shading = shading?;
    let head = shading.volume?;
    shader::volume::is_affine(shading, head).then_some((shading, head))
}

/// The terms of the camera volume `fog` over the segment of `ray` up to distance `t_end`
/// (infinite: the ray left the scene), for a ray of type `ray_type` after `depth` bounces.
#[allow(clippy::too_many_arguments)]
pub(super) fn segment_terms(
    world: &World,
    accel: &dyn Accel,
    shading: &Shading,
    fog: NodeId,
    ray: &Ray,
    t_end: f32,
    ray_type: RayType,
    depth: u32,
) -> VolumeTerms {
    let tracer = crate::tracer::SceneTracer::new(world, accel);
    // mental ray's volume state: a ray that hit nothing has `point` = `org`, `dist` 0.
    let (point, dist) = if t_end.is_finite() { (ray.origin + ray.dir * t_end, t_end) } else { (ray.origin, 0.0) };
    let state = State {
        ray_type,
        reflection_level: depth,
        org: ray.origin,
        dir: ray.dir,
        point,
        dist,
        ior_in: 1.0,
        ior: 1.0,
        child_dist: f32::INFINITY,
        time: ray.time,
        ..State::default()
    };
    let mut ctx = Ctx::new(shading, &tracer, state);
    ctx.volume_terms(fog).unwrap_or(VolumeTerms::NONE)
}

/// The mental ray ray type of a path's segment after `depth` bounces: the camera's ray,
/// then a reflection or a refraction by the side the last bounce left `ng` (the surface's
/// normal facing the arriving ray) on along `dir`; `Finalgather` after a diffuse or glossy
/// bounce (`delta` false).
pub(super) fn segment_type(depth: u32, delta: bool, ng: Vec3A, dir: Vec3A) -> RayType {
    match (depth, delta) {
        (0, _) => RayType::Eye,
        (_, false) => RayType::Finalgather,
        _ if dir.dot(ng) >= 0.0 => RayType::Reflect,
        _ => RayType::Refract,
    }
}
