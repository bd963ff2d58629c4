//! Writing images: which files the scene's `output` and `framebuffer` statements (or `-o`)
//! ask for, and each one's pixels from the film, written by the `imageio` crate in every
//! format of mental ray's `output` statement. EXR files hold every frame buffer (the motion
//! buffer when an output asks for it); 8- and 16-bit colour files go through the scene's tone
//! mapper; float files, Radiance HDR and the data formats (`zt`, `nt`, `mt`, `tt`, `st`, …)
//! hold linear values.

use std::path::{Path, PathBuf};

use bsdf::Rgb;
use imageio::{Format, ImageData, Kind, Pixels};
use render::film::Film;
use render::tonemap::ToneMapper;
use scene::camera::{Camera, Output};

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
        Extras { motion: types.iter().any(|t| base_type(t.as_ref()) == "m") }
    }

    /// Both sets of buffers.
    pub fn union(self, other: Extras) -> Extras {
        Extras { motion: self.motion || other.motion }
    }
}

/// A frame buffer type without its `+`/`-` prefix and size suffix, lower case (`rgba_16` →
/// `rgba`).
fn base_type(t: &str) -> String {
    let t = t.trim().trim_start_matches(['+', '-']).to_ascii_lowercase();
    match t.split_once('_') {
        Some((b, "16" | "h" | "fp")) => b.to_string(),
        _ => t,
    }
}

/// Which frame buffer a file holds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Buffer {
    /// The colour buffer (RGBA), with every other buffer in EXR files.
    Color,
    /// Alpha as one channel (`a`).
    Alpha,
    /// Intensity as one channel (`s`): Rec. 709 luminance of the linear colour.
    Intensity,
    /// Depth (`z`).
    Depth,
    /// Normals (`n`).
    Normal,
    /// Motion vectors (`m`).
    Motion,
    /// Labels (`tag`).
    Tag,
    /// A user frame buffer by name.
    User(String),
}

impl Buffer {
    /// From a frame buffer type (`rgba`, `+z`, `a_16`, `fb0`, …); `None` for types mira has
    /// no buffer for (`coverage`, `bit`, `vta`, `vts`).
    fn from_type(t: &str) -> Option<Buffer> {
        Some(match base_type(t).as_str() {
            "" | "rgb" | "rgba" | "rgbe" => Buffer::Color,
            "a" => Buffer::Alpha,
            "s" => Buffer::Intensity,
            "z" => Buffer::Depth,
            "n" => Buffer::Normal,
            "m" => Buffer::Motion,
            "tag" => Buffer::Tag,
            "coverage" | "bit" | "vta" | "vts" => return None,
            _ => Buffer::User(t.trim().trim_start_matches(['+', '-']).to_string()),
        })
    }

    /// The buffer a data format holds when nothing names one (`-o x.zt`).
    fn for_kind(kind: Kind) -> Buffer {
        match kind {
            Kind::MentalDepth => Buffer::Depth,
            Kind::MentalNormal => Buffer::Normal,
            Kind::MentalMotion => Buffer::Motion,
            Kind::MentalTag => Buffer::Tag,
            Kind::MentalScalar | Kind::MentalBit => Buffer::Alpha,
            _ => Buffer::Color,
        }
    }
}

/// One file to write.
#[derive(Clone, Debug, PartialEq)]
pub struct Target {
    /// Where.
    pub path: PathBuf,
    /// In which format and variant.
    pub format: Format,
    /// Which buffer.
    pub buffer: Buffer,
    /// Buffers EXR files add.
    pub extras: Extras,
}

/// The formats `-o` understands, for its error message.
const EXTENSIONS: &str =
    ".exr, .png, .jpg, .tif, .hdr, .rgb/.sgi, .pic, .iff, .tga, .ppm, .bmp, .pix, .ct, .st, .zt, .nt, .mt, .tt, .bit";

/// The files to write: `-o`'s (format from its extension), else the camera's file outputs
/// and file frame buffers, else `SCENE.exr`. Outputs mira cannot write are warned about
/// (naming the file) and skipped.
pub fn targets(camera: &Camera, dash_o: Option<&Path>, scene: &Path) -> Result<Vec<Target>, String> {
    // Buffers beyond colour some output asks for (`-o` writes them too).
    let asked = camera
        .outputs
        .iter()
        .filter_map(|o| match o {
            Output::File { types, .. } => Some(Extras::from_types(types)),
            _ => None,
        })
        .chain(camera.framebuffers.iter().map(|fb| Extras::from_types(&[&fb.datatype])))
        .fold(Extras::default(), Extras::union);
    if let Some(o) = dash_o {
        return match Format::from_path(o) {
            Some(format) => {
                Ok(vec![Target { path: o.to_path_buf(), format, buffer: Buffer::for_kind(format.kind), extras: asked }])
            }
            None => Err(format!("cannot tell the image format of '{}' (use {EXTENSIONS})", o.display())),
        };
    }
    let mut targets = Vec::new();
    for out in &camera.outputs {
        if let Output::File { types, format, file } = out {
            let Some(kind) = Format::from_name(format) else {
                eprintln!("mira: warning: output format '{format}' of '{file}' is not supported; skipped");
                continue;
            };
            if !kind.kind.writable() {
                eprintln!("mira: warning: mira does not write '{format}' files ('{file}'); skipped");
                continue;
            }
            let first = types.first().map(String::as_str).unwrap_or("");
            let Some(buffer) = Buffer::from_type(first) else {
                eprintln!("mira: warning: mira has no '{first}' frame buffer to write to '{file}'; skipped");
                continue;
            };
            if kind.kind != Kind::Exr && types.len() > 1 {
                eprintln!(
                    "mira: warning: '{file}' holds one frame buffer ('{first}'); the others it lists ({}) are \
                     written only to EXR files",
                    types[1..].join(",")
                );
            }
            let format = kind.with_data_type(first);
            if !holds(format.kind, &buffer) {
                eprintln!(
                    "mira: warning: '{format_name}' files do not hold the '{first}' frame buffer ('{file}'); skipped",
                    format_name = format.kind
                );
                continue;
            }
            targets.push(Target { path: PathBuf::from(file), format, buffer, extras: Extras::from_types(types) });
        }
    }
    for fb in &camera.framebuffers {
        let Some(file) = &fb.filename else { continue };
        let Some(format) =
            fb.filetype.as_deref().and_then(Format::from_name).or_else(|| Format::from_path(Path::new(file)))
        else {
            eprintln!("mira: warning: cannot tell the file format of frame buffer '{}' ('{file}'); skipped", fb.name);
            continue;
        };
        if !format.kind.writable() {
            eprintln!("mira: warning: mira does not write '{}' files ('{file}'); skipped", format.kind);
            continue;
        }
        let buffer = match Buffer::from_type(&fb.datatype) {
            _ if fb.primary => Buffer::Color,
            Some(Buffer::Color) => Buffer::User(fb.name.clone()),
            Some(b) => b,
            None => {
                eprintln!("mira: warning: mira has no '{}' frame buffer to write to '{file}'; skipped", fb.datatype);
                continue;
            }
        };
        let format = format.with_data_type(&fb.datatype);
        if !holds(format.kind, &buffer) {
            eprintln!(
                "mira: warning: '{}' files do not hold the '{}' frame buffer '{}' ('{file}'); skipped",
                format.kind, fb.datatype, fb.name
            );
            continue;
        }
        targets.push(Target { path: PathBuf::from(file), format, buffer, extras: Extras::from_types(&[&fb.datatype]) });
    }
    if targets.is_empty() {
        targets.push(Target {
            path: scene.with_extension("exr"),
            format: Format::of(Kind::Exr),
            buffer: Buffer::Color,
            extras: asked,
        });
    }
    Ok(targets)
}

/// Whether files of `kind` hold `buffer`.
fn holds(kind: Kind, buffer: &Buffer) -> bool {
    kind.holds(match buffer {
        Buffer::Color | Buffer::User(_) => "rgba",
        Buffer::Alpha | Buffer::Intensity => "a",
        Buffer::Depth => "z",
        Buffer::Normal => "n",
        Buffer::Motion => "m",
        Buffer::Tag => "tag",
    })
}

/// Linear and display-referred (tone mapped by `tone`) colour of RGBA pixels.
fn colour(rgba: Vec<[f32; 4]>, film: &Film, tone: &ToneMapper) -> Pixels {
    let w = film.width.max(1);
    let display = rgba
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let (x, y) = (i as u32 % w, i as u32 / w);
            let c = tone.map_at(Rgb::new(p[0], p[1], p[2]), x, y, film.width, film.height);
            [c.x, c.y, c.z, p[3]]
        })
        .collect();
    Pixels::Color { linear: rgba, display }
}

/// The pixels `target` writes.
fn image(film: &Film, target: &Target, tone: &ToneMapper) -> Result<ImageData, String> {
    let pixels = match &target.buffer {
        Buffer::Color => colour(film.rgba(), film, tone),
        Buffer::Alpha => Pixels::Scalar(film.rgba().iter().map(|p| p[3]).collect()),
        Buffer::Intensity => {
            Pixels::Scalar(film.rgba().iter().map(|p| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]).collect())
        }
        Buffer::Depth => Pixels::Depth(film.depth()),
        Buffer::Normal => Pixels::Normal(film.normals()),
        Buffer::Motion => Pixels::Motion(film.motion()),
        Buffer::Tag => Pixels::Tag(film.tags()),
        Buffer::User(name) => match film.user.iter().find(|b| b.name == *name) {
            Some(b) => colour(b.data.clone(), film, tone),
            None => return Err(format!("the scene declares no frame buffer '{name}'")),
        },
    };
    let mut image = ImageData::new(film.width, film.height, pixels);
    if target.format.kind == Kind::Exr && target.buffer == Buffer::Color {
        image = image
            .with_layer("", Pixels::Depth(film.depth()))
            .with_layer("", Pixels::Normal(film.normals()))
            .with_layer("", Pixels::Tag(film.tags()));
        for b in &film.user {
            image = image.with_layer(&b.name, Pixels::Color { linear: b.data.clone(), display: b.data.clone() });
        }
        if target.extras.motion {
            image = image.with_layer("", Pixels::Motion(film.motion()));
        }
    }
    Ok(image)
}

/// Writes `target` from `film`; 8- and 16-bit colour through `tone`.
///
/// EXR files of the colour buffer hold channels R, G, B, A (linear colour), Z (depth),
/// N.X/N.Y/N.Z (normal), tag (label, unsigned integer), `name.R/G/B/A` for each user frame
/// buffer and, when `extras` asks for it, M.X/M.Y (motion of each pixel's first hit over the
/// shutter interval in raster pixels, x right, y up as mental ray's raster space).
pub fn write(film: &Film, target: &Target, tone: &ToneMapper) -> Result<(), String> {
    let image = image(film, target, tone)?;
    imageio::write(&target.path, target.format, &image).map_err(|e| e.to_string())
}

/// Writes `target`, an EXR of a `width` × `height` image, strip by strip: `next` renders
/// and returns each strip's kept rows as a film of their own ([`Film::rows`]), top to
/// bottom, and `None` after the last; each is written as it comes, so only one strip is in
/// memory. `layout` is a film with the image's user frame buffers (any height). The file is
/// the one [`write`] makes of the whole film.
pub fn write_strips(
    target: &Target,
    tone: &ToneMapper,
    (width, height): (u32, u32),
    layout: &Film,
    mut next: impl FnMut() -> Option<Film>,
) -> Result<(), String> {
    if target.format.kind != Kind::Exr {
        return Err(format!("'{}': an image rendered in strips is written only as OpenEXR", target.path.display()));
    }
    let layout = image(layout, target, tone)?;
    imageio::exr_strips::write_exr_strips(&target.path, target.format, width, height, &layout, |sink| {
        while let Some(strip) = next() {
            let data = image(&strip, target, tone).map_err(imageio::Error::Unsupported)?;
            sink.put(strip.y0, &data)?;
        }
        Ok(())
    })
    .map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buffer_types() {
        assert_eq!(Buffer::from_type("+rgba_16"), Some(Buffer::Color));
        assert_eq!(Buffer::from_type("-z"), Some(Buffer::Depth));
        assert_eq!(Buffer::from_type("a_fp"), Some(Buffer::Alpha));
        assert_eq!(Buffer::from_type("tag"), Some(Buffer::Tag));
        assert_eq!(Buffer::from_type("fb0"), Some(Buffer::User("fb0".into())));
        assert_eq!(Buffer::from_type("coverage"), None);
        assert!(Extras::from_types(&["+rgba", "m"]).motion);
        assert!(!Extras::from_types(&["rgba"]).motion);
    }
}
