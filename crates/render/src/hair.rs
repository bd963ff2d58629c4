//! Hair as geometry both backends intersect: each hair segment becomes two crossed ribbons
//! (quads through the hair, perpendicular to each other, as wide as the hair), object
//! space.
//!
//! mental ray rendered hair as flat ribbons turned towards each ray; fixed crossed ribbons
//! are the backend-independent approximation (seen along one ribbon, the other still shows
//! at least 0.7 of the width). Cubic hairs (`degree 3`) are followed along their Bézier
//! segments, four straight pieces per segment. Every ribbon vertex carries where it is
//! along the hair (0 root … 1 tip), across the ribbon (0 … 1) and the hair's texture
//! scalars; every triangle the hair's tangent and root tangent, so that hair shaders get
//! mental ray's hair state.

use glam::{Vec3, Vec3A};
use scene::HairGeometry;

use crate::world::MeshData;

/// Per-vertex and per-triangle hair data of a ribbon mesh.
#[derive(Clone, Debug, Default)]
pub struct HairData {
    /// Position along the hair of each vertex (0 at the root, 1 at the tip).
    pub along: Vec<f32>,
    /// Position across the ribbon of each vertex (0 one edge, 1 the other).
    pub across: Vec<f32>,
    /// Per triangle: the segment's unit tangent (root to tip) and the first segment's
    /// (the "scalp normal" mental ray gives hair shaders), object space.
    pub tangents: Vec<[Vec3A; 2]>,
}

/// Pieces each cubic Bézier segment is followed with.
const BEZIER_PIECES: usize = 4;

/// The polyline of hair `h`: points, radii, and parameter along it.
fn polyline(g: &HairGeometry, h: usize) -> (Vec<Vec3>, Vec<f32>) {
    let (a, b) = (g.starts[h] as usize, g.starts[h + 1] as usize);
    let pts = &g.points[a..b];
    let radii = &g.radii[a..b];
    if g.degree != 3 || pts.len() < 4 {
        return (pts.to_vec(), radii.to_vec());
    }
    let mut out = vec![pts[0]];
    let mut out_r = vec![radii[0]];
    let mut i = 0;
    while i + 3 < pts.len() {
        let [p0, p1, p2, p3] = [pts[i], pts[i + 1], pts[i + 2], pts[i + 3]];
        for k in 1..=BEZIER_PIECES {
            let t = k as f32 / BEZIER_PIECES as f32;
            let s = 1.0 - t;
            out.push(p0 * (s * s * s) + p1 * (3.0 * s * s * t) + p2 * (3.0 * s * t * t) + p3 * (t * t * t));
            out_r.push(radii[i] * s + radii[i + 3] * t);
        }
        i += 3;
    }
    (out, out_r)
}

/// The ribbon mesh of an object's hair blocks: material slot k for block k.
pub fn ribbons(blocks: &[HairGeometry]) -> Option<(MeshData, HairData)> {
    let mut mesh = MeshData::default();
    let mut hair = HairData::default();
    // Texture spaces: the hair's scalars (per hair, then per vertex) three to a space.
    let spaces = blocks
        .iter()
        .map(|g| {
            let hairs = g.len().max(1);
            let per_hair = g.hair_scalars.len() / hairs;
            let per_vertex = if g.points.is_empty() { 0 } else { g.vertex_scalars.len() / g.points.len() };
            (per_hair + per_vertex).div_ceil(3)
        })
        .max()
        .unwrap_or(0);
    mesh.textures = vec![Vec::new(); spaces];
    for (slot, g) in blocks.iter().enumerate() {
        let hairs = g.len();
        let per_hair = g.hair_scalars.len().checked_div(hairs).unwrap_or(0);
        let per_vertex = if g.points.is_empty() { 0 } else { g.vertex_scalars.len() / g.points.len() };
        for h in 0..hairs {
            let (pts, radii) = polyline(g, h);
            if pts.len() < 2 {
                continue;
            }
            let lengths: Vec<f32> = pts.windows(2).map(|w| (w[1] - w[0]).length()).collect();
            let total: f32 = lengths.iter().sum::<f32>().max(f32::MIN_POSITIVE);
            let root = Vec3A::from(pts[1] - pts[0]).normalize_or(Vec3A::Y);
            let scalars: Vec<f32> = g.hair_scalars[h * per_hair..(h + 1) * per_hair]
                .iter()
                .copied()
                .chain(
                    g.vertex_scalars
                        .get(g.starts[h] as usize * per_vertex..)
                        .into_iter()
                        .flatten()
                        .copied()
                        .take(per_vertex),
                )
                .collect();
            let mut along = 0.0;
            for (k, w) in pts.windows(2).enumerate() {
                let (p0, p1) = (Vec3A::from(w[0]), Vec3A::from(w[1]));
                let t = (p1 - p0).normalize_or(root);
                let frame = shade::Frame::from_normal(t);
                let a0 = along / total;
                along += lengths[k];
                let a1 = along / total;
                for side in [frame.tangent, frame.bitangent] {
                    let base = mesh.positions.len() as u32;
                    let (r0, r1) = (radii[k], radii[k + 1]);
                    mesh.positions.extend([p0 - side * r0, p0 + side * r0, p1 + side * r1, p1 - side * r1]);
                    hair.along.extend([a0, a0, a1, a1]);
                    hair.across.extend([0.0, 1.0, 1.0, 0.0]);
                    for (s, space) in mesh.textures.iter_mut().enumerate() {
                        let c = |i: usize| scalars.get(3 * s + i).copied().unwrap_or(0.0);
                        space.extend([Vec3A::new(c(0), c(1), c(2)); 4]);
                    }
                    mesh.triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
                    mesh.slots.extend([slot as u32; 2]);
                    hair.tangents.extend([[t, root]; 2]);
                }
            }
        }
    }
    (!mesh.triangles.is_empty()).then_some((mesh, hair))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one_hair(degree: u8, points: Vec<Vec3>) -> HairGeometry {
        let n = points.len();
        HairGeometry {
            name: "h".into(),
            degree,
            radii: vec![0.1; n],
            points,
            starts: vec![0, n as u32],
            hair_scalars: vec![0.25, 0.75],
            ..HairGeometry::default()
        }
    }

    #[test]
    fn a_straight_hair_becomes_two_crossed_ribbons_of_its_width() {
        let (mesh, hair) = ribbons(&[one_hair(1, vec![Vec3::ZERO, Vec3::Y, Vec3::Y * 2.0])]).unwrap();
        assert_eq!(mesh.triangles.len(), 2 * 2 * 2);
        assert_eq!(hair.along[0], 0.0);
        assert_eq!(*hair.along.last().unwrap(), 1.0);
        for (i, p) in mesh.positions.iter().enumerate() {
            let radial = Vec3A::new(p.x, 0.0, p.z).length();
            assert!((radial - 0.1).abs() < 1e-6, "vertex {i} at {p}");
        }
        assert!(hair.tangents.iter().all(|[t, r]| (*t - Vec3A::Y).length() < 1e-6 && *r == *t));
        // The hair's texture scalars reach texture space 0.
        assert_eq!(mesh.textures[0][0], Vec3A::new(0.25, 0.75, 0.0));
    }

    #[test]
    fn cubic_hairs_follow_the_bezier_curve() {
        let ctrl = vec![Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 2.0, 0.0), Vec3::new(2.0, 2.0, 0.0)];
        let (pts, _) = polyline(&one_hair(3, ctrl.clone()), 0);
        assert_eq!(pts.len(), 1 + BEZIER_PIECES);
        assert_eq!(pts[0], ctrl[0]);
        assert!((pts[BEZIER_PIECES] - ctrl[3]).length() < 1e-6);
        // The middle of a cubic Bézier: (P0 + 3P1 + 3P2 + P3)/8.
        let mid = (ctrl[0] + ctrl[1] * 3.0 + ctrl[2] * 3.0 + ctrl[3]) / 8.0;
        assert!((pts[BEZIER_PIECES / 2] - mid).length() < 1e-6);
    }
}
