//! The classic (shader-driven) engine: mental ray's way of rendering. An eye ray runs the
//! camera's lens shaders, then the material shader of the surface it hits; the shader's
//! colour is the sample. Everything else — lights, shadows, reflections, final gathering —
//! is what the shaders ask for through [`shader::Tracer`], which
//! [`SceneTracer`](crate::tracer::SceneTracer) implements over the acceleration structure.

use glam::Vec2;
use shader::{Color, Ctx, RayType, Shading, State};

use crate::accel::Accel;
use crate::integrator::MediumStack;
use crate::ray::{FirstHit, RayCounts};
use crate::tracer::{raster_motion, SceneTracer};
use crate::world::World;

/// What one classic eye sample produced.
#[derive(Clone, Debug)]
pub struct ClassicSample {
    /// The colour (straight RGB and alpha).
    pub color: Color,
    /// The first surface hit.
    pub first: Option<FirstHit>,
    /// User frame buffer writes.
    pub fb: Vec<(u32, Color)>,
    /// Raster-space motion of the first hit over the shutter interval (pixels, y up).
    pub motion: Vec2,
    /// Rays cast.
    pub counts: RayCounts,
}

/// Renders one eye sample through raster position `raster` (pixels, top-left origin) of
/// pixel `pixel`, sample `index` at shutter time `time` (`sample = (index, time)`, see
/// [`crate::motion`]); final gathering interpolates from `fg_cache` if given. The eye ray
/// starts inside `camera_media` (the media around the camera's centre at the sample's time,
/// [`crate::integrator::media_at`]; an orthographic camera's ray in those around its own
/// origin, [`crate::integrator::camera_ray_media`]).
#[allow(clippy::too_many_arguments)]
pub fn eye_sample(
    world: &World,
    accel: &dyn Accel,
    shading: &Shading,
    fg_cache: Option<&shader::fgcache::FgCache>,
    camera_media: &MediumStack,
    raster: Vec2,
    pixel: [u32; 2],
    sample: (u32, f32),
) -> ClassicSample {
    let (index, time) = sample;
    let mut tracer = SceneTracer::new(world, accel);
    tracer.fg_cache = fg_cache;
    let cam = &world.camera;
    let ray = cam.ray_at(raster.x, raster.y, time);
    let mut state = State {
        ray_type: RayType::Eye,
        org: ray.origin,
        dir: ray.dir,
        point: ray.origin,
        // mental ray's raster space has its origin at the lower left.
        raster: Vec2::new(raster.x, cam.height as f32 - raster.y),
        pixel,
        sample_index: index,
        spread: cam.pixel_angle(),
        footprint: cam.pixel_width(),
        ior_in: 1.0,
        ior: 1.0,
        child_dist: f32::INFINITY,
        time,
        ..State::default()
    };
    state.normal = -ray.dir;
    // An orthographic camera's ray starts in the media around its own origin.
    let ray_media = crate::integrator::camera_ray_media(world, accel, camera_media, &ray);
    enter_media(&mut state, ray_media.as_ref().unwrap_or(camera_media));
    let mut ctx = Ctx::new(shading, &tracer, state);
    let color = ctx.trace_eye(ray.origin, ray.dir);
    let first = tracer.first.get();
    let motion = first.map_or(Vec2::ZERO, |f| raster_motion(cam, f.point, tracer.first_motion.get()));
    ClassicSample { color, first, fb: tracer.fb.into_inner(), counts: tracer.counts.get(), motion }
}

/// Puts a classic state inside `media` (the path engine's stack of world materials,
/// outermost first): the state's media chain then holds their scene materials, so that its
/// rays are attenuated and scattered by them and leave them through their surfaces as rays
/// that entered them do. The chain's index of refraction is 1 for each: the materials with
/// media are MDL materials, which refract by their BSDF, not by the chain. Nothing changes
/// outside all media (scenes without media).
pub fn enter_media(state: &mut State, media: &MediumStack) {
    for (m, own) in media.entries() {
        // World material 0 is the default; world material m is scene material m − 1.
        if let Some(material) = m.checked_sub(1) {
            let medium = shader::state::Medium { material, ior: 1.0 };
            // A medium that varies over its surface: as evaluated where the camera's
            // ray left the object (the path engine's value).
            match own {
                Some(own) => state.enter_evaluated(medium, *own),
                None => state.enter(medium),
            }
        }
    }
}
