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
//! `float4`s of the hit); so is a `floatCxR(…)` built from values of the hit, and a choice
//! between matrices by a condition of the hit. It may be multiplied with a vector (either
//! side), a matrix (of the hit, or a constant [`Value::Matrix`]) or a scalar, added to and
//! subtracted from another, combined with a scalar (`+ - * /`, either side, element by
//! element), negated, transposed (`math::transpose`) and indexed (`m[i]` its column i,
//! `m[i][j]` or `m[i].y` an element; by an index of the hit see [`super::hit_index`]):
//! each result is built from the columns, lane by lane; a constant matrix with a vector or
//! scalar of the hit likewise.

use std::sync::Arc;

use mdl_lang::ast::BinaryOp;
use mi::Span;

use super::eval::{kind, problem, Eval};
use super::hit::{fold, BinOp, HitExpr, MathFn, StateFn, UnOp};
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

/// The columns of a matrix and the length of each: one of the hit (two to four column
/// values of one width, as [`transform`] and [`construct`] build them) or a constant
/// [`Value::Matrix`]; `None` for anything else.
pub(super) fn columns_of(m: &Value) -> Option<(Vec<Arc<HitExpr>>, u8)> {
    match m {
        Value::Array(columns) if (2..=4).contains(&columns.len()) => {
            let rows = columns[0].hit_type().filter(|t| matches!(t, HitType::Vector(2..=4)))?;
            let cs =
                columns.iter().map(|c| c.to_hit().filter(|_| c.hit_type() == Some(rows))).collect::<Option<_>>()?;
            Some((cs, rows.width()))
        }
        Value::Matrix { rows, data, .. } => {
            let columns = data
                .chunks(usize::from(*rows))
                .map(|c| {
                    let mut lanes = [0.0f32; 4];
                    for (l, x) in lanes.iter_mut().zip(c) {
                        *l = *x as f32;
                    }
                    Arc::new(HitExpr::Const(glam::Vec4::from_array(lanes)))
                })
                .collect();
            Some((columns, *rows))
        }
        _ => None,
    }
}

/// Whether `v` is a matrix of the hit: an array of column vectors of one width, four of
/// them or some of the hit (an array of constant vectors is a matrix after an operation on
/// the hit folded it column by column).
fn hit_matrix(v: &Value) -> bool {
    let Value::Array(columns) = v else { return false };
    (columns.len() == 4 || columns.iter().any(|c| matches!(c, Value::Hit(..)))) && columns_of(v).is_some()
}

/// A matrix of the given columns of `rows` lanes: a constant [`Value::Matrix`] where every
/// column is constant, else a matrix of the hit.
pub(super) fn matrix(columns: Vec<Arc<HitExpr>>, rows: u8) -> Value {
    if let Some(cs) = columns.iter().map(|c| c.constant()).collect::<Option<Vec<_>>>() {
        let data = cs.iter().flat_map(|c| c.to_array()[..usize::from(rows)].to_vec()).map(f64::from).collect();
        return Value::Matrix { columns: columns.len() as u8, rows, data };
    }
    Value::Array(columns.into_iter().map(|c| Value::Hit(c, HitType::Vector(rows))).collect())
}

/// `floatCxR(…)` of `values` some of which depend on the hit: `columns` vectors of `rows`
/// lanes (the columns), or `columns · rows` scalars column after column; a matrix of the
/// hit ([`columns_of`]'s form). `None` for other arguments.
pub fn construct(columns: u8, rows: u8, values: &[Value]) -> Option<Value> {
    let (c, r) = (usize::from(columns), usize::from(rows));
    let exprs: Vec<Arc<HitExpr>> = if values.len() == c {
        values
            .iter()
            .map(|v| v.to_hit().filter(|_| v.hit_type() == Some(HitType::Vector(rows))))
            .collect::<Option<_>>()?
    } else if values.len() == c * r {
        let scalars: Vec<Arc<HitExpr>> = values
            .iter()
            .map(|v| v.to_hit().filter(|_| matches!(v.hit_type(), Some(HitType::Float | HitType::Int))))
            .collect::<Option<_>>()?;
        scalars.chunks(r).map(|col| fold(HitExpr::Compose(col.iter().map(|x| (x.clone(), 1)).collect()))).collect()
    } else {
        return None;
    };
    Some(matrix(exprs, rows))
}

/// `cond ? a : b` for matrices (constant or of the hit) of one shape and a condition of
/// the hit: column by column; `None` when `a` and `b` are not such matrices.
pub fn select(cond: &Arc<HitExpr>, a: &Value, b: &Value) -> Option<Value> {
    if !matches!(a, Value::Matrix { .. } | Value::Array(_)) {
        return None;
    }
    let ((ca, ra), (cb, rb)) = (columns_of(a)?, columns_of(b)?);
    if ca.len() != cb.len() || ra != rb {
        return None;
    }
    Some(matrix(ca.into_iter().zip(cb).map(|(x, y)| fold(HitExpr::Select(cond.clone(), x, y))).collect(), ra))
}

/// `a op b` where one side is a matrix of the hit ([`transform`]'s, [`construct`]'s), or a
/// constant matrix meets a vector of the hit: with a vector (a column vector on the right,
/// a row vector on the left), another matrix (of the hit or constant), a scalar; matrices
/// added or subtracted. `None` when the operands are not those.
pub fn matrix_binary(op: BinaryOp, a: &Value, b: &Value) -> Option<Value> {
    let constant_matrix = |v: &Value| matches!(v, Value::Matrix { .. });
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
        (BinaryOp::Mul, Some((ma, ra)), Some((mb, rb))) if ma.len() == usize::from(rb) => {
            // Column j of A·B: A's columns weighted by the lanes of B's column j.
            let columns = mb
                .iter()
                .map(|bj| {
                    (0..rb)
                        .map(|k| mul(ma[usize::from(k)].clone(), fold(HitExpr::Lane(bj.clone(), k))))
                        .reduce(add)
                        .unwrap_or_else(|| constant(0.0))
                })
                .collect();
            Some(matrix(columns, ra))
        }
        (BinaryOp::Mul, Some((ma, ra)), None) if !scalar(b) => matrix_times(&ma, ra, b),
        (BinaryOp::Mul, None, Some((mb, rb))) if !scalar(a) => {
            // A row vector times the matrix: lane j is its dot product with column j (a
            // `float3` with a 4×4 matrix: its first three rows and columns).
            let width = a.hit_type()?.width();
            let n = if width == rb { mb.len() } else { usize::from(width) };
            if !(2..=4).contains(&width) || width > rb || n > mb.len() {
                return None;
            }
            let v = a.to_hit()?;
            let lanes = mb
                .iter()
                .take(n)
                .map(|c| (fold(HitExpr::Math(MathFn::Dot(width), [v.clone(), c.clone()].into())), 1))
                .collect();
            Some(Value::from_hit(HitExpr::Compose(lanes), HitType::Vector(n as u8)))
        }
        // With a scalar: element by element, the scalar on either side.
        (BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div, Some((m, r)), None) if scalar(b) => {
            let s = b.to_hit()?;
            Some(matrix(
                m.into_iter().map(|c| within(fold(HitExpr::Binary(elementwise(op), c, s.clone())), r)).collect(),
                r,
            ))
        }
        (BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div, None, Some((m, r))) if scalar(a) => {
            let s = a.to_hit()?;
            Some(matrix(
                m.into_iter().map(|c| within(fold(HitExpr::Binary(elementwise(op), s.clone(), c)), r)).collect(),
                r,
            ))
        }
        (BinaryOp::Add | BinaryOp::Sub, Some((ma, ra)), Some((mb, rb))) if ma.len() == mb.len() && ra == rb => {
            let hop = if op == BinaryOp::Add { BinOp::Add } else { BinOp::Sub };
            Some(matrix(ma.into_iter().zip(mb).map(|(x, y)| fold(HitExpr::Binary(hop, x, y))).collect(), ra))
        }
        _ => None,
    }
}

/// The per-lane operator of an arithmetic operator on matrices and scalars.
fn elementwise(op: BinaryOp) -> BinOp {
    match op {
        BinaryOp::Add => BinOp::Add,
        BinaryOp::Sub => BinOp::Sub,
        BinaryOp::Div => BinOp::Div,
        _ => BinOp::Mul,
    }
}

/// Column `c` of `rows` lanes with the lanes past them 0 (a scalar added to a column fills
/// all four).
fn within(c: Arc<HitExpr>, rows: u8) -> Arc<HitExpr> {
    if rows >= 4 {
        c
    } else {
        fold(HitExpr::Compose([(c, rows)].into()))
    }
}

/// Matrix `m` (constant or of the hit) with column `i` replaced by the vector `v` (of the
/// hit, or constant) as long as a column; `None` for anything else.
pub fn with_column(m: &Value, i: usize, v: &Value) -> Option<Value> {
    let (mut columns, rows) = columns_of(m)?;
    let c = v.to_hit().filter(|_| v.hit_type() == Some(HitType::Vector(rows)))?;
    *columns.get_mut(i)? = c;
    Some(matrix(columns, rows))
}

/// `-m` for a matrix of the hit, column by column; `None` for anything else.
pub fn negate(m: &Value) -> Option<Value> {
    if !hit_matrix(m) {
        return None;
    }
    let (columns, rows) = columns_of(m)?;
    Some(matrix(columns.into_iter().map(|c| fold(HitExpr::Unary(UnOp::Neg, c))).collect(), rows))
}

/// `math::transpose` of a matrix of the hit (column j is lane j of each column) or of a
/// constant matrix ([`super::matrix::transpose`]).
pub fn transpose(m: &Value) -> Option<Value> {
    if matches!(m, Value::Matrix { .. }) {
        return super::matrix::transpose(m);
    }
    if !matches!(m, Value::Array(_)) {
        return None;
    }
    let (columns, rows) = columns_of(m)?;
    let rows_as_columns = (0..rows)
        .map(|j| {
            let parts = columns.iter().map(|c| (fold(HitExpr::Lane(c.clone(), j)), 1)).collect();
            fold(HitExpr::Compose(parts))
        })
        .collect();
    Some(matrix(rows_as_columns, columns.len() as u8))
}

/// `m * v` for a matrix of columns of `rows` lanes (of the hit, or constant) and a vector
/// as long as a row (or, for four columns, a `float3`: its lanes times the first three
/// columns); `None` when the operands are not those.
fn matrix_times(columns: &[Arc<HitExpr>], rows: u8, v: &Value) -> Option<Value> {
    let width = v.hit_type()?.width();
    if !(2..=4).contains(&width) || usize::from(width) > columns.len() {
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
    let ty = if usize::from(width) == columns.len() { rows } else { width };
    Some(Value::from_hit((*sum?).clone(), HitType::Vector(ty)))
}

/// The 4×4 identity.
fn identity() -> Value {
    super::matrix::diagonal(4, 4, 1.0)
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
