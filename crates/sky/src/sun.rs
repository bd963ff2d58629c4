//! The sun: its spectrum through the atmosphere as colour and illuminance, and its disk
//! (see the `mia` crate's `sun` module for the sources).

use std::cell::RefCell;
use std::f32::consts::PI;

use glam::Vec3A;

use crate::settings::{color_tweak, effective_saturation, luminance, sky_frame, turbidity, unit_conversion};

/// The sun's colour temperature outside the atmosphere, kelvin (the manual's value).
pub const SUN_TEMPERATURE: f32 = 5900.0;

/// The sun's illuminance outside the atmosphere on a plane facing it, lux (the manual's
/// calibration).
pub const EXTRATERRESTRIAL_ILLUMINANCE: f32 = 127_500.0;

/// The sun's angular radius, radians (0.2665°: its mean apparent diameter is 0.533°).
pub const SUN_ANGULAR_RADIUS: f32 = 0.00465;

/// Thickness of the ozone layer, cm (Preetham et al.'s value).
const OZONE_CM: f32 = 0.35;

/// The CIE 1931 2° colour-matching functions x̄, ȳ, z̄ at wavelength `nm`, from the
/// multi-lobe piecewise-Gaussian fit of Wyman, Sloan and Shirley, "Simple Analytic
/// Approximations to the CIE XYZ Color Matching Functions" (JCGT 2(2), 2013).
pub fn cie_cmf(nm: f32) -> Vec3A {
    let g = |mu: f32, s1: f32, s2: f32| {
        let t = (nm - mu) / if nm < mu { s1 } else { s2 };
        (-0.5 * t * t).exp()
    };
    Vec3A::new(
        1.056 * g(599.8, 37.9, 31.0) + 0.362 * g(442.0, 16.0, 26.7) - 0.065 * g(501.1, 20.4, 26.2),
        0.821 * g(568.8, 46.9, 40.5) + 0.286 * g(530.9, 16.3, 31.1),
        1.217 * g(437.0, 11.8, 36.0) + 0.681 * g(459.0, 26.0, 13.8),
    )
}

/// CIE XYZ (D65 white) → linear Rec.709 RGB, applied to `xyz`.
pub fn xyz_to_rgb(xyz: Vec3A) -> Vec3A {
    Vec3A::new(
        3.240_97 * xyz.x - 1.537_383 * xyz.y - 0.498_611 * xyz.z,
        -0.969_244 * xyz.x + 1.875_968 * xyz.y + 0.041_555 * xyz.z,
        0.055_630 * xyz.x - 0.203_977 * xyz.y + 1.056_972 * xyz.z,
    )
}

/// Planck's law at `nm` and `kelvin`, without its constant factor.
fn planck(nm: f32, kelvin: f32) -> f32 {
    const HC_K: f32 = 1.438_777e7; // nm·K
    let l = f64::from(nm);
    (l.powi(-5) / ((f64::from(HC_K) / (l * f64::from(kelvin))).exp() - 1.0) * 1e15) as f32
}

/// Relative optical air mass for a sun `cos_zenith` from the zenith (Kasten 1966, the
/// formula Preetham et al. use): 1 overhead, about 38 at the horizon.
pub fn air_mass(cos_zenith: f32) -> f32 {
    let c = cos_zenith.clamp(0.0, 1.0);
    let z_deg = c.acos().to_degrees();
    1.0 / (c + 0.15 * (93.885 - z_deg).powf(-1.253))
}

/// Ozone's absorption coefficient at `nm`, cm⁻¹: the Chappuis band as a Gaussian (see the
/// module comment).
fn ozone_k(nm: f32) -> f32 {
    let t = (nm - 600.0) / 55.0;
    0.12 * (-0.5 * t * t).exp()
}

/// The fraction of the sun's light at `nm` that crosses air mass `m` at turbidity `t`.
pub fn transmittance(nm: f32, t: f32, m: f32) -> f32 {
    let um = nm * 1e-3;
    let rayleigh = 0.008735 * um.powf(-4.08);
    let beta = (0.04608 * t - 0.04586).max(0.0);
    let aerosol = beta * um.powf(-1.3);
    let ozone = ozone_k(nm) * OZONE_CM;
    (-(rayleigh + aerosol + ozone) * m).exp()
}

/// XYZ of the black-body sun through air mass `m` (0: outside the atmosphere) at
/// turbidity `t`, relative units.
fn sun_xyz(t: f32, m: f32) -> Vec3A {
    let mut sum = Vec3A::ZERO;
    let mut nm = 380.0;
    while nm <= 780.0 {
        let tau = if m > 0.0 { transmittance(nm, t, m) } else { 1.0 };
        sum += cie_cmf(nm) * (planck(nm, SUN_TEMPERATURE) * tau);
        nm += 5.0;
    }
    sum
}

thread_local! {
    static SUN_CACHE: RefCell<Vec<([u32; 2], Vec3A)>> = const { RefCell::new(Vec::new()) };
}

/// The sun's light arriving on a plane facing it, linear Rec.709 RGB whose luminance is
/// lux, for turbidity `t` and the sun `cos_zenith` from the zenith (clamped to 0.001: the
/// sun on the horizon). Remembered per thread for the last few arguments.
pub fn sun_illuminance(t: f32, cos_zenith: f32) -> Vec3A {
    let c = cos_zenith.clamp(0.001, 1.0);
    let key = [t.to_bits(), c.to_bits()];
    if let Some(v) = SUN_CACHE.with(|s| s.borrow().iter().find(|(k, _)| *k == key).map(|e| e.1)) {
        return v;
    }
    let outside = sun_xyz(t, 0.0);
    let xyz = sun_xyz(t, air_mass(c)) * (EXTRATERRESTRIAL_ILLUMINANCE / outside.y);
    let rgb = xyz_to_rgb(xyz).max(Vec3A::ZERO);
    SUN_CACHE.with(|s| {
        let mut s = s.borrow_mut();
        if s.len() >= 8 {
            s.remove(0);
        }
        s.push((key, rgb));
    });
    rgb
}

/// `mia_physicalsun`'s parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhysicalSun {
    /// Off: no light.
    pub on: bool,
    /// Scales the light.
    pub multiplier: f32,
    /// RGB per lux (0 0 0: 1/80000 each).
    pub rgb_unit_conversion: Vec3A,
    /// 0 (clear) … 15 (heavy haze); turbidity 2 + haze.
    pub haze: f32,
    /// −1 (blue) … 1 (red): scales red by 1 + shift and blue by 1 − shift.
    pub redblueshift: f32,
    /// 0 (grey) … 2; 1 leaves the colour.
    pub saturation: f32,
    /// Tilts the horizon: −10 straight down … 10 at the zenith (0: level).
    pub horizon_height: f32,
    /// Shadow softness: 1 the real sun's disk, 0 hard shadows.
    pub shadow_softness: f32,
    /// Shadow rays for soft shadows (0 or 1: hard shadows).
    pub samples: i32,
    /// +Y is up (off: +Z).
    pub y_is_up: bool,
    /// 1: the sun's illuminance is `direct_normal_illuminance` instead of the model's.
    pub illuminance_mode: i32,
    /// Illuminance on a plane facing the sun in mode 1, lux.
    pub direct_normal_illuminance: f32,
}

impl Default for PhysicalSun {
    /// The declaration's defaults.
    fn default() -> PhysicalSun {
        PhysicalSun {
            on: true,
            multiplier: 1.0,
            rgb_unit_conversion: Vec3A::splat(1e-4),
            haze: 0.0,
            redblueshift: 0.0,
            saturation: 1.0,
            horizon_height: 0.0,
            shadow_softness: 1.0,
            samples: 8,
            y_is_up: false,
            illuminance_mode: 0,
            direct_normal_illuminance: 0.0,
        }
    }
}

impl PhysicalSun {
    /// The light's colour (output units: lux × `rgb_unit_conversion` × `multiplier`,
    /// saturation and red/blue shift applied) for `to_sun`, the world direction towards
    /// the sun; `None` when the sun is at or below the horizon, or the light is off.
    pub fn color(&self, to_sun: Vec3A) -> Option<Vec3A> {
        if !self.on || self.multiplier <= 0.0 {
            return None;
        }
        let s = sky_frame(to_sun, self.y_is_up, self.horizon_height);
        if s.z <= 0.0 {
            return None;
        }
        let t = turbidity(self.haze);
        let mut e = sun_illuminance(t, s.z);
        if self.illuminance_mode == 1 {
            let l = luminance(e);
            e = if l > 0.0 { e * (self.direct_normal_illuminance.max(0.0) / l) } else { Vec3A::ZERO };
        }
        let c = e * unit_conversion(self.rgb_unit_conversion) * self.multiplier;
        let c = color_tweak(c, effective_saturation(self.saturation, self.haze), self.redblueshift);
        (c.max_element() > 0.0).then_some(c)
    }

    /// The angular radius of the cone soft-shadow rays spread over, radians: the sun's
    /// own radius × `shadow_softness`, widened with haze (the manual says haze softens the
    /// shadows; by how much it does not say: mira doubles the radius at haze 15).
    pub fn shadow_cone(&self) -> f32 {
        SUN_ANGULAR_RADIUS * self.shadow_softness.max(0.0) * (1.0 + self.haze.clamp(0.0, 15.0) / 15.0)
    }
}

/// A direction inside the cone of half-angle `radius` around unit `axis`, uniform in
/// solid angle for (u, v) uniform in [0, 1)².
pub fn cone_direction(axis: Vec3A, radius: f32, u: f32, v: f32) -> Vec3A {
    let cos_max = radius.cos();
    let cos_a = 1.0 - u * (1.0 - cos_max);
    let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
    let phi = 2.0 * PI * v;
    let (b1, b2) = axis.any_orthonormal_pair();
    (axis * cos_a + (b1 * phi.cos() + b2 * phi.sin()) * sin_a).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_matching_fit_is_balanced_and_d65_like_black_bodies_are_white() {
        // Equal energy: x = y = 1/3 within 0.005 (the fit's error).
        let mut s = Vec3A::ZERO;
        let mut nm = 360.0;
        while nm <= 830.0 {
            s += cie_cmf(nm);
            nm += 1.0;
        }
        let (x, y) = (s.x / s.element_sum(), s.y / s.element_sum());
        assert!((x - 1.0 / 3.0).abs() < 0.005 && (y - 1.0 / 3.0).abs() < 0.005, "{x} {y}");
        // A 6504 K black body is close to D65 white in Rec.709: channels within 6 %.
        let mut bb = Vec3A::ZERO;
        let mut nm = 380.0;
        while nm <= 780.0 {
            bb += cie_cmf(nm) * planck(nm, 6504.0);
            nm += 5.0;
        }
        let rgb = xyz_to_rgb(bb / bb.y);
        assert!((rgb / rgb.max_element()).min_element() > 0.94, "{rgb}");
    }

    #[test]
    fn air_mass_is_one_overhead_and_about_38_at_the_horizon() {
        assert!((air_mass(1.0) - 1.0).abs() < 1e-3);
        assert!((air_mass(0.5) - 1.995).abs() < 0.01, "{}", air_mass(0.5)); // 60° from the zenith
        assert!((air_mass(0.0) - 36.5).abs() < 1.0, "{}", air_mass(0.0));
    }

    #[test]
    fn extraterrestrial_and_zenith_sun_illuminance() {
        // Outside the atmosphere: 127 500 lux exactly (the calibration), a warm white.
        let outside = xyz_to_rgb(sun_xyz(2.0, 0.0) * (EXTRATERRESTRIAL_ILLUMINANCE / sun_xyz(2.0, 0.0).y));
        assert!((luminance(outside) - EXTRATERRESTRIAL_ILLUMINANCE).abs() < 0.01 * EXTRATERRESTRIAL_ILLUMINANCE);
        assert!(outside.x > outside.z, "{outside}");
        // Overhead on a clear day (T = 2): about 100 000 lux, between 90 000 and 110 000.
        let e = luminance(sun_illuminance(2.0, 1.0));
        assert!((90_000.0..110_000.0).contains(&e), "{e}");
    }

    #[test]
    fn haze_dims_and_reddens_the_sun_and_so_does_a_low_sun() {
        let ratio = |c: Vec3A| c.x / c.z;
        let clear = sun_illuminance(2.0, 0.8);
        let hazy = sun_illuminance(12.0, 0.8);
        assert!(luminance(hazy) < 0.6 * luminance(clear), "{clear} {hazy}");
        assert!(ratio(hazy) > ratio(clear), "{clear} {hazy}");
        // Lowering the sun: red/blue grows monotonically, luminance falls.
        let mut last = (0.0, f32::INFINITY);
        for elevation in [90.0f32, 60.0, 30.0, 15.0, 5.0, 2.0] {
            let c = sun_illuminance(2.0, elevation.to_radians().sin());
            assert!(ratio(c) > last.0 && luminance(c) < last.1, "{elevation}°: {c}");
            last = (ratio(c), luminance(c));
        }
        assert!(last.0 > 2.0, "a sun 2° up is clearly orange: r/b = {}", last.0);
    }

    #[test]
    fn sun_light_is_linear_in_multiplier_and_off_below_the_horizon() {
        let sun = PhysicalSun::default();
        let up = Vec3A::new(0.3, 0.2, 0.9).normalize();
        let one = sun.color(up).unwrap();
        let two = PhysicalSun { multiplier: 2.0, ..sun }.color(up).unwrap();
        assert!((two - one * 2.0).abs().max_element() < 1e-5 * two.max_element());
        // Default units: lux × 1e-4.
        assert!((luminance(one) - 1e-4 * luminance(sun_illuminance(2.0, up.z))).abs() < 1e-4);
        assert!(sun.color(Vec3A::new(0.3, 0.2, -0.1).normalize()).is_none());
        assert!(PhysicalSun { on: false, ..sun }.color(up).is_none());
        // y_is_up: +Y is the zenith.
        let y_up = PhysicalSun { y_is_up: true, ..sun };
        let swapped = y_up.color(Vec3A::new(up.x, up.z, up.y)).unwrap();
        assert!((swapped - one).abs().max_element() < 1e-6);
        // Mode 1: the given illuminance, same colour.
        let fixed = PhysicalSun { illuminance_mode: 1, direct_normal_illuminance: 50_000.0, ..sun };
        assert!((luminance(fixed.color(up).unwrap()) - 5.0).abs() < 1e-3);
        // A raised horizon sets the sun earlier.
        let low = Vec3A::new(0.0, 0.99, 0.05).normalize();
        assert!(sun.color(low).is_some());
        assert!(PhysicalSun { horizon_height: 1.0, ..sun }.color(low).is_none());
    }

    #[test]
    fn shadow_rays_stay_inside_the_sun_cone() {
        let axis = Vec3A::new(0.2, -0.5, 0.8).normalize();
        let r = 0.05;
        let mut mean = Vec3A::ZERO;
        for i in 0..64 {
            let d = cone_direction(axis, r, (i as f32 + 0.5) / 64.0, ((i * 37) % 64) as f32 / 64.0);
            assert!((d.length() - 1.0).abs() < 1e-5);
            assert!(d.dot(axis) >= r.cos() - 1e-6);
            mean += d;
        }
        // Spread evenly around the axis: the mean direction is the axis.
        assert!(mean.normalize().dot(axis) > 0.99999);
    }
}
