//! A layeredShader whose rampShader layer's transparency follows the view, lit from
//! behind, in both engines: the classic stack composites its layers' light from behind
//! by their shares at the facing ratio of the ray that sees it, and the path engine
//! weights the layers' translucence lobes by the same shares at each hit's facing ratio
//! (`material::maya::StackTranslucence`).

use crate::support;
use crate::support::maya_view::{mean, pixels};

use glam::Vec3A;
use render::integrator::PathSettings;
use render::{EngineKind, Settings};

/// The image's side in pixels.
const SIDE: usize = 8;

/// The scene: the plane y = 0 (±50) of the stack — on top a rampShader (light-angle
/// input, colour (0.7, 0.5, 0.2), `translucence` 0.6, transparency ramp 0.9 at facing
/// ratio 0 to 0.2 at 0.75, linear), below it an opaque lambert (colour (0.2, 0.4, 0.9),
/// `translucence` 0.5, `translucenceFocus` 0: the layers share one lobe) — lit from straight below by a unit
/// directional light, seen from 4 away at `degrees` from the normal (focal 1, aperture
/// 1.2: the eye rays meet the plane at facing ratios from cos(degrees + 31°) to
/// cos(degrees − 31°)).
fn scene(degrees: f32) -> String {
    let (sin, cos) = degrees.to_radians().sin_cos();
    format!(
        r#"
$include "mayabase.mi"
options "opt" samples 0 2 filter box 1 1 end options
camera "cam" focal 1 aperture 1.2 aspect 1 resolution {SIDE} {SIDE} end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 {sin} {cos} 0  0 {mcos} {sin} 0  0 0 -4 1 end instance
light "l" "maya_directionallight" ("intensity" 1) direction 0 1 0 end light
instance "l_inst" "l" end instance
shader "a" "maya_rampshader" ("colorInput" 0, "diffuse" 0.8, "translucence" 0.6,
    "color" [ {{ "color_Position" 0, "color_Color" 0.7 0.5 0.2, "color_Interp" 1 }} ],
    "transparency" [ {{ "transparency_Position" 0, "transparency_Color" 0.9 0.9 0.9, "transparency_Interp" 1 }},
                     {{ "transparency_Position" 0.75, "transparency_Color" 0.2 0.2 0.2, "transparency_Interp" 1 }} ])
shader "b" "maya_lambert" ("color" 0.2 0.4 0.9, "diffuse" 0.8, "translucence" 0.5, "translucenceFocus" 0)
shader "mat" "maya_layeredshader" ("inputs" [
    {{ "color" = "a.outColor", "transparency" = "a.outTransparency" }},
    {{ "color" = "b.outColor", "transparency" = "b.outTransparency" }} ])
material "m" "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "plane" group -50 0 50  50 0 50  50 0 -50  -50 0 -50  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "l_inst" "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        mcos = -cos
    )
}

/// The path engine's pixels of `text` with `spp` samples per pixel and paths of one ray
/// (direct light, as the classic engine without final gathering), asserting the world
/// was built without a warning.
fn path_pixels(text: &str, spp: u32) -> Vec<Vec3A> {
    let (scene, shading) = support::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    let path = PathSettings { max_depth: 1, ..PathSettings::default() };
    let settings = Settings { engine: EngineKind::Path, spp: Some(spp), path, ..Settings::default() };
    support::render_world(&world, &shading, &settings).0.rgba().iter().map(|p| Vec3A::new(p[0], p[1], p[2])).collect()
}

/// [`scene`] seen at 0° (facing ratios 0.86 … 1, where the ramp layer's transparency is
/// 0.2 everywhere) and at 45° (0.24 … 0.97: 0.2 up to 0.74 of it): the path image mean
/// (16 samples per pixel) is the classic one's within 2 % per channel. The stack's colour
/// from behind, (1 − T(f)) · c_a · t_a + T(f) · c_b · t_b, shifts from the ramp
/// layer's orange towards the lambert's blue where f is low; the 45° classic image's blue
/// over red is at least 10 % above the 0° one's (the shares do change over the image).
#[test]
fn a_view_following_stack_passes_light_from_behind_by_its_shares_at_each_hit() {
    let mut ratios = Vec::new();
    for degrees in [0.0f32, 45.0] {
        let text = scene(degrees);
        let classic = mean(&pixels(&text, EngineKind::Classic, 4));
        let path = mean(&path_pixels(&text, 16));
        println!("view-following stack from behind, seen at {degrees}°: path {path} classic {classic}");
        for k in 0..3 {
            assert!((path[k] / classic[k] - 1.0).abs() < 0.02, "{degrees}°: path {path} vs classic {classic}");
        }
        ratios.push(classic.z / classic.x);
    }
    assert!(ratios[1] > ratios[0] * 1.1, "{ratios:?}");
}

/// The layers of [`many_parts_scene`]: a view-following rampShader on top (as in
/// [`scene`]), three rampShaders of differing colour ramps and five lamberts of
/// `translucenceFocus` 0, 0.2, 0.4, 0.6 and 0.8, each of transparency ½ but the last
/// (opaque): five distinct light-angle shapes (diffuse translucence counting as one) and
/// five distinct foci, more than a hit's BSDF holds of its own.
fn many_parts_layers() -> String {
    let mut text = String::from(
        r#"shader "l0" "maya_rampshader" ("colorInput" 0, "diffuse" 0.8, "translucence" 0.6,
    "color" [ { "color_Position" 0, "color_Color" 0.7 0.5 0.2, "color_Interp" 1 } ],
    "transparency" [ { "transparency_Position" 0, "transparency_Color" 0.9 0.9 0.9, "transparency_Interp" 1 },
                     { "transparency_Position" 0.75, "transparency_Color" 0.2 0.2 0.2, "transparency_Interp" 1 } ])
"#,
    );
    for i in 1..4 {
        let k = i as f32;
        let x = 0.1 + 0.1 * k;
        text += &format!(
            "shader \"l{i}\" \"maya_rampshader\" (\"colorInput\" 0, \"diffuse\" 0.8, \"translucence\" 0.6,\n\
             \"color\" [ {{ \"color_Position\" 0, \"color_Color\" 0.9 {g} 0.3, \"color_Interp\" 1 }},\n\
             {{ \"color_Position\" {x}, \"color_Color\" 0.1 0.7 {b}, \"color_Interp\" {interp} }},\n\
             {{ \"color_Position\" 0.8, \"color_Color\" 0.5 0.5 0.5, \"color_Interp\" 1 }} ],\n\
             \"transparency\" [ {{ \"transparency_Position\" 0, \"transparency_Color\" 0.5 0.5 0.5, \"transparency_Interp\" 1 }} ])\n",
            g = 0.2 + 0.2 * k,
            b = 0.2 + 0.2 * k,
            interp = i % 4,
        );
    }
    for (i, focus) in [0.0f32, 0.2, 0.4, 0.6, 0.8].iter().enumerate() {
        let k = i as f32;
        let tr = if i < 4 { 0.5 } else { 0.0 };
        text += &format!(
            "shader \"l{n}\" \"maya_lambert\" (\"color\" {r} {g} 0.6, \"diffuse\" 0.8, \"translucence\" 0.5, \
             \"translucenceFocus\" {focus}, \"transparency\" {tr} {tr} {tr})\n",
            n = i + 4,
            r = 0.2 + 0.15 * k,
            g = 0.8 - 0.1 * k,
        );
    }
    let inputs: Vec<String> = (0..9)
        .map(|i| format!("{{ \"color\" = \"l{i}.outColor\", \"transparency\" = \"l{i}.outTransparency\" }}"))
        .collect();
    text + &format!("shader \"mat\" \"maya_layeredshader\" (\"inputs\" [ {} ])\n", inputs.join(", "))
}

/// [`scene`] with the stack of [`many_parts_layers`].
fn many_parts_scene(degrees: f32) -> String {
    let text = scene(degrees);
    let start = text.find("shader \"a\"").expect("the layers");
    let end = text.find("material \"m\"").expect("the material");
    format!("{}{}{}", &text[..start], many_parts_layers(), &text[end..])
}

/// [`many_parts_scene`] (nine layers, five distinct light-angle shapes and five distinct
/// foci, the top layer's transparency following the view) lit from straight below, seen
/// at 0° and 45°: the path image mean (16 samples per pixel, no warning) is the classic
/// one's within 2 % per channel. Before, the path engine merged the parts past four at
/// each hit (a ramp into the largest one's, a focus into the nearest), warned.
#[test]
fn a_view_following_stack_of_many_ramps_and_foci_matches_the_classic_engine() {
    for degrees in [0.0f32, 45.0] {
        let text = many_parts_scene(degrees);
        let classic = mean(&pixels(&text, EngineKind::Classic, 4));
        let path = mean(&path_pixels(&text, 16));
        println!("a stack of many parts from behind, seen at {degrees}°: path {path} classic {classic}");
        for k in 0..3 {
            assert!((path[k] / classic[k] - 1.0).abs() < 0.02, "{degrees}°: path {path} vs classic {classic}");
        }
    }
}
