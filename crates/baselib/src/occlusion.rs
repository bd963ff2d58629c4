//! Ambient occlusion: probe rays over a cone around the normal (or the reflection
//! direction) measure how open the surroundings are.

use glam::{Vec2, Vec3A, Vec4};

use super::{rgb, rgba};
use bsdf::Frame;
use shader::{Ctx, NodeId, RayType, ShaderImpl, Value};

/// The settings of one occlusion probe.
struct Probe {
    samples: u32,
    bright: Vec4,
    dark: Vec4,
    /// How directions are spread around the axis.
    cone: Cone,
    max_distance: f32,
    reflective: bool,
    output_mode: i32,
    occlusion_in_alpha: bool,
    falloff: f32,
}

/// How probe directions are distributed.
#[derive(Clone, Copy)]
enum Cone {
    /// `mib_amb_occlusion`: a cosine-distributed direction d, then normalize(N (1 − s) + d s).
    Blend(f32),
    /// `mib_fast_occlusion`: uniform in the cone whose half-angle has this cosine.
    Cosine(f32),
}

fn probe_dir(axis: Vec3A, cone: Cone, u: Vec2) -> Vec3A {
    let frame = Frame::from_normal(axis);
    match cone {
        Cone::Blend(spread) => {
            let d = frame.to_world(bsdf::cosine_hemisphere(u));
            (axis * (1.0 - spread) + d * spread).normalize_or(axis)
        }
        Cone::Cosine(cos_max) => {
            let cos_t = 1.0 - u.x * (1.0 - cos_max);
            let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
            let phi = 2.0 * std::f32::consts::PI * u.y;
            frame.to_world(Vec3A::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t))
        }
    }
}

/// Encodes a unit vector as a colour: (v + 1)/2.
fn encode(v: Vec3A) -> Vec3A {
    (v.normalize_or_zero() + Vec3A::ONE) * 0.5
}

fn occlusion(ctx: &mut Ctx, p: Probe) -> Vec4 {
    let normal = ctx.state.normal;
    let site = ctx.next_site();
    let mut open = 0.0f32;
    let mut counted = 0u32;
    let mut bent = normal;
    let mut env = Vec3A::ZERO;
    let shadows = ctx.shading().shadows;
    for i in 0..p.samples {
        let u = ctx.sample2(site, i, p.samples);
        let mut d = probe_dir(normal, p.cone, u);
        if p.reflective {
            let dir = ctx.state.dir;
            d = dir - 2.0 * dir.dot(d) * d;
        }
        if d.dot(ctx.state.normal_geom) < 0.0 {
            continue;
        }
        counted += 1;
        let max = if p.max_distance > 0.0 { p.max_distance } else { f32::INFINITY };
        let hit = if shadows { ctx.probe(d, max) } else { None };
        match hit {
            Some(_) if p.max_distance <= 0.0 => {}
            Some(dist) => {
                let f = (dist / p.max_distance).powf(p.falloff);
                open += f;
                bent += d * f;
                if p.output_mode == 1 {
                    env += rgb(ctx.trace_environment(d)) * f;
                }
            }
            None => {
                open += 1.0;
                bent += d;
                if p.output_mode == 1 {
                    env += rgb(ctx.trace_environment(d));
                }
            }
        }
    }
    let n = counted.max(1) as f32;
    let o = open / n;
    let alpha = |a: f32| if p.occlusion_in_alpha { o } else { a };
    match p.output_mode {
        1 => rgba(rgb(p.dark) + rgb(p.bright) * env / n, alpha(1.0)),
        2 => rgba(encode(bent), alpha(1.0)),
        3 => {
            let cam = ctx.shading().world_to_camera;
            rgba(encode(cam.transform_vector3a(bent)), alpha(1.0))
        }
        4 => rgba(encode(ctx.state.normal_to_object(bent)), alpha(1.0)),
        _ => {
            if o <= 0.0 {
                p.dark
            } else if o >= 1.0 {
                p.bright
            } else {
                let mix = p.bright * o + p.dark * (1.0 - o);
                Vec4::new(mix.x, mix.y, mix.z, alpha(mix.w))
            }
        }
    }
}

/// `mib_amb_occlusion (integer samples, color bright, color dark, scalar spread, scalar
/// max_distance, boolean reflective, integer output_mode, boolean occlusion_in_alpha,
/// scalar falloff …)`, as mental images' source does it: `samples` probe rays, each a
/// cosine-distributed direction d pulled towards the normal as normalize(N (1 − spread) +
/// d · spread) (mirrored about d if `reflective`); rays below the geometric surface are not
/// counted. A hit occludes fully without `max_distance`, else by 1 − (dist/max)^falloff.
/// Output modes: 0 `bright` where open, `dark` where occluded, mixed by the open fraction
/// (alpha too, or the fraction with `occlusion_in_alpha`); 1 `dark` + `bright` ⊙ the
/// environment seen; 2, 3, 4 the bent normal in world, camera, object space, as (v + 1)/2.
/// With shadows off in the options no probe rays are cast (all open).
pub static AMB_OCCLUSION: ShaderImpl = ShaderImpl {
    name: "mib_amb_occlusion",
    params: &[
        "samples",
        "bright",
        "dark",
        "spread",
        "max_distance",
        "reflective",
        "output_mode",
        "occlusion_in_alpha",
        "falloff",
    ],
    run: amb_occlusion,
    ..ShaderImpl::PLAIN
};

fn amb_occlusion(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if ctx.state.ray_type == RayType::Shadow {
        *out = Value::Color(Vec4::ZERO);
        return true;
    }
    let falloff = ctx.scalar(n, 8);
    let p = Probe {
        samples: ctx.int(n, 0).max(0) as u32,
        bright: ctx.color(n, 1),
        dark: ctx.color(n, 2),
        cone: Cone::Blend(ctx.scalar(n, 3)),
        max_distance: ctx.scalar(n, 4),
        reflective: ctx.bool(n, 5),
        output_mode: ctx.int(n, 6),
        occlusion_in_alpha: ctx.bool(n, 7),
        falloff: if falloff > 0.0 { falloff } else { 1.0 },
    };
    *out = Value::Color(occlusion(ctx, p));
    true
}

/// `mib_fast_occlusion (integer samples, color bright, color dark, scalar spread, …,
/// scalar max_distance, boolean reflective, integer output_mode, boolean
/// occlusion_in_alpha …)`: the same probe with directions uniform in the cone whose
/// half-angle has cosine `spread` (0: the hemisphere), linear distance weighting, and 16
/// samples when `samples` is 0. mental ray answered it from its occlusion cache; mira
/// probes every point.
pub static FAST_OCCLUSION: ShaderImpl = ShaderImpl {
    name: "mib_fast_occlusion",
    params: &["samples", "bright", "dark", "spread", "max_distance", "reflective", "output_mode", "occlusion_in_alpha"],
    run: fast_occlusion,
    ..ShaderImpl::PLAIN
};

fn fast_occlusion(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let samples = ctx.int(n, 0);
    let p = Probe {
        samples: if samples > 0 { samples as u32 } else { 16 },
        bright: ctx.color(n, 1),
        dark: ctx.color(n, 2),
        cone: Cone::Cosine(ctx.scalar(n, 3).clamp(0.0, 1.0)),
        max_distance: ctx.scalar(n, 4),
        reflective: ctx.bool(n, 5),
        output_mode: ctx.int(n, 6),
        occlusion_in_alpha: ctx.bool(n, 7),
        falloff: 1.0,
    };
    *out = Value::Color(occlusion(ctx, p));
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encoded_normals_map_the_unit_sphere_to_the_unit_cube() {
        assert_eq!(encode(Vec3A::Z), Vec3A::new(0.5, 0.5, 1.0));
        assert_eq!(encode(-Vec3A::X), Vec3A::new(0.0, 0.5, 0.5));
    }
}
