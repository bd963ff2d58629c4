//! Tone mapping for display images: `mia_exposure_photographic`, `mia_exposure_simple`, or
//! plain sRGB encoding.
//!
//! `mia_exposure_photographic` (mental ray's architectural library, also Iray's built-in
//! tonemapper through the camera's `mip_*` attributes): exposure from ISO, shutter and
//! f-number (or a plain gain when `film_iso` is 0), white balance, highlight burn, saturation,
//! black crush, then display gamma. The exposure constant is the reflected-light meter's
//! (K = 12.5 with 18 % middle grey): the "sunny 16" defaults (ISO 100, 1/100 s, f/16) map an
//! average luminance of 3 200 cd/m² to 0.18.

use shade::Rgb;

/// Parameters of `mia_exposure_photographic`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photographic {
    /// Pixel value → cd/m² (photographic mode) or plain gain (arbitrary mode).
    pub cm2_factor: f32,
    /// White balance.
    pub whitepoint: Rgb,
    /// Film speed; 0 switches to arbitrary mode.
    pub film_iso: f32,
    /// Shutter as 1/x seconds (100 = 1/100 s).
    pub camera_shutter: f32,
    /// Aperture f-number.
    pub f_number: f32,
    /// Edge darkening strength.
    pub vignetting: f32,
    /// 0: highlights compressed (Reinhard), 1: linear.
    pub burn_highlights: f32,
    /// Shadow contrast.
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
            whitepoint: Rgb::ONE,
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

/// Luminance weights of `mia_exposure_photographic`'s saturation and black-crush steps.
fn lum(c: Rgb) -> f32 {
    0.176204 * c.x + 0.812985 * c.y + 0.0108109 * c.z
}

impl Photographic {
    /// The exposure multiplier.
    pub fn exposure(&self) -> f32 {
        if self.film_iso > 0.0 {
            let seconds = 1.0 / self.camera_shutter.max(1e-9);
            0.18 / 12.5 * self.cm2_factor * self.film_iso * seconds / (self.f_number * self.f_number).max(1e-9)
        } else {
            self.cm2_factor
        }
    }

    /// Maps a linear colour to display values in [0, 1].
    pub fn map(&self, c: Rgb) -> Rgb {
        let wp = self.whitepoint / lum(self.whitepoint).max(1e-6);
        let mut c = (c * self.exposure() / wp).max(Rgb::ZERO);
        let b = self.burn_highlights;
        c = c * (c * b + Rgb::ONE) / (c + Rgb::ONE);
        let l = lum(c);
        c = Rgb::splat(l).lerp(c, self.saturation).max(Rgb::ZERO);
        let l = lum(c);
        if l < 1.0 {
            let s = l.max(0.0).sqrt();
            let p = 1.0 + 2.0 * self.crush_blacks;
            c = c * s + Rgb::new(c.x.powf(p), c.y.powf(p), c.z.powf(p)) * (1.0 - s);
        }
        let g = 1.0 / self.gamma.max(1e-3);
        Rgb::new(c.x.powf(g), c.y.powf(g), c.z.powf(g)).clamp(Rgb::ZERO, Rgb::ONE)
    }

    /// From the Iray camera attributes (`tm_tonemapper "mia_exposure_photographic"` and
    /// `mip_*`), Iray's defaults where absent.
    pub fn from_attributes(a: &scene::values::Attributes) -> Photographic {
        let f = |name: &str, default: f32| a.get(name).and_then(|v| v.as_f64()).map_or(default, |v| v as f32);
        let whitepoint = match a.get("mip_whitepoint") {
            Some(scene::values::AttrValue::Floats(v)) if v.len() >= 3 => {
                Rgb::new(v[0] as f32, v[1] as f32, v[2] as f32)
            }
            _ => Rgb::new(1.04287, 0.983863, 1.03358),
        };
        Photographic {
            cm2_factor: f("mip_cm2_factor", 1.0),
            whitepoint,
            film_iso: f("mip_film_iso", 100.0),
            camera_shutter: f("mip_camera_shutter", 0.125),
            f_number: f("mip_f_number", 8.0),
            vignetting: f("mip_vignetting", 0.0),
            burn_highlights: f("mip_burn_highlights", 0.0),
            crush_blacks: f("mip_crush_blacks", 0.25),
            saturation: f("mip_saturation", 1.0),
            gamma: f("mip_gamma", 2.2),
        }
    }
}

/// A display transform.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ToneMapper {
    /// sRGB encoding of the clamped linear value.
    Srgb,
    /// `mia_exposure_photographic`.
    Photographic(Photographic),
}

impl ToneMapper {
    /// The camera's tonemapper (Iray attributes), or plain sRGB.
    pub fn for_camera(c: &scene::Camera) -> ToneMapper {
        match c.attributes.get("tm_tonemapper").and_then(|v| v.as_str()) {
            Some("mia_exposure_photographic") => ToneMapper::Photographic(Photographic::from_attributes(&c.attributes)),
            _ => ToneMapper::Srgb,
        }
    }

    /// Display value in [0, 1] of a linear colour.
    pub fn map(&self, c: Rgb) -> Rgb {
        match self {
            ToneMapper::Srgb => Rgb::new(srgb(c.x), srgb(c.y), srgb(c.z)),
            ToneMapper::Photographic(p) => p.map(c),
        }
    }
}

/// The sRGB transfer function of a linear value, clamped to [0, 1].
pub fn srgb(v: f32) -> f32 {
    let v = v.clamp(0.0, 1.0);
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_known_values() {
        assert_eq!(srgb(0.0), 0.0);
        assert!((srgb(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb(0.18) - 0.461_356).abs() < 1e-5);
    }

    #[test]
    fn photographic_exposure_and_curve() {
        let p = Photographic::default();
        // Sunny 16: 3 200 cd/m² → 0.18 before the curve.
        assert!((p.exposure() * 3200.0 - 0.18).abs() < 1e-5);
        // Arbitrary mode: cm2_factor is the gain.
        let a = Photographic { film_iso: 0.0, cm2_factor: 2.5, ..p };
        assert_eq!(a.exposure(), 2.5);
        // burn 1 and crush 0, gamma 1: linear (below 1).
        let lin = Photographic { film_iso: 0.0, burn_highlights: 1.0, crush_blacks: 0.0, gamma: 1.0, ..p };
        let out = lin.map(Rgb::new(0.2, 0.4, 0.6));
        assert!((out - Rgb::new(0.2, 0.4, 0.6)).abs().max_element() < 1e-6, "{out}");
        // burn 0: Reinhard c / (1 + c).
        let reinhard = Photographic { burn_highlights: 0.0, ..lin };
        assert!((reinhard.map(Rgb::splat(3.0)).x - 0.75).abs() < 1e-6);
    }
}
