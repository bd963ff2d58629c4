//! Rendering `.mi` text in the integration tests: parse, build the scene and its shading,
//! translate the world, render.

use std::sync::atomic::AtomicBool;

use render::{EngineKind, Settings};
use shader::{Shading, ShadingOptions};

/// Renders the scene `text` with `engine` (`spp` samples per pixel, or the scene's own):
/// the pixels (RGBA, rows from the top) and every message the reader, the scene layer and
/// the shading gave — for the path engine also the world's translation warnings.
pub fn render_text(text: &str, engine: EngineKind, spp: Option<u32>) -> (Vec<[f32; 4]>, Vec<String>) {
    let parsed = mi::parse_str("t.mi", text);
    let mut messages: Vec<String> = parsed.diagnostics.list.iter().map(|d| d.render(&parsed.sources)).collect();
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    let (shading, shade_diags) = Shading::build(&scene, &ShadingOptions::default(), &material::registry());
    diags.extend(shade_diags);
    messages.extend(diags.iter().map(|d| d.render(&parsed.sources)));
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    if engine == EngineKind::Path {
        messages.extend(world.warnings.iter().cloned());
    }
    let accel = render::accel::build(&world, render::Backend::default_available());
    let settings = Settings { engine, spp, ..Settings::default() };
    let (film, _) = render::render(&world, accel.as_ref(), Some(&shading), &settings, &AtomicBool::new(false), &|_| {});
    (film.rgba(), messages)
}
