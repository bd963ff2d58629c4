//! The face axes the tracer gives a Ptex lookup (`fill_state`: the hit triangle's world
//! edges and a quad face's d(u, v)/d(b1, b2), read by
//! `material::mdl_modules::ptex::footprint`): on `mdl_ptex`'s two quads (the left one `c 0
//! 1 4 5`, 1 wide along u (+x) and 2 along v (+y); the right one `p 3 4 1 2`, u along −x,
//! v along −y) and its pentagon's sub-quads, hit by rays cast here on both triangles of
//! each.
//!
//! What is asserted: a quad's dP/du, dP/dv are its edges (1e-4, the tracer's differences
//! over a 2⁻⁸ step of the barycentrics, exact for a quad's affine (u, v) up to rounding);
//! a triangle file's axes are the hit triangle's edges, whose half cross product is the
//! state's triangle area (1e-6 relative); a sub-quad's axes are its bilinear map's
//! derivatives at the hit (vertex, edge midpoints, vertex mean; 2 % of their length, the
//! step's error on the bilinear map); and a footprint 0.05 wide seen 75° off the normal,
//! tilted along the left quad's v, gets the widths (0.05, 0.05 / (2 cos 75°)) (1e-4
//! relative).

use crate::mdl_ptex::{ptex_bytes, quad_scene, FaceSpec, MODULE};
use crate::support;
use glam::{Vec2, Vec3A};
use material::mdl_modules::ptex::footprint::{face_axes, filter_widths};
use material::mdl_modules::ptex::MeshType;
use render::accel::{self, Backend};
use render::ray::Ray;
use shader::State;

/// The state of the hit of a ray toward `target` along `dir` (from 10 back), as the
/// engines fill it.
fn state_at(world: &render::World, accel: &dyn render::Accel, target: Vec3A, dir: Vec3A) -> State {
    let dir = dir.normalize();
    let origin = target - dir * 10.0;
    let hit = accel.intersect(&Ray::new(origin, dir)).expect("a hit");
    let mut s = State { org: origin, dir, ..State::default() };
    render::tracer::fill_state(world, &hit, &mut s);
    s
}

/// Whether `a` and `b` are within `tol` of each other, relative to `b`'s length.
fn near(a: Vec3A, b: Vec3A, tol: f32) -> bool {
    (a - b).length() <= tol * b.length().max(1.0)
}

#[test]
fn the_tracer_gives_each_face_its_axes() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_aniso_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    let faces =
        [FaceSpec { log2: (1, 1), texels: vec![[0.5; 3]; 4] }, FaceSpec { log2: (1, 1), texels: vec![[0.5; 3]; 4] }];
    std::fs::write(dir.join("faces.ptx"), ptex_bytes(1, &faces)).unwrap();
    let parsed = mi::parse_str("t.mi", &quad_scene());
    let built = support::build_parsed(&parsed, 8, std::slice::from_ref(&dir));
    let world = &built.built.world;
    let bvh = accel::build(world, Backend::Rust);
    let down = -Vec3A::Z;
    // Both triangles of each quad (either side of its diagonal).
    let quads = [
        ((-0.8, -0.6), Vec3A::X, Vec3A::new(0.0, 2.0, 0.0)),
        ((-0.2, 0.7), Vec3A::X, Vec3A::new(0.0, 2.0, 0.0)),
        ((0.2, -0.7), -Vec3A::X, Vec3A::new(0.0, -2.0, 0.0)),
        ((0.8, 0.6), -Vec3A::X, Vec3A::new(0.0, -2.0, 0.0)),
    ];
    for ((x, y), du, dv) in quads {
        let s = state_at(world, bvh.as_ref(), Vec3A::new(x, y, -1.0), down);
        assert!(s.ptex_quad.is_some(), "({x}, {y})");
        let [a, b] = face_axes(MeshType::Quad, &s).expect("quad axes");
        assert!(near(a, du, 1e-4) && near(b, dv, 1e-4), "({x}, {y}): {a} {b}");
        let [e1, e2] = face_axes(MeshType::Triangle, &s).expect("triangle axes");
        let area = 0.5 * e1.cross(e2).length();
        assert!((area / s.tri_area - 1.0).abs() < 1e-6, "({x}, {y}): {area} vs {}", s.tri_area);
    }
    // The pentagon `p 6 7 8 9 10`: sub-quad k runs from vertex k to the next edge's midpoint
    // (u), the vertex mean, and the previous edge's midpoint (v).
    let outline = [
        Vec2::new(10.0, 10.0),
        Vec2::new(11.0, 10.0),
        Vec2::new(11.5, 10.5),
        Vec2::new(11.0, 11.0),
        Vec2::new(10.0, 11.0),
    ];
    let centre = outline.iter().copied().sum::<Vec2>() / 5.0;
    let mut seen = [false; 5];
    for (x, y) in [(10.2, 10.2), (10.8, 10.1), (11.3, 10.5), (10.9, 10.9), (10.2, 10.8), (10.6, 10.4)] {
        let s = state_at(world, bvh.as_ref(), Vec3A::new(x, y, -1.0), down);
        let (face, u, v) = s.ptex_quad.expect("a sub-quad");
        let k = (face - 2) as usize;
        seen[k] = true;
        let (c00, c10, c11, c01) =
            (outline[k], (outline[k] + outline[(k + 1) % 5]) / 2.0, centre, (outline[k] + outline[(k + 4) % 5]) / 2.0);
        let du = (c10 - c00) * (1.0 - v) + (c11 - c01) * v;
        let dv = (c01 - c00) * (1.0 - u) + (c11 - c10) * u;
        let [a, b] = face_axes(MeshType::Quad, &s).expect("sub-quad axes");
        let (du, dv) = (Vec3A::new(du.x, du.y, 0.0), Vec3A::new(dv.x, dv.y, 0.0));
        assert!((a - du).length() <= 0.02 * du.length(), "({x}, {y}) face {face}: {a} vs {du}");
        assert!((b - dv).length() <= 0.02 * dv.length(), "({x}, {y}) face {face}: {b} vs {dv}");
    }
    assert!(seen.iter().filter(|s| **s).count() >= 4, "{seen:?}");
    // 75° off the normal, tilted along the left quad's v (+y).
    let (sin, cos) = (75f32.to_radians().sin(), 75f32.to_radians().cos());
    let mut s = state_at(world, bvh.as_ref(), Vec3A::new(-0.5, 0.1, -1.0), Vec3A::new(0.0, sin, -cos));
    s.camera_footprint = 0.05;
    let (wu, wv) = filter_widths(MeshType::Quad, &s).expect("widths");
    assert!((wu / 0.05 - 1.0).abs() < 1e-4 && (wv / (0.05 / (2.0 * cos)) - 1.0).abs() < 1e-4, "{wu} {wv}");
    std::fs::remove_dir_all(&dir).ok();
}
