//! The stand-in for a shader no one can provide (a third-party plug-in an export calls):
//! which of its parameters carries the colour a user would expect to see.
//!
//! The shader model drops a call to an undeclared shader with a warning. The stand-in
//! this module chooses is meant to replace that: the call becomes mira's Lambertian
//! `mira_diffuse` node whose `diffuse` is the chosen parameter (a constant, or the
//! connection the export wrote), and the warning names the shader, its line and the
//! parameter used, so the surface is never a silent black or white. Plugging it in is a
//! change to the shader model's graph builder (its undeclared-shader branch can call
//! [`choose`] on the call's parameters and build the node with `Builder::internal`).
//!
//! A plug-in shader the scene declares itself does get a node; [`attach_stand_ins`] gives
//! such nodes, where they serve as materials, the stand-in [`STANDIN`] now.

use mi::ast::{Param, Value};
use mi::Diagnostic;
use shader::{Ctx, NodeId, RayType, ShaderImpl, Shading, Slot};

use crate::light::light_role;
use crate::values::{rgb, rgba, write_struct};

/// Parameter names that carry a surface's colour, best first (matched ignoring case).
pub const COLOR_PARAMETERS: &[&str] = &[
    "color",
    "diffuse_color",
    "diffuseColor",
    "base_color",
    "baseColor",
    "diffuse",
    "Kd",
    "albedo",
    "tint",
    "surface_color",
    "outColor",
];

/// The colour the stand-in shows.
#[derive(Clone, Debug, PartialEq)]
pub enum StandInColor {
    /// A constant colour (linear RGB), from a colour or a single number (grey).
    Constant([f32; 3]),
    /// The shader (and member) the parameter is connected to: `"shader.member"`.
    Connected(String),
}

/// The parameter a stand-in takes its colour from.
#[derive(Clone, Debug, PartialEq)]
pub struct StandIn {
    /// The parameter's name as written.
    pub parameter: String,
    /// Its colour.
    pub color: StandInColor,
}

/// The colour a parameter value gives, if it can stand for one.
fn color_of(v: &Value) -> Option<StandInColor> {
    match v {
        Value::Num(n) => {
            let g = n.as_f64() as f32;
            Some(StandInColor::Constant([g; 3]))
        }
        Value::Tuple(t) if t.len() >= 3 => {
            Some(StandInColor::Constant([t[0].as_f64() as f32, t[1].as_f64() as f32, t[2].as_f64() as f32]))
        }
        Value::Connect(name) => Some(StandInColor::Connected(name.text.clone())),
        _ => None,
    }
}

/// Chooses the stand-in colour among a call's parameters: the first name of
/// [`COLOR_PARAMETERS`] the call gives with a usable value, else `None` (the caller
/// then uses mid grey and says so).
pub fn choose(params: &[Param]) -> Option<StandIn> {
    COLOR_PARAMETERS.iter().find_map(|want| {
        params
            .iter()
            .filter(|p| p.name.text.eq_ignore_ascii_case(want))
            .find_map(|p| color_of(&p.value).map(|color| StandIn { parameter: p.name.text.clone(), color }))
    })
}

/// Why a shader gets a stand-in, for the warning.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Missing {
    /// The scene calls a shader nothing declares (its library was not included).
    Undeclared,
    /// The scene declares the shader but mira has no implementation of it.
    Unimplemented,
}

/// The warning for shader `decl` replaced by a stand-in showing `parameter` (or mid grey).
pub fn warning(decl: &str, missing: Missing, parameter: Option<&str>) -> String {
    let why = match missing {
        Missing::Undeclared => "is not declared (a plug-in mira does not have)",
        Missing::Unimplemented => "is not implemented by mira (a plug-in's shader)",
    };
    match parameter {
        Some(p) => format!("shader '{decl}' {why}; it is shown as a diffuse surface of its '{p}'"),
        None => format!("shader '{decl}' {why} and has no colour parameter; it is shown as a mid grey diffuse surface"),
    }
}

/// The stand-in shader: a Lambertian surface (albedo the chosen colour, mental ray's
/// light units: c·I·cos θ) lit by the instance's lights and by final gathering's
/// irradiance over π (as Maya's materials take it), opaque. Its one slot holds the
/// chosen parameter.
pub static STANDIN: ShaderImpl =
    ShaderImpl { name: "(stand-in)", params: &["color"], run: stand_in, ..ShaderImpl::PLAIN };

fn stand_in(ctx: &mut Ctx, n: NodeId, out: &mut shader::Value) -> bool {
    if !ctx.state.ray_type.is_visible() || ctx.state.ray_type == RayType::Shadow {
        return false;
    }
    let color = rgb(ctx.color(n, 0));
    let mut lit = glam::Vec3A::ZERO;
    for light in ctx.instance_lights() {
        if !light_role(ctx, light).diffuse {
            continue;
        }
        let mut lp = ctx.light_loop(light);
        let mut sum = glam::Vec3A::ZERO;
        while let Some(s) = ctx.sample_light(&mut lp) {
            sum += rgb(s.color) * s.dot_nl.max(0.0);
        }
        if lp.samples > 0 {
            lit += sum / lp.samples as f32;
        }
    }
    lit += rgb(ctx.compute_irradiance()) * std::f32::consts::FRAC_1_PI;
    let c = shader::Value::Color(rgba(color * lit, 1.0));
    match out {
        shader::Value::Struct(m) => {
            // The declared result's colour member: outColor (Maya), else the first.
            let name = m.iter().find(|(n, _)| &**n == "outColor").or(m.first()).map(|(n, _)| n.clone());
            if let Some(name) = name {
                write_struct(out, &[(&name, c)]);
            }
        }
        _ => *out = c,
    }
    true
}

/// Gives every material shader of `shading` that has no implementation — a plug-in's
/// shader declared in the scene — the stand-in [`STANDIN`] with the colour parameter
/// [`COLOR_PARAMETERS`] finds among its declared parameters (its value or connection as
/// the scene gives it; mid grey when there is none). The candidates are the surface
/// shaders of materials and the materials connected to Maya shading engines. Returns a
/// warning for each, at the shader's position. Call after [`crate::attach`].
pub fn attach_stand_ins(shading: &mut Shading) -> Vec<Diagnostic> {
    let graph = &shading.graph;
    let mut candidates: Vec<NodeId> = shading.materials.iter().filter_map(|m| m.surface).collect();
    for node in &graph.nodes {
        let name = node.decl.name.as_str();
        if name == "maya_shadingengine" || name == "adskMayaShadingEngine" {
            if let Some(Slot::Connect { node: material, .. }) = node.slots.first() {
                candidates.push(*material);
            }
        }
    }
    candidates.sort_unstable();
    candidates.dedup();
    let mut warnings = Vec::new();
    for id in candidates {
        let node = &mut shading.graph.nodes[id as usize];
        if node.imp.is_some() || node.decl.kind != mi::ast::DeclKind::Shader {
            continue;
        }
        let chosen = COLOR_PARAMETERS.iter().find_map(|want| {
            node.decl.params.iter().position(|p| p.name.eq_ignore_ascii_case(want)).and_then(|i| {
                let usable = matches!(
                    node.slots.get(i),
                    Some(Slot::Connect { .. }) | Some(Slot::Value(shader::Value::Color(_) | shader::Value::Scalar(_)))
                );
                usable.then(|| (node.decl.params[i].name.to_string(), node.slots[i].clone()))
            })
        });
        let (parameter, slot) = match chosen {
            Some((p, slot)) => (Some(p), slot),
            None => (None, Slot::Value(shader::Value::Color(glam::Vec4::new(0.5, 0.5, 0.5, 1.0)))),
        };
        let message = warning(&node.decl.name, Missing::Unimplemented, parameter.as_deref());
        warnings.push(Diagnostic::warning(node.span, message));
        node.slots = vec![slot];
        node.imp = Some(&STANDIN);
    }
    warnings
}

#[cfg(test)]
mod tests {
    use super::*;
    use mi::ast::{Item, ShaderItem};

    fn params_of(text: &str) -> Vec<Param> {
        let parsed = mi::parse_str("t.mi", text);
        for item in parsed.items {
            if let Item::Shader(def) = item {
                if let Some(ShaderItem::Call { params, .. }) = def.list.0.into_iter().next() {
                    return params;
                }
            }
        }
        panic!("no shader in {text}");
    }

    #[test]
    fn chooses_the_expected_colour_parameter() {
        let p = params_of(r#"shader "s" "vendor_mtl" ("roughness" 0.3, "Base_Color" 0.8 0.2 0.1, "tint" 1 1 1)"#);
        assert_eq!(
            choose(&p),
            Some(StandIn { parameter: "Base_Color".into(), color: StandInColor::Constant([0.8, 0.2, 0.1]) })
        );
        let p = params_of(r#"shader "s" "vendor_mtl" ("outColor" = "file1.outColor", "glow" 1)"#);
        assert_eq!(choose(&p).map(|s| s.color), Some(StandInColor::Connected("file1.outColor".into())));
        let p = params_of(r#"shader "s" "vendor_mtl" ("diffuse" 0.25)"#);
        assert_eq!(choose(&p).map(|s| s.color), Some(StandInColor::Constant([0.25; 3])));
        let p = params_of(r#"shader "s" "vendor_mtl" ("roughness" 0.3)"#);
        assert_eq!(choose(&p), None);
        assert!(warning("vendor_mtl", Missing::Undeclared, None).contains("'vendor_mtl' is not declared"));
        assert!(warning("vendor_mtl", Missing::Unimplemented, Some("tint")).ends_with("of its 'tint'"));
    }
}
