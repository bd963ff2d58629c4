//! Writes the image files of mental ray 3.x's `output` statement: colour images (Softimage
//! `pic`, SGI `rgb`, Alias `pix`, Maya `iff`, `tga`, `ppm`, `bmp`, `tif`, `jpg`, `png`,
//! `hdr`, `exr`) and mental images' own frame buffer files (`ct` colour, `st` scalar, `zt`
//! depth, `nt` normals, `mt` motion, `tt` tags, `bit`).
//!
//! The crate knows nothing of the renderer: [`write()`] takes an [`ImageData`] (linear and
//! display-referred colour, or a depth, normal, motion, tag or scalar buffer) and a
//! [`Format`] parsed from an `output` statement's format name or a file extension.
//!
//! Which writer does the work: the `image` crate for PNG, JPEG, TIFF, Targa, BMP, PPM and
//! Radiance HDR; the `exr` crate for OpenEXR; this crate by hand for SGI, Softimage, Alias,
//! Maya IFF and the mental images formats, for which no maintained Rust crate exists.

mod alias;
pub mod data;
pub mod exr_strips;
pub mod format;
mod iff;
mod mental;
mod openexr;
mod pixels;
mod sgi;
mod softimage;
mod standard;

use std::path::Path;

pub use data::{quantize16, quantize8, srgb, ImageData, Pixels};
pub use format::{Format, Kind, Sample};
pub use openexr::exr_channels;

/// Why an image was not written.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The file could not be created or written.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// An encoding library refused the image.
    #[error("{0}")]
    Encode(String),
    /// The format does not hold this buffer, or mira does not write the format.
    #[error("{0}")]
    Unsupported(String),
    /// The image's size does not fit the format, or its buffers have the wrong length.
    #[error("{0}")]
    Size(String),
}

/// Writes `image` to `path` as `format`.
///
/// 8- and 16-bit colour files quantize the display values (clamped to [0, 1], rounded to
/// nearest); float and half files, RGBE and the data formats store linear values.
pub fn write(path: &Path, format: Format, image: &ImageData) -> Result<(), Error> {
    check(image)?;
    let bytes = match format.kind {
        Kind::Png | Kind::Jpeg | Kind::Tiff | Kind::Ppm | Kind::Targa | Kind::Bmp | Kind::Hdr => {
            return standard::write(path, format, image)
        }
        Kind::Exr => return openexr::write(path, format, image),
        Kind::Sgi => sgi::encode(format, image)?,
        Kind::SoftimagePic => softimage::encode(format, image)?,
        Kind::AliasPix => alias::encode(image)?,
        Kind::MayaIff => iff::encode(format, image)?,
        Kind::MentalColor
        | Kind::MentalScalar
        | Kind::MentalDepth
        | Kind::MentalNormal
        | Kind::MentalMotion
        | Kind::MentalTag
        | Kind::MentalBit => mental::encode(format, image)?,
        Kind::SoftimageZpic => softimage::encode_zpic(image)?,
        Kind::MemoryMap | Kind::Unwritten(_) => {
            return Err(Error::Unsupported(format!("mira does not write '{}' files", format.kind)))
        }
    };
    std::fs::write(path, bytes)?;
    Ok(())
}

/// Checks that every buffer of `image` has `width × height` pixels and the image is not empty.
fn check(image: &ImageData) -> Result<(), Error> {
    let n = image.pixel_count();
    if n == 0 {
        return Err(Error::Size(format!("an image of {} × {} pixels is empty", image.width, image.height)));
    }
    for (name, p) in std::iter::once(("", &image.pixels)).chain(image.layers.iter().map(|(n, p)| (n.as_str(), p))) {
        if p.len() != n {
            return Err(Error::Size(format!(
                "buffer '{}{name}' has {} pixels, the image {} × {} = {n}",
                p.type_name(),
                p.len(),
                image.width,
                image.height
            )));
        }
    }
    Ok(())
}

/// The error for a buffer a colour format does not hold.
fn not_colour(format: Format, pixels: &Pixels) -> Error {
    Error::Unsupported(format!(
        "'{}' files hold colour; the '{}' buffer is written to {} or exr files",
        format.kind,
        pixels.type_name(),
        match pixels {
            Pixels::Depth(_) => "zt",
            Pixels::Normal(_) => "nt",
            Pixels::Motion(_) => "mt",
            Pixels::Tag(_) => "tt",
            _ => "st",
        }
    ))
}
