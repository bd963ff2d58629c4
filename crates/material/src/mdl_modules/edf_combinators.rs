//! The combinators of emission distributions (`edf`s): `df::tint(color, edf)`,
//! `df::directional_factor(…, edf)` and the mixes of edfs (`normalized_mix`,
//! `clamped_mix`, `unbounded_mix` and their `color_` forms), built as [`Edf`] values with
//! constant weights, and lowered to the [`EdfTree`] the renderer evaluates (the mixes'
//! weights normalised or clamped as for bsdfs, [`mix_weights`]). Their components may be
//! `diffuse_edf`, `spot_edf`, `edf()` and other combinators; a `measured_edf` among them
//! and weights that vary over the surface are not compiled (an error naming them).

use bsdf::Rgb;
use mi::Span;

use super::eval::{problem, Eval, Problem};
use super::natives::mix_weights;
use super::value::{Edf, Leaf, MixBound, Value};
use crate::edf_tree::EdfTree;

/// A constant colour argument `what` of `df::{function}` (a number is a grey).
fn constant(function: &str, what: &str, v: Option<&Value>, default: Rgb, span: Span) -> Result<Rgb, Problem> {
    match v {
        None => Ok(default),
        Some(v) => v.color().filter(|c| c.is_finite()).ok_or_else(|| {
            problem(
                span,
                format!("`df::{function}` of an edf with a `{what}` that varies over the surface is not compiled yet"),
            )
        }),
    }
}

/// `e` itself, or an error at `span` naming `df::{function}` when a `measured_edf` lies in
/// it (its profile and frame are not combined with others yet).
fn combinable(function: &str, e: &Edf, span: Span) -> Result<Edf, Problem> {
    fn has_measured(e: &Edf) -> bool {
        match e {
            Edf::Measured { .. } => true,
            Edf::Mix { parts, .. } => parts.iter().any(|(_, p)| has_measured(p)),
            Edf::DirectionalFactor { base, .. } => has_measured(base),
            Edf::Black | Edf::Diffuse | Edf::Spot(_) => false,
        }
    }
    if has_measured(e) {
        return Err(problem(span, format!("`df::{function}` of a `measured_edf` is not compiled yet")));
    }
    Ok(e.clone())
}

/// `df::{name}` of the edf components `components` (structs of `weight` and `component`).
pub fn mix(name: &str, components: &[Value], bound: MixBound, span: Span) -> Eval {
    let mut parts = Vec::with_capacity(components.len());
    for c in components {
        let w = constant(name, "weight", c.field("weight"), Rgb::ZERO, span)?;
        match c.field("component") {
            Some(Value::Edf(e)) => parts.push((Leaf::Const(w), combinable(name, e, span)?)),
            _ => return Err(problem(span, format!("a component of `df::{name}` is not an edf"))),
        }
    }
    Ok(Value::Edf(Edf::Mix { parts, bound }))
}

/// `df::tint(tint, base)` of an edf: its radiance times the tint (a one-component
/// unbounded mix).
pub fn tint(tint: Option<&Value>, base: &Edf, span: Span) -> Eval {
    let t = constant("tint", "tint", tint, Rgb::ONE, span)?;
    let base = combinable("tint", base, span)?;
    Ok(Value::Edf(Edf::Mix { parts: vec![(Leaf::Const(t), base)], bound: MixBound::Unbounded }))
}

/// `df::directional_factor(normal_tint, grazing_tint, exponent, base)` of an edf, its
/// arguments given by parameter name by `arg`.
pub fn directional_factor<'a>(arg: &dyn Fn(&str) -> Option<&'a Value>, base: &Edf, span: Span) -> Eval {
    let f = "directional_factor";
    Ok(Value::Edf(Edf::DirectionalFactor {
        normal: constant(f, "normal_tint", arg("normal_tint"), Rgb::ONE, span)?,
        grazing: constant(f, "grazing_tint", arg("grazing_tint"), Rgb::ONE, span)?,
        exponent: constant(f, "exponent", arg("exponent"), Rgb::splat(5.0), span)?.x,
        base: Box::new(combinable(f, base, span)?),
    }))
}

/// The tree the renderer evaluates for `edf`; `Err` names what is not compiled.
pub fn tree(edf: &Edf) -> Result<EdfTree, &'static str> {
    Ok(match edf {
        Edf::Black => EdfTree::Sum(Vec::new()),
        Edf::Diffuse => EdfTree::Diffuse,
        Edf::Spot(spot) => EdfTree::Spot(*spot),
        Edf::Measured { .. } => return Err("a measured_edf under a tint, a directional_factor or a mix"),
        Edf::Mix { parts, bound } => {
            let mut sum = Vec::with_capacity(parts.len());
            let mut failed = None;
            mix_weights(parts, *bound, &[], |w, e| match tree(e) {
                Ok(t) => sum.push((w, t)),
                Err(what) => failed = Some(what),
            });
            if let Some(what) = failed {
                return Err(what);
            }
            EdfTree::Sum(sum)
        }
        Edf::DirectionalFactor { normal, grazing, exponent, base } => {
            EdfTree::Factor { normal: *normal, grazing: *grazing, exponent: *exponent, base: Box::new(tree(base)?) }
        }
    })
}
