//! MDL functions of Iray `.mi` files (the `::base` module's texturing functions and its
//! `sun_and_sky` and `perez_sun_and_sky` environments) as shader graph nodes, so that material parameters connected
//! to them are evaluated at each hit like mental ray shaders are.
//!
//! Their declarations ([`DECLARATIONS`]) are built in: a scene names them with or without
//! the MDL signature (`mdl::base::file_texture(texture_2d,color,…)`). MDL materials
//! themselves (`::nvidia::core_definitions`) are translated to BSDFs by the `material`
//! crate, not run as nodes. The library plugs into the shader model as [`LIBRARY`].

pub mod perez;
pub mod sky;
pub mod texture;

use shader::{Library, ShaderImpl};

/// The declarations of the MDL functions mira implements, in `.mi` syntax.
pub const DECLARATIONS: &str = include_str!("base.mi");

/// The library as the shader model's registry sees it.
pub static LIBRARY: Library = Library { name: "mdl", shaders: SHADERS, declarations: &[("mdl_base.mi", DECLARATIONS)] };

/// The MDL functions mira implements.
pub static SHADERS: &[&ShaderImpl] = &[
    &texture::COORDINATE_SOURCE,
    &texture::TRANSFORM_COORDINATE,
    &texture::ROTATION_TRANSLATION_SCALE,
    &texture::FILE_TEXTURE,
    &texture::TANGENT_SPACE_NORMAL,
    &texture::FILE_BUMP,
    &texture::BLEND_COLOR_LAYERS,
    &texture::GLOSS_TO_ROUGH,
    &sky::SUN_AND_SKY,
    &perez::PEREZ_SUN_AND_SKY,
];

#[cfg(test)]
mod tests {
    use super::*;
    use shader::Registry;

    /// Every implementation's parameters are declared (with its name) in mira's built-in
    /// declarations: a misspelt name would silently read zero.
    #[test]
    fn implementations_match_their_declarations() {
        assert_eq!(LIBRARY.problems(), Vec::<String>::new());
        let decls = Registry::new(&[&LIBRARY]).builtin_decls();
        let sig = decls.get("mdl::base::file_texture(texture_2d,color,color)").expect("found without signature");
        assert_eq!(sig.name, "mdl::base::file_texture");
    }
}
