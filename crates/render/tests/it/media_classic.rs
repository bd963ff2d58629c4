//! MDL participating media in the classic engine, against the path engine and closed
//! forms (materials of scenes/mdl/media.mdl; scene pieces from [`super::media`]): a
//! classic camera inside nested absorbing boxes sees through them as the path engine's
//! does (exp(−1.5σa); exp(−4σa − 0.5)).

use render::integrator::PathSettings;
use render::EngineKind;

use super::media::{assert_pixels, closed_box, render_by, scene_with, wall, SIGMA_A};

/// Renders `text` with the classic engine at 4², `spp` samples: the pixels and every message.
fn classic(text: &str, spp: u32) -> (Vec<[f32; 4]>, Vec<String>) {
    render_by(EngineKind::Classic, text, 4, spp, PathSettings::default())
}

#[test]
fn a_classic_camera_inside_a_medium_sees_through_it() {
    // As `media::a_camera_inside_a_medium_sees_through_it` for the path engine: a glow of
    // radiance 1 at distance 1.5 inside a gel box around the camera: exp(−1.5 σa); inside
    // that box and a second (σa 0.25) a glow outside both: exp(−4 σa − 0.5). Treated as
    // outside, the camera would see 1 and exp(−σa·4 + …) of the far side only.
    let inner = closed_box("inner", [-5.0, -5.0, -4.0], [5.0, 5.0, 4.0], "inner_mtl");
    let glow = r#"shader "glow_mtl" "mdl::media::glow" ()
shader "inner_mtl" "mdl::media::tinted_gel" ()"#;
    let text = scene_with(&format!("{glow}\n{inner}{}", wall("w", -1.5, "glow_mtl")), &["inner_inst", "w_inst"], 4);
    let (px, messages) = classic(&text, 4);
    assert!(messages.is_empty(), "{messages:#?}");
    eprintln!("classic camera in one box: {:?}", px[0]);
    assert_pixels(&px, SIGMA_A.map(|s| (-1.5 * s).exp()), 1e-3, "a wall inside the box");

    let outer = closed_box("outer", [-10.0, -10.0, -6.0], [10.0, 10.0, 6.0], "outer_mtl");
    let text = scene_with(
        &format!(
            "{glow}\nshader \"outer_mtl\" \"mdl::media::tinted_gel\" (\"absorption\" 0.25 0.25 0.25)\n{inner}{outer}{}",
            wall("w", -8.0, "glow_mtl")
        ),
        &["inner_inst", "outer_inst", "w_inst"],
        4,
    );
    let (px, messages) = classic(&text, 4);
    assert!(messages.is_empty(), "{messages:#?}");
    eprintln!("classic camera in two boxes: {:?}", px[0]);
    assert_pixels(&px, SIGMA_A.map(|s| (-4.0 * s - 0.5).exp()), 1e-3, "a wall outside two boxes");
}
