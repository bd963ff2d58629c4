//! `material::compile_shading`: a plug-in material shader no library implements renders as a
//! stand-in of its colour parameter, with a warning naming it at its line.

use shader::ShadingOptions;

#[test]
fn a_plug_in_material_gets_a_stand_in_of_its_colour_and_a_warning() {
    let text = r#"
declare shader struct { color "outColor" } "acmeSuperMtl" (color "diffuse_color", scalar "gloss") end declare
options "opt" end options
camera "cam" focal 1 aperture 1 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
shader "plug" "acmeSuperMtl" ("diffuse_color" 0.2 0.4 0.6, "gloss" 0.5)
material "m" = "plug" end material
object "tri" visible
    group 0 0 -1  1 0 -1  0 1 -1 v 0 v 1 v 2 p "m" 0 1 2 end group
end object
instance "tri_inst" "tri" end instance
instgroup "root" "cam_inst" "tri_inst" end instgroup
render "root" "cam_inst" "opt"
"#;
    let parsed = mi::parse_str("plug.mi", text);
    assert!(!parsed.diagnostics.has_errors());
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    let (shading, diags) = material::compile_shading(&scene, &ShadingOptions::default());
    let messages: Vec<String> = diags.iter().map(|d| d.render(&parsed.sources)).collect();
    let stand_in: Vec<_> = messages.iter().filter(|m| m.contains("acmeSuperMtl")).collect();
    assert_eq!(stand_in.len(), 1, "{messages:?}");
    assert!(stand_in[0].starts_with("plug.mi:6:"), "{stand_in:?}");
    assert!(stand_in[0].contains("diffuse surface of its 'diffuse_color'"), "{stand_in:?}");
    let surface = shading.materials[0].surface.expect("a surface shader");
    let node = &shading.graph.nodes[surface as usize];
    assert_eq!(node.imp.map(|i| i.name), Some("(stand-in)"));
    assert_eq!(node.slots.len(), 1);
    match &node.slots[0] {
        shader::Slot::Value(shader::Value::Color(c)) => {
            assert!((c.truncate() - glam::Vec3::new(0.2, 0.4, 0.6)).abs().max_element() < 1e-6, "{c}")
        }
        other => panic!("stand-in colour {other:?}"),
    }
}
