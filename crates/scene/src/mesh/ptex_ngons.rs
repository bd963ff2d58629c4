//! The outlines of a mesh's n-gons for quad-mesh Ptex files ([`Mesh::ptex_ngons`]): where
//! a hit on an n-gon's triangle finds its sub-quad ([`super::ptex_quads`] numbers them).
//!
//! The scene keeps each n-gon's outline (its first face id and its mesh vertex indices in
//! polygon order: 16 bytes a polygon and 4 a vertex); the renderer, where the scene reads
//! a quad-mesh Ptex file, [`Ngons::prepare`]s the search once per polygon: its plane (the
//! outline's Newell normal), its centroid (vertex mean), and the angle of each spoke from
//! the centroid to an edge midpoint. Sub-quad i lies between spokes i − 1 and i; where the
//! spokes run in angular order around the centroid, each sector under π, and each vertex
//! inside its own sector, the sub-quads are the polygon cut by the sectors, and a hit's
//! sub-quad is found by a binary search on the hit's angle (O(log n)), its (u, v) by
//! inverting that sub-quad's bilinear map (its neighbours tried too, for points on a
//! border); otherwise (a polygon that is not star-shaped about its centroid) every
//! sub-quad is tried and the one whose inverse lies inside [0, 1]², or nearest to it, is
//! kept (O(n), with n at most [`MAX_NGON_VERTICES`]).
//!
//! A polygon with holes is given its outer boundary's sub-quads (or, of 4 vertices, that
//! quad's one face): Ptex and OpenSubdiv have no faces with holes, so this is mira's
//! reading (warned of where a quad-mesh file is read), the holes then simply have no hits.
//!
//! [`Mesh::ptex_ngons`]: super::Mesh::ptex_ngons
//! [`MAX_NGON_VERTICES`]: super::ptex_quads::MAX_NGON_VERTICES

use glam::{DVec3, Vec3};

use super::ptex_quads::{self, invert_bilinear};
use super::ptex_refined::Refined;

/// One n-gon's outline and, once prepared, its search data.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ngon {
    /// Its first Ptex face id.
    pub first: u32,
    /// Where its outline starts in [`Ngons::outline`].
    pub start: u32,
    /// Its vertex count n.
    pub len: u32,
    /// Whether it is one quad face (a 4-vertex outline with holes) rather than n sub-quads.
    pub one_quad: bool,
}

/// The plane and spokes of a prepared n-gon (object space).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Frame {
    /// The vertex mean.
    centroid: Vec3,
    /// Unit vectors spanning the polygon's plane, e1 × e2 along the Newell normal (the
    /// outline runs counter-clockwise in them).
    e1: Vec3,
    e2: Vec3,
    /// Whether the sub-quads lie in angular order (the binary search applies).
    star: bool,
    /// The polygon's area (object space; of its projection on its Newell plane).
    area: f32,
}

/// The n-gons of a mesh, in increasing first face id.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Ngons {
    /// Each n-gon.
    pub polygons: Vec<Ngon>,
    /// Their outlines one after another: mesh vertex indices in polygon order.
    pub outline: Vec<u32>,
    /// Per polygon, once prepared ([`Ngons::prepare`]); empty before.
    frames: Vec<Frame>,
    /// Per outline vertex i of a star-shaped polygon: the angle (radians, (0, 2π]) from
    /// the polygon's last spoke (centroid to the midpoint of edge n−1 → 0) to spoke i
    /// (to the midpoint of edge i → i+1), counter-clockwise; the last is 2π. Empty before
    /// [`Ngons::prepare`].
    angles: Vec<f32>,
}

impl Ngons {
    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.polygons.is_empty()
    }

    /// Bytes held.
    pub fn memory_bytes(&self) -> usize {
        self.polygons.len() * std::mem::size_of::<Ngon>()
            + self.outline.len() * 4
            + self.frames.len() * std::mem::size_of::<Frame>()
            + self.angles.len() * 4
    }

    /// Adds an n-gon of first face id `first` (above every one added before) and outline
    /// `outline` (mesh vertex indices); `one_quad` for a 4-vertex outline with holes.
    pub fn push(&mut self, first: u32, outline: &[u32], one_quad: bool) {
        let start = self.outline.len() as u32;
        self.outline.extend_from_slice(outline);
        self.polygons.push(Ngon { first, start, len: outline.len() as u32, one_quad });
    }

    /// Appends `other` (a mesh appended after this one: its face ids moved on by `faces`,
    /// its vertex indices by `vertices`); unprepared.
    pub fn append(&mut self, other: &Ngons, faces: u32, vertices: u32) {
        let start = self.outline.len() as u32;
        self.polygons.extend(
            other
                .polygons
                .iter()
                .filter_map(|p| Some(Ngon { first: p.first.checked_add(faces)?, start: p.start + start, ..*p })),
        );
        self.outline.extend(other.outline.iter().map(|&v| v + vertices));
        self.frames.clear();
        self.angles.clear();
    }

    /// The n-gon whose first face id is `first`.
    fn find(&self, first: u32) -> Option<usize> {
        let i = self.polygons.partition_point(|p| p.first < first);
        (self.polygons.get(i)?.first == first).then_some(i)
    }

    /// Computes every polygon's plane, centroid and spoke angles from `positions` (the
    /// mesh's object-space vertices), once: O(total outline length).
    pub fn prepare(&mut self, positions: &[Vec3]) {
        self.frames.clear();
        self.angles.clear();
        self.angles.resize(self.outline.len(), 0.0);
        for p in &self.polygons {
            let range = p.start as usize..(p.start + p.len) as usize;
            let frame = self.outline.get(range.clone()).and_then(|o| frame(o, positions, &mut self.angles[range]));
            self.frames.push(frame.unwrap_or_default());
        }
    }

    /// The object-space area of each Ptex face of the prepared n-gon of first face id
    /// `first`: the polygon's area over its n sub-quads (the whole, for a polygon given one
    /// quad face); `None` before [`Ngons::prepare`] or for a polygon without a plane.
    pub fn face_area(&self, first: u32) -> Option<f64> {
        let k = self.find(first)?;
        let (p, f) = (self.polygons[k], self.frames.get(k)?);
        let faces = if p.one_quad { 1.0 } else { f64::from(p.len.max(1)) };
        (f.area > 0.0).then(|| f64::from(f.area) / faces)
    }

    /// The sub-quad face id and (u, v) of the object-space point `hit` on the n-gon of first
    /// face id `first` (prepared), and how many sub-quads' bilinear maps were inverted (the
    /// search's work).
    pub fn locate(&self, first: u32, positions: &[Vec3], hit: DVec3) -> (Option<(u32, f32, f32)>, usize) {
        let Some(k) = self.find(first) else { return (None, 0) };
        let (p, Some(f)) = (self.polygons[k], self.frames.get(k)) else { return (None, 0) };
        if f.e1 == Vec3::ZERO {
            return (None, 0);
        }
        let Some(outline) = self.outline.get(p.start as usize..(p.start + p.len) as usize) else { return (None, 0) };
        let (c, e1, e2) = (f.centroid.as_dvec3(), f.e1.as_dvec3(), f.e2.as_dvec3());
        let flat = |q: DVec3| [(q - c).dot(e1), (q - c).dot(e2)];
        // The outline's points are read as the search needs them (three sub-quads' worth
        // for a star-shaped polygon), never all n per hit.
        let point = |i: usize| outline.get(i).and_then(|&v| positions.get(v as usize)).map(|q| q.as_dvec3());
        let at = flat(hit);
        let n = outline.len();
        if n < 3 {
            return (None, 0);
        }
        if p.one_quad {
            let [Some(a), Some(b), Some(d), Some(e)] = [0, 1, 2, 3].map(point) else { return (None, 0) };
            let quad = [a, b, d, e].map(flat);
            let uv =
                invert_bilinear(quad, at).map(|[u, v]| (p.first, u.clamp(0.0, 1.0) as f32, v.clamp(0.0, 1.0) as f32));
            return (uv, 1);
        }
        let sub_quad = |i: usize| {
            let (prev, here, next) = (point((i + n - 1) % n)?, point(i)?, point((i + 1) % n)?);
            Some([here, (here + next) * 0.5, c, (prev + here) * 0.5].map(flat))
        };
        let mut tried = 0;
        let mut best: Option<(f64, usize, [f64; 2])> = None;
        let mut try_one = |i: usize| {
            tried += 1;
            if let Some(uv) = sub_quad(i).and_then(|quad| invert_bilinear(quad, at)) {
                let outside = [-uv[0], uv[0] - 1.0, -uv[1], uv[1] - 1.0].into_iter().fold(0.0, f64::max);
                if best.is_none_or(|b| outside < b.0) {
                    best = Some((outside, i, uv));
                }
            }
        };
        if f.star {
            let angles = &self.angles[p.start as usize..(p.start + p.len) as usize];
            let (Some(end), Some(start)) = (point(n - 1), point(0)) else { return (None, 0) };
            let last = 0.5 * (end + start);
            let phi = angle_from(flat(last), at);
            let i = angles.partition_point(|&a| f64::from(a) <= phi).min(n - 1);
            for k in [i, (i + 1) % n, (i + n - 1) % n] {
                try_one(k);
            }
        } else {
            (0..n).for_each(&mut try_one);
        }
        let uv = best.and_then(|(_, i, [u, v])| {
            Some((p.first.checked_add(i as u32)?, u.clamp(0.0, 1.0) as f32, v.clamp(0.0, 1.0) as f32))
        });
        (uv, tried)
    }
}

/// The counter-clockwise angle (radians, [0, 2π)) from 2D direction `from` to `to`.
fn angle_from(from: [f64; 2], to: [f64; 2]) -> f64 {
    let cross = from[0] * to[1] - from[1] * to[0];
    let dot = from[0] * to[0] + from[1] * to[1];
    let a = cross.atan2(dot);
    if a < 0.0 {
        a + std::f64::consts::TAU
    } else {
        a
    }
}

/// The frame of the polygon of outline `outline` (vertex indices into `positions`), its
/// spokes' angles written to `angles` where it is star-shaped; `None` where it has no plane.
fn frame(outline: &[u32], positions: &[Vec3], angles: &mut [f32]) -> Option<Frame> {
    let points: Vec<DVec3> =
        outline.iter().map(|&v| positions.get(v as usize).map(|p| p.as_dvec3())).collect::<Option<_>>()?;
    let n = points.len();
    if n < 3 {
        return None;
    }
    let mut normal = DVec3::ZERO;
    for k in 0..n {
        let (a, b) = (points[k], points[(k + 1) % n]);
        normal += DVec3::new((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    let area = 0.5 * normal.length();
    let normal = normal.try_normalize()?;
    let e1 = normal.any_orthonormal_vector();
    let e2 = normal.cross(e1);
    let centroid = points.iter().sum::<DVec3>() / n as f64;
    let flat = |q: DVec3| [(q - centroid).dot(e1), (q - centroid).dot(e2)];
    let spoke = |i: usize| flat(0.5 * (points[i % n] + points[(i + 1) % n]));
    let last = spoke(n - 1);
    let mut star = true;
    let mut previous = 0.0;
    for i in 0..n {
        let a = if i == n - 1 { std::f64::consts::TAU } else { angle_from(last, spoke(i)) };
        // The vertex between spokes i − 1 and i, each sector under π.
        let vertex = angle_from(last, flat(points[i]));
        let vertex = if i == 0 && vertex > a { vertex - std::f64::consts::TAU } else { vertex };
        star &= a > previous && a - previous < std::f64::consts::PI && vertex > previous && vertex < a;
        angles[i] = a as f32;
        previous = a;
    }
    Some(Frame { centroid: centroid.as_vec3(), e1: e1.as_vec3(), e2: e2.as_vec3(), star, area: area as f32 })
}

/// The area of the quad-mesh Ptex face a hit on triangle `prim` lies on, over the
/// triangle's own area (both object space; arguments as [`hit_face_uv`]): 2 on a quad of
/// two triangles, ⅓ on a lone triangle (each of its 3 sub-quads), an n-gon's area over n
/// over the triangle's on an n-gon's sub-quads, one over the triangle's share of its face
/// on a refined surface ([`Refined::area_share`]); `None` where the triangle has no face
/// or no area. A Ptex filter width in face units needs the face's size, not the
/// triangle's.
pub fn face_area_ratio(
    codes: &[u32],
    ngons: &Ngons,
    refined: &Refined,
    triangles: &[[u32; 3]],
    positions: &[Vec3],
    prim: usize,
) -> Option<f64> {
    let code = *codes.get(prim)?;
    if let Some(number) = ptex_quads::refined_number(code) {
        return refined.area_share(number).filter(|s| *s > 0.0).map(|s| 1.0 / s);
    }
    if ptex_quads::decode(code).is_some() {
        return Some(2.0);
    }
    if ptex_quads::triangle_first(code).is_some() {
        return Some(1.0 / 3.0);
    }
    let first = ptex_quads::ngon_first(code)?;
    let t = triangles.get(prim)?;
    let [a, b, c] = [t[0], t[1], t[2]].map(|v| positions.get(v as usize).map(|p| p.as_dvec3()));
    let (a, b, c) = (a?, b?, c?);
    let own = 0.5 * (b - a).cross(c - a).length();
    (own > 0.0).then_some(())?;
    Some(ngons.face_area(first)? / own)
}

/// The quad-mesh Ptex face id and (u, v) of a hit at barycentrics `bary` on triangle
/// `prim` of a mesh (`codes` its packed values, [`ptex_quads`]; `ngons` its prepared
/// n-gons; `refined` its refined surfaces; `triangles` its vertex indices; `positions`
/// its object-space vertices), or `None` where the triangle has no face.
pub fn hit_face_uv(
    codes: &[u32],
    ngons: &Ngons,
    refined: &Refined,
    triangles: &[[u32; 3]],
    positions: &[Vec3],
    prim: usize,
    bary: [f32; 3],
) -> Option<(u32, f32, f32)> {
    let code = *codes.get(prim)?;
    if let Some(hit) = ptex_quads::face_uv(code, bary) {
        return Some(hit);
    }
    if let Some(number) = ptex_quads::refined_number(code) {
        return refined.face_uv(number, bary);
    }
    if let Some(first) = ptex_quads::triangle_first(code) {
        return ptex_quads::triangle_face_uv(first, bary);
    }
    let first = ptex_quads::ngon_first(code)?;
    let t = triangles.get(prim)?;
    let mut hit = DVec3::ZERO;
    for (v, b) in t.iter().zip(bary) {
        hit += positions.get(*v as usize)?.as_dvec3() * f64::from(b);
    }
    ngons.locate(first, positions, hit).0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// N-gon `points` (2D, in the plane z = 1) as a `c` polygon fanned from vertex 0: each
    /// point of `uvs` placed by each sub-quad's bilinear map is hit on the fan triangle
    /// that holds it (barycentrics in f64), and found as that sub-quad's face and (u, v)
    /// within 1e-5, after at most `most` inversions each; every fan triangle is hit.
    fn check_fan(points: &[[f32; 2]], uvs: &[(f64, f64)], most: usize) {
        let positions: Vec<Vec3> = points.iter().map(|p| Vec3::new(p[0], p[1], 1.0)).collect();
        let n = points.len();
        let triangles: Vec<[u32; 3]> = (1..n as u32 - 1).map(|k| [0, k, k + 1]).collect();
        let codes = vec![ptex_quads::encode_ngon(40); triangles.len()];
        let mut ngons = Ngons::default();
        ngons.push(40, &(0..n as u32).collect::<Vec<_>>(), false);
        ngons.prepare(&positions);
        let p = |i: usize| positions[i % n].as_dvec3();
        let centroid = (0..n).map(p).sum::<DVec3>() / n as f64;
        let mut hit_triangles = std::collections::HashSet::new();
        for i in 0..n {
            let quad = [p(i), (p(i) + p(i + 1)) * 0.5, centroid, (p(i + n - 1) + p(i)) * 0.5];
            for &(u, v) in uvs {
                let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
                let x: DVec3 = (0..4).map(|k| quad[k] * w[k]).sum();
                let (prim, bary) = (0..triangles.len())
                    .find_map(|t| {
                        let [a, b, c] = triangles[t].map(|k| positions[k as usize].as_dvec3());
                        let (v0, v1, v2) = (b - a, c - a, x - a);
                        let d = v0.x * v1.y - v1.x * v0.y;
                        let b1 = (v2.x * v1.y - v1.x * v2.y) / d;
                        let b2 = (v0.x * v2.y - v2.x * v0.y) / d;
                        (b1 >= -1e-9 && b2 >= -1e-9 && b1 + b2 <= 1.0 + 1e-9)
                            .then_some((t, [(1.0 - b1 - b2) as f32, b1 as f32, b2 as f32]))
                    })
                    .expect("inside the polygon");
                hit_triangles.insert(prim);
                let (face, gu, gv) =
                    hit_face_uv(&codes, &ngons, &Refined::default(), &triangles, &positions, prim, bary)
                        .expect("an n-gon face");
                assert_eq!(face, 40 + i as u32, "{n}-gon, sub-quad {i} at ({u}, {v})");
                let (du, dv) = ((f64::from(gu) - u).abs(), (f64::from(gv) - v).abs());
                assert!(du < 1e-5 && dv < 1e-5, "sub-quad {i}: ({u}, {v}) vs ({gu}, {gv})");
                let hit = (0..3).map(|k| positions[triangles[prim][k] as usize].as_dvec3() * f64::from(bary[k])).sum();
                let tried = ngons.locate(40, &positions, hit).1;
                assert!(tried <= most, "{tried} inversions");
            }
        }
        assert_eq!(hit_triangles.len(), triangles.len(), "every fan triangle");
    }

    /// A convex pentagon and a 200-gon (on an ellipse): each sub-quad's centre and inner
    /// points, hit on the fan triangles, come back as its face and (u, v) (1e-5) after at
    /// most 3 inversions each (the binary search's sub-quad and its two neighbours, not
    /// the 200 a scan would try).
    #[test]
    fn ngon_points_are_found_in_their_sub_quads_from_every_fan_triangle() {
        let uvs = [(0.5, 0.5), (0.1, 0.2), (0.9, 0.05), (0.3, 0.95), (0.02, 0.02), (0.98, 0.98), (0.7, 0.6)];
        check_fan(&[[0.0, 0.0], [2.0, 0.0], [2.5, 1.5], [1.0, 2.5], [-0.5, 1.5]], &uvs, 3);
        let ring: Vec<[f32; 2]> = (0..200)
            .map(|k| {
                let a = std::f64::consts::TAU * f64::from(k) / 200.0;
                [(3.0 * a.cos()) as f32, (2.0 * a.sin()) as f32]
            })
            .collect();
        check_fan(&ring, &uvs, 3);
    }

    /// An L (its centroid outside it) is not star-shaped about its centroid: every one of
    /// its 6 sub-quads is tried (exact count), and a point gets a face.
    #[test]
    fn a_polygon_not_star_shaped_is_scanned() {
        let l = [[0.0, 0.0], [4.0, 0.0], [4.0, 0.5], [0.5, 0.5], [0.5, 4.0], [0.0, 4.0]];
        let mut ngons = Ngons::default();
        ngons.push(0, &[0, 1, 2, 3, 4, 5], false);
        let positions: Vec<Vec3> = l.iter().map(|p| Vec3::new(p[0], p[1], 0.0)).collect();
        ngons.prepare(&positions);
        assert!(!ngons.frames[0].star);
        let (found, tried) = ngons.locate(0, &positions, DVec3::new(3.5, 0.25, 0.0));
        assert_eq!(tried, 6);
        assert!(found.is_some());
        // The frames and angles cost nothing until prepared; a missing n-gon is none.
        assert_eq!(ngons.locate(7, &positions, DVec3::ZERO), (None, 0));
    }

    /// The face-area ratio a Ptex filter width needs: 2 on a quad's triangle, ⅓ on a lone
    /// triangle (exact), and on a fan triangle of a unit-circumradius hexagon (area
    /// 3√3/2, its triangles from vertex 0 of areas √3/4, √3/2, √3/2, √3/4) the hexagon's
    /// area over 6 over that triangle's, within 1e-6; `None` before `prepare`.
    #[test]
    fn face_areas_are_the_ptex_faces_not_the_triangles() {
        let positions: Vec<Vec3> = (0..6)
            .map(|k| {
                let a = std::f32::consts::TAU * k as f32 / 6.0;
                Vec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let triangles: Vec<[u32; 3]> = (1..5u32).map(|k| [0, k, k + 1]).collect();
        let mut ngons = Ngons::default();
        ngons.push(10, &(0..6u32).collect::<Vec<_>>(), false);
        let codes = vec![ptex_quads::encode_ngon(10); 4];
        assert_eq!(face_area_ratio(&codes, &ngons, &Refined::default(), &triangles, &positions, 0), None);
        ngons.prepare(&positions);
        let hexagon = 1.5 * 3f64.sqrt();
        for (prim, own) in
            [(0, 3f64.sqrt() / 4.0), (1, 3f64.sqrt() / 2.0), (2, 3f64.sqrt() / 2.0), (3, 3f64.sqrt() / 4.0)]
        {
            let r = face_area_ratio(&codes, &ngons, &Refined::default(), &triangles, &positions, prim)
                .expect("a prepared n-gon");
            assert!((r - hexagon / 6.0 / own).abs() < 1e-6, "{prim}: {r}");
        }
        let quad = [ptex_quads::encode(3, [0, 1, 2])];
        assert_eq!(face_area_ratio(&quad, &ngons, &Refined::default(), &triangles, &positions, 0), Some(2.0));
        let lone = [ptex_quads::encode_triangle(7)];
        assert_eq!(face_area_ratio(&lone, &ngons, &Refined::default(), &triangles, &positions, 0), Some(1.0 / 3.0));
    }
}
