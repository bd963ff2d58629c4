//! The Architectural library's tone mappers, `mia_exposure_simple` and
//! `mia_exposure_photographic`: the curves, and the lens shaders that apply them to every
//! eye sample (mental ray applied them before pixel filtering; as camera output shaders or
//! Iray camera attributes the renderer applies the same curves to the finished pixels).
//!
//! Sources and the standing of each formula: `/work/notes/mia-details.md` §8–9. In short:
//! the order of operations and the defaults are documented; the knee curve of
//! `mia_exposure_simple` is mira's reading (a rational shoulder whose asymptote is 1 at the
//! default knee and compression); the exposure constant, white balance, luminance-based
//! burn, saturation and black crush of `mia_exposure_photographic` follow the public
//! re-implementations of Iray's equivalent tone mapper.

use glam::Vec3A;

use shader::{rgb, rgba};
use shader::{Color, Ctx, NodeId, ShaderImpl, Value};

/// CIE Y weights of the renderer's RGB used by the photographic mapper's burn, saturation
/// and crush steps.
pub fn cie_luminance(c: Vec3A) -> f32 {
    0.176204 * c.x + 0.812985 * c.y + 0.010_810_9 * c.z
}

/// `mia_exposure_simple`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Simple {
    /// Added first (negative: a black level).
    pub pedestal: f32,
    /// Multiplier.
    pub gain: f32,
    /// Where highlight compression starts (after the gain).
    pub knee: f32,
    /// Compression above the knee (0: none).
    pub compression: f32,
    /// Display gamma (1: none).
    pub gamma: f32,
}

impl Default for Simple {
    fn default() -> Simple {
        Simple { pedestal: 0.0, gain: 1.0, knee: 0.5, compression: 2.0, gamma: 2.2 }
    }
}

impl Simple {
    /// Maps a linear colour: `(c + pedestal) · gain`, above `knee` compressed to
    /// `knee + x/(1 + compression · x)` (x the excess; slope 1 at the knee, approaching
    /// `knee + 1/compression`), then `^(1/gamma)`.
    pub fn map(&self, c: Vec3A) -> Vec3A {
        let f = |v: f32| {
            let v = (v + self.pedestal) * self.gain;
            let v = if self.compression > 0.0 && v > self.knee {
                let x = v - self.knee;
                self.knee + x / (1.0 + self.compression * x)
            } else {
                v
            }
            .max(0.0);
            if self.gamma > 0.0 && self.gamma != 1.0 {
                v.powf(1.0 / self.gamma)
            } else {
                v
            }
        };
        Vec3A::new(f(c.x), f(c.y), f(c.z))
    }
}

/// `mia_exposure_photographic`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photographic {
    /// Pixel value → cd/m² (photographic mode) or plain gain (arbitrary mode).
    pub cm2_factor: f32,
    /// White balance: this colour maps to grey.
    pub whitepoint: Vec3A,
    /// Film speed; 0 switches to arbitrary mode.
    pub film_iso: f32,
    /// Shutter as 1/x seconds (100 = 1/100 s).
    pub camera_shutter: f32,
    /// Aperture f-number.
    pub f_number: f32,
    /// Edge darkening: cos^vignetting of the angle to the optical axis.
    pub vignetting: f32,
    /// 0: highlights compressed like c/(1 + c), 1: linear.
    pub burn_highlights: f32,
    /// Shadow toe (0: linear).
    pub crush_blacks: f32,
    /// 0: grey, 1: unchanged.
    pub saturation: f32,
    /// Display gamma.
    pub gamma: f32,
}

impl Default for Photographic {
    fn default() -> Photographic {
        Photographic {
            cm2_factor: 1.0,
            whitepoint: Vec3A::ONE,
            film_iso: 100.0,
            camera_shutter: 100.0,
            f_number: 16.0,
            vignetting: 0.0,
            burn_highlights: 0.0,
            crush_blacks: 0.25,
            saturation: 1.0,
            gamma: 2.2,
        }
    }
}

/// The photographic exposure constant: pixel value × cm2_factor × C × ISO × t / N² is the
/// exposed value (C = 18 / (106 · 15.4), the constant of Iray-compatible implementations;
/// the sunny-16 defaults bring a sunlit 18 % grey card to about 0.25).
pub const EXPOSURE_CONSTANT: f32 = 18.0 / (106.0 * 15.4);

impl Photographic {
    /// The exposure multiplier.
    pub fn exposure(&self) -> f32 {
        if self.film_iso > 0.0 {
            EXPOSURE_CONSTANT * self.cm2_factor * self.film_iso
                / (self.camera_shutter.max(1e-9) * (self.f_number * self.f_number).max(1e-9))
        } else {
            self.cm2_factor
        }
    }

    /// Maps a linear colour to display values; `cos_axis` is the cosine of the pixel's ray
    /// with the optical axis (for vignetting; 1 at the centre).
    pub fn map(&self, c: Vec3A, cos_axis: f32) -> Vec3A {
        let inv_wp = Vec3A::new(
            if self.whitepoint.x > 0.0 { 1.0 / self.whitepoint.x } else { 1.0 },
            if self.whitepoint.y > 0.0 { 1.0 / self.whitepoint.y } else { 1.0 },
            if self.whitepoint.z > 0.0 { 1.0 / self.whitepoint.z } else { 1.0 },
        );
        let mut scale = inv_wp * self.exposure() / cie_luminance(inv_wp).max(1e-6);
        if self.vignetting != 0.0 {
            scale *= cos_axis.clamp(0.0, 1.0).powf(self.vignetting);
        }
        let mut c = (c * scale).max(Vec3A::ZERO);
        let b = self.burn_highlights.max(1e-4);
        let l = cie_luminance(c);
        c *= (l * b + 1.0) / (l + 1.0);
        let l = cie_luminance(c);
        c = Vec3A::splat(l) + (c - Vec3A::splat(l)) * self.saturation;
        c = c.max(Vec3A::ZERO);
        let p = 1.0 + 2.0 * self.crush_blacks;
        let l = cie_luminance(c);
        if p > 1.0 && l < 1.0 {
            let s = l.max(0.0).sqrt();
            c = c * s + Vec3A::new(c.x.powf(p), c.y.powf(p), c.z.powf(p)) * (1.0 - s);
        }
        let g = 1.0 / self.gamma.max(1e-3);
        Vec3A::new(c.x.powf(g), c.y.powf(g), c.z.powf(g))
    }
}

/// `mia_exposure_simple` as a lens shader: maps each eye sample.
pub static EXPOSURE_SIMPLE: ShaderImpl = ShaderImpl {
    name: "mia_exposure_simple",
    params: &["pedestal", "gain", "knee", "compression", "gamma"],
    run: exposure_simple,
    ..ShaderImpl::PLAIN
};

/// The simple mapper of node `n`'s parameters.
pub fn simple_of(ctx: &mut Ctx, n: NodeId) -> Simple {
    Simple {
        pedestal: ctx.scalar(n, 0),
        gain: ctx.scalar(n, 1),
        knee: ctx.scalar(n, 2),
        compression: ctx.scalar(n, 3),
        gamma: ctx.scalar(n, 4),
    }
}

fn eye(ctx: &mut Ctx) -> Color {
    let (org, dir) = (ctx.state.org, ctx.state.dir);
    ctx.trace_eye(org, dir)
}

fn exposure_simple(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let c = eye(ctx);
    let m = simple_of(ctx, n);
    *out = Value::Color(rgba(m.map(rgb(c)), c.w));
    true
}

/// `mia_exposure_photographic` as a lens shader.
pub static EXPOSURE_PHOTOGRAPHIC: ShaderImpl = ShaderImpl {
    name: "mia_exposure_photographic",
    params: &[
        "cm2_factor",
        "whitepoint",
        "film_iso",
        "camera_shutter",
        "f_number",
        "vignetting",
        "burn_highlights",
        "crush_blacks",
        "saturation",
        "gamma",
    ],
    run: exposure_photographic,
    ..ShaderImpl::PLAIN
};

/// The photographic mapper of node `n`'s parameters.
pub fn photographic_of(ctx: &mut Ctx, n: NodeId) -> Photographic {
    Photographic {
        cm2_factor: ctx.scalar(n, 0),
        whitepoint: rgb(ctx.color(n, 1)),
        film_iso: ctx.scalar(n, 2),
        camera_shutter: ctx.scalar(n, 3),
        f_number: ctx.scalar(n, 4),
        vignetting: ctx.scalar(n, 5),
        burn_highlights: ctx.scalar(n, 6),
        crush_blacks: ctx.scalar(n, 7),
        saturation: ctx.scalar(n, 8),
        gamma: ctx.scalar(n, 9),
    }
}

fn exposure_photographic(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let c = eye(ctx);
    let m = photographic_of(ctx, n);
    let axis = ctx.shading().world_to_camera.transform_vector3a(ctx.state.dir);
    let cos_axis = (-axis.z).clamp(0.0, 1.0);
    *out = Value::Color(rgba(m.map(rgb(c), cos_axis), c.w));
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_mapping_known_values() {
        let m = Simple::default();
        // Below the knee: gain and gamma only.
        let c = m.map(Vec3A::splat(0.25));
        assert!((c.x - 0.25f32.powf(1.0 / 2.2)).abs() < 1e-6);
        // Above: 0.5 + x/(1 + 2x); 1.5 → 0.5 + 1/3.
        let lin = Simple { gamma: 1.0, ..m };
        assert!((lin.map(Vec3A::splat(1.5)).x - (0.5 + 1.0 / 3.0)).abs() < 1e-6);
        // The asymptote at the defaults is 1.
        assert!(lin.map(Vec3A::splat(1e6)).x < 1.0 && lin.map(Vec3A::splat(1e6)).x > 0.9999);
        // Pedestal and gain come first.
        let p = Simple { pedestal: -0.1, gain: 2.0, compression: 0.0, gamma: 1.0, ..m };
        assert!((p.map(Vec3A::splat(0.3)).x - 0.4).abs() < 1e-6);
    }

    #[test]
    fn photographic_known_values() {
        let p = Photographic::default();
        // Sunny 16: k = C · 100 / (100 · 256).
        assert!((p.exposure() - EXPOSURE_CONSTANT / 256.0).abs() < 1e-12);
        // Arbitrary mode, burn 1, crush 0, gamma 1: linear.
        let lin =
            Photographic { film_iso: 0.0, cm2_factor: 2.0, burn_highlights: 1.0, crush_blacks: 0.0, gamma: 1.0, ..p };
        let c = lin.map(Vec3A::new(0.1, 0.2, 0.3), 1.0);
        assert!((c - Vec3A::new(0.2, 0.4, 0.6)).abs().max_element() < 1e-6, "{c}");
        // Burn 0 on a grey of luminance 3: 3 / (1 + 3) = 0.75 (luminance-based: grey stays grey).
        let burn = Photographic { burn_highlights: 0.0, cm2_factor: 1.0, ..lin };
        let c = burn.map(Vec3A::splat(3.0), 1.0);
        assert!((c - Vec3A::splat(0.75)).abs().max_element() < 5e-4, "{c}");
        // Saturation 0: grey of the CIE luminance.
        let grey = Photographic { saturation: 0.0, ..lin };
        let c = grey.map(Vec3A::new(0.5, 0.0, 0.0), 1.0);
        assert!((c - Vec3A::splat(2.0 * 0.5 * 0.176204)).abs().max_element() < 1e-6, "{c}");
        // Vignetting: cos^v.
        let v = Photographic { vignetting: 2.0, ..lin };
        assert!((v.map(Vec3A::splat(0.1), 0.5).x - 0.2 * 0.25).abs() < 1e-6);
        // Crush: below luminance 1, lerp(c^p, c, √L).
        let crush = Photographic { crush_blacks: 0.5, ..lin };
        let x: f32 = 0.04 * 2.0;
        let l = x; // a grey: luminance equals the value (weights sum to 1)
        let want = x * l.sqrt() + x * x * (1.0 - l.sqrt());
        assert!((crush.map(Vec3A::splat(0.04), 1.0).x - want).abs() < 1e-5);
    }
}
