//! Rendering in parts and merging: `mira render --part K/N` then `mira merge` writes the
//! same file, byte for byte (so every channel bit for bit), as one `mira render`; and merge
//! refuses sets of parts that do not make one image, naming the culprit.

use std::path::{Path, PathBuf};
use std::process::Command;

fn mira(args: &[&str]) -> (i32, String) {
    let out =
        Command::new(env!("CARGO_BIN_EXE_mira")).args(args).current_dir(env!("CARGO_MANIFEST_DIR")).output().unwrap();
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mira-farm-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Removes the temporary folders of `tags`.
fn clean(tags: &[&str]) {
    for tag in tags {
        std::fs::remove_dir_all(temp_dir(tag)).ok();
    }
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Renders `scene` in one process (2 threads) and as `n` parts (0 = all cores, 1 or 2
/// threads) with `options`, merges the parts, and asserts both images are the same bytes.
/// Returns the part files.
fn assert_merge_identical(tag: &str, scene: &Path, n: u32, options: &[&str], ext: &str) -> Vec<PathBuf> {
    let dir = temp_dir(tag);
    let one = dir.join(format!("one.{ext}"));
    let merged = dir.join(format!("merged.{ext}"));
    let mut args = vec!["render", s(scene), "-o", s(&one), "--threads", "2"];
    args.extend(options);
    let (code, err) = mira(&args);
    assert_eq!(code, 0, "{err}");
    let mut parts = Vec::new();
    for k in 1..=n {
        let part = dir.join(format!("part{k}.exr"));
        let spec = format!("{k}/{n}");
        // Parts run with other thread counts than the one-process render.
        let threads = (k % 3).to_string();
        let mut args = vec!["render", s(scene), "--part", &spec, "-o", s(&part)];
        args.extend(options);
        args.extend(["--threads", &threads]);
        let (code, err) = mira(&args);
        assert_eq!(code, 0, "part {spec}: {err}");
        parts.push(part);
    }
    // Any order of the parts.
    let mut args = vec!["merge", "-o", s(&merged)];
    args.extend(parts.iter().rev().map(|p| s(p)));
    let (code, err) = mira(&args);
    assert_eq!(code, 0, "{err}");
    let (a, b) = (std::fs::read(&one).unwrap(), std::fs::read(&merged).unwrap());
    assert!(a == b, "{tag}: the merged {ext} differs from the one-process render ({} vs {} bytes)", a.len(), b.len());
    parts
}

/// The Cornell box (path engine) in 4 parts at 80 × 70 (four EXR tiles), 4 spp: EXR (every
/// buffer) and PNG.
#[test]
fn path_engine_parts_merge_bit_identically() {
    let scene = Path::new("../../scenes/iray_cornell_box.mi");
    let options = ["--resolution", "80", "70", "--spp", "4"];
    assert_merge_identical("path4", scene, 4, &options, "exr");
    // An uneven split (70 rows in 8 parts) and a tone-mapped output.
    assert_merge_identical("path8", scene, 8, &options, "png");
    clean(&["path4", "path8"]);
}

/// A classic scene with adaptive sampling (samples 0 2, contrast 0.02), a Gaussian filter
/// of radius 2 (samples splat into neighbouring rows), a moving object (motion buffer) and a
/// user frame buffer, in 3 parts.
#[test]
fn classic_adaptive_parts_merge_bit_identically() {
    let dir = temp_dir("classic-scene");
    let scene = dir.join("adaptive.mi");
    std::fs::write(
        &scene,
        r#"
options "opt" samples 0 2 contrast 0.02 0.02 0.02 1 filter gauss 2 2 shutter 0 1 end options
light "l" "mib_light_point" ("color" 3 3 3) origin 0 3 2 end light
instance "l_inst" "l" end instance
camera "cam" focal 1 aperture 1 aspect 1.3333 resolution 32 24
    output "+rgba,m" "exr" "unused.exr"
    framebuffer "extra" datatype "rgba" user true
end camera
instance "cam_inst" "cam" end instance
material "m" "mib_illum_phong" ("ambience" 0.1 0.1 0.1, "diffuse" 0.7 0.5 0.3, "specular" 0.5 0.5 0.5,
    "exponent" 30, "lights" ["l_inst"]) end material
object "quad" group
    -1 -1 -4  1 -1 -4  1 1 -4  -1 1 -4  -3 -1 -6  3 -1 -6  3 -1 -2  -3 -1 -2
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7
    c "m" 0 1 2 3
    c "m" 4 5 6 7
end group end object
instance "quad_inst" "quad" motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -0.2 0.1 0 1 end instance
instgroup "root" "cam_inst" "quad_inst" "l_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
    )
    .unwrap();
    let parts = assert_merge_identical("classic3", &scene, 3, &["--engine", "classic"], "exr");
    // The adaptive sampler did vary the sample counts (1 to 16 per pixel, samples 0 2).
    let image = exr::prelude::read_all_flat_layers_from_file(&parts[1]).unwrap();
    let samples = image.layer_data[0].channel_data.list.iter().find(|c| c.name.to_string() == "samples").unwrap();
    let counts: Vec<f32> = samples.sample_data.values_as_f32().collect();
    let (lo, hi) = counts.iter().fold((f32::MAX, 0f32), |(lo, hi), &c| (lo.min(c), hi.max(c)));
    assert!(lo == 1.0 && hi == 16.0, "sample counts {lo} to {hi}");
    let (_, err) = mira(&["merge", "-o", s(&dir.join("x.exr")), s(&parts[0])]);
    assert!(err.contains("part 2/3 is missing") && err.contains("part 3/3 is missing"), "{err}");
    clean(&["classic-scene", "classic3"]);
}

/// Merge refuses a missing part, a part of another scene, a part given twice and a partial
/// part (unless --allow-partial), naming each.
#[test]
fn merge_refuses_parts_that_do_not_belong_together() {
    let dir = temp_dir("refuse");
    let (a, b) = (dir.join("a.mi"), dir.join("b.mi"));
    let text = std::fs::read_to_string("../../scenes/iray_cornell_box.mi").unwrap();
    std::fs::write(&a, &text).unwrap();
    std::fs::write(&b, text + "\n# another scene\n").unwrap();
    let opts = ["--resolution", "16", "12", "--spp", "1"];
    let part = |scene: &Path, k: u32, name: &str| {
        let out = dir.join(name);
        let spec = format!("{k}/3");
        let mut args = vec!["render", s(scene), "--part", &spec, "-o", s(&out)];
        args.extend(opts);
        let (code, err) = mira(&args);
        assert_eq!(code, 0, "{err}");
        out
    };
    let (p1, p2, p3) = (part(&a, 1, "p1.exr"), part(&a, 2, "p2.exr"), part(&a, 3, "p3.exr"));
    let foreign = part(&b, 3, "foreign.exr");
    let out = dir.join("out.exr");
    let merge = |parts: &[&PathBuf]| {
        let mut args = vec!["merge", "-o", s(&out)];
        args.extend(parts.iter().map(|p| s(p)));
        mira(&args)
    };
    let (code, err) = merge(&[&p1, &p3]);
    assert_eq!(code, 1);
    assert!(err.contains("part 2/3 is missing"), "{err}");
    let (code, err) = merge(&[&p1, &p2, &foreign]);
    assert_eq!(code, 1);
    assert!(err.contains("foreign.exr belongs to another scene"), "{err}");
    assert!(err.contains("part 3/3 is missing"), "{err}");
    let (code, err) = merge(&[&p1, &p2, &p2, &p3]);
    assert_eq!(code, 1);
    assert!(err.contains("part 2/3 is given twice"), "{err}");
    assert!(!out.exists(), "nothing is written when parts are refused");
    // Another seed is another set of settings.
    let other = dir.join("seed.exr");
    let mut args = vec!["render", s(&a), "--part", "2/3", "--seed", "7", "-o", s(&other)];
    args.extend(opts);
    assert_eq!(mira(&args).0, 0);
    let (code, err) = merge(&[&p1, &other, &p3]);
    assert_eq!(code, 1);
    assert!(err.contains("seed.exr was rendered with other settings (seed=7)"), "{err}");
    let (code, err) = merge(&[&p1, &p2, &p3]);
    assert_eq!(code, 0, "{err}");
    clean(&["refuse"]);
}

/// SIGTERM (a scheduler's time limit) makes a part write what it rendered, marked partial;
/// merge refuses it unless --allow-partial.
#[cfg(unix)]
#[test]
fn a_terminated_part_is_written_partial_and_refused() {
    let dir = temp_dir("sigterm");
    let part = dir.join("p1.exr");
    // Enough samples that the render is still running when the signal comes.
    let mut child = Command::new(env!("CARGO_BIN_EXE_mira"))
        .args(["render", "../../scenes/iray_cornell_box.mi", "--resolution", "64", "48", "--spp", "100000"])
        .args(["--part", "1/2", "-o", s(&part), "--threads", "1"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let killed = Command::new("kill").args(["-TERM", &child.id().to_string()]).status().unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "an interrupted render exits with 130");
    assert!(part.exists(), "the part is written on SIGTERM");
    let mut args = vec!["render", "../../scenes/iray_cornell_box.mi", "--resolution", "64", "48", "--spp", "100000"];
    let p2 = dir.join("p2.exr");
    args.extend(["--part", "2/2", "--time", "0.5", "-o", s(&p2)]);
    let (code, err) = mira(&args);
    assert_eq!(code, 1, "a part cannot stop on a time limit");
    assert!(err.contains("cannot render part 2/2"), "{err}");
    let (code, err) = mira(&["merge", "-o", s(&dir.join("m.exr")), s(&part)]);
    assert_eq!(code, 1);
    assert!(err.contains("p1.exr is partial"), "{err}");
    assert!(err.contains("part 2/2 is missing"), "{err}");
    clean(&["sigterm"]);
}

/// `--frames A..B` renders each render statement to its own numbered file; a frame the file
/// does not have is an error naming it.
#[test]
fn frames_render_each_render_statement() {
    let dir = temp_dir("frames");
    let scene = dir.join("two.mi");
    let text = std::fs::read_to_string("../../scenes/iray_cornell_box.mi").unwrap();
    let render = text.lines().rev().find(|l| l.starts_with("render ")).unwrap().to_string();
    std::fs::write(&scene, format!("{text}\n{render}\n")).unwrap();
    let out = dir.join("f.exr");
    let (code, err) =
        mira(&["render", s(&scene), "--frames", "1..2", "--resolution", "8", "6", "--spp", "1", "-o", s(&out)]);
    assert_eq!(code, 0, "{err}");
    assert!(dir.join("f.0001.exr").exists() && dir.join("f.0002.exr").exists(), "{err}");
    let (code, err) =
        mira(&["render", s(&scene), "--frames", "2..3", "--resolution", "8", "6", "--spp", "1", "-o", s(&out)]);
    assert_eq!(code, 1);
    assert!(err.contains("no render statement number 3"), "{err}");
    let (code, err) = mira(&["render", s(&scene), "--frames", "3..2"]);
    assert_eq!(code, 1);
    assert!(err.contains("'3..2' is not a frame range"), "{err}");
    clean(&["frames"]);
}

/// `mira farm slurm` without --submit writes and prints a job array of parts × frames and a
/// merge job per frame that names every part file.
#[test]
fn farm_slurm_writes_a_job_array_and_a_merge_job() {
    let dir = temp_dir("slurm");
    let out = dir.join("anim.png");
    let out_s = out.to_str().unwrap().to_string();
    let args = ["farm", "slurm", "../../scenes/iray_cornell_box.mi", "-o", &out_s, "--parts", "3"];
    let output = Command::new(env!("CARGO_BIN_EXE_mira"))
        .args(args)
        .args(["--frames", "2..3", "--spp", "8", "--partition", "render", "--time", "30:00"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let farm = dir.join("anim.png.farm");
    let render = std::fs::read_to_string(farm.join("render.sbatch")).unwrap();
    let merge = std::fs::read_to_string(farm.join("merge.sbatch")).unwrap();
    for line in ["#SBATCH --array=0-5", "#SBATCH --partition=render", "#SBATCH --time=30:00", "#SBATCH --requeue"] {
        assert!(render.contains(line), "{line}: {render}");
    }
    assert!(render.contains("frame=$(( 2 + task / 3 ))") && render.contains("--part \"$part/3\""), "{render}");
    assert!(render.contains("--spp 8") && render.contains("scontrol requeue"), "{render}");
    assert!(render.contains("logs/render-%A_%a.log"), "one log per task: {render}");
    for frame in ["0002", "0003"] {
        let parts: Vec<String> =
            (1..=3).map(|k| farm.join(format!("part-{frame}-{k}-of-3.exr")).display().to_string()).collect();
        let want = format!("merge {} -o {}", parts.join(" "), dir.join(format!("anim.{frame}.png")).display());
        assert!(merge.contains(&want), "{want}\n{merge}");
    }
    let printed = String::from_utf8_lossy(&output.stdout);
    assert!(printed.contains("--dependency=afterok:$id"), "{printed}");
    clean(&["slurm"]);
}
