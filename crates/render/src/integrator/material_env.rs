//! A material's own `environment` shader list in the path engine: mental ray gives the
//! rays that leave a material with an environment of its own (its reflection and
//! refraction rays) that environment when they miss, instead of the camera's. The path
//! engine does the same for every ray that leaves such a material and finds nothing, and
//! does not sample the scene's environment at its surface: what leaves it sees only its
//! own environment, all of it (no MIS), so nothing is counted twice.

use bsdf::Rgb;
use glam::Vec3A;
use shader::{NodeId, Shading};

use crate::accel::Accel;
use crate::environment::Source;
use crate::world::World;

/// The environment shader list of world material `material` (0: the default material,
/// which has none), if it names one.
#[inline]
pub(super) fn own(shading: Option<&Shading>, material: u32) -> Option<NodeId> {
    let shading = shading?;
    shading.materials.get(material.checked_sub(1)? as usize)?.environment
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
