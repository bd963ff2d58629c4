//! Lowering a material's `material_volume` to the homogeneous participating medium the path
//! engine renders inside the surface ([`bsdf::Medium`]).
//!
//! MDL's `absorption_coefficient` and `scattering_coefficient` are per metre; mira's scene
//! unit is the metre (as `state::meters_per_scene_unit` answers), so they are used per
//! scene unit as they are. The volume's `scattering` vdf gives the phase function:
//! `df::anisotropic_vdf(directional_bias)` is Henyey–Greenstein with g = directional_bias,
//! the default `vdf()` isotropic. A thin-walled material has no inside: its volume is not
//! used (MDL ignores it too).
//!
//! A mix of vdfs (`df::normalized_mix`, `clamped_mix` and their colour forms) is lowered to
//! one medium ([`mix`]): its total weight W per channel (≤ 1) is the fraction of the
//! scattering coefficient that scatters (σs·W; the rest, σs·(1 − W), is absorbed, so the
//! extinction is unchanged), and its phase function the mixture of its Henyey–Greenstein
//! lobes ([`bsdf::Phase`], up to four; more are merged, keeping the mean cosine), each
//! weighted by how much it scatters (the mean of its weight's channels: one phase function
//! serves all three channels, exact for grey weights).
//!
//! A tint of a vdf (`df::tint(color, vdf)`) scales what it scatters by the tint (clamped to
//! [0, 1] per channel, as a mix's weights): the same lowering as a mix of that one
//! component, σs·tint scattering with the vdf's phase function, σs·(1 − tint) absorbed.

use bsdf::{Medium, Phase, Rgb};
use mi::Span;

use super::eval::{problem, Eval};
use super::value::{Leaf, Value, Vdf};

/// `df::{name}` (a normalized or, when `clamped`, clamped mix) of the vdf components
/// `components` (structs of `weight` and `component`), called at `span`: a
/// [`Vdf::Mixture`]. Normalized: weights summing past 1 (per channel) are scaled to sum to 1;
/// clamped: the weights are taken in order until they reach 1, the one crossing it cut
/// short. A component mira does not compile makes the mix that vdf (warned where it is
/// used); weights that vary over the surface make it unsupported.
pub fn mix(name: &str, components: &[Value], clamped: bool, span: Span) -> Eval {
    let mut parts = Vec::with_capacity(components.len());
    for c in components {
        let weight = match c.field("weight") {
            None => Rgb::ZERO,
            Some(Value::Hit(..)) => {
                return Ok(Value::Vdf(Vdf::Unsupported(
                    format!("`df::{name}` of vdfs with weights that vary over the surface"),
                    span,
                )))
            }
            Some(w) => w
                .color()
                .filter(|w| w.is_finite())
                .ok_or_else(|| problem(span, format!("a weight of `df::{name}` is not a number or colour")))?
                .max(Rgb::ZERO),
        };
        let (albedo, lobes) = match c.field("component") {
            Some(Value::Vdf(Vdf::HenyeyGreenstein(g))) => (Rgb::ONE, vec![(1.0, *g)]),
            Some(Value::Vdf(Vdf::Mixture { albedo, lobes })) => (*albedo, lobes.clone()),
            Some(Value::Vdf(unsupported @ Vdf::Unsupported(..))) => return Ok(Value::Vdf(unsupported.clone())),
            _ => return Err(problem(span, format!("a component of `df::{name}` is not a vdf"))),
        };
        parts.push((weight, albedo, lobes));
    }
    let mut used = Rgb::ZERO;
    let sum = parts.iter().fold(Rgb::ZERO, |s, (w, _, _)| s + *w);
    let scale = Rgb::ONE / sum.max(Rgb::ONE);
    let (mut albedo, mut lobes) = (Rgb::ZERO, Vec::new());
    for (w, a, inner) in parts {
        let w = if clamped {
            let w = w.min((Rgb::ONE - used).max(Rgb::ZERO));
            used += w;
            w
        } else {
            w * scale
        };
        let scattered = w * a;
        let amount = (scattered.x + scattered.y + scattered.z) / 3.0;
        albedo += scattered;
        // The component's lobes share what it scatters in their own proportions.
        let inner_total: f32 = inner.iter().map(|(x, _)| x).sum();
        if inner_total > 0.0 {
            lobes.extend(inner.iter().map(|(x, g)| (amount * x / inner_total, *g)));
        }
    }
    Ok(Value::Vdf(Vdf::Mixture { albedo: albedo.min(Rgb::ONE), lobes }))
}

/// `df::tint(tint, vdf)` called at `span`: the vdf scattering `tint` of what it scattered
/// (per channel, clamped to [0, 1]), the rest absorbed ([`Vdf::Mixture`]); a tint that
/// varies over the surface makes it unsupported (a homogeneous medium has one albedo).
pub fn tint(vdf: &Vdf, tint: Leaf, span: Span) -> Vdf {
    let Leaf::Const(t) = tint else {
        return Vdf::Unsupported("`df::tint` of a vdf with a tint that varies over the surface".into(), span);
    };
    let t = if t.is_finite() { t.clamp(Rgb::ZERO, Rgb::ONE) } else { Rgb::ZERO };
    match vdf {
        Vdf::HenyeyGreenstein(g) => Vdf::Mixture { albedo: t, lobes: vec![(1.0, *g)] },
        // The tint scales every lobe alike: their proportions stay.
        Vdf::Mixture { albedo, lobes } => Vdf::Mixture { albedo: *albedo * t, lobes: lobes.clone() },
        unsupported @ Vdf::Unsupported(..) => unsupported.clone(),
    }
}

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
    let (mut sigma_a, mut sigma_s) = (sigma_a?, sigma_s?);
    let phase = match volume.field("scattering") {
        Some(Value::Vdf(Vdf::HenyeyGreenstein(g))) => Phase::henyey_greenstein(*g),
        Some(Value::Vdf(Vdf::Mixture { albedo, lobes })) => {
            // What the mix does not scatter is absorbed: the extinction stays σa + σs.
            sigma_a += sigma_s * (Rgb::ONE - *albedo);
            sigma_s *= *albedo;
            Phase::mixture(lobes)
        }
        Some(Value::Vdf(Vdf::Unsupported(what, span))) => {
            if sigma_s != Rgb::ZERO {
                warnings.push(format!(
                    "material '{name}': {what} (at {}) is not compiled yet; its volume scatters isotropically",
                    location(*span)
                ));
            }
            Phase::henyey_greenstein(0.0)
        }
        _ => Phase::henyey_greenstein(0.0),
    };
    let medium = Medium::with_phase(sigma_a, sigma_s, phase);
    (!medium.is_vacuum()).then_some(medium)
}
