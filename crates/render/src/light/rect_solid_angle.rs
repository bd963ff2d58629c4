//! Sampling a rectangle light uniformly in the solid angle it subtends from a shading point.
//!
//! The area-preserving parametrisation of spherical rectangles of Ureña, Fajardo and King
//! (2013, "An Area-Preserving Parametrization for Spherical Rectangles"), written from the
//! paper's formulas. Seen from a point `p`, the rectangle spans a spherical quadrilateral of
//! solid angle Ω = γ0 + γ1 + γ2 + γ3 − 2π (its internal angles γi); the parametrisation maps
//! the unit square onto it with constant Jacobian, so the density per solid angle is 1 / Ω.
//!
//! Near the light, sampling by area has a density per solid angle of dist² / (cos · A) that
//! varies across the light by large factors; uniform solid-angle sampling removes that
//! variance. Far away the two coincide and the parametrisation loses precision (Ω is the
//! difference of numbers near 2π), so [`SphericalRect::view`] declines by a deterministic
//! criterion of the point and the light alone (the light's estimated solid angle below
//! [`MIN_SOLID_ANGLE`], or edges that are not orthogonal), and the light falls back to area
//! sampling. The sampler and the density both ask it, so they agree on the density.

use std::f32::consts::PI;

use glam::{Vec2, Vec3A};

/// The estimated solid angle (steradians; area × cos / dist² at the light's centre) below
/// which a rectangle is sampled by area: there the two densities differ less, and the
/// parametrisation's setup (four arc cosines, a sine and cosine, eight square roots per
/// sample and per density) costs more than the variance it saves. Measured on the bench
/// Cornell box (docs/performance.md, speed37): sampling every point of it (≈ 0.02–0.5 sr)
/// in solid angle cut the relMSE by 4 % for 38 % more render CPU.
pub const MIN_SOLID_ANGLE: f32 = 0.25;

/// The least solid angle Ω (steradians) sampled by the parametrisation: Ω is computed as
/// γ0 + γ1 + γ2 + γ3 − 2π, whose `f32` rounding (≈ 1e-6 sr) would be a large share of a
/// smaller Ω.
const MIN_EXACT_SOLID_ANGLE: f32 = 1e-3;

/// Edges whose cosine is above this are not a rectangle: the parallelogram is sampled by
/// area.
const MAX_EDGE_COSINE: f32 = 1e-4;

/// A rectangle as seen from a point, in the rectangle's frame: what sampling it uniformly in
/// solid angle needs (world units; the frame is orthonormal).
#[derive(Clone, Copy, Debug)]
pub struct SphericalRect {
    /// The viewpoint, world space.
    origin: Vec3A,
    /// Unit vector along the first edge.
    x: Vec3A,
    /// Unit vector along the second edge.
    y: Vec3A,
    /// Unit normal of the rectangle's plane pointing away from the viewpoint.
    z: Vec3A,
    /// The rectangle's extent along `x`, from the viewpoint: [x0, x1].
    x0: f32,
    x1: f32,
    /// The rectangle's extent along `y`, from the viewpoint: [y0, y1].
    y0: f32,
    y1: f32,
    /// The plane's offset along `z` from the viewpoint (negative: `z` points to the viewpoint's side flipped).
    z0: f32,
    /// z components of the normals of the planes through the viewpoint and the edges y = y0
    /// and y = y1.
    b0: f32,
    b1: f32,
    /// 2π − γ2 − γ3: where the sampled angle starts.
    k: f32,
    /// The solid angle Ω (steradians).
    solid_angle: f32,
}

impl SphericalRect {
    /// The rectangle centred at `centre` with full edges `eu`, `ev` (orthogonal), unit normal
    /// `normal` and area `area` as seen from `p`, when it is to be sampled in solid angle:
    /// `None` (sample it by area) when its edges are not orthogonal, when it subtends an
    /// estimated solid angle below [`MIN_SOLID_ANGLE`] (this covers `p` in its plane), or
    /// when Ω does not come out positive and finite. A function of `p` and the light alone.
    #[inline]
    pub fn view(centre: Vec3A, eu: Vec3A, ev: Vec3A, normal: Vec3A, area: f32, p: Vec3A) -> Option<SphericalRect> {
        let rel = p - centre;
        let h = rel.dot(normal).abs();
        let r2 = rel.length_squared();
        // area · cos / dist² ≥ MIN (cos = h / dist), without a division.
        // (False for NaN too.)
        // (h > 0: a point in the light's plane, its centre included, is sampled by area.)
        let large = h > 0.0 && area * h >= MIN_SOLID_ANGLE * r2 * r2.sqrt();
        if !large || eu.dot(ev).abs() > MAX_EDGE_COSINE * area {
            return None;
        }
        let rect = Self::new(centre - 0.5 * (eu + ev), eu, ev, p);
        // The estimate at the centre is far above Ω for a long thin strip; below
        // MIN_EXACT_SOLID_ANGLE Ω, a difference of angles near 2π in `f32`, loses its
        // precision, so such a strip is sampled by area too.
        (rect.solid_angle >= MIN_EXACT_SOLID_ANGLE && rect.solid_angle.is_finite()).then_some(rect)
    }

    /// The rectangle with corner `corner` and orthogonal edges `eu`, `ev` seen from `p`.
    fn new(corner: Vec3A, eu: Vec3A, ev: Vec3A, p: Vec3A) -> SphericalRect {
        let (lu, lv) = (eu.length(), ev.length());
        let (x, y) = (eu / lu, ev / lv);
        let mut z = x.cross(y);
        let d = corner - p;
        let (x0, y0, mut z0) = (d.dot(x), d.dot(y), d.dot(z));
        if z0 > 0.0 {
            z0 = -z0;
            z = -z;
        }
        let (x1, y1) = (x0 + lu, y0 + lv);
        // Normals of the planes through the viewpoint and each edge, pointing inwards:
        // n0 = (0, z0, −y0)/a, n1 = (−z0, 0, x1)/b, n2 = (0, −z0, y1)/c, n3 = (z0, 0, −x0)/e.
        let z02 = z0 * z0;
        let a = (z02 + y0 * y0).sqrt();
        let b = (z02 + x1 * x1).sqrt();
        let c = (z02 + y1 * y1).sqrt();
        let e = (z02 + x0 * x0).sqrt();
        // Internal angles γi = acos(−n_i · n_{i+1}).
        let g0 = (y0 * x1 / (a * b)).clamp(-1.0, 1.0).acos();
        let g1 = (-x1 * y1 / (b * c)).clamp(-1.0, 1.0).acos();
        let g2 = (x0 * y1 / (c * e)).clamp(-1.0, 1.0).acos();
        let g3 = (-x0 * y0 / (e * a)).clamp(-1.0, 1.0).acos();
        let k = 2.0 * PI - g2 - g3;
        let solid_angle = g0 + g1 - k;
        SphericalRect { origin: p, x, y, z, x0, x1, y0, y1, z0, b0: -y0 / a, b1: y1 / c, k, solid_angle }
    }

    /// The solid angle Ω the rectangle subtends (steradians).
    #[inline]
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle
    }

    /// The density per solid angle of [`SphericalRect::point`]'s directions: 1 / Ω.
    #[inline]
    pub fn pdf(&self) -> f32 {
        1.0 / self.solid_angle
    }

    /// The point of the rectangle (world space) in the direction that `u` (uniform in
    /// [0, 1)²) picks uniformly in solid angle.
    #[inline]
    pub fn point(&self, u: Vec2) -> Vec3A {
        // The first coordinate: the angle of the sub-rectangle [x0, xu] grows linearly in u.x.
        let au = u.x * self.solid_angle + self.k;
        let (sin_au, cos_au) = au.sin_cos();
        let fu = (cos_au * self.b0 - self.b1) / sin_au;
        let cu = ((fu * fu + self.b0 * self.b0).sqrt().recip()).copysign(fu).clamp(-1.0, 1.0);
        let xu = (-(cu * self.z0) / (1.0 - cu * cu).max(1e-12).sqrt()).clamp(self.x0, self.x1);
        let xu = if xu.is_nan() { self.x1 } else { xu };
        // The second: uniform in the height of the great-circle arc over xu.
        let dist = (xu * xu + self.z0 * self.z0).sqrt();
        let h0 = self.y0 / (dist * dist + self.y0 * self.y0).sqrt();
        let h1 = self.y1 / (dist * dist + self.y1 * self.y1).sqrt();
        let hv = h0 + u.y * (h1 - h0);
        let hv2 = hv * hv;
        let yv = if hv2 < 1.0 - 1e-6 { (hv * dist / (1.0 - hv2).sqrt()).clamp(self.y0, self.y1) } else { self.y1 };
        self.origin + xu * self.x + yv * self.y + self.z0 * self.z
    }
}

#[cfg(test)]
#[path = "rect_solid_angle_tests.rs"]
mod tests;
