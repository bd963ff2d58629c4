//! Multi-sampled glossy reflection and refraction layered over other materials (mental
//! ray 3.6's `mib_glossy_reflection` and `mib_glossy_refraction`).
//!
//! Both cast `samples` rays spread around the mirror (or refracted) direction by a Ward
//! distribution of microfacet normals with widths `u_spread`, `v_spread` (radians, along
//! `u_axis`, `v_axis`; the surface's dP/du and its cross product with the normal when the
//! axes are not given) and average what the rays see. Spreads of zero give the perfect
//! mirror (or refraction) of `mib_reflect` / `mib_refract`. The traced colour is weighted by
//! the colour parameter times a view-angle curve
//! `w = base + (edge − base)·(1 − cos θ)^edge_factor` (θ between the normal and the view,
//! the curve mental ray's car-paint shaders use) and **added** to the base (`base_material`,
//! `top_material`), which the manual says is "simply added to the result".
//!
//! `max_distance` > 0 limits the rays: a hit at distance d fades towards the environment
//! (reflection) or the `deep_material` (refraction) by t = (d / max_distance)^falloff;
//! past the distance the ray sees only that. mira's readings where the manual is silent:
//! `samples` 0 casts nothing (the base alone); below the eye level the sample count is
//! quartered per level of depth (at least one ray); `dispersion` and `spectrum` are ignored.

use glam::{Vec2, Vec3A, Vec4};

use super::{rgb, rgba};
use shader::{Color, Ctx, NodeId, RayType, ShaderImpl, Tag, Value};

/// A direction a glossy lobe is built around: the surface frame and the spreads.
struct Lobe {
    u: Vec3A,
    v: Vec3A,
    n: Vec3A,
    spread_u: f32,
    spread_v: f32,
}

impl Lobe {
    /// The lobe at the state's shading normal with the axes of parameters `u_axis`, `v_axis`.
    fn new(ctx: &mut Ctx, node: NodeId, spreads: (usize, usize), axes: (usize, usize)) -> Lobe {
        let n = ctx.state.normal;
        let spread_u = ctx.scalar(node, spreads.0).max(0.0);
        let spread_v = ctx.scalar(node, spreads.1).max(0.0);
        let given = ctx.vector(node, axes.0);
        let base = if given.length_squared() > 0.0 { given } else { ctx.state.derivs[0] };
        let u = (base - n * base.dot(n)).try_normalize().unwrap_or_else(|| bsdf::Frame::from_normal(n).tangent);
        let v_given = ctx.vector(node, axes.1);
        let v = (v_given - n * v_given.dot(n) - u * v_given.dot(u)).try_normalize().unwrap_or_else(|| n.cross(u));
        Lobe { u, v, n, spread_u, spread_v }
    }

    /// Whether the lobe is a perfect mirror (one direction).
    fn is_sharp(&self) -> bool {
        self.spread_u <= 1e-6 && self.spread_v <= 1e-6
    }

    /// A microfacet normal drawn from Ward's distribution of slopes (Walter 2005's form of
    /// Ward 1992): φ from the aspect ratio of the spreads, tan²θ = −ln ξ / (cos²φ/αu² +
    /// sin²φ/αv²).
    fn half_vector(&self, u: Vec2) -> Vec3A {
        if self.is_sharp() {
            return self.n;
        }
        let (au, av) = (self.spread_u.max(1e-6), self.spread_v.max(1e-6));
        let a = std::f32::consts::TAU * u.y;
        let phi = (av * a.sin()).atan2(au * a.cos());
        let (s, c) = phi.sin_cos();
        let tan2 = -(1.0 - u.x).max(1e-12).ln() / (c * c / (au * au) + s * s / (av * av));
        let cos_t = 1.0 / (1.0 + tan2).sqrt();
        let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
        (self.u * (sin_t * c) + self.v * (sin_t * s) + self.n * cos_t).normalize()
    }
}

/// The view-angle weight `base + (edge − base)·(1 − cos θ)^factor`.
fn edge_weight(ctx: &Ctx, (base, edge, factor): (f32, f32, f32)) -> f32 {
    let cos = (-ctx.state.dir.dot(ctx.state.normal)).clamp(0.0, 1.0);
    base + (edge - base) * (1.0 - cos).powf(factor.max(0.0))
}

/// Rays a glossy shader casts at this depth: `samples` from the eye, a quarter per level
/// deeper, at least one.
fn ray_count(ctx: &Ctx, samples: i32) -> u32 {
    if samples <= 0 {
        return 0;
    }
    let level = ctx.state.reflection_level + ctx.state.refraction_level;
    ((samples as u32) >> (2 * level.min(15))).max(1)
}

/// The fade of a hit at distance `d` towards what lies beyond `max_distance`:
/// (d / max)^falloff, 1 for a miss, 0 without a limit.
pub fn distance_fade(d: f32, max_distance: f32, falloff: f32) -> f32 {
    if max_distance <= 0.0 {
        return 0.0;
    }
    if !d.is_finite() || d >= max_distance {
        return 1.0;
    }
    (d / max_distance).powf(falloff.max(0.0))
}

/// The environment along `dir`: the shader `env` if given (run for a ray leaving the
/// point), else the material's or camera's environment.
fn environment(ctx: &mut Ctx, env: Option<Tag>, dir: Vec3A) -> Color {
    match env {
        Some(Tag::Shader(node)) => {
            let mut ray = ctx.state.child(RayType::Environment, ctx.state.point, dir);
            ray.point = ray.org;
            ray.material = ctx.state.material;
            let mut sub = Ctx::new(ctx.shading(), ctx.tracer, ray);
            let mut out = Value::Color(Color::ZERO);
            sub.run_list(node, &mut out);
            ctx.counts.calls += sub.counts.calls;
            out.color()
        }
        _ => ctx.trace_environment(dir),
    }
}

/// The colour of a material-type parameter (a shader), or `None` if it is not given.
fn material(ctx: &mut Ctx, node: NodeId, i: usize) -> Option<Color> {
    match ctx.tag(node, i) {
        Some(Tag::Shader(s)) => Some(ctx.result(s).color()),
        _ => None,
    }
}

/// `mib_glossy_reflection`: `base_material` plus glossy reflections weighted by
/// `reflection_color` (hits) or `environment_color` (the environment: misses, rays past
/// `max_distance`, rays the depth limit forbids) and the view-angle curve.
pub static GLOSSY_REFLECTION: ShaderImpl = ShaderImpl {
    name: "mib_glossy_reflection",
    params: &[
        "base_material",
        "reflection_color",
        "max_distance",
        "falloff",
        "environment_color",
        "reflection_base_weight",
        "reflection_edge_weight",
        "edge_factor",
        "environment",
        "single_env_sample",
        "samples",
        "u_spread",
        "v_spread",
        "u_axis",
        "v_axis",
    ],
    run: glossy_reflection,
    ..ShaderImpl::PLAIN
};

fn glossy_reflection(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !ctx.state.ray_type.is_visible() {
        return false;
    }
    let base = material(ctx, n, 0).unwrap_or(Vec4::new(0.0, 0.0, 0.0, 1.0));
    let samples = ctx.int(n, 10);
    let count = ray_count(ctx, samples);
    let refl = rgb(ctx.color(n, 1));
    let env_color = rgb(ctx.color(n, 4));
    let curve = (ctx.scalar(n, 5), ctx.scalar(n, 6), ctx.scalar(n, 7));
    let w = edge_weight(ctx, curve);
    if count == 0 || w == 0.0 || (refl == Vec3A::ZERO && env_color == Vec3A::ZERO) {
        *out = Value::Color(base);
        return true;
    }
    let max_distance = ctx.scalar(n, 2).max(0.0);
    let falloff = ctx.scalar(n, 3);
    let env = ctx.tag(n, 8);
    let single_env = ctx.bool(n, 9);
    let lobe = Lobe::new(ctx, n, (11, 12), (13, 14));
    let count = if lobe.is_sharp() { 1 } else { count };
    let mirror = ctx.reflection_dir();
    let mut single: Option<Vec3A> = None;
    let mut env_along = |ctx: &mut Ctx, dir: Vec3A| -> Vec3A {
        if single_env {
            *single.get_or_insert_with(|| rgb(environment(ctx, env, mirror)))
        } else {
            rgb(environment(ctx, env, dir))
        }
    };
    let site = ctx.next_site();
    let (mut sum, mut used) = (Vec3A::ZERO, 0u32);
    let limit = if max_distance > 0.0 { max_distance } else { f32::MAX };
    for i in 0..count {
        let h = lobe.half_vector(ctx.sample2(site, i, count));
        let d = ctx.state.dir;
        let dir = (d - 2.0 * d.dot(h) * h).normalize_or(mirror);
        if dir.dot(ctx.state.normal_geom) <= 0.0 {
            continue;
        }
        used += 1;
        sum += match ctx.cast(RayType::Reflect, dir, limit) {
            Some((c, dist)) => {
                let t = if max_distance > 0.0 { distance_fade(dist, max_distance, falloff) } else { 0.0 };
                let far = dist.is_infinite() || t > 0.0;
                let e = if far { env_along(ctx, dir) * env_color } else { Vec3A::ZERO };
                if dist.is_infinite() {
                    e
                } else {
                    rgb(c) * refl * (1.0 - t) + e * t
                }
            }
            None => env_along(ctx, dir) * env_color,
        };
    }
    if used == 0 {
        // Every sampled direction went below the surface: the mirror's environment.
        sum = env_along(ctx, mirror) * env_color;
        used = 1;
    }
    let c = rgb(base) + sum * (w / used as f32);
    *out = Value::Color(rgba(c, base.w));
    true
}

/// `mib_glossy_refraction`: `top_material` (`back_material` where the ray hits the back of
/// the surface, shaded from the outside when `render_reverse_of_back_material` is on) plus
/// glossy refraction through a surface of index of refraction `ior` weighted by
/// `refraction_color` and the view-angle curve; under total internal reflection the
/// sampled direction reflects. With `max_distance` > 0 the refracted rays fade into
/// `deep_material`.
pub static GLOSSY_REFRACTION: ShaderImpl = ShaderImpl {
    name: "mib_glossy_refraction",
    params: &[
        "top_material",
        "deep_material",
        "back_material",
        "render_reverse_of_back_material",
        "refraction_color",
        "max_distance",
        "falloff",
        "refraction_base_weight",
        "refraction_edge_weight",
        "edge_factor",
        "ior",
        "samples",
        "u_spread",
        "v_spread",
        "u_axis",
        "v_axis",
    ],
    run: glossy_refraction,
    ..ShaderImpl::PLAIN
};

/// The back material seen from the outside: normals turned away from the ray.
fn reversed(ctx: &mut Ctx, n: NodeId, i: usize) -> Option<Color> {
    let saved = (ctx.state.normal, ctx.state.normal_geom, ctx.state.dot_nd, ctx.state.inv_normal);
    ctx.state.normal = -saved.0;
    ctx.state.normal_geom = -saved.1;
    ctx.state.dot_nd = -saved.2;
    ctx.state.inv_normal = !saved.3;
    ctx.flush_cache();
    let c = material(ctx, n, i);
    ctx.flush_cache();
    (ctx.state.normal, ctx.state.normal_geom, ctx.state.dot_nd, ctx.state.inv_normal) = saved;
    c
}

fn glossy_refraction(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !ctx.state.ray_type.is_visible() {
        return false;
    }
    let back = ctx.state.inv_normal;
    let top = if !back {
        material(ctx, n, 0)
    } else if ctx.bool(n, 3) {
        reversed(ctx, n, 2)
    } else {
        material(ctx, n, 2)
    };
    let top = top.map_or(Vec3A::ZERO, rgb);
    let samples = ctx.int(n, 11);
    let count = ray_count(ctx, samples);
    let refr = rgb(ctx.color(n, 4));
    let curve = (ctx.scalar(n, 7), ctx.scalar(n, 8), ctx.scalar(n, 9));
    let w = edge_weight(ctx, curve);
    if count == 0 || w == 0.0 || refr == Vec3A::ZERO {
        *out = Value::Color(rgba(top, 1.0));
        return true;
    }
    let max_distance = ctx.scalar(n, 5).max(0.0);
    let falloff = ctx.scalar(n, 6);
    let ior = ctx.scalar(n, 10);
    let ior = if ior > 0.0 { ior } else { 1.0 };
    let (ior_in, ior_out) = if back { (ior, 1.0) } else { (1.0, ior) };
    ctx.state.ior = ior;
    let lobe = Lobe::new(ctx, n, (12, 13), (14, 15));
    let count = if lobe.is_sharp() { 1 } else { count };
    let deep = if max_distance > 0.0 { material(ctx, n, 1).map_or(Vec3A::ZERO, rgb) } else { Vec3A::ZERO };
    let limit = if max_distance > 0.0 { max_distance } else { f32::INFINITY };
    let site = ctx.next_site();
    let (mut sum, mut used) = (Vec3A::ZERO, 0u32);
    for i in 0..count {
        let h = lobe.half_vector(ctx.sample2(site, i, count));
        let d = ctx.state.dir;
        let (kind, dir) = match shader::trace::refract(d, h, ior_in / ior_out) {
            Some(t) if ior_in != ior_out || !lobe.is_sharp() => (RayType::Refract, t),
            Some(_) => (RayType::Transparent, d),
            None => (RayType::Reflect, (d - 2.0 * d.dot(h) * h).normalize_or(ctx.state.normal)),
        };
        // A refracted ray must leave through the surface; a reflected one must not.
        let through = dir.dot(ctx.state.normal_geom) < 0.0;
        if through != (kind != RayType::Reflect) {
            continue;
        }
        used += 1;
        let Some((c, dist)) = ctx.cast(kind, dir, limit) else { continue };
        let t = distance_fade(dist, max_distance, falloff);
        sum += rgb(c) * (1.0 - t) + deep * t;
    }
    let c = if used > 0 { top + refr * sum * (w / used as f32) } else { top };
    *out = Value::Color(rgba(c, 1.0));
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_fade_follows_the_falloff_power() {
        assert_eq!(distance_fade(5.0, 0.0, 2.0), 0.0, "no limit: no fade");
        assert!((distance_fade(5.0, 10.0, 2.0) - 0.25).abs() < 1e-6);
        assert!((distance_fade(5.0, 10.0, 3.0) - 0.125).abs() < 1e-6);
        assert_eq!(distance_fade(f32::INFINITY, 10.0, 2.0), 1.0);
        assert_eq!(distance_fade(12.0, 10.0, 2.0), 1.0);
    }

    #[test]
    fn ward_half_vectors_follow_the_spreads() {
        let lobe = Lobe { u: Vec3A::X, v: Vec3A::Y, n: Vec3A::Z, spread_u: 0.2, spread_v: 0.05 };
        // Mean squared slope along each axis is α²/2 for Ward's distribution.
        let (mut su, mut sv) = (0.0f64, 0.0f64);
        let n = 4096;
        for i in 0..n {
            let u = Vec2::new((i as f32 + 0.5) / n as f32, ((i as f32 * 0.618_034) % 1.0).abs());
            let h = lobe.half_vector(u);
            su += f64::from((h.x / h.z).powi(2));
            sv += f64::from((h.y / h.z).powi(2));
        }
        let (su, sv) = (su / f64::from(n), sv / f64::from(n));
        assert!((su - 0.02).abs() < 0.002, "u slope variance {su}");
        assert!((sv - 0.00125).abs() < 0.000125, "v slope variance {sv}");
        let sharp = Lobe { spread_u: 0.0, spread_v: 0.0, ..lobe };
        assert_eq!(sharp.half_vector(Vec2::new(0.3, 0.7)), Vec3A::Z);
    }
}
