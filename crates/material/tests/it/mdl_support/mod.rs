//! What the MDL compiler's tests share: compiling a `.mi` fragment whose shaders are
//! instances of the test modules (tests/mdl/, scenes/mdl/), and finding a compiled material;
//! the per-hit tests' shading points ([`per_hit`]).
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use bsdf::Rgb;
use material::mdl_modules::{compile, MdlMaterials};
use material::SurfaceMaterial;
use mdl_lang::MdlSearchPath;
use mi::ast::ShaderItem;

pub mod per_hit;

/// The test modules' directories (the MDL search path of the tests).
pub fn dirs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    vec![root.join("tests/mdl"), root.join("../../scenes/mdl")]
}

/// Compiles the shaders of `text` (a `.mi` fragment): the compiled set, the library and
/// the rendered diagnostics.
pub fn compile_text(text: &str) -> (MdlMaterials, scene::Library, Vec<String>) {
    compile_text_with(text, &[])
}

/// [`compile_text`] with `more` directories searched after the test modules'.
pub fn compile_text_with(text: &str, more: &[PathBuf]) -> (MdlMaterials, scene::Library, Vec<String>) {
    let full = format!(
        "{text}\noptions \"o\" end options\ncamera \"test_cam\" end camera\ninstance \"ci\" \"test_cam\" end instance\n\
         instgroup \"root\" \"ci\" end instgroup\nrender \"root\" \"ci\" \"o\"\n"
    );
    let parsed = mi::parse_str("t.mi", &full);
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    let mut search = dirs();
    search.extend(more.iter().cloned());
    let (mdl, found) = compile(&scene.library, MdlSearchPath::for_scene(None, &search, None));
    diags.extend(found);
    let rendered = diags.iter().map(|d| d.render(&parsed.sources)).collect();
    (mdl, scene.library, rendered)
}

/// The compiled material of shader `name`.
pub fn get<'a>(mdl: &'a MdlMaterials, lib: &scene::Library, name: &str) -> &'a SurfaceMaterial {
    let Some(ShaderItem::Call { span, .. }) = lib.shaders[name].list.0.first() else { panic!("no call") };
    mdl.get(*span).unwrap_or_else(|| panic!("'{name}' was not compiled"))
}

/// Whether two colours differ by at most `tol` in every channel.
pub fn close(a: Rgb, b: Rgb, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol
}
