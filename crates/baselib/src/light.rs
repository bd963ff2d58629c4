//! Light shaders (`mib_light_point`, `_spot`, `_infinite`, `_photometric`) and the shadow
//! shader `mib_shadow_transparency`.
//!
//! A light shader runs in a light state (see [`shader::lights`]): `dist` is the
//! distance from the light to the illuminated point and `dir` points from the light to it.
//! The base lights are not physical: the colour arrives undiminished by distance unless
//! `atten` asks for a linear ramp.

use scene::LightKind;

pub use shader::light::simple::spot_factor;
use shader::light::simple::{attenuation, constant, shadowed, SimpleLight};
use shader::{Color, Ctx, NodeId, ShaderImpl, Slot, Tag, Value};

/// Shadows of the base lights: with `shadow` on and `factor` < 1, the light is filtered by
/// the occluders' shadow shaders; what an occluder blocks is let through in proportion
/// `factor` (0 hard shadows, 1 none). Returns false if nothing arrives.
fn shadow(ctx: &mut Ctx, color: &mut Color, on: bool, factor: f32) -> bool {
    if !on || factor >= 1.0 {
        return true;
    }
    let mut filter = Color::ONE;
    let through = ctx.trace_shadow(&mut filter);
    match shadowed(*color, factor, through, filter) {
        Some(c) => {
            *color = c;
            true
        }
        None => false,
    }
}

/// `mib_light_point (color color, boolean shadow, scalar factor, boolean atten, scalar
/// start, scalar stop)`.
pub static POINT: ShaderImpl = ShaderImpl {
    name: "mib_light_point",
    params: &["color", "shadow", "factor", "atten", "start", "stop"],
    run: point,
    simple_light: Some(point_simple),
    ..ShaderImpl::PLAIN
};

/// `mib_light_point` with constant parameters as a [`SimpleLight`] (what [`point`]
/// computes).
fn point_simple(slots: &[Slot]) -> Option<SimpleLight> {
    let p = |i| constant(slots, i);
    let atten = match p(3)?.bool() {
        true => Some((p(4)?.scalar(), p(5)?.scalar())),
        false => None,
    };
    Some(SimpleLight { color: p(0)?.color(), atten, shadow: p(1)?.bool(), factor: p(2)?.scalar(), cone: None })
}

fn point(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let mut c = ctx.color(n, 0);
    if ctx.bool(n, 3) {
        let Some(a) = attenuation(ctx.state.dist, ctx.scalar(n, 4), ctx.scalar(n, 5)) else { return false };
        c *= a;
    }
    let (on, factor) = (ctx.bool(n, 1), ctx.scalar(n, 2));
    let ok = shadow(ctx, &mut c, on, factor);
    *out = Value::Color(c);
    ok
}

/// `mib_light_spot (color color, boolean shadow, scalar factor, boolean atten, scalar
/// start, scalar stop, scalar cone)`: no light outside the light's `spread` cone (a
/// cosine); between the inner `cone` (a cosine) and the spread the light falls off
/// linearly in the cosine.
pub static SPOT: ShaderImpl = ShaderImpl {
    name: "mib_light_spot",
    params: &["color", "shadow", "factor", "atten", "start", "stop", "cone"],
    run: spot,
    simple_light: Some(spot_simple),
    ..ShaderImpl::PLAIN
};

/// `mib_light_spot` with constant parameters as a [`SimpleLight`] (what [`spot`]
/// computes: the spot factor, then the ramp, then shadows).
fn spot_simple(slots: &[Slot]) -> Option<SimpleLight> {
    let cone = constant(slots, 6)?.scalar();
    Some(SimpleLight { cone: Some(cone), ..point_simple(slots)? })
}

fn spot(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(light) = ctx.state.light.and_then(|l| ctx.light(l)) else { return false };
    let c_axis = light.direction.dot(ctx.state.dir);
    let cone = ctx.scalar(n, 6);
    let Some(s) = spot_factor(c_axis, light.spread, cone) else { return false };
    let mut c = ctx.color(n, 0) * s;
    if ctx.bool(n, 3) {
        let Some(a) = attenuation(ctx.state.dist, ctx.scalar(n, 4), ctx.scalar(n, 5)) else { return false };
        c *= a;
    }
    let (on, factor) = (ctx.bool(n, 1), ctx.scalar(n, 2));
    let ok = shadow(ctx, &mut c, on, factor);
    *out = Value::Color(c);
    ok
}

/// `mib_light_infinite (color color, boolean shadow, scalar factor)`: a directional light.
pub static INFINITE: ShaderImpl = ShaderImpl {
    name: "mib_light_infinite",
    params: &["color", "shadow", "factor"],
    run: infinite,
    simple_light: Some(infinite_simple),
    ..ShaderImpl::PLAIN
};

/// `mib_light_infinite` with constant parameters as a [`SimpleLight`] (what [`infinite`]
/// computes).
fn infinite_simple(slots: &[Slot]) -> Option<SimpleLight> {
    let p = |i| constant(slots, i);
    Some(SimpleLight { color: p(0)?.color(), atten: None, shadow: p(1)?.bool(), factor: p(2)?.scalar(), cone: None })
}

fn infinite(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let mut c = ctx.color(n, 0);
    let (on, factor) = (ctx.bool(n, 1), ctx.scalar(n, 2));
    let ok = shadow(ctx, &mut c, on, factor);
    *out = Value::Color(c);
    ok
}

/// `mib_light_photometric (color color, boolean shadow, scalar factor, scalar start,
/// scalar stop, lightprofile profile)`: a point light falling off as 1/dist^exponent (the
/// light's `exponent`, 2 for the inverse square law); when `stop` > `start` > … the falloff
/// applies only between them (outside, the colour arrives unchanged, as in mental ray).
/// The colour is multiplied by the light profile's normalised value (intensity / peak) for
/// the direction from the light to the point, in the light's local frame (nadir = local −Z;
/// see [`shader::light::ies`]); without a `profile` the light's own `lightprofile`
/// statement is used, and without either (or with an unreadable one) the light is uniform.
pub static PHOTOMETRIC: ShaderImpl = ShaderImpl {
    name: "mib_light_photometric",
    params: &["color", "shadow", "factor", "start", "stop", "profile"],
    run: photometric,
    ..ShaderImpl::PLAIN
};

fn photometric(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let Some(light) = ctx.state.light.and_then(|l| ctx.light(l)) else { return false };
    let (exponent, kind, to_local, own) = (light.exponent, light.kind, light.to_local, light.profile);
    let mut c = ctx.color(n, 0);
    let (start, stop) = (ctx.scalar(n, 3), ctx.scalar(n, 4));
    let d = ctx.state.dist;
    let ranged = stop > start && stop > 0.0;
    if kind != LightKind::Directional && exponent > 0.0 && (!ranged || (d > start && d < stop)) && d > 0.0 {
        c *= d.powf(-exponent);
    }
    let shading = ctx.shading();
    let tagged = ctx.eval(n, 5);
    let profile = shading
        .lightprofile_of(&tagged)
        .or_else(|| own.and_then(|i| shading.lightprofiles.get(i as usize)?.as_deref()));
    if let Some(p) = profile {
        let f = p.normalized(to_local * ctx.state.dir);
        if f <= 0.0 {
            return false;
        }
        c *= f;
    }
    let (on, factor) = (ctx.bool(n, 1), ctx.scalar(n, 2));
    let ok = shadow(ctx, &mut c, on, factor);
    *out = Value::Color(c);
    ok
}

/// `physical_light (color color, scalar cone, scalar threshold, scalar cos_exp)` from the
/// physics library: a physically falling-off light. Point, spot and sphere lights give
/// color / (4π r^e) (e the light's `exponent`, 2 when 0); rectangle and disc lights
/// color · cos^cos_exp / (π r²), nothing behind their emitting side (cos_exp 0: 1);
/// directional lights the colour. Spot lights use `cone` as `mib_light_spot` does.
/// Below `threshold` (of the largest channel) the sample is dropped. Shadows are always
/// traced.
pub static PHYSICAL: ShaderImpl = ShaderImpl {
    name: "physical_light",
    params: &["color", "cone", "threshold", "cos_exp"],
    run: physical,
    ..ShaderImpl::PLAIN
};

fn physical(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    use shader::light::Shape;
    let Some(light) = ctx.state.light.and_then(|l| ctx.light(l)) else { return false };
    let (kind, shape, spread, direction, exponent) =
        (light.kind, &light.shape, light.spread, light.direction, light.exponent);
    let r = ctx.state.dist;
    // Flat shapes: the normal at the sampled point (an object light's triangle there).
    let flat = match shape {
        Some(Shape::Rect { normal, .. } | Shape::Disc { normal, .. }) => Some(*normal),
        Some(m @ Shape::Mesh(_)) => Some(m.normal_at(light.origin, ctx.state.org)),
        _ => None,
    };
    let f = match (kind, flat) {
        (LightKind::Directional, _) => 1.0,
        (_, Some(normal)) => {
            let cos = normal.dot(ctx.state.dir);
            if cos <= 0.0 {
                return false;
            }
            let e = ctx.scalar(n, 3);
            cos.powf(if e > 0.0 { e } else { 1.0 }) / (std::f32::consts::PI * r * r)
        }
        _ => {
            let e = if exponent > 0.0 { exponent } else { 2.0 };
            1.0 / (4.0 * std::f32::consts::PI * r.powf(e))
        }
    };
    let mut f = f;
    if kind == LightKind::Spot {
        let c = direction.dot(ctx.state.dir);
        let Some(s) = spot_factor(c, spread, ctx.scalar(n, 1)) else { return false };
        f *= s;
    }
    let mut c = ctx.color(n, 0) * f;
    if c.x.max(c.y).max(c.z) < ctx.scalar(n, 2) {
        return false;
    }
    let mut filter = Color::ONE;
    if !ctx.trace_shadow(&mut filter) {
        return false;
    }
    c *= filter;
    c.w = 1.0;
    *out = Value::Color(c);
    true
}

/// `mib_shadow_transparency (color color, color transp, integer mode, array light light)`:
/// a shadow shader. With t = 2 · transp · color.a per channel, the light is multiplied by
/// t · color where t < 1 (0: opaque, ½: filtered by `color`) and by (t − 1) + (2 − t) · color
/// above (1: clear). `mode` 0 and 1 apply it to the listed lights and 2 to the others —
/// for the rest the object casts no shadow at all; 3 and above apply it to every light.
pub static SHADOW_TRANSPARENCY: ShaderImpl = ShaderImpl {
    name: "mib_shadow_transparency",
    params: &["color", "transp", "mode", "light"],
    run: shadow_transparency,
    ..ShaderImpl::PLAIN
};

/// The factor `mib_shadow_transparency` multiplies the light by, per channel.
pub fn transparency_filter(color: Color, transp: Color) -> [f32; 3] {
    let mut f = [0.0; 3];
    for k in 0..3 {
        let t = transp[k] * color.w * 2.0;
        f[k] = if t < 1.0 { t * color[k] } else { (t - 1.0) + (2.0 - t) * color[k] };
    }
    f
}

fn shadow_transparency(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if ctx.state.ray_type != shader::RayType::Shadow {
        return false;
    }
    let mode = ctx.int(n, 2);
    if mode < 3 {
        let lights = ctx.eval(n, 3);
        let listed = ctx.state.light.is_some_and(|l| lights.array().iter().any(|v| v.tag() == Some(Tag::Light(l))));
        let applies = if mode == 2 { !listed } else { listed };
        if !applies {
            return true;
        }
    }
    let f = transparency_filter(ctx.color(n, 0), ctx.color(n, 1));
    let light = out.color();
    let passed = Color::new(light.x * f[0], light.y * f[1], light.z * f[2], light.w);
    *out = Value::Color(passed);
    passed.x != 0.0 || passed.y != 0.0 || passed.z != 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spot_falls_off_linearly_in_the_cosine_between_cone_and_spread() {
        assert_eq!(spot_factor(0.95, 0.8, 0.9), Some(1.0));
        assert!((spot_factor(0.85, 0.8, 0.9).unwrap() - 0.5).abs() < 1e-6);
        assert_eq!(spot_factor(0.79, 0.8, 0.9), None);
        assert_eq!(spot_factor(-0.5, -1.0, 0.9), None);
    }

    #[test]
    fn attenuation_is_a_linear_ramp() {
        assert_eq!(attenuation(1.0, 2.0, 4.0), Some(1.0));
        assert_eq!(attenuation(3.0, 2.0, 4.0), Some(0.5));
        assert_eq!(attenuation(4.0, 2.0, 4.0), None);
        // `atten on` with stop 0: no light anywhere.
        assert_eq!(attenuation(0.5, 0.0, 0.0), None);
    }

    #[test]
    fn shadow_transparency_runs_from_opaque_through_coloured_to_clear() {
        let red = Color::new(1.0, 0.0, 0.0, 1.0);
        assert_eq!(transparency_filter(red, Color::ZERO), [0.0; 3]);
        assert_eq!(transparency_filter(red, Color::splat(0.5)), [1.0, 0.0, 0.0]);
        assert_eq!(transparency_filter(red, Color::ONE), [1.0; 3]);
        let f = transparency_filter(red, Color::splat(0.75));
        assert!((f[0] - 1.0).abs() < 1e-6 && (f[1] - 0.5).abs() < 1e-6);
    }
}
