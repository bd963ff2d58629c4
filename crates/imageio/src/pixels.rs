//! Colour samples of an image as a colour file stores them: interleaved, rows top to bottom,
//! one (grey), three (RGB) or four (RGBA) channels, quantized or linear.

use crate::{not_colour, Error, Format, ImageData, Pixels, Sample};

/// Interleaved samples and their channel count.
pub(crate) struct Interleaved<T> {
    /// Samples, `channels` per pixel, rows top to bottom.
    pub samples: Vec<T>,
    /// 1, 3 or 4.
    pub channels: usize,
}

/// The main buffer of `image` as a colour file of `format` holds it: colour as RGB or RGBA
/// (by `format.alpha`), a scalar buffer as grey when `grey` allows it, else as RGB(A) grey
/// with alpha 1. `encode` maps a value to a sample; `linear` picks the linear colour values
/// (float files) rather than the display values.
pub(crate) fn interleaved<T: Copy>(
    format: Format,
    image: &ImageData,
    grey: bool,
    linear: bool,
    encode: impl Fn(f32) -> T,
) -> Result<Interleaved<T>, Error> {
    let channels = if format.alpha { 4 } else { 3 };
    match &image.pixels {
        Pixels::Color { linear: lin, display } => {
            let src = if linear { lin } else { display };
            let samples = src.iter().flat_map(|p| p[..channels].iter().map(|v| encode(*v))).collect();
            Ok(Interleaved { samples, channels })
        }
        Pixels::Scalar(v) if grey => Ok(Interleaved { samples: v.iter().map(|s| encode(*s)).collect(), channels: 1 }),
        Pixels::Scalar(v) => {
            let samples = v
                .iter()
                .flat_map(|s| [*s, *s, *s, 1.0][..channels].iter().map(|x| encode(*x)).collect::<Vec<_>>())
                .collect();
            Ok(Interleaved { samples, channels })
        }
        other => Err(not_colour(format, other)),
    }
}

/// 8-bit samples of display values.
pub(crate) fn u8s(format: Format, image: &ImageData, grey: bool) -> Result<Interleaved<u8>, Error> {
    interleaved(format, image, grey, false, crate::quantize8)
}

/// 16-bit samples of display values.
pub(crate) fn u16s(format: Format, image: &ImageData, grey: bool) -> Result<Interleaved<u16>, Error> {
    interleaved(format, image, grey, false, crate::quantize16)
}

/// Float samples of linear values.
pub(crate) fn f32s(format: Format, image: &ImageData, grey: bool) -> Result<Interleaved<f32>, Error> {
    interleaved(format, image, grey, true, |v| v)
}

/// Checks that a size fits a format's 16-bit width and height fields.
pub(crate) fn fits_u16(format: Format, image: &ImageData) -> Result<(u16, u16), Error> {
    match (u16::try_from(image.width), u16::try_from(image.height)) {
        (Ok(w), Ok(h)) => Ok((w, h)),
        _ => Err(Error::Size(format!(
            "'{}' files are at most 65535 pixels a side; the image is {} × {}",
            format.kind, image.width, image.height
        ))),
    }
}

/// The sample type, checked against those the format holds.
pub(crate) fn sample(format: Format) -> Result<Sample, Error> {
    if format.kind.samples().contains(&format.sample) {
        Ok(format.sample)
    } else {
        Err(Error::Unsupported(format!("'{}' files do not hold {:?} samples", format.kind, format.sample)))
    }
}
