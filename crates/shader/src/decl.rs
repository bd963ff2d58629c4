//! Shader declarations: the parameter types, defaults and result types of every shader a
//! scene uses — from its `declare` statements, with mira's built-in declarations of the
//! standard libraries standing in for ones the scene does not include.

use std::collections::HashMap;
use std::sync::{Arc, OnceLock};

use mi::ast::{self, DeclKind, ParamType};

use crate::Implementation;

/// One declared parameter.
#[derive(Clone, Debug)]
pub struct DeclParam {
    /// Its name.
    pub name: Arc<str>,
    /// Its type.
    pub ty: ParamType,
    /// `default …`, if declared.
    pub default: Option<ast::Value>,
}

/// A shader or phenomenon declaration.
#[derive(Clone, Debug)]
pub struct Decl {
    /// The declared name.
    pub name: String,
    /// Shader, phenomenon or data.
    pub kind: DeclKind,
    /// The result type (`None`: colour).
    pub ret: Option<ParamType>,
    /// Parameters in declaration order.
    pub params: Vec<DeclParam>,
    /// The whole declaration (a phenomenon's body is read from it).
    pub source: Arc<ast::Declaration>,
    /// Comes from mira's built-in declarations, not from the scene.
    pub builtin: bool,
}

impl Decl {
    fn from_ast(d: &ast::Declaration, builtin: bool) -> Decl {
        Decl {
            name: d.name.text.clone(),
            kind: d.kind,
            ret: d.ret.clone(),
            params: d
                .params
                .iter()
                .map(|p| DeclParam {
                    name: Arc::from(p.name.text.as_str()),
                    ty: p.ty.clone(),
                    default: p.default.clone(),
                })
                .collect(),
            source: Arc::new(d.clone()),
            builtin,
        }
    }

    /// Index of parameter `name`.
    pub fn param(&self, name: &str) -> Option<usize> {
        self.params.iter().position(|p| &*p.name == name)
    }

    /// The names of a struct result's members, in order.
    pub fn members(&self) -> Vec<Arc<str>> {
        match &self.ret {
            Some(ParamType::Struct(fields)) => fields.iter().map(|f| Arc::from(f.name.text.as_str())).collect(),
            _ => Vec::new(),
        }
    }
}

/// The declaration name without an MDL signature (`mdl::base::x(float,…)` → `mdl::base::x`).
pub fn declaration_name(decl: &str) -> &str {
    decl.split('(').next().unwrap_or(decl)
}

/// Declarations of shaders the model itself uses (never written in scenes).
const INTERNAL: &str = r#"
# A Lambertian surface lit by all lights, with final gathering: the classic engine's
# stand-in for materials it has no mental ray shader for (MDL materials). A library
# implements it (the base library does).
declare shader color "mira_diffuse" (color "diffuse", color "emission") end declare
# The classic engine's form of a material with a path-engine BSDF (MDL module materials):
# the renderer gives the BSDF per hit; the parameters are the stand-in's, its fallback.
declare shader color "mira_bsdf_material" (color "diffuse", color "emission") end declare
"#;

/// What a render has built in: declarations (mental ray's standard `.mi` files, the
/// model's internal ones and those the libraries bring) and the shader implementations, by
/// name. Made once per set of libraries (see [`Registry`](crate::Registry)).
#[derive(Debug, Default)]
pub struct Builtins {
    declarations: HashMap<String, Arc<Decl>>,
    shaders: HashMap<&'static str, Implementation>,
}

impl Builtins {
    /// The standard declarations, those of `texts` (`(file name, .mi text)`), and
    /// `shaders` (the first of two with one name wins).
    pub fn new<'t>(texts: impl IntoIterator<Item = (&'t str, &'t str)>, shaders: &[Implementation]) -> Builtins {
        let mut declarations = HashMap::new();
        let all = mi::stdlib::FILES.iter().copied().chain([("internal.mi", INTERNAL)]).chain(texts);
        for (name, text) in all {
            for item in &mi::parse_str(name, text).items {
                if let ast::Item::Declare(d) = item {
                    declarations.insert(d.name.text.clone(), Arc::new(Decl::from_ast(d, true)));
                }
            }
        }
        let mut by_name = HashMap::new();
        for imp in shaders {
            by_name.entry(imp.name).or_insert(*imp);
        }
        Builtins { declarations, shaders: by_name }
    }

    /// The standard declarations alone, no implementation (shared).
    pub fn standard() -> Arc<Builtins> {
        static STANDARD: OnceLock<Arc<Builtins>> = OnceLock::new();
        STANDARD.get_or_init(|| Arc::new(Builtins::new([], &[]))).clone()
    }

    /// The built-in declaration of `name` (exactly as named).
    pub fn declaration(&self, name: &str) -> Option<&Arc<Decl>> {
        self.declarations.get(name)
    }

    /// The implementation of the declared shader `name` (an MDL signature is ignored).
    pub fn implementation(&self, name: &str) -> Option<Implementation> {
        self.shaders.get(declaration_name(name)).copied()
    }
}

/// All declarations a scene can use.
#[derive(Clone, Debug)]
pub struct Decls {
    map: HashMap<String, Arc<Decl>>,
    builtins: Arc<Builtins>,
}

impl Default for Decls {
    /// mental ray's standard declarations, no library's.
    fn default() -> Decls {
        Decls::new([], Builtins::standard())
    }
}

impl Decls {
    /// The scene's declarations, over `builtins`.
    pub fn new<'a>(declarations: impl IntoIterator<Item = &'a ast::Declaration>, builtins: Arc<Builtins>) -> Decls {
        Decls {
            map: declarations.into_iter().map(|d| (d.name.text.clone(), Arc::new(Decl::from_ast(d, false)))).collect(),
            builtins,
        }
    }

    /// The implementation of the declared shader `name`, if a library has one.
    pub fn implementation(&self, name: &str) -> Option<Implementation> {
        self.builtins.implementation(name)
    }

    /// The declaration of `name`: the scene's, else mira's built-in one. A name with an
    /// MDL signature (`mdl::base::f(float,color)`) finds the declaration of `mdl::base::f`.
    pub fn get(&self, name: &str) -> Option<Arc<Decl>> {
        let found = self.map.get(name).or_else(|| self.builtins.declaration(name));
        match found {
            Some(d) => Some(d.clone()),
            None if name.contains('(') => self.get(declaration_name(name)),
            None => None,
        }
    }

    /// Whether the scene itself declares `name`.
    pub fn declared_by_scene(&self, name: &str) -> bool {
        self.map.contains_key(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_declarations_cover_the_base_library() {
        let decls = Decls::default();
        let phong = decls.get("mib_illum_phong").expect("declared");
        let names: Vec<&str> = phong.params.iter().map(|p| &*p.name).collect();
        assert_eq!(names, ["ambience", "ambient", "diffuse", "specular", "exponent", "mode", "lights"]);
        assert!(matches!(&phong.params[6].ty, ParamType::Array(t) if **t == ParamType::Light));
        let rotate = decls.get("mib_texture_rotate").unwrap();
        assert_eq!(rotate.members().iter().map(|m| &**m).collect::<Vec<_>>(), ["u", "v"]);
        assert!(decls.get("mia_material_x").is_some());
    }
}
