//! Where a path meets the light from infinitely far away: portal windows a ray leaves
//! through, and the environment a ray that left the scene sees (its MIS weight against
//! environment sampling); and the way towards a point on a sphere of light (Maya's
//! ambient lights' raytraced shadows).

use bsdf::Rgb;
use glam::Vec3A;

use super::power_heuristic;
use crate::environment::Environment;
use crate::light::LightSource;
use crate::ray::Ray;

/// Whether a ray from `origin` along unit `dir` leaves through the emitting side of a portal
/// window: the portal light then accounts for the environment in that direction.
pub(super) fn through_portal(lights: &[LightSource], origin: Vec3A, dir: Vec3A) -> bool {
    lights.iter().any(|l| l.is_portal() && l.intersect(&Ray::new(origin, dir)).is_some())
}

/// The environment seen by a ray that left the scene after `depth` bounces: all of it for
/// camera rays (when the camera sees it), after delta bounces and when next-event
/// estimation does not sample it, else its MIS share
/// against environment sampling chosen with probability `pick` (none without MIS).
pub(super) fn environment_seen(
    env: &Environment,
    ray: &Ray,
    depth: u32,
    last: (f32, bool),
    pick: f32,
    mis: bool,
) -> Rgb {
    let (last_pdf, last_delta) = last;
    if depth == 0 {
        return if env.camera_visible { env.radiance(ray.dir) } else { Rgb::ZERO };
    }
    let weight = if last_delta || !env.sampled {
        1.0
    } else if mis && !env.nee_only() {
        power_heuristic(last_pdf, pick * env.pdf(ray.dir))
    } else {
        0.0
    };
    if weight == 0.0 {
        return Rgb::ZERO;
    }
    // After a mirror bounce the environment is seen; after others it is light.
    let l = if last_delta { env.radiance(ray.dir) } else { env.light_radiance(ray.dir) };
    l * (env.lighting_scale * weight)
}

/// The direction (unit) and distance from `p` to a point uniform over the surface of the
/// sphere of `radius` around `centre`, picked by `u` (uniform in [0, 1)²); to the centre
/// itself when that point is `p`.
pub(super) fn towards_sphere(p: Vec3A, centre: Vec3A, radius: f32, u: glam::Vec2) -> (Vec3A, f32) {
    let z = 1.0 - 2.0 * u.x;
    let s = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * u.y;
    let d = centre + radius * Vec3A::new(s * phi.cos(), s * phi.sin(), z) - p;
    let dist = d.length();
    if dist > 0.0 && dist.is_finite() {
        (d / dist, dist)
    } else {
        let d = centre - p;
        (d.normalize_or(Vec3A::Y), d.length())
    }
}
