//! The MDL material compiler: a `.mi` shader instance `"mdl::m::mat" (params)` of a
//! material from a module on the MDL search path becomes a path-engine
//! [`SurfaceMaterial`].
//!
//! The scene's modules (its `$include "x.mdl"` lines, and any module a shader names) are
//! loaded with `mdl_lang` from the search path: the directories of the scene files that
//! include them, `-M DIR`, `MDL_PATHS`. Each instance's parameters bind to the material's
//! parameters (type errors and unknown names are errors at the `.mi` parameter; absent ones
//! take the definition's defaults), the material's expression is evaluated to constants
//! ([`eval`], [`natives`]) and lowered to mira's BSDF families ([`lower`]). What depends on
//! the shading point (`state::` values, `tex::` lookups, `::base` textures and what is
//! computed from them) is compiled once into expression trees ([`hit`], [`hit_natives`])
//! that the path engine evaluates at each hit; textures are read once ([`textures`]). What
//! is not compiled is a warning at the `.mi` instance naming the construct and its module
//! `file:line:col`, and the material is rendered grey.
//!
//! The `::nvidia::core_definitions` materials keep mira's native translation unless a
//! `core_definitions.mdl` on the search path replaces them.

pub mod annotations;
pub mod base_volume;
pub mod connections;
pub mod dds;
pub mod edf_combinators;
pub mod environment;
pub mod eval;
pub mod hit;
pub mod hit_base;
pub mod hit_eq;
pub mod hit_index;
pub mod hit_loop;
pub mod hit_natives;
pub mod lower;
pub mod matrix;
pub mod natives;
pub mod procedural;
pub mod projection;
pub mod ptex;
pub mod sky;
pub mod sky_model;
pub mod spectral;
pub mod state_space;
pub mod statement_loops;
pub mod statements;
pub mod texture_3d;
pub mod texture_cube;
pub mod textures;
pub mod tiles;
pub mod value;
pub mod volume;

use std::collections::HashMap;
use std::path::PathBuf;

use mdl_lang::{split_mi_name, MdlSearchPath, ModuleSet, Resolution, Type};
use mi::ast::{Param, ShaderItem};
use mi::{Diagnostic, Span};
use scene::Library;

use crate::SurfaceMaterial;
use eval::Evaluator;
use textures::Textures;
use value::Value;

/// The module whose materials mira translates natively (unless a file replaces it).
const CORE: &str = "::nvidia::core_definitions";

/// The compiled MDL material instances of a scene, by the place of their `.mi` call.
#[derive(Debug, Default)]
pub struct MdlMaterials {
    by_call: HashMap<(u32, u32), SurfaceMaterial>,
    /// The text of every MDL module file that was read (imports included), in reading
    /// order: what a farm part's scene hash covers besides the `.mi` files.
    pub module_sources: Vec<std::sync::Arc<[u8]>>,
    /// Whether a quad-mesh Ptex file was read: the renderer then keeps the meshes' quad
    /// faces ([`ptex::quad`]).
    pub quad_ptex: bool,
    /// Whether any Ptex file was read: a triangle mesh's Ptex faces are its triangles by
    /// index and corner, so the renderer then keeps every mesh's triangles in their order.
    pub reads_ptex: bool,
}

impl MdlMaterials {
    /// The compiled material of the shader call at `span`, if it is one.
    pub fn get(&self, span: Span) -> Option<&SurfaceMaterial> {
        self.by_call.get(&(span.file.0, span.lo))
    }

    /// How many instances were compiled.
    pub fn len(&self) -> usize {
        self.by_call.len()
    }

    /// Whether none was.
    pub fn is_empty(&self) -> bool {
        self.by_call.is_empty()
    }
}

/// The search path of a scene: the directories of its files that include MDL modules
/// (`Library::mdl_dirs`), then `extra` (`-M DIR`), then `MDL_PATHS`.
pub fn search_path(lib: &Library, extra: &[PathBuf]) -> MdlSearchPath {
    let mut dirs: Vec<PathBuf> = lib.mdl_dirs.clone();
    dirs.extend(extra.iter().cloned());
    MdlSearchPath::from_env(None, &dirs)
}

/// The absolute module name of a `$include` of an MDL module: `"x.mdl"` is `::x`,
/// `"::a::b.mdl"` is `::a::b`, `"a/b.mdl"` is `::b` (the file's own name).
pub(super) fn included_module(written: &str) -> String {
    let stem = written.strip_suffix(".mdl").unwrap_or(written);
    if stem.starts_with("::") {
        return stem.to_string();
    }
    let file = stem.rsplit(['/', '\\']).next().unwrap_or(stem);
    format!("::{file}")
}

/// Compiles every MDL material instance of `lib` (the named shaders whose declaration is
/// `mdl::…`) with modules from `search`. Problems are diagnostics at the `.mi` places.
pub fn compile(lib: &Library, search: MdlSearchPath) -> (MdlMaterials, Vec<Diagnostic>) {
    let mut out = MdlMaterials::default();
    let mut diags = Vec::new();
    let core_on_path = search.find(CORE).is_some();
    let mut texture_dirs = lib.mdl_dirs.clone();
    texture_dirs.extend(search.dirs().iter().cloned());
    let mut textures = Textures::new(texture_dirs);
    let mut set = ModuleSet::new(search);
    // The `::base` functions `.mi` connections may name (a built-in module: it loads).
    let _ = set.load("::base");
    let mut failed: HashMap<String, String> = HashMap::new();
    // Included modules that do not load, with where they were included: reported there
    // unless a shader using them reports it.
    let mut unused_failures = Vec::new();
    for (k, written) in lib.mdl_modules.iter().enumerate() {
        let name = included_module(written);
        if failed.contains_key(&name) {
            continue;
        }
        if let Err(e) = set.load(&name) {
            failed.insert(name.clone(), e.to_string());
            unused_failures.push((name, lib.mdl_module_spans.get(k).copied().unwrap_or_default()));
        }
    }
    for (shader, def) in &lib.shaders {
        let Some(ShaderItem::Call { decl, params, span }) = def.list.0.first() else { continue };
        let Some((module, item)) = split_mi_name(&decl.text) else { continue };
        if module == "::base" || (module == CORE && !core_on_path) {
            continue;
        }
        if set.module(&module).is_none() && !failed.contains_key(&module) {
            if let Err(e) = set.load(&module) {
                failed.insert(module.clone(), e.to_string());
            }
        }
        if let Some(why) = failed.get(&module) {
            diags.push(Diagnostic::warning(
                decl.span,
                format!("MDL module `{module}` could not be loaded; '{shader}' renders grey:\n{why}"),
            ));
            unused_failures.retain(|(m, _)| *m != module);
            continue;
        }
        let qualified = format!("{module}::{item}");
        if set.material(&qualified).is_none() {
            // A function used as a shader (a texture lookup connected to a parameter).
            if set.functions(&qualified).is_empty() {
                diags.push(Diagnostic::error(decl.span, format!("MDL module `{module}` exports no `{item}`")));
            }
            continue;
        }
        let mut warnings = Vec::new();
        let mut cx = Instance { set: &set, lib, textures: &mut textures, diags: &mut diags, warnings: &mut warnings };
        let surface = cx.compile(&qualified, shader, params);
        // What was approximated or not compiled, and texture files with NaN or infinite
        // texels (once per file: the first instance that reads it): warnings at the
        // instance's `.mi` call.
        diags.extend(warnings.into_iter().map(|w| Diagnostic::warning(decl.span, w)));
        diags.extend(textures.warnings.drain(..).map(|w| Diagnostic::warning(decl.span, w)));
        out.by_call.insert((span.file.0, span.lo), surface);
    }
    for (module, span) in unused_failures {
        diags.push(Diagnostic::warning(
            span,
            format!("MDL module `{module}` could not be loaded:\n{}", failed[&module]),
        ));
    }
    out.module_sources = set.sources().files().map(|(_, f)| f.bytes.shared_bytes()).collect();
    out.quad_ptex = textures.read_quad_ptex();
    out.reads_ptex = textures.read_any_ptex();
    (out, diags)
}

/// What compiling one instance reads and writes.
struct Instance<'a> {
    set: &'a ModuleSet,
    lib: &'a Library,
    textures: &'a mut Textures,
    diags: &'a mut Vec<Diagnostic>,
    warnings: &'a mut Vec<String>,
}

impl Instance<'_> {
    /// Compiles one instance of material `qualified` with the `.mi` `params`.
    fn compile(&mut self, qualified: &str, shader: &str, params: &[Param]) -> SurfaceMaterial {
        let set = self.set;
        let diags = &mut *self.diags;
        let warnings = &mut *self.warnings;
        let Some(def) = set.material(qualified) else { return SurfaceMaterial::grey(shader) };
        let enum_value = |ty: &str, name: &str| {
            set.enum_decl(ty).and_then(|e| e.values.iter().find(|v| v.name == name).map(|v| v.value))
        };
        let mut given: Vec<Option<Value>> = vec![None; def.params.len()];
        let mut bad = false;
        let mut ev = Evaluator::new(set, self.textures);
        for p in params {
            let Some((i, decl)) = def.param(&p.name.text) else {
                let known: Vec<&str> = def.params.iter().map(|p| p.name.as_str()).collect();
                diags.push(Diagnostic::error(
                    p.name.span,
                    format!("`{qualified}` has no parameter '{}' (it has: {})", p.name.text, known.join(", ")),
                ));
                bad = true;
                continue;
            };
            if let mi::ast::Value::Connect(target) = &p.value {
                match connections::value(&mut ev, self.lib, &target.text, &decl.ty.ty, 0) {
                    Ok(v) => given[i] = Some(coerce(v, &decl.ty.ty)),
                    Err(why) => diags.push(Diagnostic::warning(
                        p.span,
                        format!(
                            "parameter '{}' of `{qualified}` is connected to '{}', which is not compiled ({why}); its default is used",
                            p.name.text, target.text
                        ),
                    )),
                }
                continue;
            }
            if let (Type::Texture(shape), mi::ast::Value::Str(name)) = (&decl.ty.ty, &p.value) {
                match ev.textures.value_from_mi(*shape, &name.text, self.lib) {
                    Ok(texture) => given[i] = Some(texture),
                    Err(why) => {
                        diags.push(Diagnostic::warning(
                            p.span,
                            format!("parameter '{}' of `{qualified}`: {why}; an invalid texture is used", p.name.text),
                        ));
                        given[i] = Some(textures::invalid(*shape));
                    }
                }
                continue;
            }
            if let (Type::BsdfMeasurement, mi::ast::Value::Str(name)) = (&decl.ty.ty, &p.value) {
                match ev.textures.bsdf_measurement(&name.text, None) {
                    Ok(m) => given[i] = Some(Value::BsdfMeasurement(Some(m))),
                    Err(why) => {
                        diags.push(Diagnostic::warning(
                            p.span,
                            format!(
                                "parameter '{}' of `{qualified}`: {why}; the invalid measurement (no scattering) is used",
                                p.name.text
                            ),
                        ));
                        given[i] = Some(Value::BsdfMeasurement(None));
                    }
                }
                continue;
            }
            if let (Type::LightProfile, mi::ast::Value::Str(name)) = (&decl.ty.ty, &p.value) {
                match ev.textures.profile_from_mi(&name.text, self.lib) {
                    Ok(profile) => given[i] = Some(Value::LightProfile(Some(profile))),
                    Err(why) => {
                        diags.push(Diagnostic::warning(
                            p.span,
                            format!(
                                "parameter '{}' of `{qualified}`: {why}; the invalid light profile (no emission) is used",
                                p.name.text
                            ),
                        ));
                        given[i] = Some(Value::LightProfile(None));
                    }
                }
                continue;
            }
            match value::from_mi(&p.value, &decl.ty.ty, &enum_value) {
                Ok(v) => given[i] = Some(coerce(v, &decl.ty.ty)),
                Err(why) => {
                    diags.push(Diagnostic::error(
                        p.span,
                        format!("parameter '{}' of `{qualified}` is of type `{}`: {why}", p.name.text, decl.ty.ty),
                    ));
                    bad = true;
                }
            }
        }
        if bad {
            // The errors say what is wrong; the material renders grey.
            return SurfaceMaterial::grey(shader);
        }
        let res = Resolution::Material {
            module: qualified.rsplit_once("::").map_or("", |(m, _)| m).to_string(),
            name: def.name.clone(),
            decl: 0,
        };
        let result = ev.complete(def, given, def.span).and_then(|args| ev.call(def, &res, args, def.span));
        match result {
            Ok(v @ Value::Struct(..)) => {
                let mut surface = lower::surface(shader, &v, std::mem::take(&mut ev.leaves), warnings);
                let location = |span| set.sources().location(span);
                (surface.medium, surface.varying_medium) = volume::medium(shader, &v, &location, warnings);
                surface
            }
            Ok(other) => {
                warnings.push(format!(
                    "material '{shader}': `{qualified}` gave {}, not a material; rendered grey",
                    eval::kind(&other)
                ));
                SurfaceMaterial::grey(shader)
            }
            Err(p) => {
                warnings.push(format!(
                    "material '{shader}' (`{qualified}`): {}: {}; rendered grey",
                    set.sources().location(p.span),
                    p.message
                ));
                SurfaceMaterial::grey(shader)
            }
        }
    }
}

/// A `.mi` value converted to the parameter's type where MDL converts implicitly (an int
/// for a float).
fn coerce(v: Value, ty: &Type) -> Value {
    match (v, ty) {
        (Value::Int(i), Type::Scalar(mdl_lang::ast::Scalar::Float | mdl_lang::ast::Scalar::Double)) => {
            Value::Float(i as f64)
        }
        (v, _) => v,
    }
}
