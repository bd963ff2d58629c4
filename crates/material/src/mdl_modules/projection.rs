//! The texture-space projections of `base::coordinate_projection` as pure functions of
//! the point and normals in the projector's space (the chosen coordinate system through
//! `projection_transform`), following the formulas of MDL's `::base` module:
//!
//! - planar (5): (x, y);
//! - cubic (1) and tri-planar (9): a planar projection on the plane of the normal's major
//!   axis: +x → (y, z), −x → (−y, z), +y → (−x, z), −y → (x, z), +z → (x, y), −z → (−x, y);
//! - spherical (2): u = r·atan2(y, x), v = r·atan2(z, √(x² + y²)) with r = |p| (the
//!   arc length on a sphere of that radius), or r = 1/π when normalized (6);
//! - cylindrical (3): on the caps (normal's major axis ±z) the planar projection, (x, y)
//!   or (−x, y); elsewhere u = ρ·atan2(y, x), v = z with ρ = √(x² + y²), or ρ = 1/π when
//!   normalized (7); the infinite forms (4, 8) have no caps.
//!
//! Before the major axis is chosen the normal is turned to point away from the
//! projector's origin, judged by the geometric normal. Coordinates are in the
//! projector's space (units of the chosen coordinate system); angles in radians.

use glam::Vec3;

/// `base::projection_mode`'s value for the planar projection (the default).
pub const PLANAR: u8 = 5;

/// Whether `mode` is a `base::projection_mode` value mira compiles (1–9).
pub fn known(mode: u8) -> bool {
    (1..=9).contains(&mode)
}

/// The shading normal `n` turned to point away from the projector's origin, judged by
/// the geometric normal `g` at the point `p` (all in the projector's space).
fn outward(p: Vec3, n: Vec3, g: Vec3) -> Vec3 {
    if p.dot(g) < (p.length() * 1e-9).min(1e-5) {
        -n
    } else {
        n
    }
}

/// The rows (u axis, v axis) of the planar map that `mode` uses at this point, or `None`
/// where the projection is curved (spherical, or a cylinder's side).
fn planar_rows(mode: u8, p: Vec3, n: Vec3, g: Vec3) -> Option<(Vec3, Vec3)> {
    let n = outward(p, n, g);
    let (ax, ay, az) = (n.x.abs(), n.y.abs(), n.z.abs());
    let z_major = az >= ax && az >= ay;
    let z_face = |neg: bool| if neg { (-Vec3::X, Vec3::Y) } else { (Vec3::X, Vec3::Y) };
    match mode {
        1 | 9 => Some(if ax >= ay && ax >= az {
            if n.x > 0.0 {
                (Vec3::Y, Vec3::Z)
            } else {
                (-Vec3::Y, Vec3::Z)
            }
        } else if ay >= ax && ay >= az {
            if n.y > 0.0 {
                (-Vec3::X, Vec3::Z)
            } else {
                (Vec3::X, Vec3::Z)
            }
        } else {
            z_face(n.z < 0.0)
        }),
        3 | 7 if z_major => Some(z_face(n.z < 0.0)),
        2 | 4 | 6 | 8 | 3 | 7 => None,
        _ => Some((Vec3::X, Vec3::Y)),
    }
}

/// The projected coordinate (u, v, 0) of the point `p` with shading normal `n` and
/// geometric normal `g`, all in the projector's space, by `base::projection_mode` `mode`.
pub fn coordinate(mode: u8, p: Vec3, n: Vec3, g: Vec3) -> Vec3 {
    if let Some((ru, rv)) = planar_rows(mode, p, n, g) {
        return Vec3::new(ru.dot(p), rv.dot(p), 0.0);
    }
    let normalized = (6..=8).contains(&mode);
    let rho = (p.x * p.x + p.y * p.y).sqrt();
    let around = if p.x != 0.0 || p.y != 0.0 { p.y.atan2(p.x) } else { 0.0 };
    if matches!(mode, 2 | 6) {
        let r = if normalized { std::f32::consts::FRAC_1_PI } else { p.length() };
        if p == Vec3::ZERO {
            return Vec3::ZERO;
        }
        Vec3::new(r * around, r * p.z.atan2(rho), 0.0)
    } else {
        let r = if normalized { std::f32::consts::FRAC_1_PI } else { rho };
        Vec3::new(r * around, p.z, 0.0)
    }
}

/// The directions, in the projector's space, along which the coordinate's u (`axis` 0)
/// or v (`axis` 1) grows at `p` (unit; for the curved projections the local east and
/// north directions, as MDL's `::base` builds them).
pub fn axis(mode: u8, p: Vec3, n: Vec3, g: Vec3, axis: u8) -> Vec3 {
    if let Some((ru, rv)) = planar_rows(mode, p, n, g) {
        return if axis == 0 { ru } else { rv };
    }
    let out = if matches!(mode, 2 | 6) { p } else { Vec3::new(p.x, p.y, 0.0) };
    let out = out.normalize_or(Vec3::X);
    let east = Vec3::Z.cross(out).normalize_or(Vec3::Y);
    if axis == 0 {
        east
    } else if matches!(mode, 2 | 6) {
        out.cross(east).normalize_or(Vec3::Z)
    } else {
        Vec3::Z
    }
}

/// The surface tangent of a projected coordinate (`axis` 0: u, 1: v) at a point with
/// shading normal `n`, from the directions `u_dir` and `v_dir` in which u and v grow
/// (all in the same space, unit): v's direction and the normal give u's tangent in the
/// surface, each turned to agree with its direction. Where the normal is (within 0.999)
/// along either direction, any frame around the normal.
pub fn surface_tangent(u_dir: Vec3, v_dir: Vec3, n: Vec3, axis: u8) -> Vec3 {
    let (tu, tv) = if n.dot(v_dir).abs() > 0.999 || n.dot(u_dir).abs() > 0.999 {
        let tv = if n.z.abs() > 0.99999 {
            Vec3::new(-n.x * n.y, 1.0 - n.y * n.y, -n.y * n.z)
        } else {
            Vec3::new(-n.x * n.z, -n.y * n.z, 1.0 - n.z * n.z)
        }
        .normalize_or(Vec3::Y);
        (tv.cross(n).normalize_or(Vec3::X), tv)
    } else {
        let mut tu = v_dir.cross(n).normalize_or(Vec3::X);
        let mut tv = n.cross(tu).normalize_or(Vec3::Y);
        if tu.dot(u_dir) < 0.0 {
            tu = -tu;
        }
        if tv.dot(v_dir) < 0.0 {
            tv = -tv;
        }
        (tu, tv)
    };
    if axis == 0 {
        tu
    } else {
        tv
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4, FRAC_PI_6};

    const TOL: f32 = 1e-5;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).abs().max_element() < TOL
    }

    /// A point on a sphere of radius `r` at longitude `phi` and latitude `theta`.
    fn on_sphere(r: f32, phi: f32, theta: f32) -> Vec3 {
        r * Vec3::new(theta.cos() * phi.cos(), theta.cos() * phi.sin(), theta.sin())
    }

    #[test]
    fn spherical_gives_arc_lengths_on_a_sphere() {
        for (r, phi, theta) in [(2.0, FRAC_PI_4, FRAC_PI_6), (0.5, -2.0, -1.0), (3.0, 3.0, 0.0)] {
            let p = on_sphere(r, phi, theta);
            let n = p.normalize();
            let uv = coordinate(2, p, n, n);
            assert!(close(uv, Vec3::new(r * phi, r * theta, 0.0)), "r {r} φ {phi} θ {theta}: {uv}");
            // Normalized: u in [−1, 1], v in [−0.5, 0.5], whatever the radius.
            let uv = coordinate(6, p, n, n);
            assert!(close(uv, Vec3::new(phi * FRAC_1_PI, theta * FRAC_1_PI, 0.0)), "{uv}");
            // The u axis is east, the v axis north: each is where its coordinate grows.
            let (eu, ev) = (axis(2, p, n, n, 0), axis(2, p, n, n, 1));
            let h = 1e-3;
            let du = coordinate(2, on_sphere(r, phi + h, theta), n, n) - coordinate(2, p, n, n);
            let dv = coordinate(2, on_sphere(r, phi, theta + h), n, n) - coordinate(2, p, n, n);
            assert!(du.x > 0.0 && eu.dot(on_sphere(r, phi + h, theta) - p) > 0.0);
            assert!(dv.y > 0.0 && ev.dot(on_sphere(r, phi, theta + h) - p) > 0.0);
            assert!(eu.dot(n).abs() < TOL && ev.dot(n).abs() < TOL && eu.dot(ev).abs() < TOL);
        }
        // The pole and the origin.
        assert!(close(coordinate(2, Vec3::new(0.0, 0.0, 2.0), Vec3::Z, Vec3::Z), Vec3::new(0.0, 2.0 * FRAC_PI_2, 0.0)));
        assert_eq!(coordinate(2, Vec3::ZERO, Vec3::Z, Vec3::Z), Vec3::ZERO);
    }

    #[test]
    fn cylindrical_wraps_the_side_and_projects_the_caps() {
        // The side of a cylinder of radius 1.5: u is the arc length, v the height.
        let p = Vec3::new(1.5 * 1.0f32.cos(), 1.5 * 1.0f32.sin(), 0.7);
        let n = Vec3::new(p.x, p.y, 0.0).normalize();
        for mode in [3, 4] {
            assert!(close(coordinate(mode, p, n, n), Vec3::new(1.5, 0.7, 0.0)), "mode {mode}");
        }
        for mode in [7, 8] {
            assert!(close(coordinate(mode, p, n, n), Vec3::new(FRAC_1_PI, 0.7, 0.0)), "mode {mode}");
        }
        // The top cap (normal +z): (x, y); the bottom cap (−z): (−x, y).
        let top = Vec3::new(0.3, -0.4, 1.0);
        assert!(close(coordinate(3, top, Vec3::Z, Vec3::Z), Vec3::new(0.3, -0.4, 0.0)));
        let bottom = Vec3::new(0.3, -0.4, -1.0);
        assert!(close(coordinate(3, bottom, -Vec3::Z, -Vec3::Z), Vec3::new(-0.3, -0.4, 0.0)));
        // A normal facing inwards (the back face) is turned outwards first.
        assert!(close(coordinate(3, bottom, Vec3::Z, Vec3::Z), Vec3::new(-0.3, -0.4, 0.0)));
        // The infinite cylinder has no caps: the top point wraps.
        let u = (-0.4f32).atan2(0.3) * 0.5;
        assert!(close(coordinate(4, top, Vec3::Z, Vec3::Z), Vec3::new(u, 1.0, 0.0)));
    }

    #[test]
    fn cubic_picks_the_face_of_the_major_axis() {
        let p = Vec3::new(0.2, -0.3, 0.4);
        let cases = [
            (Vec3::X, Vec3::new(-0.3, 0.4, 0.0)),
            (-Vec3::X, Vec3::new(0.3, 0.4, 0.0)),
            (Vec3::Y, Vec3::new(-0.2, 0.4, 0.0)),
            (-Vec3::Y, Vec3::new(0.2, 0.4, 0.0)),
            (Vec3::Z, Vec3::new(0.2, -0.3, 0.0)),
            (-Vec3::Z, Vec3::new(-0.2, -0.3, 0.0)),
        ];
        for (face, uv) in cases {
            // A point on that face of a unit box: the face's own coordinate is 1.
            let on_face = p + face * (1.0 - face.dot(p));
            let want = uv + Vec3::ZERO;
            for mode in [1, 9] {
                let got = coordinate(mode, on_face, face, face);
                assert!(close(got, want), "face {face} mode {mode}: {got} vs {want}");
                let (ru, rv) = (axis(mode, on_face, face, face, 0), axis(mode, on_face, face, face, 1));
                assert!(close(Vec3::new(ru.dot(on_face), rv.dot(on_face), 0.0), want));
            }
        }
        // Planar ignores the normal.
        assert!(close(coordinate(PLANAR, p, Vec3::X, Vec3::X), Vec3::new(0.2, -0.3, 0.0)));
    }

    #[test]
    fn surface_tangents_lie_in_the_surface_and_follow_the_axes() {
        let n = Vec3::new(1.0, 2.0, 2.0) / 3.0;
        let (u_dir, v_dir) = (Vec3::X, Vec3::Y);
        let (tu, tv) = (surface_tangent(u_dir, v_dir, n, 0), surface_tangent(u_dir, v_dir, n, 1));
        assert!(tu.dot(n).abs() < TOL && tv.dot(n).abs() < TOL && tu.dot(tv).abs() < TOL);
        assert!((tu.length() - 1.0).abs() < TOL && (tv.length() - 1.0).abs() < TOL);
        assert!(tu.dot(u_dir) > 0.0 && tv.dot(v_dir) > 0.0);
        // Normal along u's direction: still a unit frame around the normal.
        let (tu, tv) = (surface_tangent(Vec3::Z, Vec3::Y, Vec3::Z, 0), surface_tangent(Vec3::Z, Vec3::Y, Vec3::Z, 1));
        assert!(tu.dot(Vec3::Z).abs() < TOL && tv.dot(Vec3::Z).abs() < TOL && tu.dot(tv).abs() < TOL);
    }
}
