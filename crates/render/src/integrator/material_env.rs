//! A material's own `environment` shader list in the path engine: mental ray gives the
//! rays that leave a material with an environment of its own (its reflection and
//! refraction rays) that environment when they miss, instead of the camera's. The path
//! engine does the same for every ray that leaves such a material and finds nothing, and
//! does not sample the scene's environment at its surface: what leaves it sees only its
//! own environment, all of it (no MIS), so nothing is counted twice. A
//! `mib_glossy_reflection` surface shader's `environment` parameter (the environment its
//! reflection rays see) is such an environment too, ahead of the material's.

use bsdf::Rgb;
use glam::Vec3A;
use shader::{NodeId, Shading, Slot, Tag, Value};

use crate::accel::Accel;
use crate::environment::Source;
use crate::world::World;

/// The environment shader list of world material `material` (0: the default material,
/// which has none), if it names one: the `environment` of a `mib_glossy_reflection` that
/// is its surface shader (and casts rays), else the material's own.
#[inline]
pub(super) fn own(shading: Option<&Shading>, material: u32) -> Option<NodeId> {
    let shading = shading?;
    let m = shading.materials.get(material.checked_sub(1)? as usize)?;
    m.surface.and_then(|s| glossy_environment(shading, s)).or(m.environment)
}

/// The `environment` parameter of `node` when it is a `mib_glossy_reflection` that casts
/// glossy rays (`samples` above 0, a `reflection_color` other than black, as the path
/// engine translates it): the environment its reflection rays see where they miss.
#[inline]
fn glossy_environment(shading: &Shading, node: NodeId) -> Option<NodeId> {
    let glossy = &baselib::glossy::GLOSSY_REFLECTION;
    let n = shading.graph.nodes.get(node as usize)?;
    // (The test inlined into every hit's question; the glossy shader's slots out of line.)
    if !n.imp.is_some_and(|i| std::ptr::eq(i, glossy)) {
        return None;
    }
    glossy_slots_environment(n)
}

/// [`glossy_environment`] for a node `n` of `mib_glossy_reflection`.
#[inline(never)]
fn glossy_slots_environment(n: &shader::graph::Node) -> Option<NodeId> {
    let glossy = &baselib::glossy::GLOSSY_REFLECTION;
    let slot = |name: &str| glossy.params.iter().position(|p| *p == name).and_then(|i| n.slots.get(i));
    let constant = |name: &str| match slot(name) {
        Some(Slot::Value(v)) => Some(v),
        _ => None,
    };
    if constant("samples").is_some_and(|v| v.int() <= 0)
        || constant("reflection_color").is_some_and(|v| v.color().truncate() == glam::Vec3::ZERO)
    {
        return None;
    }
    match slot("environment")? {
        Slot::Value(Value::Tag(Tag::Shader(env))) | Slot::Connect { node: env, member: None } => Some(*env),
        _ => None,
    }
}

/// The radiance `node` gives along unit direction `dir`, run as an environment ray; with
/// `gather` as a final gather ray's (after a bounce that is not a mirror's: the light it
/// casts).
pub(super) fn radiance(
    world: &World,
    accel: &dyn Accel,
    shading: &Shading,
    node: NodeId,
    dir: Vec3A,
    gather: bool,
) -> Rgb {
    Source::Shader { world, accel, shading, node }.eval_as(dir, gather)
}
