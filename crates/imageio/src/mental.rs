//! mental images' own frame buffer files, written by hand (no library writes them): `ct`
//! colour, `st` scalar, `zt` depth, `nt` normals, `mt` motion, `tt` tags and `bit`.
//!
//! mental ray's manual names these formats but does not publish their layout; mira writes
//! the layout that the one public reader of them, mrViewer's `mrayImage`, expects: an 8-byte
//! header — a type byte (`ct` 0x0b, `st` 0x04, `zt` 0x08, `nt` 0x09, `tt` 0x0a, `mt` 0x0c,
//! `bit` 0x0d), a zero byte, width and height as big-endian 16-bit integers, and two zero
//! bytes — then the pixels uncompressed, components interleaved, big-endian, the bottom
//! scanline first. Component counts and sizes follow mental ray's frame buffer types
//! (`shader.h`): colour 4 × 8 bits, 16 bits, half or float (a reader tells 8, 16 and 32 bits
//! apart by the file size; half files are told by their `cth` name); scalar 1 × 8, 16 or 32
//! bits; depth 1 float; normals 3 floats; motion 3 floats (raster x, y and 0); tags one
//! 32-bit unsigned integer; bit one byte, 0 or 1. This layout has not been checked against a
//! file written by mental ray itself.

use crate::pixels::{fits_u16, sample};
use crate::{not_colour, quantize16, quantize8, Error, Format, ImageData, Kind, Pixels, Sample};

/// The type byte of each format.
fn type_code(kind: Kind) -> u8 {
    match kind {
        Kind::MentalColor => 0x0b,
        Kind::MentalScalar => 0x04,
        Kind::MentalDepth => 0x08,
        Kind::MentalNormal => 0x09,
        Kind::MentalTag => 0x0a,
        Kind::MentalMotion => 0x0c,
        _ => 0x0d,
    }
}

/// Encodes the main buffer of `image` as the mental images file `format.kind` names.
pub(crate) fn encode(format: Format, image: &ImageData) -> Result<Vec<u8>, Error> {
    let (w16, h16) = fits_u16(format, image)?;
    let (w, h) = (w16 as usize, h16 as usize);
    let mut out = vec![type_code(format.kind), 0];
    out.extend_from_slice(&w16.to_be_bytes());
    out.extend_from_slice(&h16.to_be_bytes());
    out.extend_from_slice(&[0, 0]);
    let wrong = |expected: &str| {
        Error::Unsupported(format!(
            "'{}' files hold the {expected} buffer, not '{}'",
            format.kind,
            image.pixels.type_name()
        ))
    };
    // Pixel index of file pixel k: rows bottom first.
    let order = (0..h).rev().flat_map(|y| (0..w).map(move |x| y * w + x));
    match (format.kind, &image.pixels) {
        (Kind::MentalColor, Pixels::Color { linear, display }) => {
            let sample = sample(format)?;
            for i in order {
                for k in 0..4 {
                    match sample {
                        Sample::U8 => out.push(quantize8(display[i][k])),
                        Sample::U16 => out.extend_from_slice(&quantize16(display[i][k]).to_be_bytes()),
                        Sample::Half => out.extend_from_slice(&half_bits(linear[i][k]).to_be_bytes()),
                        Sample::F32 => out.extend_from_slice(&linear[i][k].to_be_bytes()),
                    }
                }
            }
        }
        (Kind::MentalColor, other) => return Err(not_colour(format, other)),
        (Kind::MentalScalar, Pixels::Scalar(v)) => {
            let sample = sample(format)?;
            for i in order {
                match sample {
                    Sample::U8 => out.push(quantize8(v[i])),
                    Sample::U16 => out.extend_from_slice(&quantize16(v[i]).to_be_bytes()),
                    _ => out.extend_from_slice(&v[i].to_be_bytes()),
                }
            }
        }
        (Kind::MentalDepth, Pixels::Depth(v)) => order.for_each(|i| out.extend_from_slice(&v[i].to_be_bytes())),
        (Kind::MentalNormal, Pixels::Normal(v)) => {
            order.for_each(|i| v[i].iter().for_each(|c| out.extend_from_slice(&c.to_be_bytes())))
        }
        (Kind::MentalMotion, Pixels::Motion(v)) => {
            order.for_each(|i| [v[i][0], v[i][1], 0.0].iter().for_each(|c| out.extend_from_slice(&c.to_be_bytes())))
        }
        (Kind::MentalTag, Pixels::Tag(v)) => order.for_each(|i| out.extend_from_slice(&v[i].to_be_bytes())),
        (Kind::MentalBit, Pixels::Scalar(v)) => order.for_each(|i| out.push(u8::from(v[i] >= 0.5))),
        (Kind::MentalBit, Pixels::Tag(v)) => order.for_each(|i| out.push(u8::from(v[i] != 0))),
        (Kind::MentalScalar | Kind::MentalBit, _) => return Err(wrong("scalar")),
        (Kind::MentalDepth, _) => return Err(wrong("z")),
        (Kind::MentalNormal, _) => return Err(wrong("n")),
        (Kind::MentalMotion, _) => return Err(wrong("m")),
        (Kind::MentalTag, _) => return Err(wrong("tag")),
        (kind, _) => return Err(Error::Unsupported(format!("'{kind}' is not a mental images data format"))),
    }
    Ok(out)
}

/// The IEEE 754 half-precision bits of `v`, rounded to nearest even.
fn half_bits(v: f32) -> u16 {
    exr::prelude::f16::from_f32(v).to_bits()
}
