//! Photon shaders: what a surface does with a photon that hits it.
//!
//! mental ray runs a material's `photon` shader for each photon hit; the shader stores the
//! photon where the surface is diffuse and sends it on by one of its scattering kinds,
//! chosen by Russian roulette with the kinds' reflectances as probabilities (mental ray's
//! `mi_choose_scatter_type`). mira describes each surface by a [`Scatter`] (the reflectance
//! of each kind at the hit); the renderer's photon pass stores, chooses and traces.
//!
//! Photon shaders read: `mib_photon_basic` (diffuse, specular reflection, transmission with
//! `ior_frac`), `dielectric_material_photon` (Fresnel-weighted reflection and refraction),
//! `transmat_photon` (the photon goes on unchanged), `dgs_material_photon` (diffuse, glossy
//! as specular, specular, transparency with `ior`) and `mia_material` in the photon slot
//! ([`crate::mia::photon`]). A material without a photon shader is read from its material
//! shader (mental ray would absorb the photon there; exporters normally set the photon
//! slot to the same shader): `mia_material`, the `mib_illum_*` shaders and mira's
//! Lambertian stand-in by their diffuse colour, `mib_dielectric` as clear glass of its
//! `ior`. Other shaders absorb photons.

use glam::Vec3A;

use super::rgb;
use crate::model::graph::Slot;
use crate::model::{Ctx, NodeId, ShaderImpl, Value};

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

/// `mib_photon_basic (color diffuse, color specular, color transp, scalar ior_frac)`.
pub static PHOTON_BASIC: ShaderImpl =
    ShaderImpl { name: "mib_photon_basic", params: &["diffuse", "specular", "transp", "ior_frac"], run: photon_only };

/// `dielectric_material_photon (color col, scalar ior, color col_out, scalar ior_out, …)`.
pub static DIELECTRIC_PHOTON: ShaderImpl =
    ShaderImpl { name: "dielectric_material_photon", params: &["col", "ior", "col_out", "ior_out"], run: photon_only };

/// `transmat_photon ()`.
pub static TRANSMAT_PHOTON: ShaderImpl = ShaderImpl { name: "transmat_photon", params: &[], run: photon_only };

/// `dgs_material_photon (color diffuse, color glossy, color specular, …, scalar transp,
/// scalar ior)`.
pub static DGS_PHOTON: ShaderImpl = ShaderImpl {
    name: "dgs_material_photon",
    params: &["diffuse", "glossy", "specular", "transp", "ior"],
    run: photon_only,
};

/// A photon shader called on an eye or secondary ray: it contributes nothing (mental ray
/// runs photon shaders only while tracing photons).
fn photon_only(_: &mut Ctx, _: NodeId, _: &mut Value) -> bool {
    false
}

/// How the surface of the state's hit scatters photons: its material's photon shader,
/// else what its material shader says (see the module documentation). No material:
/// absorbed.
pub fn scatter_at(ctx: &mut Ctx) -> Scatter {
    let shading = ctx.shading();
    let Some(m) = ctx.state.material.and_then(|m| shading.materials.get(m as usize)) else {
        return Scatter::default();
    };
    let Some(node) = m.photon.or(m.surface).map(|n| resolve(ctx, n)) else { return Scatter::default() };
    let Some(imp) = ctx.node(node).imp else { return Scatter::default() };
    let c = |ctx: &mut Ctx, i: usize| rgb(ctx.color(node, i)).max(Vec3A::ZERO);
    match imp.name {
        "mib_photon_basic" => {
            let transmit = c(ctx, 2);
            Scatter {
                diffuse: c(ctx, 0) * (Vec3A::ONE - transmit).max(Vec3A::ZERO),
                reflect: c(ctx, 1),
                transmit,
                ior: positive(ctx.scalar(node, 3)),
                ..Scatter::default()
            }
        }
        "dielectric_material_photon" => {
            let ior = positive(ctx.scalar(node, 1));
            let ior_out = positive(ctx.scalar(node, 3));
            let cos = (-ctx.state.dir.dot(ctx.state.normal)).clamp(0.0, 1.0);
            let eta = if ctx.state.inv_normal { ior_out / ior } else { ior / ior_out };
            let f = super::reflectance::fresnel(eta, cos.max(1e-6)).clamp(0.0, 1.0);
            Scatter {
                reflect: Vec3A::splat(f),
                transmit: Vec3A::splat(1.0 - f),
                ior: ior / ior_out,
                ..Scatter::default()
            }
        }
        "transmat_photon" => Scatter { pass: true, ..Scatter::default() },
        "dgs_material_photon" => {
            let t = ctx.scalar(node, 3).clamp(0.0, 1.0);
            Scatter {
                diffuse: c(ctx, 0) * (1.0 - t),
                reflect: (c(ctx, 1) + c(ctx, 2)) * (1.0 - t),
                transmit: Vec3A::splat(t),
                ior: positive(ctx.scalar(node, 4)),
                ..Scatter::default()
            }
        }
        "mia_material" | "mia_material_x" | "mia_material_x_passes" => crate::mia::photon::scatter(ctx, node),
        "mib_illum_lambert"
        | "mib_illum_phong"
        | "mib_illum_blinn"
        | "mib_illum_cooktorr"
        | "mib_illum_ward"
        | "mib_illum_ward_deriv" => Scatter { diffuse: c(ctx, 2), ..Scatter::default() },
        "mira_diffuse" => Scatter { diffuse: c(ctx, 0), ..Scatter::default() },
        "mib_dielectric" => {
            let amount = ctx.scalar(node, 2).clamp(0.0, 1.0);
            Scatter { transmit: Vec3A::splat(amount), ior: positive(ctx.scalar(node, 3)), ..Scatter::default() }
        }
        _ => Scatter::default(),
    }
}

/// An index of refraction: 1 where a parameter gives none.
fn positive(ior: f32) -> f32 {
    if ior > 0.0 && ior.is_finite() {
        ior
    } else {
        1.0
    }
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
