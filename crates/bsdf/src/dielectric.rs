//! A dielectric interface (glass, water): Fresnel-weighted reflection and refraction, smooth
//! (Dirac lobes) or rough (GGX microfacets, Walter et al. 2007), with the choice between
//! reflecting and refracting made by the Fresnel term and micro-normals sampled from the
//! visible normals.
//!
//! `eta` is the index inside over outside (the side the normal points to is outside).
//! Radiance crossing into a denser medium is compressed by 1/η² (the path tracer carries
//! radiance, not importance).

use glam::{Vec2, Vec3A};

use super::microfacet::Ggx;
use super::BsdfSample;
use crate::Rgb;

/// Unpolarised Fresnel reflectance of a dielectric for the cosine `cos_i` between the
/// incident direction and the normal on the side it comes from (negative: from inside)
/// and relative index `eta` (inside / outside). 1 under total internal reflection.
pub fn fresnel(cos_i: f32, eta: f32) -> f32 {
    let (cos_i, eta) = if cos_i < 0.0 { (-cos_i, 1.0 / eta) } else { (cos_i, eta) };
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// Refracts `w` (pointing away from the surface) about micro-normal `n` (on `w`'s side)
/// with relative index `eta` = n_transmitted / n_incident; `None` under total internal
/// reflection.
pub fn refract(w: Vec3A, n: Vec3A, eta: f32) -> Option<Vec3A> {
    let cos_i = n.dot(w);
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((-w / eta + n * (cos_i / eta - cos_t)).normalize())
}

fn reflect(w: Vec3A, n: Vec3A) -> Vec3A {
    -w + 2.0 * w.dot(n) * n
}

/// A dielectric boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric {
    /// Index inside over outside.
    pub eta: f32,
    /// Micro-normal distribution (smooth when tiny).
    pub ggx: Ggx,
    /// Tint of the reflection.
    pub reflect_tint: Rgb,
    /// Tint of the refraction.
    pub transmit_tint: Rgb,
    /// The share of the refracted light that passes through unscattered, 0 to 1: 1 for
    /// glass; the unified material's `spec_trans`, whose remainder its diffuse lobe
    /// takes. The choice between reflecting and refracting is sampled in proportion to
    /// F and (1 − F)·`transmission`.
    pub transmission: f32,
    /// Weight of the reflection, 0 to 1: the Fresnel term F becomes `specular`·F (1 for
    /// glass; MDL's `reflectivity` and the unified material's `specular`).
    pub specular: f32,
}

impl Dielectric {
    /// Clear glass (untinted, everything refracted passes through) of index `eta`.
    pub fn glass(eta: f32, ggx: Ggx) -> Dielectric {
        Dielectric { eta, ggx, reflect_tint: Rgb::ONE, transmit_tint: Rgb::ONE, transmission: 1.0, specular: 1.0 }
    }

    /// The weighted Fresnel reflectance for `cos` (negative: from inside).
    fn fresnel(&self, cos: f32) -> f32 {
        self.specular * fresnel(cos, self.eta)
    }

    /// The probability of choosing reflection for Fresnel reflectance `f`.
    fn reflect_probability(&self, f: f32) -> f32 {
        let total = f + (1.0 - f) * self.transmission;
        if total > 0.0 {
            f / total
        } else {
            0.0
        }
    }

    /// The relative index for the pair: 1 for reflection, η entering, 1/η leaving.
    fn etap(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z * wi.z > 0.0 {
            1.0
        } else if wo.z > 0.0 {
            self.eta
        } else {
            1.0 / self.eta
        }
    }

    /// f(ωo, ωi) (zero for smooth interfaces, whose lobes are Dirac deltas).
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if self.ggx.is_smooth() || self.eta == 1.0 || wo.z == 0.0 || wi.z == 0.0 {
            return Rgb::ZERO;
        }
        let reflect = wo.z * wi.z > 0.0;
        let etap = self.etap(wo, wi);
        let Some(h) = half_vector(wo, wi, etap) else { return Rgb::ZERO };
        // Discard back-facing micro-normals.
        if h.dot(wi) * wi.z < 0.0 || h.dot(wo) * wo.z < 0.0 {
            return Rgb::ZERO;
        }
        let f = self.fresnel(wo.dot(h));
        let d = self.ggx.d(h);
        // Λ depends on z² only: the sides do not matter.
        let g = self.ggx.g2(wo, wi);
        if reflect {
            self.reflect_tint * (d * g * f / (4.0 * (wo.z * wi.z).abs()))
        } else {
            let denom = wi.dot(h) + wo.dot(h) / etap;
            let ft = d * (1.0 - f) * g * (wi.dot(h) * wo.dot(h)).abs() / (wi.z * wo.z * denom * denom).abs();
            self.transmit_tint * (ft * self.transmission / (etap * etap))
        }
    }

    /// Samples ωi: a micro-normal from the visible normals, then reflection or refraction
    /// in proportion to F and (1 − F)·`transmission`.
    pub fn sample(&self, wo: Vec3A, u: Vec2, u_choice: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let side = wo.z.signum();
        if self.ggx.is_smooth() || self.eta == 1.0 {
            let n = Vec3A::Z * side;
            let f = if self.eta == 1.0 { 0.0 } else { self.fresnel(wo.z) };
            let p_reflect = self.reflect_probability(f);
            if u_choice < p_reflect {
                let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
                return Some(BsdfSample { wi, f: self.reflect_tint * (f / wi.z.abs()), pdf: p_reflect, delta: true });
            }
            if p_reflect >= 1.0 {
                return None;
            }
            let etap = if wo.z > 0.0 { self.eta } else { 1.0 / self.eta };
            let wi = refract(wo, n, etap)?;
            let ft = self.transmit_tint * ((1.0 - f) * self.transmission / (wi.z.abs() * etap * etap));
            return Some(BsdfSample { wi, f: ft, pdf: 1.0 - p_reflect, delta: true });
        }
        let h = self.ggx.sample_visible(wo * side, u) * side;
        // The Fresnel term takes the cosine on the outside-facing micro-normal.
        let f = self.fresnel(wo.dot(h * side));
        let reflected = u_choice < self.reflect_probability(f);
        let wi = if reflected {
            reflect(wo, h)
        } else {
            let etap = if wo.z > 0.0 { self.eta } else { 1.0 / self.eta };
            refract(wo, h, etap)?
        };
        // A reflection off a steep micro-normal can leave through the surface (and a
        // refraction come back out on wo's side): those paths end here, as `pdf` and
        // `eval` count them under the other lobe's half vector.
        if (wi.z * wo.z > 0.0) != reflected {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample { wi, f: self.eval(wo, wi), pdf, delta: false })
    }

    /// Density of sampling ωi.
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if self.ggx.is_smooth() || self.eta == 1.0 || wo.z == 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        let reflect = wo.z * wi.z > 0.0;
        let etap = self.etap(wo, wi);
        let Some(h) = half_vector(wo, wi, etap) else { return 0.0 };
        if h.dot(wi) * wi.z < 0.0 || h.dot(wo) * wo.z < 0.0 {
            return 0.0;
        }
        let side = wo.z.signum();
        let dv = self.ggx.d_visible(wo * side, h);
        let p_reflect = self.reflect_probability(self.fresnel(wo.dot(h)));
        if reflect {
            dv / (4.0 * wo.dot(h).abs()) * p_reflect
        } else {
            let denom = wi.dot(h) + wo.dot(h) / etap;
            dv * wi.dot(h).abs() / (denom * denom) * (1.0 - p_reflect)
        }
    }
}

/// The micro-normal (with z ≥ 0) that maps ωo to ωi for relative index `etap`
/// (1 for reflection).
fn half_vector(wo: Vec3A, wi: Vec3A, etap: f32) -> Option<Vec3A> {
    let h = wi * etap + wo;
    if h.length_squared() == 0.0 {
        return None;
    }
    let h = h.normalize();
    Some(if h.z < 0.0 { -h } else { h })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fresnel_values() {
        assert!((fresnel(1.0, 1.5) - 0.04).abs() < 1e-6);
        // From inside past the critical angle: total reflection.
        assert_eq!(fresnel(-0.5, 1.5), 1.0);
        // Brewster's angle: only s-polarised light reflects.
        let b = 1.5f32.atan();
        let rs = ((b.cos() - 1.5 * (1.0 - (b.sin() / 1.5).powi(2)).sqrt())
            / (b.cos() + 1.5 * (1.0 - (b.sin() / 1.5).powi(2)).sqrt()))
        .powi(2);
        assert!((fresnel(b.cos(), 1.5) - 0.5 * rs).abs() < 1e-5);
    }

    #[test]
    fn smooth_glass_splits_by_fresnel_and_refracts_by_snell() {
        let d = Dielectric::glass(1.5, Ggx::isotropic(0.0));
        let a = 40f32.to_radians();
        let wo = Vec3A::new(a.sin(), 0.0, a.cos());
        let r = d.sample(wo, Vec2::ZERO, 0.0).unwrap();
        assert!(r.delta && r.wi.z > 0.0);
        let t = d.sample(wo, Vec2::ZERO, 0.99).unwrap();
        assert!(t.wi.z < 0.0 && (t.wi.x + a.sin() / 1.5).abs() < 1e-5, "{}", t.wi);
        // Weights: reflection F·1, transmission (1 − F)/η² for radiance.
        let f = fresnel(a.cos(), 1.5);
        assert!((r.weight().x - 1.0).abs() < 1e-5);
        assert!((t.weight().x - 1.0 / 2.25).abs() < 1e-5, "{}", t.weight().x);
        assert!((r.pdf - f).abs() < 1e-6);
    }

    /// Sampling matches the density, from outside and from inside, smooth-ish to rough.
    #[test]
    fn sampling_matches_the_density() {
        for alpha in [0.15, 0.4] {
            let b = crate::Bsdf::Dielectric(Dielectric::glass(1.5, Ggx { alpha_x: alpha, alpha_y: alpha * 1.5 }));
            for wo in [Vec3A::new(0.4, 0.2, 0.89).normalize(), Vec3A::new(-0.7, 0.1, 0.3).normalize()] {
                crate::testing::chi_square(&b, wo);
                crate::testing::chi_square(&b, -wo);
            }
        }
    }

    /// Rough glass conserves energy (radiance carries 1/n² of it: a white furnace in
    /// n²-weighted radiance scatters at most all of it) and obeys
    /// the generalised reciprocity of refraction, f(a, b)/n(b)² = f(b, a)/n(a)².
    #[test]
    fn energy_and_generalised_reciprocity() {
        let d = Dielectric::glass(1.5, Ggx::isotropic(0.3));
        let n = |w: Vec3A| if w.z < 0.0 { 1.5f32 } else { 1.0 };
        for i in 0..12 {
            let t = (i as f32 + 0.5) / 12.0 * 1.5;
            for wo in [Vec3A::new(t.sin(), 0.0, t.cos()), Vec3A::new(t.sin(), 0.0, -t.cos())] {
                // Energy (radiance times n²) scattered: all of it less what the single-
                // scattering model loses to masking at rough, grazing angles.
                let mut energy = 0.0;
                for k in 0..20_000 {
                    let (u, u_choice) = crate::testing::r3(k);
                    if let Some(s) = d.sample(wo, u, u_choice) {
                        energy += s.weight().x * (n(s.wi) / n(wo)).powi(2);
                    }
                }
                energy /= 20_000.0;
                assert!(energy <= 1.0 + 0.01 && energy > 0.75, "from {wo}: {energy}");
            }
        }
        for i in 0..40 {
            let a = crate::testing::r2(i + 1);
            let c = crate::testing::r2(i + 101);
            let sph = |u: Vec2| {
                let z = 1.0 - 2.0 * u.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                Vec3A::new(r * (std::f32::consts::TAU * u.y).cos(), r * (std::f32::consts::TAU * u.y).sin(), z)
            };
            let (wa, wb) = (sph(a), sph(c));
            let (f1, f2) = (d.eval(wa, wb).x / (n(wb) * n(wb)), d.eval(wb, wa).x / (n(wa) * n(wa)));
            assert!((f1 - f2).abs() <= 1e-4 * f1.max(f2).max(1e-3), "{wa} {wb}: {f1} vs {f2}");
        }
    }
}
