//! The world-space geometric normals and hit-error bounds of the triangles of instances
//! that hold still, with their object-space vertices and materials, computed once when
//! the world is built (and again after displacement has edited it) instead of at every
//! hit: the path engine's `surface` reads them where it found them computed
//! ([`FaceCache::face`]), the same numbers bit for bit as the ones it computes itself
//! ([`face_normal`], [`shader::trace::hit_error`], the mesh's vertices and slots).

use glam::{Mat3A, Vec3, Vec3A};

use super::InstanceData;
use crate::mesh::MeshData;

/// Most triangles an instance may have for its faces to be kept (60 bytes each): larger
/// meshes' faces are as far from the cache in memory as their vertices are.
pub const FACE_CACHE_TRIANGLES: usize = 1 << 16;

/// Most faces kept over all instances (60 MiB).
pub const FACE_CACHE_BUDGET: usize = 1 << 20;

/// Per instance (as [`World::instances`](super::World::instances)), for each triangle of its
/// mesh, what a hit on it needs that does not change ([`Face`]); an empty list for
/// instances whose faces are computed at each hit (they move, their mesh deforms or is
/// large, or the budget is spent).
#[derive(Clone, Debug, Default)]
pub struct FaceCache {
    faces: Vec<Box<[Face]>>,
}

/// A kept triangle of an instance that holds still.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Face {
    /// The triangle's vertices (object space, the mesh's positions).
    pub vertices: [Vec3; 3],
    /// The unit geometric normal (world space, the counter-clockwise front; [`face_normal`]).
    pub ng: Vec3,
    /// The bound on how far a hit point lies off the triangle (world units).
    pub err: f32,
    /// The material (an index into [`World::materials`](super::World::materials)): the
    /// instance's material of the triangle's slot, 0 where either is missing.
    pub material: u32,
    /// Whether the mesh has vertex shading normals ([`MeshData::has_normals`]).
    pub smooth: bool,
}

impl FaceCache {
    /// The faces of `instances` of `meshes` that hold still, within
    /// [`FACE_CACHE_TRIANGLES`] an instance and [`FACE_CACHE_BUDGET`] in all (in instance
    /// order). To be built anew whenever the meshes or the instances change.
    pub fn build(meshes: &[MeshData], instances: &[InstanceData]) -> FaceCache {
        let mut budget = FACE_CACHE_BUDGET;
        let faces = instances
            .iter()
            .map(|inst| {
                let mesh = &meshes[inst.mesh as usize];
                let n = mesh.triangles.len();
                if inst.moves() || mesh.moves() || n > FACE_CACHE_TRIANGLES || n > budget {
                    return Box::default();
                }
                budget -= n;
                mesh.triangles
                    .iter()
                    .enumerate()
                    .map(|(prim, &tri)| {
                        let [p0, p1, p2] = mesh.triangle_at(tri, 0.0);
                        let slot = mesh.slots.get(prim).copied().unwrap_or(0) as usize;
                        Face {
                            vertices: [p0, p1, p2].map(Vec3::from),
                            ng: face_normal(&inst.normal_to_world, p0, p1, p2).into(),
                            err: shader::trace::hit_error(p0, p1, p2, &inst.object_to_world),
                            material: inst.materials.get(slot).copied().unwrap_or(0),
                            smooth: mesh.has_normals(),
                        }
                    })
                    .collect()
            })
            .collect();
        FaceCache { faces }
    }

    /// The unit world-space geometric normal of triangle `prim` of instance `instance` and
    /// its hit-error bound, when kept.
    #[inline(always)]
    pub fn get(&self, instance: u32, prim: u32) -> Option<(Vec3A, f32)> {
        let f = self.face(instance, prim)?;
        Some((Vec3A::from(f.ng), f.err))
    }

    /// Triangle `prim` of instance `instance`, when kept.
    #[inline(always)]
    pub fn face(&self, instance: u32, prim: u32) -> Option<&Face> {
        self.faces.get(instance as usize)?.get(prim as usize)
    }

    /// Faces kept, over all instances.
    pub fn len(&self) -> usize {
        self.faces.iter().map(|f| f.len()).sum()
    }

    /// Whether no face is kept.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The unit geometric normal (world space) of the triangle `p0 p1 p2` (object space,
/// counter-clockwise front) whose normals go to world space by `normal_to_world` (the
/// inverse transpose, so mirroring transforms keep the counter-clockwise side as the
/// front); +Z for a degenerate triangle.
#[inline(always)]
pub fn face_normal(normal_to_world: &Mat3A, p0: Vec3A, p1: Vec3A, p2: Vec3A) -> Vec3A {
    (*normal_to_world * (p1 - p0).cross(p2 - p0)).normalize_or(Vec3A::Z)
}
