//! A conductor (metal): Fresnel reflection with a complex index of refraction η + ik per
//! channel, smooth (a Dirac mirror lobe) or rough (GGX microfacets with height-correlated
//! masking, micro-normals sampled from the visible normals).
//!
//! The Fresnel term is the exact unpolarised reflectance of a planar interface between a
//! vacuum-like outside (index 1) and the metal, evaluated from the complex Fresnel equations.
//! Artists' parameters map onto η and k by Gulbrandsen 2014, "Artist Friendly Metallic
//! Fresnel" (JCGT 3(4)): a reflectivity at normal incidence and an edge tint that bends the
//! curve towards grazing angles ([`artist_to_ior`], [`Conductor::from_artist`]).
//!
//! Metals scatter on the side ωo is on (mira shades both sides of a surface, as its other
//! reflection lobes do); light never reaches the other side.

use glam::{Vec2, Vec3A};

use super::microfacet::Ggx;
use super::BsdfSample;
use crate::Rgb;

/// Largest reflectivity the artist mapping accepts: at 1, n and k diverge.
pub const MAX_REFLECTIVITY: f32 = 1.0 - 1e-4;

/// A complex number in f64, just enough for the Fresnel equations.
#[derive(Clone, Copy, Debug)]
struct C64 {
    re: f64,
    im: f64,
}

impl C64 {
    fn new(re: f64, im: f64) -> C64 {
        C64 { re, im }
    }
    fn add(self, o: C64) -> C64 {
        C64::new(self.re + o.re, self.im + o.im)
    }
    fn sub(self, o: C64) -> C64 {
        C64::new(self.re - o.re, self.im - o.im)
    }
    fn mul(self, o: C64) -> C64 {
        C64::new(self.re * o.re - self.im * o.im, self.re * o.im + self.im * o.re)
    }
    fn scale(self, s: f64) -> C64 {
        C64::new(self.re * s, self.im * s)
    }
    fn norm2(self) -> f64 {
        self.re * self.re + self.im * self.im
    }
    /// Principal square root (non-negative real part).
    fn sqrt(self) -> C64 {
        let m = self.norm2().sqrt();
        let re = (0.5 * (m + self.re)).max(0.0).sqrt();
        let im = (0.5 * (m - self.re)).max(0.0).sqrt();
        C64::new(re, if self.im < 0.0 { -im } else { im })
    }
}

/// |a/b|², 1 where both vanish (the grazing limit of a reflection coefficient).
fn ratio2(a: C64, b: C64) -> f64 {
    let d = b.norm2();
    if d == 0.0 {
        1.0
    } else {
        a.norm2() / d
    }
}

/// Unpolarised Fresnel reflectance (0 to 1) of a conductor with complex relative index
/// `eta` + i`k` (metal over outside), for the cosine `cos_i` between the incident
/// direction and the normal (its absolute value is used).
///
/// From the complex Fresnel equations: with w = √(η̃² − sin²θ) (η̃ = η + ik, principal
/// root, so that the refracted wave decays into the metal), r_s = (cos θ − w)/(cos θ + w)
/// and r_p = (η̃² cos θ − w)/(η̃² cos θ + w); the result is (|r_s|² + |r_p|²)/2.
pub fn fresnel_conductor(cos_i: f32, eta: f32, k: f32) -> f32 {
    let c = f64::from(cos_i.abs().min(1.0));
    let s2 = 1.0 - c * c;
    let n = C64::new(f64::from(eta), f64::from(k));
    let n2 = n.mul(n);
    let w = n2.sub(C64::new(s2, 0.0)).sqrt();
    let cc = C64::new(c, 0.0);
    let rs = ratio2(cc.sub(w), cc.add(w));
    let n2c = n2.scale(c);
    let rp = ratio2(n2c.sub(w), n2c.add(w));
    (0.5 * (rs + rp)).clamp(0.0, 1.0) as f32
}

/// [`fresnel_conductor`] per RGB channel.
pub fn fresnel_conductor_rgb(cos_i: f32, eta: Rgb, k: Rgb) -> Rgb {
    Rgb::new(
        fresnel_conductor(cos_i, eta.x, k.x),
        fresnel_conductor(cos_i, eta.y, k.y),
        fresnel_conductor(cos_i, eta.z, k.z),
    )
}

/// Gulbrandsen's bounds on n for reflectivity r: n_min = (1 − r)/(1 + r) (edge tint 1)
/// and n_max = (1 + √r)/(1 − √r) (edge tint 0, the dielectric with that reflectivity).
fn n_bounds(r: f64) -> (f64, f64) {
    let sr = r.sqrt();
    ((1.0 - r) / (1.0 + r), (1.0 + sr) / (1.0 - sr))
}

/// One channel of [`artist_to_ior`], in f64.
fn artist_to_ior_1(r: f32, g: f32) -> (f32, f32) {
    let r = f64::from(r.clamp(0.0, MAX_REFLECTIVITY));
    let g = f64::from(g.clamp(0.0, 1.0));
    let (n_min, n_max) = n_bounds(r);
    let n = g * n_min + (1.0 - g) * n_max;
    // Solve F(0) = ((n − 1)² + k²)/((n + 1)² + k²) = r for k.
    let k2 = (r * (n + 1.0) * (n + 1.0) - (n - 1.0) * (n - 1.0)) / (1.0 - r);
    (n as f32, k2.max(0.0).sqrt() as f32)
}

/// Gulbrandsen 2014: the complex index (η, k) per channel whose reflectance at normal
/// incidence is `reflectivity` (0 to 1, clamped to [`MAX_REFLECTIVITY`]) and whose curve
/// towards grazing angles is bent by `edge_tint` (0 to 1; at 0 the curve is a dielectric's,
/// at 1 it stays near the reflectivity longest). Returns (η, k).
pub fn artist_to_ior(reflectivity: Rgb, edge_tint: Rgb) -> (Rgb, Rgb) {
    let (a, b, c) = (
        artist_to_ior_1(reflectivity.x, edge_tint.x),
        artist_to_ior_1(reflectivity.y, edge_tint.y),
        artist_to_ior_1(reflectivity.z, edge_tint.z),
    );
    (Rgb::new(a.0, b.0, c.0), Rgb::new(a.1, b.1, c.1))
}

/// One channel of [`ior_to_artist`], in f64.
fn ior_to_artist_1(eta: f32, k: f32) -> (f32, f32) {
    let (n, k) = (f64::from(eta), f64::from(k));
    let r = ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
    let (n_min, n_max) = n_bounds(r);
    let g = if n_max > n_min { (n_max - n) / (n_max - n_min) } else { 0.0 };
    (r as f32, g as f32)
}

/// The inverse of [`artist_to_ior`]: (reflectivity, edge tint) of a complex index (η, k)
/// per channel. The edge tint falls outside 0 to 1 for indices outside Gulbrandsen's range.
pub fn ior_to_artist(eta: Rgb, k: Rgb) -> (Rgb, Rgb) {
    let (a, b, c) = (ior_to_artist_1(eta.x, k.x), ior_to_artist_1(eta.y, k.y), ior_to_artist_1(eta.z, k.z));
    (Rgb::new(a.0, b.0, c.0), Rgb::new(a.1, b.1, c.1))
}

fn reflect(w: Vec3A, n: Vec3A) -> Vec3A {
    -w + 2.0 * w.dot(n) * n
}

/// A metal surface: GGX micro-mirrors with the conductor Fresnel term.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor {
    /// Micro-normal distribution (a single mirror when [`Ggx::is_smooth`]).
    pub ggx: Ggx,
    /// Real part of the complex index of refraction per channel (metal over outside).
    pub eta: Rgb,
    /// Extinction coefficient (imaginary part of the index) per channel.
    pub k: Rgb,
}

impl Conductor {
    /// A conductor from Gulbrandsen's artist parameters: reflectivity at normal incidence
    /// and edge tint, both per channel, 0 to 1 (see [`artist_to_ior`]).
    pub fn from_artist(reflectivity: Rgb, edge_tint: Rgb, ggx: Ggx) -> Conductor {
        let (eta, k) = artist_to_ior(reflectivity, edge_tint);
        Conductor { ggx, eta, k }
    }

    /// Fresnel reflectance per channel for the cosine between a direction and the
    /// (micro-)normal.
    pub fn fresnel(&self, cos_i: f32) -> Rgb {
        fresnel_conductor_rgb(cos_i, self.eta, self.k)
    }

    /// f(ωo, ωi) = F(ωo·h) D(h) G2(ωo, ωi) / (4 |cos θo cos θi|) for ωo and ωi on the same
    /// side (zero for a smooth conductor, whose lobe is a Dirac delta).
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if self.ggx.is_smooth() || wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        // Mirror both into the upper hemisphere (D and Λ are even in x, y).
        let side = wo.z.signum();
        let (wo, wi) = (wo * side, wi * side);
        let h = wo + wi;
        if h.length_squared() == 0.0 {
            return Rgb::ZERO;
        }
        let h = h.normalize();
        let d = self.ggx.d(h);
        let g = self.ggx.g2(wo, wi);
        self.fresnel(wo.dot(h)) * (d * g / (4.0 * wo.z * wi.z))
    }

    /// Samples ωi: a visible micro-normal seen from ωo, then the mirror direction about
    /// it. A reflection that leaves through the surface (off a steep micro-normal) ends the
    /// path: `None`.
    pub fn sample(&self, wo: Vec3A, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        if self.ggx.is_smooth() {
            let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
            let f = self.fresnel(wo.z) / wi.z.abs();
            return Some(BsdfSample { wi, f, pdf: 1.0, delta: true });
        }
        let side = wo.z.signum();
        let h = self.ggx.sample_visible(wo * side, u) * side;
        let wi = reflect(wo, h);
        if wi.z * wo.z <= 0.0 {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample { wi, f: self.eval(wo, wi), pdf, delta: false })
    }

    /// Density per solid angle of sampling ωi: Dv(h) / (4 |ωo·h|).
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if self.ggx.is_smooth() || wo.z * wi.z <= 0.0 {
            return 0.0;
        }
        let side = wo.z.signum();
        let (wo, wi) = (wo * side, wi * side);
        let h = wo + wi;
        if h.length_squared() == 0.0 {
            return 0.0;
        }
        let h = h.normalize();
        let cos_oh = wo.dot(h);
        if cos_oh <= 0.0 {
            return 0.0;
        }
        self.ggx.d_visible(wo, h) / (4.0 * cos_oh)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;
    use crate::Bsdf;

    /// Gold at the sRGB primaries (the usual RGB reduction of its measured spectrum).
    const GOLD_ETA: Rgb = Rgb::new(0.143_119, 0.374_957, 1.442_48);
    const GOLD_K: Rgb = Rgb::new(3.983_16, 2.385_72, 1.603_22);
    /// Aluminium, likewise.
    const AL_ETA: Rgb = Rgb::new(1.657_46, 0.880_369, 0.521_229);
    const AL_K: Rgb = Rgb::new(9.223_87, 6.269_52, 4.837);

    /// The closed real form of the conductor reflectance (Born & Wolf's a², b²), written
    /// out independently of the complex evaluation, in f64.
    fn fresnel_real_form(c: f64, n: f64, k: f64) -> f64 {
        let s2 = 1.0 - c * c;
        let t = n * n - k * k - s2;
        let a2b2 = (t * t + 4.0 * n * n * k * k).sqrt();
        let a = (0.5 * (a2b2 + t)).max(0.0).sqrt();
        let rs = (a2b2 - 2.0 * a * c + c * c) / (a2b2 + 2.0 * a * c + c * c);
        let rp = rs * (a2b2 * c * c - 2.0 * a * c * s2 + s2 * s2) / (a2b2 * c * c + 2.0 * a * c * s2 + s2 * s2);
        0.5 * (rs + rp)
    }

    #[test]
    fn fresnel_matches_the_real_form_the_dielectric_and_the_limits() {
        for (n, k) in [(0.143, 3.98), (1.44, 1.6), (1.66, 9.22), (0.2, 0.1), (2.5, 0.0), (1.0, 0.5), (40.0, 3.0)] {
            for i in 0..=40 {
                let c = i as f32 / 40.0;
                let want = fresnel_real_form(f64::from(c), f64::from(n), f64::from(k));
                let got = fresnel_conductor(c, n, k);
                assert!((f64::from(got) - want).abs() < 2e-6, "n {n} k {k} cos {c}: {got} vs {want}");
            }
            // Normal incidence: ((n − 1)² + k²)/((n + 1)² + k²); grazing: 1.
            let f0 = ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
            assert!((fresnel_conductor(1.0, n, k) - f0).abs() < 1e-6);
            assert!((fresnel_conductor(0.0, n, k) - 1.0).abs() < 1e-6);
        }
        // k = 0 is a dielectric (seen from the thin side).
        for i in 0..=20 {
            let c = i as f32 / 20.0;
            let d = crate::dielectric::fresnel(c, 1.5);
            assert!((fresnel_conductor(c, 1.5, 0.0) - d).abs() < 1e-6, "cos {c}");
        }
    }

    #[test]
    fn artist_mapping_round_trips_and_gives_plausible_metals() {
        for r in [0.0f32, 0.02, 0.1, 0.3, 0.5, 0.8, 0.95, 0.99, 0.999] {
            for g in [0.0f32, 0.1, 0.5, 0.9, 1.0] {
                let (n, k) = artist_to_ior(Rgb::splat(r), Rgb::splat(g));
                assert!(n.x > 0.0 && k.x >= 0.0 && n.x.is_finite() && k.x.is_finite(), "r {r} g {g}: {n} {k}");
                let f0 = fresnel_conductor(1.0, n.x, k.x);
                assert!((f0 - r).abs() < 1e-5, "r {r} g {g}: F(0) = {f0}");
                // Edge tint 0 is the dielectric of that reflectivity: no absorption.
                if g == 0.0 {
                    assert!(k.x < 1e-2 * n.x.max(1.0), "r {r}: k {}", k.x);
                }
                // And back.
                let (r2, g2) = ior_to_artist(n, k);
                assert!((r2.x - r).abs() < 1e-5, "r {r} g {g}: back {r2}");
                if r > 0.0 && r < 0.999 {
                    assert!((g2.x - g).abs() < 1e-3, "r {r} g {g}: back {g2}");
                }
            }
        }
        // Edge tint raises the reflectance at intermediate angles (curve bends later).
        let (n0, k0) = artist_to_ior(Rgb::splat(0.5), Rgb::splat(0.0));
        let (n1, k1) = artist_to_ior(Rgb::splat(0.5), Rgb::splat(1.0));
        let c = 60f32.to_radians().cos();
        assert!(fresnel_conductor(c, n1.x, k1.x) > fresnel_conductor(c, n0.x, k0.x));
        // Gold: reflective in red, much less in blue, edge tint near 1 in red and green.
        let (r, g) = ior_to_artist(GOLD_ETA, GOLD_K);
        assert!(r.x > 0.9 && r.y > 0.7 && r.y < 0.85 && r.z > 0.25 && r.z < 0.4, "gold r {r}");
        assert!(g.max_element() <= 1.0 && g.min_element() > 0.0, "gold g {g}");
        let gold = Conductor::from_artist(r, g, Ggx::isotropic(0.0));
        assert!((gold.eta - GOLD_ETA).abs().max_element() < 1e-3 && (gold.k - GOLD_K).abs().max_element() < 1e-3);
        // Aluminium: grey and bright.
        let (r, _) = ior_to_artist(AL_ETA, AL_K);
        assert!(r.min_element() > 0.85 && r.max_element() < 0.95, "aluminium r {r}");
    }

    fn metals() -> Vec<Conductor> {
        let mut v = Vec::new();
        for ggx in [
            Ggx::isotropic(0.05),
            Ggx::isotropic(0.3),
            Ggx::isotropic(0.7),
            Ggx { alpha_x: 0.1, alpha_y: 0.45 },
            Ggx { alpha_x: 0.6, alpha_y: 0.08 },
        ] {
            v.push(Conductor { ggx, eta: GOLD_ETA, k: GOLD_K });
            v.push(Conductor { ggx, eta: AL_ETA, k: AL_K });
        }
        v
    }

    /// A chi-square test of sampled directions against `pdf` for narrow lobes at grazing
    /// angles, where [`testing::chi_square`]'s quadrature is too coarse: cells of equal
    /// width in cos θ (10) and φ (20) on ωo's side, expected counts by a fine midpoint rule
    /// (uniform in cos θ and φ, i.e. in solid angle), cells expecting fewer than 5 pooled.
    fn chi_square_fine(c: &Conductor, wo: Vec3A) {
        const MU: usize = 10;
        const PHI: usize = 20;
        const SUB: usize = 320;
        const SAMPLES: u32 = 200_000;
        let side = wo.z.signum();
        let cell = |w: Vec3A| {
            let mu = ((w.z * side).clamp(0.0, 1.0) * MU as f32).min(MU as f32 - 1.0) as usize;
            let phi = w.y.atan2(w.x).rem_euclid(std::f32::consts::TAU);
            mu * PHI + ((phi / std::f32::consts::TAU * PHI as f32) as usize).min(PHI - 1)
        };
        let mut observed = vec![0f64; MU * PHI];
        for i in 0..SAMPLES {
            let u = testing::r2(i * 2 + 1);
            // Decorrelate from the R2 lattice's structure with a Cranley–Patterson shift.
            let u = (u + Vec2::new(0.137, 0.731)).fract();
            if let Some(s) = c.sample(wo, u) {
                observed[cell(s.wi)] += 1.0;
            }
        }
        let mut expected = vec![0f64; MU * PHI];
        let d_area = (1.0 / (MU * SUB) as f64) * (std::f64::consts::TAU / (PHI * SUB) as f64);
        for i in 0..MU * SUB {
            let mu = (i as f64 + 0.5) / (MU * SUB) as f64;
            let r = (1.0 - mu * mu).sqrt();
            for j in 0..PHI * SUB {
                let phi = (j as f64 + 0.5) / (PHI * SUB) as f64 * std::f64::consts::TAU;
                let wi = Vec3A::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, (mu * f64::from(side)) as f32);
                expected[(i / SUB) * PHI + j / SUB] += f64::from(c.pdf(wo, wi)) * d_area * f64::from(SAMPLES);
            }
        }
        let p = testing::pooled_chi_square(&observed, &expected);
        let (chi2, limit) = (p.chi2, testing::chi_square_limit_99(p.dof));
        assert!(chi2 < limit, "{:?} wo {wo}: chi-square {chi2:.1} over the 99% limit {limit:.1}", c.ggx);
    }

    /// Sampling matches the density, at several roughnesses, isotropic and anisotropic,
    /// from both sides, at grazing ωo too (there with a finer quadrature: the lobes of the
    /// smoother surfaces are a few degrees wide in φ).
    #[test]
    fn sampling_matches_the_density() {
        for ggx in [
            Ggx::isotropic(0.08),
            Ggx::isotropic(0.3),
            Ggx::isotropic(0.75),
            Ggx { alpha_x: 0.1, alpha_y: 0.5 },
            Ggx { alpha_x: 0.7, alpha_y: 0.2 },
        ] {
            let c = Conductor { ggx, eta: GOLD_ETA, k: GOLD_K };
            let b = Bsdf::Conductor(c);
            for wo in [Vec3A::new(0.3, 0.1, 0.95).normalize(), Vec3A::new(-0.5, 0.6, 0.62).normalize()] {
                testing::chi_square(&b, wo);
            }
            testing::chi_square(&b, Vec3A::new(0.4, 0.2, -0.89).normalize());
            for wo in [
                Vec3A::new(0.99, 0.05, 0.12).normalize(),
                Vec3A::new(0.1, -0.998, 0.03).normalize(),
                Vec3A::new(-0.6, 0.78, -0.08).normalize(),
            ] {
                chi_square_fine(&c, wo);
            }
        }
    }

    #[test]
    fn reciprocal() {
        for c in metals() {
            testing::reciprocity(&Bsdf::Conductor(c), 2e-4);
        }
    }

    /// The cosine-weighted hemispherical average of a reflectance: 2 ∫ R(μ) μ dμ.
    fn hemispherical_average(r: impl Fn(f32) -> Rgb) -> Rgb {
        let n = 2000;
        (0..n).map(|i| (i as f32 + 0.5) / n as f32).map(|mu| r(mu) * (2.0 * mu / n as f32)).sum()
    }

    /// White furnace: no channel reflects more than it receives, from any direction; a
    /// conductor whose Fresnel term is 1 loses only what single scattering loses to masking;
    /// averaged over incident directions, a rough metal reflects no more than a smooth one
    /// of the same metal (the Fresnel average).
    #[test]
    fn energy() {
        // k = 1e4: F ≈ 1 at every angle. What single scattering loses (reflections off
        // micro-normals steeper than the bisector of ωo and the horizon, masking) is
        // large for rough surfaces: the estimate must match ∫ f cos by quadrature.
        for ggx in [Ggx::isotropic(0.02), Ggx::isotropic(0.1), Ggx::isotropic(0.4), Ggx { alpha_x: 0.1, alpha_y: 0.6 }]
        {
            let c = Conductor { ggx, eta: Rgb::ONE, k: Rgb::splat(1e4) };
            let white = Bsdf::Conductor(c);
            for i in 0..6 {
                let t = (i as f32 + 0.5) / 6.0 * 1.5;
                let wo = Vec3A::new(t.sin(), 0.0, t.cos());
                let a = testing::albedo(&white, wo, 20_000).x;
                let n = if ggx.alpha_x == 0.02 { 0 } else { 600 };
                let mut q = 0.0f64;
                for i in 0..n {
                    let mu = (i as f32 + 0.5) / n as f32;
                    let r = (1.0 - mu * mu).sqrt();
                    for j in 0..n {
                        let phi = std::f32::consts::TAU * (j as f32 + 0.5) / n as f32;
                        q += f64::from(c.eval(wo, Vec3A::new(r * phi.cos(), r * phi.sin(), mu)).x * mu);
                    }
                }
                let q = (q * std::f64::consts::TAU / f64::from((n * n).max(1))) as f32;
                assert!(a <= 1.0 + 1e-3, "{ggx:?} at {wo}: {a}");
                if ggx.alpha_x == 0.02 {
                    // Too narrow for the quadrature; nearly a mirror.
                    assert!(a > 0.99, "{ggx:?} at {wo}: {a}");
                } else {
                    assert!((a - q).abs() < 5e-3, "{ggx:?} at {wo}: {a} vs {q} by quadrature");
                }
            }
        }
        for c in metals() {
            let b = Bsdf::Conductor(c);
            let bound = hemispherical_average(|mu| c.fresnel(mu));
            let avg = hemispherical_average(|mu| {
                let wo = Vec3A::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
                testing::albedo(&b, wo, 512)
            });
            assert!(avg.cmple(bound + 2e-3).all(), "{c:?}: average albedo {avg} over the Fresnel average {bound}");
            for i in 0..8 {
                let t = (i as f32 + 0.5) / 8.0 * 1.55;
                let wo = Vec3A::new(t.sin() * 0.6, t.sin() * 0.8, t.cos());
                let a = testing::albedo(&b, wo, 20_000);
                assert!(a.max_element() <= 1.0 + 2e-3, "{c:?} at {wo}: {a}");
            }
        }
    }

    /// A smooth metal reflects in the mirror direction with weight F(cos θo), per channel,
    /// and is a delta lobe (no eval, no pdf).
    #[test]
    fn smooth_conductor_weight_is_the_fresnel_reflectance() {
        let c = Conductor { ggx: Ggx::isotropic(0.0), eta: GOLD_ETA, k: GOLD_K };
        let b = Bsdf::Conductor(c);
        assert!(b.is_delta());
        for i in 0..16 {
            let t = (i as f32 + 0.5) / 16.0 * 1.57;
            for side in [1.0, -1.0] {
                let wo = Vec3A::new(t.sin() * 0.8, -t.sin() * 0.6, side * t.cos());
                let s = b.sample(wo, Vec2::new(0.3, 0.7), 0.5).unwrap();
                assert!(s.delta && (s.wi - Vec3A::new(-wo.x, -wo.y, wo.z)).length() < 1e-6);
                let want = fresnel_conductor_rgb(t.cos(), GOLD_ETA, GOLD_K);
                let w = s.weight();
                assert!((w - want).abs().max_element() <= 1e-6 * want.max_element(), "{w} vs {want}");
                assert_eq!(b.eval(wo, s.wi), Rgb::ZERO);
                assert_eq!(b.pdf(wo, s.wi), 0.0);
            }
        }
    }

    /// Values by hand at one configuration: normal incidence and the mirror direction.
    #[test]
    fn eval_at_the_peak() {
        let alpha = 0.3f32;
        let c = Conductor { ggx: Ggx::isotropic(alpha), eta: AL_ETA, k: AL_K };
        let f = c.eval(Vec3A::Z, Vec3A::Z);
        // D(z) = 1/(π α²), G2 = 1, F = F0, cosines 1.
        let want = c.fresnel(1.0) / (4.0 * std::f32::consts::PI * alpha * alpha);
        assert!((f - want).abs().max_element() < 1e-5 * want.max_element(), "{f} vs {want}");
        assert!((c.pdf(Vec3A::Z, Vec3A::Z) - 1.0 / (4.0 * std::f32::consts::PI * alpha * alpha)).abs() < 1e-4);
        // Below the surface and across sides: nothing.
        assert_eq!(c.eval(Vec3A::Z, -Vec3A::Z), Rgb::ZERO);
        assert_eq!(c.pdf(Vec3A::Z, Vec3A::new(0.6, 0.0, -0.8)), 0.0);
    }
}
