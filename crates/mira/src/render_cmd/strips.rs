//! Rendering an image in strips of rows, each written to the EXR file as it finishes, so
//! that memory holds one strip: whether to, and the render itself.

use std::process::ExitCode;
use std::time::Instant;

use render::part::Part;
use render::tonemap::ToneMapper;

use super::load::{restore_sources, LoadedScene};
use super::{FrameJob, RenderArgs};
use crate::output;
use crate::render_stats::{add_strip_stats, print_stats};

/// Renders the frame `job` in strips of `rows` rows, each written to the one target (an
/// EXR file, as [`choose_strips`] made sure) as it finishes: stages 4 and 6 together.
pub(super) fn render_in_strips(
    job: &FrameJob,
    rows: u32,
    targets: &[output::Target],
    tone: &ToneMapper,
) -> Result<(), ExitCode> {
    let err = |msg: String| {
        eprintln!("mira: error: {msg}");
        ExitCode::FAILURE
    };
    let FrameJob {
        args,
        scene: sc,
        world,
        accel,
        shading,
        prepared,
        settings,
        engine,
        classic,
        pool,
        cancel,
        bar,
        stages,
        ..
    } = *job;
    // `choose_strips` made sure there is exactly one target, an EXR file.
    let target = targets.first().cloned().ok_or_else(|| err("no image to write".into()))?;
    if sc.camera.outputs.iter().any(|o| matches!(o, scene::camera::Output::Shader { .. })) {
        eprintln!("mira: warning: output shaders are not run on an image rendered in strips");
    }
    let on_progress = |p: render::Progress| {
        if let Some(bar) = bar {
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
    let written = output::write_strips(&target, tone, (w, h), &layout, || {
        let (i, strip) = next.next()?;
        if let Some(bar) = bar {
            bar.set_message(format!("strip {}/{}", i + 1, strips.len()));
        }
        let settings = render::strips::strip_settings(&world.options, settings, &strips, i, prepared.time, first_spp);
        let (film, stats) = pool.install(|| {
            render::render_prepared(world, accel, Some(shading), prepared, &settings, cancel, &on_progress)
        });
        add_strip_stats(&mut total, &stats, i == 0);
        if i == 0 {
            first_spp = stats.spp;
        }
        Some(film.rows(strip.keep.clone()))
    });
    total.render_time = prepared.time + start.elapsed();
    if let Some(bar) = bar {
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
        print_stats(world, accel, (w, h), &total, classic, stages);
    }
    if failed {
        Err(ExitCode::FAILURE)
    } else if total.cancelled {
        Err(ExitCode::from(130))
    } else {
        Ok(())
    }
}

/// Whether to render in strips, and of how many rows: `--strip-rows`, else strips when the
/// whole image's film and frame buffers need more than `--max-memory` (an error when they
/// cannot be used: a farm part, or outputs other than one EXR file).
pub(super) fn choose_strips(
    args: &RenderArgs,
    loaded: &mut LoadedScene,
    part: Option<Part>,
) -> Result<Option<u32>, String> {
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
