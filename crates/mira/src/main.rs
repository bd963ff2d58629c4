//! `mira`: render mental ray and Iray `.mi` scenes.

mod check;
mod farm_cmd;
mod heap;
mod limits;
mod merge_cmd;
mod output;
mod part_file;
mod prepass_cmd;
mod render_cmd;
mod render_stats;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Render mental ray and Iray `.mi` scenes.
#[derive(Parser)]
#[command(name = "mira", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Read .mi files (following $include) and report problems and a summary of each.
    ///
    /// Exit status 0 when no file has errors, 1 otherwise.
    Check(check::CheckArgs),
    /// Render a scene.
    ///
    /// Writes the images the scene's camera asks for (or -o FILE), rendered by progressive
    /// path tracing. Ctrl-C (or SIGTERM) stops early and still writes the image rendered so
    /// far. With --part K/N, renders one part of the image for `mira merge`.
    Render(render_cmd::RenderArgs),
    /// Merge the parts of an image rendered with `mira render --part K/N`.
    ///
    /// Checks that the parts belong together (same scene text, settings and frame; every
    /// part once; none stopped early unless --allow-partial) and writes the image, bit for
    /// bit what one `mira render` with the same settings writes.
    Merge(merge_cmd::MergeArgs),
    /// Compute a classic scene's pre-passes (photon maps, final gather points) once.
    ///
    /// Writes them to a file that `mira render --part K/N --prepass FILE` reads instead of
    /// computing them in every part; the image stays bit for bit the same.
    Prepass(prepass_cmd::PrepassArgs),
    /// Render on a cluster scheduler: one task per part (and frame), then a merge.
    Farm(farm_cmd::FarmArgs),
}

/// Include-path options shared by every command that reads scenes.
#[derive(clap::Args, Clone, Debug)]
pub struct IncludeArgs {
    /// Directory to search for $include files (repeatable; searched in order, before the
    /// directories of the MI_INCLUDE_PATH environment variable).
    #[arg(short = 'I', long = "include", value_name = "DIR")]
    pub include: Vec<PathBuf>,
    /// Directory to search for MDL modules (repeatable; after the scene's own directory,
    /// before the directories of the MDL_PATHS environment variable).
    #[arg(short = 'M', long = "mdl-path", value_name = "DIR")]
    pub mdl_paths: Vec<PathBuf>,
}

impl IncludeArgs {
    /// The read options these arguments ask for.
    pub fn read_options(&self) -> mi::ReadOptions {
        mi::ReadOptions { include_paths: self.include.clone(), ..mi::ReadOptions::default() }.with_env_include_path()
    }
}

fn main() -> ExitCode {
    heap::fix_mmap_threshold();
    let cli = Cli::parse();
    match cli.command {
        Command::Check(args) => check::run(&args),
        Command::Render(args) => render_cmd::run(&args),
        Command::Merge(args) => merge_cmd::run(&args),
        Command::Prepass(args) => prepass_cmd::run(&args),
        Command::Farm(args) => farm_cmd::run(&args),
    }
}
