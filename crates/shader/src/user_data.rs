//! User data elements (`data "name" "declaration" ( … )`) as shaders read them, and which
//! of them each instance's object carries (its `data "name"` statements): mental ray's
//! `mi_query(miQ_DATA_…)` on the hit object's data chain.
//!
//! The values are read as written, without their declaration: a number written without a
//! point is an integer, with one a scalar; several numbers in a row are a vector (three) or
//! a colour (four); strings, `{ … }` structs and `[ … ]` arrays keep their shape. Raw-byte
//! and file payloads have no parameters (an empty struct).

use std::sync::Arc;

use glam::{Vec3A, Vec4};
use mi::ast::{self, DataBody, Num};

use super::value::Value;

/// One `data` element of the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct UserData {
    /// Its full name.
    pub name: Arc<str>,
    /// The `declare data` name it was written with (`None`: raw bytes or a file).
    pub declaration: Option<Arc<str>>,
    /// Its parameters as a struct (named members in the order written).
    pub value: Value,
}

impl UserData {
    /// Reads `data` as written.
    pub fn read(data: &ast::Data) -> UserData {
        let (declaration, value) = match &data.body {
            DataBody::Params { decl, params } => (Some(Arc::from(decl.text.as_str())), params_value(params)),
            DataBody::Bytes { .. } | DataBody::File(_) => (None, Value::Struct(Arc::from([]))),
        };
        UserData { name: Arc::from(data.name.text.as_str()), declaration, value }
    }

    /// The member `name` of its parameters.
    pub fn member(&self, name: &str) -> Option<&Value> {
        member(&self.value, name)
    }
}

/// The member `name` of a struct value.
pub fn member<'v>(value: &'v Value, name: &str) -> Option<&'v Value> {
    match value {
        Value::Struct(members) => members.iter().find(|(n, _)| &**n == name).map(|(_, v)| v),
        _ => None,
    }
}

fn params_value(params: &[ast::Param]) -> Value {
    Value::Struct(params.iter().map(|p| (Arc::from(p.name.text.as_str()), value(&p.value))).collect())
}

fn num(n: Num) -> Value {
    match n {
        Num::Int(i) => Value::Int(i32::try_from(i).unwrap_or(if i < 0 { i32::MIN } else { i32::MAX })),
        Num::Float(f) => Value::Scalar(f as f32),
    }
}

fn value(v: &ast::Value) -> Value {
    match v {
        ast::Value::Bool(b) => Value::Bool(*b),
        ast::Value::Num(n) => num(*n),
        ast::Value::Tuple(t) => {
            let f: Vec<f32> = t.iter().map(|n| n.as_f64() as f32).collect();
            match f.as_slice() {
                [x, y, z] => Value::Vector(Vec3A::new(*x, *y, *z)),
                [r, g, b, a] => Value::Color(Vec4::new(*r, *g, *b, *a)),
                _ => Value::Array(t.iter().map(|n| num(*n)).collect()),
            }
        }
        ast::Value::Str(s) => Value::Str(Arc::from(s.text.as_str())),
        ast::Value::Struct(params) => params_value(params),
        // `[ { … } { … } ]` (Maya's nomenclature blocks leave out the commas) reads as one
        // run of values inside the array: its values are the array's elements.
        ast::Value::Array(items) => Value::Array(
            items
                .iter()
                .flat_map(|v| match v {
                    ast::Value::Seq(run) => run.iter().map(value).collect(),
                    v => vec![value(v)],
                })
                .collect(),
        ),
        ast::Value::Seq(items) => Value::Array(items.iter().map(value).collect()),
        ast::Value::Null | ast::Value::Connect(_) | ast::Value::Interface(_) | ast::Value::Define(_) => Value::Null,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Maya per-vertex nomenclature block reads back with its shape: an integer, arrays
    /// of structs with a string and an integer.
    #[test]
    fn a_data_block_reads_as_written() {
        let text = r#"
declare data "D" (integer "n", scalar "s", array struct "tex" { string "name", integer "index" }) end declare
data "d" "D" ("n" 5149248936, "s" 0.5, "v" 1 2 3, "tex" [ { "name" "uvset1", "index" 0 } { "name" "map2", "index" 1 } ])
"#;
        let parsed = mi::parse_str("d.mi", text);
        assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
        let data = parsed
            .items
            .iter()
            .find_map(|i| if let ast::Item::Data(d) = i { Some(d) } else { None })
            .expect("a data element");
        let d = UserData::read(data);
        assert_eq!(d.declaration.as_deref(), Some("D"));
        assert_eq!(d.member("n"), Some(&Value::Int(i32::MAX)), "out of range integers saturate");
        assert_eq!(d.member("s"), Some(&Value::Scalar(0.5)));
        assert_eq!(d.member("v"), Some(&Value::Vector(Vec3A::new(1.0, 2.0, 3.0))));
        let Some(Value::Array(tex)) = d.member("tex") else { panic!("tex is {:?}", d.member("tex")) };
        assert_eq!(tex.len(), 2);
        assert_eq!(member(&tex[1], "name"), Some(&Value::Str(Arc::from("map2"))));
        assert_eq!(member(&tex[1], "index"), Some(&Value::Int(1)));
    }
}
