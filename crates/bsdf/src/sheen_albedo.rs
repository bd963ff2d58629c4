//! The directional albedo E(μ, r) = ∫ f_sheen(ωo, ωi) cos θi dωi of a unit-tint
//! [`crate::sheen::Sheen`] lobe, tabulated once (the first time it is asked for) over the
//! cosine μ of ωo and the roughness r, and interpolated bilinearly: what a sheen layer
//! takes from its base (MDL's `sheen_bsdf` gives its `multiscatter` base what the sheen
//! leaves).

use std::sync::OnceLock;

use glam::Vec3A;

use crate::sheen::Sheen;
use crate::testing::r2;
use crate::{cosine_hemisphere, Rgb};

/// Table nodes along μ (0 to 1) and along the roughness (0 to 1).
const MU_NODES: usize = 32;
const ROUGHNESS_NODES: usize = 32;
/// Cosine-weighted sample directions per table entry.
const SAMPLES: u32 = 4096;

fn table() -> &'static [[f32; MU_NODES]; ROUGHNESS_NODES] {
    static TABLE: OnceLock<Box<[[f32; MU_NODES]; ROUGHNESS_NODES]>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t = Box::new([[0.0f32; MU_NODES]; ROUGHNESS_NODES]);
        for (ri, row) in t.iter_mut().enumerate() {
            let sheen = Sheen::new(Rgb::ONE, ri as f32 / (ROUGHNESS_NODES - 1) as f32);
            for (mi, e) in row.iter_mut().enumerate() {
                // μ = 0 exactly is a direction in the surface: use a small positive cosine.
                let mu = (mi as f32 / (MU_NODES - 1) as f32).max(1e-3);
                let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
                let mut sum = 0.0f64;
                for i in 0..SAMPLES {
                    // Cosine-weighted: the estimate of ∫ f cos dω is π · mean(f).
                    let wi = cosine_hemisphere(r2(i + 1));
                    sum += f64::from(sheen.eval(wo, wi).x);
                }
                *e = (sum / f64::from(SAMPLES) * std::f64::consts::PI) as f32;
            }
        }
        t
    })
}

/// E(μ, r) for the cosine `mu` of the outgoing direction (its absolute value) and the
/// sheen roughness `roughness` (clamped to [0, 1], as the lobe clamps it).
pub fn albedo(mu: f32, roughness: f32) -> f32 {
    let t = table();
    let x = mu.abs().clamp(0.0, 1.0) * (MU_NODES - 1) as f32;
    let y = roughness.clamp(0.0, 1.0) * (ROUGHNESS_NODES - 1) as f32;
    let (x0, y0) = ((x as usize).min(MU_NODES - 2), (y as usize).min(ROUGHNESS_NODES - 2));
    let (fx, fy) = (x - x0 as f32, y - y0 as f32);
    let row = |r: usize| t[r][x0] * (1.0 - fx) + t[r][x0 + 1] * fx;
    (row(y0) * (1.0 - fy) + row(y0 + 1) * fy).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::albedo as estimate;
    use crate::{Bsdf, Lobe, Lobes};

    /// The table agrees with an independent estimate (the BSDF test harness's sampling of
    /// the lobe, 100 000 samples) within 0.01 between its nodes.
    #[test]
    fn the_table_matches_a_sampled_estimate_between_nodes() {
        for r in [0.15, 0.45, 0.83] {
            for mu in [0.1f32, 0.37, 0.62, 0.95] {
                let mut l = Lobes::default();
                assert!(l.push(Rgb::ONE, Lobe::Sheen(r)));
                let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
                let e = estimate(&Bsdf::Lobes(l), wo, 100_000).x;
                let t = albedo(mu, r);
                assert!((e - t).abs() < 0.01, "r {r}, μ {mu}: sampled {e}, table {t}");
            }
        }
    }
}
