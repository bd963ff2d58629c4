//! The combinators of emission distributions (`edf`s): `df::tint(color, edf)`,
//! `df::directional_factor(…, edf)` and the mixes of edfs (`normalized_mix`,
//! `clamped_mix`, `unbounded_mix` and their `color_` forms), built as [`Edf`] values, and
//! lowered to the [`EdfTree`] the renderer evaluates (the mixes' weights normalised or
//! clamped as for bsdfs, [`mix_weights`]). The weights of mixes, the tint and the factor's
//! tints and exponent may vary over the surface ([`Leaf::Hit`]: the tree is then lowered
//! again at each hit, [`tree`] of the hit's values). Their components may be
//! `diffuse_edf`, `spot_edf`, `measured_edf`, `edf()` and other combinators (the
//! measured ones in power mode are each normalised to the power they emit alone,
//! [`per_power`]).

use std::sync::Arc;

use bsdf::Rgb;
use glam::Vec4;
use mi::Span;

use super::eval::{problem, Eval, Problem};
use super::hit::HitExpr;
use super::natives::{leaf, mix_weights, MAX_LEAVES};
use super::value::{Edf, Leaf, MixBound, Value};
use crate::edf_tree::EdfTree;

/// A constant colour argument `what` of `df::{function}` (a number is a grey; finite).
fn constant(function: &str, what: &str, v: &Value, span: Span) -> Result<Rgb, Problem> {
    v.color().filter(|c| c.is_finite()).ok_or_else(|| {
        problem(
            span,
            format!("`{what}` of `df::{function}` of an edf is {}, not a finite colour", super::eval::kind(v)),
        )
    })
}

/// A weight or tint `what` of `df::{function}` of edfs as a [`Leaf`] (`default` when not
/// given): a constant, or an expression of the hit added to `leaves`.
fn weight(
    function: &str,
    what: &str,
    v: Option<&Value>,
    default: Rgb,
    leaves: &mut Vec<Arc<HitExpr>>,
    span: Span,
) -> Result<Leaf, Problem> {
    match v {
        None => Ok(Leaf::Const(default)),
        Some(v @ Value::Hit(..)) => leaf(v, leaves).ok_or_else(|| {
            problem(
                span,
                format!(
                    "`{what}` of `df::{function}` of an edf depends on the shading point and the material reads more than {MAX_LEAVES} such values; not compiled"
                ),
            )
        }),
        Some(v) => constant(function, what, v, span).map(Leaf::Const),
    }
}

/// `df::{name}` of the edf components `components` (structs of `weight` and `component`);
/// weights that depend on the hit are added to `leaves`.
pub fn mix(name: &str, components: &[Value], bound: MixBound, leaves: &mut Vec<Arc<HitExpr>>, span: Span) -> Eval {
    let mut parts = Vec::with_capacity(components.len());
    for c in components {
        let w = weight(name, "weight", c.field("weight"), Rgb::ZERO, leaves, span)?;
        match c.field("component") {
            Some(Value::Edf(e)) => parts.push((w, e.clone())),
            _ => return Err(problem(span, format!("a component of `df::{name}` is not an edf"))),
        }
    }
    Ok(Value::Edf(Edf::Mix { parts, bound }))
}

/// `df::tint(tint, base)` of an edf: its radiance times the tint (a one-component
/// unbounded mix); a tint that depends on the hit is added to `leaves`.
pub fn tint(tint: Option<&Value>, base: &Edf, leaves: &mut Vec<Arc<HitExpr>>, span: Span) -> Eval {
    let t = weight("tint", "tint", tint, Rgb::ONE, leaves, span)?;
    Ok(Value::Edf(Edf::Mix { parts: vec![(t, base.clone())], bound: MixBound::Unbounded }))
}

/// `df::directional_factor(normal_tint, grazing_tint, exponent, base)` of an edf, its
/// arguments given by parameter name by `arg` (those that depend on the hit added to
/// `leaves`).
pub fn directional_factor<'a>(
    arg: &dyn Fn(&str) -> Option<&'a Value>,
    base: &Edf,
    leaves: &mut Vec<Arc<HitExpr>>,
    span: Span,
) -> Eval {
    let f = "directional_factor";
    Ok(Value::Edf(Edf::DirectionalFactor {
        normal: weight(f, "normal_tint", arg("normal_tint"), Rgb::ONE, leaves, span)?,
        grazing: weight(f, "grazing_tint", arg("grazing_tint"), Rgb::ONE, leaves, span)?,
        exponent: weight(f, "exponent", arg("exponent"), Rgb::splat(5.0), leaves, span)?,
        base: Box::new(base.clone()),
    }))
}

/// Whether a weight of the tree depends on the hit (then it is lowered at each hit).
pub fn varies(edf: &Edf) -> bool {
    match edf {
        Edf::Mix { parts, .. } => parts.iter().any(|(w, e)| matches!(w, Leaf::Hit(_)) || varies(e)),
        Edf::DirectionalFactor { normal, grazing, exponent, base } => {
            [normal, grazing, exponent].iter().any(|l| matches!(l, Leaf::Hit(_))) || varies(base)
        }
        Edf::Black | Edf::Diffuse | Edf::Spot(_) | Edf::Measured { .. } => false,
    }
}

/// The tree the renderer evaluates for `edf`, its weights evaluated to `hit` (the values
/// of the material's expressions); `Err` names what is not compiled.
pub fn tree(edf: &Edf, hit: &[Vec4]) -> Result<EdfTree, &'static str> {
    Ok(match edf {
        Edf::Black => EdfTree::Sum(Vec::new()),
        Edf::Diffuse => EdfTree::Diffuse,
        Edf::Spot(spot) => EdfTree::Spot(*spot),
        Edf::Measured { edf, .. } => EdfTree::Measured(edf.clone()),
        Edf::Mix { parts, bound } => {
            let mut sum = Vec::with_capacity(parts.len());
            let mut failed = None;
            mix_weights(parts, *bound, hit, |w, e| match tree(e, hit) {
                Ok(t) => sum.push((w, t)),
                Err(what) => failed = Some(what),
            });
            if let Some(what) = failed {
                return Err(what);
            }
            EdfTree::Sum(sum)
        }
        Edf::DirectionalFactor { normal, grazing, exponent, base } => EdfTree::Factor {
            normal: normal.get(hit),
            grazing: grazing.get(hit),
            exponent: exponent.get(hit).x,
            base: Box::new(tree(base, hit)?),
        },
    })
}

/// The tree with each `measured_edf` in it scaled to emit, per unit of intensity, the
/// power a lone one does in `intensity_power` mode: its multiplier divided by what it
/// emits over the hemisphere of its axis ([`crate::measured_edf::MeasuredEdf::hemisphere_power`];
/// 0 when that is 0). Diffuse and spot components already emit their intensity.
pub fn per_power(edf: &Edf) -> Edf {
    match edf {
        Edf::Measured { edf: m, tangent } => {
            let p = m.hemisphere_power();
            let multiplier = if p > 0.0 { m.multiplier / p } else { 0.0 };
            let scaled = crate::measured_edf::MeasuredEdf::new(m.profile.clone(), multiplier, m.global_frame);
            Edf::Measured { edf: Arc::new(scaled), tangent: tangent.clone() }
        }
        Edf::Mix { parts, bound } => {
            Edf::Mix { parts: parts.iter().map(|(w, e)| (*w, per_power(e))).collect(), bound: *bound }
        }
        Edf::DirectionalFactor { normal, grazing, exponent, base } => Edf::DirectionalFactor {
            normal: *normal,
            grazing: *grazing,
            exponent: *exponent,
            base: Box::new(per_power(base)),
        },
        Edf::Black | Edf::Diffuse | Edf::Spot(_) => edf.clone(),
    }
}

/// The `tangent_u` expressions of the tree's `measured_edf`s in the surface's frame, in
/// order (a profile in a global frame has none).
pub fn measured_tangents(edf: &Edf) -> Vec<Arc<HitExpr>> {
    let mut out = Vec::new();
    fn walk(e: &Edf, out: &mut Vec<Arc<HitExpr>>) {
        match e {
            Edf::Measured { tangent: Some(t), .. } => out.push(t.clone()),
            Edf::Mix { parts, .. } => parts.iter().for_each(|(_, p)| walk(p, out)),
            Edf::DirectionalFactor { base, .. } => walk(base, out),
            Edf::Black | Edf::Diffuse | Edf::Spot(_) | Edf::Measured { .. } => {}
        }
    }
    walk(edf, &mut out);
    out
}
