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
//! difference of numbers near 2π), so [`RectFrame::view`] declines by a deterministic
//! criterion of the point and the light alone (the light's estimated solid angle below
//! [`MIN_SOLID_ANGLE`]), and the light falls back to area sampling; so does a light whose
//! edges are not orthogonal (it has no [`RectFrame`]). The sampler and the density both ask
//! it, so they agree on the density. What depends on the light alone (its frame, edge
//! lengths, the orthogonality test) is worked out once, when the light is built.

use std::f32::consts::PI;

use glam::{Vec2, Vec3A};
use shader::light::Shape;

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

/// What sampling a rectangle light in solid angle needs of the light alone, worked out once
/// when the light is built ([`RectFrame::of`]): its orthonormal frame, edge lengths, normal
/// and area (world units). Only rectangles with orthogonal edges have one; a skewed
/// parallelogram is always sampled by area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RectFrame {
    /// Half the sum of the full edges: the first corner is the centre minus this.
    half_diagonal: Vec3A,
    /// Unit vector along the first edge.
    x: Vec3A,
    /// Unit vector along the second edge.
    y: Vec3A,
    /// `x × y`.
    z: Vec3A,
    /// Unit normal of the shape (either side: the test takes |cos|).
    normal: Vec3A,
    /// Lengths of the first and second edges.
    lu: f32,
    lv: f32,
    /// The rectangle's area (world units²).
    area: f32,
    /// The squared distance from the centre beyond which the rectangle never looks large:
    /// area × cos / dist² ≥ [`MIN_SOLID_ANGLE`] needs dist² ≤ area × |normal| / MIN; 1 %
    /// more, a margin far above the test's `f32` rounding (≈ 1e-6 relative), so that this
    /// quick test never changes the decision.
    reach2: f32,
}

impl RectFrame {
    /// The frame of `shape` when it is a rectangle whose edges are orthogonal (their cosine
    /// at most `MAX_EDGE_COSINE`); `None` for any other shape.
    pub fn of(shape: &Shape) -> Option<RectFrame> {
        let Shape::Rect { u: eu, v: ev, normal, area, .. } = *shape else { return None };
        if eu.dot(ev).abs() > MAX_EDGE_COSINE * area {
            return None;
        }
        let (lu, lv) = (eu.length(), ev.length());
        let (x, y) = (eu / lu, ev / lv);
        let reach2 = 1.01 * area * normal.length() / MIN_SOLID_ANGLE;
        Some(RectFrame { half_diagonal: 0.5 * (eu + ev), x, y, z: x.cross(y), normal, lu, lv, area, reach2 })
    }

    /// Whether the rectangle centred at `centre` looks large from `p`: its estimated solid
    /// angle, area × cos / dist² at its centre, at least [`MIN_SOLID_ANGLE`] (false for a
    /// point in its plane, its centre included, and for NaN). The per-point half of the
    /// decision that [`RectFrame::view`] makes; the sampler and the density both ask it.
    #[inline(always)]
    pub fn looks_large(&self, centre: Vec3A, p: Vec3A) -> bool {
        let rel = p - centre;
        let r2 = rel.length_squared();
        // Far away (most points of a room lit by a small light): no more.
        if r2 > self.reach2 {
            return false;
        }
        let h = rel.dot(self.normal).abs();
        // area · cos / dist² ≥ MIN (cos = h / dist), without a division.
        h > 0.0 && self.area * h >= MIN_SOLID_ANGLE * r2 * r2.sqrt()
    }

    /// The rectangle centred at `centre` as seen from `p`, when it is to be sampled in
    /// solid angle: `None` (sample it by area) when it does not [`RectFrame::looks_large`]
    /// from `p`, or when Ω does not come out at least `MIN_EXACT_SOLID_ANGLE` and finite. A
    /// function of `p` and the light alone.
    #[inline]
    pub fn view(&self, centre: Vec3A, p: Vec3A) -> Option<SphericalRect> {
        if !self.looks_large(centre, p) {
            return None;
        }
        self.view_large(centre, p)
    }

    /// [`RectFrame::view`] for a point from which the rectangle [`RectFrame::looks_large`]:
    /// the parametrisation's setup, out of line (most points of a scene with small lights
    /// never get here).
    #[inline(never)]
    pub fn view_large(&self, centre: Vec3A, p: Vec3A) -> Option<SphericalRect> {
        let rect = SphericalRect::new(self, centre - self.half_diagonal, p);
        // The estimate at the centre is far above Ω for a long thin strip; below
        // MIN_EXACT_SOLID_ANGLE Ω, a difference of angles near 2π in `f32`, loses its
        // precision, so such a strip is sampled by area too.
        (rect.solid_angle >= MIN_EXACT_SOLID_ANGLE && rect.solid_angle.is_finite()).then_some(rect)
    }
}

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
    /// The rectangle of frame `frame` with first corner `corner` seen from `p`.
    fn new(frame: &RectFrame, corner: Vec3A, p: Vec3A) -> SphericalRect {
        let (lu, lv) = (frame.lu, frame.lv);
        let (x, y, mut z) = (frame.x, frame.y, frame.z);
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
