//! The catalogue of hostile `.mi` files (issue 15): every file under `tests/hostile/`, what
//! `mira` says about it, and that it never panics or aborts.
//!
//! Each case runs `mira check --scene -W --max-memory 1G FILE` in `tests/hostile/` (the
//! texture cases run `mira render`, since only rendering reads textures) and asserts the
//! exit status and either the exact first diagnostic line (the first error, else the first
//! warning) or, for files whose documented fallback gives no diagnostic, a line of the
//! report. The first comment line of each file says what it tries. Cases too large to
//! keep in the repository (20 000 nested instgroups, 50 000 connected shaders) are written
//! to a temporary directory by the tests below.

use std::path::{Path, PathBuf};
use std::process::Command;

/// What a case must print.
enum Expect {
    /// This exact first diagnostic line on stderr.
    Diag(&'static str),
    /// No diagnostic; this text in the report on stdout (the documented fallback).
    Report(&'static str),
}
use Expect::*;

struct Case {
    file: &'static str,
    exit: i32,
    expect: Expect,
}

/// `mira check --scene` cases. Fallbacks without a diagnostic: 2000 frame buffers that are
/// not `user` take no film memory; a window beyond the image is clipped to it by the
/// renderer; two billion photons are what the file asks for (`--time` bounds their pass).
const CHECK: &[Case] = &[
    Case { file: "binary_garbage.mi", exit: 1, expect: Diag("binary_garbage.mi:1:2: error: unexpected character byte 0xfc") },
    Case { file: "camera_aperture_infinite.mi", exit: 1, expect: Diag("camera_aperture_infinite.mi:8:5: error: camera aperture -infinity is not a positive finite number") },
    Case { file: "camera_aspect_zero.mi", exit: 0, expect: Diag("camera_aspect_zero.mi:9:5: warning: camera aspect 0 is not a positive finite number: the resolution's ratio 1 is used") },
    Case { file: "camera_clip_inverted.mi", exit: 0, expect: Diag("camera_clip_inverted.mi:11:5: warning: camera clip 10 1 is not a range from a near distance ≥ 0 to a farther one: 0.001 1e30 is used") },
    Case { file: "camera_degenerate.mi", exit: 1, expect: Diag("camera_degenerate.mi:7:5: error: camera focal length 0 is not a positive finite number (or 'infinity' for an orthographic camera)") },
    Case { file: "camera_focal_infinite.mi", exit: 1, expect: Diag("camera_focal_infinite.mi:7:5: error: camera focal length infinity is not a positive finite number (or 'infinity' for an orthographic camera)") },
    Case { file: "camera_focal_negative.mi", exit: 1, expect: Diag("camera_focal_negative.mi:7:5: error: camera focal length -2 is not a positive finite number (or 'infinity' for an orthographic camera)") },
    Case { file: "camera_offset_infinite.mi", exit: 0, expect: Diag("camera_offset_infinite.mi:11:5: warning: camera offset is not finite: no offset is used") },
    Case { file: "camera_transform_infinite.mi", exit: 0, expect: Diag("camera_transform_infinite.mi:13:5: warning: singular or invalid transform: identity used") },
    Case { file: "camera_transform_singular.mi", exit: 0, expect: Diag("camera_transform_singular.mi:13:5: warning: singular or invalid transform: identity used") },
    Case { file: "ccmesh_huge_header.mi", exit: 0, expect: Diag("ccmesh_huge_header.mi:31:9: warning: ccmesh 'c' declares 4000000000 polygons and 4000000000 vertex references but holds 1 and 3") },
    Case { file: "data_huge_header.mi", exit: 0, expect: Diag("data_huge_header.mi:35:1: warning: data 'd' declares 4000000000 bytes but holds 2") },
    Case { file: "deep_brackets.mi", exit: 1, expect: Diag("deep_brackets.mi:22:169: error: nesting deeper than 128 levels") },
    Case { file: "empty.mi", exit: 1, expect: Diag("empty.mi:1:1: error: the file has no 'render' statement") },
    Case { file: "filter_absurd.mi", exit: 0, expect: Diag("filter_absurd.mi:5:5: warning: filter 1000000000000000 x 0 pixels is outside (0, 64]: 64 x 1 is used") },
    Case { file: "finalgather_absurd.mi", exit: 1, expect: Diag("finalgather_absurd.mi:6:5: error: 'finalgather accuracy' has a number that is not finite (infinity)") },
    Case { file: "framebuffers_many.mi", exit: 0, expect: Report("camera 'cam' (instance 'cam_inst'): at (0, 0, 5) looking along (0, 0, -1), up (0, 1, 0), 8x8 pixels") },
    Case { file: "hair_absurd.mi", exit: 0, expect: Diag("hair_absurd.mi:25:8: warning: object 'tri': hair with non-finite points or radii is left out") },
    Case { file: "hair_huge_header.mi", exit: 1, expect: Diag("hair_huge_header.mi:26:5: error: hair declares 4000000000 scalars but the file is shorter") },
    Case { file: "include_dev_zero.mi", exit: 1, expect: Diag("include_dev_zero.mi:2:11: error: include file '/dev/zero' is not a regular file (/dev/zero)") },
    Case { file: "include_directory.mi", exit: 1, expect: Diag("include_directory.mi:2:11: error: include file '.' is a directory (.)") },
    Case { file: "include_loop_a.mi", exit: 1, expect: Diag("include_loop_b.mi:2:11: error: include loop: include_loop_a.mi -> include_loop_b.mi -> include_loop_a.mi") },
    Case { file: "include_loop_b.mi", exit: 1, expect: Diag("include_loop_a.mi:2:11: error: include loop: include_loop_b.mi -> include_loop_a.mi -> include_loop_b.mi") },
    Case { file: "include_missing.mi", exit: 1, expect: Diag("include_missing.mi:2:11: error: cannot find include file 'no_such_file.mi'") },
    Case { file: "include_self.mi", exit: 1, expect: Diag("include_self.mi:2:11: error: include loop: include_self.mi -> include_self.mi") },
    Case { file: "instance_of_itself.mi", exit: 1, expect: Diag("instance_of_itself.mi:35:22: error: instgroup 'g' contains itself (through root -> g)") },
    Case { file: "instance_transform_nan.mi", exit: 0, expect: Diag("instance_transform_nan.mi:35:5: warning: singular or invalid transform: identity used") },
    Case { file: "instance_transform_overflow.mi", exit: 0, expect: Diag("instance_transform_overflow.mi:35:5: warning: singular or invalid transform: identity used") },
    Case { file: "instgroup_cycle.mi", exit: 1, expect: Diag("instgroup_cycle.mi:36:15: error: instgroup 'a' contains itself (through root -> a -> b)") },
    Case { file: "light_color_infinite.mi", exit: 1, expect: Diag("light_color_infinite.mi:16:24: error: shader parameter 'color' has a number that is not finite (infinity)") },
    Case { file: "light_energy_infinite.mi", exit: 1, expect: Diag("light_energy_infinite.mi:18:5: error: 'energy' has a number that is not finite (infinity)") },
    Case { file: "light_origin_infinite.mi", exit: 1, expect: Diag("light_origin_infinite.mi:17:5: error: 'origin' has a number that is not finite (-infinity)") },
    Case { file: "light_rectangle_zero_area.mi", exit: 0, expect: Diag("light_rectangle_zero_area.mi:18:5: warning: area light 'key_inst' has no area: it is used without its shape") },
    Case { file: "long_name.mi", exit: 0, expect: Report("1 polygon (1 triangles)") },
    Case { file: "motion_transform_singular.mi", exit: 0, expect: Diag("motion_transform_singular.mi:37:5: warning: singular or invalid motion transform: the instance does not move") },
    Case { file: "motion_steps_absurd.mi", exit: 1, expect: Diag("motion_steps_absurd.mi:7:5: error: 'shutter' has a number that is not finite (infinity)") },
    Case { file: "no_render.mi", exit: 1, expect: Diag("no_render.mi:1:1: error: the file has no 'render' statement") },
    Case { file: "nul_bytes.mi", exit: 1, expect: Diag("nul_bytes.mi:2:14: error: unexpected character byte 0x00") },
    Case { file: "ok_baseline.mi", exit: 0, expect: Report("ok_baseline.mi: 0 errors, 0 warnings;") },
    Case { file: "phenomenon_cycle.mi", exit: 1, expect: Diag("phenomenon_cycle.mi:27:20: error: phenomenon 'pb' nests too deeply") },
    Case { file: "phenomenon_self.mi", exit: 1, expect: Diag("phenomenon_self.mi:23:20: error: phenomenon 'ph' nests too deeply") },
    Case { file: "photons_absurd.mi", exit: 1, expect: Diag("photons_absurd.mi:7:5: error: 'caustic accuracy' has a number that is not finite (infinity)") },
    Case { file: "photons_many.mi", exit: 0, expect: Report("photons_many.mi: 0 errors, 0 warnings;") },
    Case { file: "polygon_index_out_of_range.mi", exit: 1, expect: Diag("polygon_index_out_of_range.mi:31:9: error: polygon uses vertex 7 but the group has 3 vertices") },
    Case { file: "progressive_absurd.mi", exit: 0, expect: Diag("progressive_absurd.mi:6:5: warning: \"progressive max samples\" 2000000000 is more than mira takes: 1000000000 is used") },
    Case { file: "resolution_huge.mi", exit: 1, expect: Diag("resolution_huge.mi:10:5: error: camera resolution 4000000000 x 4000000000 is outside 1 … 65536 pixels per side") },
    Case { file: "resolution_large.mi", exit: 1, expect: Diag("resolution_large.mi:10:5: error: resolution 65536 x 65536 needs 1.16 TiB of film and frame buffers, more than the limit of 1.00 GiB (--max-memory)") },
    Case { file: "resolution_negative.mi", exit: 1, expect: Diag("resolution_negative.mi:10:5: error: camera resolution -640 x 480 is outside 1 … 65536 pixels per side") },
    Case { file: "resolution_zero.mi", exit: 1, expect: Diag("resolution_zero.mi:10:5: error: camera resolution 0 x 0 is outside 1 … 65536 pixels per side") },
    Case { file: "samples_absurd.mi", exit: 0, expect: Diag("samples_absurd.mi:4:5: warning: samples level 200 asks for more than the 1024 samples per pixel mira takes: level 5 is used") },
    Case { file: "shutter_reversed.mi", exit: 0, expect: Diag("shutter_reversed.mi:6:5: warning: shutter closes at 0 before it opens at 1: no motion blur is rendered") },
    Case { file: "shader_cycle.mi", exit: 1, expect: Diag("shader_cycle.mi:23:50: error: shader connections form a cycle: 'a' -> 'b' -> 'a'") },
    Case { file: "shader_self.mi", exit: 1, expect: Diag("shader_self.mi:22:50: error: shader connections form a cycle: 'a' -> 'a'") },
    Case { file: "shader_unknown_reference.mi", exit: 1, expect: Diag("shader_unknown_reference.mi:23:38: error: unknown shader 'nowhere'") },
    Case { file: "trace_depth_absurd.mi", exit: 0, expect: Diag("trace_depth_absurd.mi:5:5: warning: trace depth 2000000000 is deeper than mira traces: 65536 is used") },
    Case { file: "triangle_zero_area.mi", exit: 0, expect: Diag("triangle_zero_area.mi:31:9: warning: degenerate polygon (no area or invalid coordinates) skipped") },
    Case { file: "trilist_huge_header.mi", exit: 1, expect: Diag("trilist_huge_header.mi:26:5: error: trilist of 4000000000 vertex lines of 3 numbers is too large") },
    Case { file: "truncated.mi", exit: 1, expect: Diag("truncated.mi:26:5: error: 'group' is not closed by 'end group'") },
    Case { file: "unknown_root.mi", exit: 1, expect: Diag("unknown_root.mi:35:8: error: unknown instgroup 'nowhere'") },
    Case { file: "vertex_huge.mi", exit: 0, expect: Diag("vertex_huge.mi:31:9: warning: degenerate polygon (no area or invalid coordinates) skipped") },
    Case { file: "vertex_infinite.mi", exit: 0, expect: Diag("vertex_infinite.mi:31:9: warning: degenerate polygon (no area or invalid coordinates) skipped") },
    Case { file: "window_absurd.mi", exit: 0, expect: Report("8x8 pixels") },
];

/// `mira render` cases (textures are read when shading is built).
const RENDER: &[Case] = &[
    Case {
        file: "texture_corrupt.mi",
        exit: 0,
        expect: Diag(
            "texture_corrupt.mi:22:21: warning: texture file 'corrupt.png': cannot read: Format error decoding Png",
        ),
    },
    Case {
        file: "texture_huge_header.mi",
        exit: 0,
        expect: Diag(
            "texture_huge_header.mi:22:21: warning: texture file 'huge_header.png': cannot read: Memory limit exceeded",
        ),
    },
    Case {
        file: "texture_nonfinite.mi",
        exit: 0,
        expect: Diag(
            "texture_nonfinite.mi:22:21: warning: texture file 'nan_texels.exr': 3 texel components are NaN or infinite; they are read as 0",
        ),
    },
    Case {
        file: "texture_missing.mi",
        exit: 0,
        expect: Diag(
            "texture_missing.mi:22:21: warning: texture file 'no_such_image.png' not found; lookups of it give black",
        ),
    },
];

/// Cases whose tessellation is capped at 2^23 faces (93 s for the three on a loaded 2-core
/// machine):
/// `cargo test -p mira --test it hostile:: -- --ignored`.
const HEAVY: &[Case] = &[
    Case {
        file: "approximation_absurd.mi",
        exit: 0,
        expect: Diag("approximation_absurd.mi:32:29: warning: subdivision surface 's': 16 levels would make too many faces; using 11"),
    },
    Case {
        file: "approximation_surface_absurd.mi",
        exit: 0,
        expect: Diag("approximation_surface_absurd.mi:33:9: warning: free-form surface 'surf': its approximation asks for too many triangles; a coarser grid is used"),
    },
    Case {
        file: "ccmesh_absurd.mi",
        exit: 0,
        expect: Diag("ccmesh_absurd.mi:32:16: warning: ccmesh 'c': 16 levels would make too many faces; using 11"),
    },
];

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/hostile")
}

/// Runs mira in `cwd`; returns (exit status, stdout, stderr). A signal (abort, stack
/// overflow) or a panic message fails the test.
fn mira(cwd: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_mira")).args(args).current_dir(cwd).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let code = out.status.code().unwrap_or_else(|| panic!("mira {args:?} was killed by a signal:\n{stderr}"));
    assert!(!stderr.contains("panicked"), "mira {args:?} panicked:\n{stderr}");
    (code, stdout, stderr)
}

/// The first error line of `stderr`, else its first warning line.
fn first_diagnostic(stderr: &str) -> Option<&str> {
    let starts = |kind: &str| stderr.lines().find(|l| !l.starts_with(' ') && l.contains(kind));
    starts(": error: ").or_else(|| starts(": warning: "))
}

fn run(cases: &[Case], args: &[&str]) {
    let mut failures = Vec::new();
    for case in cases {
        let mut all: Vec<&str> = args.to_vec();
        all.push(case.file);
        let (code, stdout, stderr) = mira(&dir(), &all);
        let found = first_diagnostic(&stderr);
        let ok = code == case.exit
            && match case.expect {
                Diag(line) => found.is_some_and(|f| f == line || (line.ends_with("Png") && f.starts_with(line))),
                Report(text) => found.is_none() && stdout.contains(text),
            };
        if !ok {
            failures.push(format!("{}: exit {code}, first diagnostic {found:?}\n{stdout}", case.file));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn check_catalogue() {
    run(CHECK, &["check", "--scene", "-W", "--max-memory", "1G"]);
}

#[test]
fn render_catalogue() {
    let out = std::env::temp_dir().join(format!("mira-hostile-{}.png", std::process::id()));
    run(RENDER, &["render", "-W", "--spp", "1", "-o", out.to_str().unwrap()]);
}

#[test]
#[ignore]
fn heavy_catalogue() {
    run(HEAVY, &["check", "--scene", "-W", "--max-memory", "1G"]);
}

#[test]
fn every_file_is_catalogued() {
    let mut listed: Vec<&str> = CHECK.iter().chain(RENDER).chain(HEAVY).map(|c| c.file).collect();
    listed.sort();
    let mut files: Vec<String> = std::fs::read_dir(dir())
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".mi"))
        .collect();
    files.sort();
    assert_eq!(files, listed);
    assert!(files.len() >= 40, "{} files", files.len());
}

/// Files that check without errors also render (8 × 8, 1 sample per pixel) without a
/// panic or an abort, and with exit status 0: their fallbacks reach the renderer finite.
#[test]
fn sanitised_files_render() {
    let out = std::env::temp_dir().join(format!("mira-hostile-r-{}.png", std::process::id()));
    for case in CHECK.iter().filter(|c| c.exit == 0) {
        let args =
            ["render", "--resolution", "8", "8", "--spp", "1", "--time", "10", "-o", out.to_str().unwrap(), case.file];
        let (code, _, stderr) = mira(&dir(), &args);
        assert_eq!(code, 0, "{}: {stderr}", case.file);
    }
}

/// The baseline scene with `extra` inserted before its material (line 19 on).
fn baseline_with(extra: &str, diffuse: &str) -> String {
    let text = std::fs::read_to_string(dir().join("ok_baseline.mi")).unwrap();
    text.replace("material \"mtl\"", &format!("{extra}material \"mtl\"")).replace("\"diffuse\" 0.5 0.5 0.5 1", diffuse)
}

fn scratch(name: &str, text: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mira-hostile-gen-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join(name), text).unwrap();
    d
}

/// `--time` bounds the photon pre-pass too (it ignored the clock and traced two billion
/// photons): the render stops within seconds, warns, and writes its image.
#[test]
fn time_limit_stops_the_photon_pass() {
    let out = std::env::temp_dir().join(format!("mira-hostile-photons-{}.png", std::process::id()));
    let start = std::time::Instant::now();
    let args = ["render", "--time", "1", "--spp", "1", "-o", out.to_str().unwrap(), "photons_many.mi"];
    let (code, _, stderr) = mira(&dir(), &args);
    let secs = start.elapsed().as_secs_f64();
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("mira: warning: --time 1 s ran out in the pre-passes"), "{stderr}");
    // Generous for a loaded machine: the pass alone takes hours.
    assert!(secs < 60.0, "{secs} s");
    assert!(out.is_file());
}

/// NaN and infinite texels are read as 0: none reaches the film (without the sanitising,
/// every sample that looks up the texel is NaN and `--stats` counts it).
#[test]
fn nonfinite_texels_never_reach_the_film() {
    let out = std::env::temp_dir().join(format!("mira-hostile-nan-{}.exr", std::process::id()));
    let args = ["render", "--spp", "4", "--stats", "-o", out.to_str().unwrap(), "texture_nonfinite.mi"];
    let (code, stdout, _) = mira(&dir(), &args);
    assert_eq!(code, 0);
    assert!(stdout.contains("non-finite:     0 channels"), "{stdout}");
}

/// Issue 15: a chain of 50 000 connected shaders overflowed the stack.
#[test]
fn fifty_thousand_connected_shaders() {
    let mut chain = String::from("shader \"s0\" \"mib_color_mix\" (\"num\" 0)\n");
    for i in 1..50_000 {
        chain += &format!("shader \"s{i}\" \"mib_color_mix\" (\"num\" 1, \"color_0\" = \"s{}\")\n", i - 1);
    }
    let d = scratch("chain.mi", &baseline_with(&chain, "\"diffuse\" = \"s49999\""));
    for command in ["check", "render"] {
        let args: Vec<&str> = match command {
            "check" => vec!["check", "--scene", "chain.mi"],
            _ => vec!["render", "--spp", "1", "-o", "chain.png", "chain.mi"],
        };
        let (code, _, stderr) = mira(&d, &args);
        assert_eq!(code, 1);
        assert_eq!(
            first_diagnostic(&stderr),
            Some(
                "chain.mi:50021:1: error: shader 's49999' starts a chain of 50000 connected shaders; mira evaluates \
                 chains of at most 256"
            ),
            "{command}"
        );
    }
}

/// A phenomenon whose body chains `n` local shaders, each connected to the one before
/// (local shaders are built in order, so the graph builder's nesting limit never sees the
/// chain), used by the material through shader "use".
fn phenomenon_chain(n: usize) -> String {
    let mut body = String::from(
        "declare phenomenon color \"longchain\" (color \"c\")\n\
         shader \"s0\" \"mib_color_mix\" (\"num\" 0, \"color_base\" = interface \"c\")\n",
    );
    for i in 1..n {
        body += &format!("shader \"s{i}\" \"mib_color_mix\" (\"num\" 1, \"color_0\" = \"s{}\")\n", i - 1);
    }
    body += &format!("root = \"s{}\"\nend declare\nshader \"use\" \"longchain\" (\"c\" 1 0 0)\n", n - 1);
    baseline_with(&body, "\"diffuse\" = \"use\"")
}

/// Issue 15: a chain of connections inside a phenomenon body escaped the graph's nesting
/// limit (each local shader is built before the next uses it) and its evaluation recursed
/// once per shader. Chains longer than the evaluation limit are now an error where the
/// graph is built, naming the shader that starts them; a chain at the limit renders.
#[test]
fn long_chains_inside_phenomena() {
    let d = scratch("phen_chain.mi", &phenomenon_chain(50_000));
    for args in [&["check", "--scene", "phen_chain.mi"][..], &["render", "--spp", "1", "-o", "p.png", "phen_chain.mi"]]
    {
        let (code, _, stderr) = mira(&d, args);
        assert_eq!(code, 1, "{stderr}");
        let first = first_diagnostic(&stderr).unwrap_or_default();
        assert!(
            first.starts_with("phen_chain.mi:")
                && first.ends_with(
                    "error: shader 'mib_illum_lambert#1' starts a chain of 50002 connected shaders ('use' -> \
                     's49999' -> 's49998' -> …, counting those inside phenomena); mira evaluates chains of at \
                     most 256"
                ),
            "{first}"
        );
    }
    // The material's shader, the phenomenon's node and 254 shaders in its body: 256, the
    // limit, renders (evaluated 256 deep on a worker thread's stack).
    let d = scratch("phen_chain_256.mi", &phenomenon_chain(254));
    let (code, _, stderr) = mira(&d, &["render", "--spp", "1", "-o", "p.png", "phen_chain_256.mi"]);
    assert_eq!(code, 0, "{stderr}");
}

/// Includes nest at most 64 files deep; deeper is an error at the `$include` (the
/// preprocessor keeps its files on a stack of its own, not the call stack).
#[test]
fn deep_include_nesting_is_an_error_at_the_include() {
    let d = scratch("inc0.mi", "$include \"inc1.mi\"\n");
    for i in 1..100 {
        std::fs::write(d.join(format!("inc{i}.mi")), format!("# level {i}\n$include \"inc{}.mi\"\n", i + 1)).unwrap();
    }
    let (code, _, stderr) = mira(&d, &["check", "inc0.mi"]);
    assert_eq!(code, 1);
    assert_eq!(first_diagnostic(&stderr), Some("inc64.mi:2:11: error: includes nest deeper than 64 files"), "{stderr}");
}

/// Issue 15: 20 000 nested instgroups were reported as "contains itself".
#[test]
fn twenty_thousand_nested_instgroups() {
    let text = std::fs::read_to_string(dir().join("ok_baseline.mi")).unwrap();
    let mut groups = String::from("instgroup \"g0\" \"tri_inst\" end instgroup\n");
    for i in 1..20_000 {
        groups += &format!("instgroup \"g{i}\" \"g{}\" end instgroup\n", i - 1);
    }
    let text = text.replace(
        "instgroup \"root\" \"cam_inst\" \"key_inst\" \"tri_inst\" end instgroup",
        &format!("{groups}instgroup \"root\" \"cam_inst\" \"key_inst\" \"g19999\" end instgroup"),
    );
    let d = scratch("nested.mi", &text);
    let (code, _, stderr) = mira(&d, &["check", "--scene", "nested.mi"]);
    assert_eq!(code, 1);
    let first = first_diagnostic(&stderr).unwrap_or_default();
    assert!(
        first.contains("error: instgroup 'g19744' is nested 257 levels deep; mira follows at most 256 levels"),
        "{first}"
    );
    assert!(!stderr.contains("contains itself"), "{stderr}");
}

/// Command-line values that would panic (`Duration` of an infinite time), start
/// millions of threads or allocate an absurd film are errors before anything is read.
#[test]
fn absurd_command_line_values_are_errors() {
    for (args, message) in [
        (&["--time", "inf"][..], "mira: error: --time inf is not a number of seconds ≥ 0"),
        (&["--time", "NaN"][..], "mira: error: --time NaN is not a number of seconds ≥ 0"),
        (&["--threads", "100000000"][..], "mira: error: --threads 100000000 is more than mira starts (4096)"),
        (&["--resolution", "0", "10"][..], "mira: error: --resolution 0 10 is outside 1 … 65536 pixels per side"),
        (
            &["--resolution", "30000", "30000", "--max-memory", "8G"][..],
            // The size depends on the film's pixel layout (296 bytes a pixel when written).
            "ok_baseline.mi:10:5: error: --resolution 30000 x 30000 needs * GiB of film and frame buffers, more than \
             the limit of 8.00 GiB (--max-memory)",
        ),
    ] {
        let out = std::env::temp_dir().join(format!("mira-hostile-cli-{}.png", std::process::id()));
        let mut all = vec!["render", "-o", out.to_str().unwrap()];
        all.extend_from_slice(args);
        all.push("ok_baseline.mi");
        let (code, _, stderr) = mira(&dir(), &all);
        assert_eq!(code, 1, "{args:?}: {stderr}");
        let first = stderr.lines().next().unwrap_or_default();
        let (head, tail) = message.split_once('*').unwrap_or((message, ""));
        assert!(first.starts_with(head) && first.ends_with(tail) && first.len() >= message.len(), "{stderr}");
    }
}
