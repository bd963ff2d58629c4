//! Where the path engine's rays leave a surface: off the hit point by a bound on its
//! rounding error, which the point's own ulps do not give on large triangles
//! ([`hit_error`], shared with the classic engine's shaders), so that no ray finds the
//! surface it leaves again.

use glam::Vec3A;

use super::Surface;

pub(super) use shader::trace::{hit_error, leave_point as leave_surface};

impl Surface {
    /// The origin of a ray that leaves the hit along `dir`, moved off the surface to the
    /// side of the normal `n` (`ng` or its opposite) that `dir` leaves to.
    #[inline]
    pub(super) fn leave(&self, n: Vec3A, dir: Vec3A) -> Vec3A {
        leave_surface(self.p, self.err, n, dir)
    }
}
