//! The integration tests' way from `.mi` text to pixels: parse, build the scene and compile
//! its shading ([`compile`]), translate the world and render it ([`render_world`]), or all of
//! it at once ([`render_text`]); scenes with MDL module materials through the render
//! pipeline's world stage ([`build_parsed`]); and the textured square the material tests and
//! benchmarks look at ([`lit_square`]); the top-down view of the Maya path-engine tests
//! ([`maya_view`]); the two-tone scene of the glossy path tests ([`two_tone`]); a box object
//! of quads ([`box_object`]); the builder of their scenes' `.mi` text ([`scene_text`]). The benchmarks include this file
//! too.

#![allow(dead_code)]

pub mod backends;
pub mod maya_view;
pub mod moving_quad;
pub mod rays;
pub mod scene_text;
pub mod two_tone;

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use render::film::Film;
use render::{EngineKind, Settings, Stats};
use shader::{Shading, ShadingOptions};

/// A test scene read, built and compiled, with every message of the reader, the scene layer
/// and the shading (rendered with file:line:col).
pub struct Compiled {
    /// The scene.
    pub scene: scene::Scene,
    /// Its shading, with every library.
    pub shading: Shading,
    /// The messages.
    pub messages: Vec<String>,
    /// How many of `messages` come first from reading the text (the rest from building
    /// the scene and compiling its shading).
    pub read: usize,
}

/// Reads, builds and compiles `text` (file name `t.mi`) with the default shading options.
pub fn compile(text: &str) -> Compiled {
    compile_with(text, &ShadingOptions::default())
}

/// Reads, builds and compiles `text` with shading `options`. Panics, with every message,
/// when no scene can be built.
pub fn compile_with(text: &str, options: &ShadingOptions) -> Compiled {
    let parsed = mi::parse_str("t.mi", text);
    let mut messages: Vec<String> = parsed.diagnostics.list.iter().map(|d| d.render(&parsed.sources)).collect();
    let read = messages.len();
    let mut diags = Vec::new();
    let Some(scene) = scene::Scene::build(&parsed, 0, &mut diags) else {
        let all: Vec<String> = diags.iter().map(|d| d.render(&parsed.sources)).collect();
        panic!("no scene: {messages:?} {all:?}");
    };
    let (shading, shade_diags) = Shading::build(&scene, options, &material::registry());
    diags.extend(shade_diags);
    messages.extend(diags.iter().map(|d| d.render(&parsed.sources)));
    Compiled { scene, shading, messages, read }
}

/// Reads, builds and compiles `text` (file name `t.mi`) with the default shading options,
/// asserting that the reader found no error (the scene layer's and the shading's warnings
/// are dropped): the scene and its shading.
pub fn build_clean(text: &str) -> (scene::Scene, Shading) {
    let parsed = mi::parse_str("t.mi", text);
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    let (shading, _) = Shading::build(&scene, &ShadingOptions::default(), &material::registry());
    (scene, shading)
}

/// Renders `world` with `shading` and `settings` on the default acceleration structure:
/// the film and the statistics.
pub fn render_world(world: &render::World, shading: &Shading, settings: &Settings) -> (Film, Stats) {
    let accel = render::accel::build(world, render::Backend::default_available());
    render::render(world, accel.as_ref(), Some(shading), settings, &AtomicBool::new(false), &|_| {})
}

/// Renders the scene `text` with `engine` (`spp` samples per pixel, or the scene's own):
/// the pixels (RGBA, rows from the top) and every message the reader, the scene layer and
/// the shading gave — for the path engine also the world's translation warnings.
pub fn render_text(text: &str, engine: EngineKind, spp: Option<u32>) -> (Vec<[f32; 4]>, Vec<String>) {
    let Compiled { scene, shading, mut messages, .. } = compile(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    if engine == EngineKind::Path {
        messages.extend(world.warnings.iter().cloned());
    }
    let settings = Settings { engine, spp, ..Settings::default() };
    let (film, _) = render_world(&world, &shading, &settings);
    (film.rgba(), messages)
}

/// The directory of the example MDL modules (`scenes/mdl`).
pub fn mdl_modules() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/mdl"))
}

/// A scene built through the render pipeline's world stage, with every message.
pub struct BuiltScene {
    /// The scene (its camera at the asked resolution).
    pub scene: scene::Scene,
    /// Its shading, MDL module materials and world ([`render::pipeline::build_world`]).
    pub built: render::pipeline::Built,
    /// The messages of the reader, the scene layer, the compilers and the world's
    /// translation (file:line:col where they have one).
    pub messages: Vec<String>,
}

/// Builds `parsed` at `res`² as `mira render` does: shading with every library, MDL modules
/// from the scene's directory then `mdl_paths`, the world. Panics, with every message, when
/// no scene can be built.
pub fn build_parsed(parsed: &mi::Parsed, res: u32, mdl_paths: &[PathBuf]) -> BuiltScene {
    let mut messages: Vec<String> = parsed.diagnostics.list.iter().map(|d| d.render(&parsed.sources)).collect();
    let mut diags = Vec::new();
    let Some(mut scene) = scene::Scene::build(parsed, 0, &mut diags) else {
        let all: Vec<String> = diags.iter().map(|d| d.render(&parsed.sources)).collect();
        panic!("no scene: {messages:?} {all:?}");
    };
    scene.camera.resolution = (res, res);
    let built = render::pipeline::build_world(&scene, &ShadingOptions::default(), mdl_paths);
    messages.extend(diags.iter().chain(&built.diagnostics).map(|d| d.render(&parsed.sources)));
    messages.extend(built.world.warnings.iter().cloned());
    BuiltScene { scene, built, messages }
}

/// A 4×4 texture of four 2×2 blocks: bottom left red, bottom right green, top left blue,
/// top right white (rows listed from the bottom).
pub const QUADRANTS: &str = r#"color texture "quadrants" [ 4 4 ]
    'ff0000' 'ff0000' '00ff00' '00ff00'  'ff0000' 'ff0000' '00ff00' '00ff00'
    '0000ff' '0000ff' 'ffffff' 'ffffff'  '0000ff' '0000ff' 'ffffff' 'ffffff'"#;

/// A 2 × 2 square (texture coordinates 0…1) seen head-on by an 8×8 camera and lit head-on
/// by a directional light of irradiance π, so that a Lambertian pixel's value is its
/// albedo: `body` (textures, shaders, materials) goes before the square, whose instance
/// takes `material`.
pub fn lit_square(body: &str, material: &str) -> String {
    scene_text::SceneText::head_on(8)
        .text(body)
        .text(&format!(
            r#"object "square" group
    -1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1
    0 0 0  1 0 0  1 1 0  0 1 0
    v 0 t 4 v 1 t 5 v 2 t 6 v 3 t 7
    p 0 1 2 3
end group end object
instance "square_inst" "square" material "{material}" end instance"#
        ))
        .instance("square_inst")
        .build()
}

/// The mean colour of the pixels in columns `x0..x1` and rows `y0..y1` (from the top) of a
/// `width`-wide image.
pub fn mean(px: &[[f32; 4]], width: usize, (x0, x1): (usize, usize), (y0, y1): (usize, usize)) -> [f32; 3] {
    let mut sum = [0.0; 3];
    let mut n = 0.0;
    for y in y0..y1 {
        for x in x0..x1 {
            for k in 0..3 {
                sum[k] += px[y * width + x][k];
            }
            n += 1.0;
        }
    }
    sum.map(|s| s / n)
}

/// An axis-aligned box from `lo` to `hi` (world space) as `.mi` text: object `name` of six
/// quads of `material`, counter-clockwise seen from outside, and its instance
/// `{name}_inst` with `placement` (transform or motion statements; may be empty).
pub fn box_object(name: &str, material: &str, lo: [f32; 3], hi: [f32; 3], placement: &str) -> String {
    let v = |i: usize| {
        let p = [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ];
        format!("{} {} {}", p[0], p[1], p[2])
    };
    let points: Vec<String> = (0..8).map(v).collect();
    let verts: String = (0..8).map(|i| format!(" v {i}")).collect();
    let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let polys: String =
        quads.iter().map(|q| format!(" c \"{material}\" {} {} {} {}\n", q[0], q[1], q[2], q[3])).collect();
    format!(
        "object \"{name}\" group\n {}\n{verts}\n{polys} end group end object\ninstance \"{name}_inst\" \"{name}\" {placement} end instance\n",
        points.join("  ")
    )
}
