//! `.mi` parameters of module material instances connected to MDL function shaders
//! (`"tint" = "tex.tint"` where `tex` is `mdl::base::file_texture (…)`, as Iray exporters
//! write them): the connected shader becomes a call of its MDL function with its own `.mi`
//! parameters (themselves constants, texture names or further connections), evaluated like
//! a call written in a module — per hit where it depends on the shading point.

use mdl_lang::{split_mi_name, Resolution, Type};
use mi::ast::{ShaderItem, Value as MiValue};
use scene::Library;

use super::eval::Evaluator;
use super::value::{self, Value};

/// Deepest chain of connections followed.
const MAX_DEPTH: u32 = 32;

/// The value of the connection `target` (`"shader"` or `"shader.member"`) as MDL type
/// `ty`; `Err` says why it is not compiled.
pub fn value(ev: &mut Evaluator, lib: &Library, target: &str, ty: &Type, depth: u32) -> Result<Value, String> {
    if depth >= MAX_DEPTH {
        return Err(format!("connections nested more than {MAX_DEPTH} deep"));
    }
    let (shader, member) = match target.split_once('.') {
        Some((s, m)) => (s, Some(m)),
        None => (target, None),
    };
    let Some(ShaderItem::Call { decl, params, .. }) = lib.shaders.get(shader).and_then(|d| d.list.0.first()) else {
        return Err(format!("'{shader}' is not a shader call"));
    };
    let v = function_call(ev, lib, shader, &decl.text, params, depth)?;
    let v = match member {
        Some(m) => v.field(m).cloned().ok_or_else(|| format!("`{}` has no member `{m}`", decl.text))?,
        None => v,
    };
    Ok(texture_return_as(ty, v))
}

/// The value of a call of the `.mi` declaration `decl` (`mdl::module::function`) with the
/// `.mi` parameters `params` (of shader `shader`, named in messages), as MDL type `ty`: a
/// `texture_return` given for a colour or number is its tint or mono.
pub fn call_value(
    ev: &mut Evaluator,
    lib: &Library,
    shader: &str,
    decl: &str,
    params: &[mi::ast::Param],
    ty: &Type,
    depth: u32,
) -> Result<Value, String> {
    Ok(texture_return_as(ty, function_call(ev, lib, shader, decl, params, depth)?))
}

/// A `texture_return` `v` connected to a colour or number: its tint or mono (else `v`).
fn texture_return_as(ty: &Type, v: Value) -> Value {
    match (ty, &v) {
        (Type::Color, Value::Struct(..)) => v.field("tint").cloned().unwrap_or(v),
        (Type::Scalar(_), Value::Struct(..)) => v.field("mono").cloned().unwrap_or(v),
        _ => v,
    }
}

/// The value the MDL function `decl` returns for the `.mi` parameters `params`.
fn function_call(
    ev: &mut Evaluator,
    lib: &Library,
    shader: &str,
    decl: &str,
    params: &[mi::ast::Param],
    depth: u32,
) -> Result<Value, String> {
    let Some((module, item)) = split_mi_name(decl) else {
        return Err(format!("'{shader}' is a mental ray shader ({decl}), not an MDL function"));
    };
    let set = ev.set;
    let qualified = format!("{module}::{item}");
    let overloads = set.functions(&qualified);
    // The overload whose parameters take every `.mi` parameter by name.
    let Some(def) = overloads.iter().copied().find(|f| params.iter().all(|p| f.param(&p.name.text).is_some())) else {
        return Err(format!("`{qualified}` is not a function of a loaded module with these parameters"));
    };
    let enum_value = |ty: &str, name: &str| {
        set.enum_decl(ty).and_then(|e| e.values.iter().find(|v| v.name == name).map(|v| v.value))
    };
    let mut given: Vec<Option<Value>> = vec![None; def.params.len()];
    for p in params {
        let Some((i, decl)) = def.param(&p.name.text) else { continue };
        given[i] = Some(match (&decl.ty.ty, &p.value) {
            (_, MiValue::Connect(next)) => value(ev, lib, &next.text, &decl.ty.ty, depth + 1)?,
            (Type::Texture(shape), MiValue::Str(name)) => {
                ev.textures.value_from_mi(*shape, &name.text, lib).unwrap_or_else(|_| super::textures::invalid(*shape))
            }
            (Type::BsdfMeasurement, MiValue::Str(name)) => {
                Value::BsdfMeasurement(ev.textures.bsdf_measurement(&name.text, None).ok())
            }
            (ty, v) => {
                value::from_mi(v, ty, &enum_value).map_err(|why| format!("'{}' of '{shader}': {why}", p.name.text))?
            }
        });
    }
    let res = Resolution::Function { module: module.clone(), name: item.clone(), decl: 0 };
    let span = def.span;
    let result = ev.complete(def, given, span).and_then(|args| ev.call(def, &res, args, span));
    result.map_err(|p| format!("{}: {}", set.sources().location(p.span), p.message))
}
