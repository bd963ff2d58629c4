//! A homogeneous participating medium: RGB absorption and scattering coefficients (per
//! scene unit of length), the radiance it emits per unit length, its phase function ([`crate::phase`]: a Henyey–Greenstein lobe,
//! or a mixture of up to [`MAX_PHASE_LOBES`] of them, per channel), transmittance
//! (Beer–Lambert) and chromatic free-flight sampling.
//!
//! Free flights with per-channel coefficients pick a colour channel and draw the distance
//! from that channel's exponential; the density of the distance is the channels' densities
//! mixed by the probabilities of picking them (one-sample MIS with the balance heuristic
//! over channels), so the weights stay finite when the channels differ. The probabilities
//! are the path's throughput per channel, normalised ([`channel_probabilities`]; uniform
//! for a white or zero throughput): a path whose light is mostly in one channel draws its
//! distances mostly for that channel, and weights do not compound over many scatterings
//! (as [`crate::phase`] picks channels too).

use glam::Vec2;

pub use crate::phase::{channel_probabilities, HenyeyGreenstein, Phase, PhaseSample, MAX_PHASE_LOBES};
use crate::Rgb;

/// A homogeneous medium: absorption and scattering coefficients per channel (1 / scene
/// unit of length; MDL's are per metre, and mira's scene unit is the metre) and how it
/// scatters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Medium {
    /// σa, the absorption coefficient (≥ 0).
    pub sigma_a: Rgb,
    /// σs, the scattering coefficient (≥ 0).
    pub sigma_s: Rgb,
    /// The phase function of its scattering.
    pub phase: Phase,
    /// ε, the radiance it emits per unit length (per channel; ≥ 0): along a ray,
    /// dL/ds = ε − σt·L (MDL's `material_volume.emission_intensity`).
    pub emission: Rgb,
}

/// Where a free flight through a [`Medium`] ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Flight {
    /// The ray reached the end of the segment; multiply the path's throughput by `weight`
    /// (transmittance over the sampling probability of getting there).
    Through {
        /// Throughput factor.
        weight: Rgb,
    },
    /// The light scattered at distance `t` (< the segment's end); multiply the throughput by
    /// `weight` (transmittance × σs over the distance's density), then sample the phase
    /// function.
    Scattered {
        /// Distance along the ray (units of the ray's unit direction).
        t: f32,
        /// Throughput factor.
        weight: Rgb,
    },
}

impl Medium {
    /// A medium of absorption `sigma_a` and scattering `sigma_s` (negative and non-finite
    /// channels read as 0) scattering with asymmetry `g`.
    pub fn new(sigma_a: Rgb, sigma_s: Rgb, g: f32) -> Medium {
        Medium::with_phase(sigma_a, sigma_s, Phase::henyey_greenstein(g))
    }

    /// A medium of absorption `sigma_a` and scattering `sigma_s` (negative and non-finite
    /// channels read as 0) scattering by `phase`.
    pub fn with_phase(sigma_a: Rgb, sigma_s: Rgb, phase: Phase) -> Medium {
        Medium { sigma_a: clean(sigma_a), sigma_s: clean(sigma_s), phase, emission: Rgb::ZERO }
    }

    /// The medium emitting radiance `emission` per unit length (negative and non-finite
    /// channels read as 0).
    pub fn with_emission(self, emission: Rgb) -> Medium {
        Medium { emission: clean(emission), ..self }
    }

    /// The radiance the medium emits towards the start of a segment of length `d` (scene
    /// units; may be infinite), attenuated on the way: ∫₀ᵈ exp(−σt·s)·ε ds =
    /// ε·(1 − exp(−σt·d))/σt per channel (ε·d where σt = 0; 0 where σt = 0 over an
    /// infinite segment, which no closed object holds).
    pub fn emitted(&self, d: f32) -> Rgb {
        let st = self.sigma_t();
        let f = |e: f32, s: f32| {
            if e <= 0.0 || d <= 0.0 {
                0.0
            } else if s > 0.0 {
                e * -(-s * d).exp_m1() / s
            } else if d.is_finite() {
                e * d
            } else {
                0.0
            }
        };
        Rgb::new(f(self.emission.x, st.x), f(self.emission.y, st.y), f(self.emission.z, st.z))
    }

    /// σt = σa + σs, the extinction coefficient.
    pub fn sigma_t(&self) -> Rgb {
        self.sigma_a + self.sigma_s
    }

    /// Whether the medium scatters light (else it only absorbs: Beer–Lambert along rays,
    /// no scattering events).
    pub fn scatters(&self) -> bool {
        self.sigma_s != Rgb::ZERO
    }

    /// Whether the medium does anything at all (absorbs, scatters or emits).
    pub fn is_vacuum(&self) -> bool {
        self.sigma_t() == Rgb::ZERO && self.emission == Rgb::ZERO
    }

    /// The fraction of light per channel that crosses distance `d` (scene units; may be
    /// infinite) without being absorbed or scattered: exp(−σt·d).
    pub fn transmittance(&self, d: f32) -> Rgb {
        transmittance(self.sigma_t(), d)
    }

    /// A free flight along a segment of length `t_end` (may be infinite) of a path of
    /// throughput `by` per channel, from `u` in [0, 1)²: `u.x` picks the channel (by
    /// [`channel_probabilities`] of `by`), `u.y` the distance. Absorbing-only media never
    /// scatter: the flight goes through with the Beer–Lambert transmittance.
    pub fn sample_flight(&self, t_end: f32, u: Vec2, by: Rgb) -> Flight {
        let sigma_t = self.sigma_t();
        if !self.scatters() {
            return Flight::Through { weight: transmittance(sigma_t, t_end) };
        }
        let picks = channel_probabilities(by);
        let channel = if u.x < picks.x {
            0
        } else if u.x < picks.x + picks.y {
            1
        } else {
            2
        };
        let s = sigma_t[channel];
        let t = if s > 0.0 { -(1.0 - u.y).max(f32::MIN_POSITIVE).ln() / s } else { f32::INFINITY };
        if t < t_end {
            let tr = transmittance(sigma_t, t);
            // The density of t: the channels' exponential densities mixed by their picks.
            let pdf = (sigma_t * tr).dot(picks);
            if pdf <= 0.0 || !pdf.is_finite() {
                return Flight::Through { weight: Rgb::ZERO };
            }
            Flight::Scattered { t, weight: tr * self.sigma_s / pdf }
        } else {
            let tr = transmittance(sigma_t, t_end);
            // The probability of passing t_end: the channels' survival mixed by their picks.
            let p = tr.dot(picks);
            Flight::Through { weight: if p > 0.0 { tr / p } else { Rgb::ZERO } }
        }
    }
}

/// `c` with its negative and non-finite channels 0.
fn clean(c: Rgb) -> Rgb {
    Rgb::select(c.cmpgt(Rgb::ZERO) & c.is_finite_mask(), c, Rgb::ZERO)
}

/// exp(−σ·d) per channel, 1 where σ is 0 (even for infinite `d`).
fn transmittance(sigma: Rgb, d: f32) -> Rgb {
    let f = |s: f32| if s <= 0.0 { 1.0 } else { (-s * d).exp() };
    Rgb::new(f(sigma.x), f(sigma.y), f(sigma.z))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::r2;

    /// Beer–Lambert: exp(−σt·d) per channel within 1e-6, 1 for σt = 0 even over an
    /// infinite distance, 0 for σt > 0 over an infinite one.
    #[test]
    fn transmittance_is_beer_lambert() {
        let m = Medium::new(Rgb::new(0.5, 2.0, 0.0), Rgb::new(0.25, 0.0, 0.0), 0.0);
        let tr = m.transmittance(1.5);
        assert!((tr.x - (-0.75f32 * 1.5).exp()).abs() < 1e-6);
        assert!((tr.y - (-3.0f32).exp()).abs() < 1e-6);
        assert_eq!(tr.z, 1.0);
        let inf = m.transmittance(f32::INFINITY);
        assert_eq!(inf, Rgb::new(0.0, 0.0, 1.0));
        assert_eq!(Medium::new(Rgb::splat(-1.0), Rgb::splat(f32::NAN), 0.0).sigma_t(), Rgb::ZERO);
    }

    /// Emission along a segment: ε·(1 − exp(−σt·d))/σt per channel within 1e-6 relative
    /// (the integral of the transmittance-weighted emission, checked against a midpoint sum
    /// of 10 000 steps too), ε·d without extinction, ε/σt over an infinite segment.
    #[test]
    fn emission_is_the_attenuated_integral() {
        let m =
            Medium::new(Rgb::new(0.5, 0.0, 2.0), Rgb::new(0.25, 0.0, 0.0), 0.0).with_emission(Rgb::new(1.0, 2.0, -3.0));
        let d = 1.5f32;
        let got = m.emitted(d);
        assert!((got.x - (1.0 - (-0.75f32 * d).exp()) / 0.75).abs() < 1e-6, "{got:?}");
        assert!((got.y - 2.0 * d).abs() < 1e-6, "{got:?}");
        assert_eq!(got.z, 0.0, "negative emission reads as 0");
        let n = 10_000;
        let sum: f32 = (0..n).map(|i| (-0.75 * (i as f32 + 0.5) * d / n as f32).exp() * d / n as f32).sum();
        assert!((got.x - sum).abs() < 1e-4, "{} vs {sum}", got.x);
        let far = m.emitted(f32::INFINITY);
        assert!((far.x - 1.0 / 0.75).abs() < 1e-6 && far.y == 0.0, "{far:?}");
        assert!(!Medium::new(Rgb::ZERO, Rgb::ZERO, 0.0).with_emission(Rgb::ONE).is_vacuum());
    }

    /// An absorbing-only medium never scatters: its flight weight is exactly its
    /// transmittance.
    #[test]
    fn absorbing_flights_are_beer_lambert() {
        let m = Medium::new(Rgb::new(0.3, 1.0, 4.0), Rgb::ZERO, 0.0);
        for i in 0..100 {
            match m.sample_flight(0.7, r2(i), Rgb::ONE) {
                Flight::Through { weight } => assert_eq!(weight, m.transmittance(0.7)),
                other => panic!("an absorbing medium scattered: {other:?}"),
            }
        }
    }

    /// Chromatic free flights are unbiased whatever throughput picks the channels (white,
    /// and mostly blue): over 400 000 flights through a segment of length 1.3 of a medium
    /// whose channels differ by 16×, the mean weight of flights that go through is the
    /// transmittance, and the mean weight of flights that scatter before distance x
    /// (divided by σs) is ∫₀ˣ exp(−σt s) ds, each channel within 1 %.
    #[test]
    fn chromatic_free_flights_are_unbiased() {
        for by in [Rgb::ONE, Rgb::new(0.1, 0.3, 2.0)] {
            chromatic_free_flights_are_unbiased_for(by);
        }
        let picks = channel_probabilities(Rgb::new(0.1, 0.3, 2.0));
        assert!((picks - Rgb::new(0.1, 0.3, 2.0) / 2.4).abs().max_element() < 1e-6, "{picks:?}");
        assert_eq!(channel_probabilities(Rgb::new(-1.0, 0.0, f32::NAN)), Rgb::splat(1.0 / 3.0));
        assert_eq!(channel_probabilities(Rgb::ONE), Rgb::splat(1.0 / 3.0));
    }

    fn chromatic_free_flights_are_unbiased_for(by: Rgb) {
        let m = Medium::new(Rgb::new(0.1, 0.4, 1.2), Rgb::new(0.2, 0.6, 2.0), 0.3);
        let (t_end, x, n) = (1.3f32, 0.5f32, 400_000u32);
        let (mut through, mut early) = (Rgb::ZERO, Rgb::ZERO);
        for i in 0..n {
            match m.sample_flight(t_end, r2(i), by) {
                Flight::Through { weight } => through += weight,
                Flight::Scattered { t, weight } => {
                    assert!(t >= 0.0 && t < t_end);
                    if t < x {
                        early += weight / m.sigma_s;
                    }
                }
            }
        }
        let st = m.sigma_t();
        let expect_through = m.transmittance(t_end);
        let expect_early = (Rgb::ONE - m.transmittance(x)) / st;
        for c in 0..3 {
            let got = through[c] / n as f32;
            assert!(
                (got / expect_through[c] - 1.0).abs() < 0.01,
                "channel {c}: through {got} vs {}",
                expect_through[c]
            );
            let got = early[c] / n as f32;
            assert!((got / expect_early[c] - 1.0).abs() < 0.01, "channel {c}: early {got} vs {}", expect_early[c]);
        }
    }

    /// An albedo-1 grey medium has weight 1 for every flight (scattering or not): the
    /// white furnace inside the medium holds sample by sample.
    #[test]
    fn grey_scattering_weights_are_one() {
        let m = Medium::new(Rgb::ZERO, Rgb::splat(2.0), 0.6);
        for i in 0..1000 {
            let w = match m.sample_flight(0.8, r2(i), Rgb::ONE) {
                Flight::Through { weight } | Flight::Scattered { weight, .. } => weight,
            };
            assert!((w - Rgb::ONE).abs().max_element() < 1e-5, "{w:?}");
        }
    }
}
