//! Ptex face ids of quad-mesh files ([`Mesh::ptex_quads`](super::Mesh::ptex_quads)): for
//! each triangle of an object, the Ptex face of the polygon it was cut from, packed in one
//! `u32` (4 bytes per triangle).
//!
//! Ptex numbers the faces of a quad mesh in polygon order: a quad is one face, any other
//! polygon of n vertices n faces (its n sub-quads, one per corner). A quad face's
//! coordinates (u, v) ∈ [0, 1]² have their origin at the polygon's vertex 0, u along the
//! edge 0 → 1 and v along 0 → 3: corner k of the quad lies at [`CORNER_UV`]`[k]`. A hit on
//! a triangle of the quad with barycentrics (b0, b1, b2) lies at Σ bᵢ · [`CORNER_UV`]`[kᵢ]`
//! (exact for a planar parallelogram; on other quads, the linear map of each of the
//! quad's two triangles).
//!
//! An n-gon (n ≠ 4) is split into n sub-quads: sub-quad i has the corners (vertex i, the
//! midpoint of edge i → i+1, the polygon's centroid (vertex mean), the midpoint of edge
//! i−1 → i) at (u, v) = (0, 0), (1, 0), (1, 1), (0, 1), and face id = the polygon's first
//! face id + i (OpenSubdiv's and Ptex's one face per corner, the level-1 Catmull-Clark
//! children).
//!
//! A triangle that is a polygon of its own (a 3-vertex `c` or `p` polygon, each triangle
//! of a `strip` or a `fan`, each triangle of a trilist — mira's reading: mental ray
//! documents no Ptex numbering for strips, fans or trilists, whose triangles are its
//! faces once it has read them, and OpenSubdiv and Ptex count a mesh's faces in order,
//! a triangle three sub-quads) keeps its vertex order, so its sub-quad and (u, v) follow
//! from the hit's barycentrics alone ([`triangle_face_uv`]: the bilinear maps of the
//! sub-quads are inverted in barycentric coordinates, which any affine map of the triangle
//! leaves unchanged). A larger n-gon's outline is kept per polygon
//! ([`super::ptex_ngons`]), where the hit's sub-quad is found.
//!
//! A triangle of a subdivision surface or a ccmesh refined by one level or more lies in
//! one fine quad of the refinement, inside one Ptex face of its control cage (a cage quad
//! one face, a cage n-gon one per corner: its level-1 sub-quads); its value holds its
//! number among the mesh's refined triangles, by which [`super::ptex_refined`] finds the
//! face and the fine quad's place on it.
//!
//! Packing: a quad's triangle has bit 31 clear, bits 0–5 the corners k₀, k₁, k₂ of its
//! vertices 0, 1, 2 (two bits each), bits 6–30 the face id (at most [`MAX_FACE`]); an
//! n-gon's triangle has bits 31, 30, 29 = 1, 0, 0 and bits 0–28 the polygon's first face
//! id (at most [`MAX_NGON_FACE`]); a refined triangle bits 31, 30, 29 = 1, 0, 1 and bits
//! 0–28 its refined number (at most [`MAX_REFINED`]); a triangle of its own has bits 31,
//! 30 = 1, 1 and bits 0–29 its first face id (at most [`MAX_TRIANGLE_FACE`]); [`NONE`]
//! for a triangle that has no face (a polygon of too many vertices, or beyond the face
//! ids the packing holds).

/// The packed value of a triangle with no quad face.
pub const NONE: u32 = u32::MAX;

/// The largest quad face id the packing holds.
pub const MAX_FACE: u32 = (1 << 25) - 1;

/// The largest first face id of an n-gon the packing holds.
pub const MAX_NGON_FACE: u32 = (1 << 29) - 1;

/// The largest refined triangle number the packing holds.
pub const MAX_REFINED: u32 = (1 << 29) - 1;

/// The largest first face id of a triangle that is a polygon of its own.
pub const MAX_TRIANGLE_FACE: u32 = (1 << 30) - 2;

/// The most vertices an n-gon may have to get sub-quad faces: a hostile polygon of more
/// (10⁶ vertices, say) gets [`NONE`] and the unmapped-polygon warning at its line. Its
/// outline is searched in O(log n) per hit where its sub-quads lie in angular order
/// around its centroid, else in O(n) ([`super::ptex_ngons`]).
pub const MAX_NGON_VERTICES: usize = 4096;

/// The bit that marks an n-gon's or a lone triangle's value.
const NGON: u32 = 1 << 31;

/// The bit that, with [`NGON`], marks a triangle that is a polygon of its own.
const OWN: u32 = 1 << 30;

/// The bit that, with [`NGON`] and without [`OWN`], marks a refined triangle.
const REFINED: u32 = 1 << 29;

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
/// its faces numbered after that one's) and, for a refined triangle, its refined number
/// by `refined_by` (its faces are moved on in its surface's record).
pub fn offset(code: u32, by: u32, refined_by: u32) -> u32 {
    if let Some(number) = refined_number(code) {
        return number.checked_add(refined_by).map_or(NONE, encode_refined);
    }
    if let Some(first) = triangle_first(code) {
        return first.checked_add(by).map_or(NONE, encode_triangle);
    }
    if let Some(first) = ngon_first(code) {
        return first.checked_add(by).map_or(NONE, encode_ngon);
    }
    match decode(code) {
        Some((face, corners)) => face.checked_add(by).map_or(NONE, |f| encode(f, corners)),
        None => NONE,
    }
}

/// The face id and the quad corners of packed value `code` (`None` for [`NONE`], an
/// n-gon's triangle and a lone triangle).
pub fn decode(code: u32) -> Option<(u32, [u8; 3])> {
    (code & NGON == 0).then(|| (code >> 6, [0, 2, 4].map(|s| (code >> s & 3) as u8)))
}

/// The packed value of a triangle of an n-gon whose first face id is `first`; [`NONE`]
/// beyond [`MAX_NGON_FACE`].
pub fn encode_ngon(first: u32) -> u32 {
    if first > MAX_NGON_FACE {
        return NONE;
    }
    NGON | first
}

/// The first face id of the n-gon of packed value `code` (`None` for any other value and
/// [`NONE`]).
pub fn ngon_first(code: u32) -> Option<u32> {
    (code & (NGON | OWN | REFINED) == NGON).then_some(code & MAX_NGON_FACE)
}

/// The packed value of the refined triangle of refined number `number`; [`NONE`] beyond
/// [`MAX_REFINED`].
pub fn encode_refined(number: u32) -> u32 {
    if number > MAX_REFINED {
        return NONE;
    }
    NGON | REFINED | number
}

/// The refined number of the refined triangle of packed value `code` (`None` for any
/// other value and [`NONE`]).
pub fn refined_number(code: u32) -> Option<u32> {
    (code & (NGON | OWN | REFINED) == NGON | REFINED).then_some(code & MAX_REFINED)
}

/// The packed value of a triangle that is a polygon of its own, its vertex 0 the
/// polygon's, whose first sub-quad face id is `first`; [`NONE`] beyond
/// [`MAX_TRIANGLE_FACE`].
pub fn encode_triangle(first: u32) -> u32 {
    if first > MAX_TRIANGLE_FACE {
        return NONE;
    }
    NGON | OWN | first
}

/// The first sub-quad face id of the lone triangle of packed value `code` (`None` for any
/// other value and [`NONE`]).
pub fn triangle_first(code: u32) -> Option<u32> {
    (code & (NGON | OWN) == NGON | OWN && code != NONE).then_some(code & (OWN - 1))
}

/// The sub-quad face id and its (u, v) of a hit at barycentrics `bary` on a triangle that
/// is a polygon of its own with first face id `first`: sub-quad i is where bᵢ is the
/// largest (its borders, the lines from the edge midpoints to the centroid, are where two
/// weights are equal; ties go to the lower i), (u, v) its bilinear map's inverse at
/// (b1, b2) in the plane of barycentric coordinates, clamped to [0, 1].
pub fn triangle_face_uv(first: u32, bary: [f32; 3]) -> Option<(u32, f32, f32)> {
    let b = bary.map(f64::from);
    let i = if b[0] >= b[1] && b[0] >= b[2] {
        0
    } else if b[1] >= b[2] {
        1
    } else {
        2
    };
    // Vertices, edge midpoints and centroid at (b1, b2).
    const V: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    let mid = |a: usize, c: usize| [(V[a][0] + V[c][0]) * 0.5, (V[a][1] + V[c][1]) * 0.5];
    let quad = [V[i], mid(i, (i + 1) % 3), [1.0 / 3.0; 2], mid((i + 2) % 3, i)];
    let [u, v] = invert_bilinear(quad, [b[1], b[2]])?;
    Some((first.checked_add(i as u32)?, u.clamp(0.0, 1.0) as f32, v.clamp(0.0, 1.0) as f32))
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

/// The (u, v) of 2D point `p` in the bilinear map of quad `q` (corners at (u, v) = (0, 0),
/// (1, 0), (1, 1), (0, 1)): p = q₀ + u e + v f + u v g with e = q₁ − q₀, f = q₃ − q₀,
/// g = q₀ − q₁ + q₂ − q₃; eliminating u gives a quadratic in v, of whose roots the one
/// nearest [0, 1] is kept. `None` for a degenerate quad.
pub fn invert_bilinear(q: [[f64; 2]; 4], p: [f64; 2]) -> Option<[f64; 2]> {
    let sub = |a: [f64; 2], b: [f64; 2]| [a[0] - b[0], a[1] - b[1]];
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let (e, f, h) = (sub(q[1], q[0]), sub(q[3], q[0]), sub(p, q[0]));
    let g = sub(sub(q[0], q[1]), sub(q[3], q[2]));
    let (k2, k1, k0) = (cross(g, f), cross(e, f) + cross(h, g), cross(h, e));
    let scale = cross(e, f).abs().max(f64::MIN_POSITIVE);
    let roots: Vec<f64> = if k2.abs() <= 1e-12 * scale {
        if k1 == 0.0 {
            return None;
        }
        vec![-k0 / k1]
    } else {
        let d = (k1 * k1 - 4.0 * k2 * k0).max(0.0).sqrt();
        vec![(-k1 + d) / (2.0 * k2), (-k1 - d) / (2.0 * k2)]
    };
    let outside = |t: f64| (-t).max(t - 1.0).max(0.0);
    let mut best: Option<(f64, [f64; 2])> = None;
    for v in roots {
        let den = [e[0] + v * g[0], e[1] + v * g[1]];
        let c = if den[0].abs() >= den[1].abs() { 0 } else { 1 };
        if den[c] == 0.0 {
            continue;
        }
        let u = (h[c] - v * f[c]) / den[c];
        let worst = outside(u).max(outside(v));
        if u.is_finite() && v.is_finite() && best.is_none_or(|b| worst < b.0) {
            best = Some((worst, [u, v]));
        }
    }
    best.map(|b| b.1)
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
    /// The bilinear inverse gives back the (u, v) a general quad's bilinear map sends to a
    /// point (1e-9), inside and on the border.
    #[test]
    fn bilinear_inverse_round_trips() {
        let q = [[0.0, 0.0], [2.0, 0.3], [2.4, 1.9], [-0.2, 1.1]];
        for u in [0.0, 0.1, 0.5, 0.77, 1.0] {
            for v in [0.0, 0.25, 0.6, 1.0] {
                let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
                let p = [0, 1].map(|c| (0..4).map(|k| w[k] * q[k][c]).sum::<f64>());
                let [gu, gv] = invert_bilinear(q, p).expect("a quad");
                assert!((gu - u).abs() < 1e-9 && (gv - v).abs() < 1e-9, "{u} {v}: {gu} {gv}");
            }
        }
        // A parallelogram (no quadratic term).
        let q = [[0.0, 0.0], [1.0, 0.0], [1.5, 1.0], [0.5, 1.0]];
        let [u, v] = invert_bilinear(q, [0.75, 0.5]).unwrap();
        assert!((u - 0.5).abs() < 1e-12 && (v - 0.5).abs() < 1e-12, "{u} {v}");
    }

    /// A lone triangle's sub-quads: points placed by each sub-quad's bilinear map (in
    /// barycentric coordinates) come back as that sub-quad's face and (u, v) (1e-6); lone
    /// triangle and n-gon values round-trip, offset, and stay apart from quads and none.
    #[test]
    fn a_lone_triangles_hits_map_to_its_sub_quads() {
        let v = [[1.0f64, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let mix = |a: [f64; 3], b: [f64; 3], t: f64| [0, 1, 2].map(|k| a[k] * (1.0 - t) + b[k] * t);
        for i in 0..3 {
            let quad = [v[i], mix(v[i], v[(i + 1) % 3], 0.5), [1.0 / 3.0; 3], mix(v[(i + 2) % 3], v[i], 0.5)];
            for (u, w) in [(0.5, 0.5), (0.1, 0.2), (0.9, 0.05), (0.3, 0.95), (0.0, 0.0), (0.97, 0.97)] {
                let wt = [(1.0 - u) * (1.0 - w), u * (1.0 - w), u * w, (1.0 - u) * w];
                let b = [0, 1, 2].map(|k| (0..4).map(|c| wt[c] * quad[c][k]).sum::<f64>() as f32);
                let (face, gu, gv) = triangle_face_uv(10, b).expect("a face");
                assert_eq!(face, 10 + i as u32, "sub-quad {i} at ({u}, {w})");
                assert!((f64::from(gu) - u).abs() < 1e-6 && (f64::from(gv) - w).abs() < 1e-6, "{i}: {gu} {gv}");
            }
        }
        let code = encode_triangle(12);
        assert_eq!((triangle_first(code), ngon_first(code), decode(code)), (Some(12), None, None));
        assert_eq!(triangle_first(offset(code, 3, 100)), Some(15));
        assert_eq!((triangle_first(encode_ngon(12)), ngon_first(encode_ngon(12))), (None, Some(12)));
        assert_eq!((triangle_first(NONE), ngon_first(NONE)), (None, None));
        assert_eq!(encode_triangle(MAX_TRIANGLE_FACE + 1), NONE);
        assert_eq!(triangle_first(encode_triangle(MAX_TRIANGLE_FACE)), Some(MAX_TRIANGLE_FACE));
        assert_eq!(triangle_first(encode(7, [0, 1, 2])), None);
        assert_eq!(ngon_first(encode_ngon(MAX_NGON_FACE)), Some(MAX_NGON_FACE));
        assert_eq!(encode_ngon(MAX_NGON_FACE + 1), NONE);
    }

    /// Refined triangles' values round-trip (exact), move on by the refined offset alone,
    /// and stay apart from every other kind; beyond [`MAX_REFINED`] they are none.
    #[test]
    fn refined_values_round_trip_apart_from_the_others() {
        for number in [0, 1, 12345, MAX_REFINED] {
            let code = encode_refined(number);
            assert_eq!(refined_number(code), Some(number));
            assert_eq!((ngon_first(code), triangle_first(code), decode(code)), (None, None, None));
        }
        assert_eq!(refined_number(offset(encode_refined(7), 1000, 5)), Some(12));
        assert_eq!(offset(encode_refined(MAX_REFINED), 0, 1), NONE);
        assert_eq!(encode_refined(MAX_REFINED + 1), NONE);
        for other in [encode_ngon(3), encode_triangle(3), encode(3, [0, 1, 2]), NONE] {
            assert_eq!(refined_number(other), None);
        }
    }
}
