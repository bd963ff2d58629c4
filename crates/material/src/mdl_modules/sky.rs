//! `base::sun_and_sky` called inside module materials and functions: the same daylight
//! model the `.mi` shader `mdl::base::sun_and_sky` runs ([`mdl::sky::SunAndSky`], π ×
//! `mia_physicalsky`'s value), built as a [`HitExpr::Sky`] node of the ray's direction
//! (`state::direction()`, world space) whose `texture_return` has the radiance as `tint`
//! and 1 as `mono`, as the MDL SDK's definition returns.
//!
//! Every parameter must be a constant (the daylight model is set up once per material
//! instance); one that varies over the surface is an error naming it. `flags` is unused,
//! as in the MDL SDK. `base::perez_sun_and_sky` (Perez's all-weather sky from measured
//! irradiances) has no implementation in mira, neither in modules nor as a `.mi` shader:
//! an error at its module line.

use std::sync::Arc;

use glam::Vec3A;
use mdl_lang::Function;
use mi::Span;

use mdl::sky::SunAndSky;

use super::eval::{kind, problem, Eval, Problem};
use super::hit::{HitExpr, StateFn};
use super::value::{HitType, Value};

/// `base::sun_and_sky` of `args` (bound to `def`'s parameters, defaults filled in).
pub fn sun_and_sky(def: &Function, args: &[Value], span: Span) -> Eval {
    let arg = |p: &str| def.param(p).and_then(|(i, _)| args.get(i));
    let not_constant = |p: &str, v: &Value| -> Problem {
        problem(span, format!("`base::sun_and_sky`'s `{p}` is {}; mira compiles it only as a constant", kind(v)))
    };
    let mut sky = SunAndSky::default();
    let num = |p: &str, d: f32| -> Result<f32, Problem> {
        match arg(p) {
            None => Ok(d),
            Some(v) => v.float().map(|f| f as f32).ok_or_else(|| not_constant(p, v)),
        }
    };
    let flag = |p: &str, d: bool| -> Result<bool, Problem> {
        match arg(p) {
            None => Ok(d),
            Some(Value::Bool(b)) => Ok(*b),
            Some(v) => Err(not_constant(p, v)),
        }
    };
    let triple = |p: &str, d: Vec3A| -> Result<Vec3A, Problem> {
        match arg(p) {
            None => Ok(d),
            Some(v) => v.color().ok_or_else(|| not_constant(p, v)),
        }
    };
    let s = &mut sky.sky;
    sky.on = flag("on", sky.on)?;
    s.multiplier = num("multiplier", s.multiplier)?;
    s.rgb_unit_conversion = triple("rgb_unit_conversion", s.rgb_unit_conversion)?;
    s.haze = num("haze", s.haze)?;
    s.redblueshift = num("redblueshift", s.redblueshift)?;
    s.saturation = num("saturation", s.saturation)?;
    s.horizon_height = num("horizon_height", s.horizon_height)?;
    s.horizon_blur = num("horizon_blur", s.horizon_blur)?;
    s.ground_color = triple("ground_color", s.ground_color)?;
    s.night_color = triple("night_color", s.night_color)?;
    s.sun_direction = triple("sun_direction", s.sun_direction)?;
    s.sun_disk_intensity = num("sun_disk_intensity", s.sun_disk_intensity)?;
    s.sun_disk_scale = num("sun_disk_scale", s.sun_disk_scale)?;
    s.sun_glow_intensity = num("sun_glow_intensity", s.sun_glow_intensity)?;
    s.y_is_up = flag("y_is_up", s.y_is_up)?;
    s.physically_scaled_sun = flag("physically_scaled_sun", s.physically_scaled_sun)?;
    let dir = Arc::new(HitExpr::State(StateFn::Direction));
    let tint = Value::from_hit(HitExpr::Sky(Arc::new(sky), dir), HitType::Color);
    Ok(Value::Struct("texture_return".into(), vec![("tint".into(), tint), ("mono".into(), Value::Float(1.0))]))
}

/// `base::perez_sun_and_sky`: not implemented (see the module comment).
pub fn perez_sun_and_sky(span: Span) -> Eval {
    Err(problem(
        span,
        "`base::perez_sun_and_sky` is not compiled: mira has no Perez all-weather sky model \
         (use `base::sun_and_sky`)",
    ))
}
