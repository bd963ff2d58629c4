//! A sheen lobe: the "Charlie" distribution of Estevez and Kulla (2017) for fibres,
//! D(h) = (2 + 1/r) sin^(1/r) θh / (2π) of roughness r ∈ (0, 1], with the visibility term
//! V = 1 / (4 (cos θi + cos θo − cos θi cos θo)) of Neubelt and Pettineo (2013); sampled by
//! cosine-weighted directions. MDL's `sheen_bsdf`. Local frame, z = normal.

use std::f32::consts::PI;

use glam::{Vec2, Vec3A};

use crate::{cosine_on_side, cosine_pdf_on_side, BsdfSample, Rgb};

/// Smallest roughness used (the lobe's exponent 1/r stays finite).
const MIN_ROUGHNESS: f32 = 0.02;

/// A sheen lobe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sheen {
    /// Tint of the lobe.
    pub tint: Rgb,
    /// Roughness r (clamped to [0.02, 1]).
    pub roughness: f32,
}

impl Sheen {
    /// A sheen lobe of `tint` and roughness `roughness`.
    pub fn new(tint: Rgb, roughness: f32) -> Sheen {
        Sheen { tint, roughness: roughness.clamp(MIN_ROUGHNESS, 1.0) }
    }

    /// f(ωo, ωi) on ωo's side.
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let (co, ci) = (wo.z.abs(), wi.z.abs());
        let o = Vec3A::new(wo.x, wo.y, co);
        let i = Vec3A::new(wi.x, wi.y, ci);
        let h = (o + i).normalize_or_zero();
        if h == Vec3A::ZERO {
            return Rgb::ZERO;
        }
        let inv = 1.0 / self.roughness;
        let sin_h = (1.0 - h.z * h.z).max(0.0).sqrt();
        let d = (2.0 + inv) * sin_h.powf(inv) / (2.0 * PI);
        let v = 1.0 / (4.0 * (ci + co - ci * co));
        self.tint * (d * v)
    }

    /// Cosine-weighted density on ωo's side.
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        cosine_pdf_on_side(wo, wi)
    }

    /// A cosine-weighted direction on ωo's side.
    pub fn sample(&self, wo: Vec3A, u: Vec2) -> Option<BsdfSample> {
        let wi = cosine_on_side(wo, u)?;
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample { wi, f: self.eval(wo, wi), pdf, delta: false })
    }
}
