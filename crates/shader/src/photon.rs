//! Photon scattering as the shader model describes it: what a surface does with a photon
//! that hits it.
//!
//! mental ray runs a material's `photon` shader for each photon hit; the shader stores the
//! photon where the surface is diffuse and sends it on by one of its scattering kinds,
//! chosen by Russian roulette with the kinds' reflectances as probabilities (mental ray's
//! `mi_choose_scatter_type`). mira describes each surface by a [`Scatter`] (the reflectance
//! of each kind at the hit), which each shader gives through its
//! [`photon`](crate::ShaderImpl::photon) function; the renderer's photon pass stores,
//! chooses and traces.

use glam::Vec3A;

use crate::graph::Slot;
use crate::{Ctx, NodeId};

/// How a surface scatters photons at one hit; colours are reflectances (0–1 per channel).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Scatter {
    /// Lambertian reflection: photons are stored here and bounce diffusely.
    pub diffuse: Vec3A,
    /// Specular (or glossy, see `gloss`) reflection.
    pub reflect: Vec3A,
    /// Glossy reflection lobe: mia's shininess (u, v); `None`: a mirror.
    pub gloss: Option<(f32, f32)>,
    /// Specular transmission (refraction by `ior`).
    pub transmit: Vec3A,
    /// Diffuse transmission (translucency): photons are stored on this side and go on
    /// diffusely on the other.
    pub translucent: Vec3A,
    /// Index of refraction of the material behind the surface's front side.
    pub ior: f32,
    /// Thin walled: transmission goes straight through without bending.
    pub thin: bool,
    /// The photon passes on unchanged, as if there were no surface (`transmat_photon`).
    pub pass: bool,
}

/// What Russian roulette chose at a hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event {
    /// Diffuse reflection.
    Diffuse,
    /// Specular or glossy reflection.
    Reflect,
    /// Refraction.
    Transmit,
    /// Diffuse transmission.
    Translucent,
    /// Absorbed: the path ends.
    Absorb,
}

impl Scatter {
    /// Whether photons landing here are stored (the surface has a diffuse part).
    pub fn stores(&self) -> bool {
        !self.pass && (self.diffuse.max_element() > 0.0 || self.translucent.max_element() > 0.0)
    }

    /// Chooses the event for uniform `u` ∈ [0, 1): each kind with probability the mean of
    /// its reflectance (scaled down together if they sum past 1), absorption with the rest.
    /// Returns the event and the factor the photon's power is multiplied by (reflectance /
    /// probability, so that the power's expectation is right and its grey part constant).
    pub fn choose(&self, u: f32) -> (Event, Vec3A) {
        if self.pass {
            return (Event::Transmit, Vec3A::ONE);
        }
        let kinds = [
            (Event::Diffuse, self.diffuse),
            (Event::Reflect, self.reflect),
            (Event::Transmit, self.transmit),
            (Event::Translucent, self.translucent),
        ];
        let probs = kinds.map(|(_, c)| (c.max(Vec3A::ZERO).element_sum() / 3.0).max(0.0));
        let total: f32 = probs.iter().sum();
        let scale = if total > 1.0 { 1.0 / total } else { 1.0 };
        let mut acc = 0.0;
        for ((event, c), p) in kinds.into_iter().zip(probs) {
            let p = p * scale;
            if p <= 0.0 {
                continue;
            }
            acc += p;
            if u < acc {
                return (event, c.max(Vec3A::ZERO) / p);
            }
        }
        (Event::Absorb, Vec3A::ZERO)
    }
}

/// How the surface of the state's hit scatters photons: its material's photon shader,
/// else its material shader, as the shader's implementation says. No material, or a
/// shader without photon behaviour: absorbed.
pub fn scatter_at(ctx: &mut Ctx) -> Scatter {
    let shading = ctx.shading();
    let Some(m) = ctx.state.material.and_then(|m| shading.materials.get(m as usize)) else {
        return Scatter::default();
    };
    let Some(node) = m.photon.or(m.surface).map(|n| resolve(ctx, n)) else { return Scatter::default() };
    let Some(imp) = ctx.node(node).imp else { return Scatter::default() };
    imp.photon.map_or_else(Scatter::default, |photon| photon(ctx, node))
}

/// The shader a list head stands for: a phenomenon's root, else the head itself.
fn resolve(ctx: &Ctx, mut node: NodeId) -> NodeId {
    for _ in 0..16 {
        let n = ctx.node(node);
        match (n.imp.map(|i| i.name), n.slots.first()) {
            (Some("(phenomenon)"), Some(Slot::Connect { node: root, member: None })) => node = *root,
            _ => break,
        }
    }
    node
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roulette_keeps_the_expected_power() {
        let s = Scatter {
            diffuse: Vec3A::new(0.6, 0.3, 0.3),
            reflect: Vec3A::splat(0.2),
            transmit: Vec3A::new(0.1, 0.0, 0.2),
            ..Scatter::default()
        };
        // Stratified u: the mean power multiplier of each event is its reflectance.
        let n = 100_000;
        let mut sums = [Vec3A::ZERO; 5];
        for i in 0..n {
            let (e, f) = s.choose((i as f32 + 0.5) / n as f32);
            sums[e as usize] += f / n as f32;
        }
        for (got, want) in sums.iter().zip([s.diffuse, s.reflect, s.transmit, Vec3A::ZERO]) {
            assert!((*got - want).abs().max_element() < 1e-3, "{got} vs {want}");
        }
        // Reflectances past 1 in sum: probabilities scaled, never absorbed.
        let bright = Scatter { diffuse: Vec3A::ONE, reflect: Vec3A::ONE, ..Scatter::default() };
        assert_eq!(bright.choose(0.999).0, Event::Reflect);
        assert_eq!(bright.choose(0.2).1, Vec3A::splat(2.0));
    }
}
