//! Adaptive subdivision of a displaced mesh under a [`Criteria`] plan: level by level,
//! every edge of the displaced triangles whose criteria fail is split at its middle, and
//! each triangle is split by the edges of it that were split (one → two triangles, two →
//! three, three → four). Each edge is decided once for the whole mesh (by its two
//! vertices' displaced positions and the two triangles beside it), so the triangles that
//! share an edge agree on it and share its middle vertex: no cracks, no T-junctions. The
//! new vertices' undisplaced attributes (position, normal, texture coordinates, user
//! vectors, bump basis) are the means of their edge's ends; the displacement is evaluated
//! at each new vertex (in parallel; the result is the same at any thread count). Levels
//! below the plan's least split every edge; refinement ends where no edge fails, at the
//! greatest level, or before the level that would pass the plan's `max` triangles.

use std::collections::HashMap;

use glam::{Affine3A, Vec3, Vec3A};
use rayon::prelude::*;

use super::plan::{Criteria, MAX_LEVEL};
use super::subdivide::vertex_normals;
use crate::camera::CameraModel;
use crate::mesh::ptex_split::FineOrigin;
use crate::mesh::MeshData;

/// How `view` criteria measure: the camera, and where the instance and the camera stand
/// at the times the measure is taken.
///
/// A still instance under a still camera is measured where it stands. One that moves
/// while the shutter is open (instance `motion transform`, or a moving camera) is
/// measured at each of the times its keys and the camera's lie at over the shutter
/// (opening, close and the keys between), and an edge is as long as its longest there:
/// the criteria then hold at every time the shutter sees (mental ray's motion time 0
/// may lie before the shutter opens, and an instance coming towards the camera is
/// larger at the close). Between two keys a point moves linearly, so an edge's world
/// length is convex in time and its depth linear: their ratio is quasi-convex, its
/// largest value on the interval at one of its ends; the keys give the exact largest
/// on-screen size (while the edge stays in front of the camera, and for a still camera:
/// a moving camera's depth is taken at the same key times).
pub struct View<'a> {
    /// The camera the image is rendered from.
    pub camera: &'a CameraModel,
    /// (object → world, world → camera) at each time the measure is taken.
    pub poses: Vec<(Affine3A, Affine3A)>,
}

impl<'a> View<'a> {
    /// The measure of `inst` seen by `camera`: where both stand at every key time over
    /// the shutter (the union of the instance's and the camera's key times), or where they
    /// stand when neither moves.
    pub fn over_shutter(inst: &crate::world::InstanceData, camera: &'a CameraModel) -> View<'a> {
        let times = |n: usize| (0..n).map(move |j| if n == 1 { 0.0 } else { j as f32 / (n - 1) as f32 });
        let mut at: Vec<f32> = times(inst.keys.len()).chain(times(camera.keys.len())).collect();
        at.sort_by(f32::total_cmp);
        at.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
        let poses = if at.is_empty() {
            vec![(inst.object_to_world, camera.world_to_camera)]
        } else {
            at.iter()
                .map(|&t| {
                    let to_camera = if camera.keys.is_empty() {
                        camera.world_to_camera
                    } else {
                        camera.camera_to_world_at(t).inverse()
                    };
                    (inst.object_to_world_at(t), to_camera)
                })
                .collect()
        };
        View { camera, poses }
    }

    /// Raster length, in pixel diagonals, of the object-space vector `d` seen at the
    /// object-space point `at` as if parallel to the image plane (mental ray's measure of
    /// view-dependent approximations): world length × focal·width/aperture ÷ depth
    /// (orthographic cameras: no division by depth), the depth at least the near clip
    /// distance and 1e-4; the largest over the poses.
    fn pixels(&self, d: Vec3A, at: Vec3A) -> f32 {
        let c = self.camera;
        let per_unit = c.width.max(1) as f32 / c.aperture.max(f32::MIN_POSITIVE);
        let mut most = 0.0f32;
        for (object_to_world, world_to_camera) in &self.poses {
            let world = object_to_world.transform_vector3a(d).length();
            let pixels = if c.orthographic {
                world * per_unit
            } else {
                let depth = -world_to_camera.transform_point3a(object_to_world.transform_point3a(at)).z;
                world * per_unit * c.focal / depth.abs().max(c.clip.0).max(1e-4)
            };
            most = most.max(pixels);
        }
        most / std::f32::consts::SQRT_2
    }
}

/// The displacement of a vertex: `(mesh, vertex, slot)` → the object-space offset of
/// vertex `vertex` of the undisplaced `mesh`, whose triangle of material slot `slot` made it.
pub type Offset<'a> = dyn Fn(&MeshData, usize, u32) -> Vec3 + Sync + 'a;

/// Refines and displaces `mesh` (object space) under `c`: the displaced mesh (normals
/// recomputed) and, where `carry` asks for them (a scene reading a quad-mesh Ptex file),
/// where each fine triangle lies on `mesh`'s triangles (else empty); or `Err(n)` when the
/// next level would make `n` triangles, more than `budget`. `view` is needed by `view`
/// criteria (without it they measure in object space).
pub fn refine(
    mesh: &MeshData,
    c: &Criteria,
    view: Option<&View>,
    budget: usize,
    offset: &Offset,
    carry: bool,
) -> Result<(MeshData, Vec<FineOrigin>), usize> {
    // The levels every edge is split for make 4^min_level triangles of each.
    let forced = mesh.triangles.len() as f64 * 4f64.powi(c.min_level.min(MAX_LEVEL) as i32);
    if forced > budget as f64 {
        return Err(forced.min(usize::MAX as f64) as usize);
    }
    let normals = if mesh.normals.len() == mesh.positions.len() {
        mesh.normals.clone()
    } else {
        vertex_normals(&mesh.positions, &mesh.triangles)
    };
    let bump_basis = if mesh.bump_basis.len() == mesh.positions.len() { mesh.bump_basis.clone() } else { Vec::new() };
    let mut base = MeshData {
        positions: mesh.positions.clone(),
        normals,
        textures: mesh.textures.clone(),
        user: mesh.user.clone(),
        bump_basis,
        ..MeshData::default()
    };
    let mut triangles = mesh.triangles.clone();
    let mut slots = mesh.slots.clone();
    let mut origins: Vec<FineOrigin> =
        if carry { (0..triangles.len() as u32).map(FineOrigin::whole).collect() } else { Vec::new() };
    let slot_of = |slots: &[u32], t: usize| slots.get(t).copied().unwrap_or(0);
    // Each original vertex is displaced by the material of the first triangle using it.
    let mut owner: Vec<Option<u32>> = vec![None; base.positions.len()];
    for (t, tri) in triangles.iter().enumerate() {
        for &v in tri {
            owner[v as usize].get_or_insert(slot_of(&slots, t));
        }
    }
    let mut shifted: Vec<Vec3> = (0..base.positions.len())
        .into_par_iter()
        .map(|v| base.positions[v] + owner[v].map_or(Vec3::ZERO, |s| offset(&base, v, s)))
        .collect();

    for level in 0..c.max_level {
        // The edges, numbered in the order the triangles meet them.
        let mut index: HashMap<(u32, u32), u32> = HashMap::with_capacity(triangles.len() * 2);
        let mut ends: Vec<(u32, u32)> = Vec::with_capacity(triangles.len() * 2);
        let mut sides: Vec<[u32; 2]> = Vec::with_capacity(triangles.len() * 2);
        let mut tri_edges: Vec<[u32; 3]> = Vec::with_capacity(triangles.len());
        for (t, tri) in triangles.iter().enumerate() {
            let mut e3 = [0u32; 3];
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let key = (a.min(b), a.max(b));
                let e = *index.entry(key).or_insert_with(|| {
                    ends.push(key);
                    sides.push([u32::MAX; 2]);
                    (ends.len() - 1) as u32
                });
                let s = &mut sides[e as usize];
                if s[0] == u32::MAX {
                    s[0] = t as u32;
                } else if s[1] == u32::MAX {
                    s[1] = t as u32;
                }
                e3[k] = e;
            }
            tri_edges.push(e3);
        }
        drop(index);
        let split: Vec<bool> = if level < c.min_level {
            vec![true; ends.len()]
        } else {
            let faces: Vec<Vec3A> = triangles
                .par_iter()
                .map(|t| {
                    let [a, b, p] = t.map(|i| Vec3A::from(shifted[i as usize]));
                    (b - a).cross(p - a).normalize_or_zero()
                })
                .collect();
            (0..ends.len())
                .into_par_iter()
                .map(|e| fails(c, view, &base, &shifted, &faces, ends[e], sides[e]))
                .collect()
        };
        if !split.iter().any(|&s| s) {
            break;
        }
        let made: usize = tri_edges.iter().map(|e| 1 + e.iter().filter(|&&e| split[e as usize]).count()).sum::<usize>();
        if c.max_triangles.is_some_and(|cap| made > cap) {
            break;
        }
        if made > budget {
            return Err(made);
        }
        // The middle vertices, made in edge order.
        let first_new = base.positions.len();
        let mut middle = vec![u32::MAX; ends.len()];
        let mut new_slots = Vec::new();
        for (e, &(a, b)) in ends.iter().enumerate() {
            if split[e] {
                middle[e] = base.positions.len() as u32;
                push_middle(&mut base, a as usize, b as usize);
                new_slots.push(slot_of(&slots, sides[e][0] as usize));
            }
        }
        let moved: Vec<Vec3> = (first_new..base.positions.len())
            .into_par_iter()
            .map(|v| base.positions[v] + offset(&base, v, new_slots[v - first_new]))
            .collect();
        shifted.extend(moved);
        // The triangles, each split by its split edges.
        let mut next = Vec::with_capacity(made);
        let mut next_slots = Vec::with_capacity(if slots.is_empty() { 0 } else { made });
        let mut next_origins = Vec::with_capacity(if carry { made } else { 0 });
        for (t, tri) in triangles.iter().enumerate() {
            let m = tri_edges[t].map(|e| middle[e as usize]);
            let first = next.len();
            split_triangle(*tri, m, &shifted, &mut next);
            if !slots.is_empty() {
                next_slots.resize(next.len(), slots[t]);
            }
            if carry {
                let o = origins[t];
                next_origins.extend(next[first..].iter().map(|f| FineOrigin {
                    triangle: o.triangle,
                    corners: f.map(|v| corner_place(*tri, m, &o.corners, v)),
                }));
            }
        }
        triangles = next;
        slots = next_slots;
        origins = next_origins;
    }
    let normals = vertex_normals(&shifted, &triangles);
    Ok((MeshData { positions: shifted, normals, triangles, slots, ..base }, origins))
}

/// The barycentrics (b1, b2) on the original triangle of vertex `v` of a triangle split
/// from `tri` (corners a, b, c at `places` on the original) by the middles `m` of its
/// edges ab, bc, ca: a corner's own place, or the mean of its edge's ends'.
fn corner_place(tri: [u32; 3], m: [u32; 3], places: &[[f32; 2]; 3], v: u32) -> [f32; 2] {
    if let Some(k) = tri.iter().position(|&x| x == v) {
        return places[k];
    }
    match m.iter().position(|&x| x == v) {
        Some(k) => {
            let (p, q) = (places[k], places[(k + 1) % 3]);
            [(p[0] + q[0]) * 0.5, (p[1] + q[1]) * 0.5]
        }
        None => places[0],
    }
}

/// Whether the edge `(a, b)` (between the triangles `sides`, `u32::MAX` where none) fails
/// the criteria and is split.
fn fails(
    c: &Criteria,
    view: Option<&View>,
    base: &MeshData,
    shifted: &[Vec3],
    faces: &[Vec3A],
    (a, b): (u32, u32),
    sides: [u32; 2],
) -> bool {
    let (pa, pb) = (Vec3A::from(shifted[a as usize]), Vec3A::from(shifted[b as usize]));
    let measure = |d: Vec3A| match view.filter(|_| c.view) {
        Some(v) => v.pixels(d, (pa + pb) * 0.5),
        None => d.length(),
    };
    let mut held = Vec::with_capacity(3);
    if let Some(l) = c.length {
        held.push(measure(pb - pa) <= l);
    }
    if let Some(d) = c.distance {
        let offset = |v: u32| Vec3A::from(shifted[v as usize]) - Vec3A::from(base.positions[v as usize]);
        held.push(measure(offset(b) - offset(a)) <= d);
    }
    if let Some(angle) = c.angle {
        let ok = match sides {
            [s, t] if s != u32::MAX && t != u32::MAX => {
                let (n, m) = (faces[s as usize], faces[t as usize]);
                n == Vec3A::ZERO || m == Vec3A::ZERO || n.dot(m).clamp(-1.0, 1.0).acos() <= angle
            }
            _ => true,
        };
        held.push(ok);
    }
    if c.any {
        !held.iter().any(|&h| h)
    } else {
        !held.iter().all(|&h| h)
    }
}

/// Appends the vertex halfway between vertices `a` and `b` of `base` (every attribute the
/// mean of theirs; the normal renormalised).
fn push_middle(base: &mut MeshData, a: usize, b: usize) {
    let mid3 = |x: Vec3, y: Vec3| (x + y) * 0.5;
    base.positions.push(mid3(base.positions[a], base.positions[b]));
    let n = (Vec3A::from(base.normals[a]) + Vec3A::from(base.normals[b])).normalize_or_zero();
    base.normals.push(Vec3::from(n));
    for t in &mut base.textures {
        t.push((t[a] + t[b]) * 0.5);
    }
    for u in &mut base.user {
        u.push(mid3(u[a], u[b]));
    }
    if !base.bump_basis.is_empty() {
        let (x, y) = (base.bump_basis[a], base.bump_basis[b]);
        base.bump_basis.push([(x[0] + y[0]) * 0.5, (x[1] + y[1]) * 0.5]);
    }
}

/// Appends the triangles `tri` (corners a, b, c) splits into, given the middle vertices
/// `m` of its edges ab, bc, ca (`u32::MAX`: not split); the winding is kept. A quad left
/// by two split edges is cut along its shorter diagonal (displaced positions `p`).
fn split_triangle(tri: [u32; 3], m: [u32; 3], p: &[Vec3], out: &mut Vec<[u32; 3]>) {
    let n = m.iter().filter(|&&x| x != u32::MAX).count();
    // Rotate so that (for one split edge) edge 0 is split, (for two) edge 2 is not.
    let r = match n {
        1 => m.iter().position(|&x| x != u32::MAX).unwrap_or(0),
        2 => (m.iter().position(|&x| x == u32::MAX).unwrap_or(2) + 1) % 3,
        _ => 0,
    };
    let [a, b, c] = [tri[r], tri[(r + 1) % 3], tri[(r + 2) % 3]];
    let [m0, m1, m2] = [m[r], m[(r + 1) % 3], m[(r + 2) % 3]];
    match n {
        0 => out.push(tri),
        1 => out.extend([[a, m0, c], [m0, b, c]]),
        2 => {
            out.push([m0, b, m1]);
            let len = |x: u32, y: u32| (p[x as usize] - p[y as usize]).length_squared();
            if len(a, m1) <= len(m0, c) {
                out.extend([[a, m0, m1], [a, m1, c]]);
            } else {
                out.extend([[a, m0, c], [m0, m1, c]]);
            }
        }
        _ => out.extend([[a, m0, m2], [m0, b, m1], [m2, m1, c], [m0, m1, m2]]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::displace::plan::DEFAULT_MAX_LEVEL;

    fn criteria(length: f32, max_level: u32) -> Criteria {
        Criteria {
            length: Some(length),
            distance: None,
            angle: None,
            view: false,
            any: false,
            min_level: 0,
            max_level,
            max_triangles: None,
        }
    }

    /// A closed mesh (a unit tetrahedron) refined until every edge is at most 0.2 long,
    /// its vertices pushed out by 0.1 along their normals: every edge of the result is
    /// shared by exactly two triangles (crack-free, no T-junctions), every edge is at most
    /// 0.2 (the greatest level not reached), and the area grew from the base's.
    #[test]
    fn a_closed_mesh_stays_closed_under_uneven_splits() {
        let mesh = MeshData {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
            ..MeshData::default()
        };
        let push = |m: &MeshData, v: usize, _s: u32| m.normals[v] * (0.1 * (m.positions[v].x * 7.0).sin());
        let out =
            refine(&mesh, &criteria(0.2, DEFAULT_MAX_LEVEL + 4), None, 1 << 20, &push, false).expect("within budget").0;
        let mut count: HashMap<(u32, u32), u32> = HashMap::new();
        for t in &out.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *count.entry((a.min(b), a.max(b))).or_default() += 1;
                let l = (out.positions[a as usize] - out.positions[b as usize]).length();
                assert!(l <= 0.2, "edge {l}");
            }
        }
        assert!(count.values().all(|&n| n == 2), "an edge not shared by two triangles");
        assert!(out.triangles.len() > 4 * 16, "{}", out.triangles.len());
    }

    /// The triangle limit: a refinement that would pass it is `Err` with the count.
    #[test]
    fn the_budget_bounds_the_refinement() {
        let mesh = MeshData {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            triangles: vec![[0, 1, 2]],
            ..MeshData::default()
        };
        let zero = |_: &MeshData, _: usize, _: u32| Vec3::ZERO;
        assert_eq!(refine(&mesh, &criteria(1e-6, 16), None, 1000, &zero, false).err(), Some(1024));
    }

    /// Two triangles of unequal edges refined unevenly (edges at most 0.3, displaced by 0),
    /// carrying where each fine triangle lies: every fine corner's carried barycentrics,
    /// mixed over its original's corners, give the corner's position (within 1e-6), and the
    /// fine triangles of each original cover its area (within 1e-5); without `carry`
    /// nothing is kept.
    #[test]
    fn fine_triangles_carry_their_places_on_the_originals() {
        let positions = vec![Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(1.5, 0.4, 0.0), Vec3::new(0.0, 1.0, 0.0)];
        let triangles = vec![[0, 1, 2], [0, 2, 3]];
        let mesh = MeshData { positions: positions.clone(), triangles: triangles.clone(), ..MeshData::default() };
        let zero = |_: &MeshData, _: usize, _: u32| Vec3::ZERO;
        let (out, origins) = refine(&mesh, &criteria(0.3, 8), None, 1 << 20, &zero, true).expect("within budget");
        assert_eq!(origins.len(), out.triangles.len());
        let area = |p: [Vec3; 3]| (p[1] - p[0]).cross(p[2] - p[0]).length() * 0.5;
        let mut covered = [0.0f32; 2];
        for (tri, o) in out.triangles.iter().zip(&origins) {
            let t = triangles[o.triangle as usize].map(|v| positions[v as usize]);
            for (&v, c) in tri.iter().zip(o.corners) {
                let back = t[0] * (1.0 - c[0] - c[1]) + t[1] * c[0] + t[2] * c[1];
                assert!((back - out.positions[v as usize]).length() < 1e-6, "{back} vs {}", out.positions[v as usize]);
            }
            covered[o.triangle as usize] += area(tri.map(|v| out.positions[v as usize]));
        }
        for (t, c) in covered.iter().enumerate() {
            let whole = area(triangles[t].map(|v| positions[v as usize]));
            assert!((c - whole).abs() < 1e-5, "triangle {t}: {c} of {whole}");
        }
        assert!(!(0..9).any(|k| out.triangles.len() == 2 << (2 * k)), "an uneven split: {}", out.triangles.len());
        assert!(refine(&mesh, &criteria(0.3, 8), None, 1 << 20, &zero, false).expect("within budget").1.is_empty());
    }
}
