//! Illumination shaders: the classic light loop with Lambert, Phong, Blinn, Cook–Torrance
//! and Ward highlights, the hair shader, and mira's diffuse stand-in.
//!
//! All follow one recipe (`shared/spec/shaders.md` §0.2):
//!
//! ```text
//! result = ambience ⊙ ambient
//! for each light L of the light list:   result += mean over L's samples of
//!     (N·L) diffuse ⊙ c  +  highlight(L) specular ⊙ c       (c: the light's colour)
//! result += diffuse ⊙ irradiance                             (final gathering)
//! result.a = 1
//! ```
//!
//! The light colours are mental ray's: no 1/π anywhere, a light of colour 1 straight above
//! a white Lambertian surface gives 1.

use glam::{Vec3A, Vec4};

use super::{rgb, rgba};
use bsdf::reflectance;
use shader::lights::LightSample;
use shader::{Ctx, NodeId, ShaderImpl, Value};

/// Parameter positions shared by the illumination shaders.
struct Layout {
    ambience: usize,
    ambient: usize,
    diffuse: usize,
    mode: usize,
    lights: usize,
}

/// The ambient term plus the light loop with `highlight` giving the specular colour for
/// each light sample, plus final gathering.
fn illuminate(ctx: &mut Ctx, n: NodeId, at: Layout, mut highlight: impl FnMut(&Ctx, &LightSample) -> Vec3A) -> Vec3A {
    let mut result = rgb(ctx.color(n, at.ambience)) * rgb(ctx.color(n, at.ambient));
    let diffuse = rgb(ctx.color(n, at.diffuse));
    let mode = ctx.int(n, at.mode);
    let lights = ctx.eval(n, at.lights);
    for light in ctx.light_list(mode, &lights) {
        let mut lp = ctx.light_loop(light);
        let mut sum = Vec3A::ZERO;
        while let Some(s) = ctx.sample_light(&mut lp) {
            let c = rgb(s.color);
            sum += s.dot_nl * diffuse * c + highlight(ctx, &s) * c;
        }
        if lp.samples > 0 {
            result += sum / lp.samples as f32;
        }
    }
    if diffuse != Vec3A::ZERO {
        result += diffuse * rgb(ctx.compute_irradiance());
    }
    result
}

fn finish(out: &mut Value, c: Vec3A) -> bool {
    *out = Value::Color(rgba(c, 1.0));
    true
}

/// Whether the state is one illumination shaders answer (not shadow or light work).
fn shades(ctx: &Ctx) -> bool {
    ctx.state.ray_type.is_visible()
}

/// `mib_illum_lambert (color ambience, color ambient, color diffuse, integer mode, array
/// light lights)`.
pub static LAMBERT: ShaderImpl = ShaderImpl {
    name: "mib_illum_lambert",
    params: &["ambience", "ambient", "diffuse", "mode", "lights"],
    run: lambert,
    photon: Some(crate::photon::illum_diffuse),
    ..ShaderImpl::PLAIN
};

fn lambert(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !shades(ctx) {
        return false;
    }
    let at = Layout { ambience: 0, ambient: 1, diffuse: 2, mode: 3, lights: 4 };
    let c = illuminate(ctx, n, at, |_, _| Vec3A::ZERO);
    finish(out, c)
}

/// `mib_illum_phong (… color specular, scalar exponent …)`: Phong's highlight
/// (R·L)^exponent, R the mirror direction of the view ray.
pub static PHONG: ShaderImpl = ShaderImpl {
    name: "mib_illum_phong",
    params: &["ambience", "ambient", "diffuse", "specular", "exponent", "mode", "lights"],
    run: phong,
    photon: Some(crate::photon::illum_diffuse),
    ..ShaderImpl::PLAIN
};

fn phong(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !shades(ctx) {
        return false;
    }
    let spec = rgb(ctx.color(n, 3));
    let exponent = ctx.scalar(n, 4);
    let at = Layout { ambience: 0, ambient: 1, diffuse: 2, mode: 5, lights: 6 };
    let c =
        illuminate(ctx, n, at, |ctx, s| spec * reflectance::phong(exponent, ctx.state.dir, ctx.state.normal, s.dir));
    finish(out, c)
}

/// `mib_illum_blinn (… color specular, scalar roughness, scalar ior …)`: the Blinn
/// (Torrance–Sparrow) highlight with a scalar Fresnel term.
pub static BLINN: ShaderImpl = ShaderImpl {
    name: "mib_illum_blinn",
    params: &["ambience", "ambient", "diffuse", "specular", "roughness", "ior", "mode", "lights"],
    run: blinn,
    photon: Some(crate::photon::illum_diffuse),
    ..ShaderImpl::PLAIN
};

fn blinn(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !shades(ctx) {
        return false;
    }
    let spec = rgb(ctx.color(n, 3));
    let roughness = ctx.scalar(n, 4);
    let ior = ctx.scalar(n, 5);
    let at = Layout { ambience: 0, ambient: 1, diffuse: 2, mode: 6, lights: 7 };
    let c = illuminate(ctx, n, at, |ctx, s| {
        spec * reflectance::blinn(ctx.state.dir, s.dir, ctx.state.normal, roughness, ior)
    });
    finish(out, c)
}

/// `mib_illum_cooktorr (… color specular, scalar roughness, color ior …)`: the
/// Cook–Torrance highlight with Fresnel per channel (colour shift at grazing angles).
pub static COOKTORR: ShaderImpl = ShaderImpl {
    name: "mib_illum_cooktorr",
    params: &["ambience", "ambient", "diffuse", "specular", "roughness", "ior", "mode", "lights"],
    run: cooktorr,
    photon: Some(crate::photon::illum_diffuse),
    ..ShaderImpl::PLAIN
};

fn cooktorr(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !shades(ctx) {
        return false;
    }
    let spec = rgb(ctx.color(n, 3));
    let roughness = ctx.scalar(n, 4);
    let ior = rgb(ctx.color(n, 5));
    let at = Layout { ambience: 0, ambient: 1, diffuse: 2, mode: 6, lights: 7 };
    let c = illuminate(ctx, n, at, |ctx, s| {
        spec * reflectance::cooktorr(ctx.state.dir, s.dir, ctx.state.normal, roughness, ior)
    });
    finish(out, c)
}

/// `mib_illum_ward (… color glossy, scalar shiny_u, scalar shiny_v, vector u, vector v
/// …)`: Ward's anisotropic glossy highlight along the brushing directions `u`, `v`.
pub static WARD: ShaderImpl = ShaderImpl {
    name: "mib_illum_ward",
    params: &["ambience", "ambient", "diffuse", "glossy", "shiny_u", "shiny_v", "u", "v", "mode", "lights"],
    run: ward,
    photon: Some(crate::photon::illum_diffuse),
    ..ShaderImpl::PLAIN
};

fn ward(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !shades(ctx) {
        return false;
    }
    let u = ctx.vector(n, 6);
    let v = ctx.vector(n, 7);
    ward_with(ctx, n, u, v, Layout { ambience: 0, ambient: 1, diffuse: 2, mode: 8, lights: 9 }, out)
}

fn ward_with(ctx: &mut Ctx, n: NodeId, u: Vec3A, v: Vec3A, at: Layout, out: &mut Value) -> bool {
    let glossy = rgb(ctx.color(n, 3));
    let (su, sv) = (ctx.scalar(n, 4), ctx.scalar(n, 5));
    // Equal widths: the isotropic form, for which u and v do not matter.
    let (u, v) = if su == sv {
        let f = bsdf::Frame::from_normal(ctx.state.normal);
        (f.tangent, f.bitangent)
    } else {
        (u, v)
    };
    let c = illuminate(ctx, n, at, |ctx, s| {
        glossy * reflectance::ward(ctx.state.dir, s.dir, ctx.state.normal, u, v, su, sv) * s.dot_nl
    });
    finish(out, c)
}

/// `mib_illum_ward_deriv`: `mib_illum_ward` with u from the surface (mental ray 3.7's
/// rule: the bump basis u of the first texture space if the geometry has one, else dP/du,
/// normalised) and v = N × u.
pub static WARD_DERIV: ShaderImpl = ShaderImpl {
    name: "mib_illum_ward_deriv",
    params: &["ambience", "ambient", "diffuse", "glossy", "shiny_u", "shiny_v", "mode", "lights"],
    run: ward_deriv,
    photon: Some(crate::photon::illum_diffuse),
    ..ShaderImpl::PLAIN
};

fn ward_deriv(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !shades(ctx) {
        return false;
    }
    let normal = ctx.state.normal;
    let d = ctx.state.bump_basis.map_or(ctx.state.derivs[0], |b| b[0]);
    let u = d.try_normalize().unwrap_or_else(|| bsdf::Frame::from_normal(normal).tangent);
    let v = normal.cross(u);
    ward_with(ctx, n, u, v, Layout { ambience: 0, ambient: 1, diffuse: 2, mode: 6, lights: 7 }, out)
}

/// `mib_illum_hair (… color specular, scalar exponent …)`: hair ribbons lit from the
/// hair tangent t (`derivs[0]`) as mental images' source has it: a diffuse term on a normal
/// blended between the scalp normal (`normal_geom`) and the part of it perpendicular to t,
/// darker towards the root; the highlight sin(t, H)^exponent; opacity falling from 1 at the
/// root to 0 at the tip, the rest let through to what lies behind. No indirect term. For
/// shadow rays it filters the light by `diffuse`.
pub static HAIR: ShaderImpl = ShaderImpl {
    name: "mib_illum_hair",
    params: &["ambience", "ambient", "diffuse", "specular", "exponent", "mode", "lights"],
    run: hair,
    ..ShaderImpl::PLAIN
};

/// Cubic smoothstep of `x` clamped to [a, b].
fn smooth(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

fn hair(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    use shader::RayType;
    if ctx.state.ray_type == RayType::Shadow {
        let d = rgb(ctx.color(n, 2));
        let c = out.color();
        *out = Value::Color(rgba(rgb(c) * d, c.w));
        return true;
    }
    if ctx.state.ray_type == RayType::Light {
        return false;
    }
    let s = &ctx.state;
    let t = s.hair.map_or(s.derivs[0], |h| h.tangent).normalize_or(Vec3A::Y);
    let along = s.hair.map_or(s.bary[1], |h| h.along);
    let scalp = s.hair.map_or(s.normal_geom, |h| h.root);
    let view = -s.dir;
    let hair_n = t.cross(scalp.cross(t));
    let b = scalp.dot(t);
    let ns = (hair_n * (1.0 - b) + scalp * b).normalize_or(s.normal);
    let ambient = rgb(ctx.color(n, 0)) * rgb(ctx.color(n, 1));
    let diffuse = rgb(ctx.color(n, 2)) * (0.5 + 0.5 * smooth(0.4, 0.8, along));
    let spec = rgb(ctx.color(n, 3));
    let exponent = ctx.scalar(n, 4);
    let mode = ctx.int(n, 5);
    let lights = ctx.eval(n, 6);
    let mut result = ambient;
    for light in ctx.light_list(mode, &lights) {
        let mut lp = ctx.light_loop(light);
        // The light sampler must not cull lights by the normal: hair has no back.
        lp.both_sides = true;
        let mut sum = Vec3A::ZERO;
        while let Some(sample) = ctx.sample_light(&mut lp) {
            let c = rgb(sample.color);
            let d = ns.dot(sample.dir).clamp(0.0, 1.0);
            sum += d * diffuse * c + reflectance::hair_specular(t, sample.dir, view, exponent) * spec * c;
        }
        if lp.samples > 0 {
            result += sum / lp.samples as f32;
        }
    }
    let alpha = 1.0 - smooth(0.3, 1.0, along);
    let mut c = rgba(result, alpha);
    if alpha < 0.9999 {
        let behind = ctx.trace_transparent().unwrap_or(Vec4::ZERO);
        c = rgba(rgb(behind) * (1.0 - alpha) + result * alpha, alpha + (1.0 - alpha) * behind.w);
    }
    *out = Value::Color(c);
    true
}

/// `mira_diffuse (color diffuse, color emission)`: mira's stand-in, in scenes rendered by
/// the classic engine, for materials that have no mental ray shader (MDL materials): the
/// Lambertian light loop over all lights with final gathering, plus the emission.
pub static MIRA_DIFFUSE: ShaderImpl = ShaderImpl {
    name: "mira_diffuse",
    params: &["diffuse", "emission"],
    run: mira_diffuse,
    photon: Some(crate::photon::stand_in_diffuse),
    ..ShaderImpl::PLAIN
};

fn mira_diffuse(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !shades(ctx) {
        return false;
    }
    let emission = rgb(ctx.color(n, 1));
    let diffuse = rgb(ctx.color(n, 0));
    let mut result = emission;
    for light in ctx.light_list(3, &Value::Null) {
        let mut lp = ctx.light_loop(light);
        let mut sum = Vec3A::ZERO;
        while let Some(s) = ctx.sample_light(&mut lp) {
            sum += s.dot_nl * diffuse * rgb(s.color);
        }
        if lp.samples > 0 {
            result += sum / lp.samples as f32;
        }
    }
    result += diffuse * rgb(ctx.compute_irradiance());
    finish(out, result)
}
