//! Maya's ambient light in the path engine against the classic engine and against its
//! formula: a lambert of colour c receives c · C·I · ((1 − s) + s · cos θ) from an ambient
//! light of colour C, intensity I and `ambientShade` s (θ: from the normal to the
//! direction towards the light), not scaled by `diffuse`.

use crate::support;

use glam::Vec3A;
use render::{EngineKind, Settings};

/// A lambert plane (colour 0.6 0.5 0.4, diffuse 0.8) seen from 4 above at 16² pixels
/// (aperture 1.2: x and z in ±2.4), lit by an ambient light (colour 1 0.9 0.8, intensity
/// 0.5, `ambientShade` `shade`) 2 above the plane's centre, through `shader` (the Maya
/// 8.5–2015 or the 2016–2018 names).
fn ambient_lit_plane(shade: f32, light: &str, lambert: &str, engine: &str) -> String {
    let view = support::maya_view::top_down(16);
    format!(
        r#"
$include "mayabase.mi"
$include "AdskShaderSDK.mi"
{view}
light "amb" "{light}" ("color" 1 0.9 0.8, "intensity" 0.5, "ambientShade" {shade}) origin 0 0 0 end light
instance "amb_inst" "amb" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 -2 0 1 end instance
shader "lam" "{lambert}" ("color" 0.6 0.5 0.4, "diffuse" 0.8)
material "m" opaque "{engine}" ("surfaceShader" = "lam.outColor") end material
object "plane" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "amb_inst" "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

fn mean(px: &[[f32; 4]]) -> Vec3A {
    px.iter().map(|p| Vec3A::new(p[0], p[1], p[2])).sum::<Vec3A>() / px.len() as f32
}

/// Both name families, `ambientShade` 0 (uniform), the default 0.45 and 1 (all from the
/// light): the path engine's image mean is the classic engine's within 0.5 %, and both are
/// the formula's mean over the pixel centres within 1 % (the classic engine's samples lie
/// anywhere in their pixels).
#[test]
fn an_ambient_light_lights_a_lambert_alike_in_both_engines() {
    let families = [
        ("maya_ambientlight", "maya_lambert", "maya_shadingengine"),
        ("adskMayaAmbientLight", "adskMayaLambert", "adskMayaShadingEngine"),
    ];
    for (light, lambert, engine) in families {
        for shade in [0.0f32, 0.45, 1.0] {
            let text = ambient_lit_plane(shade, light, lambert, engine);
            let (scene, shading) = support::build_clean(&text);
            let world = render::World::from_scene_shaded(&scene, Some(&shading));
            assert!(world.warnings.is_empty(), "{:?}", world.warnings);
            assert_eq!((world.lights.len(), world.ambient.len()), (0, 1), "an ambient light, not a sampled one");
            let run = |engine, spp| {
                let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
                mean(&support::render_world(&world, &shading, &settings).0.rgba())
            };
            let (classic, path) = (run(EngineKind::Classic, 4), run(EngineKind::Path, 4));
            let mut want = Vec3A::ZERO;
            for row in 0..16 {
                for col in 0..16 {
                    let x = ((col as f32 + 0.5) / 16.0 - 0.5) * 4.8;
                    let z = ((row as f32 + 0.5) / 16.0 - 0.5) * 4.8;
                    let cos = 2.0 / (x * x + z * z + 4.0).sqrt();
                    want += Vec3A::new(0.6, 0.5, 0.4) * Vec3A::new(1.0, 0.9, 0.8) * 0.5 * ((1.0 - shade) + shade * cos);
                }
            }
            want /= 256.0;
            println!("{light}, ambientShade {shade}: formula {want}, classic {classic}, path {path}");
            for k in 0..3 {
                assert!((path[k] / classic[k] - 1.0).abs() < 5e-3, "{light} {shade}: path {path} vs classic {classic}");
                assert!((classic[k] / want[k] - 1.0).abs() < 0.01, "{light} {shade}: classic {classic} vs {want}");
            }
        }
    }
}

/// The plane of [`ambient_lit_plane`] (ambient light `ambientShade` 0.45, Maya 8.5–2015
/// names) with the material `top` that `materials` defines.
fn ambient_lit_material(materials: &str) -> String {
    ambient_lit_plane(0.45, "maya_ambientlight", "maya_lambert", "maya_shadingengine")
        .replace(r#"shader "lam" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 0.8)"#, materials)
        .replace("lam.outColor", "top.outColor")
}

/// rampShader and layeredShader under an ambient light alone: the classic rampShader adds
/// C(1) ⊙ ambient light (light-angle input; the facing-angle input C(f), here a one-key
/// ramp), whatever `diffuse` and `translucence`; the classic layeredShader composites its
/// layers' results, each adding its own ambient light as above. The path engine's image mean is the classic engine's within 1 % per channel
/// (without the translation's ambient factor: 0, a factor 1/(d + t) or a mix off).
#[test]
fn an_ambient_light_lights_ramp_and_layered_shaders_alike_in_both_engines() {
    let cases = [
        (
            "rampShader, light angle",
            r#"shader "top" "maya_rampshader" ("colorInput" 0, "diffuse" 0.6, "translucence" 0.2,
    "color" [ { "color_Position" 0, "color_Color" 0.1 0.1 0.1, "color_Interp" 1 },
              { "color_Position" 1, "color_Color" 0.8 0.6 0.4, "color_Interp" 1 } ])"#,
        ),
        (
            "rampShader, facing angle",
            r#"shader "top" "maya_rampshader" ("colorInput" 1, "diffuse" 0.5,
    "color" [ { "color_Position" 0.5, "color_Color" 0.3 0.6 0.9, "color_Interp" 1 } ])"#,
        ),
        (
            "layeredShader of two lamberts of different diffuse",
            r#"shader "a" "maya_lambert" ("color" 0.9 0.2 0.1, "diffuse" 0.8, "transparency" 0.6 0.6 0.6)
shader "b" "maya_lambert" ("color" 0.1 0.5 0.9, "diffuse" 0.5)
shader "top" "maya_layeredshader" ("inputs" [
    { "color" = "a.outColor", "transparency" = "a.outTransparency" },
    { "color" = "b.outColor", "transparency" = "b.outTransparency" } ])"#,
        ),
        (
            "layeredShader of a rampShader over a lambert",
            r#"shader "a" "maya_rampshader" ("colorInput" 0, "diffuse" 0.7, "transparency" [
    { "transparency_Position" 0, "transparency_Color" 0.5 0.5 0.5, "transparency_Interp" 1 } ],
    "color" [ { "color_Position" 1, "color_Color" 0.2 0.7 0.4, "color_Interp" 1 } ])
shader "b" "maya_lambert" ("color" 0.3 0.3 0.1, "diffuse" 0.9)
shader "top" "maya_layeredshader" ("inputs" [
    { "color" = "a.outColor", "transparency" = "a.outTransparency" },
    { "color" = "b.outColor", "transparency" = "b.outTransparency" } ])"#,
        ),
    ];
    for (what, materials) in cases {
        let (scene, shading) = support::build_clean(&ambient_lit_material(materials));
        let world = render::World::from_scene_shaded(&scene, Some(&shading));
        let run = |engine, spp| {
            let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
            mean(&support::render_world(&world, &shading, &settings).0.rgba())
        };
        let (classic, path) = (run(EngineKind::Classic, 4), run(EngineKind::Path, 4));
        println!("{what}: classic {classic}, path {path}, warnings {:?}", world.warnings);
        for k in 0..3 {
            assert!(classic[k] > 0.02, "{what}: classic {classic}");
            assert!((path[k] / classic[k] - 1.0).abs() < 0.01, "{what}: path {path} vs classic {classic}");
        }
    }
}
