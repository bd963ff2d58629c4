//! Gaussian weights along an elliptical footprint's major axis (`Ptex::sample_ellipse`,
//! `anisotropic::major_axis_weights`): Ptex's kernel exp(−2 x²), x the distance from the
//! footprint's centre in major widths, over the footprint's own major width. Files written
//! byte by byte by `mdl_ptex`'s writer.

use material::mdl_modules::ptex::anisotropic::{major_axis_weights, MAX_PROBES};
use material::mdl_modules::ptex::footprint::FaceEllipse;
use material::mdl_modules::ptex::Ptex;

use crate::mdl_ptex::{ptex_file_full, read, reduced_levels, Face, How};

/// One quad face of 64 × 64 texels, texel (i, j) = `f(i, j)`, with its box-reduced levels
/// down to 2 × 2.
fn face_of(f: impl Fn(usize, usize) -> f64) -> Ptex {
    let n = 64usize;
    let texels: Vec<f64> = (0..n * n).map(|t| f(t % n, t / n)).collect();
    let levels = reduced_levels(&texels, n);
    read(&ptex_file_full(1, 3, 1, &[Face { log2: (6, 6), texels, how: How::Zipped }], 6, &[], &levels))
}

fn ellipse_at(ptex: &Ptex, u: f32, v: f32, ellipse: FaceEllipse) -> f32 {
    let mut out = [0.0f32; 1];
    assert!(ptex.sample_ellipse(0, u, v, ellipse, 0, &mut out));
    out[0]
}

/// The weights of 1 to 16 probes sum to 1 (1e-6), are symmetric about the centre (1e-6),
/// fall off from the centre, and follow exp(−2 x²) (x = (k + ½) / n − ½; the ratio of
/// each weight to the centre's, 1e-5); entries past the probes are 0.
#[test]
fn the_weights_are_a_normalised_gaussian() {
    for n in 1..=MAX_PROBES {
        let w = major_axis_weights(n);
        let sum: f32 = w.iter().sum();
        assert!((sum - 1.0).abs() <= 1e-6, "n {n}: sum {sum}");
        assert!(w[n..].iter().all(|&x| x == 0.0), "n {n}: {w:?}");
        for k in 0..n {
            assert!((w[k] - w[n - 1 - k]).abs() <= 1e-6, "n {n}: {w:?}");
            let x = (k as f64 + 0.5) / n as f64 - 0.5;
            let x0 = (n / 2) as f64 + 0.5;
            let x0 = x0 / n as f64 - 0.5;
            let ratio = f64::from(w[k]) / f64::from(w[n / 2]);
            assert!((ratio - (-2.0 * (x * x - x0 * x0)).exp()).abs() <= 1e-5, "n {n} k {k}: {ratio}");
            if k + 1 < n.div_ceil(2) {
                assert!(w[k] < w[k + 1], "n {n}: {w:?}");
            }
        }
    }
}

/// A face whose texels ramp linearly along the footprint's major axis reads the ramp's
/// value at the footprint's centre (the weights are symmetric; 1e-5): along u (value u),
/// along the diagonal (value (u + v) / 2, axis (1, 1) / √2), at several centres, a
/// footprint 0.4 × 1/256 (16 probes on level 0 or 1).
#[test]
fn a_ramp_along_the_axis_reads_its_centre() {
    let along_u = face_of(|i, _| (i as f64 + 0.5) / 64.0);
    let diagonal = face_of(|i, j| (i as f64 + j as f64 + 1.0) / 128.0);
    let h = std::f32::consts::FRAC_1_SQRT_2;
    for (u, v) in [(0.5f32, 0.5f32), (0.4, 0.6), (0.55, 0.45)] {
        let got = ellipse_at(&along_u, u, v, FaceEllipse { axis: (1.0, 0.0), major: 0.4, minor: 1.0 / 256.0 });
        assert!((got - u).abs() <= 1e-5, "along u at ({u}, {v}): {got}");
        let got = ellipse_at(&diagonal, u, v, FaceEllipse { axis: (h, h), major: 0.4, minor: 1.0 / 256.0 });
        assert!((got - (u + v) / 2.0).abs() <= 1e-5, "diagonal at ({u}, {v}): {got}");
    }
}

/// A step edge across the major axis (texels 0 for i < 32, 1 from i = 32: the edge at
/// u = ½) a quarter of the major width right of the footprint's centre: a footprint 0.5 ×
/// 1/256 along u centred at u = 0.375 has 16 probes 1/32 apart, at level 1's texel
/// centres, the last 4 past the edge; it reads the truncated Gaussian's weight right of
/// the edge, (erf(√2 ½) − erf(√2 ¼)) / (2 erf(√2 ½)) ≈ 0.2195 (the kernel's integral,
/// Simpson's rule), within 1e-3 (the 16 probes' midpoint sum: 0.21951); equal (box)
/// weights would read 4 / 16 = 0.25, off by > 0.02. Mirrored (centre 0.625, edge a
/// quarter width left of it): 1 − that, 1e-3.
#[test]
fn a_step_edge_reads_the_gaussian_cdf() {
    let step = face_of(|i, _| if i >= 32 { 1.0 } else { 0.0 });
    let kernel = |x: f64| (-2.0 * x * x).exp();
    let integral = |a: f64, b: f64| {
        let n = 2000;
        let h = (b - a) / n as f64;
        (0..=n)
            .map(|k| {
                let c = if k == 0 || k == n {
                    1.0
                } else if k % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                c * kernel(a + k as f64 * h)
            })
            .sum::<f64>()
            * h
            / 3.0
    };
    let want = integral(0.25, 0.5) / integral(-0.5, 0.5);
    let ellipse = FaceEllipse { axis: (1.0, 0.0), major: 0.5, minor: 1.0 / 256.0 };
    let right = f64::from(ellipse_at(&step, 0.375, 0.5, ellipse));
    let left = f64::from(ellipse_at(&step, 0.625, 0.5, ellipse));
    let message = format!("right of the edge {right}, left {left}, Gaussian {want}");
    assert!((right - want).abs() <= 1e-3, "{message}");
    assert!((left - (1.0 - want)).abs() <= 1e-3, "{message}");
    assert!((right - 0.25).abs() > 0.02, "{message}");
    eprintln!("{message}");
}
