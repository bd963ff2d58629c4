//! A bilinear Ptex lookup blends the two levels around its filter width
//! (`Ptex::blend_for`): no step where the width crosses from one level to the next; and a
//! footprint with separate widths along u and v (`Ptex::sample_rect`) reads its rectangle.

use material::mdl_modules::ptex::{Filter, Ptex};

use crate::mdl_ptex::{ptex_file_full, read, reduced_levels, Face, How};

/// One float channel of the first lookup lane.
fn at(ptex: &Ptex, u: f32, v: f32, width: Option<f32>) -> f32 {
    let mut out = [0.0f32; 1];
    assert!(ptex.sample(0, u, v, width, Filter::Bilinear, 0, &mut out));
    out[0]
}

/// One quad face of 16 × 16 texels of exp(−(r / 0.12)²) (r the distance of the texel
/// centre from the face centre, face units) with its reduced levels 8², 4², 2² (box averages) and its
/// average. Looked up at the face centre with widths from 1/64 to 2 (400 steps, evenly on
/// a log scale): the values never rise as the width grows (1e-6), the largest step between
/// neighbouring widths is within 1e-2, and each level's own texel width gives that level's
/// value (the mean of its four central texels, 1e-6); where a lookup read one level per
/// width it would step by the difference between neighbouring levels, which here is over
/// 0.02 at every crossing of levels 0 to 3 (asserted, so the sweep would see it; at the
/// face centre the 2 × 2 level already reads the average).
#[test]
fn a_width_sweep_has_no_steps() {
    let n = 16usize;
    let texels: Vec<f64> = (0..n * n)
        .map(|t| {
            let (x, y) = (((t % n) as f64 + 0.5) / n as f64 - 0.5, ((t / n) as f64 + 0.5) / n as f64 - 0.5);
            (-(x * x + y * y) / (0.12 * 0.12)).exp()
        })
        .collect();
    let levels = reduced_levels(&texels, n);
    let face = Face { log2: (4, 4), texels: texels.clone(), how: How::Zipped };
    let ptex = read(&ptex_file_full(1, 3, 1, &[face], 6, &[], &levels));
    // Each level's own texel width: its central four texels' mean.
    let mut pure = Vec::new();
    let mut level_values = vec![texels.clone()];
    level_values.extend(levels.iter().map(|l| l[0].texels.clone()));
    for (k, values) in level_values.iter().enumerate() {
        let side = n >> k;
        let c = side / 2;
        let want = (values[(c - 1) * side + c - 1]
            + values[(c - 1) * side + c]
            + values[c * side + c - 1]
            + values[c * side + c])
            / 4.0;
        let got = at(&ptex, 0.5, 0.5, Some(1.0 / side as f32));
        assert!((got - want as f32).abs() <= 1e-6, "level {k}: {got} vs {want}");
        pure.push(got);
    }
    let mean = (texels.iter().sum::<f64>() / texels.len() as f64) as f32;
    for pair in pure.windows(2) {
        assert!(pair[0] - pair[1] > 0.02, "neighbouring levels {pair:?}");
    }
    let steps = 400;
    let mut previous = at(&ptex, 0.5, 0.5, Some(1.0 / 64.0));
    let mut largest = 0.0f32;
    for k in 1..=steps {
        let width = (1.0f32 / 64.0) * 128f32.powf(k as f32 / steps as f32);
        let value = at(&ptex, 0.5, 0.5, Some(width));
        assert!(value <= previous + 1e-6, "width {width}: {value} rose from {previous}");
        largest = largest.max((previous - value).abs());
        previous = value;
    }
    assert!(largest <= 1e-2, "largest step {largest}");
    assert!((previous - mean).abs() <= 1e-6, "a face-wide width reads the average: {previous} vs {mean}");
}

/// The average over the rectangle [u0, u1] × [v0, v1] (face units) of the piecewise
/// constant n × n image `texels` (each texel weighted by its overlap).
fn rectangle_average(texels: &[f64], n: usize, (u0, u1): (f64, f64), (v0, v1): (f64, f64)) -> f64 {
    let overlap =
        |a0: f64, a1: f64, i: usize| (a1.min((i + 1) as f64 / n as f64) - a0.max(i as f64 / n as f64)).max(0.0);
    let mut sum = 0.0;
    for j in 0..n {
        for i in 0..n {
            sum += texels[j * n + i] * overlap(u0, u1, i) * overlap(v0, v1, j);
        }
    }
    sum / ((u1 - u0) * (v1 - v0))
}

/// A 64 × 64 quad face of 0.5 + 0.25 sin(2π · 2u) + 0.2 cos(2π · 4v) with its box-reduced
/// levels, read by `Ptex::sample_rect` over a footprint 1/32 wide along u and 1/32 / cos 75°
/// along v (a face seen at 75° from its normal, tilted about u) at a crest along u and a
/// trough along v: within 2 % of the rectangle's average of level 0 (the texels weighted
/// by their overlap), where the isotropic width (the footprint's area as a square, √ of
/// the widths' product, `footprint::filter_width`'s reading) is off by more than 2 %.
#[test]
fn a_grazing_footprint_reads_its_rectangle() {
    let n = 64usize;
    let tau = std::f64::consts::TAU;
    let texels: Vec<f64> = (0..n * n)
        .map(|t| {
            let (u, v) = (((t % n) as f64 + 0.5) / n as f64, ((t / n) as f64 + 0.5) / n as f64);
            0.5 + 0.25 * (tau * 2.0 * u).sin() + 0.2 * (tau * 4.0 * v).cos()
        })
        .collect();
    let levels = reduced_levels(&texels, n);
    let ptex = read(&ptex_file_full(
        1,
        3,
        1,
        &[Face { log2: (6, 6), texels: texels.clone(), how: How::Zipped }],
        6,
        &[],
        &levels,
    ));
    let (u, v) = (0.125f32, 0.375f32);
    let wu = 1.0f32 / 32.0;
    let wv = wu / 75f32.to_radians().cos();
    let want = rectangle_average(
        &texels,
        n,
        (f64::from(u - wu / 2.0), f64::from(u + wu / 2.0)),
        (f64::from(v - wv / 2.0), f64::from(v + wv / 2.0)),
    );
    let mut out = [0.0f32; 1];
    assert!(ptex.sample_rect(0, u, v, (wu, wv), 0, &mut out));
    let rect = f64::from(out[0]);
    let iso = f64::from(at(&ptex, u, v, Some((wu * wv).sqrt())));
    assert!((rect - want).abs() <= 0.02 * want, "rectangle {rect} vs {want}");
    assert!((iso - want).abs() > 0.02 * want, "isotropic {iso} vs {want}");
}
