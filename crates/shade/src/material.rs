//! Surface materials for the path integrator, translated from the scene's materials.
//!
//! This is the first step of the translation: every material becomes a two-sided
//! Lambertian surface with an optional emission. MDL `flex_material` keeps its
//! `base_color` (the diffuse layer; its glossy layers come with the unified material),
//! MDL `diffuse` its `diffuse_color`, and the mental ray illumination shaders
//! (`mib_illum_*`) their `diffuse` colour. Anything else is a grey diffuse surface, with a
//! warning naming what was not understood.

use mi::ast::{Num, Param, ShaderItem, Value};
use scene::{Library, Material, MaterialKind};

use crate::bsdf::{Bsdf, Lambert};
use crate::Rgb;

/// A surface's scattering and emission.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceMaterial {
    /// The material's name.
    pub name: String,
    /// Diffuse reflectance.
    pub diffuse: Rgb,
    /// Emitted radiance (W·m⁻²·sr⁻¹ in scene units), both sides.
    pub emission: Rgb,
}

impl SurfaceMaterial {
    /// A grey diffuse surface (the fallback for what is not understood).
    pub fn grey(name: &str) -> SurfaceMaterial {
        SurfaceMaterial { name: name.to_string(), diffuse: Rgb::splat(0.5), emission: Rgb::ZERO }
    }

    /// The BSDF at a shading point.
    pub fn bsdf(&self) -> Bsdf {
        Bsdf::Lambert(Lambert { albedo: self.diffuse })
    }
}

/// The declaration name without an MDL signature (`mdl::base::x(float,…)` → `mdl::base::x`).
pub fn declaration_name(decl: &str) -> &str {
    decl.split('(').next().unwrap_or(decl)
}

/// A constant colour parameter (`"p" r g b [a]` or a single grey value).
pub fn color_param(params: &[Param], name: &str) -> Option<Result<Rgb, String>> {
    let p = params.iter().rev().find(|p| p.name.text == name)?;
    Some(match &p.value {
        Value::Tuple(v) if v.len() >= 3 => {
            Ok(Rgb::new(v[0].as_f64() as f32, v[1].as_f64() as f32, v[2].as_f64() as f32))
        }
        Value::Num(n) => Ok(Rgb::splat(n.as_f64() as f32)),
        Value::Connect(c) => Err(format!("'{name}' is connected to '{}'", c.text)),
        _ => Err(format!("'{name}' is not a colour")),
    })
}

/// A constant scalar parameter.
pub fn scalar_param(params: &[Param], name: &str) -> Option<f64> {
    params.iter().rev().find(|p| p.name.text == name).and_then(|p| match &p.value {
        Value::Num(n) => Some(n.as_f64()),
        Value::Tuple(v) => v.first().map(|n: &Num| n.as_f64()),
        Value::Bool(b) => Some(f64::from(u8::from(*b))),
        _ => None,
    })
}

/// A string parameter.
pub fn string_param<'a>(params: &'a [Param], name: &str) -> Option<&'a str> {
    params.iter().rev().find(|p| p.name.text == name).and_then(|p| match &p.value {
        Value::Str(s) => Some(s.text.as_str()),
        _ => None,
    })
}

/// The declaration and parameters of a shader list's first shader (following one `= "x"`).
pub fn first_call<'a>(items: &'a [ShaderItem], lib: &'a Library) -> Option<(&'a str, &'a [Param])> {
    match items.first()? {
        ShaderItem::Call { decl, params, .. } => Some((decl.text.as_str(), params.as_slice())),
        ShaderItem::Ref(name) => {
            let def = lib.shaders.get(&name.text)?;
            match def.list.0.first()? {
                ShaderItem::Call { decl, params, .. } => Some((decl.text.as_str(), params.as_slice())),
                _ => None,
            }
        }
        ShaderItem::Define { list, .. } => match list.0.first()? {
            ShaderItem::Call { decl, params, .. } => Some((decl.text.as_str(), params.as_slice())),
            _ => None,
        },
    }
}

/// Translates a scene material; the strings are warnings about what was approximated.
pub fn translate(m: &Material, lib: &Library) -> (SurfaceMaterial, Vec<String>) {
    let mut warnings = Vec::new();
    let call = match &m.kind {
        MaterialKind::Shader(def) => first_call(&def.list.0, lib),
        MaterialKind::Material(defs) => defs.iter().rev().find_map(|d| d.shaders.as_ref()).and_then(|l| {
            // In a shader list the last shader's result is the material's; a passthrough
            // bump shader comes first.
            let illum = l.0.iter().rev().find_map(|item| first_call(std::slice::from_ref(item), lib));
            illum.or_else(|| first_call(&l.0, lib))
        }),
    };
    let Some((decl, params)) = call else {
        warnings.push(format!("material '{}' has no shader mira understands; rendered grey", m.name));
        return (SurfaceMaterial::grey(&m.name), warnings);
    };
    let decl = declaration_name(decl);
    let (param, default) = match decl {
        "mdl::nvidia::core_definitions::flex_material" | "mdl::nvidia::core_definitions::flex_material_v2" => {
            ("base_color", Rgb::splat(0.5))
        }
        "mdl::nvidia::core_definitions::diffuse" => ("diffuse_color", Rgb::splat(0.8)),
        "mib_illum_lambert"
        | "mib_illum_phong"
        | "mib_illum_blinn"
        | "mib_illum_cooktorr"
        | "mib_illum_ward"
        | "mib_illum_ward_deriv"
        | "mib_illum_hair" => ("diffuse", Rgb::ZERO),
        other => {
            warnings.push(format!(
                "material '{}': shader '{other}' is not supported by the path integrator yet; rendered grey",
                m.name
            ));
            return (SurfaceMaterial::grey(&m.name), warnings);
        }
    };
    let diffuse = match color_param(params, param) {
        None => default,
        Some(Ok(c)) => c,
        Some(Err(why)) => {
            warnings.push(format!("material '{}': {why}; its default is used", m.name));
            default
        }
    };
    (
        SurfaceMaterial { name: m.name.clone(), diffuse: diffuse.clamp(Rgb::ZERO, Rgb::ONE), emission: Rgb::ZERO },
        warnings,
    )
}
