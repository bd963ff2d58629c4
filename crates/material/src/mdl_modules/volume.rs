//! Lowering a material's `material_volume` to the homogeneous participating medium the path
//! engine renders inside the surface ([`bsdf::Medium`]).
//!
//! MDL's `absorption_coefficient` and `scattering_coefficient` are per metre; mira's scene
//! unit is the metre (as `state::meters_per_scene_unit` answers), so they are used per
//! scene unit as they are. The volume's `scattering` vdf gives the phase function:
//! `df::anisotropic_vdf(directional_bias)` is Henyey–Greenstein with g = directional_bias,
//! the default `vdf()` isotropic. A thin-walled material has no inside: its volume is not
//! used (MDL ignores it too).

use bsdf::{Medium, Rgb};

use super::value::{Value, Vdf};

/// The medium of the evaluated `material` value of material `name`, or `None` when it has
/// no volume that absorbs or scatters. What is not compiled is appended to `warnings`,
/// places formatted by `location`: an unsupported vdf (isotropic scattering is used), a
/// coefficient that varies over the surface (no medium), volume emission (ignored).
pub fn medium(
    name: &str,
    material: &Value,
    location: &dyn Fn(mi::Span) -> String,
    warnings: &mut Vec<String>,
) -> Option<Medium> {
    if matches!(material.field("thin_walled"), Some(Value::Bool(true))) {
        return None;
    }
    let volume = material.field("volume")?;
    let mut coefficient = |field: &str| -> Option<Rgb> {
        match volume.field(field) {
            None => Some(Rgb::ZERO),
            Some(Value::Hit(..)) => {
                warnings.push(format!(
                    "material '{name}': its volume's {field} varies over the surface; a homogeneous medium needs a constant, so the volume is ignored"
                ));
                None
            }
            Some(v) => match v.color() {
                Some(c) if c.is_finite() && c.min_element() >= 0.0 => Some(c),
                Some(c) => {
                    warnings.push(format!(
                        "material '{name}': its volume's {field} {:.4} {:.4} {:.4} is negative or not finite; those channels are 0",
                        c.x, c.y, c.z
                    ));
                    Some(c)
                }
                None => {
                    warnings.push(format!(
                        "material '{name}': its volume's {field} is not a colour; the volume is ignored"
                    ));
                    None
                }
            },
        }
    };
    let sigma_a = coefficient("absorption_coefficient");
    let sigma_s = coefficient("scattering_coefficient");
    let emission = coefficient("emission_intensity");
    if emission.is_some_and(|e| e != Rgb::ZERO) {
        warnings.push(format!("material '{name}': volume emission (emission_intensity) is not rendered yet; ignored"));
    }
    let (sigma_a, sigma_s) = (sigma_a?, sigma_s?);
    let g = match volume.field("scattering") {
        Some(Value::Vdf(Vdf::HenyeyGreenstein(g))) => *g,
        Some(Value::Vdf(Vdf::Unsupported(what, span))) => {
            if sigma_s != Rgb::ZERO {
                warnings.push(format!(
                    "material '{name}': {what} (at {}) is not compiled yet; its volume scatters isotropically",
                    location(*span)
                ));
            }
            0.0
        }
        _ => 0.0,
    };
    let medium = Medium::new(sigma_a, sigma_s, g);
    (!medium.is_vacuum()).then_some(medium)
}
