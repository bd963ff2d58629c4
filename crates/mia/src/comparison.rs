//! `mira_lobe_reflection`: glossy reflection the usual way — directions jittered in a
//! Ward lobe around the mirror direction, which is what mental ray's glossy reflection
//! functions give (and the author set mia's jittered normals against). It exists to show
//! the difference (`scenes/mia_reflections.mi`), not as part of any library.

use glam::Vec3A;

use bsdf::mia::lobes::{base_shininess, sample_ward_half};
use bsdf::Frame;
use shader::{rgb, rgba};
use shader::{Ctx, NodeId, ShaderImpl, Value};

/// `mira_lobe_reflection (color input, color reflect, scalar gloss, integer samples)`:
/// `input` plus `reflect` × the mean of `samples` rays in a Ward lobe of shininess
/// 2^(8·gloss) around the mirror direction (rays below the surface are dropped).
pub static LOBE_REFLECTION: ShaderImpl = ShaderImpl {
    name: "mira_lobe_reflection",
    params: &["input", "reflect", "gloss", "samples"],
    run: lobe_reflection,
    ..ShaderImpl::PLAIN
};

fn lobe_reflection(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let input = ctx.color(n, 0);
    let weight = rgb(ctx.color(n, 1));
    let shiny = base_shininess(ctx.scalar(n, 2));
    let count = ctx.int(n, 3).max(1) as u32;
    let count = if ctx.state.reflection_level + ctx.state.refraction_level > 0 { 1 } else { count };
    let mirror = ctx.reflection_dir();
    let frame = Frame::from_normal(mirror);
    let site = ctx.next_site();
    let mut sum = Vec3A::ZERO;
    for i in 0..count {
        let d = sample_ward_half(&frame, shiny, shiny, ctx.sample2(site, i, count));
        if d.dot(ctx.state.normal_geom) <= 0.0 {
            continue;
        }
        sum += ctx.trace_reflection(d).map_or(Vec3A::ZERO, rgb);
    }
    *out = Value::Color(rgba(rgb(input) + weight * sum / count as f32, input.w.max(1.0)));
    true
}
