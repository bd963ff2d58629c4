//! MDL's `df::fog_vdf(particle_size)` (MDL 1.8): "volume light distribution based on an
//! approximation of the Mie scattering function particularly suitable for fog or
//! cloud-like media", `particle_size` the mean diameter of the particles in micrometres
//! (default 8; the MDL specification 1.8+ §"Volume distribution functions" and the MDL
//! SDK's `df.mdl`). The specification cites, as its approximation, Jendersie and d'Eon,
//! "An Approximate Mie Scattering Function for Fog and Cloud Rendering" (SIGGRAPH 2023
//! Talks): Mie scattering by water droplets of diameter d is a blend of a
//! Henyey–Greenstein lobe (the forward diffraction peak) and a [`Draine`] lobe (the
//! rest),
//!
//! p(θ) = (1 − w_D) · HG(θ; g_HG) + w_D · Draine(θ; g_D, α),
//!
//! with the four parameters fitted to Mie theory as functions of d (µm, natural
//! logarithms; the paper's equations 7–10 for 5 ≤ d ≤ 50 and its supplement's for
//! smaller droplets):
//!
//! - 5 ≤ d ≤ 50: g_HG = exp(−0.0990567/(d − 1.67154)), g_D = exp(−2.20679/(d + 3.91029)
//!   − 0.428934), α = exp(3.62489 − 8.29288/(d + 5.52825)), w_D = exp(−0.599085/(d −
//!   0.641583) − 0.665888);
//! - 1.5 ≤ d < 5: g_HG = 0.0604931 ln ln d + 0.940256, g_D = 0.500411 −
//!   0.081287/(−2 ln d + tan ln d + 1.27551), α = 7.30354 ln d + 6.31675, w_D = 0.026914
//!   (ln d − cos(5.68947 (ln ln d − 0.0292149))) + 0.376475;
//! - 0.1 < d < 1.5: g_HG = 0.862 − 0.143 ln²d, g_D = 0.379685 cos(1.19692 cos((ln d −
//!   0.238604)(ln d + 1.00667)/(0.507522 − 0.15677 ln d)) + 1.37932 ln d + 0.0625835) +
//!   0.344213, α = 250, w_D = 0.146209 cos(3.38707 ln d + 2.11193) + 0.316072 + 0.0778917
//!   ln d;
//! - d ≤ 0.1: g_HG = 13.8 d², g_D = 1.1456 d sin(9.29044 d), α = 250, w_D = 0.252977 −
//!   312.983 d^4.3.
//!
//! The diameter is clamped to [0, 50] µm (the fits' range; NaN is the default 8) and w_D
//! to [0, 1]. Both lobes are sampled exactly ([`Draine`]), so the blend is its own
//! sampling density.

use super::Draine;

/// `df::fog_vdf`'s default `particle_size`, µm (the MDL SDK's `df.mdl`).
pub const DEFAULT_PARTICLE_SIZE: f32 = 8.0;

/// The fitted parameters of droplets of diameter `d` (µm): (g_HG, g_D, α, w_D).
fn fit(d: f32) -> (f32, f32, f32, f32) {
    let d = if d.is_nan() { DEFAULT_PARTICLE_SIZE } else { d.clamp(0.0, 50.0) };
    if d >= 5.0 {
        (
            (-0.099_056_7 / (d - 1.671_54)).exp(),
            (-2.206_79 / (d + 3.910_29) - 0.428_934).exp(),
            (3.624_89 - 8.292_88 / (d + 5.528_25)).exp(),
            (-0.599_085 / (d - 0.641_583) - 0.665_888).exp(),
        )
    } else if d >= 1.5 {
        let l = d.ln();
        let ll = l.ln();
        (
            0.060_493_1 * ll + 0.940_256,
            0.500_411 - 0.081_287 / (-2.0 * l + l.tan() + 1.275_51),
            7.303_54 * l + 6.316_75,
            0.026_914 * (l - (5.689_47 * (ll - 0.029_214_9)).cos()) + 0.376_475,
        )
    } else if d > 0.1 {
        let l = d.ln();
        let inner = ((l - 0.238_604) * (l + 1.006_67) / (0.507_522 - 0.156_77 * l)).cos();
        (
            0.862 - 0.143 * l * l,
            0.379_685 * (1.196_92 * inner + 1.379_32 * l + 0.062_583_5).cos() + 0.344_213,
            250.0,
            0.146_209 * (3.387_07 * l + 2.111_93).cos() + 0.316_072 + 0.077_891_7 * l,
        )
    } else {
        (13.8 * d * d, 1.1456 * d * (9.290_44 * d).sin(), 250.0, 0.252_977 - 312.983 * d.powf(4.3))
    }
}

/// The two lobes of `df::fog_vdf` for droplets of diameter `particle_size` (µm), with
/// their weights (summing to 1): Henyey–Greenstein first, then Draine's.
pub fn fog_lobes(particle_size: f32) -> [(f32, Draine); 2] {
    let (g_hg, g_d, alpha, w_d) = fit(particle_size);
    let w_d = w_d.clamp(0.0, 1.0);
    [(1.0 - w_d, Draine::henyey_greenstein(g_hg)), (w_d, Draine::new(g_d, alpha))]
}
