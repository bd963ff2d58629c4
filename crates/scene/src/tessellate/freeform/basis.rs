//! One parametric direction of a free-form curve or surface: a basis (`bezier`, `bspline`,
//! `taylor`, `cardinal`, `matrix`) with its parameter list, evaluated to the weights of
//! the control points that influence a parameter value (and their derivatives).
//!
//! Conventions (mental ray's parameter lists):
//! - `bspline d`: the parameter list is the whole knot vector, `control points + d + 1`
//!   values (exporters repeat the end knots); the curve is defined on
//!   `[knot[d], knot[n]]` for `n` control points.
//! - `bezier d`, `taylor d`, `cardinal`, `matrix d step`: the parameter list holds the
//!   segment boundaries. Segment `s` spans `params[s] .. params[s + 1]` with the local
//!   parameter `t` running 0…1 over it and uses control points `s·step ..= s·step + d`,
//!   where the step is `d` for Bézier (neighbouring segments share their end point),
//!   `d + 1` for Taylor (each segment has its own monomial coefficients
//!   `Σ cₖ tᵏ`), 1 for cardinal (cubic Catmull–Rom, passing through the inner two points
//!   of each four) and the given step for a basis matrix. A basis matrix lists
//!   `(d + 1)²` values row by row; row `i` holds the coefficients of `t^(d − i)`,
//!   column `j` belongs to control point `j` (the Bézier matrix
//!   `-1 3 -3 1 / 3 -6 3 0 / -3 3 0 0 / 1 0 0 0` gives the cubic Bézier).

use mi::ast::{BasisKind, SurfaceDir};

/// Highest degree accepted (mental ray's limit is 21).
pub const MAX_DEGREE: usize = 21;

/// A basis direction ready to evaluate.
#[derive(Clone, Debug, PartialEq)]
pub struct Direction {
    kind: Kind,
    /// Degree of the polynomial pieces.
    pub degree: usize,
    /// Number of control points this direction needs.
    pub count: usize,
    /// The parameter range used, `lo < hi` (the written range clamped to the domain).
    pub lo: f64,
    /// End of the parameter range.
    pub hi: f64,
    /// Boundaries of the polynomial pieces inside `[lo, hi]`, `lo` and `hi` included,
    /// increasing (the patches of the `parametric` approximation).
    pub breaks: Vec<f64>,
}

#[derive(Clone, Debug, PartialEq)]
enum Kind {
    Bspline {
        knots: Vec<f64>,
    },
    /// Power-form segments: `coef[i][j]` multiplies `t^i` for local control point `j`.
    Segments {
        params: Vec<f64>,
        step: usize,
        coef: Vec<Vec<f64>>,
    },
}

/// The weights of the control points `first .. first + w.len()` at one parameter value.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Weights {
    /// Index of the first influencing control point.
    pub first: usize,
    /// Basis function values.
    pub w: Vec<f64>,
    /// Their derivatives with respect to the parameter.
    pub dw: Vec<f64>,
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Power-form coefficients (`[i][j]`: coefficient of `tⁱ` for control point `j`) of the
/// Bernstein polynomials of degree `d`.
fn bernstein_coefficients(d: usize) -> Vec<Vec<f64>> {
    let mut c = vec![vec![0.0; d + 1]; d + 1];
    // B_j(t) = C(d,j) t^j (1-t)^(d-j) = C(d,j) Σ_k C(d-j,k) (-1)^k t^(j+k)
    for j in 0..=d {
        for k in 0..=d - j {
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            c[j + k][j] += binomial(d, j) * binomial(d - j, k) * sign;
        }
    }
    c
}

impl Direction {
    /// Builds a direction from a declared basis and the written parameters; the error
    /// says what does not fit.
    pub fn new(kind: &BasisKind, dir: &SurfaceDir) -> Result<Direction, String> {
        Direction::from_parts(kind, &dir.params, dir.range)
    }

    /// As [`Direction::new`], from the parameter list and the optional range.
    pub fn from_parts(kind: &BasisKind, params: &[f64], range: Option<(f64, f64)>) -> Result<Direction, String> {
        if params.iter().any(|p| !p.is_finite()) {
            return Err("a parameter value is not finite".into());
        }
        if params.windows(2).any(|w| w[1] < w[0]) {
            return Err("the parameter values decrease".into());
        }
        let degree_of = |d: i64| -> Result<usize, String> {
            if d < 1 || d as usize > MAX_DEGREE {
                Err(format!("degree {d} is outside 1…{MAX_DEGREE}"))
            } else {
                Ok(d as usize)
            }
        };
        let (kind, degree, count, domain) = match kind {
            BasisKind::Bspline(d) => {
                let d = degree_of(*d)?;
                if params.len() < 2 * d + 2 {
                    return Err(format!(
                        "a degree {d} B-spline needs at least {} knots, {} given",
                        2 * d + 2,
                        params.len()
                    ));
                }
                let n = params.len() - d - 1;
                let domain = (params[d], params[n]);
                (Kind::Bspline { knots: params.to_vec() }, d, n, domain)
            }
            other => {
                let (d, step, coef) = match other {
                    BasisKind::Bezier(d) => {
                        let d = degree_of(*d)?;
                        (d, d, bernstein_coefficients(d))
                    }
                    BasisKind::Taylor(d) => {
                        let d = degree_of(*d)?;
                        let coef = (0..=d).map(|i| (0..=d).map(|j| f64::from(u8::from(i == j))).collect()).collect();
                        (d, d + 1, coef)
                    }
                    BasisKind::Cardinal => {
                        // Catmull–Rom: ½[−t + 2t² − t³, 2 − 5t² + 3t³, t + 4t² − 3t³, −t² + t³].
                        let coef = vec![
                            vec![0.0, 1.0, 0.0, 0.0],
                            vec![-0.5, 0.0, 0.5, 0.0],
                            vec![1.0, -2.5, 2.0, -0.5],
                            vec![-0.5, 1.5, -1.5, 0.5],
                        ];
                        (3, 1, coef)
                    }
                    BasisKind::Matrix { degree, step, values } => {
                        let d = degree_of(*degree)?;
                        if values.len() != (d + 1) * (d + 1) {
                            return Err(format!("a degree {d} basis matrix needs {} values", (d + 1) * (d + 1)));
                        }
                        if *step < 1 {
                            return Err(format!("basis matrix step {step} is below 1"));
                        }
                        // Row r is t^(d - r): coefficient of t^i is row d - i.
                        let coef = (0..=d).map(|i| values[(d - i) * (d + 1)..(d - i + 1) * (d + 1)].to_vec()).collect();
                        (d, *step as usize, coef)
                    }
                    BasisKind::Bspline(_) => unreachable!("handled above"),
                };
                if params.len() < 2 {
                    return Err("at least two parameter values are needed".into());
                }
                let segments = params.len() - 1;
                let count = (segments - 1) * step + d + 1;
                let domain = (params[0], params[segments]);
                (Kind::Segments { params: params.to_vec(), step, coef }, d, count, domain)
            }
        };
        let (mut lo, mut hi) = range.unwrap_or(domain);
        if !(lo.is_finite() && hi.is_finite()) {
            return Err("the parameter range is not finite".into());
        }
        if lo > hi {
            std::mem::swap(&mut lo, &mut hi);
        }
        lo = lo.clamp(domain.0, domain.1);
        hi = hi.clamp(domain.0, domain.1);
        if hi - lo <= 0.0 {
            return Err(format!("the parameter range {lo}…{hi} is empty"));
        }
        let knots = match &kind {
            Kind::Bspline { knots } => knots.as_slice(),
            Kind::Segments { params, .. } => params.as_slice(),
        };
        let mut breaks = vec![lo];
        for &k in knots {
            if k > lo && k < hi && k > *breaks.last().expect("not empty") {
                breaks.push(k);
            }
        }
        breaks.push(hi);
        Ok(Direction { kind, degree, count, lo, hi, breaks })
    }

    /// Basis weights at parameter `u` (clamped to the range).
    pub fn eval(&self, u: f64) -> Weights {
        let u = u.clamp(self.lo, self.hi);
        match &self.kind {
            Kind::Bspline { knots } => bspline(knots, self.degree, self.count, u),
            Kind::Segments { params, step, coef } => {
                let segments = params.len() - 1;
                // The last segment with params[s] <= u, skipping empty ones.
                let mut s = params[..segments].partition_point(|&p| p <= u).saturating_sub(1);
                while s + 1 < segments && params[s + 1] - params[s] <= 0.0 {
                    s += 1;
                }
                let len = params[s + 1] - params[s];
                let t = if len > 0.0 { ((u - params[s]) / len).clamp(0.0, 1.0) } else { 0.0 };
                let d = self.degree;
                let mut w = vec![0.0; d + 1];
                let mut dw = vec![0.0; d + 1];
                let mut tp = 1.0; // t^i
                let mut tp1 = 0.0; // i t^(i-1)
                for (i, row) in coef.iter().enumerate() {
                    for j in 0..=d {
                        w[j] += row[j] * tp;
                        dw[j] += row[j] * tp1;
                    }
                    tp1 = (i + 1) as f64 * tp;
                    tp *= t;
                }
                if len > 0.0 {
                    dw.iter_mut().for_each(|x| *x /= len);
                }
                Weights { first: s * step, w, dw }
            }
        }
    }
}

/// The `p + 1` non-zero B-spline basis functions of degree `p` at `u` and their
/// derivatives (Cox–de Boor recursion on the knot span holding `u`).
fn bspline(knots: &[f64], p: usize, n: usize, u: f64) -> Weights {
    // The span: knots[span] <= u < knots[span + 1], span in p ..= n - 1.
    let mut span = knots[..n + 1].partition_point(|&k| k <= u).saturating_sub(1).clamp(p, n - 1);
    while span > p && knots[span + 1] - knots[span] <= 0.0 {
        span -= 1;
    }
    // table[k][r]: basis of degree k for control point span - k + r.
    let mut n_prev = vec![1.0];
    let mut lower = vec![1.0];
    for k in 1..=p {
        let mut cur = vec![0.0; k + 1];
        for r in 0..k {
            let i = span - (k - 1) + r; // control point of n_prev[r]
            let (a0, a1) = (knots[i], knots[i + k]);
            // N_{i,k} gets the rising part of N_{i,k-1}; N_{i-1,k} its falling part.
            let left = if a1 > a0 { (u - a0) / (a1 - a0) } else { 0.0 };
            let right = if a1 > a0 { (a1 - u) / (a1 - a0) } else { 0.0 };
            cur[r] += right * n_prev[r];
            cur[r + 1] += left * n_prev[r];
        }
        if k == p {
            lower = n_prev.clone();
        }
        n_prev = cur;
    }
    // Derivatives: N'_{i,p} = p N_{i,p-1}/(k_{i+p} - k_i) - p N_{i+1,p-1}/(k_{i+p+1} - k_{i+1}).
    let first = span - p;
    let mut dw = vec![0.0; p + 1];
    for (r, d) in dw.iter_mut().enumerate() {
        let i = first + r;
        // lower[q] is N_{span - p + 1 + q, p - 1}.
        let a = if r >= 1 { lower[r - 1] } else { 0.0 };
        let b = if r < p { lower[r] } else { 0.0 };
        let da = knots[i + p] - knots[i];
        let db = knots[i + p + 1] - knots[i + 1];
        *d = p as f64 * (if da > 0.0 { a / da } else { 0.0 } - if db > 0.0 { b / db } else { 0.0 });
    }
    Weights { first, w: n_prev, dw }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_partition(dir: &Direction) {
        for k in 0..=40 {
            let u = dir.lo + (dir.hi - dir.lo) * k as f64 / 40.0;
            let e = dir.eval(u);
            assert!((e.w.iter().sum::<f64>() - 1.0).abs() < 1e-12, "sum at {u}: {e:?}");
            assert!(e.dw.iter().sum::<f64>().abs() < 1e-9, "derivative sum at {u}: {e:?}");
            assert!(e.first + e.w.len() <= dir.count);
        }
    }

    #[test]
    fn bases_partition_unity() {
        let knots = [0.0, 0.0, 0.0, 0.0, 1.0, 2.5, 3.0, 3.0, 3.0, 3.0];
        check_partition(&Direction::from_parts(&BasisKind::Bspline(3), &knots, None).unwrap());
        check_partition(&Direction::from_parts(&BasisKind::Bezier(3), &[0.0, 1.0, 2.0], None).unwrap());
        check_partition(&Direction::from_parts(&BasisKind::Cardinal, &[0.0, 1.0, 2.0], None).unwrap());
        let bez = vec![-1., 3., -3., 1., 3., -6., 3., 0., -3., 3., 0., 0., 1., 0., 0., 0.];
        let m = BasisKind::Matrix { degree: 3, step: 3, values: bez };
        check_partition(&Direction::from_parts(&m, &[0.0, 0.5, 1.0], None).unwrap());
    }

    #[test]
    fn bspline_derivative_matches_difference_quotient() {
        let knots = [0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 3.0, 3.0, 3.0];
        let dir = Direction::from_parts(&BasisKind::Bspline(2), &knots, None).unwrap();
        assert_eq!(dir.count, 6);
        assert_eq!(dir.breaks, vec![0.0, 1.0, 2.0, 3.0]);
        let h = 1e-6;
        for u in [0.3, 0.99, 1.5, 2.7] {
            let (a, b, c) = (dir.eval(u - h), dir.eval(u + h), dir.eval(u));
            assert_eq!(a.first, c.first);
            for r in 0..3 {
                let fd = (b.w[r] - a.w[r]) / (2.0 * h);
                assert!((fd - c.dw[r]).abs() < 1e-5, "u {u} r {r}: {fd} vs {}", c.dw[r]);
            }
        }
    }

    #[test]
    fn bezier_matrix_equals_bezier_basis() {
        let bez = vec![-1., 3., -3., 1., 3., -6., 3., 0., -3., 3., 0., 0., 1., 0., 0., 0.];
        let m = Direction::from_parts(&BasisKind::Matrix { degree: 3, step: 3, values: bez }, &[0.0, 1.0], None);
        let b = Direction::from_parts(&BasisKind::Bezier(3), &[0.0, 1.0], None);
        for u in [0.0, 0.2, 0.7, 1.0] {
            let (x, y) = (m.as_ref().unwrap().eval(u), b.as_ref().unwrap().eval(u));
            for r in 0..4 {
                assert!((x.w[r] - y.w[r]).abs() < 1e-12 && (x.dw[r] - y.dw[r]).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn bad_parameter_lists_are_errors() {
        assert!(Direction::from_parts(&BasisKind::Bspline(3), &[0.0, 0.0, 1.0, 1.0], None).is_err());
        assert!(Direction::from_parts(&BasisKind::Bezier(0), &[0.0, 1.0], None).is_err());
        assert!(Direction::from_parts(&BasisKind::Bezier(1), &[1.0, 0.0], None).is_err());
        assert!(Direction::from_parts(&BasisKind::Bezier(1), &[0.0, 1.0], Some((2.0, 3.0))).is_err());
    }
}
