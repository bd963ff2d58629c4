//! The progressive render loop: passes of samples over all pixels, bands of rows in
//! parallel, a per-pixel error estimate, and stopping by sample count, convergence, time or
//! cancellation.
//!
//! Every pixel sample is fully determined by the pixel, its index and the seed, and each
//! pixel adds its samples in index order: the image is the same bit for bit for any thread
//! count, band order or pass split.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use glam::Vec2;
use shader::Shading;

use crate::accel::Accel;
use crate::film::{Film, Pixel};
use crate::filter::PixelFilter;
use crate::integrator::PathSettings;
use crate::part::{Part, Split};
use crate::path_band::{BandOutput, PathBand};
use crate::prepare::{prepare, Prepared};
use crate::ray::RayCounts;
use crate::sampler::{pixel_seed, Sampler};
use crate::world::World;

pub use crate::engine::EngineKind;

/// How to render.
#[derive(Clone, Debug)]
pub struct Settings {
    /// The engine.
    pub engine: EngineKind,
    /// Samples per pixel to stop at (overrides the scene's progressive maximum).
    pub spp: Option<u32>,
    /// Seed of the sample scrambling.
    pub seed: u32,
    /// Stop after this long.
    pub max_time: Option<Duration>,
    /// Path tracing settings.
    pub path: PathSettings,
    /// Rows per parallel work item.
    pub band: u32,
    /// Render only this part of the image (see [`crate::part`]); `None`: all of it.
    pub part: Option<Part>,
    /// Render only these image rows, into a film of just these rows (its
    /// [`Film::y0`](crate::film::Film::y0) is their first): a strip of an image too large
    /// for one film (see [`crate::strips`]). `None`: every row. Not with `part`.
    pub rows: Option<std::ops::Range<u32>>,
    /// Stop after the pass that reaches this many samples per pixel, and not on the clock:
    /// the strips after the first of a time-limited render in strips take the first one's
    /// count (see [`crate::strips::strip_settings`]). Unlike `spp` it changes neither the
    /// target nor the classic engine's adaptive sampling.
    pub stop_at_samples: Option<u32>,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            engine: EngineKind::Path,
            spp: None,
            seed: 0,
            max_time: None,
            path: PathSettings::default(),
            band: 4,
            part: None,
            rows: None,
            stop_at_samples: None,
        }
    }
}

/// Progress after a pass.
#[derive(Clone, Copy, Debug)]
pub struct Progress {
    /// Samples per pixel done.
    pub samples: u32,
    /// Samples per pixel aimed at.
    pub target: u32,
    /// Fraction of pixels converged (when the convergence test is on).
    pub converged: Option<f32>,
    /// Time since the start.
    pub elapsed: Duration,
}

/// Counts for `--stats`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stats {
    /// Camera and scattered rays.
    pub rays: u64,
    /// Shadow rays.
    pub shadow_rays: u64,
    /// Pixel samples taken.
    pub samples: u64,
    /// Colour channels that were NaN or infinite (stored as 1.0).
    pub nonfinite: u64,
    /// Time to render.
    pub render_time: Duration,
    /// Time until the first band of pixels was done.
    pub first_pixels: Option<Duration>,
    /// Samples per pixel reached.
    pub spp: u32,
    /// Stopped by cancellation.
    pub cancelled: bool,
    /// Stopped because enough pixels converged.
    pub converged: bool,
    /// Final gather points the classic engine's pre-pass computed (0: none, or brute
    /// force).
    pub fg_points: u64,
    /// Time the final gather pre-pass took (included in `render_time`).
    pub fg_time: Duration,
    /// What the classic engine's photon pass did, if it ran (its time is included in
    /// `render_time`).
    pub photons: Option<crate::photons::PhotonStats>,
}

impl Stats {
    /// All rays traced.
    pub fn total_rays(&self) -> u64 {
        self.rays + self.shadow_rays
    }
}

/// One parallel work item: a band's index and pixels, and its splat buffer (classic).
type BandWork<'a> = ((usize, &'a mut [Pixel]), Option<&'a mut Splat>);

/// The filtered contributions of one band's samples to the pixels their filter covers
/// (the band's rows and `radius` rows around them).
struct Splat {
    /// First image row covered.
    y0: usize,
    /// Rows covered.
    rows: usize,
    width: usize,
    height: usize,
    /// Σ w·rgba and Σ w per covered pixel.
    sums: Vec<[f64; 5]>,
}

impl Splat {
    fn new(filter: &PixelFilter, band_y: usize, band_rows: usize, width: u32, height: u32) -> Splat {
        let ry = filter.radius().1.ceil() as usize;
        let y0 = band_y.saturating_sub(ry);
        let y1 = (band_y + band_rows + ry).min(height as usize);
        let rows = y1 - y0;
        Splat { y0, rows, width: width as usize, height: height as usize, sums: vec![[0.0; 5]; rows * width as usize] }
    }

    /// Adds a sample at raster position `p` with colour `c` (NaN and infinities as 1.0).
    fn add(&mut self, filter: &PixelFilter, p: Vec2, c: [f32; 4]) {
        let c = c.map(|v| if v.is_finite() { v } else { 1.0 });
        let (rx, ry) = filter.radius();
        let x_lo = (p.x - rx - 0.5).ceil().max(0.0) as usize;
        let x_hi = ((p.x + rx - 0.5).floor() as i64).min(self.width as i64 - 1);
        let y_lo = (p.y - ry - 0.5).ceil().max(self.y0 as f32) as usize;
        let y_hi = ((p.y + ry - 0.5).floor() as i64).min((self.y0 + self.rows) as i64 - 1).min(self.height as i64 - 1);
        if x_hi < x_lo as i64 || y_hi < y_lo as i64 {
            return;
        }
        // The filter is separable: one weight per column and per row.
        let mut wx = [0.0f32; 32];
        let columns = ((x_hi - x_lo as i64 + 1) as usize).min(wx.len());
        for (i, w) in wx[..columns].iter_mut().enumerate() {
            *w = filter.eval_x((x_lo + i) as f32 + 0.5 - p.x);
        }
        for y in y_lo..=y_hi as usize {
            let wy = filter.eval_y(y as f32 + 0.5 - p.y);
            if wy == 0.0 {
                continue;
            }
            let row = (y - self.y0) * self.width + x_lo;
            for (s, w) in self.sums[row..row + columns].iter_mut().zip(&wx[..columns]) {
                let w64 = f64::from(w * wy);
                for k in 0..4 {
                    s[k] += w64 * f64::from(c[k]);
                }
                s[4] += w64;
            }
        }
    }

    /// Adds the band's sums to the film's and clears them for the next pass.
    fn merge_into(&mut self, film: &mut [[f64; 5]], width: usize) {
        for (r, row) in self.sums.chunks_mut(width).enumerate() {
            let base = (self.y0 + r) * width;
            for (dst, src) in film[base..base + width].iter_mut().zip(row) {
                for k in 0..5 {
                    dst[k] += src[k];
                }
                *src = [0.0; 5];
            }
        }
    }
}

/// Samples per pixel of the classic engine: (first pass, most) from the options'
/// `samples min max` (4^level; levels below 0 are taken as 0, mental ray's infrasampling
/// is not done) unless `spp` fixes the count.
pub fn classic_samples(options: &scene::Options, spp: Option<u32>) -> (u32, u32) {
    if let Some(n) = spp {
        return (n.max(1), n.max(1));
    }
    let (lo, hi) = options.samples;
    let hi = hi.clamp(0, 5);
    let lo = lo.clamp(0, hi);
    (4u32.pow(lo as u32), 4u32.pow(hi as u32))
}

/// The contrast test of the classic engine: whether pixel `i` has to be sampled further
/// (its samples spread by more than `contrast` in some channel, or, after the first pass,
/// its colour differs from a neighbour's by more).
fn needs_more(film: &Film, i: usize, contrast: [f32; 4], neighbours: bool) -> bool {
    let p = &film.pixels[i];
    if (0..4).any(|k| p.hi[k] - p.lo[k] > contrast[k]) {
        return true;
    }
    if !neighbours {
        return false;
    }
    let (w, h) = (film.width as usize, film.height as usize);
    let (x, y) = (i % w, i / w);
    let c = p.rgba();
    let near = [(x > 0).then(|| i - 1), (x + 1 < w).then(|| i + 1), (y > 0).then(|| i - w), (y + 1 < h).then(|| i + w)];
    near.into_iter().flatten().any(|j| {
        let d = film.pixels[j].rgba();
        (0..4).any(|k| (c[k] - d[k]).abs() > contrast[k])
    })
}

/// Renders `world` progressively: [`prepare`], then [`render_prepared`]. `progress` is
/// called after each pass; `cancel` stops the render at the next row (the image keeps what
/// was done). The classic engine needs the scene's compiled `shading`.
pub fn render(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    settings: &Settings,
    cancel: &AtomicBool,
    progress: &(dyn Fn(Progress) + Sync),
) -> (Film, Stats) {
    let prepared = prepare(world, accel, shading, settings.engine, cancel);
    render_prepared(world, accel, shading, &prepared, settings, cancel, progress)
}

/// Why a part of an image cannot be rendered on its own, if it cannot: a stop that looks at
/// the whole image (the path engine's convergence test) or at the clock.
pub fn part_problem(world: &World, settings: &Settings) -> Option<String> {
    let prog = &world.options.progressive;
    settings.part?;
    if settings.max_time.is_some() {
        return Some("a part cannot stop on a time limit (parts would differ in samples); drop --time".into());
    }
    if let Some(t) = prog.max_time {
        return Some(format!(
            "the scene stops rendering after {t} s (progressive max time), and parts stopped by the clock do not fit together"
        ));
    }
    if settings.engine == EngineKind::Path && settings.spp.is_none() && prog.quality_enabled {
        return Some("the scene stops the path engine by its convergence over the whole image, which no part can see; give --spp".into());
    }
    None
}

/// Stage 4, **render**: the sample passes over the pixels of `world` (of
/// `settings.part` only, when set), with the pre-passes of `prepared`. Returns the film
/// (stage 5) and what was done.
pub fn render_prepared(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    prepared: &Prepared,
    settings: &Settings,
    cancel: &AtomicBool,
    progress: &(dyn Fn(Progress) + Sync),
) -> (Film, Stats) {
    render_prepared_with_film(world, accel, shading, prepared, settings, cancel, &mut |_, p| progress(p))
}

/// [`render_prepared`] that hands `after_pass` the film as it stands after each pass (every
/// pixel's samples so far, the classic engine's splats merged) with the progress: what a
/// progressive preview writes. It is called on the calling thread, between passes.
pub fn render_prepared_with_film(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    prepared: &Prepared,
    settings: &Settings,
    cancel: &AtomicBool,
    after_pass: &mut dyn FnMut(&Film, Progress),
) -> (Film, Stats) {
    let cam = &world.camera;
    let w = cam.width;
    // The film's rows: the whole image, or a strip of it (`fy0` its first image row).
    let (fy0, h) = match &settings.rows {
        Some(r) => (r.start.min(cam.height), r.end.min(cam.height).saturating_sub(r.start)),
        None => (0, cam.height),
    };
    let mut film = Film::new(w, h);
    film.y0 = fy0;
    for (name, datatype) in &world.user_buffers {
        film.add_user_buffer(name, datatype);
    }
    let filter = PixelFilter::new(&world.options.filter);
    let prog = &world.options.progressive;
    let classic = match (prepared.engine, shading) {
        (EngineKind::Classic, Some(s)) => Some(s),
        _ => None,
    };
    let env = prepared.env.as_ref();
    // The path engine's settings, with the scene's `"gi depth"` (GI "Next") as its depth.
    let path_settings = settings.path.with_scene_options(&world.options);
    // The path engine's constant materials, built once (empty for the classic engine).
    let constants = if classic.is_none() { crate::integrator::constant_materials(world) } else { Vec::new() };
    // Which of them the path engine's kernel for plain hits may trace.
    let plain = if classic.is_none() { crate::integrator::plain_materials(world, shading) } else { Vec::new() };
    // The media the camera is in (both engines; found once, where the camera is when the
    // shutter opens; a moving camera follows its way from there, per sample).
    let camera_media = crate::integrator::media_at(world, accel, cam.camera_to_world_at(0.0).translation, 0.0);
    let (first_pass, target) = match classic {
        Some(_) => classic_samples(&world.options, settings.spp),
        None => (1, settings.spp.unwrap_or(prog.max_samples).max(1)),
    };
    let contrast = world.options.contrast.map(|c| c as f32);
    let max_time = match settings.stop_at_samples {
        Some(_) => None,
        None => settings.max_time.or(prog.max_time.map(Duration::from_secs_f64)),
    };
    let quality = (classic.is_none() && settings.spp.is_none() && prog.quality_enabled).then_some(prog);
    // The rows this render samples: all, or a part's (with its halo).
    let rows_on: Vec<bool> = match settings.part {
        None => vec![true; h as usize],
        Some(part) => {
            let split = Split::for_engine(if classic.is_some() { EngineKind::Classic } else { EngineKind::Path });
            split.rendered_rows(part, h, filter.radius().1.ceil() as u32 + 1)
        }
    };
    let start = Instant::now();
    let rays = AtomicU64::new(0);
    let shadow_rays = AtomicU64::new(0);
    let nonfinite = AtomicU64::new(0);
    let first_pixels: Mutex<Option<Duration>> = Mutex::new(None);
    let mut done = 0u32;
    let mut stats = Stats::default();
    let (x0, y0, x1, y1) = cam.window;
    let band = settings.band.max(1) as usize;
    let fb_writes: Mutex<Vec<(usize, u32, [f32; 4])>> = Mutex::new(Vec::new());
    if let Some(p) = prepared.photons {
        rays.fetch_add(p.rays, Ordering::Relaxed);
        stats.photons = Some(p);
    }
    if let Some(p) = &prepared.fg {
        rays.fetch_add(p.counts.rays, Ordering::Relaxed);
        shadow_rays.fetch_add(p.counts.shadow_rays, Ordering::Relaxed);
        stats.fg_points = p.cache.len() as u64;
        stats.fg_time = prepared.fg_time;
    }
    let fg_cache = prepared.fg.as_ref().map(|p| &p.cache);
    // The classic engine's per-band splat buffers, kept across passes.
    let band_count = (h as usize).div_ceil(band);
    let mut band_splats: Vec<Splat> = match classic {
        Some(_) => {
            film.splat = vec![[0.0; 5]; film.pixels.len()];
            (0..band_count).map(|b| Splat::new(&filter, b * band, band.min(h as usize - b * band), w, h)).collect()
        }
        None => Vec::new(),
    };
    while done < target {
        // Pass sizes 1, 1, 2, 4, … so that the first image comes quickly (the classic
        // engine starts with its minimum samples).
        let pass = if done == 0 { first_pass } else { done }.min(target - done).min(64.max(first_pass));
        let mut splat_slots: Vec<Option<&mut Splat>> = band_splats.iter_mut().map(Some).collect();
        splat_slots.resize_with(band_count, || None);
        let rows: Vec<BandWork> = film.pixels.chunks_mut(w as usize * band).enumerate().zip(splat_slots).collect();
        rows.into_par_iter().for_each(|((b, chunk), mut splat)| {
            let mut counts = RayCounts::default();
            let mut bad = 0u64;
            let mut writes = Vec::new();
            if let Some(shading) = classic {
                for (k, px) in chunk.iter_mut().enumerate() {
                    if cancel.load(Ordering::Relaxed) {
                        break;
                    }
                    let x = (k % w as usize) as u32;
                    let y = fy0 + (b * band + k / w as usize) as u32;
                    if x < x0 || x >= x1 || y < y0 || y >= y1 || px.converged || !rows_on[(y - fy0) as usize] {
                        continue;
                    }
                    // One sampler per pixel, restarted for each sample: the scrambles that
                    // depend on the pixel alone are hashed once.
                    let mut sampler = Sampler::new(pixel_seed(x, y, settings.seed), done);
                    for index in done..done + pass {
                        sampler.restart(index);
                        let u = sampler.next_2d();
                        // Motion blur: the sample's shutter time is the next dimension, so that
                        // a pixel's samples are stratified in (x, y, time) together; scenes
                        // where nothing moves draw none and keep their numbers.
                        let time =
                            world.shutter.as_ref().map_or(0.0, |shutter| shutter.shape.sample(sampler.next_1d()));
                        // The classic engine samples the pixel and splats.
                        let raster = Vec2::new(x as f32 + u.x, y as f32 + u.y);
                        // A camera that moves across a medium's surface while the shutter is
                        // open: the media where it is at this sample's time.
                        let moved_media = crate::integrator::camera_media_at(world, accel, &camera_media, time);
                        let sample_media = moved_media.as_ref().unwrap_or(&camera_media);
                        let s = crate::classic::eye_sample(
                            world,
                            accel,
                            shading,
                            fg_cache,
                            sample_media,
                            raster,
                            [x, y],
                            (index, time),
                        );
                        counts.rays += s.counts.rays;
                        counts.shadow_rays += s.counts.shadow_rays;
                        let i = b * band * w as usize + k;
                        writes.extend(s.fb.iter().map(|(buf, v)| (i, *buf, v.to_array())));
                        if let Some(splat) = splat.as_deref_mut() {
                            // Splats are kept in the film's rows.
                            splat.add(&filter, raster - Vec2::new(0.0, fy0 as f32), s.color.to_array());
                        }
                        if index == 0 {
                            if let Some(f) = s.first {
                                px.depth = cam.depth(f.point);
                                px.normal = f.normal.to_array();
                                px.tag = f.tag;
                                px.motion = s.motion.to_array();
                            }
                        }
                        let color = bsdf::Rgb::new(s.color.x, s.color.y, s.color.z);
                        bad += u64::from(px.add(color, s.color.w, 1.0, index));
                    }
                }
            } else {
                // The path engine: camera rays traced in packets (see `crate::path_band`).
                let place = |k: usize| {
                    let x = (k % w as usize) as u32;
                    let y = fy0 + (b * band + k / w as usize) as u32;
                    let inside = x >= x0 && x < x1 && y >= y0 && y < y1 && rows_on[(y - fy0) as usize];
                    inside.then_some((x, y))
                };
                let mut out = BandOutput::default();
                let job = PathBand {
                    world,
                    accel,
                    shading,
                    env,
                    constants: &constants,
                    plain: &plain,
                    filter: &filter,
                    camera_media: &camera_media,
                    path: &path_settings,
                    seed: settings.seed,
                    first: done,
                    count: pass,
                };
                job.render(chunk, b * band * w as usize, place, cancel, &mut out);
                (counts, bad, writes) = (out.counts, out.nonfinite, out.writes);
            }
            if !writes.is_empty() {
                fb_writes.lock().unwrap_or_else(|e| e.into_inner()).extend(writes);
            }
            rays.fetch_add(counts.rays, Ordering::Relaxed);
            shadow_rays.fetch_add(counts.shadow_rays, Ordering::Relaxed);
            nonfinite.fetch_add(bad, Ordering::Relaxed);
            let mut first = first_pixels.lock().unwrap_or_else(|e| e.into_inner());
            if first.is_none() {
                *first = Some(prepared.time + start.elapsed());
            }
        });
        if cancel.load(Ordering::Relaxed) {
            stats.cancelled = true;
            break;
        }
        done += pass;
        // Merge the bands' splats in band order: the sums are the same for any thread
        // count.
        for s in &mut band_splats {
            s.merge_into(&mut film.splat, w as usize);
        }
        for (i, buf, v) in fb_writes.lock().unwrap_or_else(|e| e.into_inner()).drain(..) {
            if let Some(user) = film.user.get_mut(buf as usize) {
                user.put(i, v);
            }
        }
        let mut converged_ratio = None;
        if classic.is_some() && settings.spp.is_none() {
            // mental ray's adaptive supersampling: only pixels with contrast go on.
            let more: Vec<bool> =
                (0..film.pixels.len()).map(|i| needs_more(&film, i, contrast, done == first_pass)).collect();
            let mut count = 0usize;
            for (p, m) in film.pixels.iter_mut().zip(&more) {
                if !*m {
                    p.converged = true;
                }
                count += usize::from(p.converged);
            }
            converged_ratio = Some(count as f32 / film.pixels.len().max(1) as f32);
            if count == film.pixels.len() {
                stats.converged = true;
            }
        }
        if let Some(q) = quality {
            if done >= q.min_samples {
                let threshold = 0.05 / q.quality.max(1e-3) as f32;
                let mut count = 0usize;
                let mut total = 0usize;
                for (i, p) in film.pixels.iter_mut().enumerate() {
                    let (x, y) = ((i % w as usize) as u32, fy0 + (i / w as usize) as u32);
                    if x < x0 || x >= x1 || y < y0 || y >= y1 {
                        continue;
                    }
                    total += 1;
                    if p.converged || p.error() < threshold {
                        p.converged = true;
                        count += 1;
                    }
                }
                let ratio = count as f32 / total.max(1) as f32;
                converged_ratio = Some(ratio);
                if f64::from(ratio) >= q.converged_pixel_ratio {
                    stats.converged = true;
                }
            }
        }
        let elapsed = prepared.time + start.elapsed();
        after_pass(&film, Progress { samples: done, target, converged: converged_ratio, elapsed });
        if stats.converged
            || max_time.is_some_and(|t| elapsed >= t)
            || settings.stop_at_samples.is_some_and(|n| done >= n)
        {
            break;
        }
    }
    stats.rays = rays.load(Ordering::Relaxed);
    stats.shadow_rays = shadow_rays.load(Ordering::Relaxed);
    stats.nonfinite = nonfinite.load(Ordering::Relaxed);
    stats.samples = film.pixels.iter().map(|p| u64::from(p.samples)).sum();
    stats.render_time = prepared.time + start.elapsed();
    stats.first_pixels = *first_pixels.lock().unwrap_or_else(|e| e.into_inner());
    stats.spp = done;
    (film, stats)
}
