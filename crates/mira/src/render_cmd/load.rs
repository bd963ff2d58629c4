//! Stage 1 for the commands: the scene loaded at a render statement, its messages shown.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::IncludeArgs;

/// A scene loaded for rendering or merging.
pub struct LoadedScene {
    /// The parsed file (its sources, for messages).
    pub parsed: mi::Parsed,
    /// The scene at the chosen render statement, resolution applied.
    pub scene: scene::Scene,
    /// Hash of the scene's text (0 when loaded without it: `hash` false).
    pub content_hash: u64,
    /// How long parsing and building the scene took.
    pub times: render::pipeline::LoadTimes,
}

/// Stage 1 for the commands: loads `path` at `frame` (1 = the first render statement),
/// prints its errors (and warnings when asked), applies `resolution`; hashes the scene's
/// text when `hash` says so (for part and pre-pass files).
pub fn load_scene(
    path: &Path,
    include: &[PathBuf],
    frame: usize,
    resolution: Option<(u32, u32)>,
    warnings: bool,
    hash: bool,
) -> Result<LoadedScene, String> {
    let options = IncludeArgs { include: include.to_vec(), mdl_paths: Vec::new() }.read_options();
    let frame = frame.saturating_sub(1);
    let loaded = if hash {
        render::pipeline::load(path, &options, frame)?
    } else {
        render::pipeline::load_unhashed(path, &options, frame)?
    };
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
    let content_hash = loaded.content_hash().unwrap_or(0);
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

/// Reads the source text freed after parsing again, for messages that quote it.
pub(super) fn restore_sources(sources: &mut mi::SourceMap) {
    if let Err(e) = sources.restore_text() {
        eprintln!("mira: warning: {e}");
    }
}
