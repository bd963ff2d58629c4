//! `mib_glossy_refraction`'s `deep_material` in the path engine: the colour its glossy
//! rays fade into over `max_distance` ([`super::glossy_reach`] splits the segments).
//!
//! This follows mental ray's shader, not a physical medium: the classic shader runs the
//! deep material's shader once at the entry point (the hit of the glossy refraction
//! surface), with that point's state (its normal turned towards the view), and blends
//! each refracted or totally reflected ray's colour towards that one result. So a
//! `mib_illum_lambert` deep material gives the direct light of a Lambertian of its colour
//! from the lights on the view's side (no light arriving along the ray, no final
//! gathering), a constant colour (`mib_color_mix` …) that colour. The path engine runs
//! the same shader through the scene's shader graph at the same state (the path's sample
//! stream and bounce in place of the classic engine's pixel and sample, for the shader's
//! own sample numbers): the classic engine's estimate, its light loop and shadow rays
//! included.

use bsdf::Rgb;
use shader::{Ctx, NodeId, RayType, Shading, Slot, State, Tag, Value};

use crate::accel::{Accel, Hit};
use crate::ray::Ray;
use crate::tracer::{fill_state, SceneTracer};
use crate::world::World;

/// The deep material's colour at `hit` along `ray` on a surface of world material
/// `material`; black where there is no shader graph, the material's surface shader is not
/// a `mib_glossy_refraction`, or it names no deep material (the classic shader's fade to
/// black then). `site` (the path's sample stream and its bounce) stands in for the classic
/// engine's pixel, so the shader's own sample numbers (area-light positions, soft shadows)
/// differ from path to path and bounce to bounce, as they differ from pixel to pixel and
/// sample to sample there; `levels` are the path's (reflection, refraction) counts.
pub(super) fn colour(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    material: u32,
    (ray, hit): (&Ray, &Hit),
    site: [u32; 2],
    levels: (u32, u32),
) -> Rgb {
    let Some((shading, node)) = shading.and_then(|s| deep_node(s, material).map(|n| (s, n))) else {
        return Rgb::ZERO;
    };
    let tracer = SceneTracer::new(world, accel);
    let mut state = State {
        ray_type: RayType::Eye,
        org: ray.origin,
        dir: ray.dir,
        ior_in: 1.0,
        ior: 1.0,
        child_dist: f32::INFINITY,
        time: ray.time,
        pixel: site,
        reflection_level: levels.0,
        refraction_level: levels.1,
        ..State::default()
    };
    fill_state(world, hit, &mut state);
    let mut ctx = Ctx::new(shading, &tracer, state);
    let c = ctx.result(node).color();
    Rgb::new(c.x, c.y, c.z)
}

/// The `deep_material` shader of world material `material` (0: the default material)
/// whose surface shader is a `mib_glossy_refraction`.
fn deep_node(shading: &Shading, material: u32) -> Option<NodeId> {
    let refraction = &baselib::glossy::GLOSSY_REFRACTION;
    let m = shading.materials.get(material.checked_sub(1)? as usize)?;
    let n = shading.graph.nodes.get(m.surface? as usize)?;
    if !n.imp.is_some_and(|i| std::ptr::eq(i, refraction)) {
        return None;
    }
    let slot = refraction.params.iter().position(|p| *p == "deep_material")?;
    match n.slots.get(slot)? {
        Slot::Value(Value::Tag(Tag::Shader(deep))) | Slot::Connect { node: deep, member: None } => Some(*deep),
        _ => None,
    }
}
