//! Ptex's sub-faces (quad-mesh files: the sub-quads of a non-quad face, flagged 8, half a
//! quad face's size in parameter space) met by the elliptical lookup's probes
//! (`Ptex::across_edges`, `Ptex::sample_ellipse`). Files written byte by byte by
//! `mdl_ptex`'s writer.

use material::mdl_modules::ptex::anisotropic::major_axis_weights;
use material::mdl_modules::ptex::footprint::FaceEllipse;
use material::mdl_modules::ptex::{Filter, Ptex};

use crate::mdl_ptex::{ptex_file_sub_faces, read, reduce, Face, How};

/// A quad face 0 whose edge 1 (u = 1) lies against a non-quad face's two sub-faces: the
/// primary, face 1, along the edge's first half (v < ½) by its edge 3 (u = 0), and the
/// secondary, face 2, along the second half by its edge 0 (v = 0); faces 1 and 2 share
/// face 1's edge 2 and face 2's edge 1 (Ptex's layout of sub-quads i + 1 and i about the
/// midpoint of polygon edge i → i + 1). Each 8 × 8 texels, `texel(face, i, j)`, with its
/// box-reduced levels; faces 1 and 2 flagged sub-faces.
fn quad_beside_sub_faces(texel: impl Fn(usize, usize, usize) -> f64) -> Ptex {
    let faces: Vec<Vec<f64>> = (0..3).map(|f| (0..64).map(|t| texel(f, t % 8, t / 8)).collect()).collect();
    let mut levels = Vec::new();
    let (mut values, mut side) = (faces.clone(), 8usize);
    while side > 1 {
        values = values.iter().map(|v| reduce(v, side)).collect();
        side /= 2;
        let log2 = side.trailing_zeros() as i8;
        levels.push(values.iter().map(|v| Face { log2: (log2, log2), texels: v.clone(), how: How::Zipped }).collect());
    }
    let level0: Vec<Face> = faces.into_iter().map(|t| Face { log2: (3, 3), texels: t, how: How::Zipped }).collect();
    let adjacency = [([-1, 1, -1, -1], [0, 3, 0, 0]), ([-1, -1, 2, 0], [0, 0, 1, 1]), ([0, 1, -1, -1], [1, 2, 0, 0])];
    read(&ptex_file_sub_faces(1, 3, 1, &level0, 6, &adjacency, &levels, &[1, 2]))
}

/// A point 0.1 past the quad face's edge lands 0.2 into a sub-face (twice the depth), at
/// twice its distance from the edge's start: at v = ¼ on the primary at (0.2, ½), at v = ¾
/// on the secondary at (½, 0.2) (carried on from the primary across their shared edge);
/// a point 0.2 past either sub-face's edge lands 0.1 into the quad face at the matching
/// half of its edge, (0.9, ¼) and (0.9, ¾); 0.05 past at v = 0.1 and 0.9: (0.1, 0.2) on
/// the primary, (0.2, 0.1) on the secondary (1e-6). The sub-face flags read back.
#[test]
fn sub_faces_meet_a_quad_face_at_half_its_edge() {
    let ptex = quad_beside_sub_faces(|_, _, _| 0.5);
    assert!(!ptex.is_subface(0) && ptex.is_subface(1) && ptex.is_subface(2));
    let near =
        |(f, u, v): (u32, f32, f32), (g, a, b): (u32, f32, f32)| f == g && (u - a).abs() < 1e-6 && (v - b).abs() < 1e-6;
    for (from, to) in [
        ((0, 1.1, 0.25), (1, 0.2, 0.5)),
        ((0, 1.1, 0.75), (2, 0.5, 0.2)),
        ((1, -0.2, 0.5), (0, 0.9, 0.25)),
        ((2, 0.5, -0.2), (0, 0.9, 0.75)),
        ((0, 1.05, 0.1), (1, 0.1, 0.2)),
        ((0, 1.05, 0.9), (2, 0.2, 0.1)),
    ] {
        let got = ptex.across_edges(from.0, from.1, from.2);
        assert!(near(got, to), "{from:?}: {got:?}, want {to:?}");
    }
}

/// An elliptical footprint on the quad face reaching into the primary sub-face reads its
/// probes there at twice their width in the quad face's units: a footprint 1 along u and
/// 0.3 across at (0.75, ¼) of face 0 (4 probes 1/4 apart: the texel along the axis 1/4 on
/// face 0 at the level its 0.3 picks, 1/2 of the sub-face's at the level 0.6 picks, read
/// at half: 1/4), the last at (0.25, ½) of face 1 read 0.6 wide (2 × max(0.3, 0.25)),
/// the others 0.3 wide: the probes' weighted sum read by hand (1e-6). Face 1 ramps along
/// u (texel (i, j) = i / 7), so its width matters: read 0.3 wide there, off by > 0.005.
#[test]
fn a_probe_in_a_sub_face_reads_it_at_twice_the_width() {
    let ptex =
        quad_beside_sub_faces(|f, i, j| if f == 1 { i as f64 / 7.0 } else { ((i + 2 * j + f) % 5) as f64 / 4.0 });
    let sample = |face: u32, u: f32, v: f32, width: f32| {
        let mut out = [0.0f32; 1];
        assert!(ptex.sample(face, u, v, Some(width), Filter::Bilinear, 0, &mut out));
        out[0]
    };
    let mut got = [0.0f32; 1];
    let ellipse = FaceEllipse { axis: (1.0, 0.0), major: 1.0, minor: 0.3 };
    assert!(ptex.sample_ellipse(0, 0.75, 0.25, ellipse, 0, &mut got));
    let weights = major_axis_weights(4);
    let probes = [(0u32, 0.375f32, 0.25f32), (0, 0.625, 0.25), (0, 0.875, 0.25), (1, 0.25, 0.5)];
    let read = |sub_width: f32| -> f32 {
        probes
            .iter()
            .zip(weights)
            .map(|(&(f, u, v), w)| w * sample(f, u, v, if f == 1 { sub_width } else { 0.3 }))
            .sum()
    };
    let (want, unscaled) = (read(0.6), read(0.3));
    let message = format!("got {}, by hand {want}, the sub-face read 0.3 wide {unscaled}", got[0]);
    assert!((got[0] - want).abs() <= 1e-6, "{message}");
    assert!((unscaled - want).abs() > 0.005, "{message}");
    eprintln!("{message}");
}
