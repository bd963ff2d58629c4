//! Next-event estimation towards the environment, with mental ray's environment-light
//! settings (`scene::options::modes`): `"environment lighting quality"` averages several
//! directions per estimate ([`Environment::samples`]; noise only, the mean is unchanged),
//! `"environment lighting shadow"` decides what its shadow rays do
//! ([`environment_transmittance`]). With solid shadows or none the environment's direct
//! light is estimated by next-event estimation alone (no MIS: a scattered ray that finds
//! the environment sees through no cut-out the shadow ray would not, and meets surfaces a
//! shadowless light ignores), so that the estimate has the mean the mode asks for.

use bsdf::Rgb;
use glam::Vec2;
use scene::options::EnvironmentShadow;
use shader::Shading;

use super::media::{self, Departure};
use super::{leave, power_heuristic, through_portal, Vertex};
use crate::accel::Accel;
use crate::environment::Environment;
use crate::ray::{mask, Ray, RayCounts};
use crate::sampler::Sampler;
use crate::world::World;

/// The fraction of the environment's light the shadow ray `shadow` (leaving `from`) lets
/// through, as `mode` says: transparent — through cut-outs and transparency, filtered, as
/// other lights' shadow rays; solid — nothing past any surface (media still attenuate);
/// off — only the media's transmittance.
#[allow(clippy::too_many_arguments)]
pub(super) fn environment_transmittance(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    from: &Departure,
    shadow: &Ray,
    seed: u32,
    mode: EnvironmentShadow,
) -> Rgb {
    match mode {
        EnvironmentShadow::Transparent => media::shadow_transmittance(world, accel, shading, from, shadow, seed),
        EnvironmentShadow::Solid if accel.occluded(shadow) => Rgb::ZERO,
        EnvironmentShadow::Solid | EnvironmentShadow::Off => {
            media::light_transmittance(world, accel, shading, from, shadow, seed, false, None)
        }
    }
}

/// Next-event estimation towards the environment (chosen with probability `pick`): the
/// mean of [`Environment::samples`] directions drawn from it (the first by `u`, the
/// others by further numbers of the path's `sampler`, each stratified over the pixel's
/// samples as `u` is), each unless it leaves through a portal (the
/// portal's share) or is shadowed; MIS against the BSDF when `mis` and the shadow mode
/// allow it.
#[allow(clippy::too_many_arguments)]
pub(super) fn environment_light(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    env: &Environment,
    v: &Vertex,
    pick: f32,
    (u, sampler): (Vec2, &mut Sampler),
    seed: u32,
    mis: bool,
    counts: &mut RayCounts,
) -> Rgb {
    let one =
        |u: Vec2, counts: &mut RayCounts| one_direction(world, accel, shading, env, v, pick, u, seed, mis, counts);
    let n = env.samples.max(1);
    if n == 1 {
        return one(u, counts);
    }
    let mut sum = one(u, counts);
    for _ in 1..n {
        sum += one(sampler.next_2d(), counts);
    }
    sum / n as f32
}

/// One direction of [`environment_light`].
#[allow(clippy::too_many_arguments)]
fn one_direction(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    env: &Environment,
    v: &Vertex,
    pick: f32,
    u: Vec2,
    seed: u32,
    mis: bool,
    counts: &mut RayCounts,
) -> Rgb {
    let Some(es) = env.sample(u) else { return Rgb::ZERO };
    if es.pdf <= 0.0 || es.radiance == Rgb::ZERO {
        return Rgb::ZERO;
    }
    let wi = v.frame.to_local(es.dir);
    if (es.dir.dot(v.ng) > 0.0) != (wi.z > 0.0) {
        return Rgb::ZERO;
    }
    let f = v.bsdf.eval(v.wo, wi);
    if f == Rgb::ZERO {
        return Rgb::ZERO;
    }
    let origin = leave::leave_surface(v.p, v.err, v.ng, es.dir);
    if through_portal(&world.lights, origin, es.dir) {
        return Rgb::ZERO;
    }
    counts.shadow_rays += 1;
    let shadow = Ray { mask: mask::SHADOW, origin, dir: es.dir, tmin: 0.0, tmax: f32::INFINITY, time: v.time };
    let tr = environment_transmittance(world, accel, shading, &v.departure, &shadow, seed, env.shadow);
    if tr == Rgb::ZERO {
        return Rgb::ZERO;
    }
    let weight = if mis && !env.nee_only() { power_heuristic(pick * es.pdf, v.bsdf.pdf(v.wo, wi)) } else { 1.0 };
    f * es.radiance * tr * (env.lighting_scale * wi.z.abs() * weight / (pick * es.pdf))
}
