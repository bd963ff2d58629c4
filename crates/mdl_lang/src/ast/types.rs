//! MDL types: the built-in scalar, vector, matrix, colour, resource and distribution-function
//! types, user structs and enums, and arrays.

use std::fmt;

use mi::Span;

use super::QualName;

/// Element type of a vector or matrix.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scalar {
    /// `bool`.
    Bool,
    /// `int` (32-bit signed).
    Int,
    /// `float` (32-bit).
    Float,
    /// `double` (64-bit).
    Double,
}

impl Scalar {
    fn name(self) -> &'static str {
        match self {
            Scalar::Bool => "bool",
            Scalar::Int => "int",
            Scalar::Float => "float",
            Scalar::Double => "double",
        }
    }
}

/// Shape of a texture resource.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TextureShape {
    /// `texture_2d`.
    Tex2d,
    /// `texture_3d`.
    Tex3d,
    /// `texture_cube`.
    Cube,
    /// `texture_ptex`.
    Ptex,
}

/// Length of an array type.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum ArrayLen {
    /// A known number of elements (`float[3]`).
    Fixed(u64),
    /// A size given by a named integer constant, resolved by the semantic pass.
    Named(QualName),
    /// A deferred size, `T[<N>]`: any length, bound to the symbol `N` (parameters only).
    Deferred(String),
    /// No size written, `T[]`: the length of an array constructor's argument list.
    Unsized,
}

/// A type as the semantic pass understands it.
///
/// The parser produces every built-in type directly; user type names are
/// [`Type::Named`] until the semantic pass resolves them to [`Type::Struct`] or
/// [`Type::Enum`] with their absolute names (`::pkg::module::name`).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Type {
    /// A scalar: `bool`, `int`, `float`, `double`.
    Scalar(Scalar),
    /// `float2`…`float4`, `int2`…, `bool2`…, `double2`…: element type and 2–4 components.
    Vector(Scalar, u8),
    /// `float3x3` etc.: element type, columns, rows (2–4 each).
    Matrix(Scalar, u8, u8),
    /// `color`: a spectral colour, RGB in mira.
    Color,
    /// `string`.
    String,
    /// A texture resource.
    Texture(TextureShape),
    /// `light_profile` (an IES file).
    LightProfile,
    /// `bsdf_measurement` (an MBSDF file).
    BsdfMeasurement,
    /// `bsdf`: a bidirectional scattering distribution function.
    Bsdf,
    /// `edf`: an emission distribution function.
    Edf,
    /// `vdf`: a volume (phase) distribution function.
    Vdf,
    /// `hair_bsdf`.
    HairBsdf,
    /// `material`: the result type of material definitions (a struct of the language).
    Material,
    /// A struct, by absolute name (`::material_surface`, `::base::texture_return`).
    Struct(String),
    /// An enum, by absolute name (`::df::scatter_mode`).
    Enum(String),
    /// A user type name not yet resolved (parser output only).
    Named(QualName),
    /// An array of elements of the inner type.
    Array(Box<Type>, ArrayLen),
}

impl Type {
    /// `float`.
    pub const FLOAT: Type = Type::Scalar(Scalar::Float);
    /// `int`.
    pub const INT: Type = Type::Scalar(Scalar::Int);
    /// `bool`.
    pub const BOOL: Type = Type::Scalar(Scalar::Bool);
    /// `double`.
    pub const DOUBLE: Type = Type::Scalar(Scalar::Double);

    /// The built-in type spelled `name`, if it is one (`material` included).
    pub fn builtin(name: &str) -> Option<Type> {
        let scalar = |s: &str| match s {
            "bool" => Some(Scalar::Bool),
            "int" => Some(Scalar::Int),
            "float" => Some(Scalar::Float),
            "double" => Some(Scalar::Double),
            _ => None,
        };
        if let Some(s) = scalar(name) {
            return Some(Type::Scalar(s));
        }
        let simple = match name {
            "color" => Some(Type::Color),
            "string" => Some(Type::String),
            "texture_2d" => Some(Type::Texture(TextureShape::Tex2d)),
            "texture_3d" => Some(Type::Texture(TextureShape::Tex3d)),
            "texture_cube" => Some(Type::Texture(TextureShape::Cube)),
            "texture_ptex" => Some(Type::Texture(TextureShape::Ptex)),
            "light_profile" => Some(Type::LightProfile),
            "bsdf_measurement" => Some(Type::BsdfMeasurement),
            "bsdf" => Some(Type::Bsdf),
            "edf" => Some(Type::Edf),
            "vdf" => Some(Type::Vdf),
            "hair_bsdf" => Some(Type::HairBsdf),
            "material" => Some(Type::Material),
            _ => None,
        };
        if simple.is_some() {
            return simple;
        }
        // Vectors `float3` and matrices `float3x4`.
        let split = name.find(|c: char| c.is_ascii_digit())?;
        let elem = scalar(&name[..split])?;
        let dims = &name.as_bytes()[split..];
        let dim = |b: u8| (b'2'..=b'4').contains(&b).then_some(b - b'0');
        match dims {
            [n] => Some(Type::Vector(elem, dim(*n)?)),
            [c, b'x', r] if elem != Scalar::Bool && elem != Scalar::Int => Some(Type::Matrix(elem, dim(*c)?, dim(*r)?)),
            _ => None,
        }
    }

    /// Whether this is `int`, `float` or `double` (the arithmetic scalars).
    pub fn is_numeric_scalar(&self) -> bool {
        matches!(self, Type::Scalar(Scalar::Int | Scalar::Float | Scalar::Double))
    }

    /// Whether a value of this type may be passed where `to` is expected: equal types,
    /// conversions between the numeric scalars (widening `bool`→`int`→`float`→`double`, and
    /// narrowing, which MDL compilers accept with a warning; element-wise for vectors and
    /// matrices), `enum`→`int`, a scalar or a `float3` to `color` and back to `float3`, a file
    /// name (string) to a resource,
    /// and arrays whose element types agree
    /// where the target's size is deferred or the source's is unsized.
    pub fn converts_to(&self, to: &Type) -> bool {
        self.conversion_cost(to).is_some()
    }

    /// How far a conversion of a value of this type to `to` goes (0 for none, more for each
    /// widening step, most for a change of kind such as a scalar to `color`), or `None` if
    /// there is no implicit conversion. Overload resolution picks the cheapest candidate.
    pub fn conversion_cost(&self, to: &Type) -> Option<u32> {
        fn rank(s: Scalar) -> u32 {
            match s {
                Scalar::Bool => 0,
                Scalar::Int => 1,
                Scalar::Float => 2,
                Scalar::Double => 3,
            }
        }
        // Widening costs one per step; narrowing (`float` to `int`), which MDL compilers accept
        // with a warning, costs more than any widening.
        let widen = |a: Scalar, b: Scalar| Some(if rank(a) <= rank(b) { rank(b) - rank(a) } else { 10 });
        match (self, to) {
            (a, b) if a == b => Some(0),
            (Type::Scalar(a), Type::Scalar(b)) => widen(*a, *b),
            (Type::Vector(a, n), Type::Vector(b, m)) if n == m => widen(*a, *b),
            (Type::Matrix(a, c, r), Type::Matrix(b, c2, r2)) if c == c2 && r == r2 => widen(*a, *b),
            (Type::Enum(_), Type::Scalar(Scalar::Int | Scalar::Float | Scalar::Double)) => Some(4),
            (Type::Scalar(_), Type::Color) => Some(5),
            (Type::Vector(Scalar::Int | Scalar::Float, 3), Type::Color) => Some(5),
            (Type::Color, Type::Vector(Scalar::Float | Scalar::Double, 3)) => Some(5),
            (Type::String, Type::Texture(_) | Type::LightProfile | Type::BsdfMeasurement) => Some(5),
            (Type::Array(a, la), Type::Array(b, lb)) => {
                let len_ok = la == lb
                    || matches!(lb, ArrayLen::Deferred(_) | ArrayLen::Unsized | ArrayLen::Named(_))
                    || matches!(la, ArrayLen::Unsized | ArrayLen::Deferred(_) | ArrayLen::Named(_));
                (len_ok && a == b).then_some(1)
            }
            _ => None,
        }
    }

    /// The element type of a vector, matrix column, colour channel or array element.
    pub fn element(&self) -> Option<Type> {
        match self {
            Type::Vector(s, _) => Some(Type::Scalar(*s)),
            Type::Matrix(s, _, r) => Some(Type::Vector(*s, *r)),
            Type::Color => Some(Type::FLOAT),
            Type::Array(t, _) => Some((**t).clone()),
            _ => None,
        }
    }
}

impl fmt::Display for Type {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Type::Scalar(s) => f.write_str(s.name()),
            Type::Vector(s, n) => write!(f, "{}{n}", s.name()),
            Type::Matrix(s, c, r) => write!(f, "{}{c}x{r}", s.name()),
            Type::Color => f.write_str("color"),
            Type::String => f.write_str("string"),
            Type::Texture(TextureShape::Tex2d) => f.write_str("texture_2d"),
            Type::Texture(TextureShape::Tex3d) => f.write_str("texture_3d"),
            Type::Texture(TextureShape::Cube) => f.write_str("texture_cube"),
            Type::Texture(TextureShape::Ptex) => f.write_str("texture_ptex"),
            Type::LightProfile => f.write_str("light_profile"),
            Type::BsdfMeasurement => f.write_str("bsdf_measurement"),
            Type::Bsdf => f.write_str("bsdf"),
            Type::Edf => f.write_str("edf"),
            Type::Vdf => f.write_str("vdf"),
            Type::HairBsdf => f.write_str("hair_bsdf"),
            Type::Material => f.write_str("material"),
            Type::Struct(n) | Type::Enum(n) => f.write_str(n),
            Type::Named(q) => write!(f, "{q}"),
            Type::Array(t, len) => match len {
                ArrayLen::Fixed(n) => write!(f, "{t}[{n}]"),
                ArrayLen::Named(q) => write!(f, "{t}[{q}]"),
                ArrayLen::Deferred(s) => write!(f, "{t}[<{s}>]"),
                ArrayLen::Unsized => write!(f, "{t}[]"),
            },
        }
    }
}

/// Whether values of a type may vary over a surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Frequency {
    /// No modifier written (`auto`-typed in MDL terms).
    #[default]
    Auto,
    /// `uniform`: one value per material instance.
    Uniform,
    /// `varying`: may vary per shading point.
    Varying,
}

/// A type as written: its modifier, the type it names and where.
#[derive(Clone, Debug)]
pub struct TypeRef {
    /// `uniform`, `varying` or neither.
    pub frequency: Frequency,
    /// Whether `const` was written (constants and local declarations).
    pub constant: bool,
    /// The type (built-ins resolved by the parser, user names by the semantic pass).
    pub ty: Type,
    /// Where it was written.
    pub span: Span,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_type_name_is_known_and_prints_back() {
        let names = [
            "bool",
            "int",
            "float",
            "double",
            "color",
            "string",
            "float2",
            "float3",
            "float4",
            "int2",
            "int3",
            "int4",
            "bool2",
            "bool3",
            "bool4",
            "double3",
            "float2x2",
            "float3x3",
            "float4x4",
            "float3x4",
            "double4x3",
            "texture_2d",
            "texture_3d",
            "texture_cube",
            "texture_ptex",
            "light_profile",
            "bsdf_measurement",
            "bsdf",
            "edf",
            "vdf",
            "hair_bsdf",
            "material",
        ];
        for n in names {
            let t = Type::builtin(n).unwrap_or_else(|| panic!("{n} unknown"));
            assert_eq!(t.to_string(), n);
        }
        assert_eq!(Type::builtin("float3x3"), Some(Type::Matrix(Scalar::Float, 3, 3)));
        for bad in ["float5", "float1", "int3x3", "bool2x2", "float22", "vec3", "float3x", "Color"] {
            assert_eq!(Type::builtin(bad), None, "{bad}");
        }
    }

    #[test]
    fn conversions_widen_and_rank_exact_matches_first() {
        let f3 = Type::Vector(Scalar::Float, 3);
        assert_eq!(Type::FLOAT.conversion_cost(&Type::FLOAT), Some(0));
        assert_eq!(Type::INT.conversion_cost(&Type::FLOAT), Some(1));
        assert!(Type::FLOAT.conversion_cost(&Type::INT).unwrap() > Type::INT.conversion_cost(&Type::DOUBLE).unwrap());
        assert!(Type::FLOAT.converts_to(&Type::Color) && f3.converts_to(&Type::Color));
        assert!(!Type::String.converts_to(&Type::Color));
        assert!(!Type::Vector(Scalar::Float, 2).converts_to(&f3));
        assert!(!Type::Bsdf.converts_to(&Type::Edf));
        let deferred = Type::Array(Box::new(Type::Color), ArrayLen::Deferred("N".into()));
        assert!(Type::Array(Box::new(Type::Color), ArrayLen::Fixed(4)).converts_to(&deferred));
        assert!(!Type::Array(Box::new(Type::FLOAT), ArrayLen::Fixed(4)).converts_to(&deferred));
        assert!(!Type::Array(Box::new(Type::FLOAT), ArrayLen::Fixed(3))
            .converts_to(&Type::Array(Box::new(Type::FLOAT), ArrayLen::Fixed(4))));
    }
}
