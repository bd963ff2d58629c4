//! `math::blackbody`: the colour of a black body, as MDL defines it — the Planck spectrum
//! at the temperature (at least 500 K) through the CIE 1931 colour matching functions,
//! scaled to luminance Y = 1, in linear Rec. 709 / sRGB primaries with negative channels
//! clamped to 0 (the MDL SDK's runtime does the same). mira integrates the spectrum with
//! its own table ([`baselib::color::blackbody_xyz`]).

use mi::Span;

use super::eval::{kind, problem, Eval};
use super::value::Value;

/// The lowest temperature read (kelvin); lower ones read as it.
const MIN_KELVIN: f32 = 500.0;

/// `math::blackbody(temperature)` of a constant temperature (kelvin).
pub fn blackbody(args: &[Value], span: Span) -> Eval {
    let t = match args.first() {
        Some(v) => v.float().ok_or_else(|| {
            problem(span, format!("`math::blackbody` of a temperature that is {} is not compiled", kind(v)))
        })?,
        None => return Err(problem(span, "`math::blackbody` without a temperature")),
    };
    let xyz = baselib::color::blackbody_xyz((t as f32).max(MIN_KELVIN));
    let rgb = baselib::color::XYZ_TO_RGB * (xyz / xyz.y);
    Ok(Value::Color(rgb.max(bsdf::Rgb::ZERO)))
}
