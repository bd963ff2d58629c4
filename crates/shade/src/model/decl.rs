//! Shader declarations: the parameter types, defaults and result types of every shader a
//! scene uses — from its `declare` statements, with mira's built-in declarations of the
//! standard libraries standing in for ones the scene does not include.

use std::collections::HashMap;
use std::sync::{Arc, OnceLock};

use mi::ast::{self, DeclKind, ParamType};

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

/// Declarations of shaders mira uses internally (never written in scenes).
const INTERNAL: &str = r#"
# A Lambertian surface lit by all lights, with final gathering: the classic engine's
# stand-in for materials it has no mental ray shader for (MDL materials).
declare shader color "mira_diffuse" (color "diffuse", color "emission") end declare
# Glossy reflection jittered around the mirror direction, to compare with mia_material's
# jittered normals.
declare shader color "mira_lobe_reflection" (color "input", color "reflect", scalar "gloss",
    integer "samples" default 16) end declare
"#;

/// mira's built-in declarations (`base.mi`, `physics.mi`, `contour.mi`, `architectural.mi`,
/// `production.mi`, and the internal ones), parsed once.
fn builtin() -> &'static HashMap<String, Arc<Decl>> {
    static BUILTIN: OnceLock<HashMap<String, Arc<Decl>>> = OnceLock::new();
    BUILTIN.get_or_init(|| {
        let mut map = HashMap::new();
        for (name, text) in mi::stdlib::FILES
            .iter()
            .copied()
            .chain([("internal.mi", INTERNAL), ("mdl_base.mi", crate::mdl::DECLARATIONS)])
        {
            let parsed = mi::parse_str(name, text);
            for item in &parsed.items {
                if let ast::Item::Declare(d) = item {
                    map.insert(d.name.text.clone(), Arc::new(Decl::from_ast(d, true)));
                }
            }
        }
        map
    })
}

/// All declarations a scene can use.
#[derive(Clone, Debug, Default)]
pub struct Decls {
    map: HashMap<String, Arc<Decl>>,
}

impl Decls {
    /// The scene's declarations.
    pub fn new<'a>(declarations: impl IntoIterator<Item = &'a ast::Declaration>) -> Decls {
        Decls {
            map: declarations.into_iter().map(|d| (d.name.text.clone(), Arc::new(Decl::from_ast(d, false)))).collect(),
        }
    }

    /// The declaration of `name`: the scene's, else mira's built-in one. A name with an
    /// MDL signature (`mdl::base::f(float,color)`) finds the declaration of `mdl::base::f`.
    pub fn get(&self, name: &str) -> Option<Arc<Decl>> {
        let found = self.map.get(name).or_else(|| builtin().get(name));
        match found {
            Some(d) => Some(d.clone()),
            None if name.contains('(') => self.get(crate::material::declaration_name(name)),
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
