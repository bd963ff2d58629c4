//! A Maya lambert's `translucence` and `translucenceFocus` in both engines against the
//! forward lobe's closed form (`bsdf::maya_highlight::translucence`): a unit light
//! straight below the ground passes c · t · K(n, v_y) to a viewer above, v the unit
//! direction to the eye and n = 2φ/(1 − φ) the focus φ's exponent.

use crate::support;
use crate::support::maya_view::{ground_points, mean, mean_and_error, pixels_warned, EYE};

/// The pixels of `text`, whose world warns only that `translucenceDepth` is not read.
fn pixels(text: &str, engine: EngineKind, spp: u32) -> Vec<Vec3A> {
    pixels_warned(text, engine, spp, "translucenceDepth")
}

use bsdf::maya_highlight::translucence::{focus_exponent, forward_lobe};
use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 16;

/// The ground's colour c (`diffuse` 0.8, which a light from below does not show).
const COLOR: Vec3A = Vec3A::new(0.6, 0.5, 0.4);

/// The ground's `translucence` t.
const T: f32 = 0.7;

/// The lambert ground (translucence [`T`], focus `focus`) lit by a unit directional light
/// travelling straight up, seen from above.
fn scene(focus: f32) -> String {
    let view = support::maya_view::top_down(SIDE);
    format!(
        r#"
$include "mayabase.mi"
{view}
light "l" "maya_directionallight" ("intensity" 1) direction 0 1 0 end light
instance "l_inst" "l" end instance
shader "mat" "maya_lambert" ("color" {} {} {}, "diffuse" 0.8, "translucence" {T}, "translucenceFocus" {focus})
material "m" opaque "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "ground" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
instgroup "root" "cam_inst" "l_inst" "ground_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        COLOR.x, COLOR.y, COLOR.z
    )
}

/// The closed form c · t · K(n, v_y) averaged over pixel (`col`, `row`) (8 × 8 points).
fn formula(col: usize, row: usize, n: f32) -> Vec3A {
    let points: Vec<Vec3A> = ground_points(SIDE, col, row, 8).collect();
    let k = points.iter().map(|p| forward_lobe(n, (EYE - *p).normalize().y)).sum::<f32>() / points.len() as f32;
    COLOR * T * k
}

/// Focus 0 is diffuse translucence: every classic pixel c · t within 1e-4. Focus 0.5
/// and 0.8: the classic image's mean over its focus-0 mean (the measured concentration
/// along the light's direction) equals the closed form's mean K within 0.5 %, its centre
/// pixels are brighter than its corners by the closed form's ratio within 2 %, and the
/// path engine's image mean is the classic engine's within 2 % per channel (focus 0
/// included). Before, the path engine passed no light from behind at all and the
/// classic engine read no focus.
#[test]
fn translucence_focus_concentrates_the_light_along_its_direction_in_both_engines() {
    let flat = pixels(&scene(0.0), EngineKind::Classic, 4);
    for p in &flat {
        assert!((*p - COLOR * T).abs().max_element() < 1e-4, "focus 0: {p} vs {}", COLOR * T);
    }
    let flat_mean = mean(&flat);
    for focus in [0.0f32, 0.5, 0.8] {
        let n = focus_exponent(focus);
        let text = scene(focus);
        let classic = pixels(&text, EngineKind::Classic, 4);
        let want: Vec<Vec3A> = (0..SIDE * SIDE).map(|i| formula(i % SIDE, i / SIDE, n)).collect();
        let ratio = mean(&classic).x / flat_mean.x;
        let want_ratio = mean(&want).x / (COLOR.x * T);
        println!("focus {focus}: measured concentration {ratio}, closed form {want_ratio}");
        assert!((ratio / want_ratio - 1.0).abs() < 5e-3, "focus {focus}: {ratio} vs {want_ratio}");
        let at = |px: &[Vec3A], i: usize| px[i].x;
        let (centre, corner) = (SIDE / 2 * SIDE + SIDE / 2, 0);
        let measured = at(&classic, centre) / at(&classic, corner);
        let closed = at(&want, centre) / at(&want, corner);
        assert!((measured / closed - 1.0).abs() < 0.02, "focus {focus}: centre/corner {measured} vs {closed}");
        if focus > 0.0 {
            assert!(measured > 1.05, "focus {focus}: centre/corner {measured}");
        }
        let classic_mean = mean(&classic);
        let (path, error) = mean_and_error(&pixels(&text, EngineKind::Path, 64));
        println!("focus {focus}: classic {classic_mean}, path {path} ± {error}");
        for k in 0..3 {
            assert!((path[k] / classic_mean[k] - 1.0).abs() < 0.02, "focus {focus}: path {path} vs {classic_mean}");
        }
    }
}

/// [`scene`] with the lambert's `color` connected to a texture (a checker of one colour,
/// [`COLOR`] on both squares) and the focus `focus`.
fn connected_scene(focus: f32) -> String {
    let c = format!("{} {} {}", COLOR.x, COLOR.y, COLOR.z);
    let constant = format!(r#"shader "mat" "maya_lambert" ("color" {c},"#);
    let connected = format!(
        r#"shader "tex" "maya_checker" ("color1" {c}, "color2" {c})
shader "mat" "maya_lambert" ("color" = "tex.outColor","#
    );
    let text = scene(focus);
    assert!(text.contains(&constant), "{text}");
    text.replace(&constant, &connected)
}

/// A connected `color` (a texture of colour c everywhere) passes the light from behind
/// by c · t in the path engine as a constant one does: focus 0, every classic pixel
/// c · t within 1e-4 and the path engine's image mean within 2 % per channel of it;
/// focus 0.5: the path engine's mean is the classic engine's within 2 % per channel.
/// Before, the path engine passed it by the default colour 0.5 (0.35 against c·t =
/// (0.42, 0.35, 0.28)).
#[test]
fn translucence_follows_a_connected_colour_in_the_path_engine() {
    for focus in [0.0f32, 0.5] {
        let text = connected_scene(focus);
        let classic = pixels(&text, EngineKind::Classic, 4);
        if focus == 0.0 {
            for p in &classic {
                assert!((*p - COLOR * T).abs().max_element() < 1e-4, "classic {p} vs {}", COLOR * T);
            }
        }
        let classic_mean = mean(&classic);
        let (path, error) = mean_and_error(&pixels(&text, EngineKind::Path, 64));
        println!("focus {focus}: classic {classic_mean}, path {path} ± {error}");
        for k in 0..3 {
            assert!((path[k] / classic_mean[k] - 1.0).abs() < 0.02, "focus {focus}: path {path} vs {classic_mean}");
        }
    }
}
