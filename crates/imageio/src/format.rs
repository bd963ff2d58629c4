//! File formats of mental ray's `output` statement, by the name a `.mi` file gives them or by
//! a file's extension, and the data types (`rgba`, `rgb_16`, `rgba_fp`, `z`, …) that choose a
//! format's variant.

use std::fmt;
use std::path::Path;

/// A file format mental ray 3.x's `output` statement names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// Softimage `pic`: 8-bit RGB(A), run-length encoded.
    SoftimagePic,
    /// Softimage depth map `Zpic` (headerless big-endian floats, one per pixel; see
    /// `softimage::encode_zpic`).
    SoftimageZpic,
    /// Alias `pix` (`alias`): 8-bit RGB, run-length encoded.
    AliasPix,
    /// Silicon Graphics `rgb`: 8- or 16-bit RGB(A), run-length encoded.
    Sgi,
    /// JFIF JPEG: 8-bit RGB.
    Jpeg,
    /// PNG: 8- or 16-bit RGB(A) (or grey for scalar buffers).
    Png,
    /// OpenEXR: half or float channels; every buffer of an image under its channel names.
    Exr,
    /// TIFF: 8-, 16-bit or float RGB(A) (or grey).
    Tiff,
    /// Portable pixmap `ppm`: 8-bit RGB.
    Ppm,
    /// Truevision Targa `tga`: 8-bit RGB(A), uncompressed.
    Targa,
    /// Microsoft bitmap `bmp`: 8-bit RGB(A).
    Bmp,
    /// Radiance `hdr`: RGBE (shared exponent), linear.
    Hdr,
    /// Maya `iff`: 8- or 16-bit RGB(A), tiled.
    MayaIff,
    /// mental images colour `ct`: 8-, 16-bit, half or float RGBA.
    MentalColor,
    /// mental images scalar `st`: 8-, 16-bit or float, one channel.
    MentalScalar,
    /// mental images depth `zt`: float.
    MentalDepth,
    /// mental images normals `nt`: three floats.
    MentalNormal,
    /// mental images motion `mt`: three floats (raster x, y, and 0).
    MentalMotion,
    /// mental images tags `tt`: 32-bit labels.
    MentalTag,
    /// mental images bit map `bit`: one byte per pixel, 0 or 1.
    MentalBit,
    /// mental ray's memory-mapped texture `map` (not written: its layout is not published).
    MemoryMap,
    /// A format mental ray names that mira does not write (`rla`, `rlb`, `picture`, `qntpal`,
    /// `qntntsc`, `vt`, `wt`, `lwi`, `ps`, `eps`, `shmap`), with that name.
    Unwritten(&'static str),
}

/// The numeric type of a file's samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sample {
    /// 8-bit unsigned, display-referred (tone mapped) for colour.
    U8,
    /// 16-bit unsigned, display-referred (tone mapped) for colour.
    U16,
    /// 16-bit IEEE half float, linear.
    Half,
    /// 32-bit IEEE float, linear.
    F32,
}

/// What one `output` statement writes: the file format, its sample type, and whether colour
/// files carry alpha.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Format {
    /// The file format.
    pub kind: Kind,
    /// The sample type of colour and scalar channels.
    pub sample: Sample,
    /// Colour files hold an alpha channel.
    pub alpha: bool,
}

const UNWRITTEN: [&str; 12] =
    ["rla", "rlb", "picture", "catia", "qntpal", "qntntsc", "vt", "wt", "lwi", "ps", "eps", "shmap"];

impl Kind {
    /// From a format name as an `output` statement or a `framebuffer`'s `filetype` writes it
    /// (`pic`, `rgb`, `tif`, `ctfp`, `zt`, …), case-insensitive except `Zpic`.
    pub fn from_name(name: &str) -> Option<Kind> {
        if name == "Zpic" || name == "zpic" {
            return Some(Kind::SoftimageZpic);
        }
        let lower = name.to_ascii_lowercase();
        Some(match lower.as_str() {
            "pic" | "si" => Kind::SoftimagePic,
            "alias" | "pix" | "als" => Kind::AliasPix,
            "rgb" | "sgi" | "rgba" | "bw" | "int" | "inta" => Kind::Sgi,
            "jpg" | "jpeg" => Kind::Jpeg,
            "png" => Kind::Png,
            "exr" => Kind::Exr,
            "tif" | "tiff" | "tifu" | "tif3" | "tifu3" | "tif16" | "tifu16" | "tif16_3" | "tifu16_3" | "tiff16" => {
                Kind::Tiff
            }
            "ppm" => Kind::Ppm,
            "tga" | "targa" => Kind::Targa,
            "bmp" => Kind::Bmp,
            "hdr" | "rgbe" => Kind::Hdr,
            "iff" => Kind::MayaIff,
            "ct" | "ct16" | "ct_16" | "ctfp" | "ct_fp" | "cth" | "ct_h" => Kind::MentalColor,
            "st" | "st16" | "st_16" | "stfp" | "st_fp" => Kind::MentalScalar,
            "zt" => Kind::MentalDepth,
            "nt" => Kind::MentalNormal,
            "mt" => Kind::MentalMotion,
            "tt" => Kind::MentalTag,
            "bit" => Kind::MentalBit,
            "map" => Kind::MemoryMap,
            _ => return UNWRITTEN.iter().find(|u| **u == lower).map(|u| Kind::Unwritten(u)),
        })
    }

    /// The sample type a format name implies (`ct16`: 16-bit, `ctfp`: float, `cth`: half,
    /// `tif16`: 16-bit), else the format's default.
    fn name_sample(self, name: &str) -> Sample {
        let lower = name.to_ascii_lowercase();
        if lower.ends_with("fp") {
            Sample::F32
        } else if lower.ends_with('h') && lower.starts_with("ct") {
            Sample::Half
        } else if lower.contains("16") {
            Sample::U16
        } else {
            self.default_sample()
        }
    }

    /// The sample type written when the data type does not say.
    pub fn default_sample(self) -> Sample {
        match self {
            Kind::Exr
            | Kind::Hdr
            | Kind::MentalDepth
            | Kind::MentalNormal
            | Kind::MentalMotion
            | Kind::SoftimageZpic => Sample::F32,
            _ => Sample::U8,
        }
    }

    /// The sample types a file of this format can hold.
    pub fn samples(self) -> &'static [Sample] {
        match self {
            Kind::Sgi | Kind::Png | Kind::MayaIff => &[Sample::U8, Sample::U16],
            Kind::Tiff | Kind::MentalScalar => &[Sample::U8, Sample::U16, Sample::F32],
            Kind::MentalColor => &[Sample::U8, Sample::U16, Sample::Half, Sample::F32],
            Kind::Exr => &[Sample::Half, Sample::F32],
            Kind::Hdr | Kind::MentalDepth | Kind::MentalNormal | Kind::MentalMotion | Kind::SoftimageZpic => {
                &[Sample::F32]
            }
            Kind::MentalTag | Kind::MentalBit | Kind::MemoryMap | Kind::Unwritten(_) => &[],
            _ => &[Sample::U8],
        }
    }

    /// Whether colour files of this format carry alpha unless the data type says `rgb`.
    fn default_alpha(self) -> bool {
        !matches!(self, Kind::Jpeg | Kind::Ppm | Kind::Hdr | Kind::AliasPix)
    }

    /// Whether [`crate::write`] writes this format (all but `map` and [`Kind::Unwritten`]).
    pub fn writable(self) -> bool {
        !matches!(self, Kind::MemoryMap | Kind::Unwritten(_))
    }

    /// Whether files of this format hold a buffer of type `buffer` as [`crate::Pixels::type_name`]
    /// names it (`rgba`, `a`, `z`, `n`, `m`, `tag`): colour formats hold colour and scalars
    /// (as grey), EXR every buffer, the mental images data formats their own.
    pub fn holds(self, buffer: &str) -> bool {
        if !self.writable() {
            return false;
        }
        match self {
            Kind::Exr => true,
            Kind::MentalColor => buffer == "rgba",
            Kind::MentalScalar => buffer == "a",
            Kind::MentalDepth | Kind::SoftimageZpic => buffer == "z",
            Kind::MentalNormal => buffer == "n",
            Kind::MentalMotion => buffer == "m",
            Kind::MentalTag => buffer == "tag",
            Kind::MentalBit => buffer == "a" || buffer == "tag",
            _ => buffer == "rgba" || buffer == "a",
        }
    }

    /// The usual file extension.
    pub fn extension(self) -> &'static str {
        match self {
            Kind::SoftimagePic => "pic",
            Kind::SoftimageZpic => "zpic",
            Kind::AliasPix => "pix",
            Kind::Sgi => "rgb",
            Kind::Jpeg => "jpg",
            Kind::Png => "png",
            Kind::Exr => "exr",
            Kind::Tiff => "tif",
            Kind::Ppm => "ppm",
            Kind::Targa => "tga",
            Kind::Bmp => "bmp",
            Kind::Hdr => "hdr",
            Kind::MayaIff => "iff",
            Kind::MentalColor => "ct",
            Kind::MentalScalar => "st",
            Kind::MentalDepth => "zt",
            Kind::MentalNormal => "nt",
            Kind::MentalMotion => "mt",
            Kind::MentalTag => "tt",
            Kind::MentalBit => "bit",
            Kind::MemoryMap => "map",
            Kind::Unwritten(name) => name,
        }
    }
}

impl fmt::Display for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Kind::Unwritten(name) => name,
            Kind::SoftimageZpic => "Zpic",
            Kind::AliasPix => "alias",
            Kind::Sgi => "rgb",
            other => other.extension(),
        })
    }
}

impl Format {
    /// The default variant of a format.
    pub fn of(kind: Kind) -> Format {
        Format { kind, sample: kind.default_sample(), alpha: kind.default_alpha() }
    }

    /// From a format name as a `.mi` file writes it (`rgb`, `tif16`, `ctfp`, `exr`, …).
    pub fn from_name(name: &str) -> Option<Format> {
        let kind = Kind::from_name(name)?;
        Some(Format { sample: kind.name_sample(name), ..Format::of(kind) })
    }

    /// From a path's extension (`x.sgi`, `x.tif`, `x.zt`, …).
    pub fn from_path(path: &Path) -> Option<Format> {
        Format::from_name(path.extension()?.to_str()?)
    }

    /// This format with the sample type and alpha an `output` data type asks for (`rgb`,
    /// `rgba_16`, `rgb_h`, `rgba_fp`, `a_16`, …). A type without a size suffix (`rgba`, `z`,
    /// `n`, `m`, `tag`, `coverage`) keeps the sample type of the format name (`tif16`,
    /// `ctfp`, else the format's default); a size the format cannot hold becomes the deepest
    /// one it can that is not deeper (`rgba_fp` into `rgb` files: 16-bit).
    pub fn with_data_type(self, data_type: &str) -> Format {
        let t = data_type.trim().trim_start_matches(['+', '-']).to_ascii_lowercase();
        let (base, suffix) = t.split_once('_').unwrap_or((t.as_str(), ""));
        let sample = match suffix {
            "16" => Some(Sample::U16),
            "h" => Some(Sample::Half),
            "fp" => Some(Sample::F32),
            _ => None,
        };
        let mut out = self;
        if let Some(s) = sample {
            if self.kind.samples().contains(&s) {
                out.sample = s;
            } else if let Some(&best) = self.kind.samples().iter().rev().find(|c| **c <= s) {
                out.sample = best;
            }
        }
        match base {
            "rgb" => out.alpha = false,
            "rgba" => out.alpha = self.kind.default_alpha(),
            _ => {}
        }
        out
    }
}

impl PartialOrd for Sample {
    fn partial_cmp(&self, other: &Sample) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Sample {
    fn cmp(&self, other: &Sample) -> std::cmp::Ordering {
        let rank = |s: &Sample| match s {
            Sample::U8 => 0,
            Sample::U16 => 1,
            Sample::Half => 2,
            Sample::F32 => 3,
        };
        rank(self).cmp(&rank(other))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_extensions() {
        assert_eq!(Format::from_name("rgb").unwrap().kind, Kind::Sgi);
        assert_eq!(Format::from_path(Path::new("square.sgi")).unwrap().kind, Kind::Sgi);
        assert_eq!(Format::from_name("Zpic").unwrap().kind, Kind::SoftimageZpic);
        assert_eq!(Format::from_name("pic").unwrap().kind, Kind::SoftimagePic);
        assert_eq!(Format::from_name("ctfp").unwrap().sample, Sample::F32);
        assert_eq!(Format::from_name("ct16").unwrap().sample, Sample::U16);
        assert_eq!(Format::from_name("cth").unwrap().sample, Sample::Half);
        assert_eq!(Format::from_name("tif16").unwrap().sample, Sample::U16);
        assert_eq!(Format::from_name("qntpal").unwrap().kind, Kind::Unwritten("qntpal"));
        assert_eq!(Format::from_name("exr").unwrap().sample, Sample::F32);
        assert!(Format::from_name("xyz").is_none());
        assert!(!Format::from_name("jpg").unwrap().alpha);
    }

    #[test]
    fn data_types_choose_variants() {
        let sgi = Format::from_name("rgb").unwrap();
        assert_eq!(sgi.with_data_type("rgb_16"), Format { kind: Kind::Sgi, sample: Sample::U16, alpha: false });
        assert_eq!(sgi.with_data_type("+rgba"), Format { kind: Kind::Sgi, sample: Sample::U8, alpha: true });
        let exr = Format::from_name("exr").unwrap();
        assert_eq!(exr.with_data_type("rgba_h").sample, Sample::Half);
        assert_eq!(exr.with_data_type("rgba").sample, Sample::F32);
        // A float request to an 8/16-bit format takes its deepest integer type.
        assert_eq!(sgi.with_data_type("rgba_fp").sample, Sample::U16);
        let tif = Format::from_name("tif").unwrap();
        assert_eq!(tif.with_data_type("rgba_fp").sample, Sample::F32);
        assert_eq!(tif.with_data_type("z"), tif);
    }
}
