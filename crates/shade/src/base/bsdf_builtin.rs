//! mental ray 3.7's built-in BSDFs (`builtin_bsdf_lambert`, `_phong`, `_ashikhmin`,
//! `_mirror`, `_architectural`; `shared/spec/shaders.md` §12) for a material's `bsdf` slot.
//!
//! [`BuiltinBsdf`] is the scattering function itself, in the local shading frame (+Z the
//! shading normal, directions pointing away from the surface, `eval` without the cosine),
//! like the BSDFs of [`crate::bsdf`]: the path engine uses it through
//! [`builtin_bsdf_surface`]. The classic engine runs each as the material shader of a
//! material that has a `bsdf` but no material shader, as mental ray's default BSDF
//! illumination does: a light loop over the non-delta lobes, final gathering for the
//! diffuse part, one sampled ray for the glossy part when final gathering is on, and traced
//! rays for the delta lobes (mirror, specular transmission).
//!
//! Units (mira's reading): the base shaders' light colours carry no 1/π (a light of colour
//! 1 straight above a white `mib_illum_lambert` gives 1), so the direct term is
//! `π · f(ωo, ωi) · cos θi · light colour`; a Lambertian BSDF of reflectance ρ then shades
//! exactly as `mib_illum_lambert` with `diffuse` ρ. The diffuse indirect term is
//! `ρ ⊙ irradiance` as in the base shaders; glossy and mirror rays return the traced
//! radiance times f·cos/pdf (the mirror: times `reflection`, as `mib_reflect`).

use std::f32::consts::{FRAC_1_PI, PI, TAU};

use glam::{Vec2, Vec3A};

use super::{rgb, rgba};
use crate::bsdf::{cosine_on_side, cosine_pdf_on_side, BsdfSample, Lambert, OrenNayar};
use crate::color::luminance;
use crate::mia::bsdf::{anisotropic_roughness, gloss_to_roughness, MiaBsdf};
use crate::model::{Ctx, NodeId, RayType, ShaderImpl, Value};
use crate::{Frame, Rgb};

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
    fn mirror_weight(&self) -> Rgb {
        match self {
            BuiltinBsdf::Mirror(r) => *r,
            BuiltinBsdf::Architectural(m) if m.reflect_ggx.is_smooth() => m.reflect,
            _ => Rgb::ZERO,
        }
    }

    /// Whether some scattering is glossy (non-delta and not diffuse).
    fn has_glossy(&self) -> bool {
        match self {
            BuiltinBsdf::Phong { glossy, .. } | BuiltinBsdf::Ashikhmin { glossy, .. } => *glossy != Rgb::ZERO,
            BuiltinBsdf::Architectural(m) => !m.reflect_ggx.is_smooth() && m.reflect != Rgb::ZERO,
            _ => false,
        }
    }
}

/// Where a built-in BSDF's parameters come from.
trait Params {
    fn color(&mut self, name: &str, default: Rgb) -> Rgb;
    fn scalar(&mut self, name: &str, default: f32) -> f32;
    fn boolean(&mut self, name: &str, default: bool) -> bool;
}

/// Parameters of a shader node (its declaration's defaults already filled in).
struct NodeParams<'c, 'a> {
    ctx: &'c mut Ctx<'a>,
    node: NodeId,
    names: &'static [&'static str],
}

impl NodeParams<'_, '_> {
    fn index(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| *n == name)
    }
}

impl Params for NodeParams<'_, '_> {
    fn color(&mut self, name: &str, default: Rgb) -> Rgb {
        self.index(name).map_or(default, |i| rgb(self.ctx.color(self.node, i)))
    }
    fn scalar(&mut self, name: &str, default: f32) -> f32 {
        self.index(name).map_or(default, |i| self.ctx.scalar(self.node, i))
    }
    fn boolean(&mut self, name: &str, default: bool) -> bool {
        self.index(name).map_or(default, |i| self.ctx.bool(self.node, i))
    }
}

/// Constant parameters looked up by name.
struct ValueParams<'f>(&'f dyn Fn(&str) -> Option<Value>);

impl Params for ValueParams<'_> {
    fn color(&mut self, name: &str, default: Rgb) -> Rgb {
        (self.0)(name).map_or(default, |v| rgb(v.color()))
    }
    fn scalar(&mut self, name: &str, default: f32) -> f32 {
        (self.0)(name).map_or(default, |v| v.scalar())
    }
    fn boolean(&mut self, name: &str, default: bool) -> bool {
        (self.0)(name).map_or(default, |v| v.bool())
    }
}

/// The BSDF of declaration `name` from its parameters; `None` if `name` is not a
/// built-in BSDF.
fn build(name: &str, p: &mut dyn Params) -> Option<BuiltinBsdf> {
    let clamp = |c: Rgb| c.clamp(Rgb::ZERO, Rgb::ONE);
    Some(match name {
        "builtin_bsdf_lambert" => BuiltinBsdf::Lambert(Lambert { albedo: clamp(p.color("diffuse", Rgb::ZERO)) }),
        "builtin_bsdf_phong" => BuiltinBsdf::Phong {
            diffuse: clamp(p.color("diffuse", Rgb::ZERO)),
            glossy: clamp(p.color("glossy", Rgb::ZERO)),
            exponent: p.scalar("exponent", 0.0).max(0.0),
        },
        "builtin_bsdf_ashikhmin" => BuiltinBsdf::Ashikhmin {
            diffuse: clamp(p.color("diffuse", Rgb::ZERO)),
            glossy: clamp(p.color("glossy", Rgb::ZERO)),
            nu: p.scalar("exp_u", 0.0).max(0.0),
            nv: p.scalar("exp_v", 0.0).max(0.0),
        },
        "builtin_bsdf_mirror" => BuiltinBsdf::Mirror(clamp(p.color("reflection", Rgb::ZERO))),
        "builtin_bsdf_architectural" => {
            let d = clamp(p.color("diffuse_refl", Rgb::ZERO) * p.scalar("diffuse_refl_scalar", 1.0));
            let r = clamp(p.color("specular_refl", Rgb::ZERO) * p.scalar("specular_refl_scalar", 1.0));
            let t = clamp(p.color("specular_trans", Rgb::ZERO) * p.scalar("specular_trans_scalar", 1.0));
            let dt = clamp(p.color("diffuse_trans", Rgb::ZERO) * p.scalar("diffuse_trans_scalar", 1.0));
            // Layered from the top: reflection, specular transmission, translucency,
            // diffuse, each taking what the layers above leave (by luminance).
            let left_r = 1.0 - luminance(r).min(1.0);
            let left_t = left_r * (1.0 - luminance(t).min(1.0));
            let left_dt = left_t * (1.0 - luminance(dt).min(1.0));
            let metal = p.boolean("metal_material", true);
            let reflect = if metal { r * d } else { r };
            let (ax, ay) = anisotropic_roughness(
                gloss_to_roughness(p.scalar("refl_gloss", 1.0)),
                p.scalar("anisotropy", 1.0).max(1e-3),
            );
            BuiltinBsdf::Architectural(MiaBsdf {
                diffuse: OrenNayar::new(d * left_dt, p.scalar("diffuse_dev", 0.0).max(0.0)),
                reflect,
                reflect_ggx: crate::bsdf::microfacet::Ggx { alpha_x: ax, alpha_y: ay },
                transmit: t * left_r,
                transmit_ggx: crate::bsdf::microfacet::Ggx::isotropic(gloss_to_roughness(p.scalar("trans_gloss", 1.0))),
                eta: 1.0,
                thin: true,
                transl: dt * left_t,
            })
        }
        _ => return None,
    })
}

/// The built-in BSDF of declaration `decl` with constant parameters `param(name)`
/// (missing ones take the declaration's defaults), for the path engine; `None` when
/// `decl` is not a built-in BSDF. The path engine evaluates it as any other BSDF (local
/// shading frame, `eval` without the cosine, radiometric units: no π convention).
pub fn builtin_bsdf_surface(decl: &str, param: &dyn Fn(&str) -> Option<Value>) -> Option<BuiltinBsdf> {
    build(crate::material::declaration_name(decl), &mut ValueParams(param))
}

macro_rules! builtin {
    ($id:ident, $name:literal, [$($p:literal),*]) => {
        #[doc = concat!("`", $name, "` as the classic engine's material shader (see the module documentation).")]
        pub static $id: ShaderImpl = ShaderImpl { name: $name, params: &[$($p),*], run: |c, n, o| shade(c, n, o, &$id) };
    };
}

builtin!(LAMBERT, "builtin_bsdf_lambert", ["diffuse", "lights", "mode"]);
builtin!(PHONG, "builtin_bsdf_phong", ["diffuse", "glossy", "exponent", "lights", "mode"]);
builtin!(ASHIKHMIN, "builtin_bsdf_ashikhmin", ["diffuse", "glossy", "exp_u", "exp_v", "lights", "mode"]);
builtin!(MIRROR, "builtin_bsdf_mirror", ["reflection"]);
builtin!(
    ARCHITECTURAL,
    "builtin_bsdf_architectural",
    [
        "diffuse_refl",
        "diffuse_refl_scalar",
        "diffuse_dev",
        "specular_refl",
        "specular_refl_scalar",
        "refl_gloss",
        "metal_material",
        "specular_trans",
        "specular_trans_scalar",
        "trans_gloss",
        "diffuse_trans",
        "diffuse_trans_scalar",
        "anisotropy",
        "anisotropy_rotation",
        "mode",
        "lights"
    ]
);

/// The shading frame: the normal and, for anisotropic lobes, dP/du rotated by
/// `anisotropy_rotation` (turns) where given.
fn shading_frame(ctx: &mut Ctx, n: NodeId, imp: &ShaderImpl) -> Frame {
    let normal = ctx.state.normal;
    let du = ctx.state.bump_basis.map_or(ctx.state.derivs[0], |b| b[0]);
    let Some(t) = (du - normal * du.dot(normal)).try_normalize() else { return Frame::from_normal(normal) };
    let b = normal.cross(t);
    let turn = imp.params.iter().position(|p| *p == "anisotropy_rotation").map_or(0.0, |i| ctx.scalar(n, i));
    let (s, c) = (TAU * turn).sin_cos();
    Frame { tangent: t * c + b * s, bitangent: b * c - t * s, normal }
}

fn shade(ctx: &mut Ctx, n: NodeId, out: &mut Value, imp: &'static ShaderImpl) -> bool {
    if !ctx.state.ray_type.is_visible() {
        return false;
    }
    let Some(bsdf) = build(imp.name, &mut NodeParams { ctx, node: n, names: imp.params }) else { return false };
    let frame = shading_frame(ctx, n, imp);
    let wo = frame.to_local(-ctx.state.dir);
    let mut result = Rgb::ZERO;
    // Direct light over the non-delta lobes, in the base shaders' units (π · f · cos).
    if !bsdf.is_delta() {
        let index = |name: &str| imp.params.iter().position(|p| *p == name);
        let mode = index("mode").map_or(3, |i| ctx.int(n, i));
        let lights = index("lights").map_or(Value::Null, |i| ctx.eval(n, i));
        for light in ctx.light_list(mode, &lights) {
            let mut lp = ctx.light_loop(light);
            lp.both_sides = matches!(bsdf, BuiltinBsdf::Architectural(m) if m.transl != Rgb::ZERO);
            let mut sum = Rgb::ZERO;
            while let Some(s) = ctx.sample_light(&mut lp) {
                let wi = frame.to_local(s.dir);
                sum += bsdf.eval(wo, wi) * (PI * wi.z.abs()) * rgb(s.color);
            }
            if lp.samples > 0 {
                result += sum / lp.samples as f32;
            }
        }
        let diffuse = bsdf.diffuse_albedo();
        if diffuse != Rgb::ZERO {
            result += diffuse * rgb(ctx.compute_irradiance());
        }
    }
    // Delta reflection: the traced mirror ray (the environment past the depth limit).
    let mirror_weight = bsdf.mirror_weight();
    if mirror_weight != Rgb::ZERO {
        let dir = ctx.reflection_dir();
        let c = ctx.trace_reflection(dir).unwrap_or_else(|| ctx.trace_environment(dir));
        result += mirror_weight * rgb(c);
    }
    // Transmission (architectural): straight through, thin-walled.
    if let BuiltinBsdf::Architectural(m) = bsdf {
        if m.transmit != Rgb::ZERO {
            result += m.transmit * rgb(ctx.trace_transparent().unwrap_or_default());
        }
    }
    // One glossy sample when final gathering is on.
    if bsdf.has_glossy() && ctx.shading().finalgather.enabled && ctx.may_trace(RayType::Reflect) {
        let site = ctx.next_site();
        let u = ctx.sample2(site, 0, 1);
        let u_lobe = ctx.sample2(site + 1000, 0, 1).x;
        if let Some(s) = bsdf.sample(wo, u, u_lobe) {
            let diffuse_part = bsdf.diffuse_albedo() * FRAC_1_PI;
            let f = (s.f - diffuse_part).max(Rgb::ZERO);
            let dir = frame.to_world(s.wi);
            if !s.delta && s.pdf > 0.0 && f != Rgb::ZERO && dir.dot(ctx.state.normal_geom) > 0.0 {
                if let Some(c) = ctx.trace_reflection(dir) {
                    result += f * (s.wi.z.abs() / s.pdf) * rgb(c);
                }
            }
        }
    }
    *out = Value::Color(rgba(result, 1.0));
    true
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

    #[test]
    fn path_engine_reads_constant_parameters() {
        let p = |name: &str| match name {
            "diffuse" => Some(Value::Color(glam::Vec4::new(0.2, 0.4, 0.6, 1.0))),
            _ => None,
        };
        assert_eq!(
            builtin_bsdf_surface("builtin_bsdf_lambert", &p),
            Some(BuiltinBsdf::Lambert(Lambert { albedo: Rgb::new(0.2, 0.4, 0.6) }))
        );
        assert_eq!(builtin_bsdf_surface("mib_illum_lambert", &p), None);
        let a = builtin_bsdf_surface("builtin_bsdf_architectural", &|_| None).unwrap();
        assert!(a.is_delta() || a.eval(Vec3A::Z, Vec3A::Z) == Rgb::ZERO, "black by default");
    }
}
