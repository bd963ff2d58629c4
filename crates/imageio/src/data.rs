//! The pixels handed to the writers: one frame buffer (colour, scalar, depth, normal, motion
//! or tag) plus, for formats that hold several, more named buffers.

/// One frame buffer's pixels, `width × height` of them, rows top to bottom, each row left to
/// right.
#[derive(Clone, Debug, PartialEq)]
pub enum Pixels {
    /// Colour. `linear`: scene-referred RGBA as rendered (float files take these);
    /// `display`: the same pixels tone mapped and display-encoded, RGB in [0, 1], alpha as
    /// rendered (8- and 16-bit files quantize these).
    Color {
        /// Linear RGBA.
        linear: Vec<[f32; 4]>,
        /// Display-referred RGBA in [0, 1].
        display: Vec<[f32; 4]>,
    },
    /// One channel (alpha, intensity, coverage), 0…1 for 8- and 16-bit files.
    Scalar(Vec<f32>),
    /// Depth: −z in camera space of the frontmost object, 0 where there is none.
    Depth(Vec<f32>),
    /// Surface normals (x, y, z).
    Normal(Vec<[f32; 3]>),
    /// Motion vectors in raster pixels over the shutter interval (x right, y up).
    Motion(Vec<[f32; 2]>),
    /// Object labels (`tag`).
    Tag(Vec<u32>),
}

impl Pixels {
    /// The number of pixels.
    pub fn len(&self) -> usize {
        match self {
            Pixels::Color { linear, display } => linear.len().min(display.len()),
            Pixels::Scalar(v) | Pixels::Depth(v) => v.len(),
            Pixels::Normal(v) => v.len(),
            Pixels::Motion(v) => v.len(),
            Pixels::Tag(v) => v.len(),
        }
    }

    /// Whether there are no pixels.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The buffer type as an `output` statement names it (`rgba`, `a`, `z`, `n`, `m`, `tag`).
    pub fn type_name(&self) -> &'static str {
        match self {
            Pixels::Color { .. } => "rgba",
            Pixels::Scalar(_) => "a",
            Pixels::Depth(_) => "z",
            Pixels::Normal(_) => "n",
            Pixels::Motion(_) => "m",
            Pixels::Tag(_) => "tag",
        }
    }
}

/// An image to write: its main buffer and, for multi-channel formats (EXR), more named
/// buffers.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageData {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The buffer every format writes.
    pub pixels: Pixels,
    /// Further buffers, by name, that EXR files add as channels (`Z`, `N.X`, `fb0.R`, …; see
    /// [`crate::exr_channels`]); other formats ignore them.
    pub layers: Vec<(String, Pixels)>,
}

impl ImageData {
    /// An image of one buffer.
    pub fn new(width: u32, height: u32, pixels: Pixels) -> ImageData {
        ImageData { width, height, pixels, layers: Vec::new() }
    }

    /// A colour image whose display values are the sRGB encoding of its linear values
    /// (clamped to [0, 1]; alpha unchanged).
    pub fn srgb(width: u32, height: u32, linear: Vec<[f32; 4]>) -> ImageData {
        let display = linear.iter().map(|p| [srgb(p[0]), srgb(p[1]), srgb(p[2]), p[3]]).collect();
        ImageData::new(width, height, Pixels::Color { linear, display })
    }

    /// This image with one more named buffer.
    pub fn with_layer(mut self, name: &str, pixels: Pixels) -> ImageData {
        self.layers.push((name.to_string(), pixels));
        self
    }

    /// The number of pixels, `width × height`.
    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }
}

/// The sRGB transfer function of a linear value, clamped to [0, 1].
pub fn srgb(v: f32) -> f32 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// A value in [0, 1] as an 8-bit code: clamped, scaled by 255, rounded half up (NaN is 0).
pub fn quantize8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
}

/// A value in [0, 1] as a 16-bit code: clamped, scaled by 65535, rounded half up (NaN is 0).
pub fn quantize16(v: f32) -> u16 {
    (v.clamp(0.0, 1.0) * 65535.0 + 0.5) as u16
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantization_rounds_to_nearest_and_clamps() {
        assert_eq!(quantize8(0.0), 0);
        assert_eq!(quantize8(1.0), 255);
        assert_eq!(quantize8(2.0), 255);
        assert_eq!(quantize8(-1.0), 0);
        assert_eq!(quantize8(f32::NAN), 0);
        assert_eq!(quantize8(0.5), 128);
        assert_eq!(quantize8(127.4 / 255.0), 127);
        assert_eq!(quantize16(0.5), 32768);
        assert_eq!(quantize16(1.0), 65535);
    }

    #[test]
    fn srgb_matches_the_standard_curve() {
        assert_eq!(srgb(0.0), 0.0);
        assert!((srgb(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb(0.18) - 0.461_356).abs() < 1e-5);
        assert!((srgb(0.002) - 0.025_84).abs() < 1e-6);
    }
}
