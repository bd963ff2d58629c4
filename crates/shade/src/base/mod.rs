//! mental ray's base shader library (`base.mi`), and `physical_light` and
//! `physical_lens_dof` of the physics library, on the shader model of [`crate::model`].
//!
//! Each module holds a family; each shader is a [`ShaderImpl`] whose `params` list the
//! declared parameter names in the order its code indexes them. Formulas follow
//! `shared/spec/shaders.md` (paraphrased from mental images' sources and manual); where a
//! shader's behaviour is mira's reading of an unclear text, its doc comment says so.

pub mod bsdf_builtin;
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
pub mod reflectance;
pub mod texture;
pub mod volume;

use glam::{Vec3A, Vec4};

use crate::model::{Color, ShaderImpl};

/// Every shader mira implements.
pub static REGISTRY: &[&ShaderImpl] = &[
    &illum::LAMBERT,
    &illum::PHONG,
    &illum::BLINN,
    &illum::COOKTORR,
    &illum::WARD,
    &illum::WARD_DERIV,
    &illum::HAIR,
    &illum::MIRA_DIFFUSE,
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
    &crate::mia::shader::MIA_MATERIAL,
    &crate::mia::shader::MIA_MATERIAL_X,
    &crate::mia::shader::MIA_MATERIAL_X_PASSES,
    &crate::mia::exposure::EXPOSURE_SIMPLE,
    &crate::mia::exposure::EXPOSURE_PHOTOGRAPHIC,
    &crate::mia::sky::MIA_PHYSICALSKY,
    &crate::mia::photometric::MIA_PHOTOMETRIC_LIGHT,
    &crate::mia::sun::MIA_PHYSICALSUN,
    &crate::mia::roundcorners::MIA_ROUNDCORNERS,
    &crate::mia::envblur::MIA_ENVBLUR,
    &crate::mia::bokeh::MIA_LENS_BOKEH,
    &crate::mia::comparison::LOBE_REFLECTION,
    &crate::mia::portal::PORTAL_LIGHT,
    &crate::mia::light_surface::LIGHT_SURFACE,
    &photon::PHOTON_BASIC,
    &photon::DIELECTRIC_PHOTON,
    &photon::TRANSMAT_PHOTON,
    &photon::DGS_PHOTON,
];

/// RGB of a colour.
#[inline]
pub(crate) fn rgb(c: Color) -> Vec3A {
    Vec3A::new(c.x, c.y, c.z)
}

/// A colour from RGB and alpha.
#[inline]
pub(crate) fn rgba(c: Vec3A, a: f32) -> Color {
    Vec4::new(c.x, c.y, c.z, a)
}

/// Whether all four components are zero.
#[inline]
pub(crate) fn is_zero(c: Color) -> bool {
    c == Vec4::ZERO
}

/// Whether all four components are one.
#[inline]
pub(crate) fn is_one(c: Color) -> bool {
    c == Vec4::ONE
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::decl::Decls;

    /// Every implementation's parameters are declared (with its name) in mira's built-in
    /// declarations: a misspelt name would silently read zero.
    #[test]
    fn implementations_match_their_declarations() {
        let decls = Decls::default();
        for imp in REGISTRY {
            let decl = decls.get(imp.name).unwrap_or_else(|| panic!("{} is not declared", imp.name));
            for p in imp.params {
                assert!(decl.param(p).is_some(), "{} has no parameter '{p}'", imp.name);
            }
        }
        let mut names: Vec<&str> = REGISTRY.iter().map(|s| s.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), REGISTRY.len(), "a shader is registered twice");
    }
}
