//! The two-tone scene of the `mib_glossy_reflection` and `mib_glossy_refraction` path
//! tests (`mib_glossy_path`, `mib_glossy_refraction_path`): a glossy surface facing a plane that glows 1 for x < 0 and 0.2 for x > 0, seen from above, and the
//! check that the path engine's image agrees with the classic engine's.

use glam::Vec3A;
use render::EngineKind;

use super::maya_view::{mean, pixels};

/// The view of the two-tone scenes: `maya_view::top_down` of a `side` × `side` image with
/// 2 samples per pixel (at least and at most: every pixel sees the same count).
pub fn view(side: usize) -> String {
    super::maya_view::top_down(side).replace("samples 0 2", "samples 2 2")
}

/// A `.mi` scene: `view` ([`view`]), `material` (the surface's material "g",
/// a whole `material … end material`), the surface `surface` (a square at height
/// `surface_y` facing up) and, at height `glow_y`, a plane glowing 1 for x < 0 and 0.2 for
/// x > 0 (Maya lamberts of colour 0 and that incandescence).
pub fn scene(view: &str, material: &str, surface: &str, surface_y: f32, glow_y: f32) -> String {
    let s = surface_y;
    let object = format!(
        r#"object "{surface}" group -500 {s} 500  500 {s} 500  500 {s} -500  -500 {s} -500  v 0 v 1 v 2 v 3 c "g" 0 1 2 3 end group end object
instance "{surface}_inst" "{surface}" end instance"#
    );
    with_objects(view, material, &object, &format!("\"{surface}_inst\""), glow_y)
}

/// A `.mi` scene: `view`, `material` (material "g" and whatever else it needs) and a
/// square of "g" at height `y` facing up (`up`) or down, over the plane glowing 1 for x < 0
/// and 0.2 for x > 0 at height `glow_y` (none: nothing else); the instances `extra`
/// (quoted names: lights `material` defines) join the root group.
pub fn facing(view: &str, material: &str, (y, up): (f32, bool), glow_y: Option<f32>, extra: &str) -> String {
    let corners = if up { "0 1 2 3" } else { "3 2 1 0" };
    let object = format!(
        r#"object "pane" group -500 {y} 500  500 {y} 500  500 {y} -500  -500 {y} -500  v 0 v 1 v 2 v 3 c "g" {corners} end group end object
instance "pane_inst" "pane" end instance"#
    );
    let instances = format!("\"pane_inst\" {extra}");
    match glow_y {
        Some(g) => with_objects(view, material, &object, &instances, g),
        None => format!(
            "\n$include \"mayabase.mi\"\n{view}\n{material}\n{object}\n\
             instgroup \"root\" \"cam_inst\" {instances} end instgroup\nrender \"root\" \"cam_inst\" \"opt\"\n"
        ),
    }
}

/// `view`, `material`, the `objects` (`.mi` text) whose instances `instances` (quoted
/// names) join the root group, and the two-tone glowing plane at height `glow_y`.
fn with_objects(view: &str, material: &str, objects: &str, instances: &str, glow_y: f32) -> String {
    let g = glow_y;
    format!(
        r#"
$include "mayabase.mi"
{view}
{material}
shader "bright" "maya_lambert" ("color" 0 0 0, "incandescence" 1 1 1)
material "b" opaque "maya_shadingengine" ("surfaceShader" = "bright.outColor") end material
shader "dim" "maya_lambert" ("color" 0 0 0, "incandescence" 0.2 0.2 0.2)
material "d" opaque "maya_shadingengine" ("surfaceShader" = "dim.outColor") end material
{objects}
object "left" group -500 {g} 500  0 {g} 500  0 {g} -500  -500 {g} -500  v 0 v 1 v 2 v 3 c "b" 0 1 2 3 end group end object
instance "left_inst" "left" end instance
object "right" group 0 {g} 500  500 {g} 500  500 {g} -500  0 {g} -500  v 0 v 1 v 2 v 3 c "d" 0 1 2 3 end group end object
instance "right_inst" "right" end instance
instgroup "root" "cam_inst" {instances} "left_inst" "right_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The mean of the left (`left`) or right half of the pixels `px` of an image `side`
/// pixels wide.
pub fn half_mean(px: &[Vec3A], side: usize, left: bool) -> Vec3A {
    let sel: Vec<Vec3A> =
        px.iter().enumerate().filter(|(i, _)| ((i % side) < side / 2) == left).map(|(_, p)| *p).collect();
    mean(&sel)
}

/// The path engine's image of `text` (256 samples per pixel, an image `side` pixels
/// wide) agrees with the classic engine's (4): the image mean and the means of its left
/// and right halves within 2 % of the classic value's largest channel (`case` names the
/// case in messages). Returns the classic pixels.
pub fn assert_path_agrees_with_classic(text: &str, side: usize, case: &str) -> Vec<Vec3A> {
    let classic = pixels(text, EngineKind::Classic, 4);
    let path = pixels(text, EngineKind::Path, 256);
    assert_halves_agree(&classic, &path, side, case);
    classic
}

/// The path engine's pixels `path` agree with the classic engine's `classic` (an image
/// `side` pixels wide): the image mean and the means of its left and right halves within
/// 2 % of the classic value's largest channel (`case` names the case in messages).
pub fn assert_halves_agree(classic: &[Vec3A], path: &[Vec3A], side: usize, case: &str) {
    for (what, c, p) in [
        ("image", mean(classic), mean(path)),
        ("left half", half_mean(classic, side, true), half_mean(path, side, true)),
        ("right half", half_mean(classic, side, false), half_mean(path, side, false)),
    ] {
        println!("{case}, {what}: classic {c}, path {p}");
        assert!((p - c).abs().max_element() <= 0.02 * c.max_element(), "{case}, {what}: path {p} vs classic {c}");
    }
}
