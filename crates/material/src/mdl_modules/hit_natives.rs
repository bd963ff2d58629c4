//! The standard functions whose results may depend on the shading point, built as
//! [`HitExpr`] trees (folded to constants where their arguments are): `::state` values,
//! `::math` functions, `::tex` lookups and the `::base` texturing functions
//! (`coordinate_source`, `transform_coordinate`, `rotation_translation_scale`,
//! `file_texture`, `tangent_space_normal_texture`).

use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};
use mdl_lang::ast::TextureShape;
use mdl_lang::Function;
use mi::Span;

use super::eval::{kind, problem, Eval, Problem};
use super::hit::{BinOp, HitExpr, MathFn, StateFn};
use super::value::{HitType, Value};

/// The `::state` function `name` with `args`.
pub fn state(name: &str, args: &[Value], span: Span) -> Eval {
    let v3 = |f: StateFn| Ok(Value::Hit(Arc::new(HitExpr::State(f)), HitType::Vector(3)));
    let space = || match args.first() {
        Some(Value::Int(i)) if (0..shader::state::MAX_TEXTURES as i64).contains(i) => Ok(*i as u8),
        Some(v) => Err(problem(span, format!("`state::{name}` of texture space {} is not compiled", kind(v)))),
        None => Ok(0),
    };
    match name {
        "position" => v3(StateFn::Position),
        "normal" => v3(StateFn::Normal),
        "geometry_normal" => v3(StateFn::GeometryNormal),
        "direction" => v3(StateFn::Direction),
        "motion" => v3(StateFn::Motion),
        "texture_coordinate" => v3(StateFn::TextureCoordinate(space()?)),
        "texture_tangent_u" | "geometry_tangent_u" => {
            space()?;
            v3(StateFn::TangentU)
        }
        "texture_tangent_v" | "geometry_tangent_v" => {
            space()?;
            v3(StateFn::TangentV)
        }
        "texture_space_max" => Ok(Value::Int(shader::state::MAX_TEXTURES as i64)),
        "animation_time" => Ok(Value::Hit(Arc::new(HitExpr::State(StateFn::Time)), HitType::Float)),
        "object_id" => Ok(Value::Hit(Arc::new(HitExpr::State(StateFn::ObjectId)), HitType::Int)),
        // Scene units are metres unless the scene says otherwise (Iray's default).
        "meters_per_scene_unit" | "scene_units_per_meter" => Ok(Value::Float(1.0)),
        "transform" | "transform_point" | "transform_vector" | "transform_normal" | "transform_scale" => {
            super::state_space::transform(name, args, span)
        }
        _ => Err(problem(span, format!("`state::{name}` is not compiled yet"))),
    }
}

/// The math function of `::math::name` for arguments of type `first`, if it is one.
fn math_fn(name: &str, first: HitType) -> Option<MathFn> {
    use MathFn::*;
    let n = first.width();
    Some(match name {
        "min" => Min,
        "max" => Max,
        "clamp" => Clamp,
        "saturate" => Saturate,
        "lerp" => Lerp,
        "step" => Step,
        "smoothstep" => Smoothstep,
        "sqrt" => Sqrt,
        "exp" => Exp,
        "exp2" => Exp2,
        "log" => Log,
        "log2" => Log2,
        "log10" => Log10,
        "pow" => Pow,
        "abs" => Abs,
        "sign" => Sign,
        "floor" => Floor,
        "ceil" => Ceil,
        "round" => Round,
        "frac" => Frac,
        "fmod" => Fmod,
        "sin" => Sin,
        "cos" => Cos,
        "tan" => Tan,
        "asin" => Asin,
        "acos" => Acos,
        "atan" => Atan,
        "atan2" => Atan2,
        "radians" => Radians,
        "degrees" => Degrees,
        "dot" => Dot(n),
        "length" => Length(n),
        "distance" => Distance(n),
        "normalize" => Normalize(n),
        "cross" => Cross,
        "luminance" => Luminance,
        "average" => Average(n),
        "max_value" => MaxValue(n),
        "min_value" => MinValue(n),
        _ => return None,
    })
}

/// `::math::name` of `args` (any of them may depend on the hit), of `def`'s return type.
pub fn math(def: &Function, args: &[Value], span: Span) -> Eval {
    let name = def.name.as_str();
    let first = args.first().and_then(Value::hit_type).unwrap_or(HitType::Float);
    let f = math_fn(name, first).ok_or_else(|| problem(span, format!("`math::{name}` is not compiled yet")))?;
    let ty = HitType::of(&def.ret.ty)
        .ok_or_else(|| problem(span, format!("`math::{name}` returning `{}` is not compiled yet", def.ret.ty)))?;
    let mut operands = Vec::with_capacity(args.len());
    for a in args {
        operands.push(a.to_hit().ok_or_else(|| problem(span, format!("`math::{name}` of {}", kind(a))))?);
    }
    Ok(Value::from_hit(HitExpr::Math(f, operands.into()), ty))
}

/// An enum argument's value (`default` when absent or not constant).
pub fn enum_arg(v: Option<&Value>, default: i64) -> i64 {
    match v {
        Some(Value::Enum(_, i)) => *i,
        Some(Value::Int(i)) => *i,
        _ => default,
    }
}

/// `tex::wrap_mode`'s enumerator names, by value.
pub fn wrap_name(v: i64) -> &'static str {
    match v {
        0 => "wrap_clamp",
        2 => "wrap_mirrored_repeat",
        3 => "wrap_clip",
        _ => "wrap_repeat",
    }
}

/// `base::mono_mode`'s enumerator names, by value.
pub fn mono_name(v: i64) -> &'static str {
    match v {
        1 => "mono_average",
        2 => "mono_luminance",
        3 => "mono_maximum",
        _ => "mono_alpha",
    }
}

/// A `float2` crop argument (`crop_u`/`crop_v`): the part of the image [0, 1) maps to;
/// (0, 1) when absent. A crop that is not a constant pair within [0, 1] is an error.
pub fn crop(v: Option<&Value>, name: &str, span: Span) -> Result<[f32; 2], Problem> {
    match v {
        None => Ok([0.0, 1.0]),
        Some(Value::Vector(c)) if c.len() == 2 && c.iter().all(|x| (0.0..=1.0).contains(x)) => {
            Ok([c[0] as f32, c[1] as f32])
        }
        Some(v) => {
            Err(problem(span, format!("a `{name}` crop that is {} (a constant float2 in [0, 1] is needed)", kind(v))))
        }
    }
}

/// The `crop_u` and `crop_v` arguments of a lookup as (u0, u1, v0, v1).
pub fn crops(u: Option<&Value>, v: Option<&Value>, span: Span) -> Result<[f32; 4], Problem> {
    let (u, v) = (crop(u, "crop_u", span)?, crop(v, "crop_v", span)?);
    Ok([u[0], u[1], v[0], v[1]])
}

/// The RGBA texel expression of `texture` at `coord` with wrap modes, clip and crop.
pub fn lookup(
    texture: &Value,
    coord: &Value,
    wrap: [&'static str; 2],
    clip: bool,
    crop: [f32; 4],
    span: Span,
) -> Result<HitExpr, Problem> {
    let coord = coord.to_hit().ok_or_else(|| problem(span, format!("a texture coordinate that is {}", kind(coord))))?;
    match texture {
        Value::Texture(Some(image)) => Ok(HitExpr::Lookup { image: image.clone(), coord, wrap, clip, crop }),
        Value::Texture(None) => Ok(HitExpr::Const(Vec4::ZERO)),
        v => Err(problem(span, format!("a texture lookup of {}", kind(v)))),
    }
}

/// The `::tex` function `def` with `args`.
pub fn tex(def: &Function, args: &[Value], span: Span) -> Eval {
    let name = def.name.as_str();
    let arg = |p: &str| def.param(p).and_then(|(i, _)| args.get(i));
    let texture = args.first().ok_or_else(|| problem(span, format!("`tex::{name}` without a texture")))?;
    let size = || match texture {
        Value::Texture(Some(image)) => image.size(),
        _ => (0, 0),
    };
    let shape = match def.params.first().map(|p| &p.ty.ty) {
        Some(mdl_lang::Type::Texture(shape)) => Some(*shape),
        _ => None,
    };
    let is_2d = shape == Some(TextureShape::Tex2d);
    if matches!(shape, Some(TextureShape::Tex3d | TextureShape::Cube)) && name != "texture_isvalid" {
        return tex_3d_or_cube(name, &arg, texture, span);
    }
    if shape == Some(TextureShape::Ptex) && name != "texture_isvalid" {
        return tex_ptex(name, arg("channel"), texture, span);
    }
    match name {
        "width" if is_2d => Ok(Value::Int(size().0 as i64)),
        "height" if is_2d => Ok(Value::Int(size().1 as i64)),
        "texture_isvalid" => Ok(Value::Bool(matches!(
            texture,
            Value::Texture(Some(_))
                | Value::Texture3d(Some(_))
                | Value::TextureCube(Some(_))
                | Value::TexturePtex(Some(_))
        ))),
        "lookup_color" | "lookup_float" | "lookup_float2" | "lookup_float3" | "lookup_float4" if is_2d => {
            let crop = crops(arg("crop_u"), arg("crop_v"), span)?;
            let coord = arg("coord").ok_or_else(|| problem(span, "a lookup without a coordinate"))?;
            let wrap = [wrap_name(enum_arg(arg("wrap_u"), 1)), wrap_name(enum_arg(arg("wrap_v"), 1))];
            let texel = Arc::new(lookup(texture, coord, wrap, false, crop, span)?);
            Ok(texel_value(name, texel))
        }
        "texel_color" | "texel_float" | "texel_float2" | "texel_float3" | "texel_float4" if is_2d => {
            if !is_zero(arg("uv_tile")) {
                return Err(problem(
                    span,
                    format!(
                        "`tex::{name}` of a uv tile other than (0, 0) is not compiled (mira reads no tiled textures)"
                    ),
                ));
            }
            let coord = arg("coord").ok_or_else(|| problem(span, "a texel read without a coordinate"))?;
            let coord =
                coord.to_hit().ok_or_else(|| problem(span, format!("a texel position that is {}", kind(coord))))?;
            let texel = match texture {
                Value::Texture(Some(image)) => super::hit::fold(HitExpr::Texel { image: image.clone(), coord }),
                _ => Arc::new(HitExpr::Const(Vec4::ZERO)),
            };
            Ok(texel_value(name, texel))
        }
        _ => Err(problem(span, format!("`tex::{name}` is not compiled yet"))),
    }
}

/// The `::tex` function `name` of a `texture_3d` or `texture_cube` (`arg`: an argument by
/// its parameter's name): sizes, filtered lookups, voxel reads.
fn tex_3d_or_cube<'a>(name: &str, arg: &dyn Fn(&str) -> Option<&'a Value>, texture: &Value, span: Span) -> Eval {
    let size = match texture {
        Value::Texture3d(Some(v)) => v.size,
        Value::TextureCube(Some(c)) => [c.size, c.size, 0],
        _ => [0; 3],
    };
    let texel = match name {
        "width" => return Ok(Value::Int(size[0] as i64)),
        "height" => return Ok(Value::Int(size[1] as i64)),
        "depth" => return Ok(Value::Int(size[2] as i64)),
        "lookup_color" | "lookup_float" | "lookup_float2" | "lookup_float3" | "lookup_float4" => {
            let coord = arg("coord").ok_or_else(|| problem(span, "a lookup without a coordinate"))?;
            let coord =
                coord.to_hit().ok_or_else(|| problem(span, format!("a texture coordinate that is {}", kind(coord))))?;
            match texture {
                Value::Texture3d(Some(volume)) => {
                    let wrap = ["wrap_u", "wrap_v", "wrap_w"].map(|p| wrap_name(enum_arg(arg(p), 1)));
                    let crop = [
                        crop(arg("crop_u"), "crop_u", span)?,
                        crop(arg("crop_v"), "crop_v", span)?,
                        crop(arg("crop_w"), "crop_w", span)?,
                    ];
                    HitExpr::Lookup3d { volume: volume.clone(), coord, wrap, crop }
                }
                Value::TextureCube(Some(cube)) => HitExpr::LookupCube { cube: cube.clone(), dir: coord },
                Value::Texture3d(None) | Value::TextureCube(None) | Value::Texture(None) => HitExpr::Const(Vec4::ZERO),
                v => return Err(problem(span, format!("a texture lookup of {}", kind(v)))),
            }
        }
        "texel_color" | "texel_float" | "texel_float2" | "texel_float3" | "texel_float4" => {
            let coord = arg("coord").ok_or_else(|| problem(span, "a texel read without a coordinate"))?;
            let coord =
                coord.to_hit().ok_or_else(|| problem(span, format!("a texel position that is {}", kind(coord))))?;
            match texture {
                Value::Texture3d(Some(volume)) => {
                    return Ok(texel_value(name, super::hit::fold(HitExpr::Texel3d { volume: volume.clone(), coord })))
                }
                _ => HitExpr::Const(Vec4::ZERO),
            }
        }
        _ => return Err(problem(span, format!("`tex::{name}` is not compiled yet"))),
    };
    Ok(texel_value(name, Arc::new(texel)))
}

/// The `::tex` function `name` of a `texture_ptex` (`channel`: its first channel, a
/// constant): a lookup at the hit's Ptex face and barycentric coordinates
/// ([`super::ptex`]).
fn tex_ptex(name: &str, channel: Option<&Value>, texture: &Value, span: Span) -> Eval {
    if !matches!(name, "lookup_color" | "lookup_float" | "lookup_float2" | "lookup_float3" | "lookup_float4") {
        return Err(problem(span, format!("`tex::{name}` of a `texture_ptex` is not compiled")));
    }
    let channel = match channel {
        None => 0,
        Some(Value::Int(c)) if *c >= 0 => *c as usize,
        Some(v) => {
            return Err(problem(
                span,
                format!("`tex::{name}` of a Ptex texture reads a constant channel ≥ 0, not {}", kind(v)),
            ))
        }
    };
    let texel = match texture {
        Value::TexturePtex(Some(ptex)) => HitExpr::LookupPtex { ptex: ptex.clone(), channel },
        Value::TexturePtex(None) | Value::Texture(None) => HitExpr::Const(Vec4::ZERO),
        v => return Err(problem(span, format!("a Ptex lookup of {}", kind(v)))),
    };
    Ok(texel_value(name, Arc::new(texel)))
}

/// Whether an optional `int2` argument is absent or (0, 0).
fn is_zero(v: Option<&Value>) -> bool {
    match v {
        None => true,
        Some(Value::Vector(c)) => c.iter().all(|x| *x == 0.0),
        _ => false,
    }
}

/// The value a `tex::lookup_*` or `tex::texel_*` function `name` returns from the RGBA texel.
fn texel_value(name: &str, texel: Arc<HitExpr>) -> Value {
    let suffix = name.rsplit('_').next().unwrap_or("");
    match suffix {
        "float" => Value::from_hit(HitExpr::Lane(texel, 0), HitType::Float),
        "float2" => Value::from_hit(HitExpr::Compose([(texel, 2)].into()), HitType::Vector(2)),
        "float3" => Value::from_hit(HitExpr::Compose([(texel, 3)].into()), HitType::Vector(3)),
        "float4" => Value::from_hit((*texel).clone(), HitType::Vector(4)),
        _ => Value::from_hit(HitExpr::Compose([(texel, 3)].into()), HitType::Color),
    }
}

/// A `texture_coordinate_info` struct of the three expressions.
pub fn coordinate_info(position: Value, tangent_u: Value, tangent_v: Value) -> Value {
    Value::Struct(
        "texture_coordinate_info".into(),
        vec![
            ("position".into(), position),
            ("tangent_u".into(), tangent_u),
            ("tangent_v".into(), tangent_v),
            ("source_flags".into(), Value::Int(0)),
        ],
    )
}

/// A `float3` value of the state.
pub fn state_value(f: StateFn) -> Value {
    Value::Hit(Arc::new(HitExpr::State(f)), HitType::Vector(3))
}

/// A constant `float4x4` value as a matrix.
fn matrix(v: &Value) -> Option<Mat4> {
    super::matrix::mat4(v)
}

/// The `::base` function `def` with `args`.
pub fn base(def: &Function, args: &[Value], span: Span) -> Eval {
    let name = def.name.as_str();
    let arg = |p: &str| def.param(p).and_then(|(i, _)| args.get(i));
    let field = |v: Option<&Value>, f: &str| v.and_then(|v| v.field(f)).cloned();
    match name {
        "coordinate_source" => {
            let space = match arg("texture_space") {
                Some(Value::Int(i)) => *i,
                _ => 0,
            };
            match enum_arg(arg("coordinate_system"), 0) {
                // texture_coordinate_world
                1 => Ok(coordinate_info(
                    state_value(StateFn::Position),
                    Value::Vector(vec![1.0, 0.0, 0.0]),
                    Value::Vector(vec![0.0, 1.0, 0.0]),
                )),
                // texture_coordinate_object
                2 => Ok(coordinate_info(
                    state_value(StateFn::ObjectPosition),
                    state_value(StateFn::ObjectAxisX),
                    state_value(StateFn::ObjectAxisY),
                )),
                _ => {
                    let space = [Value::Int(space)];
                    Ok(coordinate_info(
                        state("texture_coordinate", &space, span)?,
                        state("texture_tangent_u", &space, span)?,
                        state("texture_tangent_v", &space, span)?,
                    ))
                }
            }
        }
        "rotation_translation_scale" => {
            let v3 = |p: &str, d: f32| match arg(p) {
                Some(Value::Vector(v)) if v.len() == 3 => Ok(Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)),
                None => Ok(Vec3::splat(d)),
                Some(v) => Err(problem(span, format!("`base::{name}` of a `{p}` that is {}", kind(v)))),
            };
            let (r, t, s) = (v3("rotation", 0.0)?, v3("translation", 0.0)?, v3("scaling", 1.0)?);
            // Scale, then rotate about x, y and z in that order, then translate.
            let rotation = glam::Quat::from_euler(glam::EulerRot::ZYX, r.z, r.y, r.x);
            let m = Mat4::from_scale_rotation_translation(s, rotation, t);
            Ok(super::matrix::from_mat4(m))
        }
        "transform_coordinate" => {
            let m = arg("transform")
                .and_then(matrix)
                .ok_or_else(|| problem(span, "`base::transform_coordinate` of a matrix that is not constant"))?;
            let c = arg("coordinate");
            let through = |f: &str, point: bool| -> Eval {
                let v = field(c, f).ok_or_else(|| problem(span, format!("a coordinate without `{f}`")))?;
                let of = v.to_hit().ok_or_else(|| problem(span, format!("a coordinate `{f}` that is {}", kind(&v))))?;
                Ok(Value::from_hit(HitExpr::Transform { matrix: m, of, point }, HitType::Vector(3)))
            };
            Ok(coordinate_info(through("position", true)?, through("tangent_u", false)?, through("tangent_v", false)?))
        }
        "file_texture" => {
            let crop = crops(arg("crop_u"), arg("crop_v"), span)?;
            let texture = arg("texture").ok_or_else(|| problem(span, "`base::file_texture` without a texture"))?;
            let position = field(arg("uvw"), "position").unwrap_or(Value::Vector(vec![0.0; 3]));
            let wrap = [wrap_name(enum_arg(arg("wrap_u"), 1)), wrap_name(enum_arg(arg("wrap_v"), 1))];
            let clip = matches!(arg("clip"), Some(Value::Bool(true)));
            let texel = Arc::new(lookup(texture, &position, wrap, clip, crop, span)?);
            let colour = |p: &str, d: f32| {
                arg(p).and_then(Value::to_hit).unwrap_or_else(|| Arc::new(HitExpr::Const(Vec4::splat(d))))
            };
            // tint = texel · color_scale + color_offset; mono from the texel.
            let scaled = super::hit::fold(HitExpr::Binary(BinOp::Mul, texel.clone(), colour("color_scale", 1.0)));
            let tint =
                Value::from_hit(HitExpr::Binary(BinOp::Add, scaled, colour("color_offset", 0.0)), HitType::Color);
            let mono = Value::from_hit(
                HitExpr::Math(MathFn::Mono(mono_name(enum_arg(arg("mono_source"), 0))), [texel].into()),
                HitType::Float,
            );
            Ok(Value::Struct("texture_return".into(), vec![("tint".into(), tint), ("mono".into(), mono)]))
        }
        "tangent_space_normal_texture" => tangent_space_normal(def, args, span),
        _ => super::hit_base::base(def, args, span),
    }
}

/// `base::tangent_space_normal_texture`: the texel t becomes (t − offset)·2/scale − 1; its
/// x and y, times `factor` (and flipped as asked), lean the shading normal along the
/// coordinate's tangents; z keeps the normal (world space, unit).
fn tangent_space_normal(def: &Function, args: &[Value], span: Span) -> Eval {
    let arg = |p: &str| def.param(p).and_then(|(i, _)| args.get(i));
    let num = |p: &str, d: f32| arg(p).and_then(Value::float).map_or(d, |f| f as f32);
    let texture = arg("texture").ok_or_else(|| problem(span, "a normal map without a texture"))?;
    let uvw = arg("uvw");
    let part = |f: &str| -> Result<Arc<HitExpr>, Problem> {
        uvw.and_then(|c| c.field(f))
            .and_then(Value::to_hit)
            .ok_or_else(|| problem(span, format!("a normal map's coordinate without `{f}`")))
    };
    let wrap = [wrap_name(enum_arg(arg("wrap_u"), 1)), wrap_name(enum_arg(arg("wrap_v"), 1))];
    let clip = matches!(arg("clip"), Some(Value::Bool(true)));
    let crop = crops(arg("crop_u"), arg("crop_v"), span)?;
    let texel = Arc::new(lookup(texture, &Value::Hit(part("position")?, HitType::Vector(3)), wrap, clip, crop, span)?);
    let scale = num("scale", 1.0);
    let scale = if scale != 0.0 { scale } else { 1.0 };
    let c = |v: f32| Arc::new(HitExpr::Const(Vec4::splat(v)));
    let f = super::hit::fold;
    // t = (texel − offset) · 2/scale − 1
    let t = f(HitExpr::Binary(
        BinOp::Sub,
        f(HitExpr::Binary(BinOp::Mul, f(HitExpr::Binary(BinOp::Sub, texel, c(num("offset", 0.0)))), c(2.0 / scale))),
        c(1.0),
    ));
    let factor = num("factor", 1.0);
    let su = if matches!(arg("flip_tangent_u"), Some(Value::Bool(true))) { -factor } else { factor };
    let sv = if matches!(arg("flip_tangent_v"), Some(Value::Bool(true))) { -factor } else { factor };
    let lane = |i: u8| f(HitExpr::Lane(t.clone(), i));
    let term = |a: Arc<HitExpr>, b: Arc<HitExpr>| f(HitExpr::Binary(BinOp::Mul, a, b));
    let along_u = term(part("tangent_u")?, term(lane(0), c(su)));
    let along_v = term(part("tangent_v")?, term(lane(1), c(sv)));
    let up = term(Arc::new(HitExpr::State(StateFn::Normal)), f(HitExpr::Math(MathFn::Max, [lane(2), c(0.0)].into())));
    let sum = f(HitExpr::Binary(BinOp::Add, f(HitExpr::Binary(BinOp::Add, along_u, along_v)), up));
    Ok(Value::from_hit(HitExpr::Math(MathFn::Normalize(3), [sum].into()), HitType::Vector(3)))
}
