//! Phase functions of participating media: the Henyey–Greenstein lobe, Draine's
//! ([`Draine`], Henyey–Greenstein reshaped by 1 + α cos²θ), and mixtures of up to
//! [`MAX_PHASE_LOBES`] of them ([`Phase`], MDL's mixes of `anisotropic_vdf`s and
//! `fog_vdf`s, the latter two lobes each: [`fog_lobes`]), whose weights may differ per
//! colour channel.
//!
//! A *chromatic* mixture (colour weights that are not proportional to each other) is one
//! phase function per channel: p_c(θ) = Σₖ w_{c,k} HGₖ(θ), each normalised. Its
//! directions are drawn as chromatic free flights draw distances ([`crate::medium`]): a
//! channel picked at random, a lobe by that channel's weights, a direction from the lobe;
//! their density is the channels' densities mixed by the probabilities of picking them,
//! p̄ = Σ_c P_c p_c (one-sample MIS over channels with the balance heuristic), so a
//! sampled direction weighs p_c/p̄ per channel. The probabilities are the path's
//! throughput per channel, normalised (uniform when it is zero): then the path's
//! throughput summed over the channels is the same after the scattering as before, and
//! weights cannot grow over many scatterings (with uniform picks, a channel whose phase
//! function differs from the others' mean compounds factors up to 3 per scattering).
//! Light sampling weighs a light's direction by p_c per channel and against the same p̄
//! for MIS. A mixture whose weights are the same in every channel is *grey*: then p̄ is
//! every channel's density, a sampled direction weighs exactly 1, and nothing per channel
//! is computed.

use glam::{Vec2, Vec3A};

use crate::{Frame, Rgb};

mod draine;
mod fog;

pub use draine::Draine;
pub use fog::{fog_lobes, DEFAULT_PARTICLE_SIZE};

/// The Henyey–Greenstein phase function with asymmetry `g` in (−1, 1): the mean cosine
/// between the direction light travelled before and after scattering (> 0 forward, < 0
/// backward, 0 isotropic). MDL's `df::anisotropic_vdf(directional_bias)` is this with
/// g = directional_bias.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    /// The asymmetry parameter, clamped to [−0.999, 0.999].
    pub g: f32,
}

/// |g| below this is sampled as isotropic (the inverse CDF divides by g).
const ISOTROPIC_G: f32 = 1e-3;

impl HenyeyGreenstein {
    /// The phase function of asymmetry `g` (clamped to [−0.999, 0.999]; NaN is 0).
    pub fn new(g: f32) -> HenyeyGreenstein {
        let g = if g.is_nan() { 0.0 } else { g.clamp(-0.999, 0.999) };
        HenyeyGreenstein { g }
    }

    /// The density (per steradian) of scattering by angle θ, given cos θ between the
    /// travel direction before and after.
    pub fn eval_cos(&self, cos_theta: f32) -> f32 {
        let g = self.g;
        let denom = (1.0 + g * g - 2.0 * g * cos_theta).max(1e-12);
        (1.0 - g * g) / (4.0 * std::f32::consts::PI * denom * denom.sqrt())
    }

    /// The density of light travelling along unit `dir_in` leaving along unit `dir_out`
    /// (both world space, directions of travel). The phase function is its own sampling
    /// density: this is also [`HenyeyGreenstein::sample`]'s pdf.
    pub fn eval(&self, dir_in: Vec3A, dir_out: Vec3A) -> f32 {
        self.eval_cos(dir_in.dot(dir_out))
    }

    /// cos θ of a scattering angle drawn from the phase function with `u` in [0, 1).
    pub fn sample_cos(&self, u: f32) -> f32 {
        let g = self.g;
        if g.abs() < ISOTROPIC_G {
            return 1.0 - 2.0 * u;
        }
        let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
        ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
    }

    /// A direction of travel after scattering light that travelled along unit `dir_in`
    /// (world space), and its density (per steradian), from `u` in [0, 1)².
    pub fn sample(&self, dir_in: Vec3A, u: Vec2) -> (Vec3A, f32) {
        let cos = self.sample_cos(u.x);
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * std::f32::consts::PI * u.y;
        let local = Vec3A::new(sin * phi.cos(), sin * phi.sin(), cos);
        let dir = Frame::from_normal(dir_in).to_world(local).normalize();
        (dir, self.eval_cos(cos))
    }
}

/// Most Henyey–Greenstein lobes a [`Phase`] mixes.
pub const MAX_PHASE_LOBES: usize = 4;

/// A phase function: a mixture of Henyey–Greenstein or Draine lobes, usually one, with
/// weights per colour channel summing to 1 in each channel (see the module documentation).
/// A grey one (equal weights in all channels) is its own sampling density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Phase {
    /// The mixture's mean cosine, Σₖ wₖ ⟨cos θ⟩ₖ (a Henyey–Greenstein lobe's g when there
    /// is one; the channels' mean of it when the weights differ per channel).
    pub g: f32,
    /// The lobes' weights per channel (r, g, b); the first `count` are used.
    weights: [[f32; 3]; MAX_PHASE_LOBES],
    /// The lobes; the first `count` are used.
    lobes: [Draine; MAX_PHASE_LOBES],
    /// How many lobes are used (≥ 1).
    count: u8,
    /// Whether the weights differ per channel.
    chromatic: bool,
}

/// A direction drawn from a [`Phase`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseSample {
    /// The direction of travel after scattering (world space, unit).
    pub dir: Vec3A,
    /// Its sampling density per steradian ([`Phase::pdf`]).
    pub pdf: f32,
    /// The phase function's value per channel over `pdf` ([`Phase::value`] / `pdf`): what
    /// the path's throughput is multiplied by; exactly 1 for a grey phase function.
    pub weight: Rgb,
}

impl Phase {
    /// One Henyey–Greenstein lobe of asymmetry `g` (see [`HenyeyGreenstein::new`]).
    pub fn henyey_greenstein(g: f32) -> Phase {
        let lobe = Draine::henyey_greenstein(g);
        Phase {
            g: lobe.g,
            weights: [[1.0; 3]; MAX_PHASE_LOBES],
            lobes: [lobe; MAX_PHASE_LOBES],
            count: 1,
            chromatic: false,
        }
    }

    /// The grey mixture of lobes (weight, g): weights below 0 or not finite count as 0 and
    /// the rest are normalized to sum to 1 (none left: isotropic); past
    /// [`MAX_PHASE_LOBES`] lobes, the lightest ones are merged into one lobe of their
    /// weighted mean g (which keeps the mixture's mean cosine).
    pub fn mixture(lobes: &[(f32, f32)]) -> Phase {
        let lobes: Vec<(f32, Draine)> =
            lobes.iter().filter(|(_, g)| !g.is_nan()).map(|(w, g)| (*w, Draine::henyey_greenstein(*g))).collect();
        Phase::mixture_of(&lobes)
    }

    /// [`Phase::mixture`] of any lobes (weight, lobe); merged lobes become one
    /// Henyey–Greenstein lobe of their weighted mean cosine.
    pub fn mixture_of(lobes: &[(f32, Draine)]) -> Phase {
        let mut used: Vec<(f32, Draine)> = lobes.iter().filter(|(w, _)| w.is_finite() && *w > 0.0).copied().collect();
        let total: f32 = used.iter().map(|(w, _)| w).sum();
        if used.is_empty() || total <= 0.0 {
            return Phase::henyey_greenstein(0.0);
        }
        if used.len() == 1 {
            return Phase {
                g: used[0].1.mean_cosine(),
                lobes: [used[0].1; MAX_PHASE_LOBES],
                ..Phase::henyey_greenstein(0.0)
            };
        }
        if used.len() > MAX_PHASE_LOBES {
            used.sort_by(|a, b| b.0.total_cmp(&a.0));
            let rest = used.split_off(MAX_PHASE_LOBES - 1);
            let w: f32 = rest.iter().map(|(w, _)| w).sum();
            let g = rest.iter().map(|(w, l)| w * l.mean_cosine()).sum::<f32>() / w;
            used.push((w, Draine::henyey_greenstein(g)));
        }
        let mut phase = Phase::henyey_greenstein(0.0);
        phase.count = used.len() as u8;
        phase.g = 0.0;
        for (k, (w, lobe)) in used.iter().enumerate() {
            phase.weights[k] = [w / total; 3];
            phase.lobes[k] = *lobe;
            phase.g += phase.weights[k][0] * lobe.mean_cosine();
        }
        phase
    }

    /// The mixture of lobes (weight per channel, g), each channel's weights normalized to
    /// sum to 1: a channel's phase function is its own mixture. Weights below 0 or not
    /// finite count as 0; a channel with no weight at all (it scatters nothing) takes the
    /// other channels' mean mixture; past [`MAX_PHASE_LOBES`] lobes the lightest (by their
    /// channels' mean weight) are merged into one lobe of their weighted mean g. Weights
    /// proportional in every channel give the grey [`Phase::mixture`].
    pub fn chromatic_mixture(lobes: &[(Rgb, f32)]) -> Phase {
        let lobes: Vec<(Rgb, Draine)> =
            lobes.iter().filter(|(_, g)| !g.is_nan()).map(|(w, g)| (*w, Draine::henyey_greenstein(*g))).collect();
        Phase::chromatic_mixture_of(&lobes)
    }

    /// [`Phase::chromatic_mixture`] of any lobes (weight per channel, lobe); merged lobes
    /// become one Henyey–Greenstein lobe of their weighted mean cosine.
    pub fn chromatic_mixture_of(lobes: &[(Rgb, Draine)]) -> Phase {
        let clean = |w: Rgb| Rgb::select(w.cmpgt(Rgb::ZERO) & w.is_finite_mask(), w, Rgb::ZERO);
        let mut used: Vec<(Rgb, Draine)> =
            lobes.iter().map(|(w, l)| (clean(*w), *l)).filter(|(w, _)| *w != Rgb::ZERO).collect();
        if used.len() > MAX_PHASE_LOBES {
            used.sort_by(|a, b| b.0.element_sum().total_cmp(&a.0.element_sum()));
            let rest = used.split_off(MAX_PHASE_LOBES - 1);
            let w = rest.iter().fold(Rgb::ZERO, |s, (w, _)| s + *w);
            let g = rest.iter().map(|(w, l)| w.element_sum() * l.mean_cosine()).sum::<f32>() / w.element_sum();
            used.push((w, Draine::henyey_greenstein(g)));
        }
        let total = used.iter().fold(Rgb::ZERO, |s, (w, _)| s + *w);
        let scatters = total.cmpgt(Rgb::ZERO);
        if !scatters.any() {
            return Phase::henyey_greenstein(0.0);
        }
        // Each channel's weights normalized; a channel without any, the others' mean.
        let normalized: Vec<(Rgb, Draine)> = used
            .iter()
            .map(|(w, l)| {
                let own = Rgb::select(scatters, *w / total, Rgb::ZERO);
                let mean = own.element_sum() / scatters.bitmask().count_ones() as f32;
                (Rgb::select(scatters, own, Rgb::splat(mean)), *l)
            })
            .collect();
        let grey = normalized.iter().all(|(w, _)| (w.max_element() - w.min_element()).abs() <= 1e-6);
        if grey {
            let lobes: Vec<(f32, Draine)> = normalized.iter().map(|(w, l)| (w.element_sum() / 3.0, *l)).collect();
            return Phase::mixture_of(&lobes);
        }
        let mut phase = Phase::henyey_greenstein(0.0);
        phase.count = normalized.len() as u8;
        phase.chromatic = true;
        let mut mean_cosine = Rgb::ZERO;
        for (k, (w, lobe)) in normalized.iter().enumerate() {
            phase.weights[k] = [w.x, w.y, w.z];
            phase.lobes[k] = *lobe;
            mean_cosine += *w * lobe.mean_cosine();
        }
        phase.g = mean_cosine.element_sum() / 3.0;
        phase
    }

    /// Whether the lobes' weights differ per channel (then [`Phase::sample`]'s weights are
    /// not 1).
    pub fn is_chromatic(&self) -> bool {
        self.chromatic
    }

    /// The lobes: their weights per channel (each channel's summing to 1) and lobes.
    pub fn lobes(&self) -> impl ExactSizeIterator<Item = (Rgb, Draine)> + '_ {
        let n = usize::from(self.count);
        self.weights[..n].iter().zip(&self.lobes[..n]).map(|(w, l)| (Rgb::from_array(*w), *l))
    }

    /// The sampling density (per steradian) of light travelling along unit `dir_in`
    /// leaving along unit `dir_out` (world space, directions of travel) for a path of
    /// throughput `by` per channel: the phase function itself when grey, the channels'
    /// densities mixed by the probabilities of picking them when chromatic
    /// ([`channel_probabilities`]). [`Phase::sample`]'s pdf.
    pub fn pdf(&self, dir_in: Vec3A, dir_out: Vec3A, by: Rgb) -> f32 {
        if self.count == 1 {
            return self.lobes[0].eval(dir_in, dir_out);
        }
        if self.chromatic {
            return self.value_cos(dir_in.dot(dir_out)).dot(channel_probabilities(by));
        }
        self.pdf_cos(dir_in.dot(dir_out))
    }

    /// The density of a grey phase function (per steradian) of scattering by angle θ,
    /// given cos θ; of a chromatic one, the channels' mean.
    pub fn pdf_cos(&self, cos_theta: f32) -> f32 {
        let lobes = self.weights[..usize::from(self.count)].iter().zip(&self.lobes);
        if self.chromatic {
            lobes.map(|(w, l)| (w[0] + w[1] + w[2]) / 3.0 * l.eval_cos(cos_theta)).sum()
        } else {
            lobes.map(|(w, l)| w[0] * l.eval_cos(cos_theta)).sum()
        }
    }

    /// The phase function per channel (per steradian) of light travelling along unit
    /// `dir_in` leaving along unit `dir_out` (world space, directions of travel).
    pub fn value(&self, dir_in: Vec3A, dir_out: Vec3A) -> Rgb {
        if !self.chromatic {
            return Rgb::splat(self.pdf(dir_in, dir_out, Rgb::ONE));
        }
        self.value_cos(dir_in.dot(dir_out))
    }

    /// [`Phase::value`] of scattering by angle θ, given cos θ.
    pub fn value_cos(&self, cos_theta: f32) -> Rgb {
        let lobes = self.weights[..usize::from(self.count)].iter().zip(&self.lobes);
        lobes.fold(Rgb::ZERO, |s, (w, l)| s + Rgb::from_array(*w) * l.eval_cos(cos_theta))
    }

    /// A direction of travel after scattering light that travelled along unit `dir_in`
    /// (world space) on a path of throughput `by` per channel, from `u` in [0, 1)²: `u.x`
    /// chooses the channel (when chromatic, by [`channel_probabilities`]), the lobe
    /// and, rescaled, its angle; `u.y` the azimuth.
    pub fn sample(&self, dir_in: Vec3A, u: Vec2, by: Rgb) -> PhaseSample {
        if self.count == 1 {
            let (dir, pdf) = self.lobes[0].sample(dir_in, u);
            return PhaseSample { dir, pdf, weight: Rgb::ONE };
        }
        if !self.chromatic {
            let dir = self.sample_in_channel(0, dir_in, u);
            return PhaseSample { dir, pdf: self.pdf(dir_in, dir, by), weight: Rgb::ONE };
        }
        let probabilities = channel_probabilities(by);
        let (mut channel, mut left) = (2, u.x);
        for c in 0..2 {
            if left < probabilities[c] {
                channel = c;
                break;
            }
            left -= probabilities[c];
        }
        let p = probabilities[channel];
        let ux = if p > 0.0 { (left / p).clamp(0.0, 1.0 - f32::EPSILON) } else { 0.0 };
        let dir = self.sample_in_channel(channel, dir_in, Vec2::new(ux, u.y));
        let value = self.value(dir_in, dir);
        let pdf = value.dot(probabilities);
        let weight = if pdf > 0.0 { value / pdf } else { Rgb::ZERO };
        PhaseSample { dir, pdf, weight }
    }

    /// A direction drawn from channel `channel`'s mixture: `u.x` chooses the lobe by that
    /// channel's weights and, rescaled, its angle.
    fn sample_in_channel(&self, channel: usize, dir_in: Vec3A, u: Vec2) -> Vec3A {
        let mut left = u.x;
        let last = usize::from(self.count) - 1;
        let mut k = last;
        for (i, w) in self.weights[..=last].iter().enumerate() {
            if left < w[channel] || i == last {
                k = i;
                break;
            }
            left -= w[channel];
        }
        let w = self.weights[k][channel];
        let ux = if w > 0.0 { (left / w).clamp(0.0, 1.0 - f32::EPSILON) } else { 0.0 };
        self.lobes[k].sample(dir_in, Vec2::new(ux, u.y)).0
    }
}

/// The probabilities of picking each colour channel to sample a free flight or a
/// chromatic phase function for a path of throughput `by`: proportional to it (negative
/// and non-finite channels count as 0), uniform when nothing is left. A white throughput
/// picks each channel with probability exactly 1/3.
pub fn channel_probabilities(by: Rgb) -> Rgb {
    let by = Rgb::select(by.cmpgt(Rgb::ZERO) & by.is_finite_mask(), by, Rgb::ZERO);
    let sum = by.element_sum();
    if sum > 0.0 && sum.is_finite() {
        by / sum
    } else {
        Rgb::splat(1.0 / 3.0)
    }
}

#[cfg(test)]
mod tests;
