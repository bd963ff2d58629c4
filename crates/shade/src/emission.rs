//! What lights emit: MDL light materials (`light_omni`, `light_spot`) with MDL's units, and
//! mental ray's base light shaders (`mib_light_point`, `mib_light_spot`,
//! `mib_light_infinite`).

use scene::{Library, Light};

use crate::material::{color_param, declaration_name, first_call, scalar_param, string_param};
use crate::Rgb;

/// How a light's colour is to be read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Power {
    /// Radiant exitance of the light's surface (MDL `lumen_m2`): L = E / π.
    Exitance(Rgb),
    /// Radiance of the light's surface (MDL `nit`).
    Radiance(Rgb),
    /// Total power over the whole light (MDL `lumen`).
    Flux(Rgb),
    /// Radiant intensity along the main direction (MDL `candela`; point lights).
    Intensity(Rgb),
    /// mental ray base light shaders: the colour arriving at a lit point, with no distance
    /// falloff (area lights average it over their samples); `atten` gives a linear falloff
    /// between `start` and `stop`.
    Constant {
        /// The colour.
        color: Rgb,
        /// Linear falloff distances, if `atten` is on.
        falloff: Option<(f32, f32)>,
    },
}

/// A light's emission, and whether it is a spot with an exponent distribution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emission {
    /// The amount and its unit.
    pub power: Power,
    /// MDL `light_spot`: cosine power of the spot distribution around the light's −Z.
    pub spot_exponent: Option<f32>,
    /// mental ray `mib_light_spot`: cosine of the inner (full-intensity) cone.
    pub cone: Option<f32>,
}

/// The emission of `light`, or a message saying why it cannot be read.
pub fn emission(light: &Light, lib: &Library) -> Result<Emission, String> {
    let Some(list) = &light.shader else {
        return Err(format!("light '{}' has no light shader", light.name));
    };
    let Some((decl, params)) = first_call(&list.0, lib) else {
        return Err(format!("light '{}': its shader cannot be found", light.name));
    };
    let color = |name: &str, default: Rgb| match color_param(params, name) {
        Some(Ok(c)) => c,
        _ => default,
    };
    match declaration_name(decl) {
        "mdl::nvidia::core_definitions::light_omni" | "mdl::nvidia::core_definitions::light_spot" => {
            let amount = color("tint", Rgb::ONE)
                * (scalar_param(params, "intensity").unwrap_or(1000.0)
                    * scalar_param(params, "unit_scale").unwrap_or(1.0)) as f32;
            let power = match string_param(params, "unit").unwrap_or("lumen_m2") {
                "lumen" => Power::Flux(amount),
                "candela" => Power::Intensity(amount),
                "nit" => Power::Radiance(amount),
                _ => Power::Exitance(amount),
            };
            let spot_exponent = declaration_name(decl)
                .ends_with("light_spot")
                .then(|| scalar_param(params, "spot_exponent").unwrap_or(30.0) as f32);
            Ok(Emission { power, spot_exponent, cone: None })
        }
        "mib_light_point" | "mib_light_spot" | "mib_light_infinite" => {
            let atten = scalar_param(params, "atten").unwrap_or(0.0) != 0.0;
            let falloff = atten.then(|| {
                (
                    scalar_param(params, "start").unwrap_or(0.0) as f32,
                    scalar_param(params, "stop").unwrap_or(0.0) as f32,
                )
            });
            let cone = (declaration_name(decl) == "mib_light_spot")
                .then(|| scalar_param(params, "cone").unwrap_or(0.0) as f32);
            Ok(Emission {
                power: Power::Constant { color: color("color", Rgb::ZERO), falloff },
                spot_exponent: None,
                cone,
            })
        }
        other => Err(format!("light '{}': light shader '{other}' is not supported yet", light.name)),
    }
}
