//! The `sharp s` of a displacement approximation (mental ray's fine approximation):
//! the displaced surface's shading normals are its smooth interpolated vertex normals at
//! 0, the faceted geometric normals of the fine triangles at 1, and lean between them in
//! between, in both engines' hits; `offscreen` and `grading` are named in warnings.

use glam::Vec3A;
use render::accel::{self, Backend};
use render::ray::Ray;
use render::tracer::fill_state;
use shader::State;

use crate::displacement::{build, plane};

/// The cosine wave h(u) = 0.1·cos 2πu of the first texture space (u = x on the plane) as
/// the displacement of material `m`.
const WAVE: &str = r#"shader "coord" "mib_texture_vector" ("select" 0, "selspace" 0)
shader "wave" "mib_texture_wave" ("coord" = "coord", "amplitude_x" 0.1, "amplitude_y" 0, "amplitude_z" 0, "offset" 0)
shader "lam" "mib_illum_lambert" ("diffuse" 1 1 1)
material "m" = "lam" displace = "wave" end material"#;

/// Normals at one hit: the geometric normal, the classic engine's and the path engine's
/// shading normals, and the interpolation of the mesh's vertex normals there (`None`
/// where the mesh keeps none); world space = object space here.
struct Normals {
    ng: Vec3A,
    classic: Vec3A,
    path: Vec3A,
    interpolated: Option<Vec3A>,
}

/// The normals where rays straight down hit the displaced square of `approx`, at 36 points
/// off the vertices (the messages must hold no error).
fn normals(approx: &str) -> Vec<Normals> {
    let b = build(&plane("", WAVE, approx, "m"));
    assert!(!b.messages.iter().any(|m| m.contains("error")), "{:?}", b.messages);
    let world = &b.built.world;
    let bvh = accel::build(world, Backend::Rust);
    let mut out = Vec::new();
    for i in 0..6 {
        for j in 0..6 {
            let (x, y) = (0.07 + 0.163 * i as f32, 0.05 + 0.171 * j as f32);
            let ray = Ray::new(Vec3A::new(x, y, 10.0), Vec3A::new(0.0, 0.0, -1.0));
            let hit = bvh.intersect(&ray).expect("the square is hit");
            let mut s = State { org: ray.origin, dir: ray.dir, ..State::default() };
            fill_state(world, &hit, &mut s);
            let (ng, path) = render::integrator::hit_normals(world, &ray, &hit);
            // The ray comes from above: the classic state faces it, as the path's normals do.
            assert!((s.normal_geom - ng).length() < 1e-6, "{approx}: {} vs {ng}", s.normal_geom);
            let mesh = &world.meshes[world.instances[hit.instance as usize].mesh as usize];
            let interpolated = mesh.has_normals().then(|| {
                let t = mesh.triangles[hit.prim as usize];
                let w = 1.0 - hit.u - hit.v;
                (mesh.normal(t[0]) * w + mesh.normal(t[1]) * hit.u + mesh.normal(t[2]) * hit.v).normalize()
            });
            out.push(Normals { ng, classic: s.normal, path, interpolated });
        }
    }
    out
}

/// `fine length 0.1 sharp 0` shades with the interpolated vertex normals (both engines
/// within 1e-5 of them), which differ from the geometric normals somewhere by more than
/// 1e-3 (so the next checks can tell); `sharp 1` shades every hit with the geometric normal
/// of its triangle (1e-5, both engines); `sharp 0.5` with normalize(½·interpolated +
/// ½·geometric) (1e-5), strictly closer to the geometric normal than the interpolated one
/// wherever the two differ by more than 1e-3.
#[test]
fn sharp_blends_the_interpolated_and_the_geometric_normals() {
    let smooth = normals("approximate displace fine length 0.1 sharp 0 0 6");
    let mut widest = 0f32;
    for n in &smooth {
        let i = n.interpolated.expect("sharp 0 keeps the vertex normals");
        assert!((n.classic - i).length() < 1e-5 && (n.path - i).length() < 1e-5, "{} {} {i}", n.classic, n.path);
        widest = widest.max((i - n.ng).length());
    }
    assert!(widest > 1e-3, "the wave's smooth normals should differ from the facets: {widest}");

    for n in normals("approximate displace fine length 0.1 sharp 1 0 6") {
        assert!((n.classic - n.ng).length() < 1e-5, "classic {} vs {}", n.classic, n.ng);
        assert!((n.path - n.ng).length() < 1e-5, "path {} vs {}", n.path, n.ng);
    }

    for n in normals("approximate displace fine length 0.1 sharp 0.5 0 6") {
        let i = n.interpolated.expect("sharp 0.5 keeps the vertex normals");
        let expect = (i * 0.5 + n.ng * 0.5).normalize();
        assert!((n.classic - expect).length() < 1e-5, "classic {} vs {expect}", n.classic);
        assert!((n.path - expect).length() < 1e-5, "path {} vs {expect}", n.path);
        if (i - n.ng).length() > 1e-3 {
            assert!(n.classic.dot(n.ng) > i.dot(n.ng), "{} leans no closer to {} than {i}", n.classic, n.ng);
        }
    }
}

/// A `sharp` outside 0…1 is clamped with a warning (`sharp 3` shades like 1: the geometric
/// normals, 1e-5); `offscreen` and `grading` are read with a warning naming them
/// (`displacement_adaptive.rs` shows they change no triangle).
#[test]
fn out_of_range_sharp_and_unused_words_are_named() {
    let b = build(&plane("", WAVE, "approximate displace fine view offscreen length 0.1 grading 2 sharp 3 0 6", "m"));
    let warned = |w: &str| b.messages.iter().any(|m| m.contains("warning") && m.contains(w));
    assert!(warned("sharp 3"), "{:?}", b.messages);
    assert!(warned("'offscreen'") && warned("'grading 2'"), "{:?}", b.messages);
    for n in normals("approximate displace fine length 0.1 sharp 3 0 6") {
        assert!((n.classic - n.ng).length() < 1e-5 && (n.path - n.ng).length() < 1e-5);
    }
}
