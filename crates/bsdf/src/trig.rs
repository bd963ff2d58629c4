//! Sine and cosine over a quarter turn's reduced range, as polynomials: the cosine lobe's
//! concentric mapping ([`crate::concentric_disc`]) needs both at angles in [−π/4, π/4],
//! where a call of libm's `sincosf` (its range reduction for any angle, about 37
//! instructions) cost more than the polynomials below.
//!
//! The coefficients were fitted in double precision to minimise the largest error over
//! [−π/4, π/4] (the sine's relative, the cosine's absolute; Lawson's iteratively
//! reweighted least squares on Chebyshev nodes) and rounded to `f32`. Evaluated in `f32`
//! (Horner's rule, no fused multiply-adds), both are within 7e-8 of the true values there,
//! as close as libm's `f32` results (4e-8 and 5e-8).

/// sin(x) − x = x·z·(S1 + S2·z + S3·z²), z = x².
const S1: f32 = -0.166_666_55;
const S2: f32 = 0.008_332_178;
const S3: f32 = -0.000_195_173;
/// cos(x) − 1 = z·(C1 + C2·z + C3·z² + C4·z³), z = x².
const C1: f32 = -0.5;
const C2: f32 = 0.041_666_623;
const C3: f32 = -0.001_388_676_3;
const C4: f32 = 2.439_045e-5;

/// (sin x, cos x) for `x` in [−π/4, π/4] (radians): each within 7e-8 of the true value
/// there (outside it the error grows quickly; callers reduce their angle first).
#[inline]
pub fn sin_cos_reduced(x: f32) -> (f32, f32) {
    let z = x * x;
    let sin = x + x * (z * (S1 + z * (S2 + z * S3)));
    let cos = 1.0 + z * (C1 + z * (C2 + z * (C3 + z * C4)));
    (sin, cos)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against double precision at 2,000,001 angles over [−π/4, π/4]: each of sin and cos
    /// within 1e-7 (the fit gives 7e-8), the sine relatively too (1e-7 of |sin x|, so
    /// small angles keep their digits), and sin² + cos² within 3e-7 of 1.
    #[test]
    fn reduced_sin_cos_match_double_precision() {
        let n = 1_000_000;
        let quarter = std::f64::consts::FRAC_PI_4;
        let (mut worst_sin, mut worst_cos, mut worst_rel, mut worst_norm) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for i in -n..=n {
            let x = (quarter * f64::from(i) / f64::from(n)) as f32;
            let (s, c) = sin_cos_reduced(x);
            let (ts, tc) = f64::from(x).sin_cos();
            worst_sin = worst_sin.max((f64::from(s) - ts).abs());
            worst_cos = worst_cos.max((f64::from(c) - tc).abs());
            if ts != 0.0 {
                worst_rel = worst_rel.max(((f64::from(s) - ts) / ts).abs());
            }
            worst_norm = worst_norm.max((f64::from(s).powi(2) + f64::from(c).powi(2) - 1.0).abs());
        }
        assert!(worst_sin <= 1e-7, "sin off by {worst_sin:e}");
        assert!(worst_cos <= 1e-7, "cos off by {worst_cos:e}");
        assert!(worst_rel <= 1e-7, "sin off relatively by {worst_rel:e}");
        assert!(worst_norm <= 3e-7, "sin² + cos² off 1 by {worst_norm:e}");
    }

    /// The concentric mapping with these polynomials against the same mapping with
    /// double-precision sin and cos, on a 1025² grid over [0, 1]²: every point within
    /// 3e-7 of it (per coordinate: the f32 ratio's rounding, the polynomials' 7e-8 and the
    /// products' rounding) and inside the unit disc (|d| ≤ 1 + 2e-7).
    #[test]
    fn concentric_disc_matches_trigonometric_mapping() {
        let n = 1024;
        for i in 0..=n {
            for j in 0..=n {
                let u = glam::Vec2::new(i as f32 / n as f32, j as f32 / n as f32);
                let d = crate::concentric_disc(u);
                let (ox, oy) = (2.0 * f64::from(u.x) - 1.0, 2.0 * f64::from(u.y) - 1.0);
                let (r, theta) = if ox == 0.0 && oy == 0.0 {
                    (0.0, 0.0)
                } else if ox.abs() > oy.abs() {
                    (ox, std::f64::consts::FRAC_PI_4 * (oy / ox))
                } else {
                    (oy, std::f64::consts::FRAC_PI_2 - std::f64::consts::FRAC_PI_4 * (ox / oy))
                };
                let (ex, ey) = (r * theta.cos(), r * theta.sin());
                let off = (f64::from(d.x) - ex).abs().max((f64::from(d.y) - ey).abs());
                assert!(off <= 3e-7, "u {u}: {d} against ({ex}, {ey})");
                assert!(f64::from(d.length()) <= 1.0 + 2e-7, "u {u}: |d| = {}", d.length());
            }
        }
    }
}
