//! `mira prepass`: computes the classic engine's pre-passes of a scene once — the photon
//! maps and the final gather points — and writes them to a file that every part of a farm
//! render reads (`mira render --part K/N --prepass FILE`) instead of computing them again.
//! The file is keyed by the scene (its text and the files it reads) and the settings the
//! pre-passes depend on; a render with another scene or settings refuses it
//! ([`render::prepass_file`]).

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Instant;

use render::prepass_file::{self, PrepassKey};
use render::EngineKind;

use crate::render_cmd::{
    asked_engine, backend_of, load_scene, prepass_scene_hash, prepass_settings_text, shading_options, RenderOptions,
};

/// Arguments of `mira prepass`.
#[derive(clap::Args, Debug)]
pub struct PrepassArgs {
    /// The scene.
    #[arg(value_name = "SCENE")]
    scene: PathBuf,
    /// The pre-pass file to write.
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Which `render` statement of the file (1 = the first).
    #[arg(long, default_value_t = 1)]
    frame: usize,
    /// The options the parts will be rendered with (those the pre-passes depend on —
    /// resolution, seed, --fg-rays, accelerator, engine — must be the same).
    #[command(flatten)]
    options: RenderOptions,
    /// Print warnings.
    #[arg(short = 'W', long)]
    warnings: bool,
}

/// Runs the command.
pub fn run(args: &PrepassArgs) -> ExitCode {
    match prepass(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("mira: error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn prepass(args: &PrepassArgs) -> Result<(), String> {
    let t0 = Instant::now();
    let opts = &args.options;
    let resolution = opts.resolution.as_ref().map(|r| (r[0], r[1]));
    let loaded = load_scene(&args.scene, &opts.include.include, args.frame, resolution, args.warnings, true)?;
    let sc = &loaded.scene;
    let name = args.scene.display();
    if render::pipeline::choose_engine(sc, asked_engine(opts.engine)) != EngineKind::Classic {
        return Err(format!("{name} renders with the path engine, which has no pre-pass to save"));
    }
    if !prepass_file::scene_has_prepass(&sc.options) {
        return Err(format!(
            "{name} has no pre-pass to save: no caustics, no photon global illumination, no final gathering \
             through a cache"
        ));
    }
    let backend = backend_of(opts.accel)?;
    let shading_options = shading_options(&args.scene, opts);
    let built = render::pipeline::build_world(sc, &shading_options, &opts.include.mdl_paths);
    {
        let mut stderr = std::io::stderr().lock();
        for d in &built.diagnostics {
            if d.is_error() || args.warnings {
                let _ = write!(stderr, "{}", d.render(&loaded.parsed.sources));
            }
        }
    }
    if built.diagnostics.iter().any(|d| d.is_error()) {
        return Err(format!("{name} has errors; no pre-pass computed"));
    }
    let inputs_hash = render::pipeline::inputs_hash(sc, &shading_options.search, &built);
    let (world, shading) = (&built.world, &built.shading);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads)
        .build()
        .map_err(|e| format!("cannot start worker threads: {e}"))?;
    // SIGINT and SIGTERM stop the pre-passes; what they made is incomplete and not written.
    let cancel = Arc::new(AtomicBool::new(false));
    {
        let cancel = cancel.clone();
        let _ = ctrlc::set_handler(move || {
            if cancel.swap(true, std::sync::atomic::Ordering::SeqCst) {
                std::process::exit(130);
            }
        });
    }
    let accel = pool.install(|| render::accel::build(world, backend));
    let prepared =
        pool.install(|| render::prepare::prepare(world, accel.as_ref(), Some(shading), EngineKind::Classic, &cancel));
    if cancel.load(std::sync::atomic::Ordering::SeqCst) {
        return Err("interrupted: no pre-pass file written".into());
    }
    let key = PrepassKey {
        scene_hash: prepass_scene_hash(loaded.content_hash, inputs_hash),
        settings: prepass_settings_text(
            args.frame,
            (world.camera.width, world.camera.height),
            opts.seed,
            opts.fg_rays,
            backend,
        ),
    };
    let photons = shading.photons.get().zip(prepared.photons.as_ref());
    let bytes = prepass_file::encode(&key, photons, prepared.fg.as_ref());
    std::fs::write(&args.output, &bytes).map_err(|e| format!("cannot write {}: {e}", args.output.display()))?;
    let stats = prepared.photons.map_or(String::new(), |p| {
        format!("{} caustic + {} global photons ({:.3} s)", p.caustic, p.global, p.time.as_secs_f64())
    });
    let fg = prepared.fg.as_ref().map_or(String::new(), |f| {
        format!("{} final gather points ({:.3} s)", f.cache.len(), prepared.fg_time.as_secs_f64())
    });
    eprintln!(
        "mira: wrote {} ({:.1} MiB: {}) in {:.3} s",
        args.output.display(),
        bytes.len() as f64 / f64::from(1 << 20),
        [stats, fg].into_iter().filter(|s| !s.is_empty()).collect::<Vec<_>>().join(", "),
        t0.elapsed().as_secs_f64()
    );
    Ok(())
}
