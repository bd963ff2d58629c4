//! The Beckmann microfacet distribution (Beckmann and Spizzichino 1963; Walter et al.
//! 2007): Gaussian slopes of roughness α (the RMS slope, along the frame's x and y), with
//! Smith's shadowing through Walter's rational fit of Λ, and a reflection lobe on it
//! without a Fresnel term (MDL's `microfacet_beckmann_*_bsdf`). Local frame, z = normal.

use std::f32::consts::PI;

use glam::{Vec2, Vec3A};

use crate::{BsdfSample, Rgb};

/// Smallest α used (smoother surfaces are numerically a mirror).
const MIN_ALPHA: f32 = 1e-3;

/// A Beckmann distribution of micro-normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beckmann {
    /// RMS slope along x.
    pub alpha_x: f32,
    /// RMS slope along y.
    pub alpha_y: f32,
}

impl Beckmann {
    /// A distribution of roughness (α along x, α along y), clamped to at least 10⁻³.
    pub fn new(alpha_x: f32, alpha_y: f32) -> Beckmann {
        Beckmann { alpha_x: alpha_x.max(MIN_ALPHA), alpha_y: alpha_y.max(MIN_ALPHA) }
    }

    /// D(h): micro-normal density per solid angle (∫ D(h) cos θh dω = 1).
    pub fn d(&self, h: Vec3A) -> f32 {
        if h.z <= 0.0 {
            return 0.0;
        }
        let cos2 = h.z * h.z;
        let e = ((h.x / self.alpha_x).powi(2) + (h.y / self.alpha_y).powi(2)) / cos2;
        (-e).exp() / (PI * self.alpha_x * self.alpha_y * cos2 * cos2)
    }

    /// Smith's Λ(ω), Walter et al.'s rational approximation.
    pub fn lambda(&self, w: Vec3A) -> f32 {
        let projected = ((w.x * self.alpha_x).powi(2) + (w.y * self.alpha_y).powi(2)).sqrt();
        if projected == 0.0 {
            return 0.0;
        }
        let a = w.z.abs() / projected;
        if a >= 1.6 {
            0.0
        } else {
            (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a)
        }
    }

    /// Height-correlated masking–shadowing G2.
    pub fn g2(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// A micro-normal drawn with density D(h) cos θh: Gaussian slopes scaled by α.
    pub fn sample(&self, u: Vec2) -> Vec3A {
        let r = (-(1.0 - u.x).max(1e-12).ln()).sqrt();
        let phi = 2.0 * PI * u.y;
        let (sx, sy) = (self.alpha_x * r * phi.cos(), self.alpha_y * r * phi.sin());
        Vec3A::new(-sx, -sy, 1.0).normalize()
    }
}

/// Reflection from Beckmann micro-mirrors of reflectance `tint` (no Fresnel term), on ωo's
/// side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BeckmannReflection {
    /// Reflectance of the micro-mirrors.
    pub tint: Rgb,
    /// The distribution.
    pub dist: Beckmann,
}

/// ωo and ωi flipped onto +z together when ωo is below (two-sided); `None` when they lie
/// on opposite sides or in the surface.
fn upper(wo: Vec3A, wi: Vec3A) -> Option<(Vec3A, Vec3A)> {
    if wo.z * wi.z <= 0.0 {
        return None;
    }
    let flip = |w: Vec3A| if wo.z < 0.0 { Vec3A::new(w.x, w.y, -w.z) } else { w };
    Some((flip(wo), flip(wi)))
}

impl BeckmannReflection {
    /// f(ωo, ωi) = tint · D(h) G2 / (4 |cos θo cos θi|).
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        let Some((o, i)) = upper(wo, wi) else { return Rgb::ZERO };
        let h = (o + i).normalize_or_zero();
        if h == Vec3A::ZERO {
            return Rgb::ZERO;
        }
        self.tint * (self.dist.d(h) * self.dist.g2(o, i) / (4.0 * o.z * i.z))
    }

    /// Density of [`BeckmannReflection::sample`]: D(h) cos θh / (4 |ωo·h|).
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let Some((o, i)) = upper(wo, wi) else { return 0.0 };
        let h = (o + i).normalize_or_zero();
        let oh = o.dot(h);
        if h == Vec3A::ZERO || oh <= 0.0 {
            return 0.0;
        }
        self.dist.d(h) * h.z / (4.0 * oh)
    }

    /// The mirror direction about a micro-normal drawn from D(h) cos θh.
    pub fn sample(&self, wo: Vec3A, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let o = if wo.z < 0.0 { Vec3A::new(wo.x, wo.y, -wo.z) } else { wo };
        let h = self.dist.sample(u);
        let i = 2.0 * o.dot(h) * h - o;
        if i.z <= 0.0 || o.dot(h) <= 0.0 {
            return None;
        }
        let wi = if wo.z < 0.0 { Vec3A::new(i.x, i.y, -i.z) } else { i };
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample { wi, f: self.eval(wo, wi), pdf, delta: false })
    }
}
