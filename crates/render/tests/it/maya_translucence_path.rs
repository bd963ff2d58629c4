//! A Maya lambert's `translucence` and `translucenceFocus` in both engines against the
//! forward lobe's closed form (`bsdf::maya_highlight::translucence`): a unit light
//! straight below the ground passes c · t · K(n, v_y) to a viewer above, v the unit
//! direction to the eye and n = 2φ/(1 − φ) the focus φ's exponent.

use crate::support;
use crate::support::maya_view::{ground_points, mean, mean_and_error, pixels, EYE};

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

/// The ground of [`scene`] (focus 0), with UVs (a 3 × 3 repeated place2dTexture
/// "place" for textures), its lambert's `color` `color`, `diffuse` `diffuse` and
/// `translucence` `translucence` (values or `= "node.output"` connections) after the
/// shaders `shaders`.
fn connected(shaders: &str, color: &str, diffuse: f32, translucence: &str) -> String {
    let view = support::maya_view::top_down(SIDE);
    format!(
        r#"
$include "mayabase.mi"
{view}
light "l" "maya_directionallight" ("intensity" 1) direction 0 1 0 end light
instance "l_inst" "l" end instance
shader "place" "maya_place2dtexture" ("repeatU" 3, "repeatV" 3)
{shaders}
shader "mat" "maya_lambert" ("color" {color}, "diffuse" {diffuse}, "translucence" {translucence},
  "translucenceFocus" 0)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "ground" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  0 0 0  1 0 0  1 1 0  0 1 0
  v 0 t 4 v 1 t 5 v 2 t 6 v 3 t 7 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
instgroup "root" "cam_inst" "l_inst" "ground_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Whether `a` and `b` agree per pixel within `tol` per channel.
fn same(a: &[Vec3A], b: &[Vec3A], tol: f32) -> bool {
    a.iter().zip(b).all(|(p, q)| (*p - *q).abs().max_element() < tol)
}

/// A connected `translucence` (a plusMinusAverage of one input, 0.7), also beside a
/// connected `color` (a checker of [`COLOR`] on both squares), and a connected `color`
/// with `diffuse` 0 give per pixel (1e-4) what the same constant values give, in both
/// engines. Before, the path engine took the default (no translucence, warned) for the
/// first and passed the light by the default colour 0.5 for the last.
#[test]
fn a_connected_constant_translucence_or_colour_matches_the_constant_values() {
    let c = format!("{} {} {}", COLOR.x, COLOR.y, COLOR.z);
    let unit = r#"shader "u" "maya_plusminusaverage" ("input1D" [0.7])"#;
    let one = format!(r#"shader "chk" "maya_checker" ("uvCoord" = "place.outUV", "color1" {c}, "color2" {c})"#);
    let tex = r#"= "chk.outColor""#;
    let util = r#"= "u.output1D""#;
    let cases = [
        (connected("", &c, 0.8, &T.to_string()), connected(unit, &c, 0.8, util)),
        (connected("", &c, 0.8, &T.to_string()), connected(&format!("{unit}\n{one}"), tex, 0.8, util)),
        (connected("", &c, 0.0, &T.to_string()), connected(&one, tex, 0.0, &T.to_string())),
        (connected("", &c, 0.0, &T.to_string()), connected(&format!("{unit}\n{one}"), tex, 0.0, util)),
    ];
    for (i, (constant, linked)) in cases.iter().enumerate() {
        for engine in [EngineKind::Classic, EngineKind::Path] {
            let (want, got) = (pixels(constant, engine, 4), pixels(linked, engine, 4));
            println!("case {i} {engine:?}: constant {} connected {}", want[0], got[0]);
            assert!(same(&got, &want, 1e-4), "case {i} {engine:?}: {} vs {}", got[0], want[0]);
            assert!((want[0] - COLOR * T).abs().max_element() < 1e-4, "case {i} {engine:?}: {}", want[0]);
        }
    }
}

/// Textures that vary: a checker's alpha (0.9 / 0.3, its luminance) on `translucence`, a
/// checker (0.9 0.6 0.3 / 0.2 0.4 0.8) on `color` with `diffuse` 0, and both at once:
/// the path engine's image mean is the classic engine's within 2 % per channel, and its
/// brightest red pixel is more than twice its dimmest (the checker shows; closed form 3
/// and 4.5).
#[test]
fn a_varying_translucence_or_colour_follows_the_texture_in_the_path_engine() {
    let alpha = r#"shader "a" "maya_checker" ("uvCoord" = "place.outUV", "alphaIsLuminance" on,
  "color1" 0.9 0.9 0.9, "color2" 0.3 0.3 0.3)"#;
    let colour = r#"shader "chk" "maya_checker" ("uvCoord" = "place.outUV", "color1" 0.9 0.6 0.3,
  "color2" 0.2 0.4 0.8)"#;
    let c = format!("{} {} {}", COLOR.x, COLOR.y, COLOR.z);
    let (by_alpha, by_colour) = (r#"= "a.outAlpha""#, r#"= "chk.outColor""#);
    let cases = [
        connected(alpha, &c, 0.8, by_alpha),
        connected(colour, by_colour, 0.0, &T.to_string()),
        connected(&format!("{alpha}\n{colour}"), by_colour, 0.0, by_alpha),
    ];
    for (i, text) in cases.iter().enumerate() {
        let classic = mean(&pixels(text, EngineKind::Classic, 4));
        let px = pixels(text, EngineKind::Path, 4);
        let path = mean(&px);
        let (hi, lo) = px.iter().fold((0.0f32, f32::INFINITY), |(h, l), p| (h.max(p.x), l.min(p.x)));
        println!("case {i}: classic {classic}, path {path}, red {lo}..{hi}");
        for k in 0..3 {
            assert!((path[k] / classic[k] - 1.0).abs() < 0.02, "case {i}: path {path} vs classic {classic}");
        }
        assert!(hi > 2.0 * lo, "case {i}: red {lo}..{hi}");
    }
}

/// The ground of [`scene`] showing a layeredShader of two translucent lamberts: on top
/// "a" (colour [`COLOR`], focus 0, transparency 1 − `w`: share w), below it "b" (colour
/// [`COLOR_B`], focus 0.5, opaque: share 1 − w).
fn stack_scene(w: f32) -> String {
    let ta = 1.0 - w;
    let shaders = format!(
        r#"shader "a" "maya_lambert" ("color" {} {} {}, "diffuse" 0.8, "translucence" {T}, "translucenceFocus" 0,
  "transparency" {ta} {ta} {ta})
shader "b" "maya_lambert" ("color" {} {} {}, "diffuse" 0.8, "translucence" {T}, "translucenceFocus" 0.5)
shader "mat" "maya_layeredshader" ("inputs" [
    {{ "color" = "a.outColor", "transparency" = "a.outTransparency" }},
    {{ "color" = "b.outColor", "transparency" = "b.outTransparency" }} ])"#,
        COLOR.x, COLOR.y, COLOR.z, COLOR_B.x, COLOR_B.y, COLOR_B.z
    );
    let lambert = format!(
        r#"shader "mat" "maya_lambert" ("color" {} {} {}, "diffuse" 0.8, "translucence" {T}, "translucenceFocus" 0)"#,
        COLOR.x, COLOR.y, COLOR.z
    );
    scene(0.0).replace(&lambert, &shaders)
}

/// The lower layer's colour in [`stack_scene`].
const COLOR_B: Vec3A = Vec3A::new(0.3, 0.6, 0.8);

/// A layeredShader keeps each translucent layer's `translucenceFocus` in the path engine:
/// layers of focus 0 and 0.5 at shares w and 1 − w (w = 0.25, 0.5, 0.75) under a unit
/// light straight below: the classic image mean is the closed form
/// w · c_a · t + (1 − w) · c_b · t · K(2, v_y) within 0.5 % per channel, and every path
/// pixel (64 samples) is the classic pixel within 2 % per channel; no warning. Before,
/// the path engine gave the stack the first translucent layer's focus (0: the lower
/// layer's light spread evenly, K = 1 where it is 2 straight above) and warned.
#[test]
fn a_layered_shader_keeps_each_layers_focus_in_the_path_engine() {
    let n = focus_exponent(0.5);
    for w in [0.25f32, 0.5, 0.75] {
        let text = stack_scene(w);
        let classic = pixels(&text, EngineKind::Classic, 4);
        let want: Vec<Vec3A> = (0..SIDE * SIDE)
            .map(|i| COLOR * T * w + (formula(i % SIDE, i / SIDE, n) / COLOR) * COLOR_B * (1.0 - w))
            .collect();
        let (got, closed) = (mean(&classic), mean(&want));
        println!("w {w}: classic {got}, closed form {closed}");
        for k in 0..3 {
            assert!((got[k] / closed[k] - 1.0).abs() < 5e-3, "w {w}: classic {got} vs {closed}");
        }
        let path = pixels(&text, EngineKind::Path, 64);
        let worst =
            path.iter().zip(&classic).map(|(p, c)| (*p / *c - Vec3A::ONE).abs().max_element()).fold(0.0, f32::max);
        println!("w {w}: path vs classic per pixel, worst {worst}");
        assert!(worst < 0.02, "w {w}: a path pixel {worst} off the classic one");
    }
}
