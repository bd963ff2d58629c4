//! Triangle-mesh light shapes (mental ray's `object` area lights): an object instance's
//! triangles in world space, sampled uniformly by area through a CDF over the triangles'
//! areas, and intersected for the path engine's MIS.

use std::fmt;

use std::sync::Arc;

use glam::{Affine3A, DMat4, Mat3A, Vec2, Vec3A};
use scene::Scene;

/// The emitting triangles of an object light, world space: the triangles where the
/// scene puts them, and (for a moving light, see [`MeshShape::displaced`]) where that
/// light's motion has carried them at one shutter time.
#[derive(Clone, PartialEq)]
pub struct MeshShape {
    /// The triangles at motion time 0, shared by every displaced copy.
    still: Arc<Triangles>,
    /// World → world displacement applied to `still` on the fly (`None`: none).
    placed: Option<Displacement>,
    /// The triangles over the shutter when they change shape while it is open (`still`
    /// is then their shape at the opening); see [`MeshShape::at_time`].
    deforming: Option<Arc<super::DeformingMesh>>,
}

/// World-space triangles and their sampling data.
#[derive(PartialEq)]
struct Triangles {
    /// Triangle vertices, world space, counter-clockwise seen from the emitting side.
    triangles: Vec<[Vec3A; 3]>,
    /// Unit normal of each triangle's emitting side.
    normals: Vec<Vec3A>,
    /// Running sum of the triangles' areas (`cdf[i]` = area of triangles `0..=i`).
    cdf: Vec<f32>,
    /// Bounds of all triangles (quick rejection of rays).
    lo: Vec3A,
    hi: Vec3A,
}

/// A similarity (rotation, translation, uniform scale, maybe a mirror) carrying the still
/// triangles to where they are: uniform sampling by area stays uniform under it.
#[derive(Clone, Copy, PartialEq)]
struct Displacement {
    /// Still → displaced, world space.
    by: Affine3A,
    /// Displaced → still.
    back: Affine3A,
    /// Still normals → displaced normals (inverse transpose; normalise after).
    normals: Mat3A,
    /// Displaced area over still area (the scale squared).
    area_scale: f32,
}

impl fmt::Debug for MeshShape {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "MeshShape {{ {} triangles, area {} }}", self.len(), self.area())
    }
}

impl MeshShape {
    /// A mesh shape from world-space triangles (front: counter-clockwise). Triangles without
    /// area are dropped; `None` if none is left.
    pub fn new(triangles: impl IntoIterator<Item = [Vec3A; 3]>) -> Option<MeshShape> {
        let mut out = Triangles {
            triangles: Vec::new(),
            normals: Vec::new(),
            cdf: Vec::new(),
            lo: Vec3A::splat(f32::INFINITY),
            hi: Vec3A::splat(f32::NEG_INFINITY),
        };
        let mut sum = 0.0f64;
        for t in triangles {
            let c = (t[1] - t[0]).cross(t[2] - t[0]);
            let a = 0.5 * c.length();
            if !(a > 0.0 && a.is_finite() && t.iter().all(|p| p.is_finite())) {
                continue;
            }
            sum += f64::from(a);
            out.triangles.push(t);
            out.normals.push(c / (2.0 * a));
            out.cdf.push(sum as f32);
            for p in t {
                out.lo = out.lo.min(p);
                out.hi = out.hi.max(p);
            }
        }
        (!out.triangles.is_empty()).then_some(MeshShape { still: Arc::new(out), placed: None, deforming: None })
    }

    /// These triangles carried by `by` (world → world: a moving light's displacement at
    /// one shutter time, see `Tracer::light_motion`), on top of any displacement they
    /// already have. A similarity (what a rigid motion with a uniform scale gives) shares
    /// the triangles and moves each point, normal and ray on the fly; any other affine map
    /// (a non-uniform scale changes the triangles' relative areas) builds the moved
    /// triangles, so that sampling stays uniform by area. A map that flattens them (or is
    /// not finite) leaves them where they are.
    pub fn displaced(&self, by: Affine3A) -> MeshShape {
        let by = match self.placed {
            Some(d) => by * d.by,
            None => by,
        };
        let m = by.matrix3;
        let det = m.determinant();
        if !by.is_finite() || !det.is_finite() || det == 0.0 {
            return self.clone();
        }
        let gram = m.transpose() * m;
        let s2 = (gram.x_axis.x + gram.y_axis.y + gram.z_axis.z) / 3.0;
        if gram.abs_diff_eq(Mat3A::from_diagonal(glam::Vec3::splat(s2)), 1e-5 * s2) {
            let placed = Displacement { by, back: by.inverse(), normals: m.inverse().transpose(), area_scale: s2 };
            return MeshShape { still: Arc::clone(&self.still), placed: Some(placed), deforming: None };
        }
        let flip = det < 0.0;
        let moved = self.still.triangles.iter().map(|t| {
            let [a, b, c] = t.map(|p| by.transform_point3a(p));
            if flip {
                [a, c, b]
            } else {
                [a, b, c]
            }
        });
        MeshShape::new(moved).unwrap_or_else(|| self.clone())
    }

    /// These triangles (their shape at the shutter's opening) changing shape over the
    /// shutter as `deforming` gives (see [`MeshShape::at_time`]).
    pub fn deforming(self, deforming: Arc<super::DeformingMesh>) -> MeshShape {
        MeshShape { deforming: Some(deforming), ..self }
    }

    /// The triangles where they are at shutter time `s` (0…1) when they change shape
    /// while the shutter is open ([`MeshShape::deforming`]); `None` when they do not (or
    /// have no area then): this shape holds at every time.
    pub fn at_time(&self, s: f32) -> Option<MeshShape> {
        self.deforming.as_ref()?.at(s)
    }

    /// The triangles of the scene instance named `name` (or, when no instance has that
    /// name, of every instance of the object named `name`), carried to world space. A
    /// mirroring transform keeps the emitting side the one its normals give (as rectangle
    /// lights do).
    pub fn of_instance(scene: &Scene, name: &str) -> Result<MeshShape, String> {
        let mut picked: Vec<_> = scene.instances.iter().filter(|i| i.name == name).collect();
        if picked.is_empty() {
            picked = scene
                .instances
                .iter()
                .filter(|i| scene.objects.get(i.object as usize).is_some_and(|o| o.name == name))
                .collect();
        }
        if picked.is_empty() {
            return Err(format!("no object instance '{name}'"));
        }
        let mut tris = Vec::new();
        for inst in picked {
            let Some(obj) = scene.objects.get(inst.object as usize) else { continue };
            let m: DMat4 = inst.object_to_world;
            let flip = m.determinant() < 0.0;
            let mesh = &obj.geometry.mesh;
            for t in &mesh.triangles {
                let Some(p) = t.iter().map(|&i| mesh.positions.get(i as usize)).collect::<Option<Vec<_>>>() else {
                    continue;
                };
                let w = |v: &glam::Vec3| m.transform_point3(v.as_dvec3()).as_vec3a();
                let (a, b, c) = (w(p[0]), w(p[1]), w(p[2]));
                tris.push(if flip { [a, c, b] } else { [a, b, c] });
            }
        }
        MeshShape::new(tris).ok_or_else(|| format!("object instance '{name}' has no triangles with area"))
    }

    /// Total area, world units².
    pub fn area(&self) -> f32 {
        self.still.area() * self.placed.map_or(1.0, |d| d.area_scale)
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.still.triangles.len()
    }

    /// Whether there are no triangles (never, for a constructed shape).
    pub fn is_empty(&self) -> bool {
        self.still.triangles.is_empty()
    }

    /// A point uniformly distributed by area for `u` uniform in [0,1)², and the unit normal
    /// of its triangle's emitting side.
    pub fn point_on(&self, u: Vec2) -> (Vec3A, Vec3A) {
        let (p, n) = self.still.point_on(u);
        match self.placed {
            None => (p, n),
            Some(d) => (d.by.transform_point3a(p), (d.normals * n).normalize_or(n)),
        }
    }

    /// The emitting-side normal of the triangle that `q` (a point on the mesh) lies on.
    pub fn normal_at(&self, q: Vec3A) -> Vec3A {
        match self.placed {
            None => self.still.normal_at(q),
            Some(d) => {
                let n = self.still.normal_at(d.back.transform_point3a(q));
                (d.normals * n).normalize_or(n)
            }
        }
    }

    /// The nearest triangle the ray `origin + t·dir` meets with t in `(tmin, tmax)`: the
    /// distance and whether the ray arrives at the emitting side. (An affine map keeps a
    /// line's parameter and the sign of its direction's dot product with the normal, so
    /// a displaced mesh is met by the ray carried back.)
    pub fn intersect(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> Option<(f32, bool)> {
        match self.placed {
            None => self.still.intersect(origin, dir, tmin, tmax),
            Some(d) => {
                self.still.intersect(d.back.transform_point3a(origin), d.back.transform_vector3a(dir), tmin, tmax)
            }
        }
    }
}

impl Triangles {
    fn area(&self) -> f32 {
        self.cdf.last().copied().unwrap_or(0.0)
    }

    fn point_on(&self, u: Vec2) -> (Vec3A, Vec3A) {
        let total = self.area();
        let x = u.x.clamp(0.0, 1.0) * total;
        let i = self.cdf.partition_point(|&c| c <= x).min(self.cdf.len() - 1);
        let start = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        let width = self.cdf[i] - start;
        // Reuse the rest of u.x inside the chosen triangle's slot.
        let ux = if width > 0.0 { ((x - start) / width).clamp(0.0, 1.0 - f32::EPSILON) } else { 0.5 };
        let su = ux.sqrt();
        let (b0, b1) = (1.0 - su, u.y * su);
        let [a, b, c] = self.triangles[i];
        (a * b0 + b * b1 + c * (1.0 - b0 - b1), self.normals[i])
    }

    fn normal_at(&self, q: Vec3A) -> Vec3A {
        let mut best = (f32::INFINITY, Vec3A::ZERO);
        for (t, &n) in self.triangles.iter().zip(&self.normals) {
            let d = (q - t[0]).dot(n).abs();
            if d < best.0 && inside(t, n, q) {
                best = (d, n);
            }
        }
        if best.1 == Vec3A::ZERO {
            // Not inside any triangle (rounding at an edge): the nearest plane.
            for (t, &n) in self.triangles.iter().zip(&self.normals) {
                let d = (q - t[0]).dot(n).abs();
                if d < best.0 || best.1 == Vec3A::ZERO {
                    best = (d, n);
                }
            }
        }
        best.1
    }

    fn intersect(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> Option<(f32, bool)> {
        if !slab(self.lo, self.hi, origin, dir, tmin, tmax) {
            return None;
        }
        let mut best: Option<(f32, bool)> = None;
        let mut far = tmax;
        for (t, &n) in self.triangles.iter().zip(&self.normals) {
            // Möller–Trumbore.
            let e1 = t[1] - t[0];
            let e2 = t[2] - t[0];
            let pv = dir.cross(e2);
            let det = e1.dot(pv);
            if det == 0.0 {
                continue;
            }
            let inv = 1.0 / det;
            let tv = origin - t[0];
            let u = tv.dot(pv) * inv;
            if !(0.0..=1.0).contains(&u) {
                continue;
            }
            let qv = tv.cross(e1);
            let v = dir.dot(qv) * inv;
            if v < 0.0 || u + v > 1.0 {
                continue;
            }
            let d = e2.dot(qv) * inv;
            if d > tmin && d < far {
                far = d;
                best = Some((d, dir.dot(n) < 0.0));
            }
        }
        best
    }
}

/// Whether `q` (near the plane of triangle `t` with normal `n`) lies inside it, with a
/// small tolerance for rounding.
fn inside(t: &[Vec3A; 3], n: Vec3A, q: Vec3A) -> bool {
    let scale = (t[1] - t[0]).length_squared().max((t[2] - t[0]).length_squared());
    let tol = -1e-4 * scale;
    (0..3).all(|k| (t[(k + 1) % 3] - t[k]).cross(q - t[k]).dot(n) >= tol)
}

/// Whether the ray meets the box `[lo, hi]` within `(tmin, tmax)`.
fn slab(lo: Vec3A, hi: Vec3A, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> bool {
    let inv = dir.recip();
    let a = (lo - origin) * inv;
    let b = (hi - origin) * inv;
    let near = a.min(b);
    let far = a.max(b);
    // NaN (a zero direction component on the box's face) compares false: keep the ray.
    let t0 = near.max_element().max(tmin);
    let t1 = far.min_element().min(tmax);
    t0 <= t1 * (1.0 + 4.0 * f32::EPSILON) + 1e-6 || t0.is_nan() || t1.is_nan()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square (two triangles) beside a triangle of area 4: 5 in all.
    fn l_mesh() -> MeshShape {
        MeshShape::new([
            [Vec3A::ZERO, Vec3A::new(1.0, 0.0, 0.0), Vec3A::new(1.0, 1.0, 0.0)],
            [Vec3A::ZERO, Vec3A::new(1.0, 1.0, 0.0), Vec3A::new(0.0, 1.0, 0.0)],
            [Vec3A::new(1.0, 0.0, 0.0), Vec3A::new(5.0, 0.0, 0.0), Vec3A::new(1.0, 2.0, 0.0)],
        ])
        .expect("a mesh")
    }

    #[test]
    fn sampling_is_uniform_by_area_chi_square() {
        // Cells of 0.5 × 0.5 over the mesh's bounding box [0,5]×[0,2]; each cell's expected
        // count is its covered area / 5 of the samples.
        let m = l_mesh();
        assert!((m.area() - 5.0).abs() < 1e-5);
        let n = 1 << 16;
        let (cols, rows) = (10usize, 4usize);
        let mut counts = vec![0u32; cols * rows];
        // Independent pseudo-random points (xorshift32).
        let mut state = 0x9e37_79b9u32;
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state >> 8) as f32 / (1u32 << 24) as f32
        };
        for _ in 0..n {
            let (p, normal) = m.point_on(Vec2::new(rnd(), rnd()));
            assert!((normal - Vec3A::Z).length() < 1e-6 && p.z.abs() < 1e-6);
            let (cx, cy) = ((p.x * 2.0) as usize, (p.y * 2.0) as usize);
            counts[cy.min(rows - 1) * cols + cx.min(cols - 1)] += 1;
        }
        // Expected covered area of each cell by fine supersampling.
        let mut chi2 = 0.0;
        let mut dof = 0;
        for cy in 0..rows {
            for cx in 0..cols {
                let mut covered = 0;
                let k = 64;
                for sy in 0..k {
                    for sx in 0..k {
                        let q = Vec3A::new(
                            (cx as f32 + (sx as f32 + 0.5) / k as f32) * 0.5,
                            (cy as f32 + (sy as f32 + 0.5) / k as f32) * 0.5,
                            0.0,
                        );
                        let ins = m.still.triangles.iter().any(|t| tri_strict(t, q));
                        covered += usize::from(ins);
                    }
                }
                let expected = covered as f64 / (k * k) as f64 * 0.25 / 5.0 * n as f64;
                let got = f64::from(counts[cy * cols + cx]);
                if expected < 5.0 {
                    assert!(got <= expected * 3.0 + 10.0, "cell ({cx},{cy}): {got} vs {expected}");
                    continue;
                }
                chi2 += (got - expected).powi(2) / expected;
                dof += 1;
            }
        }
        // The 99.9th percentile of χ² with ~25 degrees of freedom is about 52.6; allow
        // for the supersampled expectations' own error on cells the diagonals cross.
        eprintln!("chi-square {chi2:.1} over {dof} cells");
        assert!(chi2 < 60.0, "chi-square {chi2} over {dof} cells");
        // First moments: the mean point is the area-weighted centroid.
        let c: Vec3A =
            m.still.triangles.iter().zip(areas(&m)).map(|(t, a)| (t[0] + t[1] + t[2]) / 3.0 * a).sum::<Vec3A>()
                / m.area();
        // A midpoint grid whose u.x cells do not straddle the CDF's steps (0.1 and 0.2).
        let mut mean = Vec3A::ZERO;
        let k = 250;
        for i in 0..k {
            for j in 0..k {
                let u = Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
                mean += m.point_on(u).0;
            }
        }
        mean /= (k * k) as f32;
        assert!((mean - c).length() < 5e-4, "mean {mean} vs centroid {c}");
    }

    fn tri_strict(t: &[Vec3A; 3], q: Vec3A) -> bool {
        (0..3).all(|k| (t[(k + 1) % 3] - t[k]).cross(q - t[k]).z >= 0.0)
    }

    fn areas(m: &MeshShape) -> Vec<f32> {
        m.still
            .cdf
            .iter()
            .scan(0.0, |prev, &c| {
                let a = c - *prev;
                *prev = c;
                Some(a)
            })
            .collect()
    }

    #[test]
    fn rays_through_sampled_points_hit_them_from_the_front() {
        let m = l_mesh();
        for k in 0..64 {
            let u = Vec2::new((k % 8) as f32 / 8.0 + 0.03, (k / 8) as f32 / 8.0 + 0.05);
            let (q, n) = m.point_on(u);
            assert!((m.normal_at(q) - n).length() < 1e-6);
            let origin = q + Vec3A::new(0.3, -0.2, 2.0);
            let dir = (q - origin).normalize();
            let (t, front) = m.intersect(origin, dir, 0.0, f32::INFINITY).expect("hit");
            assert!(front);
            assert!((origin + dir * t - q).length() < 1e-4);
            let back = q - Vec3A::new(0.3, -0.2, 2.0);
            let (_, front) = m.intersect(back, (q - back).normalize(), 0.0, f32::INFINITY).expect("hit");
            assert!(!front);
        }
        assert!(m.intersect(Vec3A::new(3.0, 1.9, 1.0), -Vec3A::Z, 0.0, f32::INFINITY).is_none());
    }

    /// A displaced mesh is the still mesh carried by the displacement: turned 90° about z,
    /// doubled and moved, its sampled points are the still ones carried (so uniform by
    /// area still), its normals turn with it, its area is 4× (the scale squared), rays
    /// meet it where the carried triangles are; a non-uniform scale rebuilds the
    /// triangles (area by the determinant here, 3×) and a flattening map leaves it still.
    #[test]
    fn displaced_meshes_move_points_normals_areas_and_hits() {
        let m = l_mesh();
        let by = Affine3A::from_translation(glam::Vec3::new(1.0, 2.0, 3.0))
            * Affine3A::from_scale(glam::Vec3::splat(2.0))
            * Affine3A::from_rotation_z(std::f32::consts::FRAC_PI_2);
        let d = m.displaced(by);
        assert!((d.area() - 20.0).abs() < 1e-4, "{}", d.area());
        // Tilted about x too, so that normals turn visibly: twice over is the product.
        let tilt = Affine3A::from_rotation_x(0.5);
        let dd = d.displaced(tilt);
        for k in 0..64 {
            let u = Vec2::new((k % 8) as f32 / 8.0 + 0.03, (k / 8) as f32 / 8.0 + 0.05);
            let (p, n) = m.point_on(u);
            let (q, nq) = dd.point_on(u);
            assert!((q - (tilt * by).transform_point3a(p)).length() < 1e-4);
            let want_n = tilt.transform_vector3a(n);
            assert!((nq - want_n).length() < 1e-5, "{nq} vs {want_n}");
            assert!((dd.normal_at(q) - want_n).length() < 1e-5);
            // A ray towards the carried point from the front meets it there.
            let origin = q + want_n * 2.0 + Vec3A::new(0.01, -0.02, 0.0);
            let dir = (q - origin).normalize();
            let (t, front) = dd.intersect(origin, dir, 0.0, f32::INFINITY).expect("hit");
            assert!(front && (origin + dir * t - q).length() < 1e-3, "{t}");
        }
        let stretched = m.displaced(Affine3A::from_scale(glam::Vec3::new(3.0, 1.0, 1.0)));
        assert!((stretched.area() - 15.0).abs() < 1e-4, "{}", stretched.area());
        let flat = m.displaced(Affine3A::from_scale(glam::Vec3::new(1.0, 0.0, 1.0)));
        assert!(flat == m);
    }

    #[test]
    fn degenerate_triangles_are_dropped() {
        assert!(MeshShape::new([[Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0]]).is_none());
        let m = MeshShape::new([[Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0], [Vec3A::ZERO, Vec3A::X, Vec3A::Y]]).unwrap();
        assert_eq!(m.len(), 1);
        assert!((m.area() - 0.5).abs() < 1e-7);
    }
}
