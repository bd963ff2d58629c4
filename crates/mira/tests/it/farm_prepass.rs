//! Farm renders of classic scenes with pre-passes, and the scene hash over the files a scene
//! reads: `mira prepass` computes the photon maps and final gather points once, parts that
//! read them (`--prepass`) merge into the same bytes as one `mira render`, as parts that
//! compute them do; a pre-pass file of another scene or other settings is refused; parts
//! rendered against a changed texture or MDL module do not merge.

use std::path::{Path, PathBuf};
use std::process::Command;

fn mira(args: &[&str]) -> (i32, String) {
    let out =
        Command::new(env!("CARGO_BIN_EXE_mira")).args(args).current_dir(env!("CARGO_MANIFEST_DIR")).output().unwrap();
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mira-prepass-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `scenes/photons.mi` (caustics and photon global illumination through a glass ball) with
/// final gathering on as well, fewer photons: every classic pre-pass at once.
fn photons_and_fg_scene(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string("../../scenes/photons.mi").unwrap();
    let text = text
        .replace("    finalgather off\n", "    finalgather on\n    finalgather accuracy 48\n")
        .replace("caustic photons 200000", "caustic photons 20000")
        .replace("globillum photons 100000", "globillum photons 10000");
    assert!(text.contains("finalgather on") && text.contains("caustic photons 20000"));
    let path = dir.join("photons_fg.mi");
    std::fs::write(&path, text).unwrap();
    path
}

const OPTS: [&str; 3] = ["--resolution", "48", "30"];

/// Renders part k of n of `scene` to `dir/name` with `options`.
fn part(scene: &Path, dir: &Path, name: &str, k: u32, n: u32, options: &[&str]) -> PathBuf {
    let out = dir.join(name);
    let spec = format!("{k}/{n}");
    let mut args = vec!["render", s(scene), "--part", &spec, "-o", s(&out)];
    args.extend(options);
    let (code, err) = mira(&args);
    assert_eq!(code, 0, "part {spec}: {err}");
    out
}

/// Merges `parts` into `out`.
fn merge(parts: &[PathBuf], out: &Path) -> (i32, String) {
    let mut args = vec!["merge", "-o", s(out)];
    args.extend(parts.iter().map(|p| s(p)));
    mira(&args)
}

/// One process, 3 parts reading a pre-pass file and 4 parts computing the pre-passes
/// themselves (30 rows: uneven spans of 10 and of 7 or 8 rows) give the same EXR bytes,
/// every buffer included.
#[test]
fn parts_with_and_without_a_prepass_file_merge_bit_identically() {
    let dir = temp_dir("identical");
    let scene = photons_and_fg_scene(&dir);
    let one = dir.join("one.exr");
    let mut args = vec!["render", s(&scene), "-o", s(&one), "--threads", "2"];
    args.extend(OPTS);
    let (code, err) = mira(&args);
    assert_eq!(code, 0, "{err}");
    let file = dir.join("scene.prepass");
    let mut args = vec!["prepass", s(&scene), "-o", s(&file), "--threads", "1"];
    args.extend(OPTS);
    let (code, err) = mira(&args);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("caustic") && err.contains("final gather points"), "{err}");
    let read = [&OPTS[..], &["--prepass", s(&file)]].concat();
    let with: Vec<PathBuf> = (1..=3).map(|k| part(&scene, &dir, &format!("w{k}.exr"), k, 3, &read)).collect();
    let without: Vec<PathBuf> = (1..=4).map(|k| part(&scene, &dir, &format!("c{k}.exr"), k, 4, &OPTS)).collect();
    let reference = std::fs::read(&one).unwrap();
    for (name, parts) in [("with", &with), ("without", &without)] {
        let out = dir.join(format!("{name}.exr"));
        let (code, err) = merge(parts, &out);
        assert_eq!(code, 0, "{err}");
        assert!(std::fs::read(&out).unwrap() == reference, "parts {name} the pre-pass file differ from one process");
    }
    // The whole image from the file is the same too.
    let whole = dir.join("whole.exr");
    let mut args = vec!["render", s(&scene), "-o", s(&whole), "--prepass", s(&file)];
    args.extend(OPTS);
    assert_eq!(mira(&args).0, 0);
    assert!(std::fs::read(&whole).unwrap() == reference);
    std::fs::remove_dir_all(&dir).ok();
}

/// A pre-pass file is refused, with the reason, for other settings, another scene text, a
/// path-engine render, a damaged file; `mira prepass` refuses scenes without pre-passes.
#[test]
fn a_prepass_file_that_does_not_fit_is_refused() {
    let dir = temp_dir("refused");
    let scene = photons_and_fg_scene(&dir);
    let file = dir.join("scene.prepass");
    let mut args = vec!["prepass", s(&scene), "-o", s(&file)];
    args.extend(OPTS);
    assert_eq!(mira(&args).0, 0);
    let render = |scene: &Path, options: &[&str]| {
        let out = dir.join("x.exr");
        let mut args = vec!["render", s(scene), "--part", "1/2", "-o", s(&out), "--prepass", s(&file)];
        args.extend(options);
        mira(&args)
    };
    let (code, err) = render(&scene, &[&OPTS[..], &["--seed", "7"]].concat());
    assert_eq!(code, 1);
    assert!(err.contains("computed with other settings: seed=7 here, seed=0 in the file"), "{err}");
    let (code, err) = render(&scene, &["--resolution", "40", "30"]);
    assert_eq!(code, 1);
    assert!(err.contains("resolution=40x30 here, resolution=48x30 in the file"), "{err}");
    let changed = dir.join("changed.mi");
    std::fs::write(&changed, std::fs::read_to_string(&scene).unwrap() + "\n# changed\n").unwrap();
    let (code, err) = render(&changed, &OPTS);
    assert_eq!(code, 1);
    assert!(err.contains("computed for another scene"), "{err}");
    let (code, err) = render(&scene, &[&OPTS[..], &["--engine", "path"]].concat());
    assert_eq!(code, 1);
    assert!(err.contains("the path engine has no pre-pass to read"), "{err}");
    let mut bytes = std::fs::read(&file).unwrap();
    let at = bytes.len() / 2;
    bytes[at] ^= 0x40;
    std::fs::write(&file, &bytes).unwrap();
    let (code, err) = render(&scene, &OPTS);
    assert_eq!(code, 1);
    assert!(err.contains("damaged or truncated"), "{err}");
    let (code, err) = mira(&["prepass", "../../scenes/classic_spheres.mi", "-o", s(&dir.join("no.prepass"))]);
    assert_eq!(code, 1);
    assert!(err.contains("has no pre-pass to save"), "{err}");
    let (code, err) = mira(&["prepass", "../../scenes/iray_cornell_box.mi", "-o", s(&dir.join("no.prepass"))]);
    assert_eq!(code, 1);
    assert!(err.contains("path engine, which has no pre-pass"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Writes a 2 × 2 PNG whose first texel is `red`.
fn write_texture(path: &Path, red: u8) {
    let img = image::RgbImage::from_fn(2, 2, |x, y| image::Rgb([if x + y == 0 { red } else { 40 }, 90, 200]));
    img.save(path).unwrap();
}

/// The scene hash covers the texture files a scene reads: a part rendered after its texture
/// changed does not merge with parts rendered before (the message names it), and merges
/// again once rendered against the same texture.
#[test]
fn parts_rendered_against_a_changed_texture_do_not_merge() {
    let dir = temp_dir("texture");
    let text = std::fs::read_to_string("../../scenes/iray_cornell_box.mi").unwrap();
    let scene = dir.join("textured.mi");
    std::fs::write(&scene, format!("color texture \"tex\" \"tex.png\"\n{text}")).unwrap();
    let tex = dir.join("tex.png");
    write_texture(&tex, 10);
    let opts = ["--resolution", "16", "12", "--spp", "1"];
    let p1 = part(&scene, &dir, "p1.exr", 1, 2, &opts);
    write_texture(&tex, 11);
    let p2 = part(&scene, &dir, "p2.exr", 2, 2, &opts);
    let out = dir.join("m.exr");
    let (code, err) = merge(&[p1.clone(), p2], &out);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("was rendered against other files than the other parts"), "{err}");
    assert!(!out.exists());
    write_texture(&tex, 10);
    let p2 = part(&scene, &dir, "p2.exr", 2, 2, &opts);
    let (code, err) = merge(&[p1, p2], &out);
    assert_eq!(code, 0, "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `mira farm slurm` on a classic scene with pre-passes writes a pre-pass array (one task
/// per frame) that the render array depends on, and the render tasks read its files; a
/// path-engine scene gets none.
#[test]
fn farm_slurm_adds_a_prepass_job_when_the_scene_has_prepasses() {
    let dir = temp_dir("slurm");
    let scene = photons_and_fg_scene(&dir);
    let out = dir.join("out.exr");
    let (code, err) = mira(&["farm", "slurm", s(&scene), "-o", s(&out), "--parts", "3", "--resolution", "48", "30"]);
    assert_eq!(code, 0, "{err}");
    let farm = dir.join("out.exr.farm");
    let prepass = std::fs::read_to_string(farm.join("prepass.sbatch")).unwrap();
    let render = std::fs::read_to_string(farm.join("render.sbatch")).unwrap();
    assert!(prepass.contains("#SBATCH --array=0-0") && prepass.contains(" prepass "), "{prepass}");
    assert!(prepass.contains("--resolution 48 30") && prepass.contains("scontrol requeue"), "{prepass}");
    let file = format!("--prepass {}/prepass-$(printf %04d \"$frame\").bin", farm.display());
    assert!(render.contains(&file), "{render}");
    assert!(prepass.contains(&format!("out={}/prepass-$(printf %04d \"$frame\").bin", farm.display())), "{prepass}");
    let printed = Command::new(env!("CARGO_BIN_EXE_mira"))
        .args(["farm", "slurm", s(&scene), "-o", s(&out), "--parts", "3"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let printed = String::from_utf8_lossy(&printed.stdout);
    assert!(printed.contains("--dependency=afterok:$pre"), "the render array waits for the pre-pass: {printed}");
    let path_out = dir.join("cornell.exr");
    let (code, err) = mira(&["farm", "slurm", "../../scenes/iray_cornell_box.mi", "-o", s(&path_out), "--parts", "2"]);
    assert_eq!(code, 0, "{err}");
    assert!(!dir.join("cornell.exr.farm/prepass.sbatch").exists(), "no pre-pass job for the path engine");
    std::fs::remove_dir_all(&dir).ok();
}

/// The same for an MDL module the scene's materials come from: a part rendered after the
/// module changed does not merge with one rendered before.
#[test]
fn parts_rendered_against_a_changed_mdl_module_do_not_merge() {
    let dir = temp_dir("mdl");
    let scene = dir.join("cornell_mdl.mi");
    std::fs::copy("../../scenes/mdl/cornell_mdl.mi", &scene).unwrap();
    let module = dir.join("export_multi.mdl");
    let text = std::fs::read_to_string("../../scenes/mdl/export_multi.mdl").unwrap();
    std::fs::write(&module, &text).unwrap();
    let opts = ["--resolution", "12", "8", "--spp", "1"];
    let p1 = part(&scene, &dir, "p1.exr", 1, 2, &opts);
    std::fs::write(&module, format!("{text}\n// changed\n")).unwrap();
    let p2 = part(&scene, &dir, "p2.exr", 2, 2, &opts);
    let (code, err) = merge(&[p1, p2], &dir.join("m.exr"));
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("was rendered against other files than the other parts"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
