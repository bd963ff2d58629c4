//! `mira render`: turns its arguments into settings and runs the render crate's stages
//! (load, build the world, prepare, render) on one frame or several, then writes the images
//! (or, with `--part`, a partial EXR for `mira merge`).
//!
//! This module is the driver (a frame's stages in order); its arguments and the settings
//! they give are `args`, loading `load`, the pre-passes `prepass`, rendering in strips
//! `strips`, writing `write`, and what parts and pre-pass files must share
//! `settings_keys`.

mod args;
mod load;
mod prepass;
mod settings_keys;
mod strips;
mod write;

use std::io::{IsTerminal, Write};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use render::accel::Backend;
use render::part::Part;
use render::tonemap::ToneMapper;
use render::EngineKind;

use crate::output;
use crate::render_stats::{print_stats, StageTimes};

pub use args::{asked_engine, backend_of, frame_path, parse_frames, shading_options, RenderArgs, RenderOptions};
use load::restore_sources;
pub use load::{load_scene, LoadedScene};
pub use settings_keys::{prepass_scene_hash, prepass_settings_text};
use strips::choose_strips;
use write::write_preview;

/// Most worker threads `--threads` may ask for.
const MAX_THREADS: usize = 4096;

/// Runs the command.
pub fn run(args: &RenderArgs) -> ExitCode {
    if let Some(t) = args.time {
        if !(t.is_finite() && t >= 0.0) {
            eprintln!("mira: error: --time {t} is not a number of seconds ≥ 0");
            return ExitCode::FAILURE;
        }
    }
    if !(args.preview.is_finite() && args.preview >= 0.0) {
        eprintln!("mira: error: --preview {} is not a number of seconds ≥ 0", args.preview);
        return ExitCode::FAILURE;
    }
    if args.options.threads > MAX_THREADS {
        eprintln!("mira: error: --threads {} is more than mira starts ({MAX_THREADS})", args.options.threads);
        return ExitCode::FAILURE;
    }
    let (first, last) = match args.frames.as_deref().map(parse_frames) {
        Some(Ok(r)) => r,
        Some(Err(e)) => {
            eprintln!("mira: error: {e}");
            return ExitCode::FAILURE;
        }
        None => (args.frame, args.frame),
    };
    // SIGINT and SIGTERM (what schedulers send at a time limit) stop the render at the
    // next row; the image rendered so far is written. A second signal exits at once.
    let cancel = Arc::new(AtomicBool::new(false));
    {
        let cancel = cancel.clone();
        let _ = ctrlc::set_handler(move || {
            if cancel.swap(true, Ordering::SeqCst) {
                std::process::exit(130);
            }
        });
    }
    for frame in first..=last {
        let numbered = (args.frames.is_some()).then_some(frame);
        match render_frame(args, frame, numbered, &cancel) {
            Ok(()) => {}
            Err(code) => return code,
        }
    }
    ExitCode::SUCCESS
}

/// A frame ready for its sample passes (stage 4) and its files (stage 6): the world, its
/// acceleration structure and pre-passes, the settings, and what the files are keyed by.
#[derive(Clone, Copy)]
struct FrameJob<'a> {
    /// The command's arguments.
    args: &'a RenderArgs,
    /// How long the stages before rendering took (for `--stats`).
    stages: &'a StageTimes,
    /// The scene (its camera and shader library; its geometry is released).
    scene: &'a scene::Scene,
    /// The world rendered.
    world: &'a render::World,
    /// The world's acceleration structure.
    accel: &'a dyn render::Accel,
    /// The compiled shading, its pre-passes made.
    shading: &'a shader::Shading,
    /// The pre-passes' results.
    prepared: &'a render::prepare::Prepared<'a>,
    /// The render's settings.
    settings: &'a render::Settings,
    /// The engine that renders.
    engine: EngineKind,
    /// Whether that is the classic engine.
    classic: bool,
    /// The worker threads.
    pool: &'a rayon::ThreadPool,
    /// Set to stop rendering at the next row (SIGINT, SIGTERM).
    cancel: &'a AtomicBool,
    /// The progress bar, when stderr is a terminal.
    bar: Option<&'a indicatif::ProgressBar>,
    /// Which render statement (1 = the first).
    frame: usize,
    /// The frame number put into output names (`--frames`).
    numbered: Option<usize>,
    /// The acceleration structure's kind.
    backend: Backend,
    /// Hash of the scene's text (0 unless a part or pre-pass file needs it).
    content_hash: u64,
    /// Hash of what the scene reads besides its text (0 unless a part or pre-pass file
    /// needs it).
    inputs_hash: u64,
}

/// Renders `frame` (1 = the first render statement); `numbered` puts the frame number
/// into output names.
fn render_frame(args: &RenderArgs, frame: usize, numbered: Option<usize>, cancel: &AtomicBool) -> Result<(), ExitCode> {
    let err = |msg: String| {
        eprintln!("mira: error: {msg}");
        ExitCode::FAILURE
    };
    let opts = &args.options;
    let part = match args.part.as_deref().map(Part::parse) {
        Some(Err(e)) => return Err(err(e)),
        Some(Ok(p)) => Some(p),
        None => None,
    };
    // The worker threads: they also read big number lists while parsing.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads)
        .build()
        .map_err(|e| err(format!("cannot start worker threads: {e}")))?;
    let t0 = Instant::now();
    // Stage 1: load. The scene's text is hashed only for the files that record it (parts
    // and pre-pass files).
    let hash = part.is_some() || args.prepass.is_some();
    let resolution = opts.resolution.as_ref().map(|r| (r[0], r[1]));
    let mut loaded = pool
        .install(|| load_scene(&args.scene, &opts.include.include, frame, resolution, args.warnings, hash))
        .map_err(err)?;
    // The syntax tree is not needed past the scene: freed now, it does not add to the peak
    // memory of building the world (the sources stay, for messages).
    loaded.parsed.items = Vec::new();
    let engine = render::pipeline::choose_engine(&loaded.scene, asked_engine(opts.engine));
    let classic = engine == EngineKind::Classic;
    // Stage 2: build the world (an image too large for one film renders in strips).
    let strip_rows = choose_strips(args, &mut loaded, part).map_err(err)?;
    let shading_options = shading_options(&args.scene, opts);
    let t_world = Instant::now();
    // The world takes the scene's meshes (nothing past this point reads them).
    let scene_mut = &mut loaded.scene;
    let built = pool
        .install(|| render::pipeline::build_world_taking_meshes(scene_mut, &shading_options, &opts.include.mdl_paths));
    let sc = &loaded.scene;
    if built.diagnostics.iter().any(|d| d.is_error() || args.warnings) {
        restore_sources(&mut loaded.parsed.sources);
    }
    {
        let mut stderr = std::io::stderr().lock();
        for d in &built.diagnostics {
            if d.is_error() || args.warnings {
                let _ = write!(stderr, "{}", d.render(&loaded.parsed.sources));
            }
        }
    }
    // An error of the shaders is an error of the scene: nothing is rendered.
    if built.diagnostics.iter().any(|d| d.is_error()) {
        return Err(err(format!("{} has errors; nothing rendered", args.scene.display())));
    }
    // The file's text and syntax tree are not needed past this point, nor the scene's
    // other geometry (hair) once the world has its own: freed early, they do not add to
    // the peak memory of the acceleration structure build.
    // What the scene reads besides its text (textures, light profiles, MDL modules): parts
    // and pre-pass files rendered against other files must not be mixed.
    let inputs_hash = if part.is_some() || args.prepass.is_some() {
        render::pipeline::inputs_hash(sc, &shading_options.search, &built)
    } else {
        0
    };
    let LoadedScene { parsed, scene: mut loaded_scene, content_hash, times: load_times } = loaded;
    drop(parsed);
    loaded_scene.release_geometry();
    let t_world = t_world.elapsed();
    let sc = &loaded_scene;
    let (world, shading) = (&built.world, &built.shading);
    if args.warnings {
        // The world's warnings are the path engine's: what it renders differently.
        for w in if classic { &[][..] } else { &world.warnings[..] } {
            eprintln!("mira: warning: {w}");
        }
    }
    let t_scene = t0.elapsed();
    let backend = backend_of(opts.accel).map_err(err)?;
    let settings = render::Settings {
        engine,
        spp: opts.spp,
        seed: opts.seed,
        max_time: args.time.map(Duration::from_secs_f64),
        part,
        ..render::Settings::default()
    };
    if strip_rows.is_some() {
        if let Some(problem) = render::strips::problem(world, &settings) {
            return Err(err(format!("cannot render in strips: {problem}")));
        }
    }
    if let Some(p) = part {
        if let Some(problem) = render::render::part_problem(world, &settings) {
            return Err(err(format!("cannot render part {p}: {problem}")));
        }
        if p.count > world.camera.height {
            return Err(err(format!(
                "the image has {} rows: it cannot be cut into {} parts",
                world.camera.height, p.count
            )));
        }
    }
    // Stage 3: prepare (acceleration, then the pre-passes).
    let t1 = Instant::now();
    let accel = pool.install(|| render::accel::build(world, backend));
    let t_accel = t1.elapsed();
    let prepared = match &args.prepass {
        Some(file) => {
            let key = render::prepass_file::PrepassKey {
                scene_hash: prepass_scene_hash(content_hash, inputs_hash),
                settings: prepass_settings_text(
                    frame,
                    (world.camera.width, world.camera.height),
                    opts.seed,
                    opts.fg_rays,
                    backend,
                ),
            };
            prepass::read_saved(file, classic, &key, shading).map_err(err)?
        }
        None => prepass::prepare_within(args.time, cancel, |stop| {
            pool.install(|| render::prepare::prepare(world, accel.as_ref(), Some(shading), engine, stop))
        }),
    };
    // Stage 4: render.
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
    // The files to write (whole images): known before rendering, so that previews go
    // where the final image will.
    let tone = ToneMapper::for_camera(&sc.camera, &sc.library, classic);
    let mut targets = match part {
        Some(_) => Vec::new(),
        None => output::targets(&sc.camera, args.output.as_deref(), &args.scene).map_err(err)?,
    };
    if let Some(f) = numbered {
        for t in &mut targets {
            t.path = frame_path(&t.path, f);
        }
    }
    let stages = StageTimes {
        load: load_times,
        world: t_world,
        scene: t_scene,
        accel: t_accel,
        cpu_at_render: crate::render_stats::process_cpu_seconds(),
    };
    let job = FrameJob {
        args,
        stages: &stages,
        scene: sc,
        world,
        accel: accel.as_ref(),
        shading,
        prepared: &prepared,
        settings: &settings,
        engine,
        classic,
        pool: &pool,
        cancel,
        bar: bar.as_ref(),
        frame,
        numbered,
        backend,
        content_hash,
        inputs_hash,
    };
    if let Some(rows) = strip_rows {
        // Strips: rendered and written one after the other (stage 4 and 6 together).
        return strips::render_in_strips(&job, rows, &targets, &tone);
    }
    let render_start = Instant::now();
    let mut last_preview = render_start;
    let mut on_pass = |film: &render::film::Film, p: render::Progress| {
        if let Some(bar) = &bar {
            bar.set_position(u64::from(p.samples));
            if let Some(c) = p.converged {
                bar.set_message(format!("{:.1}% converged", c * 100.0));
            }
        }
        let due = args.preview > 0.0 && last_preview.elapsed().as_secs_f64() >= args.preview;
        if due && p.samples < p.target && !cancel.load(Ordering::Relaxed) {
            let message = write_preview(film, &targets, &tone, p.samples);
            match &bar {
                Some(bar) => bar.println(message),
                None => eprintln!("{message}"),
            }
            last_preview = Instant::now();
        }
    };
    let (mut film, stats) = pool.install(|| {
        render::render::render_prepared_with_film(
            world,
            accel.as_ref(),
            Some(shading),
            &prepared,
            &settings,
            cancel,
            &mut on_pass,
        )
    });
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    if stats.cancelled {
        eprintln!("mira: interrupted at {} samples per pixel; writing what was rendered", stats.spp);
    }
    // Stage 6: write.
    let failed = match part {
        Some(p) => write::write_part(&job, &film, &stats, p)?,
        None => write::write_images(&mut film, &targets, &tone, sc),
    };
    if args.stats {
        print_stats(world, accel.as_ref(), (film.width, film.height), &stats, classic, &stages);
    }
    if failed {
        Err(ExitCode::FAILURE)
    } else if stats.cancelled {
        // 128 + SIGINT, as shells report an interrupted command.
        Err(ExitCode::from(130))
    } else {
        Ok(())
    }
}
