//! Stage 6 of `mira render`: writing what was rendered — the images of the scene's
//! outputs (after the camera's output shaders), a farm part's partial EXR, previews while
//! rendering.

use std::process::ExitCode;

use render::part::Part;
use render::tonemap::ToneMapper;

use super::settings_keys::settings_text;
use super::{frame_path, FrameJob};
use crate::output;

/// Writes part `p` of the frame `job` (`film`, rendered with `stats`) as a partial EXR
/// for `mira merge` (-o, else SCENE.partK-of-N.exr). Returns whether writing failed (an
/// error when the file name is not an EXR file's).
pub(super) fn write_part(
    job: &FrameJob,
    film: &render::film::Film,
    stats: &render::Stats,
    p: Part,
) -> Result<bool, ExitCode> {
    let err = |msg: String| {
        eprintln!("mira: error: {msg}");
        ExitCode::FAILURE
    };
    let FrameJob { args, settings, engine, classic, numbered, frame, backend, content_hash, inputs_hash, .. } = *job;
    let opts = &args.options;
    let mut failed = false;
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
        include: opts.include.include.iter().map(|d| std::path::absolute(d).unwrap_or_else(|_| d.clone())).collect(),
        scene_hash: content_hash,
        inputs_hash,
        settings: settings_text(settings, (film.width, film.height), backend, opts.fg_rays),
        settings_hash: render::pipeline::Fnv::of(
            settings_text(settings, (film.width, film.height), backend, opts.fg_rays).as_bytes(),
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
    match crate::part_file::write(film, &info, &path) {
        Ok(()) => {
            eprintln!("mira: wrote part {p} to {}{}", path.display(), if stats.cancelled { " (partial)" } else { "" })
        }
        Err(e) => {
            eprintln!("mira: error: cannot write {}: {e}", path.display());
            failed = true;
        }
    }
    Ok(failed)
}

/// Runs the camera's output shaders on the whole image `film`, then writes it to every
/// target (-o, else the camera's file outputs and file frame buffers, else SCENE.exr;
/// numbered per frame with --frames). Returns whether some image could not be written.
pub(super) fn write_images(
    film: &mut render::film::Film,
    targets: &[output::Target],
    tone: &ToneMapper,
    sc: &scene::Scene,
) -> bool {
    let mut failed = false;
    // The camera's output shaders (Maya's glow) on the whole image.
    for w in render::output_shaders::run(film, &sc.camera, &sc.library) {
        eprintln!("mira: warning: {w}");
    }
    // Outputs: -o, else the camera's file outputs and file frame buffers, else
    // SCENE.exr; numbered per frame with --frames.
    for target in targets {
        match output::write(film, target, tone) {
            Ok(()) => eprintln!("mira: wrote {}", target.path.display()),
            Err(e) => {
                eprintln!("mira: error: cannot write {}: {e}", target.path.display());
                failed = true;
            }
        }
    }
    failed
}

/// Writes the image rendered so far (`samples` per pixel) to every target, each through a
/// hidden file beside it renamed into place, so that a viewer never reads half a file;
/// returns the line to show. A preview that cannot be written is reported, not fatal.
pub(super) fn write_preview(
    film: &render::film::Film,
    targets: &[output::Target],
    tone: &ToneMapper,
    samples: u32,
) -> String {
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
