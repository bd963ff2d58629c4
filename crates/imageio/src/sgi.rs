//! Silicon Graphics image files (`rgb`), written by hand: no maintained Rust crate writes
//! them. Layout from Paul Haeberli's "The SGI Image File Format" (version 1.00): a 512-byte
//! big-endian header, then per channel and row (bottom row first) a run-length encoded
//! scanline, found through tables of start offsets and lengths.

use crate::pixels::{fits_u16, sample, u16s, u8s};
use crate::{Error, Format, ImageData, Sample};

/// The SGI magic number.
const MAGIC: u16 = 474;
/// Size of the header in bytes.
const HEADER: usize = 512;

/// Run-length encodes one scanline of one channel: packets whose low 7 bits count values
/// and whose bit 7 says "that many literal values follow" (set) or "repeat the next value"
/// (clear), ended by a zero count.
fn rle(row: &[u16]) -> Vec<u16> {
    let mut out = Vec::with_capacity(row.len() + row.len() / 64 + 2);
    let n = row.len();
    let mut i = 0;
    while i < n {
        let mut run = 1;
        while i + run < n && row[i + run] == row[i] && run < 127 {
            run += 1;
        }
        if run >= 3 {
            out.push(run as u16);
            out.push(row[i]);
            i += run;
            continue;
        }
        let start = i;
        while i < n && i - start < 127 {
            if i + 2 < n && row[i] == row[i + 1] && row[i + 1] == row[i + 2] {
                break;
            }
            i += 1;
        }
        out.push(0x80 | (i - start) as u16);
        out.extend_from_slice(&row[start..i]);
    }
    out.push(0);
    out
}

/// Encodes the main buffer of `image` (colour as RGB or RGBA, a scalar buffer as one grey
/// channel) as an RLE SGI file with 1 byte per channel ([`Sample::U8`]) or 2 ([`Sample::U16`]).
pub(crate) fn encode(format: Format, image: &ImageData) -> Result<Vec<u8>, Error> {
    let (xsize, ysize) = fits_u16(format, image)?;
    let wide = sample(format)? == Sample::U16;
    let (samples, zsize): (Vec<u16>, usize) = if wide {
        let px = u16s(format, image, true)?;
        (px.samples, px.channels)
    } else {
        let px = u8s(format, image, true)?;
        (px.samples.iter().map(|v| *v as u16).collect(), px.channels)
    };
    let (w, h) = (xsize as usize, ysize as usize);
    let max = samples.iter().copied().max().unwrap_or(0);
    let min = samples.iter().copied().min().unwrap_or(0);

    let mut out = vec![0u8; HEADER];
    out[0..2].copy_from_slice(&MAGIC.to_be_bytes());
    out[2] = 1; // storage: RLE
    out[3] = if wide { 2 } else { 1 };
    let dimension: u16 = if zsize == 1 { 2 } else { 3 };
    out[4..6].copy_from_slice(&dimension.to_be_bytes());
    out[6..8].copy_from_slice(&xsize.to_be_bytes());
    out[8..10].copy_from_slice(&ysize.to_be_bytes());
    out[10..12].copy_from_slice(&(zsize as u16).to_be_bytes());
    out[12..16].copy_from_slice(&(min as i32).to_be_bytes());
    out[16..20].copy_from_slice(&(max as i32).to_be_bytes());
    let name = b"mira";
    out[24..24 + name.len()].copy_from_slice(name);
    // colormap (104..108) 0: normal pixels.

    let rows = h * zsize;
    let table = out.len();
    out.resize(table + 8 * rows, 0);
    let mut row = vec![0u16; w];
    for c in 0..zsize {
        for y in 0..h {
            // File row y counts from the bottom; image rows from the top.
            let src = h - 1 - y;
            for (x, v) in row.iter_mut().enumerate() {
                *v = samples[(src * w + x) * zsize + c];
            }
            let packed = rle(&row);
            let start = out.len();
            if wide {
                out.extend(packed.iter().flat_map(|v| v.to_be_bytes()));
            } else {
                out.extend(packed.iter().map(|v| *v as u8));
            }
            let (start, len) = (start as u32, (out.len() - start) as u32);
            let k = y + c * h;
            out[table + 4 * k..table + 4 * k + 4].copy_from_slice(&start.to_be_bytes());
            out[table + 4 * (rows + k)..table + 4 * (rows + k) + 4].copy_from_slice(&len.to_be_bytes());
        }
    }
    if out.len() > u32::MAX as usize {
        return Err(Error::Size("an SGI file's offsets are 32-bit; the image is too large".into()));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::rle;

    /// Expands packets back (the inverse, for checking the encoder's packet boundaries).
    fn unrle(p: &[u16]) -> Vec<u16> {
        let mut out = Vec::new();
        let mut i = 0;
        loop {
            let c = p[i];
            i += 1;
            let n = (c & 0x7f) as usize;
            if n == 0 {
                return out;
            }
            if c & 0x80 != 0 {
                out.extend_from_slice(&p[i..i + n]);
                i += n;
            } else {
                out.extend(std::iter::repeat_n(p[i], n));
                i += 1;
            }
        }
    }

    #[test]
    fn packets_round_trip_runs_literals_and_long_rows() {
        let rows: Vec<Vec<u16>> = vec![
            vec![5],
            vec![1, 2],
            vec![7; 300],
            (0..300).map(|i| (i % 251) as u16).collect(),
            vec![1, 1, 2, 2, 2, 3, 4, 4, 4, 4, 5],
            (0..1000).map(|i| ((i / 5) % 3) as u16).collect(),
        ];
        for r in rows {
            let p = rle(&r);
            assert_eq!(unrle(&p), r);
        }
        // A run of 300 takes three packets of at most 127 (6 values + end marker).
        assert_eq!(rle(&[9; 300]).len(), 7);
    }
}
