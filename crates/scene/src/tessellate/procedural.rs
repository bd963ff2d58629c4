//! mental ray's shape geometry shaders as triangle meshes: `mib_geo_sphere`, `mib_geo_cone`,
//! `mib_geo_cylinder`, `mib_geo_cube`, `mib_geo_square` and `mib_geo_torus`.
//!
//! Every shape is built in object space, in the units of the instance that places it (the
//! instance transform scales, turns and moves it), with the positions, vertex normals and
//! triangle winding of mental images' base shader sources: counter-clockwise seen from
//! outside. Where the source gives no normals (cube, square) the mesh has none and the
//! geometric normal applies. All faces take the instance's material
//! ([`MaterialSlot::Inherit`]).
//!
//! mira's additions, which mental ray's shaders do not make:
//! - the sphere, cone, cylinder and torus carry one texture space (texture space 0,
//!   two-dimensional): `u` runs once around the z axis, `v` along the shape from 0 at its
//!   bottom (the sphere's south pole, the cone's and cylinder's z = −1) to 1 at its top;
//!   the torus's `v` runs once around the tube, from its outer equator over the top; caps
//!   are mapped from the xy plane, `((x+1)/2, (y+1)/2)`;
//! - so that those coordinates do not wrap back to 0 inside a triangle, the vertices of
//!   the seam at angle 0 are duplicated (same position and normal, `u` 0 and 1) and poles
//!   and the cone's apex have one vertex per segment (the `u` of the segment's middle);
//! - triangles of zero area (the cone's source builds one per segment at the apex) are
//!   left out.

use glam::{DVec3, Vec3};
use mi::ast::Param;
use std::f64::consts::PI;

use crate::mesh::{MaterialSlot, Mesh, TexSpace};
use crate::values::AttrValue;

/// mental ray's subdivision around (`u_subdiv`) when the one given is below 3.
pub const DEFAULT_U_SUBDIV: u32 = 8;

/// mental ray's subdivision along (`v_subdiv`) when the one given is below 1 (sphere) or
/// negative (cone, cylinder).
pub const DEFAULT_V_SUBDIV: u32 = 8;

/// The torus's spans (`uSpans`, `vSpans`) when the one given is 0.
pub const DEFAULT_TORUS_SPANS: u32 = 32;

/// The torus's `radius` (centre of the tube to the z axis) when the one given is not
/// positive.
pub const DEFAULT_TORUS_RADIUS: f64 = 2.0;

/// The torus's `thickness` (radius of the tube) when the one given is not positive.
pub const DEFAULT_TORUS_THICKNESS: f64 = 1.0;

/// Most triangles one shape may have; finer subdivisions are reduced by
/// [`Shape::limited`].
pub const MAX_TRIANGLES: u64 = 8 << 20;

/// Largest subdivision count read from a parameter (before [`MAX_TRIANGLES`] applies).
const MAX_SUBDIV: i64 = 1 << 20;

/// A shape geometry shader's call, its parameters read and mental ray's defaults applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// `mib_geo_sphere`: the unit sphere at the origin, poles on ±z.
    Sphere {
        /// Points around each ring (3 or more).
        u_subdiv: u32,
        /// Rings between the poles (1 or more).
        v_subdiv: u32,
    },
    /// `mib_geo_cone`: around the z axis, base of radius 1 at z = −1, apex at the origin.
    Cone {
        /// Points around each ring (3 or more).
        u_subdiv: u32,
        /// Rings between the base and the apex (0 or more).
        v_subdiv: u32,
        /// With a bottom disc.
        capped: bool,
    },
    /// `mib_geo_cylinder`: radius 1 around the z axis, from z = −1 to z = 0.
    Cylinder {
        /// Points around each ring (3 or more).
        u_subdiv: u32,
        /// Rings between the bottom and the top ones (0 or more).
        v_subdiv: u32,
        /// With a disc at z = −1.
        bottom_capped: bool,
        /// With a disc at z = 0.
        top_capped: bool,
    },
    /// `mib_geo_cube`: the axis-aligned cube of side 1 centred at the origin.
    Cube,
    /// `mib_geo_square`: the square [−½, ½]² in the plane z = 0, facing +z.
    Square,
    /// `mib_geo_torus`: a ring around the z axis in the xy plane.
    Torus {
        /// Distance of the tube's centre from the z axis.
        radius: f64,
        /// Radius of the tube.
        thickness: f64,
        /// Segments around the z axis.
        u_spans: u32,
        /// Segments around the tube.
        v_spans: u32,
    },
}

/// The last value given to parameter `name`, if it is a constant.
fn value(params: &[Param], name: &str) -> Option<AttrValue> {
    params.iter().rev().find(|p| p.name.text == name).and_then(|p| AttrValue::from_value(&p.value))
}

/// An `integer` parameter (0 when absent, as mental ray's zeroed parameter block).
fn integer(params: &[Param], name: &str) -> i64 {
    // `as` saturates (and makes NaN 0).
    value(params, name).and_then(|v| v.as_f64()).map_or(0, |f| f as i64)
}

/// A `scalar` parameter (0 when absent).
fn scalar(params: &[Param], name: &str) -> f64 {
    value(params, name).and_then(|v| v.as_f64()).unwrap_or(0.0)
}

/// A `boolean` parameter (off when absent).
fn boolean(params: &[Param], name: &str) -> bool {
    value(params, name).and_then(|v| v.as_bool()).unwrap_or(false)
}

/// `u_subdiv` with its default.
fn u_subdiv(params: &[Param]) -> u32 {
    match integer(params, "u_subdiv") {
        u if u < 3 => DEFAULT_U_SUBDIV,
        u => u.min(MAX_SUBDIV) as u32,
    }
}

/// `v_subdiv` with its default for values below `min`.
fn v_subdiv(params: &[Param], min: i64) -> u32 {
    match integer(params, "v_subdiv") {
        v if v < min => DEFAULT_V_SUBDIV,
        v => v.min(MAX_SUBDIV) as u32,
    }
}

/// A torus span count with its default (0, or negative, gives 32).
fn spans(params: &[Param], name: &str) -> u32 {
    match integer(params, name) {
        s if s <= 0 => DEFAULT_TORUS_SPANS,
        s => s.min(MAX_SUBDIV) as u32,
    }
}

/// A positive, finite scalar parameter, or `default`.
fn positive(params: &[Param], name: &str, default: f64) -> f64 {
    match scalar(params, name) {
        s if s > 0.0 && s.is_finite() => s,
        _ => default,
    }
}

impl Shape {
    /// The shape a call of geometry shader `decl` with `params` makes, mental ray's
    /// defaults applied; `None` when `decl` is not one of the shape shaders. Parameters
    /// that are not constants (connections, interface parameters) count as absent.
    pub fn from_call(decl: &str, params: &[Param]) -> Option<Shape> {
        Some(match decl {
            "mib_geo_sphere" => Shape::Sphere { u_subdiv: u_subdiv(params), v_subdiv: v_subdiv(params, 1) },
            "mib_geo_cone" => Shape::Cone {
                u_subdiv: u_subdiv(params),
                v_subdiv: v_subdiv(params, 0),
                capped: boolean(params, "capped"),
            },
            "mib_geo_cylinder" => Shape::Cylinder {
                u_subdiv: u_subdiv(params),
                v_subdiv: v_subdiv(params, 0),
                bottom_capped: boolean(params, "bottom_capped"),
                top_capped: boolean(params, "top_capped"),
            },
            "mib_geo_cube" => Shape::Cube,
            "mib_geo_square" => Shape::Square,
            "mib_geo_torus" => Shape::Torus {
                radius: positive(params, "radius", DEFAULT_TORUS_RADIUS),
                thickness: positive(params, "thickness", DEFAULT_TORUS_THICKNESS),
                u_spans: spans(params, "uSpans"),
                v_spans: spans(params, "vSpans"),
            },
            _ => return None,
        })
    }

    /// How many triangles the shape has (zero-area ones already left out).
    pub fn triangle_count(&self) -> u64 {
        let cap = |c: bool| u64::from(c);
        match *self {
            Shape::Sphere { u_subdiv: u, v_subdiv: v } => 2 * u64::from(u) * u64::from(v),
            Shape::Cone { u_subdiv: u, v_subdiv: v, capped } => u64::from(u) * (2 * u64::from(v) + 1 + cap(capped)),
            Shape::Cylinder { u_subdiv: u, v_subdiv: v, bottom_capped, top_capped } => {
                u64::from(u) * (2 * (u64::from(v) + 1) + cap(bottom_capped) + cap(top_capped))
            }
            Shape::Cube => 12,
            Shape::Square => 2,
            Shape::Torus { u_spans, v_spans, .. } => 2 * u64::from(u_spans) * u64::from(v_spans),
        }
    }

    /// The shape with its subdivisions reduced, in proportion, until it has at most `max`
    /// triangles (or the smallest subdivisions allowed); unchanged when it already has.
    pub fn limited(self, max: u64) -> Shape {
        let mut shape = self;
        while shape.triangle_count() > max {
            let scale = (max as f64 / shape.triangle_count() as f64).sqrt().min(0.99);
            let reduce = |n: u32, min: u32| ((f64::from(n) * scale) as u32).max(min);
            let next = match shape {
                Shape::Sphere { u_subdiv, v_subdiv } => {
                    Shape::Sphere { u_subdiv: reduce(u_subdiv, 3), v_subdiv: reduce(v_subdiv, 1) }
                }
                Shape::Cone { u_subdiv, v_subdiv, capped } => {
                    Shape::Cone { u_subdiv: reduce(u_subdiv, 3), v_subdiv: reduce(v_subdiv, 0), capped }
                }
                Shape::Cylinder { u_subdiv, v_subdiv, bottom_capped, top_capped } => Shape::Cylinder {
                    u_subdiv: reduce(u_subdiv, 3),
                    v_subdiv: reduce(v_subdiv, 0),
                    bottom_capped,
                    top_capped,
                },
                Shape::Torus { radius, thickness, u_spans, v_spans } => {
                    Shape::Torus { radius, thickness, u_spans: reduce(u_spans, 3), v_spans: reduce(v_spans, 3) }
                }
                Shape::Cube | Shape::Square => shape,
            };
            if next == shape {
                break;
            }
            shape = next;
        }
        shape
    }

    /// The shape's triangle mesh, object space, named `name`.
    pub fn mesh(&self, name: &str) -> Mesh {
        let mut b = MeshBuilder::new(name);
        match *self {
            Shape::Sphere { u_subdiv, v_subdiv } => sphere(&mut b, u_subdiv, v_subdiv),
            Shape::Cone { u_subdiv, v_subdiv, capped } => cone(&mut b, u_subdiv, v_subdiv, capped),
            Shape::Cylinder { u_subdiv, v_subdiv, bottom_capped, top_capped } => {
                cylinder(&mut b, u_subdiv, v_subdiv, bottom_capped, top_capped)
            }
            Shape::Cube => cube(&mut b),
            Shape::Square => square(&mut b),
            Shape::Torus { radius, thickness, u_spans, v_spans } => torus(&mut b, radius, thickness, u_spans, v_spans),
        }
        b.finish()
    }
}

/// Collects vertices (with optional normals and texture coordinates) and triangles.
struct MeshBuilder {
    mesh: Mesh,
    uv: Vec<Vec3>,
}

impl MeshBuilder {
    fn new(name: &str) -> MeshBuilder {
        MeshBuilder { mesh: Mesh::new(name), uv: Vec::new() }
    }

    /// A vertex with a normal and texture coordinates; its index.
    fn vertex(&mut self, p: DVec3, n: DVec3, uv: (f64, f64)) -> u32 {
        self.mesh.normals.push(n.normalize_or_zero().as_vec3());
        self.uv.push(Vec3::new(uv.0 as f32, uv.1 as f32, 0.0));
        self.point(p)
    }

    /// A vertex with only a position; its index.
    fn point(&mut self, p: DVec3) -> u32 {
        self.mesh.positions.push(p.as_vec3());
        (self.mesh.positions.len() - 1) as u32
    }

    /// A triangle, counter-clockwise seen from outside; left out when it has no area.
    fn triangle(&mut self, a: u32, b: u32, c: u32) {
        let [pa, pb, pc] = [a, b, c].map(|i| self.mesh.positions[i as usize].as_dvec3());
        if (pb - pa).cross(pc - pa) == DVec3::ZERO {
            return;
        }
        self.mesh.triangles.push([a, b, c]);
    }

    /// A quad `a b c d` (counter-clockwise) as two triangles split along `a c`.
    fn quad(&mut self, a: u32, b: u32, c: u32, d: u32) {
        self.triangle(a, b, c);
        self.triangle(a, c, d);
    }

    fn finish(mut self) -> Mesh {
        let slot = self.mesh.slot(MaterialSlot::Inherit);
        self.mesh.triangle_slots = vec![slot; self.mesh.triangles.len()];
        if !self.uv.is_empty() {
            self.mesh.textures.push(TexSpace { dim: 2, coords: self.uv });
        }
        self.mesh
    }
}

/// The point at angle `2π·j/n` on the unit circle; `j = n` gives exactly the point of
/// `j = 0`, so that seam vertices coincide.
fn around(j: u32, n: u32) -> (f64, f64) {
    let a = 2.0 * PI * f64::from(j % n) / f64::from(n);
    (a.cos(), a.sin())
}

/// Planar texture coordinates of a cap vertex.
fn cap_uv(p: DVec3) -> (f64, f64) {
    ((p.x + 1.0) * 0.5, (p.y + 1.0) * 0.5)
}

fn sphere(b: &mut MeshBuilder, u: u32, v: u32) {
    let columns = u + 1;
    // Rings 1..=v from south to north, `u + 1` vertices each (the last repeats the first).
    for i in 1..=v {
        let t = f64::from(i) / f64::from(v + 1);
        let (z, r) = (-(t * PI).cos(), (t * PI).sin());
        for j in 0..=u {
            let (c, s) = around(j, u);
            let p = DVec3::new(r * c, r * s, z);
            b.vertex(p, p, (f64::from(j) / f64::from(u), t));
        }
    }
    let ring = |i: u32, j: u32| (i - 1) * columns + j;
    let mid = |j: u32| (f64::from(j) + 0.5) / f64::from(u);
    let south: Vec<u32> = (0..u).map(|j| b.vertex(DVec3::NEG_Z, DVec3::NEG_Z, (mid(j), 0.0))).collect();
    let north: Vec<u32> = (0..u).map(|j| b.vertex(DVec3::Z, DVec3::Z, (mid(j), 1.0))).collect();
    for j in 0..u {
        b.triangle(south[j as usize], ring(1, j + 1), ring(1, j));
        b.triangle(north[j as usize], ring(v, j), ring(v, j + 1));
    }
    for i in 1..v {
        for j in 0..u {
            let (p1, p2, p3, p4) = (ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j));
            b.triangle(p1, p2, p4);
            b.triangle(p2, p3, p4);
        }
    }
}

/// A bottom (`up` false) or top disc of radius 1 around the z axis at height `z`.
fn disc(b: &mut MeshBuilder, u: u32, z: f64, up: bool) {
    let n = if up { DVec3::Z } else { DVec3::NEG_Z };
    let rim: Vec<u32> = (0..u)
        .map(|j| {
            let (c, s) = around(j, u);
            let p = DVec3::new(c, s, z);
            b.vertex(p, n, cap_uv(p))
        })
        .collect();
    let centre = DVec3::new(0.0, 0.0, z);
    let centre = b.vertex(centre, n, cap_uv(centre));
    for j in 0..u as usize {
        let next = rim[(j + 1) % rim.len()];
        if up {
            b.triangle(centre, rim[j], next);
        } else {
            b.triangle(centre, next, rim[j]);
        }
    }
}

fn cone(b: &mut MeshBuilder, u: u32, v: u32, capped: bool) {
    let columns = u + 1;
    // The source's side normals: (2 cos p, 2 sin p, 1), normalised.
    let normal = |j: u32| {
        let (c, s) = around(j, u);
        DVec3::new(2.0 * c, 2.0 * s, 1.0)
    };
    for i in 0..=v {
        let t = f64::from(i) / f64::from(v + 1);
        let r = 1.0 - t;
        for j in 0..=u {
            let (c, s) = around(j, u);
            b.vertex(DVec3::new(r * c, r * s, t - 1.0), normal(j), (f64::from(j) / f64::from(u), t));
        }
    }
    let ring = |i: u32, j: u32| i * columns + j;
    let apex: Vec<u32> =
        (0..u).map(|j| b.vertex(DVec3::ZERO, normal(j), ((f64::from(j) + 0.5) / f64::from(u), 1.0))).collect();
    for i in 0..v {
        for j in 0..u {
            let (p1, p2, p3, p4) = (ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j));
            b.triangle(p1, p2, p4);
            b.triangle(p2, p3, p4);
        }
    }
    for j in 0..u {
        b.triangle(ring(v, j), ring(v, j + 1), apex[j as usize]);
    }
    if capped {
        disc(b, u, -1.0, false);
    }
}

fn cylinder(b: &mut MeshBuilder, u: u32, v: u32, bottom: bool, top: bool) {
    let columns = u + 1;
    for i in 0..=v + 1 {
        let t = f64::from(i) / f64::from(v + 1);
        for j in 0..=u {
            let (c, s) = around(j, u);
            b.vertex(DVec3::new(c, s, t - 1.0), DVec3::new(c, s, 0.0), (f64::from(j) / f64::from(u), t));
        }
    }
    let ring = |i: u32, j: u32| i * columns + j;
    for i in 0..=v {
        for j in 0..u {
            let (p1, p2, p3, p4) = (ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j));
            b.triangle(p1, p2, p4);
            b.triangle(p2, p3, p4);
        }
    }
    if bottom {
        disc(b, u, -1.0, false);
    }
    if top {
        disc(b, u, 0.0, true);
    }
}

fn cube(b: &mut MeshBuilder) {
    // The bottom square's corners at z = −½, then the same at z = +½.
    let corners = [(-0.5, -0.5), (-0.5, 0.5), (0.5, 0.5), (0.5, -0.5)];
    for z in [-0.5, 0.5] {
        for (x, y) in corners {
            b.point(DVec3::new(x, y, z));
        }
    }
    for [p, q, r, s] in [[0, 3, 7, 4], [3, 2, 6, 7], [2, 1, 5, 6], [1, 0, 4, 5], [0, 1, 2, 3], [4, 7, 6, 5]] {
        b.quad(p, q, r, s);
    }
}

fn square(b: &mut MeshBuilder) {
    for (x, y) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
        b.point(DVec3::new(x, y, 0.0));
    }
    b.quad(0, 1, 2, 3);
}

fn torus(b: &mut MeshBuilder, radius: f64, thickness: f64, u: u32, v: u32) {
    let columns = u + 1;
    for l in 0..=v {
        let (cv, sv) = around(l, v);
        for k in 0..=u {
            let (cu, su) = around(k, u);
            let ring = radius + thickness * cv;
            let p = DVec3::new(cu * ring, su * ring, thickness * sv);
            // Outward from the tube's centre line (the source scales this by the distance
            // to the axis, which turns it inward where the tube crosses the axis).
            let n = DVec3::new(cu * cv, su * cv, sv);
            b.vertex(p, n, (f64::from(k) / f64::from(u), f64::from(l) / f64::from(v)));
        }
    }
    let at = |k: u32, l: u32| l * columns + k;
    for l in 0..v {
        for k in 0..u {
            b.quad(at(k, l), at(k + 1, l), at(k + 1, l + 1), at(k, l + 1));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outward(mesh: &Mesh) -> bool {
        mesh.triangles.iter().all(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_dvec3());
            (b - a).cross(c - a).dot((a + b + c) / 3.0) > 0.0
        })
    }

    #[test]
    fn counts_match_the_formulas() {
        for shape in [
            Shape::Sphere { u_subdiv: 8, v_subdiv: 8 },
            Shape::Sphere { u_subdiv: 3, v_subdiv: 1 },
            Shape::Cone { u_subdiv: 5, v_subdiv: 0, capped: true },
            Shape::Cone { u_subdiv: 7, v_subdiv: 3, capped: false },
            Shape::Cylinder { u_subdiv: 6, v_subdiv: 0, bottom_capped: true, top_capped: false },
            Shape::Cylinder { u_subdiv: 9, v_subdiv: 4, bottom_capped: true, top_capped: true },
            Shape::Cube,
            Shape::Square,
            Shape::Torus { radius: 2.0, thickness: 0.5, u_spans: 12, v_spans: 5 },
        ] {
            let mesh = shape.mesh("s");
            assert_eq!(mesh.triangles.len() as u64, shape.triangle_count(), "{shape:?}");
            assert_eq!(mesh.triangle_slots.len(), mesh.triangles.len());
            assert_eq!(mesh.slots, vec![MaterialSlot::Inherit]);
            assert!(mesh.normals.is_empty() || mesh.normals.len() == mesh.positions.len());
            assert!(mesh.textures.iter().all(|t| t.coords.len() == mesh.positions.len()));
        }
    }

    #[test]
    fn closed_shapes_face_outward() {
        for shape in [
            Shape::Sphere { u_subdiv: 8, v_subdiv: 8 },
            Shape::Cube,
            Shape::Cylinder { u_subdiv: 6, v_subdiv: 2, bottom_capped: true, top_capped: false },
        ] {
            assert!(outward(&shape.mesh("s")), "{shape:?}");
        }
        // The cylinder and cone sides relative to their axis; their discs by normal.
        for shape in [
            Shape::Cylinder { u_subdiv: 6, v_subdiv: 2, bottom_capped: true, top_capped: true },
            Shape::Cone { u_subdiv: 6, v_subdiv: 2, capped: true },
        ] {
            let mesh = shape.mesh("s");
            for t in &mesh.triangles {
                let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_dvec3());
                let n = (b - a).cross(c - a);
                let centroid = (a + b + c) / 3.0;
                let flat = [a, b, c].iter().all(|p| p.z == a.z);
                if flat {
                    assert!(n.z * (centroid.z + 0.5) > 0.0, "{shape:?}: a cap faces inward");
                } else {
                    assert!(n.dot(DVec3::new(centroid.x, centroid.y, 0.0)) > 0.0, "{shape:?}: a side faces inward");
                }
            }
        }
    }

    #[test]
    fn limits_reduce_fine_shapes() {
        let fine = Shape::Sphere { u_subdiv: 1 << 20, v_subdiv: 1 << 20 };
        let reduced = fine.limited(MAX_TRIANGLES);
        assert!(reduced.triangle_count() <= MAX_TRIANGLES);
        assert!(reduced.triangle_count() > MAX_TRIANGLES / 4, "{reduced:?}");
        let coarse = Shape::Torus { radius: 1.0, thickness: 0.1, u_spans: 4, v_spans: 4 };
        assert_eq!(coarse.limited(MAX_TRIANGLES), coarse);
    }
}
