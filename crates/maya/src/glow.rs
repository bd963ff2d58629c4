//! `maya_shaderglow` / `adskMayaShaderGlow`: Maya's shader glow as a post pass on the
//! finished image (an output shader: it runs on the film after rendering, outside the
//! shader model; the renderer calls [`apply`]).
//!
//! Parameters (Maya's shaderGlow node): `glowType` and `haloType` (0 none, 1 linear,
//! 2 exponential, 3 ball; 4 lens flare and 5 rim halo are drawn as linear), `glowColor`
//! and `haloColor`, `glowIntensity` and `haloIntensity`, `glowSpread` and `haloSpread`
//! (the radius as a fraction of the image width), `glowEccentricity` and
//! `haloEccentricity` (the exponential falloff's length as a fraction of the radius),
//! `threshold` (source values at or below it do not glow) and `autoExposure` (on: the
//! source is divided by its brightest value, so the brightest point glows with the
//! intensity as given).
//!
//! The source is the glow frame buffer the output statement reads when the shaders wrote
//! it (the materials' glow goes to `frame buffer n` when `maya_state`'s
//! `glowColorBuffer` names it, and exports list that buffer in the glow's output
//! statement); else the materials' glow ([`BUFFER`]: what the shading engine stores of
//! each directly seen material's `outGlowColor`, `glowIntensity` × its colour, as Maya's
//! glow comes from the materials) where some material glows; otherwise the rendered colour
//! where it is brighter than white (any channel above max(1, `threshold`)), by its excess
//! over that level. Each of glow and halo adds
//! intensity × colour × (source ⊛ k), where k is its radial kernel over the pixel
//! distance d, normalised to sum to 1 (the energy added is intensity × the source's):
//! linear 1 − d/R, exponential exp(−d / (eccentricity·R)), ball 1 − (d/R)², all zero
//! beyond R.

use mi::ast::{Param, Value};

/// The shape of a glow's or halo's falloff.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Falloff {
    /// No glow (type 0).
    None,
    /// 1 − d/R (type 1; also types 4 and 5).
    Linear,
    /// exp(−d / (e·R)) (type 2) with the eccentricity e.
    Exponential(f32),
    /// 1 − (d/R)² (type 3).
    Ball,
}

impl Falloff {
    fn of(kind: i64, eccentricity: f32) -> Falloff {
        match kind {
            0 => Falloff::None,
            2 => Falloff::Exponential(eccentricity.max(1e-3)),
            3 => Falloff::Ball,
            _ => Falloff::Linear,
        }
    }

    /// The kernel's unnormalised weight at distance `d` from the source, radius `r`
    /// (both in pixels).
    pub fn weight(self, d: f32, r: f32) -> f32 {
        if d > r {
            return 0.0;
        }
        let x = d / r.max(1e-6);
        match self {
            Falloff::None => 0.0,
            Falloff::Linear => 1.0 - x,
            Falloff::Exponential(e) => (-x / e).exp(),
            Falloff::Ball => 1.0 - x * x,
        }
    }
}

/// One of the two effects (glow or halo).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Effect {
    /// Its falloff.
    pub falloff: Falloff,
    /// Linear RGB tint.
    pub color: [f32; 3],
    /// Intensity (the share of the source's energy it spreads).
    pub intensity: f32,
    /// Radius as a fraction of the image width.
    pub spread: f32,
}

/// A `maya_shaderglow` call's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Glow {
    /// The glow.
    pub glow: Effect,
    /// The halo.
    pub halo: Effect,
    /// Source values at or below it do not glow.
    pub threshold: f32,
    /// Divide the source by its brightest value.
    pub auto_exposure: bool,
}

/// The name of the user frame buffer Maya materials write their glow to
/// (`glowIntensity` × their colour, `outGlowColor`) when the camera runs a shader glow:
/// the shading engine stores it for every eye-ray hit (zero where the material does not
/// glow), so that the buffer holds the mean glow of each pixel's samples that stop at a
/// surface (the path engine stores the same at its camera rays' hits). The renderer
/// resolves the name to the frame buffer the state shader's `glowColorBuffer` names
/// ([`color_buffer`]) when the options declare it, else to a buffer of this name.
pub const BUFFER: &str = "maya_glow";

/// Whether `name` is the glow output shader (either family).
pub fn is_glow(name: &str) -> bool {
    matches!(name, "maya_shaderglow" | "adskMayaShaderGlow")
}

/// Whether `name` is Maya exports' state shader (`maya_state`, `adskFrameBufferState`).
pub fn is_state(name: &str) -> bool {
    matches!(name, "maya_state" | "adskFrameBufferState")
}

/// The number n of the user frame buffer (`frame buffer n`) the state shader's parameters
/// `params` name for the materials' glow (`glowColorBuffer`), if they name one: the
/// shading engine writes each directly seen material's glow there instead of [`BUFFER`],
/// and a glow output shader whose output statement lists `fb<n>` spreads it (mental ray
/// gives an output shader the buffers its statement lists). Negative numbers name none.
pub fn color_buffer(params: &[Param]) -> Option<u32> {
    match &params.iter().rev().find(|p| p.name.text == "glowColorBuffer")?.value {
        Value::Num(n) => u32::try_from(n.as_f64() as i64).ok(),
        _ => None,
    }
}

impl Glow {
    /// The settings of a call's parameters (Maya's defaults where absent: a linear glow of
    /// white, intensity 1, spread 0.05, eccentricity 0.1; no halo (intensity 1, spread 0.3
    /// when typed); threshold 0; auto exposure on).
    pub fn from_params(params: &[Param]) -> Glow {
        let last = |name: &str| params.iter().rev().find(|p| p.name.text == name).map(|p| &p.value);
        let num = |name: &str, default: f32| match last(name) {
            Some(Value::Num(n)) => n.as_f64() as f32,
            Some(Value::Bool(b)) => f32::from(u8::from(*b)),
            _ => default,
        };
        let int = |name: &str, default: i64| match last(name) {
            Some(Value::Num(n)) => n.as_f64() as i64,
            _ => default,
        };
        let rgb = |name: &str| match last(name) {
            Some(Value::Tuple(t)) if t.len() >= 3 => [0, 1, 2].map(|i| t[i].as_f64() as f32),
            Some(Value::Num(n)) => [n.as_f64() as f32; 3],
            _ => [1.0; 3],
        };
        let effect = |prefix: &str, kind: i64, spread: f32| Effect {
            falloff: Falloff::of(int(&format!("{prefix}Type"), kind), num(&format!("{prefix}Eccentricity"), 0.1)),
            color: rgb(&format!("{prefix}Color")),
            intensity: num(&format!("{prefix}Intensity"), 1.0),
            spread: num(&format!("{prefix}Spread"), spread),
        };
        Glow {
            glow: effect("glow", 1, 0.05),
            halo: effect("halo", 0, 0.3),
            threshold: num("threshold", 0.0),
            auto_exposure: !matches!(last("autoExposure"), Some(Value::Bool(false))),
        }
    }

    /// Adds the glow to `image` (RGBA per pixel, rows from the top, `width` × `height`;
    /// alpha unchanged), from the glow buffer `buffer` (RGB, same layout) or, without one,
    /// from the image's pixels brighter than white.
    pub fn apply(&self, image: &mut [[f32; 4]], buffer: Option<&[[f32; 3]]>, width: usize, height: usize) {
        let mut src: Vec<[f32; 3]> = match buffer {
            Some(b) => b.iter().map(|c| c.map(|v| (v - self.threshold).max(0.0))).collect(),
            None => {
                let level = self.threshold.max(1.0);
                image.iter().map(|c| [c[0], c[1], c[2]].map(|v| (v - level).max(0.0))).collect()
            }
        };
        if self.auto_exposure {
            let peak = src.iter().flat_map(|c| c.iter().copied()).fold(0.0f32, f32::max);
            if peak > 0.0 {
                src.iter_mut().for_each(|c| *c = c.map(|v| v / peak));
            }
        }
        for effect in [self.glow, self.halo] {
            spread(effect, &src, image, width, height);
        }
    }
}

/// The normalised kernel of `effect` on an image `width` pixels wide: its half size
/// and weights ((2h+1)², rows first).
pub fn kernel(effect: Effect, width: usize) -> (usize, Vec<f32>) {
    let r = (effect.spread * width as f32).max(0.5);
    let h = r.floor() as usize;
    let n = 2 * h + 1;
    let mut k = vec![0.0f32; n * n];
    for (i, w) in k.iter_mut().enumerate() {
        let (dx, dy) = ((i % n) as f32 - h as f32, (i / n) as f32 - h as f32);
        *w = effect.falloff.weight(dx.hypot(dy), r);
    }
    let sum: f32 = k.iter().sum();
    if sum > 0.0 {
        k.iter_mut().for_each(|w| *w /= sum);
    }
    (h, k)
}

fn spread(effect: Effect, src: &[[f32; 3]], image: &mut [[f32; 4]], width: usize, height: usize) {
    if effect.falloff == Falloff::None || effect.intensity == 0.0 {
        return;
    }
    let (h, k) = kernel(effect, width);
    let n = 2 * h + 1;
    let tint = effect.color.map(|c| c * effect.intensity);
    for (i, s) in src.iter().enumerate() {
        if s.iter().all(|&v| v <= 0.0) {
            continue;
        }
        let (x, y) = ((i % width) as isize, (i / width) as isize);
        for (j, w) in k.iter().enumerate().filter(|(_, w)| **w > 0.0) {
            let (tx, ty) = (x + (j % n) as isize - h as isize, y + (j / n) as isize - h as isize);
            if tx < 0 || ty < 0 || tx >= width as isize || ty >= height as isize {
                continue;
            }
            let p = &mut image[ty as usize * width + tx as usize];
            for ((pc, t), sc) in p.iter_mut().zip(tint).zip(s) {
                *pc += w * t * sc;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const W: usize = 41;

    /// The glow's radius in pixels.
    const R: f32 = 6.5;

    /// A glow of `falloff` with radius [`R`] pixels on a 41×41 image, auto exposure off.
    fn glow(falloff: Falloff, intensity: f32) -> Glow {
        let effect = Effect { falloff, color: [1.0, 0.5, 0.25], intensity, spread: R / W as f32 };
        Glow { glow: effect, halo: Effect { falloff: Falloff::None, ..effect }, threshold: 0.0, auto_exposure: false }
    }

    /// One glowing pixel (value 2) in the middle of a black image's glow buffer: what the
    /// glow adds to each pixel.
    fn single_pixel(g: &Glow) -> Vec<[f32; 4]> {
        let mut buffer = vec![[0.0f32; 3]; W * W];
        buffer[20 * W + 20] = [2.0; 3];
        let mut image = vec![[0.0f32; 4]; W * W];
        g.apply(&mut image, Some(&buffer), W, W);
        image
    }

    /// The energy spread equals intensity × colour × source (the kernel sums to 1), and
    /// each pixel gets the falloff at its distance relative to the centre's, for every
    /// falloff (tolerance 1e-5 relative).
    #[test]
    fn a_single_bright_pixel_spreads_its_energy_by_the_falloff() {
        for falloff in [Falloff::Linear, Falloff::Exponential(0.3), Falloff::Ball] {
            let image = single_pixel(&glow(falloff, 0.5));
            for (c, tint) in [1.0f32, 0.5, 0.25].iter().enumerate() {
                let total: f32 = image.iter().map(|p| p[c]).sum();
                let want = 0.5 * tint * 2.0;
                assert!((total - want).abs() < 1e-5 * want.max(1.0), "{falloff:?} channel {c}: {total} vs {want}");
            }
            let centre = image[20 * W + 20][0];
            for (dx, dy) in [(1usize, 0usize), (3, 0), (2, 2), (0, 5), (4, 4), (6, 0), (7, 0)] {
                let d = (dx as f32).hypot(dy as f32);
                let got = image[(20 + dy) * W + 20 + dx][0] / centre;
                let want = falloff.weight(d, R) / falloff.weight(0.0, R);
                assert!((got - want).abs() < 1e-5, "{falloff:?} at d = {d}: {got} vs {want}");
            }
            // By hand: linear at d = 3 of R = 6.5 is 1 − 3/6.5 of the centre's; nothing
            // past R.
            if falloff == Falloff::Linear {
                assert!((image[20 * W + 23][0] / centre - (1.0 - 3.0 / 6.5)).abs() < 1e-5);
            }
            assert_eq!(image[20 * W + 27][0], 0.0, "{falloff:?} reaches past its radius");
        }
    }

    /// A halo adds its own share on top of the glow: both energies sum.
    #[test]
    fn glow_and_halo_add_their_energies() {
        let mut g = glow(Falloff::Linear, 0.5);
        g.halo = Effect { falloff: Falloff::Ball, color: [1.0; 3], intensity: 0.25, spread: 10.0 / W as f32 };
        let total: f32 = single_pixel(&g).iter().map(|p| p[0]).sum();
        assert!((total - (0.5 + 0.25) * 2.0).abs() < 1e-5, "{total}");
    }

    /// Without a glow buffer, an image with nothing brighter than white is unchanged bit
    /// for bit; one pixel at 3 glows by its excess over 1 (auto exposure makes it 1).
    #[test]
    fn only_pixels_brighter_than_white_glow_without_a_buffer() {
        let mut image: Vec<[f32; 4]> = (0..W * W).map(|i| [(i % 7) as f32 / 6.0, 0.5, 1.0, 1.0]).collect();
        let before = image.clone();
        let mut g = glow(Falloff::Linear, 1.0);
        g.auto_exposure = true;
        g.apply(&mut image, None, W, W);
        assert_eq!(image, before);
        image[20 * W + 20] = [3.0, 0.0, 0.0, 1.0];
        let before = image.clone();
        g.apply(&mut image, None, W, W);
        let added: f32 = image.iter().zip(&before).map(|(a, b)| a[0] - b[0]).sum();
        assert!((added - 1.0).abs() < 1e-4, "{added}");
        assert!(image.iter().zip(&before).all(|(a, b)| a[3] == b[3] && a[1] == b[1]), "alpha and green untouched");
    }

    /// Parameters as exports write them, and Maya's defaults where absent.
    #[test]
    fn parameters_and_defaults() {
        let text = r#"shader "g" "maya_shaderglow" ("glowType" 2, "glowIntensity" 0.3, "glowEccentricity" 0.2,
            "haloType" 3, "haloColor" 1 0 0, "threshold" 0.1, "autoExposure" off)"#;
        let parsed = mi::parse_str("g.mi", text);
        let Some(mi::ast::Item::Shader(def)) = parsed.items.first() else { panic!("{:?}", parsed.items) };
        let mi::ast::ShaderItem::Call { params, .. } = &def.list.0[0] else { panic!() };
        let g = Glow::from_params(params);
        assert_eq!(g.glow.falloff, Falloff::Exponential(0.2));
        assert_eq!((g.glow.intensity, g.glow.spread, g.glow.color), (0.3, 0.05, [1.0; 3]));
        assert_eq!((g.halo.falloff, g.halo.color, g.halo.spread), (Falloff::Ball, [1.0, 0.0, 0.0], 0.3));
        assert!((g.threshold - 0.1).abs() < 1e-7 && !g.auto_exposure);
        let defaults = Glow::from_params(&[]);
        assert_eq!((defaults.glow.falloff, defaults.halo.falloff), (Falloff::Linear, Falloff::None));
        assert!(defaults.auto_exposure && is_glow("adskMayaShaderGlow"));
    }

    /// `glowColorBuffer` as the state shaders of exports write it: a buffer number, none
    /// when absent or negative.
    #[test]
    fn the_state_shaders_glow_buffer() {
        let text = r#"shader "s" "adskFrameBufferState" ("passAlphaThrough" off, "glowColorBuffer" 3)
            shader "t" "maya_state" ("glowColorBuffer" -1)
            shader "u" "maya_state" ("passDepthThrough" on)"#;
        let parsed = mi::parse_str("s.mi", text);
        let found: Vec<Option<u32>> = parsed
            .items
            .iter()
            .map(|item| {
                let mi::ast::Item::Shader(def) = item else { panic!("{item:?}") };
                let mi::ast::ShaderItem::Call { decl, params, .. } = &def.list.0[0] else { panic!() };
                assert!(is_state(&decl.text));
                color_buffer(params)
            })
            .collect();
        assert_eq!(found, vec![Some(3), None, None]);
    }
}
