//! Ptex face ids of quad-mesh files ([`Mesh::ptex_quads`](super::Mesh::ptex_quads)): for
//! each triangle of an object whose polygons include quads, the Ptex face id of the
//! polygon it was cut from and which corners of that quad its three vertices are, packed
//! in one `u32` (4 bytes per triangle).
//!
//! Ptex numbers the faces of a quad mesh in polygon order: a quad is one face, any other
//! polygon of n vertices n faces (its n sub-quads, one per corner). A quad face's
//! coordinates (u, v) ∈ [0, 1]² have their origin at the polygon's vertex 0, u along the
//! edge 0 → 1 and v along 0 → 3: corner k of the quad lies at [`CORNER_UV`]`[k]`. A hit on
//! a triangle of the quad with barycentrics (b0, b1, b2) lies at Σ bᵢ · [`CORNER_UV`]`[kᵢ]`
//! (exact for a planar parallelogram; on other quads, the linear map of each of the
//! quad's two triangles).
//!
//! Packing: bits 0–5 the corners k₀, k₁, k₂ of the triangle's vertices 0, 1, 2 (two bits
//! each), bits 6–31 the face id (below 2^26 − 1); [`NONE`] for a triangle that has no quad
//! face (cut from a polygon of other than 4 vertices, a polygon with holes, a strip or a
//! fan, or beyond the face ids the packing holds).

/// The packed value of a triangle with no quad face.
pub const NONE: u32 = u32::MAX;

/// The largest face id the packing holds.
pub const MAX_FACE: u32 = (1 << 26) - 2;

/// The face coordinates (u, v) of a quad's corners 0…3 (Ptex's quad convention).
pub const CORNER_UV: [[f32; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

/// The packed value of a triangle of face `face` whose vertices 0, 1, 2 are the quad's
/// corners `corners` (each 0…3); [`NONE`] for a face id beyond [`MAX_FACE`].
pub fn encode(face: u32, corners: [u8; 3]) -> u32 {
    if face > MAX_FACE {
        return NONE;
    }
    face << 6 | u32::from(corners[0] & 3) | u32::from(corners[1] & 3) << 2 | u32::from(corners[2] & 3) << 4
}

/// Packed value `code` with its face id moved on by `by` (a mesh appended after another:
/// its faces numbered after that one's).
pub fn offset(code: u32, by: u32) -> u32 {
    match decode(code) {
        Some((face, corners)) => face.checked_add(by).map_or(NONE, |f| encode(f, corners)),
        None => NONE,
    }
}

/// The face id and the quad corners of packed value `code` (`None` for [`NONE`]).
pub fn decode(code: u32) -> Option<(u32, [u8; 3])> {
    (code != NONE).then(|| (code >> 6, [0, 2, 4].map(|s| (code >> s & 3) as u8)))
}

/// The Ptex face id and the face coordinates (u, v) of a hit at barycentrics `bary`
/// (weights of the triangle's vertices 0, 1, 2) on a triangle of packed value `code`.
pub fn face_uv(code: u32, bary: [f32; 3]) -> Option<(u32, f32, f32)> {
    let (face, corners) = decode(code)?;
    let (mut u, mut v) = (0.0, 0.0);
    for (b, k) in bary.iter().zip(corners) {
        let [cu, cv] = CORNER_UV[k as usize];
        u += b * cu;
        v += b * cv;
    }
    Some((face, u, v))
}

/// The packed values of the triangles `triangles` (mesh vertex indices) cut from quad
/// `quad` (its four mesh vertex indices, in the polygon's order) of face id `face`: each
/// vertex's corner is its first position in `quad` (a vertex the quad lacks: [`NONE`]).
pub fn quad_triangles(face: u32, quad: [u32; 4], triangles: &[[u32; 3]]) -> impl Iterator<Item = u32> + '_ {
    triangles.iter().map(move |t| {
        let corner = |i: u32| quad.iter().position(|&q| q == i).map(|k| k as u8);
        match (corner(t[0]), corner(t[1]), corner(t[2])) {
            (Some(a), Some(b), Some(c)) => encode(face, [a, b, c]),
            _ => NONE,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Encoding round-trips (exact); beyond the largest face id it gives none.
    #[test]
    fn packing_round_trips() {
        for face in [0, 1, 77, MAX_FACE] {
            for corners in [[0, 1, 2], [0, 2, 3], [3, 1, 2], [2, 3, 0]] {
                assert_eq!(decode(encode(face, corners)), Some((face, corners)));
            }
        }
        assert_eq!(encode(MAX_FACE + 1, [0, 1, 2]), NONE);
        assert_eq!(decode(NONE), None);
    }

    /// The two triangles of a quad fanned from vertex 0 ((0, 1, 2) and (0, 2, 3)) or cut
    /// along the other diagonal ((1, 2, 3) and (1, 3, 0)) give the quad's (u, v) of the
    /// point their barycentrics name (1e-6): vertices at the corners, the centroid of
    /// each half, the centre on the diagonal.
    #[test]
    fn barycentrics_map_to_the_quads_face_coordinates() {
        let quad = [10, 11, 12, 13];
        for tris in [[[10, 11, 12], [10, 12, 13]], [[11, 12, 13], [11, 13, 10]]] {
            let codes: Vec<u32> = quad_triangles(5, quad, &tris).collect();
            for (t, code) in tris.iter().zip(&codes) {
                let uv = |i: u32| CORNER_UV[(i - 10) as usize];
                for bary in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0 / 3.0; 3], [0.2, 0.5, 0.3]] {
                    let (face, u, v) = face_uv(*code, bary).expect("a quad face");
                    let want_u: f32 = (0..3).map(|k| bary[k] * uv(t[k])[0]).sum();
                    let want_v: f32 = (0..3).map(|k| bary[k] * uv(t[k])[1]).sum();
                    assert_eq!(face, 5);
                    assert!((u - want_u).abs() <= 1e-6 && (v - want_v).abs() <= 1e-6, "{t:?} {bary:?}: {u} {v}");
                }
            }
        }
        // Vertex 2 of the second fanned triangle is corner 3: (0, 1).
        let code = quad_triangles(0, quad, &[[10, 12, 13]]).next().unwrap();
        assert_eq!(face_uv(code, [0.0, 0.0, 1.0]), Some((0, 0.0, 1.0)));
        // A vertex the quad lacks: none.
        assert_eq!(quad_triangles(0, quad, &[[10, 12, 99]]).next(), Some(NONE));
    }
}
