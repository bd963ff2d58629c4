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

//!
//! Anisotropic ([`filter_ellipse`], read by
//! [`Ptex::sample_ellipse`](super::Ptex::sample_ellipse)): the pixel's footprint, a disc
//! `footprint` wide across the ray, lands on the surface's tangent plane as an ellipse
//! `footprint` wide across the tilt and `footprint / |cos θ|` along the ray's projection;
//! the inverse of the face parameterisation's Jacobian (dP/du, dP/dv: [`face_axes`])
//! carries it into face coordinates ([`conjugate_diameters`]), where its principal axes
//! give the direction and aspect of the footprint read. The widths keep that aspect and
//! the isotropic width's area (major × minor = `filter_width`², so a footprint whose
//! aspect is 1 reads exactly as the isotropic lookup does; on faces whose axes are
//! orthogonal and equally long, as a grid of square quads, they are the ellipse's own
//! widths). [`filter_widths`] gives the ellipse's bounding rectangle along u and v at the
//! same area (the axis-aligned reading, [`Ptex::sample_rect`](super::Ptex::sample_rect)),
//! which is what [`filter_ellipse`] reads where the ellipse's axes lie along u and v.

use glam::Vec3A;
use shader::State;

use super::MeshType;

/// Aspect ratios (long / short) up to 1 + this are read as isotropic (exactly
/// [`filter_width`] along both axes).
pub const ISOTROPIC_ASPECT: f32 = 1e-3;

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

/// dP/du and dP/dv (world space, scene units per face unit) of the face coordinates a Ptex
/// file of mesh type `mesh` reads at hit `s`: a triangle file's barycentric (u, v), the
/// hit triangle's edges ([`State::face_edges`]); a quad file's face (u, v), those edges
/// through the inverse of [`State::ptex_quad_jacobian`]. `None` where the state has none
/// (or they are degenerate).
#[inline]
pub fn face_axes(mesh: MeshType, s: &State) -> Option<[Vec3A; 2]> {
    let [e1, e2] = s.face_edges;
    let axes = match mesh {
        MeshType::Triangle => [e1, e2],
        MeshType::Quad => {
            // (du, dv) = M (db1, db2), M's columns (du/db1, dv/db1), (du/db2, dv/db2).
            let [a, b, c, d] = s.ptex_quad_jacobian;
            let det = a * d - b * c;
            if !(det.is_finite() && det != 0.0) {
                return None;
            }
            [(e1 * d - e2 * b) / det, (e2 * a - e1 * c) / det]
        }
    };
    let area = axes[0].cross(axes[1]).length_squared();
    (area.is_finite() && area > 0.0).then_some(axes)
}

/// The extents (full widths, face units) along u and along v of the footprint `footprint`
/// wide (scene units, across the ray) of a ray along `dir` hitting a surface of geometric
/// normal `normal`, on a face whose dP/du, dP/dv are `axes` (world space): the ellipse the
/// footprint's disc casts on the tangent plane, mapped into face coordinates (least
/// squares in the plane of the axes). Grazing hits are limited to a 1/1000 cosine. `None`
/// for degenerate axes or a footprint that is not positive.
pub fn face_extents(axes: [Vec3A; 2], dir: Vec3A, normal: Vec3A, footprint: f32) -> Option<(f32, f32)> {
    let [(xu, xv), (yu, yv)] = conjugate_diameters(axes, dir, normal, footprint)?;
    let extents = ((xu * xu + yu * yu).sqrt(), (xv * xv + yv * yv).sqrt());
    (extents.0.is_finite() && extents.1.is_finite()).then_some(extents)
}

/// Two conjugate diameters (full widths, face units (du, dv) each) of the ellipse that the
/// footprint `footprint` wide (scene units, across the ray) of a ray along `dir` casts on a
/// surface of geometric normal `normal`, in the coordinates of a face whose dP/du, dP/dv
/// are `axes`: two perpendicular diameters of the pixel's disc, each carried along the ray
/// onto the tangent plane and into face coordinates (least squares in the plane of the
/// axes). The ellipse is {x c₁ + y c₂ : c₁² + c₂² ≤ ¼} for the two diameters x, y.
/// Grazing hits are limited to a 1/1000 cosine. `None` for degenerate axes or a footprint
/// that is not positive.
pub fn conjugate_diameters(axes: [Vec3A; 2], dir: Vec3A, normal: Vec3A, footprint: f32) -> Option<[(f32, f32); 2]> {
    if !(footprint.is_finite() && footprint > 0.0) {
        return None;
    }
    let [a, b] = axes;
    let (aa, ab, bb) = (a.dot(a), a.dot(b), b.dot(b));
    let det = aa * bb - ab * ab;
    if !(det.is_finite() && det > 1e-12 * aa * bb) {
        return None;
    }
    let cos = normal.dot(dir);
    let cos = if cos.abs() < 1e-3 { 1e-3f32.copysign(cos) } else { cos };
    let x = dir.any_orthonormal_vector();
    let y = x.cross(dir);
    let face = |v: Vec3A| {
        let p = (v - dir * (v.dot(normal) / cos)) * footprint;
        let (ra, rb) = (a.dot(p), b.dot(p));
        ((bb * ra - ab * rb) / det, (aa * rb - ab * ra) / det)
    };
    Some([face(x), face(y)])
}

/// A lookup's footprint in face coordinates: an ellipse (or the rectangle a lookup reads
/// for it, [`Ptex::sample_ellipse`](super::Ptex::sample_ellipse)) `major` × `minor` wide
/// (full widths, face units), its major axis along `axis`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceEllipse {
    /// Unit direction (face coordinates du, dv) of the major axis.
    pub axis: (f32, f32),
    /// Full width along the major axis (face units).
    pub major: f32,
    /// Full width along the minor axis (face units, at most `major`).
    pub minor: f32,
}

impl FaceEllipse {
    /// A round footprint `width` wide (face units): the major axis along u.
    pub fn round(width: f32) -> Self {
        Self { axis: (1.0, 0.0), major: width, minor: width }
    }

    /// The footprint `widths` wide along u and v (face units): its major axis along the
    /// longer (u where they are equal).
    pub fn along_axes((wu, wv): (f32, f32)) -> Self {
        if wu >= wv {
            Self { axis: (1.0, 0.0), major: wu, minor: wv }
        } else {
            Self { axis: (0.0, 1.0), major: wv, minor: wu }
        }
    }
}

/// The footprint of a lookup of a Ptex file of mesh type `mesh` at hit `s`, as an ellipse
/// in face coordinates for [`Ptex::sample_ellipse`](super::Ptex::sample_ellipse): the
/// ellipse of [`conjugate_diameters`] (its axes from the eigenvectors of x xᵀ + y yᵀ, its
/// aspect their singular values' ratio) at the area of [`filter_width`]'s square (major ×
/// minor = w², the isotropic width w): a footprint diagonal to the face's axes keeps its
/// direction, where [`filter_widths`] reads its bounding rectangle's aspect. Where the
/// ellipse's axes lie along u and v (no cross term) exactly [`filter_widths`]'s widths; a
/// round footprint ([`FaceEllipse::round`], w) where the aspect is within
/// [`ISOTROPIC_ASPECT`] of 1 or the state has no face axes. `None` where [`filter_width`]
/// is (the lookup then reads level 0).
#[inline]
pub fn filter_ellipse(mesh: MeshType, s: &State) -> Option<FaceEllipse> {
    let width = filter_width(s)?;
    let footprint = if s.footprint > 0.0 { s.footprint } else { s.camera_footprint };
    let diameters = face_axes(mesh, s).and_then(|axes| conjugate_diameters(axes, s.dir, s.normal_geom, footprint));
    let Some([(xu, xv), (yu, yv)]) = diameters else { return Some(FaceEllipse::round(width)) };
    // The ellipse's matrix x xᵀ + y yᵀ = [[a, b], [b, c]].
    let (a, b, c) = (xu * xu + yu * yu, xu * xv + yu * yv, xv * xv + yv * yv);
    if b == 0.0 {
        // Axes along u and v: the extents themselves, as `filter_widths` reads them.
        let (wu, wv) = widths_at_area(width, (a.sqrt(), c.sqrt()));
        return Some(FaceEllipse::along_axes((wu, wv)));
    }
    let half = 0.5 * (a - c);
    let large = 0.5 * (a + c) + (half * half + b * b).sqrt();
    // The singular values: σ₁ = √large, σ₁ σ₂ = |det| (no cancellation at large aspects).
    let (major, area) = (large.sqrt(), (xu * yv - xv * yu).abs());
    let ratio = major * major / area;
    if !(ratio.is_finite() && ratio > 0.0) || ratio <= 1.0 + ISOTROPIC_ASPECT {
        return Some(FaceEllipse::round(width));
    }
    // The eigenvector of `large`, from the row that is the better conditioned.
    let (du, dv) = if a >= c { (large - c, b) } else { (b, large - a) };
    let norm = (du * du + dv * dv).sqrt();
    if !(norm.is_finite() && norm > 0.0) {
        return Some(FaceEllipse::round(width));
    }
    let k = ratio.sqrt();
    Some(FaceEllipse { axis: (du / norm, dv / norm), major: width * k, minor: width / k })
}

/// The filter widths (face units, along u and v) of a lookup of a Ptex file of mesh type
/// `mesh` at hit `s` for [`Ptex::sample_rect`](super::Ptex::sample_rect): the aspect of the
/// footprint's extents ([`face_extents`]) at the area of [`filter_width`]'s square —
/// (w √r, w / √r) for the isotropic width w and r = extent along u / extent along v; (w, w)
/// exactly where r is within [`ISOTROPIC_ASPECT`] of 1 or the state has no face axes.
/// `None` where [`filter_width`] is (the lookup then reads level 0).
#[inline]
pub fn filter_widths(mesh: MeshType, s: &State) -> Option<(f32, f32)> {
    let width = filter_width(s)?;
    let footprint = if s.footprint > 0.0 { s.footprint } else { s.camera_footprint };
    let extents = face_axes(mesh, s).and_then(|axes| face_extents(axes, s.dir, s.normal_geom, footprint));
    let Some(extents) = extents else { return Some((width, width)) };
    Some(widths_at_area(width, extents))
}

/// Widths along u and v of the aspect of `extents` (along u, along v) whose product is
/// `width`²: (w √r, w / √r), r = extents' ratio; (w, w) where r is within
/// [`ISOTROPIC_ASPECT`] of 1 or not a positive finite number.
#[inline]
fn widths_at_area(width: f32, (wu, wv): (f32, f32)) -> (f32, f32) {
    let ratio = wu / wv;
    if !(ratio.is_finite() && ratio > 0.0) || ratio.max(ratio.recip()) <= 1.0 + ISOTROPIC_ASPECT {
        return (width, width);
    }
    let k = ratio.sqrt();
    (width * k, width / k)
}

#[cfg(test)]
mod tests {
    use super::*;

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

    /// The extents of a 0.1-wide footprint seen 60° off the normal match the closed form
    /// (1e-5): on a right triangle with legs 2 (u, along x) and 1 (v, along y), tilted
    /// along y, u spans 0.1 / 2 and v 0.1 / cos 60°; on the skewed triangle (0, 0), (2, 0),
    /// (1, 1) (u = (x − y) / 2, v = y), tilted along x (the ellipse's half axes a = 0.1 /
    /// (2 cos 60°) along x, b = 0.05 along y), u spans √(a² + b²) and v 2 b.
    #[test]
    fn extents_match_the_closed_form() {
        let f = 0.1f32;
        let cos = 60f32.to_radians().cos();
        let sin = 60f32.to_radians().sin();
        let right = [Vec3A::new(2.0, 0.0, 0.0), Vec3A::new(0.0, 1.0, 0.0)];
        let (wu, wv) = face_extents(right, Vec3A::new(0.0, sin, -cos), Vec3A::Z, f).unwrap();
        assert!((wu - f / 2.0).abs() < 1e-5 && (wv - f / cos).abs() < 1e-5, "{wu} {wv}");
        let skewed = [Vec3A::new(2.0, 0.0, 0.0), Vec3A::new(1.0, 1.0, 0.0)];
        let (wu, wv) = face_extents(skewed, Vec3A::new(sin, 0.0, -cos), Vec3A::Z, f).unwrap();
        let (a, b) = (f / (2.0 * cos), f / 2.0);
        assert!((wu - (a * a + b * b).sqrt()).abs() < 1e-5 && (wv - 2.0 * b).abs() < 1e-5, "{wu} {wv}");
        // Head-on, a normal facing away from the ray: the same widths.
        let (wu2, wv2) = face_extents(skewed, -Vec3A::Z, -Vec3A::Z, f).unwrap();
        let (wu3, wv3) = face_extents(skewed, -Vec3A::Z, Vec3A::Z, f).unwrap();
        assert!((wu2 - wu3).abs() < 1e-7 && (wv2 - wv3).abs() < 1e-7);
        assert!((wu2 - f / 2f32.sqrt()).abs() < 1e-5 && (wv2 - f).abs() < 1e-5, "{wu2} {wv2}");
        // Degenerate axes, no footprint: none.
        assert_eq!(face_extents([right[0], right[0] * 2.0], -Vec3A::Z, Vec3A::Z, f), None);
        assert_eq!(face_extents(right, -Vec3A::Z, Vec3A::Z, 0.0), None);
    }

    /// A quad face's axes from the hit triangle's edges and d(u, v)/d(b1, b2): the triangle
    /// of quad corners 0, 1, 2 at (0, 0), (2, 0), (2, 3) (u = b1 + b2, v = b2) gives dP/du =
    /// (2, 0, 0), dP/dv = (0, 3, 0); a triangle file its edges (1e-6).
    #[test]
    fn quad_axes_invert_the_face_jacobian() {
        let s = State {
            face_edges: [Vec3A::new(2.0, 0.0, 0.0), Vec3A::new(2.0, 3.0, 0.0)],
            ptex_quad_jacobian: [1.0, 0.0, 1.0, 1.0],
            ..State::default()
        };
        let [du, dv] = face_axes(MeshType::Quad, &s).unwrap();
        assert!((du - Vec3A::new(2.0, 0.0, 0.0)).length() < 1e-6 && (dv - Vec3A::new(0.0, 3.0, 0.0)).length() < 1e-6);
        assert_eq!(face_axes(MeshType::Triangle, &s), Some(s.face_edges));
        assert_eq!(face_axes(MeshType::Quad, &State { ptex_quad_jacobian: [0.0; 4], ..s.clone() }), None);
        assert_eq!(face_axes(MeshType::Triangle, &State::default()), None);
    }

    /// Widths: head-on on a square quad face (axes 2 and 2) exactly the isotropic width
    /// along both axes (bit for bit); 75° off the normal, tilted along v, the extents
    /// themselves (f / 2 along u, f / (2 cos 75°) along v, 1e-5 relative), whose product
    /// is the isotropic width's square; no axes: the isotropic width; no footprint: none.
    #[test]
    fn widths_keep_the_isotropic_area() {
        let mut s = State {
            camera_footprint: 0.1,
            tri_area: 2.0,
            normal_geom: Vec3A::Z,
            dir: -Vec3A::Z,
            face_edges: [Vec3A::new(2.0, 0.0, 0.0), Vec3A::new(2.0, 2.0, 0.0)],
            ptex_quad_jacobian: [1.0, 0.0, 1.0, 1.0],
            ..State::default()
        };
        let iso = filter_width(&s).unwrap();
        assert_eq!(filter_widths(MeshType::Quad, &s), Some((iso, iso)));
        let (cos, sin) = (75f32.to_radians().cos(), 75f32.to_radians().sin());
        s.dir = Vec3A::new(0.0, sin, -cos);
        let iso = filter_width(&s).unwrap();
        let (wu, wv) = filter_widths(MeshType::Quad, &s).unwrap();
        assert!((wu / 0.05 - 1.0).abs() < 1e-5 && (wv / (0.05 / cos) - 1.0).abs() < 1e-5, "{wu} {wv}");
        assert!((wu * wv / (iso * iso) - 1.0).abs() < 1e-5);
        s.ptex_quad_jacobian = [0.0; 4];
        assert_eq!(filter_widths(MeshType::Quad, &s), Some((iso, iso)));
        s.camera_footprint = 0.0;
        assert_eq!(filter_widths(MeshType::Quad, &s), None);
    }
}
