//! Ray-tracing compositors: reflection, refraction, transparency, opacity, dielectric,
//! two-sided materials and the refraction index of nested media.
//!
//! Inputs are evaluated only when their value can show in the result: a fully reflective
//! `mib_reflect` never runs its `input`, a fully opaque `mib_refract` never traces.

use std::sync::Arc;

use glam::Vec4;

use super::{is_one, is_zero};
use shader::{Color, Ctx, NodeId, RayType, ShaderImpl, Value};

/// Blends per component: `traced ⊙ weight + input ⊙ (1 − weight)`, reading `input` only
/// if some component of `weight` is below one.
fn blend(ctx: &mut Ctx, node: NodeId, input: usize, traced: Color, weight: Color) -> Color {
    if is_one(weight) {
        return traced;
    }
    let i = ctx.color(node, input);
    traced * weight + i * (Vec4::ONE - weight)
}

/// `mib_reflect (color input, color reflect, boolean notrace)`: mirror reflection mixed
/// over `input` by `reflect`. With `notrace`, or past the reflection depth, the
/// environment is looked up instead of tracing.
pub static REFLECT: ShaderImpl =
    ShaderImpl { name: "mib_reflect", params: &["input", "reflect", "notrace"], run: reflect, ..ShaderImpl::PLAIN };

fn reflect(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let weight = ctx.color(n, 1);
    if is_zero(weight) {
        *out = Value::Color(ctx.color(n, 0));
        return true;
    }
    let dir = ctx.reflection_dir();
    let traced = if ctx.bool(n, 2) { None } else { ctx.trace_reflection(dir) };
    let traced = traced.unwrap_or_else(|| ctx.trace_environment(dir));
    *out = Value::Color(blend(ctx, n, 0, traced, weight));
    true
}

/// Traces through the surface with relative index `ior` (outside / inside as mental ray's
/// `mi_refraction_dir(…, 1, ior)`): a straight transparent ray for 0 or 1, a refracted ray
/// otherwise, a reflected ray under total internal reflection. Black past the depth limit.
fn refract_through(ctx: &mut Ctx, ior: f32) -> Color {
    if ior == 0.0 || ior == 1.0 {
        return ctx.trace_transparent().unwrap_or(Color::ZERO);
    }
    match ctx.refraction_dir(1.0, ior) {
        Some(dir) => ctx.trace_refraction(dir),
        None => {
            let dir = ctx.reflection_dir();
            ctx.trace_reflection(dir)
        }
    }
    .unwrap_or(Color::ZERO)
}

/// `mib_refract (color input, color refract, scalar ior)`: refraction mixed over `input`
/// by `refract` (the `ior` is relative: that of the medium entered over the medium left,
/// as `mib_refraction_index` gives it).
pub static REFRACT: ShaderImpl =
    ShaderImpl { name: "mib_refract", params: &["input", "refract", "ior"], run: refract, ..ShaderImpl::PLAIN };

fn refract(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let weight = ctx.color(n, 1);
    if is_zero(weight) {
        *out = Value::Color(ctx.color(n, 0));
        return true;
    }
    let ior = ctx.scalar(n, 2);
    let traced = refract_through(ctx, ior);
    *out = Value::Color(blend(ctx, n, 0, traced, weight));
    true
}

/// `mib_transparency (color input, color transp)`: the ray continued straight through,
/// mixed over `input` by `transp`.
pub static TRANSPARENCY: ShaderImpl =
    ShaderImpl { name: "mib_transparency", params: &["input", "transp"], run: transparency, ..ShaderImpl::PLAIN };

/// Transparency compositors answer shadow rays with transparent black (mental ray's
/// sources do so): they are not shadow shaders.
fn shadow_ray(ctx: &Ctx, out: &mut Value) -> bool {
    if ctx.state.ray_type == RayType::Shadow {
        *out = Value::Color(Color::ZERO);
        return true;
    }
    false
}

fn transparency(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if shadow_ray(ctx, out) {
        return true;
    }
    let weight = ctx.color(n, 1);
    if is_zero(weight) {
        *out = Value::Color(ctx.color(n, 0));
        return true;
    }
    let traced = ctx.trace_transparent().unwrap_or(Color::ZERO);
    *out = Value::Color(blend(ctx, n, 0, traced, weight));
    true
}

/// `mib_continue (color input, color transp)`: as `mib_transparency` (mental ray 3.x
/// kept it for older scenes).
pub static CONTINUE: ShaderImpl =
    ShaderImpl { name: "mib_continue", params: &["input", "transp"], run: transparency, ..ShaderImpl::PLAIN };

/// `mib_opacity (color input, color opacity)`: `input` where opaque, the ray continued
/// through where not: `input ⊙ opacity + behind ⊙ (1 − opacity)`.
pub static OPACITY: ShaderImpl =
    ShaderImpl { name: "mib_opacity", params: &["input", "opacity"], run: opacity, ..ShaderImpl::PLAIN };

fn opacity(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if shadow_ray(ctx, out) {
        return true;
    }
    let o = ctx.color(n, 1);
    if is_one(o) {
        *out = Value::Color(ctx.color(n, 0));
        return true;
    }
    let behind = ctx.trace_transparent().unwrap_or(Color::ZERO);
    let input = if is_zero(o) { Color::ZERO } else { ctx.color(n, 0) };
    *out = Value::Color(input * o + behind * (Vec4::ONE - o));
    true
}

/// `mib_dielectric (color input, color absorb, scalar refract, scalar ior)`: refraction
/// through a dielectric of index `ior` (entering on the front side, leaving on the back),
/// attenuated by the distance the refracted ray travels: each channel with `absorb` > 0 is
/// multiplied by `absorb^d`; then mixed over `input` by the scalar `refract`.
pub static DIELECTRIC: ShaderImpl = ShaderImpl {
    name: "mib_dielectric",
    params: &["input", "absorb", "refract", "ior"],
    run: dielectric,
    photon: Some(crate::photon::dielectric_glass),
    ..ShaderImpl::PLAIN
};

fn dielectric(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if matches!(ctx.state.ray_type, RayType::Shadow | RayType::Light) {
        return false;
    }
    let amount = ctx.scalar(n, 2);
    if amount == 0.0 {
        *out = Value::Color(ctx.color(n, 0));
        return true;
    }
    let ior = ctx.scalar(n, 3);
    let relative = if ctx.state.inv_normal && ior != 0.0 { 1.0 / ior } else { ior };
    let mut c = refract_through(ctx, relative);
    let d = ctx.state.child_dist;
    let absorb = ctx.color(n, 1);
    if d.is_finite() {
        for k in 0..3 {
            if absorb[k] > 0.0 {
                c[k] *= absorb[k].powf(d);
            }
        }
    }
    if amount < 1.0 {
        let input = ctx.color(n, 0);
        c = c * amount + input * (1.0 - amount);
    }
    *out = Value::Color(c);
    true
}

/// `mib_refraction_index (scalar mtl_ior)` → `struct { scalar ior, boolean enter }`:
/// whether the ray enters or leaves the current material (decided by the media the ray
/// has passed through, not by the normal) and the relative index of refraction (outgoing
/// over incoming). Sets the state's `ior_in` and `ior` for the refraction that follows.
pub static REFRACTION_INDEX: ShaderImpl =
    ShaderImpl { name: "mib_refraction_index", params: &["mtl_ior"], run: refraction_index, ..ShaderImpl::PLAIN };

fn refraction_index(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let mtl = ctx.scalar(n, 0);
    let mtl = if mtl > 0.0 { mtl } else { 1.0 };
    let s = &ctx.state;
    let material = s.material.unwrap_or(u32::MAX);
    let (enter, ior_in, ior_out) = if s.inside(material) {
        // Leaving: the medium outside is the one entered before this material.
        let mut outward = s.media.iter().rev().skip_while(|m| m.material != material);
        let outside = outward.nth(1).map_or(1.0, |m| m.ior);
        (false, mtl, outside)
    } else {
        (true, s.medium().map_or(1.0, |m| m.ior), mtl)
    };
    ctx.state.ior_in = ior_in;
    ctx.state.ior = ior_out;
    *out = Value::Struct(Arc::from(vec![
        (Arc::from("ior"), Value::Scalar(ior_out / ior_in)),
        (Arc::from("enter"), Value::Bool(enter)),
    ]));
    true
}

/// `mib_twosided (color front, color back)`: `back` where the ray hit the back of the
/// surface, `front` elsewhere; only the side returned is evaluated.
pub static TWOSIDED: ShaderImpl =
    ShaderImpl { name: "mib_twosided", params: &["front", "back"], run: twosided, ..ShaderImpl::PLAIN };

fn twosided(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let side = if ctx.state.inv_normal { 1 } else { 0 };
    *out = Value::Color(ctx.color(n, side));
    true
}
