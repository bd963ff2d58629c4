//! Reading keyword statements and attributes into typed values.

use std::collections::BTreeMap;

use mi::ast::{Arg, Attribute, KwStmt, Num, Stmt, Value};

/// A typed attribute or string-option value.
#[derive(Clone, Debug, PartialEq)]
pub enum AttrValue {
    /// `boolean`
    Bool(bool),
    /// `integer`
    Int(i64),
    /// `scalar`
    Float(f64),
    /// `string`
    Str(String),
    /// Several numbers (`color`, `vector`).
    Floats(Vec<f64>),
}

impl AttrValue {
    /// The value as a number (booleans as 0/1).
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            AttrValue::Bool(b) => Some(f64::from(u8::from(*b))),
            AttrValue::Int(i) => Some(*i as f64),
            AttrValue::Float(f) => Some(*f),
            AttrValue::Floats(v) => v.first().copied(),
            AttrValue::Str(s) => s.parse().ok(),
        }
    }

    /// The value as a boolean (numbers: non-zero; strings: on/true/yes).
    pub fn as_bool(&self) -> Option<bool> {
        match self {
            AttrValue::Bool(b) => Some(*b),
            AttrValue::Str(s) => match s.as_str() {
                "on" | "true" | "yes" | "1" => Some(true),
                "off" | "false" | "no" | "0" => Some(false),
                _ => None,
            },
            other => other.as_f64().map(|v| v != 0.0),
        }
    }

    /// The value as a string, if it is one.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            AttrValue::Str(s) => Some(s),
            _ => None,
        }
    }

    /// From a syntax value (`None` for connections and other non-constant values).
    pub fn from_value(v: &Value) -> Option<AttrValue> {
        Some(match v {
            Value::Bool(b) => AttrValue::Bool(*b),
            Value::Num(Num::Int(i)) => AttrValue::Int(*i),
            Value::Num(Num::Float(f)) => AttrValue::Float(*f),
            Value::Tuple(ns) => AttrValue::Floats(ns.iter().map(|n| n.as_f64()).collect()),
            Value::Str(s) => AttrValue::Str(s.text.clone()),
            _ => return None,
        })
    }
}

/// Typed attributes (`attribute type "name" value`) and string options by name; the last
/// definition wins.
pub type Attributes = BTreeMap<String, AttrValue>;

/// Collects the attributes of statements.
pub fn attributes(stmts: &[&Stmt]) -> Attributes {
    let mut out = Attributes::new();
    for s in stmts {
        if let Stmt::Attribute(Attribute { name: Some(name), value: Some(v), .. }) = s {
            if let Some(v) = AttrValue::from_value(v) {
                out.insert(name.text.clone(), v);
            }
        }
    }
    out
}

/// The last keyword statement with `key`.
pub fn last<'a>(stmts: &[&'a Stmt], key: &str) -> Option<&'a KwStmt> {
    stmts.iter().rev().find_map(|s| match s {
        Stmt::Kw(k) if k.key == key => Some(k),
        _ => None,
    })
}

/// Argument `i` as a number.
pub fn f64_arg(k: &KwStmt, i: usize) -> Option<f64> {
    match k.args.get(i)? {
        Arg::Int(v) => Some(*v as f64),
        Arg::Float(v) => Some(*v),
        Arg::Num(n) => Some(n.as_f64()),
        _ => None,
    }
}

/// Argument `i` as an integer.
pub fn int_arg(k: &KwStmt, i: usize) -> Option<i64> {
    match k.args.get(i)? {
        Arg::Int(v) => Some(*v),
        Arg::Num(Num::Int(v)) => Some(*v),
        _ => None,
    }
}

/// Argument `i` as a boolean (an absent argument of a bare flag means on).
pub fn bool_arg(k: &KwStmt, i: usize) -> bool {
    match k.args.get(i) {
        Some(Arg::Bool(b)) => *b,
        Some(Arg::Int(v)) => *v != 0,
        _ => true,
    }
}

/// Argument `i` as a word or name.
pub fn str_arg(k: &KwStmt, i: usize) -> Option<&str> {
    match k.args.get(i)? {
        Arg::Word(w) => Some(w),
        Arg::Name(n) => Some(&n.text),
        _ => None,
    }
}

/// Argument `i` as a group of numbers (colour, vector, matrix).
pub fn floats_arg(k: &KwStmt, i: usize) -> Option<&[f64]> {
    match k.args.get(i)? {
        Arg::Floats(v) => Some(v),
        _ => None,
    }
}
