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
//! (the `mia` library). A material without a photon shader is read from its material
//! shader (mental ray would absorb the photon there; exporters normally set the photon
//! slot to the same shader): `mia_material`, the `mib_illum_*` shaders and mira's
//! Lambertian stand-in by their diffuse colour, `mib_dielectric` as clear glass of its
//! `ior`. Other shaders absorb photons.

use glam::Vec3A;

use super::rgb;
use shader::photon::Scatter;
use shader::{Ctx, NodeId, ShaderImpl, Value};

/// `mib_photon_basic (color diffuse, color specular, color transp, scalar ior_frac)`.
pub static PHOTON_BASIC: ShaderImpl = ShaderImpl {
    name: "mib_photon_basic",
    params: &["diffuse", "specular", "transp", "ior_frac"],
    run: photon_only,
    photon: Some(basic),
    ..ShaderImpl::PLAIN
};

/// `dielectric_material_photon (color col, scalar ior, color col_out, scalar ior_out, …)`.
pub static DIELECTRIC_PHOTON: ShaderImpl = ShaderImpl {
    name: "dielectric_material_photon",
    params: &["col", "ior", "col_out", "ior_out"],
    run: photon_only,
    photon: Some(dielectric),
    ..ShaderImpl::PLAIN
};

/// `transmat_photon ()`.
pub static TRANSMAT_PHOTON: ShaderImpl =
    ShaderImpl { name: "transmat_photon", params: &[], run: photon_only, photon: Some(transmat), ..ShaderImpl::PLAIN };

/// `dgs_material_photon (color diffuse, color glossy, color specular, …, scalar transp,
/// scalar ior)`.
pub static DGS_PHOTON: ShaderImpl = ShaderImpl {
    name: "dgs_material_photon",
    params: &["diffuse", "glossy", "specular", "transp", "ior"],
    run: photon_only,
    photon: Some(dgs),
    ..ShaderImpl::PLAIN
};

/// A photon shader called on an eye or secondary ray: it contributes nothing (mental ray
/// runs photon shaders only while tracing photons).
fn photon_only(_: &mut Ctx, _: NodeId, _: &mut Value) -> bool {
    false
}

/// A colour parameter as a reflectance (negative channels clamped).
fn reflectance(ctx: &mut Ctx, node: NodeId, i: usize) -> Vec3A {
    rgb(ctx.color(node, i)).max(Vec3A::ZERO)
}

/// `mib_photon_basic`: diffuse (less what is transmitted), specular reflection,
/// transmission by `ior_frac`.
fn basic(ctx: &mut Ctx, node: NodeId) -> Scatter {
    let transmit = reflectance(ctx, node, 2);
    Scatter {
        diffuse: reflectance(ctx, node, 0) * (Vec3A::ONE - transmit).max(Vec3A::ZERO),
        reflect: reflectance(ctx, node, 1),
        transmit,
        ior: positive(ctx.scalar(node, 3)),
        ..Scatter::default()
    }
}

/// `dielectric_material_photon`: Fresnel-weighted reflection and refraction.
fn dielectric(ctx: &mut Ctx, node: NodeId) -> Scatter {
    let ior = positive(ctx.scalar(node, 1));
    let ior_out = positive(ctx.scalar(node, 3));
    let cos = (-ctx.state.dir.dot(ctx.state.normal)).clamp(0.0, 1.0);
    let eta = if ctx.state.inv_normal { ior_out / ior } else { ior / ior_out };
    let f = bsdf::reflectance::fresnel(eta, cos.max(1e-6)).clamp(0.0, 1.0);
    Scatter { reflect: Vec3A::splat(f), transmit: Vec3A::splat(1.0 - f), ior: ior / ior_out, ..Scatter::default() }
}

/// `transmat_photon`: the photon goes on unchanged.
fn transmat(_: &mut Ctx, _: NodeId) -> Scatter {
    Scatter { pass: true, ..Scatter::default() }
}

/// `dgs_material_photon`: diffuse, glossy as specular, specular, transparency with `ior`.
fn dgs(ctx: &mut Ctx, node: NodeId) -> Scatter {
    let t = ctx.scalar(node, 3).clamp(0.0, 1.0);
    Scatter {
        diffuse: reflectance(ctx, node, 0) * (1.0 - t),
        reflect: (reflectance(ctx, node, 1) + reflectance(ctx, node, 2)) * (1.0 - t),
        transmit: Vec3A::splat(t),
        ior: positive(ctx.scalar(node, 4)),
        ..Scatter::default()
    }
}

/// The `mib_illum_*` shaders as material shaders without a photon shader: their `diffuse`
/// colour (parameter 2).
pub fn illum_diffuse(ctx: &mut Ctx, node: NodeId) -> Scatter {
    Scatter { diffuse: reflectance(ctx, node, 2), ..Scatter::default() }
}

/// mira's Lambertian stand-in (`mira_diffuse`): its `diffuse` colour (parameter 0).
pub fn stand_in_diffuse(ctx: &mut Ctx, node: NodeId) -> Scatter {
    Scatter { diffuse: reflectance(ctx, node, 0), ..Scatter::default() }
}

/// `mib_dielectric` as a material shader without a photon shader: clear glass of its `ior`.
pub fn dielectric_glass(ctx: &mut Ctx, node: NodeId) -> Scatter {
    let amount = ctx.scalar(node, 2).clamp(0.0, 1.0);
    Scatter { transmit: Vec3A::splat(amount), ior: positive(ctx.scalar(node, 3)), ..Scatter::default() }
}

/// An index of refraction: 1 where a parameter gives none.
fn positive(ior: f32) -> f32 {
    if ior > 0.0 && ior.is_finite() {
        ior
    } else {
        1.0
    }
}
