//! mental ray's base shader library (`base.mi`), and `physical_light` and
//! `physical_lens_dof` of the physics library, on mental ray's shader model (the `shader`
//! crate). The library plugs into the model as [`LIBRARY`].
//!
//! Each module holds a family; each shader is a [`ShaderImpl`] whose `params` list the
//! declared parameter names in the order its code indexes them. Formulas follow
//! `shared/spec/shaders.md` (paraphrased from mental images' sources and manual); where a
//! shader's behaviour is mira's reading of an unclear text, its doc comment says so.

pub mod bsdf_builtin;
pub mod bsdf_material;
pub mod color;
pub mod environment;
pub mod glossy;
pub mod illum;
pub mod lens;
pub mod light;
pub mod occlusion;
pub mod parti_volume;
pub mod photon;
pub mod procedural;
pub mod raytrace;
pub mod texture;
pub mod volume;

use shader::{Library, ShaderImpl};

/// The library as the shader model's registry sees it.
pub static LIBRARY: Library = Library { name: "base", shaders: SHADERS, declarations: &[] };

/// Every shader of the library.
pub static SHADERS: &[&ShaderImpl] = &[
    &illum::LAMBERT,
    &illum::PHONG,
    &illum::BLINN,
    &illum::COOKTORR,
    &illum::WARD,
    &illum::WARD_DERIV,
    &illum::HAIR,
    &illum::MIRA_DIFFUSE,
    &bsdf_material::MIRA_BSDF_MATERIAL,
    &raytrace::REFLECT,
    &raytrace::REFRACT,
    &raytrace::TRANSPARENCY,
    &raytrace::OPACITY,
    &raytrace::CONTINUE,
    &raytrace::DIELECTRIC,
    &raytrace::REFRACTION_INDEX,
    &raytrace::TWOSIDED,
    &glossy::GLOSSY_REFLECTION,
    &glossy::GLOSSY_REFRACTION,
    &bsdf_builtin::LAMBERT,
    &bsdf_builtin::PHONG,
    &bsdf_builtin::ASHIKHMIN,
    &bsdf_builtin::MIRROR,
    &bsdf_builtin::ARCHITECTURAL,
    &texture::LOOKUP,
    &texture::LOOKUP2,
    &texture::FILTER_LOOKUP,
    &texture::VECTOR,
    &texture::REMAP,
    &texture::ROTATE,
    &texture::BUMP_BASIS,
    &texture::BUMP_MAP,
    &texture::PASSTHROUGH_BUMP_MAP,
    &texture::BUMP_MAP2,
    &procedural::CHECKERBOARD,
    &procedural::POLKADOT,
    &procedural::POLKASPHERE,
    &procedural::TURBULENCE,
    &procedural::WAVE,
    &color::MIX,
    &color::ALPHA,
    &color::AVERAGE,
    &color::INTENSITY,
    &color::INTERPOLATE,
    &color::SPREAD,
    &color::CIE_D,
    &color::BLACKBODY,
    &light::POINT,
    &light::SPOT,
    &light::INFINITE,
    &light::PHOTOMETRIC,
    &light::SHADOW_TRANSPARENCY,
    &light::PHYSICAL,
    &environment::SPHERICAL,
    &environment::BACKGROUND,
    &environment::CUBE1,
    &environment::CUBE6,
    &environment::CYLINDRICAL,
    &occlusion::AMB_OCCLUSION,
    &occlusion::FAST_OCCLUSION,
    &lens::STENCIL,
    &lens::CLAMP,
    &lens::DOF,
    &volume::VOLUME,
    &volume::RAY_MARCHER,
    &parti_volume::PARTI_VOLUME,
    &photon::PHOTON_BASIC,
    &photon::DIELECTRIC_PHOTON,
    &photon::TRANSMAT_PHOTON,
    &photon::DGS_PHOTON,
];

pub(crate) use shader::{is_one, is_zero, rgb, rgba};

#[cfg(test)]
mod tests {
    use super::*;

    /// Every implementation's parameters are declared (with its name) in mira's built-in
    /// declarations: a misspelt name would silently read zero.
    #[test]
    fn implementations_match_their_declarations() {
        assert_eq!(LIBRARY.problems(), Vec::<String>::new());
    }
}
