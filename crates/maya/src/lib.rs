//! Maya's shader libraries as mental ray for Maya exports call them: the `maya_*` names
//! (Maya 8.5–2015, `mayabase.mi`) and the `adskMaya*` names (Maya 2016–2018,
//! `AdskShaderSDK.mi`), on mental ray's shader model (the `shader` crate). The library plugs
//! into the model as [`LIBRARY`].
//!
//! Each family lives in its own module; every shader is a [`ShaderImpl`] whose `params`
//! list the declared parameter names (see `crates/mi/std/mayabase.mi`) in the order its
//! code reads them, registered once under each of its two names.
//!
//! Conventions (Maya's, which mental ray for Maya follows):
//! - colours are linear RGB; a light of colour c and intensity I delivers c·I, divided by
//!   d^decayRate at distance d (scene units), with no 1/π: a lambert of colour c and
//!   diffuse d under a directional light at angle θ gives c·d·I·cos θ;
//! - a material returns Maya's output struct (`outColor`, `outTransparency`,
//!   `outGlowColor`, `outMatteOpacity`); the shading engine turns it into the colour and
//!   alpha of the sample;
//! - angles are in radians (the unit Maya stores and exports).
//!
//! Modules: [`engine`] (shading engine, shadow shaders), [`volume`] (the shading
//! group's volume sampler), [`fog`] (envFog and lightFog as volume shaders; [`physical_fog`] envFog's physical
//! fog), [`volume_fog`] (volumeFog),
//! [`material`] and [`specular`] (lambert, blinn, phong, phongE, anisotropic,
//! surfaceShader), [`ramp_shader`]
//! (rampShader), [`layered_shader`] (layeredShader), [`matte`] (useBackground),
//! [`texture`], [`ramp_texture`], [`noise`] and [`layered`] (2D textures, place2dTexture, bump2d),
//! [`pattern_textures`] (bulge, cloth), [`height_textures`] (fractal, mountain, water),
//! [`texture3d`] (place3dTexture, solidFractal, marble, wood, bump3d), [`solid_textures`]
//! (snow, rock, volumeNoise), [`fractal_textures`] (brownian, cloud), [`crater_textures`]
//! (crater, stucco), [`cell_textures`] (leather, granite), [`projection`]
//! (projection, envSphere), [`utility`], [`vertex_data`] (UV and colour sets by name:
//! uvChooser, mentalrayVertexColors), [`light`] (point, spot, directional, ambient,
//! area, volume); outside the shader model: [`output`] (`maya_colormgt`'s view transform
//! for the image), [`glow`] (`maya_shaderglow`'s post pass on the image), [`standin`]
//! (the colour of an unknown plug-in shader). Their path-engine translation (materials
//! and lights) is in the `material` crate (`maya` module).
//!
//! [`REGISTRY`] lists every implementation.

pub mod billow;
pub mod cell_textures;
pub mod crater_textures;
pub mod displacement;
pub mod engine;
pub mod file_filter;
pub mod fog;
pub mod fractal_textures;
pub mod glow;
pub mod height_textures;
pub mod lattice_hash;
pub mod layered;
pub mod layered_shader;
pub mod light;
pub mod material;
pub mod matte;
pub mod noise;
pub mod output;
pub mod pattern_textures;
pub mod physical_fog;
pub mod projection;
pub mod ramp_shader;
pub mod ramp_texture;
pub mod solid_textures;
pub mod specular;
pub mod standin;
pub mod texture;
pub mod texture3d;
pub mod utility;
mod values;
pub mod vertex_data;
pub mod volume;
pub mod volume_fog;

use shader::{Library, ShaderImpl};

/// The library as the shader model's registry sees it (its declarations, `mayabase.mi` and
/// `AdskShaderSDK.mi`, are among the `mi` crate's standard files).
pub static LIBRARY: Library = Library { name: "maya", shaders: REGISTRY, declarations: &[] };

/// Declares a shader under its `maya_*` and `adskMaya*` names with one parameter list.
macro_rules! maya_shader {
    ($(#[$doc:meta])* $maya:ident, $adsk:ident, $maya_name:literal, $adsk_name:literal, $params:expr, $run:expr) => {
        $(#[$doc])*
        pub static $maya: shader::ShaderImpl =
            shader::ShaderImpl { name: $maya_name, params: $params, run: $run, ..shader::ShaderImpl::PLAIN };
        $(#[$doc])*
        pub static $adsk: shader::ShaderImpl =
            shader::ShaderImpl { name: $adsk_name, params: $params, run: $run, ..shader::ShaderImpl::PLAIN };
    };
}
pub(crate) use maya_shader;

/// Every shader this crate implements, under both name families.
pub static REGISTRY: &[&ShaderImpl] = &[
    &engine::SHADINGENGINE,
    &engine::ADSK_SHADINGENGINE,
    &engine::SHADOW,
    &engine::ADSK_SHADOW,
    &engine::TRANSPARENT,
    &engine::ADSK_TRANSPARENT,
    &engine::MATERIAL_DISPLACE,
    &engine::ADSK_MATERIAL_DISPLACE,
    &displacement::DISPLACE,
    &displacement::ADSK_DISPLACE,
    &volume::VOLUMESAMPLER,
    &volume::ADSK_VOLUMESAMPLER,
    &fog::ENVFOG,
    &fog::ADSK_ENVFOG,
    &fog::LIGHTFOG,
    &fog::ADSK_LIGHTFOG,
    &volume_fog::VOLUMEFOG,
    &volume_fog::ADSK_VOLUMEFOG,
    &material::LAMBERT,
    &material::ADSK_LAMBERT,
    &material::BLINN,
    &material::ADSK_BLINN,
    &material::PHONG,
    &material::ADSK_PHONG,
    &material::PHONGE,
    &material::ADSK_PHONGE,
    &material::ANISOTROPIC,
    &material::ADSK_ANISOTROPIC,
    &ramp_shader::RAMPSHADER,
    &ramp_shader::ADSK_RAMPSHADER,
    &layered_shader::LAYEREDSHADER,
    &layered_shader::ADSK_LAYEREDSHADER,
    &material::SURFACESHADER,
    &material::ADSK_SURFACESHADER,
    &matte::USEBACKGROUND,
    &matte::ADSK_USEBACKGROUND,
    &texture::PLACE2D,
    &texture::ADSK_PLACE2D,
    &texture::FILE,
    &texture::ADSK_FILE,
    &texture::CHECKER,
    &texture::ADSK_CHECKER,
    &texture::GRID,
    &texture::ADSK_GRID,
    &ramp_texture::RAMP,
    &ramp_texture::ADSK_RAMP,
    &layered::LAYEREDTEXTURE,
    &layered::ADSK_LAYEREDTEXTURE,
    &noise::NOISE,
    &noise::ADSK_NOISE,
    &pattern_textures::BULGE,
    &pattern_textures::ADSK_BULGE,
    &pattern_textures::CLOTH,
    &pattern_textures::ADSK_CLOTH,
    &height_textures::FRACTAL,
    &height_textures::ADSK_FRACTAL,
    &height_textures::MOUNTAIN,
    &height_textures::ADSK_MOUNTAIN,
    &height_textures::WATER,
    &height_textures::ADSK_WATER,
    &texture::BUMP2D,
    &texture::ADSK_BUMP2D,
    &texture3d::PLACE3D,
    &texture3d::ADSK_PLACE3D,
    &texture3d::SOLIDFRACTAL,
    &texture3d::ADSK_SOLIDFRACTAL,
    &texture3d::MARBLE,
    &texture3d::ADSK_MARBLE,
    &texture3d::WOOD,
    &texture3d::ADSK_WOOD,
    &texture3d::BUMP3D,
    &texture3d::ADSK_BUMP3D,
    &solid_textures::SNOW,
    &solid_textures::ADSK_SNOW,
    &solid_textures::ROCK,
    &solid_textures::ADSK_ROCK,
    &solid_textures::VOLUME_NOISE,
    &solid_textures::ADSK_VOLUME_NOISE,
    &fractal_textures::BROWNIAN,
    &fractal_textures::ADSK_BROWNIAN,
    &fractal_textures::CLOUD,
    &fractal_textures::ADSK_CLOUD,
    &crater_textures::CRATER,
    &crater_textures::ADSK_CRATER,
    &crater_textures::STUCCO,
    &crater_textures::ADSK_STUCCO,
    &cell_textures::LEATHER,
    &cell_textures::ADSK_LEATHER,
    &cell_textures::GRANITE,
    &cell_textures::ADSK_GRANITE,
    &projection::PROJECTION,
    &projection::ADSK_PROJECTION,
    &projection::ENVSPHERE,
    &projection::ADSK_ENVSPHERE,
    &utility::MULTIPLYDIVIDE,
    &utility::ADSK_MULTIPLYDIVIDE,
    &utility::PLUSMINUSAVERAGE,
    &utility::ADSK_PLUSMINUSAVERAGE,
    &utility::REVERSE,
    &utility::ADSK_REVERSE,
    &utility::BLENDCOLORS,
    &utility::ADSK_BLENDCOLORS,
    &utility::CONDITION,
    &utility::ADSK_CONDITION,
    &utility::CLAMP,
    &utility::ADSK_CLAMP,
    &utility::SETRANGE,
    &utility::ADSK_SETRANGE,
    &utility::REMAPVALUE,
    &utility::ADSK_REMAPVALUE,
    &utility::REMAPCOLOR,
    &utility::ADSK_REMAPCOLOR,
    &utility::LUMINANCE,
    &utility::ADSK_LUMINANCE,
    &utility::GAMMACORRECT,
    &utility::ADSK_GAMMACORRECT,
    &utility::CONTRAST,
    &utility::ADSK_CONTRAST,
    &utility::RGBTOHSV,
    &utility::ADSK_RGBTOHSV,
    &utility::HSVTORGB,
    &utility::ADSK_HSVTORGB,
    &utility::VECTORPRODUCT,
    &utility::ADSK_VECTORPRODUCT,
    &utility::SAMPLERINFO,
    &utility::ADSK_SAMPLERINFO,
    &vertex_data::UVCHOOSER,
    &vertex_data::ADSK_UVCHOOSER,
    &vertex_data::VERTEXCOLORS,
    &vertex_data::ADSK_VERTEXCOLORS,
    &light::POINT,
    &light::ADSK_POINT,
    &light::SPOT,
    &light::ADSK_SPOT,
    &light::DIRECTIONAL,
    &light::ADSK_DIRECTIONAL,
    &light::AMBIENT,
    &light::ADSK_AMBIENT,
    &light::AREA,
    &light::ADSK_AREA,
    &light::VOLUME,
    &light::ADSK_VOLUME,
];

#[cfg(test)]
mod tests {
    use super::*;
    use shader::decl::Decls;

    /// Every implementation's parameters are declared under its name in mira's built-in
    /// declarations (a misspelt name would silently read zero), and no name is registered
    /// twice.
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

    /// `mayabase.mi` and `AdskShaderSDK.mi` declare the same interfaces in the same
    /// order (parameters, types, defaults, results, apply lists): each declaration printed
    /// with its name blanked reads the same; the SDK's DAG traversal shader
    /// (`adskTraversal`, no `maya_*` twin) aside.
    #[test]
    fn both_declaration_files_declare_the_same_interfaces() {
        const SDK_ONLY: &[&str] = &["adskTraversal"];
        let decls = |file: &str| -> Vec<(String, String)> {
            let text = mi::stdlib::text(file).expect("built in");
            let parsed = mi::parse_str(file, text);
            assert!(!parsed.diagnostics.has_errors(), "{file}");
            parsed
                .items
                .into_iter()
                .filter_map(|item| {
                    // Shaders only: data blocks (the older exports' `maya_vertexdata`) have
                    // no adskMaya twin.
                    let mi::ast::Item::Declare(d) = &item else { return None };
                    if d.kind == mi::ast::DeclKind::Data {
                        return None;
                    }
                    let name = d.name.text.clone();
                    // The SDK's DAG traversal shader has no maya_* twin.
                    if SDK_ONLY.contains(&name.as_str()) {
                        return None;
                    }
                    let printed = String::from_utf8(mi::print(std::slice::from_ref(&item))).expect("utf-8");
                    Some((name.clone(), printed.replace(&format!("\"{name}\""), "\"X\"")))
                })
                .collect()
        };
        let (maya, adsk) = (decls("mayabase.mi"), decls("AdskShaderSDK.mi"));
        assert_eq!(maya.len(), adsk.len());
        assert!(maya.len() >= 40);
        for ((m, mt), (a, at)) in maya.iter().zip(&adsk) {
            assert!(m.starts_with("maya_") && a.starts_with("adsk"), "{m} / {a}");
            assert!(mt.contains("\"X\" ("), "{m} printed as {mt}");
            assert_eq!(mt, at, "{m} and {a} differ");
        }
    }

    /// The AdskShaderSDK's DAG traversal shader is declared as its header
    /// (`adskTraversal.h`, struct `adskInstanceParameters`) gives it: one parameter,
    /// `passEncoding`, a tag (declared as a data element's), no result type, no apply.
    #[test]
    fn the_sdk_traversal_shader_is_declared_as_its_header_gives_it() {
        let text = mi::stdlib::text("AdskShaderSDK.mi").expect("built in");
        let parsed = mi::parse_str("AdskShaderSDK.mi", text);
        let decl = parsed
            .items
            .iter()
            .find_map(|item| match item {
                mi::ast::Item::Declare(d) if d.name.text == "adskTraversal" => Some(d),
                _ => None,
            })
            .expect("declared");
        let params: Vec<(&str, mi::ast::ParamType)> =
            decl.params.iter().map(|p| (p.name.text.as_str(), p.ty.clone())).collect();
        assert_eq!(params, vec![("passEncoding", mi::ast::ParamType::Data)]);
        assert!(decl.ret.is_none() && decl.body.is_empty(), "{:?} {:?}", decl.ret, decl.body);
    }

    /// Both families are registered: every maya_* implementation has an adskMaya* twin
    /// with the same parameter list.
    #[test]
    fn both_name_families_are_registered() {
        for pair in REGISTRY.chunks(2) {
            let (m, a) = (pair[0], pair[1]);
            assert!(m.name.starts_with("maya_") && a.name.starts_with("adsk"), "{} / {}", m.name, a.name);
            assert_eq!(m.params, a.params, "{}", m.name);
            assert!(std::ptr::fn_addr_eq(m.run, a.run), "{}", m.name);
        }
    }
}
