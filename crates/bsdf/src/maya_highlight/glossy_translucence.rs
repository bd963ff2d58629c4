//! The translucence lobes of [`MayaGlossy`] and [`MayaBsdf`]: the first lobe (with
//! rampShader's light-angle shape), up to [`MORE_TRANSLUCENCE`] further ones of their own
//! focus, and a layeredShader's [`TranslucentStack`] held by the material.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3A};

use super::translucent_stack::{StackAt, StackLobe, TranslucentStack};
use super::{translucence, MayaBsdf, MayaGlossy, Merged, MORE_TRANSLUCENCE};
use crate::{cosine_on_side, luminance, Rgb};

impl MayaGlossy {
    /// Adds a translucence of albedo `albedo` (linear RGB), forward-lobe exponent `focus`
    /// and light-angle shape `light_angle` (only for focus 0) to this one's: merged into
    /// the first lobe where the focus is the same (their light-angle shapes mixed by
    /// albedo), else carried as a lobe of its own ([`MayaGlossy::translucence_more`]; a
    /// focus-0 lobe is always the first, the only one with a light-angle shape). `Err`
    /// when no room was left and it was merged into the further lobe of the nearest
    /// exponent, which keeps its own ([`Merged`]).
    pub fn add_translucence(
        &mut self,
        albedo: Rgb,
        focus: f32,
        light_angle: Option<translucence::LightAngle>,
    ) -> Result<(), Merged> {
        self.add_translucence_with(albedo, focus, light_angle, false)
    }

    /// [`MayaGlossy::add_translucence`] whose light-angle shapes mix exactly for any
    /// number of distinct ramps ([`translucence::LightAngle::mixed_interned`]): for a
    /// material's translation only, never per hit.
    pub fn add_translucence_interned(
        &mut self,
        albedo: Rgb,
        focus: f32,
        light_angle: Option<translucence::LightAngle>,
    ) -> Result<(), Merged> {
        self.add_translucence_with(albedo, focus, light_angle, true)
    }

    /// [`MayaGlossy::add_translucence`], its light-angle shapes mixed by
    /// [`translucence::LightAngle::mixed_interned`] where `interned`.
    fn add_translucence_with(
        &mut self,
        albedo: Rgb,
        focus: f32,
        light_angle: Option<translucence::LightAngle>,
        interned: bool,
    ) -> Result<(), Merged> {
        let albedo = albedo.max(Rgb::ZERO);
        let focus = focus.max(0.0);
        if albedo == Rgb::ZERO {
            return Ok(());
        }
        if self.translucence == Rgb::ZERO {
            self.translucence = albedo;
            self.focus = focus;
            self.light_angle = if focus <= 0.0 { light_angle } else { None };
            return Ok(());
        }
        if (focus - self.focus).abs() <= 1e-6 {
            if focus <= 0.0 && (light_angle.is_some() || self.light_angle.is_some()) {
                let mine = self.light_angle.unwrap_or(translucence::LightAngle::DIFFUSE);
                let theirs = light_angle.unwrap_or(translucence::LightAngle::DIFFUSE);
                self.light_angle = Some(if interned {
                    mine.mixed_interned(self.translucence, &theirs, albedo)
                } else {
                    mine.mixed(self.translucence, &theirs, albedo)
                });
            }
            self.translucence += albedo;
            return Ok(());
        }
        if focus <= 0.0 {
            // The focus-0 lobe goes first (it alone carries a light-angle shape).
            let (first, n) = (self.translucence, self.focus);
            self.translucence = albedo;
            self.focus = 0.0;
            self.light_angle = light_angle;
            return self.add_further(first, n);
        }
        self.add_further(albedo, focus)
    }

    /// Adds a forward lobe (`albedo`, exponent `n` > 0) among the further ones (see
    /// [`MayaGlossy::add_translucence`]).
    fn add_further(&mut self, albedo: Rgb, n: f32) -> Result<(), Merged> {
        let add = |lobe: &mut [f32; 4]| {
            for c in 0..3 {
                lobe[c] += albedo[c];
            }
        };
        if let Some(lobe) = self.translucence_more.iter_mut().find(|l| l[..3] != [0.0; 3] && (l[3] - n).abs() <= 1e-6) {
            add(lobe);
            return Ok(());
        }
        if let Some(lobe) = self.translucence_more.iter_mut().find(|l| l[..3] == [0.0; 3]) {
            *lobe = [albedo.x, albedo.y, albedo.z, n];
            return Ok(());
        }
        let nearest = self
            .translucence_more
            .iter_mut()
            .min_by(|a, b| (a[3] - n).abs().total_cmp(&(b[3] - n).abs()))
            .expect("further lobes");
        add(nearest);
        Err(Merged { exponent: n, into: nearest[3] })
    }

    /// Every translucence lobe: albedo (linear RGB) and exponent, the first
    /// ([`MayaGlossy::translucence`]) first, then the further ones that are not empty.
    pub fn translucence_lobes(&self) -> impl Iterator<Item = (Rgb, f32)> + '_ {
        std::iter::once((self.translucence, self.focus)).chain(
            self.translucence_more.iter().filter(|l| l[..3] != [0.0; 3]).map(|l| (Rgb::new(l[0], l[1], l[2]), l[3])),
        )
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
        for lobe in &mut self.translucence_more {
            lobe[..3].iter_mut().for_each(|c| *c *= k);
        }
        self.translucence_per_diffuse = self.translucence_per_diffuse.map(|r| r * k);
        if let Some(at) = &mut self.translucence_stack {
            at.scale *= k;
        }
        self
    }

    /// The same with every translucence lobe's albedo divided by `k` (> 0; a stack's
    /// coverage, as its diffuse colour is).
    pub fn translucence_divided(mut self, k: f32) -> MayaGlossy {
        self.translucence /= k;
        for lobe in &mut self.translucence_more {
            lobe[..3].iter_mut().for_each(|c| *c /= k);
        }
        if let Some(at) = &mut self.translucence_stack {
            at.scale /= k;
        }
        self
    }

    /// The same with its whole translucence held by `stack` (at facing ratio 1, scale 1:
    /// [`MayaGlossy::translucence_stack`]), the lobes of its own emptied.
    pub fn with_translucence_stack(mut self, stack: &'static TranslucentStack) -> MayaGlossy {
        self.translucence = Rgb::ZERO;
        self.focus = 0.0;
        self.light_angle = None;
        self.translucence_more = [[0.0; 4]; MORE_TRANSLUCENCE];
        self.translucence_per_diffuse = None;
        self.translucence_stack = Some(StackAt::new(stack));
        self
    }

    /// Every translucence lobe with its albedo, exponent and light-angle shape: the first
    /// (with its shape), the further ones, and a stack's at its facing ratio and scale
    /// (for a material's translation: collects them).
    pub fn translucence_parts(&self) -> Vec<StackLobe> {
        let first = StackLobe {
            albedo: self.translucence,
            exponent: self.focus,
            light_angle: if self.focus <= 0.0 { self.light_angle } else { None },
        };
        let further = self.translucence_lobes().skip(1).map(|(albedo, exponent)| StackLobe {
            albedo,
            exponent,
            light_angle: None,
        });
        std::iter::once(first)
            .chain(further)
            .chain(self.translucence_stack.iter().flat_map(|s| s.lobes()))
            .filter(|l| l.albedo != Rgb::ZERO)
            .collect()
    }
}

impl MayaBsdf {
    /// The translucence's f(ωo, ωi) for ωi on the side opposite ωo: the first lobe's
    /// translucence · K(focus, −ωo·ωi)/π (times its light-angle factor at ωi where it has
    /// one) plus each further lobe's albedo · K(n, −ωo·ωi)/π; zero on ωo's side.
    pub fn eval_translucence(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z >= 0.0 {
            return Rgb::ZERO;
        }
        let x = -wo.dot(wi);
        let mut f = Rgb::ZERO;
        if self.translucence != Rgb::ZERO {
            f = self.translucence * (translucence::forward_lobe(self.focus, x) * FRAC_1_PI);
            if let Some(table) = &self.light_angle {
                f *= table.factor(wi.z.abs());
            }
        }
        for lobe in self.further() {
            f += Rgb::new(lobe[0], lobe[1], lobe[2]) * (translucence::forward_lobe(lobe[3], x) * FRAC_1_PI);
        }
        if let Some(stack) = &self.translucence_stack {
            f += stack.eval(wo, wi);
        }
        f
    }

    /// The share of the translucence's samples that the stack's lobes take (by
    /// luminance; 0 without a stack, 1 where the lobes of its own are empty).
    fn stack_share(&self) -> f32 {
        let Some(stack) = &self.translucence_stack else { return 0.0 };
        let own = luminance(self.translucence).max(0.0)
            + self.further().map(|l| luminance(Rgb::new(l[0], l[1], l[2])).max(0.0)).sum::<f32>();
        if own <= 0.0 {
            return 1.0;
        }
        let stacked = luminance(stack.albedo()).max(0.0);
        stacked / (stacked + own)
    }

    /// The further forward lobes that are not empty.
    pub(super) fn further(&self) -> impl Iterator<Item = &[f32; 4]> {
        self.translucence_more.iter().filter(|l| l[..3] != [0.0; 3])
    }

    /// The first translucence lobe's share of the translucence's samples (by luminance;
    /// 1 without further lobes).
    fn first_translucence_share(&self) -> f32 {
        let more = self.further().map(|l| luminance(Rgb::new(l[0], l[1], l[2])).max(0.0)).sum::<f32>();
        if more <= 0.0 {
            return 1.0;
        }
        let first = luminance(self.translucence).max(0.0);
        first / (first + more)
    }

    /// The density of the first translucence lobe's sampling ([`MayaBsdf::sample`]):
    /// uniform on the side opposite ωo for a light-angle shape, cosine-weighted there for
    /// diffuse translucence, else the cosine power about −ωo (over the whole sphere: its
    /// samples on ωo's side carry the other lobes' f).
    fn first_translucence_pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if self.focus <= 0.0 {
            if wo.z * wi.z < 0.0 {
                if self.light_angle.is_some() {
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

    /// The density of the translucence's sampling: the first lobe's, each further lobe's
    /// (the cosine power about −ωo) and the stack's, mixed by their luminance.
    pub(super) fn translucence_pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let stacked = self.stack_share();
        let stack_pdf = match &self.translucence_stack {
            Some(stack) if stacked > 0.0 => stacked * stack.pdf(wo, wi),
            _ => 0.0,
        };
        if stacked >= 1.0 {
            return stack_pdf;
        }
        stack_pdf + (1.0 - stacked) * self.own_translucence_pdf(wo, wi)
    }

    /// The density of sampling the lobes of its own (the first and the further ones).
    fn own_translucence_pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let first = self.first_translucence_share();
        if first >= 1.0 {
            return self.first_translucence_pdf(wo, wi);
        }
        let more = self.further().map(|l| luminance(Rgb::new(l[0], l[1], l[2])).max(0.0)).sum::<f32>();
        let x = -wo.dot(wi);
        let further = self
            .further()
            .map(|l| luminance(Rgb::new(l[0], l[1], l[2])).max(0.0) * translucence::pdf_about(l[3], x))
            .sum::<f32>();
        let first_pdf = if first > 0.0 { first * self.first_translucence_pdf(wo, wi) } else { 0.0 };
        first_pdf + (1.0 - first) * further / more
    }

    /// A direction of the translucence's sampling from `wo` by `u`, the lobe chosen by
    /// `v` ∈ [0, 1) (see [`MayaBsdf::translucence_pdf`]).
    pub(super) fn sample_translucence(&self, wo: Vec3A, u: Vec2, v: f32) -> Option<Vec3A> {
        let stacked = self.stack_share();
        if let Some(stack) = self.translucence_stack.as_ref().filter(|_| v < stacked) {
            return stack.sample(wo, u, (v / stacked).min(0.999_999));
        }
        let v = if stacked > 0.0 { ((v - stacked) / (1.0 - stacked)).clamp(0.0, 0.999_999) } else { v };
        let first = self.first_translucence_share();
        if v < first {
            return if self.focus <= 0.0 && self.light_angle.is_some() {
                Some(translucence::uniform_opposite(wo, u))
            } else if self.focus <= 0.0 {
                Some(-cosine_on_side(wo, u)?)
            } else {
                Some(translucence::sample_about(-wo, self.focus, u))
            };
        }
        let more = self.further().map(|l| luminance(Rgb::new(l[0], l[1], l[2])).max(0.0)).sum::<f32>();
        let mut pick = (v - first) / (1.0 - first) * more;
        let mut n = 0.0;
        for l in self.further() {
            n = l[3];
            pick -= luminance(Rgb::new(l[0], l[1], l[2])).max(0.0);
            if pick < 0.0 {
                break;
            }
        }
        Some(translucence::sample_about(-wo, n, u))
    }
}
