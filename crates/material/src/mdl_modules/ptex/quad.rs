//! Where a hit lies on a Ptex file's faces ([`face_at`]): the face id and the face
//! coordinates (u, v) a lookup reads, by the file's mesh type.
//!
//! A triangle-mesh file: the face is the hit triangle's index within its object, (u, v) its
//! barycentrics (u weighting the triangle's second vertex, v its third). A quad-mesh file:
//! the face is the Ptex face id of the quad polygon the triangle was cut from, or of the
//! sub-quad of an n-gon the point lies in, and (u, v) the point's place on it (a quad's
//! origin at the polygon's vertex 0, u along its edge 0 → 1, v along 0 → 3; a sub-quad's
//! at its vertex, u toward the next edge's midpoint), as the renderer found them
//! ([`scene::mesh::ptex_quads`], `State::ptex_quad`); a triangle of no such face (of a
//! subdivision or free-form surface, or adaptively displaced) has none.

use shader::State;

use super::MeshType;

/// The face id and face coordinates (u, v) of hit `s` on a Ptex file of mesh type `mesh`
/// (`None`: the hit has no face of such a file).
#[inline]
pub fn face_at(mesh: MeshType, s: &State) -> Option<(u32, f32, f32)> {
    match mesh {
        MeshType::Triangle => Some((s.prim, s.bary[1], s.bary[2])),
        MeshType::Quad => s.ptex_quad,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A triangle file reads the triangle and its barycentrics; a quad file the hit's quad
    /// face and (u, v) (the second triangle of a quad fanned from vertex 0 is corners 0, 2,
    /// 3), and nothing without them (exact).
    #[test]
    fn faces_by_mesh_type() {
        let mut s = State { prim: 7, bary: [0.2, 0.3, 0.5], ..State::default() };
        assert_eq!(face_at(MeshType::Triangle, &s), Some((7, 0.3, 0.5)));
        assert_eq!(face_at(MeshType::Quad, &s), None);
        s.ptex_quad = scene::mesh::ptex_quads::face_uv(scene::mesh::ptex_quads::encode(3, [0, 2, 3]), s.bary);
        // u = 0.3 · 1 (corner 2) = 0.3, v = 0.3 · 1 + 0.5 · 1 (corners 2 and 3) = 0.8.
        let (face, u, v) = face_at(MeshType::Quad, &s).expect("a quad face");
        assert_eq!(face, 3);
        assert!((u - 0.3).abs() < 1e-7 && (v - 0.8).abs() < 1e-7, "{u} {v}");
        assert_eq!(face_at(MeshType::Triangle, &s), Some((7, 0.3, 0.5)));
    }
}
