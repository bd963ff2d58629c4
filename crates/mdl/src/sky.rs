//! MDL `::base::sun_and_sky`: Iray's daylight environment, the MDL port of mental ray's
//! `mia_physicalsky` (the `mia` library's), as an environment function (Iray's
//! `environment_function` options attribute, or a camera `environment` shader).
//!
//! **The model** is `mia_physicalsky`'s, parameter for parameter: the same Preetham sky,
//! ground, horizon blur, night colour, saturation and red/blue shift, and the sun disk and
//! glow (with `physically_scaled_sun`, disk and glow deliver `sun_disk_intensity` × the
//! sun's illuminance). The port has no `sun` light link (the direction is
//! `sun_direction`), no `use_background`, no luminance modes, no Perez overrides and no
//! aerial perspective.
//!
//! **Units**: the port's value is π × `mia_physicalsky`'s for the same parameters (the
//! public re-implementations of the MDL function multiply the mental ray sky by π at the
//! end). mental ray's Lambertian shaders show `diffuse × irradiance` without the 1/π, so a
//! mental ray sky of value S lights a white floor to π × mean(S); Iray shades physically,
//! albedo/π × irradiance, and the π keeps the two renderers' floors equal. With
//! `rgb_unit_conversion` c and `multiplier` m, a sky of luminance L (cd/m²) is π² L c m,
//! and the sun disk and glow of a physically scaled sun irradiate a plane facing them with
//! π² × `sun_disk_intensity` × E c m (E the sun's illuminance in lux), so that a white
//! Lambertian plane lit by that sun shows π × E c m × `sun_disk_intensity` × cos θ.
//!
//! **Defaults** differ from `mia_physicalsky`'s (Iray's dialect notes, §7.2 of
//! `Iray-dialect.md`): `multiplier` 0.025, `rgb_unit_conversion` 1/1500, `haze` 0.5,
//! `saturation` 0.5, `horizon_height` 0.001, `ground_color` 0.4, `sun_direction` (0,
//! 0.229271, 0.418882), `sun_disk_intensity` 0.01, `sun_disk_scale` 0.5, `y_is_up` and
//! `physically_scaled_sun` on.
//!
//! **The sun as a light**: a renderer that samples the sun separately (it is tiny: 0.27° ×
//! `sun_disk_scale`, the glow ten times that) takes [`SunAndSky::sky_radiance`] for the
//! environment and [`SunAndSky::sun`] for the disk and glow as one light of finite size;
//! the two add up to [`SunAndSky::radiance`] wherever the night colour does not show
//! (that is, wherever the daylit sky is brighter than it in every channel).

use std::f32::consts::PI;

use glam::Vec3A;

use shader::rgb;
use shader::{Color, Ctx, NodeId, ShaderImpl, Value};
use sky::sky::{color_tweak, effective_saturation, night_factor, turbidity, unit_conversion, PhysicalSky};
use sky::sun::{sun_illuminance, SUN_ANGULAR_RADIUS};

/// A `base::sun_and_sky` call's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunAndSky {
    /// Off: black everywhere.
    pub on: bool,
    /// The sky parameters the port shares with `mia_physicalsky`.
    pub sky: PhysicalSky,
}

/// The sun disk and its glow of a [`SunAndSky`] as one light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkySun {
    /// World direction towards the sun's centre (unit).
    pub direction: Vec3A,
    /// Angular radius of the cone that holds the disk and the glow (10 × the disk's),
    /// radians: outside it the sun adds nothing.
    pub cone_radius: f32,
    /// Angular radius of the visible disk, radians (0.00465 × `sun_disk_scale`).
    pub disk_radius: f32,
    /// Irradiance the disk and glow together deliver on a plane facing the sun, output
    /// units (linear RGB).
    pub irradiance: Vec3A,
}

impl Default for SunAndSky {
    /// The MDL declaration's defaults.
    fn default() -> SunAndSky {
        SunAndSky {
            on: true,
            sky: PhysicalSky {
                multiplier: 0.025,
                rgb_unit_conversion: Vec3A::splat(1.0 / 1500.0),
                haze: 0.5,
                redblueshift: 0.0,
                saturation: 0.5,
                horizon_height: 0.001,
                horizon_blur: 0.1,
                ground_color: Vec3A::splat(0.4),
                night_color: Vec3A::ZERO,
                sun_direction: Vec3A::new(0.0, 0.229_271, 0.418_882),
                sun_disk_intensity: 0.01,
                sun_disk_scale: 0.5,
                sun_glow_intensity: 1.0,
                y_is_up: true,
                physically_scaled_sun: true,
                ..PhysicalSky::default()
            },
        }
    }
}

impl SunAndSky {
    /// What the environment shows in world direction `dir` (unit), output units (π ×
    /// `mia_physicalsky`'s value, see the module comment).
    pub fn radiance(&self, dir: Vec3A) -> Vec3A {
        if !self.on {
            return Vec3A::ZERO;
        }
        self.sky.radiance(dir) * PI
    }

    /// [`Self::radiance`] without the sun disk and glow.
    pub fn sky_radiance(&self, dir: Vec3A) -> Vec3A {
        if !self.on {
            return Vec3A::ZERO;
        }
        PhysicalSky { sun_disk_intensity: 0.0, sun_glow_intensity: 0.0, ..self.sky }.radiance(dir) * PI
    }

    /// The sun disk and glow as one light; `None` when they add nothing (off, no disk,
    /// zero intensities or multiplier, or the sun 18° or more below the horizon).
    pub fn sun(&self) -> Option<SkySun> {
        let sky = &self.sky;
        if !self.on || sky.sun_disk_scale <= 0.0 || sky.multiplier <= 0.0 {
            return None;
        }
        if sky.sun_disk_intensity <= 0.0 && sky.sun_glow_intensity <= 0.0 {
            return None;
        }
        let t = turbidity(sky.haze);
        let s = sky.sun_in_frame();
        let night = night_factor(s.z);
        if night <= 0.0 {
            return None;
        }
        let disk_radius = SUN_ANGULAR_RADIUS * sky.sun_disk_scale;
        let cone_radius = disk_radius * 10.0;
        // ∫ profile(a) cos a dω over the cone, by the midpoint rule in the angle a (the
        // profile depends on nothing else); fine enough for the disk's smooth edge, which
        // spans a tenth of the cone.
        let steps = 4000;
        let h = cone_radius / steps as f32;
        let profile: f32 = (0..steps)
            .map(|i| {
                let a = (i as f32 + 0.5) * h;
                sky.sun_profile(a, t) * 2.0 * PI * a.sin() * a.cos() * h
            })
            .sum();
        let e = sun_illuminance(t, s.z) * (profile * night);
        let c = e * unit_conversion(sky.rgb_unit_conversion) * sky.multiplier;
        let c = color_tweak(c, effective_saturation(sky.saturation, sky.haze), sky.redblueshift) * PI;
        if c.max_element() <= 0.0 {
            return None;
        }
        let up = if sky.y_is_up { Vec3A::Y } else { Vec3A::Z };
        Some(SkySun { direction: sky.sun_direction.normalize_or(up), cone_radius, disk_radius, irradiance: c })
    }
}

/// `mdl::base::sun_and_sky (on, multiplier, rgb_unit_conversion, haze, redblueshift,
/// saturation, horizon_height, horizon_blur, ground_color, night_color, sun_direction,
/// sun_disk_intensity, sun_disk_scale, sun_glow_intensity, y_is_up,
/// physically_scaled_sun)`: the environment's radiance in the ray's direction
/// ([`SunAndSky::radiance`]), alpha 1.
pub static SUN_AND_SKY: ShaderImpl = ShaderImpl {
    name: "mdl::base::sun_and_sky",
    params: &[
        "on",
        "multiplier",
        "rgb_unit_conversion",
        "haze",
        "redblueshift",
        "saturation",
        "horizon_height",
        "horizon_blur",
        "ground_color",
        "night_color",
        "sun_direction",
        "sun_disk_intensity",
        "sun_disk_scale",
        "sun_glow_intensity",
        "y_is_up",
        "physically_scaled_sun",
    ],
    run: sun_and_sky,
    ..ShaderImpl::PLAIN
};

/// The parameters of `sun_and_sky` node `n`.
pub fn sun_and_sky_of(ctx: &mut Ctx, n: NodeId) -> SunAndSky {
    SunAndSky {
        on: ctx.bool(n, 0),
        sky: PhysicalSky {
            multiplier: ctx.scalar(n, 1),
            rgb_unit_conversion: rgb(ctx.color(n, 2)),
            haze: ctx.scalar(n, 3),
            redblueshift: ctx.scalar(n, 4),
            saturation: ctx.scalar(n, 5),
            horizon_height: ctx.scalar(n, 6),
            horizon_blur: ctx.scalar(n, 7),
            ground_color: rgb(ctx.color(n, 8)),
            night_color: rgb(ctx.color(n, 9)),
            sun_direction: ctx.vector(n, 10),
            sun_disk_intensity: ctx.scalar(n, 11),
            sun_disk_scale: ctx.scalar(n, 12),
            sun_glow_intensity: ctx.scalar(n, 13),
            y_is_up: ctx.bool(n, 14),
            physically_scaled_sun: ctx.bool(n, 15),
            ..PhysicalSky::default()
        },
    }
}

fn sun_and_sky(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let c = sun_and_sky_of(ctx, n).radiance(ctx.state.dir.normalize_or(Vec3A::Z));
    *out = Value::Color(Color::new(c.x, c.y, c.z, 1.0));
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use sky::sky::luminance;

    fn dir(elevation_deg: f32, azimuth_deg: f32) -> Vec3A {
        // Y up: elevation above the XZ plane.
        let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
        Vec3A::new(e.cos() * a.cos(), e.sin(), e.cos() * a.sin())
    }

    #[test]
    fn pi_times_the_mental_ray_sky() {
        let s = SunAndSky::default();
        for d in [Vec3A::Y, dir(0.5, 30.0), dir(45.0, 200.0), dir(-20.0, 10.0)] {
            let (a, b) = (s.radiance(d), s.sky.radiance(d) * PI);
            assert!((a - b).abs().max_element() <= 1e-6 * b.max_element(), "{a} {b}");
        }
        assert_eq!(SunAndSky { on: false, ..s }.radiance(Vec3A::Y), Vec3A::ZERO);
    }

    #[test]
    fn the_sun_light_carries_what_the_disk_and_glow_add() {
        for (scale, physical, glow) in [(0.5, true, 1.0), (4.0, false, 1.0), (2.0, true, 0.0)] {
            let mut s = SunAndSky::default();
            s.sky.sun_disk_scale = scale;
            s.sky.physically_scaled_sun = physical;
            s.sky.sun_glow_intensity = glow;
            s.sky.sun_disk_intensity = 1.0;
            let sun = s.sun().expect("a sun");
            assert!((sun.direction - s.sky.sun_direction.normalize()).length() < 1e-6);
            // The cone's content, radiance − sky_radiance, integrated × cos over the cone
            // (2-D midpoint rule about the sun) is the light's irradiance within 1 %.
            let (b1, b2) = sun.direction.any_orthonormal_pair();
            let (n, m) = (600, 48);
            let r = sun.cone_radius;
            let mut sum = Vec3A::ZERO;
            for i in 0..n {
                let a = (i as f32 + 0.5) / n as f32 * r;
                for j in 0..m {
                    let phi = 2.0 * PI * (j as f32 + 0.5) / m as f32;
                    let d = (sun.direction * a.cos() + (b1 * phi.cos() + b2 * phi.sin()) * a.sin()).normalize();
                    let extra = s.radiance(d) - s.sky_radiance(d);
                    sum += extra * a.sin() * a.cos() * (r / n as f32) * (2.0 * PI / m as f32);
                }
            }
            let rel = (sum - sun.irradiance).abs().max_element() / sun.irradiance.max_element();
            assert!(rel < 0.01, "scale {scale}: {sum} vs {}", sun.irradiance);
            // Outside the cone the sun adds nothing.
            let out = (sun.direction * (1.05 * r).cos() + b1 * (1.05 * r).sin()).normalize();
            assert_eq!(s.radiance(out), s.sky_radiance(out));
        }
    }

    #[test]
    fn physically_scaled_sun_irradiance() {
        // Disk and glow deliver π² × sun_disk_intensity × E × c × m (output units; E the
        // sun's illuminance in lux), within 3 % (mira's disk profile has a smooth edge,
        // its scale assumes a flat one). Saturation 1 so that the colour is untouched.
        let mut s = SunAndSky::default();
        s.sky.saturation = 1.0;
        s.sky.sun_disk_intensity = 1.0;
        let sun = s.sun().unwrap();
        let frame_z = s.sky.sun_in_frame().z;
        let e = luminance(sun_illuminance(turbidity(s.sky.haze), frame_z)) / 1500.0 * 0.025;
        let want = PI * PI * e;
        let got = luminance(sun.irradiance);
        assert!((got / want - 1.0).abs() < 0.03, "{got} vs {want}");
        // Below the twilight limit: no sun.
        s.sky.sun_direction = Vec3A::new(0.0, -0.5, 0.5);
        assert!(s.sun().is_none());
    }
}
