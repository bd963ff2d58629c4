//! Maya's highlight formulas and the lobe shapes built on them. Interface: the
//! formulas [`schlick`], [`blinn`], [`blinn_distribution`], [`ramp_blinn`], [`phong`],
//! [`phong_e`] and [`anisotropic`] (functions of the unit normal, view and light
//! directions, as the classic materials call them), and [`Shape`], one highlight with
//! its parameters in a local frame: its value, the density it is sampled by
//! (`sample`/`pdf`, for [`super::MayaBsdf`]) and its unit lobe's directional albedo.
//! All are re-exported by [`super`].

use std::f32::consts::{FRAC_1_PI, TAU};

use glam::{Vec2, Vec3A};

use super::ALBEDO_MIN_COS;
use crate::microfacet::Ggx;
use crate::Frame;

/// Schlick's approximation with reflectance `r0` at normal incidence, for the cosine `c`
/// between the view direction and the half vector (or the normal).
pub fn schlick(r0: f32, c: f32) -> f32 {
    r0 + (1.0 - r0) * (1.0 - c.clamp(0.0, 1.0)).powi(5)
}

/// Blinn's highlight (Blinn 1977, "Models of light reflection for computer synthesized
/// pictures", the model Maya's Blinn material names its parameters after): the
/// Trowbridge–Reitz distribution of eccentricity `ecc`, D = (e² / ((e² − 1)(N·H)² +
/// 1))², which is 1 at the peak; the Torrance–Sparrow masking G = min(1, 2(N·H)(N·V)/(V·H),
/// 2(N·H)(N·L)/(V·H)); a Fresnel factor whose value at normal incidence is
/// `specularRollOff`, F = schlick(rolloff, V·H); all over N·V:
/// D·G·F / (N·V). At the mirror peak seen head-on (V = L = N) it equals `rolloff`.
/// mira's reading: Maya's documentation names the parameters but not the Fresnel form.
pub fn blinn(n: Vec3A, v: Vec3A, l: Vec3A, ecc: f32, rolloff: f32) -> f32 {
    let (nv, nl) = (n.dot(v), n.dot(l));
    if nv <= 0.0 || nl <= 0.0 {
        return 0.0;
    }
    let Some(h) = (v + l).try_normalize() else { return 0.0 };
    let (nh, vh) = (n.dot(h).max(0.0), v.dot(h).max(1e-6));
    let g = 1f32.min(2.0 * nh * nv / vh).min(2.0 * nh * nl / vh);
    blinn_distribution(ecc, nh) * g * schlick(rolloff, vh) / nv
}

/// Blinn's distribution of eccentricity `ecc` at the cosine `nh` between the normal and
/// the half vector, D = (e² / ((e² − 1)(N·H)² + 1))²: 1 at the peak, 0 for `nh` ≤ 0.
pub fn blinn_distribution(ecc: f32, nh: f32) -> f32 {
    if nh <= 0.0 {
        return 0.0;
    }
    let e2 = blinn_e2(ecc);
    let d = e2 / ((e2 - 1.0) * nh * nh + 1.0);
    d * d
}

/// rampShader's highlight: Blinn's distribution D alone (no masking, Fresnel or 1/(N·V);
/// its peak 1), where the light and the viewer are both in front; the caller tints it
/// with `specularity` × the roll-off and `specularColor` ramps.
pub fn ramp_blinn(n: Vec3A, v: Vec3A, l: Vec3A, ecc: f32) -> f32 {
    if n.dot(l) <= 0.0 || n.dot(v) <= 0.0 {
        return 0.0;
    }
    let Some(h) = (v + l).try_normalize() else { return 0.0 };
    blinn_distribution(ecc, n.dot(h))
}

/// The squared eccentricity blinn uses (kept inside (0, 1): 1 would be a constant D).
fn blinn_e2(ecc: f32) -> f32 {
    (ecc * ecc).clamp(1e-6, 0.9999)
}

/// Phong's highlight: (R·L)^cosinePower, R the mirror image of the view direction.
pub fn phong(n: Vec3A, v: Vec3A, l: Vec3A, power: f32) -> f32 {
    if n.dot(l) <= 0.0 {
        return 0.0;
    }
    let r = 2.0 * n.dot(v) * n - v;
    r.dot(l).max(0.0).powf(power.max(0.0))
}

/// PhongE's highlight: (N·H)^p with p = 1/roughness² (a rough surface spreads it),
/// scaled by `highlightSize`; the caller tints it with `whiteness`. mira's reading:
/// Maya documents PhongE only qualitatively (a softer, cheaper Phong).
pub fn phong_e(n: Vec3A, v: Vec3A, l: Vec3A, roughness: f32, size: f32) -> f32 {
    if n.dot(l) <= 0.0 || n.dot(v) <= 0.0 {
        return 0.0;
    }
    let Some(h) = (v + l).try_normalize() else { return 0.0 };
    size * n.dot(h).max(0.0).powf(phong_e_exponent(roughness))
}

/// PhongE's exponent 1/roughness² (roughness clamped to 0.01..1).
fn phong_e_exponent(roughness: f32) -> f32 {
    let r = roughness.clamp(0.01, 1.0);
    1.0 / (r * r)
}

/// Maya's anisotropic highlight for the unit groove direction `x` (in the tangent plane of
/// `n`, the U direction turned by `angle`): a Ward distribution of half-vector slopes of
/// widths (`alpha_x`, `alpha_y`) along x and n × x, exp(−((H·x/α_x)² + (H·y/α_y)²)/(N·H)²),
/// 1 at the peak, times the dielectric Fresnel reflectance of index `ior`
/// (`fresnelRefractiveIndex`) at V·H relative to its value head-on, so that the peak seen
/// head-on is 1 and the highlight brightens towards grazing angles as Fresnel does.
pub fn anisotropic(n: Vec3A, v: Vec3A, l: Vec3A, x: Vec3A, alpha_x: f32, alpha_y: f32, ior: f32) -> f32 {
    if n.dot(l) <= 0.0 || n.dot(v) <= 0.0 {
        return 0.0;
    }
    let Some(h) = (v + l).try_normalize() else { return 0.0 };
    let nh = n.dot(h);
    if nh <= 0.0 {
        return 0.0;
    }
    let y = n.cross(x);
    let (sx, sy) = (h.dot(x) / alpha_x.max(1e-4), h.dot(y) / alpha_y.max(1e-4));
    let d = (-(sx * sx + sy * sy) / (nh * nh)).exp();
    let eta = ior.max(1.0 + 1e-4);
    d * crate::dielectric::fresnel(v.dot(h).max(0.0), eta) / crate::dielectric::fresnel(1.0, eta)
}

/// One of Maya's highlights with its parameters, in a local frame (+Z the normal; for
/// anisotropic, +X the grooves).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// [`blinn`] of `eccentricity` and `specularRollOff`.
    Blinn {
        /// `eccentricity`.
        eccentricity: f32,
        /// `specularRollOff`.
        rolloff: f32,
    },
    /// [`phong`] of `cosinePower`.
    Phong {
        /// `cosinePower`.
        power: f32,
    },
    /// [`phong_e`] of `roughness` and `highlightSize` (its `whiteness` is in the tint).
    PhongE {
        /// `roughness`.
        roughness: f32,
        /// `highlightSize`.
        size: f32,
    },
    /// [`ramp_blinn`] of `eccentricity` (rampShader's highlight).
    RampBlinn {
        /// `eccentricity`.
        eccentricity: f32,
    },
    /// [`anisotropic`] with the grooves along the local +X.
    Anisotropic {
        /// The highlight's width along the grooves.
        alpha_x: f32,
        /// The highlight's width across them.
        alpha_y: f32,
        /// `fresnelRefractiveIndex`.
        ior: f32,
    },
}

/// Reflects `w` about the unit vector `h`.
fn reflect(w: Vec3A, h: Vec3A) -> Vec3A {
    2.0 * w.dot(h) * h - w
}

impl Shape {
    /// The highlight H(v, l) for the local directions `v` (viewer) and `l` (light), both
    /// on the +Z side (0 otherwise).
    pub fn value(&self, v: Vec3A, l: Vec3A) -> f32 {
        let n = Vec3A::Z;
        match *self {
            Shape::Blinn { eccentricity, rolloff } => blinn(n, v, l, eccentricity, rolloff),
            Shape::Phong { power } => phong(n, v, l, power),
            Shape::PhongE { roughness, size } => phong_e(n, v, l, roughness, size),
            Shape::RampBlinn { eccentricity } => ramp_blinn(n, v, l, eccentricity),
            Shape::Anisotropic { alpha_x, alpha_y, ior } => anisotropic(n, v, l, Vec3A::X, alpha_x, alpha_y, ior),
        }
    }

    /// The GGX distribution blinn's highlight is drawn from: Maya's D is π e² times GGX's
    /// of α = e.
    fn ggx(eccentricity: f32) -> Ggx {
        Ggx::isotropic(blinn_e2(eccentricity).sqrt())
    }

    /// A direction `l` drawn from this lobe's sampling density given `v` (v.z > 0); `None`
    /// when the draw falls below the surface.
    #[inline]
    pub(super) fn sample(&self, v: Vec3A, u: Vec2) -> Option<Vec3A> {
        let l = match *self {
            Shape::Blinn { eccentricity, .. } | Shape::RampBlinn { eccentricity } => {
                reflect(v, Shape::ggx(eccentricity).sample_visible(v, u))
            }
            Shape::Phong { power } => {
                let r = Vec3A::new(-v.x, -v.y, v.z);
                Frame::from_normal(r).to_world(cosine_power_direction(power.max(0.0), u))
            }
            Shape::PhongE { roughness, .. } => reflect(v, cosine_power_direction(phong_e_exponent(roughness), u)),
            Shape::Anisotropic { alpha_x, alpha_y, .. } => {
                reflect(v, crate::beckmann::Beckmann::new(alpha_x, alpha_y).sample(u))
            }
        };
        (l.z > 0.0).then_some(l)
    }

    /// The density of [`Shape::sample`] at `l` given `v` (both z > 0), per solid angle.
    pub(super) fn pdf(&self, v: Vec3A, l: Vec3A) -> f32 {
        let Some(h) = (v + l).try_normalize() else { return 0.0 };
        let vh = v.dot(h);
        if vh <= 0.0 {
            return 0.0;
        }
        match *self {
            Shape::Blinn { eccentricity, .. } | Shape::RampBlinn { eccentricity } => {
                Shape::ggx(eccentricity).d_visible(v, h) / (4.0 * vh)
            }
            Shape::Phong { power } => {
                let r = Vec3A::new(-v.x, -v.y, v.z);
                cosine_power_pdf(power.max(0.0), r.dot(l))
            }
            Shape::PhongE { roughness, .. } => cosine_power_pdf(phong_e_exponent(roughness), h.z) / (4.0 * vh),
            Shape::Anisotropic { alpha_x, alpha_y, .. } => {
                crate::beckmann::Beckmann::new(alpha_x, alpha_y).d(h) * h.z / (4.0 * vh)
            }
        }
    }

    /// The unit lobe's directional albedo ∫ H(v, l)/π dω_l for the view cosine `mu`
    /// (v in the xz plane), by importance sampling on a 32 × 32 stratified grid
    /// (a few per cent; used to bound the lobe and to choose between lobes).
    pub fn albedo(&self, mu: f32) -> f32 {
        let mu = mu.clamp(ALBEDO_MIN_COS, 1.0);
        let v = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        const N: u32 = 32;
        let mut sum = 0.0f64;
        for i in 0..N {
            for j in 0..N {
                let u = Vec2::new((i as f32 + 0.5) / N as f32, (j as f32 + 0.5) / N as f32);
                if let Some(l) = self.sample(v, u) {
                    let pdf = self.pdf(v, l);
                    if pdf > 0.0 {
                        sum += f64::from(self.value(v, l) * FRAC_1_PI / pdf);
                    }
                }
            }
        }
        (sum / f64::from(N * N)) as f32
    }
}

/// A direction about +Z with density (p + 1)/(2π) cos^p θ.
fn cosine_power_direction(p: f32, u: Vec2) -> Vec3A {
    let c = u.x.powf(1.0 / (p + 1.0));
    let s = (1.0 - c * c).max(0.0).sqrt();
    let (sin_phi, cos_phi) = (TAU * u.y).sin_cos();
    Vec3A::new(s * cos_phi, s * sin_phi, c)
}

/// The density of [`cosine_power_direction`] at the cosine `c`.
fn cosine_power_pdf(p: f32, c: f32) -> f32 {
    if c <= 0.0 {
        return 0.0;
    }
    (p + 1.0) / TAU * c.powf(p)
}
