//! Where a hit lies on a Ptex file's faces ([`face_at`]): the face id and the face
//! coordinates (u, v) a lookup reads, by the file's mesh type.
//!
//! A triangle-mesh file: the face is the hit triangle's index within its object, (u, v) its
//! barycentrics (u weighting the triangle's second vertex, v its third). A quad-mesh file:
//! the face is the Ptex face id of the quad polygon the triangle was cut from, and (u, v)
//! the point's place on that quad (origin at the polygon's vertex 0, u along its edge
//! 0 → 1, v along 0 → 3), both from the triangle's packed quad corners
//! ([`scene::mesh::ptex_quads`], `State::ptex_quad`); a triangle of no quad (a polygon
//! of other than 4 vertices: Ptex's sub-quads are not mapped) has none.

use scene::mesh::ptex_quads;
use shader::State;

use super::MeshType;

/// The face id and face coordinates (u, v) of hit `s` on a Ptex file of mesh type `mesh`
/// (`None`: the hit has no face of such a file).
#[inline]
pub fn face_at(mesh: MeshType, s: &State) -> Option<(u32, f32, f32)> {
    match mesh {
        MeshType::Triangle => Some((s.prim, s.bary[1], s.bary[2])),
        MeshType::Quad => ptex_quads::face_uv(s.ptex_quad?, s.bary),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A triangle file reads the triangle and its barycentrics; a quad file the packed quad
    /// corners (the second triangle of a quad fanned from vertex 0 is corners 0, 2, 3),
    /// and nothing without them (exact).
    #[test]
    fn faces_by_mesh_type() {
        let mut s = State { prim: 7, bary: [0.2, 0.3, 0.5], ..State::default() };
        assert_eq!(face_at(MeshType::Triangle, &s), Some((7, 0.3, 0.5)));
        assert_eq!(face_at(MeshType::Quad, &s), None);
        s.ptex_quad = Some(ptex_quads::encode(3, [0, 2, 3]));
        // u = 0.3 · 1 (corner 2) = 0.3, v = 0.3 · 1 + 0.5 · 1 (corners 2 and 3) = 0.8.
        let (face, u, v) = face_at(MeshType::Quad, &s).expect("a quad face");
        assert_eq!(face, 3);
        assert!((u - 0.3).abs() < 1e-7 && (v - 0.8).abs() < 1e-7, "{u} {v}");
        assert_eq!(face_at(MeshType::Triangle, &s), Some((7, 0.3, 0.5)));
    }
}
