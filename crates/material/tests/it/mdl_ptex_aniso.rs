//! Anisotropic Ptex lookups at a hit (`Ptex::lookup_at`: `footprint::filter_widths` into
//! `Ptex::sample_rect`) and `sample_rect`'s probes across face edges
//! (`Ptex::across_edges`). Files written byte by byte by `mdl_ptex`'s writer.
//!
//! The plane: 3 × 3 quad faces of 32 × 32 texels (face (i, j) is Ptex face 3 j + i, on the
//! world square [i, i + 1] × [j, j + 1] of the plane z = 0, u along x, v along y), wired
//! to their neighbours, with box-reduced levels down to 2 × 2; the texture varies along x
//! only: 0.5 + 0.4 sin(2π x / 0.3) at each texel's centre (a period of 0.3 face units,
//! so the faces differ). Hits are states as the tracer fills them (the hit triangle's
//! world edges, the quad's d(u, v)/d(b1, b2), half the quad's area, the geometric
//! normal +z) with the path engine's camera footprint.

use glam::{Vec3A, Vec4};
use material::mdl_modules::ptex::anisotropic::major_axis_weights;
use material::mdl_modules::ptex::footprint::{filter_width, filter_widths};
use material::mdl_modules::ptex::{Filter, MeshType, Ptex};
use shader::State;

use crate::mdl_ptex::{ptex_file_full, read, reduce, Face, How};

/// Texels a face side (level 0).
const SIDE: usize = 32;
/// The texture's period along x (face units).
const PERIOD: f64 = 0.3;

/// The texture at world x.
fn pattern(x: f64) -> f64 {
    0.5 + 0.4 * (std::f64::consts::TAU * x / PERIOD).sin()
}

/// The plane's file (the module documentation); `wired`: with adjacency (else none).
fn plane(wired: bool) -> Ptex {
    let mut faces = Vec::new();
    let mut levels: Vec<Vec<Face>> = Vec::new();
    for id in 0..9 {
        let i = id % 3;
        let texels: Vec<f64> =
            (0..SIDE * SIDE).map(|t| pattern(i as f64 + ((t % SIDE) as f64 + 0.5) / SIDE as f64)).collect();
        let (mut values, mut side, mut k) = (texels.clone(), SIDE, 0);
        while side > 2 {
            values = reduce(&values, side);
            side /= 2;
            let log2 = side.trailing_zeros() as i8;
            if levels.len() <= k {
                levels.push(Vec::new());
            }
            levels[k].push(Face { log2: (log2, log2), texels: values.clone(), how: How::Zipped });
            k += 1;
        }
        faces.push(Face { log2: (5, 5), texels, how: How::Zipped });
    }
    let id = |i: i32, j: i32| if (0..3).contains(&i) && (0..3).contains(&j) { j * 3 + i } else { -1 };
    let adjacency: Vec<([i32; 4], [u8; 4])> = (0..9)
        .map(|f| {
            let (i, j) = (f % 3, f / 3);
            // Edges 0 (v = 0), 1 (u = 1), 2 (v = 1), 3 (u = 0) and the neighbour's edge.
            ([id(i, j - 1), id(i + 1, j), id(i, j + 1), id(i - 1, j)], [2, 3, 0, 1])
        })
        .collect();
    read(&ptex_file_full(1, 3, 1, &faces, 6, if wired { &adjacency } else { &[] }, &levels))
}

/// A hit on the plane at face (i, j), (u, v) on it, along `dir`, with a camera footprint
/// `footprint` wide, on the quad's triangle of corners 0, 1, 2 (u = b1 + b2, v = b2).
fn hit(i: usize, j: usize, u: f32, v: f32, dir: Vec3A, footprint: f32) -> State {
    State {
        dir,
        normal_geom: Vec3A::Z,
        camera_footprint: footprint,
        tri_area: 0.5,
        face_edges: [Vec3A::X, Vec3A::new(1.0, 1.0, 0.0)],
        ptex_quad_jacobian: [1.0, 0.0, 1.0, 1.0],
        ptex_quad: Some(((j * 3 + i) as u32, u, v)),
        ..State::default()
    }
}

/// A direction `degrees` off the plane's normal, tilted toward +x (`along_x`) or +y.
fn tilted(degrees: f32, along_x: bool) -> Vec3A {
    let (s, c) = (degrees.to_radians().sin(), degrees.to_radians().cos());
    if along_x {
        Vec3A::new(s, 0.0, -c)
    } else {
        Vec3A::new(0.0, s, -c)
    }
}

/// The isotropic lookup at hit `s` (what the engines read before: the footprint's area as
/// a square).
fn isotropic(ptex: &Ptex, s: &State) -> Vec4 {
    let (face, u, v) = s.ptex_quad.unwrap();
    ptex.lookup(face, u, v, filter_width(s), 0)
}

/// Max − min of `f` over 97 points across the centre face at v = 0.5 (about 3.3 periods).
fn contrast(f: impl Fn(f32) -> f32) -> f32 {
    let values: Vec<f32> = (0..97).map(|k| f(k as f32 / 96.0)).collect();
    values.iter().copied().fold(f32::MIN, f32::max) - values.iter().copied().fold(f32::MAX, f32::min)
}

/// Seen head-on (equal extents along u and v) the lookup is the isotropic one bit for bit,
/// at footprints from 1/200 to 2 face units, on the plane's quads and on a triangle file's
/// right isosceles faces (legs 1 along x and y).
#[test]
fn an_isotropic_footprint_reads_as_before() {
    let ptex = plane(true);
    for footprint in [0.005f32, 0.03, 0.07, 0.2, 0.6, 2.0] {
        for k in 0..40 {
            let (u, v) = ((k as f32 * 0.37).fract(), (k as f32 * 0.61).fract());
            let s = hit(k % 3, (k / 3) % 3, u, v, -Vec3A::Z, footprint);
            assert_eq!(filter_widths(MeshType::Quad, &s), filter_width(&s).map(|w| (w, w)));
            assert_eq!(ptex.lookup_at(&s, 0), isotropic(&ptex, &s), "footprint {footprint} at {u} {v}");
        }
    }
    let faces: Vec<Face> = (0..2)
        .map(|f| Face {
            log2: (3, 3),
            texels: (0..64).map(|t| ((t * 7 + f * 5) % 13) as f64 / 12.0).collect(),
            how: How::Zipped,
        })
        .collect();
    let levels =
        vec![(0..2).map(|f| Face { log2: (2, 2), texels: vec![0.1 + 0.3 * f as f64; 16], how: How::Zipped }).collect()];
    let triangles = read(&ptex_file_full(0, 3, 1, &faces, 6, &[], &levels));
    for footprint in [0.01f32, 0.1, 0.3] {
        let s = State {
            dir: -Vec3A::Z,
            normal_geom: Vec3A::Z,
            footprint,
            tri_area: 0.5,
            face_edges: [Vec3A::X, Vec3A::Y],
            prim: 1,
            bary: [0.5, 0.2, 0.3],
            ..State::default()
        };
        let want = triangles.lookup(1, 0.2, 0.3, filter_width(&s), 0);
        assert_eq!(triangles.lookup_at(&s, 0), want, "footprint {footprint}");
    }
}

/// Seen 75° off the normal, tilted along y (the texture's constant axis), with a footprint
/// 1/16 face units wide: the anisotropic lookup's contrast across the centre face (max −
/// min) is 0.95 of level 0's or more, and at least 1.2 times the isotropic lookup's
/// (measured: see the assertion message; the isotropic width, f / √cos 75° ≈ 1.97 f,
/// blurs u as if the tilt were along it).
#[test]
fn a_grazing_view_along_the_constant_axis_keeps_the_contrast() {
    let ptex = plane(true);
    let dir = tilted(75.0, false);
    let f = 1.0 / 16.0;
    let sharp = contrast(|u| ptex.lookup(4, u, 0.5, None, 0).x);
    let aniso = contrast(|u| ptex.lookup_at(&hit(1, 1, u, 0.5, dir, f), 0).x);
    let iso = contrast(|u| isotropic(&ptex, &hit(1, 1, u, 0.5, dir, f)).x);
    let message = format!("level 0 {sharp}, anisotropic {aniso}, isotropic {iso}, ratio {}", aniso / iso);
    assert!(aniso >= 0.95 * sharp, "{message}");
    assert!(aniso >= 1.2 * iso, "{message}");
    eprintln!("{message}");
}

/// Seen 75° off the normal, tilted along x (the texture's varying axis), with a footprint
/// 1/16 wide (so 1/16 / cos 75° ≈ 0.24 along u): at points across the centre face,
/// including within 0.12 of its edges, where the probes read the faces beside it, the
/// lookup is the footprint's box average of the pattern along x within 0.03 (the box's
/// mean of 0.5 + 0.4 sin, exact; the probes are 4 squares 1/16 wide, each a blend of
/// levels); the isotropic lookup (narrower along u) is further off than that somewhere,
/// and so is the lookup from a file without adjacency near an edge.
#[test]
fn a_grazing_view_along_the_varying_axis_blurs_as_the_box_average() {
    let (wired, lone) = (plane(true), plane(false));
    let dir = tilted(75.0, true);
    let f = 1.0f32 / 16.0;
    let w = f64::from(f) / 75f64.to_radians().cos();
    let x = std::f64::consts::PI * w / PERIOD;
    let boxed = |centre: f64| 0.5 + 0.4 * (std::f64::consts::TAU * centre / PERIOD).sin() * x.sin() / x;
    let (mut worst, mut iso_worst, mut lone_worst) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..=40 {
        let u = k as f32 / 40.0;
        let s = hit(1, 1, u, 0.5, dir, f);
        let want = boxed(1.0 + f64::from(u));
        worst = worst.max((f64::from(wired.lookup_at(&s, 0).x) - want).abs());
        iso_worst = iso_worst.max((f64::from(isotropic(&wired, &s).x) - want).abs());
        lone_worst = lone_worst.max((f64::from(lone.lookup_at(&s, 0).x) - want).abs());
    }
    let message = format!("anisotropic off by {worst}, isotropic {iso_worst}, without adjacency {lone_worst}");
    assert!(worst <= 0.03, "{message}");
    assert!(iso_worst > 0.03 && lone_worst > 0.03, "{message}");
    eprintln!("{message}");
}

/// `sample_rect`'s probes past an edge read the face across it: a footprint 0.5 × 1/16 at
/// u = 0.9 of the centre face (8 probes from u = 0.68 to 1.12) equals the sum of the
/// probes read at their own places with their Gaussian weights (`major_axis_weights`), the last two on the face to the right at u − 1
/// (1e-6), and likewise along v into the face above; a face with no neighbour there (the
/// plane's right column, or a file without adjacency) reads its probes as before, clamped
/// to its edge (bit for bit the old loop). Triangles: faces 0 and 1 sharing their edges 1
/// (u + v = 1), a footprint 0.5 long along u at (0.68, 0.3) of face 0 (4 probes, 8 × 8
/// texels) reads its probes past the edge on face 1 at (1 − u, 1 − v) (1e-6).
#[test]
fn probes_across_an_edge_read_the_neighbour() {
    let (wired, lone) = (plane(true), plane(false));
    // The probes' places (as `sample_rect` computes them): n = long / short = 8 (short the
    // texel of the level it picks, 16 × 16) spaced long / 8 around `at`, each read with
    // the spacing's width.
    let (short, long, n) = (0.0625f32, 0.5f32, 8);
    let step = long / n as f32;
    let width = short.max(step);
    let weights = major_axis_weights(n);
    let probes = move |at: f32| (0..n).map(move |k| (at + ((k as f32 + 0.5) * step - 0.5 * long), weights[k]));
    let one = |ptex: &Ptex, face: u32, u: f32, v: f32| {
        let mut out = [0.0f32; 1];
        assert!(ptex.sample(face, u, v, Some(width), Filter::Bilinear, 0, &mut out));
        out[0]
    };
    let rect = |ptex: &Ptex, face: u32, u: f32, v: f32, widths: (f32, f32)| {
        let mut out = [0.0f32; 1];
        assert!(ptex.sample_rect(face, u, v, widths, 0, &mut out));
        out[0]
    };
    // Along u into face 5 (right of 4); along v into face 7 (above 4).
    let mut want = 0.0;
    for (pu, w) in probes(0.9) {
        want += if pu > 1.0 { one(&wired, 5, pu - 1.0, 0.4) } else { one(&wired, 4, pu, 0.4) } * w;
    }
    let got = rect(&wired, 4, 0.9, 0.4, (long, short));
    assert!((got - want).abs() <= 1e-6, "{got} vs {want}");
    let mut want = 0.0;
    for (pv, w) in probes(0.9) {
        want += if pv > 1.0 { one(&wired, 7, 0.3, pv - 1.0) } else { one(&wired, 4, 0.3, pv) } * w;
    }
    let got = rect(&wired, 4, 0.3, 0.9, (short, long));
    assert!((got - want).abs() <= 1e-6, "{got} vs {want}");
    // It differs from the clamped read (the pattern goes on across the edge).
    let clamped: f32 = probes(0.9).map(|(pu, w)| one(&wired, 4, pu, 0.4) * w).sum();
    assert!((rect(&wired, 4, 0.9, 0.4, (long, short)) - clamped).abs() > 1e-3);
    // No face across: as before (each probe at its own place, clamped by the lookup).
    for (ptex, face) in [(&wired, 5u32), (&lone, 4)] {
        let mut old = 0.0f32;
        for (pu, w) in probes(0.9) {
            old += one(ptex, face, pu, 0.4) * w;
        }
        assert_eq!(rect(ptex, face, 0.9, 0.4, (long, short)), old, "face {face}");
    }
    // Triangles: a point (u, v) past edge 1 lies t = v along it and s = 1 − u − v (< 0)
    // into the face; on face 1 that is t′ = 1 − t along its edge 1 at depth −s, face
    // coordinates (1 − (−s) − t′, t′) = (1 − u, 1 − v).
    let faces: Vec<Face> = (0..2)
        .map(|f| Face {
            log2: (3, 3),
            texels: (0..64).map(|t| ((t * 7 + f * 5) % 13) as f64 / 12.0).collect(),
            how: How::Zipped,
        })
        .collect();
    let triangles = read(&ptex_file_full(0, 3, 1, &faces, 6, &[([-1, 1, -1, -1], [0, 1, 0, 0]); 2], &[]));
    // 8 × 8 texels: level 0, its texel 1/8 the probes' spacing: 4 probes over 0.5.
    let (u, v, n) = (0.68f32, 0.3f32, 4);
    let step = long / n as f32;
    let width = 0.125f32.max(step);
    let one = |ptex: &Ptex, face: u32, u: f32, v: f32| {
        let mut out = [0.0f32; 1];
        assert!(ptex.sample(face, u, v, Some(width), Filter::Bilinear, 0, &mut out));
        out[0]
    };
    let weights = major_axis_weights(n);
    let probes = move |at: f32| (0..n).map(move |k| (at + ((k as f32 + 0.5) * step - 0.5 * long), weights[k]));
    let mut want = 0.0;
    for (pu, w) in probes(u) {
        want += if pu + v > 1.0 { one(&triangles, 1, 1.0 - pu, 1.0 - v) } else { one(&triangles, 0, pu, v) } * w;
    }
    let got = rect(&triangles, 0, u, v, (long, 0.0625));
    assert!((got - want).abs() <= 1e-6, "{got} vs {want}");
}
