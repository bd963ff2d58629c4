//! mental ray's rendering-mode string options as typed settings: `"progressive"`, `"gi"`
//! (GI "Next"), `"iray"`, `"environment lighting mode"` and `"light relative scale"`, read as mental
//! ray documented them (sources below; the stored copies of mental ray's own manual list
//! these options only by section title, so where a statement comes from another page it is
//! named).
//!
//! - `"progressive" on|off` — 3ds Max's reference of mental ray's string options
//!   (<https://help.autodesk.com/cloudhelp/2017/ENU/MAXScript-Help/files/GUID-F64266AA-19D7-4F81-A3A7-90152F50F232.htm>,
//!   "Progressive Rendering"): instead of finishing the image bucket by bucket, mental ray
//!   delivers the whole image at full resolution and refines its quality step by step, for
//!   interactive rendering of ray tracing and indirect light; off unless set.
//! - `"gi" on` — mental ray 3.13's "Global Illumination \"Next\"" (the manual's options page,
//!   <https://help.autodesk.com/cloudhelp/2016/ENU/mental-ray-docs/mr_docs/manual/options.html>,
//!   lists the section; its text is not in the stored copy). Users' notes on it
//!   (<https://3d1.com.br/forum/tira-duvidas/perguntas-de-maquete-eletronica/94349>,
//!   <https://elementalray.wordpress.com/tag/gi/>): brute-force global illumination without a
//!   cache or interpolation, which switches photons, final gathering and irradiance particles
//!   off by itself; `"gi rays"` and `"gi depth"` tune it. No stored page gives their exact
//!   meaning; mira takes the natural reading: `"gi depth" n` is the number of indirect
//!   bounces a path makes (the path engine's most scattering events become n + 1: the
//!   first hit's direct light, then n bounces, each with its direct light), and `"gi rays"`
//!   the number of GI rays mental ray shoots per shading sample. A path tracer has no
//!   counterpart of the latter (it follows one ray per bounce and averages over the pixel's
//!   samples): mira reads it and does not change its estimator for it, and says so with a
//!   warning at the option (`crate::sanity`, shown by `mira render --warnings`).
//! - `"iray" on|off` — mental ray's iray rendering mode (3.8 to 3.14). mental ray's own
//!   manual (<https://help.autodesk.com/cloudhelp/2016/ENU/mental-ray-docs/mr_docs/manual/iray.html>)
//!   says the mode is switched on globally by a scene option (or on the command line), always
//!   renders progressively (the progressive options, such as the automatic stop criteria,
//!   control it), takes a few environment lighting options from regular mental ray, and
//!   silently ignores every other rendering option of regular mental ray; Maya's exports
//!   write the switch as the string option `"iray"` (default off). It is a consistent
//!   path tracer without interpolation, which mira's path engine is: `"iray" on` takes the
//!   path engine in the automatic choice, as `"progressive" on` and `"gi" on` do. Off
//!   unless set.
//! - `"environment lighting mode"` — mental ray's built-in image-based lighting (since 3.7):
//!   NVIDIA's mental ray blog (<https://elementalray.wordpress.com/tag/hdr/>, "The Native
//!   (Builtin) IBL") describes it as fast automatic *direct* lighting from the camera's
//!   environment (a dome light: the environment is baked by point sampling and lights the
//!   scene as a light source); Maya 2015 shows it as "Light Emission". Maya writes `"off"`
//!   by default. No stored page lists the other values; `"light"` is the one mental ray
//!   scenes write to turn it on, and mira reads any value but `"off"` as on (with a warning
//!   naming the value, `crate::sanity`). With it off, the environment is not a light: it is
//!   seen only by rays that leave the scene (camera, reflection and refraction rays, and
//!   final gather / GI rays).
//! - `"light relative scale"` — the same blog page: set it (Maya 2015 writes 0.31831, 1/π)
//!   so that physically calibrated lights (the environment light, `user_ibl_env`) light
//!   *non-BSDF, legacy* materials correctly, which would otherwise blow out. It scales the
//!   light legacy shaders receive (they carry no 1/π); BSDF materials (MDL, the layering
//!   library) are lit by the lights' physical output, unscaled.
//! - `"environment lighting quality"`, `"environment lighting shadow"`,
//!   `"environment lighting scale"` — the environment light's settings. No stored page of
//!   mental ray's manual gives their text (its options page lists "Image-Based Lighting"
//!   by title only); 3ds Max's rollout of that light, "Skylight & Environment Lighting
//!   (IBL)" (<https://help.autodesk.com/cloudhelp/2015/ENU/3DSMax/files/GUID-B93DEC38-90E2-4372-AF71-F54F74767D9D.htm>),
//!   describes the first two: *Shadow Quality* — the lower, the grainier the shadows,
//!   higher takes longer (0 to 10, default 0.5) — and *Shadow Mode* — transparent (the
//!   default: accurate, slower) or opaque (less accurate, faster). mira's readings:
//!   quality q sets how many directions the environment's next-event estimate averages,
//!   max(1, ⌈2q⌉) up to 64 (the default 0.5 and below: one, as without the option) —
//!   noise only, the mean is unchanged; shadow `"transparent"` (default) lets shadow rays
//!   through cutouts and transparency as other lights' are, `"solid"` (3ds Max's opaque)
//!   stops them at any surface, `"off"` traces none (only media attenuate, as for a light
//!   with `shadow off`); scale multiplies the light the environment casts on surfaces,
//!   as Iray's `environment_lighting_scale` does (the camera's view of it is unchanged).
//!   Values mira does not understand are warnings at the option (`crate::sanity`).

use super::Options;
use crate::values::AttrValue;

/// Whether and how the camera's environment lights the scene (`"environment lighting mode"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EnvironmentLighting {
    /// `"off"`: the environment is no light source; rays that leave the scene see it.
    Off,
    /// `"light"` (or any other value): the environment lights the scene as a light source,
    /// sampled directly (mira: importance-sampled next-event estimation).
    Light,
}

/// What the environment light's shadow rays do (`"environment lighting shadow"`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EnvironmentShadow {
    /// `"transparent"` (the default): shadow rays pass cutouts and transparency, filtered.
    #[default]
    Transparent,
    /// `"solid"`: any surface stops them.
    Solid,
    /// `"off"`: no shadow rays; only media attenuate the light.
    Off,
}

impl EnvironmentShadow {
    /// The mode a value names (any case); `None` for a value mira does not understand.
    pub fn parse(v: &AttrValue) -> Option<EnvironmentShadow> {
        match v {
            AttrValue::Str(s) if s.eq_ignore_ascii_case("transparent") => Some(EnvironmentShadow::Transparent),
            AttrValue::Str(s) if s.eq_ignore_ascii_case("solid") || s.eq_ignore_ascii_case("opaque") => {
                Some(EnvironmentShadow::Solid)
            }
            AttrValue::Str(s) if s.eq_ignore_ascii_case("off") => Some(EnvironmentShadow::Off),
            AttrValue::Bool(false) => Some(EnvironmentShadow::Off),
            AttrValue::Bool(true) => Some(EnvironmentShadow::Transparent),
            _ => None,
        }
    }
}

/// Most directions one next-event estimate of the environment averages
/// (`"environment lighting quality"` 32 and above).
pub const MAX_ENVIRONMENT_SAMPLES: u32 = 64;

impl Options {
    /// `"progressive" on`: mental ray's progressive rendering mode (see the module comment).
    pub fn progressive_mode(&self) -> bool {
        self.string_options.get("progressive").and_then(AttrValue::as_bool).unwrap_or(false)
    }

    /// `"gi" on`: mental ray 3.13's brute-force global illumination, GI "Next".
    pub fn gi_next(&self) -> bool {
        self.string_options.get("gi").and_then(AttrValue::as_bool).unwrap_or(false)
    }

    /// `"gi depth"` where `"gi" on` is set: the most indirect bounces a path makes (negative
    /// read as 0); `None` without GI "Next" or without the option (see the module comment).
    pub fn gi_depth(&self) -> Option<u32> {
        if !self.gi_next() {
            return None;
        }
        let d = self.string_options.get("gi depth").and_then(AttrValue::as_f64)?;
        Some(d.clamp(0.0, u32::MAX as f64 - 1.0) as u32)
    }

    /// `"gi rays"` as written (GI rays per shading sample in mental ray); read, but it does
    /// not change mira's path engine (see the module comment).
    pub fn gi_rays(&self) -> Option<f64> {
        self.string_options.get("gi rays").and_then(AttrValue::as_f64)
    }

    /// `"iray" on`: mental ray's iray rendering mode (since 3.8; see the module comment).
    pub fn iray_mode(&self) -> bool {
        self.string_options.get("iray").and_then(AttrValue::as_bool).unwrap_or(false)
    }

    /// Whether the string options ask for mental ray's progressive, brute-force GI or iray
    /// rendering, which mira's path engine is (the automatic engine choice takes it).
    pub fn asks_for_path_tracing(&self) -> bool {
        self.progressive_mode() || self.gi_next() || self.iray_mode()
    }

    /// `"environment lighting mode"` as written; `None` where the scene does not set it (the
    /// path engine then lights with the environment as with [`EnvironmentLighting::Light`],
    /// as Iray does).
    pub fn environment_lighting(&self) -> Option<EnvironmentLighting> {
        let v = self.string_options.get("environment lighting mode")?;
        Some(match v {
            AttrValue::Str(s) if s.eq_ignore_ascii_case("off") => EnvironmentLighting::Off,
            AttrValue::Bool(false) => EnvironmentLighting::Off,
            _ => EnvironmentLighting::Light,
        })
    }

    /// `"light relative scale"` (default 1, negative read as 0): the factor on the light
    /// legacy (non-BSDF) shaders receive from physically calibrated lights; BSDF materials
    /// do not see it (see the module comment).
    pub fn light_relative_scale(&self) -> f64 {
        self.string_options.get("light relative scale").and_then(AttrValue::as_f64).map_or(1.0, |s| s.max(0.0))
    }

    /// `"environment lighting shadow"`: what the environment light's shadow rays do
    /// (absent or not understood: [`EnvironmentShadow::Transparent`], the latter with a
    /// warning from `crate::sanity`).
    pub fn environment_shadow(&self) -> EnvironmentShadow {
        self.string_options.get("environment lighting shadow").and_then(EnvironmentShadow::parse).unwrap_or_default()
    }

    /// How many directions one next-event estimate of the environment averages:
    /// max(1, ⌈2q⌉) for `"environment lighting quality"` q, at most
    /// [`MAX_ENVIRONMENT_SAMPLES`]; 1 without the option or for a value that is no
    /// finite number (a warning from `crate::sanity`).
    pub fn environment_samples(&self) -> u32 {
        let q = self.string_options.get("environment lighting quality").and_then(AttrValue::as_f64);
        match q {
            Some(q) if q.is_finite() => (2.0 * q).ceil().clamp(1.0, f64::from(MAX_ENVIRONMENT_SAMPLES)) as u32,
            _ => 1,
        }
    }

    /// `"environment lighting scale"`: the factor on the light the environment casts on
    /// surfaces (1 without the option; a colour is read as the mean of its channels, a
    /// negative or non-finite value as 1 — each with a warning from `crate::sanity`).
    pub fn environment_lighting_scale(&self) -> f64 {
        let s = match self.string_options.get("environment lighting scale") {
            Some(AttrValue::Floats(v)) if !v.is_empty() => v.iter().take(3).sum::<f64>() / v.len().min(3) as f64,
            Some(v) => v.as_f64().unwrap_or(1.0),
            None => 1.0,
        };
        if s.is_finite() && s >= 0.0 {
            s
        } else {
            1.0
        }
    }
}
