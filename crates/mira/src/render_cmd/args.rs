//! `mira render`'s arguments and what they turn into: the options a farm passes on, frame
//! ranges and numbered file names, the acceleration structure, the engine and the shading
//! options they ask for.

use std::path::{Path, PathBuf};

use render::accel::Backend;
use render::EngineKind;

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
    pub(super) scene: PathBuf,
    /// Write this image instead of the scene's outputs (format from the extension: .exr
    /// linear with every frame buffer; .png, .jpg, .tif tone mapped; .hdr linear).
    #[arg(short, long, value_name = "FILE")]
    pub(super) output: Option<PathBuf>,
    #[command(flatten)]
    pub(super) options: RenderOptions,
    /// Stop after this many seconds.
    #[arg(long, value_name = "SECONDS")]
    pub(super) time: Option<f64>,
    /// Which `render` statement of the file (1 = the first).
    #[arg(long, default_value_t = 1)]
    pub(super) frame: usize,
    /// Render the `render` statements A to B (inclusive, 1 = the first) one after the
    /// other; file names get the frame number (`out.0003.exr`).
    #[arg(long, value_name = "A..B", conflicts_with = "frame")]
    pub(super) frames: Option<String>,
    /// Render only part K of N of the image and write it as a partial EXR (-o, else
    /// SCENE.partK-of-N.exr) for `mira merge`.
    #[arg(long, value_name = "K/N")]
    pub(super) part: Option<String>,
    /// Read the classic engine's pre-passes (photon maps, final gather points) from this
    /// file, written by `mira prepass` for the same scene and settings, instead of
    /// computing them.
    #[arg(long, value_name = "FILE")]
    pub(super) prepass: Option<PathBuf>,
    /// Render the image in strips of N rows (a multiple of 64), each written to the EXR as
    /// it finishes, so that memory holds one strip (done by itself when the whole image
    /// needs more than --max-memory).
    #[arg(long, value_name = "N")]
    pub(super) strip_rows: Option<u32>,
    /// Print rays, samples per second, Mrays/s, memory and timings.
    #[arg(long)]
    pub(super) stats: bool,
    /// Print warnings.
    #[arg(short = 'W', long)]
    pub(super) warnings: bool,
    /// Write the image rendered so far after a pass once this many seconds have passed
    /// since the render started or the last preview (0: no previews; none with --part).
    #[arg(long, value_name = "SECONDS", default_value_t = DEFAULT_PREVIEW_SECONDS)]
    pub(super) preview: f64,
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
