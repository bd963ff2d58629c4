//! Rays in world space, their kinds (masks against instance flags), robust origin
//! offsetting, and what the engines count and record per ray.

use glam::Vec3A;

/// A ray `origin + t·dir` for `t` in `[tmin, tmax]`, world space (`dir` need not be unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Which instances the ray may hit: instances whose flags leave out one of these
    /// bits are skipped (see [`mask`]).
    pub mask: u32,
    /// Origin.
    pub origin: Vec3A,
    /// Direction.
    pub dir: Vec3A,
    /// Nearest accepted distance.
    pub tmin: f32,
    /// Farthest accepted distance.
    pub tmax: f32,
    /// Shutter time in `[0, 1]` at which the ray sees the scene (0: shutter open; see
    /// [`crate::motion`]); 0 in scenes without motion blur.
    pub time: f32,
}

impl Ray {
    /// A ray from `origin` along `dir` with no upper limit.
    pub fn new(origin: Vec3A, dir: Vec3A) -> Ray {
        Ray { mask: u32::MAX, origin, dir, tmin: 0.0, tmax: f32::INFINITY, time: 0.0 }
    }

    /// The point at distance `t`.
    pub fn at(&self, t: f32) -> Vec3A {
        self.origin + self.dir * t
    }
}

/// Moves a surface point off the surface along its geometric normal `n`, towards the
/// side `dir` leaves to, by a few ulps (the shading model's `offset_point`, shared by both
/// engines).
#[inline]
pub fn offset_origin(p: Vec3A, n: Vec3A, dir: Vec3A) -> Vec3A {
    shader::trace::offset_point(p, n, dir)
}

/// Ray kinds, as masks tested against instance flags.
pub mod mask {
    /// Rays from the camera: instances with `visible off` are skipped.
    pub const CAMERA: u32 = 1;
    /// Shadow rays: instances that cast no shadows are skipped.
    pub const SHADOW: u32 = 2;
    /// Secondary (scattered) rays of the path tracer: instances seen by none of
    /// reflection, refraction and final gather rays are skipped.
    pub const SECONDARY: u32 = 4;
    /// Reflection rays of the classic engine.
    pub const REFLECT: u32 = 8;
    /// Refraction rays of the classic engine.
    pub const REFRACT: u32 = 16;
    /// Transparency rays of the classic engine.
    pub const TRANSPARENT: u32 = 32;
    /// Final gather rays.
    pub const FINALGATHER: u32 = 64;
}

/// Per-thread ray counts.
#[derive(Clone, Copy, Debug, Default)]
pub struct RayCounts {
    /// Closest-hit rays.
    pub rays: u64,
    /// Shadow rays.
    pub shadow_rays: u64,
}

/// What the first hit of a camera path was.
#[derive(Clone, Copy, Debug, Default)]
pub struct FirstHit {
    /// World-space hit point.
    pub point: Vec3A,
    /// World-space shading normal.
    pub normal: Vec3A,
    /// The instance's label.
    pub tag: u32,
    /// World-space motion of the hit point over the shutter interval (`state.motion`).
    pub motion: Vec3A,
}
