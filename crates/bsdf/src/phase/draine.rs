//! Draine's phase function (Draine 2003, "Scattering by Interstellar Dust Grains. I.
//! Optical and Ultraviolet", ApJ 598): Henyey–Greenstein reshaped by a factor 1 + α cos²θ
//! and renormalised,
//!
//! p(θ) = 1/(4π) · (1 − g²)/(1 + g² − 2g cos θ)^{3/2} · (1 + α cos²θ)/(1 + α(1 + 2g²)/3).
//!
//! α = 0 is Henyey–Greenstein (evaluated and sampled exactly as [`HenyeyGreenstein`]);
//! g = 0, α = 1 is Rayleigh scattering. Its mean cosine follows from Henyey–Greenstein's
//! moments ⟨cos θ⟩ = g, ⟨cos²θ⟩ = (1 + 2g²)/3, ⟨cos³θ⟩ = g(3 + 2g²)/5:
//! ⟨cos θ⟩ = g (1 + α(3 + 2g²)/5) / (1 + α(1 + 2g²)/3).
//!
//! Sampling inverts its cumulative distribution in cos θ, which has a closed form (with
//! s = 1 + g² − 2g cos θ the Henyey–Greenstein part is ∝ s^{−1/2}, the cos²θ part a
//! polynomial in s^{±1/2}), by safeguarded Newton iterations in double precision: the
//! density [`Draine::eval_cos`] is exactly the sampling density. A lobe with α > 0 and
//! |g| < 10⁻³ is made g = 0 (the closed form divides by g³), which moves its mean cosine
//! by less than 10⁻³.

use glam::{Vec2, Vec3A};

use super::HenyeyGreenstein;
use crate::Frame;

/// One lobe of Draine's phase function (see the module documentation): asymmetry `g`
/// and shape `alpha` (0: Henyey–Greenstein).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Draine {
    /// Henyey–Greenstein's asymmetry, clamped to [−0.999, 0.999] (not the mean cosine
    /// when `alpha` > 0: see [`Draine::mean_cosine`]).
    pub g: f32,
    /// The weight of the cos²θ term, ≥ 0.
    pub alpha: f32,
}

/// |g| below this is 0 in a lobe with α > 0.
const SMALL_G: f32 = 1e-3;

impl Draine {
    /// The lobe of asymmetry `g` (NaN is 0; clamped to [−0.999, 0.999]) and shape `alpha`
    /// (NaN or negative: 0).
    pub fn new(g: f32, alpha: f32) -> Draine {
        let alpha = if alpha > 0.0 { alpha.min(1e6) } else { 0.0 };
        let mut g = HenyeyGreenstein::new(g).g;
        if alpha > 0.0 && g.abs() < SMALL_G {
            g = 0.0;
        }
        Draine { g, alpha }
    }

    /// Henyey–Greenstein of asymmetry `g`.
    pub fn henyey_greenstein(g: f32) -> Draine {
        Draine { g: HenyeyGreenstein::new(g).g, alpha: 0.0 }
    }

    /// The Henyey–Greenstein lobe it reshapes.
    fn hg(&self) -> HenyeyGreenstein {
        HenyeyGreenstein { g: self.g }
    }

    /// 1 + α(1 + 2g²)/3: what normalises the cos²θ factor.
    fn norm(&self) -> f32 {
        1.0 + self.alpha * (1.0 + 2.0 * self.g * self.g) / 3.0
    }

    /// The density (per steradian) of scattering by angle θ, given cos θ between the
    /// travel directions before and after.
    pub fn eval_cos(&self, cos_theta: f32) -> f32 {
        let hg = self.hg().eval_cos(cos_theta);
        if self.alpha == 0.0 {
            return hg;
        }
        hg * (1.0 + self.alpha * cos_theta * cos_theta) / self.norm()
    }

    /// The density of light travelling along unit `dir_in` leaving along unit `dir_out`
    /// (both world space, directions of travel); also [`Draine::sample`]'s pdf.
    pub fn eval(&self, dir_in: Vec3A, dir_out: Vec3A) -> f32 {
        self.eval_cos(dir_in.dot(dir_out))
    }

    /// The mean cosine of the scattering angle.
    pub fn mean_cosine(&self) -> f32 {
        let (g, a) = (self.g, self.alpha);
        g * (1.0 + a * (3.0 + 2.0 * g * g) / 5.0) / self.norm()
    }

    /// The probability that cos θ ≤ `mu` (in [−1, 1]), and its density in cos θ.
    fn cdf(&self, mu: f64) -> (f64, f64) {
        let (g, a) = (f64::from(self.g), f64::from(self.alpha));
        let norm = 1.0 + a * (1.0 + 2.0 * g * g) / 3.0;
        if g == 0.0 {
            let cdf = (0.5 * (mu + 1.0) + a * (mu * mu * mu + 1.0) / 6.0) / norm;
            return (cdf, 0.5 * (1.0 + a * mu * mu) / norm);
        }
        let b = 1.0 + g * g;
        let s = (b - 2.0 * g * mu).max(1e-300);
        let s0 = (1.0 + g) * (1.0 + g);
        // ∫ t² s^{−3/2} dt = k(s)/(8g³): d/dt k(s(t)) = 8g³ t² s^{−3/2}.
        let k = |s: f64| 2.0 * b * b / s.sqrt() + 4.0 * b * s.sqrt() - 2.0 / 3.0 * s * s.sqrt();
        let hg = (1.0 - g * g) / (2.0 * g) * (1.0 / s.sqrt() - 1.0 / (1.0 + g));
        let square = (1.0 - g * g) / (16.0 * g * g * g) * (k(s) - k(s0));
        let density = (1.0 - g * g) * (1.0 + a * mu * mu) / (2.0 * s * s.sqrt() * norm);
        ((hg + a * square) / norm, density)
    }

    /// cos θ of a scattering angle drawn from the phase function with `u` in [0, 1).
    pub fn sample_cos(&self, u: f32) -> f32 {
        if self.alpha == 0.0 {
            return self.hg().sample_cos(u);
        }
        let u = f64::from(u);
        // Newton's method on the CDF, kept inside a bracket that bisection shrinks.
        let (mut lo, mut hi) = (-1.0f64, 1.0f64);
        let mut mu = f64::from(self.hg().sample_cos(u as f32));
        for _ in 0..64 {
            let (f, density) = self.cdf(mu);
            let err = f - u;
            if err > 0.0 {
                hi = mu;
            } else {
                lo = mu;
            }
            if err.abs() < 1e-12 || hi - lo < 1e-12 {
                break;
            }
            let newton = mu - err / density;
            mu = if density > 0.0 && newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
        }
        (mu as f32).clamp(-1.0, 1.0)
    }

    /// A direction of travel after scattering light that travelled along unit `dir_in`
    /// (world space), and its density (per steradian), from `u` in [0, 1)².
    pub fn sample(&self, dir_in: Vec3A, u: Vec2) -> (Vec3A, f32) {
        if self.alpha == 0.0 {
            return self.hg().sample(dir_in, u);
        }
        let cos = self.sample_cos(u.x);
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * std::f32::consts::PI * u.y;
        let local = Vec3A::new(sin * phi.cos(), sin * phi.sin(), cos);
        let dir = Frame::from_normal(dir_in).to_world(local).normalize();
        (dir, self.eval_cos(dir.dot(dir_in)))
    }
}
