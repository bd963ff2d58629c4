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
//! - `emitDiffuse` off: the light is left out (the path engine has no specular-only
//!   lights); ambient lights are left out (no counterpart): both with a message.

use super::{Emission, Power};
use crate::{color_param, first_call, scalar_param};
use bsdf::Rgb;
use mi::ast::Param;

/// The Maya light family a light shader declaration belongs to.
fn family(decl: &str) -> Option<&'static str> {
    let name = decl.strip_prefix("maya_").or_else(|| decl.strip_prefix("adskMaya"))?.to_ascii_lowercase();
    ["pointlight", "spotlight", "directionallight", "ambientlight", "arealight", "volumelight"]
        .into_iter()
        .find(|f| *f == name)
}

/// The emission of a Maya light shader call, or a message saying why the path engine
/// leaves it out; `None` if the declaration is not a Maya light.
pub fn emission_of(decl: &str, params: &[Param]) -> Option<Result<Emission, String>> {
    let family = family(decl)?;
    let scalar = |name: &str, default: f64| scalar_param(params, name).unwrap_or(default) as f32;
    let color = match color_param(params, "color") {
        Some(Ok(c)) => c,
        _ => Rgb::ONE,
    } * (std::f32::consts::PI * scalar("intensity", 1.0));
    if family == "ambientlight" || family == "volumelight" {
        return Some(Err(format!("{decl} has no path-engine counterpart; the light is left out")));
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
    emission_of(decl, params)
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
        let e = emission_of("maya_pointlight", &params(r#""color" 1 0.5 0.25, "intensity" 2"#)).unwrap().unwrap();
        assert_eq!(e.power, Power::Constant { color: Rgb::new(2.0, 1.0, 0.5) * PI, falloff: None });
        let e = emission_of("adskMayaPointLight", &params(r#""decayRate" 2, "intensity" 3"#)).unwrap().unwrap();
        assert_eq!(e.power, Power::Photometric { color: Rgb::splat(3.0 * PI), exponent: 2.0, range: None });
        let e = emission_of("maya_spotlight", &params(r#""coneAngle" 1, "penumbraAngle" -0.2"#)).unwrap().unwrap();
        assert!((e.cone.unwrap() - 0.3f32.cos()).abs() < 1e-6);
        // Directional lights do not decay.
        let e = emission_of("maya_directionallight", &params(r#""decayRate" 2"#)).unwrap().unwrap();
        assert!(matches!(e.power, Power::Constant { .. }));
        assert!(emission_of("maya_ambientlight", &params("")).unwrap().is_err());
        assert!(emission_of("maya_pointlight", &params(r#""emitDiffuse" off"#)).unwrap().is_err());
        assert!(emission_of("mib_light_point", &params("")).is_none());
    }
}
