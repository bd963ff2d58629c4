//! Lambertian diffuse reflection: f = albedo / π on the side of the surface ωo is on.

use glam::{Vec2, Vec3A};

use super::{cosine_pdf_on_side, BsdfSample};
use crate::Rgb;

/// Ideal diffuse reflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambert {
    /// Directional-hemispherical reflectance, per channel, 0 to 1.
    pub albedo: Rgb,
}

impl Lambert {
    /// f(ωo, ωi): albedo/π when both are on the same side, else 0.
    #[inline]
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z > 0.0 {
            self.albedo * std::f32::consts::FRAC_1_PI
        } else {
            Rgb::ZERO
        }
    }

    /// Cosine-weighted sampling on ωo's side.
    #[inline]
    pub fn sample(&self, wo: Vec3A, u: Vec2) -> Option<BsdfSample> {
        crate::sample_cosine_lobe(wo, u, |wi| self.eval(wo, wi))
    }

    /// |cos θi| / π on ωo's side.
    #[inline]
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        cosine_pdf_on_side(wo, wi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;
    use crate::Bsdf;

    #[test]
    fn lambert_is_reciprocal_energy_conserving_and_samples_its_pdf() {
        let bsdf = Bsdf::Lambert(Lambert { albedo: Rgb::new(0.8, 0.5, 0.2) });
        testing::reciprocity(&bsdf, 1e-6);
        // Albedo: the estimate of ∫ f cos equals the albedo to Monte Carlo accuracy.
        let albedo = testing::albedo(&bsdf, Vec3A::new(0.3, 0.1, 0.95).normalize(), 20_000);
        assert!((albedo - Rgb::new(0.8, 0.5, 0.2)).abs().max_element() < 1e-3, "{albedo}");
        testing::chi_square(&bsdf, Vec3A::new(0.3, 0.1, 0.95).normalize());
        testing::chi_square(&bsdf, Vec3A::new(0.99, 0.0, 0.14).normalize());
        testing::chi_square(&bsdf, Vec3A::new(0.2, 0.3, -0.9).normalize());
    }
}
