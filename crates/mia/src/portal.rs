//! `mia_portal_light`: a light shader for an area light placed over a window, which brings
//! the environment seen through the window in as direct light (`shared/spec/mia.md` §4.1),
//! and the blocking of final gather rays by portals that goes with it.

use glam::Vec3A;

use shader::{rgb, rgba};
use shader::{Color, Ctx, NodeId, RayType, ShaderImpl, Tag, Value};

/// `mia_portal_light (boolean on, scalar multiplier, color tint_color, boolean reverse,
/// scalar cutoff_threshold, boolean shadows, boolean use_custom_environment, shader
/// custom_environment, boolean visible, color transparency)`.
///
/// On an area light (normally a rectangle over a window): the light reaching a point from
/// a sample on the portal is the environment radiance L seen from the point through the
/// sample (the camera's environment, or `custom_environment` when
/// `use_custom_environment` is on) × `tint_color` × `multiplier`. The portal emits to its
/// normal's side (the rectangle's local +Z; −Z with `reverse`), nothing behind it.
///
/// mira's reading of the radiometry: a sample's colour is L · cos θ_l · A / r² (θ_l the
/// angle at the portal, A its area, r the distance), so that the light loop's mean of
/// colour · cos θ over the samples estimates ∫ L cos θ dω over the window — the same
/// irradiance final gathering finds through the open window, on the base shaders'
/// convention (no 1/π). Samples whose L is below `cutoff_threshold` (largest channel)
/// are dropped without a shadow ray; `shadows` off casts none at all. `visible` and
/// `transparency` concern seeing the portal and are not read (the classic engine does not
/// show lights). Final gather rays that meet a portal are blocked (the shader is marked `portal`; see
/// `Shading::blocks_gather`).
pub static PORTAL_LIGHT: ShaderImpl = ShaderImpl {
    name: "mia_portal_light",
    params: &[
        "on",
        "multiplier",
        "tint_color",
        "reverse",
        "cutoff_threshold",
        "shadows",
        "use_custom_environment",
        "custom_environment",
    ],
    run: portal_light,
    portal: true,
    ..ShaderImpl::PLAIN
};

fn portal_light(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if !ctx.bool(n, 0) {
        return false;
    }
    let Some(light) = ctx.state.light.and_then(|l| ctx.light(l)) else { return false };
    let Some(shape) = &light.shape else { return false };
    let area = shape.area();
    let mut normal = shape.normal_at(light.origin, ctx.state.org);
    if ctx.bool(n, 3) {
        normal = -normal;
    }
    // `dir` runs from the portal to the lit point.
    let (dir, dist) = (ctx.state.dir, ctx.state.dist);
    let cos_l = normal.dot(dir);
    if cos_l <= 0.0 || dist.is_nan() || dist <= 0.0 || area <= 0.0 {
        return false;
    }
    let look = -dir;
    let env = match ctx.tag(n, 7) {
        Some(Tag::Shader(env)) if ctx.bool(n, 6) => environment_of(ctx, env, look),
        _ => rgb(ctx.trace_environment(look)),
    };
    let l = env * rgb(ctx.color(n, 2)) * ctx.scalar(n, 1);
    if l.max_element() < ctx.scalar(n, 4) {
        return false;
    }
    let mut c = rgba(l * (cos_l * area / (dist * dist)), 1.0);
    if ctx.bool(n, 5) {
        let mut filter = Color::ONE;
        if !ctx.trace_shadow(&mut filter) {
            return false;
        }
        c = rgba(rgb(c) * rgb(filter), 1.0);
    }
    *out = Value::Color(c);
    true
}

/// Runs the environment shader list `env` for a ray from the light state's point along
/// `dir`.
fn environment_of(ctx: &mut Ctx, env: NodeId, dir: Vec3A) -> Vec3A {
    let mut ray = ctx.state.child(RayType::Environment, ctx.state.point, dir);
    ray.point = ray.org;
    let mut sub = Ctx::new(ctx.shading(), ctx.tracer, ray);
    let mut result = Value::Color(Color::ZERO);
    sub.run_list(env, &mut result);
    ctx.counts.calls += sub.counts.calls;
    rgb(result.color())
}
