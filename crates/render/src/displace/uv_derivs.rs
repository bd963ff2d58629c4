//! The surface derivatives dP/du, dP/dv (object space, per scene unit of u and v) at each
//! vertex of a mesh, from its first texture space: the mean over the triangles using the
//! vertex of each triangle's own derivatives (the ones the tracer gives a hit on it).
//! The displacement stage hands them to displacement shaders as `state.derivs`, where
//! Maya's tangent-space vector displacement takes its tangent (dP/du).

use glam::Vec3A;

use crate::mesh::MeshData;

/// dP/du and dP/dv at each vertex of `mesh` (object space): the mean of those of the
/// triangles using it whose texture coordinates span an area, zero at a vertex without
/// one. `None` when the mesh has no first texture space (one coordinate per vertex) or
/// no triangle with an area in it.
pub fn vertex_derivs(mesh: &MeshData) -> Option<Vec<[Vec3A; 2]>> {
    let space = mesh.textures.first().filter(|s| s.len() == mesh.positions.len())?;
    let mut sum = vec![[Vec3A::ZERO; 2]; mesh.positions.len()];
    let mut count = vec![0u32; mesh.positions.len()];
    for tri in &mesh.triangles {
        let [i0, i1, i2] = tri.map(|i| i as usize);
        if [i0, i1, i2].iter().any(|&i| i >= space.len()) {
            continue;
        }
        let [p0, p1, p2] = [i0, i1, i2].map(|i| Vec3A::from(mesh.positions[i]));
        let (t0, t1, t2) = (space[i0], space[i1], space[i2]);
        let (du1, dv1, du2, dv2) = (t1.x - t0.x, t1.y - t0.y, t2.x - t0.x, t2.y - t0.y);
        let det = du1 * dv2 - du2 * dv1;
        if det.abs() <= 1e-20 {
            continue;
        }
        let (e1, e2) = (p1 - p0, p2 - p0);
        let derivs = [(e1 * dv2 - e2 * dv1) / det, (e2 * du1 - e1 * du2) / det];
        if !derivs.iter().all(|d| d.is_finite()) {
            continue;
        }
        for i in [i0, i1, i2] {
            sum[i][0] += derivs[0];
            sum[i][1] += derivs[1];
            count[i] += 1;
        }
    }
    if count.iter().all(|&c| c == 0) {
        return None;
    }
    Some(sum.into_iter().zip(count).map(|(s, c)| if c == 0 { s } else { s.map(|d| d / c as f32) }).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A unit square whose texture coordinates are turned a quarter turn (u = y, v = 1 − x)
    /// has dP/du = +y and dP/dv = −x at every vertex (1e-6); one without texture
    /// coordinates has none.
    #[test]
    fn a_square_with_turned_coordinates_has_turned_derivatives() {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        let uv = positions.iter().map(|p| Vec3A::new(p.y, 1.0 - p.x, 0.0)).collect();
        let mesh = MeshData {
            positions: positions.clone(),
            textures: vec![uv],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..MeshData::default()
        };
        let derivs = vertex_derivs(&mesh).expect("derivatives");
        for [du, dv] in derivs {
            assert!((du - Vec3A::Y).length() < 1e-6, "dP/du {du}");
            assert!((dv + Vec3A::X).length() < 1e-6, "dP/dv {dv}");
        }
        let bare = MeshData { positions, triangles: vec![[0, 1, 2]], ..MeshData::default() };
        assert!(vertex_derivs(&bare).is_none());
    }
}
