//! Where the world's meshes are placed: an instance of a mesh, its transforms (at rest
//! and, when it moves, at keys over the shutter) and the instances of the scene's objects.

use glam::{Affine3A, Mat3A};
use scene::Scene;

use super::affine;
use crate::motion::lerp_keys;

/// An instance of a mesh.
#[derive(Clone, Debug)]
pub struct InstanceData {
    /// Index into [`World::meshes`](super::World::meshes).
    pub mesh: u32,
    /// Object → world.
    pub object_to_world: Affine3A,
    /// World → object.
    pub world_to_object: Affine3A,
    /// Object-space normals → world space (inverse transpose).
    pub normal_to_world: Mat3A,
    /// Material index (into [`World::materials`](super::World::materials)) of each of the mesh's slots.
    pub materials: Vec<u32>,
    /// Render flags.
    pub flags: scene::Flags,
    /// The label written to the tag buffer.
    pub tag: u32,
    /// Index of the instance in the scene's instance list.
    pub scene_index: u32,
    /// Object → world at the end of the shutter interval, when the instance moves
    /// (`motion transform`).
    pub motion_to_world: Option<Affine3A>,
    /// Object → world at shutter times spread evenly over the shutter (see
    /// [`crate::motion`]), when the instance moves while the shutter is open; empty: it
    /// stays at `object_to_world`.
    pub keys: Vec<Affine3A>,
}

/// Where an instance is at one shutter time: its transforms then.
#[derive(Clone, Copy, Debug)]
pub struct Placement {
    /// Object → world.
    pub object_to_world: Affine3A,
    /// World → object.
    pub world_to_object: Affine3A,
    /// Object-space normals → world space (inverse transpose).
    pub normal_to_world: Mat3A,
}

impl InstanceData {
    /// Whether the instance moves while the shutter is open.
    #[inline]
    pub fn moves(&self) -> bool {
        !self.keys.is_empty()
    }

    /// Object → world at shutter time `time` (see [`crate::motion`]).
    #[inline]
    pub fn object_to_world_at(&self, time: f32) -> Affine3A {
        if self.keys.is_empty() {
            self.object_to_world
        } else {
            lerp_keys(&self.keys, time)
        }
    }

    /// The instance's transforms at shutter time `time` (the stored ones when it does not
    /// move).
    #[inline]
    pub fn placement(&self, time: f32) -> Placement {
        if self.keys.is_empty() {
            return Placement {
                object_to_world: self.object_to_world,
                world_to_object: self.world_to_object,
                normal_to_world: self.normal_to_world,
            };
        }
        let object_to_world = lerp_keys(&self.keys, time);
        Placement {
            object_to_world,
            world_to_object: object_to_world.inverse(),
            normal_to_world: object_to_world.matrix3.inverse().transpose(),
        }
    }
}

/// The instances of the scene's objects that have triangles (`object_has_triangles`, in
/// object order), in scene order: each places its object's mesh (the world's meshes start
/// with the objects' meshes, in object order).
pub(super) fn object_instances(scene: &Scene, object_has_triangles: &[bool]) -> Vec<InstanceData> {
    scene
        .instances
        .iter()
        .enumerate()
        .filter(|(_, i)| object_has_triangles.get(i.object as usize).copied().unwrap_or(false))
        .map(|(scene_index, i)| {
            let object_to_world = affine(i.object_to_world);
            InstanceData {
                mesh: i.object,
                object_to_world,
                world_to_object: affine(i.world_to_object),
                normal_to_world: object_to_world.matrix3.inverse().transpose(),
                materials: i.materials.iter().map(|m| m.map_or(0, |m| m + 1)).collect(),
                flags: i.flags,
                tag: i.tag.unwrap_or(0).clamp(0, i64::from(u32::MAX)) as u32,
                scene_index: scene_index as u32,
                motion_to_world: i.motion_world_to_object.map(|m| affine(m).inverse()),
                keys: Vec::new(),
            }
        })
        .collect()
}
