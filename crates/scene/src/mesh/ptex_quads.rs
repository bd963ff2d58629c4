//! Ptex face ids of quad-mesh files ([`Mesh::ptex_quads`](super::Mesh::ptex_quads)): for
//! each triangle of an object whose polygons include quads or n-gons, the Ptex face of
//! the polygon it was cut from, packed in one `u32` (4 bytes per triangle).
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
//! children). A hit's sub-quad and (u, v) are found at hit time ([`ngon_face_uv`]): the
//! polygon's outline is rebuilt from its triangles (consecutive, one packed value, the
//! first starting at the polygon's vertex 0), projected on its Newell plane, and the
//! bilinear map of each sub-quad inverted ([`invert_bilinear`]).
//!
//! Packing: a quad's triangle has bit 31 clear, bits 0–5 the corners k₀, k₁, k₂ of its
//! vertices 0, 1, 2 (two bits each), bits 6–30 the face id (at most [`MAX_FACE`]); an
//! n-gon's triangle has bit 31 set and bits 0–30 the polygon's first face id (at most
//! [`MAX_NGON_FACE`]); [`NONE`] for a triangle that has no face (a polygon with holes, a
//! strip or a fan, or beyond the face ids the packing holds).

use glam::DVec3;

/// The packed value of a triangle with no quad face.
pub const NONE: u32 = u32::MAX;

/// The largest quad face id the packing holds.
pub const MAX_FACE: u32 = (1 << 25) - 1;

/// The largest first face id of an n-gon the packing holds.
pub const MAX_NGON_FACE: u32 = (1 << 31) - 2;

/// The most vertices an n-gon may have to get sub-quad faces: [`ngon_face_uv`] rebuilds
/// the outline at each hit in O(n²), so a larger polygon (a hostile 10⁶-gon would hang the
/// render) gets [`NONE`] and the unmapped-polygon warning instead.
pub const MAX_NGON_VERTICES: usize = 64;

/// The bit that marks an n-gon's triangle.
const NGON: u32 = 1 << 31;

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
    if let Some(first) = ngon_first(code) {
        return first.checked_add(by).map_or(NONE, encode_ngon);
    }
    match decode(code) {
        Some((face, corners)) => face.checked_add(by).map_or(NONE, |f| encode(f, corners)),
        None => NONE,
    }
}

/// The face id and the quad corners of packed value `code` (`None` for [`NONE`] and an
/// n-gon's triangle).
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

/// The first face id of the n-gon of packed value `code` (`None` for a quad's triangle and
/// [`NONE`]).
pub fn ngon_first(code: u32) -> Option<u32> {
    (code & NGON != 0 && code != NONE).then_some(code & !NGON)
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

/// The Ptex sub-quad face id and its face coordinates (u, v) of a hit at barycentrics
/// `bary` on triangle `prim` of a mesh (`codes` its packed values, `triangles` its vertex
/// indices, `positions` its object-space vertices) whose packed value is an n-gon's
/// (`None` otherwise, or where its outline cannot be rebuilt). The polygon's triangles are
/// the run of equal packed values around `prim`; its outline their edges that no other of
/// them has reversed, from the first triangle's vertex 0 (the polygon's vertex 0). The
/// sub-quad is the one whose inverted bilinear map puts the point inside [0, 1]² (or
/// nearest to it, on a non-planar or non-convex polygon); (u, v) clamped to [0, 1]. Costs
/// O(n²) in the polygon's vertex count n.
pub fn ngon_face_uv(
    codes: &[u32],
    triangles: &[[u32; 3]],
    positions: &[glam::Vec3],
    prim: usize,
    bary: [f32; 3],
) -> Option<(u32, f32, f32)> {
    let code = *codes.get(prim)?;
    let first = ngon_first(code)?;
    let (mut lo, mut hi) = (prim, prim + 1);
    while lo > 0 && codes[lo - 1] == code {
        lo -= 1;
    }
    while hi < codes.len().min(triangles.len()) && codes[hi] == code {
        hi += 1;
    }
    let tris = triangles.get(lo..hi)?;
    // An n-gon of n vertices has n − 2 triangles; a longer run is not one (bounds the cost).
    if tris.len() + 2 > MAX_NGON_VERTICES {
        return None;
    }
    let edges: Vec<[u32; 2]> = tris.iter().flat_map(|t| [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]]).collect();
    let boundary: Vec<[u32; 2]> = edges.iter().copied().filter(|&[a, b]| !edges.contains(&[b, a])).collect();
    let mut outline = vec![tris[0][0]];
    while outline.len() < boundary.len() {
        let last = *outline.last()?;
        outline.push(boundary.iter().find(|e| e[0] == last)?[1]);
    }
    let pos = |i: u32| positions.get(i as usize).map(|p| p.as_dvec3());
    let points: Vec<DVec3> = outline.iter().map(|&i| pos(i)).collect::<Option<_>>()?;
    let tri = triangles[prim];
    let hit = pos(tri[0])? * f64::from(bary[0]) + pos(tri[1])? * f64::from(bary[1]) + pos(tri[2])? * f64::from(bary[2]);
    // The polygon's plane: Newell normal, any basis in it.
    let n = points.len();
    let mut normal = DVec3::ZERO;
    for k in 0..n {
        let (a, b) = (points[k], points[(k + 1) % n]);
        normal += DVec3::new((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    let normal = normal.try_normalize()?;
    let e1 = normal.any_orthonormal_vector();
    let e2 = normal.cross(e1);
    let flat = |p: DVec3| [p.dot(e1), p.dot(e2)];
    let centroid = points.iter().sum::<DVec3>() / n as f64;
    let mut best: Option<(f64, u32, [f64; 2])> = None;
    for i in 0..n {
        let (prev, here, next) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
        let quad = [here, (here + next) * 0.5, centroid, (prev + here) * 0.5].map(flat);
        let Some(uv) = invert_bilinear(quad, flat(hit)) else { continue };
        let outside = [-uv[0], uv[0] - 1.0, -uv[1], uv[1] - 1.0].into_iter().fold(0.0, f64::max);
        if best.is_none_or(|b| outside < b.0) {
            best = Some((outside, i as u32, uv));
        }
    }
    let (_, i, [u, v]) = best?;
    Some((first.checked_add(i)?, u.clamp(0.0, 1.0) as f32, v.clamp(0.0, 1.0) as f32))
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

    /// A pentagon fanned from vertex 0: each sub-quad's corners, centre and a point near
    /// its vertex map to that sub-quad's face and the (u, v) they have on it (1e-5), from
    /// every triangle of the fan; n-gon values round-trip and offset.
    #[test]
    fn ngon_hits_map_to_their_sub_quads() {
        use glam::Vec3;
        let pts = [[0.0, 0.0], [2.0, 0.0], [2.5, 1.5], [1.0, 2.5], [-0.5, 1.5]];
        let positions: Vec<Vec3> = pts.iter().map(|p| Vec3::new(p[0], p[1], 1.0)).collect();
        // Vertex 0 of the polygon is mesh vertex 0; a foreign triangle before and after.
        let triangles = vec![[9, 9, 9], [0, 1, 2], [0, 2, 3], [0, 3, 4], [9, 9, 9]];
        let codes = vec![encode(0, [0, 1, 2]), encode_ngon(7), encode_ngon(7), encode_ngon(7), NONE];
        assert_eq!(ngon_first(codes[1]), Some(7));
        assert_eq!(ngon_first(offset(codes[1], 3)), Some(10));
        assert_eq!(decode(codes[1]), None);
        assert_eq!(ngon_first(codes[0]), None);
        let p = |i: usize| Vec3::new(pts[i % 5][0], pts[i % 5][1], 1.0);
        let centroid = (0..5).map(p).sum::<Vec3>() / 5.0;
        for i in 0..5 {
            let quad = [p(i), (p(i) + p(i + 1)) * 0.5, centroid, (p(i + 4) + p(i)) * 0.5];
            for (u, v) in [(0.5, 0.5), (0.1, 0.2), (0.9, 0.05), (0.3, 0.95)] {
                let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
                let x: Vec3 = (0..4).map(|k| quad[k] * w[k]).sum();
                // Which fan triangle holds x, and its barycentrics there.
                let (prim, bary) = (1..4)
                    .find_map(|t| {
                        let [a, b, c] = triangles[t].map(|k| positions[k as usize]);
                        let (v0, v1, v2) = (b - a, c - a, x - a);
                        let d = v0.x * v1.y - v1.x * v0.y;
                        let b1 = (v2.x * v1.y - v1.x * v2.y) / d;
                        let b2 = (v0.x * v2.y - v2.x * v0.y) / d;
                        (b1 >= -1e-6 && b2 >= -1e-6 && b1 + b2 <= 1.0 + 1e-6).then_some((t, [1.0 - b1 - b2, b1, b2]))
                    })
                    .expect("inside the pentagon");
                let (face, gu, gv) = ngon_face_uv(&codes, &triangles, &positions, prim, bary).expect("an n-gon face");
                assert_eq!(face, 7 + i as u32, "sub-quad {i} at ({u}, {v})");
                assert!((gu - u).abs() < 1e-5 && (gv - v).abs() < 1e-5, "sub-quad {i}: ({u}, {v}) vs ({gu}, {gv})");
            }
        }
        assert_eq!(ngon_face_uv(&codes, &triangles, &positions, 0, [1.0, 0.0, 0.0]), None);
    }
}
