//! The integration tests' way from `.mi` text to pixels: parse, build the scene and compile
//! its shading ([`compile`]), translate the world and render it ([`render_world`]), or all of
//! it at once ([`render_text`]).

#![allow(dead_code)]

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
