//! Hair as geometry both backends intersect: each hair segment becomes flat ribbons (quads
//! through the hair, as wide as the hair), object space.
//!
//! mental ray rendered hair as flat ribbons turned towards each ray. mira builds two kinds
//! of ribbon mesh, each seen by different rays (see `World::from_scene`):
//!
//! - [`Facing::Point`] / [`Facing::Direction`]: one ribbon per segment, turned at build time
//!   towards the camera (at every hair vertex, perpendicular to the hair and to the line of
//!   sight), seen by eye and transparency rays only. Eye rays thus meet exactly mental
//!   ray's ray-facing ribbon, with the hair's full width from every viewing direction, in
//!   both acceleration backends, without a custom primitive (which Embree's and mira's
//!   BVH would each need: an analytic ribbon or cylinder intersector per backend).
//! - [`Facing::Crossed`]: two fixed ribbons per segment, perpendicular to each other, seen
//!   by shadow, reflection, refraction and final gather rays, which come from everywhere
//!   (a camera-facing ribbon is edge-on to a light at right angles to the view and would
//!   cast almost no shadow; seen along one crossed ribbon, the other still shows at least
//!   0.7 of the width).
//!
//! Cubic hairs (`degree 3`) are followed along their Bézier segments, four straight pieces
//! per segment. Every ribbon vertex carries where it is along the hair (0 root … 1 tip),
//! across the ribbon (0 … 1) and the hair's texture scalars; every triangle the hair's
//! tangent and root tangent, so that hair shaders get mental ray's hair state.

use glam::{Vec3, Vec3A};
use scene::HairGeometry;

use crate::mesh::{HairData, MeshData};

/// How ribbons are turned.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Facing {
    /// Two fixed ribbons per segment, perpendicular to each other.
    Crossed,
    /// One ribbon per segment facing this point (object space: a perspective camera).
    Point(Vec3A),
    /// One ribbon per segment perpendicular to this direction (object space, towards the
    /// viewer: an orthographic camera).
    Direction(Vec3A),
}

impl Facing {
    /// The unit vector across the ribbon at point `p` of a hair with unit tangent `t`:
    /// perpendicular to `t` and to the line of sight (`fallback` where they are parallel).
    fn side(self, p: Vec3A, t: Vec3A, fallback: Vec3A) -> Vec3A {
        let view = match self {
            Facing::Point(eye) => eye - p,
            Facing::Direction(d) => d,
            Facing::Crossed => return fallback,
        };
        t.cross(view).try_normalize().unwrap_or(fallback)
    }
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

/// The ribbon mesh of an object's hair blocks, turned as `facing` says: material slot k for
/// block k.
pub fn ribbons(blocks: &[HairGeometry], facing: Facing) -> Option<(MeshData, HairData)> {
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
            let segs: Vec<Vec3A> = pts.windows(2).map(|w| Vec3A::from(w[1] - w[0]).normalize_or(root)).collect();
            // Facing ribbons turn at each vertex about the mean of its segments' tangents, so
            // that neighbouring quads share their edges.
            let sides: Vec<Vec3A> = (0..pts.len())
                .map(|i| {
                    let t = (segs[i.min(segs.len() - 1)] + segs[i.saturating_sub(1)])
                        .normalize_or(segs[i.min(segs.len() - 1)]);
                    facing.side(Vec3A::from(pts[i]), t, bsdf::Frame::from_normal(t).tangent)
                })
                .collect();
            let mut along = 0.0;
            for (k, w) in pts.windows(2).enumerate() {
                let (p0, p1) = (Vec3A::from(w[0]), Vec3A::from(w[1]));
                let t = segs[k];
                let frame = bsdf::Frame::from_normal(t);
                let a0 = along / total;
                along += lengths[k];
                let a1 = along / total;
                let pairs = match facing {
                    Facing::Crossed => vec![(frame.tangent, frame.tangent), (frame.bitangent, frame.bitangent)],
                    _ => vec![(sides[k], sides[k + 1])],
                };
                for (s0, s1) in pairs {
                    let base = mesh.positions.len() as u32;
                    let (r0, r1) = (radii[k], radii[k + 1]);
                    mesh.positions.extend([p0 - s0 * r0, p0 + s0 * r0, p1 + s1 * r1, p1 - s1 * r1].map(Vec3::from));
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
        let (mesh, hair) = ribbons(&[one_hair(1, vec![Vec3::ZERO, Vec3::Y, Vec3::Y * 2.0])], Facing::Crossed).unwrap();
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

    /// The width of `mesh` seen along unit `view` across unit `hair_dir` (its extent along
    /// the axis perpendicular to both).
    fn projected_width(mesh: &MeshData, view: Vec3A, hair_dir: Vec3A) -> f32 {
        let across = view.cross(hair_dir).normalize();
        let (lo, hi) = mesh
            .positions
            .iter()
            .map(|&p| Vec3A::from(p).dot(across))
            .fold((f32::MAX, f32::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)));
        hi - lo
    }

    #[test]
    fn ribbons_facing_the_camera_keep_the_hair_width_from_every_direction() {
        // A straight hair of radius 0.1 along y (width 0.2), seen from around it.
        let hair = one_hair(1, vec![Vec3::ZERO, Vec3::Y, Vec3::Y * 2.0]);
        let mut crossed_min = f32::MAX;
        for deg in [0.0f32, 20.0, 45.0, 70.0, 90.0, 135.0] {
            let (s, c) = deg.to_radians().sin_cos();
            let towards_eye = Vec3A::new(s, 0.3, c).normalize();
            for facing in [Facing::Point(Vec3A::Y + towards_eye * 10.0), Facing::Direction(towards_eye)] {
                let (mesh, hair_data) = ribbons(std::slice::from_ref(&hair), facing).unwrap();
                assert_eq!(mesh.triangles.len(), 2 * 2, "one ribbon per segment");
                let w = projected_width(&mesh, towards_eye, Vec3A::Y);
                assert!((w - 0.2).abs() < 0.2 * 0.01, "{deg}°: width {w}");
                assert_eq!(hair_data.tangents.len(), mesh.triangles.len());
            }
            let (crossed, _) = ribbons(std::slice::from_ref(&hair), Facing::Crossed).unwrap();
            crossed_min = crossed_min.min(projected_width(&crossed, towards_eye, Vec3A::Y));
        }
        // Fixed crossed ribbons narrow to about 1/√2 of the width between their planes.
        assert!(crossed_min < 0.2 * 0.75, "{crossed_min}");
    }

    #[test]
    fn facing_ribbons_of_a_bent_hair_share_their_edges() {
        let hair = one_hair(1, vec![Vec3::ZERO, Vec3::Y, Vec3::new(1.0, 2.0, 0.0)]);
        let (mesh, _) = ribbons(&[hair], Facing::Point(Vec3A::new(0.0, 1.0, 10.0))).unwrap();
        // Quad k is positions 4k … 4k + 3; the end edge of quad 0 is the start edge of quad 1.
        assert!((mesh.positions[2] - mesh.positions[5]).length() < 1e-6);
        assert!((mesh.positions[3] - mesh.positions[4]).length() < 1e-6);
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
