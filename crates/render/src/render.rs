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

use crate::accel::Accel;
use crate::film::{Film, Pixel};
use crate::filter::PixelFilter;
use crate::integrator::{trace_path, PathSettings, RayCounts};
use crate::sampler::{pixel_seed, Sampler};
use crate::world::World;

/// How to render.
#[derive(Clone, Debug)]
pub struct Settings {
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
}

impl Default for Settings {
    fn default() -> Settings {
        Settings { spp: None, seed: 0, max_time: None, path: PathSettings::default(), band: 4 }
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
}

impl Stats {
    /// All rays traced.
    pub fn total_rays(&self) -> u64 {
        self.rays + self.shadow_rays
    }
}

/// Renders `world` progressively. `progress` is called after each pass; `cancel` stops the
/// render at the next row (the image keeps what was done).
pub fn render(
    world: &World,
    accel: &dyn Accel,
    settings: &Settings,
    cancel: &AtomicBool,
    progress: &(dyn Fn(Progress) + Sync),
) -> (Film, Stats) {
    let cam = &world.camera;
    let (w, h) = (cam.width, cam.height);
    let mut film = Film::new(w, h);
    for (name, datatype) in &world.user_buffers {
        film.add_user_buffer(name, datatype);
    }
    let filter = PixelFilter::new(&world.options.filter);
    let prog = &world.options.progressive;
    let target = settings.spp.unwrap_or(prog.max_samples).max(1);
    let max_time = settings.max_time.or(prog.max_time.map(Duration::from_secs_f64));
    let quality = (settings.spp.is_none() && prog.quality_enabled).then_some(prog);
    let start = Instant::now();
    let rays = AtomicU64::new(0);
    let shadow_rays = AtomicU64::new(0);
    let nonfinite = AtomicU64::new(0);
    let first_pixels: Mutex<Option<Duration>> = Mutex::new(None);
    let mut done = 0u32;
    let mut stats = Stats::default();
    let (x0, y0, x1, y1) = cam.window;
    let band = settings.band.max(1) as usize;
    while done < target {
        // Pass sizes 1, 1, 2, 4, … so that the first image comes quickly.
        let pass = done.max(1).min(target - done).min(64);
        let rows: Vec<(usize, &mut [Pixel])> = film.pixels.chunks_mut(w as usize * band).enumerate().collect();
        rows.into_par_iter().for_each(|(b, chunk)| {
            let mut counts = RayCounts::default();
            let mut bad = 0u64;
            for (k, px) in chunk.iter_mut().enumerate() {
                if cancel.load(Ordering::Relaxed) {
                    break;
                }
                let x = (k % w as usize) as u32;
                let y = (b * band + k / w as usize) as u32;
                if x < x0 || x >= x1 || y < y0 || y >= y1 || px.converged {
                    continue;
                }
                let seed = pixel_seed(x, y, settings.seed);
                for index in done..done + pass {
                    let mut sampler = Sampler::new(seed, index);
                    let (offset, weight) = filter.sample(sampler.next_2d());
                    let ray = cam.ray(x as f32 + 0.5 + offset.x, y as f32 + 0.5 + offset.y);
                    let r = trace_path(world, accel, ray, &mut sampler, &settings.path, &mut counts);
                    if index == 0 {
                        if let Some(f) = r.first {
                            px.depth = cam.depth(f.point);
                            px.normal = f.normal.to_array();
                            px.tag = f.tag;
                        }
                    }
                    bad += u64::from(px.add(r.radiance, r.alpha, weight, index));
                }
            }
            rays.fetch_add(counts.rays, Ordering::Relaxed);
            shadow_rays.fetch_add(counts.shadow_rays, Ordering::Relaxed);
            nonfinite.fetch_add(bad, Ordering::Relaxed);
            let mut first = first_pixels.lock().unwrap_or_else(|e| e.into_inner());
            if first.is_none() {
                *first = Some(start.elapsed());
            }
        });
        if cancel.load(Ordering::Relaxed) {
            stats.cancelled = true;
            break;
        }
        done += pass;
        let mut converged_ratio = None;
        if let Some(q) = quality {
            if done >= q.min_samples {
                let threshold = 0.05 / q.quality.max(1e-3) as f32;
                let mut count = 0usize;
                let mut total = 0usize;
                for (i, p) in film.pixels.iter_mut().enumerate() {
                    let (x, y) = ((i % w as usize) as u32, (i / w as usize) as u32);
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
        progress(Progress { samples: done, target, converged: converged_ratio, elapsed: start.elapsed() });
        if stats.converged || max_time.is_some_and(|t| start.elapsed() >= t) {
            break;
        }
    }
    stats.rays = rays.load(Ordering::Relaxed);
    stats.shadow_rays = shadow_rays.load(Ordering::Relaxed);
    stats.nonfinite = nonfinite.load(Ordering::Relaxed);
    stats.samples = film.pixels.iter().map(|p| u64::from(p.samples)).sum();
    stats.render_time = start.elapsed();
    stats.first_pixels = *first_pixels.lock().unwrap_or_else(|e| e.into_inner());
    stats.spp = done;
    (film, stats)
}
