//! Linear RGB colour (Rec.709 / sRGB primaries).

/// A linear RGB colour, one `f32` per channel (a `Vec3A` so that arithmetic is SIMD).
pub type Rgb = glam::Vec3A;

/// Luminance with the Rec.709 weights.
pub fn luminance(c: Rgb) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// The largest channel.
pub fn max_channel(c: Rgb) -> f32 {
    c.max_element()
}
