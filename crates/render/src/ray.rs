//! Rays in world space and robust origin offsetting.

use glam::Vec3A;

/// A ray `origin + t·dir` for `t` in `[tmin, tmax]`, world space (`dir` need not be unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Which instances the ray may hit: instances whose flags leave out one of these
    /// bits are skipped (see [`crate::integrator::mask`]).
    pub mask: u32,
    /// Origin.
    pub origin: Vec3A,
    /// Direction.
    pub dir: Vec3A,
    /// Nearest accepted distance.
    pub tmin: f32,
    /// Farthest accepted distance.
    pub tmax: f32,
}

impl Ray {
    /// A ray from `origin` along `dir` with no upper limit.
    pub fn new(origin: Vec3A, dir: Vec3A) -> Ray {
        Ray { mask: u32::MAX, origin, dir, tmin: 0.0, tmax: f32::INFINITY }
    }

    /// The point at distance `t`.
    pub fn at(&self, t: f32) -> Vec3A {
        self.origin + self.dir * t
    }
}

/// Moves a surface point off the surface along its geometric normal `n`, towards the
/// side `dir` leaves to, by a few ulps (the shading model's `offset_point`, shared by both
/// engines).
pub fn offset_origin(p: Vec3A, n: Vec3A, dir: Vec3A) -> Vec3A {
    shade::model::trace::offset_point(p, n, dir)
}
