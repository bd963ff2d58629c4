//! The unified material: a Disney-BSDF derivative (`../shared/seeds/unified-material-notes.md`)
//! with a decoupled metallic lobe and specular transmission.
//!
//! Seen from outside (the side the normal points to) the lobes and their weights are
//! - metal: `metallic` × GGX reflection with Schlick's Fresnel of `base_color`, or, when
//!   `edge_tint` is set, the exact conductor Fresnel of the complex index that Gulbrandsen's
//!   artist-friendly mapping (2014) gives for reflectivity `base_color` and that edge tint;
//! - dielectric specular: (1 − `metallic`) × a GGX dielectric of index `ior` with the exact
//!   Fresnel term F: reflection F (tinted by `specular_tint`), refraction (1 − F)·`spec_trans`
//!   tinted by `base_color`; the choice between them is sampled in proportion to F and
//!   (1 − F)·`spec_trans` on the sampled visible micro-normal, as the notes ask;
//! - diffuse: (1 − `metallic`)(1 − `spec_trans`) × the light the interface lets in. The notes'
//!   snippet writes `spec_trans` here, but by their own definition `spec_trans` is the share of
//!   refracted light that passes unscattered, so the scattered share, the diffuse, is
//!   1 − `spec_trans` (and the sweep "the object becomes more opaque as `spec_trans`
//!   decreases" says the same). The diffuse term is base/π·(1 − F(θo))(1 − F(θi))/(1 − F̄),
//!   F̄ the hemispherical average of F: reciprocal, and its albedo is exactly 1 − F(θo), the
//!   light a smooth interface transmits; plus Disney's sheen at grazing half angles;
//! - clearcoat: a second GGX reflection of index 1.5 with roughness from `clearcoat_gloss`,
//!   weighted by `clearcoat`; the base below sees (1 − `clearcoat`·F_cc(θo)) of the light
//!   (Disney adds the coat on top; mira attenuates so the sum stays ≤ 1).
//!
//! Inside a solid (non-thin) surface only the dielectric specular BSDF is evaluated, without
//! weights, as the notes argue: a ray refracted in was assumed not to scatter, so neither
//! the metal nor the diffuse lobe applies there. This breaks reciprocity for pairs with one
//! direction inside, which the notes accept. Thin surfaces have no inside: both sides see the
//! outside lobes, and the refraction passes straight through (the reflection mirrored
//! through the sheet).

use glam::{Vec2, Vec3A};

use super::dielectric::{fresnel, Dielectric};
use super::microfacet::Ggx;
use super::{cosine_hemisphere, BsdfSample};
use crate::color::luminance;
use crate::Rgb;

/// The unified material's parameters (all 0 to 1 unless stated), as artists set them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnifiedParams {
    /// Diffuse colour, metal reflectance at normal incidence, transmission tint.
    pub base_color: Rgb,
    /// Blend from dielectric (0) to metal (1).
    pub metallic: f32,
    /// Perceptual roughness; the GGX α is its square.
    pub roughness: f32,
    /// Anisotropy (Disney's: α along the tangent grows, across shrinks).
    pub anisotropic: f32,
    /// The share of refracted light that passes unscattered.
    pub spec_trans: f32,
    /// Index of refraction inside over outside (> 0).
    pub ior: f32,
    /// Weight of the dielectric reflection, 0 to 1 (F becomes `specular`·F; the diffuse
    /// takes what it leaves).
    pub specular: f32,
    /// Tints the dielectric reflection towards the base colour's hue.
    pub specular_tint: f32,
    /// Strength of the grazing sheen.
    pub sheen: f32,
    /// Tints the sheen towards the base colour's hue.
    pub sheen_tint: f32,
    /// Strength of the clear coat.
    pub clearcoat: f32,
    /// Glossiness of the clear coat (1: α = 0.001, 0: α = 0.1).
    pub clearcoat_gloss: f32,
    /// A thin sheet without an inside.
    pub thin: bool,
    /// Tint of the transmitted light (MDL materials have their own); `None`: the base
    /// colour, as in the Disney BSDF.
    pub transmission_color: Option<Rgb>,
    /// The metal's colour at grazing angles (Gulbrandsen's edge tint): with it the metal
    /// lobe uses a complex index of refraction instead of Schlick's approximation.
    pub edge_tint: Option<Rgb>,
}

impl Default for UnifiedParams {
    fn default() -> UnifiedParams {
        UnifiedParams {
            base_color: Rgb::splat(0.8),
            metallic: 0.0,
            roughness: 0.5,
            anisotropic: 0.0,
            spec_trans: 0.0,
            ior: 1.5,
            specular: 1.0,
            specular_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.5,
            clearcoat: 0.0,
            clearcoat_gloss: 1.0,
            thin: false,
            transmission_color: None,
            edge_tint: None,
        }
    }
}

/// The base colour's hue at unit maximum (white for black).
fn hue(c: Rgb) -> Rgb {
    let m = c.max_element();
    if m > 0.0 {
        c / m
    } else {
        Rgb::ONE
    }
}

/// The metal lobe's Fresnel term.
#[derive(Clone, Copy, Debug, PartialEq)]
enum MetalFresnel {
    /// Schlick's approximation with this reflectance at normal incidence.
    Schlick(Rgb),
    /// A conductor of complex index η + ik per channel.
    Conductor { eta: Rgb, k: Rgb },
}

impl MetalFresnel {
    fn at(&self, cos: f32) -> Rgb {
        match *self {
            MetalFresnel::Schlick(r0) => schlick(r0, cos),
            MetalFresnel::Conductor { eta, k } => super::conductor::fresnel_conductor_rgb(cos.abs(), eta, k),
        }
    }
}

/// Schlick's Fresnel for reflectance `r0` at normal incidence.
fn schlick(r0: Rgb, cos: f32) -> Rgb {
    let m = (1.0 - cos.abs()).clamp(0.0, 1.0);
    let m5 = m * m * m * m * m;
    r0 + (Rgb::ONE - r0) * m5
}

/// Hemispherical average of the dielectric Fresnel term, 2∫F(μ)μ dμ from outside.
fn fresnel_average(eta: f32) -> f32 {
    const N: usize = 32;
    (0..N)
        .map(|i| {
            let mu = (i as f32 + 0.5) / N as f32;
            2.0 * fresnel(mu, eta) * mu / N as f32
        })
        .sum()
}

fn reflect(w: Vec3A, n: Vec3A) -> Vec3A {
    -w + 2.0 * w.dot(n) * n
}

/// The unified material at one shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unified {
    params: UnifiedParams,
    /// The GGX distribution of the metal and dielectric lobes.
    ggx: Ggx,
    /// The clear coat's distribution.
    coat_ggx: Ggx,
    /// The dielectric lobe outside (weights and tints applied by `Unified`).
    dielectric: Dielectric,
    /// F̄ of `ior`.
    fresnel_avg: f32,
    /// The metal's Fresnel term.
    metal: MetalFresnel,
}

/// The largest albedo of the sheen term (1 − cos θd)⁵/π·(1 − F(θi))/(1 − F̄) over ωo, at
/// grazing (0.0281 without the Fresnel factor, by quadrature; see the test).
const SHEEN_ALBEDO_MAX: f32 = 0.032;

/// Lobe indices in the sampling mixture.
const METAL: usize = 0;
const SPECULAR: usize = 1;
const DIFFUSE: usize = 2;
const COAT: usize = 3;

impl Unified {
    /// The BSDF for `params` (clamped to their ranges).
    pub fn new(params: &UnifiedParams) -> Unified {
        let mut p = *params;
        p.base_color = p.base_color.clamp(Rgb::ZERO, Rgb::ONE);
        for v in [
            &mut p.metallic,
            &mut p.roughness,
            &mut p.anisotropic,
            &mut p.spec_trans,
            &mut p.clearcoat,
            &mut p.specular,
        ] {
            *v = v.clamp(0.0, 1.0);
        }
        p.ior = if p.ior.is_finite() && p.ior > 0.0 { p.ior } else { 1.5 };
        let alpha = p.roughness * p.roughness;
        let aspect = (1.0 - 0.9 * p.anisotropic).sqrt();
        let ggx = Ggx { alpha_x: alpha / aspect, alpha_y: alpha * aspect };
        let coat_alpha = 0.1 + (0.001 - 0.1) * p.clearcoat_gloss.clamp(0.0, 1.0);
        let spec_color = Rgb::ONE + (hue(p.base_color) - Rgb::ONE) * p.specular_tint.clamp(0.0, 1.0);
        let dielectric = Dielectric {
            eta: p.ior,
            ggx,
            reflect_tint: spec_color,
            transmit_tint: p.transmission_color.unwrap_or(p.base_color).clamp(Rgb::ZERO, Rgb::ONE),
            transmission: p.spec_trans,
            specular: p.specular,
        };
        let metal = match p.edge_tint {
            Some(tint) => {
                let (eta, k) = super::conductor::artist_to_ior(p.base_color, tint.clamp(Rgb::ZERO, Rgb::ONE));
                MetalFresnel::Conductor { eta, k }
            }
            None => MetalFresnel::Schlick(p.base_color),
        };
        Unified {
            params: p,
            ggx,
            coat_ggx: Ggx::isotropic(coat_alpha),
            dielectric,
            fresnel_avg: p.specular * fresnel_average(p.ior),
            metal,
        }
    }

    /// The parameters (clamped to their ranges).
    pub fn params(&self) -> &UnifiedParams {
        &self.params
    }

    /// The dielectric's weighted Fresnel reflectance at `cos` from outside.
    fn fresnel(&self, cos: f32) -> f32 {
        self.params.specular * fresnel(cos, self.params.ior)
    }

    /// Whether ωo sees the inside of a solid.
    fn inside(&self, wo: Vec3A) -> bool {
        wo.z < 0.0 && !self.params.thin
    }

    /// The glass seen from inside: the dielectric alone, unweighted and untinted.
    fn inner(&self) -> Dielectric {
        Dielectric::glass(self.params.ior, self.ggx)
    }

    /// Outside: the directions flipped to the side the lobes are defined on (thin sheets
    /// are the same from both sides).
    fn outward(wo: Vec3A, wi: Vec3A) -> (Vec3A, Vec3A) {
        if wo.z < 0.0 {
            (-wo, -wi)
        } else {
            (wo, wi)
        }
    }

    /// The clear coat's Fresnel at ωo's angle (what it takes from the layers below).
    fn coat_fresnel(&self, wo: Vec3A) -> f32 {
        self.params.clearcoat * fresnel(wo.z.abs(), 1.5)
    }

    /// Lobe weights (layer weights, without angular terms) seen from ωo outside, and the
    /// probabilities of sampling each.
    fn lobes(&self, wo: Vec3A) -> ([f32; 4], [f32; 4]) {
        let p = &self.params;
        let below = 1.0 - self.coat_fresnel(wo);
        let f = self.fresnel(wo.z);
        let dielectric = (1.0 - p.metallic) * below;
        let weights = [p.metallic * below, dielectric, dielectric * (1.0 - p.spec_trans), self.params.clearcoat];
        let energy = [
            weights[METAL] * luminance(self.metal.at(wo.z)).max(0.05),
            weights[SPECULAR] * (f + (1.0 - f) * p.spec_trans),
            weights[DIFFUSE] * (1.0 - f) * (luminance(p.base_color) + p.sheen * 0.1).max(0.05),
            self.coat_fresnel(wo),
        ];
        let sum: f32 = energy.iter().sum();
        let probs = if sum > 0.0 { energy.map(|e| e / sum) } else { [0.0; 4] };
        (weights, probs)
    }

    /// f of the diffuse lobe (with sheen), both directions outside: the light the interface
    /// lets in and out, T = (1 − F(θo))(1 − F(θi))/(1 − F̄), times the base colour's Lambert
    /// term and Disney's sheen. The sheen's albedo is at most `SHEEN_ALBEDO_MAX`·`sheen`
    /// (at grazing ωo), so the Lambert part gives up that much: the lobe's albedo stays at
    /// most 1 − F(θo).
    fn diffuse(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        let p = &self.params;
        let t = (1.0 - self.fresnel(wo.z)) * (1.0 - self.fresnel(wi.z)) / (1.0 - self.fresnel_avg)
            * std::f32::consts::FRAC_1_PI;
        if p.sheen <= 0.0 {
            return p.base_color * t;
        }
        let h = (wo + wi).normalize_or_zero();
        let m = (1.0 - wi.dot(h).clamp(0.0, 1.0)).powi(5);
        let sheen_color = Rgb::ONE + (hue(p.base_color) - Rgb::ONE) * p.sheen_tint.clamp(0.0, 1.0);
        (p.base_color * (1.0 - SHEEN_ALBEDO_MAX * p.sheen) + sheen_color * (p.sheen * m)) * t
    }

    /// f of a GGX reflection lobe without Fresnel (D·G/4cos cos), both outside.
    fn microfacet_reflection(ggx: &Ggx, wo: Vec3A, wi: Vec3A) -> (f32, Vec3A) {
        let h = (wo + wi).normalize_or_zero();
        if h == Vec3A::ZERO {
            return (0.0, h);
        }
        (ggx.d(h) * ggx.g2(wo, wi) / (4.0 * wo.z * wi.z), h)
    }

    /// f(ωo, ωi) of the non-delta lobes.
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z == 0.0 || wi.z == 0.0 {
            return Rgb::ZERO;
        }
        if self.inside(wo) {
            return self.inner().eval(wo, wi);
        }
        let (wo, wi) = Self::outward(wo, wi);
        let (w, _) = self.lobes(wo);
        let mut f = self.dielectric_eval(wo, wi) * w[SPECULAR];
        if wi.z > 0.0 {
            if w[METAL] > 0.0 && !self.ggx.is_smooth() {
                let (m, h) = Self::microfacet_reflection(&self.ggx, wo, wi);
                f += self.metal.at(wo.dot(h)) * (m * w[METAL]);
            }
            if w[DIFFUSE] > 0.0 {
                f += self.diffuse(wo, wi) * w[DIFFUSE];
            }
            if w[COAT] > 0.0 && !self.coat_ggx.is_smooth() {
                let (m, h) = Self::microfacet_reflection(&self.coat_ggx, wo, wi);
                f += Rgb::splat(m * fresnel(wo.dot(h), 1.5) * w[COAT]);
            }
        }
        f
    }

    /// f(ωo, ωi) of the reflection lobes alone — the dielectric's and the metal's
    /// highlights and the clear coat, without the diffuse lobe — for ωi on ωo's side
    /// outside (zero elsewhere): what a light that lights only the highlight gives (Maya's
    /// volume lights with `emitAmbient` and `emitSpecular`).
    pub fn eval_glossy(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z == 0.0 || wi.z == 0.0 || self.inside(wo) || (wo.z > 0.0) != (wi.z > 0.0) {
            return Rgb::ZERO;
        }
        let (wo, wi) = Self::outward(wo, wi);
        let (w, _) = self.lobes(wo);
        let mut f = self.dielectric_eval(wo, wi) * w[SPECULAR];
        if w[METAL] > 0.0 && !self.ggx.is_smooth() {
            let (m, h) = Self::microfacet_reflection(&self.ggx, wo, wi);
            f += self.metal.at(wo.dot(h)) * (m * w[METAL]);
        }
        if w[COAT] > 0.0 && !self.coat_ggx.is_smooth() {
            let (m, h) = Self::microfacet_reflection(&self.coat_ggx, wo, wi);
            f += Rgb::splat(m * fresnel(wo.dot(h), 1.5) * w[COAT]);
        }
        f
    }

    /// The dielectric lobe outside (thin sheets: refraction straight through).
    fn dielectric_eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if !self.params.thin || wi.z > 0.0 {
            return self.dielectric.eval(wo, wi);
        }
        // Thin: the transmitted lobe is the reflected one mirrored through the sheet,
        // weighted by (1 − F)·spec_trans instead of F.
        if self.ggx.is_smooth() {
            return Rgb::ZERO;
        }
        let wr = Vec3A::new(wi.x, wi.y, -wi.z);
        let (m, h) = Self::microfacet_reflection(&self.ggx, wo, wr);
        let f = self.fresnel(wo.dot(h));
        self.dielectric.transmit_tint * (m * (1.0 - f) * self.params.spec_trans)
    }

    fn dielectric_pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if !self.params.thin {
            return self.dielectric.pdf(wo, wi);
        }
        if self.ggx.is_smooth() {
            return 0.0;
        }
        let transmitted = wi.z < 0.0;
        let wr = if transmitted { Vec3A::new(wi.x, wi.y, -wi.z) } else { wi };
        let h = (wo + wr).normalize_or_zero();
        if h.z <= 0.0 {
            return 0.0;
        }
        let f = self.fresnel(wo.dot(h));
        let t = (1.0 - f) * self.params.spec_trans;
        let share = if transmitted { t } else { f } / (f + t).max(1e-12);
        self.ggx.d_visible(wo, h) / (4.0 * wo.dot(h)) * share
    }

    /// Density of sampling ωi (non-delta lobes).
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z == 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        if self.inside(wo) {
            return self.inner().pdf(wo, wi);
        }
        let (wo, wi) = Self::outward(wo, wi);
        let (_, prob) = self.lobes(wo);
        let mut pdf = prob[SPECULAR] * self.dielectric_pdf(wo, wi);
        if wi.z > 0.0 {
            if !self.ggx.is_smooth() {
                let h = (wo + wi).normalize_or_zero();
                pdf += prob[METAL] * self.ggx.d_visible(wo, h) / (4.0 * wo.dot(h)).max(1e-12);
            }
            pdf += prob[DIFFUSE] * wi.z * std::f32::consts::FRAC_1_PI;
            if !self.coat_ggx.is_smooth() {
                let h = (wo + wi).normalize_or_zero();
                pdf += prob[COAT] * self.coat_ggx.d_visible(wo, h) / (4.0 * wo.dot(h)).max(1e-12);
            }
        }
        pdf
    }

    /// Whether every lobe is a delta.
    pub fn is_delta(&self) -> bool {
        let p = &self.params;
        self.ggx.is_smooth() && (p.metallic >= 1.0 || p.spec_trans >= 1.0) && (p.clearcoat == 0.0)
    }

    /// Samples a lobe by its share of the energy, then a direction in it.
    pub fn sample(&self, wo: Vec3A, u: Vec2, u_lobe: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        if self.inside(wo) {
            return self.inner().sample(wo, u, u_lobe);
        }
        let flip = wo.z < 0.0;
        let unflip = |s: BsdfSample| if flip { BsdfSample { wi: -s.wi, ..s } } else { s };
        let wo = if flip { -wo } else { wo };
        let (w, prob) = self.lobes(wo);
        let mut acc = 0.0;
        let mut lobe = None;
        for (k, p) in prob.iter().enumerate() {
            if u_lobe < acc + p {
                lobe = Some((k, (u_lobe - acc) / p));
                break;
            }
            acc += p;
        }
        let (lobe, u_rest) = lobe?;
        let wi = match lobe {
            METAL | COAT => {
                let ggx = if lobe == METAL { &self.ggx } else { &self.coat_ggx };
                if ggx.is_smooth() {
                    let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
                    let f = if lobe == METAL {
                        self.metal.at(wo.z) * w[METAL]
                    } else {
                        Rgb::splat(fresnel(wo.z, 1.5) * w[COAT])
                    };
                    return Some(unflip(BsdfSample { wi, f: f / wi.z, pdf: prob[lobe], delta: true }));
                }
                let wi = reflect(wo, ggx.sample_visible(wo, u));
                if wi.z <= 0.0 {
                    return None;
                }
                wi
            }
            SPECULAR => {
                if self.ggx.is_smooth() {
                    let s = self.sample_smooth_dielectric(wo, u_rest)?;
                    return Some(unflip(BsdfSample { f: s.f * w[SPECULAR], pdf: s.pdf * prob[SPECULAR], ..s }));
                }
                if self.params.thin {
                    let h = self.ggx.sample_visible(wo, u);
                    let f = self.fresnel(wo.dot(h));
                    let t = (1.0 - f) * self.params.spec_trans;
                    let r = reflect(wo, h);
                    if r.z <= 0.0 {
                        return None;
                    }
                    if u_rest * (f + t) < f {
                        r
                    } else {
                        Vec3A::new(r.x, r.y, -r.z)
                    }
                } else {
                    self.dielectric.sample(wo, u, u_rest)?.wi
                }
            }
            _ => cosine_hemisphere(u),
        };
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| unflip(BsdfSample { wi, f: self.eval(wo, wi), pdf, delta: false }))
    }

    /// The smooth dielectric's Dirac lobes outside (thin: straight through), unweighted.
    fn sample_smooth_dielectric(&self, wo: Vec3A, u_choice: f32) -> Option<BsdfSample> {
        if !self.params.thin {
            return self.dielectric.sample(wo, Vec2::ZERO, u_choice);
        }
        let f = self.fresnel(wo.z);
        let t = (1.0 - f) * self.params.spec_trans;
        if f + t <= 0.0 {
            return None;
        }
        let spec = self.dielectric.reflect_tint;
        if u_choice * (f + t) < f {
            let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
            Some(BsdfSample { wi, f: spec * (f / wi.z), pdf: f / (f + t), delta: true })
        } else {
            Some(BsdfSample { wi: -wo, f: self.dielectric.transmit_tint * (t / wo.z), pdf: t / (f + t), delta: true })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{albedo, chi_square, r3};
    use crate::Bsdf;

    fn unified(f: impl FnOnce(&mut UnifiedParams)) -> Bsdf {
        let mut p = UnifiedParams { base_color: Rgb::ONE, ..UnifiedParams::default() };
        f(&mut p);
        Bsdf::Unified(Unified::new(&p))
    }

    fn directions() -> Vec<Vec3A> {
        (0..10)
            .map(|i| {
                let t = (i as f32 + 0.5) / 10.0 * 1.55;
                Vec3A::new(t.sin() * 0.8, t.sin() * 0.6, t.cos())
            })
            .collect()
    }

    /// The diffuse term's albedo is exactly 1 − F(θo) (its normalisation by F̄).
    #[test]
    fn diffuse_fills_what_the_interface_transmits() {
        let b = Unified::new(&UnifiedParams { base_color: Rgb::ONE, ..UnifiedParams::default() });
        for wo in directions() {
            let n = 256;
            let mut sum = 0.0;
            for i in 0..n {
                for j in 0..n {
                    let wi = cosine_hemisphere(Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32));
                    sum += b.diffuse(wo, wi).x * std::f32::consts::PI;
                }
            }
            let a = sum / (n * n) as f32;
            let want = 1.0 - fresnel(wo.z, 1.5);
            assert!((a - want).abs() < 2e-3, "θo {}: {a} vs {want}", wo.z.acos());
        }
    }

    /// The reflection lobes alone: the whole BSDF less its diffuse lobe, the same for any
    /// base colour of a dielectric, nothing towards the other side.
    #[test]
    fn glossy_lobes_alone_leave_out_the_diffuse_lobe() {
        let params =
            |base_color| UnifiedParams { base_color, roughness: 0.4, specular: 0.7, ..UnifiedParams::default() };
        let coloured = Unified::new(&params(Rgb::new(0.8, 0.5, 0.2)));
        let black = Unified::new(&params(Rgb::ZERO));
        for wo in directions() {
            for wi in directions() {
                let wi = Vec3A::new(-wi.y, wi.x, wi.z);
                let (g, whole) = (coloured.eval_glossy(wo, wi), black.eval(wo, wi));
                assert!((g - whole).abs().max_element() <= 1e-6 * whole.max_element().max(1.0), "{g} vs {whole}");
                // What is left is the diffuse lobe: positive, and coloured.
                let rest = coloured.eval(wo, wi) - g;
                assert!(g.max_element() > 0.0 && rest.min_element() > 0.0 && rest.x > rest.z, "{rest}");
                assert_eq!(coloured.eval_glossy(wo, -wi), Rgb::ZERO);
            }
        }
    }

    /// The sheen's albedo bound holds at every angle.
    #[test]
    fn sheen_albedo_is_bounded() {
        let b = Unified::new(&UnifiedParams { base_color: Rgb::ZERO, sheen: 1.0, ..UnifiedParams::default() });
        let mut worst: f32 = 0.0;
        for k in 0..=20 {
            let t = k as f32 / 20.0 * 1.5705;
            let wo = Vec3A::new(t.sin(), 0.0, t.cos());
            let n = 200;
            let mut sum = 0.0;
            for i in 0..n {
                for j in 0..n {
                    let wi = cosine_hemisphere(Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32));
                    sum += b.diffuse(wo, wi).x * std::f32::consts::PI / (1.0 - fresnel(wo.z, 1.5)).max(1e-6);
                }
            }
            worst = worst.max(sum / (n * n) as f32);
        }
        assert!(worst <= SHEEN_ALBEDO_MAX && worst > 0.8 * SHEEN_ALBEDO_MAX, "{worst}");
    }

    /// White furnace over a grid of parameters, from outside at every angle: the albedo
    /// never exceeds 1 (Monte Carlo error < 1%) and stays close to 1 where the model is
    /// nearly lossless.
    #[test]
    fn white_furnace_never_gains_energy() {
        for metallic in [0.0, 0.5, 1.0] {
            for roughness in [0.0, 0.2, 0.5, 1.0] {
                for spec_trans in [0.0, 0.5, 1.0] {
                    for clearcoat in [0.0, 1.0] {
                        let b = unified(|p| {
                            p.metallic = metallic;
                            p.roughness = roughness;
                            p.spec_trans = spec_trans;
                            p.clearcoat = clearcoat;
                            p.sheen = 0.5;
                            p.specular_tint = 0.5;
                        });
                        for wo in directions() {
                            let a = albedo(&b, wo, 8_000);
                            assert!(
                                a.max_element() <= 1.01,
                                "metallic {metallic} roughness {roughness} spec_trans {spec_trans} clearcoat {clearcoat} θo {}: {a}",
                                wo.z.acos()
                            );
                        }
                    }
                }
            }
        }
    }

    /// Where the model is lossless, nothing is lost: a smooth dielectric with `spec_trans`
    /// 1 (glass) reflects and transmits all the energy, n²-weighted (radiance entering is
    /// compressed by 1/η²).
    #[test]
    fn smooth_glass_is_lossless() {
        let b = unified(|p| {
            p.roughness = 0.0;
            p.spec_trans = 1.0;
        });
        for wo in directions() {
            let mut energy = 0.0;
            let n = 4000;
            for i in 0..n {
                let (u, u_lobe) = r3(i);
                if let Some(s) = b.sample(wo, u, u_lobe) {
                    let scale = if s.wi.z < 0.0 { 1.5f32 * 1.5 } else { 1.0 };
                    energy += s.weight().x * scale;
                }
            }
            let e = energy / n as f32;
            assert!((e - 1.0).abs() < 1e-3, "θo {}: {e}", wo.z.acos());
        }
        // Smooth white metal reflects everything.
        let m = unified(|p| {
            p.roughness = 0.0;
            p.metallic = 1.0;
        });
        let s = m.sample(Vec3A::new(0.6, 0.0, 0.8), Vec2::ZERO, 0.5).unwrap();
        assert!(s.delta && (s.weight() - Rgb::ONE).abs().max_element() < 1e-6);
    }

    /// With an edge tint the metal's Fresnel is a conductor's: at normal incidence it
    /// reflects `base_color` (Gulbrandsen's mapping is exact there), at grazing the edge
    /// tint's side of the curve; and it still samples its density and conserves energy.
    #[test]
    fn complex_ior_metal() {
        let gold = Rgb::new(0.97, 0.80, 0.32);
        let b = unified(|p| {
            p.base_color = gold;
            p.metallic = 1.0;
            p.roughness = 0.0;
            p.edge_tint = Some(Rgb::new(1.0, 0.95, 0.6));
        });
        let s = b.sample(Vec3A::Z, Vec2::ZERO, 0.5).unwrap();
        assert!(s.delta && (s.weight() - gold).abs().max_element() < 1e-4, "{}", s.weight());
        let rough = unified(|p| {
            p.base_color = gold;
            p.metallic = 1.0;
            p.roughness = 0.4;
            p.edge_tint = Some(Rgb::new(1.0, 0.95, 0.6));
        });
        chi_square(&rough, Vec3A::new(0.3, 0.2, 0.93).normalize());
        for wo in directions() {
            assert!(albedo(&rough, wo, 8_000).max_element() <= 1.01);
        }
    }

    /// The behaviours the notes' sweeps show (`scenes/unified_sweeps.mi`): rough refraction
    /// darkens as roughness grows (single-scattering microfacets lose energy, visibly so
    /// through glass), and `spec_trans` blends diffuse into glass linearly — the energy
    /// scattered at `spec_trans` t is the straight line between t = 0 and t = 1.
    #[test]
    fn sweeps_behave_as_the_notes_describe() {
        let n2_energy = |b: &Bsdf, wo: Vec3A| {
            let n = 20_000;
            let mut e = 0.0;
            for i in 0..n {
                let (u, u_lobe) = r3(i);
                if let Some(s) = b.sample(wo, u, u_lobe) {
                    e += s.weight().x * if s.wi.z < 0.0 { 2.25 } else { 1.0 };
                }
            }
            e / n as f32
        };
        let wo = Vec3A::new(0.5, 0.0, 0.866);
        let energies: Vec<f32> = [0.01, 0.3, 0.5, 0.7, 1.0]
            .iter()
            .map(|&r| {
                n2_energy(
                    &unified(|p| {
                        p.roughness = r;
                        p.spec_trans = 1.0;
                    }),
                    wo,
                )
            })
            .collect();
        for k in 1..energies.len() {
            assert!(energies[k] < energies[k - 1] - 1e-4, "not darker with roughness: {energies:?}");
        }
        assert!(energies[0] > 0.999 && energies[4] < 0.95, "{energies:?}");
        let at = |t: f32| {
            albedo(
                &unified(|p| {
                    p.roughness = 0.1;
                    p.spec_trans = t;
                    p.base_color = Rgb::new(0.9, 0.6, 0.3);
                }),
                wo,
                40_000,
            )
        };
        let (a0, a1) = (at(0.0), at(1.0));
        for t in [0.3, 0.5, 0.7] {
            let line = a0 + (a1 - a0) * t;
            let got = at(t);
            assert!((got - line).abs().max_element() < 0.01, "spec_trans {t}: {got} vs {line}");
        }
    }

    /// Sampling matches the density for each lobe alone and for mixtures, at normal and
    /// grazing angles, from outside and (solid glass) from inside.
    #[test]
    fn sampling_matches_the_density() {
        let configs: Vec<Bsdf> = vec![
            unified(|p| p.metallic = 1.0),
            unified(|p| p.spec_trans = 1.0),
            unified(|p| p.roughness = 0.3),
            unified(|p| {
                p.metallic = 0.3;
                p.spec_trans = 0.5;
                p.roughness = 0.4;
                p.anisotropic = 0.6;
                p.sheen = 1.0;
                p.clearcoat = 1.0;
                p.clearcoat_gloss = 0.3;
            }),
            unified(|p| {
                p.thin = true;
                p.spec_trans = 0.7;
                p.roughness = 0.45;
            }),
        ];
        for b in &configs {
            for wo in [Vec3A::new(0.3, 0.2, 0.93).normalize(), Vec3A::new(-0.9, 0.2, 0.2).normalize()] {
                chi_square(b, wo);
                chi_square(b, -wo);
            }
        }
    }
}
