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

use mi::ast::{Param, Value};

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

/// The warning for an unknown shader `decl` replaced by a stand-in.
pub fn warning(decl: &str, stand_in: Option<&StandIn>) -> String {
    match stand_in {
        Some(s) => format!(
            "shader '{decl}' is not declared (a plug-in mira does not have); it is shown as a diffuse surface of its '{}'",
            s.parameter
        ),
        None => format!(
            "shader '{decl}' is not declared (a plug-in mira does not have) and has no colour parameter; it is shown as mid grey"
        ),
    }
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
        assert!(warning("vendor_mtl", None).contains("vendor_mtl"));
    }
}
