//! `mira farm slurm`: render a scene on a Slurm cluster — a job array of `mira render
//! --part` tasks (one per part and frame) and a merge job that runs after all of them
//! succeeded (`--dependency=afterok`). The parts, logs and scripts go to a folder that every
//! node sees at the same path (a shared filesystem).

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use crate::render_cmd::{frame_path, parse_frames, RenderOptions};

/// Arguments of `mira farm`.
#[derive(clap::Args, Debug)]
pub struct FarmArgs {
    #[command(subcommand)]
    scheduler: Scheduler,
}

/// The schedulers mira submits to.
#[derive(clap::Subcommand, Debug)]
enum Scheduler {
    /// Slurm: write (and submit) an sbatch job array and a merge job.
    Slurm(SlurmArgs),
}

/// Arguments of `mira farm slurm`.
#[derive(clap::Args, Debug)]
pub struct SlurmArgs {
    /// The scene to render (on a filesystem every node shares).
    #[arg(value_name = "SCENE")]
    scene: PathBuf,
    /// The merged image (format from the extension); with --frames, one per frame
    /// (`out.0003.exr`).
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Parts per frame (one task each).
    #[arg(long, default_value_t = 1)]
    parts: u32,
    /// Render statements A to B (inclusive, 1 = the first); default: the first.
    #[arg(long, value_name = "A..B")]
    frames: Option<String>,
    /// Slurm partition.
    #[arg(long)]
    partition: Option<String>,
    /// Slurm time limit of each task (e.g. 30:00); at the limit Slurm sends SIGTERM and the
    /// task writes its part marked partial.
    #[arg(long, value_name = "T")]
    time: Option<String>,
    /// CPUs per task (Slurm's --cpus-per-task).
    #[arg(long, value_name = "N")]
    cpus: Option<u32>,
    /// Folder for the scripts, parts and logs (default: OUT.farm next to the output).
    #[arg(long, value_name = "DIR")]
    dir: Option<PathBuf>,
    /// Submit with sbatch (else print the scripts).
    #[arg(long)]
    submit: bool,
    /// Wait for the merge job and exit with its status (implies --submit).
    #[arg(long)]
    wait: bool,
    #[command(flatten)]
    options: RenderOptions,
}

/// Quotes `s` for a POSIX shell.
fn quote(s: &str) -> String {
    if !s.is_empty() && s.bytes().all(|b| b.is_ascii_alphanumeric() || b"/._-+=:,".contains(&b)) {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', r"'\''"))
    }
}

fn abs(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

/// The part file of part `k` (from 1) of `frame` in `dir`.
pub fn part_path(dir: &Path, frame: usize, k: u32, n: u32) -> PathBuf {
    dir.join(format!("part-{frame:04}-{k}-of-{n}.exr"))
}

/// The two sbatch scripts: the render array and the merge job.
pub struct Scripts {
    /// The job array: task i renders part `i mod N + 1` of frame `A + i / N`.
    pub render: String,
    /// The merge job: one `mira merge` per frame.
    pub merge: String,
    /// Tasks in the array.
    pub tasks: u32,
}

/// Writes the scripts for `args` with the mira binary `mira` and the farm folder `dir`.
pub fn scripts(args: &SlurmArgs, mira: &Path, dir: &Path) -> Result<Scripts, String> {
    let (a, b) = match &args.frames {
        Some(f) => parse_frames(f)?,
        None => (1, 1),
    };
    let n = args.parts;
    if n == 0 {
        return Err("--parts must be at least 1".into());
    }
    let frames = (b - a + 1) as u32;
    let tasks = frames.checked_mul(n).ok_or("too many tasks")?;
    let q = |p: &Path| quote(&p.display().to_string());
    let logs = dir.join("logs");
    let mut head = String::from("#!/bin/bash\n");
    if let Some(p) = &args.partition {
        head += &format!("#SBATCH --partition={}\n", quote(p));
    }
    if let Some(c) = args.cpus {
        head += &format!("#SBATCH --cpus-per-task={c}\n");
    }
    let options: Vec<String> = args.options.to_args().iter().map(|s| quote(s)).collect();
    let mut render = head.clone();
    render += "#SBATCH --job-name=mira-render\n";
    render += &format!("#SBATCH --array=0-{}\n", tasks - 1);
    render += &format!("#SBATCH --output={}/render-%A_%a.log\n", q(&logs));
    render += "#SBATCH --requeue\n";
    // A requeued task appends to its log: both attempts stay readable.
    render += "#SBATCH --open-mode=append\n";
    if let Some(t) = &args.time {
        render += &format!("#SBATCH --time={}\n", quote(t));
        // Slurm sends SIGTERM at the limit; mira writes its part, marked partial.
    }
    render += &format!(
        "# mira farm slurm: {tasks} tasks, {n} part(s) x {frames} frame(s) of {}\nset -u\n",
        args.scene.display()
    );
    render += &format!("task=$SLURM_ARRAY_TASK_ID\nframe=$(( {a} + task / {n} ))\npart=$(( task % {n} + 1 ))\n");
    render += &format!("out={}/part-$(printf %04d \"$frame\")-$part-of-{n}.exr\n", q(dir));
    render += &format!(
        "{} render {} --frame \"$frame\" --part \"$part/{n}\" -o \"$out\" {}\nstatus=$?\nif [ \"$status\" -ne 0 ]; then\n",
        q(mira),
        q(&abs(&args.scene)),
        options.join(" ")
    );
    render += "    # A failed task is requeued once (Slurm counts restarts in SLURM_RESTART_COUNT).\n";
    render += "    if [ \"${SLURM_RESTART_COUNT:-0}\" -lt 1 ]; then\n";
    render += "        echo \"mira farm: task $task failed ($status); requeueing it once\" >&2\n";
    render += "        scontrol requeue \"${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}\"\n";
    render += "    fi\n    exit \"$status\"\nfi\n";
    let mut merge = head;
    merge += "#SBATCH --job-name=mira-merge\n";
    merge += &format!("#SBATCH --output={}/merge-%j.log\n", q(&logs));
    merge += "set -eu\n";
    for frame in a..=b {
        let parts: Vec<String> = (1..=n).map(|k| q(&part_path(dir, frame, k, n))).collect();
        let out = if args.frames.is_some() { frame_path(&abs(&args.output), frame) } else { abs(&args.output) };
        merge += &format!("{} merge {} -o {}\n", q(mira), parts.join(" "), q(&out));
    }
    Ok(Scripts { render, merge, tasks })
}

/// Runs `sbatch ARGS SCRIPT` and returns the job id.
fn sbatch(args: &[String], script: &Path) -> Result<String, String> {
    let out = Command::new("sbatch")
        .arg("--parsable")
        .args(args)
        .arg(script)
        .output()
        .map_err(|e| format!("cannot run sbatch: {e} (is Slurm's client installed?)"))?;
    if !out.status.success() {
        return Err(format!("sbatch failed: {}", String::from_utf8_lossy(&out.stderr).trim()));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    // `--parsable` prints `id` or `id;cluster`.
    Ok(text.trim().split(';').next().unwrap_or_default().to_string())
}

/// Runs the command.
pub fn run(args: &FarmArgs) -> ExitCode {
    let Scheduler::Slurm(args) = &args.scheduler;
    let err = |msg: String| {
        eprintln!("mira: error: {msg}");
        ExitCode::FAILURE
    };
    let mira = match std::env::current_exe() {
        Ok(p) => p,
        Err(e) => return err(format!("cannot find the mira binary: {e}")),
    };
    let dir = abs(&args.dir.clone().unwrap_or_else(|| {
        let mut name = args.output.file_name().unwrap_or_default().to_os_string();
        name.push(".farm");
        args.output.with_file_name(name)
    }));
    let s = match scripts(args, &mira, &dir) {
        Ok(s) => s,
        Err(e) => return err(e),
    };
    if let Err(e) = std::fs::create_dir_all(dir.join("logs")) {
        return err(format!("cannot make {}: {e}", dir.display()));
    }
    let (render_path, merge_path) = (dir.join("render.sbatch"), dir.join("merge.sbatch"));
    for (path, text) in [(&render_path, &s.render), (&merge_path, &s.merge)] {
        if let Err(e) = std::fs::write(path, text) {
            return err(format!("cannot write {}: {e}", path.display()));
        }
    }
    if !(args.submit || args.wait) {
        println!("# {}\n{}", render_path.display(), s.render);
        println!("# {}\n{}", merge_path.display(), s.merge);
        println!(
            "# submit with:\n# id=$(sbatch --parsable {}) && sbatch --dependency=afterok:$id --kill-on-invalid-dep=yes {}",
            render_path.display(),
            merge_path.display()
        );
        return ExitCode::SUCCESS;
    }
    let render_id = match sbatch(&[], &render_path) {
        Ok(id) => id,
        Err(e) => return err(e),
    };
    eprintln!(
        "mira: submitted render job array {render_id} ({} tasks); logs in {}",
        s.tasks,
        dir.join("logs").display()
    );
    let mut merge_args = vec![format!("--dependency=afterok:{render_id}"), "--kill-on-invalid-dep=yes".to_string()];
    if args.wait {
        // sbatch --wait returns when the job ends, with its exit status.
        merge_args.push("--wait".into());
    }
    match sbatch(&merge_args, &merge_path) {
        Ok(id) if args.wait => {
            eprintln!("mira: merge job {id} done: {}", args.output.display());
            ExitCode::SUCCESS
        }
        Ok(id) => {
            eprintln!("mira: submitted merge job {id}, after {render_id}");
            ExitCode::SUCCESS
        }
        Err(e) => err(format!("{e} (logs in {})", dir.join("logs").display())),
    }
}
