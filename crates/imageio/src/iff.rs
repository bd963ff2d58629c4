//! Maya `iff` files, written by hand: no maintained Rust crate writes them. Layout (IFF-85
//! chunks, 4-byte aligned, big-endian): `FOR4 size CIMG`, a 32-byte `TBHD` header (width,
//! height, pixel aspect numerator and denominator, flags 1 RGB + 2 alpha, bytes per channel
//! − 1, tile count, compression, x and y origin), then `FOR4 size TBMP` holding one `RGBA`
//! chunk per 64 × 64 tile: the tile's corners (x0, y0, x1, y1 with y counted from the
//! bottom) and its pixels, rows bottom first, channels in reverse order (A B G R). 8-bit
//! tiles are run-length encoded per channel (a byte whose bit 7 says "repeat the next byte"
//! (set) or "copy the next bytes" (clear) and whose low 7 bits are the count − 1), or stored
//! plain where that is no smaller; 16-bit tiles are stored plain.

use crate::pixels::{fits_u16, sample, u16s, u8s};
use crate::{Error, Format, ImageData, Sample};

/// Tile side of Maya IFF files.
const TILE: usize = 64;

/// Run-length encodes one channel of a tile for Maya IFF.
fn iff_rle(data: &[u8], out: &mut Vec<u8>) {
    let n = data.len();
    let mut i = 0;
    while i < n {
        let mut run = 1;
        while i + run < n && data[i + run] == data[i] && run < 128 {
            run += 1;
        }
        if run >= 2 {
            out.push(0x80 | (run - 1) as u8);
            out.push(data[i]);
            i += run;
            continue;
        }
        let start = i;
        while i < n && i - start < 128 {
            if i + 1 < n && data[i] == data[i + 1] {
                break;
            }
            i += 1;
        }
        out.push((i - start - 1) as u8);
        out.extend_from_slice(&data[start..i]);
    }
}

fn chunk(out: &mut Vec<u8>, id: &[u8; 4], body: &[u8]) {
    out.extend_from_slice(id);
    out.extend_from_slice(&(body.len() as u32).to_be_bytes());
    out.extend_from_slice(body);
    while out.len() % 4 != 0 {
        out.push(0);
    }
}

/// Encodes the main buffer of `image` as a Maya IFF file, 8- or 16-bit RGB(A).
pub(crate) fn encode(format: Format, image: &ImageData) -> Result<Vec<u8>, Error> {
    let (w16, h16) = fits_u16(format, image)?;
    let wide = sample(format)? == Sample::U16;
    let (samples, c): (Vec<u16>, usize) = if wide {
        let px = u16s(format, image, false)?;
        (px.samples, px.channels)
    } else {
        let px = u8s(format, image, false)?;
        (px.samples.iter().map(|v| *v as u16).collect(), px.channels)
    };
    let (w, h) = (w16 as usize, h16 as usize);
    let (tx, ty) = (w.div_ceil(TILE), h.div_ceil(TILE));
    let tiles = u16::try_from(tx * ty)
        .map_err(|_| Error::Size(format!("a Maya IFF file holds at most 65535 tiles; {w} × {h} needs {}", tx * ty)))?;
    let mut header = Vec::with_capacity(32);
    header.extend_from_slice(&(w as u32).to_be_bytes());
    header.extend_from_slice(&(h as u32).to_be_bytes());
    header.extend_from_slice(&1u16.to_be_bytes());
    header.extend_from_slice(&1u16.to_be_bytes());
    header.extend_from_slice(&(if c == 4 { 3u32 } else { 1u32 }).to_be_bytes());
    header.extend_from_slice(&u16::from(wide).to_be_bytes());
    header.extend_from_slice(&tiles.to_be_bytes());
    header.extend_from_slice(&(if wide { 0u32 } else { 1u32 }).to_be_bytes());
    header.extend_from_slice(&[0; 8]);

    let mut tbmp = b"TBMP".to_vec();
    for j in 0..ty {
        for i in 0..tx {
            let (x0, y0) = (i * TILE, j * TILE);
            let (x1, y1) = ((x0 + TILE).min(w) - 1, (y0 + TILE).min(h) - 1);
            let mut body = Vec::new();
            for v in [x0, y0, x1, y1] {
                body.extend_from_slice(&(v as u16).to_be_bytes());
            }
            // Sample of channel k at tile pixel (x, y from the bottom).
            let at = |x: usize, y: usize, k: usize| samples[((h - 1 - y) * w + x) * c + k];
            let mut plain = Vec::new();
            for y in y0..=y1 {
                for x in x0..=x1 {
                    for k in (0..c).rev() {
                        if wide {
                            plain.extend_from_slice(&at(x, y, k).to_be_bytes());
                        } else {
                            plain.push(at(x, y, k) as u8);
                        }
                    }
                }
            }
            if wide {
                body.extend_from_slice(&plain);
            } else {
                let mut packed = Vec::new();
                for k in (0..c).rev() {
                    let channel: Vec<u8> = (y0..=y1)
                        .flat_map(|y| (x0..=x1).map(move |x| (x, y)))
                        .map(|(x, y)| at(x, y, k) as u8)
                        .collect();
                    iff_rle(&channel, &mut packed);
                }
                body.extend_from_slice(if packed.len() < plain.len() { &packed } else { &plain });
            }
            chunk(&mut tbmp, b"RGBA", &body);
        }
    }
    let mut cimg = b"CIMG".to_vec();
    chunk(&mut cimg, b"TBHD", &header);
    chunk(&mut cimg, b"FOR4", &tbmp);
    let mut out = Vec::with_capacity(cimg.len() + 8);
    chunk(&mut out, b"FOR4", &cimg);
    if out.len() > u32::MAX as usize {
        return Err(Error::Size("a Maya IFF file's chunk sizes are 32-bit; the image is too large".into()));
    }
    Ok(out)
}
