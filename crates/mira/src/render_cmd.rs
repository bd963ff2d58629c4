//! `mira render`: turns its arguments into settings and runs the render crate's stages
//! (load, build the world, prepare, render) on one frame or several, then writes the images
//! (or, with `--part`, a partial EXR for `mira merge`).

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use render::accel::Backend;
use render::part::Part;
use render::tonemap::ToneMapper;
use render::EngineKind;

use crate::output;
use crate::render_stats::{add_strip_stats, print_stats, StageTimes};
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

/// Render options that `mira render` and `mira farm` share (what a farm task passes on).
#[derive(clap::Args, Clone, Debug)]
pub struct RenderOptions {
    /// Image size in pixels (overrides the camera's resolution, keeping its field of view).
    #[arg(long, num_args = 2, value_names = ["W", "H"])]
    pub resolution: Option<Vec<u32>>,
    /// Samples per pixel (overrides the scene's progressive settings).
    #[arg(long, value_name = "N")]
    pub spp: Option<u32>,
    /// Worker threads (0: one per core).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Seed of the sample patterns.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Acceleration structure.
    #[arg(long, value_enum, default_value_t = AccelArg::Auto)]
    pub accel: AccelArg,
    /// Rendering engine.
    #[arg(long, value_enum, default_value_t = EngineArg::Auto)]
    pub engine: EngineArg,
    /// Final gather rays at each eye-ray hit of the classic engine (default: the scene's
    /// finalgather accuracy / 16, from 4 to 64).
    #[arg(long, value_name = "N")]
    pub fg_rays: Option<u32>,
    #[command(flatten)]
    pub include: IncludeArgs,
    #[command(flatten)]
    pub memory: crate::limits::MemoryArgs,
}

impl RenderOptions {
    /// The options as `mira render` arguments.
    pub fn to_args(&self) -> Vec<String> {
        let mut a = Vec::new();
        if let Some(r) = &self.resolution {
            a.extend(["--resolution".into(), r[0].to_string(), r[1].to_string()]);
        }
        if let Some(n) = self.spp {
            a.extend(["--spp".into(), n.to_string()]);
        }
        a.extend(["--threads".into(), self.threads.to_string(), "--seed".into(), self.seed.to_string()]);
        a.extend(["--accel".into(), value_name(&self.accel), "--engine".into(), value_name(&self.engine)]);
        if let Some(n) = self.fg_rays {
            a.extend(["--fg-rays".into(), n.to_string()]);
        }
        for dir in &self.include.include {
            a.extend(["-I".into(), dir.display().to_string()]);
        }
        for dir in &self.include.mdl_paths {
            a.extend(["-M".into(), dir.display().to_string()]);
        }
        a
    }
}

/// The command-line spelling of an option's value.
fn value_name<V: clap::ValueEnum>(v: &V) -> String {
    v.to_possible_value().map(|p| p.get_name().to_string()).unwrap_or_default()
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
    #[command(flatten)]
    options: RenderOptions,
    /// Stop after this many seconds.
    #[arg(long, value_name = "SECONDS")]
    time: Option<f64>,
    /// Which `render` statement of the file (1 = the first).
    #[arg(long, default_value_t = 1)]
    frame: usize,
    /// Render the `render` statements A to B (inclusive, 1 = the first) one after the
    /// other; file names get the frame number (`out.0003.exr`).
    #[arg(long, value_name = "A..B", conflicts_with = "frame")]
    frames: Option<String>,
    /// Render only part K of N of the image and write it as a partial EXR (-o, else
    /// SCENE.partK-of-N.exr) for `mira merge`.
    #[arg(long, value_name = "K/N")]
    part: Option<String>,
    /// Read the classic engine's pre-passes (photon maps, final gather points) from this
    /// file, written by `mira prepass` for the same scene and settings, instead of
    /// computing them.
    #[arg(long, value_name = "FILE")]
    prepass: Option<PathBuf>,
    /// Render the image in strips of N rows (a multiple of 64), each written to the EXR as
    /// it finishes, so that memory holds one strip (done by itself when the whole image
    /// needs more than --max-memory).
    #[arg(long, value_name = "N")]
    strip_rows: Option<u32>,
    /// Print rays, samples per second, Mrays/s, memory and timings.
    #[arg(long)]
    stats: bool,
    /// Print warnings.
    #[arg(short = 'W', long)]
    warnings: bool,
    /// Write the image rendered so far after a pass once this many seconds have passed
    /// since the render started or the last preview (0: no previews; none with --part).
    #[arg(long, value_name = "SECONDS", default_value_t = DEFAULT_PREVIEW_SECONDS)]
    preview: f64,
}

/// Seconds between progressive previews (`--preview`): a render that takes longer shows a
/// first picture this soon after its first passes, a short one writes none.
const DEFAULT_PREVIEW_SECONDS: f64 = 2.0;

/// Parses `A..B` (inclusive, from 1).
pub fn parse_frames(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("'{s}' is not a frame range: give A..B with 1 ≤ A ≤ B, e.g. 1..24");
    let (a, b) = s.split_once("..").ok_or_else(bad)?;
    let (a, b): (usize, usize) = (a.trim().parse().map_err(|_| bad())?, b.trim().parse().map_err(|_| bad())?);
    if a == 0 || b < a {
        return Err(bad());
    }
    Ok((a, b))
}

/// `path` with the frame number before its extension (`out.exr` → `out.0003.exr`).
pub fn frame_path(path: &Path, frame: usize) -> PathBuf {
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let name = match path.extension() {
        Some(e) => format!("{stem}.{frame:04}.{}", e.to_string_lossy()),
        None => format!("{stem}.{frame:04}"),
    };
    path.with_file_name(name)
}

/// A scene loaded for rendering or merging.
pub struct LoadedScene {
    /// The parsed file (its sources, for messages).
    pub parsed: mi::Parsed,
    /// The scene at the chosen render statement, resolution applied.
    pub scene: scene::Scene,
    /// Hash of the scene's text.
    pub content_hash: u64,
    /// How long parsing and building the scene took.
    pub times: render::pipeline::LoadTimes,
}

/// Stage 1 for the commands: loads `path` at `frame` (1 = the first render statement),
/// prints its errors (and warnings when asked), applies `resolution`.
pub fn load_scene(
    path: &Path,
    include: &[PathBuf],
    frame: usize,
    resolution: Option<(u32, u32)>,
    warnings: bool,
) -> Result<LoadedScene, String> {
    let options = IncludeArgs { include: include.to_vec(), mdl_paths: Vec::new() }.read_options();
    let loaded = render::pipeline::load(path, &options, frame.saturating_sub(1))?;
    let mut stderr = std::io::stderr().lock();
    for d in &loaded.diagnostics {
        if d.is_error() || warnings {
            let _ = write!(stderr, "{}", d.render(&loaded.parsed.sources));
        }
    }
    drop(stderr);
    if loaded.has_errors() {
        return Err(format!("{} has errors; nothing rendered", path.display()));
    }
    let content_hash = loaded.content_hash();
    let times = loaded.times;
    let Some(mut scene) = loaded.scene else { return Err("no world to render".into()) };
    if let Some((w, h)) = resolution {
        let max = scene::camera::MAX_RESOLUTION;
        if !(1..=max).contains(&w) || !(1..=max).contains(&h) {
            return Err(format!("--resolution {w} {h} is outside 1 … {max} pixels per side"));
        }
        render::pipeline::set_resolution(&mut scene, w, h);
    }
    Ok(LoadedScene { parsed: loaded.parsed, scene, content_hash, times })
}

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

/// The settings of a render as `key=value` lines: what parts of one image must share.
fn settings_text(settings: &render::Settings, size: (u32, u32), backend: Backend, fg_rays: Option<u32>) -> String {
    format!(
        "engine={:?}\nresolution={}x{}\nspp={:?}\nseed={}\nfg_rays={:?}\naccel={:?}\npath={:?}\nband={}",
        settings.engine, size.0, size.1, settings.spp, settings.seed, fg_rays, backend, settings.path, settings.band
    )
}

/// The settings the classic engine's pre-passes depend on, as `key=value` lines: what a
/// pre-pass file must have been computed with (the scene itself is in the hash beside it).
pub fn prepass_settings_text(
    frame: usize,
    size: (u32, u32),
    seed: u32,
    fg_rays: Option<u32>,
    backend: Backend,
) -> String {
    format!("frame={frame}\nresolution={}x{}\nseed={seed}\nfg_rays={fg_rays:?}\naccel={backend:?}", size.0, size.1)
}

/// The hash a pre-pass file is keyed by: the scene's text and the files it reads.
pub fn prepass_scene_hash(text_hash: u64, inputs_hash: u64) -> u64 {
    let mut h = render::pipeline::Fnv::new();
    h.write(&text_hash.to_le_bytes());
    h.write(&inputs_hash.to_le_bytes());
    h.finish()
}

/// The acceleration structure `accel` asks for, or why it cannot be had.
pub fn backend_of(accel: AccelArg) -> Result<Backend, String> {
    match accel {
        AccelArg::Auto => Ok(Backend::default_available()),
        AccelArg::Rust => Ok(Backend::Rust),
        AccelArg::Embree if Backend::Embree.available() => Ok(Backend::Embree),
        AccelArg::Embree => Err("this mira was built without Embree (install libembree-dev and rebuild)".into()),
    }
}

/// The engine `engine` asks for (`None`: the scene's choice).
pub fn asked_engine(engine: EngineArg) -> Option<EngineKind> {
    match engine {
        EngineArg::Classic => Some(EngineKind::Classic),
        EngineArg::Path => Some(EngineKind::Path),
        EngineArg::Auto => None,
    }
}

/// The shading options of a render of `scene` with `opts`.
pub fn shading_options(scene: &Path, opts: &RenderOptions) -> shader::ShadingOptions {
    shader::ShadingOptions {
        search: shader::texture::SearchPath {
            dirs: render::pipeline::texture_dirs(scene, &opts.include.read_options().include_paths),
        },
        seed: opts.seed,
        finalgather_rays: opts.fg_rays,
    }
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
    // Stage 1: load.
    let resolution = opts.resolution.as_ref().map(|r| (r[0], r[1]));
    let mut loaded = pool
        .install(|| load_scene(&args.scene, &opts.include.include, frame, resolution, args.warnings))
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
        let classic_only = if classic { render::pipeline::classic_warnings(world) } else { Vec::new() };
        for w in if classic { &classic_only } else { &world.warnings } {
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
            if !classic {
                return Err(err(format!(
                    "--prepass {}: the path engine has no pre-pass to read (it is for the classic engine)",
                    file.display()
                )));
            }
            let bytes = std::fs::read(file).map_err(|e| err(format!("cannot read {}: {e}", file.display())))?;
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
            let saved = render::prepass_file::decode(&bytes, &file.display().to_string(), &key).map_err(err)?;
            render::prepare::prepare_saved(shading, saved)
                .ok_or_else(|| err("the pre-passes were already made".into()))?
        }
        None => prepare_within(args.time, cancel, |stop| {
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
    if let Some(rows) = strip_rows {
        // Strips: rendered and written one after the other (stage 4 and 6 together).
        // `choose_strips` made sure there is exactly one target, an EXR file.
        let target = targets.first().cloned().ok_or_else(|| err("no image to write".into()))?;
        if sc.camera.outputs.iter().any(|o| matches!(o, scene::camera::Output::Shader { .. })) {
            eprintln!("mira: warning: output shaders are not run on an image rendered in strips");
        }
        let on_progress = |p: render::Progress| {
            if let Some(bar) = &bar {
                bar.set_position(u64::from(p.samples));
            }
        };
        let (w, h) = (world.camera.width, world.camera.height);
        let filter = render::filter::PixelFilter::new(&world.options.filter);
        let strips = render::strips::strips(h, rows, engine, &filter, settings.band);
        let mut layout = render::film::Film::new(w, 0);
        for (name, datatype) in &world.user_buffers {
            layout.add_user_buffer(name, datatype);
        }
        let mut total = render::Stats::default();
        let start = Instant::now();
        let mut next = strips.iter().enumerate();
        // Under a time limit, the samples per pixel the first strip reached in its share of
        // the time: every later strip stops there.
        let mut first_spp = 0;
        let written = output::write_strips(&target, &tone, (w, h), &layout, || {
            let (i, strip) = next.next()?;
            if let Some(bar) = &bar {
                bar.set_message(format!("strip {}/{}", i + 1, strips.len()));
            }
            let settings =
                render::strips::strip_settings(&world.options, &settings, &strips, i, prepared.time, first_spp);
            let (film, stats) = pool.install(|| {
                render::render_prepared(
                    world,
                    accel.as_ref(),
                    Some(shading),
                    &prepared,
                    &settings,
                    cancel,
                    &on_progress,
                )
            });
            add_strip_stats(&mut total, &stats, i == 0);
            if i == 0 {
                first_spp = stats.spp;
            }
            Some(film.rows(strip.keep.clone()))
        });
        total.render_time = prepared.time + start.elapsed();
        if let Some(bar) = &bar {
            bar.finish_and_clear();
        }
        if total.cancelled {
            eprintln!("mira: interrupted; strips not rendered are black");
        }
        let failed = match written {
            Ok(()) => {
                eprintln!("mira: wrote {} ({} strips of {rows} rows)", target.path.display(), strips.len());
                false
            }
            Err(e) => {
                eprintln!("mira: error: cannot write {}: {e}", target.path.display());
                true
            }
        };
        if args.stats {
            let stages = StageTimes { load: load_times, world: t_world, scene: t_scene, accel: t_accel };
            print_stats(world, accel.as_ref(), (w, h), &total, classic, &stages);
        }
        return if failed {
            Err(ExitCode::FAILURE)
        } else if total.cancelled {
            Err(ExitCode::from(130))
        } else {
            Ok(())
        };
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
    let mut failed = false;
    if let Some(p) = part {
        let default = args.scene.with_extension(format!("part{}-of-{}.exr", p.index, p.count));
        let path = args.output.clone().unwrap_or(default);
        let path = numbered.map_or(path.clone(), |f| frame_path(&path, f));
        if !path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")) {
            return Err(err(format!("a part is written as OpenEXR: '{}' must end in .exr", path.display())));
        }
        let split = render::part::Split::for_engine(engine);
        let owned = split.owned_rows(p, film.height);
        let info = crate::part_file::PartInfo {
            scene: std::path::absolute(&args.scene).unwrap_or_else(|_| args.scene.clone()),
            include: opts
                .include
                .include
                .iter()
                .map(|d| std::path::absolute(d).unwrap_or_else(|_| d.clone()))
                .collect(),
            scene_hash: content_hash,
            inputs_hash,
            settings: settings_text(&settings, (film.width, film.height), backend, opts.fg_rays),
            settings_hash: render::pipeline::Fnv::of(
                settings_text(&settings, (film.width, film.height), backend, opts.fg_rays).as_bytes(),
            ),
            part: p,
            split,
            frame,
            classic,
            size: (film.width, film.height),
            spp: stats.spp,
            samples: owned
                .iter()
                .flat_map(|&y| &film.pixels[(y * film.width) as usize..((y + 1) * film.width) as usize])
                .map(|px| u64::from(px.samples))
                .sum(),
            weight: owned.len() as f64 / f64::from(film.height.max(1)),
            partial: stats.cancelled,
            user: film.user.iter().map(|b| (b.name.clone(), b.datatype.clone())).collect(),
        };
        match crate::part_file::write(&film, &info, &path) {
            Ok(()) => eprintln!(
                "mira: wrote part {p} to {}{}",
                path.display(),
                if stats.cancelled { " (partial)" } else { "" }
            ),
            Err(e) => {
                eprintln!("mira: error: cannot write {}: {e}", path.display());
                failed = true;
            }
        }
    } else {
        // The camera's output shaders (Maya's glow) on the whole image.
        for w in render::output_shaders::run(&mut film, &sc.camera, &sc.library) {
            eprintln!("mira: warning: {w}");
        }
        // Outputs: -o, else the camera's file outputs and file frame buffers, else
        // SCENE.exr; numbered per frame with --frames.
        for target in &targets {
            match output::write(&film, target, &tone) {
                Ok(()) => eprintln!("mira: wrote {}", target.path.display()),
                Err(e) => {
                    eprintln!("mira: error: cannot write {}: {e}", target.path.display());
                    failed = true;
                }
            }
        }
    }
    if args.stats {
        let stages = StageTimes { load: load_times, world: t_world, scene: t_scene, accel: t_accel };
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

/// Reads the source text freed after parsing again, for messages that quote it.
fn restore_sources(sources: &mut mi::SourceMap) {
    if let Err(e) = sources.restore_text() {
        eprintln!("mira: warning: {e}");
    }
}

/// Writes the image rendered so far (`samples` per pixel) to every target, each through a
/// hidden file beside it renamed into place, so that a viewer never reads half a file;
/// returns the line to show. A preview that cannot be written is reported, not fatal.
fn write_preview(film: &render::film::Film, targets: &[output::Target], tone: &ToneMapper, samples: u32) -> String {
    let mut written = Vec::new();
    let mut failed = Vec::new();
    for target in targets {
        let name = target.path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let hidden = output::Target { path: target.path.with_file_name(format!(".{name}.preview")), ..target.clone() };
        let result = output::write(film, &hidden, tone)
            .and_then(|()| std::fs::rename(&hidden.path, &target.path).map_err(|e| e.to_string()));
        match result {
            Ok(()) => written.push(target.path.display().to_string()),
            Err(e) => {
                let _ = std::fs::remove_file(&hidden.path);
                failed.push(format!("{}: {e}", target.path.display()));
            }
        }
    }
    let mut line = format!("mira: preview at {samples} spp: {}", written.join(", "));
    if !failed.is_empty() {
        line.push_str(&format!(" (not written: {})", failed.join("; ")));
    }
    line
}

/// Runs the pre-passes (`prepare`) with a stop flag that is set once `time` seconds have
/// passed or `cancel` is set, so that `--time` bounds the photon and final gather passes as
/// well as the sample passes (they stop early with what they have); warns when the clock
/// stopped them.
fn prepare_within<T>(time: Option<f64>, cancel: &AtomicBool, prepare: impl FnOnce(&AtomicBool) -> T) -> T {
    let stop = AtomicBool::new(false);
    let start = Instant::now();
    let done = AtomicBool::new(false);
    let out = std::thread::scope(|s| {
        s.spawn(|| {
            while !done.load(Ordering::Relaxed) {
                if cancel.load(Ordering::Relaxed) || time.is_some_and(|t| start.elapsed().as_secs_f64() >= t) {
                    stop.store(true, Ordering::SeqCst);
                    return;
                }
                std::thread::sleep(Duration::from_millis(5));
            }
        });
        let out = prepare(&stop);
        done.store(true, Ordering::Relaxed);
        out
    });
    if stop.load(Ordering::SeqCst) && !cancel.load(Ordering::Relaxed) {
        if let Some(t) = time {
            eprintln!(
                "mira: warning: --time {t} s ran out in the pre-passes (photon maps, final gather points); they \
                 stopped early with what they had, and one sample pass follows"
            );
        }
    }
    out
}

/// Whether to render in strips, and of how many rows: `--strip-rows`, else strips when the
/// whole image's film and frame buffers need more than `--max-memory` (an error when they
/// cannot be used: a farm part, or outputs other than one EXR file).
fn choose_strips(args: &RenderArgs, loaded: &mut LoadedScene, part: Option<Part>) -> Result<Option<u32>, String> {
    let limit = args.options.memory.limit();
    let too_large = crate::limits::check_film(
        &loaded.scene,
        loaded.scene.camera.resolution,
        limit,
        args.options.resolution.is_some(),
    );
    if too_large.is_some() {
        // The diagnostic quotes the source text, freed after parsing.
        restore_sources(&mut loaded.parsed.sources);
    }
    let sc = &loaded.scene;
    let show = |d: &Option<mi::Diagnostic>| {
        if let Some(d) = d {
            eprint!("{}", d.render(&loaded.parsed.sources));
        }
    };
    let rows = match (args.strip_rows, &too_large) {
        (None, None) => return Ok(None),
        (Some(n), _) => {
            let align = imageio::exr_strips::STRIP_ALIGNMENT;
            if n == 0 || n % align != 0 {
                return Err(format!("--strip-rows {n} is not a positive multiple of {align}"));
            }
            n
        }
        (None, Some(_)) => {
            let (w, _) = sc.camera.resolution;
            match crate::limits::strip_rows(w, crate::limits::user_buffers(sc), limit.0) {
                Some(n) => n,
                None => {
                    show(&too_large);
                    return Err(format!(
                        "{} needs too much memory, even in strips of {} rows; nothing rendered",
                        args.scene.display(),
                        imageio::exr_strips::STRIP_ALIGNMENT
                    ));
                }
            }
        }
    };
    let targets = output::targets(&sc.camera, args.output.as_deref(), &args.scene)?;
    let problem = if part.is_some() {
        Some(render::strips::PART_PROBLEM.to_string())
    } else if targets.len() != 1 || targets[0].format.kind != imageio::Kind::Exr {
        Some(format!(
            "an image rendered in strips is written to one OpenEXR file (-o FILE.exr), not to {}",
            targets.iter().map(|t| format!("'{}'", t.path.display())).collect::<Vec<_>>().join(", ")
        ))
    } else {
        None
    };
    if let Some(p) = problem {
        show(&too_large);
        return Err(format!("cannot render in strips: {p}"));
    }
    if too_large.is_some() && args.strip_rows.is_none() {
        let (w, h) = sc.camera.resolution;
        eprintln!(
            "mira: {w} x {h} pixels need more film memory than {} ({}): rendering in strips of {rows} rows",
            crate::limits::size_text(u128::from(limit.0)),
            limit.1
        );
    }
    Ok(Some(rows))
}
