//! rampShader's `transparency` and `incandescence` ramps by the view's facing ratio in
//! the path engine: the classic shader reads both at f = N·V for each ray (shadow rays
//! included), so the path engine sets a hit's coverage, cut-out tint, faded diffuse
//! colour and incandescence from them at each hit, by the rules a constant transparency
//! follows (see `crate::maya`'s module doc), instead of taking them at f = 1. A
//! rampShader that refracts ([`ViewTransparency::refracts`]) takes T(f) as its
//! refraction's weight at each hit instead, its lit colour and incandescence faded by
//! 1 − T(f) (no cut-out for the rays that see it, as for a constant transparency).

use std::borrow::Cow;

use bsdf::maya_highlight::{table_at, VIEW_RAMP_STEPS};
use bsdf::Rgb;

use super::view_layers::StackTranslucence;
use super::MIN_HIGHLIGHT_COVERAGE;
use crate::{HitMaterial, SurfaceModel};

/// A rampShader's transparency and incandescence ramps tabulated over the facing ratio
/// (linear between [`VIEW_RAMP_STEPS`] points, as `bsdf::maya_highlight::ViewRamps`),
/// with what the hit's material is made from.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewTransparency {
    /// `transparency` T at N·V = k/32, clamped to [0, 1] per channel.
    pub transparency: [Rgb; VIEW_RAMP_STEPS],
    /// `incandescence` at N·V = k/32 (emitted radiance before the fade by 1 − T).
    pub incandescence: [Rgb; VIEW_RAMP_STEPS],
    /// The lit colour's albedo before the fade by 1 − T.
    pub albedo: Rgb,
    /// The translucence's albedo before the fade by 1 − T (the Maya model's
    /// [`bsdf::MayaGlossy::translucence`], faded at each hit as the diffuse colour is);
    /// zero: none.
    pub translucence: Rgb,
    /// The material shows a highlight or a reflection: its coverage is at least
    /// [`MIN_HIGHLIGHT_COVERAGE`].
    pub highlight: bool,
    /// The material refracts (`refractions` on): T(f) is its refraction's weight
    /// ([`bsdf::MayaGlossy::refraction`]) and the rays that see it all hit it.
    pub refracts: bool,
    /// For a layeredShader whose layers' ramps follow the view: its lit colour, its
    /// emission (each already weighted by the layers' shares, before the division by the
    /// hit's coverage) and the light its shown layers let through, P(f), at N·V = k/32;
    /// `transparency` is then the stack's (what shadow rays pass) and, when it refracts,
    /// P(f) the refraction's weight. `None` for a rampShader, whose are `albedo` ⊙ (1 −
    /// T), `incandescence` ⊙ (1 − T) and T.
    pub stack: Option<Box<[[Rgb; VIEW_RAMP_STEPS]; 3]>>,
    /// For such a stack with translucent layers: their translucence, weighted by the
    /// layers' shares at each hit's facing ratio ([`StackTranslucence::apply`]).
    pub stack_translucence: Option<Box<StackTranslucence>>,
}

impl ViewTransparency {
    /// The ramps tabulated from functions of the facing ratio.
    pub fn tabulate(
        transparency: impl Fn(f32) -> Rgb,
        incandescence: impl Fn(f32) -> Rgb,
        albedo: Rgb,
        highlight: bool,
    ) -> Self {
        let at = |k: usize| k as f32 / (VIEW_RAMP_STEPS - 1) as f32;
        ViewTransparency {
            transparency: std::array::from_fn(|k| transparency(at(k)).clamp(Rgb::ZERO, Rgb::ONE)),
            incandescence: std::array::from_fn(|k| incandescence(at(k))),
            albedo,
            translucence: Rgb::ZERO,
            highlight,
            refracts: false,
            stack: None,
            stack_translucence: None,
        }
    }

    /// A layeredShader's stack tabulated over the facing ratio: its transparency (the
    /// product of its layers'), its lit colour and its emission weighted by the layers'
    /// shares and the light its shown layers let through (see [`ViewTransparency::stack`]).
    pub fn stack(
        transparency: [Rgb; VIEW_RAMP_STEPS],
        lit: [Rgb; VIEW_RAMP_STEPS],
        emission: [Rgb; VIEW_RAMP_STEPS],
        passed: [Rgb; VIEW_RAMP_STEPS],
    ) -> Self {
        ViewTransparency {
            transparency: transparency.map(|t| t.clamp(Rgb::ZERO, Rgb::ONE)),
            incandescence: [Rgb::ZERO; VIEW_RAMP_STEPS],
            albedo: Rgb::ZERO,
            translucence: Rgb::ZERO,
            highlight: false,
            refracts: false,
            stack: Some(Box::new([lit, emission, passed])),
            stack_translucence: None,
        }
    }

    /// The same stack with its layers' translucence (see
    /// [`ViewTransparency::stack_translucence`]).
    pub fn with_stack_translucence(mut self, translucence: StackTranslucence) -> Self {
        self.stack_translucence = Some(Box::new(translucence));
        self
    }

    /// The same ramps on a material whose translucence has the albedo `translucence`
    /// before the fade (see [`ViewTransparency::translucence`]).
    pub fn with_translucence(mut self, translucence: Rgb) -> Self {
        self.translucence = translucence;
        self
    }

    /// The same ramps on a material that refracts (see [`ViewTransparency::refracts`]).
    pub fn refracting(mut self) -> Self {
        self.refracts = true;
        self
    }

    /// The transparency at facing ratio `facing` (N·V, clamped to [0, 1]).
    pub fn transparency_at(&self, facing: f32) -> Rgb {
        table_at(&self.transparency, facing)
    }

    /// Sets `hit`'s coverage p = 1 − mean T(f) (at least [`MIN_HIGHLIGHT_COVERAGE`] with a
    /// highlight), cut-out tint T(f)/(1 − p), diffuse colour albedo ⊙ (1 − T(f))/p,
    /// incandescence(f) ⊙ (1 − T(f))/p and its highlight's coverage, for the view of facing
    /// ratio `facing`.
    ///
    /// A refracting material's hit takes T(f) as its refraction's weight, its diffuse
    /// colour and incandescence faded by 1 − T(f), the coverage (for shadow rays) and
    /// tint as above without the least coverage (a refracting stack: its lit colour,
    /// emission and P(f) as the weight, undivided). A stack's ([`ViewTransparency::stack`])
    /// takes its lit colour and emission at f divided by p (its highlight untouched), and
    /// its layers' translucence by their shares at f, divided by p as well (undivided
    /// when it refracts: [`StackTranslucence::apply`]).
    pub fn apply(&self, facing: f32, hit: &mut HitMaterial<'_>) {
        let t = self.transparency_at(facing);
        let mut p = 1.0 - (t.x + t.y + t.z) / 3.0;
        if self.refracts {
            hit.opacity = p;
            hit.cutout_tint = if p < 1.0 { t / (1.0 - p) } else { Rgb::ONE };
            let weight = match &self.stack {
                Some(stack) => {
                    hit.diffuse = table_at(&stack[0], facing);
                    hit.emission = table_at(&stack[1], facing);
                    table_at(&stack[2], facing)
                }
                None => {
                    hit.diffuse = self.albedo * (Rgb::ONE - t);
                    hit.emission = table_at(&self.incandescence, facing) * (Rgb::ONE - t);
                    t
                }
            };
            let translucence = self.translucence * (Rgb::ONE - t);
            let refracting = match &*hit.model {
                SurfaceModel::Maya(g) => {
                    let g = g.with_refraction(weight, g.ior, g.refraction_limit);
                    Some(match (&self.stack, &self.stack_translucence) {
                        (Some(_), Some(layers)) => layers.apply(facing, 1.0, &g),
                        (Some(_), None) => g,
                        (None, _) => g.with_translucence(translucence, g.focus),
                    })
                }
                _ => None,
            };
            if let Some(g) = refracting {
                hit.model = Cow::Owned(SurfaceModel::Maya(Box::new(g)));
            }
            return;
        }
        if self.highlight {
            p = p.max(MIN_HIGHLIGHT_COVERAGE);
        }
        hit.opacity = p;
        hit.cutout_tint = if p < 1.0 { t / (1.0 - p) } else { Rgb::ONE };
        if let Some(stack) = &self.stack {
            let k = if p > 0.0 { 1.0 / p } else { 1.0 };
            hit.diffuse = table_at(&stack[0], facing) * k;
            hit.emission = table_at(&stack[1], facing) * k;
            let translucent = match (&self.stack_translucence, &*hit.model) {
                (Some(layers), SurfaceModel::Maya(g)) => Some(layers.apply(facing, p, g)),
                _ => None,
            };
            if let Some(g) = translucent {
                hit.model = Cow::Owned(SurfaceModel::Maya(Box::new(g)));
            }
            return;
        }
        let fade = if p > 0.0 { (Rgb::ONE - t) / p } else { Rgb::ONE };
        hit.diffuse = self.albedo * fade;
        hit.emission = table_at(&self.incandescence, facing) * fade;
        let glossy = match &*hit.model {
            SurfaceModel::Maya(g) => {
                Some(g.with_coverage(p.max(1e-3)).with_translucence(self.translucence * fade, g.focus))
            }
            _ => None,
        };
        if let Some(g) = glossy {
            hit.model = Cow::Owned(SurfaceModel::Maya(Box::new(g)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// T(f) = 1 − f grey and incandescence (f, 0, 1 − f): at f = 0.3 (a table point
    /// interpolated linearly: exact to 1e-6) the coverage is 0.3, the tint 1, the
    /// diffuse colour albedo · 0.3/0.3 and the incandescence (0.3, 0, 0.7); with a
    /// highlight at f = 0.1 the coverage is the least one and the tint 0.9/0.75.
    #[test]
    fn the_hit_follows_the_facing_ratio() {
        let v = ViewTransparency::tabulate(
            |f| Rgb::splat(1.0 - f),
            |f| Rgb::new(f, 0.0, 1.0 - f),
            Rgb::new(0.5, 0.25, 0.125),
            false,
        );
        let m = crate::SurfaceMaterial::grey("g");
        let mut hit = m.constant();
        v.apply(0.3, &mut hit);
        assert!((hit.opacity - 0.3).abs() < 1e-6);
        assert!((hit.cutout_tint - Rgb::ONE).abs().max_element() < 1e-6);
        assert!((hit.diffuse - Rgb::new(0.5, 0.25, 0.125)).abs().max_element() < 1e-6);
        assert!((hit.emission - Rgb::new(0.3, 0.0, 0.7)).abs().max_element() < 1e-6);
        let h = ViewTransparency { highlight: true, ..v };
        let mut hit = m.constant();
        h.apply(0.1, &mut hit);
        assert_eq!(hit.opacity, MIN_HIGHLIGHT_COVERAGE);
        assert!((hit.cutout_tint - Rgb::splat(0.9 / 0.75)).abs().max_element() < 1e-5);
    }

    /// A rampShader's translucence is faded at each hit as its diffuse colour: at
    /// f = 0.1 with a highlight (coverage 0.75) by (1 − 0.9)/0.75, refracting by
    /// 1 − 0.9 (within 1e-6); its focus kept.
    #[test]
    fn the_translucence_follows_the_facing_ratio() {
        let behind = Rgb::new(0.4, 0.2, 0.1);
        let v = ViewTransparency::tabulate(|f| Rgb::splat(1.0 - f), |_| Rgb::ZERO, Rgb::splat(0.5), true)
            .with_translucence(behind);
        let mut m = crate::SurfaceMaterial::grey("g");
        let g = bsdf::MayaGlossy::new(bsdf::maya_highlight::Shape::Phong { power: 1.0 }, Rgb::ZERO);
        m.model = SurfaceModel::Maya(Box::new(g.with_translucence(behind, 2.0)));
        for (view, fade) in [(v.clone(), 0.1 / MIN_HIGHLIGHT_COVERAGE), (v.refracting(), 0.1)] {
            let mut hit = m.constant();
            view.apply(0.1, &mut hit);
            let SurfaceModel::Maya(g) = &*hit.model else { panic!("not a Maya model") };
            assert!((g.translucence - behind * fade).abs().max_element() < 1e-6, "{:?}", g.translucence);
            assert_eq!(g.focus, 2.0);
        }
    }
}
