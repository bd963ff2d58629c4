//! Volumes that vary over the surface in the path engine
//! (crates/material/tests/mdl/entry_media.mdl): a medium is homogeneous inside its object,
//! so a path travels in the medium evaluated where it entered the object. A slab one unit
//! thick under a uniform white environment, seen by an orthographic camera straight
//! through its front face: the half entered at x < 0 and the half entered at x ≥ 0 show
//! the two media.

use std::path::PathBuf;

use crate::support;

use render::{EngineKind, Settings};

/// Renders an orthographic view (24², the square x, y ∈ [−1, 1], looking down −z) of a
/// slab of `shader` (a `.mi` shader statement of `slab_mtl`; z from −3 to −2, x and y
/// from −3 to 3, an index-matched box) under a uniform white environment of radiance 1,
/// `spp` samples, up to 256 bounces: the pixels with their x, and every message.
fn render_slab(shader: &str, spp: u32) -> (Vec<(f32, [f32; 4])>, Vec<String>) {
    let text = format!(
        r#"$include "entry_media.mdl"
options "opt" filter box 1 1 end options
camera "cam" focal infinity aperture 2 aspect 1 resolution 24 24
    environment "mib_color_mix" ("num" 0, "color_base" 1 1 1 1)
end camera
instance "cam_inst" "cam" end instance
{shader}
{}
instgroup "root" "cam_inst" "slab_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        crate::media::closed_box("slab", [-3.0, -3.0, -3.0], [3.0, 3.0, -2.0], "slab_mtl")
    );
    let parsed = mi::parse_str("t.mi", &text);
    let modules = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../material/tests/mdl"));
    let b = support::build_parsed(&parsed, 24, &[support::mdl_modules(), modules]);
    let path = render::integrator::PathSettings { max_depth: 256, ..Default::default() };
    let settings = Settings { engine: EngineKind::Path, spp: Some(spp), path, ..Settings::default() };
    let (film, _) = support::render_world(&b.built.world, &b.built.shading, &settings);
    let px = film.rgba().into_iter().enumerate().map(|(i, p)| ((i % 24) as f32 / 12.0 - 1.0 + 1.0 / 24.0, p));
    (px.collect(), b.messages)
}

/// The absorption depends on the entry point: every pixel of the half entered at x < 0
/// shows exp(−0.5), of the half entered at x ≥ 0 exp(−2), within 1e-3 — not the five
/// times stronger absorption of the slab's back half where the paths leave, nor the
/// volume at the material's default point (the origin: 2 everywhere). No warning.
#[test]
fn an_absorption_that_varies_is_the_one_where_the_path_entered() {
    let (px, messages) = render_slab(r#"shader "slab_mtl" "mdl::entry_media::entry_gel" ()"#, 4);
    assert!(messages.is_empty(), "{messages:#?}");
    let mut counted = [0, 0];
    for (x, p) in px.iter().filter(|(x, _)| x.abs() > 0.1) {
        let want = if *x < 0.0 { (-0.5f32).exp() } else { (-2.0f32).exp() };
        counted[usize::from(*x > 0.0)] += 1;
        for (k, v) in p[..3].iter().enumerate() {
            assert!((v - want).abs() <= 1e-3 * want, "x {x}, channel {k}: {v} vs {want}");
        }
    }
    assert_eq!(counted, [264, 264], "both halves seen");
}

/// A vdf tint that depends on the entry point: where entered at x < 0 the tint is 0 (σs
/// all absorbed, nothing scattered), so every pixel there is exp(−1.5) within 1e-3; where
/// entered at x ≥ 0 it is 1 (all scattered, albedo 1), a white furnace: the mean of that
/// half is 1 within 1 % per channel (64 samples a pixel) — though a path that scatters
/// across x = 0 or into the back half (where the tint is 0) stays in the medium it
/// entered. No warning.
#[test]
fn a_vdf_tint_that_varies_is_the_one_where_the_path_entered() {
    let (px, messages) = render_slab(r#"shader "slab_mtl" "mdl::entry_media::entry_smoke" ()"#, 64);
    assert!(messages.is_empty(), "{messages:#?}");
    let (mut sum, mut n) = ([0.0f64; 3], 0);
    for (x, p) in px.iter().filter(|(x, _)| x.abs() > 0.1) {
        if *x < 0.0 {
            let want = (-1.5f32).exp();
            for (k, v) in p[..3].iter().enumerate() {
                assert!((v - want).abs() <= 1e-3 * want, "x {x}, channel {k}: {v} vs {want}");
            }
        } else {
            for (s, v) in sum.iter_mut().zip(p) {
                *s += f64::from(*v);
            }
            n += 1;
        }
    }
    let mean = sum.map(|s| s / f64::from(n));
    eprintln!("the scattering half: {mean:?} over {n} pixels");
    assert!(mean.iter().all(|m| (m - 1.0).abs() < 0.01), "a white furnace: {mean:?}");
}

/// The classic engine takes a varying volume at the material's default point: that is a
/// warning naming the material (none for a constant volume).
#[test]
fn the_classic_engine_warns_of_a_varying_volume() {
    let build = |shader: &str| {
        let text = format!(
            "$include \"entry_media.mdl\"\n$include \"media.mdl\"\noptions \"opt\" end options\ncamera \"cam\" end camera\n\
             instance \"cam_inst\" \"cam\" end instance\n{shader}\n{}instgroup \"root\" \"cam_inst\" \"slab_inst\" end instgroup\n\
             render \"root\" \"cam_inst\" \"opt\"\n",
            crate::media::closed_box("slab", [-3.0, -3.0, -3.0], [3.0, 3.0, -2.0], "slab_mtl")
        );
        let parsed = mi::parse_str("t.mi", &text);
        let modules = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../material/tests/mdl"));
        let b = support::build_parsed(&parsed, 4, &[support::mdl_modules(), modules]);
        render::pipeline::classic_warnings(&b.built.world)
    };
    let warned = build(r#"shader "slab_mtl" "mdl::entry_media::entry_gel" ()"#);
    assert!(warned.len() == 1 && warned[0].contains("'slab_mtl'") && warned[0].contains("classic"), "{warned:?}");
    assert!(build(r#"shader "slab_mtl" "mdl::media::tinted_gel" ()"#).is_empty());
}
