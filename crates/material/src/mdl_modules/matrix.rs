//! Constant MDL matrices (`floatCxR`, `doubleCxR`): [`Value::Matrix`], held column by
//! column as MDL defines them (`float4x4(c0, c1, c2, c3)` takes columns). A matrix times a
//! vector on its right treats the vector as a column (`M * v`), on its left as a row
//! (`v * M`); `A * B` is the matrix product; `+`, `-`, `==`, `!=` work element by element
//! on matrices of one shape, and `+ - * /` with a scalar on every element. Matrices that
//! depend on the hit (`state::transform`'s) are [`super::state_space`]'s.

use mdl_lang::ast::BinaryOp;

use super::value::Value;

/// The matrix of `columns` columns of `rows` rows with `d` on its diagonal, 0 elsewhere.
pub fn diagonal(columns: u8, rows: u8, d: f64) -> Value {
    let r = usize::from(rows);
    let data = (0..usize::from(columns) * r).map(|k| if k / r == k % r { d } else { 0.0 }).collect();
    Value::Matrix { columns, rows, data }
}

/// Column `i` of a constant matrix, as a vector of its rows.
pub fn column(m: &Value, i: usize) -> Option<Value> {
    let Value::Matrix { columns, rows, data } = m else { return None };
    let r = usize::from(*rows);
    (i < usize::from(*columns)).then(|| Value::Vector(data[i * r..(i + 1) * r].to_vec()))
}

/// `m` with column `i` replaced by the vector `v` (as long as a column).
pub fn with_column(m: Value, i: usize, v: &Value) -> Option<Value> {
    let Value::Matrix { columns, rows, mut data } = m else { return None };
    let r = usize::from(rows);
    match v {
        Value::Vector(x) if x.len() == r && i < usize::from(columns) => {
            data[i * r..(i + 1) * r].copy_from_slice(x);
            Some(Value::Matrix { columns, rows, data })
        }
        _ => None,
    }
}

/// The transpose of a constant matrix: column j is row j.
pub fn transpose(m: &Value) -> Option<Value> {
    let Value::Matrix { columns, rows, data } = m else { return None };
    let (c, r) = (usize::from(*columns), usize::from(*rows));
    let data = (0..r).flat_map(|j| (0..c).map(move |k| (j, k))).map(|(j, k)| data[k * r + j]).collect();
    Some(Value::Matrix { columns: *rows, rows: *columns, data })
}

/// A constant `float4x4` as a glam matrix (MDL's column-vector convention kept).
pub fn mat4(m: &Value) -> Option<glam::Mat4> {
    match m {
        Value::Matrix { columns: 4, rows: 4, data } => {
            Some(glam::Mat4::from_cols_array(&std::array::from_fn(|k| data[k] as f32)))
        }
        _ => None,
    }
}

/// A glam matrix as a constant `float4x4`.
pub fn from_mat4(m: glam::Mat4) -> Value {
    Value::Matrix { columns: 4, rows: 4, data: m.to_cols_array().iter().map(|x| f64::from(*x)).collect() }
}

/// `-m`.
pub fn negate(m: &Value) -> Option<Value> {
    let Value::Matrix { columns, rows, data } = m else { return None };
    Some(Value::Matrix { columns: *columns, rows: *rows, data: data.iter().map(|x| -x).collect() })
}

/// `a op b` where one side is a constant matrix and the other a constant matrix, vector or
/// scalar; `None` for operators MDL does not define on them or shapes that do not fit.
pub fn binary(op: BinaryOp, a: &Value, b: &Value) -> Option<Value> {
    use BinaryOp::*;
    let elementwise = |columns: u8, rows: u8, data: Vec<f64>| Some(Value::Matrix { columns, rows, data });
    match (a, b) {
        (Value::Matrix { columns: ca, rows: ra, data: x }, Value::Matrix { columns: cb, rows: rb, data: y }) => {
            let same = ca == cb && ra == rb;
            match op {
                Eq if same => Some(Value::Bool(x == y)),
                Ne if same => Some(Value::Bool(x != y)),
                Add | Sub if same => {
                    let s = if op == Add { 1.0 } else { -1.0 };
                    elementwise(*ca, *ra, x.iter().zip(y).map(|(p, q)| p + s * q).collect())
                }
                // Element (i, j) of A·B: row i of A · column j of B.
                Mul if ca == rb => {
                    let (ra_, rb_) = (usize::from(*ra), usize::from(*rb));
                    let data = (0..usize::from(*cb))
                        .flat_map(|j| (0..ra_).map(move |i| (i, j)))
                        .map(|(i, j)| (0..rb_).map(|k| x[k * ra_ + i] * y[j * rb_ + k]).sum())
                        .collect();
                    elementwise(*cb, *ra, data)
                }
                _ => None,
            }
        }
        // M · v, v a column: Σ_k column k · v[k].
        (Value::Matrix { columns, rows, data }, Value::Vector(v)) if op == Mul && v.len() == usize::from(*columns) => {
            let r = usize::from(*rows);
            Some(Value::Vector(
                (0..r).map(|i| v.iter().enumerate().map(|(k, vk)| data[k * r + i] * vk).sum()).collect(),
            ))
        }
        // v · M, v a row: lane j is v · column j.
        (Value::Vector(v), Value::Matrix { columns, rows, data }) if op == Mul && v.len() == usize::from(*rows) => {
            let r = usize::from(*rows);
            Some(Value::Vector(
                (0..usize::from(*columns))
                    .map(|j| v.iter().enumerate().map(|(i, vi)| vi * data[j * r + i]).sum())
                    .collect(),
            ))
        }
        (Value::Matrix { columns, rows, data }, s) => {
            let s = scalar(s)?;
            let f = |x: f64| -> Option<f64> {
                Some(match op {
                    Add => x + s,
                    Sub => x - s,
                    Mul => x * s,
                    Div => x / s,
                    _ => return None,
                })
            };
            elementwise(*columns, *rows, data.iter().map(|x| f(*x)).collect::<Option<_>>()?)
        }
        (s, Value::Matrix { columns, rows, data }) => {
            let s = scalar(s)?;
            let f = |x: f64| -> Option<f64> {
                Some(match op {
                    Add => s + x,
                    Sub => s - x,
                    Mul => s * x,
                    Div => s / x,
                    _ => return None,
                })
            };
            elementwise(*columns, *rows, data.iter().map(|x| f(*x)).collect::<Option<_>>()?)
        }
        _ => None,
    }
}

/// An `int` or `float` operand.
fn scalar(v: &Value) -> Option<f64> {
    match v {
        Value::Int(i) => Some(*i as f64),
        Value::Float(f) => Some(*f),
        _ => None,
    }
}
