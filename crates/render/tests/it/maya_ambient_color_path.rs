//! A Maya material's `ambientColor` a in both engines against its closed form: the
//! classic lambert adds c ⊙ a whatever the lights, and the path engine's translation
//! emits the same c ⊙ a (constant or connected colour), so an unlit lambert of colour c
//! shows c ⊙ a and one under a unit directional light straight above c ⊙ (a + d).

use crate::support;

use glam::Vec3A;
use render::{EngineKind, Settings};

/// A lambert plane (`color` 0.6 0.5 0.4 — or a checker of those two colours when
/// `checker` — `diffuse` 0.6, `ambientColor` 0.2 0.2 0.1) seen from above at 16² pixels,
/// with `lights` (a light and its instance, or nothing).
fn plane(lights: &str, checker: bool) -> String {
    let view = support::maya_view::top_down(16);
    let (colour_shader, colour) = if checker {
        (r#"shader "tex" "maya_checker" ("color1" 0.6 0.5 0.4, "color2" 0.6 0.5 0.4)"#, r#""color" = "tex.outColor""#)
    } else {
        ("", r#""color" 0.6 0.5 0.4"#)
    };
    let light_inst = if lights.is_empty() { "" } else { r#""sun_inst""# };
    format!(
        r#"
$include "mayabase.mi"
{view}
{lights}
{colour_shader}
shader "lam" "maya_lambert" ({colour}, "diffuse" 0.6, "ambientColor" 0.2 0.2 0.1)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
object "plane" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" {light_inst} "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Unlit: c ⊙ a = (0.12, 0.1, 0.04); under a unit sun straight down: c ⊙ (a + d) = (0.48,
/// 0.4, 0.28). Classic: every pixel within 1e-4. Path: the image mean within 4 σ + 1e-3
/// (σ the standard error of the pixels' mean), for a constant and a connected colour.
#[test]
fn ambient_color_adds_the_colour_times_itself_in_both_engines() {
    let sun = r#"light "sun" "maya_directionallight" ("intensity" 1) direction 0 -1 0 end light
instance "sun_inst" "sun" end instance"#;
    for checker in [false, true] {
        for (lights, want) in [("", Vec3A::new(0.12, 0.1, 0.04)), (sun, Vec3A::new(0.48, 0.4, 0.28))] {
            let (scene, shading) = support::build_clean(&plane(lights, checker));
            let world = render::World::from_scene_shaded(&scene, Some(&shading));
            assert!(world.warnings.is_empty(), "{:?}", world.warnings);
            let run = |engine, spp| {
                let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
                support::render_world(&world, &shading, &settings).0.rgba()
            };
            let classic = run(EngineKind::Classic, 4);
            for p in &classic {
                let got = Vec3A::new(p[0], p[1], p[2]);
                assert!((got - want).abs().max_element() < 1e-4, "classic (checker {checker}): {got} vs {want}");
            }
            let path = run(EngineKind::Path, 16);
            let n = path.len() as f32;
            let px: Vec<Vec3A> = path.iter().map(|p| Vec3A::new(p[0], p[1], p[2])).collect();
            let mean = px.iter().sum::<Vec3A>() / n;
            let var = px.iter().map(|p| (*p - mean) * (*p - mean)).sum::<Vec3A>() / (n - 1.0);
            let sigma = (var / n).powf(0.5);
            println!("checker {checker}, lit {}: path {mean} ± {sigma}, want {want}", !lights.is_empty());
            for k in 0..3 {
                assert!(
                    (mean[k] - want[k]).abs() < 4.0 * sigma[k] + 1e-3,
                    "path (checker {checker}): {mean} ± {sigma} vs {want}"
                );
            }
        }
    }
}
