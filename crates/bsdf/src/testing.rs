//! Checks every BSDF must pass: reciprocity, energy (albedo ≤ 1) and a chi-square test of
//! `sample` against `pdf`.

use glam::{Vec2, Vec3A};

use super::Bsdf;
use crate::Rgb;

/// A deterministic low-discrepancy 2-D point (R2 sequence).
pub fn r2(i: u32) -> Vec2 {
    const G: f64 = 1.324_717_957_244_746;
    let a = (i as f64 / G).fract();
    let b = (i as f64 / (G * G)).fract();
    Vec2::new(a as f32, b as f32)
}

/// A deterministic low-discrepancy 3-D point (the R3 sequence): two numbers for a
/// direction and one for choosing a lobe, without the correlation that reusing R2 with an
/// offset index would give (its first coordinate is only shifted).
pub fn r3(i: u32) -> (Vec2, f32) {
    const G: f64 = 1.220_744_084_605_759_5;
    let x = i as f64 + 0.5;
    let a = (x / G).fract();
    let b = (x / (G * G)).fract();
    let c = (x / (G * G * G)).fract();
    (Vec2::new(a as f32, b as f32), c as f32)
}

/// Three directions of incidence the standard checks use: normal, 37° and 72° (local
/// frame, z up).
pub fn incidences() -> [Vec3A; 3] {
    [Vec3A::Z, Vec3A::new(0.6, 0.0, 0.8), Vec3A::new(0.0, 0.95, 0.312_25).normalize()]
}

/// The standard checks of a BSDF: reciprocity to 1e-4, an albedo of at most `max_albedo`
/// at every one of [`incidences`] (50 000 samples; `what` names the case), and chi-square
/// sampling of its density there.
pub fn standard_checks(bsdf: &Bsdf, max_albedo: f32, what: &str) {
    reciprocity(bsdf, 1e-4);
    for wo in incidences() {
        let a = albedo(bsdf, wo, 50_000);
        assert!(a.max_element() <= max_albedo, "{what}: albedo {a:?} at {wo:?}");
        chi_square(bsdf, wo);
    }
}

/// Directions on the sphere for testing.
fn directions() -> Vec<Vec3A> {
    (0..64)
        .map(|i| {
            let u = r2(i + 1);
            let z = 1.0 - 2.0 * u.x;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = std::f32::consts::TAU * u.y;
            Vec3A::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

/// f(ωo, ωi) = f(ωi, ωo) within `tol` (relative).
pub fn reciprocity(bsdf: &Bsdf, tol: f32) {
    for &a in &directions() {
        for &b in &directions() {
            let (f1, f2) = (bsdf.eval(a, b), bsdf.eval(b, a));
            let scale = f1.max_element().max(f2.max_element()).max(1e-6);
            assert!((f1 - f2).abs().max_element() / scale <= tol, "f({a},{b}) = {f1} but f({b},{a}) = {f2}");
        }
    }
}

/// ∫ f(ωo, ωi) |cos θi| dωi by importance sampling with `n` samples.
pub fn albedo(bsdf: &Bsdf, wo: Vec3A, n: u32) -> Rgb {
    let mut sum = Rgb::ZERO;
    for i in 0..n {
        let (u, u_lobe) = r3(i);
        if let Some(s) = bsdf.sample(wo, u, u_lobe) {
            sum += s.weight();
        }
    }
    sum / n as f32
}

/// Chi-square test of sampled directions against `pdf` over a θ×φ grid (Pearson, with
/// cells of low expected count merged), at the 1% significance level.
pub fn chi_square(bsdf: &Bsdf, wo: Vec3A) {
    const THETA: usize = 10;
    const PHI: usize = 20;
    const SAMPLES: u32 = 200_000;
    let cell = |w: Vec3A| {
        let theta = w.z.clamp(-1.0, 1.0).acos();
        let phi = w.y.atan2(w.x).rem_euclid(std::f32::consts::TAU);
        let t = ((theta / std::f32::consts::PI) * THETA as f32).min(THETA as f32 - 1.0) as usize;
        let p = ((phi / std::f32::consts::TAU) * PHI as f32).min(PHI as f32 - 1.0) as usize;
        t * PHI + p
    };
    let mut observed = vec![0f64; THETA * PHI];
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut rnd = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    for _ in 0..SAMPLES {
        if let Some(s) = bsdf.sample(wo, Vec2::new(rnd(), rnd()), rnd()) {
            if !s.delta {
                observed[cell(s.wi)] += 1.0;
            }
        }
    }
    // Expected counts: integrate the pdf over each cell with a fine midpoint rule (finer in
    // θ, where lobes grazing the horizon change fastest).
    let mut expected = vec![0f64; THETA * PHI];
    const SUB_THETA: usize = 64;
    const SUB_PHI: usize = 16;
    for t in 0..THETA * SUB_THETA {
        for p in 0..PHI * SUB_PHI {
            let theta = (t as f64 + 0.5) / (THETA * SUB_THETA) as f64 * std::f64::consts::PI;
            let phi = (p as f64 + 0.5) / (PHI * SUB_PHI) as f64 * std::f64::consts::TAU;
            let w = Vec3A::new((theta.sin() * phi.cos()) as f32, (theta.sin() * phi.sin()) as f32, theta.cos() as f32);
            let area = theta.sin()
                * (std::f64::consts::PI / (THETA * SUB_THETA) as f64)
                * (std::f64::consts::TAU / (PHI * SUB_PHI) as f64);
            expected[cell(w)] += f64::from(bsdf.pdf(wo, w)) * area * f64::from(SAMPLES);
        }
    }
    let p = pooled_chi_square(&observed, &expected);
    if p.pool_expected < 5.0 {
        let (pool_o, pool_e) = (p.pool_observed, p.pool_expected);
        assert!(pool_o < 5.0 + 10.0 * pool_e.max(1.0), "{pool_o} samples fell where the pdf is ~0 ({pool_e})");
    }
    let (chi2, dof, limit) = (p.chi2, p.dof, chi_square_limit_99(p.dof));
    assert!(chi2 < limit, "chi-square {chi2:.1} over the 99% limit {limit:.1} ({dof} dof) for wo = {wo}");
}

/// Pearson's statistic of `observed` against `expected` counts, cells expecting fewer than
/// 5 pooled into one (counted as a cell when it expects 5 or more).
pub struct PooledChiSquare {
    /// The statistic.
    pub chi2: f64,
    /// Degrees of freedom: the cells counted less one (at least 1).
    pub dof: f64,
    /// Samples observed in the pooled cells.
    pub pool_observed: f64,
    /// Samples expected in the pooled cells.
    pub pool_expected: f64,
}

/// Pearson's χ² over cells, with the cells expecting fewer than 5 samples pooled.
pub fn pooled_chi_square(observed: &[f64], expected: &[f64]) -> PooledChiSquare {
    let (mut chi2, mut cells) = (0.0, 0usize);
    let (mut pool_observed, mut pool_expected) = (0.0, 0.0);
    for (o, e) in observed.iter().zip(expected) {
        if *e < 5.0 {
            pool_observed += o;
            pool_expected += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            cells += 1;
        }
    }
    if pool_expected >= 5.0 {
        chi2 += (pool_observed - pool_expected) * (pool_observed - pool_expected) / pool_expected;
        cells += 1;
    }
    PooledChiSquare { chi2, dof: cells.saturating_sub(1).max(1) as f64, pool_observed, pool_expected }
}

/// The 99 % quantile of χ²(`dof`), by the Wilson–Hilferty approximation.
pub fn chi_square_limit_99(dof: f64) -> f64 {
    let z = 2.326;
    dof * (1.0 - 2.0 / (9.0 * dof) + z * (2.0 / (9.0 * dof)).sqrt()).powi(3)
}
