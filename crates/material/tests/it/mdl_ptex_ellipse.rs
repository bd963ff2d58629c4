//! Elliptical Ptex footprints (`Ptex::sample_ellipse`, `footprint::filter_ellipse`): a
//! footprint diagonal to a face's axes is probed along its major axis, not read as its
//! bounding rectangle; probes past a face edge are spaced at the finer face's texels (its
//! own resolution, the axis carried through the edge's orientation). Files written byte by
//! byte by `mdl_ptex`'s writer.

use glam::Vec3A;
use material::mdl_modules::ptex::anisotropic::major_axis_weights;
use material::mdl_modules::ptex::footprint::{filter_ellipse, filter_width, FaceEllipse};
use material::mdl_modules::ptex::{Filter, MeshType, Ptex};
use shader::State;

use crate::mdl_ptex::{ptex_file_full, read, reduced_levels, Face, How};

/// One quad face of 64 × 64 texels striped along its diagonal u = v: texel (i, j) is 1
/// where (i − j) mod 8 < 4, else 0 (stripes 4 texels wide along u), with its box-reduced
/// levels down to 2 × 2.
fn diagonal_stripes() -> Ptex {
    let n = 64usize;
    let texels: Vec<f64> =
        (0..n * n).map(|t| if ((t % n) as i64 - (t / n) as i64).rem_euclid(8) < 4 { 1.0 } else { 0.0 }).collect();
    let levels = reduced_levels(&texels, n);
    read(&ptex_file_full(1, 3, 1, &[Face { log2: (6, 6), texels, how: How::Zipped }], 6, &[], &levels))
}

fn ellipse_at(ptex: &Ptex, face: u32, u: f32, v: f32, ellipse: FaceEllipse) -> f32 {
    let mut out = [0.0f32; 1];
    assert!(ptex.sample_ellipse(face, u, v, ellipse, 0, &mut out));
    out[0]
}

fn sample_at(ptex: &Ptex, face: u32, u: f32, v: f32, width: f32) -> f32 {
    let mut out = [0.0f32; 1];
    assert!(ptex.sample(face, u, v, Some(width), Filter::Bilinear, 0, &mut out));
    out[0]
}

/// A footprint 0.25 × 1/256 (face units) in the middle of a stripe of the diagonal stripes
/// (texel-centre coordinates x − y = 1.5): along the stripes (axis (1, 1) / √2) it reads
/// the stripe's colour, 1, within 2 % (12 probes on level 0); across them (axis (1, −1) /
/// √2, 3 periods long) the stripes' mean, 0.5, within 2 %. Its bounding rectangle in face
/// space (equal widths along u and v: the isotropic width √(0.25 / 256), two texels) is
/// off the stripe's colour by more than 5 % (measured 0.930). A round footprint reads exactly the
/// isotropic lookup (bit for bit) at widths from 1/200 to 1, and one along u or v exactly
/// `sample_rect`.
#[test]
fn a_diagonal_footprint_averages_along_its_major_axis() {
    let ptex = diagonal_stripes();
    let (u, v) = (0.5 + 0.75 / 64.0, 0.5 - 0.75 / 64.0);
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let along = ellipse_at(&ptex, 0, u, v, FaceEllipse { axis: (h, h), major: 0.25, minor: 1.0 / 256.0 });
    // 3 periods across: 24 texels of i − j, 24 / (64 √2) face units.
    let across_major = 24.0 / (64.0 * std::f32::consts::SQRT_2) * (1.0 - 1e-4);
    let across = ellipse_at(&ptex, 0, u, v, FaceEllipse { axis: (h, -h), major: across_major, minor: 1.0 / 256.0 });
    let rect = {
        let w = (0.25f32 / 256.0).sqrt();
        let mut out = [0.0f32; 1];
        assert!(ptex.sample_rect(0, u, v, (w, w), 0, &mut out));
        out[0]
    };
    let message = format!("along {along}, across {across}, bounding rectangle {rect}");
    assert!((along - 1.0).abs() <= 0.02, "{message}");
    assert!((across - 0.5).abs() <= 0.02 * 0.5, "{message}");
    assert!((rect - 1.0).abs() > 0.05, "{message}");
    eprintln!("{message}");
    for width in [0.005f32, 0.02, 0.07, 0.3, 1.0] {
        for k in 0..20 {
            let (u, v) = ((k as f32 * 0.37).fract(), (k as f32 * 0.61).fract());
            assert_eq!(ellipse_at(&ptex, 0, u, v, FaceEllipse::round(width)), sample_at(&ptex, 0, u, v, width));
            let widths = (width, 3.0 * width);
            let mut out = [0.0f32; 1];
            assert!(ptex.sample_rect(0, u, v, widths, 0, &mut out));
            assert_eq!(ellipse_at(&ptex, 0, u, v, FaceEllipse::along_axes(widths)), out[0]);
        }
    }
}

/// A hit on a plane of square quad faces (dP/du = x, dP/dv = y), 75° off the normal,
/// tilted along the diagonal (1, 1): the footprint's ellipse has its major axis along
/// (1, 1) / √2 and its widths' ratio 1 / cos 75° (1e-4), their product the isotropic
/// width's square (1e-5 relative); head-on it is round at the isotropic width (exact).
#[test]
fn a_diagonal_tilt_gives_a_diagonal_ellipse() {
    let (s75, c75) = (75f32.to_radians().sin(), 75f32.to_radians().cos());
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let mut s = State {
        dir: Vec3A::new(s75 * h, s75 * h, -c75),
        normal_geom: Vec3A::Z,
        camera_footprint: 0.05,
        tri_area: 0.5,
        face_edges: [Vec3A::X, Vec3A::new(1.0, 1.0, 0.0)],
        ptex_quad_jacobian: [1.0, 0.0, 1.0, 1.0],
        ptex_quad: Some((0, 0.5, 0.5)),
        ..State::default()
    };
    let e = filter_ellipse(MeshType::Quad, &s).expect("an ellipse");
    let w = filter_width(&s).unwrap();
    let sign = e.axis.0.signum();
    assert!((e.axis.0 * sign - h).abs() < 1e-4 && (e.axis.1 * sign - h).abs() < 1e-4, "{e:?}");
    assert!((e.major / e.minor * c75 - 1.0).abs() < 1e-4, "{e:?}");
    assert!((e.major * e.minor / (w * w) - 1.0).abs() < 1e-5, "{e:?}");
    s.dir = -Vec3A::Z;
    assert_eq!(filter_ellipse(MeshType::Quad, &s), Some(FaceEllipse::round(filter_width(&s).unwrap())));
}

/// Two quad faces of different resolutions, the second turned: face 0 of 4 × 4 texels, all
/// a = 0.25, and face 1 of 4 × 16 (u × v), whose edge 0 (v = 0) is face 0's edge 1
/// (u = 1): a point past face 0's u = 1 at v lies on face 1 at (1 − v, u − 1), so face
/// 0's u runs along face 1's v. Both with their box-reduced levels. A footprint 1 long
/// along face 0's u and 1/64 wide, centred on the edge at v = 3/8 (face 1's u = 5/8, the
/// middle of its column 2): its far end lies on face 1 with the axis along face 1's v, a
/// texel there 1/16: 16 probes spaced 1/16, each 1/16 wide (level 0 on both faces). Their
/// values, by hand: 6 of face 0's a, two in face 0's half texel along the edge (3/4 a +
/// 1/4 e and 1/4 a + 3/4 e, e = (a + b) / 2 the edge's value, b face 1's column 2), 8 of
/// face 1's column 2 (at its texel centres): their sum with the probes' Gaussian weights
/// (`major_axis_weights(16)`), matched within 1e-3 for face 1 constant (b = 0.75) and for face 1 striped by column (1, 0, 1, 0: b =
/// 1). Probed at face 0's spacing (4 probes 1/4 wide: face 1's stripes read at its 1 × 4
/// level, their mean) the stripes' value is off by more than 0.1.
#[test]
fn probes_across_an_edge_take_the_neighbours_resolution() {
    let a = 0.25f64;
    for (columns, b) in [([0.75f64; 4], 0.75f64), ([1.0, 0.0, 1.0, 0.0], 1.0)] {
        let small = Face { log2: (2, 2), texels: vec![a; 16], how: How::Zipped };
        let tall_texels: Vec<f64> = (0..64).map(|t| columns[t % 4]).collect();
        let tall = Face { log2: (2, 4), texels: tall_texels, how: How::Zipped };
        // Levels 1 and 2 (reduction order: both faces' smaller side is 2^2; face order).
        let column_pairs: Vec<f64> = (0..16).map(|t| (columns[2 * (t % 2)] + columns[2 * (t % 2) + 1]) / 2.0).collect();
        let mean = columns.iter().sum::<f64>() / 4.0;
        let levels = vec![
            vec![
                Face { log2: (1, 1), texels: vec![a; 4], how: How::Zipped },
                Face { log2: (1, 3), texels: column_pairs, how: How::Zipped },
            ],
            vec![
                Face { log2: (0, 0), texels: vec![a; 1], how: How::Zipped },
                Face { log2: (0, 2), texels: vec![mean; 4], how: How::Zipped },
            ],
        ];
        let adjacency = [([-1, 1, -1, -1], [0, 0, 0, 0]), ([0, -1, -1, -1], [1, 0, 0, 0])];
        let ptex = read(&ptex_file_full(1, 3, 1, &[small, tall], 6, &adjacency, &levels));
        let (u, v) = (1.0f32, 0.375f32);
        let got =
            f64::from(ellipse_at(&ptex, 0, u, v, FaceEllipse { axis: (1.0, 0.0), major: 1.0, minor: 1.0 / 64.0 }));
        let e = (a + b) / 2.0;
        let values = [a, a, a, a, a, a, 0.75 * a + 0.25 * e, 0.25 * a + 0.75 * e, b, b, b, b, b, b, b, b];
        let weights = major_axis_weights(16);
        let want: f64 = values.iter().zip(weights).map(|(x, w)| x * f64::from(w)).sum();
        // At face 0's spacing: 4 probes 1/4 apart, each 1/4 wide.
        let first_face: f64 = (0..4)
            .map(|k| {
                let (face, pu, pv) = ptex.across_edges(0, u - 0.5 + (k as f32 + 0.5) * 0.25, v);
                f64::from(sample_at(&ptex, face, pu, pv, 0.25)) * f64::from(major_axis_weights(4)[k])
            })
            .sum();
        let message = format!("b {b}: got {got}, by hand {want}, at face 0's spacing {first_face}");
        assert!((got - want).abs() <= 1e-3, "{message}");
        if columns[0] != columns[1] {
            assert!((first_face - want).abs() > 0.1, "{message}");
        }
        eprintln!("{message}");
    }
}

/// A strip of three quad faces along u, the middle one finer: face 0 and face 2 constant
/// (1 × 1, 0), face 1 of 4 × 1 texels (0, 1, 0, 0), each sharing its u = 1 edge with the
/// next one's u = 0 edge (no reduced levels: every probe reads level 0). A footprint 3
/// long along u and 1/64 wide centred at u = 0.75 on face 0 crosses face 1 and ends
/// 0.25 into face 2: a texel along the axis is 1 at its centre and both ends but 1/4 in
/// face 1, so it is probed 12 times, 1/4 apart and 1/4 wide, and probe 8 lands on the
/// centre of face 1's texel 1, every other probe on a 0 (face 0 and face 2 blend only
/// toward edge values of 0; face 1's other texels 0, read at their centres): it reads
/// probe 8's weight, `major_axis_weights(12)[8]`, within 1e-4. Spaced by the centre and
/// the ends alone (3 probes 1 apart, 1 wide, at u = −0.25, 0.75, 1.75) the lookup would
/// read face 1 once, at its average (0.25 × the middle probe's weight, 0.0817): off by
/// more than 0.005, 50 times the tolerance.
#[test]
fn a_crossed_face_sets_the_probes_spacing() {
    let constant = || Face { log2: (0, 0), texels: vec![0.0], how: How::ConstantInfo };
    let middle = Face { log2: (2, 0), texels: vec![0.0, 1.0, 0.0, 0.0], how: How::Zipped };
    let adjacency = [([-1, 1, -1, -1], [0, 3, 0, 0]), ([-1, 2, -1, 0], [0, 3, 0, 1]), ([-1, -1, -1, 1], [0, 0, 0, 1])];
    let ptex = read(&ptex_file_full(1, 3, 1, &[constant(), middle, constant()], 6, &adjacency, &[]));
    let (u, v) = (0.75f32, 0.5f32);
    let got = ellipse_at(&ptex, 0, u, v, FaceEllipse { axis: (1.0, 0.0), major: 3.0, minor: 1.0 / 64.0 });
    let want = major_axis_weights(12)[8];
    let ends_only: f32 = (0..3)
        .map(|k| {
            let (face, pu, pv) = ptex.across_edges(0, u - 1.0 + k as f32, v);
            sample_at(&ptex, face, pu, pv, 1.0) * major_axis_weights(3)[k]
        })
        .sum();
    let message = format!("got {got}, by hand {want}, spaced by the centre and ends {ends_only}");
    assert!((got - want).abs() <= 1e-4, "{message}");
    assert!((ends_only - want).abs() > 0.005, "{message}");
    eprintln!("{message}");
}
