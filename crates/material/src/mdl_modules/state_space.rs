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
//!
//! `state::transform`'s matrix is a matrix of the hit: four column values (an array of
//! `float4`s of the hit). It may be multiplied with a vector (either side), a matrix (of
//! the hit, or a constant `float4x4`) or a scalar, added to and subtracted from another,
//! divided by a scalar, transposed (`math::transpose`) and indexed (`m[i]` its column i,
//! `m[i][j]` or `m[i].y` an element): each result is built from the columns, lane by lane.

use std::sync::Arc;

use mdl_lang::ast::BinaryOp;
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

/// The columns of a 4×4 matrix: one of the hit (four `float4` column values, as
/// [`transform`] builds it) or a constant `float4x4` (16 numbers, column by column); `None`
/// for anything else.
fn columns_of(m: &Value) -> Option<Vec<Arc<HitExpr>>> {
    match m {
        Value::Array(columns) if columns.len() == 4 => {
            columns.iter().map(|c| c.to_hit().filter(|_| c.hit_type() == Some(HitType::Vector(4)))).collect()
        }
        Value::Vector(v) if v.len() == 16 => Some(
            v.chunks(4)
                .map(|c| Arc::new(HitExpr::Const(glam::Vec4::new(c[0] as f32, c[1] as f32, c[2] as f32, c[3] as f32))))
                .collect(),
        ),
        _ => None,
    }
}

/// A matrix of the given columns: a constant `float4x4` where every column is constant,
/// else a matrix of the hit.
fn matrix(columns: Vec<Arc<HitExpr>>) -> Value {
    if let Some(cs) = columns.iter().map(|c| c.constant()).collect::<Option<Vec<_>>>() {
        return Value::Vector(cs.iter().flat_map(|c| c.to_array()).map(f64::from).collect());
    }
    Value::Array(columns.into_iter().map(|c| Value::Hit(c, HitType::Vector(4))).collect())
}

/// `a op b` where one side is a matrix of the hit ([`transform`]'s), or a constant
/// `float4x4` meets a vector of the hit: with a vector (a column vector on the right, a
/// row vector on the left), another matrix (of the hit or constant), a scalar; matrices
/// added or subtracted. `None` when the operands are not those.
pub fn matrix_binary(op: BinaryOp, a: &Value, b: &Value) -> Option<Value> {
    let hit_matrix = |v: &Value| matches!(v, Value::Array(c) if c.len() == 4);
    let constant_matrix = |v: &Value| matches!(v, Value::Vector(x) if x.len() == 16);
    let hit = |v: &Value| matches!(v, Value::Hit(..));
    let involved = hit_matrix(a) || hit_matrix(b) || (constant_matrix(a) && hit(b)) || (hit(a) && constant_matrix(b));
    if !involved {
        return None;
    }
    let (ma, mb) = (columns_of(a), columns_of(b));
    let scalar = |v: &Value| {
        matches!(v.hit_type(), Some(HitType::Float | HitType::Int))
            && !matches!(v, Value::Array(_))
            && v.to_hit().is_some()
    };
    match (op, ma, mb) {
        (BinaryOp::Mul, Some(ma), Some(mb)) => {
            // Column j of A·B: A's columns weighted by the lanes of B's column j.
            let columns = mb
                .iter()
                .map(|bj| {
                    (0..4u8)
                        .map(|k| mul(ma[usize::from(k)].clone(), fold(HitExpr::Lane(bj.clone(), k))))
                        .reduce(add)
                        .unwrap_or_else(|| constant(0.0))
                })
                .collect();
            Some(matrix(columns))
        }
        (BinaryOp::Mul, Some(ma), None) if !scalar(b) => matrix_times(&ma, b),
        (BinaryOp::Mul, None, Some(mb)) if !scalar(a) => {
            // A row vector times the matrix: lane j is its dot product with column j.
            let width = a.hit_type()?.width();
            if !(3..=4).contains(&width) {
                return None;
            }
            let v = a.to_hit()?;
            let lanes = mb
                .iter()
                .take(usize::from(width))
                .map(|c| (fold(HitExpr::Math(MathFn::Dot(width), [v.clone(), c.clone()].into())), 1))
                .collect();
            Some(Value::from_hit(HitExpr::Compose(lanes), HitType::Vector(width)))
        }
        (BinaryOp::Mul | BinaryOp::Div, Some(m), None) if scalar(b) => {
            let s = b.to_hit()?;
            let hop = if op == BinaryOp::Mul { BinOp::Mul } else { BinOp::Div };
            Some(matrix(m.into_iter().map(|c| fold(HitExpr::Binary(hop, c, s.clone()))).collect()))
        }
        (BinaryOp::Mul, None, Some(m)) if scalar(a) => {
            let s = a.to_hit()?;
            Some(matrix(m.into_iter().map(|c| mul(s.clone(), c)).collect()))
        }
        (BinaryOp::Add | BinaryOp::Sub, Some(ma), Some(mb)) => {
            let hop = if op == BinaryOp::Add { BinOp::Add } else { BinOp::Sub };
            Some(matrix(ma.into_iter().zip(mb).map(|(x, y)| fold(HitExpr::Binary(hop, x, y))).collect()))
        }
        _ => None,
    }
}

/// `math::transpose` of a matrix of the hit (or of a constant `float4x4`): column j is
/// lane j of each column.
pub fn transpose(m: &Value) -> Option<Value> {
    if !matches!(m, Value::Array(_)) {
        return None;
    }
    let columns = columns_of(m)?;
    let rows = (0..4u8)
        .map(|j| {
            let parts = columns.iter().map(|c| (fold(HitExpr::Lane(c.clone(), j)), 1)).collect();
            fold(HitExpr::Compose(parts))
        })
        .collect();
    Some(matrix(rows))
}

/// `m * v` for a matrix of four columns (of the hit, or constant) and a `float4` (or
/// `float3`: its lanes times the first three columns); `None` when the operands are not
/// those.
fn matrix_times(columns: &[Arc<HitExpr>], v: &Value) -> Option<Value> {
    let width = v.hit_type()?.width();
    if !(3..=4).contains(&width) {
        return None;
    }
    let of = v.to_hit()?;
    let mut sum: Option<Arc<HitExpr>> = None;
    for (i, c) in columns.iter().enumerate().take(usize::from(width)) {
        let term = mul(c.clone(), fold(HitExpr::Lane(of.clone(), i as u8)));
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
