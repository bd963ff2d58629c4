//! Displacement of meshes whose vertices move (motion vectors, `motion steps`): every
//! motion step is displaced on the same finer triangles, so that the triangles of each
//! step correspond and the moving surface is traced as one.
//!
//! Before subdividing, [`carry_steps`] appends each motion step's undisplaced vertex
//! positions and normals (object space; step 0 is the mesh at motion time 0, step j its
//! vertices plus their j-th motion vectors) to the mesh's user vectors, which uniform and
//! adaptive subdivision interpolate like every other vertex attribute (linearly in the
//! base vertices, as they interpolate the positions). After subdividing, [`displace_steps`]
//! takes them off again and evaluates the displacement at each step's positions and
//! normals: the displaced step 0 is the mesh, the displaced steps' differences from it
//! are its new motion vectors. A step's normal is the given normal turned by the
//! rotation that carries the vertex's area-weighted face normal at motion time 0 to the
//! one at that step (without given normals: that step's face normal itself), so that a
//! rigidly moving or turning mesh is displaced alike at every step.

use glam::{Quat, Vec3, Vec3A};
use rayon::prelude::*;

use super::subdivide::vertex_normals;
use crate::mesh::MeshData;

/// The displacement of one vertex at one motion step: `(mesh, vertex, position, normal,
/// slot)` → the object-space offset of vertex `vertex` of the subdivided, undisplaced
/// `mesh` (whose texture coordinates and bump basis it reads) placed at `position` with
/// the unit normal `normal` (object space), displaced by the material of slot `slot`.
pub type StepOffset<'a> = dyn Fn(&MeshData, usize, Vec3, Vec3, u32) -> Vec3 + Sync + 'a;

/// The motion steps of `mesh` to displace: its motion vectors per vertex, at most
/// [`crate::mesh::MAX_MOTION_STEPS`] (0: its vertices do not move).
pub fn steps_of(mesh: &MeshData) -> usize {
    if mesh.hair.is_some() {
        0
    } else {
        mesh.motion_steps().min(crate::mesh::MAX_MOTION_STEPS)
    }
}

/// `mesh` with `2 (steps + 1)` user vectors appended after its own: for each motion step
/// j = 0…`steps`, the undisplaced positions and the unit normals at that step (object
/// space). Its motion vectors are dropped (the displaced ones replace them).
pub fn carry_steps(mesh: &MeshData, steps: usize) -> MeshData {
    let base_normals = if mesh.normals.len() == mesh.positions.len() {
        mesh.normals.clone()
    } else {
        vertex_normals(&mesh.positions, &mesh.triangles)
    };
    let faces0 = vertex_normals(&mesh.positions, &mesh.triangles);
    let mut out = MeshData { motion: Vec::new(), motion_more: Vec::new(), position_keys: Vec::new(), ..mesh.clone() };
    out.normals = base_normals.clone();
    out.user.push(mesh.positions.clone());
    out.user.push(base_normals.clone());
    for j in 1..=steps {
        let positions: Vec<Vec3> = (0..mesh.positions.len())
            .map(|i| mesh.positions[i] + Vec3::from(mesh.motion_vectors(i, steps)[j - 1]))
            .collect();
        let faces = vertex_normals(&positions, &mesh.triangles);
        let normals = base_normals
            .iter()
            .zip(faces0.iter().zip(&faces))
            .map(|(n, (g0, g))| {
                if *g0 == Vec3::ZERO || *g == Vec3::ZERO {
                    *n
                } else {
                    (Quat::from_rotation_arc(*g0, *g) * *n).normalize_or_zero()
                }
            })
            .collect();
        out.user.push(positions);
        out.user.push(normals);
    }
    out
}

/// Displaces every motion step of `out` (a mesh [`carry_steps`] made, subdivided: its
/// user vectors from `first` on are the carried steps, which are taken off): its
/// positions become step 0's displaced positions, its motion vectors the displaced steps'
/// offsets from them, its normals are recomputed. Each vertex is displaced by the
/// material of the first triangle that uses it (vertices no triangle uses stay).
pub fn displace_steps(out: &mut MeshData, first: usize, steps: usize, offset: &StepOffset) {
    let carried = out.user.split_off(first.min(out.user.len()));
    if carried.len() != 2 * (steps + 1) {
        return;
    }
    let mut slot = vec![u32::MAX; out.positions.len()];
    for (t, tri) in out.triangles.iter().enumerate() {
        for &v in tri {
            if slot[v as usize] == u32::MAX {
                slot[v as usize] = out.slots.get(t).copied().unwrap_or(0);
            }
        }
    }
    let mesh = &*out;
    let displaced: Vec<Vec<Vec3>> = (0..=steps)
        .map(|j| {
            let (positions, normals) = (&carried[2 * j], &carried[2 * j + 1]);
            (0..positions.len())
                .into_par_iter()
                .map(|v| {
                    let p = positions[v];
                    match slot[v] {
                        u32::MAX => p,
                        s => p + offset(mesh, v, p, Vec3::from(Vec3A::from(normals[v]).normalize_or_zero()), s),
                    }
                })
                .collect()
        })
        .collect();
    let mut displaced = displaced.into_iter();
    let at0 = displaced.next().unwrap_or_default();
    let vectors: Vec<Vec<Vec3A>> =
        displaced.map(|pj| pj.iter().zip(&at0).map(|(p, q)| Vec3A::from(*p - *q)).collect()).collect();
    let mut vectors = vectors.into_iter();
    out.motion = vectors.next().unwrap_or_default();
    out.motion_more = vectors.collect();
    out.normals = vertex_normals(&at0, &out.triangles);
    out.positions = at0;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::displace::subdivide::subdivide;

    /// A unit square sliding 0.5 along x and turning a quarter turn about x (its normal
    /// from +z to −y) at motion step 1: the carried step normals are +z and −y, and after
    /// 2 × 2 subdivision and a constant offset of 0.25 along them, every vertex of step 0
    /// is 0.25 above the plane and every vertex of step 1 is 0.25 beyond its turned plane
    /// (y = −0.25), within 1e-5.
    #[test]
    fn each_step_is_displaced_along_its_own_normal() {
        let square = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        // Step 1: (x, y, 0) → (x + 0.5, 0, y): turned about x by a quarter turn.
        let motion: Vec<Vec3A> = square.iter().map(|p| Vec3A::new(p.x + 0.5, 0.0, p.y) - Vec3A::from(*p)).collect();
        let mesh = MeshData {
            positions: square.to_vec(),
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            motion,
            ..MeshData::default()
        };
        let carried = carry_steps(&mesh, 1);
        assert!((Vec3A::from(carried.user[3][0]) - Vec3A::NEG_Y).length() < 1e-6, "{:?}", carried.user[3][0]);
        let mut out = subdivide(&carried, 2).mesh;
        displace_steps(&mut out, 0, 1, &|_, _, _, n, _| n * 0.25);
        assert!(out.user.is_empty());
        assert_eq!(out.motion.len(), out.positions.len());
        for (p, m) in out.positions.iter().zip(&out.motion) {
            assert!((p.z - 0.25).abs() < 1e-5, "{p}");
            let at1 = Vec3A::from(*p) + *m;
            assert!((at1.y + 0.25).abs() < 1e-5, "{at1}");
        }
    }
}
