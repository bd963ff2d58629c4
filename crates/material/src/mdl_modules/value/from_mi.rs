//! Reading a `.mi` parameter value (a number, tuple, boolean, string or enum name) as a
//! value of an MDL parameter's type.

use bsdf::Rgb;
use mdl_lang::Type;
use mi::ast::Value as MiValue;

use super::Value;

/// Reads a `.mi` parameter value as MDL type `ty` (`enum_value` gives the value of an enum
/// value's name); `Err` says what was expected.
pub fn from_mi(value: &MiValue, ty: &Type, enum_value: &dyn Fn(&str, &str) -> Option<i64>) -> Result<Value, String> {
    let nums = |v: &MiValue| -> Option<Vec<f64>> {
        match v {
            MiValue::Num(n) => Some(vec![n.as_f64()]),
            MiValue::Tuple(t) => Some(t.iter().map(|n| n.as_f64()).collect()),
            MiValue::Bool(b) => Some(vec![f64::from(u8::from(*b))]),
            _ => None,
        }
    };
    let kind = match value {
        MiValue::Connect(c) => {
            return Err(format!("a connection to '{}' (MDL function calls as shaders are not compiled yet)", c.text))
        }
        MiValue::Str(_) => "a string",
        MiValue::Null => "null",
        MiValue::Array(_) => "an array",
        MiValue::Struct(_) => "a struct",
        _ => "a number",
    };
    let wrong = |what: &str| Err(format!("expected {what}, found {kind}"));
    match ty {
        Type::Scalar(mdl_lang::ast::Scalar::Bool) => match value {
            MiValue::Bool(b) => Ok(Value::Bool(*b)),
            MiValue::Num(n) => Ok(Value::Bool(n.as_f64() != 0.0)),
            _ => wrong("a boolean"),
        },
        Type::Scalar(mdl_lang::ast::Scalar::Int) => match nums(value).as_deref() {
            Some([x]) => Ok(Value::Int(*x as i64)),
            _ => wrong("an integer"),
        },
        Type::Scalar(_) => match nums(value).as_deref() {
            Some([x]) => Ok(Value::Float(*x)),
            _ => wrong("one number"),
        },
        Type::Color => match nums(value).as_deref() {
            Some([g]) => Ok(Value::Color(Rgb::splat(*g as f32))),
            Some([r, g, b, ..]) => Ok(Value::Color(Rgb::new(*r as f32, *g as f32, *b as f32))),
            _ => wrong("a colour (r g b)"),
        },
        Type::Vector(_, n) => match nums(value) {
            Some(v) if v.len() == *n as usize => Ok(Value::Vector(v)),
            _ => wrong(&format!("{n} numbers")),
        },
        // Column after column, as MDL's `floatCxR(…)` of numbers takes them and as mental
        // ray writes a `transform` (16 numbers, row-vector convention: the same order).
        Type::Matrix(_, c, r) => match nums(value) {
            Some(data) if data.len() == usize::from(*c) * usize::from(*r) => {
                Ok(Value::Matrix { columns: *c, rows: *r, data })
            }
            _ => wrong(&format!("{} numbers, column after column", usize::from(*c) * usize::from(*r))),
        },
        Type::String => match value {
            MiValue::Str(s) => Ok(Value::Str(s.text.clone())),
            _ => wrong("a string"),
        },
        Type::Enum(name) => match value {
            MiValue::Num(n) => Ok(Value::Enum(name.clone(), n.as_f64() as i64)),
            MiValue::Str(s) => enum_value(name, &s.text)
                .map(|v| Value::Enum(name.clone(), v))
                .ok_or_else(|| format!("'{}' is not a value of enum `{name}`", s.text)),
            _ => wrong("an enum value"),
        },
        other => Err(format!("parameters of type `{other}` cannot be set from a .mi file yet")),
    }
}
