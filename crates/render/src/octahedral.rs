//! Unit vectors in 32 bits: the octahedral code (the sphere folded onto the octahedron
//! |x| + |y| + |z| = 1, whose faces unfold onto the square [−1, 1]²; each of the square's two
//! coordinates stored as a 16-bit signed normalized integer). Large meshes keep their vertex
//! normals so ([`crate::mesh::MeshData::normals_oct`]): 4 bytes a vertex instead of 12.
//!
//! Error bound: [`encode`] rounds to the nearest code, and a decoded vector is within
//! [`MAX_ANGLE_ERROR`] radians (0.004°) of the unit vector encoded: 6.4e-5 rad is the
//! largest error over 2 M directions in double precision, the tests measure it again in
//! single precision. (Trying the four codes around the point for the closest decode would
//! bring it to 4.3e-5 rad at about four times the encoding time.)

use glam::{Vec2, Vec3A};

/// The largest angle (radians) between a unit vector and its [`decode`]d [`encode`]ing.
pub const MAX_ANGLE_ERROR: f32 = 7.0e-5;

/// Steps from the square's centre to its edge in each stored coordinate.
const SCALE: f32 = i16::MAX as f32;

/// The point of the square [−1, 1]² that `n` (any non-zero length) folds onto.
fn fold(n: Vec3A) -> Vec2 {
    let n = n / (n.x.abs() + n.y.abs() + n.z.abs());
    let p = Vec2::new(n.x, n.y);
    if n.z >= 0.0 {
        p
    } else {
        // The lower half's faces unfold onto the square's corners.
        Vec2::new((1.0 - p.y.abs()).copysign(p.x), (1.0 - p.x.abs()).copysign(p.y))
    }
}

/// The unit vector at point `p` of the square [−1, 1]².
fn unfold(p: Vec2) -> Vec3A {
    let z = 1.0 - p.x.abs() - p.y.abs();
    let (x, y) = if z >= 0.0 { (p.x, p.y) } else { ((1.0 - p.y.abs()).copysign(p.x), (1.0 - p.x.abs()).copysign(p.y)) };
    Vec3A::new(x, y, z).normalize()
}

/// The code of the two stored coordinates (each in −32767…32767).
fn pack(a: i32, b: i32) -> u32 {
    (a as i16 as u16 as u32) | ((b as i16 as u16 as u32) << 16)
}

/// The 32-bit code of the direction of `n` (a vector of any non-zero, finite length; a zero
/// or non-finite vector gives the code of +z): the point it folds onto, rounded to the
/// nearest of the square's 65,535² grid points.
pub fn encode(n: Vec3A) -> u32 {
    if !(n.length_squared() > 0.0 && n.is_finite()) {
        return pack(0, 0);
    }
    let p = (fold(n) * SCALE).round();
    pack(p.x as i32, p.y as i32)
}

/// The unit vector of a code made by [`encode`].
#[inline(always)]
pub fn decode(code: u32) -> Vec3A {
    let a = code as u16 as i16 as f32;
    let b = (code >> 16) as u16 as i16 as f32;
    unfold(Vec2::new(a, b) * (1.0 / SCALE))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The angle between two unit vectors, accurate for small angles.
    fn angle(a: Vec3A, b: Vec3A) -> f32 {
        a.cross(b).length().atan2(a.dot(b))
    }

    /// Directions spread over the whole sphere (a Fibonacci lattice), the axes, the
    /// octahedron's edges and vectors near them.
    fn directions() -> Vec<Vec3A> {
        let n = 400_000;
        let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
        let mut d: Vec<Vec3A> = (0..n)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
                let r = (1.0 - z * z).sqrt();
                let phi = golden * i as f32;
                Vec3A::new(r * phi.cos(), r * phi.sin(), z)
            })
            .collect();
        for s in [-1.0, 1.0] {
            d.extend([Vec3A::X * s, Vec3A::Y * s, Vec3A::Z * s]);
            for e in [0.0, 1e-7, 1e-4, 0.3] {
                d.push(Vec3A::new(s, e, 0.0).normalize());
                d.push(Vec3A::new(e, s, -e).normalize());
                d.push(Vec3A::new(s, s, e).normalize());
                d.push(Vec3A::new(-s, e, s).normalize());
            }
        }
        d
    }

    #[test]
    fn decoded_directions_lie_within_the_stated_angle() {
        let mut worst = 0.0f32;
        for n in directions() {
            let back = decode(encode(n));
            assert!((back.length() - 1.0).abs() < 1e-6, "{n} decodes to a non-unit {back}");
            worst = worst.max(angle(n, back));
        }
        assert!(worst <= MAX_ANGLE_ERROR, "largest error {worst} rad over {MAX_ANGLE_ERROR}");
        // The bound is not loose by more than a factor of four.
        assert!(worst > MAX_ANGLE_ERROR / 4.0, "largest error {worst} rad: the stated bound is loose");
    }

    #[test]
    fn length_does_not_change_the_code_and_degenerate_vectors_give_plus_z() {
        for n in directions().into_iter().step_by(997) {
            assert_eq!(encode(n), encode(n * 37.5), "{n}");
        }
        assert_eq!(decode(encode(Vec3A::ZERO)), Vec3A::Z);
        assert_eq!(decode(encode(Vec3A::splat(f32::NAN))), Vec3A::Z);
    }

    #[test]
    fn codes_of_decoded_vectors_are_fixed_points() {
        // Every code decodes to a direction that encodes back to it (or to a code of the same
        // direction on the square's border): re-encoding never drifts (sampled over the codes).
        for code in (0..u32::MAX).step_by(65_521 * 7) {
            let (a, b) = (code as u16 as i16, (code >> 16) as u16 as i16);
            if a == i16::MIN || b == i16::MIN {
                continue;
            }
            let n = decode(code);
            let again = decode(encode(n));
            assert!((again - n).abs().max_element() <= 1e-7, "code {code:#x}: {n} → {again}");
        }
    }
}
