//! Keys over the shutter of the world's moving things: instances, meshes' vertices and
//! the camera (see [`crate::motion`]), and the world-space positions and bounds of moving
//! meshes that acceleration structures read.

use glam::{Affine3A, Vec3A};
use scene::Scene;

use super::{affine, InstanceData};
use crate::camera::CameraModel;
use crate::mesh::MeshData;
use crate::motion::{motion_path, transform_keys, Shutter};

/// Keys over the shutter of everything that moves while it is open: instances with a
/// `motion transform` (object → world moved over the motion interval as mental ray moves
/// instances: linearly, or as a rotation when it turns; see [`transform_keys`]), meshes with motion vectors (one key per motion step) and
/// the camera. Returns whether anything moves.
pub(super) fn set_motion_keys(
    shutter: &Shutter,
    scene: &Scene,
    meshes: &mut [MeshData],
    instances: &mut [InstanceData],
    camera: &mut CameraModel,
    warnings: &mut Vec<String>,
) -> bool {
    let limit = scene::sanity::WORLD_LIMIT as f32;
    let steps = scene.options.motion_steps as usize;
    let placed_in_range = |m: &Affine3A| m.is_finite() && m.translation.abs().max_element() <= limit;
    let mut out_of_range = |what: String| {
        warnings.push(format!(
            "{what} moves beyond single precision (±{limit:e}) while the shutter is open: it is kept still"
        ))
    };
    let mut moving = false;
    for inst in instances.iter_mut() {
        if let Some(end) = inst.motion_to_world.filter(|m| *m != inst.object_to_world) {
            let keys = transform_keys(inst.object_to_world, end, shutter, steps);
            if keys.iter().all(|k| placed_in_range(k) && k.matrix3.determinant() != 0.0) {
                inst.keys = keys;
                moving = true;
            } else {
                out_of_range(format!("instance {}", inst.scene_index));
            }
        }
    }
    for mesh in meshes.iter_mut() {
        match vertex_keys(shutter, mesh) {
            None => {}
            Some(Some(position_keys)) => {
                mesh.position_keys = position_keys;
                moving = true;
            }
            Some(None) => out_of_range("a mesh's motion vectors: the mesh".into()),
        }
    }
    if let Some(end) = scene.camera.motion_world_to_camera {
        let end = affine(end).inverse();
        if end != camera.camera_to_world {
            let keys = transform_keys(camera.camera_to_world, end, shutter, steps);
            if keys.iter().all(|k| placed_in_range(k) && k.matrix3.determinant() != 0.0) {
                camera.keys = keys;
                moving = true;
            } else {
                out_of_range("the camera".into());
            }
        }
    }
    moving
}

/// The position keys over `shutter` of `mesh`'s vertices (object space, one key per
/// motion step, see [`crate::motion`]): `None` when they do not move (no motion vectors,
/// all zero, or hair), `Some(None)` when they move beyond single precision (the mesh is
/// then kept still).
pub fn vertex_keys(shutter: &Shutter, mesh: &MeshData) -> Option<Option<Vec<Vec<Vec3A>>>> {
    let still = |m: &[Vec3A]| m.iter().all(|v| *v == Vec3A::ZERO);
    if mesh.motion.is_empty() || mesh.hair.is_some() || still(&mesh.motion) && mesh.motion_more.iter().all(|m| still(m))
    {
        return None;
    }
    let limit = scene::sanity::WORLD_LIMIT as f32;
    // One key per motion step (each vertex's `m` vectors are its motion path's corners).
    let vectors = mesh.motion_steps().min(crate::mesh::MAX_MOTION_STEPS);
    let position_keys: Vec<Vec<Vec3A>> = shutter
        .key_times(vectors)
        .map(|tau| {
            (0..mesh.vertex_count())
                .map(|i| motion_path(mesh.position(i as u32), &mesh.motion_vectors(i, vectors), tau))
                .collect()
        })
        .collect();
    Some(
        position_keys
            .iter()
            .flatten()
            .all(|p| p.is_finite() && p.abs().max_element() <= limit)
            .then_some(position_keys),
    )
}

/// World-space positions of an instance's mesh at each key of its motion (the more keys of
/// the instance's and the mesh's), for acceleration structures that store moving
/// triangles in world space. Exact between keys when only one of the two moves (the
/// instances [`crate::accel::flat_instances`] flattens); when both do, the world-space
/// path between keys is not linear (see [`world_motion_bounds`]). Where the keys are the
/// mesh's own, each is its key as stored, not one interpolated at the key's time (the
/// last one came out a rounding off: `a + (b − a)·1`).
pub fn world_key_positions(inst: &InstanceData, mesh: &MeshData) -> Vec<Vec<Vec3A>> {
    let keys = inst.keys.len().max(mesh.position_keys.len()).max(1);
    (0..keys)
        .map(|j| {
            let s = if keys == 1 { 0.0 } else { j as f32 / (keys - 1) as f32 };
            let to_world = inst.object_to_world_at(s);
            match mesh.position_keys.get(j).filter(|_| mesh.position_keys.len() == keys) {
                Some(key) => key.iter().map(|&p| to_world.transform_point3a(p)).collect(),
                None => mesh.positions_at(s).into_iter().map(|p| to_world.transform_point3a(p)).collect(),
            }
        })
        .collect()
}

/// World-space bounds of an instance's mesh over the whole shutter, when the instance or
/// the mesh's vertices move. Between the times where either has a key both move linearly,
/// so a vertex at `A(t)·p(t)` follows a parabola: its chord between those times plus
/// `−f(1 − f)·ΔM·Δp` (`ΔM` the change of the instance's matrix, `Δp` the vertex's, `f` the
/// fraction of the interval), at most a quarter of `|ΔM·Δp|` off the chord in each axis.
/// The box holds every point at every time (the key boxes alone do when only one of
/// the two moves).
pub fn world_motion_bounds(inst: &InstanceData, mesh: &MeshData) -> (Vec3A, Vec3A) {
    let mut lo = Vec3A::splat(f32::INFINITY);
    let mut hi = Vec3A::splat(f32::NEG_INFINITY);
    let times = |keys: usize| (0..keys).map(move |j| j as f32 / (keys.max(2) - 1) as f32);
    let mut cuts: Vec<f32> = times(inst.keys.len()).chain(times(mesh.position_keys.len())).chain([0.0, 1.0]).collect();
    cuts.sort_by(f32::total_cmp);
    cuts.dedup();
    let at = |s: f32| (inst.object_to_world_at(s), mesh.positions_at(s));
    let (mut a0, mut p0) = at(cuts[0]);
    for &s in &cuts[1..] {
        let (a1, p1) = at(s);
        let dm = a1.matrix3 - a0.matrix3;
        for (q0, q1) in p0.iter().zip(&p1) {
            let (w0, w1) = (a0.transform_point3a(*q0), a1.transform_point3a(*q1));
            let bulge = (dm * (*q1 - *q0)).abs() * 0.25;
            lo = lo.min(w0.min(w1) - bulge);
            hi = hi.max(w0.max(w1) + bulge);
        }
        (a0, p0) = (a1, p1);
    }
    (lo, hi)
}
