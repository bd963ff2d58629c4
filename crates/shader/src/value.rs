//! Typed parameter values of the shader model: what `mi_eval_*` returns.

use std::sync::Arc;

use glam::{Mat4, Vec3A, Vec4};

/// A colour with alpha (mental ray's `miColor`): linear RGB and coverage.
pub type Color = Vec4;

/// A reference to an element a parameter names (mental ray's `miTag`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tag {
    /// A texture (index into the texture table).
    Texture(u32),
    /// A light instance (index into the renderer's light list).
    Light(u32),
    /// A material (index into the scene's materials).
    Material(u32),
    /// A shader node.
    Shader(u32),
    /// A user data element (index into the data table).
    Data(u32),
    /// A light profile (index into the profile table).
    Lightprofile(u32),
}

/// A parameter value or shader result.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// Nothing (`null`, an unset tag, a shader that returned false).
    Null,
    /// `boolean`
    Bool(bool),
    /// `integer`
    Int(i32),
    /// `scalar`
    Scalar(f32),
    /// `color`
    Color(Color),
    /// `vector`
    Vector(Vec3A),
    /// `transform` (mental ray's 16 numbers as a glam matrix, see `scene::transform`).
    Transform(Mat4),
    /// `string`
    Str(Arc<str>),
    /// Textures, lights, materials, shaders, data.
    Tag(Tag),
    /// `struct { … }`: named members in declaration order.
    Struct(Arc<[(Arc<str>, Value)]>),
    /// `array T`
    Array(Arc<[Value]>),
}

impl Value {
    /// As a colour: scalars become grey (alpha 1), vectors RGB (alpha 1), booleans and
    /// integers grey; a struct gives its first member.
    pub fn color(&self) -> Color {
        match self {
            Value::Color(c) => *c,
            Value::Scalar(s) => Vec4::new(*s, *s, *s, 1.0),
            Value::Int(i) => Vec4::new(*i as f32, *i as f32, *i as f32, 1.0),
            Value::Bool(b) => Vec4::splat(f32::from(u8::from(*b))),
            Value::Vector(v) => v.extend(1.0),
            Value::Struct(m) => m.first().map_or(Vec4::ZERO, |(_, v)| v.color()),
            _ => Vec4::ZERO,
        }
    }

    /// As a scalar: a colour's red (as C code reading a colour result as a scalar gets),
    /// a vector's x.
    pub fn scalar(&self) -> f32 {
        match self {
            Value::Scalar(s) => *s,
            Value::Int(i) => *i as f32,
            Value::Bool(b) => f32::from(u8::from(*b)),
            Value::Color(c) => c.x,
            Value::Vector(v) => v.x,
            Value::Struct(m) => m.first().map_or(0.0, |(_, v)| v.scalar()),
            _ => 0.0,
        }
    }

    /// As a vector (colours give their RGB).
    pub fn vector(&self) -> Vec3A {
        match self {
            Value::Vector(v) => *v,
            Value::Color(c) => Vec3A::new(c.x, c.y, c.z),
            Value::Scalar(s) => Vec3A::splat(*s),
            Value::Struct(m) => m.first().map_or(Vec3A::ZERO, |(_, v)| v.vector()),
            _ => Vec3A::ZERO,
        }
    }

    /// As an integer.
    pub fn int(&self) -> i32 {
        match self {
            Value::Int(i) => *i,
            Value::Bool(b) => i32::from(*b),
            Value::Scalar(s) => *s as i32,
            Value::Color(c) => c.x as i32,
            _ => 0,
        }
    }

    /// As a boolean.
    pub fn bool(&self) -> bool {
        match self {
            Value::Bool(b) => *b,
            Value::Int(i) => *i != 0,
            Value::Scalar(s) => *s != 0.0,
            Value::Null => false,
            _ => true,
        }
    }

    /// As a transform (identity if not one).
    pub fn transform(&self) -> Mat4 {
        match self {
            Value::Transform(m) => *m,
            _ => Mat4::IDENTITY,
        }
    }

    /// As a tag.
    pub fn tag(&self) -> Option<Tag> {
        match self {
            Value::Tag(t) => Some(*t),
            _ => None,
        }
    }

    /// As a string.
    pub fn str(&self) -> Option<&str> {
        match self {
            Value::Str(s) => Some(s),
            _ => None,
        }
    }

    /// The elements of an array (empty if not an array).
    pub fn array(&self) -> &[Value] {
        match self {
            Value::Array(a) => a,
            _ => &[],
        }
    }

    /// A member of a struct result by name (`"shader.member"` connections).
    pub fn member(&self, name: &str) -> Option<&Value> {
        match self {
            Value::Struct(m) => m.iter().find(|(n, _)| &**n == name).map(|(_, v)| v),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coercions_follow_the_c_memory_layout() {
        let c = Value::Color(Vec4::new(0.1, 0.2, 0.3, 0.4));
        assert_eq!(c.scalar(), 0.1);
        assert_eq!(c.vector(), Vec3A::new(0.1, 0.2, 0.3));
        assert_eq!(Value::Scalar(0.5).color(), Vec4::new(0.5, 0.5, 0.5, 1.0));
        let s = Value::Struct(Arc::from(vec![
            (Arc::from("u"), Value::Vector(Vec3A::X)),
            (Arc::from("v"), Value::Vector(Vec3A::Y)),
        ]));
        assert_eq!(s.member("v"), Some(&Value::Vector(Vec3A::Y)));
        assert_eq!(s.vector(), Vec3A::X);
    }
}
