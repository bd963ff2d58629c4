//! mental ray transforms as glam matrices.
//!
//! An instance `transform` is 16 numbers read row by row; points are row vectors,
//! `p' = [x y z 1] · M`, with the translation in the last row, and the matrix maps the
//! parent's space to the instance's (world → object for top-level instances). In glam's
//! column-vector convention that matrix is `Mᵀ`, which is exactly what
//! [`DMat4::from_cols_array`] makes of the same 16 numbers.

use glam::{DMat4, DVec3};

/// The glam matrix (column vectors) of mental ray's 16 row-major numbers.
pub fn from_mi(m: &[f64]) -> Option<DMat4> {
    let m: &[f64; 16] = m.get(..16)?.try_into().ok()?;
    let mat = DMat4::from_cols_array(m);
    mat.is_finite().then_some(mat)
}

/// The inverse of an affine or projective matrix, `None` when it is singular.
pub fn inverse(m: DMat4) -> Option<DMat4> {
    let det = m.determinant();
    (det.is_finite() && det.abs() > 1e-300).then(|| m.inverse())
}

/// Transforms a direction (no translation).
pub fn direction(m: DMat4, d: DVec3) -> DVec3 {
    m.transform_vector3(d)
}

/// Transforms a point (with perspective division if the matrix has a projective part).
pub fn point(m: DMat4, p: DVec3) -> DVec3 {
    m.project_point3(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cornell_camera_instance() {
        // rows (−1 0 0 0)(0 1 0 0)(0 0 −1 0)(278 −273 −800 1): camera point = (278−x, y−273, −z−800).
        let m = from_mi(&[-1., 0., 0., 0., 0., 1., 0., 0., 0., 0., -1., 0., 278., -273., -800., 1.]).unwrap();
        assert_eq!(point(m, DVec3::new(1.0, 2.0, 3.0)), DVec3::new(277.0, -271.0, -803.0));
        let camera_to_world = inverse(m).unwrap();
        assert_eq!(point(camera_to_world, DVec3::ZERO), DVec3::new(278.0, 273.0, -800.0));
        assert_eq!(direction(camera_to_world, DVec3::NEG_Z), DVec3::Z);
    }

    #[test]
    fn singular_and_short_matrices_are_refused() {
        assert!(from_mi(&[1.0; 15]).is_none());
        assert!(inverse(DMat4::ZERO).is_none());
        assert!(from_mi(&[f64::NAN; 16]).is_none());
    }
}
