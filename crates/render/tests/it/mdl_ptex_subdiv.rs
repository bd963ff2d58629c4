//! Quad-mesh Ptex files on subdivision surfaces and ccmeshes: each refined triangle keeps
//! its control cage's Ptex face (a cage quad one face, a cage n-gon one per corner) and its
//! place on it, in both engines.
//!
//! Where each face's pixels lie is found without mira's Ptex tables: on a cube cage (a
//! subdivision surface, `parametric 2`) turned so that a corner faces the camera, the
//! cube's mirror symmetries keep each face's refined region inside the cone of points whose
//! largest cube-axis coordinate is that face's, and the test casts its own rays at the
//! world's fine triangles; on a lone regular pentagon (a ccmesh face), the mirror lines
//! through its centre and edge midpoints keep each sub-quad's region the kite of vertex i,
//! the midpoints of its edges and the centre; on a lone square (boundary fixed), the
//! refinement keeps the bilinear parametrisation (Catmull–Clark's linear precision), so a
//! point's face coordinates are its place on the square.

use crate::mdl_ptex::{assert_constant_regions, ptex_bytes, ptex_scene, FaceSpec};
use crate::support;
use crate::support::scene_text::SceneText;
use glam::DVec3;
use material::mdl_modules::ptex::{reader, Ptex};
use render::{EngineKind, Settings};

/// A module with the Ptex material and a white one (the same diffuse lobe, tint 1).
const MODULE: &str = r#"mdl 1.7;
import ::df::*;
import ::tex::*;
export material faces() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: tex::lookup_color(texture_ptex("./faces.ptx")))));
export material white() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf()));
"#;

/// The constant colour of face `f`: green within [0.85, 0.9] for every face (a pixel with
/// a black sample among its 4 falls below 0.85 · ¾ + 0.9 · ¼ < 0.85), red and blue tell
/// the faces apart.
fn face_colour(f: usize) -> [f32; 3] {
    [0.1 + 0.1 * f as f32, 0.85 + 0.01 * f as f32, 0.6 - 0.08 * f as f32]
}

/// The cube's centre and its axes in world space (a corner, (1, 1, 1) in cube axes, turned
/// toward the camera at the origin).
fn cube_frame() -> (DVec3, [DVec3; 3]) {
    let towards = DVec3::new(1.0, 1.0, 1.0).normalize();
    let across = DVec3::new(1.0, -1.0, 0.0).normalize();
    let up = towards.cross(across);
    // World = x · across' + y · up' + z · towards' where ' reads a cube axis's components.
    let axis = |i: usize| DVec3::new(across[i], up[i], towards[i]);
    (DVec3::new(0.0, 0.0, -2.5), [axis(0), axis(1), axis(2)])
}

/// The cube's cage faces (vertex k at cube coordinates (±1, ±1, ±1), bit 0 x, 1 y, 2 z),
/// counter-clockwise from outside, and each one's outward cube axis (0 x, 1 y, 2 z) and
/// sign.
const CUBE_FACES: [([u32; 4], usize, f64); 6] = [
    ([0, 2, 3, 1], 2, -1.0),
    ([4, 5, 7, 6], 2, 1.0),
    ([0, 1, 5, 4], 1, -1.0),
    ([2, 6, 7, 3], 1, 1.0),
    ([0, 4, 6, 2], 0, -1.0),
    ([1, 3, 7, 5], 0, 1.0),
];

/// The turned cube as a subdivision surface refined 2 levels, lit along the view, with
/// `material`.
fn cube_scene(material: &str) -> String {
    let (centre, axes) = cube_frame();
    let mut vectors = String::new();
    for k in 0..8 {
        let c = |bit: usize| if k >> bit & 1 == 1 { 1.0 } else { -1.0 };
        let p = centre + axes[0] * c(0) + axes[1] * c(1) + axes[2] * c(2);
        vectors += &format!("{} {} {}\n", p.x, p.y, p.z);
    }
    let faces: String =
        CUBE_FACES.iter().map(|(f, ..)| format!("    p {} {} {} {}\n", f[0], f[1], f[2], f[3])).collect();
    let objects = format!(
        r#"object "cube" group
{vectors}    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7
    subdivision surface "s"
{faces}    end subdivision surface
    approximate subdivision surface parametric 2 "s"
end group end object"#
    );
    ptex_scene(SceneText::head_on(32), material, &objects, &["cube"])
}

/// The nearest hit of the ray from the origin along `dir` on `mesh`'s triangles
/// (Möller–Trumbore in f64), if any.
fn cast(mesh: &render::mesh::MeshData, dir: DVec3) -> Option<DVec3> {
    let mut best: Option<f64> = None;
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|v| mesh.positions[v as usize].as_dvec3());
        let (e1, e2) = (b - a, c - a);
        let p = dir.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-14 {
            continue;
        }
        let s = -a;
        let u = s.dot(p) / det;
        let q = s.cross(e1);
        let v = dir.dot(q) / det;
        let d = e2.dot(q) / det;
        if u >= 0.0 && v >= 0.0 && u + v <= 1.0 && d > 0.0 && best.is_none_or(|b| d < b) {
            best = Some(d);
        }
    }
    best.map(|d| dir * d)
}

/// The cage face whose refined region holds the world point `p` (its largest cube-axis
/// coordinate's face).
fn cube_face_at(p: DVec3) -> usize {
    let (centre, axes) = cube_frame();
    let local = [0, 1, 2].map(|i| (p - centre).dot(axes[i]));
    let axis = (0..3).max_by(|&a, &b| local[a].abs().total_cmp(&local[b].abs())).expect("three axes");
    CUBE_FACES.iter().position(|&(_, a, s)| a == axis && local[axis] * s > 0.0).expect("a face")
}

/// A cube cage refined 2 levels (`approximate subdivision surface parametric 2`), turned
/// so that three faces show, in a quad-mesh file whose six faces are distinct constant
/// colours; rendered with it and with a white material (same lobe, same samples): every
/// pixel whose four corners (1e-3 inside) hit one face's region (rays the test casts at
/// the fine triangles) has that face's colour as its ratio to the white render within
/// 1e-4, in both engines; all three faces are seen; every pixel wholly on the cube has a
/// green ratio of at least 0.85 (no black sample at the seams); no message.
#[test]
fn a_subdivided_cube_renders_its_cage_faces() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_subdiv_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    let faces: Vec<FaceSpec> = (0..6).map(|f| FaceSpec { log2: (0, 0), texels: vec![face_colour(f)] }).collect();
    std::fs::write(dir.join("faces.ptx"), ptex_bytes(1, &faces)).unwrap();
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let render = |material: &str| {
            let parsed = mi::parse_str("t.mi", &cube_scene(material));
            let built = support::build_parsed(&parsed, 32, std::slice::from_ref(&dir));
            assert!(built.messages.is_empty(), "{:#?}", built.messages);
            let settings = Settings { engine, spp: Some(4), ..Settings::default() };
            let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
            (film.rgba(), built)
        };
        let ((pixels, built), (white, _)) = (render("faces"), render("white"));
        let mesh = &built.built.world.meshes[0];
        assert_eq!(mesh.triangles.len(), 6 * 16 * 2, "{engine:?}");
        let mut seen = std::collections::HashSet::new();
        let mut covered = 0;
        for (k, (p, w)) in pixels.iter().zip(&white).enumerate() {
            let (px, py) = ((k % 32) as f64, (k / 32) as f64);
            let (x0, x1) = (-1.0 + px / 16.0 + 1e-3, -1.0 + (px + 1.0) / 16.0 - 1e-3);
            let (y0, y1) = (1.0 - (py + 1.0) / 16.0 + 1e-3, 1.0 - py / 16.0 - 1e-3);
            let hits = [(x0, y0), (x1, y0), (x0, y1), (x1, y1)].map(|(x, y)| cast(mesh, DVec3::new(x, y, -1.0)));
            if hits.iter().any(Option::is_none) {
                continue;
            }
            covered += 1;
            let ratio = [0, 1, 2].map(|c| p[c] / w[c]);
            assert!(w[1] > 0.05 && ratio[1] >= 0.85 - 1e-4, "{engine:?}, pixel {k}: {p:?} over {w:?}");
            let regions = hits.map(|h| cube_face_at(h.expect("a hit")));
            if regions.iter().any(|&r| r != regions[0]) {
                continue;
            }
            seen.insert(regions[0]);
            let want = face_colour(regions[0]);
            for c in 0..3 {
                assert!((ratio[c] - want[c]).abs() <= 1e-4, "{engine:?}, pixel {k} (face {}): {ratio:?}", regions[0]);
            }
        }
        assert!(covered > 60 && seen.len() == 3, "{engine:?}: {covered} pixels on the cube, faces {seen:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The ccmesh: a lone square (face 0, vertex 0 at its upper right: u along −x, v along −y)
/// and a lone regular pentagon (faces 1–5), each refined 3 levels, seen and lit head-on.
fn ccmesh_scene() -> String {
    let pentagon: String = (0..5)
        .map(|k| {
            let (x, y) = pentagon_vertex(k);
            format!("{x} {y} -1  ")
        })
        .collect();
    let objects = format!(
        r#"object "mesh" group
    -0.1 0.4 -1  -0.9 0.4 -1  -0.9 -0.4 -1  -0.1 -0.4 -1
    {pentagon}
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7 v 8
    ccmesh "c" polygon 2 vertex 9
        p 0 1 2 3
        p 4 5 6 7 8
    end ccmesh
    approximate ccmesh parametric 3 "c"
end group end object"#
    );
    ptex_scene(SceneText::head_on(32), "faces", &objects, &["mesh"])
}

/// Vertex `k` of the regular pentagon (centre (0.5, 0), radius 0.4, vertex 0 straight up).
fn pentagon_vertex(k: usize) -> (f32, f32) {
    let a = std::f64::consts::FRAC_PI_2 + std::f64::consts::TAU * k as f64 / 5.0;
    ((0.5 + 0.4 * a.cos()) as f32, (0.4 * a.sin()) as f32)
}

/// The pentagon's sub-quad (face 1 + i) whose kite holds (x, y): within the pentagon, the
/// vertex i nearest in angle from the centre.
fn kite_at(x: f32, y: f32) -> Option<usize> {
    let (dx, dy) = (f64::from(x) - 0.5, f64::from(y));
    let inside = (0..5).all(|k| {
        let (a, b) = (pentagon_vertex(k), pentagon_vertex((k + 1) % 5));
        (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0) >= 0.0
    });
    if !inside {
        return None;
    }
    let angle = dy.atan2(dx) - std::f64::consts::FRAC_PI_2;
    let i = (angle / (std::f64::consts::TAU / 5.0)).round().rem_euclid(5.0) as usize;
    Some(1 + i)
}

/// The square's 4 × 4 texels (face 0), green within [0.85, 0.9].
fn square_texels() -> Vec<[f32; 3]> {
    (0..16).map(|t| [0.05 * t as f32, 0.85 + 0.003 * t as f32, 0.9 - 0.05 * t as f32]).collect()
}

/// The square's face coordinates of (x, y): u = (−0.1 − x)/0.8, v = (0.4 − y)/0.8 (`None`
/// outside it).
fn square_uv(x: f32, y: f32) -> Option<(f32, f32)> {
    let (u, v) = ((-0.1 - x) / 0.8, (0.4 - y) / 0.8);
    ((0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v)).then_some((u, v))
}

/// A ccmesh of a lone square (one quad face of 4 × 4 texels) and a lone regular pentagon
/// (five constant sub-quad faces), refined 3 levels (`approximate ccmesh parametric 3`), in
/// both engines (the classic engine's π times): every pixel wholly inside one kite is its
/// face's colour within 1e-4, all five seen; every pixel wholly inside the square lies
/// within the range of the file's bilinear lookup (`Ptex::lookup`) at the face coordinates
/// of the points of the pixel within 1e-4 (a texel turned or misplaced leaves it), the
/// ranges narrow; every pixel wholly inside either polygon has green ≥ 0.85 (no black
/// sample at the seams); no message.
#[test]
fn a_ccmesh_renders_its_quads_texels_and_its_ngons_sub_quads() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_ccmesh_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    let mut faces = vec![FaceSpec { log2: (2, 2), texels: square_texels() }];
    faces.extend((1..6).map(|f| FaceSpec { log2: (0, 0), texels: vec![face_colour(f)] }));
    let bytes = ptex_bytes(1, &faces);
    std::fs::write(dir.join("faces.ptx"), &bytes).unwrap();
    let ptex: Ptex = reader::read(&bytes).expect("the test file").0;
    let text = ccmesh_scene();
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let parsed = mi::parse_str("t.mi", &text);
        let built = support::build_parsed(&parsed, 32, std::slice::from_ref(&dir));
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        assert_eq!(built.built.world.meshes[0].triangles.len(), (4 + 5) * 16 * 2, "{engine:?}");
        let settings = Settings { engine, spp: Some(4), ..Settings::default() };
        let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
        let pixels = film.rgba();
        let seen = assert_constant_regions(engine, &pixels, kite_at, face_colour);
        assert_eq!(seen.len(), 5, "{engine:?}: pixels of every sub-quad");
        let scale = if engine == EngineKind::Classic { std::f32::consts::PI } else { 1.0 };
        let (mut square, mut spread_sum) = (0, 0.0f32);
        for (k, p) in pixels.iter().enumerate() {
            let (px, py) = ((k % 32) as f32, (k / 32) as f32);
            let point = |a: f32, b: f32| (-1.0 + (px + a) / 16.0, 1.0 - (py + b) / 16.0);
            let corners = [(0.001, 0.001), (0.999, 0.001), (0.001, 0.999), (0.999, 0.999)].map(|(a, b)| point(a, b));
            let in_kites = corners.iter().all(|&(x, y)| kite_at(x, y).is_some());
            let in_square = corners.iter().all(|&(x, y)| square_uv(x, y).is_some());
            if in_kites || in_square {
                assert!(p[1] >= (0.85 - 1e-4) * scale, "{engine:?}, pixel {k}: {p:?}");
            }
            if !in_square {
                continue;
            }
            square += 1;
            let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
            for a in 0..=16 {
                for b in 0..=16 {
                    let (x, y) = point(a as f32 / 16.0, b as f32 / 16.0);
                    let (u, v) = square_uv(x, y).map_or((0.0, 0.0), |(u, v)| (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0)));
                    let c = ptex.lookup(0, u, v, None, 0);
                    for (ch, value) in [c.x, c.y, c.z].into_iter().enumerate() {
                        lo[ch] = lo[ch].min(value);
                        hi[ch] = hi[ch].max(value);
                    }
                }
            }
            for c in 0..3 {
                assert!(
                    p[c] >= (lo[c] - 1e-4) * scale && p[c] <= (hi[c] + 1e-4) * scale,
                    "{engine:?}, pixel {k}: {p:?} outside {lo:?} … {hi:?} × {scale}"
                );
            }
            spread_sum += (0..3).map(|c| hi[c] - lo[c]).fold(0.0, f32::max);
        }
        assert!(square >= 100 && spread_sum / (square as f32) < 0.1, "{engine:?}: {square} pixels, {spread_sum}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The pentagon's sub-quads' orientation: each of faces 1–5 holds 2 × 2 texels (red tells
/// the u half, blue the v half), the ccmesh refined 3 levels and seen at 64². Ptex's and
/// OpenSubdiv's convention puts sub-quad i's (0, 0) at vertex i, (1, 0) at the midpoint of
/// edge i → i + 1, (1, 1) at the centre and (0, 1) at the midpoint of edge i − 1 → i. At a
/// point a fifth of the way from each of the kite's corners to its centroid, the pixel's
/// colour (the classic engine's over π) is nearer the file's lookup at that corner's face
/// coordinates (0.1 or 0.9 in u and v) than at any other corner's, in both engines: a u/v
/// swap, a turned or mirrored sub-quad misplaces at least two corners' colours.
#[test]
fn a_ccmesh_pentagons_sub_quads_are_oriented_as_ptex_numbers_them() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_orient_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    let halves = (0..4).map(|t| [0.2 + 0.6 * (t & 1) as f32, 0.85, 0.2 + 0.6 * (t >> 1) as f32]).collect::<Vec<_>>();
    let mut faces = vec![FaceSpec { log2: (2, 2), texels: square_texels() }];
    faces.extend((1..6).map(|_| FaceSpec { log2: (1, 1), texels: halves.clone() }));
    let bytes = ptex_bytes(1, &faces);
    std::fs::write(dir.join("faces.ptx"), &bytes).unwrap();
    let ptex: Ptex = reader::read(&bytes).expect("the test file").0;
    let text = ccmesh_scene().replace("resolution 32 32", "resolution 64 64");
    let mid = |a: (f32, f32), b: (f32, f32)| ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let parsed = mi::parse_str("t.mi", &text);
        let built = support::build_parsed(&parsed, 64, std::slice::from_ref(&dir));
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        let settings = Settings { engine, spp: Some(4), ..Settings::default() };
        let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
        let pixels = film.rgba();
        let scale = if engine == EngineKind::Classic { std::f32::consts::PI } else { 1.0 };
        for i in 0..5 {
            let face = 1 + i as u32;
            let vertex = pentagon_vertex(i);
            let corners = [
                (vertex, (0.1, 0.1)),
                (mid(vertex, pentagon_vertex((i + 1) % 5)), (0.9, 0.1)),
                ((0.5, 0.0), (0.9, 0.9)),
                (mid(pentagon_vertex((i + 4) % 5), vertex), (0.1, 0.9)),
            ];
            let centroid = corners.iter().fold((0.0, 0.0), |s, (p, _)| (s.0 + p.0 / 4.0, s.1 + p.1 / 4.0));
            let expected = corners.map(|(_, (u, v))| ptex.lookup(face, u, v, None, 0));
            for (k, ((x, y), _)) in corners.iter().enumerate() {
                let (px, py) = (x + 0.2 * (centroid.0 - x), y + 0.2 * (centroid.1 - y));
                assert_eq!(kite_at(px, py), Some(face as usize), "the point lies in kite {i}");
                let (col, row) = (((px + 1.0) * 32.0) as usize, ((1.0 - py) * 32.0) as usize);
                let p = pixels[row * 64 + col];
                let distance = |e: glam::Vec4| (0..3).map(|c| (p[c] / scale - e[c]).abs()).fold(0.0, f32::max);
                let nearest = (0..4).min_by(|&a, &b| distance(expected[a]).total_cmp(&distance(expected[b]))).unwrap();
                assert_eq!(nearest, k, "{engine:?}: sub-quad {i}, corner {k}: pixel {p:?}, lookups {expected:?}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
