//! The annotations of the MDL materials a scene's shaders instance, for `mira check`: for
//! each material (once, in the order of the names of the shaders that name it) those of its definition
//! and of each annotated parameter, each written as the module writes it with the
//! annotation's absolute name (`::anno::display_name("Paint colour")`).

use mdl_lang::ast::Annotation;
use mdl_lang::{split_mi_name, MdlSearchPath, ModuleSet, Resolution};
use mi::ast::ShaderItem;
use mi::SourceMap;
use scene::Library;

/// The annotations of one MDL material.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialAnnotations {
    /// The material's absolute name (`::pkg::module::material`).
    pub material: String,
    /// The `.mi` shaders that instance it, by name.
    pub shaders: Vec<String>,
    /// The annotations of its definition.
    pub annotations: Vec<String>,
    /// Its annotated parameters: name and annotations, in declaration order.
    pub params: Vec<(String, Vec<String>)>,
}

/// The annotations of the module materials `lib`'s shaders instance, modules found on
/// `search`; materials with no annotation at all are left out, as are materials whose
/// module does not load (the compiler reports those).
pub fn of_scene(lib: &Library, search: MdlSearchPath) -> Vec<MaterialAnnotations> {
    let mut set = ModuleSet::new(search);
    let mut out: Vec<MaterialAnnotations> = Vec::new();
    for (shader, def) in &lib.shaders {
        let Some(ShaderItem::Call { decl, .. }) = def.list.0.first() else { continue };
        let Some((module, item)) = split_mi_name(&decl.text) else { continue };
        let qualified = format!("{module}::{item}");
        if let Some(known) = out.iter_mut().find(|m| m.material == qualified) {
            known.shaders.push(shader.clone());
            continue;
        }
        if set.load(&module).is_err() {
            continue;
        }
        let Some(f) = set.material(&qualified) else { continue };
        let sources = set.sources();
        let annotations: Vec<String> = f.annotations.iter().map(|a| written(a, sources)).collect();
        let params: Vec<(String, Vec<String>)> = f
            .params
            .iter()
            .filter(|p| !p.annotations.is_empty())
            .map(|p| (p.name.clone(), p.annotations.iter().map(|a| written(a, sources)).collect()))
            .collect();
        if annotations.is_empty() && params.is_empty() {
            continue;
        }
        out.push(MaterialAnnotations { material: qualified, shaders: vec![shader.clone()], annotations, params });
    }
    out
}

/// An annotation as written, its name made absolute where it resolved, runs of white space
/// made one space.
fn written(a: &Annotation, sources: &SourceMap) -> String {
    let file = sources.file(a.span.file);
    let text = file.bytes.get(a.span.lo as usize..a.span.hi as usize).unwrap_or_default();
    let text = String::from_utf8_lossy(text);
    let args = text.find('(').map_or("", |i| &text[i..]);
    let name = match &a.res {
        Resolution::Annotation { module, name } => format!("{module}::{name}"),
        _ => a.name.to_string(),
    };
    let args: Vec<&str> = args.split_whitespace().collect();
    format!("{name}{}", args.join(" "))
}
