//! rampShader's `ambientColor` a in both engines: the classic shader adds C_ref ⊙ a
//! (faded by 1 − T) whatever the lights, C_ref the colour ramp at 1 for the light-angle
//! input and at the facing ratio for the facing-angle input (`maya::ramp_shader`); the
//! path engine emits the same (`material::maya`'s rampShader translation).

use crate::support;
use crate::support::maya_view::{mean_and_error, pixels_warned};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 16;

/// A linear ramp of `name` through `points` (position, value).
fn ramp(name: &str, member: &str, points: &[(f32, &str)]) -> String {
    let items: Vec<String> = points
        .iter()
        .map(|(p, v)| format!(r#"{{ "{name}_Position" {p}, "{name}_{member}" {v}, "{name}_Interp" 1 }}"#))
        .collect();
    format!("[ {} ]", items.join(", "))
}

/// A rampShader plane tilted by 30° about x (facing ratios 0.45–0.99 over the image),
/// `ambientColor` 0.5 0.4 0.3, colour input `input`, colour ramp `color`, grey
/// transparency `t` (no refraction), `diffuse` 0.6, over nothing (black background);
/// `sun`: a unit directional light straight down.
fn scene(input: i32, color: &str, t: f32, sun: bool) -> String {
    let view = support::maya_view::top_down(SIDE);
    let a = 30f32.to_radians();
    let w = Vec3A::new(0.0, -a.sin(), a.cos()) * 50.0;
    let corner = |sx: f32, sw: f32| {
        let p = Vec3A::new(50.0 * sx, 0.0, 0.0) + w * sw;
        format!("{} {} {}", p.x, p.y, p.z)
    };
    let corners = [corner(1.5, -1.0), corner(-1.5, -1.0), corner(0.0, 1.0)].join("  ");
    let (light, light_inst) = if sun {
        (
            r#"light "sun" "maya_directionallight" ("intensity" 1) direction 0 -1 0 end light
instance "sun_inst" "sun" end instance"#,
            r#""sun_inst""#,
        )
    } else {
        ("", "")
    };
    format!(
        r#"
$include "mayabase.mi"
{view}
{light}
shader "mat" "maya_rampshader" ("colorInput" {input}, "diffuse" 0.6, "color" {color},
    "ambientColor" 0.5 0.4 0.3, "specularity" 0, "transparency" {transparency})
material "m" "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "plane" group {corners}  v 0 v 1 v 2 c "m" 0 1 2 end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" {light_inst} "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        transparency = ramp("transparency", "Color", &[(0.0, &format!("{t} {t} {t}"))]),
    )
}

/// Unlit: the light-angle input (C(1) ⊙ a), the facing-angle input with a colour ramp
/// from (0.2, 0.4, 0.8) at 0 to (0.8, 0.5, 0.2) at 1 (C(f) ⊙ a per ray) and a 40 %
/// transparent light-angle plane over black (0.6 · C(1) ⊙ a); lit by a unit sun
/// straight down with a constant colour ramp (C ⊙ (a + d cos θ)). The path engine's
/// image mean is the classic engine's within 2 % per channel (the classic engine's is
/// exact per ray; measured in the test's output). Before, the path engine left
/// `ambientColor` out (black unlit).
#[test]
fn ramp_shader_ambient_color_agrees_in_both_engines() {
    let varying = ramp("color", "Color", &[(0.0, "0.2 0.4 0.8"), (1.0, "0.8 0.5 0.2")]);
    let constant = ramp("color", "Color", &[(0.0, "0.8 0.5 0.2")]);
    let cases = [
        ("light angle", scene(0, &varying, 0.0, false)),
        ("facing angle", scene(1, &varying, 0.0, false)),
        ("transparent", scene(0, &varying, 0.4, false)),
        ("lit", scene(0, &constant, 0.0, true)),
    ];
    for (name, text) in cases {
        // The facing-angle input's albedo is taken at 1 (warned about; unlit here).
        let warned = |engine, spp| pixels_warned(&text, engine, spp, "indexed by FacingAngle");
        let (classic, _) = mean_and_error(&warned(EngineKind::Classic, 4));
        let (path, error) = mean_and_error(&warned(EngineKind::Path, 64));
        println!("{name}: classic {classic}, path {path} ± {error}");
        for k in 0..3 {
            assert!(classic[k] > 0.02, "{name}: classic {classic}");
            assert!((path[k] / classic[k] - 1.0).abs() < 0.02, "{name}: path {path} vs classic {classic}");
        }
    }
}
