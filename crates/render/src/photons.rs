//! The classic engine's photon pass (mental ray's caustics and photon global
//! illumination): before the image, every light with `energy` emits photons, they are
//! traced through the scene by the surfaces' photon shaders (`shader::photon` and the libraries' photon hooks) and
//! stored in the caustic and global photon maps ([`shader::photonmap`]), which
//! `compute_irradiance` then looks up.
//!
//! Emission, per light and map (`caustic photons` / `globillum photons store [emit]`,
//! 10000 stored when the light gives no count): photons are emitted in batches until
//! `store` of them are stored or `emit` were emitted (100 × `store` when not given). Each
//! photon leaves with flux `energy / emitted`, emitted counting every photon sent, stored or
//! not. Point lights emit uniformly over the sphere, spot lights uniformly within their
//! cone, area lights (rectangle, disc, sphere, cylinder) from a uniform point of their
//! surface in a cosine-distributed direction about its normal (one-sided for rectangles and
//! discs), directional lights from a disc upstream of the scene's bounding sphere covering
//! it (their `energy` is the flux through that disc). `exponent` e bends the falloff as
//! mental ray defines it: a photon's flux decays as 1/r^e instead of the natural 1/r², so
//! at its first hit at distance r it is multiplied by r^(2 − e) (not for directional
//! lights).
//!
//! Tracing: at each hit the surface's scattering decides; a photon is stored where the
//! surface is diffuse and the object receives photons of that map (`caustic` /
//! `globillum` flags' receive bit): in the caustic map when every event so far was specular
//! or glossy (at least one), in the global map when at least one was diffuse. Russian
//! roulette picks the next event by the reflectances; `photon trace depth` bounds the
//! reflections, refractions and all events of a path. Objects that do not cast photons of
//! the map (cast bit off) are passed through.
//!
//! The global map's irradiance is then precomputed at every [`FAST_STRIDE`]-th photon
//! (mental ray's fast lookup), so that final gather rays look up one point, not
//! `globillum accuracy` photons.
//!
//! Sample numbers are Sobol points per light and map, so the maps are the same for every
//! thread count.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use bsdf::Frame;
use glam::{Vec2, Vec3A};
use rayon::prelude::*;
use shader::light::ShadingLight;
use shader::photon::{scatter_at, Event};
use shader::photonmap::{Filter, Lookup, Photon, PhotonMap, PhotonMaps};
use shader::{Ctx, RayType, Shading, State};

use crate::accel::Accel;
use crate::ray::Ray;
use crate::sampler::{pixel_seed, Sampler};
use crate::tracer::{fill_state, SceneTracer};
use crate::world::World;
use scene::LightKind;

/// Photons stored per light and map when the light gives no count.
pub const DEFAULT_PHOTONS: u32 = 10_000;

/// Photons traced per parallel batch.
const BATCH: u32 = 4096;

/// Most surfaces one photon path visits.
const MAX_HITS: u32 = 256;

/// The global map's irradiance is precomputed at every this many photons.
pub const FAST_STRIDE: usize = 4;

/// Surfaces a photon may pass through (objects that cast no photons) before it is dropped.
const MAX_PASS: u32 = 16;

/// What the photon pass did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhotonStats {
    /// Photons emitted, all lights and maps.
    pub emitted: u64,
    /// Photons in the caustic map.
    pub caustic: u64,
    /// Photons in the global illumination map.
    pub global: u64,
    /// Rays cast while tracing.
    pub rays: u64,
    /// Bytes the maps hold.
    pub memory: u64,
    /// Time the pass took (emission, tracing and building the maps).
    pub time: Duration,
}

/// Which map a pass fills.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Map {
    Caustic,
    Global,
}

/// Runs the photon pass for a classic render of `world` with `shading` and stores the maps
/// in `shading.photons`: `None` when the options ask for neither caustics nor global
/// illumination, or when the maps were already made (by an earlier render of the same
/// shading). Stops early on `cancel`.
pub fn build(world: &World, accel: &dyn Accel, shading: &Shading, cancel: &AtomicBool) -> Option<PhotonStats> {
    let o = &world.options;
    if !(o.caustic || o.globillum) || shading.photons.get().is_some() {
        return None;
    }
    let start = Instant::now();
    let (lo, hi) = world.bounds();
    let diag = if lo.x <= hi.x { (hi - lo).length() } else { 1.0 };
    let mut stats = PhotonStats::default();
    let p = &o.photons;
    let lookup = |(count, radius): (u32, Option<f64>), filter: Filter, scale: [f64; 3]| Lookup {
        count,
        radius: radius.map_or(diag / 10.0, |r| r as f32),
        filter,
        scale: Vec3A::new(scale[0] as f32, scale[1] as f32, scale[2] as f32),
    };
    let mut maps = PhotonMaps::default();
    if o.caustic {
        let filter = match p.caustic_filter {
            scene::options::CausticFilter::Box => Filter::Box,
            scene::options::CausticFilter::Cone(k) => Filter::Cone(k as f32),
            scene::options::CausticFilter::Gauss => Filter::Gauss,
        };
        let photons = trace_map(world, accel, shading, Map::Caustic, cancel, &mut stats);
        stats.caustic = photons.len() as u64;
        maps.caustic = Some((PhotonMap::new(photons), lookup(p.caustic_accuracy, filter, p.caustic_scale)));
    }
    if o.globillum {
        let photons = trace_map(world, accel, shading, Map::Global, cancel, &mut stats);
        stats.global = photons.len() as u64;
        maps.global = Some((PhotonMap::new(photons), lookup(p.globillum_accuracy, Filter::Box, p.globillum_scale)));
        // Irradiance precomputed at every FAST_STRIDE-th photon.
        let n = stats.global as usize;
        let chunks: Vec<Vec<Photon>> = (0..n.div_ceil(BATCH as usize))
            .into_par_iter()
            .map(|c| {
                let lo = c * BATCH as usize;
                maps.irradiance_points(FAST_STRIDE, lo..(lo + BATCH as usize).min(n))
            })
            .collect();
        maps.global_fast = Some(PhotonMap::new(chunks.concat()));
    }
    stats.memory = maps.caustic.iter().chain(&maps.global).map(|(m, _)| m.memory() as u64).sum::<u64>()
        + maps.global_fast.as_ref().map_or(0, |m| m.memory() as u64);
    stats.time = start.elapsed();
    let _ = shading.photons.set(maps);
    Some(stats)
}

/// Emits and traces the photons of every light for one map.
fn trace_map(
    world: &World,
    accel: &dyn Accel,
    shading: &Shading,
    map: Map,
    cancel: &AtomicBool,
    stats: &mut PhotonStats,
) -> Vec<Photon> {
    let mut all = Vec::new();
    let bounds = world.bounds();
    for (li, light) in shading.lights.iter().enumerate() {
        let Some(lp) = light.photons else { continue };
        let counts = match map {
            Map::Caustic => lp.caustic,
            Map::Global => lp.globillum,
        };
        let (store, emit) = counts.unwrap_or((DEFAULT_PHOTONS, None));
        if store == 0 || lp.energy.max_element() <= 0.0 {
            continue;
        }
        let cap = emit.unwrap_or(store.saturating_mul(100)).max(1);
        let Some(emitter) = Emitter::new(light, li, bounds) else { continue };
        let seed = pixel_seed(li as u32, map as u32, shading.seed);
        let mut stored: Vec<Photon> = Vec::new();
        let mut emitted = 0u32;
        while (stored.len() as u64) < u64::from(store) && emitted < cap && !cancel.load(Ordering::Relaxed) {
            let n = BATCH.min(cap - emitted);
            let batch: Vec<(Vec<Photon>, u64)> = (emitted..emitted + n)
                .into_par_iter()
                .map(|i| {
                    let mut out = Vec::new();
                    let rays = trace_photon(world, accel, shading, &emitter, map, seed, i, &mut out);
                    (out, rays)
                })
                .collect();
            emitted += n;
            for (photons, rays) in batch {
                stats.rays += rays;
                stored.extend(photons);
            }
        }
        stats.emitted += u64::from(emitted);
        let scale = lp.energy / emitted.max(1) as f32;
        all.extend(stored.into_iter().map(|mut p| {
            p.power *= scale;
            p
        }));
    }
    all
}

/// Where and in which direction one light sends photons.
struct Emitter<'a> {
    light: &'a ShadingLight,
    /// Its index in the scene's lights (for its motion, `World::light_motion`).
    index: usize,
    /// Directional lights: the centre and radius of the scene's bounding sphere, which the
    /// emitting disc covers.
    bounds: (Vec3A, f32),
}

impl<'a> Emitter<'a> {
    fn new(light: &'a ShadingLight, index: usize, (lo, hi): (Vec3A, Vec3A)) -> Option<Emitter<'a>> {
        let bounds = if light.kind == LightKind::Directional {
            if lo.x > hi.x {
                return None;
            }
            ((lo + hi) * 0.5, ((hi - lo).length() * 0.5).max(1e-6))
        } else {
            (Vec3A::ZERO, 0.0)
        };
        Some(Emitter { light, index, bounds })
    }

    /// The light where it is at shutter time `time` (moved with its instance when that
    /// moves while the shutter is open, its object triangles where the geometry has them
    /// then when they change shape).
    fn light_at(&self, world: &World, time: f32) -> std::borrow::Cow<'a, ShadingLight> {
        let shaped = world.light_meshes.get(self.index).and_then(|m| m.as_ref()?.at(time));
        let by = world.light_motion.get(self.index).filter(|keys| !keys.is_empty());
        let by = by.map(|keys| crate::motion::lerp_keys(keys, time));
        match (shaped, by) {
            (None, None) => std::borrow::Cow::Borrowed(self.light),
            (None, Some(by)) => std::borrow::Cow::Owned(self.light.moved(by)),
            (Some(mesh), None) => std::borrow::Cow::Owned(self.light.reshaped(mesh)),
            (Some(mesh), Some(by)) => std::borrow::Cow::Owned(self.light.reshaped(mesh).moved(by)),
        }
    }

    /// A photon's origin and unit direction from light `l` (this emitter's light, maybe
    /// moved) for the sample numbers `a`, `b`, and whether the exponent's falloff applies.
    fn emit(&self, l: &ShadingLight, a: Vec2, b: Vec2) -> (Vec3A, Vec3A, bool) {
        if l.kind == LightKind::Directional {
            let (centre, radius) = self.bounds;
            let disc = centre - l.direction * (radius * 1.01);
            let frame = Frame::from_normal(l.direction);
            let (r, phi) = (a.x.sqrt() * radius, std::f32::consts::TAU * a.y);
            let origin = disc + frame.to_world(Vec3A::new(r * phi.cos(), r * phi.sin(), 0.0));
            return (origin, l.direction, false);
        }
        if let Some(shape) = l.shape.as_ref().filter(|s| !matches!(s, shader::light::Shape::Point)) {
            let (p, n) = shape.point_on(l.origin, a);
            let dir = Frame::from_normal(n).to_world(bsdf::cosine_hemisphere(b));
            return (p, dir.normalize_or(n), true);
        }
        let dir = if l.kind == LightKind::Spot {
            // Uniform within the cone cos θ ≥ spread.
            let cos_max = l.spread.clamp(-1.0, 1.0);
            let cos = 1.0 - a.x * (1.0 - cos_max);
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            let phi = std::f32::consts::TAU * a.y;
            Frame::from_normal(l.direction).to_world(Vec3A::new(sin * phi.cos(), sin * phi.sin(), cos))
        } else {
            let z = 1.0 - 2.0 * a.x;
            let s = (1.0 - z * z).max(0.0).sqrt();
            let phi = std::f32::consts::TAU * a.y;
            Vec3A::new(s * phi.cos(), s * phi.sin(), z)
        };
        (l.origin, dir, true)
    }
}

/// Traces photon `index`, pushing what it stores (flux relative to the emitted photon's)
/// onto `out`. Returns the rays cast.
#[allow(clippy::too_many_arguments)]
fn trace_photon(
    world: &World,
    accel: &dyn Accel,
    shading: &Shading,
    emitter: &Emitter,
    map: Map,
    seed: u32,
    index: u32,
    out: &mut Vec<Photon>,
) -> u64 {
    let mut sampler = Sampler::new(pixel_seed(index >> 16, 0x5eed, seed), index & 0xffff);
    let (a, b) = (sampler.next_2d(), sampler.next_2d());
    // Each photon leaves at a shutter time of its own when things move (drawn after the
    // emission's numbers, so a still scene's photons are what they were).
    let time = world.shutter.as_ref().map_or(0.0, |shutter| shutter.shape.sample(sampler.next_1d()));
    let (mut org, mut dir, falloff) = emitter.emit(&emitter.light_at(world, time), a, b);
    let mut power = Vec3A::ONE;
    let depth = world.options.photons.trace_depth;
    let (mut reflections, mut refractions, mut events) = (0u32, 0u32, 0u32);
    let (mut specular, mut diffuse) = (false, false);
    let tracer = SceneTracer::new(world, accel);
    let mut rays = 0u64;
    let exponent = emitter.light.exponent;
    // Surfaces passed unchanged (transmat_photon) count no event; this bounds the path
    // whatever the geometry.
    for _ in 0..MAX_HITS {
        // The next surface that casts photons of this map.
        let mut hit = None;
        let mut from = org;
        for _ in 0..MAX_PASS {
            rays += 1;
            let ray = Ray { mask: u32::MAX, origin: from, dir, tmin: 0.0, tmax: f32::INFINITY, time };
            let Some(h) = accel.intersect(&ray) else { break };
            let mut s = State { ray_type: RayType::Probe, org: from, dir, time, ..State::default() };
            fill_state(world, &h, &mut s);
            let flags = world.instances[h.instance as usize].flags;
            let mode = if map == Map::Caustic { flags.caustic } else { flags.globillum };
            if mode.cast {
                hit = Some((s, mode.receive));
                break;
            }
            from = shader::trace::leave_point(s.point, s.point_error, s.normal_geom, dir);
        }
        let Some((s, receive)) = hit else { break };
        if events == 0 && falloff && exponent != 2.0 && exponent.is_finite() {
            let r = s.point.distance(org).max(1e-6);
            power *= r.powf(2.0 - exponent);
        }
        let (point, normal, normal_geom, inv_normal) = (s.point, s.normal, s.normal_geom, s.inv_normal);
        // `opaque` is not read here: a speed hint for shadow rays (mental ray manual, material statement; Maya's
        // Shading Group "Opaque"), see `World::blocks_shadows`; photons follow the surface's photon shader.
        let point_error = s.point_error;
        let mut ctx = Ctx::new(shading, &tracer, s);
        let scatter = scatter_at(&mut ctx);
        drop(ctx);
        let store = receive
            && scatter.stores()
            && match map {
                Map::Caustic => specular && !diffuse,
                Map::Global => diffuse,
            };
        if store {
            out.push(Photon { position: point, power, dir, normal });
        }
        if events >= depth.2 {
            break;
        }
        let (event, factor) = scatter.choose(sampler.next_1d());
        let u = sampler.next_2d();
        let next = match event {
            Event::Absorb => break,
            Event::Diffuse | Event::Translucent if map == Map::Caustic => break,
            Event::Diffuse => {
                diffuse = true;
                Frame::from_normal(normal).to_world(bsdf::cosine_hemisphere(u))
            }
            Event::Translucent => {
                diffuse = true;
                Frame::from_normal(-normal).to_world(bsdf::cosine_hemisphere(u))
            }
            Event::Reflect => {
                reflections += 1;
                if reflections > depth.0 {
                    break;
                }
                specular = true;
                match scatter.gloss {
                    Some((su, sv)) => {
                        bsdf::mia::lobes::jittered_reflection(&Frame::from_normal(normal), normal_geom, dir, su, sv, u)
                    }
                    None => dir - 2.0 * dir.dot(normal) * normal,
                }
            }
            Event::Transmit if scatter.pass => dir,
            Event::Transmit => {
                refractions += 1;
                if refractions > depth.1 {
                    break;
                }
                specular = true;
                if scatter.thin {
                    dir
                } else {
                    let eta = if inv_normal { scatter.ior } else { 1.0 / scatter.ior };
                    shader::trace::refract(dir, normal, eta).unwrap_or(dir - 2.0 * dir.dot(normal) * normal)
                }
            }
        };
        if !scatter.pass {
            events += 1;
            power *= factor;
        }
        if power.max_element() <= 0.0 || !next.is_finite() {
            break;
        }
        dir = next.normalize();
        org = shader::trace::leave_point(point, point_error, normal_geom, dir);
    }
    rays
}
