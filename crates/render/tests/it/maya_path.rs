//! Maya scenes in the path engine: the repository's Maya exports through the render
//! pipeline's world stage (as `mira render --engine path` builds them), and box, cylinder
//! and cone volume lights against the classic engine.

use crate::support;

use std::path::PathBuf;

use render::{EngineKind, Settings};
use shader::ShadingOptions;

/// An export of `scenes/maya` built as `mira render` builds it (textures from the scene's
/// directory) at `res`²: the world stage's result and every message (file:line:col).
fn export(name: &str, res: u32) -> (render::pipeline::Built, Vec<String>) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/maya");
    let parsed = mi::parse_file(&dir.join(name), &mi::ReadOptions::default()).expect("readable");
    let mut messages: Vec<String> = parsed.diagnostics.list.iter().map(|d| d.render(&parsed.sources)).collect();
    assert!(!parsed.diagnostics.has_errors(), "{name}: {messages:?}");
    let mut diags = Vec::new();
    let mut scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    scene.camera.aspect = 1.0;
    scene.camera.resolution = (res, res);
    let options =
        ShadingOptions { search: shader::texture::SearchPath { dirs: vec![dir] }, ..ShadingOptions::default() };
    let built = render::pipeline::build_world(&scene, &options, &[]);
    assert!(
        !diags.iter().chain(&built.diagnostics).any(|d| d.severity == mi::Severity::Error),
        "{name}: errors building the scene"
    );
    messages.extend(diags.iter().chain(&built.diagnostics).map(|d| d.render(&parsed.sources)));
    messages.extend(built.world.warnings.iter().cloned());
    (built, messages)
}

/// The mean colour of `px`, asserting every value is finite.
fn mean(px: &[[f32; 4]]) -> [f32; 3] {
    let mut m = [0.0f32; 3];
    for p in px {
        assert!(p.iter().all(|v| v.is_finite()), "non-finite pixel {p:?}");
        for i in 0..3 {
            m[i] += p[i] / px.len() as f32;
        }
    }
    m
}

/// Renders `built` with `engine` at `spp`: the pixels.
fn render(built: &render::pipeline::Built, engine: EngineKind, spp: u32) -> Vec<[f32; 4]> {
    let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
    support::render_world(&built.world, &built.shading, &settings).0.rgba()
}

/// The Maya 2017 (`adskMaya*`) and Maya 2012 (`maya_*`) exports render in the path engine
/// with no error and no NaN, never black. Their image means are printed beside the classic
/// engine's; they are compared in `maya_exports_agree.rs` (as written they differ by the
/// 2017 export's lens shader, which only the classic engine runs on its samples, and by
/// the light the path engine takes from the environment and from bounces, which the
/// classic engine takes only with final gathering).
#[test]
fn the_maya_exports_render_in_the_path_engine() {
    for name in ["maya2017_export.mi", "maya2012_export.mi"] {
        let (built, messages) = export(name, 16);
        println!("{name}: {messages:#?}");
        let path = mean(&render(&built, EngineKind::Path, 16));
        let classic = mean(&render(&built, EngineKind::Classic, 1));
        println!("{name}: image means path {path:?}, classic {classic:?}");
        assert!(path.iter().all(|&m| m > 0.02), "{name}: path mean {path:?}");
    }
}

/// A lambert plane (colour 0.6 0.5 0.4, diffuse 0.8) seen from 4 above at 24² pixels
/// (aperture 1.2: x and z in ±2.4), lit by the volume light `light` (its shader
/// parameters) whose instance `placement` (a world → light transform) maps the world onto
/// the unit shape.
fn volume_lit_plane(light: &str, placement: &str) -> String {
    let view = support::maya_view::top_down(24);
    format!(
        r#"
$include "mayabase.mi"
{view}
light "vol" "maya_volumelight" ("color" 1 0.9 0.8, "intensity" 2, {light}) origin 0 0 0 end light
instance "vol_inst" "vol" transform {placement} end instance
shader "lam" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 0.8)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
object "plane" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "vol_inst" "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Renders `text` with both engines (classic 4 spp, path 16 spp), asserting the path
/// engine translated the volume light without a message about it: the pixels of each.
fn both_engines(text: &str) -> (Vec<[f32; 4]>, Vec<[f32; 4]>) {
    let (scene, shading) = support::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert_eq!(world.lights.len(), 1, "the volume light is translated: {:?}", world.warnings);
    let run = |engine, spp| {
        let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
        support::render_world(&world, &shading, &settings).0.rgba()
    };
    (run(EngineKind::Classic, 4), run(EngineKind::Path, 16))
}

/// Box (smooth ramp), cylinder (linear ramp and a penumbra graph) and cone (coneEndRadius
/// 0.2) volume lights of half-sizes 2, 2, 1.5 along x, y, z centred 1 above the plane (the
/// cylinder's and cone's axis along x, as they shine away from it: along y it would leave
/// the plane unlit): the two engines agree pixel by pixel within 2 % of the brightest
/// pixel and on the image mean within 1 %; the box also against its formula at the pixel
/// centres, c·d·I·tint·ramp(1 − d)·cos θ with d = max(|x|/2, 1/2, |z|/1.5), cos θ = 1/r
/// (no decay: the ramp is the falloff).
#[test]
fn box_cylinder_and_cone_volume_lights_agree_in_both_engines() {
    let linear = r#""colorRange" [
        { "colorRange_Position" 0, "colorRange_Color" 0 0 0, "colorRange_Interp" 1 },
        { "colorRange_Position" 1, "colorRange_Color" 1 1 1, "colorRange_Interp" 1 } ]"#;
    let smooth = linear.replace("0 0 0, \"colorRange_Interp\" 1", "0 0 0, \"colorRange_Interp\" 2");
    let penumbra = r#""penumbra" [ { "penumbra_Position" 0, "penumbra_FloatValue" 0.5, "penumbra_Interp" 1 },
        { "penumbra_Position" 1, "penumbra_FloatValue" 1 } ]"#;
    let upright = "0.5 0 0 0  0 0.5 0 0  0 0 0.6666667 0  0 -0.5 0 1";
    let along_x = "0 0.5 0 0  0.5 0 0 0  0 0 0.6666667 0  -0.5 0 0 1";
    let cases = [
        ("box", format!(r#""lightShape" 0, {smooth}"#), upright),
        ("cylinder", format!(r#""lightShape" 2, {linear}, {penumbra}"#), along_x),
        ("cone", format!(r#""lightShape" 3, "coneEndRadius" 0.2, {linear}"#), along_x),
    ];
    let albedo = [0.6 * 0.8, 0.5 * 0.8, 0.4 * 0.8];
    let tint = [1.0, 0.9, 0.8];
    let peak = albedo[0] * 2.0;
    for (what, light, placement) in &cases {
        let (classic, path) = both_engines(&volume_lit_plane(light, placement));
        let (cm, pm) = (mean(&classic), mean(&path));
        println!("{what}: image means classic {cm:?}, path {pm:?}");
        for ch in 0..3 {
            assert!(cm[ch] > 0.01, "{what}: classic mean {cm:?}");
            assert!((pm[ch] / cm[ch] - 1.0).abs() < 0.01, "{what}: path {pm:?} vs classic {cm:?}");
        }
        for (i, (c, p)) in classic.iter().zip(&path).enumerate() {
            for ch in 0..3 {
                assert!((c[ch] - p[ch]).abs() < 0.02 * peak, "{what} pixel {i} channel {ch}: {} vs {}", p[ch], c[ch]);
            }
            if *what != "box" {
                continue;
            }
            let (col, row) = ((i % 24) as f32, (i / 24) as f32);
            let x = ((col + 0.5) / 24.0 - 0.5) * 1.2 * 4.0;
            let z = ((row + 0.5) / 24.0 - 0.5) * 1.2 * 4.0;
            let d = (x.abs() / 2.0).max(0.5).max(z.abs() / 1.5);
            let t = (1.0 - d).max(0.0);
            let ramp = t * t * (3.0 - 2.0 * t);
            let r = (x * x + z * z + 1.0).sqrt();
            for ch in 0..3 {
                let want = albedo[ch] * tint[ch] * 2.0 * ramp / r;
                assert!((c[ch] - want).abs() < 0.02 * peak, "box classic pixel {i} channel {ch}: {} vs {want}", c[ch]);
            }
        }
    }
}

/// A sphere of radius `r` about the origin as a `.mi` polygon object `name` with material
/// `material`: `rings` latitude bands of `segments` quads (triangles at the poles).
fn sphere_object(name: &str, material: &str, r: f32, rings: usize, segments: usize) -> String {
    let mut vectors = String::new();
    for i in 0..=rings {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = std::f32::consts::TAU * j as f32 / segments as f32;
            let p = [r * theta.sin() * phi.cos(), r * theta.cos(), r * theta.sin() * phi.sin()];
            vectors.push_str(&format!("{} {} {}\n", p[0], p[1], p[2]));
        }
    }
    let v = |i: usize, j: usize| i * segments + j % segments;
    let mut vertices = String::new();
    for k in 0..(rings + 1) * segments {
        vertices.push_str(&format!("v {k} "));
    }
    let mut polygons = String::new();
    for i in 0..rings {
        for j in 0..segments {
            // Counter-clockwise seen from outside.
            polygons.push_str(&format!(
                "c \"{material}\" {} {} {} {}\n",
                v(i, j),
                v(i, j + 1),
                v(i + 1, j + 1),
                v(i + 1, j)
            ));
        }
    }
    format!("object \"{name}\" group\n{vectors}{vertices}\n{polygons}end group end object\n")
}

/// The scene of a glowing lambert sphere (colour 0.6, glowIntensity 0.5: glow 0.3) of
/// radius 0.8 on black, seen from 4 above at 32² with the camera's shader glow (linear,
/// spread 0.1, no auto exposure) on the output `types`, the options' statements
/// `options` added.
fn glowing_sphere(options: &str, types: &str) -> String {
    format!(
        r#"
$include "mayabase.mi"
{}
options "opt" samples 0 0 filter box 1 1 {options} end options
camera "cam" output "{types}" "maya_shaderglow" ("glowSpread" 0.1, "autoExposure" off)
    focal 1 aperture 1.2 aspect 1 resolution 32 32 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 0 1 0  0 -1 0 0  0 0 -4 1 end instance
light "sun" "maya_directionallight" ("intensity" 1) direction 0 -1 0 end light
instance "sun_inst" "sun" end instance
shader "glowing" "maya_lambert" ("color" 0.6 0.6 0.6, "diffuse" 1, "glowIntensity" 0.5)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "glowing.outColor") end material
{}instance "ball_inst" "ball" end instance
instgroup "root" "cam_inst" "sun_inst" "ball_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        r#"shader "opt:state" "maya_state" ("glowColorBuffer" 1)"#,
        sphere_object("ball", "m", 0.8, 12, 24)
    )
}

/// Renders the glowing sphere `text` with both engines (16 samples per pixel), asserting
/// that the materials' glow goes to the user frame buffer named `buffer_name`, that it
/// holds 0.3 at the sphere's centre (1e-4) and that the post pass adds the buffer's sum
/// (1e-3 relative: the kernel sums to 1): the glow added to each pixel's red, per engine.
fn glow_added(text: &str, buffer_name: &str) -> Vec<Vec<f32>> {
    let (scene, shading) = support::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    let buffer = world.glow_buffer.expect("the camera runs a shader glow") as usize;
    assert_eq!(world.user_buffers[buffer].0, buffer_name);
    let mut added = Vec::new();
    for engine in [EngineKind::Classic, EngineKind::Path] {
        let settings = Settings { engine, spp: Some(16), ..Settings::default() };
        let (before, _) = support::render_world(&world, &shading, &settings);
        let mut after = before.clone();
        let warnings = render::output_shaders::run(&mut after, &scene.camera, &scene.library);
        assert!(warnings.is_empty(), "{warnings:?}");
        let glow = &before.user[buffer].data;
        let centre = glow[16 * 32 + 16];
        assert!((centre[0] - 0.3).abs() < 1e-4, "{engine:?}: glow at the centre {centre:?}");
        let sum: f32 = glow.iter().map(|g| g[0]).sum();
        let add: Vec<f32> = after.rgba().iter().zip(before.rgba()).map(|(a, b)| a[0] - b[0]).collect();
        let total: f32 = add.iter().sum();
        println!("{engine:?}, buffer {buffer_name}: glow buffer sum {sum:.4}, glow added {total:.4}");
        assert!(sum > 1.0 && (total / sum - 1.0).abs() < 1e-3, "{engine:?}: added {total} vs buffer {sum}");
        added.push(add);
    }
    added
}

/// The glowing sphere's halo in both engines (see [`glow_added`]): the glow added sums
/// agree within 2 % and every pixel within 5 % of the largest addition. (A pixel's glow
/// is the mean over its samples that stop at a surface, in both engines: the buffers hold
/// 0.3 on every pixel some sample of the sphere hits; measured: both sums 33.6, no pixel
/// differs.)
#[test]
fn a_glowing_sphere_has_the_same_halo_in_both_engines() {
    let added = glow_added(&glowing_sphere("", "+rgba"), maya::glow::BUFFER);
    let (classic, path) = (&added[0], &added[1]);
    let (cs, ps): (f32, f32) = (classic.iter().sum(), path.iter().sum());
    assert!((ps / cs - 1.0).abs() < 0.02, "glow added: path {ps} vs classic {cs}");
    let peak = classic.iter().fold(0.0f32, |m, &v| m.max(v));
    let worst = classic.iter().zip(path).map(|(c, p)| (c - p).abs()).fold(0.0f32, f32::max);
    println!("halo: peak addition {peak:.4}, largest difference {worst:.4}");
    assert!(worst < 0.05 * peak, "largest per-pixel difference {worst} vs peak {peak}");
}

/// The state shader's `glowColorBuffer` n sends the materials' glow to `frame buffer n`
/// when the options declare it — whether the state shader is written inline or named —,
/// and the output statement listing `fb<n>` spreads it (as the Maya 2012 export's
/// `output "+rgba,fb0"`); naming an undeclared buffer leaves the glow in mira's own
/// buffer. Each engine adds the same glow in all three forms (1e-4 per pixel).
#[test]
fn the_state_shaders_glow_color_buffer_is_where_the_glow_goes() {
    let reference = glow_added(&glowing_sphere("", "+rgba"), maya::glow::BUFFER);
    let forms = [
        (r#"frame buffer 1 "+rgba_fp" state = "opt:state""#, "+rgba,fb1", "fb1"),
        (
            r#"frame buffer 0 "+rgba_fp" frame buffer 2 "+rgba_fp" state "maya_state" ("glowColorBuffer" 2)"#,
            "+rgba,fb2",
            "fb2",
        ),
        (r#"frame buffer 0 "+rgba_fp" state = "opt:state""#, "+rgba", maya::glow::BUFFER),
    ];
    for (options, types, name) in forms {
        let added = glow_added(&glowing_sphere(options, types), name);
        for (engine, (got, want)) in added.iter().zip(&reference).enumerate() {
            let worst = got.iter().zip(want).map(|(g, w)| (g - w).abs()).fold(0.0f32, f32::max);
            assert!(worst < 1e-4, "{options}: engine {engine} differs by {worst}");
        }
    }
}
