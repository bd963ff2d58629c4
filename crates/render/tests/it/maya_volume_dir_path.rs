//! Maya volume lights' `volumeLightDir` in the path engine against the classic engine and
//! the formula: inward (1), the light arrives from the side away from the light's centre;
//! down the axis (2), from the light's +y axis as from a directional light.

use crate::support;

use render::{EngineKind, Settings};

/// The image's side in pixels.
const SIDE: usize = 16;

/// A lambert ground (colour 0.6 0.5 0.4, diffuse 0.8) seen from 4 above at `SIDE`² pixels
/// (x and z in ±2.4), lit by a volume light (intensity 0.7, no raytraced shadows) of shape
/// `shape`, `volumeLightDir` `dir`, placed by `placement` (an instance transform).
fn ground(shape: i32, dir: i32, placement: &str) -> String {
    ground_with(shape, dir, placement, "")
}

/// [`ground`] with more volume light parameters `more` (", name value" pairs).
fn ground_with(shape: i32, dir: i32, placement: &str, more: &str) -> String {
    let view = support::maya_view::top_down(SIDE);
    format!(
        r#"
$include "mayabase.mi"
{view}
light "vol" "maya_volumelight" ("intensity" 0.7, "lightShape" {shape}, "volumeLightDir" {dir}{more}) origin 0 0 0 end light
instance "vol_inst" "vol" transform {placement} end instance
shader "lam" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 0.8)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
object "ground" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
instgroup "root" "cam_inst" "vol_inst" "ground_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The image mean (rgb) by `engine`.
fn mean(text: &str, engine: EngineKind) -> [f32; 3] {
    let (scene, shading) = support::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    let ambient = text.contains("emitAmbient");
    assert_eq!((world.lights.len(), world.ambient.len()), if ambient { (0, 1) } else { (1, 0) });
    let settings = Settings { engine, spp: Some(4), ..Settings::default() };
    let px = support::render_world(&world, &shading, &settings).0.rgba();
    let mut m = [0.0f32; 3];
    for p in &px {
        for k in 0..3 {
            m[k] += p[k] / px.len() as f32;
        }
    }
    m
}

/// `cos` at each pixel centre's ground point (x, z), averaged, times the lambert's
/// c·d·I.
fn formula(cos: impl Fn(f32, f32) -> f32) -> [f32; 3] {
    scaled_formula(cos, 0.8 * 0.7)
}

/// `f` at each pixel centre's ground point (x, z), averaged, times the lambert's colour
/// and `scale`.
fn scaled_formula(f: impl Fn(f32, f32) -> f32, scale: f32) -> [f32; 3] {
    let mut sum = 0.0;
    for row in 0..SIDE {
        for col in 0..SIDE {
            let x = ((col as f32 + 0.5) / SIDE as f32 - 0.5) * 4.8;
            let z = ((row as f32 + 0.5) / SIDE as f32 - 0.5) * 4.8;
            sum += f(x, z).max(0.0);
        }
    }
    let k = sum / (SIDE * SIDE) as f32 * scale;
    [0.6 * k, 0.5 * k, 0.4 * k]
}

/// A sphere volume light of radius 4 centred 1 below the ground, inward: the ground is lit
/// as by a light 1 above each point's mirror image, cos θ = 1/√(x² + z² + 1) (outward it
/// would be dark: the light's centre lies below). A box of half-size 10 turned 45° about
/// z, down its axis: lit from (−√½, √½, 0), cos 45° everywhere. Both engines' image means
/// within 1 % of each other and of the formula.
#[test]
fn inward_and_down_axis_volume_lights_shade_alike_in_both_engines() {
    let c = std::f32::consts::FRAC_1_SQRT_2 * 0.1;
    let cases = [
        (
            "inward sphere",
            ground(1, 1, "0.25 0 0 0  0 0.25 0 0  0 0 0.25 0  0 0.25 0 1"),
            formula(|x, z| 1.0 / (x * x + z * z + 1.0).sqrt()),
        ),
        (
            "down-axis box",
            ground(0, 2, &format!("{c} {} 0 0  {c} {c} 0 0  0 0 0.1 0  0 0 0 1", -c)),
            formula(|_, _| std::f32::consts::FRAC_1_SQRT_2),
        ),
    ];
    for (name, text, want) in cases {
        let classic = mean(&text, EngineKind::Classic);
        let path = mean(&text, EngineKind::Path);
        println!("{name}: formula {want:?}, classic {classic:?}, path {path:?}");
        for k in 0..3 {
            assert!((path[k] / classic[k] - 1.0).abs() < 0.01, "{name}: path {path:?} vs classic {classic:?}");
            assert!((classic[k] / want[k] - 1.0).abs() < 0.01, "{name}: classic {classic:?} vs formula {want:?}");
        }
    }
    // Outward, the sphere below the ground leaves it dark in both engines.
    let outward = ground(1, 0, "0.25 0 0 0  0 0.25 0 0  0 0 0.25 0  0 0.25 0 1");
    for engine in [EngineKind::Classic, EngineKind::Path] {
        let m = mean(&outward, engine);
        assert!(m.iter().all(|v| *v < 1e-4), "outward {engine:?}: {m:?}");
    }
}

/// A sphere volume light of radius 4 centred 1 above the ground with `emitAmbient`
/// (`emitSpecular` off): it lights as Maya's ambient light, c·C·I·((1 − s) + s·cos θ)
/// (not × `diffuse`), s = ½ with `emitDiffuse` on and 0 with it off; inward, θ from the
/// reversed direction (cos 0 on the ground: the uniform half only). Both engines' image
/// means within 1 % of each other and of the formula.
#[test]
fn a_volume_light_with_emit_ambient_lights_as_the_ambient_light_in_both_engines() {
    let above = "0.25 0 0 0  0 0.25 0 0  0 0 0.25 0  0 -0.25 0 1";
    let cos = |x: f32, z: f32| 1.0 / (x * x + z * z + 1.0).sqrt();
    let cases = [
        (
            "emitDiffuse on",
            0,
            r#", "emitAmbient" on, "emitSpecular" off"#,
            scaled_formula(|x, z| 0.5 + 0.5 * cos(x, z), 0.7),
        ),
        (
            "emitDiffuse off",
            0,
            r#", "emitAmbient" on, "emitSpecular" off, "emitDiffuse" off"#,
            scaled_formula(|_, _| 1.0, 0.7),
        ),
        ("inward", 1, r#", "emitAmbient" on, "emitSpecular" off"#, scaled_formula(|_, _| 0.5, 0.7)),
    ];
    for (name, dir, more, want) in cases {
        let text = ground_with(1, dir, above, more);
        let classic = mean(&text, EngineKind::Classic);
        let path = mean(&text, EngineKind::Path);
        println!("{name}: formula {want:?}, classic {classic:?}, path {path:?}");
        for k in 0..3 {
            assert!((path[k] / classic[k] - 1.0).abs() < 0.01, "{name}: path {path:?} vs classic {classic:?}");
            assert!((classic[k] / want[k] - 1.0).abs() < 0.01, "{name}: classic {classic:?} vs formula {want:?}");
        }
    }
}
