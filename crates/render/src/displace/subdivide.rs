//! Uniform subdivision of a mesh's triangles for displacement: each edge is split into
//! `n` equal parts and each triangle into `n²` (mental ray's `parametric` level L gives
//! n = 2^L, 4^L triangles). Vertices on an edge are shared by the triangles that share
//! the edge (by vertex index), so a mesh whose faces share vertices stays closed when
//! displaced. Every per-vertex array is interpolated barycentrically; normals are
//! renormalised.

use std::collections::HashMap;

use glam::{Vec3, Vec3A};

use crate::mesh::MeshData;

/// A subdivided mesh and, per vertex, the triangle (of the new mesh) that made it.
pub struct Subdivided {
    /// The finer mesh (normals always present).
    pub mesh: MeshData,
    /// For each vertex: a triangle of `mesh` it belongs to (its material decides which
    /// displacement shader moves it); `u32::MAX` for vertices no triangle uses.
    pub owner: Vec<u32>,
}

/// Area-weighted vertex normals of `mesh` (object space, unit length; zero where a
/// vertex has no triangle of non-zero area).
pub fn vertex_normals(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut n = vec![Vec3A::ZERO; positions.len()];
    for t in triangles {
        let [a, b, c] = t.map(|i| Vec3A::from(positions[i as usize]));
        let face = (b - a).cross(c - a);
        for i in t {
            n[*i as usize] += face;
        }
    }
    n.into_iter().map(|v| Vec3::from(v.normalize_or_zero())).collect()
}

/// Barycentric weights of one new vertex: up to three (old vertex, weight) pairs.
type Weights = [(u32, f32); 3];

/// Splits every triangle of `mesh` into `n × n` (n ≥ 1). Motion data and hair are not
/// carried (a moving mesh's motion steps travel as user vectors: see
/// [`super::moving`]).
pub fn subdivide(mesh: &MeshData, n: u32) -> Subdivided {
    let n = n.max(1);
    let normals = if mesh.normals.len() == mesh.positions.len() {
        mesh.normals.clone()
    } else {
        vertex_normals(&mesh.positions, &mesh.triangles)
    };
    let mut weights: Vec<Weights> = (0..mesh.positions.len() as u32).map(|i| [(i, 1.0), (i, 0.0), (i, 0.0)]).collect();
    let mut owner = vec![u32::MAX; mesh.positions.len()];
    let mut edges: HashMap<(u32, u32, u32), u32> = HashMap::new();
    let per = (n * n) as usize;
    let mut triangles = Vec::with_capacity(mesh.triangles.len() * per);
    let mut slots = Vec::with_capacity(if mesh.slots.is_empty() { 0 } else { mesh.triangles.len() * per });
    let mut grid: Vec<u32> = Vec::with_capacity(((n + 1) * (n + 2) / 2) as usize);
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = *tri;
        grid.clear();
        // Grid point (i, j): weight (n−i−j)/n on a, i/n on b, j/n on c; stored row by row.
        for j in 0..=n {
            for i in 0..=(n - j) {
                let index = match (i, j) {
                    (0, 0) => a,
                    (_, 0) if i == n => b,
                    (0, _) if j == n => c,
                    (_, 0) => edge_vertex(&mut edges, &mut weights, (a, b), i, n),
                    (0, _) => edge_vertex(&mut edges, &mut weights, (a, c), j, n),
                    _ if i + j == n => edge_vertex(&mut edges, &mut weights, (b, c), j, n),
                    _ => {
                        let f = 1.0 / n as f32;
                        weights.push([(a, (n - i - j) as f32 * f), (b, i as f32 * f), (c, j as f32 * f)]);
                        (weights.len() - 1) as u32
                    }
                };
                grid.push(index);
            }
        }
        let at = |i: u32, j: u32| -> u32 {
            // Rows 0..j hold (n+1) + n + … + (n−j+2) points.
            let before = j * (n + 1) - j * (j.saturating_sub(1)) / 2;
            grid[(before + i) as usize]
        };
        let slot = mesh.slots.get(t).copied();
        for j in 0..n {
            for i in 0..(n - j) {
                triangles.push([at(i, j), at(i + 1, j), at(i, j + 1)]);
                if i + j + 2 <= n {
                    triangles.push([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
        if let Some(s) = slot {
            slots.resize(triangles.len(), s);
        }
    }
    owner.resize(weights.len(), u32::MAX);
    for (t, tri) in triangles.iter().enumerate() {
        for &v in tri {
            if owner[v as usize] == u32::MAX {
                owner[v as usize] = t as u32;
            }
        }
    }
    let mix3 = |w: &Weights, f: &dyn Fn(u32) -> Vec3A| w.iter().map(|&(i, k)| f(i) * k).sum::<Vec3A>();
    let mut positions: Vec<Vec3> =
        weights.iter().map(|w| Vec3::from(mix3(w, &|i| Vec3A::from(mesh.positions[i as usize])))).collect();
    positions.reserve_exact(1);
    let normals = weights
        .iter()
        .map(|w| Vec3::from(mix3(w, &|i| Vec3A::from(normals[i as usize])).normalize_or_zero()))
        .collect();
    let textures =
        mesh.textures.iter().map(|t| weights.iter().map(|w| mix3(w, &|i| t[i as usize])).collect()).collect();
    let user = mesh
        .user
        .iter()
        .map(|u| weights.iter().map(|w| Vec3::from(mix3(w, &|i| Vec3A::from(u[i as usize])))).collect())
        .collect();
    let bump_basis = if mesh.bump_basis.len() == mesh.positions.len() {
        weights.iter().map(|w| [0, 1].map(|k| mix3(w, &|i| mesh.bump_basis[i as usize][k]))).collect()
    } else {
        Vec::new()
    };
    let mesh = MeshData { positions, normals, textures, user, bump_basis, triangles, slots, ..MeshData::default() };
    Subdivided { mesh, owner }
}

/// The vertex `k/n` of the way from `from` to `to` on that edge, shared with the
/// neighbouring triangle (made on first use).
fn edge_vertex(
    edges: &mut HashMap<(u32, u32, u32), u32>,
    weights: &mut Vec<Weights>,
    (from, to): (u32, u32),
    k: u32,
    n: u32,
) -> u32 {
    let key = if from < to { (from, to, k) } else { (to, from, n - k) };
    *edges.entry(key).or_insert_with(|| {
        let t = key.2 as f32 / n as f32;
        weights.push([(key.0, 1.0 - t), (key.1, t), (key.0, 0.0)]);
        (weights.len() - 1) as u32
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles sharing an edge, split 4 × 4: 32 triangles, the shared edge's 3 inner
    /// vertices made once (4 + 2·3 + 3 outer-edge vertices … counted: (n+1)(n+2)/2 per
    /// triangle minus the n+1 shared), positions on the plane, area kept, winding kept.
    #[test]
    fn two_triangles_split_evenly_and_share_their_edge() {
        let mesh = MeshData {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            textures: vec![vec![Vec3A::ZERO, Vec3A::X, Vec3A::new(1.0, 1.0, 0.0), Vec3A::Y]],
            ..MeshData::default()
        };
        let s = subdivide(&mesh, 4);
        assert_eq!(s.mesh.triangles.len(), 32);
        assert_eq!(s.mesh.positions.len(), 2 * 15 - 5);
        let mut area = 0.0;
        for t in &s.mesh.triangles {
            let [a, b, c] = t.map(|i| Vec3A::from(s.mesh.positions[i as usize]));
            let cross = (b - a).cross(c - a);
            assert!(cross.z > 0.0, "winding kept");
            area += 0.5 * cross.length();
        }
        assert!((area - 1.0).abs() < 1e-5, "{area}");
        for (p, uv) in s.mesh.positions.iter().zip(&s.mesh.textures[0]) {
            assert!((Vec3A::from(*p) - *uv).length() < 1e-6, "texture coordinates follow the positions");
        }
        assert!(s.mesh.normals.iter().all(|n| (n.z - 1.0).abs() < 1e-6));
        assert!(s.owner.iter().all(|&o| o != u32::MAX));
    }
}
