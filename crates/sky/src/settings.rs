//! What the sun and the sky share: turbidity from mia's `haze`, the sky's frame, the unit
//! conversion and the colour tweaks (saturation, red/blue shift).

use glam::Vec3A;

/// Rec.709 luminance of linear RGB (the weights the sun and sky use for saturation and for
/// lux).
pub fn luminance(c: Vec3A) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// Turbidity for mia's `haze` (0 … 15): 2 + haze (2 is a very clear sky).
pub fn turbidity(haze: f32) -> f32 {
    2.0 + haze.max(0.0)
}

/// `rgb_unit_conversion` as used: 0 0 0 (or anything without positive luminance) means
/// 1/80 000 in every channel.
pub fn unit_conversion(c: Vec3A) -> Vec3A {
    if luminance(c) > 0.0 {
        c
    } else {
        Vec3A::splat(1.0 / 80_000.0)
    }
}

/// World direction `d` in the sky's frame (+Z the zenith): Y and Z swapped when `y_is_up`,
/// the up component lowered by `horizon_height` / 10, renormalised (zero if degenerate).
pub fn sky_frame(d: Vec3A, y_is_up: bool, horizon_height: f32) -> Vec3A {
    let mut v = if y_is_up { Vec3A::new(d.x, d.z, d.y) } else { d };
    v.z -= horizon_height / 10.0;
    v.normalize_or_zero()
}

/// The saturation applied for mia's `saturation` and `haze`: above 1 as given, below it
/// lowered with haze, s(1 − h) + s³h with h = (haze/15)³.
pub fn effective_saturation(saturation: f32, haze: f32) -> f32 {
    if saturation > 1.0 {
        return saturation;
    }
    let h = (haze / 15.0).clamp(0.0, 1.0).powi(3);
    saturation * (1.0 - h) + saturation.powi(3) * h
}

/// Saturation (a mix with the Rec.709 luminance; 0 grey) and red/blue shift (red × (1 +
/// shift), blue × (1 − shift)); negative channels are clamped.
pub fn color_tweak(c: Vec3A, saturation: f32, redblueshift: f32) -> Vec3A {
    let l = Vec3A::splat(luminance(c));
    let c = if saturation <= 0.0 { l } else { (c * saturation + l * (1.0 - saturation)).max(Vec3A::ZERO) };
    (c * Vec3A::new(1.0 + redblueshift, 1.0, 1.0 - redblueshift)).max(Vec3A::ZERO)
}
