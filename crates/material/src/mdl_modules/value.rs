//! The values an MDL material expression evaluates to once per material instance: numbers,
//! colours, enums, structs (the `material` struct and its parts) and distribution
//! functions ([`Df`], [`Edf`]), and reading a `.mi` parameter value as one of them.

use bsdf::Rgb;
use mdl_lang::Type;
use mi::ast::Value as MiValue;

/// A distribution function tree (MDL `bsdf`), with every parameter constant.
#[derive(Clone, Debug, PartialEq)]
pub enum Df {
    /// `bsdf()`: black, scatters nothing.
    Black,
    /// `df::diffuse_reflection_bsdf`: tint and Oren–Nayar roughness σ (radians, 0 Lambert).
    Diffuse {
        /// Reflectance.
        tint: Rgb,
        /// Oren–Nayar σ.
        roughness: f32,
    },
    /// `df::diffuse_transmission_bsdf`.
    DiffuseTransmission(Rgb),
    /// `df::specular_bsdf`: tint and whether it reflects, transmits or both.
    Specular {
        /// Tint.
        tint: Rgb,
        /// The scatter mode.
        mode: ScatterMode,
    },
    /// `df::simple_glossy_bsdf` and `df::microfacet_*_bsdf`: GGX with α = roughness.
    Glossy {
        /// Tint.
        tint: Rgb,
        /// GGX α along u and v.
        roughness: (f32, f32),
        /// The scatter mode.
        mode: ScatterMode,
    },
    /// A mix of weighted components (`normalized_mix`, `clamped_mix` and the `color_`
    /// forms, `tint`): the weights already normalized or clamped.
    Mix(Vec<(Rgb, Df)>),
    /// A layer over a base (`weighted_layer`, `fresnel_layer`, `color_` forms): the layer
    /// with `weight`, times the dielectric Fresnel reflectance of `fresnel_ior` if given;
    /// the base takes what the layer leaves.
    Layer {
        /// The layer's weight.
        weight: Rgb,
        /// Index of refraction of the Fresnel term, if any.
        fresnel_ior: Option<f32>,
        /// The top layer.
        layer: Box<Df>,
        /// The base.
        base: Box<Df>,
    },
}

/// `df::scatter_mode`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScatterMode {
    /// `scatter_reflect`.
    Reflect,
    /// `scatter_transmit`.
    Transmit,
    /// `scatter_reflect_transmit`.
    ReflectTransmit,
}

impl ScatterMode {
    /// The mode of enum value `v` of `::df::scatter_mode`.
    pub fn from_enum(v: i64) -> ScatterMode {
        match v {
            1 => ScatterMode::Transmit,
            2 => ScatterMode::ReflectTransmit,
            _ => ScatterMode::Reflect,
        }
    }
}

/// An emission distribution (MDL `edf`).
#[derive(Clone, Debug, PartialEq)]
pub enum Edf {
    /// `edf()`: no emission.
    Black,
    /// `df::diffuse_edf`: Lambertian emission.
    Diffuse,
}

/// A constant MDL value.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// `bool`.
    Bool(bool),
    /// `int`.
    Int(i64),
    /// `float` or `double`.
    Float(f64),
    /// `floatN`, `intN`… as floats.
    Vector(Vec<f64>),
    /// `color` (linear RGB).
    Color(Rgb),
    /// `string`.
    Str(String),
    /// An enum value: the enum's absolute name and the value.
    Enum(String, i64),
    /// A struct: its absolute type name and its fields in declaration order.
    Struct(String, Vec<(String, Value)>),
    /// An array.
    Array(Vec<Value>),
    /// A `bsdf`.
    Bsdf(Df),
    /// An `edf`.
    Edf(Edf),
    /// A `vdf` (volume scattering is not read; only `vdf()` is accepted).
    Vdf,
    /// `hair_bsdf()`.
    HairBsdf,
    /// A `::state` function's result (`normal`, `texture_tangent_u`…): it depends on the
    /// shading point; only passing it through unchanged (the default `normal` of a layer)
    /// is compiled.
    State(String),
}

impl Value {
    /// As a float (ints and bools convert).
    pub fn float(&self) -> Option<f64> {
        match self {
            Value::Float(f) => Some(*f),
            Value::Int(i) => Some(*i as f64),
            Value::Bool(b) => Some(f64::from(u8::from(*b))),
            _ => None,
        }
    }

    /// As a colour (a float is a grey).
    pub fn color(&self) -> Option<Rgb> {
        match self {
            Value::Color(c) => Some(*c),
            Value::Vector(v) if v.len() == 3 => Some(Rgb::new(v[0] as f32, v[1] as f32, v[2] as f32)),
            _ => self.float().map(|f| Rgb::splat(f as f32)),
        }
    }

    /// A struct's field.
    pub fn field(&self, name: &str) -> Option<&Value> {
        match self {
            Value::Struct(_, fields) => fields.iter().find(|(n, _)| n == name).map(|(_, v)| v),
            _ => None,
        }
    }
}

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
