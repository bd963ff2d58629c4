//! Maya's samplerInfo at real hits of the classic engine: a 3 × 3 render of a plane
//! (y = 0 in world space) seen from 3 units above, each pixel showing one samplerInfo
//! member through a surfaceShader, against the closed forms of the scene's hand-written
//! matrices (1e-5):
//!
//! - the camera instance's world-to-camera matrix takes world (x, y, z) to
//!   (x − 0.5, 0.25 − z, y − 3) (the camera sits at (0.5, 3, 0.25) looking down −y);
//! - the plane instance's world-to-object matrix takes world (x, y, z) to
//!   (z + 1, y, 2 − x) (a quarter turn about y and a shift).

use std::sync::atomic::AtomicBool;

use shader::{Shading, ShadingOptions};

const SCENE: &str = r#"
$include "mayabase.mi"
options "opt" samples 0 0 filter box 1 1 end options
camera "cam" focal 1 aperture 0.5 aspect 1 resolution 3 3 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 0 1 0  0 -1 0 0  -0.5 0.25 -3 1 end instance
shader "si" "maya_samplerinfo" ()
{SHADERS}
shader "flat" "maya_surfaceshader" ("outColor" = "{SHOW}")
material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material
object "plane" group -20 0 20  20 0 20  20 0 -20  -20 0 -20  v 0 v 1 v 2 v 3 c "m" {ORDER} end group end object
instance "plane_inst" "plane" transform 0 0 -1 0  0 1 0 0  1 0 0 0  1 0 2 1 end instance
instgroup "root" "cam_inst" "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#;

/// Renders the plane (its polygon's vertex `order`) showing `show` (a shader output,
/// after the extra `shaders`): RGB per pixel, top row first.
fn render(show: &str, shaders: &str, order: &str) -> Vec<glam::Vec3> {
    let text = SCENE.replace("{SHOW}", show).replace("{SHADERS}", shaders).replace("{ORDER}", order);
    let parsed = mi::parse_str("sampler.mi", &text);
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    let (shading, _) = Shading::build(&scene, &ShadingOptions::default(), &material::registry());
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    let accel = render::accel::build(&world, render::Backend::Rust);
    let settings =
        render::Settings { engine: render::EngineKind::Classic, spp: Some(1), ..render::Settings::default() };
    let (film, _) = render::render(&world, accel.as_ref(), Some(&shading), &settings, &AtomicBool::new(false), &|_| {});
    assert_eq!((film.width, film.height), (3, 3));
    film.rgba().iter().map(|p| glam::Vec3::new(p[0], p[1], p[2])).collect()
}

/// Counter-clockwise seen from above (normal +y, towards the camera), and clockwise.
const FRONT: &str = "0 1 2 3";
const BACK: &str = "3 2 1 0";

fn close(got: glam::Vec3, want: glam::Vec3, what: &str) {
    assert!((got - want).abs().max_element() < 1e-5, "{what}: {got} vs {want}");
}

/// pointWorld lies on the plane (y = 0), the middle pixel's within the pixel's square
/// about the point straight below the camera, (0.5, 0, 0.25); pointCamera and pointObj are the hand-written matrices applied to
/// it at every pixel; normalCamera is +z (towards the camera) from either side.
#[test]
fn sampler_info_points_and_normal_follow_the_scene_matrices() {
    let world = render("si.pointWorld", "", FRONT);
    let camera = render("si.pointCamera", "", FRONT);
    let object = render("si.pointObj", "", FRONT);
    // The middle pixel's sample lies within its square on the ground (0.5 wide: the
    // image spans ±0.75 about the point below the camera at distance 3).
    let d = world[4] - glam::Vec3::new(0.5, 0.0, 0.25);
    assert!(d.x.abs() <= 0.25 && d.z.abs() <= 0.25, "middle pixel's pointWorld {}", world[4]);
    for i in 0..9 {
        let p = world[i];
        assert!(p.y.abs() < 1e-5, "pixel {i}: {p} off the plane");
        close(camera[i], glam::Vec3::new(p.x - 0.5, 0.25 - p.z, p.y - 3.0), &format!("pixel {i} pointCamera"));
        close(object[i], glam::Vec3::new(p.z + 1.0, p.y, 2.0 - p.x), &format!("pixel {i} pointObj"));
    }
    for order in [FRONT, BACK] {
        for (i, n) in render("si.normalCamera", "", order).into_iter().enumerate() {
            close(n, glam::Vec3::Z, &format!("pixel {i} normalCamera ({order})"));
        }
    }
}

/// flippedNormal is 0 where the camera sees the plane's front (its vertex order
/// counter-clockwise from above) and 1 where it sees its back, in every pixel (read
/// through a blendColors' blender: white when flipped, black when not).
#[test]
fn sampler_info_flipped_normal_is_set_on_the_back() {
    let shaders = r#"shader "b" "maya_blendcolors" ("blender" = "si.flippedNormal", "color1" 1 1 1, "color2" 0 0 0)"#;
    for (order, want) in [(FRONT, 0.0), (BACK, 1.0)] {
        for (i, c) in render("b.output", shaders, order).into_iter().enumerate() {
            close(c, glam::Vec3::splat(want), &format!("pixel {i} ({order})"));
        }
    }
}
