//! The `options` element as typed settings, with mental ray's defaults (and Iray's where
//! the scene is in the Iray dialect).

use mi::ast::{Arg, Block, Stmt};

mod modes;

pub use modes::{EnvironmentLighting, EnvironmentShadow, MAX_ENVIRONMENT_SAMPLES};

use crate::values::{attributes, bool_arg, f64_arg, floats_arg, int_arg, last, str_arg, AttrValue, Attributes};

/// Most photons a map's lookups gather (`caustic accuracy`, `globillum accuracy`) and most
/// final gather rays (`finalgather accuracy`) the options keep.
pub const MAX_ACCURACY: i64 = 1 << 20;

/// Most motion steps the options keep (`motion steps`).
pub const MAX_MOTION_STEPS: i64 = 15;

/// Highest frame buffer number (`frame buffer n`) and most final gather points
/// (`finalgather points`) the options keep.
pub const MAX_BUFFER_OR_POINTS: i64 = 1 << 16;

/// Most progressive samples per pixel the options keep (`progressive max samples`,
/// `progressive_rendering_max_samples`, and the minimum).
pub const MAX_PROGRESSIVE_SAMPLES: f64 = 1e9;

/// Which dialect the scene is written in; it changes how some statements are read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Dialect {
    /// Classic mental ray.
    #[default]
    MentalRay,
    /// NVIDIA Iray / RealityServer: MDL materials, attributes, filter remapping.
    Iray,
}

/// Pixel filter kinds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilterKind {
    /// Box.
    Box,
    /// Triangle (tent).
    Triangle,
    /// Gaussian.
    Gauss,
    /// Mitchell–Netravali.
    Mitchell,
    /// Lanczos.
    Lanczos,
}

/// The pixel filter: `filter kind [width [height]]`, sizes being the full footprint in
/// pixels (mental ray's convention; Iray's radius is half of it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Filter {
    /// The kind.
    pub kind: FilterKind,
    /// Footprint width in pixels.
    pub width: f64,
    /// Footprint height in pixels.
    pub height: f64,
    /// `clip mitchell`/`clip lanczos`: negative lobes clipped.
    pub clip: bool,
}

impl Filter {
    /// The filter radius in pixels (half the footprint), x and y.
    pub fn radius(&self) -> (f64, f64) {
        (self.width * 0.5, self.height * 0.5)
    }
}

/// Shadow computation mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowMode {
    /// No shadows.
    Off,
    /// Shadows, shadow shaders in any order.
    On,
    /// Shadow shaders called in order from the light.
    Sort,
    /// Shadow segments (volumes between occluders).
    Segments,
}

/// Which sides of surfaces are seen.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Face {
    /// Front faces only.
    Front,
    /// Back faces only.
    Back,
    /// Both.
    #[default]
    Both,
}

impl Face {
    /// From the keyword.
    pub fn from_word(w: &str) -> Face {
        match w {
            "front" => Face::Front,
            "back" => Face::Back,
            _ => Face::Both,
        }
    }
}

/// Final gathering settings.
#[derive(Clone, Debug, PartialEq)]
pub struct FinalGather {
    /// `finalgather on|off|fastlookup|only`.
    pub enabled: bool,
    /// `finalgather accuracy [view] rays [max [min]]`: rays per final gather point.
    pub rays: u32,
    /// Interpolation radii (max, min), in world or (with `view`) pixel units.
    pub radius: Option<(f64, f64)>,
    /// Radii are in pixels.
    pub view: bool,
    /// `finalgather trace depth reflect refract diffuse sum`.
    pub trace_depth: [u32; 4],
    /// `finalgather falloff start stop`.
    pub falloff: Option<(f64, f64)>,
    /// `finalgather scale r g b a`.
    pub scale: [f64; 4],
    /// `finalgather points n` (or the string option `"finalgather points"`): final gather
    /// points interpolated at a lookup; 0 asks for brute force (no interpolation).
    pub points: u32,
    /// `finalgather mode …` (or `"finalgather mode"`): `strict` (3.4 radii), `automatic`,
    /// `multiframe`, as written (lower case).
    pub mode: String,
    /// `finalgather presample density f`: density of the pre-pass over the image.
    pub presample_density: f64,
}

/// The filter of caustic photon lookups (`caustic filter box|cone|gauss [k]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CausticFilter {
    /// Every photon within the radius counts fully.
    Box,
    /// Weight 1 − d / (k r), `k` ≥ 1 (mental ray's default `k` 1.1).
    Cone(f64),
    /// Gaussian weight (Jensen's α = 0.918, β = 1.953).
    Gauss,
}

/// Photon map settings of the options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photons {
    /// `caustic accuracy n [radius]`: photons per caustic lookup and the largest lookup
    /// radius (world units; `None` or 0: chosen from the scene's size).
    pub caustic_accuracy: (u32, Option<f64>),
    /// `globillum accuracy n [radius]`, as `caustic_accuracy`.
    pub globillum_accuracy: (u32, Option<f64>),
    /// `caustic filter`.
    pub caustic_filter: CausticFilter,
    /// `caustic scale r g b`.
    pub caustic_scale: [f64; 3],
    /// `globillum scale r g b`.
    pub globillum_scale: [f64; 3],
    /// `photon trace depth reflect refract sum`: most specular reflections, refractions
    /// and scattering events of all kinds (diffuse bounces included) along a photon path.
    pub trace_depth: (u32, u32, u32),
}

impl Default for Photons {
    /// mental ray's defaults: 100 caustic and 500 global illumination photons per lookup,
    /// radii from the scene, box filter, unit scales, photon trace depth 5 5 5.
    fn default() -> Photons {
        Photons {
            caustic_accuracy: (100, None),
            globillum_accuracy: (500, None),
            caustic_filter: CausticFilter::Box,
            caustic_scale: [1.0; 3],
            globillum_scale: [1.0; 3],
            trace_depth: (5, 5, 5),
        }
    }
}

impl Photons {
    /// Reads the photon statements among an options element's statements.
    fn read(&mut self, stmts: &[&Stmt]) {
        let accuracy = |k: &mi::ast::KwStmt, old: (u32, Option<f64>)| {
            let n = int_arg(k, 0).map_or(old.0, |n| n.clamp(1, MAX_ACCURACY) as u32);
            (n, f64_arg(k, 1).filter(|r| *r > 0.0))
        };
        if let Some(k) = last(stmts, "caustic accuracy") {
            self.caustic_accuracy = accuracy(k, self.caustic_accuracy);
        }
        if let Some(k) = last(stmts, "globillum accuracy") {
            self.globillum_accuracy = accuracy(k, self.globillum_accuracy);
        }
        if let Some(k) = last(stmts, "caustic filter") {
            self.caustic_filter = match str_arg(k, 0) {
                Some("cone") => CausticFilter::Cone(f64_arg(k, 1).unwrap_or(1.1).max(1.0)),
                Some("gauss") => CausticFilter::Gauss,
                _ => CausticFilter::Box,
            };
        }
        let scale = |k: &mi::ast::KwStmt| floats_arg(k, 0).filter(|c| c.len() >= 3).map(|c| [c[0], c[1], c[2]]);
        if let Some(c) = last(stmts, "caustic scale").and_then(scale) {
            self.caustic_scale = c;
        }
        if let Some(c) = last(stmts, "globillum scale").and_then(scale) {
            self.globillum_scale = c;
        }
        if let Some(k) = last(stmts, "photon trace depth") {
            let d: Vec<u32> = (0..3).filter_map(|i| int_arg(k, i)).map(|v| v.clamp(0, 1 << 10) as u32).collect();
            let reflect = d.first().copied().unwrap_or(5);
            let refract = d.get(1).copied().unwrap_or(reflect);
            let sum = d.get(2).copied().unwrap_or(reflect + refract);
            self.trace_depth = (reflect, refract, sum);
        }
    }
}

/// Progressive (Iray-style) rendering limits, from Iray attributes or mental ray's
/// `"progressive …"` string options.
#[derive(Clone, Debug, PartialEq)]
pub struct Progressive {
    /// Stop after this many samples per pixel.
    pub max_samples: u32,
    /// Stop after this many seconds (`None`: no limit).
    pub max_time: Option<f64>,
    /// Do not stop for convergence before this many samples.
    pub min_samples: u32,
    /// Whether the convergence test is on.
    pub quality_enabled: bool,
    /// Relative error threshold of the convergence test (1 = Iray's default quality).
    pub quality: f64,
    /// Stop when this fraction of pixels has converged.
    pub converged_pixel_ratio: f64,
}

/// All settings of the `options` element.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The element's name.
    pub name: String,
    /// `approximate displace … all` and `max displace`: the defaults of displaced objects.
    pub displace: crate::displace::DisplaceSettings,
    /// The dialect the scene is written in.
    pub dialect: Dialect,
    /// `samples min max`: adaptive supersampling as powers of 4 per pixel (0 = 1 sample,
    /// 1 = 4, −1 = one per 2×2 pixels).
    pub samples: (i32, i32),
    /// `contrast r g b a`: adaptive sampling thresholds.
    pub contrast: [f64; 4],
    /// The pixel filter (remapped for Iray).
    pub filter: Filter,
    /// `jitter`: sample jittering, 0 to 1.
    pub jitter: f64,
    /// `trace on|off`: secondary rays.
    pub trace: bool,
    /// `trace depth reflect refract sum`.
    pub trace_depth: (u32, u32, u32),
    /// `shadow`.
    pub shadow: ShadowMode,
    /// `face`.
    pub face: Face,
    /// Final gathering.
    pub finalgather: FinalGather,
    /// `globillum` (photon global illumination).
    pub globillum: bool,
    /// `caustic`.
    pub caustic: bool,
    /// Photon map settings (`caustic accuracy`, `globillum accuracy`, `caustic filter`,
    /// `photon trace depth`, scales).
    pub photons: Photons,
    /// `motion on|off`.
    pub motion: bool,
    /// `motion steps`.
    pub motion_steps: u32,
    /// `shutter [delay] close`: the shutter interval (open, close) in frame time.
    pub shutter: (f64, f64),
    /// Pre-3.10 user frame buffers: `frame buffer n "type"`.
    pub frame_buffers: Vec<(u32, String)>,
    /// The state shaders (`state` statements, in order; the last statement that names
    /// none clears them): shaders mental ray runs at each sample's start and end, such as
    /// Maya exports' `maya_state` with its frame buffer bookkeeping.
    pub state: Vec<mi::ast::ShaderItem>,
    /// `colorclip rgb|alpha|raw`.
    pub colorclip: String,
    /// `premultiply on|off`.
    pub premultiply: bool,
    /// `gamma`.
    pub gamma: f64,
    /// `desaturate`.
    pub desaturate: bool,
    /// `dither`.
    pub dither: bool,
    /// Progressive rendering limits.
    pub progressive: Progressive,
    /// String options (`"name" value`), last one wins.
    pub string_options: Attributes,
    /// Where each string option's (last) statement is, for messages about its value.
    pub string_option_spans: std::collections::HashMap<String, mi::Span>,
    /// Typed attributes (Iray).
    pub attributes: Attributes,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            name: String::new(),
            displace: Default::default(),
            dialect: Dialect::MentalRay,
            samples: (-2, 0),
            contrast: [0.1; 4],
            filter: Filter { kind: FilterKind::Box, width: 1.0, height: 1.0, clip: false },
            jitter: 0.0,
            trace: true,
            trace_depth: (2, 2, 4),
            shadow: ShadowMode::On,
            face: Face::Both,
            finalgather: FinalGather {
                enabled: false,
                rays: 1000,
                radius: None,
                view: false,
                trace_depth: [2, 2, 0, 2],
                falloff: None,
                scale: [1.0; 4],
                points: 30,
                mode: "strict".into(),
                presample_density: 1.0,
            },
            globillum: false,
            caustic: false,
            photons: Photons::default(),
            motion: false,
            motion_steps: 1,
            shutter: (0.0, 0.0),
            frame_buffers: Vec::new(),
            state: Vec::new(),
            colorclip: "rgb".into(),
            premultiply: true,
            gamma: 1.0,
            desaturate: false,
            dither: false,
            progressive: Progressive {
                max_samples: 100,
                max_time: None,
                min_samples: 4,
                quality_enabled: false,
                quality: 1.0,
                converged_pixel_ratio: 0.95,
            },
            string_options: Attributes::new(),
            string_option_spans: Default::default(),
            attributes: Attributes::new(),
        }
    }
}

fn filter_kind(w: &str) -> FilterKind {
    match w {
        "triangle" => FilterKind::Triangle,
        "gauss" => FilterKind::Gauss,
        "mitchell" => FilterKind::Mitchell,
        "lanczos" => FilterKind::Lanczos,
        _ => FilterKind::Box,
    }
}

/// Default footprint of each filter kind (box 1, triangle 2, gauss 3, mitchell and
/// lanczos 4).
fn default_width(kind: FilterKind) -> f64 {
    match kind {
        FilterKind::Box => 1.0,
        FilterKind::Triangle => 2.0,
        FilterKind::Gauss => 3.0,
        FilterKind::Mitchell | FilterKind::Lanczos => 4.0,
    }
}

impl Options {
    /// Reads the definitions of an `options` element (the first, then incremental changes).
    pub fn from_blocks(blocks: &[&Block], dialect: Dialect) -> Options {
        let mut o = Options {
            name: blocks.first().map(|b| b.name.text.clone()).unwrap_or_default(),
            dialect,
            ..Options::default()
        };
        let stmts: Vec<&Stmt> = blocks.iter().flat_map(|b| b.stmts.iter()).collect();
        o.displace = crate::displace::DisplaceSettings::of_options(&stmts);
        if let Some(k) = last(&stmts, "samples") {
            let ints: Vec<i64> = (0..k.args.len()).filter_map(|i| int_arg(k, i)).collect();
            o.samples = match ints[..] {
                [n] => ((n - 2) as i32, n as i32),
                [a, b, ..] => (a as i32, b as i32),
                _ => o.samples,
            };
        }
        if let Some(c) = last(&stmts, "contrast").and_then(|k| floats_arg(k, 0)) {
            let a = c.get(3).copied().unwrap_or((c[0] + c[1] + c[2]) / 3.0);
            o.contrast = [c[0], c[1], c[2], a];
        }
        if let Some(k) = last(&stmts, "filter") {
            let clip = str_arg(k, 0) == Some("clip");
            let kind = filter_kind(str_arg(k, usize::from(clip)).unwrap_or("box"));
            let nums: Vec<f64> = (0..k.args.len()).filter_map(|i| f64_arg(k, i)).collect();
            let width = nums.first().copied().unwrap_or(default_width(kind));
            let height = nums.get(1).copied().unwrap_or(width);
            o.filter = Filter { kind, width, height, clip };
        }
        if dialect == Dialect::Iray && matches!(o.filter.kind, FilterKind::Mitchell | FilterKind::Lanczos) {
            // Iray has box, triangle and gauss only; the others become gauss.
            o.filter.kind = FilterKind::Gauss;
            o.filter.clip = false;
        }
        if let Some(v) = last(&stmts, "jitter").and_then(|k| f64_arg(k, 0)) {
            o.jitter = v;
        }
        if let Some(k) = last(&stmts, "trace") {
            o.trace = bool_arg(k, 0);
        }
        if let Some(k) = last(&stmts, "trace depth") {
            let d: Vec<u32> = (0..3).filter_map(|i| int_arg(k, i)).map(|v| v.clamp(0, 1 << 16) as u32).collect();
            let reflect = d.first().copied().unwrap_or(2);
            let refract = d.get(1).copied().unwrap_or(reflect);
            let sum = d.get(2).copied().unwrap_or(reflect + refract);
            o.trace_depth = (reflect, refract, sum);
        }
        if let Some(k) = last(&stmts, "shadow") {
            o.shadow = match k.args.first() {
                Some(Arg::Bool(false)) => ShadowMode::Off,
                Some(Arg::Word("sort")) => ShadowMode::Sort,
                Some(Arg::Word("segments")) => ShadowMode::Segments,
                _ => ShadowMode::On,
            };
        }
        if let Some(w) = last(&stmts, "face").and_then(|k| str_arg(k, 0)) {
            o.face = Face::from_word(w);
        }
        if let Some(k) = last(&stmts, "finalgather") {
            o.finalgather.enabled = !matches!(k.args.first(), Some(Arg::Bool(false)));
        }
        if let Some(k) = last(&stmts, "finalgather accuracy") {
            let view = str_arg(k, 0) == Some("view");
            let base = usize::from(view);
            o.finalgather.view = view;
            if let Some(r) = int_arg(k, base) {
                o.finalgather.rays = r.clamp(1, MAX_ACCURACY) as u32;
            }
            if let Some(max) = f64_arg(k, base + 1) {
                let min = f64_arg(k, base + 2).unwrap_or(max * 0.1);
                o.finalgather.radius = Some((max, min));
            }
        }
        if let Some(k) = last(&stmts, "finalgather trace depth") {
            let d: Vec<u32> = (0..4).filter_map(|i| int_arg(k, i)).map(|v| v.clamp(0, 1 << 16) as u32).collect();
            for (slot, v) in o.finalgather.trace_depth.iter_mut().zip(d) {
                *slot = v;
            }
        }
        if let Some(k) = last(&stmts, "finalgather falloff") {
            let a = f64_arg(k, 0).unwrap_or(0.0);
            o.finalgather.falloff = Some(match f64_arg(k, 1) {
                Some(b) => (a, b),
                None => (0.0, a),
            });
        }
        if let Some(c) = last(&stmts, "finalgather scale").and_then(|k| floats_arg(k, 0)) {
            o.finalgather.scale = [c[0], c[1], c[2], c.get(3).copied().unwrap_or(1.0)];
        }
        if let Some(k) = last(&stmts, "globillum") {
            o.globillum = !matches!(k.args.first(), Some(Arg::Bool(false) | Arg::Int(0)));
        }
        if let Some(k) = last(&stmts, "caustic") {
            o.caustic = !matches!(k.args.first(), Some(Arg::Bool(false) | Arg::Int(0)));
        }
        o.photons.read(&stmts);
        if let Some(k) = last(&stmts, "motion") {
            o.motion = bool_arg(k, 0);
        }
        if let Some(v) = last(&stmts, "motion steps").and_then(|k| int_arg(k, 0)) {
            o.motion_steps = v.clamp(1, MAX_MOTION_STEPS) as u32;
        }
        if let Some(k) = last(&stmts, "shutter") {
            o.shutter = match (f64_arg(k, 0), f64_arg(k, 1)) {
                (Some(d), Some(c)) => (d, c),
                (Some(c), None) => (0.0, c),
                _ => o.shutter,
            };
        }
        for s in &stmts {
            if let Stmt::Kw(k) = s {
                if k.key == "frame buffer" {
                    let n = int_arg(k, 0).unwrap_or(0).clamp(0, MAX_BUFFER_OR_POINTS) as u32;
                    let ty = str_arg(k, 1).unwrap_or("").to_string();
                    o.frame_buffers.retain(|(m, _)| *m != n);
                    o.frame_buffers.push((n, ty));
                } else if k.key == "state" {
                    o.state = match k.args.first() {
                        Some(Arg::Shaders(l) | Arg::ShaderArray(l)) => l.0.clone(),
                        _ => Vec::new(),
                    };
                }
            }
        }
        if let Some(w) = last(&stmts, "colorclip").and_then(|k| str_arg(k, 0)) {
            o.colorclip = w.to_string();
        }
        if let Some(k) = last(&stmts, "premultiply") {
            o.premultiply = bool_arg(k, 0);
        }
        if let Some(v) = last(&stmts, "gamma").and_then(|k| f64_arg(k, 0)) {
            o.gamma = v;
        }
        if let Some(k) = last(&stmts, "desaturate") {
            o.desaturate = bool_arg(k, 0);
        }
        if let Some(k) = last(&stmts, "dither") {
            o.dither = bool_arg(k, 0);
        }
        for s in &stmts {
            if let Stmt::StringOption { name, value } = s {
                if let Some(v) = AttrValue::from_value(value) {
                    o.string_options.insert(name.text.clone(), v);
                    o.string_option_spans.insert(name.text.clone(), name.span);
                }
            }
        }
        o.attributes = attributes(&stmts);
        o.read_progressive();
        o.read_finalgather(&stmts);
        o
    }

    /// Final gather interpolation settings: the keyword statements, then the string
    /// options (`"finalgather points" 30`, `"finalgather mode" "automatic"`), last one wins.
    fn read_finalgather(&mut self, stmts: &[&Stmt]) {
        let fg = &mut self.finalgather;
        if let Some(v) = last(stmts, "finalgather points").and_then(|k| int_arg(k, 0)) {
            fg.points = v.clamp(0, MAX_BUFFER_OR_POINTS) as u32;
        }
        if let Some(k) = last(stmts, "finalgather mode") {
            let words: Vec<String> = (0..k.args.len())
                .filter_map(|i| str_arg(k, i).map(str::to_string).or_else(|| f64_arg(k, i).map(|v| v.to_string())))
                .collect();
            fg.mode = words.join(" ").to_ascii_lowercase();
        }
        if let Some(v) = last(stmts, "finalgather presample density").and_then(|k| f64_arg(k, 0)) {
            fg.presample_density = v;
        }
        if let Some(v) = self.string_options.get("finalgather points").and_then(|v| v.as_f64()) {
            fg.points = v.clamp(0.0, MAX_BUFFER_OR_POINTS as f64) as u32;
        }
        if let Some(AttrValue::Str(m)) = self.string_options.get("finalgather mode") {
            fg.mode = m.to_ascii_lowercase();
        }
        if let Some(v) = self.string_options.get("finalgather presample density").and_then(|v| v.as_f64()) {
            fg.presample_density = v;
        }
    }

    /// Progressive limits from Iray attributes, then mental ray string options.
    fn read_progressive(&mut self) {
        let get = |names: &[&str]| {
            names.iter().find_map(|n| self.attributes.get(*n).or(self.string_options.get(*n))).cloned()
        };
        let p = &mut self.progressive;
        if let Some(v) = get(&["progressive_rendering_max_samples", "progressive max samples"]).and_then(|v| v.as_f64())
        {
            p.max_samples = v.clamp(1.0, MAX_PROGRESSIVE_SAMPLES) as u32;
        }
        if let Some(v) = get(&["progressive_rendering_min_samples", "progressive min samples"]).and_then(|v| v.as_f64())
        {
            p.min_samples = v.clamp(1.0, MAX_PROGRESSIVE_SAMPLES) as u32;
        }
        if let Some(v) = get(&["progressive_rendering_max_time", "progressive max time"]).and_then(|v| v.as_f64()) {
            p.max_time = (v > 0.0).then_some(v);
        }
        if let Some(v) = get(&["progressive_rendering_quality_enabled"]).and_then(|v| v.as_bool()) {
            p.quality_enabled = v;
        }
        if let Some(v) = get(&["progressive_rendering_quality", "progressive error threshold"]).and_then(|v| v.as_f64())
        {
            p.quality = v;
        }
        if let Some(v) = get(&["progressive_rendering_converged_pixel_ratio"]).and_then(|v| v.as_f64()) {
            p.converged_pixel_ratio = v.clamp(0.0, 1.0);
            p.quality_enabled = true;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn options(text: &str, dialect: Dialect) -> Options {
        let parsed = mi::parse_str("o.mi", text);
        assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
        let blocks: Vec<&Block> =
            parsed.items.iter().filter_map(|i| if let mi::Item::Options(b) = i { Some(b) } else { None }).collect();
        let blocks: Vec<Block> = blocks.into_iter().cloned().collect();
        let refs: Vec<&Block> = blocks.iter().collect();
        Options::from_blocks(&refs, dialect)
    }

    #[test]
    fn defaults() {
        let o = options("options \"o\" end options", Dialect::MentalRay);
        assert_eq!(o.samples, (-2, 0));
        assert_eq!(o.filter, Filter { kind: FilterKind::Box, width: 1.0, height: 1.0, clip: false });
        assert_eq!(o.trace_depth, (2, 2, 4));
        assert_eq!(o.shadow, ShadowMode::On);
    }

    #[test]
    fn statements_and_iray_filter_remapping() {
        let text = "options \"o\"\n samples 1\n filter mitchell 4 4\n trace depth 3\n shadow segments\n\
                    finalgather on\n finalgather accuracy view 300 25\n shutter 0.5\n frame buffer 0 \"+rgba_fp\"\n\
                    \"unified sampling\" on\n attribute integer \"progressive_rendering_max_samples\" 64\n end options";
        let o = options(text, Dialect::MentalRay);
        assert_eq!(o.samples, (-1, 1));
        assert_eq!(o.filter.kind, FilterKind::Mitchell);
        assert_eq!(o.filter.radius(), (2.0, 2.0));
        assert_eq!(o.trace_depth, (3, 3, 6));
        assert_eq!(o.shadow, ShadowMode::Segments);
        assert!(o.finalgather.enabled && o.finalgather.view);
        assert_eq!(o.finalgather.rays, 300);
        assert_eq!(o.finalgather.radius, Some((25.0, 2.5)));
        assert_eq!((o.finalgather.points, o.finalgather.mode.as_str()), (30, "strict"));
        let fg = options(
            "options \"o\" finalgather points 12 finalgather mode strict 3.4 finalgather presample density 2 end options",
            Dialect::MentalRay,
        );
        assert_eq!((fg.finalgather.points, fg.finalgather.mode.as_str()), (12, "strict 3.4"));
        assert_eq!(fg.finalgather.presample_density, 2.0);
        let strings = options(
            "options \"o\" \"finalgather points\" 5 \"finalgather mode\" \"Automatic\" end options",
            Dialect::MentalRay,
        );
        assert_eq!((strings.finalgather.points, strings.finalgather.mode.as_str()), (5, "automatic"));
        assert_eq!(o.shutter, (0.0, 0.5));
        assert_eq!(o.frame_buffers, vec![(0, "+rgba_fp".to_string())]);
        assert_eq!(o.string_options["unified sampling"], AttrValue::Bool(true));
        assert_eq!(o.progressive.max_samples, 64);
        let iray = options(text, Dialect::Iray);
        assert_eq!(iray.filter.kind, FilterKind::Gauss);
        assert_eq!(iray.filter.radius(), (2.0, 2.0));
    }

    /// mental ray 3.7+'s progressive string options (as a 3.12 MDL scene writes them) set
    /// the progressive limits as Iray's attributes do; `"progressive" on`, `"gi" on` and
    /// `"light relative scale"` read as their typed settings (`options::modes`); `"gi depth"`
    /// counts only with `"gi" on` (negative read as 0), `"gi rays"` is kept as written.
    #[test]
    fn mental_ray_progressive_string_options() {
        let o = options(
            "options \"o\" \"progressive\" on \"progressive max samples\" 64 \"progressive min samples\" 4\n\
             \"progressive max time\" 30 \"progressive error threshold\" 0.05 \"gi\" on \"light relative scale\" 0.5\n\
             end options",
            Dialect::MentalRay,
        );
        assert_eq!((o.progressive.max_samples, o.progressive.min_samples), (64, 4));
        assert_eq!((o.progressive.max_time, o.progressive.quality), (Some(30.0), 0.05));
        assert_eq!(o.string_options["progressive"], AttrValue::Bool(true));
        assert_eq!(o.string_options["gi"], AttrValue::Bool(true));
        assert_eq!(o.string_options["light relative scale"].as_f64(), Some(0.5));
        assert!(o.progressive_mode() && o.gi_next() && o.asks_for_path_tracing());
        assert_eq!(o.light_relative_scale(), 0.5);
        assert_eq!(o.environment_lighting(), None);
        let plain = options("options \"o\" \"progressive\" off end options", Dialect::MentalRay);
        assert!(!plain.progressive_mode() && !plain.gi_next() && !plain.asks_for_path_tracing());
        assert_eq!(plain.light_relative_scale(), 1.0);
        let gi = options("options \"o\" \"gi\" on end options", Dialect::MentalRay);
        assert!(gi.asks_for_path_tracing() && !gi.progressive_mode());
        assert_eq!((gi.gi_depth(), gi.gi_rays()), (None, None));
        let tuned = options("options \"o\" \"gi\" on \"gi depth\" 3 \"gi rays\" 64 end options", Dialect::MentalRay);
        assert_eq!((tuned.gi_depth(), tuned.gi_rays()), (Some(3), Some(64.0)));
        let negative = options("options \"o\" \"gi\" on \"gi depth\" -2 end options", Dialect::MentalRay);
        assert_eq!(negative.gi_depth(), Some(0));
        let off = options("options \"o\" \"gi\" off \"gi depth\" 3 end options", Dialect::MentalRay);
        assert_eq!(off.gi_depth(), None, "\"gi depth\" is GI \"Next\"'s only");
    }

    /// `"iray" on` (mental ray's iray rendering mode, switched on by a scene option: its
    /// manual's iray.html; Maya writes the string option `"iray"`) asks for path tracing;
    /// off or absent, not.
    #[test]
    fn iray_rendering_mode() {
        let on = options("options \"o\" \"iray\" on end options", Dialect::MentalRay);
        assert!(on.iray_mode() && on.asks_for_path_tracing());
        assert!(!on.progressive_mode() && !on.gi_next());
        for text in ["options \"o\" \"iray\" off end options", "options \"o\" end options"] {
            let off = options(text, Dialect::MentalRay);
            assert!(!off.iray_mode() && !off.asks_for_path_tracing(), "{text}");
        }
    }

    /// `"environment lighting mode"`: `"off"` (any case) is off, `"light"` and any other
    /// value on, absent `None`.
    #[test]
    fn environment_lighting_mode() {
        let mode = |v: &str| {
            options(&format!("options \"o\" \"environment lighting mode\" {v} end options"), Dialect::MentalRay)
                .environment_lighting()
        };
        assert_eq!(mode("\"off\""), Some(EnvironmentLighting::Off));
        assert_eq!(mode("\"Off\""), Some(EnvironmentLighting::Off));
        assert_eq!(mode("\"light\""), Some(EnvironmentLighting::Light));
        assert_eq!(mode("\"automatic\""), Some(EnvironmentLighting::Light));
        assert_eq!(options("options \"o\" end options", Dialect::MentalRay).environment_lighting(), None);
    }

    /// `"environment lighting shadow"`, `"quality"` and `"scale"`: the shadow modes (any
    /// case; absent or unknown: transparent), ⌈2q⌉ directions (1 below 0.5 and without the
    /// option, at most 64), the scale as a number or a colour's mean (negative: 1).
    #[test]
    fn environment_lighting_settings() {
        let o = |v: &str| options(&format!("options \"o\" {v} end options"), Dialect::MentalRay);
        let shadow = |v: &str| o(&format!("\"environment lighting shadow\" {v}")).environment_shadow();
        assert_eq!(shadow("\"off\""), EnvironmentShadow::Off);
        assert_eq!(shadow("\"Solid\""), EnvironmentShadow::Solid);
        assert_eq!(shadow("\"transparent\""), EnvironmentShadow::Transparent);
        assert_eq!(shadow("\"optimized\""), EnvironmentShadow::Transparent);
        assert_eq!(o("").environment_shadow(), EnvironmentShadow::Transparent);
        let samples = |v: &str| o(&format!("\"environment lighting quality\" {v}")).environment_samples();
        assert_eq!((samples("0.2"), samples("0.5"), samples("1"), samples("2.2"), samples("1000")), (1, 1, 2, 5, 64));
        assert_eq!((samples("-3"), o("").environment_samples()), (1, 1));
        let scale = |v: &str| o(&format!("\"environment lighting scale\" {v}")).environment_lighting_scale();
        assert_eq!((scale("2"), scale("0.5 1 1.5"), scale("-1")), (2.0, 1.0, 1.0));
        assert_eq!(o("").environment_lighting_scale(), 1.0);
    }

    /// The `state` statement's shaders are kept in order: an inline call, a named shader
    /// (`state = "name"`), and a later statement replaces an earlier one.
    #[test]
    fn state_shaders() {
        let inline =
            options("options \"o\" state \"maya_state\" (\"glowColorBuffer\" 1) end options", Dialect::MentalRay);
        assert!(matches!(&inline.state[..], [mi::ast::ShaderItem::Call { decl, .. }] if decl.text == "maya_state"));
        let named =
            options("options \"o\" state \"maya_state\" () state = \"opt:state\" end options", Dialect::MentalRay);
        assert!(matches!(&named.state[..], [mi::ast::ShaderItem::Ref(n)] if n.text == "opt:state"));
        assert!(options("options \"o\" end options", Dialect::MentalRay).state.is_empty());
    }
}
