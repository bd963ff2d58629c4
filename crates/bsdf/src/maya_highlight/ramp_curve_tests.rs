//! Tests of the ramp curve: each interpolation against its formula, the spline's knots
//! and continuity, the closed-form integral.

use super::*;

fn knots(interp: i32) -> [Knot; 4] {
    [
        (0.1, Rgb::new(0.9, 0.1, 0.3), interp),
        (0.3, Rgb::new(0.2, 0.8, 0.6), interp),
        (0.7, Rgb::new(0.5, 0.3, 1.2), interp),
        (0.8, Rgb::new(0.0, 1.0, 0.4), interp),
    ]
}

fn close(a: Rgb, b: Rgb, tol: f32) -> bool {
    (a - b).abs().max_element() < tol
}

/// None, linear and smooth at τ = ¼ and ¾ of the segment [0.3, 0.7] (x = 0.4, 0.6):
/// v0, v0 + (v1 − v0)τ and v0 + (v1 − v0)(3τ² − 2τ³) within 1e-5; outside the knots the
/// end values; an undefined code (7) reads as smooth.
#[test]
fn none_linear_and_smooth_follow_their_formulas() {
    let (v0, v1) = (Rgb::new(0.2, 0.8, 0.6), Rgb::new(0.5, 0.3, 1.2));
    for (x, tau) in [(0.4f32, 0.25f32), (0.6, 0.75)] {
        assert!(close(ramp_value(&knots(0), x), v0, 1e-5));
        assert!(close(ramp_value(&knots(1), x), v0 + (v1 - v0) * tau, 1e-5));
        let s = 3.0 * tau * tau - 2.0 * tau * tau * tau;
        assert!(close(ramp_value(&knots(2), x), v0 + (v1 - v0) * s, 1e-5));
        assert_eq!(ramp_value(&knots(7), x), ramp_value(&knots(2), x));
    }
    for interp in 0..4 {
        assert_eq!(ramp_value(&knots(interp), 0.05), Rgb::new(0.9, 0.1, 0.3));
        assert_eq!(ramp_value(&knots(interp), 0.95), Rgb::new(0.0, 1.0, 0.4));
    }
    assert_eq!(ramp_value(&[], 0.5), Rgb::ZERO);
}

/// The spline on [0.3, 0.7] at τ = ¼, ½, ¾ is the Hermite cubic with the slopes
/// m(0.3) = (v(0.7) − v(0.1))/0.6 and m(0.7) = (v(0.8) − v(0.3))/0.5, written out
/// (h00 = 2τ³ − 3τ² + 1, h10 = τ³ − 2τ² + τ, h01 = −2τ³ + 3τ², h11 = τ³ − τ²), within
/// 1e-5; on the first segment the end slope is half its chord, (v(0.3) − v(0.1)) / 0.4
/// (a phantom knot at −0.1 holding v(0.1)).
#[test]
fn the_spline_is_catmull_rom_with_phantom_end_knots() {
    let k = knots(3);
    let m03 = (k[2].1 - k[0].1) / 0.6;
    let m07 = (k[3].1 - k[1].1) / 0.5;
    for tau in [0.25f32, 0.5, 0.75] {
        let (t2, t3) = (tau * tau, tau * tau * tau);
        let want = k[1].1 * (2.0 * t3 - 3.0 * t2 + 1.0)
            + m03 * 0.4 * (t3 - 2.0 * t2 + tau)
            + k[2].1 * (-2.0 * t3 + 3.0 * t2)
            + m07 * 0.4 * (t3 - t2);
        let got = ramp_value(&k, 0.3 + 0.4 * tau);
        assert!(close(got, want, 1e-5), "τ {tau}: {got} vs {want}");
    }
    // First segment [0.1, 0.3]: slope (v(0.3) − v(0.1)) / 0.4 at 0.1, m(0.3) at 0.3.
    let m01 = (k[1].1 - k[0].1) / 0.4;
    let tau = 0.5f32;
    // τ = ½: h00 = h01 = ½, h10 = ⅛, h11 = −⅛.
    let want = k[0].1 * 0.5 + k[1].1 * 0.5 + m01 * 0.2 * 0.125 - m03 * 0.2 * 0.125;
    let got = ramp_value(&k, 0.1 + 0.2 * tau);
    assert!(close(got, want, 1e-5), "{got} vs {want}");
}

/// The spline passes through every knot exactly (bit for bit) and is C1 at the interior
/// knots: second-order one-sided difference quotients (h = 1e-3, each side's own
/// cubic only) agree with the knot's slope within 5e-3 (their h² f'''/3 on the short
/// segment [0.7, 0.8] is 1e-3–3e-3; a linear ramp's two sides differ by 0.3–3), and the
/// value is continuous (1e-5 at ±1e-6).
#[test]
fn the_spline_passes_through_its_knots_and_is_c1() {
    let k = knots(3);
    for (p, v, _) in k {
        assert_eq!(ramp_value(&k, p), v, "knot {p}");
    }
    for i in 1..3 {
        let p = k[i].0;
        let h = 1e-3f32;
        let f = |x: f32| ramp_value(&k, x);
        let left = (f(p) * 3.0 - f(p - h) * 4.0 + f(p - 2.0 * h)) / (2.0 * h);
        let right = (f(p + h) * 4.0 - f(p) * 3.0 - f(p + 2.0 * h)) / (2.0 * h);
        let m = spline_slope(&k, i);
        assert!(close(left, m, 5e-3) && close(right, m, 5e-3), "knot {p}: {left} {right} vs {m}");
        assert!(close(ramp_value(&k, p - 1e-6), ramp_value(&k, p + 1e-6), 1e-5));
    }
    // The ends: the slope at the first and last knot is half the end segment's chord
    // (a phantom knot one segment outside holding the end's value).
    // (Second-order one-sided quotients on the curve's side, within 5e-3 as above.)
    let f = |x: f32| ramp_value(&k, x);
    let h = 1e-3f32;
    let first = (f(0.1 + h) * 4.0 - f(0.1) * 3.0 - f(0.1 + 2.0 * h)) / (2.0 * h);
    let last = (f(0.8) * 3.0 - f(0.8 - h) * 4.0 + f(0.8 - 2.0 * h)) / (2.0 * h);
    let want_first = (k[1].1 - k[0].1) / (2.0 * (k[1].0 - k[0].0));
    let want_last = (k[3].1 - k[2].1) / (2.0 * (k[3].0 - k[2].0));
    assert_eq!(spline_slope(&k, 0), want_first);
    assert_eq!(spline_slope(&k, 3), want_last);
    assert!(close(first, want_first, 5e-3) && close(last, want_last, 5e-3), "{first} {last}");
}

/// The closed-form integral over [a, b] matches a midpoint rule (100 000 steps, f64
/// sums) within 5e-5 (a step of none costs up to half its jump times the step width)
/// for every interpolation, over ranges that start and end inside
/// segments and outside the knots.
#[test]
fn the_integral_matches_a_midpoint_rule() {
    for interp in 0..4 {
        let k = knots(interp);
        for (a, b) in [(0.0f32, 0.5f32), (0.15, 0.75), (0.35, 1.0), (0.0, 1.0)] {
            let steps = 100_000;
            let mut sum = [0.0f64; 3];
            for i in 0..steps {
                let x = a + (b - a) * (i as f32 + 0.5) / steps as f32;
                let v = ramp_value(&k, x);
                for c in 0..3 {
                    sum[c] += f64::from(v[c]);
                }
            }
            let want = sum.map(|s| s * f64::from(b - a) / f64::from(steps));
            let got = ramp_integral(&k, a, b);
            for c in 0..3 {
                assert!(
                    (got[c] - want[c]).abs() < 5e-5,
                    "interp {interp} [{a}, {b}] ch {c}: {} vs {}",
                    got[c],
                    want[c]
                );
            }
        }
    }
}
