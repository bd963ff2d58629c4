//! `mia_material` as its own photon shader: a photon meets the same layers a ray does, with
//! the weights of [`super::weights`] at the photon's incidence angle. The diffuse layer
//! stores the photon and bounces it diffusely, reflection scatters it (glossy by
//! `refl_gloss`), transparency refracts it by `refr_ior` (straight through when thin
//! walled), translucency stores it and sends it on diffusely through the surface. A cut-out
//! lets the photon through unchanged by the transparent share.

use glam::Vec3A;

use super::params::{Mia, P};
use bsdf::mia::lobes::{anisotropic_shininess, base_shininess};
use shader::photon::Scatter;
use shader::{Ctx, NodeId};

/// The scattering of the `mia_material` node `n` at the state's hit.
pub fn scatter(ctx: &mut Ctx, n: NodeId) -> Scatter {
    let opacity = ctx.scalar(n, P::CutoutOpacity as usize).clamp(0.0, 1.0);
    if opacity <= 0.0 {
        return Scatter { pass: true, ..Scatter::default() };
    }
    let m = Mia::read(ctx, n);
    let cos_nv = (-ctx.state.dir.dot(ctx.state.normal)).clamp(0.0, 1.0);
    let inside = ctx.state.inv_normal && !m.thin_walled;
    let reflect = !(inside && ctx.bool(n, P::SkipInsideRefl as usize));
    let w = m.weights(cos_nv, reflect);
    let gloss = (m.refl_gloss < 1.0).then(|| anisotropic_shininess(base_shininess(m.refl_gloss), m.anisotropy));
    // A partial cut-out: the transparent share passes on unchanged; the shader's layers
    // take the opaque share (roulette over the sum keeps the expectation).
    let through = 1.0 - opacity;
    Scatter {
        diffuse: w.diffuse * opacity,
        reflect: w.reflect * opacity,
        gloss,
        transmit: w.refract * opacity + Vec3A::splat(through),
        translucent: w.transl * opacity,
        ior: if m.ior > 0.0 { m.ior } else { 1.0 },
        thin: m.thin_walled || through > 0.0 && w.refract == Vec3A::ZERO,
        pass: false,
    }
}
