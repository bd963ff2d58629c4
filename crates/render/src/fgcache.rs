//! The classic engine's final gather pre-pass: fills the interpolation cache
//! ([`shader::fgcache`]) before the image is rendered, as mental ray's final gather
//! precomputation did.
//!
//! Eye rays go through a sequence of ever finer grids over the render window, from one
//! every [`COARSEST_SPACING`] pixels to one every [`FINEST_SPACING`] / √density pixels
//! (`finalgather presample density`). Where a grid ray hits a shaded surface that the
//! points of the coarser grids do not yet cover, a final gather point is gathered there
//! with the full `finalgather accuracy` ray count. Points are thus dense where their radii
//! are small — near other geometry, where irradiance changes fast — and sparse on open
//! surfaces. The points of one grid are gathered in parallel and each depends only on the
//! grids before it, so the cache is the same for any thread count; rendering then only
//! reads it (lookups where no point is valid gather by brute force).

use std::sync::atomic::{AtomicBool, Ordering};

use glam::Vec2;
use rayon::prelude::*;
use shader::fgcache::{FgCache, FgPoint, Radii};
use shader::{Ctx, RayType, Shading, State, Tracer};

use crate::accel::Accel;
use crate::ray::RayCounts;
use crate::tracer::SceneTracer;
use crate::world::World;

/// Spacing (pixels) of the pre-pass's coarsest grid.
pub const COARSEST_SPACING: f32 = 32.0;

/// Spacing (pixels) of its finest grid at presample density 1.
pub const FINEST_SPACING: f32 = 2.0;

/// Grid positions of the pre-pass gathered together (results held at once).
const GRID_CHUNK: usize = 1 << 16;

/// What the pre-pass made.
#[derive(Debug)]
pub struct Prepass {
    /// The final gather points, indexed.
    pub cache: FgCache,
    /// Rays it cast.
    pub counts: RayCounts,
    /// Eye rays it cast (grid positions visited).
    pub eye_rays: u64,
}

/// Runs the pre-pass for a classic render of `world` with `shading`: `None` when final
/// gathering is off or brute force. Stops early (with the points so far) on `cancel`.
pub fn prepass(world: &World, accel: &dyn Accel, shading: &Shading, cancel: &AtomicBool) -> Option<Prepass> {
    let fg = &shading.finalgather;
    let settings = fg.cache.filter(|_| fg.enabled)?;
    let cam = &world.camera;
    let (lo, hi) = world.bounds();
    let radii = settings.radii((hi - lo).length());
    let nearest = settings.nearest();
    let finest = (FINEST_SPACING / settings.density.sqrt()).clamp(0.5, COARSEST_SPACING);
    let levels = (COARSEST_SPACING / finest).log2().ceil().max(0.0) as i32;
    let (x0, y0, x1, y1) = cam.window;
    let (x1, y1) = (x1.min(cam.width), y1.min(cam.height));
    let mut points: Vec<FgPoint> = Vec::new();
    let mut cache = FgCache::new(Vec::new(), nearest);
    let mut counts = RayCounts::default();
    let mut eye_rays = 0u64;
    // The media around the camera, which its eye rays start in (as the render's).
    let camera_media = crate::integrator::media_at(world, accel, cam.camera_to_world_at(0.0).translation, 0.0);
    for level in 0..=levels {
        if cancel.load(Ordering::Relaxed) || x1 <= x0 || y1 <= y0 {
            break;
        }
        let step = finest * 2f32.powi(levels - level);
        let nx = ((x1 - x0) as f32 / step).ceil() as usize;
        let ny = ((y1 - y0) as f32 / step).ceil() as usize;
        // The grid's positions in row order, visited GRID_CHUNK at a time: memory holds one
        // chunk's results, not a whole grid's (~144 bytes a position, a third of the pixels
        // at the finest spacing: 9.6 GB for a 16k x 16k image). Every position of a level
        // sees the cache of the levels before it, so the points are the same.
        let total = nx * ny;
        for start in (0..total).step_by(GRID_CHUNK) {
            if cancel.load(Ordering::Relaxed) {
                break;
            }
            let found: Vec<Option<(Option<FgPoint>, RayCounts)>> = (start..(start + GRID_CHUNK).min(total))
                .into_par_iter()
                .map(|k| {
                    let (i, j) = (k % nx, k / nx);
                    let raster = Vec2::new(x0 as f32 + (i as f32 + 0.5) * step, y0 as f32 + (j as f32 + 0.5) * step);
                    if raster.x >= x1 as f32 || raster.y >= y1 as f32 {
                        return None;
                    }
                    if cancel.load(Ordering::Relaxed) {
                        return Some((None, RayCounts::default()));
                    }
                    Some(point_at(
                        world,
                        accel,
                        (shading, &camera_media),
                        &cache,
                        raster,
                        radii,
                        settings.point_rays,
                        level as u32,
                    ))
                })
                .collect();
            for (p, c) in found.into_iter().flatten() {
                eye_rays += 1;
                counts.rays += c.rays;
                counts.shadow_rays += c.shadow_rays;
                points.extend(p);
            }
        }
        cache = FgCache::new(points.clone(), nearest);
    }
    Some(Prepass { cache, counts, eye_rays })
}

/// The final gather point for the eye ray through `raster` (pixels, top-left origin), if
/// it hits a shaded surface that `cache` does not cover yet; and the rays cast. `shading`:
/// the scene's shading and the media around the camera (where the eye ray starts).
#[allow(clippy::too_many_arguments)]
fn point_at(
    world: &World,
    accel: &dyn Accel,
    (shading, camera_media): (&Shading, &crate::integrator::MediumStack),
    cache: &FgCache,
    raster: Vec2,
    radii: Radii,
    rays: u32,
    level: u32,
) -> (Option<FgPoint>, RayCounts) {
    let tracer = SceneTracer::new(world, accel);
    let cam = &world.camera;
    // When things move, each point is found at a shutter time of its own (a number of
    // its grid position and level), so the cache blurs what moves like the image does.
    let time = world.shutter.as_ref().map_or(0.0, |shutter| {
        let seed = crate::sampler::pixel_seed(raster.x.to_bits(), raster.y.to_bits() ^ level, shading.seed);
        shutter.shape.sample(crate::sampler::Sampler::new(seed, 0x4647).next_1d())
    });
    let ray = if world.shutter.is_some() { cam.ray_at(raster.x, raster.y, time) } else { cam.ray(raster.x, raster.y) };
    let mut root = State {
        ray_type: RayType::Eye,
        org: ray.origin,
        dir: ray.dir,
        point: ray.origin,
        raster: Vec2::new(raster.x, cam.height as f32 - raster.y),
        pixel: [raster.x as u32, raster.y as u32],
        // A sample index of its own per grid, apart from the render's first samples.
        sample_index: 0x4647_0000 + level,
        spread: cam.pixel_angle(),
        ior_in: 1.0,
        ior: 1.0,
        child_dist: f32::INFINITY,
        time,
        ..State::default()
    };
    // A camera that moves while the shutter is open: the media where it is at `time`.
    let moved = crate::integrator::camera_media_at(world, accel, camera_media, time);
    let at_centre = moved.as_ref().unwrap_or(camera_media);
    // An orthographic camera's ray starts in the media around its own origin.
    let own = crate::integrator::camera_ray_media(world, accel, at_centre, &ray);
    crate::classic::enter_media(&mut root, own.as_ref().unwrap_or(at_centre));
    let mut hit = root.child(RayType::Eye, ray.origin, ray.dir);
    let shaded = tracer.intersect(&mut hit, f32::INFINITY)
        && hit.material.and_then(|m| shading.materials.get(m as usize)).is_some_and(|m| m.surface.is_some());
    if !shaded || cache.covers(hit.point, hit.normal) {
        return (None, tracer.counts.get());
    }
    // Radii in pixels become world units through the pixel's footprint at the hit.
    let scale = match (radii.view, cam.orthographic) {
        (false, _) => 1.0,
        (true, true) => cam.pixel_width(),
        (true, false) => hit.dist * cam.pixel_angle(),
    };
    let mut ctx = Ctx::new(shading, &tracer, hit);
    let (irradiance, mean_dist) = ctx.gather(rays);
    let (p, n) = (ctx.state.point, ctx.state.normal);
    let point = FgPoint::new(p, n, irradiance, mean_dist, radii.min * scale, radii.max * scale);
    (Some(point), tracer.counts.get())
}
