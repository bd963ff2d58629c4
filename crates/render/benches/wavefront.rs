//! Whether the path engine's bounce rays would trace faster in another order (issue 13,
//! docs/performance.md, speed33): renders a scene on one thread while recording every
//! closest-hit ray in the order the paths trace them, then traces the recorded bounce rays
//! again with Embree's one-ray kernel (`rtcIntersect1`)
//! - in path order (today's order: each path's bounces one after another);
//! - in waves: the paths of a group of `P` consecutive camera samples kept in flight, all
//!   their first bounces, then all their second bounces, …, each wave in path order or
//!   sorted for coherence (direction octant then the Morton code of the origin; a Morton
//!   code over origin and direction together; the direction's octahedral cell then the
//!   origin);
//!
//! and with Embree's stream kernel (`rtcIntersect1M`, incoherent and coherent flags) and its
//! 8-ray packet kernel (`rtcIntersect8`, scenes not built compact) on
//! the same waves; and, to see whether two paths in flight would hide the hit's vertex
//! reads (the triangle's indices, then its normals) behind the other path's traversal,
//! path order with those reads after each ray against two paths' rays interleaved with
//! each hit's index line prefetched and read one ray later. Prints CPU nanoseconds per ray
//! (the median of interleaved repetitions) and checks that the one-ray kernel's hits are
//! the recorded ones in every order.
//!
//! Needs Embree and a scene: `MIRA_WAVEFRONT_SCENE=/path/heavy_4M.mi cargo bench -p render
//! --bench wavefront` (optional `MIRA_WAVEFRONT_RES=256`, `MIRA_WAVEFRONT_SPP=16`,
//! `MIRA_WAVEFRONT_REPS=3`). Without the variable it prints how to run it and stops.

use std::sync::atomic::AtomicBool;
use std::sync::Mutex;
use std::time::Instant;

use glam::Vec3A;
use render::accel::{Accel, Backend, Hit};
use render::ray::Ray;

/// The calling thread's CPU time so far in seconds (Linux `/proc/thread-self/schedstat`:
/// nanoseconds on the CPU), so that the machine's other load does not count; wall time
/// elsewhere.
fn thread_cpu() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|t| t.parse::<u64>().ok()))
        .map_or_else(
            || std::time::SystemTime::UNIX_EPOCH.elapsed().map_or(0.0, |d| d.as_secs_f64()),
            |ns| ns as f64 * 1e-9,
        )
}

/// An accel that records each closest-hit query (ray and hit) before answering it.
struct Recorder<'a> {
    inner: &'a dyn Accel,
    rays: Mutex<Vec<(Ray, Option<Hit>)>>,
}

impl Accel for Recorder<'_> {
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let h = self.inner.intersect(ray);
        self.rays.lock().unwrap().push((*ray, h));
        h
    }
    fn occluded(&self, ray: &Ray) -> bool {
        self.inner.occluded(ray)
    }
    fn occluded_batch(&self, rays: &[Ray], blocked: &mut [bool]) {
        self.inner.occluded_batch(rays, blocked)
    }
    fn backend(&self) -> Backend {
        self.inner.backend()
    }
}

/// Spreads the low 10 bits of `v` to every third bit.
fn spread3(v: u32) -> u64 {
    let mut x = u64::from(v & 0x3ff);
    x = (x | (x << 16)) & 0x0300_00ff;
    x = (x | (x << 8)) & 0x0300_f00f;
    x = (x | (x << 4)) & 0x030c_30c3;
    (x | (x << 2)) & 0x0924_9249
}

/// 30-bit Morton code of `p` in the box `lo..hi`.
fn morton(p: Vec3A, lo: Vec3A, hi: Vec3A) -> u64 {
    let q = ((p - lo) / (hi - lo).max(Vec3A::splat(1e-20)) * 1023.0).clamp(Vec3A::ZERO, Vec3A::splat(1023.0));
    spread3(q.x as u32) | (spread3(q.y as u32) << 1) | (spread3(q.z as u32) << 2)
}

/// The direction's octant (3 bits).
fn octant(d: Vec3A) -> u64 {
    u64::from(d.x < 0.0) | (u64::from(d.y < 0.0) << 1) | (u64::from(d.z < 0.0) << 2)
}

/// The direction's cell in an octahedral map of 32 × 32 cells (10 bits, Morton order).
fn octa_cell(d: Vec3A) -> u64 {
    let d = d / (d.x.abs() + d.y.abs() + d.z.abs());
    let (mut u, mut v) = (d.x, d.y);
    if d.z < 0.0 {
        (u, v) = ((1.0 - v.abs()) * u.signum(), (1.0 - u.abs()) * v.signum());
    }
    let (iu, iv) = (((u * 0.5 + 0.5) * 31.99) as u32, ((v * 0.5 + 0.5) * 31.99) as u32);
    let s = |x: u32| {
        let mut x = x & 31;
        x = (x | (x << 2)) & 0x33;
        x = (x | (x << 1)) & 0x55;
        u64::from(x)
    };
    s(iu) | (s(iv) << 1)
}

/// The sort keys tried.
#[derive(Clone, Copy, Debug)]
enum Order {
    /// Direction octant, then the origin's Morton code.
    OctantOrigin,
    /// One Morton code over origin (5 bits an axis) and direction (5 bits an axis).
    OriginDir,
    /// The direction's octahedral cell, then the origin's Morton code.
    DirOrigin,
}

fn key(order: Order, r: &Ray, lo: Vec3A, hi: Vec3A) -> u64 {
    match order {
        Order::OctantOrigin => (octant(r.dir) << 30) | morton(r.origin, lo, hi),
        Order::OriginDir => {
            let o = morton(r.origin, lo, hi) >> 15; // 5 bits an axis
            let d = (r.dir.normalize() + Vec3A::ONE) * 0.5;
            let dm = morton(d, Vec3A::ZERO, Vec3A::ONE) >> 15;
            let mut k = 0u64;
            for b in 0..15 {
                k |= ((o >> b) & 1) << (2 * b + 1);
                k |= ((dm >> b) & 1) << (2 * b);
            }
            k
        }
        Order::DirOrigin => (octa_cell(r.dir) << 30) | morton(r.origin, lo, hi),
    }
}

/// A recorded bounce ray: its index in the recording, its path and its bounce.
#[derive(Clone, Copy)]
struct Bounce {
    at: usize,
    path: u32,
    depth: u16,
}

/// Splits the recording into paths: a ray whose origin is the previous ray's hit point
/// (within a relative 1e-4 of the scene's size) goes on the previous ray's path; a ray
/// from the camera's position is a camera ray; any other ray starts a path.
fn bounces(rec: &[(Ray, Option<Hit>)], camera: Vec3A, size: f32) -> Vec<Bounce> {
    let mut out = Vec::new();
    let (mut path, mut depth) = (0u32, 0u16);
    let mut prev_end: Option<Vec3A> = None;
    for (i, (r, h)) in rec.iter().enumerate() {
        if (r.origin - camera).length() < 1e-6 * size.max(1.0) {
            prev_end = None;
            continue;
        }
        let goes_on = prev_end.is_some_and(|p| (p - r.origin).length() < 1e-4 * size);
        if goes_on {
            depth += 1;
        } else {
            path += 1;
            depth = 1;
        }
        out.push(Bounce { at: i, path, depth });
        prev_end = h.map(|h| r.at(h.t));
    }
    out
}

/// The waves of groups of `p` paths: the indices into `rec`, per group and depth, in
/// path order.
fn waves(b: &[Bounce], p: u32) -> Vec<Vec<usize>> {
    let mut out: Vec<Vec<usize>> = Vec::new();
    let mut start = 0;
    while start < b.len() {
        let group = (b[start].path - 1) / p;
        let mut end = start;
        while end < b.len() && (b[end].path - 1) / p == group {
            end += 1;
        }
        let max_depth = b[start..end].iter().map(|x| x.depth).max().unwrap_or(0);
        for d in 1..=max_depth {
            out.push(b[start..end].iter().filter(|x| x.depth == d).map(|x| x.at).collect());
        }
        start = end;
    }
    out
}

/// The vertex data the path engine's `surface` reads at a hit: the triangle's indices, then
/// its three vertex normals (folded into one number so that nothing is optimised away).
#[inline(always)]
fn hit_reads(world: &render::World, h: &Hit) -> f32 {
    let mesh = &world.meshes[world.instances[h.instance as usize].mesh as usize];
    let [i0, i1, i2] = mesh.triangles[h.prim as usize];
    if !mesh.has_normals() {
        return 0.0;
    }
    (mesh.normal(i0) + mesh.normal(i1) + mesh.normal(i2)).x
}

/// Asks the CPU to bring the cache line of the indices of the triangle `h` hit closer (a
/// hint: no load, no fault).
#[allow(unsafe_code)]
#[inline(always)]
fn prefetch_indices(world: &render::World, h: &Hit) {
    let mesh = &world.meshes[world.instances[h.instance as usize].mesh as usize];
    #[cfg(target_arch = "x86_64")]
    if let Some(t) = mesh.triangles.get(h.prim as usize) {
        // SAFETY: a prefetch reads nothing architecturally; the address is a live element.
        unsafe { std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(t.as_ptr().cast()) };
    }
}

/// Two paths' rays interleaved (the first ray of path 1, of path 2, the second of path 1,
/// …), for pairs of consecutive paths: what two paths in flight would trace.
fn two_in_flight(b: &[Bounce]) -> Vec<usize> {
    let mut out = Vec::with_capacity(b.len());
    let mut start = 0;
    while start < b.len() {
        let pair = (b[start].path - 1) / 2;
        let mut end = start;
        while end < b.len() && (b[end].path - 1) / 2 == pair {
            end += 1;
        }
        let a: Vec<usize> = b[start..end].iter().filter(|x| x.path % 2 == 1).map(|x| x.at).collect();
        let c: Vec<usize> = b[start..end].iter().filter(|x| x.path % 2 == 0).map(|x| x.at).collect();
        for k in 0..a.len().max(c.len()) {
            out.extend(a.get(k).copied());
            out.extend(c.get(k).copied());
        }
        start = end;
    }
    out
}

/// The closest hit and the hit's vertex reads of every ray of `order`, one after another
/// (`pipelined`: each hit's reads wait until the next ray is traced, its index line
/// prefetched meanwhile). Returns the CPU seconds taken and a sum of what was read.
fn trace_and_read(
    world: &render::World,
    accel: &dyn Accel,
    rec: &[(Ray, Option<Hit>)],
    order: &[usize],
    pipelined: bool,
) -> (f64, f32) {
    let mut sum = 0.0;
    let t = thread_cpu();
    let mut waiting: Option<Hit> = None;
    for &i in order {
        let h = accel.intersect(&rec[i].0);
        if !pipelined {
            if let Some(h) = &h {
                sum += hit_reads(world, h);
            }
            continue;
        }
        if let Some(h) = &h {
            prefetch_indices(world, h);
        }
        if let Some(w) = waiting.take() {
            sum += hit_reads(world, &w);
        }
        waiting = h;
    }
    if let Some(w) = waiting {
        sum += hit_reads(world, &w);
    }
    (thread_cpu() - t, sum)
}

#[cfg(embree)]
fn main() {
    let Some(path) = std::env::var_os("MIRA_WAVEFRONT_SCENE") else {
        eprintln!("wavefront: set MIRA_WAVEFRONT_SCENE to a .mi scene (e.g. the 4 M-triangle heavy scene) to run");
        return;
    };
    let env = |k: &str, d: u32| std::env::var(k).ok().and_then(|v| v.parse().ok()).unwrap_or(d);
    let (res, spp, reps) =
        (env("MIRA_WAVEFRONT_RES", 256), env("MIRA_WAVEFRONT_SPP", 16), env("MIRA_WAVEFRONT_REPS", 3));
    let path = std::path::PathBuf::from(path);
    let mut loaded = render::pipeline::load_unhashed(&path, &mi::ReadOptions::default(), 0).expect("scene loads");
    let scene = loaded.scene.as_mut().expect("scene builds");
    render::pipeline::set_resolution(scene, res, res);
    let built = render::pipeline::build_world_taking_meshes(scene, &Default::default(), &[]);
    let world = &built.world;
    let accel = render::accel::embree::EmbreeAccel::new(world);
    let recorder = Recorder { inner: &accel, rays: Mutex::new(Vec::new()) };
    let settings = render::Settings { spp: Some(spp), ..render::Settings::default() };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let t = Instant::now();
    pool.install(|| {
        render::render(world, &recorder, Some(&built.shading), &settings, &AtomicBool::new(false), &|_| {})
    });
    eprintln!("recorded render: {:.2} s", t.elapsed().as_secs_f64());
    let rec = recorder.rays.into_inner().unwrap();
    let (mut lo, mut hi) = (Vec3A::splat(f32::MAX), Vec3A::splat(f32::MIN));
    for (r, _) in &rec {
        lo = lo.min(r.origin);
        hi = hi.max(r.origin);
    }
    let camera = world.camera.camera_to_world_at(0.0).translation;
    let b = bounces(&rec, camera, (hi - lo).max_element());
    let max_depth = b.iter().map(|x| x.depth).max().unwrap_or(0);
    eprintln!(
        "{} closest-hit rays, {} of them bounce rays of {} paths (deepest bounce {max_depth})",
        rec.len(),
        b.len(),
        b.last().map_or(0, |x| x.path)
    );

    // Each variant: a list of batches (indices into `rec`) and how a batch is traced.
    #[derive(Clone, Copy, Debug)]
    enum Kernel {
        One,
        Stream {
            coherent: bool,
        },
        /// Embree's 8-ray packet kernel (`rtcIntersect8`, through `intersect_batch`) on
        /// consecutive runs of eight rays of a wave; one ray at a time where the scene is
        /// built compact (no packets there).
        Packet8,
    }
    let path_order: Vec<Vec<usize>> = vec![b.iter().map(|x| x.at).collect()];
    let mut variants: Vec<(String, Vec<Vec<usize>>, Kernel)> = vec![("path order".into(), path_order, Kernel::One)];
    for p in [256u32, 1024, 4096, 16384] {
        let w = waves(&b, p);
        variants.push((format!("waves of {p} paths, path order"), w.clone(), Kernel::One));
        for order in [Order::OctantOrigin, Order::OriginDir, Order::DirOrigin] {
            let mut sorted = w.clone();
            for wave in &mut sorted {
                wave.sort_by_key(|&i| key(order, &rec[i].0, lo, hi));
            }
            variants.push((format!("waves of {p} paths, sorted {order:?}"), sorted, Kernel::One));
        }
        variants.push((format!("waves of {p} paths, packets of 8"), w.clone(), Kernel::Packet8));
        let mut sorted = w.clone();
        for wave in &mut sorted {
            wave.sort_by_key(|&i| key(Order::OctantOrigin, &rec[i].0, lo, hi));
        }
        variants.push((format!("waves of {p} paths, sorted, packets of 8"), sorted, Kernel::Packet8));
        if p == 256 || p == 4096 {
            variants.push((
                format!("waves of {p} paths, stream incoherent"),
                w.clone(),
                Kernel::Stream { coherent: false },
            ));
            variants.push((
                format!("waves of {p} paths, stream coherent"),
                w.clone(),
                Kernel::Stream { coherent: true },
            ));
        }
    }
    // The hit's vertex reads after each ray: in path order, and with two paths in flight
    // (the reads of one path's hit overlapping the other path's traversal).
    {
        let path_order: Vec<usize> = b.iter().map(|x| x.at).collect();
        let pairs = two_in_flight(&b);
        let cases: [(&str, &[usize], bool); 3] = [
            ("path order, hit reads after each ray", &path_order, false),
            ("two paths in flight, reads after each ray", &pairs, false),
            ("two paths in flight, reads one ray later, prefetched", &pairs, true),
        ];
        let mut t = vec![Vec::new(); cases.len()];
        let mut check = 0.0;
        for _ in 0..reps {
            for (k, (_, order, pipelined)) in cases.iter().enumerate() {
                let (s, sum) = trace_and_read(world, &accel, &rec, order, *pipelined);
                t[k].push(s);
                check += sum;
            }
        }
        let med = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let base = med(&mut t[0].clone());
        for ((name, _, _), v) in cases.iter().zip(&mut t) {
            let m = med(v);
            println!("{name:<50} {:>10.1} {:>8.3}", m / b.len() as f64 * 1e9, m / base);
        }
        eprintln!("(checksum {check})");
    }
    // What sorting costs: the keys and the sort of every wave of 256 paths.
    let t = thread_cpu();
    let mut w = waves(&b, 256);
    for wave in &mut w {
        wave.sort_by_cached_key(|&i| key(Order::OctantOrigin, &rec[i].0, lo, hi));
    }
    eprintln!(
        "sorting the waves of 256 paths (octant, origin): {:.1} ns a ray",
        (thread_cpu() - t) / b.len() as f64 * 1e9
    );
    let mut times = vec![Vec::new(); variants.len()];
    let mut rays: Vec<Ray> = Vec::new();
    let mut hits: Vec<Option<Hit>> = Vec::new();
    for _ in 0..reps {
        for (k, (_, batches, kernel)) in variants.iter().enumerate() {
            let mut mismatches = 0usize;
            let t = thread_cpu();
            for batch in batches {
                match kernel {
                    Kernel::One => {
                        for &i in batch {
                            let h = accel.intersect(&rec[i].0);
                            mismatches += usize::from(h != rec[i].1);
                        }
                    }
                    Kernel::Packet8 => {
                        rays.clear();
                        rays.extend(batch.iter().map(|&i| rec[i].0));
                        hits.clear();
                        hits.resize(rays.len(), None);
                        accel.intersect_batch(&rays, &mut hits);
                        for (&i, h) in batch.iter().zip(&hits) {
                            mismatches += usize::from(h.map(|h| h.prim) != rec[i].1.map(|h| h.prim));
                        }
                    }
                    Kernel::Stream { coherent } => {
                        rays.clear();
                        rays.extend(batch.iter().map(|&i| rec[i].0));
                        hits.clear();
                        hits.resize(rays.len(), None);
                        accel.intersect_stream(&rays, &mut hits, *coherent);
                        for (&i, h) in batch.iter().zip(&hits) {
                            mismatches += usize::from(h.map(|h| h.prim) != rec[i].1.map(|h| h.prim));
                        }
                    }
                }
            }
            times[k].push(thread_cpu() - t);
            if mismatches > 0 {
                eprintln!("{}: {mismatches} hits differ from the recorded ones", variants[k].0);
            }
        }
    }
    let n = b.len() as f64;
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let base = median(&mut times[0].clone());
    println!("{:<50} {:>10} {:>8}", "bounce rays traced", "ns a ray", "ratio");
    for ((name, _, _), t) in variants.iter().zip(&mut times) {
        let m = median(t);
        println!("{name:<50} {:>10.1} {:>8.3}", m / n * 1e9, m / base);
    }
}

#[cfg(not(embree))]
fn main() {
    eprintln!("wavefront: built without Embree; nothing to measure");
}
