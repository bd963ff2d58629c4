//! `state::` transforms between object and world space (`transform`, `transform_point`,
//! `transform_vector`, `transform_normal`, `transform_scale`), built as [`HitExpr`] trees
//! over the hit instance's matrices at the ray's time ([`StateFn::ObjectToWorld`],
//! [`StateFn::WorldToObject`]: the shading state holds them for every hit, so materials
//! that do not use them cost nothing more).
//!
//! mira's internal space is world space: `coordinate_internal` and `coordinate_world` are
//! the same space, and a transform between them is the identity. Points and vectors go
//! through the matrix (vectors without its translation), normals through its inverse
//! transpose (not renormalized, as MDL defines them), a scale by the mean length of the
//! images of the three axes.

use std::sync::Arc;

use mi::Span;

use super::eval::{kind, problem, Eval};
use super::hit::{fold, BinOp, HitExpr, MathFn, StateFn};
use super::value::{HitType, Value};

/// A matrix of the hit instance, by its columns ([`StateFn::ObjectToWorld`] or
/// [`StateFn::WorldToObject`]).
type Columns = fn(u8) -> StateFn;

/// `state::coordinate_object`'s value (`coordinate_internal` 0, `coordinate_world` 2).
const COORDINATE_OBJECT: i64 = 1;

/// `state::name(from, to, …)` with its arguments `args`.
pub fn transform(name: &str, args: &[Value], span: Span) -> Eval {
    let space = |i: usize| match args.get(i) {
        Some(Value::Enum(_, s) | Value::Int(s)) => Ok(*s == COORDINATE_OBJECT),
        Some(v) => Err(problem(span, format!("`state::{name}` from or to a space that is {}", kind(v)))),
        None => Err(problem(span, format!("`state::{name}` without its spaces"))),
    };
    let (from_object, to_object) = (space(0)?, space(1)?);
    // The matrix that carries `from` to `to`, and its inverse; `None`: the identity.
    let pair: (Columns, Columns) = if from_object {
        (StateFn::ObjectToWorld, StateFn::WorldToObject)
    } else {
        (StateFn::WorldToObject, StateFn::ObjectToWorld)
    };
    let matrices = (from_object != to_object).then_some(pair);
    if name == "transform" {
        let Some((m, _)) = matrices else { return Ok(identity()) };
        // The columns as four-vectors: the axes with w = 0, the translation with w = 1.
        let columns = (0..4u8)
            .map(|i| {
                let w = if i == 3 { 1.0 } else { 0.0 };
                Value::from_hit(HitExpr::Compose([(column(m, i), 3), (constant(w), 1)].into()), HitType::Vector(4))
            })
            .collect();
        return Ok(Value::Array(columns));
    }
    let operand = args.get(2).ok_or_else(|| problem(span, format!("`state::{name}` without its value")))?;
    let Some((m, inv)) = matrices else { return Ok(operand.clone()) };
    let of = operand.to_hit().ok_or_else(|| problem(span, format!("`state::{name}` of {}", kind(operand))))?;
    let lane = |i: u8| fold(HitExpr::Lane(of.clone(), i));
    let e = match name {
        "transform_point" | "transform_vector" => {
            let mut sum = mul(column(m, 0), lane(0));
            for i in 1..3 {
                sum = add(sum, mul(column(m, i), lane(i)));
            }
            if name == "transform_point" {
                sum = add(sum, column(m, 3));
            }
            return Ok(Value::from_hit((*sum).clone(), HitType::Vector(3)));
        }
        // Through the inverse transpose: component i is column i of the inverse · n.
        "transform_normal" => HitExpr::Compose(
            (0..3).map(|i| (fold(HitExpr::Math(MathFn::Dot(3), [column(inv, i), of.clone()].into())), 1)).collect(),
        ),
        "transform_scale" => {
            let length = |i: u8| fold(HitExpr::Math(MathFn::Length(3), [column(m, i)].into()));
            let mean = mul(add(add(length(0), length(1)), length(2)), constant(1.0 / 3.0));
            return Ok(Value::from_hit(HitExpr::Binary(BinOp::Mul, mean, lane(0)), HitType::Float));
        }
        _ => return Err(problem(span, format!("`state::{name}` is not compiled yet"))),
    };
    Ok(Value::from_hit(e, HitType::Vector(3)))
}

/// `m * v` for a matrix that depends on the hit (four column values, as
/// [`transform`] builds it) and a `float4` (or `float3`: its lanes times the first three
/// columns); `None` when the operands are not those.
pub fn matrix_times(columns: &[Value], v: &Value) -> Option<Value> {
    if columns.len() != 4 {
        return None;
    }
    let width = v.hit_type()?.width();
    if !(3..=4).contains(&width) {
        return None;
    }
    let of = v.to_hit()?;
    let mut sum: Option<Arc<HitExpr>> = None;
    for (i, c) in columns.iter().enumerate().take(usize::from(width)) {
        let term = mul(c.to_hit()?, fold(HitExpr::Lane(of.clone(), i as u8)));
        sum = Some(match sum {
            Some(s) => add(s, term),
            None => term,
        });
    }
    Some(Value::from_hit((*sum?).clone(), HitType::Vector(width)))
}

/// The 4×4 identity (column-major, as constant matrices are held).
fn identity() -> Value {
    Value::Vector((0..16).map(|k| if k % 5 == 0 { 1.0 } else { 0.0 }).collect())
}

fn column(m: Columns, i: u8) -> Arc<HitExpr> {
    Arc::new(HitExpr::State(m(i)))
}

fn constant(x: f32) -> Arc<HitExpr> {
    Arc::new(HitExpr::Const(glam::Vec4::splat(x)))
}

fn mul(a: Arc<HitExpr>, b: Arc<HitExpr>) -> Arc<HitExpr> {
    fold(HitExpr::Binary(BinOp::Mul, a, b))
}

fn add(a: Arc<HitExpr>, b: Arc<HitExpr>) -> Arc<HitExpr> {
    fold(HitExpr::Binary(BinOp::Add, a, b))
}
