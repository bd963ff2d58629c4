//! A module's own function as an environment: the `.mi` shader that the camera's
//! `environment` or the options' `environment_function` names — or the call written
//! inline as the camera's `environment` — calls a function of an MDL module (`color
//! my_env()`, or one returning `base::texture_return`, whose `tint` is taken) that reads
//! `state::direction()`. A material's own `environment` (named or inline) may be one too:
//! the classic engine's rays leaving the scene from that material then look it up, as
//! mental ray's do.
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
use super::sky_model::SkyCall;
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

    /// The `::base` daylight environments (`sun_and_sky`, `perez_sun_and_sky`) its function
    /// calls, each once, in the order found (the path engine samples their suns).
    pub fn sky_calls(&self) -> Vec<Arc<SkyCall>> {
        let mut seen = std::collections::HashSet::new();
        let mut stack = vec![&self.expr];
        let mut calls: Vec<Arc<SkyCall>> = Vec::new();
        while let Some(e) = stack.pop() {
            if !seen.insert(Arc::as_ptr(e)) {
                continue;
            }
            if let HitExpr::Sky(call, _) = &**e {
                if !calls.iter().any(|c| Arc::ptr_eq(c, call)) {
                    calls.push(call.clone());
                }
            }
            stack.extend(e.operands());
        }
        calls
    }
}

/// Compiles the `.mi` shader `shader` of `lib` (a call of a module function) with modules
/// from `search` (the scene's MDL search path); `Err` says why it is not compiled.
pub fn compile(lib: &Library, search: MdlSearchPath, shader: &str) -> Result<ModuleEnvironment, String> {
    let Some(ShaderItem::Call { decl, params, .. }) = lib.shaders.get(shader).and_then(|d| d.list.0.first()) else {
        return Err(format!("'{shader}' is not a shader call"));
    };
    compile_call(lib, search, shader, &decl.text, params)
}

/// Compiles a call of the module function `decl` (`mdl::module::function`) with the
/// `.mi` parameters `params` (a shader named `shader` in messages, or written inline).
pub fn compile_call(
    lib: &Library,
    search: MdlSearchPath,
    shader: &str,
    decl: &str,
    params: &[mi::ast::Param],
) -> Result<ModuleEnvironment, String> {
    let Some((module, item)) = split_mi_name(decl) else {
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
    let v = super::connections::call_value(&mut ev, lib, shader, decl, params, &Type::Color, 0)?;
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

/// The call at the head of an environment shader list: the named shader it refers to (its
/// name, the definition's call) or the call written inline (no name).
struct EnvCall<'a> {
    /// The named shader's name, `None` for an inline call.
    name: Option<String>,
    /// The declaration called (`mdl::module::function`).
    decl: &'a mi::ast::Name,
    /// Its `.mi` parameters.
    params: &'a [mi::ast::Param],
    /// The whole call.
    span: Span,
}

/// The call at the head of `list` (a reference to a named shader, a shader defined in
/// place, or an inline call), if it calls an MDL module function.
fn head_call<'a>(lib: &'a Library, list: &'a ShaderList) -> Option<EnvCall<'a>> {
    let named = |name: &str| -> Option<EnvCall<'a>> {
        let def = lib.shaders.get(name)?;
        let Some(ShaderItem::Call { decl, params, span }) = def.list.0.first() else { return None };
        Some(EnvCall { name: Some(name.to_string()), decl, params, span: *span })
    };
    let call = match list.0.first()? {
        ShaderItem::Ref(name) => named(&name.text)?,
        ShaderItem::Define { name, .. } => named(&name.text)?,
        ShaderItem::Call { decl, params, span } => EnvCall { name: None, decl, params, span: *span },
    };
    split_mi_name(&call.decl.text).is_some().then_some(call)
}

/// The call the scene's environment is: the head of the camera's `environment` list,
/// else the call the options' `environment_function` names.
fn environment_call(scene: &scene::Scene) -> Option<EnvCall<'_>> {
    let lib = &scene.library;
    match &scene.camera.environment {
        Some(list) => head_call(lib, list),
        None => match scene.options.attributes.get("environment_function") {
            Some(scene::values::AttrValue::Str(name)) => {
                let def = lib.shaders.get(name)?;
                let Some(ShaderItem::Call { decl, params, span }) = def.list.0.first() else { return None };
                split_mi_name(&decl.text).is_some().then(|| EnvCall {
                    name: Some(name.clone()),
                    decl,
                    params,
                    span: *span,
                })
            }
            _ => None,
        },
    }
}

/// The node of the shading that runs `call` when it heads a list whose node is `current`:
/// `Ok(Some(node))` where the scene declares the function (the node the declaration
/// gave), `Ok(None)` where no node runs it, `Err(())` where `current` is something else.
fn node_of(shading: &Shading, call: &EnvCall, current: Option<NodeId>) -> Result<Option<NodeId>, ()> {
    let Some(e) = current else { return Ok(None) };
    let same = match &call.name {
        Some(name) => shading.graph.named.get(name) == Some(&e),
        None => shading.graph.nodes.get(e as usize).is_some_and(|n| n.span == call.span),
    };
    if same {
        Ok(Some(e))
    } else {
        Err(())
    }
}

/// Makes the environments that name module functions run them (see the module comment):
/// the scene's (the camera's `environment`, named or inline, or the options'
/// `environment_function`) and the materials' own `environment`s. Each is compiled with
/// modules from `search` and run at its node (the node the declaration gave, or a new one
/// where the scene does not declare the function). The warnings `diags` hold for such a
/// shader (not implemented, no shader) are replaced by nothing when it compiles, else by
/// one saying why it does not.
pub fn attach(shading: &mut Shading, scene: &scene::Scene, search: MdlSearchPath, diags: &mut Vec<Diagnostic>) {
    if let Some(call) = environment_call(scene) {
        if let Some(node) = attach_call(shading, &scene.library, search.clone(), &call, shading.environment, diags) {
            shading.environment = Some(node);
        }
    }
    for (i, m) in scene.materials.iter().enumerate() {
        let scene::MaterialKind::Material(defs) = &m.kind else { continue };
        let Some(list) = defs.last().and_then(|d| {
            d.stmts.iter().rev().find_map(|s| match s {
                mi::ast::Stmt::Kw(k) if k.key == "environment" => match k.args.first() {
                    Some(mi::ast::Arg::Shaders(l)) => Some(l),
                    _ => None,
                },
                _ => None,
            })
        }) else {
            continue;
        };
        let Some(call) = head_call(&scene.library, list) else { continue };
        let Some(current) = shading.materials.get(i).map(|s| s.environment) else { continue };
        if let Some(node) = attach_call(shading, &scene.library, search.clone(), &call, current, diags) {
            shading.materials[i].environment = Some(node);
        }
    }
}

/// Compiles `call` (heading a list whose node is `current`) and runs it at its node; the
/// node, `None` where nothing changes (another shader, one mira implements, or a call
/// that does not compile, warned about).
fn attach_call(
    shading: &mut Shading,
    lib: &Library,
    search: MdlSearchPath,
    call: &EnvCall,
    current: Option<NodeId>,
    diags: &mut Vec<Diagnostic>,
) -> Option<NodeId> {
    let head = node_of(shading, call, current).ok()?;
    // A shader mira implements (`mdl::base::sun_and_sky`): nothing to do.
    if head.is_some_and(|n| shading.graph.nodes[n as usize].imp.is_some()) {
        return None;
    }
    let label = call.name.clone().unwrap_or_else(|| call.decl.text.clone());
    let (decl_span, call_span) = (call.decl.span, call.span);
    diags.retain(|d| !is_environment_warning(d, &label, decl_span, call_span));
    match compile_call(lib, search, &label, &call.decl.text, call.params) {
        Ok(env) => {
            let node = match head {
                Some(n) => n,
                None => push_node(shading, &label, call_span)?,
            };
            shading.graph.nodes[node as usize].imp = Some(&MIRA_MDL_ENVIRONMENT);
            shading.precomputed.get_or_init(node, || env);
            Some(node)
        }
        Err(why) => {
            diags.push(Diagnostic::warning(
                decl_span,
                format!("environment '{label}' (`{}`) is not compiled: {why}; no environment", call.decl.text),
            ));
            None
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
