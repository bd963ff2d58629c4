//! The natively implemented standard functions a material expression may call: the `::df`
//! distribution functions, mixers, layerers and modifiers (built as [`Df`] trees), a few
//! `::math` functions and constants, and the `::state` functions (kept as placeholders).
//! `::tex` and `::base` lookups depend on the shading point: a [`Problem`] names them.

use bsdf::Rgb;
use mdl_lang::Function;
use mi::Span;

use super::eval::{kind, problem, Eval};
use super::value::{Df, Edf, ScatterMode, Value};

/// The value of a module constant mira implements (`::math::PI`…).
pub fn constant(module: &str, name: &str) -> Option<Value> {
    use std::f64::consts::PI;
    match (module, name) {
        ("::math", "PI") => Some(Value::Float(PI)),
        ("::math", "TWO_PI") => Some(Value::Float(2.0 * PI)),
        ("::math", "HALF_PI") => Some(Value::Float(PI / 2.0)),
        _ => None,
    }
}

/// Calls native function `def` of `module` with its parameters bound to `args`.
pub fn call(module: &str, def: &Function, args: &[Value], span: Span) -> Eval {
    let name = def.name.as_str();
    let arg = |p: &str| def.param(p).and_then(|(i, _)| args.get(i));
    let float = |p: &str| -> Result<f32, super::eval::Problem> {
        let v = arg(p).ok_or_else(|| problem(span, format!("`{name}` has no parameter `{p}`")))?;
        v.float().map(|f| f as f32).ok_or_else(|| not_constant(name, p, v, span))
    };
    let color = |p: &str| -> Result<Rgb, super::eval::Problem> {
        let v = arg(p).ok_or_else(|| problem(span, format!("`{name}` has no parameter `{p}`")))?;
        v.color().ok_or_else(|| not_constant(name, p, v, span))
    };
    let bsdf = |p: &str| -> Result<Df, super::eval::Problem> {
        match arg(p) {
            Some(Value::Bsdf(d)) => Ok(d.clone()),
            Some(v) => Err(not_constant(name, p, v, span)),
            None => Err(problem(span, format!("`{name}` has no parameter `{p}`"))),
        }
    };
    let mode = || match arg("mode") {
        Some(Value::Enum(_, v)) => ScatterMode::from_enum(*v),
        _ => ScatterMode::Reflect,
    };
    let unchanged_normal = |what: &str| -> Result<(), super::eval::Problem> {
        match arg("normal") {
            None | Some(Value::State(_)) => Ok(()),
            Some(_) => Err(problem(span, format!("`df::{what}` with its own `normal` is not compiled yet"))),
        }
    };
    match (module, name) {
        ("::df", "diffuse_reflection_bsdf") => {
            Ok(Value::Bsdf(Df::Diffuse { tint: color("tint")?, roughness: float("roughness")?.max(0.0) }))
        }
        ("::df", "diffuse_transmission_bsdf") => Ok(Value::Bsdf(Df::DiffuseTransmission(color("tint")?))),
        ("::df", "specular_bsdf") => Ok(Value::Bsdf(Df::Specular { tint: color("tint")?, mode: mode() })),
        ("::df", "simple_glossy_bsdf" | "microfacet_ggx_smith_bsdf" | "microfacet_ggx_vcavities_bsdf") => {
            Ok(Value::Bsdf(Df::Glossy {
                tint: color("tint")?,
                roughness: (float("roughness_u")?.max(0.0), float("roughness_v")?.max(0.0)),
                mode: mode(),
            }))
        }
        ("::df", "normalized_mix" | "clamped_mix" | "color_normalized_mix" | "color_clamped_mix") => {
            let Some(Value::Array(components)) = args.first() else {
                return Err(problem(span, format!("`df::{name}` needs an array of components")));
            };
            match components.first() {
                Some(Value::Struct(_, _)) | None => {}
                Some(v) => return Err(not_constant(name, "components", v, span)),
            }
            let mut weighted = Vec::with_capacity(components.len());
            for c in components {
                let w = c.field("weight").and_then(Value::color).unwrap_or(Rgb::ZERO).max(Rgb::ZERO);
                match c.field("component") {
                    Some(Value::Bsdf(d)) => weighted.push((w, d.clone())),
                    Some(Value::Edf(_)) => {
                        return Err(problem(span, format!("`df::{name}` of EDFs is not compiled yet")))
                    }
                    _ => return Err(problem(span, format!("a component of `df::{name}` is not a constant bsdf"))),
                }
            }
            let clamped = name.contains("clamped");
            Ok(Value::Bsdf(Df::Mix(mix_weights(weighted, clamped))))
        }
        ("::df", "tint") if def.params.len() == 2 => match (arg("tint"), arg("base")) {
            (Some(t), Some(Value::Bsdf(d))) => {
                let t = t.color().ok_or_else(|| not_constant(name, "tint", t, span))?;
                Ok(Value::Bsdf(Df::Mix(vec![(t, d.clone())])))
            }
            _ => Err(problem(span, "`df::tint` of an edf, vdf or hair bsdf is not compiled yet")),
        },
        ("::df", "weighted_layer" | "color_weighted_layer") => {
            unchanged_normal(name)?;
            Ok(Value::Bsdf(Df::Layer {
                weight: color("weight")?.clamp(Rgb::ZERO, Rgb::ONE),
                fresnel_ior: None,
                layer: Box::new(bsdf("layer")?),
                base: Box::new(bsdf("base")?),
            }))
        }
        ("::df", "fresnel_layer" | "color_fresnel_layer") => {
            unchanged_normal(name)?;
            let ior = color("ior")?;
            Ok(Value::Bsdf(Df::Layer {
                weight: color("weight")?.clamp(Rgb::ZERO, Rgb::ONE),
                // A colour IOR is read as its mean (the Fresnel term is not per channel).
                fresnel_ior: Some(((ior.x + ior.y + ior.z) / 3.0).max(1e-3)),
                layer: Box::new(bsdf("layer")?),
                base: Box::new(bsdf("base")?),
            }))
        }
        ("::df", "diffuse_edf") => Ok(Value::Edf(Edf::Diffuse)),
        ("::math", "max" | "min") if args.len() == 2 => {
            let (a, b) = (&args[0], &args[1]);
            let pick = |x: f64, y: f64| if name == "max" { x.max(y) } else { x.min(y) };
            match (a, b) {
                (Value::Color(_), _) | (_, Value::Color(_)) => {
                    let (x, y) = (a.color(), b.color());
                    let (x, y) = x.zip(y).ok_or_else(|| not_constant(name, "a", a, span))?;
                    Ok(Value::Color(if name == "max" { x.max(y) } else { x.min(y) }))
                }
                _ => Ok(Value::Float(pick(
                    a.float().ok_or_else(|| not_constant(name, "a", a, span))?,
                    b.float().ok_or_else(|| not_constant(name, "b", b, span))?,
                ))),
            }
        }
        ("::math", "clamp") if args.len() == 3 => {
            let f = |v: &Value| v.float().ok_or_else(|| not_constant(name, "a", v, span));
            Ok(Value::Float(f(&args[0])?.clamp(f(&args[1])?, f(&args[2])?.max(f(&args[1])?))))
        }
        ("::math", "saturate") if args.len() == 1 => match &args[0] {
            Value::Color(c) => Ok(Value::Color(c.clamp(Rgb::ZERO, Rgb::ONE))),
            v => Ok(Value::Float(v.float().ok_or_else(|| not_constant(name, "x", v, span))?.clamp(0.0, 1.0))),
        },
        ("::math", "lerp") if args.len() == 3 => {
            let t = args[2].float().ok_or_else(|| not_constant(name, "l", &args[2], span))?;
            match (&args[0], &args[1]) {
                (a, b) if a.float().is_some() && b.float().is_some() => {
                    Ok(Value::Float(a.float().unwrap_or(0.0) * (1.0 - t) + b.float().unwrap_or(0.0) * t))
                }
                (a, b) => {
                    let (x, y) = a.color().zip(b.color()).ok_or_else(|| not_constant(name, "a", a, span))?;
                    Ok(Value::Color(x * (1.0 - t as f32) + y * t as f32))
                }
            }
        }
        ("::math", f @ ("sqrt" | "exp" | "log" | "pow" | "abs" | "sin" | "cos")) => {
            let x = args
                .first()
                .and_then(Value::float)
                .ok_or_else(|| problem(span, format!("`math::{f}` of a non-constant")))?;
            let y = args.get(1).and_then(Value::float).unwrap_or(0.0);
            Ok(Value::Float(match f {
                "sqrt" => x.sqrt(),
                "exp" => x.exp(),
                "log" => x.ln(),
                "pow" => x.powf(y),
                "abs" => x.abs(),
                "sin" => x.sin(),
                _ => x.cos(),
            }))
        }
        ("::state", s) => Ok(Value::State(s.to_string())),
        ("::tex" | "::base", f) => Err(problem(
            span,
            format!(
                "`{}::{f}` depends on the shading point; per-hit evaluation of module materials is not compiled yet",
                &module[2..]
            ),
        )),
        (m, f) => Err(problem(span, format!("`{}::{f}` is not compiled yet", m.trim_start_matches("::")))),
    }
}

/// The weights of a mix's components: `normalized_mix` divides them by their sum where it
/// is above 1 (per channel), `clamped_mix` cuts the components that pass 1 (per channel).
pub fn mix_weights(components: Vec<(Rgb, Df)>, clamped: bool) -> Vec<(Rgb, Df)> {
    let sum = components.iter().fold(Rgb::ZERO, |s, (w, _)| s + *w);
    if clamped {
        let mut used = Rgb::ZERO;
        components
            .into_iter()
            .map(|(w, d)| {
                let left = (Rgb::ONE - used).max(Rgb::ZERO);
                let w = w.min(left);
                used += w;
                (w, d)
            })
            .collect()
    } else {
        let scale = Rgb::new(1.0 / sum.x.max(1.0), 1.0 / sum.y.max(1.0), 1.0 / sum.z.max(1.0));
        components.into_iter().map(|(w, d)| (w * scale, d)).collect()
    }
}

fn not_constant(function: &str, param: &str, v: &Value, span: Span) -> super::eval::Problem {
    match v {
        Value::State(s) => problem(
            span,
            format!(
                "`{param}` of `{function}` is `state::{s}()`, which depends on the shading point; not compiled yet"
            ),
        ),
        v => problem(span, format!("`{param}` of `{function}` is {}, not what it takes", kind(v))),
    }
}
