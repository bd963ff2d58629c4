//! Energy compensation of a rough dielectric lobe ([`crate::rough_glass`]; MDL's
//! `multiscatter_tint` on `scatter_reflect_transmit` and `scatter_transmit` lobes): what
//! the single-scattering glass loses to masking–shadowing, given back by a diffuse-like
//! lobe on both sides, in the manner of Kulla and Conty 2017 ("Revisiting Physically Based
//! Shading at Imageworks") for dielectrics.
//!
//! **Tables.** The glass lobe's directional albedo E(μ, α, η′) in n²-weighted radiance
//! (what refracts counted η′² times: the flux it carries) is tabulated once per
//! distribution and masking ([`Microfacet`]), for light arriving from the side of lower
//! index (η′ = η ≥ 1, entering) and from the other (η′ = 1/η, leaving): 32 points in μ =
//! cos θ ∈ [0, 1], 16 in α ∈ [0, 1] (α 0, smooth glass, loses nothing), 17 in η ∈ [1, 3]
//! (η past 3 read as 3), each entry the mean of 8192 quasi-random micro-normals, both
//! branches of each ([`RoughGlass`]'s own sampling), computed once and stored in the
//! repository (`glass_multiscatter/albedo.bin`, 16 bits an entry; `tables.rs`,
//! `generate.rs`); read trilinearly.
//! Each row's ℓ = 1 − E_avg = 1 − 2 ∫ E μ dμ is integrated from the row as interpolated,
//! so that the lobe below gives back exactly what the table says is lost.
//!
//! **The lobe.** With L(ω) = 1 − E(|μ|, α, η′ of ω's side) the loss from ω, and n(ω) the
//! index on ω's side (1 outside, η inside),
//!
//! f_ms(ωo, ωi) = c(side of ωo, side of ωi) L(ωo) L(ωi) / n(ωi)²,
//!
//! c symmetric: f_ms(ωo, ωi)/n(ωo)² = f_ms(ωi, ωo)/n(ωi)² (the generalised reciprocity of
//! refraction). Of what it gives back from outside a share t_out crosses, the glass's own
//! hemispherical transmittance 1 − F_avg(η); reciprocity then fixes the share from inside,
//! t_in = t_out ℓ_out / (η² ℓ_in) (where that would pass 1: t_in = 1, t_out = η² ℓ_in/ℓ_out),
//! and c_out,out = (1 − t_out)/(π ℓ_out), c_out,in = t_out/(π ℓ_in), c_in,in = η² (1 −
//! t_in)/(π ℓ_in): the lobe's n²-weighted albedo from ωo is exactly L(ωo) from either side,
//! so a white glass plus its compensation keeps all it receives. A `scatter_transmit`
//! lobe gets the crossing part alone (c_out,in), as it is the crossing half of the glass.
//!
//! A thin-walled sheet loses what its micro-mirrors do ([`crate::multiscatter`]'s tables of
//! the same distribution and masking); its compensation L(ωo) L(ωi)/(π ℓ) is split
//! between the two sides by the hemispherical reflectance F_avg(η): F_avg on ωo's side,
//! 1 − F_avg through (transmit-only: the latter alone).
//!
//! An anisotropic lobe is compensated as the isotropic one of α = √(αx αy); a film over
//! the glass is not seen by its compensation (plain Fresnel). Sampled by choosing the side
//! in proportion to the shares, then cosine-weighted on it. Local frame, z = the normal
//! (pointing outside).

use glam::{Vec2, Vec3A};

use crate::multiscatter::{self, Single};
use crate::rough_glass::{Halves, Microfacet, RoughGlass};

#[cfg(test)]
mod generate;
mod tables;

use tables::{fresnel_average_at, tables};

/// The compensation of a rough glass lobe (unit weight: the part's weight is the glass's
/// tint times `multiscatter_tint`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlassMultiScatter {
    /// The (isotropic) roughness the tables are read at.
    pub alpha: f32,
    /// Index of refraction inside over outside (the normal points outside).
    pub eta: f32,
    /// The glass's distribution and masking.
    pub micro: Microfacet,
    /// Which halves of the glass scatter: both (`scatter_reflect_transmit`), the crossing
    /// one alone (`scatter_transmit`: only the crossing part of the compensation) or the
    /// reflected one alone (a half `df::tint` split off: only the part that stays).
    pub halves: Halves,
    /// A thin-walled sheet (no inside).
    pub thin: bool,
}

/// The tabulated n²-weighted directional albedo of the unit-weight isotropic solid glass
/// lobe of `micro` (both halves), roughness `alpha` and relative index `etap` (across the
/// boundary from the side light arrives on) at incidence cosine `mu`.
pub fn glass_albedo(micro: Microfacet, alpha: f32, etap: f32, mu: f32) -> f32 {
    tables(micro).e(mu.abs(), alpha, etap)
}

/// The single-scattering micro-mirror model of a distribution and masking (a thin sheet's
/// loss).
fn single(micro: Microfacet) -> Single {
    match micro {
        Microfacet::Ggx => Single::GgxSmith,
        Microfacet::Beckmann => Single::BeckmannSmith,
        Microfacet::GgxVcavities => Single::GgxVcavities,
        Microfacet::BeckmannVcavities => Single::BeckmannVcavities,
    }
}

/// How the compensation of one direction ωo is shared: what stays on ωo's side and what
/// crosses (they sum to 1; transmit-only: nothing stays), with ℓ and n² of both sides.
struct Shares {
    stay: f32,
    cross: f32,
    lost_here: f32,
    lost_there: f32,
    n2_here: f32,
    n2_there: f32,
}

impl GlassMultiScatter {
    /// The compensation of a glass lobe of roughnesses `alpha_x`, `alpha_y` (read as
    /// isotropic √(αx αy), at most 1), index `eta`, `micro`, its mode and thinness.
    pub fn new(glass: &RoughGlass) -> GlassMultiScatter {
        GlassMultiScatter {
            alpha: (glass.alpha_x.max(0.0) * glass.alpha_y.max(0.0)).sqrt().min(1.0),
            eta: glass.eta,
            micro: glass.micro,
            halves: glass.halves,
            thin: glass.thin,
        }
    }

    /// The relative index across the boundary from `w`'s side.
    fn etap(&self, w: Vec3A) -> f32 {
        if w.z > 0.0 {
            self.eta
        } else {
            1.0 / self.eta
        }
    }

    /// 1 − E from direction `w`.
    fn loss(&self, w: Vec3A) -> f32 {
        let mu = w.z.abs();
        let e = if self.thin {
            multiscatter::directional_albedo(single(self.micro), self.alpha, mu)
        } else {
            tables(self.micro).e(mu, self.alpha, self.etap(w))
        };
        (1.0 - e).max(0.0)
    }

    /// The shares seen from ωo's side (`above`: outside), `None` where the glass loses
    /// (nearly) nothing or is no boundary.
    fn shares(&self, above: bool) -> Option<Shares> {
        if !self.eta.is_finite() || self.eta <= 0.0 || (!self.thin && (self.eta - 1.0).abs() < 1e-3) {
            return None;
        }
        if self.thin {
            let lost = 1.0 - multiscatter::average_albedo(single(self.micro), self.alpha);
            let f_avg = fresnel_average_at(self.eta);
            let (stay, cross) = self.halves_of(f_avg, 1.0 - f_avg);
            let (lost_here, lost_there, n2_here, n2_there) = (lost, lost, 1.0, 1.0);
            return (lost >= 1e-4).then_some(Shares { stay, cross, lost_here, lost_there, n2_here, n2_there });
        }
        let t = tables(self.micro);
        let (lost_out, lost_in) = (t.lost(self.alpha, self.eta), t.lost(self.alpha, 1.0 / self.eta));
        if lost_out < 1e-4 || lost_in < 1e-4 {
            return None;
        }
        let eta2 = self.eta * self.eta;
        let mut t_out = 1.0 - fresnel_average_at(self.eta);
        let mut t_in = t_out * lost_out / (eta2 * lost_in);
        if t_in > 1.0 {
            t_in = 1.0;
            t_out = eta2 * lost_in / lost_out;
        }
        let (t_here, here, there, n2_here, n2_there) =
            if above { (t_out, lost_out, lost_in, 1.0, eta2) } else { (t_in, lost_in, lost_out, eta2, 1.0) };
        let (stay, cross) = self.halves_of(1.0 - t_here, t_here);
        Some(Shares { stay, cross, lost_here: here, lost_there: there, n2_here, n2_there })
    }

    /// The shares `stay` and `cross` of the halves that scatter (the other one 0).
    fn halves_of(&self, stay: f32, cross: f32) -> (f32, f32) {
        match self.halves {
            Halves::Both => (stay, cross),
            Halves::Transmit => (0.0, cross),
            Halves::Reflect => (stay, 0.0),
        }
    }

    /// f_ms(ωo, ωi).
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z == 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        let Some(s) = self.shares(wo.z > 0.0) else { return 0.0 };
        // c L(ωo) L(ωi) / n(ωi)²: c is ωo's share for ωi's side times n(ωo)² over π ℓ
        // of ωi's side, so that ∫ f |cos θi| n(ωi)²/n(ωo)² dωi over that side = share ·
        // L(ωo); the shares make c symmetric (see the module's notes).
        let (share, lost, n2_i) =
            if wo.z * wi.z > 0.0 { (s.stay, s.lost_here, s.n2_here) } else { (s.cross, s.lost_there, s.n2_there) };
        share * s.n2_here * self.loss(wo) * self.loss(wi) / (std::f32::consts::PI * lost * n2_i)
    }

    /// The probability of choosing the side away from ωo: its share of what is given
    /// back from ωo (transmit-only: 1).
    fn cross_probability(&self, wo: Vec3A) -> f32 {
        match self.shares(wo.z > 0.0) {
            Some(s) if s.cross + s.stay > 0.0 => s.cross / (s.cross + s.stay),
            _ => 0.0,
        }
    }

    /// The density of [`GlassMultiScatter::sample`].
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z == 0.0 {
            return 0.0;
        }
        let cross = self.cross_probability(wo);
        let p = if wo.z * wi.z > 0.0 { 1.0 - cross } else { cross };
        p * wi.z.abs() * std::f32::consts::FRAC_1_PI
    }

    /// A direction: the side chosen with `u_choice` in proportion to the shares, then
    /// cosine-weighted on it.
    pub fn sample(&self, wo: Vec3A, u: Vec2, u_choice: f32) -> Option<Vec3A> {
        if wo.z == 0.0 || self.shares(wo.z > 0.0).is_none() {
            return None;
        }
        let wi = crate::cosine_on_side(wo, u)?;
        Some(if u_choice < self.cross_probability(wo) { Vec3A::new(wi.x, wi.y, -wi.z) } else { wi })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lobes::{Lobe, Lobes};
    use crate::rough_glass::test_glass::{glass, glass_energy, n_of};
    use crate::testing::{chi_square, incidences, r2};
    use crate::{Bsdf, Rgb};

    use tables::MICROS;

    /// The glass alone, or with its compensation.
    fn sum(g: RoughGlass, compensated: bool) -> Bsdf {
        let mut l = Lobes::default();
        assert!(l.push(Rgb::ONE, Lobe::Glass(g)));
        if compensated {
            assert!(l.push(Rgb::ONE, Lobe::GlassMultiScatter(GlassMultiScatter::new(&g))));
        }
        Bsdf::Lobes(l)
    }

    /// [`glass_energy`] of the first channel.
    fn energy(b: &Bsdf, g: &RoughGlass, wo: Vec3A, n: u32) -> f32 {
        glass_energy(b, g, wo, n).x
    }

    /// The tables are the glass's albedo: at grid points and between them (α 0.37, η 1.33),
    /// from outside (η′ = η) and inside (η′ = 1/η), the tabulated E matches the lone lobe's
    /// n²-weighted albedo by its own sampling (40 000 samples) within 0.01.
    #[test]
    fn the_tables_are_the_albedo() {
        for micro in [Microfacet::Ggx, Microfacet::BeckmannVcavities] {
            for (alpha, eta) in [(0.4, 1.5), (0.37, 1.33)] {
                let g = RoughGlass { eta, ..glass(alpha, micro, true, false) };
                for mu in [0.95f32, 0.6, 0.3] {
                    let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
                    for (w, etap) in [(wo, eta), (-wo, 1.0 / eta)] {
                        let got = glass_albedo(micro, alpha, etap, mu);
                        let want = energy(&sum(g, false), &g, w, 40_000);
                        assert!((got - want).abs() <= 0.01, "{micro:?} α {alpha} η′ {etap} μ {mu}: {got} vs {want}");
                    }
                }
            }
        }
    }

    /// The white furnace in n²-weighted radiance: rough glass plus its compensation keeps
    /// all it receives, 1 ± 2 % (20 000 samples) from outside and inside at 0°, 37° and 72°,
    /// at α 0.2, 0.5 and 1, for GGX and Beckmann with Smith's and V-cavity masking, solid
    /// and thin; without it, α 1 loses more than 3 % head-on from outside. Transmit-only
    /// glass with its (crossing) compensation scatters at most what it receives (≤ 1 + 1 %).
    #[test]
    fn compensated_glass_keeps_all_it_receives() {
        for micro in MICROS {
            for thin in [false, true] {
                for alpha in [0.2, 0.5, 1.0] {
                    let g = glass(alpha, micro, true, thin);
                    let b = sum(g, true);
                    for wo in incidences() {
                        for wo in [wo, -wo] {
                            let e = energy(&b, &g, wo, 20_000);
                            eprintln!("{micro:?} thin {thin} α {alpha} at {wo}: {e}");
                            assert!((e - 1.0).abs() <= 0.02, "{g:?} at {wo}: {e}");
                        }
                    }
                    let t = glass(alpha, micro, false, thin);
                    for wo in incidences() {
                        for wo in [wo, -wo] {
                            let e = energy(&sum(t, true), &t, wo, 20_000);
                            assert!(e <= 1.01, "{t:?} at {wo}: {e}");
                        }
                    }
                }
                let g = glass(1.0, micro, true, thin);
                let e = energy(&sum(g, false), &g, Vec3A::Z, 20_000);
                eprintln!("{micro:?} thin {thin} α 1 uncompensated head-on: {e}");
                assert!(e < 0.97, "{g:?} uncompensated: {e}");
            }
        }
    }

    /// The compensation is reciprocal in the generalised sense, f(ωo, ωi)/n(ωo)² =
    /// f(ωi, ωo)/n(ωi)² within 1e-4 (relative; 1e-6 absolute under 0.01), over 40 × 40
    /// pairs, solid and thin, both modes, α 0.5; glass plus compensation samples its
    /// density (χ² at 1 %, 200 000 samples) from outside at 37° and from inside, GGX and
    /// Beckmann V-cavities, solid and thin, both modes.
    #[test]
    fn the_compensation_is_reciprocal_and_sampled_by_its_density() {
        let sphere = |i: u32| {
            let u = r2(i);
            let z = 1.0 - 2.0 * u.x;
            let r = (1.0 - z * z).max(0.0).sqrt();
            Vec3A::new(r * (std::f32::consts::TAU * u.y).cos(), r * (std::f32::consts::TAU * u.y).sin(), z)
        };
        for thin in [false, true] {
            for reflect in [false, true] {
                for micro in [Microfacet::Ggx, Microfacet::BeckmannVcavities] {
                    let g = glass(0.5, micro, reflect, thin);
                    let m = GlassMultiScatter::new(&g);
                    for i in 0..40 {
                        for j in 0..40 {
                            let (a, b) = (sphere(i + 1), sphere(j + 201));
                            let f1 = m.eval(a, b) / n_of(&g, a).powi(2);
                            let f2 = m.eval(b, a) / n_of(&g, b).powi(2);
                            let scale = f1.max(f2).max(1e-2);
                            assert!((f1 - f2).abs() <= 1e-4 * scale, "{g:?}: f({a}, {b}) {f1} vs {f2}");
                        }
                    }
                    for wo in [Vec3A::new(0.562, 0.174, 0.808).normalize(), Vec3A::new(-0.3, 0.5, -0.81).normalize()] {
                        chi_square(&sum(g, true), wo);
                    }
                }
            }
        }
    }

    /// A `thin_film` over the glass is not seen by the compensation (it gives back plain
    /// Fresnel's loss, split by plain Fresnel's F_avg), yet glass under a film plus its
    /// compensation keeps what it receives within 1 ± 3 % (n²-weighted radiance, 20 000
    /// samples, from both sides at 0°, 37° and 72°, GGX α 0.5 and 1, film 400 nm of index
    /// (1.3, 1.4, 1.8) over glass of 1.5).
    #[test]
    fn a_film_over_compensated_glass_keeps_nearly_all() {
        use crate::layer_curve::{CurveKind, LayerCurve};
        let film = CurveKind::ThinFilm { ior: 1.5, film_ior: Rgb::new(1.3, 1.4, 1.8), thickness_nm: 400.0 };
        for alpha in [0.5, 1.0] {
            let mut l = Lobes::default();
            let k = l.add_curve(LayerCurve::new(film, Rgb::ONE, false)).unwrap();
            let g = RoughGlass { film: k + 1, ..glass(alpha, Microfacet::Ggx, true, false) };
            assert!(l.push(Rgb::ONE, Lobe::Glass(g)));
            assert!(l.push(Rgb::ONE, Lobe::GlassMultiScatter(GlassMultiScatter::new(&g))));
            let b = Bsdf::Lobes(l);
            for wo in incidences() {
                for wo in [wo, -wo] {
                    let e = glass_energy(&b, &g, wo, 20_000);
                    eprintln!("film α {alpha} at {wo}: {e}");
                    assert!((e - Rgb::ONE).abs().max_element() <= 0.03, "film α {alpha} at {wo}: {e}");
                }
            }
        }
    }
}
