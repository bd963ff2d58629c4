//! mental ray 3.7's built-in BSDFs (`builtin_bsdf_lambert`, `_phong`, `_ashikhmin`,
//! `_mirror`, `_architectural`; `shared/spec/shaders.md` §12) for a material's `bsdf` slot.
//!
//! [`BuiltinBsdf`] is the scattering function itself, in the local shading frame (+Z the
//! shading normal, directions pointing away from the surface, `eval` without the cosine),
//! like the other BSDFs of this crate. The base library builds it from a shader's parameters
//! and runs it as a material shader in the classic engine; the path engine samples it.

use std::f32::consts::{FRAC_1_PI, PI, TAU};

use glam::{Vec2, Vec3A};

use crate::color::luminance;
use crate::mia::MiaBsdf;
use crate::{cosine_on_side, cosine_pdf_on_side, BsdfSample, Frame, Lambert, Rgb};

/// A built-in BSDF with its parameters at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BuiltinBsdf {
    /// `builtin_bsdf_lambert`: ρ/π.
    Lambert(Lambert),
    /// `builtin_bsdf_phong`: Lambert plus the normalised Phong lobe
    /// `glossy · (n + 2)/(2π) · cos^n α` about the mirror direction (Lafortune and Willems
    /// 1994).
    Phong {
        /// Diffuse reflectance.
        diffuse: Rgb,
        /// Glossy reflectance (the lobe's albedo at normal incidence).
        glossy: Rgb,
        /// Phong exponent n.
        exponent: f32,
    },
    /// `builtin_bsdf_ashikhmin`: Ashikhmin and Shirley's anisotropic Phong BRDF (2000),
    /// its Fresnel-weighted diffuse and Schlick-Fresnel specular with exponents along the
    /// frame's x (`exp_u`) and y (`exp_v`).
    Ashikhmin {
        /// Diffuse reflectance R_d.
        diffuse: Rgb,
        /// Specular reflectance at normal incidence R_s.
        glossy: Rgb,
        /// Exponent along x.
        nu: f32,
        /// Exponent along y.
        nv: f32,
    },
    /// `builtin_bsdf_mirror`: a perfect mirror of reflectance `reflection` (a delta lobe).
    Mirror(Rgb),
    /// `builtin_bsdf_architectural`: mia_material's lobes with the reduced interface.
    Architectural(MiaBsdf),
}

fn mirror(w: Vec3A) -> Vec3A {
    Vec3A::new(-w.x, -w.y, w.z)
}

/// An orthonormal frame around unit `axis`.
fn frame_about(axis: Vec3A) -> Frame {
    Frame::from_normal(axis)
}

/// Sampling probability of the diffuse lobe in a diffuse + glossy mixture.
fn diffuse_share(diffuse: Rgb, glossy: Rgb) -> f32 {
    let (d, g) = (luminance(diffuse).max(0.0), luminance(glossy).max(0.0));
    if d + g > 0.0 {
        d / (d + g)
    } else {
        1.0
    }
}

/// Ashikhmin–Shirley's exponent of n·h for half vector `h`.
fn as_exponent(nu: f32, nv: f32, h: Vec3A) -> f32 {
    let s2 = (1.0 - h.z * h.z).max(1e-12);
    (nu * h.x * h.x + nv * h.y * h.y) / s2
}

/// Density of Ashikhmin–Shirley's half-vector sampling (per solid angle of h).
fn as_pdf_h(nu: f32, nv: f32, h: Vec3A) -> f32 {
    ((nu + 1.0) * (nv + 1.0)).sqrt() / TAU * h.z.max(0.0).powf(as_exponent(nu, nv, h))
}

/// Ashikhmin–Shirley's half-vector sampling.
fn as_sample_h(nu: f32, nv: f32, u: Vec2) -> Vec3A {
    // φ in the first quadrant from a quarter of the range, mirrored into the others.
    let q = (u.x * 4.0).min(3.999_999);
    let quadrant = q as u32;
    let t = q - quadrant as f32;
    let mut phi = (((nu + 1.0) / (nv + 1.0)).sqrt() * (0.5 * PI * t).tan()).atan();
    phi = match quadrant {
        0 => phi,
        1 => PI - phi,
        2 => PI + phi,
        _ => TAU - phi,
    };
    let (s, c) = phi.sin_cos();
    let cos_t = (1.0 - u.y).max(0.0).powf(1.0 / (nu * c * c + nv * s * s + 1.0));
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    Vec3A::new(sin_t * c, sin_t * s, cos_t)
}

impl BuiltinBsdf {
    /// Whether all scattering is in delta lobes.
    pub fn is_delta(&self) -> bool {
        match self {
            BuiltinBsdf::Mirror(_) => true,
            BuiltinBsdf::Architectural(m) => m.is_delta(),
            _ => false,
        }
    }

    /// The diffuse reflectance the classic engine multiplies final gathering by.
    pub fn diffuse_albedo(&self) -> Rgb {
        match self {
            BuiltinBsdf::Lambert(l) => l.albedo,
            BuiltinBsdf::Phong { diffuse, .. } => *diffuse,
            BuiltinBsdf::Ashikhmin { diffuse, glossy, .. } => *diffuse * (Rgb::ONE - *glossy),
            BuiltinBsdf::Mirror(_) => Rgb::ZERO,
            BuiltinBsdf::Architectural(m) => m.diffuse.albedo,
        }
    }

    /// f(ωo, ωi) of the non-delta lobes (reflection only on ωo's side, except
    /// architectural translucency and transmission).
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if let BuiltinBsdf::Architectural(m) = self {
            return m.eval(wo, wi);
        }
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        match *self {
            BuiltinBsdf::Lambert(l) => l.eval(wo, wi),
            BuiltinBsdf::Phong { diffuse, glossy, exponent } => {
                let n = exponent.max(0.0);
                let c = mirror(wo).dot(wi).max(0.0);
                diffuse * FRAC_1_PI + glossy * ((n + 2.0) / TAU * c.powf(n))
            }
            BuiltinBsdf::Ashikhmin { diffuse, glossy, nu, nv } => {
                let h = (wo + wi).normalize();
                let k = wi.dot(h).max(1e-6);
                let fresnel = glossy + (Rgb::ONE - glossy) * (1.0 - k).powi(5);
                let spec = ((nu + 1.0) * (nv + 1.0)).sqrt() / (8.0 * PI) * h.z.powf(as_exponent(nu, nv, h))
                    / (k * wo.z.max(wi.z));
                let d = 28.0 / (23.0 * PI) * (1.0 - (1.0 - wo.z / 2.0).powi(5)) * (1.0 - (1.0 - wi.z / 2.0).powi(5));
                diffuse * (Rgb::ONE - glossy) * d + fresnel * spec
            }
            BuiltinBsdf::Mirror(_) | BuiltinBsdf::Architectural(_) => Rgb::ZERO,
        }
    }

    /// Density of [`BuiltinBsdf::sample`] choosing ωi (non-delta lobes).
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if let BuiltinBsdf::Architectural(m) = self {
            return m.pdf(wo, wi);
        }
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        match *self {
            BuiltinBsdf::Lambert(l) => l.pdf(wo, wi),
            BuiltinBsdf::Phong { diffuse, glossy, exponent } => {
                let pd = diffuse_share(diffuse, glossy);
                let n = exponent.max(0.0);
                let c = mirror(wo).dot(wi).max(0.0);
                pd * cosine_pdf_on_side(wo, wi) + (1.0 - pd) * (n + 1.0) / TAU * c.powf(n)
            }
            BuiltinBsdf::Ashikhmin { diffuse, glossy, nu, nv } => {
                let pd = diffuse_share(diffuse * (Rgb::ONE - glossy), glossy);
                let h = (wo + wi).normalize();
                pd * cosine_pdf_on_side(wo, wi) + (1.0 - pd) * as_pdf_h(nu, nv, h) / (4.0 * wo.dot(h).max(1e-6))
            }
            BuiltinBsdf::Mirror(_) | BuiltinBsdf::Architectural(_) => 0.0,
        }
    }

    /// Samples ωi for ωo with two numbers for the direction and one for the lobe.
    pub fn sample(&self, wo: Vec3A, u: Vec2, u_lobe: f32) -> Option<BsdfSample> {
        if let BuiltinBsdf::Architectural(m) = self {
            return m.sample(wo, u, u_lobe);
        }
        if wo.z <= 0.0 {
            return None;
        }
        let wi = match *self {
            BuiltinBsdf::Mirror(r) => return Some(BsdfSample { wi: mirror(wo), f: r / wo.z, pdf: 1.0, delta: true }),
            BuiltinBsdf::Lambert(l) => return l.sample(wo, u),
            BuiltinBsdf::Phong { diffuse, glossy, exponent } => {
                if u_lobe < diffuse_share(diffuse, glossy) {
                    cosine_on_side(wo, u)?
                } else {
                    let cos_a = u.x.powf(1.0 / (exponent.max(0.0) + 1.0));
                    let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
                    let (s, c) = (TAU * u.y).sin_cos();
                    frame_about(mirror(wo)).to_world(Vec3A::new(sin_a * c, sin_a * s, cos_a))
                }
            }
            BuiltinBsdf::Ashikhmin { diffuse, glossy, nu, nv } => {
                if u_lobe < diffuse_share(diffuse * (Rgb::ONE - glossy), glossy) {
                    cosine_on_side(wo, u)?
                } else {
                    let h = as_sample_h(nu, nv, u);
                    -wo + 2.0 * wo.dot(h) * h
                }
            }
            BuiltinBsdf::Architectural(_) => return None,
        };
        if wi.z <= 0.0 {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample { wi, f: self.eval(wo, wi), pdf, delta: false })
    }

    /// The delta lobes' reflection weight (f·cos/pdf of the mirror direction).
    pub fn mirror_weight(&self) -> Rgb {
        match self {
            BuiltinBsdf::Mirror(r) => *r,
            BuiltinBsdf::Architectural(m) if m.reflect_ggx.is_smooth() => m.reflect,
            _ => Rgb::ZERO,
        }
    }

    /// Whether some scattering is glossy (non-delta and not diffuse).
    pub fn has_glossy(&self) -> bool {
        match self {
            BuiltinBsdf::Phong { glossy, .. } | BuiltinBsdf::Ashikhmin { glossy, .. } => *glossy != Rgb::ZERO,
            BuiltinBsdf::Architectural(m) => !m.reflect_ggx.is_smooth() && m.reflect != Rgb::ZERO,
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ f cos dω over the hemisphere by the BSDF's own sampling, and by uniform sampling.
    fn albedo(b: &BuiltinBsdf, wo: Vec3A) -> (Rgb, Rgb) {
        let n = 256u32;
        let (mut by_sample, mut uniform) = (Rgb::ZERO, Rgb::ZERO);
        for i in 0..n {
            for j in 0..n {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                let u_lobe = ((i * 7 + j * 13) % 97) as f32 / 97.0 + 0.005;
                if let Some(s) = b.sample(wo, u, u_lobe) {
                    by_sample += s.weight();
                }
                // Uniform hemisphere: z = u.x, pdf 1/(2π).
                let z = u.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let wi = Vec3A::new(r * (TAU * u.y).cos(), r * (TAU * u.y).sin(), z);
                uniform += b.eval(wo, wi) * z * TAU;
            }
        }
        let count = (n * n) as f32;
        (by_sample / count, uniform / count)
    }

    #[test]
    fn lambert_furnace_reflects_its_albedo() {
        let b = BuiltinBsdf::Lambert(Lambert { albedo: Rgb::new(1.0, 0.5, 0.25) });
        for cos in [1.0f32, 0.5, 0.1] {
            let wo = Vec3A::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            let (s, u) = albedo(&b, wo);
            assert!((s - Rgb::new(1.0, 0.5, 0.25)).abs().max_element() < 1e-4, "sampled {s}");
            assert!((u - Rgb::new(1.0, 0.5, 0.25)).abs().max_element() < 0.01, "uniform {u}");
        }
    }

    #[test]
    fn glossy_lobes_conserve_energy_and_sample_their_own_density() {
        let cases = [
            BuiltinBsdf::Phong { diffuse: Rgb::splat(0.3), glossy: Rgb::splat(0.7), exponent: 20.0 },
            BuiltinBsdf::Phong { diffuse: Rgb::ZERO, glossy: Rgb::ONE, exponent: 200.0 },
            BuiltinBsdf::Ashikhmin { diffuse: Rgb::splat(0.5), glossy: Rgb::splat(0.05), nu: 10.0, nv: 100.0 },
            BuiltinBsdf::Ashikhmin { diffuse: Rgb::ZERO, glossy: Rgb::ONE, nu: 50.0, nv: 50.0 },
        ];
        for b in &cases {
            for cos in [0.9f32, 0.5] {
                let wo = Vec3A::new((1.0 - cos * cos).sqrt(), 0.0, cos);
                let (s, u) = albedo(b, wo);
                assert!(s.max_element() <= 1.01, "{b:?} at cos {cos}: albedo {s}");
                // The sampler's weights and the uniform estimate agree (pdf matches sample).
                assert!((s - u).abs().max_element() < 0.02 + 0.03 * u.max_element(), "{b:?}: {s} vs {u}");
            }
        }
        // Phong with ρd + ρs = 1 at normal incidence reflects nearly everything.
        let (s, _) = albedo(&cases[0], Vec3A::Z);
        assert!(s.x > 0.95, "phong at normal incidence {s}");
    }

    #[test]
    fn mirror_reflects_exactly() {
        let b = BuiltinBsdf::Mirror(Rgb::new(0.9, 0.8, 0.7));
        let wo = Vec3A::new(0.6, 0.0, 0.8);
        let s = b.sample(wo, Vec2::new(0.3, 0.6), 0.2).unwrap();
        assert!(s.delta);
        assert!((s.wi - Vec3A::new(-0.6, 0.0, 0.8)).length() < 1e-7);
        assert!((s.weight() - Rgb::new(0.9, 0.8, 0.7)).abs().max_element() < 1e-6);
        assert_eq!(b.eval(wo, s.wi), Rgb::ZERO, "no non-delta part");
    }
}
