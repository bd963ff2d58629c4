//! Maya's highlights (blinn, phong, phongE, anisotropic, rampShader's) as mental ray for Maya computes
//! them, and the BSDF that gives the path engine exactly the same highlight.
//!
//! The formulas are functions of the unit shading normal `n`, the unit direction `v`
//! towards the viewer and the unit direction `l` towards the light (one space). Each
//! returns the factor that multiplies `specularColor ⊙ light`: no 1/π and no N·L beyond
//! the formula's own (Maya's convention). The classic Maya materials (`maya::specular`)
//! call them; [`MayaBsdf`] turns them into a scattering function.
//!
//! **Why a lobe of Maya's own shape.** Maya's highlights are not energy-normalised lobes:
//! blinn's is D·G·F/(N·V) with D = 1 at the peak, phong's (R·L)^n, phongE's (N·H)^p.
//! A classic light of colour C adds s ⊙ C · H(v, l); the path engine's lights deliver
//! π·C of irradiance per unit cos θ, so the BRDF that gives the same radiance is
//! f(v, l) = s · H(v, l) / (π · N·L). A GGX lobe scaled to the same albedo would match
//! the total but not the shape (Maya's blinn is GGX's distribution times 4α²·Fresnel,
//! but with Torrance–Sparrow's masking, Schlick's Fresnel on V·H with `specularRollOff`
//! as its normal value and the 1/(N·V) of the formula; phong's lobe is about the mirror
//! direction, not the half vector); evaluating Maya's formula itself makes every pixel
//! of a directly lit highlight equal the classic engine's, by construction. Sampling
//! uses a density shaped like each lobe (GGX visible normals for blinn, a cosine power
//! about the mirror direction for phong, about the normal for phongE's half vector,
//! Gaussian slopes for anisotropic), so indirect and area light converge.
//!
//! **Energy.** These lobes are not reciprocal and not bounded by construction: a wide
//! blinn (eccentricity 0.8, `specularColor` 1) reflects up to 1.9× the light it receives
//! at grazing views. The path engine needs albedo ≤ 1 per lobe to keep paths bounded, so
//! [`MayaGlossy`] tabulates the unit lobe's directional albedo a(μ) over the view cosine
//! μ and scales the highlight at each view by min(1, 1/(a(μ)·max s)) — the highlight
//! is Maya's exactly wherever it reflects no more than it receives (every default and
//! common setting: blinn's default reflects 0.11–0.14, phong's 0.05–0.10). The diffuse
//! part is the material's own Lambertian c·d beside it, as the classic shader adds them.
//!
//! **Reflections.** The classic materials also trace a mirror reflection weighted by
//! `reflectivity` · `specularColor` (times blinn's Schlick factor of `specularRollOff` at
//! N·V with `reflectionRolloff`); [`MayaBsdf`] carries it as a smooth mirror lobe of that
//! weight (each channel at most 1), so reflected objects, lights and the environment
//! reach the path engine as they reach the classic one; what that weight also multiplies
//! in the classic shader (`reflectedColor`, rampShader's environment ramp) the BSDF
//! emits by the weight seen from each view ([`MayaBsdf::emitted`]), and past
//! `reflectionLimit` mirror reflections the path engine drops the mirror
//! ([`MayaBsdf::without_mirror`]). With `refractions` on, T ⊙ the ray bent by Snell's
//! law (no Fresnel) is a delta refraction of weight T ([`MayaGlossy::refraction`],
//! [`MayaBsdf::refract_at`]). rampShader's ramps that follow the view are tabulated
//! ([`ViewRamps`], [`MayaGlossy::specular_ramp`]).
//!
//! **Transparency.** The classic materials fade only their diffuse part by
//! `transparency`; the highlight and the reflection stay whole. The path engine lets a
//! share 1 − c of the rays through a surface of coverage c, so [`MayaGlossy`] divides
//! both by c ([`MayaGlossy::with_coverage`]): over all rays they are Maya's exactly.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3A};

use crate::{cosine_on_side, luminance, BsdfSample, Frame, Rgb};

mod shape;
pub mod translucence;

pub use shape::{anisotropic, blinn, blinn_distribution, phong, phong_e, ramp_blinn, schlick, Shape};

/// The smallest view cosine the albedo table holds (grazing views take its value).
const ALBEDO_MIN_COS: f32 = 0.02;

/// How many view cosines the albedo table holds, evenly spaced over [0, 1].
const ALBEDO_STEPS: usize = 9;

/// How many facing ratios (or reflection heights) [`ViewRamps`] holds, evenly spaced
/// over [0, 1].
pub const VIEW_RAMP_STEPS: usize = 33;

/// How many highlight strengths a tabulated `specularColor` ramp holds
/// ([`MayaGlossy::specular_ramp`]), evenly spaced over [0, 1].
pub const SPECULAR_RAMP_STEPS: usize = 9;

/// rampShader's ramps that follow the view, tabulated (linear between the points: a
/// ramp whose points lie on the table's and interpolate linearly is exact):
/// `specularRollOff` and `reflectivity` by the facing ratio N·V, `environment` by the
/// world reflection direction's height (1 + R_y)/2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewRamps {
    /// `specularRollOff` at N·V = k/32: multiplies the highlight's tint.
    pub rolloff: [f32; VIEW_RAMP_STEPS],
    /// `reflectivity` at N·V = k/32: the mirror's weight (its tint ⊙ this).
    pub reflectivity: [f32; VIEW_RAMP_STEPS],
    /// `environment` at (1 + R_y)/2 = k/32: emitted by the mirror's weight.
    pub environment: [Rgb; VIEW_RAMP_STEPS],
}

/// A table of values at evenly spaced points over [0, 1], linearly interpolated at `x`
/// (clamped).
pub fn table_at<T>(table: &[T], x: f32) -> T
where
    T: Copy + std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>,
{
    let last = table.len() - 1;
    let x = x.clamp(0.0, 1.0) * last as f32;
    let k = (x as usize).min(last - 1);
    let t = x - k as f32;
    table[k] * (1.0 - t) + table[k + 1] * t
}

impl ViewRamps {
    /// The ramps tabulated from functions of the facing ratio (`rolloff`,
    /// `reflectivity`) and of the reflection's height (`environment`).
    pub fn tabulate(
        rolloff: impl Fn(f32) -> f32,
        reflectivity: impl Fn(f32) -> f32,
        environment: impl Fn(f32) -> Rgb,
    ) -> ViewRamps {
        let at = |k: usize| k as f32 / (VIEW_RAMP_STEPS - 1) as f32;
        ViewRamps {
            rolloff: std::array::from_fn(|k| rolloff(at(k)).max(0.0)),
            reflectivity: std::array::from_fn(|k| reflectivity(at(k)).max(0.0)),
            environment: std::array::from_fn(|k| environment(at(k)).max(Rgb::ZERO)),
        }
    }
}

/// A Maya highlight of a material: its shape, its tint (`specularColor`, ⊙ `whiteness`
/// for phongE), its mirror reflection and its unit lobe's directional albedo over the
/// view cosine, which bounds it (see the module doc). Built once per material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MayaGlossy {
    /// The highlight.
    pub shape: Shape,
    /// Its tint (linear RGB; Maya's highlight multiplies the light by it).
    pub tint: Rgb,
    /// The mirror reflection's weight, `reflectivity` · `specularColor` (linear RGB).
    pub mirror: Rgb,
    /// Blinn's `reflectionRolloff`: the mirror weight is scaled by Schlick's factor of
    /// this normal reflectance (`specularRollOff`) at N·V.
    pub mirror_rolloff: Option<f32>,
    /// The share of rays that hit the surface (its coverage, 1 − mean `transparency`;
    /// 1 for an opaque one): the highlight and the mirror are divided by it, so that a
    /// transparent Maya material, which the path engine covers stochastically, shows
    /// them at full strength on average, as the classic shader adds them unfaded.
    pub coverage: f32,
    /// What the mirror's weight multiplies besides what the mirror ray finds, emitted
    /// towards the viewer (linear RGB): blinn's, phong's … `reflectedColor` (the classic
    /// r · s ⊙ (reflectedColor + traced)), so that it follows the view as the mirror's
    /// weight does (blinn's roll-off) and a per-hit `specularColor`.
    pub reflected: Rgb,
    /// The most reflections (mirror, and the glossy ones the classic engine traces as
    /// reflection rays) a path may have made before this surface for its mirror to
    /// reflect (Maya's `reflectionLimit`: the classic shader traces its
    /// reflection while the ray's reflection level is below it); `u32::MAX`: no limit.
    pub reflection_limit: u32,
    /// The raytraced refraction's weight, `transparency` T per channel (Maya's
    /// `refractions` on; zero otherwise): what lies behind, seen along the ray bent by
    /// Snell's law with [`MayaGlossy::ior`], adds T ⊙ it, without Fresnel, as the classic
    /// shader adds T ⊙ its refraction ray (a mirror ray of the same weight under total
    /// internal reflection).
    pub refraction: Rgb,
    /// `refractiveIndex`: the index inside the surface (1 outside).
    pub ior: f32,
    /// `refractionLimit`: the most refractions (and transparency passes) a path may have
    /// made before this surface for it to bend the ray; past it the ray passes straight,
    /// as the classic shader then traces a transparency ray.
    pub refraction_limit: u32,
    /// The factor a per-hit `specularColor` multiplied the tint by ([`MayaGlossy::tinted`];
    /// 1 for a constant one), per channel.
    pub tinted_by: Rgb,
    /// rampShader's view-dependent ramps, when they vary: the highlight's tint is then
    /// multiplied by the roll-off at N·V, the mirror's weight by the reflectivity, and the
    /// mirror emits the environment ramp instead of `reflected`.
    pub view_ramps: Option<ViewRamps>,
    /// rampShader's `specularColor` ramp by the highlight's strength H ∈ [0, 1] at
    /// H = k/8, when it varies: the highlight is then tint ⊙ S(H) · H.
    pub specular_ramp: Option<[Rgb; SPECULAR_RAMP_STEPS]>,
    /// The lambert family's `translucence`: the albedo c · t of the light it passes from
    /// behind (linear RGB, faded and divided by the coverage as the diffuse colour is),
    /// concentrated about the light's straight-through direction by the cosine power
    /// [`MayaGlossy::focus`] ([`translucence`]); zero: none.
    pub translucence: Rgb,
    /// The forward lobe's exponent n ([`translucence::focus_exponent`] of
    /// `translucenceFocus`; 0: diffuse translucence).
    pub focus: f32,
    /// When the material's colour varies over the surface (a connected `color`): the
    /// translucence's albedo per unit of each hit's diffuse colour (t / `diffuse`), which
    /// then replaces [`MayaGlossy::translucence`] at every hit; `None`: constant.
    pub translucence_per_diffuse: Option<f32>,
    /// rampShader's light-angle translucence: the share g (per channel, in [0, 1]) of
    /// [`MayaGlossy::translucence`] that follows the light's angle
    /// ([`translucence::light_angle_factor`]); zero: none (the lambert family's).
    pub translucence_grazing: Rgb,
    /// The unit lobe's albedo at view cosines 0, 1/8, … 1 (the first at
    /// [`ALBEDO_MIN_COS`]).
    albedo: [f32; ALBEDO_STEPS],
}

impl MayaGlossy {
    /// The highlight `shape` tinted by `tint`, its albedo tabulated.
    pub fn new(shape: Shape, tint: Rgb) -> MayaGlossy {
        let step = 1.0 / (ALBEDO_STEPS - 1) as f32;
        let albedo = std::array::from_fn(|k| shape.albedo(k as f32 * step));
        MayaGlossy {
            shape,
            tint: tint.max(Rgb::ZERO),
            mirror: Rgb::ZERO,
            mirror_rolloff: None,
            coverage: 1.0,
            reflected: Rgb::ZERO,
            reflection_limit: u32::MAX,
            refraction: Rgb::ZERO,
            ior: 1.0,
            refraction_limit: u32::MAX,
            tinted_by: Rgb::ONE,
            view_ramps: None,
            specular_ramp: None,
            translucence: Rgb::ZERO,
            focus: 0.0,
            translucence_per_diffuse: None,
            translucence_grazing: Rgb::ZERO,
            albedo,
        }
    }

    /// The same highlight with the translucence of albedo `albedo` (per channel) and
    /// forward-lobe exponent `focus` (see [`MayaGlossy::translucence`]).
    pub fn with_translucence(mut self, albedo: Rgb, focus: f32) -> MayaGlossy {
        self.translucence = albedo.max(Rgb::ZERO);
        self.focus = focus.max(0.0);
        self
    }

    /// The same with the share `g` of the translucence that follows the light's angle
    /// (see [`MayaGlossy::translucence_grazing`]; clamped to [0, 1]).
    pub fn with_translucence_grazing(mut self, g: Rgb) -> MayaGlossy {
        self.translucence_grazing = g.clamp(Rgb::ZERO, Rgb::ONE);
        self
    }

    /// The same with the translucence following each hit's diffuse colour: its albedo is
    /// `k` × that colour (see [`MayaGlossy::translucence_per_diffuse`]).
    pub fn with_translucence_per_diffuse(mut self, k: f32) -> MayaGlossy {
        self.translucence_per_diffuse = Some(k.max(0.0));
        self
    }

    /// The same with the translucence scaled by `k` (≥ 0): its albedo, and its share of
    /// each hit's diffuse colour where it follows it (a connected `translucence` at one
    /// hit).
    pub fn translucence_scaled(mut self, k: f32) -> MayaGlossy {
        let k = k.max(0.0);
        self.translucence *= k;
        self.translucence_per_diffuse = self.translucence_per_diffuse.map(|r| r * k);
        self
    }

    /// The same highlight and mirror with rampShader's view-dependent ramps (see
    /// [`MayaGlossy::view_ramps`]).
    pub fn with_view_ramps(mut self, ramps: ViewRamps) -> MayaGlossy {
        self.view_ramps = Some(ramps);
        self
    }

    /// The same highlight coloured by a `specularColor` ramp over its strength (see
    /// [`MayaGlossy::specular_ramp`]; `ramp` gives the colour at a strength in [0, 1]).
    pub fn with_specular_ramp(mut self, ramp: impl Fn(f32) -> Rgb) -> MayaGlossy {
        self.specular_ramp =
            Some(std::array::from_fn(|k| ramp(k as f32 / (SPECULAR_RAMP_STEPS - 1) as f32).max(Rgb::ZERO)));
        self
    }

    /// The same highlight and mirror with `reflected` emitted by the mirror's weight (see
    /// [`MayaGlossy::reflected`]).
    pub fn with_reflected(mut self, reflected: Rgb) -> MayaGlossy {
        self.reflected = reflected.max(Rgb::ZERO);
        self
    }

    /// The same highlight with its mirror limited to paths of fewer than `limit` mirror
    /// reflections (see [`MayaGlossy::reflection_limit`]).
    pub fn with_reflection_limit(mut self, limit: u32) -> MayaGlossy {
        self.reflection_limit = limit;
        self
    }

    /// The same highlight with Maya's raytraced refraction of weight `t` (per channel,
    /// 0..1), index `ior` and `refractionLimit` `limit` (see [`MayaGlossy::refraction`]).
    pub fn with_refraction(mut self, t: Rgb, ior: f32, limit: u32) -> MayaGlossy {
        self.refraction = t.clamp(Rgb::ZERO, Rgb::ONE);
        self.ior = ior;
        self.refraction_limit = limit;
        self
    }

    /// The same highlight with a mirror reflection of weight `mirror` (each channel
    /// clamped to 0..1 where the BSDF is made), scaled by Schlick's factor of `rolloff`
    /// at N·V when given.
    pub fn with_mirror(mut self, mirror: Rgb, rolloff: Option<f32>) -> MayaGlossy {
        self.mirror = mirror.max(Rgb::ZERO);
        self.mirror_rolloff = rolloff;
        self
    }

    /// The same highlight and mirror on a surface hit by the share `coverage` (0..1] of
    /// the rays that reach it (see [`MayaGlossy::coverage`]).
    pub fn with_coverage(mut self, coverage: f32) -> MayaGlossy {
        self.coverage = coverage.clamp(1e-3, 1.0);
        self
    }

    /// The same highlight and mirror with their tint multiplied by `k` per channel (a
    /// connected `specularColor` at one hit, relative to the colour the material was
    /// built with).
    pub fn tinted(mut self, k: Rgb) -> MayaGlossy {
        let k = k.max(Rgb::ZERO);
        self.tint *= k;
        self.mirror *= k;
        self.tinted_by *= k;
        self
    }

    /// The same highlight, reflection and translucence with their weights scaled by `k`
    /// per channel (a layer's share).
    pub fn scaled(mut self, k: Rgb) -> MayaGlossy {
        self.tint *= k.max(Rgb::ZERO);
        self.mirror *= k.max(Rgb::ZERO);
        self.translucence *= k.max(Rgb::ZERO);
        // A layer's colour is its constant one (the layered shader warns when it varies).
        self.translucence_per_diffuse = None;
        self
    }

    /// The unit lobe's directional albedo at the view cosine `mu` (the table, linearly
    /// interpolated).
    pub fn unit_albedo(&self, mu: f32) -> f32 {
        let x = mu.abs().clamp(0.0, 1.0) * (ALBEDO_STEPS - 1) as f32;
        let k = (x as usize).min(ALBEDO_STEPS - 2);
        let t = x - k as f32;
        self.albedo[k] * (1.0 - t) + self.albedo[k + 1] * t
    }

    /// The BSDF seen from `wo` (local frame) with the Lambertian `diffuse` albedo beside
    /// the highlight, which is scaled down where it would reflect more than 1; the
    /// environment ramp (if any) taken with the local frame as the world's.
    pub fn bsdf(&self, diffuse: Rgb, wo: Vec3A) -> MayaBsdf {
        self.bsdf_seen(diffuse, wo, None)
    }

    /// [`MayaGlossy::bsdf`] with the world's local frame `frame` (world space), where
    /// the environment ramp is indexed by the world reflection direction's height.
    pub fn bsdf_seen(&self, diffuse: Rgb, wo: Vec3A, frame: Option<&Frame>) -> MayaBsdf {
        let a = self.unit_albedo(wo.z);
        let facing = wo.z.abs();
        // The highlight's tint at this view, and the largest colour of its ramp.
        let (tint, mirror_weight, reflected) = match &self.view_ramps {
            Some(r) => {
                let local = Vec3A::new(-wo.x, -wo.y, wo.z.abs());
                let height = frame.map_or(local.z, |f| f.to_world(local).y);
                (
                    self.tint * table_at(&r.rolloff, facing),
                    self.mirror * table_at(&r.reflectivity, facing),
                    table_at(&r.environment, 0.5 * (1.0 + height)),
                )
            }
            None => (self.tint, self.mirror, self.reflected),
        };
        let colour = self.specular_ramp.map_or(Rgb::ONE, |s| s.iter().fold(Rgb::ZERO, |m, c| m.max(*c)));
        let most = (tint * colour).max_element() * a;
        let tint = if most > 1.0 { tint / most } else { tint };
        let rolloff = self.mirror_rolloff.map_or(1.0, |r0| schlick(r0, facing));
        let mirror = mirror_weight.min(Rgb::ONE) * rolloff;
        let (tint, mirror) = (tint / self.coverage, mirror / self.coverage);
        let emitted =
            if reflected == Rgb::ZERO { Rgb::ZERO } else { reflected * mirror_weight * (rolloff / self.coverage) };
        // The highlight's share by its colour's mean.
        let mean = self.specular_ramp.map_or(Rgb::ONE, |s| s.iter().fold(Rgb::ZERO, |m, c| m + *c) / s.len() as f32);
        let (d, g, m) = (luminance(diffuse).max(0.0), luminance(tint * mean) * a, luminance(mirror).max(0.0));
        let t = luminance(self.refraction).max(0.0);
        let translucence = self.translucence_per_diffuse.map_or(self.translucence, |k| diffuse.max(Rgb::ZERO) * k);
        let tl = luminance(translucence).max(0.0);
        let total = d + g + m + t + tl;
        let (diffuse_share, mirror_share, refraction_share, translucence_share) =
            if total > 0.0 { (d / total, m / total, t / total, tl / total) } else { (1.0, 0.0, 0.0, 0.0) };
        MayaBsdf {
            diffuse,
            tint,
            mirror,
            shape: self.shape,
            emitted,
            reflection_limit: self.reflection_limit,
            refraction: self.refraction,
            eta: self.ior,
            refraction_limit: self.refraction_limit,
            tinted_by: self.tinted_by,
            specular_ramp: self.specular_ramp,
            translucence,
            focus: self.focus,
            translucence_grazing: self.translucence_grazing,
            diffuse_share,
            mirror_share,
            refraction_share,
            translucence_share,
        }
    }
}

/// A Maya material at one shading point: Lambertian reflection of `diffuse` plus the
/// highlight f = tint · H(v, l)/(π·N·L) plus a smooth mirror of reflectance `mirror`
/// (see the module doc). Both sides of the surface scatter alike (the classic shaders
/// turn the normal towards the viewer).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MayaBsdf {
    /// The diffuse albedo (Maya's `color` · `diffuse`).
    pub diffuse: Rgb,
    /// The highlight's tint (already bounded).
    pub tint: Rgb,
    /// The mirror reflection's reflectance (a delta lobe: not in `eval` or `pdf`).
    pub mirror: Rgb,
    /// The highlight.
    pub shape: Shape,
    /// Radiance the surface sends towards the viewer besides what it scatters: the
    /// mirror's weight (unbounded, seen from this view) ⊙ [`MayaGlossy::reflected`].
    pub emitted: Rgb,
    /// [`MayaGlossy::reflection_limit`].
    pub reflection_limit: u32,
    /// The refraction's weight ([`MayaGlossy::refraction`]; a delta lobe).
    pub refraction: Rgb,
    /// The relative index n_behind / n_front the refracted ray crosses: `refractiveIndex`
    /// as built (entering), set per hit by [`MayaBsdf::refract_at`]; 1 passes straight.
    pub eta: f32,
    /// [`MayaGlossy::refraction_limit`].
    pub refraction_limit: u32,
    /// [`MayaGlossy::tinted_by`].
    pub tinted_by: Rgb,
    /// [`MayaGlossy::specular_ramp`].
    pub specular_ramp: Option<[Rgb; SPECULAR_RAMP_STEPS]>,
    /// [`MayaGlossy::translucence`]: f = translucence · K(focus, −ωo·ωi)/π on the side
    /// opposite ωo.
    pub translucence: Rgb,
    /// [`MayaGlossy::focus`].
    pub focus: f32,
    /// [`MayaGlossy::translucence_grazing`]: f is further multiplied by
    /// [`translucence::light_angle_factor`] at ωi.
    pub translucence_grazing: Rgb,
    /// The probability of sampling the diffuse lobe.
    diffuse_share: f32,
    /// The probability of sampling the mirror.
    mirror_share: f32,
    /// The probability of sampling the refraction.
    refraction_share: f32,
    /// The probability of sampling the translucence.
    translucence_share: f32,
}

/// `wo` and `wi` mirrored to the +Z side when `wo` is below; `None` when they lie on
/// different sides.
fn upper(wo: Vec3A, wi: Vec3A) -> Option<(Vec3A, Vec3A)> {
    if wo.z * wi.z <= 0.0 {
        return None;
    }
    let flip = |w: Vec3A| if wo.z < 0.0 { Vec3A::new(w.x, w.y, -w.z) } else { w };
    Some((flip(wo), flip(wi)))
}

impl MayaBsdf {
    /// The same surface without its mirror (past its [`MayaBsdf::reflection_limit`]):
    /// the other lobes keep their shares relative to each other.
    pub fn without_mirror(&mut self) {
        let rest = 1.0 - self.mirror_share;
        self.diffuse_share = if rest > 0.0 { (self.diffuse_share / rest).min(1.0) } else { 0.0 };
        self.refraction_share = if rest > 0.0 { (self.refraction_share / rest).min(1.0) } else { 0.0 };
        self.translucence_share = if rest > 0.0 { (self.translucence_share / rest).min(1.0) } else { 0.0 };
        self.mirror = Rgb::ZERO;
        self.mirror_share = 0.0;
    }

    /// Sets the refraction for a hit from the back of the surface (`inside`: the ray
    /// leaves the material, relative index 1/`refractiveIndex`) or the front, on a path
    /// that has made `refractions` refractions and transparency passes: at or past
    /// [`MayaBsdf::refraction_limit`] the ray passes straight (relative index 1), as the
    /// classic shader traces a transparency ray there. Called once per hit.
    pub fn refract_at(&mut self, inside: bool, refractions: u32) {
        self.eta = if refractions >= self.refraction_limit || self.eta <= 0.0 {
            1.0
        } else if inside {
            1.0 / self.eta
        } else {
            self.eta
        };
    }

    /// The refracted direction for `wo` (Snell's law with [`MayaBsdf::eta`]; straight
    /// through for 1), the mirror direction under total internal reflection.
    pub fn refracted(&self, wo: Vec3A) -> Vec3A {
        if (self.eta - 1.0).abs() <= 1e-6 {
            return -wo;
        }
        let n = Vec3A::new(0.0, 0.0, wo.z.signum());
        crate::dielectric::refract(wo, n, self.eta).unwrap_or(Vec3A::new(-wo.x, -wo.y, wo.z))
    }

    /// The translucence's f(ωo, ωi): translucence · K(focus, −ωo·ωi)/π for ωi on the side
    /// opposite ωo, zero on ωo's side.
    pub fn eval_translucence(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z >= 0.0 || self.translucence == Rgb::ZERO {
            return Rgb::ZERO;
        }
        let f = self.translucence * (translucence::forward_lobe(self.focus, -wo.dot(wi)) * FRAC_1_PI);
        if self.translucence_grazing == Rgb::ZERO {
            return f;
        }
        f * translucence::light_angle_factor(self.translucence_grazing, wi.z.abs())
    }

    /// The density of the translucence's sampling ([`MayaBsdf::sample`]): cosine-weighted
    /// on the side opposite ωo for diffuse translucence, else the cosine power about −ωo
    /// (over the whole sphere: its samples on ωo's side carry the other lobes' f).
    fn translucence_pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if self.focus <= 0.0 {
            if wo.z * wi.z < 0.0 {
                if self.translucence_grazing != Rgb::ZERO {
                    return translucence::UNIFORM_PDF;
                }
                wi.z.abs() * FRAC_1_PI
            } else {
                0.0
            }
        } else {
            translucence::pdf_about(self.focus, -wo.dot(wi))
        }
    }

    /// f(ωo, ωi): diffuse/π + tint · H(ωo, ωi)/(π |cos θi|) on ωo's side, the
    /// translucence ([`MayaBsdf::eval_translucence`]) on the other.
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        let Some((v, l)) = upper(wo, wi) else { return self.eval_translucence(wo, wi) };
        let h = self.shape.value(v, l);
        let tint = match &self.specular_ramp {
            Some(s) => self.tint * table_at(s, h),
            None => self.tint,
        };
        (self.diffuse + tint * (h / l.z)) * FRAC_1_PI
    }

    /// The density of the non-delta part of the mixture: the diffuse lobe's cosine
    /// density and the highlight's, by their shares.
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let translucent =
            if self.translucence_share > 0.0 { self.translucence_share * self.translucence_pdf(wo, wi) } else { 0.0 };
        let Some((v, l)) = upper(wo, wi) else { return translucent };
        let p = self.diffuse_share;
        let glossy = (1.0 - p - self.mirror_share - self.refraction_share - self.translucence_share).max(0.0);
        p * l.z * FRAC_1_PI + glossy * self.shape.pdf(v, l) + translucent
    }

    /// Chooses the mirror with probability `mirror_share`, the refraction with
    /// `refraction_share`, the diffuse lobe with `diffuse_share`, else the highlight's
    /// density, by `u_lobe`; a continuous sample carries the continuous mixture's f and
    /// pdf, a delta its weight over |cos θ| and its share.
    pub fn sample(&self, wo: Vec3A, u: Vec2, u_lobe: f32) -> Option<BsdfSample> {
        if wo.z == 0.0
            || (self.mirror_share <= 0.0
                && self.refraction_share <= 0.0
                && self.diffuse == Rgb::ZERO
                && self.tint == Rgb::ZERO
                && self.translucence == Rgb::ZERO)
        {
            return None;
        }
        if u_lobe >= 1.0 - self.mirror_share {
            let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
            return Some(BsdfSample { wi, f: self.mirror / wo.z.abs(), pdf: self.mirror_share, delta: true });
        }
        if u_lobe >= 1.0 - self.mirror_share - self.refraction_share {
            let wi = self.refracted(wo);
            if wi.z == 0.0 {
                return None;
            }
            let f = self.refraction / wi.z.abs();
            return Some(BsdfSample { wi, f, pdf: self.refraction_share, delta: true });
        }
        let wi = if u_lobe < self.diffuse_share {
            cosine_on_side(wo, u)?
        } else if u_lobe < self.diffuse_share + self.translucence_share {
            if self.focus <= 0.0 && self.translucence_grazing != Rgb::ZERO {
                translucence::uniform_opposite(wo, u)
            } else if self.focus <= 0.0 {
                -cosine_on_side(wo, u)?
            } else {
                translucence::sample_about(-wo, self.focus, u)
            }
        } else {
            let v = Vec3A::new(wo.x, wo.y, wo.z.abs());
            let l = self.shape.sample(v, u)?;
            if wo.z < 0.0 {
                Vec3A::new(l.x, l.y, -l.z)
            } else {
                l
            }
        };
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample { wi, f: self.eval(wo, wi), pdf, delta: false })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{testing, Bsdf};
    use std::f32::consts::{PI, TAU};

    fn shapes() -> [Shape; 6] {
        [
            Shape::Blinn { eccentricity: 0.3, rolloff: 0.7 },
            Shape::RampBlinn { eccentricity: 0.3 },
            Shape::Blinn { eccentricity: 0.8, rolloff: 0.7 },
            Shape::Phong { power: 20.0 },
            Shape::PhongE { roughness: 0.5, size: 0.5 },
            Shape::Anisotropic { alpha_x: 0.2, alpha_y: 0.4, ior: 6.0 },
        ]
    }

    /// ∫ H/π dω over the hemisphere by a midpoint rule in (cos θ, φ), 1000 × 1000.
    fn albedo_by_quadrature(shape: Shape, mu: f32) -> f32 {
        let v = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        let n = 1000;
        let mut sum = 0.0f64;
        for i in 0..n {
            let c = (i as f32 + 0.5) / n as f32;
            let s = (1.0 - c * c).sqrt();
            for j in 0..n {
                let phi = (j as f32 + 0.5) / n as f32 * TAU;
                let l = Vec3A::new(s * phi.cos(), s * phi.sin(), c);
                sum += f64::from(shape.value(v, l));
            }
        }
        (sum * f64::from(TAU) / f64::from(n * n) / f64::from(PI)) as f32
    }

    /// The refraction bends by Snell's law (sin θt = sin θo / η, η = `refractiveIndex`
    /// entering, its inverse leaving, 1 past `refractionLimit`), reflects under total
    /// internal reflection, and weighs T per channel (no Fresnel).
    #[test]
    fn the_refraction_bends_by_snell_and_weighs_the_transparency() {
        let t = Rgb::new(0.9, 0.5, 0.2);
        let g = MayaGlossy::new(Shape::Phong { power: 20.0 }, Rgb::ZERO).with_refraction(t, 1.5, 1);
        let wo = Vec3A::new(0.6, 0.0, 0.8);
        for (inside, made, eta) in [(false, 0, 1.5), (true, 0, 1.0 / 1.5), (false, 1, 1.0), (true, 3, 1.0)] {
            let mut b = g.bsdf(Rgb::ZERO, wo);
            b.refract_at(inside, made);
            let s = b.sample(wo, Vec2::splat(0.5), 0.5).expect("a refraction");
            assert!(s.delta && s.wi.z < 0.0, "{s:?}");
            let sin_t = (s.wi.x * s.wi.x + s.wi.y * s.wi.y).sqrt();
            assert!((sin_t - 0.6 / eta).abs() < 1e-5 && s.wi.x < 0.0, "{inside} {made}: {s:?}");
            assert!((s.weight() - t).abs().max_element() < 1e-5, "{}", s.weight());
        }
        // Leaving at sin θ = 0.8 > 1/1.5: the mirror direction, same weight.
        let wo = Vec3A::new(0.8, 0.0, 0.6);
        let mut b = g.bsdf(Rgb::ZERO, wo);
        b.refract_at(true, 0);
        let s = b.sample(wo, Vec2::splat(0.5), 0.5).expect("a reflection");
        assert!((s.wi - Vec3A::new(-0.8, 0.0, 0.6)).length() < 1e-6, "{s:?}");
        assert!((s.weight() - t).abs().max_element() < 1e-5);
        // Beside a diffuse lobe the delta is chosen by its share: its weight × share is T.
        let b = g.bsdf(Rgb::splat(0.3), wo);
        let s = b.sample(wo, Vec2::splat(0.5), 0.999).expect("a refraction");
        assert!(s.delta && s.pdf < 1.0 && (s.weight() * s.pdf - t).abs().max_element() < 1e-5, "{s:?}");
    }

    #[test]
    fn the_evaluation_gives_the_classic_highlight_under_a_light_of_pi_times_its_colour() {
        // A light of colour C from l: the classic material adds s·C·H(v, l); the path
        // engine's light brings π·C·cos θ of irradiance, reflected by f.
        let v = Vec3A::new(0.3, -0.1, 0.9).normalize();
        let l = Vec3A::new(-0.35, 0.05, 0.8).normalize();
        for shape in shapes() {
            let g = MayaGlossy::new(shape, Rgb::new(0.5, 0.4, 0.3));
            let b = g.bsdf(Rgb::new(0.4, 0.2, 0.1), v);
            let path = b.eval(v, l) * (PI * l.z);
            let classic = Rgb::new(0.4, 0.2, 0.1) * l.z + Rgb::new(0.5, 0.4, 0.3) * shape.value(v, l);
            assert!((path - classic).abs().max_element() < 1e-5, "{shape:?}: {path} vs {classic}");
            // Both sides alike.
            let flip = |w: Vec3A| Vec3A::new(w.x, w.y, -w.z);
            assert!((b.eval(flip(v), flip(l)) - b.eval(v, l)).abs().max_element() < 1e-6);
            assert_eq!(b.eval(v, flip(l)), Rgb::ZERO);
        }
    }

    #[test]
    fn the_tabulated_albedo_matches_quadrature_and_sampling_matches_the_density() {
        for shape in shapes() {
            for mu in [1.0, 0.6, 0.25] {
                let (table, exact) = (shape.albedo(mu), albedo_by_quadrature(shape, mu));
                assert!((table - exact).abs() < 0.03 * exact + 1e-3, "{shape:?} at {mu}: {table} vs {exact}");
            }
            let b = Bsdf::Maya(MayaGlossy::new(shape, Rgb::splat(0.5)).bsdf(Rgb::splat(0.3), testing::incidences()[1]));
            for wo in testing::incidences() {
                testing::chi_square(&b, wo);
            }
        }
    }

    #[test]
    fn a_highlight_that_would_reflect_more_than_it_receives_is_bounded_to_one() {
        // Blinn of eccentricity 0.8 and specularColor 1: its unit albedo exceeds 1 at
        // grazing views (1.9 at μ = 0.05 by quadrature).
        let wide = Shape::Blinn { eccentricity: 0.8, rolloff: 0.7 };
        assert!(albedo_by_quadrature(wide, 0.1) > 1.3);
        let g = MayaGlossy::new(wide, Rgb::ONE);
        for mu in [1.0f32, 0.5, 0.2, 0.1, 0.03] {
            let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
            // The highlight alone (no diffuse): its white-furnace albedo.
            let a = testing::albedo(&Bsdf::Maya(g.bsdf(Rgb::ZERO, wo)), wo, 100_000);
            assert!(a.max_element() <= 1.03, "albedo {a} at μ = {mu}");
        }
        // A default blinn is not touched: its tint stays specularColor at every view.
        let default = MayaGlossy::new(Shape::Blinn { eccentricity: 0.3, rolloff: 0.7 }, Rgb::splat(0.5));
        for mu in [1.0f32, 0.5, 0.1, 0.0] {
            let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu.max(1e-3));
            assert_eq!(default.bsdf(Rgb::splat(0.4), wo).tint, Rgb::splat(0.5));
        }
    }

    #[test]
    fn the_mirror_reflects_its_weight_beside_the_other_lobes() {
        // Blinn's default with reflectivity 0.5 · specularColor (0.5, 0.4, 0.2) and
        // reflectionRolloff: the mirror reflects its weight × schlick(0.7, N·V); the
        // furnace albedo is diffuse + highlight + mirror.
        let shape = Shape::Blinn { eccentricity: 0.3, rolloff: 0.7 };
        let tint = Rgb::new(0.5, 0.4, 0.2);
        let g = MayaGlossy::new(shape, tint).with_mirror(tint * 0.5, Some(0.7));
        for mu in [1.0f32, 0.5] {
            let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
            let b = g.bsdf(Rgb::splat(0.3), wo);
            let mirror = tint * 0.5 * schlick(0.7, mu);
            assert!((b.mirror - mirror).abs().max_element() < 1e-6);
            let s = b.sample(wo, Vec2::new(0.3, 0.6), 0.9999).expect("the mirror");
            assert!(s.delta && (s.wi - Vec3A::new(-wo.x, 0.0, wo.z)).length() < 1e-6);
            assert!((s.weight() - mirror / b.mirror_share).abs().max_element() < 1e-5);
            let want = Rgb::splat(0.3) + tint * g.unit_albedo(mu) + mirror;
            let a = testing::albedo(&Bsdf::Maya(b), wo, 200_000);
            assert!((a - want).abs().max_element() < 0.01, "μ = {mu}: {a} vs {want}");
        }
    }

    #[test]
    fn reflected_colour_is_emitted_by_the_mirror_weight_and_the_limit_drops_the_mirror() {
        // Blinn with reflectivity 0.5 · specularColor, Schlick's roll-off of 0.3,
        // reflectedColor R, on a surface of coverage ½: emitted r·s·F(N·V) ⊙ R / ½; past
        // the reflection limit the mirror is gone and the rest keeps its albedo.
        let tint = Rgb::new(0.5, 0.4, 0.2);
        let reflected = Rgb::new(0.3, 0.2, 0.1);
        let g = MayaGlossy::new(Shape::Blinn { eccentricity: 0.3, rolloff: 0.7 }, tint)
            .with_mirror(tint * 0.5, Some(0.3))
            .with_reflected(reflected)
            .with_coverage(0.5);
        for mu in [1.0f32, 0.4, 0.1] {
            let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
            let b = g.bsdf(Rgb::splat(0.3), wo);
            let want = reflected * tint * 0.5 * schlick(0.3, mu) / 0.5;
            assert!((b.emitted - want).abs().max_element() < 1e-6, "μ = {mu}: {} vs {want}", b.emitted);
            let mut c = b;
            c.without_mirror();
            assert_eq!((c.mirror, c.emitted), (Rgb::ZERO, b.emitted));
            for u in [0.0, 0.5, 0.9999] {
                assert!(c.sample(wo, Vec2::new(0.3, 0.6), u).is_none_or(|s| !s.delta));
            }
            let a = testing::albedo(&Bsdf::Maya(c), wo, 100_000);
            let want = Rgb::splat(0.3) + tint * g.unit_albedo(mu) / 0.5;
            assert!((a - want).abs().max_element() < 0.01, "μ = {mu}: {a} vs {want}");
        }
        // A mirror alone, dropped: nothing to sample.
        let mut m = MayaGlossy::new(Shape::Phong { power: 20.0 }, Rgb::ZERO)
            .with_mirror(Rgb::ONE, None)
            .bsdf(Rgb::ZERO, Vec3A::Z);
        m.without_mirror();
        assert!(m.sample(Vec3A::Z, Vec2::new(0.3, 0.6), 0.5).is_none());
    }

    #[test]
    fn view_ramps_scale_the_highlight_and_the_mirror_and_colour_them() {
        // rampShader's roll-off 1 − ¾f and reflectivity 0.8 − 0.6f over the facing ratio
        // f, environment (y, 0, 1 − y) over the reflection's height y = (1 + R_z)/2
        // (no frame: local z is up), specular colour (h, h, 1 − h) over the highlight H.
        let ramps = ViewRamps::tabulate(|f| 1.0 - 0.75 * f, |f| 0.8 - 0.6 * f, |y| Rgb::new(y, 0.0, 1.0 - y));
        let g = MayaGlossy::new(Shape::RampBlinn { eccentricity: 0.3 }, Rgb::splat(0.8))
            .with_mirror(Rgb::ONE, None)
            .with_view_ramps(ramps)
            .with_specular_ramp(|h| Rgb::new(h, h, 1.0 - h));
        let wo = Vec3A::new(0.6, 0.0, 0.8);
        let b = g.bsdf(Rgb::ZERO, wo);
        let r = 0.8 - 0.6 * 0.8;
        assert!((b.mirror - Rgb::splat(r)).abs().max_element() < 1e-5, "{}", b.mirror);
        let env = Rgb::new(0.9, 0.0, 0.1);
        assert!((b.emitted - env * r).abs().max_element() < 1e-5, "{}", b.emitted);
        for l in [Vec3A::new(-0.6, 0.0, 0.8), Vec3A::new(-0.3, 0.2, 0.9).normalize()] {
            let h = ramp_blinn(Vec3A::Z, wo, l, 0.3);
            let want = 0.8 * (1.0 - 0.75 * 0.8) * Rgb::new(h, h, 1.0 - h) * h;
            let got = b.eval(wo, l) * (PI * l.z);
            assert!((got - want).abs().max_element() < 1e-5, "{l}: {got} vs {want}");
        }
        // In a frame the height is the world's y.
        let frame = Frame::from_normal(Vec3A::X);
        let world_y = frame.to_world(Vec3A::new(-0.6, 0.0, 0.8)).y;
        let b = g.bsdf_seen(Rgb::ZERO, wo, Some(&frame));
        let y = 0.5 * (1.0 + world_y);
        assert!((b.emitted - Rgb::new(y, 0.0, 1.0 - y) * r).abs().max_element() < 1e-5, "{}", b.emitted);
    }

    #[test]
    fn the_peak_is_the_formula_over_pi() {
        // Seen and lit head-on, blinn's highlight is the roll-off, phong's and
        // anisotropic's 1, phongE's its size: f = diffuse/π + tint·H/π.
        let n = Vec3A::Z;
        let cases = [
            (Shape::Blinn { eccentricity: 0.3, rolloff: 0.7 }, 0.7),
            (Shape::Phong { power: 20.0 }, 1.0),
            (Shape::PhongE { roughness: 0.5, size: 0.6 }, 0.6),
            (Shape::RampBlinn { eccentricity: 0.4 }, 1.0),
            (Shape::Anisotropic { alpha_x: 0.2, alpha_y: 0.4, ior: 6.0 }, 1.0),
        ];
        for (shape, peak) in cases {
            let b = MayaGlossy::new(shape, Rgb::splat(0.5)).bsdf(Rgb::splat(0.2), n);
            let want = (0.2 + 0.5 * peak) / PI;
            assert!((b.eval(n, n).x - want).abs() < 1e-6, "{shape:?}");
        }
    }
}
