//! DirectDraw Surface (DDS) files as MDL's 3D and cube textures read them: the container
//! (header, legacy and DX10 pixel formats, volume depth, cube faces, array layers, mip
//! chains) is parsed by the `ddsfile` crate; the texels of the full-resolution level are
//! decoded here to RGBA `f32`, block-compressed formats (BC1–BC7, DXT1–DXT5) through
//! `bcdec_rs`. Values are used as stored (8- and 16-bit unsigned normalized values scaled
//! to [0, 1], no gamma, `_sRGB` formats included, as mira's other textures are read).
//!
//! Layout of [`DdsImage::layers`]: one vector per array layer (a cube map's six faces in
//! the file's order +x, −x, +y, −y, +z, −z), each holding the level's slices one after the
//! other (a volume's `depth` slices, else one), each slice's rows as stored (the file's
//! first row first, top to bottom of the picture), each row left to right.

use std::path::Path;

use ddsfile::{D3DFormat, Dds, DxgiFormat};
use glam::Vec4;

/// Largest side (texels) and largest number of texels in all layers mira reads from a DDS
/// file, so that a corrupt header cannot ask for terabytes.
const MAX_SIDE: u32 = 16384;
const MAX_TEXELS: u64 = 1 << 28;

/// The full-resolution level of a DDS file, decoded.
#[derive(Clone, Debug)]
pub struct DdsImage {
    /// Texels in x.
    pub width: usize,
    /// Texels in y.
    pub height: usize,
    /// Slices (1 unless a volume texture).
    pub depth: usize,
    /// Whether the file is a cube map (its layers are faces, six per cube).
    pub cube: bool,
    /// The decoded texels per layer (see the module's layout).
    pub layers: Vec<Vec<Vec4>>,
}

/// How one texel or block of a format is stored.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Encoding {
    /// Unsigned normalized bytes: texel size, then the byte offsets of R, G, B, A (`None`:
    /// G and B copy R for grey formats, A is 1 when absent).
    Bytes { size: usize, r: usize, g: Option<usize>, b: Option<usize>, a: Option<usize>, grey: bool },
    /// Little-endian numbers of `bits` (16: unsigned normalized, `half` when `float`; 32:
    /// `f32`), `n` channels R, G, B, A in order (one channel is grey).
    Numbers { bits: u8, float: bool, n: usize },
    /// A block-compressed format (4×4 texels a block).
    Block(Block),
}

/// The block-compressed formats.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Block {
    Bc1,
    Bc2,
    Bc3,
    Bc4,
    Bc5,
    Bc6h { signed: bool },
    Bc7,
}

impl Block {
    fn bytes(self) -> usize {
        match self {
            Block::Bc1 | Block::Bc4 => 8,
            _ => 16,
        }
    }
}

impl Encoding {
    /// Bytes of one level of `w` × `h` × `d` texels.
    fn level_bytes(self, w: u64, h: u64, d: u64) -> u64 {
        match self {
            Encoding::Bytes { size, .. } => w * h * d * size as u64,
            Encoding::Numbers { bits, n, .. } => w * h * d * u64::from(bits / 8) * n as u64,
            Encoding::Block(b) => w.div_ceil(4) * h.div_ceil(4) * d * b.bytes() as u64,
        }
    }
}

fn bytes(size: usize, r: usize, g: usize, b: usize, a: Option<usize>) -> Encoding {
    Encoding::Bytes { size, r, g: Some(g), b: Some(b), a, grey: false }
}

fn d3d_encoding(f: D3DFormat) -> Option<Encoding> {
    use D3DFormat as F;
    Some(match f {
        F::A8R8G8B8 => bytes(4, 2, 1, 0, Some(3)),
        F::X8R8G8B8 => bytes(4, 2, 1, 0, None),
        F::A8B8G8R8 => bytes(4, 0, 1, 2, Some(3)),
        F::X8B8G8R8 => bytes(4, 0, 1, 2, None),
        F::R8G8B8 => bytes(3, 2, 1, 0, None),
        F::L8 => Encoding::Bytes { size: 1, r: 0, g: None, b: None, a: None, grey: true },
        F::A8L8 => Encoding::Bytes { size: 2, r: 0, g: None, b: None, a: Some(1), grey: true },
        F::L16 => Encoding::Numbers { bits: 16, float: false, n: 1 },
        F::A16B16G16R16 => Encoding::Numbers { bits: 16, float: false, n: 4 },
        F::R16F => Encoding::Numbers { bits: 16, float: true, n: 1 },
        F::G16R16F => Encoding::Numbers { bits: 16, float: true, n: 2 },
        F::A16B16G16R16F => Encoding::Numbers { bits: 16, float: true, n: 4 },
        F::R32F => Encoding::Numbers { bits: 32, float: true, n: 1 },
        F::G32R32F => Encoding::Numbers { bits: 32, float: true, n: 2 },
        F::A32B32G32R32F => Encoding::Numbers { bits: 32, float: true, n: 4 },
        F::DXT1 => Encoding::Block(Block::Bc1),
        F::DXT2 | F::DXT3 => Encoding::Block(Block::Bc2),
        F::DXT4 | F::DXT5 => Encoding::Block(Block::Bc3),
        _ => return None,
    })
}

fn dxgi_encoding(f: DxgiFormat) -> Option<Encoding> {
    use DxgiFormat as F;
    Some(match f {
        F::R32G32B32A32_Float => Encoding::Numbers { bits: 32, float: true, n: 4 },
        F::R32G32B32_Float => Encoding::Numbers { bits: 32, float: true, n: 3 },
        F::R32G32_Float => Encoding::Numbers { bits: 32, float: true, n: 2 },
        F::R32_Float => Encoding::Numbers { bits: 32, float: true, n: 1 },
        F::R16G16B16A16_Float => Encoding::Numbers { bits: 16, float: true, n: 4 },
        F::R16G16_Float => Encoding::Numbers { bits: 16, float: true, n: 2 },
        F::R16_Float => Encoding::Numbers { bits: 16, float: true, n: 1 },
        F::R16G16B16A16_UNorm => Encoding::Numbers { bits: 16, float: false, n: 4 },
        F::R16G16_UNorm => Encoding::Numbers { bits: 16, float: false, n: 2 },
        F::R16_UNorm => Encoding::Numbers { bits: 16, float: false, n: 1 },
        F::R8G8B8A8_UNorm | F::R8G8B8A8_UNorm_sRGB => bytes(4, 0, 1, 2, Some(3)),
        F::B8G8R8A8_UNorm | F::B8G8R8A8_UNorm_sRGB => bytes(4, 2, 1, 0, Some(3)),
        F::B8G8R8X8_UNorm | F::B8G8R8X8_UNorm_sRGB => bytes(4, 2, 1, 0, None),
        F::R8G8_UNorm => Encoding::Bytes { size: 2, r: 0, g: Some(1), b: None, a: None, grey: false },
        F::R8_UNorm => Encoding::Bytes { size: 1, r: 0, g: None, b: None, a: None, grey: true },
        F::BC1_UNorm | F::BC1_UNorm_sRGB => Encoding::Block(Block::Bc1),
        F::BC2_UNorm | F::BC2_UNorm_sRGB => Encoding::Block(Block::Bc2),
        F::BC3_UNorm | F::BC3_UNorm_sRGB => Encoding::Block(Block::Bc3),
        F::BC4_UNorm => Encoding::Block(Block::Bc4),
        F::BC5_UNorm => Encoding::Block(Block::Bc5),
        F::BC6H_UF16 => Encoding::Block(Block::Bc6h { signed: false }),
        F::BC6H_SF16 => Encoding::Block(Block::Bc6h { signed: true }),
        F::BC7_UNorm | F::BC7_UNorm_sRGB => Encoding::Block(Block::Bc7),
        _ => return None,
    })
}

/// Reads the DDS file at `path`. `Err` says why it cannot be read (not a DDS file, a
/// format mira does not decode, sizes past its limits, data shorter than the header says).
pub fn read(path: &Path) -> Result<DdsImage, String> {
    let file = std::fs::read(path).map_err(|e| format!("cannot open: {e}"))?;
    parse(&file)
}

/// [`read`] of a file's bytes.
pub fn parse(file: &[u8]) -> Result<DdsImage, String> {
    let dds = Dds::read(file).map_err(|e| format!("not a DDS file mira reads: {e}"))?;
    let encoding = match (dds.get_dxgi_format(), dds.get_d3d_format()) {
        (Some(f), _) => dxgi_encoding(f).ok_or_else(|| format!("DDS format {f:?} is not decoded by mira"))?,
        (None, Some(f)) => d3d_encoding(f).ok_or_else(|| format!("DDS format {f:?} is not decoded by mira"))?,
        (None, None) => return Err("the DDS file's pixel format is not one mira knows".into()),
    };
    let (w, h, d) = (dds.get_width(), dds.get_height(), dds.get_depth().max(1));
    let layers = dds.get_num_array_layers().max(1);
    let levels = dds.get_num_mipmap_levels().clamp(1, 32);
    if w == 0 || h == 0 || w > MAX_SIDE || h > MAX_SIDE || d > MAX_SIDE || layers > 6 * 2048 {
        return Err(format!(
            "{w}×{h}×{d} texels in {layers} layers is outside what mira reads (1 to {MAX_SIDE} a side)"
        ));
    }
    let texels = u64::from(w) * u64::from(h) * u64::from(d) * u64::from(layers);
    if texels > MAX_TEXELS {
        return Err(format!("{texels} texels is more than mira reads from a DDS file ({MAX_TEXELS})"));
    }
    // Each layer holds its whole mip chain; only the first level is decoded.
    let (w, h, d) = (u64::from(w), u64::from(h), u64::from(d));
    let first = encoding.level_bytes(w, h, d);
    let stride: u64 =
        (0..levels).map(|l| encoding.level_bytes((w >> l).max(1), (h >> l).max(1), (d >> l).max(1))).sum();
    let need = stride * u64::from(layers - 1) + first;
    if (dds.data.len() as u64) < need {
        return Err(format!("the DDS file holds {} bytes of texels, its header needs {need}", dds.data.len()));
    }
    let (w, h, d) = (w as usize, h as usize, d as usize);
    let layers = (0..layers as usize)
        .map(|i| {
            let at = i * stride as usize;
            decode(&dds.data[at..at + first as usize], encoding, w, h, d)
        })
        .collect();
    Ok(DdsImage { width: w, height: h, depth: d, cube: is_cube(&dds), layers })
}

fn is_cube(dds: &Dds) -> bool {
    match &dds.header10 {
        Some(h10) => h10.misc_flag.contains(ddsfile::MiscFlag::TEXTURECUBE),
        None => dds.header.caps2.contains(ddsfile::Caps2::CUBEMAP),
    }
}

/// The `w` × `h` × `d` texels of one level stored in `data` (long enough).
fn decode(data: &[u8], encoding: Encoding, w: usize, h: usize, d: usize) -> Vec<Vec4> {
    let mut out = vec![Vec4::ZERO; w * h * d];
    match encoding {
        Encoding::Bytes { size, r, g, b, a, grey } => {
            for (texel, bytes) in out.iter_mut().zip(data.chunks_exact(size)) {
                let unorm = |i: usize| f32::from(bytes[i]) / 255.0;
                let red = unorm(r);
                let (green, blue) = if grey { (red, red) } else { (g.map_or(0.0, unorm), b.map_or(0.0, unorm)) };
                *texel = Vec4::new(red, green, blue, a.map_or(1.0, unorm));
            }
        }
        Encoding::Numbers { bits, float, n } => {
            let size = usize::from(bits / 8);
            for (texel, bytes) in out.iter_mut().zip(data.chunks_exact(size * n)) {
                let number = |i: usize| {
                    let b = &bytes[i * size..(i + 1) * size];
                    match (bits, float) {
                        (32, _) => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
                        (_, true) => half::f16::from_le_bytes([b[0], b[1]]).to_f32(),
                        _ => f32::from(u16::from_le_bytes([b[0], b[1]])) / 65535.0,
                    }
                };
                *texel = match n {
                    1 => Vec4::new(number(0), number(0), number(0), 1.0),
                    2 => Vec4::new(number(0), number(1), 0.0, 1.0),
                    3 => Vec4::new(number(0), number(1), number(2), 1.0),
                    _ => Vec4::new(number(0), number(1), number(2), number(3)),
                };
            }
        }
        Encoding::Block(block) => {
            let (bw, bh) = (w.div_ceil(4), h.div_ceil(4));
            let size = block.bytes();
            for (i, compressed) in data.chunks_exact(size).take(bw * bh * d).enumerate() {
                let (z, by, bx) = (i / (bw * bh), i / bw % bh, i % bw);
                let texels = decode_block(block, compressed);
                for (k, t) in texels.iter().enumerate() {
                    let (x, y) = (bx * 4 + k % 4, by * 4 + k / 4);
                    if x < w && y < h {
                        out[(z * h + y) * w + x] = *t;
                    }
                }
            }
        }
    }
    // NaN and infinite values (float formats) would reach the film through every lookup.
    for t in &mut out {
        if !t.is_finite() {
            *t = Vec4::select(t.is_finite_mask(), *t, Vec4::ZERO);
        }
    }
    out
}

/// The 16 texels of one compressed block, rows top to bottom.
fn decode_block(block: Block, compressed: &[u8]) -> [Vec4; 16] {
    let mut out = [Vec4::ZERO; 16];
    match block {
        Block::Bc6h { signed } => {
            let mut rgb = [0.0f32; 48];
            bcdec_rs::bc6h_float(compressed, &mut rgb, 12, signed);
            for (t, c) in out.iter_mut().zip(rgb.chunks_exact(3)) {
                *t = Vec4::new(c[0], c[1], c[2], 1.0);
            }
        }
        Block::Bc4 | Block::Bc5 => {
            let channels = if block == Block::Bc4 { 1 } else { 2 };
            let mut bytes = [0u8; 32];
            if channels == 1 {
                bcdec_rs::bc4(compressed, &mut bytes, 4, false);
            } else {
                bcdec_rs::bc5(compressed, &mut bytes, 8, false);
            }
            for (t, c) in out.iter_mut().zip(bytes.chunks_exact(channels)) {
                let r = f32::from(c[0]) / 255.0;
                *t = if channels == 1 {
                    Vec4::new(r, r, r, 1.0)
                } else {
                    Vec4::new(r, f32::from(c[1]) / 255.0, 0.0, 1.0)
                };
            }
        }
        _ => {
            let mut rgba = [0u8; 64];
            match block {
                Block::Bc1 => bcdec_rs::bc1(compressed, &mut rgba, 16),
                Block::Bc2 => bcdec_rs::bc2(compressed, &mut rgba, 16),
                Block::Bc3 => bcdec_rs::bc3(compressed, &mut rgba, 16),
                _ => bcdec_rs::bc7(compressed, &mut rgba, 16),
            }
            for (t, c) in out.iter_mut().zip(rgba.chunks_exact(4)) {
                *t = Vec4::new(f32::from(c[0]), f32::from(c[1]), f32::from(c[2]), f32::from(c[3])) / 255.0;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A DX10 file of `w` × `h` × `d` texels of `format` with `data` after the headers.
    fn dx10(w: u32, h: u32, d: u32, format: u32, data: &[u8]) -> Vec<u8> {
        let flags = 0x1 | 0x2 | 0x4 | 0x1000 | if d > 1 { 0x80_0000 } else { 0 };
        let mut words = vec![124, flags, h, w, 0, d, 1];
        words.extend([0; 11]);
        words.extend([32, 0x4, u32::from_le_bytes(*b"DX10"), 0, 0, 0, 0, 0]);
        words.extend([0x1000, if d > 1 { 0x20_0000 } else { 0 }, 0, 0, 0]);
        words.extend([format, if d > 1 { 4 } else { 3 }, 0, 1, 0]);
        let mut out = b"DDS ".to_vec();
        out.extend(words.iter().flat_map(|w| w.to_le_bytes()));
        out.extend_from_slice(data);
        out
    }

    /// BC1 with both end points pure red (R5G6B5 0xf800) is red in all 16 texels (the
    /// format's end points are 5:6:5 colours, 31 → 1.0); a 6 × 5 image of such blocks
    /// crops the edge blocks.
    #[test]
    fn block_compressed_texels_decode() {
        let block = [0x00, 0xf8, 0x00, 0xf8, 0, 0, 0, 0];
        let image = parse(&dx10(6, 5, 1, 71, &block.repeat(4))).unwrap();
        assert_eq!((image.width, image.height, image.layers[0].len()), (6, 5, 30));
        assert!(image.layers[0].iter().all(|t| *t == Vec4::new(1.0, 0.0, 0.0, 1.0)));
    }

    /// Truncated, corrupt and oversized files are errors, never a panic: every prefix of
    /// a valid file, every byte of its headers flipped, sizes past the limits.
    #[test]
    fn hostile_files_are_errors() {
        let texels: Vec<u8> = (0..8 * 16).map(|i| i as u8).collect();
        let good = dx10(2, 2, 2, 2, &texels);
        assert!(parse(&good).is_ok());
        for n in 0..good.len() {
            assert!(parse(&good[..n]).is_err(), "a file cut at {n} bytes");
        }
        for i in 0..148 {
            for bits in [0x01u8, 0x80, 0xff] {
                let mut bad = good.clone();
                bad[i] ^= bits;
                let _ = parse(&bad);
            }
        }
        assert!(parse(&dx10(1 << 20, 1 << 20, 1, 2, &texels)).is_err());
        assert!(parse(&dx10(16384, 16384, 16384, 71, &texels)).is_err());
        assert!(parse(b"not a dds file at all").is_err());
    }
}
