//! Where the path engine's rays leave a surface: off the hit point by a bound on its
//! rounding error, which the point's own ulps do not give on large triangles
//! ([`hit_error`]), so that no ray finds the surface it leaves again.

use glam::Vec3A;

use super::Surface;
use crate::ray::offset_origin;

impl Surface {
    /// The origin of a ray that leaves the hit along `dir`, moved off the surface to the
    /// side of the normal `n` (`ng` or its opposite) that `dir` leaves to.
    #[inline]
    pub(super) fn leave(&self, n: Vec3A, dir: Vec3A) -> Vec3A {
        leave_surface(self.p, self.err, n, dir)
    }
}

/// [`offset_origin`] of `p` after a step of `err` along `n`, towards the side `dir` leaves
/// to: past the hit point's rounding error (which the ulps of `p` alone do not bound), so
/// the ray cannot find the surface it leaves again — in particular not the neighbour
/// across a shared edge, whose plane the rounded point may lie behind.
#[inline]
pub(super) fn leave_surface(p: Vec3A, err: f32, n: Vec3A, dir: Vec3A) -> Vec3A {
    let n = if n.dot(dir) < 0.0 { -n } else { n };
    offset_origin(p + n * err, n, dir)
}

/// A bound on how far a hit point on the triangle `p0 p1 p2` (object space), placed by
/// `to_world`, lies off the triangle and its neighbours as the ray–triangle test sees
/// them (world units): the test and the barycentric sum round in units of the vertices'
/// coordinates (and the placement's), not of the point's own, so on a large triangle the
/// point's ulps are far too small — a point near the origin on a 100-unit mirror split in
/// two lay behind its neighbour's plane, and the mirror ray found the neighbour at
/// t ≈ 1e-5 (the reflection counted twice along the shared edge). [`HIT_ERROR_ULPS`] of
/// the largest coordinate involved.
#[inline]
pub(super) fn hit_error(p0: Vec3A, p1: Vec3A, p2: Vec3A, to_world: &glam::Affine3A) -> f32 {
    let reach = p0.abs().max(p1.abs()).max(p2.abs());
    let m = &to_world.matrix3;
    let world =
        m.x_axis.abs() * reach.x + m.y_axis.abs() * reach.y + m.z_axis.abs() * reach.z + to_world.translation.abs();
    HIT_ERROR_ULPS * f32::EPSILON * world.max_element()
}

/// The multiple of the largest coordinate's relative rounding (`f32::EPSILON`) a hit point
/// is taken to be off its surface by ([`hit_error`]): Möller–Trumbore's t rounds by a few
/// of them (measured: self-hits up to 2.5 ε × the coordinates along the ray).
const HIT_ERROR_ULPS: f32 = 16.0;
