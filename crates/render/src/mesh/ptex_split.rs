//! Quad-mesh Ptex faces of a mesh made by splitting another's triangles: each fine
//! triangle keeps its original triangle's Ptex face and its place on it. Split evenly
//! (uniform displacement, [`crate::displace::subdivide`]), the original and the place are
//! found from the fine triangle's index alone (no bytes per fine triangle); split unevenly
//! (adaptive displacement, [`crate::displace::adaptive`]), each fine triangle carries them
//! ([`FineOrigin`], 28 bytes a fine triangle, kept only in scenes that read a quad-mesh
//! Ptex file).
//!
//! Triangle t of the original split n × n gives fine triangles t·n² … t·n² + n² − 1, row
//! by row: row j (j = 0 … n − 1) holds 2(n − j) − 1 of them, starting at j(2n − j); in a
//! row, triangle 2i has the grid corners (i, j), (i + 1, j), (i, j + 1) and triangle
//! 2i + 1 the corners (i + 1, j), (i + 1, j + 1), (i, j + 1), grid point (i, j) lying at
//! the original's barycentrics ((n − i − j)/n, i/n, j/n). A hit's barycentrics on the
//! fine triangle, mixed over its corners, are the hit's on the original, where the
//! original's table ([`scene::mesh::ptex_ngons::hit_face_uv`]) gives the face and (u, v):
//! unchanged by the displacement, which moves the vertices but not their place on the
//! faces.

use glam::Vec3;

/// Where a fine triangle of an unevenly split mesh lies on the original's triangles: the
/// original triangle, and its corners' barycentrics (b1, b2) on it (b0 = 1 − b1 − b2;
/// midpoints of midpoints, exact in `f32` to far past the deepest level). 28 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FineOrigin {
    /// The original triangle's index.
    pub triangle: u32,
    /// Each corner's barycentrics (b1, b2) on the original triangle.
    pub corners: [[f32; 2]; 3],
}

impl FineOrigin {
    /// An original triangle `t` itself (its corners at its own corners).
    pub fn whole(t: u32) -> Self {
        FineOrigin { triangle: t, corners: [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] }
    }
}

/// The original mesh's Ptex data and how its triangles were split.
#[derive(Clone, Debug, Default)]
pub struct PtexSplit {
    /// n: each original triangle split n × n (when `fine` is empty).
    pub n: u32,
    /// Per fine triangle, where it lies on the originals (uneven splits); empty for even
    /// splits, whose places follow from `n`.
    pub fine: Vec<FineOrigin>,
    /// The original's packed values ([`scene::mesh::ptex_quads`]).
    pub codes: Vec<u32>,
    /// The original's prepared n-gons.
    pub ngons: scene::mesh::ptex_ngons::Ngons,
    /// The original's refined surfaces.
    pub refined: scene::mesh::ptex_refined::Refined,
    /// The original's triangles.
    pub triangles: Vec<[u32; 3]>,
    /// The original's object-space vertices (undisplaced).
    pub positions: Vec<Vec3>,
}

impl PtexSplit {
    /// The original triangle and the barycentrics on it of a hit at barycentrics `bary` on
    /// fine triangle `prim`.
    pub fn original(&self, prim: usize, bary: [f32; 3]) -> Option<(usize, [f32; 3])> {
        if !self.fine.is_empty() {
            let o = self.fine.get(prim)?;
            let mut b = [0.0f64; 3];
            for (c, w) in o.corners.into_iter().zip(bary) {
                let (c1, c2, w) = (f64::from(c[0]), f64::from(c[1]), f64::from(w));
                b[0] += w * (1.0 - c1 - c2);
                b[1] += w * c1;
                b[2] += w * c2;
            }
            return Some((o.triangle as usize, b.map(|x| x as f32)));
        }
        let n = u64::from(self.n.max(1));
        let per = n * n;
        let (t, k) = (prim as u64 / per, prim as u64 % per);
        // The row j: the largest with j(2n − j) ≤ k.
        let start = |j: u64| j * (2 * n - j);
        let mut j = (n as f64 - ((n * n - k) as f64).sqrt()).floor().clamp(0.0, (n - 1) as f64) as u64;
        while j > 0 && start(j) > k {
            j -= 1;
        }
        while j + 1 < n && start(j + 1) <= k {
            j += 1;
        }
        let r = k - start(j);
        let (i, upper) = (r / 2, r % 2 == 1);
        let corners = if upper { [(i + 1, j), (i + 1, j + 1), (i, j + 1)] } else { [(i, j), (i + 1, j), (i, j + 1)] };
        let nf = n as f64;
        let mut b = [0.0f64; 3];
        for ((ci, cj), w) in corners.into_iter().zip(bary) {
            let (ci, cj, w) = (ci as f64, cj as f64, f64::from(w));
            b[0] += w * (nf - ci - cj) / nf;
            b[1] += w * ci / nf;
            b[2] += w * cj / nf;
        }
        Some((usize::try_from(t).ok()?, b.map(|x| x as f32)))
    }

    /// The share of its original triangle's area that fine triangle `prim` covers, in the
    /// original's barycentric parameters (1/n² for an even split; the corners' barycentric
    /// triangle's area for an uneven one): a fine triangle's world area divided by it is the
    /// original's, which a Ptex filter width in face units needs.
    pub fn area_share(&self, prim: usize) -> f32 {
        if self.fine.is_empty() {
            let n = self.n.max(1) as f32;
            return 1.0 / (n * n);
        }
        self.fine.get(prim).map_or(1.0, |o| {
            let [c0, c1, c2] = o.corners;
            let (e1, e2) = ([c1[0] - c0[0], c1[1] - c0[1]], [c2[0] - c0[0], c2[1] - c0[1]]);
            (e1[0] * e2[1] - e1[1] * e2[0]).abs()
        })
    }

    /// Bytes held: the fine triangles' places and the copies of the original's Ptex
    /// tables, triangles and vertices (each displaced mesh holds its own).
    pub fn memory_bytes(&self) -> usize {
        self.fine.len() * std::mem::size_of::<FineOrigin>()
            + self.codes.len() * 4
            + self.ngons.memory_bytes()
            + self.refined.memory_bytes()
            + self.triangles.len() * 12
            + self.positions.len() * 12
    }

    /// The quad-mesh Ptex face and (u, v) of a hit at barycentrics `bary` on fine triangle
    /// `prim`.
    pub fn face_uv(&self, prim: usize, bary: [f32; 3]) -> Option<(u32, f32, f32)> {
        let (t, b) = self.original(prim, bary)?;
        scene::mesh::ptex_ngons::hit_face_uv(
            &self.codes,
            &self.ngons,
            &self.refined,
            &self.triangles,
            &self.positions,
            t,
            b,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::displace::subdivide::subdivide;
    use crate::mesh::MeshData;
    use glam::Vec3A;

    /// Two triangles split by `subdivide` at n = 1, 3, 4: the centroid of every fine
    /// triangle, mapped back, is that fine triangle's centroid on its original (the
    /// original's barycentrics reproduce the fine centroid's position within 1e-6), and
    /// the originals are found in order.
    #[test]
    fn fine_triangles_map_back_to_their_original() {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::new(0.0, 1.5, 0.0)];
        let triangles = vec![[0, 1, 2], [0, 2, 3]];
        let mesh = MeshData { positions: positions.clone(), triangles: triangles.clone(), ..MeshData::default() };
        for n in [1, 3, 4] {
            let fine = subdivide(&mesh, n).mesh;
            let split =
                PtexSplit { n, triangles: triangles.clone(), positions: positions.clone(), ..PtexSplit::default() };
            for (prim, tri) in fine.triangles.iter().enumerate() {
                let centroid = tri.iter().map(|&v| Vec3A::from(fine.positions[v as usize])).sum::<Vec3A>() / 3.0;
                let (t, b) = split.original(prim, [1.0 / 3.0; 3]).expect("an original");
                assert_eq!(t, prim / (n * n) as usize);
                let back: Vec3A = (0..3).map(|k| Vec3A::from(positions[triangles[t][k] as usize]) * b[k]).sum();
                assert!((back - centroid).length() < 1e-6, "n {n}, fine {prim}: {back} vs {centroid}");
            }
        }
    }

    /// A fine triangle's share of its original's area: 1/n² for an even split (exact), and
    /// for an uneven one its corners' barycentric triangle's area (a quarter of the
    /// original, then a sixteenth, within 1e-7), so the original's area is recovered.
    #[test]
    fn a_fine_triangle_knows_its_share_of_the_original() {
        let even = PtexSplit { n: 3, ..PtexSplit::default() };
        assert_eq!(even.area_share(5), 1.0 / 9.0);
        let quarter = FineOrigin { triangle: 0, corners: [[0.5, 0.0], [0.5, 0.5], [0.0, 0.5]] };
        let sixteenth = FineOrigin { triangle: 1, corners: [[0.0, 0.0], [0.25, 0.0], [0.0, 0.25]] };
        let uneven = PtexSplit { n: 1, fine: vec![FineOrigin::whole(2), quarter, sixteenth], ..PtexSplit::default() };
        for (prim, share) in [(0, 1.0), (1, 0.25), (2, 1.0 / 16.0)] {
            assert!((uneven.area_share(prim) - share).abs() < 1e-7, "{prim}: {}", uneven.area_share(prim));
        }
    }

    /// A split's bytes count the fine triangles' places and its copies of the original's
    /// codes, triangles and vertices (exact).
    #[test]
    fn a_split_counts_the_originals_copies() {
        let split = PtexSplit {
            n: 1,
            fine: vec![FineOrigin::whole(0); 5],
            codes: vec![0; 2],
            triangles: vec![[0, 1, 2]; 2],
            positions: vec![Vec3::ZERO; 4],
            ..PtexSplit::default()
        };
        let empty = PtexSplit::default().memory_bytes();
        assert_eq!(split.memory_bytes() - empty, 5 * std::mem::size_of::<FineOrigin>() + 2 * 4 + 2 * 12 + 4 * 12);
    }
}
