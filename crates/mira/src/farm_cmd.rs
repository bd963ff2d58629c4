//! `mira farm slurm`: render a scene on a Slurm cluster — for a classic scene with
//! pre-passes, a job array of `mira prepass` tasks (one per frame); a job array of `mira
//! render --part` tasks (one per part and frame) after it; and a merge job that runs after
//! all of them succeeded (`--dependency=afterok`). The parts, logs and scripts go to a folder that every
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

/// The sbatch scripts: the pre-pass array (when the scene has pre-passes), the render array
/// and the merge job.
pub struct Scripts {
    /// The pre-pass job array, one task per frame: `mira prepass` writes the photon maps
    /// and final gather points every part of the frame reads.
    pub prepass: Option<String>,
    /// The job array: task i renders part `i mod N + 1` of frame `A + i / N`.
    pub render: String,
    /// The merge job: one `mira merge` per frame.
    pub merge: String,
    /// Tasks in the array.
    pub tasks: u32,
}

/// The lines of a task script that requeue it once when it failed (`status`).
const REQUEUE_ONCE: &str = "status=$?\nif [ \"$status\" -ne 0 ]; then
    # A failed task is requeued once (Slurm counts restarts in SLURM_RESTART_COUNT).
    if [ \"${SLURM_RESTART_COUNT:-0}\" -lt 1 ]; then
        echo \"mira farm: task $task failed ($status); requeueing it once\" >&2
        scontrol requeue \"${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}\"
    fi
    exit \"$status\"
fi
";

/// Writes the scripts for `args` with the mira binary `mira` and the farm folder `dir`;
/// `with_prepass`: the scene's classic pre-passes are computed once per frame by a job
/// before the parts.
pub fn scripts(args: &SlurmArgs, mira: &Path, dir: &Path, with_prepass: bool) -> Result<Scripts, String> {
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
    let prepass = with_prepass.then(|| {
        let mut p = head.clone();
        p += "#SBATCH --job-name=mira-prepass\n";
        p += &format!("#SBATCH --array=0-{}\n", frames - 1);
        p += &format!("#SBATCH --output={}/prepass-%A_%a.log\n", q(&logs));
        p += "#SBATCH --requeue\n#SBATCH --open-mode=append\n";
        if let Some(t) = &args.time {
            p += &format!("#SBATCH --time={}\n", quote(t));
        }
        p += &format!("# mira farm slurm: the pre-passes of {frames} frame(s) of {}\nset -u\n", args.scene.display());
        p += &format!("task=$SLURM_ARRAY_TASK_ID\nframe=$(( {a} + task ))\n");
        p += &format!("out={}/prepass-$(printf %04d \"$frame\").bin\n", q(dir));
        p += &format!(
            "{} prepass {} --frame \"$frame\" -o \"$out\" {}\n",
            q(mira),
            q(&abs(&args.scene)),
            options.join(" ")
        );
        p + REQUEUE_ONCE
    });
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
    let read_prepass = if with_prepass {
        format!(" --prepass {}/prepass-$(printf %04d \"$frame\").bin", q(dir))
    } else {
        String::new()
    };
    render += &format!(
        "{} render {} --frame \"$frame\" --part \"$part/{n}\"{read_prepass} -o \"$out\" {}\n",
        q(mira),
        q(&abs(&args.scene)),
        options.join(" ")
    );
    render += REQUEUE_ONCE;
    let mut merge = head;
    merge += "#SBATCH --job-name=mira-merge\n";
    merge += &format!("#SBATCH --output={}/merge-%j.log\n", q(&logs));
    merge += "set -eu\n";
    for frame in a..=b {
        let parts: Vec<String> = (1..=n).map(|k| q(&part_path(dir, frame, k, n))).collect();
        let out = if args.frames.is_some() { frame_path(&abs(&args.output), frame) } else { abs(&args.output) };
        merge += &format!("{} merge {} -o {}\n", q(mira), parts.join(" "), q(&out));
    }
    Ok(Scripts { prepass, render, merge, tasks })
}

/// Whether the farm render of `args` gets a pre-pass job: when its first frame renders
/// with the classic engine and has pre-passes (photon maps, cached final gathering).
fn needs_prepass(args: &SlurmArgs) -> Result<bool, String> {
    let first = match &args.frames {
        Some(f) => parse_frames(f)?.0,
        None => 1,
    };
    let o = &args.options;
    let resolution = o.resolution.as_ref().map(|r| (r[0], r[1]));
    let loaded = crate::render_cmd::load_scene(&args.scene, &o.include.include, first, resolution, false, false)?;
    let engine = render::pipeline::choose_engine(&loaded.scene, crate::render_cmd::asked_engine(o.engine));
    Ok(engine == render::EngineKind::Classic && render::prepass_file::scene_has_prepass(&loaded.scene.options))
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
    // A scene that cannot be read here gets no pre-pass job; its tasks report why.
    let with_prepass = needs_prepass(args).unwrap_or_else(|e| {
        eprintln!("mira: warning: {e}; no pre-pass job");
        false
    });
    let s = match scripts(args, &mira, &dir, with_prepass) {
        Ok(s) => s,
        Err(e) => return err(e),
    };
    if let Err(e) = std::fs::create_dir_all(dir.join("logs")) {
        return err(format!("cannot make {}: {e}", dir.display()));
    }
    let (render_path, merge_path) = (dir.join("render.sbatch"), dir.join("merge.sbatch"));
    let prepass_path = dir.join("prepass.sbatch");
    let mut files = vec![(&render_path, &s.render), (&merge_path, &s.merge)];
    if let Some(p) = &s.prepass {
        files.insert(0, (&prepass_path, p));
    }
    for (path, text) in &files {
        if let Err(e) = std::fs::write(path, text) {
            return err(format!("cannot write {}: {e}", path.display()));
        }
    }
    if !(args.submit || args.wait) {
        for (path, text) in &files {
            println!("# {}\n{}", path.display(), text);
        }
        let first = match &s.prepass {
            Some(_) => format!(
                "pre=$(sbatch --parsable {}) && id=$(sbatch --parsable --dependency=afterok:$pre --kill-on-invalid-dep=yes {})",
                prepass_path.display(),
                render_path.display()
            ),
            None => format!("id=$(sbatch --parsable {})", render_path.display()),
        };
        println!(
            "# submit with:\n# {first} && sbatch --dependency=afterok:$id --kill-on-invalid-dep=yes {}",
            merge_path.display()
        );
        return ExitCode::SUCCESS;
    }
    let mut render_args = Vec::new();
    if s.prepass.is_some() {
        let prepass_id = match sbatch(&[], &prepass_path) {
            Ok(id) => id,
            Err(e) => return err(e),
        };
        eprintln!("mira: submitted pre-pass job {prepass_id}; logs in {}", dir.join("logs").display());
        render_args = vec![format!("--dependency=afterok:{prepass_id}"), "--kill-on-invalid-dep=yes".to_string()];
    }
    let render_id = match sbatch(&render_args, &render_path) {
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
