//! Indexing by an integer of the hit (`a[i]`, `m[i]`, `v[i]` where `i` depends on the
//! shading point, as the counter of a loop of the hit does): a choice per hit between an
//! array's elements, a matrix's columns (constant or of the hit) or a vector's lanes, and
//! assigning through such an index, where each element keeps its value unless the index is
//! its own. MDL leaves an index out of range undefined; mira takes the nearest end (an
//! index below 0 the first element, past the end the last) when reading, and changes
//! nothing when assigning.

use std::sync::Arc;

use glam::Vec4;

use super::hit::{fold, BinOp, HitExpr};
use super::state_space::matrix;
use super::statements::select;
use super::value::{HitType, Value};

/// `v[at]` for an index of the hit: `None` where `v` is not an array, matrix or vector.
pub fn element(v: &Value, at: &Arc<HitExpr>) -> Option<Value> {
    let mut items = parts(v)?.into_iter().enumerate().rev();
    let (_, mut out) = items.next()?;
    // From the last element down: element k where at ≤ k (at is whole).
    for (k, item) in items {
        let here = fold(HitExpr::Binary(BinOp::Lt, at.clone(), number(k as f32 + 1.0)));
        out = select(&here, item, out)?;
    }
    Some(out)
}

/// `whole` with `whole[at] = v` for an index of the hit: each element chosen per hit
/// between `v` (where `at` is its index) and its value. `None` where `whole` is not an
/// array, matrix or vector, or `v` does not fit in it.
pub fn assign(whole: &Value, at: &Arc<HitExpr>, v: &Value) -> Option<Value> {
    let items = parts(whole)?;
    let mut out = Vec::with_capacity(items.len());
    for (k, item) in items.into_iter().enumerate() {
        let here = fold(HitExpr::Binary(BinOp::Eq, at.clone(), number(k as f32)));
        out.push(select(&here, converted(v, &item), item)?);
    }
    match whole {
        Value::Array(_) => Some(Value::Array(out)),
        Value::Matrix { rows, .. } => {
            let columns = out
                .iter()
                .map(|c| c.to_hit().filter(|_| c.hit_type() == Some(HitType::Vector(*rows))))
                .collect::<Option<_>>()?;
            Some(matrix(columns, *rows))
        }
        _ => {
            let width = whole.hit_type()?.width();
            let lanes = out
                .iter()
                .map(|x| x.to_hit().filter(|_| x.hit_type().is_some_and(|t| t.width() == 1)).map(|e| (e, 1)))
                .collect::<Option<Box<[_]>>>()?;
            Some(Value::from_hit(HitExpr::Compose(lanes), HitType::Vector(width)))
        }
    }
}

/// What an index chooses between: an array's elements, a matrix's columns, a vector's
/// lanes (as `float`s).
fn parts(v: &Value) -> Option<Vec<Value>> {
    match v {
        Value::Array(items) if !items.is_empty() => Some(items.clone()),
        Value::Matrix { columns, .. } => (0..usize::from(*columns)).map(|i| super::matrix::column(v, i)).collect(),
        Value::Vector(x) if !x.is_empty() => Some(x.iter().map(|f| Value::Float(*f)).collect()),
        Value::Hit(e, HitType::Vector(n)) => {
            Some((0..*n).map(|k| Value::from_hit(HitExpr::Lane(e.clone(), k), HitType::Float)).collect())
        }
        _ => None,
    }
    .filter(|items| !items.is_empty())
}

/// `v` as a value of `like`'s type where MDL converts implicitly (an int stored in a
/// float).
fn converted(v: &Value, like: &Value) -> Value {
    match (v, like.hit_type()) {
        (Value::Int(i), Some(HitType::Float)) => Value::Float(*i as f64),
        (Value::Hit(e, HitType::Int), Some(HitType::Float)) => Value::Hit(e.clone(), HitType::Float),
        _ => v.clone(),
    }
}

/// A scalar constant.
fn number(x: f32) -> Arc<HitExpr> {
    Arc::new(HitExpr::Const(Vec4::splat(x)))
}
