//! An orthonormal frame around a normal: world ↔ local shading space (+Z = normal).

use glam::Vec3A;

/// Tangent, bitangent and normal, all unit length and orthogonal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Local +X.
    pub tangent: Vec3A,
    /// Local +Y.
    pub bitangent: Vec3A,
    /// Local +Z.
    pub normal: Vec3A,
}

impl Frame {
    /// A frame around unit normal `n` (Duff et al. 2017, "Building an orthonormal basis,
    /// revisited": continuous everywhere except on a measure-zero set, branch-free).
    #[inline]
    pub fn from_normal(n: Vec3A) -> Frame {
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let tangent = Vec3A::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let bitangent = Vec3A::new(b, sign + n.y * n.y * a, -n.y);
        Frame { tangent, bitangent, normal: n }
    }

    /// A frame around unit normal `n` whose local +X follows `tangent` (any direction not
    /// along `n`; only its part perpendicular to `n` counts): the axes of an anisotropic
    /// lobe. Falls back to [`Frame::from_normal`] when `tangent` is (nearly) along `n`.
    #[inline]
    pub fn from_normal_and_tangent(n: Vec3A, tangent: Vec3A) -> Frame {
        let perpendicular = tangent - n * n.dot(tangent);
        // Nearly along the normal (or not finite): rounding would give an arbitrary axis.
        if perpendicular.length_squared() > 1e-10 * tangent.length_squared() {
            let t = perpendicular.normalize();
            Frame { tangent: t, bitangent: n.cross(t), normal: n }
        } else {
            Frame::from_normal(n)
        }
    }

    /// World direction → local.
    #[inline]
    pub fn to_local(&self, v: Vec3A) -> Vec3A {
        Vec3A::new(v.dot(self.tangent), v.dot(self.bitangent), v.dot(self.normal))
    }

    /// Local direction → world.
    #[inline]
    pub fn to_world(&self, v: Vec3A) -> Vec3A {
        self.tangent * v.x + self.bitangent * v.y + self.normal * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_orthonormal_and_round_trip() {
        for n in [
            Vec3A::Z,
            -Vec3A::Z,
            Vec3A::X,
            Vec3A::new(0.3, -0.5, 0.81).normalize(),
            Vec3A::new(1e-8, 0.0, -1.0).normalize(),
        ] {
            let f = Frame::from_normal(n);
            for (a, b) in [(f.tangent, f.bitangent), (f.tangent, f.normal), (f.bitangent, f.normal)] {
                assert!(a.dot(b).abs() < 1e-5);
            }
            assert!((f.tangent.cross(f.bitangent) - n).length() < 1e-5, "right-handed");
            let v = Vec3A::new(0.2, 0.7, -0.4);
            assert!((f.to_world(f.to_local(v)) - v).length() < 1e-5);
        }
    }

    #[test]
    fn a_frame_with_a_tangent_puts_the_tangent_on_local_x() {
        let n = Vec3A::new(0.3, -0.5, 0.81).normalize();
        // A tangent off the tangent plane: only its perpendicular part counts.
        let t = Vec3A::new(1.0, 0.4, 0.2);
        let f = Frame::from_normal_and_tangent(n, t);
        let want = (t - n * n.dot(t)).normalize();
        assert!((f.tangent - want).length() < 1e-6);
        for (a, b) in [(f.tangent, f.bitangent), (f.tangent, f.normal), (f.bitangent, f.normal)] {
            assert!(a.dot(b).abs() < 1e-5);
        }
        assert!((f.tangent.cross(f.bitangent) - n).length() < 1e-5, "right-handed");
        assert!((f.to_local(want) - Vec3A::X).length() < 1e-6);
        // A tangent along the normal: the plain frame.
        assert_eq!(Frame::from_normal_and_tangent(n, n * 2.0), Frame::from_normal(n));
        assert_eq!(Frame::from_normal_and_tangent(n, Vec3A::splat(f32::NAN)), Frame::from_normal(n));
    }
}
