//! mental ray 3.7's built-in BSDFs (`builtin_bsdf_lambert`, `_phong`, `_ashikhmin`,
//! `_mirror`, `_architectural`; `shared/spec/shaders.md` §12) for a material's `bsdf` slot.
//!
//! [`BuiltinBsdf`] is the scattering function itself, in the local shading frame (+Z the
//! shading normal, directions pointing away from the surface, `eval` without the cosine),
//! like the BSDFs of the [`bsdf`] crate: the path engine uses it through
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

use bsdf::color::luminance;
use bsdf::mia::{anisotropic_roughness, gloss_to_roughness, MiaBsdf};
use bsdf::{BuiltinBsdf, Frame, Lambert, OrenNayar, Rgb};
use shader::{rgb, rgba, Ctx, NodeId, RayType, ShaderImpl, Value};

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
                reflect_ggx: bsdf::microfacet::Ggx { alpha_x: ax, alpha_y: ay },
                transmit: t * left_r,
                transmit_ggx: bsdf::microfacet::Ggx::isotropic(gloss_to_roughness(p.scalar("trans_gloss", 1.0))),
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
    build(shader::decl::declaration_name(decl), &mut ValueParams(param))
}

macro_rules! builtin {
    ($id:ident, $name:literal, [$($p:literal),*]) => {
        #[doc = concat!("`", $name, "` as the classic engine's material shader (see the module documentation).")]
        pub static $id: ShaderImpl = ShaderImpl { name: $name, params: &[$($p),*], run: |c, n, o| shade(c, n, o, &$id), ..ShaderImpl::PLAIN };
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
    use bsdf::Lambert;
    use glam::Vec3A;

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
