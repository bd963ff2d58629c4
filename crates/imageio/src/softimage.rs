//! Softimage `pic` files, written by hand: no maintained Rust crate writes them. Layout from
//! Softimage's PIC format description: a 104-byte big-endian header (magic 0x5380F634,
//! version, 80-byte comment, `PICT`, width, height, pixel ratio, fields, padding), a chain of
//! 4-byte channel packets (chained flag, bits per channel, encoding, channel mask), then each
//! scanline, top first, holding each packet's channels in that packet's encoding — here
//! mixed run-length (encoding 2) for RGB and for alpha.

use crate::pixels::{fits_u16, u8s};
use crate::{Error, Format, ImageData};

const MAGIC: u32 = 0x5380_F634;
const VERSION: f32 = 3.71;
/// Channel mask bits.
const RED: u8 = 0x80;
const GREEN: u8 = 0x40;
const BLUE: u8 = 0x20;
const ALPHA: u8 = 0x10;
/// Mixed run-length encoding.
const MIXED_RLE: u8 = 2;

/// Mixed run-length encodes one scanline of `pixels` (each a slice of its channels): a
/// count byte below 128 is followed by count + 1 literal pixels; 129…255 by one pixel
/// repeated count − 127 times; 128 by a 16-bit count and one pixel repeated that often.
fn mixed_rle(pixels: &[&[u8]], out: &mut Vec<u8>) {
    let n = pixels.len();
    let mut i = 0;
    while i < n {
        let mut run = 1;
        while i + run < n && pixels[i + run] == pixels[i] && run < u16::MAX as usize {
            run += 1;
        }
        if run >= 2 {
            if run <= 128 {
                out.push((run + 127) as u8);
            } else {
                out.push(128);
                out.extend_from_slice(&(run as u16).to_be_bytes());
            }
            out.extend_from_slice(pixels[i]);
            i += run;
            continue;
        }
        let start = i;
        while i < n && i - start < 128 {
            if i + 1 < n && pixels[i] == pixels[i + 1] {
                break;
            }
            i += 1;
        }
        out.push((i - start - 1) as u8);
        for p in &pixels[start..i] {
            out.extend_from_slice(p);
        }
    }
}

/// Encodes the main buffer of `image` as an 8-bit Softimage picture, RGB and (when
/// `format.alpha`) alpha.
pub(crate) fn encode(format: Format, image: &ImageData) -> Result<Vec<u8>, Error> {
    let (w16, h16) = fits_u16(format, image)?;
    let px = u8s(format, image, false)?;
    let (w, h, c) = (w16 as usize, h16 as usize, px.channels);
    let mut out = Vec::with_capacity(128 + w * h * c);
    out.extend_from_slice(&MAGIC.to_be_bytes());
    out.extend_from_slice(&VERSION.to_be_bytes());
    let mut comment = [0u8; 80];
    comment[..4].copy_from_slice(b"mira");
    out.extend_from_slice(&comment);
    out.extend_from_slice(b"PICT");
    out.extend_from_slice(&w16.to_be_bytes());
    out.extend_from_slice(&h16.to_be_bytes());
    out.extend_from_slice(&1.0f32.to_be_bytes()); // pixel aspect ratio
    out.extend_from_slice(&3u16.to_be_bytes()); // both fields: a full frame
    out.extend_from_slice(&0u16.to_be_bytes());
    let alpha = c == 4;
    out.extend_from_slice(&[u8::from(alpha), 8, MIXED_RLE, RED | GREEN | BLUE]);
    if alpha {
        out.extend_from_slice(&[0, 8, MIXED_RLE, ALPHA]);
    }
    for y in 0..h {
        let row = &px.samples[y * w * c..(y + 1) * w * c];
        let rgb: Vec<&[u8]> = row.chunks_exact(c).map(|p| &p[..3]).collect();
        mixed_rle(&rgb, &mut out);
        if alpha {
            let a: Vec<&[u8]> = row.chunks_exact(c).map(|p| &p[3..4]).collect();
            mixed_rle(&a, &mut out);
        }
    }
    Ok(out)
}

/// The farthest depth a Softimage `Zpic` file holds (scene units; its values run from 0
/// at the camera to this).
pub const ZPIC_FAR: f32 = -100_000.0;

/// A Softimage `Zpic` depth file, written by hand (no crate writes it): no header, one
/// big-endian 32-bit float per pixel, rows top first, `width × height` of the `pic` image
/// it goes with (which says the size). Values are camera-space z — the depth along −Z
/// negated, 0 at the camera, negative in front of it — clamped to [`ZPIC_FAR`]; pixels where
/// nothing was hit (depth 0 or not finite) get [`ZPIC_FAR`], behind everything.
pub(crate) fn encode_zpic(image: &ImageData) -> Result<Vec<u8>, Error> {
    let crate::Pixels::Depth(depth) = &image.pixels else {
        return Err(Error::Unsupported(format!("'Zpic' files hold the z buffer, not '{}'", image.pixels.type_name())));
    };
    let z = |d: f32| if d > 0.0 && d.is_finite() { (-d).max(ZPIC_FAR) } else { ZPIC_FAR };
    Ok(depth.iter().flat_map(|d| z(*d).to_be_bytes()).collect())
}
