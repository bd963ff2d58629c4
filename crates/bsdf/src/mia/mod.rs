//! `mia_material` as a BSDF for the path integrator.
//!
//! The layers keep the classic shader's weights (the reflectivity curve at the viewing
//! angle, the author's luminance-based conservation), each with one lobe:
//! - reflection: GGX microfacets whose roughness comes from `refl_gloss` by NVIDIA's
//!   "mia semantic" fit (`2^(−1.5 − 7·gloss)`, a mirror at gloss 1), anisotropic with
//!   mia's split; highlights and reflections are this one distribution — unlike the
//!   classic shader, whose highlights are three Ward lobes and whose reflection rays come
//!   from jittered normals;
//! - diffuse: Oren–Nayar (without the classic shader's terminator smoothing, which would
//!   break reciprocity);
//! - transparency: GGX transmission through the interface (straight through when
//!   thin-walled), total internal reflection reflected;
//! - translucency: Lambert on the far side.
//!
//! Each lobe is reciprocal and energy conserving; the weights depend on the viewing
//! direction, as in the classic shader, so the sum is not reciprocal. With grey layer
//! colours the weights sum to at most 1, so the BSDF never creates energy.

pub mod lobes;

use glam::{Vec2, Vec3A};

use crate::color::luminance;
use crate::dielectric::refract;
use crate::microfacet::Ggx;
use crate::Rgb;
use crate::{cosine_hemisphere, BsdfSample, OrenNayar};

/// The roughness of glossiness `g` by NVIDIA's fit of mia's reflections
/// (`::base::architectural_gloss_to_rough`): √(2·2^(−4−14g)), 0 (a mirror) at 1.
pub fn gloss_to_roughness(g: f32) -> f32 {
    if g >= 1.0 {
        0.0
    } else {
        (2.0f32 * (2.0f32).powf(-4.0 - 14.0 * g.max(0.0))).sqrt()
    }
}

/// The anisotropic roughnesses (along the frame's x, y) for roughness `r` and mia's
/// `anisotropy` (the geometric mean is kept).
pub fn anisotropic_roughness(r: f32, anisotropy: f32) -> (f32, f32) {
    let (su, sv) = lobes::anisotropic_shininess(1.0, anisotropy);
    (r / su, r / sv)
}

/// The material at one shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MiaBsdf {
    /// Diffuse layer (Oren–Nayar with the conserved diffuse level as albedo).
    pub diffuse: OrenNayar,
    /// Reflection weight (curve at the viewing angle, tint, conservation).
    pub reflect: Rgb,
    /// Reflection micro-normals.
    pub reflect_ggx: Ggx,
    /// Transparency weight.
    pub transmit: Rgb,
    /// Refraction micro-normals.
    pub transmit_ggx: Ggx,
    /// Index inside over outside.
    pub eta: f32,
    /// Thin-walled: light goes straight through.
    pub thin: bool,
    /// Translucency weight.
    pub transl: Rgb,
}

fn reflect(w: Vec3A, n: Vec3A) -> Vec3A {
    -w + 2.0 * w.dot(n) * n
}

impl MiaBsdf {
    /// The lobes' selection probabilities: diffuse, reflection, transmission, translucency.
    fn probabilities(&self) -> [f32; 4] {
        let w =
            [luminance(self.diffuse.albedo), luminance(self.reflect), luminance(self.transmit), luminance(self.transl)];
        let sum: f32 = w.iter().sum();
        if sum <= 0.0 {
            return [0.0; 4];
        }
        w.map(|x| x / sum)
    }

    /// Whether all scattering is in Dirac lobes.
    pub fn is_delta(&self) -> bool {
        let p = self.probabilities();
        p[0] == 0.0 && p[3] == 0.0 && self.reflect_ggx.is_smooth() && (p[2] == 0.0 || self.transmit_ggx.is_smooth())
    }

    fn etap(&self, wo: Vec3A) -> f32 {
        if self.thin {
            1.0
        } else if wo.z > 0.0 {
            self.eta
        } else {
            1.0 / self.eta
        }
    }

    /// f(ωo, ωi) of the non-delta lobes.
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z == 0.0 || wi.z == 0.0 {
            return Rgb::ZERO;
        }
        let same = wo.z * wi.z > 0.0;
        let mut f = self.diffuse.eval(wo, wi);
        if !same {
            f += self.transl * std::f32::consts::FRAC_1_PI;
        }
        let side = wo.z.signum();
        if same && !self.reflect_ggx.is_smooth() {
            let h = (wo + wi).normalize() * side;
            f += self.reflect * (self.reflect_ggx.d(h) * self.reflect_ggx.g2(wo, wi) / (4.0 * (wo.z * wi.z).abs()));
        }
        if !self.transmit_ggx.is_smooth() && self.transmit != Rgb::ZERO {
            f += self.transmit * self.transmission(wo, wi);
        }
        f
    }

    /// The transmission lobe's f without its weight (straight through, or total internal
    /// reflection, as the geometry says).
    fn transmission(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let g = &self.transmit_ggx;
        let side = wo.z.signum();
        let same = wo.z * wi.z > 0.0;
        if self.thin {
            if same {
                return 0.0;
            }
            // The reflection mirrored through the sheet.
            let wr = Vec3A::new(wi.x, wi.y, -wi.z);
            let h = (wo + wr).normalize() * side;
            return g.d(h) * g.g2(wo, wr) / (4.0 * (wo.z * wi.z).abs());
        }
        let etap = self.etap(wo);
        if same {
            // Reflected where the micro-normal reflects totally.
            let h = (wo + wi).normalize() * side;
            if refract(wo, h * side, etap).is_some() {
                return 0.0;
            }
            return g.d(h) * g.g2(wo, wi) / (4.0 * (wo.z * wi.z).abs());
        }
        let mut h = (wi * etap + wo).normalize();
        if h.z < 0.0 {
            h = -h;
        }
        if h.dot(wi) * wi.z < 0.0 || h.dot(wo) * wo.z < 0.0 {
            return 0.0;
        }
        let denom = wi.dot(h) + wo.dot(h) / etap;
        g.d(h) * g.g2(wo, wi) * (wi.dot(h) * wo.dot(h)).abs() / (wi.z * wo.z * denom * denom).abs() / (etap * etap)
    }

    fn transmission_pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let g = &self.transmit_ggx;
        let side = wo.z.signum();
        let same = wo.z * wi.z > 0.0;
        let wv = wo * side;
        if self.thin {
            if same {
                return 0.0;
            }
            let wr = Vec3A::new(wi.x, wi.y, -wi.z);
            let h = (wo + wr).normalize() * side;
            return g.d_visible(wv, h) / (4.0 * wo.dot(h * side).abs());
        }
        let etap = self.etap(wo);
        if same {
            let h = (wo + wi).normalize() * side;
            if refract(wo, h * side, etap).is_some() {
                return 0.0;
            }
            return g.d_visible(wv, h) / (4.0 * wo.dot(h * side).abs());
        }
        let mut h = (wi * etap + wo).normalize();
        if h.z < 0.0 {
            h = -h;
        }
        if h.dot(wi) * wi.z < 0.0 || h.dot(wo) * wo.z < 0.0 {
            return 0.0;
        }
        let denom = wi.dot(h) + wo.dot(h) / etap;
        g.d_visible(wv, h) * wi.dot(h).abs() / (denom * denom)
    }

    /// The share (by luminance, 0..1) of f(ωo, ωi) that the glossy reflection lobe gives:
    /// the probability with which a sample in ωi is taken as a glossy reflection (mental
    /// ray's `mia_material` traces those as reflection rays); 0 on opposite sides or for a
    /// smooth reflection (a delta lobe, not in f).
    pub fn reflection_share(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z * wi.z <= 0.0 || self.reflect_ggx.is_smooth() {
            return 0.0;
        }
        let h = (wo + wi).normalize() * wo.z.signum();
        let glossy = self.reflect * (self.reflect_ggx.d(h) * self.reflect_ggx.g2(wo, wi) / (4.0 * (wo.z * wi.z).abs()));
        let all = luminance(self.eval(wo, wi));
        if all > 0.0 {
            (luminance(glossy) / all).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// Density of sampling ωi (non-delta lobes).
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z == 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        let p = self.probabilities();
        let same = wo.z * wi.z > 0.0;
        let side = wo.z.signum();
        let mut pdf = p[0] * self.diffuse.pdf(wo, wi);
        if !same {
            pdf += p[3] * wi.z.abs() * std::f32::consts::FRAC_1_PI;
        }
        if same && !self.reflect_ggx.is_smooth() {
            let h = (wo + wi).normalize() * side;
            pdf += p[1] * self.reflect_ggx.d_visible(wo * side, h) / (4.0 * wo.dot(h).abs());
        }
        if !self.transmit_ggx.is_smooth() {
            pdf += p[2] * self.transmission_pdf(wo, wi);
        }
        pdf
    }

    /// Samples a lobe by its weight, then a direction in it.
    pub fn sample(&self, wo: Vec3A, u: Vec2, u_lobe: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let p = self.probabilities();
        let side = wo.z.signum();
        let lobe = if u_lobe < p[0] {
            0
        } else if u_lobe < p[0] + p[1] {
            1
        } else if u_lobe < p[0] + p[1] + p[2] {
            2
        } else if p[3] > 0.0 {
            3
        } else {
            return None;
        };
        let wi = match lobe {
            0 | 3 => {
                let mut wi = cosine_hemisphere(u);
                if (lobe == 0) != (wo.z > 0.0) {
                    wi.z = -wi.z;
                }
                wi
            }
            1 => {
                if self.reflect_ggx.is_smooth() {
                    let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
                    return Some(BsdfSample { wi, f: self.reflect * (1.0 / wi.z.abs()), pdf: p[1], delta: true });
                }
                let h = self.reflect_ggx.sample_visible(wo * side, u) * side;
                let wi = reflect(wo, h);
                // Reflected through the surface by a steep micro-normal: the path ends.
                if wi.z * wo.z <= 0.0 {
                    return None;
                }
                wi
            }
            _ => {
                let g = &self.transmit_ggx;
                if g.is_smooth() {
                    let wi = if self.thin {
                        -wo
                    } else {
                        let etap = self.etap(wo);
                        match refract(wo, Vec3A::Z * side, etap) {
                            Some(t) => t,
                            None => Vec3A::new(-wo.x, -wo.y, wo.z),
                        }
                    };
                    let scale =
                        if wi.z * wo.z < 0.0 && !self.thin { 1.0 / (self.etap(wo) * self.etap(wo)) } else { 1.0 };
                    return Some(BsdfSample { wi, f: self.transmit * (scale / wi.z.abs()), pdf: p[2], delta: true });
                }
                let h = g.sample_visible(wo * side, u) * side;
                let (wi, through) = if self.thin {
                    let r = reflect(wo, h);
                    (Vec3A::new(r.x, r.y, -r.z), r.z * wo.z > 0.0)
                } else {
                    match refract(wo, h, self.etap(wo)) {
                        Some(t) => (t, t.z * wo.z < 0.0),
                        None => {
                            let r = reflect(wo, h);
                            (r, r.z * wo.z > 0.0)
                        }
                    }
                };
                // Scattered to the wrong side of the macro-surface: the path ends (`eval`
                // and `pdf` would count the direction under another half vector).
                if !through {
                    return None;
                }
                wi
            }
        };
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample { wi, f: self.eval(wo, wi), pdf, delta: false })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{albedo, chi_square};
    use crate::Bsdf;

    fn mia(diffuse: f32, reflect: f32, transmit: f32, transl: f32, gloss: f32, thin: bool) -> Bsdf {
        let r = gloss_to_roughness(gloss);
        Bsdf::Mia(MiaBsdf {
            diffuse: OrenNayar::new(Rgb::splat(diffuse), 0.3),
            reflect: Rgb::splat(reflect),
            reflect_ggx: Ggx::isotropic(r),
            transmit: Rgb::splat(transmit),
            transmit_ggx: Ggx::isotropic(r),
            eta: 1.5,
            thin,
            transl: Rgb::splat(transl),
        })
    }

    #[test]
    fn gloss_mapping_follows_nvidias_fit() {
        assert_eq!(gloss_to_roughness(1.0), 0.0);
        assert!((gloss_to_roughness(0.0) - (2.0f32 / 16.0).sqrt()).abs() < 1e-6);
        assert!((gloss_to_roughness(0.5) - 2f32.powf(-5.0)).abs() < 1e-6);
    }

    /// Sampling agrees with the density, for each layer and mixtures, seen from outside and
    /// from inside. (The test's quadrature resolves lobes down to about gloss 0.1: the
    /// transmitted lobe is three times narrower than the reflected one.)
    #[test]
    fn sampling_matches_the_density() {
        let wos = [Vec3A::new(0.4, 0.2, 0.89).normalize(), Vec3A::new(-0.7, 0.1, 0.3).normalize()];
        for b in [
            mia(0.8, 0.0, 0.0, 0.0, 0.5, false),
            mia(0.0, 0.5, 0.0, 0.0, 0.3, false),
            mia(0.0, 0.0, 0.9, 0.0, 0.0, false),
            mia(0.0, 0.0, 0.9, 0.0, 0.1, true),
            mia(0.3, 0.2, 0.4, 0.1, 0.1, false),
        ] {
            for wo in wos {
                chi_square(&b, wo);
                chi_square(&b, -wo);
            }
        }
    }

    /// A white furnace: with grey layers whose weights sum to 1 the BSDF scatters at most
    /// all the energy, from any direction. (From inside, radiance leaving the glass is
    /// expanded by η² — the 1/η² compression of radiance entering it, undone — so the bound
    /// there is η².)
    #[test]
    fn never_creates_energy() {
        for b in [
            mia(0.5, 0.5, 0.0, 0.0, 0.2, false),
            mia(0.2, 0.3, 0.4, 0.1, 0.6, false),
            mia(0.0, 0.2, 0.8, 0.0, 0.1, true),
            mia(0.0, 0.1, 0.9, 0.0, 0.0, false),
        ] {
            for i in 0..16 {
                let t = (i as f32 + 0.5) / 16.0 * 1.5;
                let wo = Vec3A::new(t.sin(), 0.0, t.cos());
                let a = albedo(&b, wo, 20_000);
                assert!(a.max_element() <= 1.0 + 0.01, "{b:?} from {wo}: albedo {a}");
                let a = albedo(&b, -wo, 20_000);
                assert!(a.max_element() <= 1.5 * 1.5 + 0.01, "{b:?} from inside {wo}: albedo {a}");
            }
        }
    }
}
