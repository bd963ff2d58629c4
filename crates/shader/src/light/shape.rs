//! The shapes of lights, world space: sampling points on them and intersecting rays with
//! them. Shared by the path integrator (physical area lights) and the mental ray light
//! loop (area light samples).

use std::f32::consts::PI;
use std::sync::Arc;

use glam::{Vec2, Vec3A};
use scene::{AreaShape, Scene};

use super::MeshShape;
use bsdf::Frame;

/// The geometry of a light, world space.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A point (or the origin of a directional light).
    Point,
    /// A parallelogram centred on the position, full edges `u` and `v`. Build it with
    /// [`Shape::rect`], which works out `area` from the edges.
    Rect {
        /// First edge.
        u: Vec3A,
        /// Second edge.
        v: Vec3A,
        /// Unit normal of the emitting side.
        normal: Vec3A,
        /// Its area, `u.cross(v).length()` (world units²): kept with the shape so that a
        /// light sample's density needs no square root.
        area: f32,
        /// The edges' dot products, kept with the shape so that a ray's hit test (asked of
        /// every ray the path engine traces) does not work them out again.
        gram: EdgeGram,
    },
    /// A disc centred on the position.
    Disc {
        /// Unit normal.
        normal: Vec3A,
        /// Radius.
        radius: f32,
    },
    /// A sphere around the position.
    Sphere {
        /// Radius.
        radius: f32,
    },
    /// A cylinder around the position along `axis` (full length).
    Cylinder {
        /// Axis.
        axis: Vec3A,
        /// Radius.
        radius: f32,
    },
    /// Triangles of an object instance (`object` area lights), world space; the light's
    /// position plays no part.
    Mesh(Arc<MeshShape>),
}

/// The dot products of a parallelogram's full edges `u` and `v` and the determinant of
/// their Gram matrix (world units², units⁴): what solving a point in the edges' basis
/// needs of the edges alone ([`EdgeGram::of`]; the same numbers, bit for bit, as working
/// them out at each hit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeGram {
    /// `u · u`.
    pub uu: f32,
    /// `u · v`.
    pub uv: f32,
    /// `v · v`.
    pub vv: f32,
    /// `uu · vv − uv²` (0 for parallel edges).
    pub det: f32,
}

impl EdgeGram {
    /// The Gram matrix of edges `u` and `v`.
    pub fn of(u: Vec3A, v: Vec3A) -> EdgeGram {
        let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
        EdgeGram { uu, uv, vv, det: uu * vv - uv * uv }
    }
}

impl Shape {
    /// The parallelogram of full edges `u`, `v` (world space) and unit normal `normal`
    /// (its emitting side), with its area.
    pub fn rect(u: Vec3A, v: Vec3A, normal: Vec3A) -> Shape {
        Shape::Rect { u, v, normal, area: u.cross(v).length(), gram: EdgeGram::of(u, v) }
    }

    /// The shape of a scene area light (`None` for object and user shapes, which have no
    /// shape of their own).
    pub fn from_area(area: &AreaShape) -> Option<Shape> {
        Some(match area {
            AreaShape::Rectangle { edge_u, edge_v, normal } => {
                Shape::rect(edge_u.as_vec3a(), edge_v.as_vec3a(), normal.as_vec3a())
            }
            AreaShape::Disc { normal, radius } => Shape::Disc { normal: normal.as_vec3a(), radius: *radius as f32 },
            AreaShape::Sphere { radius } => Shape::Sphere { radius: *radius as f32 },
            AreaShape::Cylinder { axis, radius } => Shape::Cylinder { axis: axis.as_vec3a(), radius: *radius as f32 },
            AreaShape::Object { .. } | AreaShape::User => return None,
        })
    }

    /// The shape of a scene area light, with `object` lights' triangles looked up in
    /// `scene`. User shapes have no geometry (their light shader picks the points) and
    /// give an error, as do object lights naming no instance with triangles.
    pub fn of_area(area: &AreaShape, scene: &Scene) -> Result<Shape, String> {
        match area {
            AreaShape::Object { instance } => Ok(Shape::Mesh(Arc::new(
                MeshShape::of_instance(scene, instance).map_err(|e| format!("object area light: {e}"))?,
            ))),
            AreaShape::User => Err("user area lights have no shape: their light shader picks the points".into()),
            a => Shape::from_area(a).ok_or_else(|| "no area shape".to_string()),
        }
    }

    /// Surface area (0 for a point).
    pub fn area(&self) -> f32 {
        match *self {
            Shape::Point => 0.0,
            Shape::Rect { area, .. } => area,
            Shape::Disc { radius, .. } => PI * radius * radius,
            Shape::Sphere { radius } => 4.0 * PI * radius * radius,
            Shape::Cylinder { axis, radius } => 2.0 * PI * radius * axis.length(),
            Shape::Mesh(ref m) => m.area(),
        }
    }

    /// A point on the shape centred at `center` (uniform by area for `u` uniform in
    /// [0,1)²) and the unit surface normal there (zero for a point).
    #[inline]
    pub fn point_on(&self, center: Vec3A, u: Vec2) -> (Vec3A, Vec3A) {
        match *self {
            Shape::Point => (center, Vec3A::ZERO),
            Shape::Rect { u: eu, v: ev, normal, .. } => (center + eu * (u.x - 0.5) + ev * (u.y - 0.5), normal),
            Shape::Disc { normal, radius } => {
                let f = Frame::from_normal(normal);
                let d = bsdf::concentric_disc(u) * radius;
                (center + f.tangent * d.x + f.bitangent * d.y, normal)
            }
            Shape::Sphere { radius } => {
                let z = 1.0 - 2.0 * u.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * PI * u.y;
                let n = Vec3A::new(r * phi.cos(), r * phi.sin(), z);
                (center + n * radius, n)
            }
            Shape::Cylinder { axis, radius } => {
                let f = Frame::from_normal(axis.normalize_or(Vec3A::Z));
                let phi = 2.0 * PI * u.y;
                let n = f.tangent * phi.cos() + f.bitangent * phi.sin();
                (center + axis * (u.x - 0.5) + n * radius, n)
            }
            Shape::Mesh(ref m) => m.point_on(u),
        }
    }

    /// The unit normal of the shape (centred at `center`) at its surface point `q`.
    pub fn normal_at(&self, center: Vec3A, q: Vec3A) -> Vec3A {
        match *self {
            Shape::Rect { normal, .. } | Shape::Disc { normal, .. } => normal,
            Shape::Sphere { .. } => (q - center).normalize_or_zero(),
            Shape::Cylinder { axis, .. } => {
                let a = axis.normalize_or(Vec3A::Z);
                let r = q - center;
                (r - a * r.dot(a)).normalize_or_zero()
            }
            Shape::Mesh(ref m) => m.normal_at(q),
            Shape::Point => Vec3A::ZERO,
        }
    }

    /// Where the ray `origin + t·dir` (t in `(tmin, tmax)`) meets the shape centred at
    /// `center`: the distance and whether the ray arrives at the front (the side the normal
    /// faces; the outside of a sphere). Cylinders and points are never hit.
    #[inline]
    pub fn intersect(&self, center: Vec3A, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> Option<(f32, bool)> {
        let plane = |n: Vec3A| {
            let denom = dir.dot(n);
            if denom == 0.0 {
                return None;
            }
            let t = (center - origin).dot(n) / denom;
            (t > tmin && t < tmax).then_some((t, denom))
        };
        match *self {
            Shape::Mesh(ref m) => m.intersect(origin, dir, tmin, tmax),
            Shape::Rect { u, v, normal, gram, .. } => {
                let (t, denom) = plane(normal)?;
                let q = origin + dir * t - center;
                // The edges need not be orthogonal: solve in the parallelogram's own basis.
                let EdgeGram { uu, uv, vv, det } = gram;
                let (a, b) = if det.abs() > 0.0 {
                    ((q.dot(u) * vv - q.dot(v) * uv) / det, (q.dot(v) * uu - q.dot(u) * uv) / det)
                } else {
                    (q.dot(u) / uu, q.dot(v) / vv)
                };
                if a.abs() > 0.5 || b.abs() > 0.5 {
                    return None;
                }
                Some((t, denom < 0.0))
            }
            Shape::Disc { normal, radius } => {
                let (t, denom) = plane(normal)?;
                if (origin + dir * t - center).length_squared() > radius * radius {
                    return None;
                }
                Some((t, denom < 0.0))
            }
            Shape::Sphere { radius } => {
                let oc = origin - center;
                let a = dir.length_squared();
                let b = oc.dot(dir);
                let cc = oc.length_squared() - radius * radius;
                let disc = b * b - a * cc;
                if disc < 0.0 {
                    return None;
                }
                let sq = disc.sqrt();
                let t0 = (-b - sq) / a;
                let t1 = (-b + sq) / a;
                let t = if t0 > tmin && t0 < tmax {
                    t0
                } else if t1 > tmin && t1 < tmax {
                    t1
                } else {
                    return None;
                };
                Some((t, cc > 0.0))
            }
            Shape::Cylinder { .. } | Shape::Point => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rectangle keeps the area its edges give, `u.cross(v).length()`, bit for bit (what
    /// light samples' densities used before the shape kept it), and the edges' dot products
    /// and Gram determinant as the hit test worked them out before the shape kept them,
    /// for edges of many lengths and angles, and so does a rectangle carried by a rigid
    /// motion with a scale ([`super::super::ShadingLight::moved`] rebuilds it from its moved
    /// edges).
    #[test]
    fn rectangles_keep_their_edges_area_bit_for_bit() {
        let gram_bits = |u: Vec3A, v: Vec3A| {
            let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
            [uu, uv, vv, uu * vv - uv * uv].map(f32::to_bits)
        };
        let kept_bits = |g: EdgeGram| [g.uu, g.uv, g.vv, g.det].map(f32::to_bits);
        let mut z = 0x5eed_u32;
        let mut r = move || {
            z ^= z << 13;
            z ^= z >> 17;
            z ^= z << 5;
            (z >> 8) as f32 / (1u32 << 24) as f32
        };
        for _ in 0..1000 {
            let scale = 10f32.powf(6.0 * r() - 3.0);
            let u = Vec3A::new(r() - 0.5, r() - 0.5, r() - 0.5) * scale;
            let v = Vec3A::new(r() - 0.5, r() - 0.5, r() - 0.5) * scale * (0.1 + r());
            let n = u.cross(v).normalize_or(Vec3A::Z);
            let s = Shape::rect(u, v, n);
            assert_eq!(s.area().to_bits(), u.cross(v).length().to_bits(), "{u} {v}");
            let Shape::Rect { gram, .. } = s else { panic!("a rectangle") };
            assert_eq!(kept_bits(gram), gram_bits(u, v), "{u} {v}");
            let by = glam::Affine3A::from_scale_rotation_translation(
                glam::Vec3::splat(0.5 + 2.0 * r()),
                glam::Quat::from_rotation_arc(glam::Vec3::Z, glam::Vec3::new(r() - 0.5, r(), 0.3).normalize()),
                glam::Vec3::new(r(), r(), r()),
            );
            let light = super::super::ShadingLight {
                name: "rect".into(),
                shader: None,
                kind: scene::LightKind::Point,
                origin: Vec3A::ZERO,
                direction: -Vec3A::Z,
                spread: 0.0,
                shape: Some(s),
                user: false,
                samples: (1, 1),
                low: None,
                visible: true,
                exponent: 2.0,
                to_local: glam::Mat3A::IDENTITY,
                profile: None,
                photons: None,
            }
            .moved(by);
            let Some(Shape::Rect { u: mu, v: mv, area, gram, .. }) = light.shape else { panic!("a rectangle") };
            assert_eq!(area.to_bits(), mu.cross(mv).length().to_bits(), "{mu} {mv}");
            assert_eq!(kept_bits(gram), gram_bits(mu, mv), "{mu} {mv}");
            assert_eq!(mu, by.transform_vector3a(u));
        }
    }

    #[test]
    fn sampled_points_lie_on_the_surface_and_are_hit_by_rays_through_them() {
        let c = Vec3A::new(1.0, 2.0, 3.0);
        let shapes = [
            Shape::rect(Vec3A::X * 2.0, Vec3A::new(0.5, 1.0, 0.0), Vec3A::Z),
            Shape::Disc { normal: Vec3A::Z, radius: 0.7 },
            Shape::Sphere { radius: 0.5 },
        ];
        for s in shapes {
            for k in 0..64 {
                let u = Vec2::new((k % 8) as f32 / 8.0 + 0.03, (k / 8) as f32 / 8.0 + 0.05);
                let (q, n) = s.point_on(c, u);
                assert!((s.normal_at(c, q) - n).length() < 1e-5);
                let origin = q + n * 3.0 + Vec3A::new(0.01, 0.02, 0.0);
                let dir = (q - origin).normalize();
                let (t, front) = s.intersect(c, origin, dir, 0.0, f32::INFINITY).expect("hit");
                assert!(front, "{s:?}");
                assert!((origin + dir * t - q).length() < 1e-4, "{s:?}");
            }
        }
    }
}
