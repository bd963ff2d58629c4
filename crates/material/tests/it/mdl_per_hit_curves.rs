//! Measured curves (`measured_curve_layer`, `color_measured_curve_layer`,
//! `measured_curve_factor`) whose `curve_values` vary over the surface, read at each hit
//! into the lobe sum's own table (tests/mdl/per_hit_curves.mdl). Each varying material,
//! driven by the texture coordinate u, is compared at two points with its constant twin
//! of the samples u gives there. Each test states its tolerance.

use crate::mdl_support;

use material::SurfaceModel;
use mdl_support::per_hit::{at, direction_pairs, twins_text};
use mdl_support::{close, compile_text, get};

/// Compiles `varying` and, for each (u, constant shader parameters), its constant twin
/// `constant`; checks that at u the varying material's BSDF (a per-hit wide lobe sum that
/// keeps the samples) agrees with the twin's (a compact sum of the interned curve) at
/// every pair of directions within 1e-6 of the larger value, and that the BSDFs at the
/// two points differ by more than 1e-3 somewhere (the samples are read per hit).
fn same_as_constant_twins(varying: &str, constant: &str, twins: [(f32, &str); 2]) {
    within_of_constant_twins(varying, constant, twins, &|_| 0.0, None);
}

/// As [`same_as_constant_twins`], the BSDFs at u agreeing within `tol(u)` plus 1e-6 of the
/// larger value; `resampled`: the varying material has a curve of that many samples, and
/// its one diagnostic is the warning that it is resampled (naming the count).
fn within_of_constant_twins(
    varying: &str,
    constant: &str,
    twins: [(f32, &str); 2],
    tol: &dyn Fn(f32) -> f32,
    resampled: Option<usize>,
) {
    let (mdl, lib, diags) = compile_text(&twins_text("per_hit_curves", varying, constant, &twins));
    match resampled {
        None => assert!(diags.is_empty(), "{varying}: {diags:#?}"),
        Some(n) => assert!(
            diags.len() == 1 && diags[0].contains(&format!("{n} samples")) && diags[0].contains("resampled to 16"),
            "{varying}: {diags:#?}"
        ),
    }
    let v = get(&mdl, &lib, "v");
    let mut values = Vec::new();
    for (k, (u, _)) in twins.iter().enumerate() {
        let h = at(v, *u);
        assert!(matches!(*h.model, SurfaceModel::MdlWideAt(_)), "{varying}: {:?}", h.model);
        let want = get(&mdl, &lib, &format!("c{k}"));
        let mut these = Vec::new();
        for (wo, wi) in direction_pairs() {
            let a = h.model.bsdf(h.diffuse, wo).eval(wo, wi);
            let b = want.bsdf(wo).eval(wo, wi);
            let scale = a.max_element().max(b.max_element()).max(1.0);
            assert!(close(a, b, tol(*u) + 1e-6 * scale), "{varying} at u = {u}, {wo:?} → {wi:?}: {a:?} vs {b:?}");
            these.push(a);
        }
        values.push(these);
    }
    let most = values[0].iter().zip(&values[1]).map(|(a, b)| (*a - *b).abs().max_element()).fold(0.0, f32::max);
    assert!(most > 1e-3, "{varying}: the samples change the BSDF (most difference {most})");
}

/// `color_measured_curve_layer` of three samples (0.25, 0.5, 0.125) + u/2, u, 1 − u/2 over
/// rough GGX and a white Lambertian base is, at u = 0.5 and 0.75, the constant curve of
/// those samples (BSDF values within 1e-6).
#[test]
fn a_measured_curve_layer_of_varying_samples_is_read_per_hit() {
    same_as_constant_twins(
        "layer_varying",
        "layer_of",
        [
            (0.5, r#""a" 0.5 0.75 0.375, "b" 0.5 0.5 0.5, "c" 0.75 0.75 0.75"#),
            (0.75, r#""a" 0.625 0.875 0.5, "b" 0.75 0.75 0.75, "c" 0.625 0.625 0.625"#),
        ],
    );
    same_as_constant_twins(
        "grey_layer_varying",
        "grey_layer_of",
        [(0.5, r#""a" 0.5, "b" 0.5"#), (0.75, r#""a" 0.625, "b" 0.25"#)],
    );
}

/// `measured_curve_factor` of samples (u, 0.5, 1 − u), u/2 over rough GGX is, at u = 0.5
/// and 0.75, the constant factor of those samples (BSDF values within 1e-6).
#[test]
fn a_measured_curve_factor_of_varying_samples_is_read_per_hit() {
    same_as_constant_twins(
        "factor_varying",
        "factor_of",
        [(0.5, r#""a" 0.5 0.5 0.5, "b" 0.25 0.25 0.25"#), (0.75, r#""a" 0.75 0.5 0.25, "b" 0.375 0.375 0.375"#)],
    );
}

/// Samples of the `wave` curve of tests/mdl/per_hit_curves.mdl at x (f64): sample i is
/// (0.5 + 0.4 x cos 0.3i, 0.5, 0.5 − 0.4 x sin 0.2i).
fn wave(i: usize, x: f64) -> [f64; 3] {
    let i = i as f64;
    [0.5 + 0.4 * x * (0.3 * i).cos(), 0.5, 0.5 - 0.4 * x * (0.2 * i).sin()]
}

/// The largest distance (any channel) of the n samples of `curve` from the curve
/// resampled to m steps uniform in the angle, both linear in the angle between their
/// samples — the bound the resampling states (f64, independent of mira's code).
fn resampling_bound(curve: &dyn Fn(usize) -> [f64; 3], n: usize, m: usize) -> f64 {
    let lerp = |at: f64, value: &dyn Fn(usize) -> [f64; 3], last: usize| {
        let i = (at.floor() as usize).min(last - 1);
        let t = at - i as f64;
        let (a, b) = (value(i), value(i + 1));
        [0, 1, 2].map(|k| a[k] * (1.0 - t) + b[k] * t)
    };
    let resampled: Vec<[f64; 3]> =
        (0..m).map(|j| lerp(j as f64 * (n - 1) as f64 / (m - 1) as f64, curve, n - 1)).collect();
    (0..n)
        .map(|i| {
            let g = lerp(i as f64 * (m - 1) as f64 / (n - 1) as f64, &|j| resampled[j], m - 1);
            let s = curve(i);
            (0..3).map(|k| (s[k] - g[k]).abs()).fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// A varying curve of more samples than the lobe sum keeps per curve (16) is resampled to
/// 16 steps uniform in the angle at each hit: the 31 samples of `kinked` (linear between
/// those steps: every other sample the mean of its neighbours) give the constant curve of
/// the same samples within 1e-6 at u = 0.5 and 0.9; the 25 samples of `wave` (a smooth
/// curve) under a `measured_curve_factor` over a white Lambertian (f = curve/π) give the
/// constant curve's f within the resampling's bound / π (the largest distance of a sample
/// from the resampled curve, computed here: 0.0069 at u = 0.5, 0.012 at 0.9) plus 1e-6.
/// Each compiles with one warning naming the count and the resampling.
#[test]
fn a_varying_curve_of_many_samples_is_resampled_within_its_bound() {
    let twins = [(0.5, r#""x" 0.5"#), (0.9, r#""x" 0.9"#)];
    within_of_constant_twins("kinked_varying", "kinked_of", twins, &|_| 0.0, Some(31));
    let bound = |u: f32| resampling_bound(&|i| wave(i, f64::from(u)), 25, 16);
    for u in [0.5f32, 0.9] {
        assert!(bound(u) > 1e-3, "the resampling loses something at u = {u}: {}", bound(u));
    }
    let tol = |u: f32| (bound(u) / std::f64::consts::PI) as f32;
    within_of_constant_twins("wave_varying", "wave_of", twins, &tol, Some(25));
}
