//! Filtered Ptex lookups (`ptex::filter`) and reduced levels, on files written byte by
//! byte by `mdl_ptex`'s writer (adjacency in the face infos, reduced levels after level 0
//! in Ptex's reduction order).
//!
//! What is asserted: bilinear on a 2 × 2 quad face at texel centres, the face centre,
//! edges and corners (1e-6); on triangle faces each texel at its centroid, grid vertices
//! the mean of the texels around them, and linear data reproduced inside the face (1e-5);
//! constant faces unchanged without neighbours (1e-6); across a shared edge (quads and triangles, edges
//! turned against each other) values agree on both sides within 1e-4, where without the
//! adjacency they do not; reduced levels read back as written (1e-6), in Ptex's reduction
//! order, and a filter width picks them; bad adjacency and cut or inconsistent levels are
//! errors at their byte offset, never a panic.

use material::mdl_modules::ptex::{reader, Filter, Ptex};

use crate::mdl_ptex::{centroid, ptex_file, ptex_file_full, read, reduce, Face, How};

/// One float channel per texel, from `values` (row by row, v = 0 first).
fn face(log2: (i8, i8), values: Vec<f64>) -> Face {
    Face { log2, texels: values, how: How::Zipped }
}

/// The first channel of `ptex` at face `f`, (`u`, `v`).
fn at(ptex: &Ptex, f: u32, u: f32, v: f32, width: Option<f32>, filter: Filter) -> f32 {
    let mut out = [0.0f32; 1];
    assert!(ptex.sample(f, u, v, width, filter, 0, &mut out), "face {f}");
    out[0]
}

fn bilinear(ptex: &Ptex, f: u32, u: f32, v: f32) -> f32 {
    at(ptex, f, u, v, None, Filter::Bilinear)
}

/// A 2 × 2 quad face with texels a, b (row v = 0) and c, d: the texel at its centre, the
/// mean of the four at the face centre, of two at an edge's midpoint (clamped at the
/// face's border), the corner texel at a corner, and 3:1 a quarter texel from a centre
/// (1e-6). The nearest filter still gives the texel.
#[test]
fn bilinear_of_a_two_by_two_quad_face() {
    let (a, b, c, d) = (0.1, 0.5, 0.3, 0.9);
    let ptex = read(&ptex_file(1, 3, 1, &[face((1, 1), vec![a, b, c, d])], 6));
    let cases = [
        ((0.25, 0.25), a),
        ((0.75, 0.75), d),
        ((0.5, 0.5), (a + b + c + d) / 4.0),
        ((0.5, 0.0), (a + b) / 2.0),
        ((0.5, 1.0), (c + d) / 2.0),
        ((0.0, 0.5), (a + c) / 2.0),
        ((1.0, 0.5), (b + d) / 2.0),
        ((0.0, 0.0), a),
        ((1.0, 1.0), d),
        ((0.375, 0.25), 0.75 * a + 0.25 * b),
    ];
    for ((u, v), want) in cases {
        let got = bilinear(&ptex, 0, u, v);
        assert!((got - want as f32).abs() <= 1e-6, "({u}, {v}): {got} vs {want}");
    }
    assert!((at(&ptex, 0, 0.45, 0.3, None, Filter::Nearest) - a as f32).abs() <= 1e-6);
    // Through `lookup` (the MDL lookup's default filter), one channel in every lane.
    let l = ptex.lookup(0, 0.5, 0.5, None, 0);
    assert!((l.x - 0.45).abs() <= 1e-6 && l.x == l.w, "{l:?}");
}

/// Triangle faces: every texel at its small triangle's centroid, a grid vertex the mean
/// of the texels around it (1e-6); texels linear in their centroid (1 + 2u − 3v) give
/// that linear function inside the face, around its inner grid vertices (1e-5).
#[test]
fn triangle_interpolation_is_exact_at_centroids_and_linear_inside() {
    let n = 4usize;
    let values: Vec<f64> = (0..n * n).map(|t| ((t * 7) % 11) as f64 / 10.0).collect();
    let linear = |(u, v): (f32, f32)| 1.0 + 2.0 * u - 3.0 * v;
    let lin: Vec<f64> = (0..n * n).map(|t| f64::from(linear(centroid(n, t)))).collect();
    let ptex = read(&ptex_file(0, 3, 1, &[face((2, 2), values.clone()), face((2, 2), lin)], 6));
    for (t, want) in values.iter().enumerate() {
        let (u, v) = centroid(n, t);
        let got = bilinear(&ptex, 0, u, v);
        assert!((got - *want as f32).abs() <= 1e-6, "texel {t} at ({u}, {v}): {got}");
    }
    // Grid vertices: the mean of the texels whose centroids lie around them, found by
    // centroid (six around an inner vertex, three around one on the face's edge).
    let around = |(vi, vj): (f32, f32)| -> Vec<usize> {
        let near = |a: (f32, f32), b: (f32, f32)| (a.0 - b.0).abs() < 1e-4 && (a.1 - b.1).abs() < 1e-4;
        let offsets = [(1.0, 1.0), (-2.0, 1.0), (1.0, -2.0), (-1.0, -1.0), (2.0, -1.0), (-1.0, 2.0)];
        let points = offsets.map(|(a, b)| ((vi + a / 3.0) / n as f32, (vj + b / 3.0) / n as f32));
        (0..n * n).filter(|&t| points.iter().any(|p| near(*p, centroid(n, t)))).collect()
    };
    for (vertex, count) in [((1.0, 1.0), 6), ((2.0, 1.0), 6), ((2.0, 0.0), 3), ((0.0, 3.0), 3), ((2.0, 2.0), 3)] {
        let texels = around(vertex);
        assert_eq!(texels.len(), count, "{vertex:?}");
        let mean = texels.iter().map(|&t| values[t]).sum::<f64>() / count as f64;
        let got = bilinear(&ptex, 0, vertex.0 / n as f32, vertex.1 / n as f32);
        assert!((got - mean as f32).abs() <= 1e-6, "vertex {vertex:?}: {got} vs {mean} of {texels:?}");
    }
    for (vi, vj) in [(1.0, 1.0), (2.0, 1.0), (1.0, 2.0)] {
        for k in 0..12 {
            let angle = k as f32 * std::f32::consts::TAU / 12.0;
            let p = ((vi + 0.25 * angle.cos()) / n as f32, (vj + 0.25 * angle.sin()) / n as f32);
            let got = bilinear(&ptex, 1, p.0, p.1);
            assert!((got - linear(p)).abs() <= 1e-5, "at {p:?}: {got} vs {}", linear(p));
        }
    }
}

/// Files of constant faces (flagged constant, and a constant block) read their value
/// everywhere without adjacency, and with it at a face's centre (its texel's centre or
/// centroid; elsewhere a constant face is blended with its neighbours, `mdl_ptex_seams`),
/// 1e-6.
#[test]
fn constant_faces_are_unchanged() {
    for mesh in [0, 1] {
        let faces = [
            Face { log2: (0, 0), texels: vec![0.25], how: How::ConstantInfo },
            Face { log2: (2, 2), texels: vec![0.75], how: How::ConstantInfo },
            Face { log2: (0, 0), texels: vec![0.5], how: How::ConstantBlock },
        ];
        let adjacency =
            [([1, 2, -1, -1], [0, 0, 0, 0]), ([0, -1, -1, -1], [0, 0, 0, 0]), ([-1, 0, -1, -1], [0, 1, 0, 0])];
        for adj in [&adjacency[..], &[]] {
            let ptex = read(&ptex_file_full(mesh, 3, 1, &faces, 6, adj, &[]));
            for (id, f) in faces.iter().enumerate() {
                let all = [(0.0, 0.0), (0.5, 0.0), (0.2, 0.3), (0.01, 0.98), (0.5, 0.5), (1.0 / 3.0, 1.0 / 3.0)];
                let points = match (mesh, adj.is_empty()) {
                    (_, true) => &all[..],
                    (0, false) => &all[5..],
                    _ => &all[4..5],
                };
                for &(u, v) in points {
                    for width in [None, Some(0.3), Some(2.0)] {
                        let got = at(&ptex, id as u32, u, v, width, Filter::Bilinear);
                        assert!((got - f.texels[0] as f32).abs() <= 1e-6, "mesh {mesh}, face {id}: {got}");
                    }
                }
            }
        }
    }
}

/// Texel values varied per face and texel.
fn varied(face: usize, count: usize) -> Vec<f64> {
    (0..count).map(|t| ((face * 37 + t * 13) % 29) as f64 / 28.0).collect()
}

/// Two quads of 4 × 4 texels sharing face 0's top edge (2) and face 1's right edge (1):
/// just inside either side of the edge, away from its ends, the values agree within 1e-4
/// (the bilinear slope is at most 4 per unit here, the points 1e-6 apart); without the
/// adjacency they differ by more than 0.01 somewhere.
#[test]
fn quad_values_are_continuous_across_a_shared_edge() {
    let faces = [face((2, 2), varied(0, 16)), face((2, 2), varied(1, 16))];
    let adjacency = [([-1, -1, 1, -1], [0, 0, 1, 0]), ([-1, 0, -1, -1], [0, 2, 0, 0])];
    let joined = read(&ptex_file_full(1, 3, 1, &faces, 6, &adjacency, &[]));
    let apart = read(&ptex_file_full(1, 3, 1, &faces, 6, &[], &[]));
    let eps = 1e-6;
    let mut seam = 0.0f32;
    for k in 0..=40 {
        // Face 0's edge 2 runs from u = 1 to u = 0 (t = 1 − u); face 1's edge 1 from v = 0
        // to v = 1: face 0's u is face 1's v.
        let u = 0.2 + 0.6 * k as f32 / 40.0;
        let (f0, f1) = (bilinear(&joined, 0, u, 1.0 - eps), bilinear(&joined, 1, 1.0 - eps, u));
        assert!((f0 - f1).abs() <= 1e-4, "u = {u}: {f0} vs {f1}");
        seam = seam.max((bilinear(&apart, 0, u, 1.0 - eps) - bilinear(&apart, 1, 1.0 - eps, u)).abs());
    }
    assert!(seam > 0.01, "the faces differ at the edge without adjacency ({seam})");
}

/// Three triangles of resolution 4: face 0's long edge (1) against face 1's long edge, and
/// face 0's edge 0 against face 2's edge 2; just inside either side of each edge, away
/// from its ends, the values agree within 1e-4; without adjacency they do not (> 0.01).
#[test]
fn triangle_values_are_continuous_across_shared_edges() {
    let faces = [face((2, 2), varied(0, 16)), face((2, 2), varied(1, 16)), face((2, 2), varied(2, 16))];
    let adjacency = [([2, 1, -1, -1], [2, 1, 0, 0]), ([-1, 0, -1, -1], [0, 1, 0, 0]), ([-1, -1, 0, -1], [0, 0, 0, 0])];
    let joined = read(&ptex_file_full(0, 3, 1, &faces, 6, &adjacency, &[]));
    let apart = read(&ptex_file_full(0, 3, 1, &faces, 6, &[], &[]));
    let eps = 1e-6;
    let mut seam = 0.0f32;
    for k in 0..=40 {
        let t = 0.2 + 0.6 * k as f32 / 40.0;
        // Edge 1 of face 0 at fraction t (from (1, 0) to (0, 1)): (1 − t − ε, t); face 1's
        // edge 1 at fraction 1 − t: (t − ε, 1 − t).
        let pairs = [
            ((0, 1.0 - t - eps, t), (1, t - eps, 1.0 - t)),
            // Edge 0 of face 0 at t: (t, ε); face 2's edge 2 (from (0, 1) to (0, 0)) at
            // 1 − t (its end vertex 0's weight 1 − u − v): (ε, t − ε).
            ((0, t, eps), (2, eps, t - eps)),
        ];
        for ((fa, ua, va), (fb, ub, vb)) in pairs {
            let (a, b) = (bilinear(&joined, fa, ua, va), bilinear(&joined, fb, ub, vb));
            assert!((a - b).abs() <= 1e-4, "faces {fa}/{fb} at t = {t}: {a} vs {b}");
            seam = seam.max((bilinear(&apart, fa, ua, va) - bilinear(&apart, fb, ub, vb)).abs());
        }
    }
    assert!(seam > 0.01, "the faces differ at their edges without adjacency ({seam})");
}

/// Quad faces of 2^1, 2^3 and 2^4 texels a side: Ptex's reduction order is face 2, face 1,
/// face 0 (larger smaller side first); level 1 holds faces 2 and 1, level 2 face 2. The
/// reduced levels read back as written (box reductions; 1e-6), each face ends in its
/// average, and a filter width picks the level whose texels it spans.
#[test]
fn reduced_levels_read_back_and_a_wide_footprint_picks_them() {
    let sizes = [1i8, 3, 4];
    let faces: Vec<Face> = sizes.iter().enumerate().map(|(id, &l)| face((l, l), varied(id, 1 << (2 * l)))).collect();
    let reduced = |f: &Face, times: usize| {
        let (mut values, mut n) = (f.texels.clone(), 1usize << f.log2.0);
        for _ in 0..times {
            values = reduce(&values, n);
            n /= 2;
        }
        face((n.trailing_zeros() as i8, n.trailing_zeros() as i8), values)
    };
    let level1 = vec![reduced(&faces[2], 1), reduced(&faces[1], 1)];
    let level2 = vec![reduced(&faces[2], 2)];
    let ptex = read(&ptex_file_full(1, 3, 1, &faces, 6, &[], &[level1.clone(), level2.clone()]));
    let expect = [vec![], vec![&level1[1]], vec![&level1[0], &level2[0]]];
    for (id, levels) in expect.iter().enumerate() {
        assert_eq!(ptex.reductions[id].len(), levels.len() + 1, "face {id}: its levels and its average");
        for (k, written) in levels.iter().enumerate() {
            let stored = ptex.reductions[id][k];
            assert_eq!((stored.ulog2, stored.vlog2), (written.log2.0 as u8, written.log2.1 as u8));
            let n = 1usize << stored.ulog2;
            for (t, want) in written.texels.iter().enumerate() {
                let (u, v) = (((t % n) as f32 + 0.5) / n as f32, ((t / n) as f32 + 0.5) / n as f32);
                // A width of one texel of this level picks it.
                let width = Some(1.0 / n as f32);
                assert_eq!(ptex.level_for(id, width), k + 1);
                let got = at(&ptex, id as u32, u, v, width, Filter::Nearest);
                assert!((got - *want as f32).abs() <= 1e-6, "face {id} level {}: texel {t} {got} vs {want}", k + 1);
            }
        }
        let mean = faces[id].texels.iter().sum::<f64>() / faces[id].texels.len() as f64;
        let got = at(&ptex, id as u32, 0.3, 0.6, Some(1.0), Filter::Bilinear);
        assert!((got - mean as f32).abs() <= 1e-6, "face {id}: a face-wide footprint reads the average {got}");
    }
    // Narrow widths read level 0; a width between two levels' texels the finer one.
    assert_eq!(ptex.level_for(2, None), 0);
    assert_eq!(ptex.level_for(2, Some(1.0 / 16.0)), 0);
    assert_eq!(ptex.level_for(2, Some(1.5 / 16.0)), 0);
    assert_eq!(ptex.level_for(2, Some(3.0 / 16.0)), 1);
    assert_eq!(ptex.level_for(2, Some(0.25)), 2);
    // Exactly between two levels (the geometric mean of their texel widths): the finer.
    assert_eq!(ptex.level_for(2, Some(2f32.sqrt() / 16.0)), 0);
    assert_eq!(ptex.level_for(2, Some(2f32.sqrt() / 8.0)), 1);
    // Face 1 has one reduced level: wider widths fall back to it until the face's width.
    assert_eq!(ptex.level_for(1, Some(0.5)), 1);
    assert_eq!(ptex.level_for(1, Some(1.0)), 2);
    // Bilinear at level 1 of face 2 interpolates that level's texels.
    let l1 = &level1[0].texels;
    let got = at(&ptex, 2, 0.25, 0.25, Some(0.125), Filter::Bilinear);
    let want = (l1[8 + 1] + l1[8 + 2] + l1[16 + 1] + l1[16 + 2]) / 4.0;
    assert!((got - want as f32).abs() <= 1e-6, "{got} vs {want}");
}

/// With an alpha channel Ptex stores reduced levels premultiplied by alpha (level 0 and
/// the averages straight): RGBA floats, alpha channel 3, read back straight (1e-6); alpha
/// channel 0 divides the channels after it. A face with an edit drops its reduced levels
/// (the file's are of the face before the edit).
#[test]
fn reduced_levels_are_read_straight_and_edits_drop_them() {
    let texels = |n: usize, alpha_at: usize| -> Vec<f64> {
        (0..n * 4)
            .map(|k| if k % 4 == alpha_at { 0.25 + 0.5 * ((k / 4) % 2) as f64 } else { (k % 7) as f64 / 8.0 })
            .collect()
    };
    for alpha_at in [3usize, 0] {
        let straight = texels(16, alpha_at);
        let premultiplied: Vec<f64> = straight
            .chunks(4)
            .flat_map(|t| {
                (0..4).map(move |c| {
                    let colour = if alpha_at == 0 { c > 0 } else { c < alpha_at };
                    if colour {
                        t[c] * t[alpha_at]
                    } else {
                        t[c]
                    }
                })
            })
            .collect();
        let faces = [Face { log2: (3, 3), texels: texels(64, alpha_at), how: How::Zipped }];
        let level1 = vec![Face { log2: (2, 2), texels: premultiplied, how: How::Zipped }];
        let mut file = ptex_file_full(1, 3, 4, &faces, 6, &[], &[level1]);
        file[16..20].copy_from_slice(&(alpha_at as i32).to_le_bytes());
        let ptex = read(&file);
        assert_eq!(ptex.alpha, Some(alpha_at));
        for t in 0..16 {
            let (u, v) = (((t % 4) as f32 + 0.5) / 4.0, ((t / 4) as f32 + 0.5) / 4.0);
            let mut out = [0.0f32; 4];
            assert!(ptex.sample(0, u, v, Some(0.25), Filter::Nearest, 0, &mut out));
            for c in 0..4 {
                let want = straight[t * 4 + c] as f32;
                assert!((out[c] - want).abs() <= 1e-6, "alpha {alpha_at}, texel {t}, channel {c}: {out:?}");
            }
        }
    }

    // An edit of face 0 (after the file's sections): its reduced level is dropped, its
    // average is the edit's constant value.
    let faces = [face((3, 3), varied(0, 64))];
    let mut file = ptex_file_full(1, 3, 1, &faces, 6, &[], &[vec![face((2, 2), varied(1, 16))]]);
    assert_eq!(read(&file).reductions[0].len(), 2);
    let data = {
        let floats: Vec<u8> = varied(2, 4).iter().flat_map(|x| (*x as f32).to_le_bytes()).collect();
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::new(6));
        std::io::Write::write_all(&mut z, &floats).unwrap();
        z.finish().unwrap()
    };
    let mut body = 0u32.to_le_bytes().to_vec();
    body.extend([1u8, 1, 0, 0]);
    body.extend([-1i32; 4].iter().flat_map(|a| a.to_le_bytes()));
    body.extend((data.len() as u32 | 1 << 30).to_le_bytes());
    body.extend(0.625f32.to_le_bytes());
    body.extend(data);
    file.push(0);
    file.extend((body.len() as u32).to_le_bytes());
    file.extend(body);
    let ptex = read(&file);
    assert_eq!(ptex.reductions[0].len(), 1, "the edit's average only");
    assert!((at(&ptex, 0, 0.5, 0.5, Some(1.0), Filter::Bilinear) - 0.625).abs() <= 1e-6);
    assert!((at(&ptex, 0, 0.25, 0.25, Some(0.25), Filter::Nearest) - varied(2, 4)[0] as f32).abs() <= 1e-6);
}

/// Triangle faces' reduced levels (square, in Ptex's triangle layout) read back texel by
/// texel at their small triangles' centroids (1e-6).
#[test]
fn triangle_reduced_levels_read_back() {
    let faces = [face((3, 3), varied(0, 64)), face((1, 1), varied(1, 4))];
    let level1 = vec![face((2, 2), varied(5, 16))];
    let level2 = vec![face((1, 1), varied(6, 4))];
    let ptex = read(&ptex_file_full(0, 3, 1, &faces, 0, &[], &[level1.clone(), level2.clone()]));
    for (k, written) in [&level1[0], &level2[0]].iter().enumerate() {
        let n = 1usize << written.log2.0;
        for (t, want) in written.texels.iter().enumerate() {
            let (u, v) = centroid(n, t);
            let got = at(&ptex, 0, u, v, Some(1.0 / n as f32), Filter::Nearest);
            assert!((got - *want as f32).abs() <= 1e-6, "level {}: texel {t} {got} vs {want}", k + 1);
        }
    }
    assert_eq!(ptex.reductions[1].len(), 1, "face 1: its average only");
}

/// Hostile adjacency and levels: errors naming the byte offset of the part (the face
/// infos at byte 104; a level's info or data), and every byte of a file with adjacency
/// and levels changed in turn is an error or a texture whose lookups do not panic.
#[test]
fn bad_adjacency_and_levels_are_errors_at_their_offset() {
    let faces = [face((2, 2), varied(0, 16)), face((2, 2), varied(1, 16))];
    let bad_face = [([7, -1, -1, -1], [0; 4]), ([-1; 4], [0; 4])];
    let e = reader::read(&ptex_file_full(1, 3, 1, &faces, 0, &bad_face, &[])).unwrap_err();
    assert!(e.offset == 104 && e.message.contains("face 0") && e.message.contains("edge 0"), "{e}");
    let negative = [([-1, -5, -1, -1], [0; 4]), ([-1; 4], [0; 4])];
    assert_eq!(reader::read(&ptex_file_full(1, 3, 1, &faces, 0, &negative, &[])).unwrap_err().offset, 104);
    // A triangle's edge 3 does not exist.
    let edge3 = [([1, -1, -1, -1], [3, 0, 0, 0]), ([-1; 4], [0; 4])];
    let e = reader::read(&ptex_file_full(0, 3, 1, &faces, 0, &edge3, &[])).unwrap_err();
    assert!(e.offset == 104 && e.message.contains("edge 3"), "{e}");

    let faces = [face((3, 3), varied(0, 64)), face((3, 3), varied(1, 64))];
    let level1 = vec![face((2, 2), varied(2, 16)), face((2, 2), varied(3, 16))];
    let good = ptex_file_full(1, 3, 1, &faces, 0, &[([1, -1, -1, -1], [2, 0, 0, 0]); 2], &[level1]);
    read(&good);
    let info_at = 64
        + 40
        + u32::from_le_bytes(good[32..36].try_into().unwrap()) as usize
        + u32::from_le_bytes(good[36..40].try_into().unwrap()) as usize;
    let level0_size = u64::from_le_bytes(good[info_at..info_at + 8].try_into().unwrap()) as usize;
    let level1_at = info_at + 32 + level0_size;
    // Level 1 cut short (the file ends inside it): an error at or after level 1's start,
    // never before it.
    let level1_size = u64::from_le_bytes(good[info_at + 16..info_at + 24].try_into().unwrap()) as usize;
    for len in level1_at..level1_at + level1_size {
        let e = reader::read(&good[..len]).expect_err("a cut level");
        assert!(e.offset >= level1_at as u64 && e.offset <= len as u64, "cut at {len}: {e}");
    }
    // Level 1 claiming more faces than the file has: an error at its level info.
    let mut many = good.clone();
    many[info_at + 28..info_at + 32].copy_from_slice(&3u32.to_le_bytes());
    let e = reader::read(&many).unwrap_err();
    assert!(e.offset == info_at as u64 + 16 && e.message.contains("level 1"), "{e}");
    // Level 1's size too small for its faces: an error at its data.
    let mut small = good.clone();
    small[info_at + 16..info_at + 24].copy_from_slice(&10u64.to_le_bytes());
    let e = reader::read(&small).unwrap_err();
    assert_eq!(e.offset, level1_at as u64, "{e}");

    for at in 0..good.len() {
        for x in [0x00, 0xff, 0x80] {
            let mut bytes = good.clone();
            bytes[at] ^= x | 1;
            if let Ok((ptex, _)) = reader::read(&bytes) {
                let mut out = [0.0f32; 4];
                for f in 0..3 {
                    for (u, v) in [(0.0, 0.0), (0.99, 0.5), (0.5, 1.0), (0.1, 0.01)] {
                        for width in [None, Some(0.2), Some(1.0)] {
                            ptex.sample(f, u, v, width, Filter::Bilinear, 0, &mut out);
                        }
                    }
                }
            }
        }
    }
}
