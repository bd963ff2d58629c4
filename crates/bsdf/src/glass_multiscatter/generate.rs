//! The generator of the stored tables of [`super::tables`] (`albedo.bin`), and the check
//! that they are what it computes. Regenerate them (after any change to the glass lobe's
//! albedo) with
//! `cargo test --release -p bsdf --lib generate_the_stored_glass_tables -- --ignored`.

use glam::{Vec2, Vec3A};

use super::tables::{grid_eta, index, stored, ALPHAS, ENTRIES, ETAS, MICROS, MUS};
use crate::rough_glass::{Halves, Microfacet, RoughGlass};

/// Micro-normals per table entry.
const SAMPLES: u32 = 8192;

/// Entry `n` of the E table of `micro` (side, η index, α index and μ index in that order
/// of nesting). Rows of α = 0 (smooth glass) lose nothing: 1.
fn entry(micro: Microfacet, n: usize) -> f32 {
    let (r, j) = (n / MUS, n % MUS);
    let (side, i, k) = (r / (ETAS * ALPHAS), r / ALPHAS % ETAS, r % ALPHAS);
    if k == 0 {
        return 1.0;
    }
    // η = 1 is no boundary: tabulated just above it, where the lobe is one from both
    // sides ([`RoughGlass::is_valid`]: |η′ − 1| ≥ 10⁻³).
    let eta = grid_eta(i).max(1.002);
    let etap = if side == 0 { eta } else { 1.0 / eta };
    let alpha = k as f32 / (ALPHAS - 1) as f32;
    let glass =
        RoughGlass { alpha_x: alpha, alpha_y: alpha, eta: etap, micro, halves: Halves::Both, thin: false, film: 0 };
    let mu = (j as f32 / (MUS - 1) as f32).max(1e-3);
    let wo = Vec3A::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
    albedo(&glass, wo).clamp(0.0, 1.0)
}

/// The albedo of `glass` at `wo` by [`SAMPLES`] micro-normals (R2 quasi-random points).
fn albedo(glass: &RoughGlass, wo: Vec3A) -> f32 {
    const G: f64 = 1.324_717_957_244_746;
    let sum: f64 = (0..SAMPLES)
        .map(|i| {
            let x = f64::from(i) + 0.5;
            let u = Vec2::new((x / G).fract() as f32, (x / (G * G)).fract() as f32);
            f64::from(glass.albedo_sample(wo, u))
        })
        .sum();
    (sum / f64::from(SAMPLES)) as f32
}

/// The stored form of E: E · 65535 rounded.
fn quantised(e: f32) -> u16 {
    (e.clamp(0.0, 1.0) * f32::from(u16::MAX)).round() as u16
}

/// Computes every table and writes `albedo.bin` (entries shared among the machine's
/// cores; each is computed alone, so the file does not depend on their count).
#[test]
#[ignore]
fn generate_the_stored_glass_tables() {
    let threads = std::thread::available_parallelism().map_or(1, usize::from);
    let mut bytes = Vec::with_capacity(MICROS.len() * ENTRIES * 2);
    for micro in MICROS {
        let mut e = vec![0u16; ENTRIES];
        let per_thread = ENTRIES.div_ceil(threads);
        std::thread::scope(|scope| {
            for (c, chunk) in e.chunks_mut(per_thread).enumerate() {
                scope.spawn(move || {
                    for (n, q) in chunk.iter_mut().enumerate() {
                        *q = quantised(entry(micro, c * per_thread + n));
                    }
                });
            }
        });
        bytes.extend(e.iter().flat_map(|q| q.to_le_bytes()));
    }
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/glass_multiscatter/albedo.bin");
    std::fs::write(path, bytes).unwrap();
}

/// The stored tables are what the generator computes: 8 entries of each distribution and
/// masking spread over sides, η, α > 0 and μ equal the generator's value within 1e-5 (the
/// rounding to 16 bits is 7.6e-6).
#[test]
fn the_stored_glass_tables_are_what_the_generator_computes() {
    for micro in MICROS {
        let e = stored(micro);
        for m in 0..8 {
            let (side, i, k, j) =
                (m % 2, (5 * m + index(micro)) % ETAS, 1 + (3 * m) % (ALPHAS - 1), (11 * m + 4) % MUS);
            let n = ((side * ETAS + i) * ALPHAS + k) * MUS + j;
            let want = f32::from(quantised(entry(micro, n))) / f32::from(u16::MAX);
            assert!((e[n] - want).abs() <= 1e-5, "{micro:?} entry {n}: stored {} vs {want}", e[n]);
        }
    }
}
