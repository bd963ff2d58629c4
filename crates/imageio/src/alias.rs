//! Alias `pix` files, written by hand: no maintained Rust crate writes them. Layout: a
//! 10-byte big-endian header (width, height, x and y offset, bits per pixel: 24), then each
//! scanline, top first, as runs of (count 1…255, blue, green, red).

use crate::pixels::{fits_u16, u8s};
use crate::{Error, Format, ImageData, Sample};

/// Encodes the main buffer of `image` as an Alias pix file (8-bit RGB).
pub(crate) fn encode(image: &ImageData) -> Result<Vec<u8>, Error> {
    let format = Format { kind: crate::Kind::AliasPix, sample: Sample::U8, alpha: false };
    let (w16, h16) = fits_u16(format, image)?;
    let px = u8s(format, image, false)?;
    let (w, h) = (w16 as usize, h16 as usize);
    let mut out = Vec::with_capacity(10 + w * h * 4);
    for v in [w16, h16, 0, 0, 24] {
        out.extend_from_slice(&v.to_be_bytes());
    }
    for y in 0..h {
        let row: Vec<&[u8]> = px.samples[y * w * 3..(y + 1) * w * 3].chunks_exact(3).collect();
        let mut i = 0;
        while i < w {
            let mut run = 1;
            while i + run < w && row[i + run] == row[i] && run < 255 {
                run += 1;
            }
            out.extend_from_slice(&[run as u8, row[i][2], row[i][1], row[i][0]]);
            i += run;
        }
    }
    Ok(out)
}
