//! Rendering in strips (issue 15): an image too large for one film is rendered strip by
//! strip and written to its EXR as each strip finishes. The file must be the one a
//! one-film render writes, byte for byte, in both engines (the classic engine's halo rows
//! and band alignment make its splats and adaptive sampling come out the same).

use std::path::{Path, PathBuf};
use std::process::Command;

fn mira(args: &[&str]) -> (i32, String, String) {
    let out =
        Command::new(env!("CARGO_BIN_EXE_mira")).args(args).current_dir(env!("CARGO_MANIFEST_DIR")).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn scratch() -> PathBuf {
    let d = std::env::temp_dir().join(format!("mira-strips-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Renders `scene` with `extra` arguments once as one film and once in strips of 64 rows,
/// and asserts the two EXR files are equal byte for byte.
fn same_file_in_strips(scene: &str, name: &str, extra: &[&str]) {
    let d = scratch();
    let whole = d.join(format!("{name}-whole.exr"));
    let strips = d.join(format!("{name}-strips.exr"));
    let run = |out: &Path, more: &[&str]| {
        let mut args = vec!["render", scene, "-o", out.to_str().unwrap()];
        args.extend(extra);
        args.extend(more);
        let (code, _, err) = mira(&args);
        assert_eq!(code, 0, "{err}");
        err
    };
    run(&whole, &[]);
    let err = run(&strips, &["--strip-rows", "64"]);
    assert!(err.contains("strips of 64 rows"), "{err}");
    let (a, b) = (std::fs::read(&whole).unwrap(), std::fs::read(&strips).unwrap());
    assert!(a.len() > 1000);
    assert!(a == b, "{name}: the strips' file differs from the one-film file ({} vs {} bytes)", a.len(), b.len());
}

#[test]
fn path_engine_strips_give_the_same_file() {
    same_file_in_strips("../../scenes/iray_cornell_box.mi", "cornell", &["--resolution", "40", "150", "--spp", "2"]);
}

#[test]
fn classic_engine_strips_with_adaptive_sampling_give_the_same_file() {
    // No --spp: the options' adaptive sampling (neighbour contrast) and the filter's splats.
    same_file_in_strips("../../scenes/classic_reflections.mi", "reflections", &["--resolution", "48", "150"]);
}

/// An image whose film exceeds --max-memory is rendered in strips by itself (it was
/// refused before), and the file equals the one-film render's.
#[test]
fn too_large_for_one_film_renders_in_strips() {
    let d = scratch();
    let (whole, strips) = (d.join("auto-whole.exr"), d.join("auto-strips.exr"));
    let base = ["render", "../../scenes/iray_cornell_box.mi", "--resolution", "64", "600", "--spp", "1"];
    let mut args = base.to_vec();
    args.extend(["-o", whole.to_str().unwrap()]);
    let (code, _, err) = mira(&args);
    assert_eq!(code, 0, "{err}");
    let mut args = base.to_vec();
    args.extend(["-o", strips.to_str().unwrap(), "--max-memory", "10500K"]);
    let (code, _, err) = mira(&args);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("rendering in strips of 64 rows"), "{err}");
    assert!(std::fs::read(&whole).unwrap() == std::fs::read(&strips).unwrap());
    // Strips are written only as EXR; a PNG of that size is still refused at its statement.
    let mut args = base.to_vec();
    args.extend(["-o", "x.png", "--max-memory", "10500K"]);
    let (code, _, err) = mira(&args);
    assert_eq!(code, 1);
    assert!(err.contains("error: --resolution 64 x 600 needs"), "{err}");
    assert!(
        err.contains("cannot render in strips: an image rendered in strips is written to one OpenEXR file"),
        "{err}"
    );
}

#[test]
fn strip_rows_must_be_a_multiple_of_64() {
    let (code, _, err) = mira(&["render", "../../scenes/iray_cornell_box.mi", "--strip-rows", "100", "-o", "x.exr"]);
    assert_eq!(code, 1);
    assert!(err.contains("--strip-rows 100 is not a positive multiple of 64"), "{err}");
}

/// `check --scene` says what `render` will do: an image over the limit that strips can
/// render is a warning naming the strips, not an error.
#[test]
fn check_reports_strips_as_a_warning() {
    let d = scratch();
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/hostile/ok_baseline.mi"))
        .unwrap()
        .replace("resolution 8 8", "resolution 64 600");
    let scene = d.join("tall.mi");
    std::fs::write(&scene, text).unwrap();
    let (code, _, err) = mira(&["check", "--scene", "-W", "--max-memory", "10500K", scene.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("tall.mi:10:5: warning: resolution 64 x 600 needs 10.84 MiB of film and frame buffers, more than the limit of 10.25 MiB (--max-memory): mira render renders it in strips of 64 rows"),
        "{err}"
    );
    let (code, _, err) = mira(&["check", "--scene", "--max-memory", "1M", scene.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("tall.mi:10:5: error: resolution 64 x 600 needs"), "{err}");
}

/// `--time` with strips (refused before): the first strip stops on its share of the time,
/// every later strip at the samples per pixel the first reached, so all pixels hold the
/// same count (`--stats`: samples = spp × pixels) and the whole stops near the limit.
#[test]
fn a_time_limit_renders_every_strip_to_the_first_ones_samples() {
    let d = scratch();
    let out = d.join("timed.exr");
    let args = [
        "render",
        "../../scenes/iray_cornell_box.mi",
        "--resolution",
        "40",
        "150",
        "--spp",
        "1000000",
        "--time",
        "2",
        "--strip-rows",
        "64",
        "--threads",
        "1",
        "--stats",
        "-o",
        out.to_str().unwrap(),
    ];
    let start = std::time::Instant::now();
    let (code, stdout, err) = mira(&args);
    let secs = start.elapsed().as_secs_f64();
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("(3 strips of 64 rows)"), "{err}");
    let field = |prefix: &str, word: usize| -> u64 {
        let line = stdout.lines().find(|l| l.starts_with(prefix)).unwrap_or_else(|| panic!("{stdout}"));
        let words: Vec<&str> = line.split_whitespace().collect();
        words[word].trim_end_matches(',').parse().unwrap_or_else(|_| panic!("{line}"))
    };
    // "render: T s (path), 40 x 150 pixels, N spp" and "samples: M (…)".
    let spp = field("render:", 8);
    let samples = field("samples:", 1);
    assert!((1..1_000_000).contains(&spp), "{stdout}");
    assert_eq!(samples, spp * 40 * 150, "every strip stops at the first one's {spp} spp:\n{stdout}");
    // Generous for a loaded machine: without the time limit the render takes hours.
    assert!(secs < 60.0, "{secs} s");
}

/// A farm part is not rendered in strips: a clear error before anything renders.
#[test]
fn a_part_in_strips_is_an_error_at_the_command_line() {
    let (code, _, err) =
        mira(&["render", "../../scenes/iray_cornell_box.mi", "--part", "1/2", "--strip-rows", "64", "-o", "x.exr"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("mira: error: cannot render in strips: a farm part is not rendered in strips (a part is rendered in one film of the whole image"),
        "{err}"
    );
}
