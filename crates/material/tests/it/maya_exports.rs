//! The repository's Maya export scenes (`scenes/maya/`: the Maya 2012 and 2017 exports
//! and `maya_materials.mi`, Maya's rampShader, layeredShader, anisotropic and 3D textures)
//! compile with every Maya shader they call bound to an implementation of this crate, and
//! their materials shade.

use crate::support;

use std::path::PathBuf;

use shader::{Shading, ShadingOptions};
use support::maya::{point, run_in};
use support::Empty;

/// Shaders the scenes call that this crate declares but leaves to the renderer: the
/// state shader and the image-level output shaders.
const NOT_SHADING: &[&str] = &["adskFrameBufferState", "maya_state", "maya_colormgt", "maya_shaderglow"];

struct Export {
    shading: Shading,
    warnings: Vec<String>,
}

fn load(name: &str) -> Export {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/maya");
    let parsed = mi::parse_file(&dir.join(name), &mi::ReadOptions::default()).expect("readable");
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    let options =
        ShadingOptions { search: shader::texture::SearchPath { dirs: vec![dir] }, ..ShadingOptions::default() };
    let (shading, shade_diags) = Shading::build(&scene, &options, &material::registry());
    diags.extend(shade_diags);
    let maya_nodes = shading
        .graph
        .nodes
        .iter()
        .filter(|n| n.imp.is_some_and(|i| maya::REGISTRY.iter().any(|m| std::ptr::eq(*m, i))));
    assert!(maya_nodes.count() > 0);
    let warnings = diags.iter().map(|d| d.render(&parsed.sources)).collect();
    Export { shading, warnings }
}

/// Every node of a Maya shader is bound (but the non-shading ones), the only warnings
/// are the shader model's "not implemented" ones for nodes this crate bound or for the
/// non-shading shaders, and each material shades to a finite, opaque, lit colour at a
/// point on the ground; `linked` instances have a light list (each excluding one light).
fn check(name: &str, linked: usize) {
    let e = load(name);
    for node in &e.shading.graph.nodes {
        let decl = node.decl.name.as_str();
        let maya = decl.starts_with("maya_") || decl.starts_with("adsk");
        if maya && !NOT_SHADING.contains(&decl) {
            assert!(node.imp.is_some(), "{name}: {} ({decl}) has no implementation", node.name);
        }
    }
    for w in &e.warnings {
        let bound_later = w.contains("is not implemented by mira");
        assert!(bound_later, "{name}: unexpected warning {w}");
    }
    for (i, m) in e.shading.materials.iter().enumerate() {
        let surface = m.surface.expect("a surface shader");
        let mut s = point([0.3, 0.6]);
        s.material = Some(i as u32);
        let c = run_in(&e.shading, &Empty::default(), surface, s).color();
        assert!(c.is_finite() && c.x > 0.0 && c.y > 0.0 && c.z > 0.0, "{name}: {} gives {c}", m.name);
        assert!((c.w - 1.0).abs() < 1e-5, "{name}: {} alpha {}", m.name, c.w);
    }
    // The ground's instance excludes the point light.
    let lists: Vec<_> = e.shading.instance_lights.iter().flatten().collect();
    assert_eq!(lists.len(), linked, "{name}: instances with a light list");
    assert!(lists.iter().all(|l| l.exclusive && l.lights.len() == 1));
}

#[test]
fn maya2017_export_compiles_and_shades() {
    check("maya2017_export.mi", 1);
}

#[test]
fn maya2012_export_compiles_and_shades() {
    check("maya2012_export.mi", 1);
}

#[test]
fn maya_materials_scene_compiles_and_shades() {
    check("maya_materials.mi", 0);
}
