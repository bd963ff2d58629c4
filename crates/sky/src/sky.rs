//! The daylight sky model of Preetham, Shirley and Smits with mental ray's parameters onto it
//! (see the `mia` crate's `sky` module for the parameters' meaning and sources).

use std::cell::RefCell;
use std::f32::consts::PI;

use glam::Vec3A;

pub use crate::settings::{color_tweak, effective_saturation, luminance, sky_frame, turbidity, unit_conversion};
use crate::sun::{sun_illuminance, xyz_to_rgb, SUN_ANGULAR_RADIUS};

/// sin 18°: the sky is dark when the sun is this far (as a sine) below the horizon.
const TWILIGHT: f32 = 0.309_017;

/// Directions are lifted to at least this up component for the sky model.
const MIN_UP: f32 = 0.001;

/// Coefficients of the Perez all-weather sky distribution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perez {
    /// Darkening (A < 0) or brightening towards the horizon.
    pub a: f32,
    /// Gradient of the horizon term.
    pub b: f32,
    /// Strength of the circumsolar region.
    pub c: f32,
    /// Width of the circumsolar region.
    pub d: f32,
    /// Backscattered light.
    pub e: f32,
}

impl Perez {
    /// F(θ, γ) for cos θ (clamped to 0.001, the horizon), γ and cos γ.
    pub fn f(&self, cos_theta: f32, gamma: f32, cos_gamma: f32) -> f32 {
        let ct = cos_theta.max(MIN_UP);
        (1.0 + self.a * (self.b / ct).exp()) * (1.0 + self.c * (self.d * gamma).exp() + self.e * cos_gamma * cos_gamma)
    }

    /// Preetham et al.'s coefficients for luminance Y at turbidity `t`.
    pub fn luminance(t: f32) -> Perez {
        Perez {
            a: 0.1787 * t - 1.4630,
            b: -0.3554 * t + 0.4275,
            c: -0.0227 * t + 5.3251,
            d: 0.1206 * t - 2.5771,
            e: -0.0670 * t + 0.3703,
        }
    }

    /// Preetham et al.'s coefficients for chromaticity x.
    pub fn chroma_x(t: f32) -> Perez {
        Perez {
            a: -0.0193 * t - 0.2592,
            b: -0.0665 * t + 0.0008,
            c: -0.0004 * t + 0.2125,
            d: -0.0641 * t - 0.8989,
            e: -0.0033 * t + 0.0452,
        }
    }

    /// Preetham et al.'s coefficients for chromaticity y.
    pub fn chroma_y(t: f32) -> Perez {
        Perez {
            a: -0.0167 * t - 0.2608,
            b: -0.0950 * t + 0.0092,
            c: -0.0079 * t + 0.2102,
            d: -0.0441 * t - 1.6537,
            e: -0.0109 * t + 0.0529,
        }
    }
}

/// Preetham et al.'s daylight sky for one turbidity and sun position, in the sky frame
/// (+Z the zenith).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Daylight {
    /// Turbidity (2 very clear … 10 hazy; mia goes to 17).
    pub turbidity: f32,
    /// Unit direction to the sun, at or above the horizon.
    pub sun: Vec3A,
    /// Distributions of Y, x and y.
    pub perez: [Perez; 3],
    /// Zenith luminance (cd/m²) and chromaticity x, y.
    pub zenith: [f32; 3],
}

impl Daylight {
    /// The sky for turbidity `t` and unit `sun` (lifted to the horizon if below it).
    pub fn new(t: f32, sun: Vec3A) -> Daylight {
        let sun = lift(sun);
        let ts = sun.z.clamp(-1.0, 1.0).acos();
        let chi = (4.0 / 9.0 - t / 120.0) * (PI - 2.0 * ts);
        let y_z = 1000.0 * ((4.0453 * t - 4.9710) * chi.tan() - 0.2155 * t + 2.4192).max(0.0);
        let (t2, ts2, ts3) = (t * t, ts * ts, ts * ts * ts);
        let x_z = t2 * (0.00166 * ts3 - 0.00375 * ts2 + 0.00209 * ts)
            + t * (-0.02903 * ts3 + 0.06377 * ts2 - 0.03202 * ts + 0.00394)
            + (0.11693 * ts3 - 0.21196 * ts2 + 0.06052 * ts + 0.25886);
        let y_zc = t2 * (0.00275 * ts3 - 0.00610 * ts2 + 0.00317 * ts)
            + t * (-0.04214 * ts3 + 0.08970 * ts2 - 0.04153 * ts + 0.00516)
            + (0.15346 * ts3 - 0.26756 * ts2 + 0.06670 * ts + 0.26688);
        Daylight {
            turbidity: t,
            sun,
            perez: [Perez::luminance(t), Perez::chroma_x(t), Perez::chroma_y(t)],
            zenith: [y_z, x_z, y_zc],
        }
    }

    /// Component `k` (0 Y, 1 x, 2 y) at unit `dir` relative to the zenith:
    /// F(θ, γ) / F(0, θ_s).
    pub fn relative(&self, k: usize, dir: Vec3A) -> f32 {
        let cos_g = dir.dot(self.sun).clamp(-1.0, 1.0);
        let cos_s = self.sun.z.clamp(-1.0, 1.0);
        let p = &self.perez[k];
        p.f(dir.z, cos_g.acos(), cos_g) / p.f(1.0, cos_s.acos(), cos_s)
    }

    /// Luminance (cd/m²) and chromaticity x, y at unit `dir` (lifted to the horizon if
    /// below it).
    pub fn xyy(&self, dir: Vec3A) -> Vec3A {
        let d = lift(dir);
        Vec3A::new(
            self.zenith[0] * self.relative(0, d),
            self.zenith[1] * self.relative(1, d),
            self.zenith[2] * self.relative(2, d),
        )
    }

    /// Radiance at unit `dir` as linear Rec.709 RGB in cd/m² (its luminance is Y).
    pub fn rgb(&self, dir: Vec3A) -> Vec3A {
        let v = self.xyy(dir);
        if v.x <= 0.0 || v.z <= 0.0 {
            return Vec3A::ZERO;
        }
        let xyz = Vec3A::new(v.y / v.z * v.x, v.x, (1.0 - v.y - v.z) / v.z * v.x);
        xyz_to_rgb(xyz).max(Vec3A::ZERO)
    }

    /// The sky's illuminance on a horizontal plane (lux, as RGB: its luminance is lux),
    /// ∫ L cos θ dω over the upper hemisphere by a 24 × 48 cosine-weighted grid;
    /// remembered per thread for the last few skies.
    pub fn horizontal_illuminance(&self) -> Vec3A {
        thread_local! {
            static CACHE: RefCell<Vec<([u32; 8], Vec3A)>> = const { RefCell::new(Vec::new()) };
        }
        let p = self.perez[0];
        let key = [self.turbidity, self.sun.z, p.a, p.b, p.c, p.d, p.e, self.zenith[0]].map(f32::to_bits);
        if let Some(v) = CACHE.with(|c| c.borrow().iter().find(|(k, _)| *k == key).map(|e| e.1)) {
            return v;
        }
        // The integral does not depend on the sun's azimuth: put it in the XZ plane.
        let mut sky = *self;
        sky.sun = Vec3A::new((1.0 - self.sun.z * self.sun.z).max(0.0).sqrt(), 0.0, self.sun.z);
        let (n, m) = (24, 48);
        let mut sum = Vec3A::ZERO;
        for i in 0..n {
            let r = ((i as f32 + 0.5) / n as f32).sqrt();
            let z = (1.0 - r * r).max(0.0).sqrt();
            for j in 0..m {
                let phi = 2.0 * PI * (j as f32 + 0.5) / m as f32;
                sum += sky.rgb(Vec3A::new(r * phi.cos(), r * phi.sin(), z));
            }
        }
        let e = sum * (PI / (n * m) as f32);
        CACHE.with(|c| {
            let mut c = c.borrow_mut();
            if c.len() >= 8 {
                c.remove(0);
            }
            c.push((key, e));
        });
        e
    }
}

/// `d` with its up component raised to at least 0.001, renormalised.
pub(crate) fn lift(d: Vec3A) -> Vec3A {
    if d.z >= MIN_UP {
        return d;
    }
    let h = Vec3A::new(d.x, d.y, 0.0);
    let len = h.length();
    let h = if len > 0.0 { h / len } else { Vec3A::X };
    h * (1.0 - MIN_UP * MIN_UP).sqrt() + Vec3A::new(0.0, 0.0, MIN_UP)
}

/// Hermite smoothstep of `x` between the edges `e0` and `e1`.
pub(crate) fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// How much of the daylit sky remains for a sun whose up component (sky frame) is `z`:
/// 1 above the horizon, ((z + s)/s)⁴ below it, s = sin 18°.
pub fn night_factor(z: f32) -> f32 {
    if z >= 0.0 {
        1.0
    } else if z <= -TWILIGHT {
        0.0
    } else {
        ((z + TWILIGHT) / TWILIGHT).powi(4)
    }
}

/// What a [`PhysicalSky`]'s radiance takes from its parameters alone, whatever the
/// direction: computed once ([`PhysicalSky::setup`]) for many lookups.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkySetup {
    /// Turbidity (2 + haze).
    pub turbidity: f32,
    /// Unit direction to the sun in the sky frame (+Z up), not lifted.
    pub sun_real: Vec3A,
    /// How much of the daylit sky remains ([`night_factor`]).
    pub night: f32,
    /// The sun lifted to at least the horizon.
    pub sun: Vec3A,
    /// The daylight model.
    pub day: Daylight,
    /// What its luminance is scaled by (mode 2).
    pub scale: f32,
    /// The glow's and the disk's gains.
    pub gains: (f32, f32),
}

/// The two terms of a sky's radiance that cost most: the sun's illuminance on a plane
/// facing it and the sky's on a horizontal plane (lux, as RGB).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyLight {
    /// The sun's illuminance ([`sun_illuminance`]).
    pub sun: Vec3A,
    /// The sky's illuminance on a horizontal plane ([`Daylight::horizontal_illuminance`]).
    pub sky_horizontal: Vec3A,
}

impl SkySetup {
    /// The light terms, exactly.
    pub fn light(&self) -> SkyLight {
        SkyLight { sun: sun_illuminance(self.turbidity, self.sun.z), sky_horizontal: self.day.horizontal_illuminance() }
    }
}

/// `mia_physicalsky`'s parameters (those the environment uses).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhysicalSky {
    /// Scales the sky, ground, sun disk and glow (not `night_color`).
    pub multiplier: f32,
    /// RGB per lux (0 0 0: 1/80 000).
    pub rgb_unit_conversion: Vec3A,
    /// 0 (clear) … 15; turbidity 2 + haze.
    pub haze: f32,
    /// −1 (blue) … 1 (red).
    pub redblueshift: f32,
    /// 0 (grey) … 2.
    pub saturation: f32,
    /// −10 (horizon straight down) … 10 (at the zenith); 0 level.
    pub horizon_height: f32,
    /// Width of the sky–ground blend below the horizon, tenths of the up component.
    pub horizon_blur: f32,
    /// Albedo of the ground below the horizon.
    pub ground_color: Vec3A,
    /// The least the sky gives, output units.
    pub night_color: Vec3A,
    /// World direction towards the sun (zero: the zenith).
    pub sun_direction: Vec3A,
    /// Brightness of the visible sun disk (0: none).
    pub sun_disk_intensity: f32,
    /// Size of the visible disk, × the real sun's (the glow reaches 10 × that).
    pub sun_disk_scale: f32,
    /// Brightness of the glow around the disk.
    pub sun_glow_intensity: f32,
    /// +Y is up (off: +Z).
    pub y_is_up: bool,
    /// 0 the model's luminance; 1 `zenith_luminance`; 2 `diffuse_horizontal_illuminance`.
    pub sky_luminance_mode: i32,
    /// The zenith's luminance in mode 1, cd/m².
    pub zenith_luminance: f32,
    /// The sky's illuminance on a horizontal plane in mode 2, lux.
    pub diffuse_horizontal_illuminance: f32,
    /// Perez A … E for the luminance; all zero: the model's.
    pub perez: [f32; 5],
    /// Disk and glow deliver the sun's illuminance × `sun_disk_intensity`.
    pub physically_scaled_sun: bool,
}

impl Default for PhysicalSky {
    /// The declaration's defaults (the sun at the zenith).
    fn default() -> PhysicalSky {
        PhysicalSky {
            multiplier: 1.0,
            rgb_unit_conversion: Vec3A::splat(1e-4),
            haze: 0.0,
            redblueshift: 0.0,
            saturation: 1.0,
            horizon_height: 0.0,
            horizon_blur: 0.1,
            ground_color: Vec3A::splat(0.2),
            night_color: Vec3A::ZERO,
            sun_direction: Vec3A::ZERO,
            sun_disk_intensity: 1.0,
            sun_disk_scale: 4.0,
            sun_glow_intensity: 1.0,
            y_is_up: false,
            sky_luminance_mode: 0,
            zenith_luminance: 0.0,
            diffuse_horizontal_illuminance: 0.0,
            perez: [0.0; 5],
            physically_scaled_sun: false,
        }
    }
}

impl PhysicalSky {
    /// The direction to the sun in the sky frame (not lifted).
    pub fn sun_in_frame(&self) -> Vec3A {
        let s = if self.sun_direction.length_squared() > 0.0 {
            self.sun_direction
        } else if self.y_is_up {
            Vec3A::Y
        } else {
            Vec3A::Z
        };
        sky_frame(s.normalize(), self.y_is_up, self.horizon_height)
    }

    /// The daylight model with the overrides applied, and the factor the sky's luminance
    /// is scaled by (mode 2).
    pub fn daylight(&self, sun: Vec3A) -> (Daylight, f32) {
        let mut day = Daylight::new(turbidity(self.haze), sun);
        if self.perez.iter().any(|&v| v != 0.0) {
            let [a, b, c, d, e] = self.perez;
            day.perez[0] = Perez { a, b, c, d, e };
        }
        let mut scale = 1.0;
        match self.sky_luminance_mode {
            1 => day.zenith[0] = self.zenith_luminance.max(0.0),
            2 => {
                let e = luminance(day.horizontal_illuminance());
                scale = if e > 0.0 { self.diffuse_horizontal_illuminance.max(0.0) / e } else { 0.0 };
            }
            _ => {}
        }
        (day, scale)
    }

    /// The multipliers of the glow's and the disk's profiles (see the module comment).
    fn sun_gains(&self, glow_radius: f32) -> (f32, f32) {
        let glow = 2.0 * self.sun_glow_intensity.max(0.0);
        let disk = 100.0 * self.sun_disk_intensity.max(0.0);
        if !self.physically_scaled_sun {
            return (glow, disk);
        }
        // ∫ glow · (1 − x/R)³ · 2π sin x dx over [0, R], by the midpoint rule.
        let steps = 64;
        let h = glow_radius / steps as f32;
        let profile: f32 = (0..steps)
            .map(|i| {
                let x = (i as f32 + 0.5) * h;
                (1.0 - x / glow_radius).powi(3) * 2.0 * PI * x.sin() * h
            })
            .sum();
        let target = PI * self.sun_disk_intensity.max(0.0);
        let glow_integral = glow * profile;
        let (glow, rest) = if glow_integral > 0.5 * target {
            (glow * 0.5 * target / glow_integral, 0.5 * target)
        } else {
            (glow, target - glow_integral)
        };
        let disk_area = 2.0 * PI * (1.0 - (glow_radius / 10.0).cos());
        (glow, if disk_area > 0.0 { rest / disk_area } else { 0.0 })
    }

    /// The sun disk and glow at `angle` (radians) from the sun, × the sun's illuminance,
    /// for turbidity `t` (zero beyond 10 × the disk's radius).
    pub fn sun_profile(&self, angle: f32, t: f32) -> f32 {
        let radius = SUN_ANGULAR_RADIUS * self.sun_disk_scale * 10.0;
        if radius <= 0.0 || angle >= radius {
            return 0.0;
        }
        self.profile_with(angle, t, self.sun_gains(radius))
    }

    /// [`PhysicalSky::sun_profile`] with the gains [`PhysicalSky::sun_gains`] gave.
    fn profile_with(&self, angle: f32, t: f32, (glow, disk): (f32, f32)) -> f32 {
        let radius = SUN_ANGULAR_RADIUS * self.sun_disk_scale * 10.0;
        if radius <= 0.0 || angle >= radius {
            return 0.0;
        }
        let k = (1.0 - angle / radius) * 10.0;
        (k / 10.0).powi(3) * glow + smoothstep(8.5, 9.5 + t / 50.0, k) * disk
    }

    /// What [`PhysicalSky::radiance`] computes from the parameters alone, for any
    /// direction (see [`SkySetup`]).
    pub fn setup(&self) -> SkySetup {
        let radius = SUN_ANGULAR_RADIUS * self.sun_disk_scale * 10.0;
        let gains = if radius > 0.0 { self.sun_gains(radius) } else { (0.0, 0.0) };
        self.setup_with_gains(gains)
    }

    /// [`PhysicalSky::setup`] taking the sun's gains from `other`, the setup of a sky
    /// whose disk and glow parameters (`sun_disk_scale`, `sun_disk_intensity`,
    /// `sun_glow_intensity`, `physically_scaled_sun`) are this one's.
    pub fn setup_like(&self, other: &SkySetup) -> SkySetup {
        self.setup_with_gains(other.gains)
    }

    fn setup_with_gains(&self, gains: (f32, f32)) -> SkySetup {
        let turbidity = turbidity(self.haze);
        let sun_real = self.sun_in_frame();
        let night = night_factor(sun_real.z);
        let sun = lift(sun_real);
        let (day, scale) = self.daylight(sun);
        SkySetup { turbidity, sun_real, night, sun, day, scale, gains }
    }

    /// Whether the daylight model is Preetham's own (no Perez coefficients or luminance
    /// mode given): then its light terms depend on the turbidity and the sun's height only.
    pub fn is_plain_daylight(&self) -> bool {
        self.perez.iter().all(|&v| v == 0.0) && self.sky_luminance_mode == 0
    }

    /// What the sky shows in world direction `dir` (unit), output units (see the module
    /// comment), without alpha.
    pub fn radiance(&self, dir: Vec3A) -> Vec3A {
        let setup = self.setup();
        self.radiance_in(&setup, dir, &mut || setup.light())
    }

    /// [`PhysicalSky::radiance`] with the parameters' part computed beforehand (`setup`,
    /// this sky's or one that equals it), and `light` giving the sun's illuminance and the
    /// sky's horizontal illuminance (asked for only within the sun's disk and glow and
    /// below the horizon: [`SkySetup::light`], or an approximation of it).
    pub fn radiance_in(&self, setup: &SkySetup, dir: Vec3A, light: &mut dyn FnMut() -> SkyLight) -> Vec3A {
        let t = setup.turbidity;
        let d = sky_frame(dir, self.y_is_up, self.horizon_height);
        let (s_real, night, day, scale) = (setup.sun_real, setup.night, &setup.day, setup.scale);
        let mut lit: Option<SkyLight> = None;
        let mut c = Vec3A::ZERO;
        if night > 0.0 {
            c = day.rgb(lift(d)) * (PI * scale);
            // The angle by atan2: acos of a dot product near 1 loses the tiny disk in f32.
            let profile = self.profile_with(d.cross(s_real).length().atan2(d.dot(s_real)), t, setup.gains);
            if profile != 0.0 {
                c += lit.get_or_insert_with(&mut *light).sun * profile;
            }
            c *= night;
        }
        let mut night_weight = 1.0;
        if d.z <= 0.0 {
            let ground = if night > 0.0 {
                let l = *lit.get_or_insert_with(&mut *light);
                let e = l.sky_horizontal * scale + l.sun * s_real.z.max(0.0);
                self.ground_color.max(Vec3A::ZERO) * e * night
            } else {
                Vec3A::ZERO
            };
            let blur = self.horizon_blur / 10.0;
            let w = if blur > 0.0 { smoothstep(0.0, 1.0, (-d.z / blur).min(1.0)) } else { 1.0 };
            c = c + (ground - c) * w;
            night_weight = 1.0 - w;
        }
        let c = c * unit_conversion(self.rgb_unit_conversion) * self.multiplier;
        let c = color_tweak(c, effective_saturation(self.saturation, self.haze), self.redblueshift);
        c.max(self.night_color * night_weight)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(elevation_deg: f32, azimuth_deg: f32) -> Vec3A {
        let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
        Vec3A::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
    }

    #[test]
    fn perez_is_one_at_the_zenith_and_symmetric_about_the_sun() {
        for t in [2.0, 4.0, 8.0, 12.0] {
            for sun_el in [5.0, 30.0, 60.0, 85.0] {
                let day = Daylight::new(t, dir(sun_el, 40.0));
                for k in 0..3 {
                    // Exactly 1 at the zenith (by construction), to rounding.
                    assert!((day.relative(k, Vec3A::Z) - 1.0).abs() < 1e-6);
                    // Mirror images across the sun's vertical plane agree to 1e-5 relative.
                    for (el, da) in [(10.0, 30.0), (45.0, 100.0), (70.0, 170.0)] {
                        let a = day.relative(k, dir(el, 40.0 + da));
                        let b = day.relative(k, dir(el, 40.0 - da));
                        assert!((a - b).abs() <= 1e-5 * a.abs(), "T {t} sun {sun_el} k {k}: {a} {b}");
                    }
                }
            }
        }
    }

    #[test]
    fn known_values_of_the_model() {
        // Zenith luminance, T = 2, sun 45° up: χ = (4/9 − 1/60)·π/2, Y_z = 3.1196 tan χ + 1.9882
        // kcd/m² = 4.472 kcd/m².
        let day = Daylight::new(2.0, dir(45.0, 0.0));
        assert!((day.zenith[0] - 4472.0).abs() < 5.0, "{}", day.zenith[0]);
        // Its chromaticity is bluish: x_z, y_z below D65's (0.3127, 0.3290).
        assert!(day.zenith[1] < 0.30 && day.zenith[2] < 0.31, "{:?}", day.zenith);
        // The luminance of the RGB is Y.
        let d = dir(30.0, 120.0);
        assert!((luminance(day.rgb(d)) - day.xyy(d).x).abs() < 1e-3 * day.xyy(d).x);
        // Clear-sky horizontal illuminance with the sun 45° up: the model gives about
        // 25 000 lux (measured clear skies: 15 000 – 25 000).
        let e = luminance(day.horizontal_illuminance());
        assert!((15_000.0..30_000.0).contains(&e), "{e}");
    }

    #[test]
    fn clear_sky_brightens_towards_the_sun_and_towards_the_horizon() {
        let day = Daylight::new(2.5, dir(30.0, 0.0));
        // At 30° elevation, luminance grows as the azimuth nears the sun's from 100° (83°
        // from the sun; the sky is darkest about 90° from the sun, backscatter brightens
        // the opposite side a little).
        let mut last = 0.0;
        for az in [100.0, 75.0, 45.0, 15.0, 5.0] {
            let y = day.xyy(dir(30.0, az)).x;
            assert!(y > last, "azimuth {az}: {y} ≤ {last}");
            last = y;
        }
        // At 90° azimuth from the sun, luminance grows towards the horizon (by ≥ 5 % each
        // step down).
        let mut last = 0.0;
        for el in [80.0, 60.0, 40.0, 20.0, 10.0, 3.0] {
            let y = day.xyy(dir(el, 90.0)).x;
            assert!(y > 1.05 * last, "elevation {el}: {y} vs {last}");
            last = y;
        }
        // And the sky is blue there: b > r.
        let c = day.rgb(dir(60.0, 180.0));
        assert!(c.z > c.x, "{c}");
    }

    #[test]
    fn haze_whitens_the_sky() {
        let sat = |c: Vec3A| (c.max_element() - c.min_element()) / c.max_element();
        let clear = Daylight::new(turbidity(0.0), dir(40.0, 0.0)).rgb(dir(60.0, 180.0));
        let hazy = Daylight::new(turbidity(6.0), dir(40.0, 0.0)).rgb(dir(60.0, 180.0));
        assert!(sat(hazy) < 0.8 * sat(clear), "{clear} {hazy}");
    }

    #[test]
    fn y_is_up_swaps_the_axes() {
        let z_up = PhysicalSky { sun_direction: Vec3A::new(0.3, -0.4, 0.6), ..PhysicalSky::default() };
        let y_up = PhysicalSky { sun_direction: Vec3A::new(0.3, 0.6, -0.4), y_is_up: true, ..z_up };
        for d in [Vec3A::new(0.1, 0.2, 0.9), Vec3A::new(-0.7, 0.1, 0.2), Vec3A::new(0.2, 0.5, -0.4)] {
            let d = d.normalize();
            let a = z_up.radiance(d);
            let b = y_up.radiance(Vec3A::new(d.x, d.z, d.y));
            assert!((a - b).abs().max_element() <= 1e-6 * a.max_element().max(1.0), "{a} {b}");
        }
        // And Y up really is up: straight up (+Y) is sky, +Z is the horizon.
        let up = y_up.radiance(Vec3A::Y);
        assert!(up.z > up.x, "{up}");
    }

    #[test]
    fn below_the_horizon_is_the_lit_ground() {
        let sky = PhysicalSky {
            sun_direction: dir(50.0, 0.0),
            horizon_blur: 0.0,
            ground_color: Vec3A::new(0.3, 0.2, 0.1),
            ..PhysicalSky::default()
        };
        let t = turbidity(0.0);
        let s = dir(50.0, 0.0);
        let e = Daylight::new(t, s).horizontal_illuminance() + sun_illuminance(t, s.z) * s.z;
        let want = Vec3A::new(0.3, 0.2, 0.1) * e * 1e-4;
        for d in [dir(-1.0, 10.0), dir(-30.0, 200.0), -Vec3A::Z] {
            let got = sky.radiance(d);
            assert!((got - want).abs().max_element() < 1e-4 * want.max_element(), "{got} {want}");
        }
        // Around 10 000 lux × 0.3 × 1e-4 + sun: between 2 and 5 in red.
        assert!((2.0..5.0).contains(&want.x), "{want}");
        // Blurred: the sky just below the horizon, the ground a blur-width down.
        let blurred = PhysicalSky { horizon_blur: 1.0, ..sky };
        let just_below = blurred.radiance(dir(-0.01, 90.0));
        let horizon = blurred.radiance(dir(0.5, 90.0));
        assert!((just_below - horizon).abs().max_element() < 0.05 * horizon.max_element(), "{just_below} {horizon}");
        let deep = blurred.radiance(dir(-8.0, 90.0)); // sin 8° > 0.1
        assert!((deep - want).abs().max_element() < 1e-4 * want.max_element());
        // A raised horizon: 5° up is ground when the horizon is at sin⁻¹ 0.1 ≈ 5.7°.
        let raised = PhysicalSky { horizon_height: 1.0, ..sky };
        let (g, ground) = (raised.radiance(dir(5.0, 90.0)), raised.radiance(-Vec3A::Z));
        assert!((g - ground).abs().max_element() < 1e-6 * ground.max_element(), "{g} {ground}");
        assert!(raised.radiance(dir(6.0, 90.0)).z > ground.z);
    }

    #[test]
    fn night_colour_after_dusk() {
        let night = Vec3A::new(0.01, 0.02, 0.05);
        let sky = PhysicalSky { sun_direction: dir(-25.0, 0.0), night_color: night, ..PhysicalSky::default() };
        for d in [Vec3A::Z, dir(10.0, 0.0), dir(40.0, 180.0)] {
            assert_eq!(sky.radiance(d), night);
        }
        // The ground is black at night (no night colour below a sharp horizon).
        assert_eq!(PhysicalSky { horizon_blur: 0.0, ..sky }.radiance(-Vec3A::Z), Vec3A::ZERO);
        // Twilight: darker than the day, brighter than the night, above the floor.
        let day = PhysicalSky { sun_direction: dir(2.0, 0.0), ..sky }.radiance(Vec3A::Z);
        let dusk = PhysicalSky { sun_direction: dir(-4.0, 0.0), ..sky }.radiance(Vec3A::Z);
        assert!(dusk.x < day.x && dusk.z < day.z && dusk.z > night.z, "{day} {dusk}");
        assert_eq!(night_factor(-TWILIGHT), 0.0);
        assert!((night_factor(-TWILIGHT / 2.0) - 1.0 / 16.0).abs() < 1e-6);
    }

    #[test]
    fn linear_in_multiplier_and_the_unit_conversion() {
        let a = PhysicalSky { sun_direction: dir(35.0, 60.0), ..PhysicalSky::default() };
        let b = PhysicalSky { multiplier: 3.0, ..a };
        let c = PhysicalSky { rgb_unit_conversion: Vec3A::ZERO, ..a };
        for d in [dir(20.0, 60.0), dir(35.0, 60.0), dir(70.0, 300.0), dir(-20.0, 0.0)] {
            let (x, y) = (a.radiance(d), b.radiance(d));
            assert!((y - 3.0 * x).abs().max_element() <= 1e-5 * y.max_element(), "{x} {y}");
            // 0 0 0: 1/80 000 instead of 1/10 000.
            let z = c.radiance(d);
            assert!((z * 8.0 - x).abs().max_element() <= 1e-5 * x.max_element(), "{x} {z}");
        }
    }

    #[test]
    fn sun_disk_and_glow() {
        let s = dir(40.0, 0.0);
        let sky = PhysicalSky { sun_direction: s, ..PhysicalSky::default() };
        let e = luminance(sun_illuminance(2.0, s.z)) * 1e-4;
        // The disk centre: the sky + 2 × glow + 100 × the sun.
        let centre = luminance(sky.radiance(s));
        assert!(centre > 100.0 * e && centre < 103.0 * e + 10.0, "{centre} {e}");
        // Outside 10 × the disk radius: no glow; inside the glow, brighter than without.
        let no_sun = PhysicalSky { sun_disk_intensity: 0.0, sun_glow_intensity: 0.0, ..sky };
        let far = dir(40.0, 12.0); // 9.2° away; the glow ends at 10.7°
        assert!(luminance(sky.radiance(far)) > luminance(no_sun.radiance(far)));
        let beyond = dir(40.0, 16.0);
        assert_eq!(sky.radiance(beyond), no_sun.radiance(beyond));
        // Physically scaled: disk + glow integrate to the sun's illuminance (±3 %).
        let phys = PhysicalSky { physically_scaled_sun: true, ..sky };
        let radius = SUN_ANGULAR_RADIUS * 4.0 * 10.0;
        let (n, m) = (400, 64);
        let mut sum = 0.0;
        let (b1, b2) = s.any_orthonormal_pair();
        for i in 0..n {
            let a = (i as f32 + 0.5) / n as f32 * radius;
            for j in 0..m {
                let phi = 2.0 * PI * (j as f32 + 0.5) / m as f32;
                let d = s * a.cos() + (b1 * phi.cos() + b2 * phi.sin()) * a.sin();
                let extra = luminance(phys.radiance(d) - no_sun.radiance(d));
                sum += extra * a.sin() * (radius / n as f32) * (2.0 * PI / m as f32);
            }
        }
        // Output units: π × the sun's illuminance × the conversion.
        assert!((sum / (PI * e) - 1.0).abs() < 0.03, "{} vs {}", sum, PI * e);
    }

    #[test]
    fn saturation_and_red_blue_shift() {
        let c = Vec3A::new(0.2, 0.4, 0.8);
        let grey = color_tweak(c, 0.0, 0.0);
        assert!((grey - Vec3A::splat(luminance(c))).abs().max_element() < 1e-6);
        assert_eq!(color_tweak(c, 1.0, 0.0), c);
        let warm = color_tweak(c, 1.0, 0.5);
        assert!((warm - Vec3A::new(0.3, 0.4, 0.4)).abs().max_element() < 1e-6);
        assert_eq!(effective_saturation(1.0, 15.0), 1.0);
        assert!((effective_saturation(0.5, 15.0) - 0.125).abs() < 1e-6);
        assert_eq!(effective_saturation(0.5, 0.0), 0.5);
    }
}
