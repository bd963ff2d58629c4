//! Continuity of the Ptex filter where neighbouring faces differ (`ptex::edges`): a
//! constant quad beside a textured one, quads of 2 × 2 and 4 × 4 texels, a vertex of four
//! quads of four different resolutions (a constant one among them), a vertex of six
//! triangles, a constant triangle beside a textured one and triangles of 2 × 2 and 4 × 4
//! texels. Files written byte by byte by `mdl_ptex`'s writer.
//!
//! What is asserted: points 1e-6 apart on either side of each shared edge, along its
//! whole length (its vertices included), read values within 1e-4 of each other (the
//! filter's slopes are below 20 per face unit here); at a shared vertex every face reads
//! the mean of the corner texels of the faces around it (1e-6); and each case blends
//! something (a value at the edge or vertex differs from a face's own texel by > 0.01),
//! so continuity is not had for free.

use material::mdl_modules::ptex::{Filter, Ptex};

use crate::mdl_ptex::{ptex_file_full, read, Face, How};

/// The first channel of `ptex` at face `f`, (`u`, `v`), bilinear at level 0.
fn at(ptex: &Ptex, f: usize, u: f32, v: f32) -> f32 {
    let mut out = [0.0f32; 1];
    assert!(ptex.sample(f as u32, u, v, None, Filter::Bilinear, 0, &mut out), "face {f}");
    out[0]
}

/// Texel values varied per face and texel, in [0, 1].
fn varied(face: usize, count: usize) -> Vec<f64> {
    (0..count).map(|t| ((face * 37 + t * 13) % 29) as f64 / 28.0).collect()
}

fn zipped(log2: (i8, i8), face: usize) -> Face {
    Face { log2, texels: varied(face, 1 << (log2.0 + log2.1)), how: How::Zipped }
}

const EPS: f32 = 1e-6;

/// Face 0 (constant 0.9) and face 1 (4 × 4 texels) side by side: face 0's edge 1 (u = 1)
/// is face 1's edge 3 (u = 0); at height v both sides agree within 1e-4 for v from 0 to 1;
/// the constant face still reads 0.9 at its centre, and is blended toward its neighbour
/// at the edge (> 0.01 from 0.9 somewhere).
#[test]
fn a_constant_quad_meets_a_textured_one_without_a_seam() {
    let faces = [Face { log2: (0, 0), texels: vec![0.9], how: How::ConstantInfo }, zipped((2, 2), 1)];
    let adjacency = [([-1, 1, -1, -1], [0, 3, 0, 0]), ([-1, -1, -1, 0], [0, 0, 0, 1])];
    let ptex = read(&ptex_file_full(1, 3, 1, &faces, 6, &adjacency, &[]));
    let mut blended = 0.0f32;
    for k in 0..=40 {
        let v = k as f32 / 40.0;
        let (a, b) = (at(&ptex, 0, 1.0 - EPS, v), at(&ptex, 1, EPS, v));
        assert!((a - b).abs() <= 1e-4, "v = {v}: {a} vs {b}");
        blended = blended.max((a - 0.9).abs());
    }
    assert!(blended > 0.01, "the constant face is blended at the edge ({blended})");
    assert!((at(&ptex, 0, 0.5, 0.5) - 0.9).abs() <= 1e-6);
}

/// A face of 2 × 2 texels (face 0, its edge 2, v = 1) against one of 4 × 4 (face 1, its
/// edge 1, u = 1, turned: face 0's u is face 1's v): both sides agree within 1e-4 along the
/// whole edge, where the two rows differ by > 0.01.
#[test]
fn faces_of_two_and_four_texels_a_side_meet_without_a_seam() {
    let faces = [zipped((1, 1), 0), zipped((2, 2), 1)];
    let adjacency = [([-1, -1, 1, -1], [0, 0, 1, 0]), ([-1, 0, -1, -1], [0, 2, 0, 0])];
    let ptex = read(&ptex_file_full(1, 3, 1, &faces, 6, &adjacency, &[]));
    let apart = read(&ptex_file_full(1, 3, 1, &faces, 6, &[], &[]));
    let mut seam = 0.0f32;
    for k in 0..=64 {
        let u = k as f32 / 64.0;
        let (a, b) = (at(&ptex, 0, u, 1.0 - EPS), at(&ptex, 1, 1.0 - EPS, u));
        assert!((a - b).abs() <= 1e-4, "u = {u}: {a} vs {b}");
        seam = seam.max((at(&apart, 0, u, 1.0 - EPS) - at(&apart, 1, 1.0 - EPS, u)).abs());
    }
    assert!(seam > 0.01, "the rows differ without adjacency ({seam})");
}

/// Four quads around the point (1, 1) of the square [0, 2]²: face 0 lower left (4 × 4
/// texels), 1 lower right (2 × 2), 2 upper right (4 × 2), 3 upper left (constant), each
/// with u to the right and v up. Across both lines x = 1 and y = 1, over their whole
/// length, points 1e-6 either side agree within 1e-4; at the vertex every face reads the
/// mean of the four corner texels there (1e-6), which differs from face 0's by > 0.01.
#[test]
fn four_quads_around_a_vertex_are_continuous() {
    let faces = [
        zipped((2, 2), 0),
        zipped((1, 1), 1),
        zipped((2, 1), 2),
        Face { log2: (0, 0), texels: vec![0.2], how: How::ConstantInfo },
    ];
    let adjacency = [
        ([-1, 1, 3, -1], [0, 3, 0, 0]),
        ([-1, -1, 2, 0], [0, 0, 0, 1]),
        ([1, -1, -1, 3], [2, 0, 0, 1]),
        ([0, 2, -1, -1], [2, 3, 0, 0]),
    ];
    let ptex = read(&ptex_file_full(1, 3, 1, &faces, 6, &adjacency, &[]));
    let value = |x: f32, y: f32| {
        let face = match (x >= 1.0, y >= 1.0) {
            (false, false) => 0,
            (true, false) => 1,
            (true, true) => 2,
            (false, true) => 3,
        };
        at(&ptex, face, x - x.floor().min(1.0), y - y.floor().min(1.0))
    };
    for k in 0..=80 {
        let c = 2.0 * k as f32 / 80.0;
        let (a, b) = (value(1.0 - EPS, c), value(1.0 + EPS, c));
        assert!((a - b).abs() <= 1e-4, "across x = 1 at y = {c}: {a} vs {b}");
        let (a, b) = (value(c, 1.0 - EPS), value(c, 1.0 + EPS));
        assert!((a - b).abs() <= 1e-4, "across y = 1 at x = {c}: {a} vs {b}");
    }
    // Corner texels at the vertex: face 0's (3, 3), face 1's (0, 1), face 2's (0, 0),
    // face 3's only one.
    let corners = [varied(0, 16)[15], varied(1, 4)[2], varied(2, 8)[0], 0.2];
    let mean = (corners.iter().sum::<f64>() / 4.0) as f32;
    for (face, (u, v)) in [(0, (1.0, 1.0)), (1, (0.0, 1.0)), (2, (0.0, 0.0)), (3, (1.0, 0.0))] {
        let got = at(&ptex, face, u, v);
        assert!((got - mean).abs() <= 1e-6, "face {face} at the vertex: {got} vs {mean}");
    }
    assert!((mean - corners[0] as f32).abs() > 0.01);
}

/// Six triangles of 4 × 4 texels around their common corner 0 (a hexagon fan: face k's
/// edge 2 is face k + 1's edge 0). Along each shared edge, from the vertex out to the rim,
/// points 1e-6 either side agree within 1e-4; at the vertex every face reads the mean of
/// the six corner texels (1e-6), which differs from face 0's by > 0.01.
#[test]
fn six_triangles_around_a_vertex_are_continuous() {
    let faces: Vec<Face> = (0..6).map(|k| zipped((2, 2), k)).collect();
    let adjacency: Vec<([i32; 4], [u8; 4])> =
        (0..6).map(|k| ([(k + 5) % 6, -1, (k + 1) % 6, -1], [2, 0, 0, 0])).collect();
    let ptex = read(&ptex_file_full(0, 3, 1, &faces, 6, &adjacency, &[]));
    for k in 0..6usize {
        let next = (k + 1) % 6;
        for s in [1e-5f32, 1e-3, 0.01, 0.04, 0.1, 0.2, 0.3, 0.45, 0.6, 0.77, 0.9, 0.99] {
            // Face k's edge 2 (u = 0) at distance s from the vertex is face k + 1's edge 0
            // (v = 0) at s.
            let (a, b) = (at(&ptex, k, EPS, s), at(&ptex, next, s, EPS));
            assert!((a - b).abs() <= 1e-4, "faces {k}/{next} at {s}: {a} vs {b}");
        }
    }
    let mean = ((0..6).map(|k| varied(k, 16)[0]).sum::<f64>() / 6.0) as f32;
    for k in 0..6 {
        let got = at(&ptex, k, 0.0, 0.0);
        assert!((got - mean).abs() <= 1e-6, "face {k} at the vertex: {got} vs {mean}");
    }
    assert!((mean - varied(0, 16)[0] as f32).abs() > 0.01);
}

/// Points 1e-6 apart across the shared edge of two triangles, face 0's edge 1 (u + v = 1,
/// at fraction t from (1, 0)) and face 1's edge `edge_b` (at fraction 1 − t), over the
/// edge's whole length (its vertices included): their largest difference, and the largest
/// difference between face 0's side with and without the adjacency (the blend).
fn across_triangle_edge(faces: &[Face], edge_b: u8) -> (f32, f32) {
    let mut adjacency = [([-1, 1, -1, -1], [0, edge_b, 0, 0]), ([-1; 4], [0; 4])];
    (adjacency[1].0[edge_b as usize], adjacency[1].1[edge_b as usize]) = (0, 1);
    let joined = read(&ptex_file_full(0, 3, 1, faces, 6, &adjacency, &[]));
    let apart = read(&ptex_file_full(0, 3, 1, faces, 6, &[], &[]));
    // A point at fraction t along a triangle's edge, depth ε inside (`filter::from_edge`).
    let inside = |edge: u8, t: f32| match edge {
        0 => (t, EPS),
        1 => (1.0 - EPS - t, t),
        _ => (EPS, 1.0 - EPS - t),
    };
    let (mut gap, mut blended) = (0.0f32, 0.0f32);
    for k in 0..=96 {
        let t = k as f32 / 96.0;
        let (ua, va) = inside(1, t);
        let (ub, vb) = inside(edge_b, 1.0 - t);
        let a = at(&joined, 0, ua, va);
        gap = gap.max((a - at(&joined, 1, ub, vb)).abs());
        blended = blended.max((a - at(&apart, 0, ua, va)).abs());
    }
    (gap, blended)
}

/// A constant triangle (face 0, 0.9) beside one of 4 × 4 texels (its long edge against
/// the other's): across the edge within 1e-4 over its whole length; the constant face is
/// blended toward its neighbour there (> 0.01 from 0.9) and keeps 0.9 at its centroid
/// (1e-6).
#[test]
fn a_constant_triangle_meets_a_textured_one_without_a_seam() {
    let faces = [Face { log2: (0, 0), texels: vec![0.9], how: How::ConstantInfo }, zipped((2, 2), 1)];
    let (gap, blended) = across_triangle_edge(&faces, 1);
    assert!(gap <= 1e-4, "seam {gap}");
    assert!(blended > 0.01, "the constant face is blended at the edge ({blended})");
    let adjacency = [([-1, 1, -1, -1], [0, 1, 0, 0]), ([-1, 0, -1, -1], [0, 1, 0, 0])];
    let ptex = read(&ptex_file_full(0, 3, 1, &faces, 6, &adjacency, &[]));
    assert!((at(&ptex, 0, 1.0 / 3.0, 1.0 / 3.0) - 0.9).abs() <= 1e-6);
}

/// A triangle of 2 × 2 texels (face 0, its long edge) against one of 4 × 4 (face 1, its
/// edge 2, u = 0: turned), and the same with face 1's edge 0: across the edge within 1e-4
/// over its whole length, each blended (> 0.01 from its value without adjacency).
#[test]
fn triangles_of_two_and_four_texels_a_side_meet_without_a_seam() {
    let faces = [zipped((1, 1), 0), zipped((2, 2), 1)];
    for edge_b in [2, 0] {
        let (gap, blended) = across_triangle_edge(&faces, edge_b);
        assert!(gap <= 1e-4, "edge {edge_b}: seam {gap}");
        assert!(blended > 0.01, "edge {edge_b}: blended {blended}");
    }
}
