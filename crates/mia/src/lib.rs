//! The Architectural library: `mia_material` (Arch & Design) and its helpers, and the
//! physical sun and sky, on mental ray's shader model (the `shader` crate). The library plugs
//! into the model as [`LIBRARY`]. Its scattering functions (`mia_material`'s BSDF and lobes)
//! live in the `bsdf` crate, the sun and sky model in the `sky` crate.

pub mod aerial;
pub mod bokeh;
pub mod comparison;
pub mod envblur;
pub mod exposure;
pub mod interpolate;
pub mod light_surface;
pub mod material;
pub mod params;
pub mod photometric;
pub mod photon;
pub mod portal;
pub mod roundcorners;
pub mod sky;
pub mod sun;
pub mod weights;

use shader::{Library, ShaderImpl};

/// The library as the shader model's registry sees it.
pub static LIBRARY: Library =
    Library { name: "architectural", shaders: SHADERS, declarations: &[("mira_architectural.mi", DECLARATIONS)] };

/// Every shader of the library.
pub static SHADERS: &[&ShaderImpl] = &[
    &material::MIA_MATERIAL,
    &material::MIA_MATERIAL_X,
    &material::MIA_MATERIAL_X_PASSES,
    &exposure::EXPOSURE_SIMPLE,
    &exposure::EXPOSURE_PHOTOGRAPHIC,
    &sky::MIA_PHYSICALSKY,
    &photometric::MIA_PHOTOMETRIC_LIGHT,
    &sun::MIA_PHYSICALSUN,
    &roundcorners::MIA_ROUNDCORNERS,
    &envblur::MIA_ENVBLUR,
    &bokeh::MIA_LENS_BOKEH,
    &comparison::LOBE_REFLECTION,
    &portal::PORTAL_LIGHT,
    &light_surface::LIGHT_SURFACE,
];

/// Declarations of mira's own shaders in this library (the architectural library's own
/// declarations are mental ray's `architectural.mi`, built into the `mi` crate).
const DECLARATIONS: &str = r#"
# Glossy reflection jittered around the mirror direction, to compare with mia_material's
# jittered normals.
declare shader color "mira_lobe_reflection" (color "input", color "reflect", scalar "gloss",
    integer "samples" default 16) end declare
"#;

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
