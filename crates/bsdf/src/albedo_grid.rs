//! Uniform grids of tabulated albedos ([`crate::multiscatter`]'s micro-mirror tables and
//! [`crate::glass_multiscatter`]'s glass tables): the grid position of a coordinate and
//! the cosine-weighted mean of a row in μ = cos θ as it is interpolated.

/// Grid position of `x` ∈ [0, 1] (clamped) on `n` ≥ 2 uniform points: the lower index
/// and the fraction towards the next.
pub(crate) fn grid(x: f32, n: usize) -> (usize, f32) {
    let f = x.clamp(0.0, 1.0) * (n - 1) as f32;
    let k = (f as usize).min(n - 2);
    (k, f - k as f32)
}

/// The hemispherical (cosine-weighted) mean 2 ∫₀¹ E(μ) μ dμ of a row of E on uniform
/// points μ = j/(n − 1), linearly interpolated between them as it is read (midpoint rule,
/// 2048 points).
pub(crate) fn cosine_mean(row: &[f32]) -> f64 {
    const N: usize = 2048;
    let sum: f64 = (0..N)
        .map(|i| {
            let mu = (i as f32 + 0.5) / N as f32;
            let (j, t) = grid(mu, row.len());
            f64::from((row[j] * (1.0 - t) + row[j + 1] * t) * mu)
        })
        .sum();
    2.0 * sum / N as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mean of a row is exact for a linear E: E = a + b μ gives a + 2b/3 (within 1e-6),
    /// a constant row gives itself.
    #[test]
    fn the_cosine_mean_of_a_linear_row_is_exact() {
        let (a, b) = (0.3f32, 0.5f32);
        let row: Vec<f32> = (0..32).map(|j| a + b * j as f32 / 31.0).collect();
        assert!((cosine_mean(&row) - f64::from(a + 2.0 * b / 3.0)).abs() <= 1e-6);
        assert!((cosine_mean(&[0.7; 5]) - 0.7).abs() <= 1e-6);
    }
}
