//! Oren–Nayar diffuse reflection (the two-coefficient form): rough diffuse surfaces that
//! scatter back towards the light; σ = 0 is Lambert.

use glam::{Vec2, Vec3A};

use super::{cosine_pdf_on_side, BsdfSample};
use crate::Rgb;

/// Rough diffuse reflection on the side of ωo.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrenNayar {
    /// Reflectance.
    pub albedo: Rgb,
    /// A and B of the model for the roughness σ (radians).
    a: f32,
    b: f32,
}

impl OrenNayar {
    /// With roughness σ in radians.
    pub fn new(albedo: Rgb, sigma: f32) -> OrenNayar {
        let s2 = sigma * sigma;
        OrenNayar { albedo, a: 1.0 - 0.5 * s2 / (s2 + 0.33), b: 0.45 * s2 / (s2 + 0.09) }
    }

    /// The model's factor over Lambert for the pair of directions (same side).
    pub fn factor(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if self.b == 0.0 {
            return self.a;
        }
        let (co, ci) = (wo.z.abs(), wi.z.abs());
        let (so, si) = ((1.0 - co * co).max(0.0).sqrt(), (1.0 - ci * ci).max(0.0).sqrt());
        let cos_phi = if so > 1e-4 && si > 1e-4 { ((wo.x * wi.x + wo.y * wi.y) / (so * si)).max(0.0) } else { 0.0 };
        let (sin_a, tan_b) = if ci < co { (si, so / co.max(1e-6)) } else { (so, si / ci.max(1e-6)) };
        self.a + self.b * cos_phi * sin_a * tan_b
    }

    /// f(ωo, ωi).
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z > 0.0 {
            self.albedo * (self.factor(wo, wi) * std::f32::consts::FRAC_1_PI)
        } else {
            Rgb::ZERO
        }
    }

    /// Cosine-weighted sampling on ωo's side.
    pub fn sample(&self, wo: Vec3A, u: Vec2) -> Option<BsdfSample> {
        crate::sample_cosine_lobe(wo, u, |wi| self.eval(wo, wi))
    }

    /// |cos θi| / π on ωo's side.
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        cosine_pdf_on_side(wo, wi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{albedo, chi_square, reciprocity};
    use crate::Bsdf;

    #[test]
    fn oren_nayar_is_reciprocal_energy_conserving_and_samples_its_pdf() {
        for sigma in [0.0, 0.3, 1.0] {
            let b = Bsdf::OrenNayar(OrenNayar::new(Rgb::ONE, sigma));
            reciprocity(&b, 1e-5);
            chi_square(&b, Vec3A::new(0.3, 0.1, 0.95).normalize());
            chi_square(&b, -Vec3A::new(-0.8, 0.2, 0.2).normalize());
            for i in 0..8 {
                let t = (i as f32 + 0.5) / 8.0 * 1.5;
                let a = albedo(&b, Vec3A::new(t.sin(), 0.0, t.cos()), 20_000).x;
                // The qualitative model loses energy with roughness but never gains it.
                assert!(a <= 1.0 + 0.01 && a > 0.6, "σ {sigma}, θo {t}: albedo {a}");
            }
        }
        // σ = 0 is Lambert exactly.
        let wo = Vec3A::new(0.3, 0.1, 0.95).normalize();
        let wi = Vec3A::new(-0.5, 0.4, 0.77).normalize();
        let f = OrenNayar::new(Rgb::ONE, 0.0).eval(wo, wi).x;
        assert!((f - std::f32::consts::FRAC_1_PI).abs() < 1e-7);
    }
}
