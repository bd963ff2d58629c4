//! `mia_photometric_light`: the Architectural library's photometric point light — an
//! intensity in candela (given at the peak, as a total flux in lumens, or taken from an IES
//! profile), spread isotropically, as a cosine-power spot or by the profile, falling off
//! with the square of the distance in metres.
//!
//! The colour arriving at a point at scene distance d towards light-local direction ω is
//! color · multiplier · I(ω) / (d · units_to_meter_scale)² / cm2_factor, with
//! I(ω) = peak · shape(ω). The shape is 1 (isotropic), cos^bias of the angle from the
//! light's local −Z (spot, `spotlight_cosine_bias`; nothing behind), or the profile's
//! normalised value (IES; see [`shader::light::ies`] for its axes). The peak is
//! `manual_peak_intensity_cd` (intensity mode 0), `manual_flux_lm` over the shape's solid
//! angle ∫ shape dω (mode 1: 4π, 2π/(bias + 1), profile flux / profile peak) or the
//! profile's own peak (mode 2). `cm2_factor` is read as in the exposure shaders, pixel
//! value × cm2_factor = cd/m², so the light divides by it (mira's reading; 1 by default).
//! Shadows are always traced, as for `physical_light`. Where the IES modes have no
//! readable profile the light falls back to isotropic and the manual peak.

use std::f32::consts::PI;
use std::sync::Arc;

use shader::light::ies::Profile;
use shader::light::profiles::Distribution;
use shader::{Color, Ctx, NodeId, ShaderImpl, Value};

/// The parameters that decide a photometric light's intensity over directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// 0 manual peak candela, 1 manual flux in lumens, 2 from the profile.
    pub intensity_mode: i32,
    /// `manual_peak_intensity_cd`.
    pub peak_cd: f32,
    /// `manual_flux_lm`.
    pub flux_lm: f32,
    /// 0 isotropic, 1 spot (cosine power), 2 the IES profile.
    pub distribution_mode: i32,
    /// `spotlight_cosine_bias`: the spot's cosine exponent.
    pub cosine_bias: f32,
}

impl Settings {
    /// The peak intensity (candela) and the normalised shape (peak 1; `None`: isotropic).
    pub fn resolve(&self, profile: Option<Arc<Profile>>) -> (f32, Option<Distribution>) {
        let profile = profile.filter(|p| p.peak() > 0.0);
        let shape = match (self.distribution_mode, &profile) {
            (1, _) => Some(Distribution::Cosine(self.cosine_bias.max(0.0))),
            (2, Some(p)) => Some(Distribution::Profile { profile: p.clone(), scale: 1.0 / p.peak() }),
            _ => None,
        };
        let solid_angle = match &shape {
            None => 4.0 * PI,
            Some(Distribution::Cosine(e)) => 2.0 * PI / (e + 1.0),
            Some(Distribution::Profile { profile, .. }) => profile.flux() / profile.peak(),
        };
        let peak = match (self.intensity_mode, &profile) {
            (1, _) if solid_angle > 0.0 => self.flux_lm / solid_angle,
            (1, _) => 0.0,
            (2, Some(p)) => p.peak(),
            _ => self.peak_cd,
        };
        (peak.max(0.0), shape)
    }
}

/// `mia_photometric_light (boolean on, scalar multiplier, color color, integer
/// intensity_mode, scalar manual_peak_intensity_cd, scalar manual_flux_lm, integer
/// distribution_mode, scalar spotlight_cosine_bias, lightprofile profile, scalar
/// units_to_meter_scale, scalar cm2_factor)`; see the module documentation. Without a
/// `profile` the light's own `lightprofile` statement is used.
pub static MIA_PHOTOMETRIC_LIGHT: ShaderImpl = ShaderImpl {
    name: "mia_photometric_light",
    params: &[
        "on",
        "multiplier",
        "color",
        "intensity_mode",
        "manual_peak_intensity_cd",
        "manual_flux_lm",
        "distribution_mode",
        "spotlight_cosine_bias",
        "profile",
        "units_to_meter_scale",
        "cm2_factor",
    ],
    run,
    ..ShaderImpl::PLAIN
};

fn run(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !ctx.bool(n, 0) {
        return false;
    }
    let shading = ctx.shading();
    let Some(light) = ctx.state.light.and_then(|l| ctx.light(l)) else { return false };
    let (to_local, own) = (light.to_local, light.profile);
    let settings = Settings {
        intensity_mode: ctx.int(n, 3),
        peak_cd: ctx.scalar(n, 4),
        flux_lm: ctx.scalar(n, 5),
        distribution_mode: ctx.int(n, 6),
        cosine_bias: ctx.scalar(n, 7),
    };
    let tagged = ctx.eval(n, 8);
    let profile = match tagged.tag() {
        Some(shader::Tag::Lightprofile(i)) => shading.lightprofiles.get(i as usize).cloned().flatten(),
        _ => own.and_then(|i| shading.lightprofiles.get(i as usize).cloned().flatten()),
    };
    let (peak, shape) = settings.resolve(profile);
    let f = shape.map_or(1.0, |s| s.factor(to_local * ctx.state.dir));
    let u = positive_or_one(ctx.scalar(n, 9));
    let cm2 = positive_or_one(ctx.scalar(n, 10));
    let d = ctx.state.dist * u;
    if f <= 0.0 || peak <= 0.0 || d <= 0.0 {
        return false;
    }
    let scale = ctx.scalar(n, 1) * peak * f / (d * d * cm2);
    let mut c = ctx.color(n, 2) * scale;
    let mut filter = Color::ONE;
    if !ctx.trace_shadow(&mut filter) {
        return false;
    }
    c *= filter;
    c.w = 1.0;
    *out = Value::Color(c);
    true
}

/// `x` where it is a positive number, else 1 (an unset scale).
pub fn positive_or_one(x: f32) -> f32 {
    if x > 0.0 && x.is_finite() {
        x
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(intensity_mode: i32, distribution_mode: i32) -> Settings {
        Settings { intensity_mode, peak_cd: 1000.0, flux_lm: 4000.0, distribution_mode, cosine_bias: 3.0 }
    }

    #[test]
    fn intensity_modes_give_the_peak_in_candela() {
        // Manual peak, any shape.
        assert_eq!(settings(0, 0).resolve(None).0, 1000.0);
        // Flux over an isotropic shape: Φ / 4π.
        let (peak, shape) = settings(1, 0).resolve(None);
        assert!((peak - 4000.0 / (4.0 * PI)).abs() < 1e-3 && shape.is_none());
        // Flux over cos³: ∫ cos³ dω = 2π/4.
        let (peak, shape) = settings(1, 1).resolve(None);
        assert!((peak - 4000.0 * 4.0 / (2.0 * PI)).abs() < 1e-2);
        assert_eq!(shape, Some(Distribution::Cosine(3.0)));
        // IES without a profile: isotropic with the manual peak.
        assert_eq!(settings(2, 2).resolve(None), (1000.0, None));
    }

    #[test]
    fn ies_modes_take_peak_and_shape_from_the_profile() {
        // An isotropic 50 cd profile: peak 50, flux 200π; flux mode with 4000 lm gives
        // 4000 / 4π whatever the profile's own scale.
        let text = "TILT=NONE\n1 -1 1 3 1 1 2 0 0 0 1 1 1\n0 90 180\n0\n50 50 50\n";
        let p = Arc::new(Profile::parse(text, false).unwrap().0);
        let (peak, shape) = settings(2, 2).resolve(Some(p.clone()));
        assert!((peak - 50.0).abs() < 1e-4);
        assert!((shape.unwrap().factor(glam::Vec3A::X) - 1.0).abs() < 1e-5);
        let (peak, _) = settings(1, 2).resolve(Some(p));
        assert!((peak - 4000.0 / (4.0 * PI)).abs() < 1e-2, "{peak}");
    }
}
