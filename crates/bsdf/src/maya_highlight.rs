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
use std::sync::Mutex;

use glam::{Vec2, Vec3A};

use crate::{cosine_on_side, luminance, BsdfSample, Frame, Rgb};

mod glossy_translucence;
mod light_angle;
pub mod ramp_curve;
mod shape;
pub mod translucence;
pub mod translucent_stack;

pub use shape::{anisotropic, blinn, blinn_distribution, phong, phong_e, ramp_blinn, schlick, Shape};
pub use translucence::Merged;

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

/// A tabulated `specularColor` ramp: the colour (linear RGB) at highlight strengths
/// k/8 ([`MayaGlossy::specular_ramp`]).
pub type SpecularRamp = [[f32; 3]; SPECULAR_RAMP_STEPS];

/// Every distinct [`SpecularRamp`] interned so far (kept for the life of the process, as
/// a ramp's knots: a BSDF holds a reference, 8 bytes instead of 108).
static SPECULAR_RAMPS: Mutex<Vec<&'static SpecularRamp>> = Mutex::new(Vec::new());

/// The interned copy of `table` (an equal one, bit for bit, interned before, or a new one).
fn intern_specular_ramp(table: SpecularRamp) -> &'static SpecularRamp {
    let bits = |t: &SpecularRamp| t.map(|c| c.map(f32::to_bits));
    let mut ramps = SPECULAR_RAMPS.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(r) = ramps.iter().find(|r| bits(r) == bits(&table)) {
        return r;
    }
    let ramp: &'static SpecularRamp = Box::leak(Box::new(table));
    ramps.push(ramp);
    ramp
}

/// How many further forward lobes of their own focus a [`MayaGlossy`] carries besides
/// its first translucence (a layeredShader's layers of other `translucenceFocus`: four
/// distinct foci in all; a stack of more holds them in [`translucent_stack`], the
/// translation's choice where [`MayaGlossy::add_translucence`] says [`Merged`]).
pub const MORE_TRANSLUCENCE: usize = 3;

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

/// A table of colours (linear RGB) at evenly spaced points over [0, 1], linearly
/// interpolated at `x` (clamped), as [`table_at`] of the same colours as [`Rgb`].
pub fn rgb_table_at(table: &[[f32; 3]], x: f32) -> Rgb {
    let last = table.len() - 1;
    let x = x.clamp(0.0, 1.0) * last as f32;
    let k = (x as usize).min(last - 1);
    let t = x - k as f32;
    Rgb::from(table[k]) * (1.0 - t) + Rgb::from(table[k + 1]) * t
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
    /// H = k/8 (linear RGB), when it varies: the highlight is then tint ⊙ S(H) · H
    /// (interned).
    pub specular_ramp: Option<&'static SpecularRamp>,
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
    /// rampShader's light-angle translucence: the shape over the light's angle
    /// ([`translucence::LightAngle`]) of [`MayaGlossy::translucence`] where its focus is
    /// 0; `None`: diffuse (the lambert family's).
    pub light_angle: Option<translucence::LightAngle>,
    /// Further forward lobes, each of its own focus (a layeredShader whose translucent
    /// layers differ in `translucenceFocus`): albedo (linear RGB, as
    /// [`MayaGlossy::translucence`]) and exponent n; an albedo of zero: none.
    pub translucence_more: [[f32; 4]; MORE_TRANSLUCENCE],
    /// A layeredShader's translucence held by the material
    /// ([`translucent_stack::TranslucentStack`]: any number of lobes, weighted by the
    /// layers' shares at the hit's facing ratio) where its lobes do not fit the ones above
    /// or its layers' shares follow the view; the lobes above are then empty.
    pub translucence_stack: Option<translucent_stack::StackAt>,
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
            light_angle: None,
            translucence_more: [[0.0; 4]; MORE_TRANSLUCENCE],
            translucence_stack: None,
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

    /// The same with the translucence shaped over the light's angle by `table` (see
    /// [`MayaGlossy::light_angle`]).
    pub fn with_light_angle(mut self, table: translucence::LightAngle) -> MayaGlossy {
        self.light_angle = Some(table);
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
        let table = std::array::from_fn(|k| ramp(k as f32 / (SPECULAR_RAMP_STEPS - 1) as f32).max(Rgb::ZERO).into());
        self.specular_ramp = Some(intern_specular_ramp(table));
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
        for lobe in &mut self.translucence_more {
            for c in 0..3 {
                lobe[c] *= k[c].max(0.0);
            }
        }
        if let Some(at) = &mut self.translucence_stack {
            // (For a material's translation: interns the scaled stack.)
            at.stack = at.stack.scaled(k);
        }
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
        let colour = self.specular_ramp.map_or(Rgb::ONE, |s| s.iter().fold(Rgb::ZERO, |m, c| m.max(Rgb::from(*c))));
        let most = (tint * colour).max_element() * a;
        let tint = if most > 1.0 { tint / most } else { tint };
        let rolloff = self.mirror_rolloff.map_or(1.0, |r0| schlick(r0, facing));
        let mirror = mirror_weight.min(Rgb::ONE) * rolloff;
        let (tint, mirror) = (tint / self.coverage, mirror / self.coverage);
        let emitted =
            if reflected == Rgb::ZERO { Rgb::ZERO } else { reflected * mirror_weight * (rolloff / self.coverage) };
        // The highlight's share by its colour's mean.
        let mean = self
            .specular_ramp
            .map_or(Rgb::ONE, |s| s.iter().fold(Rgb::ZERO, |m, c| m + Rgb::from(*c)) / s.len() as f32);
        let (d, g, m) = (luminance(diffuse).max(0.0), luminance(tint * mean) * a, luminance(mirror).max(0.0));
        let t = luminance(self.refraction).max(0.0);
        let translucence = self.translucence_per_diffuse.map_or(self.translucence, |k| diffuse.max(Rgb::ZERO) * k);
        let more = self.translucence_more.iter().map(|l| luminance(Rgb::new(l[0], l[1], l[2])).max(0.0)).sum::<f32>();
        let stacked = self.translucence_stack.map_or(0.0, |s| luminance(s.albedo()).max(0.0));
        let tl = luminance(translucence).max(0.0) + more + stacked;
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
            light_angle: self.light_angle,
            translucence_more: self.translucence_more,
            translucence_stack: self.translucence_stack,
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
    pub specular_ramp: Option<&'static SpecularRamp>,
    /// [`MayaGlossy::translucence`]: f = translucence · K(focus, −ωo·ωi)/π on the side
    /// opposite ωo.
    pub translucence: Rgb,
    /// [`MayaGlossy::focus`].
    pub focus: f32,
    /// [`MayaGlossy::light_angle`]: the first lobe's f is further multiplied by
    /// [`translucence::LightAngle::factor`] at ωi.
    pub light_angle: Option<translucence::LightAngle>,
    /// [`MayaGlossy::translucence_more`]: further forward lobes, each
    /// albedo · K(n, −ωo·ωi)/π.
    pub translucence_more: [[f32; 4]; MORE_TRANSLUCENCE],
    /// [`MayaGlossy::translucence_stack`] at this hit: its f is added to the lobes above
    /// (which are then empty).
    pub translucence_stack: Option<translucent_stack::StackAt>,
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

    /// f(ωo, ωi): diffuse/π + tint · H(ωo, ωi)/(π |cos θi|) on ωo's side, the
    /// translucence ([`MayaBsdf::eval_translucence`]) on the other.
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        let Some((v, l)) = upper(wo, wi) else { return self.eval_translucence(wo, wi) };
        let h = self.shape.value(v, l);
        let tint = match &self.specular_ramp {
            Some(s) => self.tint * rgb_table_at(&s[..], h),
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
                && self.translucence == Rgb::ZERO
                && self.further().next().is_none()
                && self.translucence_stack.is_none())
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
            self.sample_translucence(wo, u, ((u_lobe - self.diffuse_share) / self.translucence_share).min(0.999_999))?
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
mod tests;
