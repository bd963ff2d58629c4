//! `mira render`: build the world, render it progressively, write the images.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use render::accel::Backend;
use render::tonemap::ToneMapper;

use crate::output::{self, Format};
use crate::IncludeArgs;

/// Which acceleration structure to use.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum AccelArg {
    /// Embree if mira was built with it, else the Rust BVH.
    Auto,
    /// mira's own BVHs.
    Rust,
    /// Intel Embree 3.
    Embree,
}

/// Which engine renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum EngineArg {
    /// Classic if the scene's materials are mental ray shaders, else path.
    Auto,
    /// mental ray's shader-driven ray tracing.
    Classic,
    /// Iray-style progressive path tracing.
    Path,
}

/// Arguments of `mira render`.
#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// The scene to render.
    #[arg(value_name = "SCENE")]
    scene: PathBuf,
    /// Write this image instead of the scene's outputs (format from the extension: .exr
    /// linear with every frame buffer; .png, .jpg, .tif tone mapped; .hdr linear).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Image size in pixels (overrides the camera's resolution, keeping its field of view).
    #[arg(long, num_args = 2, value_names = ["W", "H"])]
    resolution: Option<Vec<u32>>,
    /// Samples per pixel (overrides the scene's progressive settings).
    #[arg(long, value_name = "N")]
    spp: Option<u32>,
    /// Worker threads (0: one per core).
    #[arg(long, default_value_t = 0)]
    threads: usize,
    /// Seed of the sample patterns.
    #[arg(long, default_value_t = 0)]
    seed: u32,
    /// Stop after this many seconds.
    #[arg(long, value_name = "SECONDS")]
    time: Option<f64>,
    /// Acceleration structure.
    #[arg(long, value_enum, default_value_t = AccelArg::Auto)]
    accel: AccelArg,
    /// Rendering engine.
    #[arg(long, value_enum, default_value_t = EngineArg::Auto)]
    engine: EngineArg,
    /// Final gather rays at each eye-ray hit of the classic engine (default: the scene's
    /// finalgather accuracy / 16, from 4 to 64).
    #[arg(long, value_name = "N")]
    fg_rays: Option<u32>,
    /// Which `render` statement of the file (1 = the first).
    #[arg(long, default_value_t = 1)]
    frame: usize,
    /// Print rays, samples per second, Mrays/s, memory and timings.
    #[arg(long)]
    stats: bool,
    /// Print warnings.
    #[arg(short = 'W', long)]
    warnings: bool,
    #[command(flatten)]
    include: IncludeArgs,
    #[command(flatten)]
    memory: crate::limits::MemoryArgs,
}

/// Most worker threads `--threads` may ask for.
const MAX_THREADS: usize = 4096;

/// Peak resident memory of this process, in bytes (Linux).
fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Runs the command.
pub fn run(args: &RenderArgs) -> ExitCode {
    let err = |msg: String| {
        eprintln!("mira: error: {msg}");
        ExitCode::FAILURE
    };
    if let Some(t) = args.time {
        if !(t.is_finite() && t >= 0.0) {
            return err(format!("--time {t} is not a number of seconds ≥ 0"));
        }
    }
    if args.threads > MAX_THREADS {
        return err(format!("--threads {} is more than mira starts ({MAX_THREADS})", args.threads));
    }
    let t0 = Instant::now();
    let options = args.include.read_options();
    let parsed = match mi::parse_file(&args.scene, &options) {
        Ok(p) => p,
        Err(e) => return err(e.to_string()),
    };
    let mut diags = parsed.diagnostics.list.clone();
    let world_scene = if parsed.diagnostics.has_errors() {
        None
    } else {
        scene::Scene::build(&parsed, args.frame.saturating_sub(1), &mut diags)
    };
    let mut stderr = std::io::stderr().lock();
    for d in &diags {
        if d.is_error() || args.warnings {
            let _ = write!(stderr, "{}", d.render(&parsed.sources));
        }
    }
    drop(stderr);
    if diags.iter().any(|d| d.is_error()) {
        return err(format!("{} has errors; nothing rendered", args.scene.display()));
    }
    let Some(mut sc) = world_scene else { return err("no world to render".into()) };
    if let Some(res) = &args.resolution {
        let max = scene::camera::MAX_RESOLUTION;
        if !(1..=max).contains(&res[0]) || !(1..=max).contains(&res[1]) {
            return err(format!("--resolution {} {} is outside 1 … {max} pixels per side", res[0], res[1]));
        }
        let (w, h) = (res[0], res[1]);
        let old = sc.camera.resolution;
        // Keep the image plane: aspect stays as the camera had it relative to its pixels.
        let pixel_aspect = old.0 as f64 / (sc.camera.aspect * old.1 as f64);
        sc.camera.aspect = w as f64 / (h as f64 * pixel_aspect);
        sc.camera.resolution = (w, h);
        sc.camera.offset = (sc.camera.offset.0 * w as f64 / old.0 as f64, sc.camera.offset.1 * h as f64 / old.1 as f64);
        sc.camera.window = sc.camera.window.map(|[a, b, c, d]| {
            let sx = w as f64 / old.0 as f64;
            let sy = h as f64 / old.1 as f64;
            [(a as f64 * sx) as i64, (b as f64 * sy) as i64, (c as f64 * sx) as i64, (d as f64 * sy) as i64]
        });
    }
    if let Some(d) =
        crate::limits::check_film(&sc, sc.camera.resolution, args.memory.limit(), args.resolution.is_some())
    {
        eprint!("{}", d.render(&parsed.sources));
        return err(format!("{} needs too much memory; nothing rendered", args.scene.display()));
    }
    let classic = match args.engine {
        EngineArg::Classic => true,
        EngineArg::Path => false,
        EngineArg::Auto => shade::model::Shading::wants_classic(&sc),
    };
    // Both engines use the compiled shading: the classic one runs the material shaders,
    // the path engine the shaders connected to material parameters (textures, bumps).
    let shading = {
        let mut dirs: Vec<PathBuf> = args.scene.parent().map(Path::to_path_buf).into_iter().collect();
        dirs.extend(options.include_paths.iter().cloned());
        let shading_options = shade::model::ShadingOptions {
            search: shade::texture::SearchPath { dirs },
            seed: args.seed,
            finalgather_rays: args.fg_rays,
        };
        let (shading, shade_diags) = shade::model::Shading::build(&sc, &shading_options);
        let mut stderr = std::io::stderr().lock();
        for d in &shade_diags {
            if d.is_error() || args.warnings {
                let _ = write!(stderr, "{}", d.render(&parsed.sources));
            }
        }
        drop(stderr);
        // An error of the shaders is an error of the scene: nothing is rendered.
        if shade_diags.iter().any(|d| d.is_error()) {
            return err(format!("{} has errors; nothing rendered", args.scene.display()));
        }
        shading
    };
    let world = render::World::from_scene_shaded(&sc, Some(&shading));
    if args.warnings && !classic {
        for w in &world.warnings {
            eprintln!("mira: warning: {w}");
        }
    }
    let t_scene = t0.elapsed();
    let backend = match args.accel {
        AccelArg::Auto => Backend::default_available(),
        AccelArg::Rust => Backend::Rust,
        AccelArg::Embree => {
            if !Backend::Embree.available() {
                return err("this mira was built without Embree (install libembree-dev and rebuild)".into());
            }
            Backend::Embree
        }
    };
    let pool = match rayon::ThreadPoolBuilder::new().num_threads(args.threads).build() {
        Ok(p) => p,
        Err(e) => return err(format!("cannot start worker threads: {e}")),
    };
    let t1 = Instant::now();
    let accel = pool.install(|| render::accel::build(&world, backend));
    let t_accel = t1.elapsed();
    let cancel = Arc::new(AtomicBool::new(false));
    {
        let cancel = cancel.clone();
        let _ = ctrlc::set_handler(move || {
            if cancel.swap(true, Ordering::SeqCst) {
                std::process::exit(130);
            }
        });
    }
    let settings = render::Settings {
        engine: if classic { render::EngineKind::Classic } else { render::EngineKind::Path },
        spp: args.spp,
        seed: args.seed,
        max_time: args.time.map(Duration::from_secs_f64),
        ..render::Settings::default()
    };
    let target = if classic {
        render::render::classic_samples(&world.options, settings.spp).1
    } else {
        settings.spp.unwrap_or(world.options.progressive.max_samples).max(1)
    };
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(u64::from(target));
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} spp ({eta} left) {msg}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar
    });
    let on_progress = |p: render::Progress| {
        if let Some(bar) = &bar {
            bar.set_position(u64::from(p.samples));
            if let Some(c) = p.converged {
                bar.set_message(format!("{:.1}% converged", c * 100.0));
            }
        }
    };
    let (film, stats) =
        pool.install(|| render::render(&world, accel.as_ref(), Some(&shading), &settings, &cancel, &on_progress));
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    if stats.cancelled {
        eprintln!("mira: interrupted at {} samples per pixel; writing what was rendered", stats.spp);
    }
    // Outputs: -o, else the camera's file outputs in formats mira writes, else SCENE.exr.
    let tone = ToneMapper::for_camera(&sc.camera, &sc.library, classic);
    let mut targets: Vec<(PathBuf, Format, output::Extras)> = Vec::new();
    // Buffers beyond colour some output asks for (`-o` writes them too).
    let asked = sc
        .camera
        .outputs
        .iter()
        .filter_map(|o| match o {
            scene::camera::Output::File { types, .. } => Some(output::Extras::from_types(types)),
            _ => None,
        })
        .chain(sc.camera.framebuffers.iter().map(|fb| output::Extras::from_types(&[&fb.datatype])))
        .fold(output::Extras::default(), output::Extras::union);
    if let Some(o) = &args.output {
        match Format::from_path(o) {
            Some(f) => targets.push((o.clone(), f, asked)),
            None => {
                return err(format!(
                    "cannot tell the image format of '{}' (use .exr, .png, .jpg, .tif or .hdr)",
                    o.display()
                ))
            }
        }
    } else {
        for out in &sc.camera.outputs {
            if let scene::camera::Output::File { types, format, file } = out {
                let extras = output::Extras::from_types(types);
                match Format::from_name(format) {
                    Some(f) if extras.motion && f != Format::Exr => {
                        eprintln!("mira: warning: the motion buffer of '{file}' is written only to EXR files; skipped")
                    }
                    Some(f) => targets.push((PathBuf::from(file), f, extras)),
                    None => eprintln!("mira: warning: output format '{format}' of '{file}' is not supported; skipped"),
                }
            }
        }
        for fb in &sc.camera.framebuffers {
            let extras = output::Extras::from_types(&[&fb.datatype]);
            if let (Some(file), true) = (&fb.filename, fb.primary || fb.datatype.starts_with("rgb") || extras.motion) {
                let format =
                    fb.filetype.as_deref().and_then(Format::from_name).or_else(|| Format::from_path(Path::new(file)));
                match format {
                    Some(f) if extras.motion && f != Format::Exr => {
                        eprintln!(
                            "mira: warning: the motion buffer '{}' is written only to EXR files; skipped",
                            fb.name
                        )
                    }
                    Some(f) => targets.push((PathBuf::from(file), f, extras)),
                    None => {}
                }
            }
        }
        if targets.is_empty() {
            targets.push((args.scene.with_extension("exr"), Format::Exr, asked));
        }
    }
    let mut failed = false;
    for (path, format, extras) in &targets {
        match output::write(&film, path, *format, &tone, *extras) {
            Ok(()) => eprintln!("mira: wrote {}", path.display()),
            Err(e) => {
                eprintln!("mira: error: cannot write {}: {e}", path.display());
                failed = true;
            }
        }
    }
    if args.stats {
        let secs = stats.render_time.as_secs_f64().max(1e-9);
        println!(
            "scene:          {:.3} s (parse, build, translate), {} instances, {} triangles",
            t_scene.as_secs_f64(),
            world.instances.len(),
            world.instanced_triangles()
        );
        println!("acceleration:   {:?}, built in {:.3} s", accel.backend(), t_accel.as_secs_f64());
        let engine = if classic { "classic" } else { "path" };
        println!(
            "render:         {:.3} s ({engine}), {} x {} pixels, {} spp",
            secs, film.width, film.height, stats.spp
        );
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
    if failed {
        ExitCode::FAILURE
    } else if stats.cancelled {
        // 128 + SIGINT, as shells report an interrupted command.
        ExitCode::from(130)
    } else {
        ExitCode::SUCCESS
    }
}
