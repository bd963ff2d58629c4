//! Lowering a material's `material_volume` to the homogeneous participating medium the path
//! engine renders inside the surface ([`bsdf::Medium`]).
//!
//! MDL's `absorption_coefficient` and `scattering_coefficient` are per metre; mira's scene
//! unit is the metre (as `state::meters_per_scene_unit` answers), so they are used per
//! scene unit as they are. The volume's `scattering` vdf gives the phase function:
//! `df::anisotropic_vdf(directional_bias)` is Henyey–Greenstein with g = directional_bias,
//! the default `vdf()` isotropic, `df::fog_vdf(particle_size)` the blend of a
//! Henyey–Greenstein and a Draine lobe that approximates Mie scattering by droplets of
//! that diameter in µm ([`bsdf::phase::fog_lobes`], where its definition and sources are). A thin-walled material has no inside: its volume is not
//! used (MDL ignores it too).
//!
//! A mix of vdfs (`df::normalized_mix`, `clamped_mix` and their colour forms) is lowered to
//! one medium ([`mix`]): its total weight W per channel (≤ 1) is the fraction of the
//! scattering coefficient that scatters (σs·W; the rest, σs·(1 − W), is absorbed, so the
//! extinction is unchanged), and its phase function in each channel the mixture of its
//! lobes weighted by what each scatters in that channel
//! ([`bsdf::Phase::chromatic_mixture_of`], up to four lobes; more are merged). A tint of a vdf
//! (`df::tint(color, vdf)`) scales what it scatters by the tint (clamped to [0, 1] per
//! channel, as a mix's weights): a clamped mix of that one component.
//!
//! Coefficients, weights, tints and biases may depend on the shading point. A medium is
//! homogeneous inside its object, so such a volume is evaluated where a path enters the
//! object ([`VolumeAtHit`], `SurfaceMaterial::medium_at`): the path travels in the medium
//! of its entry point until it leaves. This is how Iray treats volume coefficients that
//! vary over the surface (its volumes are uniform inside; a spatially varying volume needs
//! a volume texture). What is constant is lowered once.
//!
//! `emission_intensity` is the radiance the medium emits per unit length (per metre, per
//! channel; the emission coefficient of the radiative transfer equation, dL/ds = ε −
//! σt·L): a ray crossing a length d of the medium gains ε·(1 − exp(−σt·d))/σt
//! ([`Medium::emitted`]). It may vary over the surface like the coefficients.

use std::sync::Arc;

use bsdf::phase::{fog_lobes, Draine};
use bsdf::{Medium, Phase, Rgb};
use glam::{Vec3A, Vec4};
use mi::Span;

use super::eval::{problem, Eval};
use super::hit::{too_costly, HitExpr};
use super::natives::MAX_LEAVES;
use super::value::{Leaf, Value, Vdf, VdfNumber};
use crate::inputs::{MediumEvaluator, VaryingMedium};

/// `df::{name}` (a normalized or, when `clamped`, clamped mix) of the vdf components
/// `components` (structs of `weight` and `component`), called at `span`: a [`Vdf::Mix`].
/// Normalized: weights summing past 1 (per channel) are scaled to sum to 1; clamped: the
/// weights are taken in order until they reach 1, the one crossing it cut short. A
/// component mira does not compile makes the mix that vdf (warned where it is used).
pub fn mix(name: &str, components: &[Value], clamped: bool, span: Span) -> Eval {
    let mut parts = Vec::with_capacity(components.len());
    for c in components {
        let weight = match c.field("weight") {
            None => VdfNumber::Const(Rgb::ZERO),
            Some(w) => number(w)
                .filter(|n| !matches!(n, VdfNumber::Const(c) if !c.is_finite()))
                .ok_or_else(|| problem(span, format!("a weight of `df::{name}` is not a number or colour")))?,
        };
        match c.field("component") {
            Some(Value::Vdf(unsupported @ Vdf::Unsupported(..))) => return Ok(Value::Vdf(unsupported.clone())),
            Some(Value::Vdf(v)) => parts.push((weight, v.clone())),
            _ => return Err(problem(span, format!("a component of `df::{name}` is not a vdf"))),
        }
    }
    Ok(Value::Vdf(Vdf::Mix { parts, clamped }))
}

/// `df::tint(tint, vdf)` called at `span`: the vdf scattering `tint` of what it scattered
/// (per channel, clamped to [0, 1]), the rest absorbed: a clamped [`Vdf::Mix`] of one
/// component.
pub fn tint(vdf: &Vdf, tint: Option<&Value>, span: Span) -> Eval {
    if let unsupported @ Vdf::Unsupported(..) = vdf {
        return Ok(Value::Vdf(unsupported.clone()));
    }
    let t = tint.and_then(number).ok_or_else(|| problem(span, "the tint of `df::tint` is not a number or colour"))?;
    Ok(Value::Vdf(Vdf::Mix { parts: vec![(t, vdf.clone())], clamped: true }))
}

/// A number or colour value as a vdf's number.
fn number(v: &Value) -> Option<VdfNumber> {
    match v {
        Value::Hit(e, _) => Some(VdfNumber::Hit(e.clone())),
        v => v.color().map(VdfNumber::Const),
    }
}

/// A vdf with its numbers as [`Leaf`]s of one list of expressions.
#[derive(Debug, PartialEq)]
enum VdfTree {
    /// Henyey–Greenstein of asymmetry g (the leaf's first lane).
    HenyeyGreenstein(Leaf),
    /// `df::fog_vdf` of the particle diameter (µm, the leaf's first lane).
    Fog(Leaf),
    /// A mix: weights and components, clamped or normalized.
    Mix { parts: Vec<(Leaf, VdfTree)>, clamped: bool },
}

/// A material's volume with its numbers as [`Leaf`]s: what [`lower`] turns into a medium.
#[derive(Debug, PartialEq)]
struct Volume {
    sigma_a: Leaf,
    sigma_s: Leaf,
    emission: Leaf,
    scattering: VdfTree,
}

/// A volume whose numbers depend on the shading point: its expressions, evaluated where a
/// path enters the object, and the volume over them.
#[derive(Debug, PartialEq)]
pub struct VolumeAtHit {
    leaves: Vec<Arc<HitExpr>>,
    volume: Volume,
}

impl MediumEvaluator for VolumeAtHit {
    fn medium(&self, state: &shader::State) -> Medium {
        let mut values = [Vec4::ZERO; MAX_LEAVES];
        for (v, e) in values.iter_mut().zip(&self.leaves) {
            *v = e.eval_finite(state);
        }
        lower(&self.volume, &values[..self.leaves.len()])
    }
}

/// The [`Leaf`] of `n`, its expression added to `leaves` once; `None` past [`MAX_LEAVES`].
fn leaf(n: &VdfNumber, leaves: &mut Vec<Arc<HitExpr>>) -> Option<Leaf> {
    match n {
        VdfNumber::Const(c) => Some(Leaf::Const(*c)),
        VdfNumber::Hit(e) => {
            let i = match leaves.iter().position(|l| Arc::ptr_eq(l, e) || **l == **e) {
                Some(i) => i,
                None if leaves.len() < MAX_LEAVES => {
                    leaves.push(e.clone());
                    leaves.len() - 1
                }
                None => return None,
            };
            Some(Leaf::Hit(i as u16))
        }
    }
}

/// `vdf` as a [`VdfTree`] over `leaves`; `Err` with what is not compiled (an unsupported
/// vdf and where, or too many expressions).
fn tree(vdf: &Vdf, leaves: &mut Vec<Arc<HitExpr>>) -> Result<VdfTree, (String, Option<Span>)> {
    let too_many = || (format!("a vdf reading more than {MAX_LEAVES} values of the shading point"), None);
    match vdf {
        Vdf::HenyeyGreenstein(g) => Ok(VdfTree::HenyeyGreenstein(leaf(g, leaves).ok_or_else(too_many)?)),
        Vdf::Fog(d) => Ok(VdfTree::Fog(leaf(d, leaves).ok_or_else(too_many)?)),
        Vdf::Mix { parts, clamped } => {
            let parts = parts
                .iter()
                .map(|(w, c)| Ok((leaf(w, leaves).ok_or_else(too_many)?, tree(c, leaves)?)))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(VdfTree::Mix { parts, clamped: *clamped })
        }
        Vdf::Unsupported(what, span) => Err((what.clone(), Some(*span))),
    }
}

/// What `tree` scatters per channel (its albedo, ≤ 1) and its lobes: (what each scatters
/// per channel, lobe), with its expressions evaluated to `values`.
fn scattered(tree: &VdfTree, values: &[Vec4], lobes: &mut Vec<(Rgb, Draine)>) -> Rgb {
    match tree {
        VdfTree::HenyeyGreenstein(g) => {
            lobes.push((Rgb::ONE, Draine::henyey_greenstein(g.get(values).x)));
            Rgb::ONE
        }
        VdfTree::Fog(d) => {
            lobes.extend(fog_lobes(d.get(values).x).map(|(w, l)| (Rgb::splat(w), l)));
            Rgb::ONE
        }
        VdfTree::Mix { parts, clamped } => {
            let weight = |w: &Leaf| {
                let w = w.get(values);
                if w.is_finite() {
                    w.max(Rgb::ZERO)
                } else {
                    Rgb::ZERO
                }
            };
            let sum = parts.iter().fold(Rgb::ZERO, |s, (w, _)| s + weight(w));
            let scale = Rgb::ONE / sum.max(Rgb::ONE);
            let (mut used, mut albedo) = (Rgb::ZERO, Rgb::ZERO);
            for (w, component) in parts {
                let w = if *clamped {
                    let w = weight(w).min((Rgb::ONE - used).max(Rgb::ZERO));
                    used += w;
                    w
                } else {
                    weight(w) * scale
                };
                // The component's lobes scatter its weight's share, channel by channel.
                let first = lobes.len();
                albedo += w * scattered(component, values, lobes);
                for (amount, _) in &mut lobes[first..] {
                    *amount *= w;
                }
            }
            albedo.min(Rgb::ONE)
        }
    }
}

/// The medium of `volume` with its expressions evaluated to `values`: what the mix does
/// not scatter is absorbed (the extinction stays σa + σs); each channel scatters by its
/// own mixture of the lobes.
fn lower(volume: &Volume, values: &[Vec4]) -> Medium {
    let coefficient = |l: &Leaf| {
        let c = l.get(values);
        Rgb::select(c.is_finite_mask(), c.max(Rgb::ZERO), Rgb::ZERO)
    };
    let (mut sigma_a, mut sigma_s) = (coefficient(&volume.sigma_a), coefficient(&volume.sigma_s));
    let mut lobes = Vec::new();
    let albedo = scattered(&volume.scattering, values, &mut lobes);
    sigma_a += sigma_s * (Rgb::ONE - albedo);
    sigma_s *= albedo;
    Medium::with_phase(sigma_a, sigma_s, Phase::chromatic_mixture_of(&lobes))
        .with_emission(coefficient(&volume.emission))
}

/// The medium of the evaluated `material` value of material `name`: `None` when it has no
/// volume that absorbs or scatters; with a [`VaryingMedium`] when the volume depends on the
/// shading point (then the medium given is the volume at a default point: texture
/// coordinates 0, normal +z, the origin). What is not compiled is appended to `warnings`,
/// places formatted by `location`: an unsupported vdf (isotropic scattering is used), a
/// coefficient that is not a colour (no medium).
pub fn medium(
    name: &str,
    material: &Value,
    location: &dyn Fn(mi::Span) -> String,
    warnings: &mut Vec<String>,
) -> (Option<Medium>, Option<VaryingMedium>) {
    if matches!(material.field("thin_walled"), Some(Value::Bool(true))) {
        return (None, None);
    }
    let Some(volume) = material.field("volume") else { return (None, None) };
    let mut leaves = Vec::new();
    let mut coefficient = |field: &str| -> Option<Leaf> {
        match volume.field(field) {
            None => Some(Leaf::Const(Rgb::ZERO)),
            Some(v) => match number(v).and_then(|n| leaf(&n, &mut leaves)) {
                Some(Leaf::Const(c)) if !c.is_finite() || c.min_element() < 0.0 => {
                    warnings.push(format!(
                        "material '{name}': its volume's {field} {:.4} {:.4} {:.4} is negative or not finite; those channels are 0",
                        c.x, c.y, c.z
                    ));
                    Some(Leaf::Const(c))
                }
                Some(l) => Some(l),
                None => {
                    warnings.push(format!(
                        "material '{name}': its volume's {field} is not a colour (or reads too many values of the shading point); the volume is ignored"
                    ));
                    None
                }
            },
        }
    };
    let sigma_a = coefficient("absorption_coefficient");
    let sigma_s = coefficient("scattering_coefficient");
    let emission = coefficient("emission_intensity");
    let (Some(sigma_a), Some(sigma_s), Some(emission)) = (sigma_a, sigma_s, emission) else { return (None, None) };
    let scattering = match volume.field("scattering") {
        Some(Value::Vdf(vdf)) => match tree(vdf, &mut leaves) {
            Ok(t) => t,
            Err((what, span)) => {
                if sigma_s != Leaf::Const(Rgb::ZERO) {
                    let at = span.map_or(String::new(), |s| format!(" (at {})", location(s)));
                    warnings.push(format!(
                        "material '{name}': {what}{at} is not compiled yet; its volume scatters isotropically"
                    ));
                }
                VdfTree::HenyeyGreenstein(Leaf::Const(Rgb::ZERO))
            }
        },
        _ => VdfTree::HenyeyGreenstein(Leaf::Const(Rgb::ZERO)),
    };
    let volume = Volume { sigma_a, sigma_s, emission, scattering };
    if leaves.is_empty() {
        let medium = lower(&volume, &[]);
        return ((!medium.is_vacuum()).then_some(medium), None);
    }
    if let Some(why) = leaves.iter().find_map(too_costly) {
        warnings.push(format!("material '{name}': its volume: {why}; the volume is ignored"));
        return (None, None);
    }
    let state =
        shader::State { normal: Vec3A::Z, normal_geom: Vec3A::Z, dir: -Vec3A::Z, tex_count: 1, ..Default::default() };
    let at_hit = VolumeAtHit { leaves, volume };
    let default = at_hit.medium(&state);
    (Some(default), Some(VaryingMedium(Arc::new(at_hit))))
}
