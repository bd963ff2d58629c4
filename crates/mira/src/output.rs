//! Writing images: multi-channel linear EXR with every frame buffer (the motion buffer when
//! an output asks for it), and 8-bit PNG (or JPEG, TIFF) through the scene's tone mapper,
//! Radiance HDR linear.

use std::path::Path;

use exr::prelude::*;
use render::film::Film;
use render::tonemap::ToneMapper;
use shade::Rgb;

/// An image file format mira writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// OpenEXR, linear, all buffers.
    Exr,
    /// 8-bit PNG through the tone mapper.
    Png,
    /// 8-bit JPEG through the tone mapper.
    Jpeg,
    /// 8-bit TIFF through the tone mapper.
    Tiff,
    /// Radiance HDR, linear RGB.
    Hdr,
}

impl Format {
    /// From a file extension or a mental ray format name (`exr`, `png`, `jpg`, `tif`, `hdr`).
    pub fn from_name(name: &str) -> Option<Format> {
        Some(match name.to_ascii_lowercase().as_str() {
            "exr" => Format::Exr,
            "png" => Format::Png,
            "jpg" | "jpeg" => Format::Jpeg,
            "tif" | "tiff" => Format::Tiff,
            "hdr" | "pic" | "rgbe" => Format::Hdr,
            _ => return None,
        })
    }

    /// From a path's extension.
    pub fn from_path(path: &Path) -> Option<Format> {
        Format::from_name(path.extension()?.to_str()?)
    }
}

/// Buffers an output asks for beyond what every file of its format holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Extras {
    /// The motion buffer (`m`): raster-space motion vectors, written to EXR files as
    /// channels `M.X`, `M.Y`.
    pub motion: bool,
}

impl Extras {
    /// From an `output` statement's frame buffer types (`rgba`, `+m`, `-z`, …) or a
    /// `framebuffer`'s data type.
    pub fn from_types<S: AsRef<str>>(types: &[S]) -> Extras {
        Extras { motion: types.iter().any(|t| t.as_ref().trim().trim_start_matches(['+', '-']) == "m") }
    }

    /// Both sets of buffers.
    pub fn union(self, other: Extras) -> Extras {
        Extras { motion: self.motion || other.motion }
    }
}

/// Writes `film` to `path` in `format` with the buffers of `extras` (EXR only; other
/// formats hold the colour buffer alone).
pub fn write(
    film: &Film,
    path: &Path,
    format: Format,
    tone: &ToneMapper,
    extras: Extras,
) -> std::result::Result<(), String> {
    match format {
        Format::Exr => write_exr(film, path, extras),
        Format::Hdr => {
            let rgba = film.rgba();
            let img = image::Rgb32FImage::from_fn(film.width, film.height, |x, y| {
                let p = rgba[(y * film.width + x) as usize];
                image::Rgb([p[0], p[1], p[2]])
            });
            image::DynamicImage::ImageRgb32F(img).save(path).map_err(|e| e.to_string())
        }
        Format::Png | Format::Jpeg | Format::Tiff => {
            let rgba = film.rgba();
            let img = image::RgbaImage::from_fn(film.width, film.height, |x, y| {
                let p = rgba[(y * film.width + x) as usize];
                let c = tone.map_at(Rgb::new(p[0], p[1], p[2]), x, y, film.width, film.height);
                let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
                image::Rgba([q(c.x), q(c.y), q(c.z), q(p[3])])
            });
            if format == Format::Jpeg {
                image::DynamicImage::ImageRgba8(img).to_rgb8().save(path).map_err(|e| e.to_string())
            } else {
                img.save(path).map_err(|e| e.to_string())
            }
        }
    }
}

/// One EXR part with channels R, G, B, A (linear colour), Z (depth), N.X/N.Y/N.Z (normal),
/// tag (label, unsigned integer), `name.R/G/B/A` for each user frame buffer and, when
/// `extras` asks for it, M.X/M.Y (motion of each pixel's first hit over the shutter
/// interval in raster pixels, x right, y up as mental ray's raster space).
fn write_exr(film: &Film, path: &Path, extras: Extras) -> std::result::Result<(), String> {
    let (w, h) = (film.width as usize, film.height as usize);
    let rgba = film.rgba();
    let normals = film.normals();
    let channel = |name: &str, data: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(data));
    let mut user: Vec<AnyChannel<FlatSamples>> = Vec::new();
    for b in &film.user {
        for (k, c) in ["R", "G", "B", "A"].iter().enumerate() {
            user.push(channel(&format!("{}.{c}", b.name), b.data.iter().map(|p| p[k]).collect()));
        }
    }
    if extras.motion {
        let motion = film.motion();
        user.push(channel("M.X", motion.iter().map(|m| m[0]).collect()));
        user.push(channel("M.Y", motion.iter().map(|m| m[1]).collect()));
    }
    let channels = AnyChannels::sort(
        vec![
            channel("R", rgba.iter().map(|p| p[0]).collect()),
            channel("G", rgba.iter().map(|p| p[1]).collect()),
            channel("B", rgba.iter().map(|p| p[2]).collect()),
            channel("A", rgba.iter().map(|p| p[3]).collect()),
            channel("Z", film.depth()),
            channel("N.X", normals.iter().map(|n| n[0]).collect()),
            channel("N.Y", normals.iter().map(|n| n[1]).collect()),
            channel("N.Z", normals.iter().map(|n| n[2]).collect()),
            AnyChannel::new("tag", FlatSamples::U32(film.tags())),
        ]
        .into_iter()
        .chain(user)
        .collect(),
    );
    // Tiles in increasing order: the same image gives the same file, byte for byte (the
    // default order is whichever parallel compression finishes first).
    let encoding = Encoding { line_order: LineOrder::Increasing, ..Encoding::FAST_LOSSLESS };
    let layer = Layer::new((w, h), LayerAttributes::default(), encoding, channels);
    Image::from_layer(layer).write().to_file(path).map_err(|e| e.to_string())
}
