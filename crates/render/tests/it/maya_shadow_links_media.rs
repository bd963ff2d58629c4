//! Shadow linking (an instance's `light shadow ["exclusive"] [ … ]` list) in the path
//! engine in a scene with participating media: the board and ground of
//! `maya_shadow_links`, with an absorbing slab (`media.mdl`'s `tinted_gel`, index-matched,
//! σa = 0.5 1 2 per unit) one unit thick between the camera and the board, which every
//! shadow ray from the ground to the two lights straight above crosses.

use crate::media::{closed_box, render_by, SIGMA_A};

use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 16;

/// The ground (lambert colour 0.6 0.5 0.4, diffuse 0.8) seen from 4 above under "sun_a"
/// (intensity 0.3) and "sun_b" (0.5), both straight down with raytraced shadows; the gel
/// slab from y = 4.5 to 5.5 over the whole ground; a board at y = 6 over x < 0 with the
/// instance statements `link`.
fn scene(link: &str) -> String {
    let view = crate::support::maya_view::top_down(SIDE);
    let slab = closed_box("slab", [-8.0, 4.5, -8.0], [8.0, 5.5, 8.0], "slab_mtl");
    format!(
        r#"
$include "mayabase.mi"
$include "media.mdl"
{view}
light "sun_a" "maya_directionallight" ("intensity" 0.3, "useRayTraceShadows" on) direction 0 -1 0 end light
instance "sun_a_inst" "sun_a" end instance
light "sun_b" "maya_directionallight" ("intensity" 0.5, "useRayTraceShadows" on) direction 0 -1 0 end light
instance "sun_b_inst" "sun_b" end instance
shader "lam" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 0.8)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor")
    shadow "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
shader "slab_mtl" "mdl::media::tinted_gel" ()
{slab}
object "ground" group -6 0 6  6 0 6  6 0 -6  -6 0 -6  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
object "board" group -8 6 8  0 6 8  0 6 -8  -8 6 -8  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "board_inst" "board" {link} end instance
instgroup "root" "cam_inst" "sun_a_inst" "sun_b_inst" "ground_inst" "board_inst" "slab_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The path engine's pixels of `text` (direct light only: bounces off the board would add
/// to it), asserting no message.
fn pixels(text: &str) -> Vec<[f32; 4]> {
    let path = render::integrator::PathSettings { max_depth: 1, ..Default::default() };
    let (px, messages) = render_by(EngineKind::Path, text, SIDE as u32, 2, path);
    assert!(messages.is_empty(), "{messages:#?}");
    px
}

/// The mean of channel `k` over the left columns (x < −0.6) and the right (x > 0.6).
fn halves(px: &[[f32; 4]], k: usize) -> (f32, f32) {
    let mean = |cols: std::ops::Range<usize>| {
        let n = (cols.len() * SIDE) as f32;
        (0..SIDE).flat_map(|row| cols.clone().map(move |col| row * SIDE + col)).map(|i| px[i][k]).sum::<f32>() / n
    };
    (mean(0..SIDE / 2 - 2), mean(SIDE / 2 + 2..SIDE))
}

/// Closed form per channel k, with the slab's transmittance T = exp(−σa_k · 1) on every
/// shadow ray: no list: the left half is in both lights' shadow (0); `light shadow
/// ["sun_a_inst"]`: the board shadows sun_a alone, the left half gets c·d·0.5·T; `light
/// shadow "exclusive" ["sun_a_inst"]`: it shadows every light but sun_a, the left half gets
/// c·d·0.3·T. The right half always gets c·d·0.8·T. Within 2 % of the closed form (0.001
/// absolute where it is 0); delta lights on a lambert: no noise.
#[test]
fn shadow_links_hold_in_a_scene_with_an_absorbing_medium() {
    let colour = [0.6f32, 0.5, 0.4];
    for (link, left_intensity) in
        [("", 0.0), (r#"light shadow ["sun_a_inst"]"#, 0.5), (r#"light shadow "exclusive" ["sun_a_inst"]"#, 0.3)]
    {
        let px = pixels(&scene(link));
        for k in 0..3 {
            let cdt = colour[k] * 0.8 * (-SIGMA_A[k]).exp();
            let (l, r) = halves(&px, k);
            let (want_l, want_r) = (cdt * left_intensity, cdt * 0.8);
            assert!((l - want_l).abs() <= (0.02 * want_l).max(1e-3), "`{link}` channel {k}: left {l} vs {want_l}");
            assert!((r - want_r).abs() <= 0.02 * want_r, "`{link}` channel {k}: right {r} vs {want_r}");
        }
    }
}

/// A list naming every light (the board casts shadows for both, as with no list) takes
/// the linked walk through the media, and gives the image without a list bit for bit.
#[test]
fn a_list_linking_every_light_changes_nothing_in_a_scene_with_media() {
    let plain = pixels(&scene(""));
    let linked = pixels(&scene(r#"light shadow ["sun_a_inst", "sun_b_inst"]"#));
    assert!(plain == linked, "a list of every light changed the image");
}
