//! Unidirectional path tracing with next-event estimation and multiple importance sampling
//! (power heuristic), Russian roulette after a few bounces (by each bounce's own weight);
//! participating media inside surfaces in [`media`], the camera's volume (Maya's fogs) in
//! [`fog`].

mod ambient_highlight;
mod cutout;
mod deep_material;
mod emitters;
mod env_light;
mod fog;
mod gi_depth;
mod glossy_reach;
mod hit_material;
mod hit_surface;
mod lambert_hit;
mod leave;
mod levels;
mod light_lobes;
mod material_env;
mod matte;
mod media;
mod own_stretch;
mod path_state;
mod plain_path;
mod roulette;

use bsdf::Bsdf;
use bsdf::{Frame, Rgb};
use glam::Vec3A;
use material::HitMaterial;
use shader::{RayType, Shading};

use crate::accel::{Accel, Hit};
use crate::environment::Environment;
use crate::light::LightSource;
use crate::ray::{mask, FirstHit, Ray, RayCounts};
use crate::sampler::Sampler;
use crate::world::World;
use cutout::{cutout_number, linked_shadow_passed, shadow_passed, MAX_CUTOUT_CROSSINGS};
use emitters::{environment_seen, through_portal, towards_sphere};
pub use hit_material::constant_materials;
use hit_material::material_at;
pub use hit_surface::hit_normals;
use hit_surface::{surface, surface_into, Surface};
use media::Departure;
pub use media::{camera_media_at, camera_ray_media, media_at, MediumStack};
use path_state::Resume;
pub use plain_path::plain_materials;
use roulette::roulette_survival;

/// Integrator settings.
#[derive(Clone, Copy, Debug)]
pub struct PathSettings {
    /// Most scattering events along a path.
    pub max_depth: u32,
    /// Bounces before Russian roulette starts. From then on a path goes on past a surface
    /// with the probability of that bounce's own weight (its largest channel, at most 0.95:
    /// [`roulette::roulette_survival`]); past a medium's scattering with that of its throughput's.
    pub rr_depth: u32,
    /// Combine light and BSDF sampling with MIS (off: light sampling only for lights that
    /// can be sampled, BSDF sampling only for emitters that cannot).
    pub mis: bool,
}

impl Default for PathSettings {
    fn default() -> PathSettings {
        PathSettings { max_depth: 16, rr_depth: 3, mis: true }
    }
}

/// The result of one camera path.
#[derive(Clone, Copy, Debug)]
pub struct PathResult {
    /// Radiance.
    pub radiance: Rgb,
    /// 1 when the path hit something (geometry or a visible light).
    pub alpha: f32,
    /// The first hit, if any.
    pub first: Option<FirstHit>,
    /// The glow of the surface the camera ray stopped at (its material's
    /// [`material::SurfaceMaterial::glow`], zero when it does not glow); `None` when the
    /// camera ray stopped at no surface.
    pub glow: Option<Rgb>,
    /// The first bounce's shadow ray when the caller asked to trace it itself
    /// ([`CameraRay::defer_shadow`]): then `radiance` is the path's radiance if the ray is
    /// not blocked, and this holds the radiance if it is.
    pub pending: Option<PendingShadow>,
}

/// A camera path's first shadow ray, left to the caller (which traces it with its
/// neighbours' in one packet, [`Accel::occluded_batch`]).
#[derive(Clone, Copy, Debug)]
pub struct PendingShadow {
    /// The shadow ray (world space), as the path would have traced it.
    pub ray: Ray,
    /// The path's radiance if `ray` is blocked.
    pub blocked: Rgb,
}

impl PathResult {
    /// No radiance, nothing hit: a placeholder for a result still to be traced.
    pub const EMPTY: PathResult =
        PathResult { radiance: Rgb::ZERO, alpha: 0.0, first: None, glow: None, pending: None };

    /// The radiance of the path given whether its pending shadow ray is `blocked` (the
    /// radiance itself when none is pending).
    pub fn radiance_given(&self, blocked: bool) -> Rgb {
        match self.pending {
            Some(p) if blocked => p.blocked,
            _ => self.radiance,
        }
    }
}

/// Power heuristic weight of a strategy with density `a` against one with `b`.
fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 == 0.0 {
        0.0
    } else {
        a2 / (a2 + b2)
    }
}

/// The closest visible light hit by `ray` before distance `tmax` (instead of the ray's
/// own); camera rays pass through portal windows. (Inlined into the path loop: every ray
/// asks it.)
#[inline]
fn hit_light(lights: &[LightSource], ray: &Ray, tmax: f32, camera: bool) -> Option<(usize, f32, Rgb)> {
    let mut best: Option<(usize, f32, Rgb)> = None;
    for (i, l) in lights.iter().enumerate() {
        if !l.visible || camera && l.is_portal() {
            continue;
        }
        if let Some((t, le)) = l.intersect_until(ray, tmax) {
            if best.is_none_or(|(_, bt, _)| t < bt) {
                best = Some((i, t, le));
            }
        }
    }
    best
}

/// Radiance `le` of a light's surface seen along unit `dir`; a portal's is its scale × the
/// environment seen through it along `dir` (× the environment's lighting scale).
fn light_radiance(light: &LightSource, le: Rgb, env: Option<&Environment>, dir: Vec3A) -> Rgb {
    if !light.is_portal() {
        return le;
    }
    env.map_or(Rgb::ZERO, |env| le * env.light_radiance(dir) * env.lighting_scale)
}

/// A shading point as next-event estimation sees it.
struct Vertex<'v> {
    p: Vec3A,
    /// How far `p` may lie off the surface ([`Surface::err`]).
    err: f32,
    /// The path's shutter time.
    time: f32,
    ng: Vec3A,
    frame: &'v Frame,
    wo: Vec3A,
    bsdf: &'v Bsdf,
    /// Where its shadow rays leave from (the media they start in).
    departure: Departure<'v>,
}

/// The local shading frame around the unit normal `ns`: its x axis along the material's
/// tangent (the axis an anisotropic lobe is stretched along), or any tangent when the
/// material names none.
#[inline]
fn shading_frame(ns: Vec3A, tangent: Option<Vec3A>) -> Frame {
    match tangent {
        Some(t) => Frame::from_normal_and_tangent(ns, t),
        None => Frame::from_normal(ns),
    }
}

/// Traces one camera path through `scene` (its compiled shader graph evaluates materials
/// with connected parameters; its environment lights it from infinitely far away; its
/// constant materials, [`constant_materials`], built once by the caller for all its paths).
///
/// Portal lights (`mia_portal_light`) and the environment share the environment's light
/// without counting it twice: a ray that crosses a portal window from its emitting side
/// finds the portal (radiance: the environment along the ray × the portal's scale, MIS
/// against sampling the portal), whatever lies beyond; only rays that leave the scene
/// without crossing one find the environment (MIS against sampling the environment), and
/// environment samples whose direction crosses a portal count nothing. Camera rays pass
/// through portals.
///
/// `camera_media` are the media around the camera ray's origin (see [`media_at`]; the
/// default outside all).
pub fn trace_path(
    scene: &PathScene,
    camera_ray: Ray,
    camera_media: &MediumStack,
    sampler: &mut Sampler,
    settings: &PathSettings,
    counts: &mut RayCounts,
) -> PathResult {
    let camera = CameraRay { ray: camera_ray, hit: None, defer_shadow: false };
    trace_camera_path(scene, camera, camera_media, sampler, settings, counts)
}

/// What paths are traced in: the scene and what the render made of it once.
#[derive(Clone, Copy)]
pub struct PathScene<'a> {
    /// The scene.
    pub world: &'a World,
    /// Its acceleration structure.
    pub accel: &'a dyn Accel,
    /// The compiled shader graph (materials with connected parameters, fogs).
    pub shading: Option<&'a Shading>,
    /// The environment lighting the scene from infinitely far away, if any.
    pub env: Option<&'a Environment<'a>>,
    /// `world`'s materials with their constant parameters ([`constant_materials`]).
    pub constants: &'a [HitMaterial<'a>],
    /// Which of them the compact kernel for plain hits may trace ([`plain_materials`],
    /// built with `shading`); empty: the general loop traces every path.
    pub plain: &'a [bool],
}

/// A camera ray, and what [`Accel::intersect`] finds along it when that is known already
/// (a tile's camera rays traced together, [`Accel::intersect_batch`]).
#[derive(Clone, Copy, Debug)]
pub struct CameraRay {
    /// The ray (world space).
    pub ray: Ray,
    /// `Some(found)`: the closest hit along `ray`, as `accel.intersect(&ray)` gives it;
    /// `None`: not traced yet.
    pub hit: Option<Option<Hit>>,
    /// Leave the first bounce's shadow ray to the caller ([`PathResult::pending`]) where
    /// its answer is all or nothing (a light that casts shadows, no `shadowColor`, a scene
    /// without media or cutouts); `false`: trace it in the path.
    pub defer_shadow: bool,
}

/// [`trace_path`] from a [`CameraRay`] whose closest hit may be known already (then the
/// path is the same, bit for bit, as the one traced from the bare ray).
#[inline]
pub fn trace_camera_path(
    scene: &PathScene,
    camera: CameraRay,
    camera_media: &MediumStack,
    sampler: &mut Sampler,
    settings: &PathSettings,
    counts: &mut RayCounts,
) -> PathResult {
    let mut result = PathResult::EMPTY;
    trace_camera_path_into(scene, camera, camera_media, sampler, settings, counts, &mut result);
    result
}

/// [`trace_camera_path`] writing its result to `out` (where the caller keeps it: a
/// result returned by value was copied there through a `memcpy`).
pub fn trace_camera_path_into(
    scene: &PathScene,
    camera: CameraRay,
    camera_media: &MediumStack,
    sampler: &mut Sampler,
    settings: &PathSettings,
    counts: &mut RayCounts,
    out: &mut PathResult,
) {
    // Paths that meet only plain surfaces are traced by a compact kernel of their own
    // (`plain_path`); it hands any other path over at the bounce it meets anything else.
    let resume = if !scene.plain.is_empty() && camera_media.is_empty() {
        match plain_path::trace(scene, &camera, camera_media, sampler, settings, counts, out) {
            Some(handed) => handed,
            None => return,
        }
    } else {
        Resume::camera(&camera)
    };
    let PathScene { world, accel, shading, env, constants, .. } = *scene;
    let Resume { depth: start, mut ray, known: mut camera_hit, mut throughput, .. } = resume;
    let mut radiance = resume.radiance;
    // The first bounce's shadow ray, when it is left to the caller.
    let (mut pending, mut first, mut glow, mut alpha) = (resume.pending, resume.first, resume.glow, resume.alpha);
    // The BSDF density of the last bounce (for MIS on lights hit), and whether it was a delta.
    let (mut last_pdf, mut last_delta) = (resume.last_pdf, resume.last_delta);
    // The environment of the material the path last scattered at, when it has its own.
    let mut last_env = None;
    // The glossy share of the last bounce, where it splits what its rays see.
    let mut reach: Option<glossy_reach::Reach> = None;
    // The share of the last bounce that next-event estimation left out (`glossy_reach::unlit_share`).
    let mut unlit = Rgb::ZERO;
    let light_count = world.lights.len();
    // The environment is one more light to choose for next-event estimation.
    let choices = light_count + usize::from(env.is_some_and(|e| e.sampled));
    let pick = if choices > 0 { 1.0 / choices as f32 } else { 0.0 };
    let seed = sampler.stream();
    // The media the path is in.
    let mut media = camera_media.clone();
    // The instance the path last scattered at (light linking; none at the camera).
    let mut from_instance = resume.from_instance;
    // The camera's and materials' fogs, when the path engine applies them (see `fog`),
    // the mental ray type of the path's current segment, and the share of the camera
    // ray's colour they cover (for alpha, as the classic fogs give it).
    let mut fogs = fog::PathFog::new(shading);
    // (Most scenes have no fog: the bookkeeping is then skipped.)
    let fog_possible = fogs.possible();
    let mut segment_type = RayType::Eye;
    let mut fog_cover = 0.0f32;
    // The mirror and glossy reflections the path has made (Maya's `reflectionLimit`
    // counts them as mental ray's reflection level does; see `levels`).
    let mut reflections = 0u32;
    // The delta transmissions and cut-out passes the path has made (Maya's
    // `refractionLimit` counts them as mental ray's refraction level counts refraction
    // and transparency rays).
    let mut refractions = 0u32;
    // The material of the surface last found, when it is not the constant one of
    // `world.materials` (connected parameters, view-dependent transparency); `None` for a
    // constant one, which is built after the cutout loop, in its place. Written where it
    // lives and only read by reference: moved as an `Option` (208 bytes) it went through
    // two `memcpy` calls at every hit, constant or not, whose wide loads of fields just
    // stored stalled on store forwarding; declared out here, it is dropped once a path
    // rather than at every bounce (speed29 in `docs/performance.md`).
    let mut varying: Option<HitMaterial> = None;
    // The surface data of the last hit found (written in place, [`surface_into`]).
    let mut s = Surface::UNSET;
    for depth in start..settings.max_depth {
        counts.rays += 1;
        // (The last bounce's glossy share, `reach`, is read where it is used below, not
        // moved out here at every bounce: every bounce that goes on sets it anew.)
        // The nearest surface that stops the ray (cutouts let it through by their
        // opacity): its hit, and in `s` its surface data.
        let mut found: Option<Hit> = None;
        // The ray on from the last cutout it passed (none passed: `ray` itself, not copied).
        let mut passed: Option<Ray> = None;
        for crossing in 0..MAX_CUTOUT_CROSSINGS {
            let through = passed.as_ref().unwrap_or(&ray);
            // The camera ray's hit may be known (only for the ray itself, not past a cutout).
            let h = match camera_hit.take() {
                Some(known) => known,
                None => accel.intersect(through),
            };
            let Some(h) = h else { break };
            surface_into(world, through, &h, &mut s);
            let surface_material = &world.materials[s.material as usize];
            let constant =
                !(shading.is_some() && surface_material.is_varying()) && surface_material.view_transparency.is_none();
            if !constant {
                varying = Some(material_at(world, accel, shading, through, &h, s.material));
            } else if varying.is_some() {
                // (A varying material's hit passed through before.)
                varying = None;
            }
            // (What `material_at` gives a constant material, read in place.)
            let (opacity, refracts, cutout_tint) = match &varying {
                Some(m) => (m.opacity, m.model.refracts(), m.cutout_tint),
                None => (surface_material.opacity, surface_material.model.refracts(), surface_material.cutout_tint),
            };
            // (A Maya material that refracts stops every ray but shadow rays: its BSDF
            // refracts them.)
            if opacity >= 1.0
                || refracts
                || surface_material.maya_matte.is_some()
                || cutout_number(seed, s.p, depth * MAX_CUTOUT_CROSSINGS + crossing) < opacity
            {
                // Distances along the original ray.
                let t = (s.p - ray.origin).dot(ray.dir);
                found = Some(Hit { t, ..h });
                break;
            }
            counts.rays += 1;
            // A coloured transparency filters what passes, per channel; the pass is a
            // transparency ray of mental ray's refraction level (Maya's `refractionLimit`).
            throughput *= cutout_tint;
            refractions += 1;
            if fog_possible {
                fogs.passed_through(s.material, (s.p - ray.origin).dot(ray.dir), h.instance);
            }
            passed = Some(Ray { origin: s.leave(s.ng, ray.dir), ..ray });
        }
        let hit = found;
        let tmax = hit.map_or(ray.tmax, |h| h.t);
        let light_hit = hit_light(&world.lights, &ray, tmax, depth == 0);
        if !media.is_empty() {
            // In a medium the ray may scatter before what it found.
            let t_end = light_hit.map_or(tmax, |(_, t, _)| t);
            // What the medium emits along the whole segment, attenuated on the way.
            if let Some(m) = media.current(world).filter(|m| m.emission != Rgb::ZERO) {
                radiance += throughput * m.emitted(t_end);
            }
            match media::fly(world, &media, t_end, throughput, sampler) {
                Some(bsdf::medium::Flight::Scattered { t, weight }) => {
                    throughput *= weight;
                    let Some(medium) = media.current(world) else { break };
                    let p = ray.origin + ray.dir * t;
                    let lighting = media::Lighting {
                        world,
                        accel,
                        shading,
                        env,
                        pick,
                        choices,
                        seed,
                        mis: settings.mis && depth + 1 < settings.max_depth,
                    };
                    radiance += throughput
                        * media::direct_light(
                            &lighting,
                            medium,
                            &media,
                            (p, throughput),
                            ray.dir,
                            ray.time,
                            sampler,
                            counts,
                        );
                    // (A grey phase function's sample weighs exactly 1; a chromatic one picks
                    // its channel by the throughput.)
                    let bsdf::PhaseSample { dir, pdf, weight } =
                        medium.phase.sample(ray.dir, sampler.next_2d(), throughput);
                    throughput *= weight;
                    last_pdf = pdf;
                    last_delta = false;
                    last_env = None;
                    from_instance = None;
                    let u_rr = sampler.next_1d();
                    if depth + 1 >= settings.rr_depth {
                        let q = throughput.max_element().min(0.95);
                        if q <= 0.0 || u_rr >= q {
                            break;
                        }
                        throughput /= q;
                    }
                    ray = Ray { mask: mask::SECONDARY, origin: p, dir, tmin: 0.0, tmax: f32::INFINITY, time: ray.time };
                    reach = None;
                    unlit = Rgb::ZERO;
                    continue;
                }
                Some(bsdf::medium::Flight::Through { weight }) => throughput *= weight,
                None => {}
            }
        }
        if fog_possible && fogs.is_active() {
            // The fogs over the segment, in front of all that lies behind it.
            let (t_end, end) = match (&light_hit, &hit) {
                (Some((_, t, _)), _) => (*t, None),
                (None, Some(h)) => (h.t, Some(h.instance)),
                (None, None) => (f32::INFINITY, None),
            };
            let apply = media.is_empty();
            let terms = fogs.along(world, accel, &ray, t_end, end, segment_type, depth, apply);
            if apply {
                radiance += throughput * terms.add;
                throughput *= terms.keep;
                if depth == 0 {
                    fog_cover = (3.0 - terms.keep.element_sum()) / 3.0;
                }
            }
        }
        if let Some(r) = reach {
            // Past a glossy bounce whose rays see the environment their own way.
            let d = light_hit.map(|(_, t, _)| t).or(hit.map(|h| h.t)).unwrap_or(f32::INFINITY);
            let left = light_hit.is_none() && found.is_none();
            let (keep, weight, deep) = r.segment(d, left);
            if let Some(deep) = deep {
                radiance += throughput * deep;
            }
            if weight != Rgb::ZERO {
                radiance += throughput
                    * weight
                    * glossy_reach::environment(world, accel, shading, env, last_env, ray.dir, last_delta);
            }
            if left {
                break;
            }
            throughput *= keep;
            unlit = r.unlit_after(unlit, d);
        }
        if let (None, None, Some(node), Some(shading)) = (&light_hit, &found, last_env, shading) {
            // Left a material with an environment of its own: that one, all of it.
            radiance += throughput * material_env::radiance(world, accel, shading, node, ray.dir, !last_delta);
            break;
        }
        if let (None, None, Some(env)) = (&light_hit, &found, env) {
            // Left the scene: the environment.
            let le = environment_seen(env, &ray, depth, (last_pdf, last_delta), pick, settings.mis);
            if depth == 0 && le != Rgb::ZERO {
                alpha = 1.0;
            }
            radiance += throughput * le;
            break;
        }
        if let Some((li, t, le)) = light_hit {
            let le = light_radiance(&world.lights[li], le, env, ray.dir);
            if depth == 0 {
                alpha = 1.0;
            }
            // Emission found by the BSDF: all of it when light sampling could not have
            // found it (camera rays, delta bounces); else the MIS share, or nothing when
            // light sampling alone accounts for it.
            let linked = from_instance.is_none_or(|i| world.lights_instance(li, i));
            let weight = if !linked {
                0.0
            } else if depth == 0 || last_delta {
                1.0
            } else if settings.mis {
                power_heuristic(last_pdf, pick * world.lights[li].pdf_at(ray.origin, ray.dir, t, ray.time))
            } else {
                0.0
            };
            let weight = glossy_reach::hit_weight(if linked { unlit } else { Rgb::ZERO }, weight);
            radiance += throughput * le * weight;
            break;
        }
        let Some(stop) = found else { break };
        // (A constant material is read where the render built it once.)
        let material: &HitMaterial = match &varying {
            Some(m) => m,
            None => &constants[s.material as usize],
        };
        let own_env = material_env::own(shading, s.material);
        if depth == 0 {
            alpha = 1.0;
            let motion = crate::tracer::hit_motion(world, &stop, s.p, ray.time);
            first = Some(FirstHit { point: s.p, normal: s.ns, tag: s.tag, motion });
            glow = Some(material.glow);
        }
        if let Some(m) = &world.materials[s.material as usize].maya_matte {
            // Maya's useBackground: the background less the shadows, and its mirror.
            let at =
                matte::Arrival { ray: &ray, surface: &s, instance: stop.instance, camera: depth == 0, reflections };
            let hit = matte::shade(world, accel, shading, env, m, &at, sampler.next_2d(), seed, counts);
            alpha = if depth == 0 { hit.alpha } else { alpha };
            radiance += throughput * hit.color;
            let Some((weight, next)) = hit.mirror else { break };
            (throughput, ray, reflections, last_delta, from_instance) =
                (throughput * weight, next, reflections + 1, true, Some(stop.instance));
            last_env = own_env;
            reach = None;
            unlit = Rgb::ZERO;
            continue;
        }
        // The commonest hit, one Lambertian lobe, skips the general BSDF's dispatch below
        // (`lambert_hit`: the same numbers bit for bit).
        let lambert = lambert_hit::is_lambert(material);
        if material.emission != Rgb::ZERO {
            let spread =
                material.emission_shape.as_deref().map_or(Rgb::ONE, |e| e.factor(s.ns, material.tangent, -ray.dir));
            radiance += throughput * material.emission * spread;
        }
        // Two-sided shading: face the normals towards the ray, unless light can enter the
        // surface — then the front is outside, and a ray from behind sees the inside.
        let facing = !lambert && material.model.has_inside() || s.ng.dot(ray.dir) <= 0.0;
        let (ng, mut ns) = if facing { (s.ng, s.ns) } else { (-s.ng, -s.ns) };
        if let Some(bent) = material.normal {
            // A bump or normal map (given facing the ray): on the side of `ns`.
            ns = if bent.dot(ns) < 0.0 { -bent } else { bent };
        }
        let frame = shading_frame(ns, material.tangent);
        let wo = frame.to_local(-ray.dir);
        let mut bsdf = if lambert {
            Bsdf::Lambert(bsdf::Lambert { albedo: material.diffuse })
        } else {
            material.model.bsdf_in(material.diffuse, wo, &frame)
        };
        if let Bsdf::Maya(b) = &mut bsdf {
            // Maya's `reflectionLimit`: no mirror past that many reflections; and
            // what the mirror's weight adds besides them (`reflectedColor`).
            if reflections >= b.reflection_limit {
                b.without_mirror();
            }
            // Maya's refraction: leaving through the back (mental ray's `inv_normal`), and
            // straight past `refractionLimit`.
            b.refract_at(s.ng.dot(ray.dir) > 0.0, refractions);
            radiance += throughput * b.emitted;
        }
        // (Built where a shadow ray leaves: most bounces trace theirs in a packet or not at all.)
        let departure = || Departure { media: &media, surface: Some((s.material, s.ng, &ray, &stop)) };
        // Next-event estimation (the sample numbers are drawn even when unused, so that
        // every bounce uses the same dimensions).
        let choice = sampler.next_1d();
        let u_light = sampler.next_2d();
        // Maya's ambient lights: the material's colour × what they give here, added as
        // it is (no BSDF; a shadow ray for those with raytraced shadows, over the sphere
        // of their `lightRadius` by `u_light`; see `material::emission::ambient`), and
        // the highlight of volume lights among them with `emitSpecular`. (The scene's list
        // first: most scenes have none, and then the material's colour is not read.)
        if !world.ambient.is_empty() && world.materials[s.material as usize].ambient != Rgb::ZERO {
            let ambient = world.materials[s.material as usize].ambient;
            let (mut sum, mut highlight) = (Rgb::ZERO, Rgb::ZERO);
            for a in world.ambient_lighting(stop.instance) {
                let through = match a.shadow {
                    Some(shadow) => {
                        let (dir, dist) = towards_sphere(s.p, a.source(s.p), shadow.radius, u_light);
                        let origin = s.leave(ng, dir);
                        counts.shadow_rays += 1;
                        let shadow = Ray {
                            mask: mask::SHADOW,
                            origin,
                            dir,
                            tmin: 0.0,
                            tmax: dist * (1.0 - 1e-4),
                            time: ray.time,
                        };
                        media::light_transmittance(world, accel, shading, &departure(), &shadow, seed, true, None)
                    }
                    None => Rgb::ONE,
                };
                sum += a.shadowed_at(s.p, ns, through);
                let at = ambient_highlight::Viewpoint { p: s.p, ns, ng, frame: &frame, wo };
                let classic = world.materials[s.material as usize].maya_highlight.as_ref();
                highlight += ambient_highlight::radiance(a, &at, through, classic, &bsdf);
            }
            radiance += throughput * (material.diffuse * ambient * sum + highlight);
        }
        // At the last vertex no scattered ray follows to find the lights by BSDF sampling:
        // light sampling takes all of their light (no MIS), or a short depth loses it.
        let mis = settings.mis && depth + 1 < settings.max_depth;
        // (One choice — one light, the common case — needs no float-to-index conversion.)
        let k = if choices <= 1 { 0 } else { ((choice * choices as f32) as usize).min(choices - 1) };
        // (A Lambertian lobe neither fades into a deep material nor is a delta: light
        // sampling always applies.)
        let reaching = !lambert && glossy_reach::reaches(&material.model);
        let unlit_lobe = !lambert && glossy_reach::unlit_lobe(&material.model);
        let env_here = env.filter(|_| own_env.is_none() && !reaching);
        let sampled = lambert || !bsdf.is_delta();
        if let (Some(env), true) = (env_here, k == light_count && choices > light_count && sampled) {
            let v = Vertex {
                p: s.p,
                err: s.err,
                time: ray.time,
                ng,
                frame: &frame,
                wo,
                bsdf: &bsdf,
                departure: departure(),
            };
            radiance += throughput
                * env_light::environment_light(
                    world,
                    accel,
                    shading,
                    env,
                    &v,
                    pick,
                    (u_light, sampler),
                    seed,
                    mis,
                    counts,
                );
        } else if k < light_count && sampled && world.lights_instance(k, stop.instance) {
            let light = &world.lights[k];
            if let Some(mut ls) = light.sample_at(s.p, u_light, ray.time) {
                ls.radiance = light_radiance(light, ls.radiance, env, ls.wi);
                let wi = frame.to_local(ls.wi);
                let mut f = if lambert {
                    lambert_hit::eval(material.diffuse, wo, wi, light.lobes)
                } else {
                    light_lobes::eval(&bsdf, wo, wi, light.lobes)
                };
                if unlit_lobe {
                    f = glossy_reach::light_through(&material.model, &bsdf, (wo, wi), light.lobes.specular, ls.dist, f);
                }
                // The light must be on the side of the geometric surface the shading frame
                // puts it on (reflection above, transmission below).
                if (ls.wi.dot(ng) > 0.0) == (wi.z > 0.0) && f != Rgb::ZERO && ls.radiance != Rgb::ZERO {
                    // Maya's soft shadows spread the shadow ray (`lightRadius`, `lightAngle`).
                    let (dir, dist) = light.shadow_ray_at(s.p, &ls, u_light, ray.time);
                    let origin = s.leave(ng, dir);
                    let tmax = if dist.is_finite() { dist * (1.0 - 1e-4) } else { f32::INFINITY };
                    counts.shadow_rays += 1;
                    let shadow = Ray { mask: mask::SHADOW, origin, dir, tmin: 0.0, tmax, time: ray.time };
                    // The caller may trace the first bounce's shadow ray (with others in a
                    // packet) where its answer is all or nothing: the light is then taken
                    // as unblocked here, and the sum without it kept beside.
                    let defer = depth == 0
                        && camera.defer_shadow
                        && light.shadow
                        && light.shadow_color == Rgb::ZERO
                        && !world.has_media
                        && !world.has_cutouts
                        && world.shadow_unlinked.is_empty()
                        && !(fog_possible && fogs.is_active());
                    let mut unshadowed = if defer {
                        pending = Some(shadow);
                        Rgb::ONE
                    } else if light.shadow && !world.shadow_unlinked.is_empty() && !world.has_media {
                        // Shadow links: objects that cast no shadow for this light let it pass.
                        linked_shadow_passed(world, accel, shading, &shadow, seed, (k, Some(stop.instance)))
                    } else {
                        media::light_transmittance(
                            world,
                            accel,
                            shading,
                            &departure(),
                            &shadow,
                            seed,
                            light.shadow,
                            Some(k),
                        )
                    };
                    if fog_possible && fogs.is_active() && unshadowed != Rgb::ZERO {
                        unshadowed *= fogs.light_keep(world, accel, s.p, ls.wi, ls.dist, ray.time);
                    }
                    // Maya's `shadowColor`: what a shadowed point still receives.
                    // (Skipped for black, the default: it would add exactly nothing.)
                    let tr = if light.shadow && light.shadow_color != Rgb::ZERO {
                        unshadowed + (Rgb::ONE - unshadowed) * light.shadow_color
                    } else {
                        unshadowed
                    };
                    if tr != Rgb::ZERO {
                        let weight = if ls.delta || !mis {
                            1.0
                        } else {
                            let bsdf_pdf = if lambert { lambert_hit::pdf(wo, wi) } else { bsdf.pdf(wo, wi) };
                            power_heuristic(pick * ls.pdf, bsdf_pdf)
                        };
                        let term = throughput * f * ls.radiance * tr * (wi.z.abs() * weight / (pick * ls.pdf));
                        if defer {
                            radiance.lit += term;
                        } else {
                            radiance += term;
                        }
                    }
                }
            }
        }
        // Scatter.
        let u_dir = sampler.next_2d();
        let u_lobe = sampler.next_1d();
        // (Each branch ends the path itself: one merged `Option` went through the stack.)
        let bs = if lambert {
            let Some(bs) = lambert_hit::sample(material.diffuse, wo, u_dir) else { break };
            bs
        } else {
            let Some(bs) = bsdf.sample(wo, u_dir, u_lobe) else { break };
            bs
        };
        let wi = frame.to_world(bs.wi);
        // A reflected ray must leave above the geometric surface, a transmitted one below:
        // shading normals can say otherwise, and then the path ends.
        if (bs.wi.z > 0.0) != (wi.dot(ng) > 0.0) {
            break;
        }
        // (A Lambertian sample is neither a mirror's nor a transmission, nor glossy.)
        if !lambert {
            if levels::reflects(&bsdf, wo, &bs, || cutout_number(seed, s.p, depth + levels::SALT)) {
                reflections += 1;
            } else if levels::refracts(&bsdf, wo, &bs, || cutout_number(seed, s.p, depth + levels::SALT)) {
                refractions += 1;
            }
        }
        let bounce_weight = bs.weight();
        let deep = || {
            let levels = (reflections, refractions);
            deep_material::colour(world, accel, shading, s.material, (&ray, &stop), [seed, depth], levels)
        };
        reach = if reaching { glossy_reach::Reach::after(&material.model, &bsdf, wo, &bs, deep) } else { None };
        throughput *= bounce_weight;
        from_instance = Some(stop.instance);
        last_env = own_env;
        if fog_possible {
            fogs.scattered(s.material, s.ng, ray.dir, wi);
            if fogs.is_active() {
                segment_type = fog::segment_type(depth + 1, bs.delta, ng, wi);
            }
        }
        // Straight through an index-matched medium boundary is no bounce for MIS: what is
        // found next is weighed against the sampling at the vertex before.
        if !(world.has_media && media.follow(world, s.material, s.ng, wi, (&ray, &stop))) {
            last_pdf = bs.pdf;
            last_delta = bs.delta;
            unlit = if unlit_lobe { glossy_reach::unlit_share(&bsdf, wo, &bs) } else { Rgb::ZERO };
        }
        let u_rr = sampler.next_1d();
        if depth + 1 >= settings.rr_depth {
            let q = roulette_survival(bounce_weight);
            if q.is_nan() || q <= 0.0 || u_rr >= q {
                break;
            }
            throughput /= q;
        }
        ray = Ray {
            mask: mask::SECONDARY,
            origin: s.leave(ng, wi),
            dir: wi,
            tmin: 0.0,
            tmax: f32::INFINITY,
            time: ray.time,
        };
    }
    // The camera ray's fog covers what it did not find, as the classic fogs' alpha.
    let alpha = alpha + (1.0 - alpha) * fog_cover.clamp(0.0, 1.0);
    let pending = pending.map(|ray| PendingShadow { ray, blocked: radiance.shadowed });
    *out = PathResult { radiance: radiance.lit, alpha, first, glow, pending };
}
