//! Partial EXR files: one part of an image rendered by `mira render --part K/N`, read back
//! by `mira merge`.
//!
//! A part file is an OpenEXR image of the rows the part owns (in order, see
//! [`render::part::Split`]), with the final frame buffers of those pixels — `R G B A`
//! (linear colour), `Z`, `N.X N.Y N.Z`, `tag`, `M.X M.Y` (motion), `name.R/G/B/A` per user
//! frame buffer — and `samples` (samples taken per pixel). Colour is stored as the f32 the
//! one-process render writes, so merging copies pixels and is exact. The header's `mira.*`
//! text attributes say what merging checks: the scene (path and a hash of its text), the
//! files it reads (textures, light profiles, MDL modules: a second hash), the settings (a
//! hash and the readable list), the part, the split, the frame, the engine, the
//! sample counts, the part's weight (its share of the rows) and whether it was cut short
//! (`mira.partial`).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use exr::prelude::*;
use render::film::Film;
use render::part::{Part, Split};

/// Version of the part file layout.
const LAYOUT: &str = "2";

/// What a part file's header records.
#[derive(Clone, Debug, PartialEq)]
pub struct PartInfo {
    /// The scene file (absolute).
    pub scene: PathBuf,
    /// `$include` directories the scene was read with.
    pub include: Vec<PathBuf>,
    /// Hash of the scene's text (all its files).
    pub scene_hash: u64,
    /// Hash of the files the scene reads besides its text: textures, light profiles, MDL
    /// modules ([`render::pipeline::inputs_hash`]).
    pub inputs_hash: u64,
    /// The settings, one `key=value` per line.
    pub settings: String,
    /// Hash of `settings`.
    pub settings_hash: u64,
    /// Which part.
    pub part: Part,
    /// How the image was cut.
    pub split: Split,
    /// The `render` statement (1 = the first).
    pub frame: usize,
    /// Whether the classic engine rendered (tone mapping of 8-bit outputs depends on it).
    pub classic: bool,
    /// Full image width and height in pixels.
    pub size: (u32, u32),
    /// Samples per pixel the part's passes reached.
    pub spp: u32,
    /// Samples the part took over its own pixels.
    pub samples: u64,
    /// The part's share of the image: its rows over all rows.
    pub weight: f64,
    /// Whether the render was stopped before it finished (SIGINT, SIGTERM).
    pub partial: bool,
    /// User frame buffers: name and data type, in order.
    pub user: Vec<(String, String)>,
}

impl PartInfo {
    fn attributes(&self) -> Vec<(&'static str, String)> {
        let lines = |v: &[PathBuf]| v.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join("\n");
        vec![
            ("mira.layout", LAYOUT.to_string()),
            ("mira.scene", self.scene.display().to_string()),
            ("mira.include", lines(&self.include)),
            ("mira.scenehash", format!("{:016x}", self.scene_hash)),
            ("mira.inputshash", format!("{:016x}", self.inputs_hash)),
            ("mira.settings", self.settings.clone()),
            ("mira.settingshash", format!("{:016x}", self.settings_hash)),
            ("mira.part", self.part.to_string()),
            ("mira.split", self.split.name().to_string()),
            ("mira.frame", self.frame.to_string()),
            ("mira.engine", if self.classic { "classic" } else { "path" }.to_string()),
            ("mira.size", format!("{}x{}", self.size.0, self.size.1)),
            ("mira.spp", self.spp.to_string()),
            ("mira.samples", self.samples.to_string()),
            ("mira.weight", format!("{:.17}", self.weight)),
            ("mira.partial", u8::from(self.partial).to_string()),
            ("mira.user", self.user.iter().map(|(n, t)| format!("{n}\t{t}")).collect::<Vec<_>>().join("\n")),
        ]
    }

    fn from_attributes(a: &HashMap<String, String>) -> std::result::Result<PartInfo, String> {
        let get = |k: &str| a.get(k).cloned().ok_or_else(|| format!("no {k} in its header: not a mira part file"));
        let num = |k: &str| -> std::result::Result<u64, String> {
            get(k)?.parse().map_err(|_| format!("its header's {k} is not a number"))
        };
        let hex = |k: &str| -> std::result::Result<u64, String> {
            u64::from_str_radix(&get(k)?, 16).map_err(|_| format!("its header's {k} is not a hash"))
        };
        if get("mira.layout")? != LAYOUT {
            return Err("it was written by another version of mira's part layout".into());
        }
        let size = get("mira.size")?;
        let (w, h) = size
            .split_once('x')
            .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
            .ok_or("its header's mira.size is not W x H")?;
        let split = get("mira.split")?;
        Ok(PartInfo {
            scene: PathBuf::from(get("mira.scene")?),
            include: get("mira.include")?.lines().filter(|l| !l.is_empty()).map(PathBuf::from).collect(),
            scene_hash: hex("mira.scenehash")?,
            inputs_hash: hex("mira.inputshash")?,
            settings: get("mira.settings")?,
            settings_hash: hex("mira.settingshash")?,
            part: Part::parse(&get("mira.part")?)?,
            split: Split::from_name(&split).ok_or_else(|| format!("unknown split '{split}'"))?,
            frame: num("mira.frame")? as usize,
            classic: get("mira.engine")? == "classic",
            size: (w, h),
            spp: num("mira.spp")? as u32,
            samples: num("mira.samples")?,
            weight: get("mira.weight")?.parse().map_err(|_| "its header's mira.weight is not a number")?,
            partial: get("mira.partial")? == "1",
            user: get("mira.user")?
                .lines()
                .filter_map(|l| l.split_once('\t'))
                .map(|(n, t)| (n.to_string(), t.to_string()))
                .collect(),
        })
    }
}

/// Writes the rows of `film` that `info.part` owns to `path`.
pub fn write(film: &Film, info: &PartInfo, path: &Path) -> std::result::Result<(), String> {
    let rows = info.split.owned_rows(info.part, film.height);
    if rows.is_empty() {
        return Err(format!("part {} owns no rows of a {}-row image", info.part, film.height));
    }
    let w = film.width as usize;
    let index = |f: &dyn Fn(usize) -> f32| -> Vec<f32> {
        rows.iter().flat_map(|&y| (0..w).map(move |x| y as usize * w + x)).map(f).collect()
    };
    let pixels: Vec<usize> = rows.iter().flat_map(|&y| (0..w).map(move |x| y as usize * w + x)).collect();
    let rgba = film.rgba();
    let f32s = |name: &str, data: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(data));
    let u32s = |name: &str, data: Vec<u32>| AnyChannel::new(name, FlatSamples::U32(data));
    let mut channels = Vec::new();
    for (k, c) in ["R", "G", "B", "A"].iter().enumerate() {
        channels.push(f32s(c, index(&|i| rgba[i][k])));
    }
    channels.push(f32s("Z", index(&|i| film.pixels[i].depth)));
    for (k, c) in ["N.X", "N.Y", "N.Z"].iter().enumerate() {
        channels.push(f32s(c, index(&|i| film.pixels[i].normal[k])));
    }
    channels.push(f32s("M.X", index(&|i| film.pixels[i].motion[0])));
    channels.push(f32s("M.Y", index(&|i| film.pixels[i].motion[1])));
    channels.push(u32s("tag", pixels.iter().map(|&i| film.pixels[i].tag).collect()));
    channels.push(u32s("samples", pixels.iter().map(|&i| film.pixels[i].samples).collect()));
    for b in &film.user {
        for (k, c) in ["R", "G", "B", "A"].iter().enumerate() {
            channels.push(f32s(&format!("{}.{c}", b.name), index(&|i| b.data[i][k])));
        }
    }
    let mut attributes = LayerAttributes::default();
    for (k, v) in info.attributes() {
        attributes.other.insert(
            Text::from_slice_unchecked(k.as_bytes()),
            AttributeValue::Text(Text::from_slice_unchecked(v.as_bytes())),
        );
    }
    let encoding = Encoding { line_order: LineOrder::Increasing, ..Encoding::FAST_LOSSLESS };
    let layer = Layer::new((w, rows.len()), attributes, encoding, AnyChannels::sort(channels.into()));
    Image::from_layer(layer).write().to_file(path).map_err(|e| e.to_string())
}

/// A part file read back.
pub struct PartFile {
    /// Its header.
    pub info: PartInfo,
    /// Its channels by name, over its rows (row by row).
    channels: HashMap<String, FlatSamples>,
}

/// Reads the header and channels of the part file at `path`.
pub fn read(path: &Path) -> std::result::Result<PartFile, String> {
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_file(path)
        .map_err(|e| e.to_string())?;
    let layer = image.layer_data.into_iter().next().ok_or("it holds no image")?;
    let attributes: HashMap<String, String> = layer
        .attributes
        .other
        .iter()
        .filter_map(|(k, v)| match v {
            AttributeValue::Text(t) => Some((
                String::from_utf8_lossy(k.as_slice()).into_owned(),
                String::from_utf8_lossy(t.as_slice()).into_owned(),
            )),
            _ => None,
        })
        .collect();
    let info = PartInfo::from_attributes(&attributes)?;
    let rows = info.split.owned_rows(info.part, info.size.1).len();
    if layer.size.width() != info.size.0 as usize || layer.size.height() != rows {
        return Err(format!(
            "it is {}×{} pixels, but part {} of a {}×{} image has {} rows",
            layer.size.width(),
            layer.size.height(),
            info.part,
            info.size.0,
            info.size.1,
            rows
        ));
    }
    let channels = layer
        .channel_data
        .list
        .into_iter()
        .map(|c| (String::from_utf8_lossy(c.name.as_slice()).into_owned(), c.sample_data))
        .collect();
    Ok(PartFile { info, channels })
}

impl PartFile {
    fn f32s(&self, name: &str) -> std::result::Result<&[f32], String> {
        match self.channels.get(name) {
            Some(FlatSamples::F32(v)) => Ok(v),
            _ => Err(format!("it has no 32-bit float channel {name}")),
        }
    }

    fn u32s(&self, name: &str) -> std::result::Result<&[u32], String> {
        match self.channels.get(name) {
            Some(FlatSamples::U32(v)) => Ok(v),
            _ => Err(format!("it has no unsigned integer channel {name}")),
        }
    }

    /// Copies this part's pixels into `film` (a film of the full image, made by
    /// [`empty_film`]). Colour is stored so that [`Film::rgba`] gives back exactly the
    /// part's values.
    pub fn copy_into(&self, film: &mut Film) -> std::result::Result<(), String> {
        let rows = self.info.split.owned_rows(self.info.part, film.height);
        let w = film.width as usize;
        let rgba = [self.f32s("R")?, self.f32s("G")?, self.f32s("B")?, self.f32s("A")?];
        let z = self.f32s("Z")?;
        let n = [self.f32s("N.X")?, self.f32s("N.Y")?, self.f32s("N.Z")?];
        let m = [self.f32s("M.X")?, self.f32s("M.Y")?];
        let tag = self.u32s("tag")?;
        let samples = self.u32s("samples")?;
        let mut user = Vec::new();
        for b in &film.user {
            let c = |s: &str| self.f32s(&format!("{}.{s}", b.name));
            user.push([c("R")?, c("G")?, c("B")?, c("A")?]);
        }
        for (r, &y) in rows.iter().enumerate() {
            for x in 0..w {
                let (src, dst) = (r * w + x, y as usize * w + x);
                let p = &mut film.pixels[dst];
                // Σ w·c = c and Σ w = 1: `rgba()` returns c bit for bit.
                p.sum = rgba.map(|c| f64::from(c[src]));
                p.weight = 1.0;
                p.samples = samples[src];
                p.depth = z[src];
                p.normal = n.map(|c| c[src]);
                p.motion = m.map(|c| c[src]);
                p.tag = tag[src];
                for (b, data) in film.user.iter_mut().zip(&user) {
                    b.data[dst] = data.map(|c| c[src]);
                    b.writes[dst] = 1;
                }
            }
        }
        Ok(())
    }
}

/// An empty film of the image `info` describes, with its user frame buffers.
pub fn empty_film(info: &PartInfo) -> Film {
    let mut film = Film::new(info.size.0, info.size.1);
    for (name, datatype) in &info.user {
        film.add_user_buffer(name, datatype);
    }
    film
}
