//! Soft shadows of Maya's point, spot and directional lights in the path engine against
//! the classic engine: `lightRadius` (shadow rays towards points uniform over the sphere
//! of that radius around the light) and `lightAngle` (shadow rays over the cone of that
//! angular diameter), the light itself still arriving from its point or direction.

use crate::support;

use render::integrator::PathSettings;
use render::{EngineKind, Settings};

/// The image's side in pixels.
const SIDE: usize = 24;

/// A lambert ground (colour 0.7, diffuse 0.8) seen from 4 above at `SIDE`² pixels (aperture
/// 1.2: x and z in ±2.4 on the ground), half covered by a lambert board 1 above it (x < 0),
/// lit by `light` (a light statement named "l", placed by `placement`, an instance
/// transform's 16 numbers).
fn shadowed_ground(light: &str, placement: &str) -> String {
    let view = support::maya_view::top_down(SIDE);
    format!(
        r#"
$include "mayabase.mi"
{view}
{light}
instance "l_inst" "l" transform {placement} end instance
shader "lam" "maya_lambert" ("color" 0.7 0.7 0.7, "diffuse" 0.8)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
object "ground" group -6 0 6  6 0 6  6 0 -6  -6 0 -6  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
object "board" group -6 1 6  0 1 6  0 1 -6  -6 1 -6  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "board_inst" "board" end instance
instgroup "root" "cam_inst" "l_inst" "ground_inst" "board_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The image's column means (grey), left to right, by `engine` at `spp` samples a pixel,
/// direct light only (one scattering event in the path engine; the classic engine's
/// lambert gathers none).
fn columns(text: &str, engine: EngineKind, spp: u32) -> Vec<f32> {
    let (scene, shading) = support::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    let path = PathSettings { max_depth: 1, ..PathSettings::default() };
    let settings = Settings { engine, spp: Some(spp), path, ..Settings::default() };
    let px = support::render_world(&world, &shading, &settings).0.rgba();
    (0..SIDE).map(|col| (0..SIDE).map(|row| px[row * SIDE + col][1]).sum::<f32>() / SIDE as f32).collect()
}

/// Renders `light` soft (its soft parameter `soft`) in both engines and hard in the path
/// engine, and asserts: the image means agree within 2 %; every column mean of the path
/// engine is the classic engine's within 4 % of the brightest column (the penumbra's
/// shape); the soft shadow is not the hard one (some column differs by over 20 % of the
/// brightest lit ground column).
fn soft_against_classic(name: &str, light: &str, soft: &str, placement: &str) {
    let text = shadowed_ground(&light.replace("SOFT", soft), placement);
    let hard = shadowed_ground(&light.replace("SOFT", ""), placement);
    let classic = columns(&text, EngineKind::Classic, 4);
    let path = columns(&text, EngineKind::Path, 64);
    let path_hard = columns(&hard, EngineKind::Path, 16);
    let brightest = classic.iter().fold(0.0f32, |a, &b| a.max(b));
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    println!("{name}: classic {classic:.3?}\n  path {path:.3?}\n  hard {path_hard:.3?}");
    assert!(brightest > 0.1, "{name}: the ground is lit ({brightest})");
    let (mc, mp) = (mean(&classic), mean(&path));
    assert!((mp / mc - 1.0).abs() < 0.02, "{name}: image means path {mp} vs classic {mc}");
    for (col, (c, p)) in classic.iter().zip(&path).enumerate() {
        assert!((c - p).abs() < 0.04 * brightest, "{name}: column {col}: path {p} vs classic {c}");
    }
    // The ground's lit columns (right of the board) against the softening.
    let ground = path_hard[SIDE / 2..].iter().fold(0.0f32, |a, &b| a.max(b));
    let softened = path.iter().zip(&path_hard).map(|(s, h)| (s - h).abs()).fold(0.0f32, f32::max);
    assert!(softened > 0.2 * ground, "{name}: the soft shadow is the hard one ({softened} of {ground})");
}

/// A point light (intensity 1.5) at (−1, 2, 0) of `lightRadius` 0.4: its shadow edge on the
/// ground at x = 1, softened over about ±0.4.
#[test]
fn a_point_lights_radius_softens_its_shadow_alike_in_both_engines() {
    soft_against_classic(
        "point",
        r#"light "l" "maya_pointlight" ("intensity" 1.5, "useRayTraceShadows" on, "shadowRays" 16 SOFT)
            origin 0 0 0 end light"#,
        r#", "lightRadius" 0.4"#,
        "1 0 0 0  0 1 0 0  0 0 1 0  1 -2 0 1",
    );
}

/// A spot light (cone 2.4 rad, pointing down) in the point light's place, `lightRadius`
/// 0.4, quadratic decay.
#[test]
fn a_spot_lights_radius_softens_its_shadow_alike_in_both_engines() {
    soft_against_classic(
        "spot",
        r#"light "l" "maya_spotlight" ("intensity" 6, "decayRate" 2, "coneAngle" 2.4,
            "useRayTraceShadows" on, "shadowRays" 16 SOFT)
            origin 0 0 0 direction 0 -1 0 spread 0.3623578 end light"#,
        r#", "lightRadius" 0.4"#,
        "1 0 0 0  0 1 0 0  0 0 1 0  1 -2 0 1",
    );
}

/// A directional light travelling along (1, −2, 0) (shadow edge at x = 0.5) of
/// `lightAngle` 0.8 rad.
#[test]
fn a_directional_lights_angle_softens_its_shadow_alike_in_both_engines() {
    soft_against_classic(
        "directional",
        r#"light "l" "maya_directionallight" ("intensity" 1, "useRayTraceShadows" on, "shadowRays" 16 SOFT)
            direction 1 -2 0 end light"#,
        r#", "lightAngle" 0.8"#,
        "1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1",
    );
}
