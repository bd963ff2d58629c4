//! Shadow linking (an instance's `light shadow ["exclusive"] [ … ]` list, which mental ray
//! for Maya writes for Maya's shadow links: "selected objects only cast shadows from light
//! sources with which they are linked") in both engines: a board above the camera covers
//! the left half of a lambert ground from two directional lights straight down; the board
//! casts shadows only for the lights its list lets it.

use crate::support;

use render::{EngineKind, Settings};

/// The image's side in pixels.
const SIDE: usize = 16;

/// The ground (lambert colour 0.6 0.5 0.4, diffuse 0.8) seen from 4 above under "sun_a"
/// (intensity 0.3) and "sun_b" (0.5), both straight down with raytraced shadows; a board
/// at y = 6 (behind the camera, which looks down) over x < 0 with the instance statements
/// `link`.
fn scene(link: &str) -> String {
    let view = support::maya_view::top_down(SIDE);
    format!(
        r#"
$include "mayabase.mi"
{view}
light "sun_a" "maya_directionallight" ("intensity" 0.3, "useRayTraceShadows" on) direction 0 -1 0 end light
instance "sun_a_inst" "sun_a" end instance
light "sun_b" "maya_directionallight" ("intensity" 0.5, "useRayTraceShadows" on) direction 0 -1 0 end light
instance "sun_b_inst" "sun_b" end instance
shader "lam" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 0.8)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor")
    shadow "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
object "ground" group -6 0 6  6 0 6  6 0 -6  -6 0 -6  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
object "board" group -8 6 8  0 6 8  0 6 -8  -8 6 -8  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "board_inst" "board" {link} end instance
instgroup "root" "cam_inst" "sun_a_inst" "sun_b_inst" "ground_inst" "board_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The mean red of the left columns (x < −0.6) and the right columns (x > 0.6) by `engine`.
fn halves(text: &str, engine: EngineKind) -> (f32, f32) {
    let (scene, shading) = support::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    // Direct light only (the path engine's bounces off the board would add to it).
    let path = render::integrator::PathSettings { max_depth: 1, ..Default::default() };
    let settings = Settings { engine, spp: Some(2), path, ..Settings::default() };
    let px = support::render_world(&world, &shading, &settings).0.rgba();
    let mean = |cols: std::ops::Range<usize>| {
        let n = (cols.len() * SIDE) as f32;
        (0..SIDE).flat_map(|row| cols.clone().map(move |col| row * SIDE + col)).map(|i| px[i][0]).sum::<f32>() / n
    };
    (mean(0..SIDE / 2 - 2), mean(SIDE / 2 + 2..SIDE))
}

/// No list: the left half is in both lights' shadow (0); `light shadow ["sun_a_inst"]`:
/// the board shadows sun_a alone, the left half gets sun_b's 0.6·0.8·0.5; `light shadow
/// "exclusive" ["sun_a_inst"]`: it shadows every light but sun_a, the left half gets
/// sun_a's 0.6·0.8·0.3. The right half always gets both, 0.6·0.8·0.8. Each engine within
/// 1e-3 of the formula (direct light of delta lights on a lambert: no noise).
#[test]
fn an_object_casts_shadows_only_for_its_linked_lights_in_both_engines() {
    let k = 0.6 * 0.8;
    for (link, left) in [
        ("", 0.0),
        (r#"light shadow ["sun_a_inst"]"#, k * 0.5),
        (r#"light shadow "exclusive" ["sun_a_inst"]"#, k * 0.3),
    ] {
        let text = scene(link);
        for engine in [EngineKind::Classic, EngineKind::Path] {
            let (l, r) = halves(&text, engine);
            assert!((l - left).abs() < 1e-3, "{engine:?} `{link}`: left {l} vs {left}");
            assert!((r - k * 0.8).abs() < 1e-3, "{engine:?} `{link}`: right {r} vs {}", k * 0.8);
        }
    }
}
