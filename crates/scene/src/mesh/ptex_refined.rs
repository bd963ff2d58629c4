//! Quad-mesh Ptex faces of refined subdivision surfaces and ccmeshes ([`Mesh::ptex_refined`]):
//! where a triangle of the refinement lies on its control cage's Ptex faces.
//!
//! Ptex was made for Catmull–Clark surfaces: a cage quad is one Ptex face, a cage n-gon
//! (n ≠ 4) n faces (one per corner: its level-1 sub-quads), numbered as
//! [`super::ptex_quads`] numbers polygons (cage faces in order, a quad one id, any other
//! face one per vertex). One level of [`subdivide`](crate::tessellate::subdiv::subdivide)
//! replaces face f of n vertices by n quads, quad i = (vertex i, the point of edge
//! i → i+1, the face point, the point of edge i−1 → i), the faces' children one after
//! another in face order; every fine quad of level L ≥ 1 therefore lies inside one level-1
//! quad, and its corners' face coordinates are dyadic fractions the refinement's path
//! gives: a level-1 quad i of a cage quad has its corners at (u, v) = corner i, the
//! midpoint of corners i, i+1, the centre (½, ½), the midpoint of corners i−1, i (Ptex's
//! quad convention: corner k at [`CORNER_UV`]`[k]`); a level-1 quad of an n-gon is its own
//! face, corners at (0, 0), (1, 0), (1, 1), (0, 1); each further level's child j of a quad
//! of corners c₀…c₃ has the corners cⱼ, (cⱼ + cⱼ₊₁)/2, the quad's centre, (cⱼ₋₁ + cⱼ)/2.
//! Fine quad q of a surface refined L levels is child path q mod 4^(L−1) (base-4 digits,
//! the coarsest first) of level-1 quad ⌊q / 4^(L−1)⌋; it is cut into the triangles
//! (c₀, c₁, c₂), number 2q, and (c₀, c₂, c₃), number 2q + 1.
//!
//! So nothing is kept per triangle but its packed value ([`ptex_quads::encode_refined`]:
//! its number among the mesh's refined triangles) and, per surface, 16 bytes and 8 per
//! cage face ([`Refined::memory_bytes`]).
//!
//! [`Mesh::ptex_refined`]: super::Mesh::ptex_refined
//! [`CORNER_UV`]: super::ptex_quads::CORNER_UV

use super::ptex_quads::{self, CORNER_UV};

/// One refined surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// The refined number of its first triangle (its triangles' numbers follow).
    pub first_triangle: u32,
    /// Its subdivision levels (≥ 1).
    pub levels: u32,
    /// Its first cage face in [`Refined::faces`].
    pub first_cage_face: u32,
    /// The Ptex face id of its first cage face's first face (the mesh's faces before it
    /// come first).
    pub first_face: u32,
}

/// One cage face of a refined surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CageFace {
    /// Its first level-1 quad, counted within its surface (its n quads follow).
    pub first_quad: u32,
    /// Its first Ptex face id, counted within its surface.
    pub face: u32,
}

/// The refined surfaces of a mesh, in increasing refined number.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Refined {
    /// Each surface.
    pub surfaces: Vec<Surface>,
    /// Their cage faces one after another, each surface's closed by an end mark (its
    /// level-1 quad count as `first_quad`).
    pub faces: Vec<CageFace>,
    /// How many refined triangles the surfaces number.
    pub triangles: u32,
}

impl Refined {
    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.surfaces.is_empty()
    }

    /// Bytes held.
    pub fn memory_bytes(&self) -> usize {
        self.surfaces.len() * std::mem::size_of::<Surface>() + self.faces.len() * std::mem::size_of::<CageFace>()
    }

    /// Adds a surface refined `levels` (≥ 1) levels from a cage whose faces have the vertex
    /// counts `degrees`, its Ptex faces numbered from `first_face`: returns the packed values
    /// of its triangles in the refinement's order (2 per fine quad) and how many Ptex faces
    /// its cage numbers; `None` (nothing added) where the numbers do not fit the packing.
    pub fn push_surface(&mut self, degrees: &[u32], levels: u32, first_face: u32) -> Option<(Vec<u32>, u32)> {
        if levels == 0 || levels > 16 {
            return None;
        }
        let first_cage_face = u32::try_from(self.faces.len()).ok()?;
        let (mut quads, mut faces) = (0u32, 0u32);
        let mut cage = Vec::with_capacity(degrees.len() + 1);
        for &n in degrees {
            cage.push(CageFace { first_quad: quads, face: faces });
            quads = quads.checked_add(n)?;
            faces = faces.checked_add(if n == 4 { 1 } else { n })?;
        }
        cage.push(CageFace { first_quad: quads, face: faces });
        let triangles = u64::from(quads) << (2 * (levels - 1)) << 1;
        let end = u64::from(self.triangles) + triangles;
        if end > u64::from(ptex_quads::MAX_REFINED) + 1 {
            return None;
        }
        first_face.checked_add(faces)?;
        let first_triangle = self.triangles;
        self.surfaces.push(Surface { first_triangle, levels, first_cage_face, first_face });
        self.faces.extend(cage);
        self.triangles = end as u32;
        Some(((first_triangle..end as u32).map(ptex_quads::encode_refined).collect(), faces))
    }

    /// Appends `other` (a mesh appended after this one: its Ptex face ids moved on by
    /// `faces`, its refined numbers by this one's count).
    pub fn append(&mut self, other: &Refined, faces: u32) {
        let (triangles, cage) = (self.triangles, self.faces.len() as u32);
        self.surfaces.extend(other.surfaces.iter().map(|s| Surface {
            first_triangle: s.first_triangle + triangles,
            first_cage_face: s.first_cage_face + cage,
            first_face: s.first_face.saturating_add(faces),
            ..*s
        }));
        self.faces.extend_from_slice(&other.faces);
        self.triangles = self.triangles.saturating_add(other.triangles);
    }

    /// The surface, the cage face, its vertex count, which of its level-1 quads, and the
    /// fine quad's child path and whether the triangle is the quad's second of refined
    /// triangle `number`.
    fn place(&self, number: u32) -> Option<(Surface, CageFace, u32, u32, u64, bool)> {
        let at = self.surfaces.partition_point(|s| s.first_triangle <= number).checked_sub(1)?;
        let s = self.surfaces[at];
        let local = u64::from(number - s.first_triangle);
        let (quad, second) = (local >> 1, local & 1 == 1);
        let shift = 2 * (s.levels - 1);
        let (level1, path) = (quad >> shift, quad & ((1u64 << shift) - 1));
        let level1 = u32::try_from(level1).ok()?;
        let start = s.first_cage_face as usize;
        // The surface's cage faces and its end mark.
        let end = self.surfaces.get(at + 1).map_or(self.faces.len(), |o| o.first_cage_face as usize);
        let faces = self.faces.get(start..end)?;
        let k = faces.partition_point(|f| f.first_quad <= level1).checked_sub(1)?;
        let (face, next) = (*faces.get(k)?, *faces.get(k + 1)?);
        let n = next.first_quad - face.first_quad;
        Some((s, face, n, level1 - face.first_quad, path, second))
    }

    /// The Ptex face id and the face coordinates (u, v) of a hit at barycentrics `bary`
    /// (weights of the triangle's vertices 0, 1, 2) on refined triangle `number`.
    pub fn face_uv(&self, number: u32, bary: [f32; 3]) -> Option<(u32, f32, f32)> {
        let (s, face, n, i, path, second) = self.place(number)?;
        let (id, mut quad) = level1_quad(n, i);
        for level in (0..s.levels - 1).rev() {
            quad = child(quad, (path >> (2 * level) & 3) as usize);
        }
        let corners = if second { [quad[0], quad[2], quad[3]] } else { [quad[0], quad[1], quad[2]] };
        let (mut u, mut v) = (0.0f64, 0.0f64);
        for (c, b) in corners.iter().zip(bary) {
            u += c[0] * f64::from(b);
            v += c[1] * f64::from(b);
        }
        let id = s.first_face.checked_add(face.face)?.checked_add(id)?;
        Some((id, u.clamp(0.0, 1.0) as f32, v.clamp(0.0, 1.0) as f32))
    }

    /// The share of its Ptex face's (u, v) square that refined triangle `number` covers:
    /// half a fine quad, 4^−L / 2 on a cage quad refined L levels, 4^−(L−1) / 2 on an
    /// n-gon's sub-quad. A fine triangle's area over it is its face's area (for the filter
    /// width in face units).
    pub fn area_share(&self, number: u32) -> Option<f64> {
        let (s, _, n, ..) = self.place(number)?;
        let quarterings = if n == 4 { s.levels } else { s.levels - 1 };
        Some(0.5 * 0.25f64.powi(quarterings as i32))
    }
}

/// The Ptex face id (within its cage face's ids) and the (u, v) corners of level-1 quad `i`
/// of a cage face of `n` vertices.
fn level1_quad(n: u32, i: u32) -> (u32, [[f64; 2]; 4]) {
    let c = CORNER_UV.map(|[u, v]| [f64::from(u), f64::from(v)]);
    if n != 4 {
        return (i, c);
    }
    let i = i as usize;
    let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5];
    (0, [c[i], mid(c[i], c[(i + 1) % 4]), [0.5, 0.5], mid(c[(i + 3) % 4], c[i])])
}

/// Child `j` (0…3) of a quad of (u, v) corners `q`, as one level of refinement makes it.
fn child(q: [[f64; 2]; 4], j: usize) -> [[f64; 2]; 4] {
    let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5];
    let centre = mid(mid(q[0], q[1]), mid(q[2], q[3]));
    [q[j], mid(q[j], q[(j + 1) % 4]), centre, mid(q[(j + 3) % 4], q[j])]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quad and a pentagon refined 2 levels: 4 · 4 + 5 · 4 fine quads, 72 triangles;
    /// the quad's 16 fine quads tile its face's square (each a 1/4 × 1/4 square, all
    /// different, exact), the pentagon's sub-quads (faces 1…5) each by 4 of ½ × ½; a
    /// vertex's (u, v) is a corner of its fine quad's square; shares exact.
    #[test]
    fn fine_quads_tile_their_faces() {
        let mut r = Refined::default();
        let (codes, faces) = r.push_surface(&[4, 5], 2, 10).expect("fits");
        assert_eq!((codes.len(), faces), (72, 6));
        let mut squares = std::collections::HashSet::new();
        for (t, &code) in codes.iter().enumerate() {
            let number = ptex_quads::refined_number(code).expect("a refined value");
            assert_eq!(number, t as u32);
            let corners: Vec<(u32, f32, f32)> = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
                .iter()
                .map(|b| r.face_uv(number, *b).expect("a face"))
                .collect();
            let face = corners[0].0;
            assert!(corners.iter().all(|c| c.0 == face));
            let side = if t < 32 { 0.25 } else { 0.5 };
            assert_eq!(face, if t < 32 { 10 } else { 11 + ((t as u32 - 32) / 8) });
            let (lo_u, lo_v) = corners.iter().fold((1.0f32, 1.0f32), |a, c| (a.0.min(c.1), a.1.min(c.2)));
            for c in &corners {
                assert!(c.1 == lo_u || c.1 == lo_u + side, "{t}: {corners:?}");
                assert!(c.2 == lo_v || c.2 == lo_v + side, "{t}: {corners:?}");
            }
            squares.insert((face, (lo_u / side) as u32, (lo_v / side) as u32));
            assert_eq!(r.area_share(number), Some(0.5 * f64::from(side * side)));
        }
        assert_eq!(squares.len(), 16 + 5 * 4);
        assert_eq!(r.face_uv(72, [1.0, 0.0, 0.0]), None);
    }

    /// A second surface appended after another mesh numbers on: its triangles' numbers and
    /// faces move on, the first's stay (exact).
    #[test]
    fn appended_surfaces_number_on() {
        let mut a = Refined::default();
        a.push_surface(&[4], 1, 0).unwrap();
        let mut b = Refined::default();
        b.push_surface(&[3], 1, 0).unwrap();
        a.append(&b, 7);
        assert_eq!(a.triangles, 8 + 6);
        assert_eq!(a.face_uv(0, [1.0, 0.0, 0.0]), Some((0, 0.0, 0.0)));
        // The triangle's first quad, vertex 0 at its corner 0; the appended one's quads
        // are faces 7, 8, 9.
        assert_eq!(a.face_uv(8, [1.0, 0.0, 0.0]), Some((7, 0.0, 0.0)));
        assert_eq!(a.face_uv(8 + 5, [0.0, 1.0, 0.0]), Some((9, 1.0, 1.0)));
    }
}
