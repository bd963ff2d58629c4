//! BSDFs: the closed set of scattering lobes mira's materials are built from.
//!
//! Conventions: directions are in the local shading frame (+Z = shading normal) and point
//! away from the surface; `eval` returns f(ωo, ωi) without the cosine; `sample` returns a
//! direction with `f · |cos θi| / pdf` as its weight; `pdf` is per unit solid angle.

mod albedo_grid;
pub mod beckmann;
pub mod builtin;
pub mod color;
pub mod conductor;
pub mod dielectric;
pub mod frame;
pub mod glass_multiscatter;
mod lambert;
pub mod layer_curve;
pub mod lobes;
pub mod maya_highlight;
pub mod measured_bsdf;
pub mod measured_curve;
pub mod measured_factor;
pub mod medium;
pub mod mia;
pub mod mib_glossy;
pub mod mib_glossy_refraction;
pub mod microfacet;
pub mod multiscatter;
mod oren_nayar;
pub mod phase;
pub mod reflectance;
pub mod rough_glass;
pub mod sheen;
pub mod sheen_albedo;
pub mod trig;
pub mod unified;
pub mod vcavity;

pub use builtin::BuiltinBsdf;
pub use color::{luminance, Rgb};
pub use conductor::Conductor;
pub use dielectric::Dielectric;
pub use frame::Frame;
pub use lambert::Lambert;
pub use layer_curve::{CurveKind, LayerCurve};
pub use lobes::{Lobe, LobeSum, Lobes, Role, SharedLobes, WideBsdf, WideLobes};
pub use maya_highlight::{MayaBsdf, MayaGlossy, Merged};
pub use medium::Medium;
pub use mia::MiaBsdf;
pub use mib_glossy::{MibGlossy, MibGlossyLobe};
pub use mib_glossy_refraction::{MibGlossyRefraction, MibGlossyRefractionLobe};
pub use oren_nayar::OrenNayar;
pub use phase::{HenyeyGreenstein, Phase, PhaseSample};
pub use unified::{Unified, UnifiedParams};

use glam::{Vec2, Vec3A};

/// A sampled direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// The incident direction ωi, local frame.
    pub wi: Vec3A,
    /// f(ωo, ωi).
    pub f: Rgb,
    /// Probability density of ωi per solid angle.
    pub pdf: f32,
    /// The lobe is a Dirac delta (mirror, smooth glass): `pdf` is a discrete probability.
    pub delta: bool,
}

impl BsdfSample {
    /// `f · |cos θi| / pdf`, the path throughput factor.
    #[inline]
    pub fn weight(&self) -> Rgb {
        if self.pdf > 0.0 {
            self.f * (self.wi.z.abs() / self.pdf)
        } else {
            Rgb::ZERO
        }
    }
}

/// A BSDF at one shading point. Every variant but [`Bsdf::Wide`] is plain data on the
/// stack (at most 416 bytes); `Wide` shares its sum ([`SharedLobes`], an `Arc`: cloning it
/// counts a reference, allocates nothing).
#[derive(Clone, Debug, PartialEq)]
pub enum Bsdf {
    /// Lambertian diffuse reflection.
    Lambert(Lambert),
    /// Oren–Nayar rough diffuse reflection.
    OrenNayar(OrenNayar),
    /// A dielectric interface.
    Dielectric(Dielectric),
    /// A metal: conductor Fresnel on GGX micro-mirrors, or a smooth mirror.
    Conductor(Conductor),
    /// `mia_material`'s layers.
    Mia(MiaBsdf),
    /// The unified (Disney-derived) material.
    Unified(Unified),
    /// mental ray's built-in BSDFs (`builtin_bsdf_*`).
    Builtin(BuiltinBsdf),
    /// A weighted sum of elemental lobes (MDL's mixes and layers of them).
    Lobes(Lobes),
    /// A sum of lobes too large for [`Bsdf::Lobes`] (more lobes, layer curves or own
    /// normals than a compact sum holds).
    Wide(WideBsdf),
    /// A Maya material: Lambert plus Maya's own highlight (blinn, phong, phongE,
    /// anisotropic), unnormalised as Maya computes it.
    Maya(MayaBsdf),
    /// mental ray's `mib_glossy_reflection`: a Ward-spread reflection (or mirror) over a
    /// Lambertian base, as the classic shader's estimate converges to.
    MibGlossy(MibGlossy),
    /// mental ray's `mib_glossy_refraction`: a Ward-spread refraction (or sharp one) under a
    /// Lambertian top, as the classic shader's estimate converges to.
    MibGlossyRefraction(MibGlossyRefraction),
}

impl Bsdf {
    /// f(ωo, ωi) of the non-delta lobes.
    #[inline]
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        match self {
            Bsdf::Lambert(l) => l.eval(wo, wi),
            Bsdf::OrenNayar(l) => l.eval(wo, wi),
            Bsdf::Dielectric(l) => l.eval(wo, wi),
            Bsdf::Conductor(l) => l.eval(wo, wi),
            Bsdf::Mia(l) => l.eval(wo, wi),
            Bsdf::Unified(l) => l.eval(wo, wi),
            Bsdf::Builtin(l) => l.eval(wo, wi),
            Bsdf::Lobes(l) => l.eval(wo, wi),
            Bsdf::Wide(l) => l.eval(wo, wi),
            Bsdf::Maya(l) => l.eval(wo, wi),
            Bsdf::MibGlossy(l) => l.eval(wo, wi),
            Bsdf::MibGlossyRefraction(l) => l.eval(wo, wi),
        }
    }

    /// Samples ωi given ωo, two uniform numbers for the direction and one for choosing a
    /// lobe.
    #[inline]
    pub fn sample(&self, wo: Vec3A, u: Vec2, u_lobe: f32) -> Option<BsdfSample> {
        match self {
            Bsdf::Lambert(l) => l.sample(wo, u),
            Bsdf::OrenNayar(l) => l.sample(wo, u),
            Bsdf::Dielectric(l) => l.sample(wo, u, u_lobe),
            Bsdf::Conductor(l) => l.sample(wo, u),
            Bsdf::Mia(l) => l.sample(wo, u, u_lobe),
            Bsdf::Unified(l) => l.sample(wo, u, u_lobe),
            Bsdf::Builtin(l) => l.sample(wo, u, u_lobe),
            Bsdf::Lobes(l) => l.sample(wo, u, u_lobe),
            Bsdf::Wide(l) => l.sample(wo, u, u_lobe),
            Bsdf::Maya(l) => l.sample(wo, u, u_lobe),
            Bsdf::MibGlossy(l) => l.sample(wo, u, u_lobe),
            Bsdf::MibGlossyRefraction(l) => l.sample(wo, u, u_lobe),
        }
    }

    /// Density of sampling ωi given ωo (non-delta lobes).
    #[inline]
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        match self {
            Bsdf::Lambert(l) => l.pdf(wo, wi),
            Bsdf::OrenNayar(l) => l.pdf(wo, wi),
            Bsdf::Dielectric(l) => l.pdf(wo, wi),
            Bsdf::Conductor(l) => l.pdf(wo, wi),
            Bsdf::Mia(l) => l.pdf(wo, wi),
            Bsdf::Unified(l) => l.pdf(wo, wi),
            Bsdf::Builtin(l) => l.pdf(wo, wi),
            Bsdf::Lobes(l) => l.pdf(wo, wi),
            Bsdf::Wide(l) => l.pdf(wo, wi),
            Bsdf::Maya(l) => l.pdf(wo, wi),
            Bsdf::MibGlossy(l) => l.pdf(wo, wi),
            Bsdf::MibGlossyRefraction(l) => l.pdf(wo, wi),
        }
    }

    /// Whether every lobe is a delta (no light sampling helps).
    #[inline]
    pub fn is_delta(&self) -> bool {
        match self {
            Bsdf::Lambert(_) | Bsdf::OrenNayar(_) | Bsdf::Maya(_) => false,
            Bsdf::Lobes(l) => l.is_delta(),
            Bsdf::Wide(l) => l.sum.is_delta(),
            Bsdf::Dielectric(d) => d.ggx.is_smooth() || d.eta == 1.0,
            Bsdf::Conductor(c) => c.ggx.is_smooth(),
            Bsdf::Mia(m) => m.is_delta(),
            Bsdf::Unified(u) => u.is_delta(),
            Bsdf::Builtin(b) => b.is_delta(),
            Bsdf::MibGlossy(g) => g.is_delta(),
            Bsdf::MibGlossyRefraction(g) => g.is_delta(),
        }
    }
}

/// Cosine-weighted direction on the +Z hemisphere (Malley's method, concentric disc).
#[inline]
pub fn cosine_hemisphere(u: Vec2) -> Vec3A {
    let d = concentric_disc(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3A::new(d.x, d.y, z)
}

/// A cosine-distributed direction on ωo's side of the surface (`None` when ωo lies in it).
#[inline]
pub fn cosine_on_side(wo: Vec3A, u: Vec2) -> Option<Vec3A> {
    if wo.z == 0.0 {
        return None;
    }
    let wi = cosine_hemisphere(u);
    Some(if wo.z < 0.0 { Vec3A::new(wi.x, wi.y, -wi.z) } else { wi })
}

/// The density of [`cosine_on_side`]: |cos θi|/π on ωo's side, 0 on the other.
#[inline]
pub fn cosine_pdf_on_side(wo: Vec3A, wi: Vec3A) -> f32 {
    if wo.z * wi.z > 0.0 {
        wi.z.abs() * std::f32::consts::FRAC_1_PI
    } else {
        0.0
    }
}

/// Samples a lobe sampled by cosine-weighted directions on ωo's side (Lambert,
/// Oren–Nayar): `eval(ωi)` is the lobe's f(ωo, ωi); the pdf is |cos θi|/π.
#[inline]
pub(crate) fn sample_cosine_lobe(wo: Vec3A, u: Vec2, eval: impl FnOnce(Vec3A) -> Rgb) -> Option<BsdfSample> {
    let wi = cosine_on_side(wo, u)?;
    let pdf = cosine_pdf_on_side(wo, wi);
    (pdf > 0.0).then(|| BsdfSample { wi, f: eval(wi), pdf, delta: false })
}

/// Uniform point on the unit disc (Shirley–Chiu concentric mapping).
#[inline]
pub fn concentric_disc(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    // The angle is π/4 · ratio in the x-major wedges, π/2 − π/4 · ratio in the y-major
    // ones: both take sin and cos of π/4 · ratio ∈ [−π/4, π/4], swapped in the latter.
    let x_major = o.x.abs() > o.y.abs();
    let (r, ratio) = if x_major { (o.x, o.y / o.x) } else { (o.y, o.x / o.y) };
    let (s, c) = trig::sin_cos_reduced(std::f32::consts::FRAC_PI_4 * ratio);
    if x_major {
        Vec2::new(r * c, r * s)
    } else {
        Vec2::new(r * s, r * c)
    }
}

pub mod testing;
