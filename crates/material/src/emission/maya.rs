//! Maya lights for the path engine: what a Maya light shader emits, as the radiometric
//! quantity the path engine's base-light outputs carry (the irradiance a surface facing
//! the light receives; the path engine's Lambertian lobe is albedo/π).
//!
//! - π · `color` · `intensity` arrives undiminished with `decayRate` 0 (point, spot,
//!   directional, area), else falls off as d^−decayRate (a photometric falloff of that
//!   exponent). The factor π makes a lambert of albedo c·d give c·d·I·cos θ in the path
//!   engine too, as mental ray for Maya's classic shaders do (no 1/π in their light units);
//! - a spot's cone: full light inside the inner half-angle (`coneAngle`/2, narrowed by a
//!   negative `penumbraAngle`), fading to the scene light's `spread` — linear in the cosine
//!   where the classic shader fades linearly in the angle; `dropoff` is not represented
//!   (and the renderer's photometric output, used with a decay, ignores the cone today);
//! - a volume light of sphere shape (`lightShape` 1) whose transform scales the unit
//!   sphere uniformly to radius R: a point light at its centre with a linear falloff from
//!   the centre to R when `colorRange` runs linearly from black on the boundary (position
//!   0) to a colour c at the centre (position 1) — the classic light's c·(1 − r/R) exactly
//!   —, or constant inside R when `colorRange` is one colour or empty (white); other
//!   shapes, scales, ramps, arcs below 360° and light directions other than outward are
//!   left out with a message;
//! - `emitDiffuse` off: the light is left out (the path engine has no specular-only
//!   lights); ambient lights are left out (no counterpart): both with a message.

use super::{Emission, Power};
use crate::{color_param, first_call, scalar_param};
use bsdf::Rgb;
use glam::DMat4;
use mi::ast::{Param, Value};

/// The Maya light family a light shader declaration belongs to.
fn family(decl: &str) -> Option<&'static str> {
    let name = decl.strip_prefix("maya_").or_else(|| decl.strip_prefix("adskMaya"))?.to_ascii_lowercase();
    ["pointlight", "spotlight", "directionallight", "ambientlight", "arealight", "volumelight"]
        .into_iter()
        .find(|f| *f == name)
}

/// The emission of a Maya light shader call on a light placed by `light_to_world`, or a
/// message saying why the path engine leaves it out; `None` if the declaration is not a
/// Maya light.
pub fn emission_of(decl: &str, params: &[Param], light_to_world: DMat4) -> Option<Result<Emission, String>> {
    let family = family(decl)?;
    let scalar = |name: &str, default: f64| scalar_param(params, name).unwrap_or(default) as f32;
    let color = match color_param(params, "color") {
        Some(Ok(c)) => c,
        _ => Rgb::ONE,
    } * (std::f32::consts::PI * scalar("intensity", 1.0));
    if family == "ambientlight" {
        return Some(Err(format!("{decl} has no path-engine counterpart; the light is left out")));
    }
    if family == "volumelight" {
        return Some(volume_emission(decl, params, light_to_world, color));
    }
    if scalar("emitDiffuse", 1.0) == 0.0 {
        return Some(Err(format!("{decl} with emitDiffuse off: the path engine leaves the light out")));
    }
    let rate = if family == "directionallight" { 0 } else { (scalar("decayRate", 0.0) as i32).clamp(0, 3) };
    let power = match rate {
        0 => Power::Constant { color, falloff: None },
        r => Power::Photometric { color, exponent: r as f32, range: None },
    };
    let cone = (family == "spotlight").then(|| {
        let half = 0.5 * scalar("coneAngle", 0.698_131_7);
        let inner = half + scalar("penumbraAngle", 0.0).min(0.0);
        inner.clamp(0.0, std::f32::consts::FRAC_PI_2).cos()
    });
    Some(Ok(Emission { power, spot_exponent: None, cone, distribution: None }))
}

/// The emission of a scene light whose shader is a Maya light (see [`emission_of`]).
pub fn light_emission(light: &scene::Light, lib: &scene::Library) -> Option<Result<Emission, String>> {
    let list = light.shader.as_ref()?;
    let (decl, params) = first_call(&list.0, lib)?;
    emission_of(decl, params, light.light_to_world)
}

/// The keys (position, colour) of a constant `colorRange` ramp.
fn ramp_keys(params: &[Param]) -> Vec<(f32, Rgb)> {
    let Some(Value::Array(items)) = params.iter().rev().find(|p| p.name.text == "colorRange").map(|p| &p.value) else {
        return Vec::new();
    };
    items
        .iter()
        .filter_map(|item| {
            let Value::Struct(members) = item else { return None };
            let position = scalar_param(members, "colorRange_Position")? as f32;
            let color = color_param(members, "colorRange_Color")?.ok()?;
            Some((position, color))
        })
        .collect()
}

/// A volume light (see the module doc): `color` is π · colour · intensity.
fn volume_emission(decl: &str, params: &[Param], light_to_world: DMat4, color: Rgb) -> Result<Emission, String> {
    let shape = scalar_param(params, "lightShape").unwrap_or(1.0) as i32;
    if shape != 1 {
        return Err(format!("{decl} of lightShape {shape} (not a sphere) has no path-engine counterpart; left out"));
    }
    let arc = scalar_param(params, "arc").unwrap_or(360.0);
    if arc < 360.0 {
        return Err(format!("{decl}: a sphere cut to an arc of {arc}° has no path-engine counterpart; left out"));
    }
    let direction = scalar_param(params, "volumeLightDir").unwrap_or(0.0);
    if direction != 0.0 {
        return Err(format!(
            "{decl}: volumeLightDir {direction} (inward or down the axis) has no path-engine counterpart; left out"
        ));
    }
    let scales = [0, 1, 2].map(|i| light_to_world.col(i).truncate().length());
    let radius = scales[0];
    if radius.is_nan() || radius <= 0.0 || scales.iter().any(|s| (s - radius).abs() > 1e-3 * radius) {
        return Err(format!("{decl}: a sphere scaled unevenly ({scales:?}) has no path-engine counterpart; left out"));
    }
    let radius = radius as f32;
    let keys = ramp_keys(params);
    let (tint, start) = match keys.as_slice() {
        [] => (Rgb::ONE, radius),
        [(_, c)] => (*c, radius),
        [a, b] => {
            let (boundary, centre) = if a.0 <= b.0 { (a, b) } else { (b, a) };
            if boundary.0 != 0.0 || centre.0 != 1.0 || boundary.1 != Rgb::ZERO {
                return Err(format!(
                    "{decl}: a colorRange other than black on the boundary to a colour at the centre has no \
                     path-engine counterpart; left out"
                ));
            }
            (centre.1, 0.0)
        }
        _ => {
            return Err(format!("{decl}: a colorRange of {} keys has no path-engine counterpart; left out", keys.len()))
        }
    };
    // A constant light stops at the boundary: a falloff over the last 10⁻⁴ of the radius.
    let start = start.min(radius * (1.0 - 1e-4));
    Ok(Emission {
        power: Power::Constant { color: color * tint, falloff: Some((start, radius)) },
        spot_exponent: None,
        cone: None,
        distribution: None,
    })
}

#[cfg(test)]
mod tests {
    use std::f32::consts::PI;

    use super::*;

    fn params(text: &str) -> Vec<Param> {
        let parsed = mi::parse_str("t.mi", &format!("shader \"s\" \"x\" ({text})"));
        for item in parsed.items {
            if let mi::ast::Item::Shader(def) = item {
                if let Some(mi::ast::ShaderItem::Call { params, .. }) = def.list.0.into_iter().next() {
                    return params;
                }
            }
        }
        panic!("no call");
    }

    #[test]
    fn maya_lights_become_constant_or_photometric_emission() {
        let e = emission_of("maya_pointlight", &params(r#""color" 1 0.5 0.25, "intensity" 2"#), DMat4::IDENTITY)
            .unwrap()
            .unwrap();
        assert_eq!(e.power, Power::Constant { color: Rgb::new(2.0, 1.0, 0.5) * PI, falloff: None });
        let e = emission_of("adskMayaPointLight", &params(r#""decayRate" 2, "intensity" 3"#), DMat4::IDENTITY)
            .unwrap()
            .unwrap();
        assert_eq!(e.power, Power::Photometric { color: Rgb::splat(3.0 * PI), exponent: 2.0, range: None });
        let e = emission_of("maya_spotlight", &params(r#""coneAngle" 1, "penumbraAngle" -0.2"#), DMat4::IDENTITY)
            .unwrap()
            .unwrap();
        assert!((e.cone.unwrap() - 0.3f32.cos()).abs() < 1e-6);
        // Directional lights do not decay.
        let e = emission_of("maya_directionallight", &params(r#""decayRate" 2"#), DMat4::IDENTITY).unwrap().unwrap();
        assert!(matches!(e.power, Power::Constant { .. }));
        assert!(emission_of("maya_ambientlight", &params(""), DMat4::IDENTITY).unwrap().is_err());
        assert!(emission_of("maya_pointlight", &params(r#""emitDiffuse" off"#), DMat4::IDENTITY).unwrap().is_err());
        assert!(emission_of("mib_light_point", &params(""), DMat4::IDENTITY).is_none());
    }

    /// A sphere volume light of radius 3 with colorRange black on the boundary to white at
    /// the centre: a point light of π·colour·intensity falling off linearly from the
    /// centre (1 − r/R, the classic light's ramp at 1 − r/R); one colour: constant to R.
    #[test]
    fn sphere_volume_lights_become_point_lights_with_their_falloff() {
        let scale = DMat4::from_scale(glam::DVec3::splat(3.0));
        let linear = r#""intensity" 2, "lightShape" 1, "colorRange" [
            { "colorRange_Position" 0, "colorRange_Color" 0 0 0, "colorRange_Interp" 1 },
            { "colorRange_Position" 1, "colorRange_Color" 1 0.5 0.25, "colorRange_Interp" 1 } ]"#;
        let e = emission_of("maya_volumelight", &params(linear), scale).unwrap().unwrap();
        assert_eq!(e.power, Power::Constant { color: Rgb::new(2.0, 1.0, 0.5) * PI, falloff: Some((0.0, 3.0)) });
        let constant =
            r#""lightShape" 1, "colorRange" [ { "colorRange_Position" 0.5, "colorRange_Color" 0.5 0.5 0.5 } ]"#;
        let e = emission_of("adskMayaVolumeLight", &params(constant), scale).unwrap().unwrap();
        let Power::Constant { color, falloff: Some((start, stop)) } = e.power else { panic!("{:?}", e.power) };
        assert!((color - Rgb::splat(0.5 * PI)).abs().max_element() < 1e-6);
        assert!(stop == 3.0 && (3.0 - start) < 1e-3 && start < 3.0);
        // Boxes, uneven scales and other ramps are left out with a message.
        assert!(emission_of("maya_volumelight", &params(r#""lightShape" 0"#), scale).unwrap().is_err());
        let uneven = DMat4::from_scale(glam::DVec3::new(1.0, 2.0, 1.0));
        assert!(emission_of("maya_volumelight", &params(""), uneven).unwrap().is_err());
    }
}
