//! A layeredShader's translucence held by the material, not the hit: every layer's
//! translucence lobes (albedo, `translucenceFocus` exponent, rampShader light-angle shape)
//! and its transparency over the facing ratio, interned for the life of the process (as
//! [`super::translucence::RampShape`]). The per-hit BSDF carries a reference to it, the
//! hit's facing ratio f and a scale ([`StackAt`], 16 bytes) and evaluates the stack's
//! lobes at f itself:
//!
//! ```text
//! f(ωo, ωi) = scale · Σ_i w_i(f) ⊙ Σ_j a_ij · K(n_ij, −ωo·ωi)/π · [S_ij(u)/u]
//! w_i(f) = T_0(f) ⊙ ⋯ ⊙ T_(i−1)(f) ⊙ (1 − T_i(f))   (per channel)
//! ```
//!
//! (K the forward lobe of `super::translucence`, S_ij/u the light-angle factor where the
//! lobe has one, u = |cos θi|; T_i read linearly between its table's points, as the
//! classic stack's shares are tabulated for the path engine's other per-hit quantities).
//! Exact for any number of layers, foci and ramps, where the BSDF's own slots hold four
//! foci and four ramp shapes mixed once: a stack whose shares follow the view needs one
//! weight per part and hit, which a fixed-size, heap-free `Bsdf` cannot hold past a few.
//! Sampling picks a lobe by the luminance of its weighted albedo and samples it as the
//! single lobe is sampled (uniform on the far side for a light-angle shape, cosine there
//! for diffuse translucence, the cosine power about −ωo for a focus).

use std::f32::consts::FRAC_1_PI;
use std::sync::Mutex;

use glam::{Vec2, Vec3A};

use super::table_at;
use super::translucence::{self, LightAngle};
use crate::{cosine_on_side, luminance, Rgb};

/// One translucence lobe of a layer before the layer's share: albedo (linear RGB),
/// forward-lobe exponent n (0: diffuse translucence) and, for n = 0, rampShader's
/// light-angle shape (`None`: diffuse).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackLobe {
    /// The lobe's albedo (linear RGB).
    pub albedo: Rgb,
    /// Its forward-lobe exponent ([`translucence::focus_exponent`]).
    pub exponent: f32,
    /// Its light-angle shape (only where `exponent` is 0).
    pub light_angle: Option<LightAngle>,
}

/// One layer of a [`TranslucentStack`]: its transparency at evenly spaced facing ratios
/// over [0, 1] (at least two points; a constant layer repeats its value) and its lobes.
#[derive(Clone, Debug, PartialEq)]
pub struct StackLayer {
    /// The layer's transparency T per channel at facing ratios k/(len − 1).
    pub transparency: Vec<Rgb>,
    /// Its translucence lobes before its share.
    pub lobes: Vec<StackLobe>,
}

/// A stack's layers, top first (see the module doc). Made by [`TranslucentStack::interned`].
#[derive(Debug, PartialEq)]
pub struct TranslucentStack {
    /// The layers, top first.
    layers: Vec<StackLayer>,
}

/// Every distinct stack interned so far (kept for the life of the process).
static STACKS: Mutex<Vec<&'static TranslucentStack>> = Mutex::new(Vec::new());

/// Whether two stacks hold the same numbers bit for bit (NaNs included; light-angle shapes
/// by their interned parts).
fn same_bits(a: &TranslucentStack, b: &TranslucentStack) -> bool {
    let rgb = |x: Rgb| x.to_array().map(f32::to_bits);
    let lobe = |x: &StackLobe, y: &StackLobe| {
        rgb(x.albedo) == rgb(y.albedo)
            && x.exponent.to_bits() == y.exponent.to_bits()
            && match (&x.light_angle, &y.light_angle) {
                (None, None) => true,
                (Some(p), Some(q)) => p.same_parts(q),
                _ => false,
            }
    };
    a.layers.len() == b.layers.len()
        && a.layers.iter().zip(&b.layers).all(|(x, y)| {
            x.transparency.len() == y.transparency.len()
                && x.transparency.iter().zip(&y.transparency).all(|(s, t)| rgb(*s) == rgb(*t))
                && x.lobes.len() == y.lobes.len()
                && x.lobes.iter().zip(&y.lobes).all(|(s, t)| lobe(s, t))
        })
}

impl TranslucentStack {
    /// The interned stack of `layers` (top first): transparencies clamped to [0, 1] (a
    /// table of one point repeated), lobes of zero albedo dropped, negative albedos and
    /// exponents taken as 0, a light-angle shape kept only on a lobe of exponent 0. An
    /// equal stack interned before is returned instead of a new one.
    pub fn interned(layers: Vec<StackLayer>) -> &'static TranslucentStack {
        let layers = layers
            .into_iter()
            .map(|l| {
                let mut transparency: Vec<Rgb> = l.transparency.iter().map(|t| t.clamp(Rgb::ZERO, Rgb::ONE)).collect();
                match transparency.len() {
                    0 => transparency = vec![Rgb::ZERO; 2],
                    1 => transparency.push(transparency[0]),
                    _ => {}
                }
                let lobes = l
                    .lobes
                    .into_iter()
                    .map(|x| {
                        let exponent = x.exponent.max(0.0);
                        let light_angle = if exponent <= 0.0 { x.light_angle } else { None };
                        StackLobe { albedo: x.albedo.max(Rgb::ZERO), exponent, light_angle }
                    })
                    .filter(|x| x.albedo != Rgb::ZERO)
                    .collect();
                StackLayer { transparency, lobes }
            })
            .collect();
        let stack = TranslucentStack { layers };
        let mut stacks = STACKS.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        if let Some(s) = stacks.iter().find(|s| same_bits(s, &stack)) {
            return s;
        }
        let stack: &'static TranslucentStack = Box::leak(Box::new(stack));
        stacks.push(stack);
        stack
    }

    /// A stack of one opaque layer holding `lobes` (a constant stack's lobes, already
    /// weighted by their layers' shares).
    pub fn constant(lobes: Vec<StackLobe>) -> &'static TranslucentStack {
        TranslucentStack::interned(vec![StackLayer { transparency: vec![Rgb::ZERO; 2], lobes }])
    }

    /// The same stack with every lobe's albedo multiplied by `k` per channel (for a
    /// material's translation: interns a stack).
    pub fn scaled(&self, k: Rgb) -> &'static TranslucentStack {
        let k = k.max(Rgb::ZERO);
        let layers = self
            .layers
            .iter()
            .map(|l| StackLayer {
                transparency: l.transparency.clone(),
                lobes: l.lobes.iter().map(|x| StackLobe { albedo: x.albedo * k, ..*x }).collect(),
            })
            .collect();
        TranslucentStack::interned(layers)
    }

    /// How many layers the stack holds.
    pub fn len(&self) -> usize {
        self.layers.len()
    }

    /// Whether the stack holds no layer.
    pub fn is_empty(&self) -> bool {
        self.layers.is_empty()
    }
}

/// A [`TranslucentStack`] seen at one hit: the hit's facing ratio N·V and a factor on
/// every lobe (the hit's coverage divided out, a connected `translucence` at the hit).
/// 16 bytes, `Copy`: what a per-hit BSDF carries of a stack's translucence.
#[derive(Clone, Copy, Debug)]
pub struct StackAt {
    /// The stack (interned).
    pub stack: &'static TranslucentStack,
    /// The facing ratio N·V in [0, 1] at which the layers' shares are read.
    pub facing: f32,
    /// The factor on every lobe's albedo.
    pub scale: f32,
}

impl PartialEq for StackAt {
    fn eq(&self, other: &StackAt) -> bool {
        std::ptr::eq(self.stack, other.stack) && self.facing == other.facing && self.scale == other.scale
    }
}

/// The density of sampling one lobe of exponent `n` (with a light-angle shape where
/// `light_angle`) from `wo` at `wi` (see the module doc).
fn lobe_pdf(n: f32, light_angle: bool, wo: Vec3A, wi: Vec3A) -> f32 {
    if n > 0.0 {
        return translucence::pdf_about(n, -wo.dot(wi));
    }
    if wo.z * wi.z >= 0.0 {
        0.0
    } else if light_angle {
        translucence::UNIFORM_PDF
    } else {
        wi.z.abs() * FRAC_1_PI
    }
}

impl StackAt {
    /// The stack `stack` at facing ratio 1, scale 1.
    pub fn new(stack: &'static TranslucentStack) -> StackAt {
        StackAt { stack, facing: 1.0, scale: 1.0 }
    }

    /// Every lobe with its weighted albedo scale · w_i(f) ⊙ a_ij, top layer first.
    pub fn weighted(&self) -> impl Iterator<Item = (Rgb, &'static StackLobe)> {
        let (facing, scale) = (self.facing, self.scale);
        let mut through = Rgb::ONE;
        self.stack.layers.iter().flat_map(move |layer| {
            let t = table_at(&layer.transparency, facing).clamp(Rgb::ZERO, Rgb::ONE);
            let w = through * (Rgb::ONE - t) * scale;
            through *= t;
            layer.lobes.iter().map(move |l| (w * l.albedo, l))
        })
    }

    /// The lobes as single ones: their weighted albedo, exponent and light-angle shape.
    pub fn lobes(&self) -> impl Iterator<Item = StackLobe> {
        self.weighted().map(|(a, l)| StackLobe { albedo: a, ..*l })
    }

    /// The sum of the lobes' weighted albedos (linear RGB).
    pub fn albedo(&self) -> Rgb {
        self.weighted().fold(Rgb::ZERO, |s, (a, _)| s + a)
    }

    /// f(ωo, ωi) for ωi on the side opposite ωo (zero on ωo's side; see the module doc).
    pub fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z >= 0.0 {
            return Rgb::ZERO;
        }
        let x = -wo.dot(wi);
        let u = wi.z.abs();
        let mut f = Rgb::ZERO;
        for (a, l) in self.weighted() {
            let mut v = a * (translucence::forward_lobe(l.exponent, x) * FRAC_1_PI);
            if let Some(shape) = &l.light_angle {
                v *= shape.factor(u);
            }
            f += v;
        }
        f
    }

    /// The density of [`StackAt::sample`]: each lobe's by the luminance of its weighted
    /// albedo.
    pub fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let (mut total, mut pdf) = (0.0f32, 0.0f32);
        for (a, l) in self.weighted() {
            let p = luminance(a).max(0.0);
            if p > 0.0 {
                total += p;
                pdf += p * lobe_pdf(l.exponent, l.light_angle.is_some(), wo, wi);
            }
        }
        if total > 0.0 {
            pdf / total
        } else {
            0.0
        }
    }

    /// A direction from `wo` by `u`, the lobe chosen by `v` ∈ [0, 1) in proportion to the
    /// luminance of its weighted albedo; `None` where every lobe is black.
    pub fn sample(&self, wo: Vec3A, u: Vec2, v: f32) -> Option<Vec3A> {
        let total = self.weighted().map(|(a, _)| luminance(a).max(0.0)).sum::<f32>();
        if total <= 0.0 {
            return None;
        }
        let mut pick = v * total;
        let mut chosen = None;
        for (a, l) in self.weighted() {
            let p = luminance(a).max(0.0);
            if p > 0.0 {
                chosen = Some(l);
                pick -= p;
                if pick < 0.0 {
                    break;
                }
            }
        }
        let l = chosen?;
        if l.exponent > 0.0 {
            Some(translucence::sample_about(-wo, l.exponent, u))
        } else if l.light_angle.is_some() {
            Some(translucence::uniform_opposite(wo, u))
        } else {
            Some(-cosine_on_side(wo, u)?)
        }
    }
}

#[cfg(test)]
#[path = "translucent_stack_tests.rs"]
mod tests;
