//! The stand-in warning of a plug-in shader behind a Maya shading engine names the `.mi`
//! line of the shader statement (file:line:column as mira reports every diagnostic), as
//! does that of a plug-in shader used as a material's shader, under both engine names.

use shader::ShadingOptions;

/// The 1-based line of `text` that contains `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).expect("the line is in the text") + 1
}

#[test]
fn the_stand_in_warning_names_the_shader_line() {
    for engine in ["maya_shadingengine", "adskMayaShadingEngine"] {
        let text = format!(
            r#"$include "mayabase.mi"
$include "AdskShaderSDK.mi"
declare shader struct {{ color "outColor", color "outTransparency" }} "vendorMaterial" (
    scalar "rough", color "baseColor") end declare
declare shader color "vendor_mtl" (color "Diffuse_Color", scalar "gloss") end declare
options "opt" end options
camera "cam" focal 1 aperture 1 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance

shader "vm"
    "vendorMaterial" ("baseColor" 0.8 0.2 0.1, "rough" 0.3)
material "m" opaque "{engine}" ("surfaceShader" = "vm.outColor") end material
material "v" opaque
    "vendor_mtl" ("Diffuse_Color" 0.1 0.5 0.3) end material
object "tri" visible
    group 0 0 -1  1 0 -1  0 1 -1 v 0 v 1 v 2 p "m" 0 1 2 end group
end object
object "tri2" visible
    group 0 0 -2  1 0 -2  0 1 -2 v 0 v 1 v 2 p "v" 0 1 2 end group
end object
instance "tri_inst" "tri" end instance
instance "tri2_inst" "tri2" end instance
instgroup "root" "cam_inst" "tri_inst" "tri2_inst" end instgroup
render "root" "cam_inst" "opt"
"#
        );
        let parsed = mi::parse_str("vendor.mi", &text);
        assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
        let mut diags = Vec::new();
        let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
        let (_, diags) = material::compile_shading(&scene, &ShadingOptions::default());
        let messages: Vec<String> = diags.iter().map(|d| d.render(&parsed.sources)).collect();
        for (shader, param, needle) in [
            ("'vendorMaterial'", "'baseColor'", r#""vendorMaterial" ("baseColor""#),
            ("'vendor_mtl'", "'Diffuse_Color'", r#""vendor_mtl" ("Diffuse_Color""#),
        ] {
            let found: Vec<&String> = messages.iter().filter(|m| m.contains(shader)).collect();
            assert_eq!(found.len(), 1, "{engine}: {messages:?}");
            let at = format!("vendor.mi:{}:", line_of(&text, needle));
            assert!(found[0].starts_with(&at) && found[0].contains(param), "{engine}: {found:?}, want {at}");
        }
    }
}
