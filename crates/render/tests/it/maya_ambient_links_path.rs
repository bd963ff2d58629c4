//! Maya's ambient light in the path engine against the classic engine: an instance whose
//! light list leaves an ambient light out receives none of it; with `useRayTraceShadows`
//! its directional share is shadowed (softly over `lightRadius`, tinted by `shadowColor`).

use crate::support;

use render::{EngineKind, Settings};

/// The image's side in pixels.
const SIDE: usize = 16;

/// Two lambert half planes (x < 0 and x > 0) seen from 4 above, lit by an ambient light
/// (`ambientShade` 0.45) and a directional light straight down; the left half's light list
/// is `left`, the right half's `right` (instance statements' `light …` parts).
fn linked_halves(left: &str, right: &str) -> String {
    let view = support::maya_view::top_down(SIDE);
    format!(
        r#"
$include "mayabase.mi"
{view}
light "amb" "maya_ambientlight" ("color" 1 0.9 0.8, "intensity" 0.5) origin 0 0 0 end light
instance "amb_inst" "amb" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 -2 0 1 end instance
light "sun" "maya_directionallight" ("intensity" 0.3) direction 0 -1 0 end light
instance "sun_inst" "sun" end instance
shader "lam" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 0.8)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
object "left" group -5 0 5  0 0 5  0 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
object "right" group 0 0 5  5 0 5  5 0 -5  0 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "left_inst" "left" {left} end instance
instance "right_inst" "right" {right} end instance
instgroup "root" "cam_inst" "amb_inst" "sun_inst" "left_inst" "right_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The mean red of the left and the right half of the image by `engine`, and the path
/// world's ambient light count.
fn halves(text: &str, engine: EngineKind) -> (f32, f32, usize) {
    let (scene, shading) = support::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    let settings = Settings { engine, spp: Some(4), ..Settings::default() };
    let px = support::render_world(&world, &shading, &settings).0.rgba();
    let half = |cols: std::ops::Range<usize>| {
        let n = (cols.len() * SIDE) as f32;
        (0..SIDE).flat_map(|row| cols.clone().map(move |col| row * SIDE + col)).map(|i| px[i][0]).sum::<f32>() / n
    };
    (half(0..SIDE / 2), half(SIDE / 2..SIDE), world.ambient.len())
}

/// The left half leaves the ambient light out (`light "exclusive" ["amb_inst"]`), the right
/// half names only it (`light ["amb_inst"]`); then the same lists swapped onto the
/// directional light. Each half's mean is the classic engine's within 1 % (0.002 where the
/// classic engine's is 0), and both engines give what the linked lights alone give: the
/// left half with the ambient light unlinked gets only the directional light's
/// 0.6·0.8·0.3 (a lambert's c·d·I, cos 1), the right half only the ambient light.
#[test]
fn an_instance_unlinked_from_an_ambient_light_receives_none_of_it_in_both_engines() {
    for (left, right, left_formula) in [
        (r#"light "exclusive" ["amb_inst"]"#, r#"light ["amb_inst"]"#, Some(0.6 * 0.8 * 0.3)),
        (r#"light "exclusive" ["sun_inst"]"#, r#"light ["sun_inst"]"#, None),
    ] {
        let text = linked_halves(left, right);
        let (cl, cr, n) = halves(&text, EngineKind::Classic);
        let (pl, pr, _) = halves(&text, EngineKind::Path);
        println!("{left} / {right}: classic {cl} {cr}, path {pl} {pr}");
        assert_eq!(n, 1, "one ambient light");
        for (c, p) in [(cl, pl), (cr, pr)] {
            assert!(c > 0.0 || p.abs() < 2e-3, "{left}: path {p} where classic is {c}");
            assert!(c == 0.0 || (p / c - 1.0).abs() < 0.01, "{left}: path {p} vs classic {c}");
        }
        if let Some(want) = left_formula {
            assert!((pl / want - 1.0).abs() < 1e-3, "left half: {pl} vs the directional light's {want}");
            // The right half gets the ambient light alone: well below what both give.
            let (_, both, _) = halves(&linked_halves("", ""), EngineKind::Path);
            assert!(pr < both - 0.5 * want, "right half {pr} vs both lights {both}");
        }
    }
}

/// A lambert ground half covered by a board 1 above it (x < 0), seen from 4 above at
/// `SIDE`², lit by an ambient light at (−1, 2, 0) with raytraced shadows (the shadow's
/// edge on the ground at x = 1)
/// (`ambientShade` `shade`, `lightRadius` `radius`, `shadowColor` 0.2 0.3 0.4, 16
/// `shadowRays`); the column means (red) by `engine`.
fn shadowed_columns(shade: f32, radius: f32, engine: EngineKind) -> Vec<f32> {
    let light = format!(
        r#"light "amb" "maya_ambientlight" ("color" 1 0.9 0.8, "intensity" 0.5, "ambientShade" {shade},
    "useRayTraceShadows" on, "shadowColor" 0.2 0.3 0.4, "shadowRays" 16, "lightRadius" {radius})
    origin 0 0 0 end light
instance "amb_inst" "amb" transform 1 0 0 0  0 1 0 0  0 0 1 0  1 -2 0 1 end instance"#
    );
    under_board(&light, engine)
}

/// The column means (red) of the ground half under the board by `engine`, lit by `light`
/// (statements defining a light instance "amb_inst").
fn under_board(light: &str, engine: EngineKind) -> Vec<f32> {
    let view = support::maya_view::top_down(SIDE);
    let text = format!(
        r#"
$include "mayabase.mi"
{view}
{light}
shader "lam" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 0.8)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
object "ground" group -6 0 6  6 0 6  6 0 -6  -6 0 -6  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
object "board" group -6 1 6  0 1 6  0 1 -6  -6 1 -6  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "board_inst" "board" end instance
instgroup "root" "cam_inst" "amb_inst" "ground_inst" "board_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    );
    let (scene, shading) = support::build_clean(&text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    let spp = if engine == EngineKind::Path { 64 } else { 4 };
    let path = render::integrator::PathSettings { max_depth: 1, ..Default::default() };
    let settings = Settings { engine, spp: Some(spp), path, ..Settings::default() };
    let px = support::render_world(&world, &shading, &settings).0.rgba();
    (0..SIDE).map(|col| (0..SIDE).map(|row| px[row * SIDE + col][0]).sum::<f32>() / SIDE as f32).collect()
}

/// Hard (`lightRadius` 0) and soft (0.5) shadows at `ambientShade` 1 and 0.45: every
/// column mean of the path engine within 3 % of the brightest column of the classic
/// engine's; the shadowed ground keeps the uniform share and `shadowColor`'s share of the
/// directional one (not black); the shadows are there (the ground under the board is
/// darker than the lit ground by over 20 %).
#[test]
fn an_ambient_lights_raytraced_shadows_darken_alike_in_both_engines() {
    for (shade, radius) in [(1.0f32, 0.0f32), (1.0, 0.5), (0.45, 0.5)] {
        let classic = shadowed_columns(shade, radius, EngineKind::Classic);
        let path = shadowed_columns(shade, radius, EngineKind::Path);
        println!("shade {shade} radius {radius}:\n  classic {classic:.3?}\n  path {path:.3?}");
        let brightest = classic.iter().fold(0.0f32, |a, &b| a.max(b));
        for (col, (c, p)) in classic.iter().zip(&path).enumerate() {
            assert!((c - p).abs() < 0.03 * brightest, "{shade} {radius}: column {col}: path {p} vs classic {c}");
        }
        let lit = classic[SIDE - 1];
        let under = path[SIDE / 2 + 1];
        assert!(under > 0.0 && under < 0.8 * lit, "{shade} {radius}: under the board {under} vs lit {lit}");
    }
}

/// A volume light with `emitAmbient` and raytraced shadows (a sphere of radius 8 centred at
/// (−1, 2, 0), the whole view inside, `shadowColor` 0.2 0.3 0.4, `emitSpecular` off): shadowed as the classic
/// light shadows it (all of its colour), every column mean of the path engine within 3 %
/// of the brightest classic column; the ground under the board darker by over 20 %.
#[test]
fn a_volume_light_with_emit_ambient_is_shadowed_alike_in_both_engines() {
    let light = r#"light "amb" "maya_volumelight" ("color" 1 0.9 0.8, "intensity" 0.5, "lightShape" 1,
    "emitAmbient" on, "emitSpecular" off, "useRayTraceShadows" on, "shadowColor" 0.2 0.3 0.4)
    origin 0 0 0 end light
instance "amb_inst" "amb" transform 0.125 0 0 0  0 0.125 0 0  0 0 0.125 0  0.125 -0.25 0 1 end instance"#;
    let classic = under_board(light, EngineKind::Classic);
    let path = under_board(light, EngineKind::Path);
    println!("volume emitAmbient:\n  classic {classic:.3?}\n  path {path:.3?}");
    let brightest = classic.iter().fold(0.0f32, |a, &b| a.max(b));
    for (col, (c, p)) in classic.iter().zip(&path).enumerate() {
        assert!((c - p).abs() < 0.03 * brightest, "column {col}: path {p} vs classic {c}");
    }
    let (lit, under) = (classic[SIDE - 1], path[SIDE / 2 + 1]);
    assert!(under > 0.0 && under < 0.8 * lit, "under the board {under} vs lit {lit}");
}
