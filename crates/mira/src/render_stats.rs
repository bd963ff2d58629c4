//! `mira render --stats`: the report printed after a render (stage times, rays, samples,
//! photons, final gather points, first pixels, peak memory), and the sums over an image's
//! strips that go into it.

use std::time::Duration;

/// Peak resident memory of this process, in bytes (Linux).
fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// CPU time this process has used so far, all threads, in seconds (Linux: `/proc/self/stat`'s
/// user and system times, in the kernel's 1/100 s ticks).
pub fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which may hold spaces, so split after its ')'):
    // state is the 3rd field, utime the 14th, stime the 15th.
    let mut rest = stat.rsplit_once(')')?.1.split_whitespace().skip(11);
    let (user, system): (u64, u64) = (rest.next()?.parse().ok()?, rest.next()?.parse().ok()?);
    Some((user + system) as f64 / 100.0)
}

/// Bytes of the world's vertex and triangle arrays (positions, normals, interleaved
/// vertex records, texture and user coordinates, bump bases, motion, triangles, material
/// slots, Ptex face codes, hair data): the geometry mira holds while it renders, each
/// array counted at its length (the allocator may hold a little more).
pub fn geometry_bytes(world: &render::World) -> u64 {
    fn bytes<T>(v: &[T]) -> usize {
        std::mem::size_of_val(v)
    }
    let mesh = |m: &render::mesh::MeshData| {
        bytes(&m.positions)
            + bytes(&m.normals)
            + bytes(&m.normals_oct)
            + bytes(&m.vertices)
            + m.textures.iter().map(|t| bytes(t)).sum::<usize>()
            + m.user.iter().map(|u| bytes(u)).sum::<usize>()
            + bytes(&m.bump_basis)
            + bytes(&m.triangles)
            + bytes(&m.slots)
            + bytes(&m.ptex_quads)
            + m.hair.as_ref().map_or(0, |h| bytes(&h.along) + bytes(&h.across) + bytes(&h.tangents))
            + bytes(&m.motion)
            + m.motion_more.iter().map(|k| bytes(k)).sum::<usize>()
            + m.position_keys.iter().map(|k| bytes(k)).sum::<usize>()
    };
    world.meshes.iter().map(mesh).sum::<usize>() as u64
}

/// The `geometry:` line of `--stats`: the world's vertex and triangle bytes
/// ([`geometry_bytes`]) and the acceleration structure's as its backend reports them.
fn geometry_line(world: &render::World, accel: &dyn render::Accel) -> String {
    let mib = |b: u64| b as f64 / (1 << 20) as f64;
    let triangles = world.instanced_triangles().max(1) as f64;
    let geometry = geometry_bytes(world);
    let mut line = format!(
        "geometry:       {:.1} MiB vertices and triangles ({:.1} B a triangle)",
        mib(geometry),
        geometry as f64 / triangles
    );
    match accel.memory() {
        Some(m) if m.counted => {
            line += &format!(", BVH {:.1} MiB ({:.1} B a triangle)", mib(m.bytes), m.bytes as f64 / triangles)
        }
        Some(m) => {
            line += &format!(
                ", BVH {:.1} MiB as Embree reports its allocations, with the quads it reads ({:.1} B a triangle)",
                mib(m.bytes),
                m.bytes as f64 / triangles
            )
        }
        None => {}
    }
    line
}

/// Adds one strip's counts to the whole image's (the pre-passes' once: every strip reports
/// the same).
pub fn add_strip_stats(total: &mut render::Stats, strip: &render::Stats, first: bool) {
    total.rays += strip.rays;
    total.shadow_rays += strip.shadow_rays;
    total.samples += strip.samples;
    total.nonfinite += strip.nonfinite;
    total.cancelled |= strip.cancelled;
    if first {
        total.first_pixels = strip.first_pixels;
        total.spp = strip.spp;
        total.fg_points = strip.fg_points;
        total.fg_time = strip.fg_time;
        total.photons = strip.photons;
    } else {
        total.spp = total.spp.min(strip.spp);
    }
}

/// Wall-clock times of the stages before rendering, for `--stats`.
pub struct StageTimes {
    /// Parsing and building the scene.
    pub load: render::pipeline::LoadTimes,
    /// Building the world (shading, MDL, meshes) and freeing what it no longer needs.
    pub world: Duration,
    /// From the start to the world built: the load and world stages and what lies between.
    pub scene: Duration,
    /// Building the acceleration structure.
    pub accel: Duration,
    /// The process's CPU seconds when rendering starts ([`process_cpu_seconds`]).
    pub cpu_at_render: Option<f64>,
}

/// Prints `--stats`.
pub fn print_stats(
    world: &render::World,
    accel: &dyn render::Accel,
    (width, height): (u32, u32),
    stats: &render::Stats,
    classic: bool,
    stages: &StageTimes,
) {
    let (t_scene, t_accel) = (stages.scene, stages.accel);
    let secs = stats.render_time.as_secs_f64().max(1e-9);
    println!(
        "scene:          {:.3} s (parse, build, translate), {} instances, {} triangles",
        t_scene.as_secs_f64(),
        world.instances.len(),
        world.instanced_triangles()
    );
    println!(
        "stages:         parse {:.3} s, scene {:.3} s, world {:.3} s, acceleration {:.3} s",
        stages.load.parse.as_secs_f64(),
        stages.load.scene.as_secs_f64(),
        stages.world.as_secs_f64(),
        t_accel.as_secs_f64()
    );
    println!("acceleration:   {:?}, built in {:.3} s", accel.backend(), t_accel.as_secs_f64());
    println!("{}", geometry_line(world, accel));
    let engine = if classic { "classic" } else { "path" };
    println!("render:         {:.3} s ({engine}), {} x {} pixels, {} spp", secs, width, height, stats.spp);
    if let (Some(start), Some(now)) = (stages.cpu_at_render, process_cpu_seconds()) {
        println!("render CPU:     {:.2} s (all threads, until the report)", now - start);
    }
    println!("samples:        {} ({:.0} samples/s)", stats.samples, stats.samples as f64 / secs);
    println!(
        "rays:           {} ({} shadow), {:.2} Mrays/s",
        stats.total_rays(),
        stats.shadow_rays,
        stats.total_rays() as f64 / secs / 1e6
    );
    if let Some(p) = &stats.photons {
        println!(
            "photons:        {} emitted, {} caustic + {} global stored, {:.1} MiB, {:.3} s",
            p.emitted,
            p.caustic,
            p.global,
            p.memory as f64 / (1 << 20) as f64,
            p.time.as_secs_f64()
        );
    }
    if stats.fg_points > 0 {
        println!(
            "final gather:   {} interpolation points, pre-pass {:.3} s",
            stats.fg_points,
            stats.fg_time.as_secs_f64()
        );
    }
    if let Some(t) = stats.first_pixels {
        println!("first pixels:   {:.3} s", t.as_secs_f64() + t_scene.as_secs_f64() + t_accel.as_secs_f64());
    }
    println!("non-finite:     {} channels stored as 1.0", stats.nonfinite);
    if let Some(m) = peak_memory() {
        println!("peak memory:    {:.1} MiB", m as f64 / (1 << 20) as f64);
    }
}
