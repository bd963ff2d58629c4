//! The tables of [`super`]: the n²-weighted directional albedo E(μ, α, η′) of the
//! unit-weight isotropic solid glass lobe (both halves) of each distribution and masking,
//! from the side of lower index (η′ = η ≥ 1, entering) and from the other (η′ = 1/η,
//! leaving), on 32 points in μ = cos θ ∈ [0, 1], 16 in α ∈ [0, 1] and 17 in η ∈ [1, 3]
//! (denser towards 1; η past 3 read as 3), read trilinearly; and the loss ℓ = 1 − E_avg =
//! 1 − 2 ∫ E μ dμ of each row as interpolated.
//!
//! E is stored in the repository (`albedo.bin`, 34 816 bytes a distribution and masking:
//! each entry E · 65535 rounded, a little-endian `u16`), computed by the generator in
//! `generate.rs` (the mean of 8192 quasi-random micro-normals an entry, both branches of
//! each) and checked against it by a test; decoding it and integrating ℓ takes a few
//! milliseconds at the first use of a distribution and masking, where computing it took
//! ≈ 0.4 s.

use std::sync::OnceLock;

use crate::albedo_grid::{cosine_mean, grid};
use crate::dielectric::fresnel;
use crate::rough_glass::Microfacet;

/// Grid points in μ = cos θ (μ = j / 31).
pub(super) const MUS: usize = 32;
/// Grid points in roughness (α = k / 15).
pub(super) const ALPHAS: usize = 16;
/// Grid points in the index η ≥ 1: η = 1 + 2 x², x = i / 16 (η 1.0078, 1.031, 1.07, 1.125,
/// 1.195, 1.28, 1.38, 1.5, …, 3), dense where the critical angle of total internal
/// reflection from inside moves fastest (cos θc = √(1 − 1/η²) ≈ 2x near η = 1).
pub(super) const ETAS: usize = 17;
/// The largest index tabulated.
const MAX_ETA: f32 = 3.0;
/// Entries in the E table of one distribution and masking (2 sides × η × α × μ).
pub(super) const ENTRIES: usize = 2 * ETAS * ALPHAS * MUS;
/// Every distribution and masking, in the order of [`index`] (and of the stored tables).
pub(super) const MICROS: [Microfacet; 4] =
    [Microfacet::Ggx, Microfacet::Beckmann, Microfacet::GgxVcavities, Microfacet::BeckmannVcavities];

/// The stored E tables (see the module's notes), by distribution and masking ([`index`]),
/// then side (0 entering, 1 leaving), η, α and μ in that order of nesting.
static STORED: &[u8; MICROS.len() * ENTRIES * 2] = include_bytes!("albedo.bin");

/// The tables of one distribution and masking: E by side (0: entering, η′ = η; 1:
/// leaving, η′ = 1/η), η, α and μ; ℓ = 1 − E_avg by side, η and α.
pub(super) struct Tables {
    e: Vec<f32>,
    lost: Vec<f32>,
}

static TABLES: [OnceLock<Tables>; 4] = [const { OnceLock::new() }; 4];

/// F_avg at the grid's indices η ≥ 1 (entering), built on first use.
static FRESNEL_AVERAGES: OnceLock<[f32; ETAS]> = OnceLock::new();

/// The index η ≥ 1 of grid point `i`.
pub(super) fn grid_eta(i: usize) -> f32 {
    let x = i as f32 / (ETAS - 1) as f32;
    1.0 + (MAX_ETA - 1.0) * x * x
}

/// The side (0 entering, 1 leaving) and grid position of relative index `etap` (linear
/// in x = √((η − 1)/(η_max − 1))).
fn side_and_eta(etap: f32) -> (usize, (usize, f32)) {
    let (side, eta) = if etap >= 1.0 { (0, etap) } else { (1, 1.0 / etap) };
    (side, grid(((eta - 1.0) / (MAX_ETA - 1.0)).max(0.0).sqrt(), ETAS))
}

/// The hemispherical average Fresnel reflectance F_avg(η′) from the side of relative
/// index `etap`, linear between the grid's points; from the denser side by the
/// reciprocity of a smooth boundary (n² T_avg alike from both sides): 1 − (1 −
/// F_avg(1/η′)) η′².
pub(super) fn fresnel_average_at(etap: f32) -> f32 {
    let table = FRESNEL_AVERAGES.get_or_init(|| std::array::from_fn(|i| fresnel_average(grid_eta(i))));
    let (side, (i, s)) = side_and_eta(etap);
    let entering = table[i] * (1.0 - s) + table[i + 1] * s;
    if side == 0 {
        entering
    } else {
        1.0 - (1.0 - entering) * etap * etap
    }
}

/// The position of `micro`'s tables among [`MICROS`].
pub(super) fn index(micro: Microfacet) -> usize {
    match micro {
        Microfacet::Ggx => 0,
        Microfacet::Beckmann => 1,
        Microfacet::GgxVcavities => 2,
        Microfacet::BeckmannVcavities => 3,
    }
}

/// The tables of `micro`, decoded on first use.
pub(super) fn tables(micro: Microfacet) -> &'static Tables {
    TABLES[index(micro)].get_or_init(|| Tables::decode(micro))
}

/// The hemispherical average 2 ∫₀¹ F(μ, η′) μ dμ of the Fresnel reflectance (midpoint
/// rule, 4096 points).
fn fresnel_average(etap: f32) -> f32 {
    const N: usize = 4096;
    let sum: f64 = (0..N)
        .map(|i| {
            let mu = (i as f32 + 0.5) / N as f32;
            f64::from(fresnel(mu, etap) * mu)
        })
        .sum();
    (2.0 * sum / N as f64) as f32
}

/// The stored E tables of `micro` as numbers.
pub(super) fn stored(micro: Microfacet) -> Vec<f32> {
    STORED[index(micro) * ENTRIES * 2..][..ENTRIES * 2]
        .chunks_exact(2)
        .map(|b| f32::from(u16::from_le_bytes([b[0], b[1]])) / f32::from(u16::MAX))
        .collect()
}

impl Tables {
    /// The tables of `micro` from the stored ones.
    fn decode(micro: Microfacet) -> Tables {
        let e = stored(micro);
        // 1 − 2 ∫ E(μ) μ dμ of each row as interpolated.
        let lost = e.chunks(MUS).map(|row| (1.0 - cosine_mean(row)).max(0.0) as f32).collect();
        Tables { e, lost }
    }

    /// E(μ, α, η′), trilinear.
    pub(super) fn e(&self, mu: f32, alpha: f32, etap: f32) -> f32 {
        let (side, (i, s)) = side_and_eta(etap);
        let (k, r) = grid(alpha, ALPHAS);
        let (j, t) = grid(mu, MUS);
        let at = |i: usize, k: usize| {
            let row = &self.e[((side * ETAS + i) * ALPHAS + k) * MUS..][..MUS];
            row[j] * (1.0 - t) + row[j + 1] * t
        };
        let blend = |i: usize| at(i, k) * (1.0 - r) + at(i, k + 1) * r;
        blend(i) * (1.0 - s) + blend(i + 1) * s
    }

    /// ℓ(α, η′) = 1 − E_avg, bilinear (the exact mean of the interpolated E).
    pub(super) fn lost(&self, alpha: f32, etap: f32) -> f32 {
        let (side, (i, s)) = side_and_eta(etap);
        let (k, r) = grid(alpha, ALPHAS);
        let at = |i: usize, k: usize| self.lost[(side * ETAS + i) * ALPHAS + k];
        let blend = |i: usize| at(i, k) * (1.0 - r) + at(i, k + 1) * r;
        blend(i) * (1.0 - s) + blend(i + 1) * s
    }
}
