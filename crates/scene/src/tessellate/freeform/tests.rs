//! Free-form tessellation against closed forms: flat Bézier quads, rational circles,
//! cylinder and sphere areas, a trimmed hole, texture coordinates.

use std::f64::consts::{FRAC_1_SQRT_2, PI};

use super::*;
use crate::tessellate::tessellate;

/// The object of a one-object `.mi` text.
fn object(text: &str) -> mi::ast::Object {
    let parsed = mi::parse_str("t.mi", text);
    assert!(parsed.diagnostics.list.iter().all(|d| !d.is_error()), "{:?}", parsed.diagnostics);
    match parsed.items.into_iter().next() {
        Some(mi::ast::Item::Object(o)) => o,
        other => panic!("not an object: {other:?}"),
    }
}

fn mesh_of(text: &str) -> (Mesh, Vec<Diagnostic>) {
    let mut diags = Vec::new();
    let g = tessellate(&object(text), &mut diags);
    (g.mesh, diags)
}

/// The nine control points (x, y, weight) of the unit circle as a rational quadratic
/// B-spline, and its knots.
fn circle() -> (Vec<(f64, f64, f64)>, &'static str) {
    let w = FRAC_1_SQRT_2;
    let pts = vec![
        (1.0, 0.0, 1.0),
        (1.0, 1.0, w),
        (0.0, 1.0, 1.0),
        (-1.0, 1.0, w),
        (-1.0, 0.0, 1.0),
        (-1.0, -1.0, w),
        (0.0, -1.0, 1.0),
        (1.0, -1.0, w),
        (1.0, 0.0, 1.0),
    ];
    (pts, "0. 0. 0. 1. 1. 2. 2. 3. 3. 4. 4. 4.")
}

/// A cylinder of radius 1 and height 1 around z: u the circle, v linear in z.
fn cylinder(approx: &str) -> String {
    let (pts, knots) = circle();
    let mut vectors = String::new();
    let mut refs = String::new();
    for z in [0.0, 1.0] {
        for (x, y, _) in &pts {
            vectors += &format!("{x} {y} {z}\n");
        }
    }
    for k in 0..18 {
        refs += &format!("{k} w {} ", pts[k % 9].2);
    }
    let verts: String = (0..18).map(|k| format!("v {k} ")).collect();
    format!(
        "object \"cyl\" basis \"b2\" rational bspline 2 basis \"b1\" bspline 1 group\n{vectors}{verts}\n\
         surface \"s\" \"m\" \"b2\" 0 4 {knots} \"b1\" 0 1 0. 0. 1. 1. {refs}\n{approx}\nend group end object"
    )
}

/// A unit sphere: u the circle, v a half circle from the south to the north pole.
fn sphere(approx: &str) -> String {
    let (pts, knots) = circle();
    let w = FRAC_1_SQRT_2;
    let meridian = [(0.0, -1.0, 1.0), (1.0, -1.0, w), (1.0, 0.0, 1.0), (1.0, 1.0, w), (0.0, 1.0, 1.0)];
    let mut vectors = String::new();
    let mut refs = String::new();
    for (r, z, wv) in meridian {
        for (x, y, wu) in &pts {
            vectors += &format!("{} {} {z}\n", x * r, y * r);
            refs += &format!("w {} ", wu * wv);
        }
    }
    let refs: String = refs.split("w ").skip(1).enumerate().map(|(k, w)| format!("{k} w {w}")).collect();
    let verts: String = (0..45).map(|k| format!("v {k} ")).collect();
    format!(
        "object \"ball\" basis \"b2\" rational bspline 2 group\n{vectors}{verts}\n\
         surface \"s\" \"\" \"b2\" 0 4 {knots} \"b2\" 0 2 0. 0. 0. 1. 1. 2. 2. 2. {refs}\n{approx}\nend group end object"
    )
}

#[test]
fn bilinear_bezier_patch_is_the_flat_quad() {
    let text = "object \"q\" basis \"lin\" bezier 1 group\n\
        0 0 0  2 0 0  0 1 0  2 1 0.5\n v 0 v 1 v 2 v 3\n\
        surface \"s\" \"m\" \"lin\" 0 1 0. 1. \"lin\" 0 1 0. 1. 0 1 2 3\n\
        approximate surface regular parametric 4 3 \"s\"\nend group end object";
    let (mesh, diags) = mesh_of(text);
    assert!(diags.is_empty(), "{diags:?}");
    assert_eq!(mesh.triangles.len(), 4 * 3 * 2);
    assert_eq!(mesh.positions.len(), 5 * 4);
    let corners = [DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0), DVec3::new(2.0, 1.0, 0.5)];
    for (p, t) in mesh.positions.iter().zip(&mesh.textures[0].coords) {
        let (u, v) = (f64::from(t.x), f64::from(t.y));
        let expect =
            (corners[0] * (1.0 - u) + corners[1] * u) * (1.0 - v) + (corners[2] * (1.0 - u) + corners[3] * u) * v;
        assert!(p.as_dvec3().distance(expect) < 1e-6, "{p} vs {expect} at ({u}, {v})");
    }
    // The front faces +z (∂P/∂u × ∂P/∂v), and the triangles wind the same way.
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        assert!((b - a).cross(c - a).z > 0.0);
        assert!(mesh.normals[t[0] as usize].z > 0.0);
    }
    assert_eq!(mesh.slots, vec![MaterialSlot::Named("m".into())]);
}

#[test]
fn rational_bspline_circle_has_radius_one() {
    let text = cylinder("");
    let o = object(&text);
    let mi::ast::Geometry::Group(g) = &o.geometry[0] else { panic!() };
    let GroupItem::Surface(s) = &g.items[0] else { panic!() };
    let f = Context::new(&o.bases, g).surface(s).expect("builds");
    let mut worst = 0.0f64;
    for k in 0..=400 {
        let u = 4.0 * k as f64 / 400.0;
        let at = f.patch.eval(u, 0.5);
        worst = worst.max((at.p.truncate().length() - 1.0).abs());
        // The tangent is perpendicular to the radius.
        assert!(at.du.truncate().normalize().dot(at.p.truncate()).abs() < 1e-9);
        // The normal points outwards.
        assert!(f.patch.normal(u, 0.5, &at).dot(at.p.with_z(0.0)) > 0.999);
    }
    assert!(worst < 1e-6, "radius error {worst}");
    // The quarter points lie where the circle passes through its control points.
    assert!(f.patch.eval(1.0, 0.0).p.distance(DVec3::new(0.0, 1.0, 0.0)) < 1e-12);
}

#[test]
fn cylinder_and_sphere_areas_converge() {
    let mut last = f64::INFINITY;
    for n in [8, 16, 32, 64] {
        let (mesh, diags) = mesh_of(&cylinder(&format!("approximate surface regular parametric {n} 1 \"s\"")));
        assert!(diags.is_empty(), "{diags:?}");
        let err = (mesh.area() - 2.0 * PI).abs() / (2.0 * PI);
        assert!(err < last, "n {n}: {err} after {last}");
        last = err;
    }
    assert!(last < 2e-3, "cylinder area error {last}");
    let mut last = f64::INFINITY;
    for n in [4, 8, 16, 32] {
        let (mesh, diags) = mesh_of(&sphere(&format!("approximate surface parametric {n} {n} \"s\"")));
        assert!(diags.is_empty(), "{diags:?}");
        let err = (mesh.area() - 4.0 * PI).abs() / (4.0 * PI);
        assert!(err < last, "n {n}: {err} after {last}");
        last = err;
        // Every vertex on the unit sphere, every normal radial (the poles included).
        for (p, nrm) in mesh.positions.iter().zip(&mesh.normals) {
            assert!((p.length() - 1.0).abs() < 1e-5, "{p}");
            assert!(nrm.dot(p.normalize()) > 0.999, "normal {nrm} at {p}");
        }
    }
    assert!(last < 1e-3, "sphere area error {last}");
}

#[test]
fn length_and_angle_criteria_pick_grids_that_meet_them() {
    // Angle 5°: the circle's 360° of turn need at least 72 parts in u; v is straight.
    let (mesh, _) = mesh_of(&cylinder("approximate surface angle 5 0 8 \"s\""));
    let ring = mesh.positions.iter().filter(|p| p.z == 0.0).count();
    assert!((73..=80).contains(&ring), "{ring} vertices around");
    // Length 0.1 on the height 1: 10 parts in v.
    let (mesh, _) = mesh_of(&cylinder("approximate surface length 0.1 0 8 \"s\""));
    let mut zs: Vec<f32> = mesh.positions.iter().map(|p| p.z).collect();
    zs.sort_by(f32::total_cmp);
    zs.dedup();
    assert_eq!(zs.len(), 11);
    let edge = mesh.triangles.iter().flat_map(|t| {
        let p = t.map(|i| mesh.positions[i as usize]);
        [(p[0] - p[1]).length(), (p[1] - p[2]).length()]
    });
    assert!(edge.fold(0.0f32, f32::max) < 0.1 * 1.5, "grid edges near the length");
}

fn holed_square(trim: bool) -> String {
    let (pts, knots) = circle();
    let mut vectors = String::from("0 0 0  1 0 0  0 1 0  1 1 0\n0 0 0  1 0 0  1 1 0  0 1 0  0 0 0\n");
    for (x, y, _) in &pts {
        vectors += &format!("{} {} 0\n", 0.5 + 0.25 * x, 0.5 + 0.25 * y);
    }
    let verts: String = (0..18).map(|k| format!("v {k} ")).collect();
    let circle_refs: String = (0..9).map(|k| format!("{} w {} ", 9 + k, pts[k].2)).collect();
    let outer = if trim { "trim \"edge\" 0 4" } else { "" };
    format!(
        "object \"holed\" basis \"lin\" bezier 1 basis \"b1\" bspline 1 basis \"b2\" rational bspline 2 group\n\
         {vectors}{verts}\n\
         curve \"edge\" \"b1\" 0. 0. 1. 2. 3. 4. 4. 4 5 6 7 8\n\
         curve \"ring\" \"b2\" {knots} {circle_refs}\n\
         surface \"s\" \"m\" \"lin\" 0 1 0. 1. \"lin\" 0 1 0. 1. 0 1 2 3 {outer} hole \"ring\" 0 4\n\
         approximate surface regular parametric 16 16 \"s\"\nend group end object"
    )
}

#[test]
fn square_with_a_circular_hole_has_the_area_left() {
    let expect = 1.0 - PI * 0.25 * 0.25;
    for trim in [false, true] {
        let (mesh, diags) = mesh_of(&holed_square(trim));
        assert!(diags.is_empty(), "{diags:?}");
        let area = mesh.area();
        assert!((area - expect).abs() < 2e-3, "trim {trim}: area {area}, expected {expect}");
        // Nothing inside the hole.
        for t in &mesh.triangles {
            let c = t.iter().map(|&i| mesh.positions[i as usize].as_dvec3()).sum::<DVec3>() / 3.0;
            assert!(c.truncate().distance(DVec2::splat(0.5)) > 0.25 - 1.0 / 128.0, "{c}");
        }
    }
}

#[test]
fn texture_surfaces_and_uv_follow_the_parameters() {
    // A texture surface mapping (u, v) ∈ [0, 2] × [0, 1] to (0.5 + u/4, 2v, 0).
    let text = "object \"t\" basis \"lin\" bezier 1 group\n\
        0 0 0  1 0 0  0 1 0  1 1 0\n0.5 0 0  1 0 0  0.5 2 0  1 2 0\n\
        v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7\n\
        surface \"s\" \"m\" \"lin\" 0 2 0. 2. \"lin\" 0 1 0. 1. 0 1 2 3\n\
        texture \"lin\" 0. 2. \"lin\" 0. 1. 4 5 6 7\n\
        approximate surface regular parametric 5 5 \"s\"\nend group end object";
    let (mesh, diags) = mesh_of(text);
    assert!(diags.is_empty(), "{diags:?}");
    assert_eq!(mesh.textures.len(), 1);
    for (p, t) in mesh.positions.iter().zip(&mesh.textures[0].coords) {
        let (u, v) = (f64::from(p.x) * 2.0, f64::from(p.y));
        assert!(
            (f64::from(t.x) - (0.5 + u / 4.0)).abs() < 1e-6 && (f64::from(t.y) - 2.0 * v).abs() < 1e-6,
            "{t} at {p}"
        );
    }
    // mib_geo_add_uv_texsurf appends the (u, v) parameters as the last space.
    let mut o = object(text);
    assert_eq!(add_uv_texture_surfaces(&mut o), 1);
    let mut diags = Vec::new();
    let mesh = tessellate(&o, &mut diags).mesh;
    assert!(diags.is_empty(), "{diags:?}");
    assert_eq!(mesh.textures.len(), 2);
    for (p, t) in mesh.positions.iter().zip(&mesh.textures[1].coords) {
        assert!((t.x - 2.0 * p.x).abs() < 1e-6 && (t.y - p.y).abs() < 1e-6, "{t} at {p}");
    }
}

#[test]
fn bad_surfaces_are_reported_and_left_out() {
    let text = "object \"bad\" basis \"lin\" bezier 1 group\n0 0 0  1 0 0  0 1 0  1 1 0\nv 0 v 1 v 2 v 3\n\
        surface \"few\" \"m\" \"lin\" 0 1 0. 1. \"lin\" 0 1 0. 1. 0 1 2\n\
        surface \"nobasis\" \"m\" \"cubic\" 0 1 0. 1. \"lin\" 0 1 0. 1. 0 1 2 3\n\
        surface \"far\" \"m\" \"lin\" 0 1 0. 1. \"lin\" 0 1 0. 1. 0 1 2 9\n\
        surface \"ok\" \"m\" \"lin\" 0 1 0. 1. \"lin\" 0 1 0. 1. 0 1 2 3 hole \"nothing\" 0 1\n\
        end group end object";
    let (mesh, diags) = mesh_of(text);
    assert!(mesh.triangles.is_empty());
    let errors: Vec<&str> = diags.iter().filter(|d| d.is_error()).map(|d| d.message.as_str()).collect();
    assert_eq!(errors.len(), 4, "{errors:?}");
    assert!(errors[0].contains("'few'") && errors[0].contains("3 control points"), "{errors:?}");
    assert!(errors[1].contains("unknown basis 'cubic'"), "{errors:?}");
    assert!(errors[2].contains("vertex 9"), "{errors:?}");
    assert!(errors[3].contains("unknown curve 'nothing'"), "{errors:?}");
}
