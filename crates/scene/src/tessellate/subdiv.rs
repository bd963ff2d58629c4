//! Catmull–Clark subdivision with creases, for `subdivision surface` and `ccmesh`.
//!
//! One level replaces every n-sided face by n quads through a face point, edge points and
//! moved vertex points. Edges carry a sharpness in levels (infinite for fully sharp edges
//! and open boundaries): an edge of sharpness ≥ 1 uses the sharp (midpoint) rule and passes
//! sharpness − 1 to its two halves, an edge between 0 and 1 blends the two rules (the
//! semi-sharp creases of DeRose, Kass and Truong 1998). A vertex with two sharp edges moves
//! along the crease curve, a vertex with more (or marked `corner`) stays put. Texture
//! coordinates are interpolated linearly over the refined faces.
//!
//! After the last level every vertex is placed on the limit surface and given the limit
//! normal: for smooth interior vertices by the limit position and tangent masks of
//! Halstead, Kass and DeRose 1993, for crease vertices on the limit of their crease curve
//! with an area-weighted normal, corners staying where they are.

use std::collections::HashMap;

use glam::{DVec3, Vec3};

use crate::mesh::{Mesh, TexSpace};

/// Sharpness that never runs out.
pub const SHARP: f64 = f64::INFINITY;

/// A polygon mesh being subdivided.
#[derive(Clone, Debug, Default)]
pub struct Cage {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Texture spaces: one coordinate per vertex each.
    pub textures: Vec<Vec<DVec3>>,
    /// Start of each face in `face_verts`, plus the end.
    pub face_starts: Vec<u32>,
    /// Vertex indices of all faces, counter-clockwise.
    pub face_verts: Vec<u32>,
    /// Material slot of each face.
    pub face_slots: Vec<u32>,
    /// Sharpness (in levels) of creased edges, keyed by (smaller, larger) vertex index.
    pub creases: HashMap<(u32, u32), f64>,
    /// Sharpness of corner vertices (absent = smooth).
    pub corners: HashMap<u32, f64>,
    /// Displacements of refined vertices applied by the next level (`detail` statements):
    /// (face, mask, one offset per set bit). Bit k < n selects the refined corner k of an
    /// n-sided face, n ≤ k < 2n the point of its edge k − n, and 2n the face point.
    pub details: Vec<(u32, u32, Vec<DVec3>)>,
}

fn key(a: u32, b: u32) -> (u32, u32) {
    if a < b {
        (a, b)
    } else {
        (b, a)
    }
}

impl Cage {
    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_starts.len().saturating_sub(1)
    }

    /// The vertices of face `f`.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_verts[self.face_starts[f] as usize..self.face_starts[f + 1] as usize]
    }

    /// Adds a face.
    pub fn push_face(&mut self, verts: &[u32], slot: u32) {
        if self.face_starts.is_empty() {
            self.face_starts.push(0);
        }
        self.face_verts.extend_from_slice(verts);
        self.face_starts.push(self.face_verts.len() as u32);
        self.face_slots.push(slot);
    }

    /// Number of faces after `levels` more levels.
    pub fn faces_after(&self, levels: u32) -> u64 {
        let mut faces = self.face_verts.len() as u64; // an n-gon makes n quads
        for _ in 1..levels {
            faces = faces.saturating_mul(4);
        }
        if levels == 0 {
            self.face_count() as u64
        } else {
            faces
        }
    }
}

/// Edge table of a cage: edges keyed by vertex pair, with their faces.
struct Edges {
    index: HashMap<(u32, u32), u32>,
    ends: Vec<(u32, u32)>,
    faces: Vec<[u32; 2]>,
    face_count: Vec<u8>,
}

impl Edges {
    fn new(cage: &Cage) -> Edges {
        let mut e = Edges {
            index: HashMap::with_capacity(cage.face_verts.len()),
            ends: Vec::new(),
            faces: Vec::new(),
            face_count: Vec::new(),
        };
        for f in 0..cage.face_count() {
            let vs = cage.face(f);
            for i in 0..vs.len() {
                let k = key(vs[i], vs[(i + 1) % vs.len()]);
                let id = *e.index.entry(k).or_insert_with(|| {
                    e.ends.push(k);
                    e.faces.push([u32::MAX; 2]);
                    e.face_count.push(0);
                    (e.ends.len() - 1) as u32
                }) as usize;
                let c = e.face_count[id] as usize;
                if c < 2 {
                    e.faces[id][c] = f as u32;
                }
                e.face_count[id] = e.face_count[id].saturating_add(1);
            }
        }
        e
    }

    fn id(&self, a: u32, b: u32) -> u32 {
        self.index[&key(a, b)]
    }
}

/// One level of Catmull–Clark subdivision.
pub fn subdivide(cage: &Cage) -> Cage {
    let nv = cage.positions.len();
    let nf = cage.face_count();
    let edges = Edges::new(cage);
    let ne = edges.ends.len();
    let sharpness = |e: usize| -> f64 {
        if edges.face_count[e] != 2 {
            SHARP
        } else {
            cage.creases.get(&edges.ends[e]).copied().unwrap_or(0.0)
        }
    };
    let avg = |idx: &[u32], data: &[DVec3]| idx.iter().map(|&i| data[i as usize]).sum::<DVec3>() / idx.len() as f64;

    // Face points.
    let face_points: Vec<DVec3> = (0..nf).map(|f| avg(cage.face(f), &cage.positions)).collect();
    // Edge points.
    let edge_points: Vec<DVec3> = (0..ne)
        .map(|e| {
            let (a, b) = edges.ends[e];
            let mid = (cage.positions[a as usize] + cage.positions[b as usize]) * 0.5;
            let s = sharpness(e);
            if s >= 1.0 {
                return mid;
            }
            let [f0, f1] = edges.faces[e];
            let smooth = (mid * 2.0 + face_points[f0 as usize] + face_points[f1 as usize]) * 0.25;
            if s <= 0.0 {
                smooth
            } else {
                smooth.lerp(mid, s)
            }
        })
        .collect();
    // Vertex points.
    let mut vert_faces: Vec<Vec<u32>> = vec![Vec::new(); nv];
    for f in 0..nf {
        for &v in cage.face(f) {
            vert_faces[v as usize].push(f as u32);
        }
    }
    let mut vert_edges: Vec<Vec<u32>> = vec![Vec::new(); nv];
    for (e, &(a, b)) in edges.ends.iter().enumerate() {
        vert_edges[a as usize].push(e as u32);
        vert_edges[b as usize].push(e as u32);
    }
    let vertex_points: Vec<DVec3> = (0..nv)
        .map(|v| {
            let p = cage.positions[v];
            let es = &vert_edges[v];
            if es.is_empty() {
                return p;
            }
            let sharp: Vec<u32> = es.iter().copied().filter(|&e| sharpness(e as usize) > 0.0).collect();
            let n = es.len() as f64;
            let smooth = || {
                let q =
                    vert_faces[v].iter().map(|&f| face_points[f as usize]).sum::<DVec3>() / vert_faces[v].len() as f64;
                let r = es
                    .iter()
                    .map(|&e| {
                        let (a, b) = edges.ends[e as usize];
                        (cage.positions[a as usize] + cage.positions[b as usize]) * 0.5
                    })
                    .sum::<DVec3>()
                    / n;
                (q + r * 2.0 + p * (n - 3.0)) / n
            };
            // A boundary vertex of a single face is a corner (the "edge and corner"
            // boundary rule: the corners of an open grid stay put).
            let corner =
                if vert_faces[v].len() == 1 { SHARP } else { cage.corners.get(&(v as u32)).copied().unwrap_or(0.0) };
            let moved = match sharp.len() {
                0 | 1 if vert_faces[v].len() == es.len() => smooth(),
                2 => {
                    let other = |e: u32| {
                        let (a, b) = edges.ends[e as usize];
                        cage.positions[if a as usize == v { b } else { a } as usize]
                    };
                    let crease = (p * 6.0 + other(sharp[0]) + other(sharp[1])) / 8.0;
                    let s = 0.5 * (sharpness(sharp[0] as usize).min(1.0) + sharpness(sharp[1] as usize).min(1.0));
                    if s >= 1.0 || vert_faces[v].len() != es.len() {
                        crease
                    } else {
                        smooth().lerp(crease, s)
                    }
                }
                _ => p,
            };
            if corner >= 1.0 {
                p
            } else if corner > 0.0 {
                moved.lerp(p, corner)
            } else {
                moved
            }
        })
        .collect();

    let mut out = Cage::default();
    out.positions.reserve(nv + ne + nf);
    out.positions.extend(vertex_points);
    out.positions.extend(edge_points);
    out.positions.extend(face_points);
    // Texture coordinates: linear.
    for tex in &cage.textures {
        let mut t = Vec::with_capacity(nv + ne + nf);
        t.extend_from_slice(tex);
        t.extend(edges.ends.iter().map(|&(a, b)| (tex[a as usize] + tex[b as usize]) * 0.5));
        t.extend((0..nf).map(|f| avg(cage.face(f), tex)));
        out.textures.push(t);
    }
    let (ev, fv) = (nv as u32, (nv + ne) as u32);
    out.face_starts.reserve(cage.face_verts.len() + 1);
    out.face_verts.reserve(cage.face_verts.len() * 4);
    for f in 0..nf {
        let vs = cage.face(f);
        let k = vs.len();
        for i in 0..k {
            let (prev, cur, next) = (vs[(i + k - 1) % k], vs[i], vs[(i + 1) % k]);
            let quad = [cur, ev + edges.id(cur, next), fv + f as u32, ev + edges.id(prev, cur)];
            out.push_face(&quad, cage.face_slots[f]);
        }
    }
    for (e, &(a, b)) in edges.ends.iter().enumerate() {
        let s = cage.creases.get(&(a, b)).copied().unwrap_or(0.0) - 1.0;
        if s > 0.0 {
            let mid = ev + e as u32;
            out.creases.insert(key(a, mid), s);
            out.creases.insert(key(mid, b), s);
        }
    }
    for (&v, &s) in &cage.corners {
        if s - 1.0 > 0.0 {
            out.corners.insert(v, s - 1.0);
        }
    }
    for (f, mask, offsets) in &cage.details {
        let Some(vs) = (*f as usize).checked_sub(0).filter(|&f| f < nf).map(|f| cage.face(f)) else { continue };
        let k = vs.len();
        let mut offsets = offsets.iter();
        for bit in 0..(2 * k + 1).min(32) {
            if mask & (1 << bit) == 0 {
                continue;
            }
            let Some(offset) = offsets.next() else { break };
            let target = if bit < k {
                vs[bit]
            } else if bit < 2 * k {
                ev + edges.id(vs[bit - k], vs[(bit - k + 1) % k])
            } else {
                fv + f
            };
            out.positions[target as usize] += *offset;
        }
    }
    out
}

/// The cage as a triangle mesh after `levels` levels, vertices on the limit surface with
/// limit normals (for `levels` ≥ 1; level 0 is the cage itself with flat shading). Its
/// triangles carry their cage faces' quad-mesh Ptex faces, numbered from 0
/// ([`crate::mesh::ptex_refined`] for `levels` ≥ 1; level 0 as polygons,
/// [`crate::mesh::ptex_quads`]).
pub fn subdivided_mesh(cage: &Cage, levels: u32, name: &str) -> Mesh {
    let mut c = cage.clone();
    for _ in 0..levels {
        c = subdivide(&c);
    }
    let mut mesh = Mesh::new(name);
    if levels > 0 {
        let (positions, normals) = limit(&c);
        mesh.positions = positions;
        mesh.normals = normals;
    } else {
        mesh.positions = c.positions.iter().map(|p| p.as_vec3()).collect();
    }
    mesh.textures =
        c.textures.iter().map(|t| TexSpace { dim: 3, coords: t.iter().map(|p| p.as_vec3()).collect() }).collect();
    for f in 0..c.face_count() {
        let vs = c.face(f);
        for k in 1..vs.len().saturating_sub(1) {
            mesh.triangles.push([vs[0], vs[k], vs[k + 1]]);
            mesh.triangle_slots.push(c.face_slots[f]);
        }
    }
    if levels == 0 {
        cage_ptex_faces(&c, &mut mesh);
    } else {
        let degrees: Vec<u32> = (0..cage.face_count()).map(|f| cage.face(f).len() as u32).collect();
        // All quads after a level: two triangles each, in the order the table numbers them.
        if let Some((codes, faces)) = mesh.ptex_refined.push_surface(&degrees, levels, 0) {
            if codes.len() == mesh.triangles.len() {
                mesh.ptex_quads = codes;
                mesh.ptex_faces = faces;
            } else {
                mesh.ptex_refined = Default::default();
            }
        }
    }
    mesh
}

/// The quad-mesh Ptex faces of an unrefined cage's fanned triangles, as polygons number
/// them ([`crate::mesh::ptex_quads`]): a quad one face, a triangle its 3 sub-quads from its
/// barycentrics, a larger n-gon its sub-quads found on its outline (none beyond
/// [`MAX_NGON_VERTICES`](crate::mesh::ptex_quads::MAX_NGON_VERTICES) vertices).
fn cage_ptex_faces(c: &Cage, mesh: &mut Mesh) {
    use crate::mesh::ptex_quads;
    let mut face = 0u32;
    let mut at = 0;
    for f in 0..c.face_count() {
        let vs = c.face(f);
        let count = vs.len().saturating_sub(2);
        let triangles = &mesh.triangles[at..at + count];
        at += count;
        match vs.len() {
            4 => {
                let quad = [vs[0], vs[1], vs[2], vs[3]];
                let codes: Vec<u32> = ptex_quads::quad_triangles(face, quad, triangles).collect();
                mesh.ptex_quads.extend(codes);
            }
            3 => mesh.ptex_quads.push(ptex_quads::encode_triangle(face)),
            n => {
                let fits = n <= ptex_quads::MAX_NGON_VERTICES && face <= ptex_quads::MAX_NGON_FACE;
                mesh.ptex_quads.extend(std::iter::repeat_n(
                    if fits { ptex_quads::encode_ngon(face) } else { ptex_quads::NONE },
                    count,
                ));
                if fits {
                    mesh.ptex_ngons.push(face, vs, false);
                }
            }
        }
        face = face.saturating_add(if vs.len() == 4 { 1 } else { vs.len() as u32 });
    }
    mesh.ptex_faces = face;
}

/// Limit positions and normals of every vertex of a (once or more subdivided, all-quad) cage.
pub fn limit(cage: &Cage) -> (Vec<Vec3>, Vec<Vec3>) {
    let nv = cage.positions.len();
    let edges = Edges::new(cage);
    // For each vertex: its corners (face, position of the vertex in the face).
    let mut corners: Vec<Vec<(u32, u8)>> = vec![Vec::new(); nv];
    for f in 0..cage.face_count() {
        for (i, &v) in cage.face(f).iter().enumerate() {
            corners[v as usize].push((f as u32, i as u8));
        }
    }
    let face_normal = |f: usize| {
        let vs = cage.face(f);
        let mut n = DVec3::ZERO;
        for i in 0..vs.len() {
            let (a, b) = (cage.positions[vs[i] as usize], cage.positions[vs[(i + 1) % vs.len()] as usize]);
            n += a.cross(b);
        }
        n * 0.5
    };
    let mut positions = Vec::with_capacity(nv);
    let mut normals = Vec::with_capacity(nv);
    for (v, around) in corners.iter().enumerate() {
        let p = cage.positions[v];
        let area_normal: DVec3 = around.iter().map(|&(f, _)| face_normal(f as usize)).sum();
        let sharp: Vec<u32> = {
            let mut s = Vec::new();
            for &(f, i) in around {
                let vs = cage.face(f as usize);
                let next = vs[(i as usize + 1) % vs.len()];
                let e = edges.id(v as u32, next) as usize;
                let sh = if edges.face_count[e] != 2 {
                    SHARP
                } else {
                    cage.creases.get(&edges.ends[e]).copied().unwrap_or(0.0)
                };
                if sh > 0.0 {
                    s.push(next);
                }
                let prev = vs[(i as usize + vs.len() - 1) % vs.len()];
                let e = edges.id(prev, v as u32) as usize;
                // A boundary edge seen from its only face is counted here.
                if edges.face_count[e] == 1 {
                    s.push(prev);
                }
            }
            s.sort_unstable();
            s.dedup();
            s
        };
        let corner = around.len() == 1 || cage.corners.get(&(v as u32)).copied().unwrap_or(0.0) > 0.0;
        let (pos, normal) = match (sharp.len(), corner) {
            (0, false) => smooth_limit(cage, v as u32, around).unwrap_or((p, area_normal)),
            (2, false) => {
                ((cage.positions[sharp[0] as usize] + p * 4.0 + cage.positions[sharp[1] as usize]) / 6.0, area_normal)
            }
            _ => (p, area_normal),
        };
        let normal = if normal.dot(area_normal) < 0.0 { -normal } else { normal };
        positions.push(pos.as_vec3());
        normals.push(normal.normalize_or_zero().as_vec3());
    }
    (positions, normals)
}

/// Limit position and normal of a smooth interior vertex surrounded by quads, from its
/// ordered one-ring; `None` if the ring is not a closed fan of quads.
fn smooth_limit(cage: &Cage, v: u32, corners: &[(u32, u8)]) -> Option<(DVec3, DVec3)> {
    let n = corners.len();
    if n < 3 {
        return None;
    }
    let at = |(f, i): (u32, u8), k: usize| {
        let vs = cage.face(f as usize);
        vs[(i as usize + k) % vs.len()]
    };
    if corners.iter().any(|&(f, _)| cage.face(f as usize).len() != 4) {
        return None;
    }
    // Order the faces around the vertex: the next face's "next" is this face's "previous".
    let mut ring = Vec::with_capacity(n);
    let mut cur = corners[0];
    for _ in 0..n {
        ring.push(cur);
        let prev = at(cur, 3);
        cur = *corners.iter().find(|&&c| at(c, 1) == prev)?;
    }
    if cur != corners[0] {
        return None;
    }
    let p = cage.positions[v as usize];
    let e = |j: usize| cage.positions[at(ring[j % n], 1) as usize];
    let f = |j: usize| cage.positions[at(ring[j % n], 2) as usize];
    let nf = n as f64;
    let sum_e: DVec3 = (0..n).map(e).sum();
    let sum_f: DVec3 = (0..n).map(f).sum();
    let pos = (p * nf * nf + sum_e * 4.0 + sum_f) / (nf * (nf + 5.0));
    let tau = std::f64::consts::TAU;
    let a = 1.0 + (tau / nf).cos() + (std::f64::consts::PI / nf).cos() * (2.0 * (9.0 + (tau / nf).cos())).sqrt();
    let (mut t1, mut t2) = (DVec3::ZERO, DVec3::ZERO);
    for j in 0..n {
        let (c0, s0) = ((tau * j as f64 / nf).cos(), (tau * j as f64 / nf).sin());
        let (c1, s1) = ((tau * (j + 1) as f64 / nf).cos(), (tau * (j + 1) as f64 / nf).sin());
        t1 += e(j) * (a * c0) + f(j) * (c0 + c1);
        t2 += e(j) * (a * s0) + f(j) * (s0 + s1);
    }
    Some((pos, t1.cross(t2)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cube of side 2 centred at the origin, faces counter-clockwise seen from outside.
    fn cube() -> Cage {
        let mut c = Cage::default();
        for z in [-1.0, 1.0] {
            for y in [-1.0, 1.0] {
                for x in [-1.0, 1.0] {
                    c.positions.push(DVec3::new(x, y, z));
                }
            }
        }
        for f in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
            c.push_face(&f, 0);
        }
        c
    }

    #[test]
    fn cube_vertex_counts_per_level() {
        let mut c = cube();
        let mut counts = Vec::new();
        for _ in 0..4 {
            c = subdivide(&c);
            counts.push(c.positions.len());
        }
        assert_eq!(counts, vec![26, 98, 386, 1538]);
        assert_eq!(c.face_count(), 6 * 4usize.pow(4));
    }

    #[test]
    fn limit_points_do_not_move_with_more_levels() {
        // The limit point of a vertex is a property of the surface: every level must put
        // the cube's corners (vertices 0..8 at every level) at the same place.
        let reference = limit(&subdivide(&cube())).0;
        let mut c = subdivide(&cube());
        for _ in 2..=4 {
            c = subdivide(&c);
            let l = limit(&c).0;
            for v in 0..8 {
                assert!((l[v] - reference[v]).length() < 1e-6, "corner {v}: {} vs {}", l[v], reference[v]);
            }
        }
        // A smooth cube's limit corner lies inside the cube, on the diagonal.
        let corner = reference[7];
        assert!(corner.x > 0.3 && corner.x < 5.0 / 9.0 && (corner.x - corner.y).abs() < 1e-6, "{corner}");
    }

    #[test]
    fn subdivided_cube_is_watertight_and_faces_outwards() {
        let m = subdivided_mesh(&cube(), 3, "c");
        // Closed mesh: signed volume positive (outward winding) and every edge shared twice.
        let vol: f64 = m
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.positions[i as usize].as_dvec3());
                a.dot(b.cross(c)) / 6.0
            })
            .sum();
        // The limit surface lies well inside the cube (its corners' limit is at 5/9).
        assert!(vol > 2.0 && vol < 4.2, "volume {vol}");
        let mut edges = HashMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                *edges.entry(key(t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        assert!(edges.values().all(|&n| n == 2));
        // Limit normals point away from the centre.
        for (p, n) in m.positions.iter().zip(&m.normals) {
            assert!(p.normalize().dot(*n) > 0.5, "normal {n} at {p}");
        }
    }

    #[test]
    fn fully_creased_cube_stays_a_cube() {
        let mut c = cube();
        for f in 0..6 {
            let vs = c.face(f).to_vec();
            for i in 0..4 {
                c.creases.insert(key(vs[i], vs[(i + 1) % 4]), SHARP);
            }
        }
        let m = subdivided_mesh(&c, 4, "c");
        for p in &m.positions {
            let max = p.abs().max_element();
            assert!((max - 1.0).abs() < 1e-5, "{p} left the cube's surface");
        }
        assert!((m.area() - 24.0).abs() < 1e-3, "area {}", m.area());
    }

    #[test]
    fn flat_grid_stays_flat_with_up_normals() {
        let mut c = Cage::default();
        for y in 0..4 {
            for x in 0..4 {
                c.positions.push(DVec3::new(x as f64, y as f64, 0.0));
            }
        }
        for y in 0..3 {
            for x in 0..3 {
                let a = y * 4 + x;
                c.push_face(&[a, a + 1, a + 5, a + 4], 0);
            }
        }
        let m = subdivided_mesh(&c, 2, "g");
        assert!(m.positions.iter().all(|p| p.z.abs() < 1e-6));
        assert!(m.normals.iter().all(|n| (n.z - 1.0).abs() < 1e-5), "{:?}", m.normals);
        // Open boundary: the corners stay put.
        assert!(m.positions.contains(&Vec3::new(0.0, 0.0, 0.0)));
        assert!(m.positions.contains(&Vec3::new(3.0, 3.0, 0.0)));
    }

    /// The Ptex face and (u, v) of each corner of fine triangle `t` of `m` (exact data, `None`
    /// where it has none).
    fn corner_faces(m: &Mesh, t: usize) -> [(u32, f32, f32); 3] {
        let at = |b: [f32; 3]| {
            crate::mesh::ptex_ngons::hit_face_uv(
                &m.ptex_quads,
                &m.ptex_ngons,
                &m.ptex_refined,
                &m.triangles,
                &m.positions,
                t,
                b,
            )
            .expect("a Ptex face")
        };
        [at([1.0, 0.0, 0.0]), at([0.0, 1.0, 0.0]), at([0.0, 0.0, 1.0])]
    }

    /// A lone unit square (its boundary fixed: every vertex a corner of one face) keeps the
    /// identity parametrisation at every level (Catmull–Clark's linear precision): each fine
    /// triangle's corners carry face 0 and (u, v) = their position (x, y) within 1e-6, so
    /// the refinement's order and the table's agree, at levels 0 to 3; the triangles'
    /// shares of the face sum to 1 (1e-12).
    #[test]
    fn a_refined_square_carries_its_faces_coordinates() {
        let mut c = Cage::default();
        for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
            c.positions.push(DVec3::new(p[0], p[1], 0.0));
        }
        c.push_face(&[0, 1, 2, 3], 0);
        for levels in 0..=3 {
            let m = subdivided_mesh(&c, levels, "s");
            assert_eq!((m.ptex_faces, m.ptex_quads.len()), (1, 2 << (2 * levels)));
            let mut share = 0.0;
            for (t, tri) in m.triangles.iter().enumerate() {
                for (k, (face, u, v)) in corner_faces(&m, t).into_iter().enumerate() {
                    let p = m.positions[tri[k] as usize];
                    assert_eq!(face, 0);
                    assert!((u - p.x).abs() < 1e-6 && (v - p.y).abs() < 1e-6, "level {levels}, {t}: {u} {v} at {p}");
                }
                if levels > 0 {
                    let number = crate::mesh::ptex_quads::refined_number(m.ptex_quads[t]).expect("refined");
                    share += m.ptex_refined.area_share(number).expect("a share");
                }
            }
            assert!(levels == 0 || (share - 1.0).abs() < 1e-12, "level {levels}: {share}");
        }
    }

    /// A lone regular pentagon refined 1 to 3 levels: by its mirror symmetries each
    /// sub-quad's region stays the kite (vertex i, the midpoints of its edges, the centre),
    /// so every fine triangle's centroid lies in the kite of its face (face − first = i,
    /// by angle from the centre, 1e-6 slack), every face is met and each one's triangles'
    /// shares sum to 1 (1e-12).
    #[test]
    fn a_refined_pentagon_carries_its_sub_quads() {
        let mut c = Cage::default();
        let angle = |k: f64| std::f64::consts::TAU * k / 5.0;
        for k in 0..5 {
            c.positions.push(DVec3::new(angle(k as f64).cos(), angle(k as f64).sin(), 0.0));
        }
        c.push_face(&[0, 1, 2, 3, 4], 0);
        for levels in 1..=3 {
            let m = subdivided_mesh(&c, levels, "p");
            assert_eq!(m.ptex_faces, 5);
            let mut shares = [0.0; 5];
            for (t, tri) in m.triangles.iter().enumerate() {
                let faces = corner_faces(&m, t);
                let face = faces[0].0 as usize;
                assert!(face < 5 && faces.iter().all(|f| f.0 as usize == face), "{t}: {faces:?}");
                let centroid = tri.iter().map(|&v| m.positions[v as usize].as_dvec3()).sum::<DVec3>() / 3.0;
                // Kite i spans the angles between the spokes to the midpoints of edges
                // i − 1 → i and i → i + 1: angle(i) ± π/5.
                let off = centroid.y.atan2(centroid.x) - angle(face as f64);
                let off = (off + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
                assert!(off.abs() <= std::f64::consts::PI / 5.0 + 1e-6, "level {levels}, {t}: face {face}, {off}");
                let number = crate::mesh::ptex_quads::refined_number(m.ptex_quads[t]).expect("refined");
                shares[face] += m.ptex_refined.area_share(number).expect("a share");
            }
            assert!(shares.iter().all(|s| (s - 1.0).abs() < 1e-12), "level {levels}: {shares:?}");
        }
    }

    #[test]
    fn semi_sharp_crease_lies_between_smooth_and_sharp() {
        let height = |s: f64| {
            let mut c = cube();
            // Crease the four edges of the top face (z = 1).
            for (a, b) in [(4, 5), (5, 7), (7, 6), (6, 4)] {
                if s > 0.0 {
                    c.creases.insert(key(a, b), s);
                }
            }
            let m = subdivided_mesh(&c, 3, "c");
            m.positions.iter().map(|p| p.z).fold(f32::MIN, f32::max)
        };
        let (smooth, half, sharp) = (height(0.0), height(0.5), height(SHARP));
        assert!(smooth < half && half < sharp, "{smooth} {half} {sharp}");
        assert!((sharp - 1.0).abs() < 1e-5);
    }
}
