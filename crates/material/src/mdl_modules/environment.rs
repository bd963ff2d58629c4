//! A module's own function as the scene's environment: the `.mi` shader that the camera's
//! `environment` or the options' `environment_function` names calls a function of an MDL
//! module (`color my_env()`, or one returning `base::texture_return`, whose `tint` is
//! taken) that reads `state::direction()`.
//!
//! The function is compiled once, like a function connected to a material parameter
//! ([`super::connections`]): its `.mi` parameters bind to the definition, what does not
//! depend on the direction is folded, and the rest becomes a [`HitExpr`] evaluated for each
//! direction asked for ([`ModuleEnvironment::radiance`]; world space, the direction the
//! environment is looked at along, as MDL's `state::direction()` of an environment call).
//! Every other `state::` value reads as at the origin (position 0, no normal).
//!
//! In the scene's shading the environment becomes a node run by [`MIRA_MDL_ENVIRONMENT`]
//! (the classic engine's environment lookups run it as any environment shader); the path
//! engine takes the compiled function itself ([`of_node`]) and samples it by an importance
//! table baked from it (`render::environment`).

use std::sync::Arc;

use bsdf::Rgb;
use glam::{Vec3A, Vec4};
use mdl_lang::{split_mi_name, MdlSearchPath, ModuleSet, Type};
use mi::ast::{ShaderItem, ShaderList};
use mi::{Diagnostic, Span};
use scene::Library;
use shader::{Color, Ctx, NodeId, RayType, ShaderImpl, Shading, State, Value as ShaderValue};

use super::eval::{kind, Evaluator};
use super::hit::{too_costly, HitExpr};
use super::textures::Textures;
use super::value::Value;

/// A compiled module function giving the environment's radiance along a direction.
#[derive(Clone, Debug)]
pub struct ModuleEnvironment {
    /// The `.mi` shader's name.
    pub shader: String,
    /// The colour, lanes x, y, z.
    expr: Arc<HitExpr>,
}

impl ModuleEnvironment {
    /// An environment that is black everywhere.
    fn black(shader: &str) -> ModuleEnvironment {
        ModuleEnvironment { shader: shader.to_string(), expr: Arc::new(HitExpr::Const(Vec4::ZERO)) }
    }

    /// The radiance seen looking along unit world direction `dir` (non-finite lanes read
    /// as 0).
    pub fn radiance(&self, dir: Vec3A) -> Rgb {
        let state = State { ray_type: RayType::Environment, dir, ..State::default() };
        self.at(&state)
    }

    /// The radiance for the environment ray `state` (its `dir`).
    pub fn at(&self, state: &State) -> Rgb {
        let v = self.expr.eval_finite(state);
        Rgb::new(v.x, v.y, v.z)
    }

    /// Whether it is the same colour along every direction: that colour.
    pub fn constant(&self) -> Option<Rgb> {
        self.expr.constant().map(|v| Rgb::new(v.x, v.y, v.z))
    }
}

/// Compiles the `.mi` shader `shader` of `lib` (a call of a module function) with modules
/// from `search` (the scene's MDL search path); `Err` says why it is not compiled.
pub fn compile(lib: &Library, search: MdlSearchPath, shader: &str) -> Result<ModuleEnvironment, String> {
    let Some(ShaderItem::Call { decl, .. }) = lib.shaders.get(shader).and_then(|d| d.list.0.first()) else {
        return Err(format!("'{shader}' is not a shader call"));
    };
    let Some((module, item)) = split_mi_name(&decl.text) else {
        return Err(format!("'{shader}' is not an MDL function"));
    };
    let mut texture_dirs = lib.mdl_dirs.clone();
    texture_dirs.extend(search.dirs().iter().cloned());
    let mut textures = Textures::new(texture_dirs);
    let mut set = ModuleSet::new(search);
    let _ = set.load("::base");
    for written in &lib.mdl_modules {
        let _ = set.load(&super::included_module(written));
    }
    if set.module(&module).is_none() {
        set.load(&module).map_err(|e| format!("MDL module `{module}` could not be loaded:\n{e}"))?;
    }
    if set.material(&format!("{module}::{item}")).is_some() {
        return Err(format!("`{module}::{item}` is a material, not a function"));
    }
    let mut ev = Evaluator::new(&set, &mut textures);
    let v = super::connections::value(&mut ev, lib, shader, &Type::Color, 0)?;
    let expr = match &v {
        Value::Hit(e, _) => e.clone(),
        other => match other.color() {
            Some(c) => Arc::new(HitExpr::Const(Vec4::new(c.x, c.y, c.z, 0.0))),
            None => return Err(format!("`{module}::{item}` gives {}, not a colour", kind(other))),
        },
    };
    if let Some(why) = too_costly(&expr) {
        return Err(why);
    }
    Ok(ModuleEnvironment { shader: shader.to_string(), expr })
}

/// `mira_mdl_environment`: runs the compiled module function stored for its node
/// ([`attach`]) along the ray's direction.
pub static MIRA_MDL_ENVIRONMENT: ShaderImpl =
    ShaderImpl { name: "mira_mdl_environment", params: &[], run: run_environment, ..ShaderImpl::PLAIN };

fn run_environment(ctx: &mut Ctx, node: NodeId, result: &mut ShaderValue) -> bool {
    let Some(env) = of_node(ctx.shading(), node) else { return false };
    let c = env.at(&ctx.state);
    *result = ShaderValue::Color(Color::new(c.x, c.y, c.z, 1.0));
    true
}

/// The compiled module function of node `node` of `shading`, if [`attach`] made it one.
pub fn of_node(shading: &Shading, node: NodeId) -> Option<Arc<ModuleEnvironment>> {
    let n = shading.graph.nodes.get(node as usize)?;
    if !n.imp.is_some_and(|imp| std::ptr::eq(imp, &MIRA_MDL_ENVIRONMENT)) {
        return None;
    }
    shading.precomputed.get_or_init(node, || ModuleEnvironment::black(&n.name))
}

/// The named shader the scene's environment is: the head of the camera's `environment`
/// list when it names one, else the options' `environment_function`.
fn environment_shader(scene: &scene::Scene) -> Option<String> {
    let named = |list: &ShaderList| match list.0.first()? {
        ShaderItem::Ref(name) => Some(name.text.clone()),
        ShaderItem::Define { name, .. } => Some(name.text.clone()),
        ShaderItem::Call { .. } => None,
    };
    match &scene.camera.environment {
        Some(list) => named(list),
        None => match scene.options.attributes.get("environment_function") {
            Some(scene::values::AttrValue::Str(name)) => Some(name.clone()),
            _ => None,
        },
    }
}

/// Makes the scene's environment a module function where it names one (see the module
/// comment): compiles it with modules from `search`, and runs it at the environment's
/// node (the node the declaration gave, or a new one where the scene does not declare the
/// function). The warnings `diags` hold for the environment's shader (not implemented,
/// no shader) are replaced by nothing when it compiles, else by one saying why it does not.
pub fn attach(shading: &mut Shading, scene: &scene::Scene, search: MdlSearchPath, diags: &mut Vec<Diagnostic>) {
    let Some(name) = environment_shader(scene) else { return };
    let lib = &scene.library;
    let Some(ShaderItem::Call { decl, span, .. }) = lib.shaders.get(&name).and_then(|d| d.list.0.first()) else {
        return;
    };
    if split_mi_name(&decl.text).is_none() {
        return;
    }
    // The node the declaration gave the shader, if the scene declares it.
    let head = match (shading.environment, shading.graph.named.get(&name).copied()) {
        (Some(e), Some(n)) if e == n => Some(e),
        // Something else is the environment.
        (Some(_), _) => return,
        (None, _) => None,
    };
    // A shader mira implements (`mdl::base::sun_and_sky`): nothing to do.
    if head.is_some_and(|n| shading.graph.nodes[n as usize].imp.is_some()) {
        return;
    }
    let (decl_span, call_span) = (decl.span, *span);
    match compile(lib, search, &name) {
        Ok(env) => {
            let node = match head {
                Some(n) => n,
                None => {
                    let Some(n) = push_node(shading, &name, call_span) else { return };
                    shading.environment = Some(n);
                    n
                }
            };
            shading.graph.nodes[node as usize].imp = Some(&MIRA_MDL_ENVIRONMENT);
            shading.precomputed.get_or_init(node, || env);
            diags.retain(|d| !is_environment_warning(d, &name, decl_span, call_span));
        }
        Err(why) => {
            diags.retain(|d| !is_environment_warning(d, &name, decl_span, call_span));
            diags.push(Diagnostic::warning(
                decl_span,
                format!("environment '{name}' (`{}`) is not compiled: {why}; no environment", decl.text),
            ));
        }
    }
}

/// Whether `d` is the shading's warning that the environment shader `name` is not
/// implemented or no shader.
fn is_environment_warning(d: &Diagnostic, name: &str, decl_span: Span, call_span: Span) -> bool {
    let at = d.span == decl_span || d.span == call_span;
    (at && d.message.contains("is not implemented by mira"))
        || d.message.contains(&format!("environment_function names '{name}', which is no shader"))
}

/// A node of its own for the environment shader `name` (a module function the scene does
/// not declare).
fn push_node(shading: &mut Shading, name: &str, span: Span) -> Option<NodeId> {
    let text = "declare shader color \"mira_mdl_environment\" () end declare";
    let parsed = mi::parse_str("internal.mi", text);
    let Some(mi::ast::Item::Declare(d)) = parsed.items.first() else { return None };
    let decl = shader::decl::Decl {
        name: d.name.text.clone(),
        kind: d.kind,
        ret: d.ret.clone(),
        params: Vec::new(),
        source: Arc::new(d.clone()),
        builtin: true,
    };
    let nodes = &mut shading.graph.nodes;
    nodes.push(shader::graph::Node {
        name: Arc::from(name),
        decl: Arc::new(decl),
        imp: Some(&MIRA_MDL_ENVIRONMENT),
        slots: Vec::new(),
        next: None,
        span,
    });
    Some((nodes.len() - 1) as NodeId)
}
