//! How much each layer of `mia_material` contributes: the reflectivity-versus-angle curve
//! and the energy conservation between the layers, exactly as the shader's author describes
//! them (`shared/seeds/mia_material-history.md`).
//!
//! Layers, top to bottom: reflection, diffuse, transparency (refraction), translucency.
//! With conservation on:
//!
//! ```text
//! orig_transl = luminance(transl)
//! diffuse *= 1 − luminance(refract)      transparency takes from diffuse
//! refract *= 1 − luminance(reflect)      reflection takes from everything below it
//! diffuse *= 1 − luminance(reflect)
//! transl  *= refract                     translucency is a share of the transparency
//! refract *= 1 − orig_transl
//! ```
//!
//! "Luminance" uses the Rec.709 weights of mira's working space, so a 100 % red reflection
//! takes 21.26 % from the layers below — not 100 % of their red, which would tint them cyan.
//! The author calls this "technically wrong": a coloured layer can leave a channel's total
//! above 1 (the red channel of a red mirror over a red diffuse). In metal mode the
//! reflection is tinted by the diffuse colour, but the conservation uses the untinted
//! reflection.

use glam::Vec3A;

use bsdf::color::luminance;

/// The reflectivity at an angle whose cosine with the normal is `cos_nv`: `brdf_fresnel`
/// gives the dielectric Fresnel reflectance of `ior`; otherwise the custom curve
/// R0 (1 − f) + R90 f with f = (1 − N·V)^curve.
pub fn brdf_curve(fresnel: bool, ior: f32, r0: f32, r90: f32, curve: f32, cos_nv: f32) -> f32 {
    let c = cos_nv.clamp(0.0, 1.0);
    if fresnel {
        // Unpolarised dielectric Fresnel reflectance from outside; an index of 1 reflects
        // nothing.
        bsdf::reflectance::fresnel(ior.max(1.0), c.max(1e-6))
    } else {
        let f = (1.0 - c).powf(curve);
        r0 * (1.0 - f) + r90 * f
    }
}

/// What the layers ask for, before conservation (colours as the parameters give them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayerInputs {
    /// `diffuse · diffuse_weight`.
    pub diffuse: Vec3A,
    /// `reflectivity · curve · refl_color` (untinted, even in metal mode).
    pub reflect: Vec3A,
    /// `transparency · refr_color`.
    pub refract: Vec3A,
    /// `refr_trans_color · refr_trans_weight` when translucency is on, else zero.
    pub transl: Vec3A,
    /// Metal mode: the reflection is tinted by this colour (the diffuse colour).
    pub metal_tint: Option<Vec3A>,
    /// `brdf_conserve_energy`.
    pub conserve: bool,
}

/// The absolute weight of each layer.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LayerWeights {
    /// Diffuse.
    pub diffuse: Vec3A,
    /// Reflection (and highlights).
    pub reflect: Vec3A,
    /// Transparency (refraction).
    pub refract: Vec3A,
    /// Translucency.
    pub transl: Vec3A,
}

/// Applies the author's energy conservation (see the module documentation).
pub fn conserve(i: &LayerInputs) -> LayerWeights {
    let mut diffuse = i.diffuse;
    let mut refract = i.refract;
    let mut transl = i.transl;
    let reflect = i.reflect;
    let orig_transl = luminance(transl);
    if i.conserve {
        diffuse *= 1.0 - luminance(refract);
        refract *= 1.0 - luminance(reflect);
        diffuse *= 1.0 - luminance(reflect);
    }
    // Translucency is a share of the transparency whether or not energy is conserved.
    transl *= refract;
    refract *= 1.0 - orig_transl;
    let reflect = match i.metal_tint {
        Some(tint) => reflect * tint,
        None => reflect,
    };
    LayerWeights { diffuse, reflect, refract, transl }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inputs() -> LayerInputs {
        LayerInputs {
            diffuse: Vec3A::splat(0.5),
            reflect: Vec3A::ZERO,
            refract: Vec3A::ZERO,
            transl: Vec3A::ZERO,
            metal_tint: None,
            conserve: true,
        }
    }

    #[test]
    fn default_curve_at_normal_incidence_is_0_12() {
        // reflectivity 0.6 × R0 0.2.
        let w = 0.6 * brdf_curve(false, 1.4, 0.2, 1.0, 5.0, 1.0);
        assert!((w - 0.12).abs() < 1e-5, "{w}");
        // Grazing: R90.
        assert!((brdf_curve(false, 1.4, 0.2, 1.0, 5.0, 0.0) - 1.0).abs() < 1e-6);
        // Half way in cosine: f = 0.5^5.
        let f = 0.5f32.powi(5);
        assert!((brdf_curve(false, 1.4, 0.2, 1.0, 5.0, 0.5) - (0.2 * (1.0 - f) + f)).abs() < 1e-6);
        // Fresnel mode at normal incidence: ((n − 1)/(n + 1))².
        assert!((brdf_curve(true, 1.5, 0.0, 0.0, 0.0, 1.0) - 0.04).abs() < 1e-5);
    }

    #[test]
    fn a_red_reflection_takes_its_luminance_from_every_channel_below() {
        let w = conserve(&LayerInputs { diffuse: Vec3A::ONE, reflect: Vec3A::X, ..inputs() });
        // 1 − 0.2126 in every channel: not 0 red, not cyan.
        assert!((w.diffuse - Vec3A::splat(1.0 - 0.2126)).abs().max_element() < 1e-5, "{}", w.diffuse);
        assert_eq!(w.reflect, Vec3A::X);
    }

    #[test]
    fn the_seeds_order_of_operations() {
        let i = LayerInputs {
            diffuse: Vec3A::new(0.8, 0.6, 0.4),
            reflect: Vec3A::splat(0.3),
            refract: Vec3A::splat(0.5),
            transl: Vec3A::splat(0.4),
            metal_tint: None,
            conserve: true,
        };
        let w = conserve(&i);
        // diffuse × (1 − 0.5) × (1 − 0.3); refract × (1 − 0.3) then × (1 − 0.4);
        // transl = 0.4 × refract after reflection (0.35).
        assert!((w.diffuse - i.diffuse * 0.5 * 0.7).abs().max_element() < 1e-6);
        assert!((w.refract - Vec3A::splat(0.5 * 0.7 * 0.6)).abs().max_element() < 1e-6);
        assert!((w.transl - Vec3A::splat(0.4 * 0.35)).abs().max_element() < 1e-6);
    }

    #[test]
    fn metal_mode_tints_the_reflection_but_conserves_with_the_untinted_one() {
        let tint = Vec3A::new(1.0, 0.5, 0.0);
        let plain = conserve(&LayerInputs { reflect: Vec3A::splat(0.5), ..inputs() });
        let metal = conserve(&LayerInputs { reflect: Vec3A::splat(0.5), metal_tint: Some(tint), ..inputs() });
        assert_eq!(plain.diffuse, metal.diffuse);
        assert_eq!(metal.reflect, Vec3A::splat(0.5) * tint);
    }

    #[test]
    fn conservation_off_leaves_the_layers_as_given() {
        let i = LayerInputs { reflect: Vec3A::splat(0.9), refract: Vec3A::splat(0.9), conserve: false, ..inputs() };
        let w = conserve(&i);
        assert_eq!(w.diffuse, i.diffuse);
        assert_eq!(w.refract, i.refract);
    }

    /// For grey reflection, transparency and translucency colours (any diffuse colour, any
    /// amounts in [0, 1]) the layers never sum above 1 in any channel. (Coloured ones can:
    /// that is the luminance rule the author describes.) Random parameters, fixed seed.
    #[test]
    fn grey_layers_never_sum_above_one() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut rnd = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        for _ in 0..100_000 {
            let i = LayerInputs {
                diffuse: Vec3A::new(rnd(), rnd(), rnd()),
                reflect: Vec3A::splat(rnd()),
                refract: Vec3A::splat(rnd()),
                transl: Vec3A::splat(rnd()),
                metal_tint: None,
                conserve: true,
            };
            let w = conserve(&i);
            let total = w.diffuse + w.reflect + w.refract + w.transl;
            assert!(total.max_element() <= 1.0 + 1e-5, "{i:?} → {total}");
        }
    }
}
