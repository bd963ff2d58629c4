//! MDL functions of Iray `.mi` files (the `::base` module's texturing functions and its
//! `sun_and_sky` environment) as shader graph nodes, so that material parameters connected
//! to them are evaluated at each hit like mental ray shaders are.
//!
//! Their declarations ([`DECLARATIONS`]) are built in: a scene names them with or without
//! the MDL signature (`mdl::base::file_texture(texture_2d,color,…)`). MDL materials
//! themselves (`::nvidia::core_definitions`) are translated to BSDFs by
//! [`crate::material`], not run as nodes.

pub mod sky;
pub mod texture;

use crate::model::ShaderImpl;

/// The declarations of the MDL functions mira implements, in `.mi` syntax.
pub const DECLARATIONS: &str = include_str!("base.mi");

/// The MDL functions mira implements.
pub static REGISTRY: &[&ShaderImpl] = &[
    &texture::COORDINATE_SOURCE,
    &texture::TRANSFORM_COORDINATE,
    &texture::ROTATION_TRANSLATION_SCALE,
    &texture::FILE_TEXTURE,
    &texture::TANGENT_SPACE_NORMAL,
    &texture::FILE_BUMP,
    &texture::BLEND_COLOR_LAYERS,
    &texture::GLOSS_TO_ROUGH,
    &sky::SUN_AND_SKY,
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::decl::Decls;

    /// Every MDL function's parameters are declared with its name.
    #[test]
    fn implementations_match_their_declarations() {
        let decls = Decls::default();
        for imp in REGISTRY {
            let decl = decls.get(imp.name).unwrap_or_else(|| panic!("{} is not declared", imp.name));
            for p in imp.params {
                assert!(decl.param(p).is_some(), "{} has no parameter '{p}'", imp.name);
            }
        }
        let sig = decls.get("mdl::base::file_texture(texture_2d,color,color)").expect("found without signature");
        assert_eq!(sig.name, "mdl::base::file_texture");
    }
}
