//! Object lights whose triangles change shape while the shutter is open: the emitting
//! object's vertices carry motion vectors, or several instances of it (an object light
//! naming an object takes the triangles of all its instances) move differently. Their
//! world-space triangles are taken from the world's moving geometry at keys over the
//! shutter ([`shader::light::DeformingMesh`]), so that a light sample, a shadow ray and
//! a photon see them where the geometry is at the ray's time.

use std::sync::Arc;

use shader::light::DeformingMesh;

use super::InstanceData;
use crate::mesh::MeshData;

/// Most shutter intervals a deforming light's triangles are kept at.
const MAX_SEGMENTS: usize = 64;

/// The triangles of the scene instances `picked` (scene indices; their object meshes in
/// world space, as the world moves them: each instance's keys and its mesh's position
/// keys) at keys over the shutter. Where the geometry moves linearly between its keys
/// the light's keys hold each of those keys, so the triangles between them are the
/// geometry's own; an instance that moves while its vertices move (a curved path
/// between keys) gets four light keys per key interval. `None` when no picked instance
/// has triangles in the world.
pub fn deforming_mesh(picked: &[u32], meshes: &[MeshData], instances: &[InstanceData]) -> Option<DeformingMesh> {
    let chosen: Vec<(&InstanceData, &MeshData)> = instances
        .iter()
        .filter(|i| picked.contains(&i.scene_index))
        .filter_map(|i| meshes.get(i.mesh as usize).filter(|m| m.hair.is_none()).map(|m| (i, m)))
        .collect();
    let intervals = |keys: usize| keys.saturating_sub(1).max(1);
    let mut segments = 1usize;
    for (inst, mesh) in &chosen {
        let (a, b) = (intervals(inst.keys.len()), intervals(mesh.position_keys.len()));
        let curved = !inst.keys.is_empty() && !mesh.position_keys.is_empty();
        segments = lcm(lcm(segments, a), b * if curved { 4 } else { 1 }).min(MAX_SEGMENTS);
    }
    let keys = (0..=segments)
        .map(|j| {
            let s = j as f32 / segments as f32;
            let mut triangles = Vec::new();
            for (inst, mesh) in &chosen {
                let to_world = inst.object_to_world_at(s);
                // The emitting side stays the one the normals give under a mirroring
                // placement (as `MeshShape::of_instance` keeps it).
                let flip = inst.object_to_world.matrix3.determinant() < 0.0;
                let positions = positions_at_key(inst, mesh, j, segments, s);
                for t in &mesh.triangles {
                    let vertex = |k: usize| positions.get(t[k] as usize).copied();
                    let (Some(a), Some(b), Some(c)) = (vertex(0), vertex(1), vertex(2)) else {
                        continue;
                    };
                    let [a, b, c] = [a, b, c].map(|p| to_world.transform_point3a(p));
                    triangles.push(if flip { [a, c, b] } else { [a, b, c] });
                }
            }
            triangles
        })
        .collect();
    DeformingMesh::new(keys)
}

/// The vertices of `mesh` at light key `j` of `segments` (shutter time `s`), object space,
/// as the world's moving geometry holds them ([`super::world_key_positions`]): where one of
/// the geometry's keys falls at that time and the mesh has a key at each of them, that key
/// itself (interpolating at its time could come out a last bit off it), else interpolated.
fn positions_at_key(inst: &InstanceData, mesh: &MeshData, j: usize, segments: usize, s: f32) -> Vec<glam::Vec3A> {
    let geometry_intervals = inst.keys.len().max(mesh.position_keys.len()).max(1) - 1;
    if mesh.position_keys.len() == geometry_intervals + 1 && (j * geometry_intervals) % segments == 0 {
        return mesh.position_keys[j * geometry_intervals / segments].clone();
    }
    mesh.positions_at(s)
}

/// Least common multiple.
fn lcm(a: usize, b: usize) -> usize {
    let gcd = |mut x: usize, mut y: usize| {
        while y != 0 {
            (x, y) = (y, x % y);
        }
        x
    };
    a / gcd(a, b) * b
}

/// The deforming shape of each light (scene order) whose `picked` instances are given.
pub fn deforming_meshes(
    picked: &[Option<Vec<u32>>],
    meshes: &[MeshData],
    instances: &[InstanceData],
) -> Vec<Option<Arc<DeformingMesh>>> {
    picked.iter().map(|p| p.as_deref().and_then(|p| deforming_mesh(p, meshes, instances)).map(Arc::new)).collect()
}
