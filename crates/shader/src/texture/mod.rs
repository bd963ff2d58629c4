//! Textures: image files (PNG, JPEG, TIFF, Radiance HDR, OpenEXR, Targa, BMP) and inline
//! pixels as filtered image pyramids, and procedural textures (texture shaders).
//!
//! Pixel values are used as stored (8-bit values scaled to [0, 1]); mental ray applied no
//! gamma to textures unless a colour profile said so.

pub mod mipmap;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{Vec3A, Vec4};
use mi::ast::{self, TextureKind, TextureSource};

use crate::graph::NodeId;
pub use mipmap::MipMap;

/// Largest texture mira loads (texels on a side).
pub const MAX_TEXTURE_SIDE: u32 = 32768;

/// A texture the shaders look up.
#[derive(Clone, Debug)]
pub enum Texture {
    /// An image.
    Image {
        /// The pyramid.
        image: Arc<MipMap>,
        /// `filter s`: pyramid filtering with the footprint scaled by `s`; `None`: bilinear
        /// lookups of the full image.
        filter: Option<f32>,
        /// Colour, scalar or vector.
        kind: TextureKind,
    },
    /// A procedural texture: the shader computes the value.
    Shader(NodeId),
    /// A texture whose image could not be read (lookups fail).
    Missing,
}

impl Texture {
    /// The value at texture coordinate `coord` (its x and y; [0, 1)² covers the image once)
    /// for a footprint `width` in texture units. `None` outside [0, 1)² (mental ray's
    /// lookups fail there) or for missing images. Shader textures are run by the context.
    pub fn lookup(&self, coord: Vec3A, width: f32) -> Option<Vec4> {
        let Texture::Image { image, filter, .. } = self else { return None };
        let (u, v) = (coord.x, coord.y);
        if !(0.0..1.0).contains(&u) || !(0.0..1.0).contains(&v) {
            return None;
        }
        let width = filter.map_or(0.0, |s| width * s.max(0.0));
        let mut c = image.lookup(u, v, width);
        if image.channels < 3 {
            // Grey (and alpha) images: the grey value in all three colour channels.
            let a = if image.channels == 2 { c.y } else { 1.0 };
            c = Vec4::new(c.x, c.x, c.x, a);
        }
        Some(c)
    }
}

/// Where texture files are looked for: the directory of the scene file, then the include
/// directories, then the current directory.
#[derive(Clone, Debug, Default)]
pub struct SearchPath {
    /// Directories in order.
    pub dirs: Vec<PathBuf>,
}

impl SearchPath {
    /// The first existing file `name` resolves to. Windows paths (backslashes, drive
    /// letters) are tried as written, then by their file name alone in each directory.
    pub fn resolve(&self, name: &str) -> Option<PathBuf> {
        let unix = name.replace('\\', "/");
        let path = Path::new(&unix);
        if path.is_absolute() && path.is_file() {
            return Some(path.to_path_buf());
        }
        let mut candidates: Vec<PathBuf> = self.dirs.iter().map(|d| d.join(path)).collect();
        candidates.push(path.to_path_buf());
        if let Some(file) = path.file_name() {
            candidates.extend(self.dirs.iter().map(|d| d.join(file)));
        }
        candidates.into_iter().find(|p| p.is_file())
    }
}

/// An image file read into a pyramid.
pub struct LoadedImage {
    /// The pyramid.
    pub image: MipMap,
    /// Texel components of the file that were NaN or infinite, read as 0 (they would
    /// otherwise reach the film through every lookup that touches them).
    pub non_finite: usize,
}

/// Reads an image file into a pyramid; NaN and infinite texel components are read as 0
/// and counted ([`LoadedImage::non_finite`]).
pub fn load_image(path: &Path) -> Result<LoadedImage, String> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if ext == "map" {
        return Err("mental ray .map files cannot be read; convert the texture to EXR or TIFF".into());
    }
    let reader = image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .map_err(|e| format!("cannot open: {e}"))?;
    let (w, h) = reader.into_dimensions().map_err(|e| format!("cannot read: {e}"))?;
    if w == 0 || h == 0 || w > MAX_TEXTURE_SIDE || h > MAX_TEXTURE_SIDE {
        return Err(format!("{w}×{h} texels is outside what mira loads (1 to {MAX_TEXTURE_SIDE} a side)"));
    }
    let img = image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .map_err(|e| format!("cannot open: {e}"))?
        .decode()
        .map_err(|e| format!("cannot read: {e}"))?;
    let channels = img.color().channel_count();
    let (w, h) = (img.width() as usize, img.height() as usize);
    let mut non_finite = 0;
    let image = match img {
        image::DynamicImage::ImageLuma8(_)
        | image::DynamicImage::ImageLumaA8(_)
        | image::DynamicImage::ImageRgb8(_)
        | image::DynamicImage::ImageRgba8(_) => {
            let rgba = img.to_rgba8();
            let texels: Vec<[u8; 4]> = rgba.pixels().map(|p| p.0).collect();
            MipMap::from_rgba8(w, h, &texels, channels)
        }
        _ => {
            let rgba = img.to_rgba32f();
            let texels: Vec<[f32; 4]> = rgba
                .pixels()
                .map(|p| {
                    p.0.map(|v| {
                        if v.is_finite() {
                            v
                        } else {
                            non_finite += 1;
                            0.0
                        }
                    })
                })
                .collect();
            MipMap::from_rgba32f(w, h, &texels, channels)
        }
    };
    Ok(LoadedImage { image, non_finite })
}

/// Builds a pyramid from a texture's inline pixels: `[ w h [bytes per component] ]` and
/// the bytes, rows from the bottom up, components interleaved (1, 2, 3 or 4 per texel,
/// whichever the byte count implies).
pub fn inline_pixels(dims: &[i64], bytes: &[u8]) -> Result<MipMap, String> {
    let (w, h) = match dims {
        [w, h, ..] if *w > 0 && *h > 0 && *w <= i64::from(MAX_TEXTURE_SIDE) && *h <= i64::from(MAX_TEXTURE_SIDE) => {
            (*w as usize, *h as usize)
        }
        _ => return Err("inline texture needs a width and height between 1 and 32768".into()),
    };
    let depth = dims.get(2).copied().unwrap_or(1).clamp(1, 4) as usize;
    let per_texel = bytes.len() / (w * h * depth);
    if !(1..=4).contains(&per_texel) {
        return Err(format!("{} bytes do not fill {w}×{h} texels", bytes.len()));
    }
    let max = ((1u64 << (8 * depth)) - 1) as f32;
    let component = |i: usize| -> f32 {
        let mut v = 0u64;
        for b in &bytes[i * depth..(i + 1) * depth] {
            v = (v << 8) | u64::from(*b);
        }
        v as f32 / max
    };
    let mut texels = Vec::with_capacity(w * h);
    for t in 0..w * h {
        let c: Vec<f32> = (0..per_texel).map(|k| component(t * per_texel + k)).collect();
        texels.push(match per_texel {
            1 => [c[0], c[0], c[0], 1.0],
            2 => [c[0], c[0], c[0], c[1]],
            3 => [c[0], c[1], c[2], 1.0],
            _ => [c[0], c[1], c[2], c[3]],
        });
    }
    // Stored bottom-up already: flip so that from_rgba32f (which expects top-down) keeps it.
    let top_down: Vec<[f32; 4]> = (0..h).rev().flat_map(|r| texels[r * w..(r + 1) * w].iter().copied()).collect();
    Ok(MipMap::from_rgba32f(w, h, &top_down, per_texel as u8))
}

/// The `filter` scale of a texture's flags (`filter` alone: 1).
pub fn filter_flag(t: &ast::Texture) -> Option<f32> {
    t.flags.iter().find(|k| k.key == "filter").map(|k| match k.args.first() {
        Some(ast::Arg::Float(f)) => *f as f32,
        Some(ast::Arg::Int(i)) => *i as f32,
        _ => 1.0,
    })
}

/// Whether a texture is an image file (rather than inline pixels or a shader).
pub fn file_name(t: &ast::Texture) -> Option<&str> {
    match &t.source {
        TextureSource::File { file, .. } => Some(&file.text),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inline_pixels_are_bottom_up() {
        // 1×2 grey: bottom 0, top 255.
        let m = inline_pixels(&[1, 2], &[0, 255]).unwrap();
        let t = Texture::Image { image: Arc::new(m), filter: None, kind: TextureKind::Color };
        assert_eq!(t.lookup(Vec3A::new(0.5, 0.25, 0.0), 0.0).unwrap().x, 0.0);
        assert_eq!(t.lookup(Vec3A::new(0.5, 0.75, 0.0), 0.0).unwrap().x, 1.0);
        assert!(t.lookup(Vec3A::new(1.0, 0.5, 0.0), 0.0).is_none());
        assert!(t.lookup(Vec3A::new(-0.1, 0.5, 0.0), 0.0).is_none());
    }

    #[test]
    fn sixteen_bit_inline_pixels() {
        let m = inline_pixels(&[1, 1, 2], &[0x80, 0x00, 0xff, 0xff, 0x00, 0x00]).unwrap();
        let c = m.texel(0, 0);
        assert!((c.x - 0x8000 as f32 / 65535.0).abs() < 1e-6 && c.y == 1.0 && c.z == 0.0);
    }

    #[test]
    fn files_round_trip_through_png_and_exr() {
        let dir = std::env::temp_dir().join(format!("mira-tex-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut img = image::RgbImage::new(4, 2);
        img.put_pixel(0, 0, image::Rgb([255, 0, 0])); // top left
        img.put_pixel(0, 1, image::Rgb([0, 0, 255])); // bottom left
        let png = dir.join("t.png");
        img.save(&png).unwrap();
        let m = load_image(&png).unwrap().image;
        assert_eq!(m.size(), (4, 2));
        assert_eq!(m.texel(0, 0), Vec4::new(0.0, 0.0, 1.0, 1.0), "row 0 is the bottom");
        assert_eq!(m.texel(0, 1), Vec4::new(1.0, 0.0, 0.0, 1.0));
        let mut hdr = image::Rgb32FImage::new(1, 1);
        hdr.put_pixel(0, 0, image::Rgb([4.5, 0.25, 1e3]));
        let exr = dir.join("t.exr");
        hdr.save(&exr).unwrap();
        let m = load_image(&exr).unwrap().image;
        assert_eq!(m.texel(0, 0).truncate(), glam::Vec3::new(4.5, 0.25, 1e3));
        // NaN and infinities (issue 15) are read as 0 and counted.
        let mut bad = image::Rgb32FImage::new(2, 1);
        bad.put_pixel(0, 0, image::Rgb([f32::NAN, f32::INFINITY, 0.5]));
        bad.put_pixel(1, 0, image::Rgb([f32::NEG_INFINITY, 2.0, 0.25]));
        let exr = dir.join("nan.exr");
        bad.save(&exr).unwrap();
        let loaded = load_image(&exr).unwrap();
        assert_eq!(loaded.non_finite, 3);
        assert_eq!(loaded.image.texel(0, 0).truncate(), glam::Vec3::new(0.0, 0.0, 0.5));
        assert_eq!(loaded.image.texel(1, 0).truncate(), glam::Vec3::new(0.0, 2.0, 0.25));
        for level_texel in [loaded.image.lookup(0.5, 0.5, 1.0), loaded.image.lookup(0.3, 0.5, 0.0)] {
            assert!(level_texel.is_finite(), "{level_texel}");
        }
        let search = SearchPath { dirs: vec![dir.clone()] };
        assert_eq!(search.resolve("C:\\maps\\t.png"), Some(png));
        std::fs::remove_dir_all(&dir).ok();
    }
}
