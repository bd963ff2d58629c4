//! The light terms of a daylight sky ([`SkyLight`]: the sun's illuminance and the sky's
//! illuminance on a horizontal plane) interpolated between turbidities and sun heights on
//! a grid, for skies whose haze varies from one lookup to the next (MDL's
//! `base::sun_and_sky` with a varying `haze`).
//!
//! Exactly, each term costs a spectral integral (the sun, 2 × 81 wavelengths) or a
//! 24 × 48-point integral of the sky (1152 evaluations of the Perez model): more than
//! a thousand times a lookup's own work, and a haze that varies continuously never
//! meets the same sky twice. Both are smooth functions of the turbidity T (2 + haze) and of
//! the sun's height z (the up component of the lifted sun) alone, for Preetham's plain
//! model ([`PhysicalSky::is_plain_daylight`](crate::sky::PhysicalSky::is_plain_daylight)):
//! they are computed exactly at grid nodes T = 2 + i/64 (at the sky's own z), remembered
//! per thread, and interpolated linearly in between: within 1e-4 relative (to each term's
//! largest channel) for hazes 0 to 10 and the sun 5° to 80° up. (In the sun's height the
//! terms curve too sharply near the horizon and the zenith for a coarse grid: a sky whose
//! horizon height varies is computed exactly.)

use std::cell::RefCell;
use std::collections::HashMap;

use glam::Vec3A;

use crate::sky::{Daylight, SkyLight};
use crate::sun::sun_illuminance;

/// Turbidity between grid nodes.
const T_STEP: f32 = 1.0 / 64.0;
/// Nodes remembered per thread before the table starts over.
const MAX_NODES: usize = 8192;

thread_local! {
    static NODES: RefCell<HashMap<(u32, u32), SkyLight>> = RefCell::new(HashMap::new());
}

/// The exact light terms at turbidity `t` and sun height `z`, remembered per thread.
fn node(t: f32, z: f32) -> SkyLight {
    let key = (t.to_bits(), z.to_bits());
    if let Some(l) = NODES.with(|n| n.borrow().get(&key).copied()) {
        return l;
    }
    // The terms do not depend on the sun's azimuth.
    let sun = Vec3A::new((1.0 - z * z).max(0.0).sqrt(), 0.0, z);
    let l = SkyLight { sun: sun_illuminance(t, z), sky_horizontal: Daylight::new(t, sun).horizontal_illuminance() };
    NODES.with(|n| {
        let mut n = n.borrow_mut();
        if n.len() >= MAX_NODES {
            n.clear();
        }
        n.insert(key, l);
    });
    l
}

/// `a` + (`b` − `a`) × `w`, term by term.
fn lerp(a: SkyLight, b: SkyLight, w: f32) -> SkyLight {
    SkyLight {
        sun: a.sun + (b.sun - a.sun) * w,
        sky_horizontal: a.sky_horizontal + (b.sky_horizontal - a.sky_horizontal) * w,
    }
}

/// The light terms of Preetham's plain daylight at turbidity `t` (≥ 2) and lifted sun
/// height `z`, interpolated in the turbidity between nodes 1/64 apart.
pub fn interpolated(t: f32, z: f32) -> SkyLight {
    let f = ((t - 2.0).max(0.0) / T_STEP).min(1e6);
    let i = f.floor();
    let (t0, t1) = (2.0 + i * T_STEP, 2.0 + (i + 1.0) * T_STEP);
    lerp(node(t0, z), node(t1, z), f - i)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact terms at turbidity `t` and sun height `z`.
    fn exact(t: f32, z: f32) -> SkyLight {
        let sun = Vec3A::new((1.0 - z * z).sqrt(), 0.0, z);
        SkyLight { sun: sun_illuminance(t, z), sky_horizontal: Daylight::new(t, sun).horizontal_illuminance() }
    }

    /// Error of `got` against `want` relative to each term's largest channel, the worse term.
    fn error(got: SkyLight, want: SkyLight) -> f32 {
        let rel = |a: Vec3A, b: Vec3A| (a - b).abs().max_element() / b.max_element();
        rel(got.sun, want.sun).max(rel(got.sky_horizontal, want.sky_horizontal))
    }

    /// Between the nodes the interpolated terms are the exact ones within 1e-4 relative to
    /// each term's largest channel (haze 0 to 10, the sun 5° to 80° up); at a node,
    /// exactly.
    #[test]
    fn interpolated_terms_are_the_exact_ones_within_1e4() {
        let mut worst = 0.0f32;
        for i in 0..24 {
            let t = 2.0 + 10.0 * (i as f32 + 0.31) / 24.0;
            for el in [5.0f32, 20.0, 47.0, 80.0] {
                let z = el.to_radians().sin();
                let want = exact(t, z);
                worst = worst.max(error(interpolated(t, z), want));
            }
        }
        eprintln!("worst relative error {worst}");
        assert!(worst < 1e-4, "worst relative error {worst}");
        assert_eq!(interpolated(2.5, 0.5), exact(2.5, 0.5));
    }
}
