//! `base::sun_and_sky` called inside module materials and functions: the same daylight
//! model the `.mi` shader `mdl::base::sun_and_sky` runs ([`mdl::sky::SunAndSky`], π ×
//! `mia_physicalsky`'s value), built as a [`HitExpr::Sky`] node of the ray's direction
//! (`state::direction()`, world space) whose `texture_return` has the radiance as `tint`
//! and 1 as `mono`, as the MDL SDK's definition returns.
//!
//! The parameters the MDL SDK's `base.mdl` declares `uniform` must be constants (the
//! daylight model is set up once per call); one that varies is an error naming it. The
//! varying ones (`multiplier`, `haze`, `redblueshift`, `horizon_height`, `horizon_blur`,
//! `ground_color`, `night_color`) may depend on the hit or the direction: they are then
//! evaluated at each lookup and the model is set up with their values there
//! ([`SkyCall::radiance`]). `flags` is unused, as in the MDL SDK.
//!
//! `base::perez_sun_and_sky` likewise: Perez's all-weather sky ([`sky::perez`], the `.mi`
//! shader `mdl::base::perez_sun_and_sky` of the `mdl` library), set up once per call, its
//! `ground_color` evaluated per lookup where it depends on the hit.

use std::sync::Arc;

use glam::Vec3A;
use mdl_lang::Function;
use mi::Span;

use mdl::sky::SunAndSky;
use sky::perez::{PerezSky, PerezSunAndSky};

use super::eval::{kind, problem, Eval, Problem};
use super::hit::{HitExpr, StateFn};
use super::sky_model::{SkyCall, SkyModel, SkyParam};
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
    // The varying parameters that depend on the hit: given per lookup (their constant
    // values are read below like the others').
    let mut varying = Vec::new();
    let mut operands = vec![Arc::new(HitExpr::State(StateFn::Direction))];
    for (param, name) in SkyParam::ALL {
        if let Some(Value::Hit(e, _)) = arg(name) {
            varying.push(param);
            operands.push(e.clone());
        }
    }
    let constant = |p: &str| !matches!(arg(p), Some(Value::Hit(..)));
    let s = &mut sky.sky;
    sky.on = flag("on", sky.on)?;
    let read = |p: &str, d: f32| if constant(p) { num(p, d) } else { Ok(d) };
    let read3 = |p: &str, d: Vec3A| if constant(p) { triple(p, d) } else { Ok(d) };
    s.multiplier = read("multiplier", s.multiplier)?;
    s.rgb_unit_conversion = triple("rgb_unit_conversion", s.rgb_unit_conversion)?;
    s.haze = read("haze", s.haze)?;
    s.redblueshift = read("redblueshift", s.redblueshift)?;
    s.saturation = num("saturation", s.saturation)?;
    s.horizon_height = read("horizon_height", s.horizon_height)?;
    s.horizon_blur = read("horizon_blur", s.horizon_blur)?;
    s.ground_color = read3("ground_color", s.ground_color)?;
    s.night_color = read3("night_color", s.night_color)?;
    s.sun_direction = triple("sun_direction", s.sun_direction)?;
    s.sun_disk_intensity = num("sun_disk_intensity", s.sun_disk_intensity)?;
    s.sun_disk_scale = num("sun_disk_scale", s.sun_disk_scale)?;
    s.sun_glow_intensity = num("sun_glow_intensity", s.sun_glow_intensity)?;
    s.y_is_up = flag("y_is_up", s.y_is_up)?;
    s.physically_scaled_sun = flag("physically_scaled_sun", s.physically_scaled_sun)?;
    let call = SkyCall::new(SkyModel::SunAndSky(sky), varying.into());
    let tint = Value::from_hit(HitExpr::Sky(Arc::new(call), operands.into()), HitType::Color);
    Ok(Value::Struct("texture_return".into(), vec![("tint".into(), tint), ("mono".into(), Value::Float(1.0))]))
}

/// `base::perez_sun_and_sky` of `args` (bound to `def`'s parameters, defaults filled in):
/// Perez's all-weather sky ([`sky::perez::PerezSky`]), set up once from the parameters
/// MDL declares `uniform` (constants, else an error naming the parameter); `ground_color`
/// may depend on the hit and is then evaluated per lookup. A `color`, as MDL declares it.
pub fn perez_sun_and_sky(def: &Function, args: &[Value], span: Span) -> Eval {
    let arg = |p: &str| def.param(p).and_then(|(i, _)| args.get(i));
    let not_constant = |p: &str, v: &Value| -> Problem {
        problem(span, format!("`base::perez_sun_and_sky`'s `{p}` is {}; mira compiles it only as a constant", kind(v)))
    };
    let num = |p: &str, d: f32| -> Result<f32, Problem> {
        match arg(p) {
            None => Ok(d),
            Some(v) => v.float().map(|f| f as f32).ok_or_else(|| not_constant(p, v)),
        }
    };
    let triple = |p: &str, d: Vec3A| -> Result<Vec3A, Problem> {
        match arg(p) {
            None => Ok(d),
            Some(v) => v.color().ok_or_else(|| not_constant(p, v)),
        }
    };
    let d = PerezSunAndSky::default();
    let mut varying = Vec::new();
    let mut operands = vec![Arc::new(HitExpr::State(StateFn::Direction))];
    let ground_color = match arg("ground_color") {
        Some(Value::Hit(e, _)) => {
            varying.push(SkyParam::GroundColor);
            operands.push(e.clone());
            d.ground_color
        }
        _ => triple("ground_color", d.ground_color)?,
    };
    let params = PerezSunAndSky {
        direct_normal_irradiance: num("direct_normal_irradiance", d.direct_normal_irradiance)?,
        diffuse_horizontal_irradiance: num("diffuse_horizontal_irradiance", d.diffuse_horizontal_irradiance)?,
        sun_direction: triple("sun_direction", d.sun_direction)?,
        ground_color,
        horizon_blur: num("horizon_blur", d.horizon_blur)?,
        y_is_up: match arg("y_is_up") {
            None => d.y_is_up,
            Some(Value::Bool(b)) => *b,
            Some(v) => return Err(not_constant("y_is_up", v)),
        },
        julian_date: num("julian_date", d.julian_date)?,
        dew_point: num("dew_point", d.dew_point)?,
        haze: num("haze", d.haze)?,
    };
    let call = SkyCall::new(SkyModel::Perez(Box::new(PerezSky::new(params))), varying.into());
    Ok(Value::from_hit(HitExpr::Sky(Arc::new(call), operands.into()), HitType::Color))
}
