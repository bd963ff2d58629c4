//! The filter width of a Ptex lookup at a hit ([`filter_width`]): the ray's footprint
//! (scene units) in face units, where a face is 1 across.
//!
//! The footprint is the classic engine's `State::footprint` (the pixel's width carried
//! along the ray), or the path engine's `State::camera_footprint` (pbrt-v4's camera-ray
//! approximation). Isotropic: the footprint is taken as a square on the surface of the
//! same area as the pixel's projection, `footprint / √|cos θ|` a side (θ between the ray
//! and the geometric normal, |cos θ| at least 1/1000), and the face's size in scene units
//! is `√(2 A)` for a hit triangle of area `A`: a triangle-mesh face (barycentric u, v each
//! spanning one such side, the face's (u, v) area ½) or half of a quad (the quad's area
//! 2 A, exact for a planar parallelogram). For a quad-mesh file's other faces the render
//! hands in half the face's own area as `A` (`render`'s tracer): a lone triangle's
//! sub-quads A/6 of its triangle's, an n-gon's sub-quads half the polygon's area over n
//! (scaled from object to world space by the hit triangle), a displaced mesh's faces its
//! original triangles' — so a sub-quad's width is its own, not the triangle's.

use shader::State;

/// The filter width (face units) of a Ptex lookup at hit `s`; `None` where the state has
/// no footprint or no triangle area (the lookup then reads level 0).
#[inline]
pub fn filter_width(s: &State) -> Option<f32> {
    let footprint = if s.footprint > 0.0 { s.footprint } else { s.camera_footprint };
    if !(footprint.is_finite() && footprint > 0.0 && s.tri_area.is_finite() && s.tri_area > 0.0) {
        return None;
    }
    let cos = s.normal_geom.dot(s.dir).abs().max(1e-3);
    let width = footprint / (cos * 2.0 * s.tri_area).sqrt();
    width.is_finite().then_some(width)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    /// A footprint of 0.1 on a triangle of area 2 (face side 2) seen head-on is 0.05 face
    /// units; at 60° from the normal √2 times that; the path engine's footprint is used
    /// where the classic one is 0; none without a footprint or an area (1e-6).
    #[test]
    fn footprint_in_face_units() {
        let mut s = State { footprint: 0.1, tri_area: 2.0, normal_geom: Vec3A::Z, dir: -Vec3A::Z, ..State::default() };
        assert!((filter_width(&s).unwrap() - 0.05).abs() < 1e-6);
        s.dir = Vec3A::new(0.75f32.sqrt(), 0.0, -0.5);
        assert!((filter_width(&s).unwrap() - 0.05 * 2f32.sqrt()).abs() < 1e-6);
        s.dir = -Vec3A::Z;
        s.footprint = 0.0;
        assert_eq!(filter_width(&s), None);
        s.camera_footprint = 0.4;
        assert!((filter_width(&s).unwrap() - 0.2).abs() < 1e-6);
        s.tri_area = 0.0;
        assert_eq!(filter_width(&s), None);
    }
}
