//! The path engine's samples over one band of pixels: each pixel's samples in index order,
//! as one pass of [`crate::render`] asks for them, with the camera rays of eight
//! consecutive samples (the same pixel's, or neighbours' along the row) traced together
//! ([`Accel::intersect_batch`]: one Embree packet) before their paths go on one by one;
//! their first bounces' shadow rays are traced together too, after the paths
//! ([`Accel::occluded_batch`]: each path keeps its radiance with and without that ray's
//! light, [`crate::integrator::PendingShadow`], so the answer picks one, bit for bit the
//! sum the path makes tracing the ray itself).
//!
//! Every sample's numbers depend on its pixel, index and dimension only, and its path goes
//! on from the hit the batch gave its camera ray. Packets are made per row and pass, so the
//! image is the same bit for bit for any thread count, band order or split into parts and
//! strips. With the Rust backend (which traces a batch ray by ray) it is also the one-ray
//! image bit for bit. Embree's packet kernel can break an exact tie — a ray through the
//! edge two triangles share, at the same distance on both — otherwise than its one-ray
//! kernel, as its kernels for different vector units already may: in the 256², 64-spp
//! render of the bench's Cornell box, one camera ray of 4,194,304 (through the diagonal of
//! a wall's quad) found the other triangle, and one pixel of 65,536 changed by 0.0025.

use std::sync::atomic::{AtomicBool, Ordering};

use glam::Vec2;
use shader::Shading;

use crate::accel::{Accel, Hit};
use crate::environment::Environment;
use crate::film::Pixel;
use crate::filter::PixelFilter;
use crate::integrator::{trace_camera_path_into, CameraRay, MediumStack, PathResult, PathScene, PathSettings};
use crate::ray::{Ray, RayCounts};
use crate::sampler::{pixel_seed, Sampler, SamplerPosition};
use crate::world::World;

/// Camera rays traced together: Embree's widest packet that every x86-64 CPU with AVX runs
/// natively.
const PACKET: usize = 8;

/// What the path engine needs to sample a band of pixels in one pass.
pub(crate) struct PathBand<'a> {
    /// The scene.
    pub world: &'a World,
    /// Its acceleration structure.
    pub accel: &'a dyn Accel,
    /// The compiled shader graph (materials with connected parameters).
    pub shading: Option<&'a Shading>,
    /// The environment, if the scene has one.
    pub env: Option<&'a Environment<'a>>,
    /// The world's materials with their constant parameters, built once per render
    /// ([`crate::integrator::constant_materials`]).
    pub constants: &'a [material::HitMaterial<'a>],
    /// Which of them the path engine's kernel for plain hits may trace
    /// ([`crate::integrator::plain_materials`]).
    pub plain: &'a [bool],
    /// The pixel filter the camera samples are drawn from.
    pub filter: &'a PixelFilter,
    /// The media around the camera.
    pub camera_media: &'a MediumStack,
    /// The path tracer's settings.
    pub path: &'a PathSettings,
    /// The render's seed.
    pub seed: u32,
    /// The pass's first sample index.
    pub first: u32,
    /// Samples per pixel in this pass.
    pub count: u32,
}

/// What sampling a band gave besides its pixels.
#[derive(Default)]
pub(crate) struct BandOutput {
    /// Rays traced.
    pub counts: RayCounts,
    /// Non-finite colour channels stored as 1.0.
    pub nonfinite: u64,
    /// Writes to user frame buffers: (film pixel index, buffer, value).
    pub writes: Vec<(usize, u32, [f32; 4])>,
}

/// A camera sample waiting for its ray's hit.
struct Lane {
    /// The pixel's index in the band.
    k: usize,
    /// The sample's index.
    index: u32,
    /// The filter's weight of the sample.
    weight: f32,
    /// Its camera ray.
    ray: Ray,
    /// Where its sample numbers go on from.
    position: SamplerPosition,
    /// Which of the open samplers is its pixel's.
    sampler: usize,
    /// Its shutter time.
    time: f32,
}

impl PathBand<'_> {
    /// Samples `pixels` (a band of the film, its first pixel at film index `base`; pixel `k`
    /// is at image position `place(k)`, `None` for pixels this render leaves alone): each
    /// pixel not converged gets samples `first .. first + count`. Stops at the next pixel
    /// when `cancel` is set (the pixels begun keep their samples).
    pub fn render(
        &self,
        pixels: &mut [Pixel],
        base: usize,
        place: impl Fn(usize) -> Option<(u32, u32)>,
        cancel: &AtomicBool,
        out: &mut BandOutput,
    ) {
        let cam = self.world.camera.raster_rays();
        let mut lanes: Vec<Lane> = Vec::with_capacity(PACKET);
        // The samplers of the pixels with lanes waiting and of the current pixel, in a ring of
        // `PACKET + 1` slots reused in place (a pixel begins with fewer than `PACKET` lanes
        // waiting, so with its own at most `PACKET` pixels are open: a slot is free again by
        // the time the ring comes back to it). `current`: the current pixel's slot.
        let mut samplers: Vec<Sampler> = Vec::with_capacity(PACKET + 1);
        let mut current: Option<usize> = None;
        let mut packet = PacketBuffers::new();
        let mut row = None;
        for k in 0..pixels.len() {
            if cancel.load(Ordering::Relaxed) {
                break;
            }
            let Some((x, y)) = place(k) else { continue };
            if pixels[k].converged {
                continue;
            }
            if row != Some(y) {
                // Packets never span two rows: a row's packets are then the same whichever
                // rows are rendered with it (a part of interleaved rows, a strip).
                self.finish(&mut lanes, &mut samplers, &mut packet, pixels, base, out);
                row = Some(y);
            }
            // One sampler per pixel, restarted for each sample: the scrambles that depend
            // on the pixel alone are hashed once.
            let s = current.map_or(0, |c| (c + 1) % (PACKET + 1));
            let seed = pixel_seed(x, y, self.seed);
            match samplers.get_mut(s) {
                Some(slot) => slot.start_pixel(seed, self.first),
                None => samplers.push(Sampler::new(seed, self.first)),
            }
            current = Some(s);
            for index in self.first..self.first + self.count {
                let sampler = &mut samplers[s];
                sampler.restart(index);
                let u = sampler.next_2d();
                // Motion blur: the sample's shutter time is the next dimension, so that a
                // pixel's samples are stratified in (x, y, time) together; scenes where
                // nothing moves draw none and keep their numbers.
                let time = self.world.shutter.as_ref().map_or(0.0, |shutter| shutter.shape.sample(sampler.next_1d()));
                let (offset, weight) = self.filter.sample(u);
                let raster = Vec2::new(x as f32 + 0.5 + offset.x, y as f32 + 0.5 + offset.y);
                let ray = cam.ray_at(raster.x, raster.y, time);
                lanes.push(Lane { k, index, weight, ray, position: sampler.position(), sampler: s, time });
                if lanes.len() == PACKET {
                    self.finish(&mut lanes, &mut samplers, &mut packet, pixels, base, out);
                }
            }
        }
        self.finish(&mut lanes, &mut samplers, &mut packet, pixels, base, out);
    }

    /// Traces the waiting lanes' camera rays together, then each lane's path in order, and
    /// adds the samples to their pixels.
    fn finish(
        &self,
        lanes: &mut Vec<Lane>,
        samplers: &mut [Sampler],
        packet: &mut PacketBuffers,
        pixels: &mut [Pixel],
        base: usize,
        out: &mut BandOutput,
    ) {
        let n = lanes.len();
        if n == 0 {
            return;
        }
        let PacketBuffers { rays, hits, results, shadows } = packet;
        for (r, lane) in rays.iter_mut().zip(lanes.iter()) {
            *r = lane.ray;
        }
        self.accel.intersect_batch(&rays[..n], &mut hits[..n]);
        // (Each path writes its whole result in place: returned by value, it was copied.)
        let scene = PathScene {
            world: self.world,
            accel: self.accel,
            shading: self.shading,
            env: self.env,
            constants: self.constants,
            plain: self.plain,
        };
        for ((lane, &hit), result) in lanes.iter().zip(hits.iter()).zip(results.iter_mut()) {
            let sampler = &mut samplers[lane.sampler];
            sampler.resume(&lane.position);
            let camera = CameraRay { ray: lane.ray, hit: Some(hit), defer_shadow: true };
            if !self.world.has_media {
                // (No media: the camera is in none, wherever it moves: what the two
                // questions below answer.)
                trace_camera_path_into(&scene, camera, self.camera_media, sampler, self.path, &mut out.counts, result);
                continue;
            }
            // A camera that moves across a medium's surface while the shutter is open: the
            // media where it is at this sample's time.
            let moved_media = crate::integrator::camera_media_at(self.world, self.accel, self.camera_media, lane.time);
            let at_centre = moved_media.as_ref().unwrap_or(self.camera_media);
            // An orthographic camera's ray starts in the media around its own origin.
            let ray_media = crate::integrator::camera_ray_media(self.world, self.accel, at_centre, &lane.ray);
            trace_camera_path_into(
                &scene,
                camera,
                ray_media.as_ref().unwrap_or(at_centre),
                sampler,
                self.path,
                &mut out.counts,
                result,
            );
        }
        // The first bounces' shadow rays, traced together.
        let mut owner = [0usize; PACKET];
        let mut m = 0;
        for (i, r) in results[..n].iter().enumerate() {
            if let Some(p) = r.pending.as_ref() {
                shadows[m] = p.ray;
                owner[m] = i;
                m += 1;
            }
        }
        let mut blocked = [false; PACKET];
        self.accel.occluded_batch(&shadows[..m], &mut blocked[..m]);
        let mut lane_blocked = [false; PACKET];
        for (&i, &b) in owner[..m].iter().zip(&blocked[..m]) {
            lane_blocked[i] = b;
        }
        let cam = &self.world.camera;
        for ((lane, r), blocked) in lanes.drain(..).zip(results.iter()).zip(lane_blocked) {
            let radiance = r.radiance_given(blocked);
            let px = &mut pixels[lane.k];
            if lane.index == 0 {
                if let Some(f) = r.first {
                    px.depth = cam.depth(f.point);
                    px.normal = f.normal.to_array();
                    px.tag = f.tag;
                    px.motion = crate::tracer::raster_motion(cam, f.point, f.motion).to_array();
                }
            }
            if let (Some(buffer), Some(g)) = (self.world.glow_buffer, r.glow) {
                // The glow the camera sees, as the classic shading engine stores it: each
                // sample's, zero where nothing glows.
                let g = g.max(bsdf::Rgb::ZERO);
                out.writes.push((base + lane.k, buffer, [g.x, g.y, g.z, 1.0]));
            }
            out.nonfinite += u64::from(px.add(radiance, r.alpha, lane.weight, lane.index));
        }
    }
}

/// A packet's camera rays, their hits, its paths' results and the first bounces' shadow
/// rays: made once per band and reused by every packet (each packet writes the first `n`
/// entries it reads, so nothing is cleared between packets: the `PathResult`s' zeroing
/// was a `memset` per packet).
struct PacketBuffers {
    /// The waiting lanes' camera rays (world space).
    rays: [Ray; PACKET],
    /// What [`Accel::intersect_batch`] found along each.
    hits: [Option<Hit>; PACKET],
    /// Each lane's path, as [`trace_camera_path_into`] wrote it.
    results: [PathResult; PACKET],
    /// The deferred first-bounce shadow rays, packed (world space).
    shadows: [Ray; PACKET],
}

impl PacketBuffers {
    /// Buffers for one band (their contents are placeholders until a packet writes them).
    fn new() -> Self {
        let ray = Ray::new(glam::Vec3A::ZERO, glam::Vec3A::Z);
        PacketBuffers {
            rays: [ray; PACKET],
            hits: [None; PACKET],
            results: [PathResult::EMPTY; PACKET],
            shadows: [ray; PACKET],
        }
    }
}
