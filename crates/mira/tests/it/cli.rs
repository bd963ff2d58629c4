//! The `mira` command as a user runs it.

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

#[test]
fn check_passes_the_shipped_scenes() {
    let (code, out, err) = mira(&["check", "../../scenes/iray_cornell_box.mi", "../../scenes/classic_spheres.mi"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("iray_cornell_box.mi: 0 errors, 3 warnings; 1 camera, 7 instances"), "{out}");
    assert!(out.contains("5 polygons (28 triangles), 20 trilist triangles"), "{out}");
    assert!(out.contains("shaders used: mdl::nvidia::core_definitions::flex_material"), "{out}");
    assert_eq!(out.lines().count(), 2);
    assert!(err.is_empty(), "warnings are printed only with -W: {err}");
}

#[test]
fn check_reports_errors_with_location_and_exit_status_1() {
    let dir = std::env::temp_dir().join(format!("mira-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.mi");
    std::fs::write(&bad, "options \"o\"\n    samples 0 x\nend options\n$include \"nowhere.mi\"\n").unwrap();
    let (code, out, err) = mira(&["check", bad.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("bad.mi:2:15: error: expected on or off") || err.contains("bad.mi:2:15: error:"), "{err}");
    assert!(err.contains("        samples 0 x\n"), "the source line is shown: {err}");
    assert!(err.contains("bad.mi:4:11: error: cannot find include file 'nowhere.mi'"), "{err}");
    assert!(out.contains("bad.mi: 2 errors"), "{out}");
}

#[test]
fn check_warnings_flag_and_include_path() {
    let dir = std::env::temp_dir().join(format!("mira-cli-inc-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("lib")).unwrap();
    std::fs::write(dir.join("lib/extra.mi"), "declare shader \"extra\" () end declare\n").unwrap();
    std::fs::write(dir.join("s.mi"), "$include <extra.mi>\nshader \"e\" \"extra\" ()\n").unwrap();
    let s = dir.join("s.mi");
    let (code, _, err) = mira(&["check", s.to_str().unwrap()]);
    assert_eq!(code, 1, "angle includes are not looked up beside the file: {err}");
    let lib = dir.join("lib");
    let (code, out, err) = mira(&["check", "-I", lib.to_str().unwrap(), s.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("1 declare") && out.contains("shaders used: extra"), "{out}");
    let (code, _, err) = mira(&["check", "-W", "../../scenes/iray_cornell_box.mi"]);
    assert_eq!(code, 0);
    assert!(err.contains("warning: ccmesh polygon has 4 edges but 6 crease values"), "{err}");
}

#[test]
fn missing_file_is_an_error() {
    let (code, _, err) = mira(&["check", "no/such/file.mi"]);
    assert_eq!(code, 1);
    assert!(err.contains("no/such/file.mi: error:"), "{err}");
}

#[test]
fn render_writes_exr_and_png() {
    let dir = std::env::temp_dir().join(format!("mira-render-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let exr = dir.join("cb.exr");
    let png = dir.join("cb.png");
    for out in [&exr, &png] {
        let (code, stdout, err) = mira(&[
            "render",
            "../../scenes/iray_cornell_box.mi",
            "--resolution",
            "32",
            "32",
            "--spp",
            "4",
            "--stats",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{err}");
        assert!(
            stdout.contains("Mrays/s")
                && stdout.contains("samples/s")
                && stdout.contains("peak memory")
                && stdout.contains("MiB vertices and triangles")
                && stdout.contains("BVH"),
            "{stdout}"
        );
        assert!(err.contains("wrote"), "{err}");
    }
    let png_bytes = std::fs::read(&png).unwrap();
    assert_eq!(&png_bytes[1..4], b"PNG");
    let exr_bytes = std::fs::read(&exr).unwrap();
    assert_eq!(&exr_bytes[..4], &[0x76, 0x2f, 0x31, 0x01], "OpenEXR magic number");
    // Every frame buffer is a channel.
    for name in [&b"N.X"[..], b"tag", b"Z\0"] {
        assert!(exr_bytes.windows(name.len()).any(|w| w == name), "channel {}", String::from_utf8_lossy(name));
    }
}

#[test]
fn render_refuses_scenes_with_errors() {
    let dir = std::env::temp_dir().join(format!("mira-render-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.mi");
    std::fs::write(&bad, "options \"o\" end options\nrender \"root\" \"cam\" \"o\"\n").unwrap();
    let (code, _, err) = mira(&["render", bad.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("bad.mi:2:15: error: unknown camera instance 'cam'"), "{err}");
}

#[test]
fn mdl_modules_are_found_with_dash_m_and_their_materials_checked() {
    let dir = std::env::temp_dir().join(format!("mira-cli-mdl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // The Cornell box without its module beside it.
    let scene = std::fs::read_to_string("../../scenes/mdl/cornell_mdl.mi").unwrap();
    let s = dir.join("cornell.mi");
    std::fs::write(&s, &scene).unwrap();
    let (code, _, err) = mira(&["check", "--scene", "-W", s.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("MDL module `::export_multi` could not be loaded"), "{err}");
    let (code, _, err) = mira(&["check", "--scene", "-W", "-M", "../../scenes/mdl", s.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("could not be loaded"), "{err}");
    // A parameter of the wrong type is an error at its .mi line.
    let bad = dir.join("bad.mi");
    std::fs::write(&bad, scene.replace(r#"("tint" 0.5 0 0, "roughness" 0)"#, r#"("tint" "red")"#)).unwrap();
    let (code, _, err) = mira(&["check", "--scene", "-M", "../../scenes/mdl", bad.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("bad.mi:20:") && err.contains("expected a colour"), "{err}");
    // Rendering by default (the automatic engine: path for MDL materials).
    let png = dir.join("cornell.png");
    let (code, _, err) =
        mira(&["render", "-M", "../../scenes/mdl", s.to_str().unwrap(), "-o", png.to_str().unwrap(), "--spp", "2"]);
    assert_eq!(code, 0, "{err}");
    assert!(png.is_file());
}

/// The third place modules are searched: the directories of `MDL_PATHS` (`:`-separated,
/// after the scene's directory and `-M`). The Cornell box without its module beside it
/// finds `::export_multi` through `MDL_PATHS` (a missing directory first is skipped), and
/// a scene naming `mdl::chain::top::red_coat` loads the three-module chain
/// `chain/top.mdl` → `chain/middle.mdl` → `chain/bottom.mdl` from there, with no warning.
#[test]
fn mdl_modules_are_found_on_mdl_paths() {
    let dir = std::env::temp_dir().join(format!("mira-cli-mdl-paths-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let modules = std::fs::canonicalize("../../scenes/mdl").unwrap();
    let scene = std::fs::read_to_string("../../scenes/mdl/cornell_mdl.mi").unwrap();
    let s = dir.join("cornell.mi");
    std::fs::write(
        &s,
        scene.replace(
            r#""mdl::export_multi::matte" ("tint" 0.5 0 0, "roughness" 0)"#,
            r#""mdl::chain::top::red_coat" ()"#,
        ),
    )
    .unwrap();
    let check = |paths: Option<String>| {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_mira"));
        cmd.args(["check", "--scene", "-W", s.to_str().unwrap()]).current_dir(env!("CARGO_MANIFEST_DIR"));
        cmd.env_remove("MDL_PATHS");
        if let Some(p) = paths {
            cmd.env("MDL_PATHS", p);
        }
        let out = cmd.output().unwrap();
        (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (code, err) = check(None);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("MDL module `::export_multi` could not be loaded"), "{err}");
    let (code, err) = check(Some(format!("{}:{}", dir.join("absent").display(), modules.display())));
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("could not be loaded") && !err.contains("warning"), "{err}");
}

/// `--preview` writes the image rendered so far after every pass but the last (passes of
/// 1, 1, 2 and 4 samples for 8 spp), changes no pixel of the final image, and leaves no
/// hidden file behind; `--preview 0` writes none, and a negative interval is an error.
#[test]
fn previews_are_written_between_passes_and_change_no_pixel() {
    let dir = std::env::temp_dir().join(format!("mira-cli-preview-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let render = |out: &str, preview: &str| {
        let path = dir.join(out);
        let args = ["render", "../../scenes/iray_cornell_box.mi", "-o", path.to_str().unwrap(), "--resolution", "16"];
        let rest = ["16", "--spp", "8", "--threads", "2", "--preview", preview];
        let (code, _, err) = mira(&[&args[..], &rest[..]].concat());
        assert_eq!(code, 0, "{err}");
        (std::fs::read(path).unwrap(), err)
    };
    let (with, err) = render("with.exr", "0.000001");
    for spp in [1, 2, 4] {
        assert!(err.contains(&format!("mira: preview at {spp} spp: ")), "{err}");
    }
    assert!(!err.contains("preview at 8 spp"), "the last pass writes the final image only: {err}");
    let (without, err) = render("without.exr", "0");
    assert!(!err.contains("mira: preview at"), "{err}");
    assert!(with == without, "a preview changes no pixel of the final image");
    let hidden: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with('.'))
        .collect();
    assert!(hidden.is_empty(), "{hidden:?}");
    let (code, _, err) = mira(&["render", "../../scenes/iray_cornell_box.mi", "--preview=-1"]);
    assert_eq!(code, 1);
    assert!(err.contains("--preview -1 is not a number of seconds"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `mira check --scene` prints the annotations of the module materials the scene's shaders
/// instance: after `MDL annotations:`, each material (its absolute name, the shaders that
/// instance it) with its definition's annotations (absolute names, arguments as written),
/// then one line per annotated parameter; a parameter or material without annotations is
/// not listed.
#[test]
fn check_prints_the_annotations_of_mdl_materials() {
    let dir = std::env::temp_dir().join(format!("mira-cli-annotations-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("notes.mdl"),
        r#"mdl 1.7;
import ::anno::*;
import ::df::*;
export material painted(
    color tint = color(0.5) [[ anno::display_name("Paint colour"), anno::in_group("Base") ]],
    uniform float weight = 1.0 [[ anno::soft_range(0.0,   1.0) ]],
    float plain = 0.0
)
[[
    anno::display_name("Painted surface"),
    anno::description("A wall's paint"),
    anno::key_words(string[]("paint", "wall"))
]]
= material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(tint: tint * weight)));
export material bare(color tint = color(0.5)) = material();
"#,
    )
    .unwrap();
    let scene = dir.join("notes.mi");
    std::fs::write(
        &scene,
        r#"$include "notes.mdl"
options "opt" end options
camera "cam" focal 1 aperture 1 aspect 1 resolution 4 4 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
shader "wall" "mdl::notes::painted" ("tint" 1 0 0)
shader "wall2" "mdl::notes::painted" ()
shader "other" "mdl::notes::bare" ()
object "tri" group
    0 0 0  1 0 0  0 1 0
    v 0 v 1 v 2
    p "wall" 0 1 2
end group end object
instance "tri_inst" "tri" end instance
instgroup "root" "cam_inst" "tri_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
    )
    .unwrap();
    let (code, out, err) = mira(&["check", "--scene", scene.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let section: Vec<&str> = out.lines().skip_while(|l| *l != "MDL annotations:").collect();
    assert_eq!(
        section,
        [
            "MDL annotations:",
            r#"  ::notes::painted (shader "wall", "wall2"): ::anno::display_name("Painted surface"), ::anno::description("A wall's paint"), ::anno::key_words(string[]("paint", "wall"))"#,
            r#"    tint: ::anno::display_name("Paint colour"), ::anno::in_group("Base")"#,
            "    weight: ::anno::soft_range(0.0, 1.0)",
        ],
        "{out}"
    );
    // Without annotations, no section.
    std::fs::write(dir.join("notes.mi"), std::fs::read_to_string(&scene).unwrap().replace("painted", "bare")).unwrap();
    let (code, out, err) = mira(&["check", "--scene", scene.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("MDL annotations"), "{out}");
    std::fs::remove_dir_all(&dir).ok();
}
