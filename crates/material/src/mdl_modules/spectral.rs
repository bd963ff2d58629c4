//! `math::blackbody`: the colour of a black body, as MDL defines it — the Planck spectrum
//! at the temperature (at least 500 K) through the CIE 1931 colour matching functions,
//! scaled to luminance Y = 1, in linear Rec. 709 / sRGB primaries with negative channels
//! clamped to 0 (the MDL SDK's runtime does the same). mira integrates the spectrum with
//! its own table ([`baselib::color::blackbody_xyz`]). A temperature that varies over the
//! surface is a per-hit node ([`MathFn::Blackbody`]) computing the same colour.

use bsdf::Rgb;
use mi::Span;

use super::eval::{kind, problem, Eval};
use super::hit::{HitExpr, MathFn};
use super::value::{HitType, Value};

/// The lowest temperature read (kelvin); lower ones (and NaN) read as it.
const MIN_KELVIN: f32 = 500.0;

/// The black body colour of temperature `kelvin`, luminance 1, linear Rec. 709.
pub fn blackbody_rgb(kelvin: f32) -> Rgb {
    let xyz = baselib::color::blackbody_xyz(kelvin.max(MIN_KELVIN));
    let rgb = baselib::color::XYZ_TO_RGB * (xyz / xyz.y);
    rgb.max(Rgb::ZERO)
}

/// `math::blackbody(temperature)` of a temperature (kelvin): a colour when it is constant,
/// a per-hit colour when it depends on the hit.
pub fn blackbody(args: &[Value], span: Span) -> Eval {
    match args.first() {
        Some(Value::Hit(t, _)) => {
            Ok(Value::from_hit(HitExpr::Math(MathFn::Blackbody, [t.clone()].into()), HitType::Color))
        }
        Some(v) => {
            let t = v.float().ok_or_else(|| {
                problem(span, format!("`math::blackbody` of a temperature that is {} is not compiled", kind(v)))
            })?;
            Ok(Value::Color(blackbody_rgb(t as f32)))
        }
        None => Err(problem(span, "`math::blackbody` without a temperature")),
    }
}
