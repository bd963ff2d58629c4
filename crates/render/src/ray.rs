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

/// Moves a surface point off the surface along its geometric normal `n` (towards the side
/// `dir` leaves to), by a few ulps of the coordinates: no fixed epsilon, so it works at
/// every scene scale (Wächter and Binder, "A fast and robust method for avoiding
/// self-intersection", Ray Tracing Gems, 2019).
pub fn offset_origin(p: Vec3A, n: Vec3A, dir: Vec3A) -> Vec3A {
    const ORIGIN: f32 = 1.0 / 32.0;
    const FLOAT_SCALE: f32 = 1.0 / 65536.0;
    const INT_SCALE: f32 = 256.0;
    let n = if n.dot(dir) < 0.0 { -n } else { n };
    let of_i = [(INT_SCALE * n.x) as i32, (INT_SCALE * n.y) as i32, (INT_SCALE * n.z) as i32];
    let step = |p: f32, o: i32| {
        let bits = p.to_bits() as i32;
        f32::from_bits((bits + if p < 0.0 { -o } else { o }) as u32)
    };
    let p_i = Vec3A::new(step(p.x, of_i[0]), step(p.y, of_i[1]), step(p.z, of_i[2]));
    Vec3A::new(
        if p.x.abs() < ORIGIN { p.x + FLOAT_SCALE * n.x } else { p_i.x },
        if p.y.abs() < ORIGIN { p.y + FLOAT_SCALE * n.y } else { p_i.y },
        if p.z.abs() < ORIGIN { p.z + FLOAT_SCALE * n.z } else { p_i.z },
    )
}
