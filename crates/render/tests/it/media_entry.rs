//! Volumes that vary over the surface in the path engine
//! (crates/material/tests/mdl/entry_media.mdl): a medium is homogeneous inside its object,
//! so a path travels in the medium evaluated where it entered the object. A slab one unit
//! thick under a uniform white environment, seen by an orthographic camera straight
//! through its front face: the half entered at x < 0 and the half entered at x ≥ 0 show
//! the two media. The classic engine's refraction chain keeps the medium evaluated where
//! its ray entered alike.

use std::path::PathBuf;

use crate::support;

use render::{EngineKind, Settings};

/// Renders an orthographic view (24², the square x, y ∈ [−1, 1], looking down −z) of a
/// slab of `shader` (a `.mi` shader statement of `slab_mtl`; z from −3 to −2, x and y
/// from −3 to 3, an index-matched box) under a uniform white environment of radiance 1,
/// `spp` samples, up to 256 bounces, in the path engine: the pixels with their x, and
/// every message.
fn render_slab(shader: &str, spp: u32) -> (Vec<(f32, [f32; 4])>, Vec<String>) {
    render_slab_by(EngineKind::Path, shader, spp)
}

/// [`render_slab`] in `engine`.
fn render_slab_by(engine: EngineKind, shader: &str, spp: u32) -> (Vec<(f32, [f32; 4])>, Vec<String>) {
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
    let settings = Settings { engine, spp: Some(spp), path, ..Settings::default() };
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
    for engine in [EngineKind::Path, EngineKind::Classic] {
        assert_the_entry_absorption(engine);
    }
}

/// The pixels of the `entry_gel` slab in `engine`: exp(−0.5) where entered at x < 0,
/// exp(−2) where entered at x ≥ 0, within 1e-3; no message.
fn assert_the_entry_absorption(engine: EngineKind) {
    let (px, messages) = render_slab_by(engine, r#"shader "slab_mtl" "mdl::entry_media::entry_gel" ()"#, 4);
    assert!(messages.is_empty(), "{engine:?}: {messages:#?}");
    let mut counted = [0, 0];
    for (x, p) in px.iter().filter(|(x, _)| x.abs() > 0.1) {
        let want = if *x < 0.0 { (-0.5f32).exp() } else { (-2.0f32).exp() };
        counted[usize::from(*x > 0.0)] += 1;
        for (k, v) in p[..3].iter().enumerate() {
            assert!((v - want).abs() <= 1e-3 * want, "{engine:?}: x {x}, channel {k}: {v} vs {want}");
        }
    }
    assert_eq!(counted, [264, 264], "{engine:?}: both halves seen");
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

/// Building the scene warns of neither a varying volume nor a constant one (the world's
/// warnings are what the path engine renders differently; the classic engine evaluates
/// varying volumes where a ray enters too).
#[test]
fn no_engine_warns_of_a_varying_volume() {
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
        assert!(b.messages.is_empty(), "{:#?}", b.messages);
        b.built.world.warnings.clone()
    };
    assert!(build(r#"shader "slab_mtl" "mdl::entry_media::entry_gel" ()"#).is_empty());
    assert!(build(r#"shader "slab_mtl" "mdl::media::tinted_gel" ()"#).is_empty());
}

/// Shadow rays evaluate a varying volume where they enter the object too, in both
/// engines. A matte wall (0.8) at z = −5 lit head-on by a directional light (irradiance π)
/// through the `entry_gel` slab, seen through it by a camera at the origin (field of view
/// 0.6°, 4², so the two left columns look through x < 0): the eye ray enters at z = −2
/// (σa 0.5 or 2), the shadow ray at z = −3, in the back half (σa 2.5 or 10), so the wall is
/// 0.8 exp(−3) where x < 0 and 0.8 exp(−12) where x ≥ 0 — the path engine within 2e-3,
/// the classic engine's pixels (π times, mental ray's lights carry no 1/π) within 1 %.
/// Shadow rays taking the volume at the material's default point (σa 2) would give
/// 0.8 exp(−2.5) and 0.8 exp(−4).
#[test]
fn shadow_rays_take_a_varying_volume_where_they_enter() {
    let text = format!(
        r#"$include "entry_media.mdl"
$include "export_multi.mdl"
options "opt" filter box 1 1 end options
camera "cam" focal 1 aperture 0.01 aspect 1 resolution 4 4 end camera
instance "cam_inst" "cam" end instance
shader "matte_mtl" "mdl::export_multi::matte" ("tint" 0.8 0.8 0.8)
shader "slab_mtl" "mdl::entry_media::entry_gel" ()
light "sun" "mib_light_infinite" ("color" 3.14159265 3.14159265 3.14159265, "shadow" on) direction 0 0 -1 shadow on end light
instance "sun_inst" "sun" end instance
{}{}instgroup "root" "cam_inst" "sun_inst" "slab_inst" "w_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        crate::media::closed_box("slab", [-3.0, -3.0, -3.0], [3.0, 3.0, -2.0], "slab_mtl"),
        crate::media::wall("w", -5.0, "matte_mtl")
    );
    let parsed = mi::parse_str("t.mi", &text);
    let modules = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../material/tests/mdl"));
    let b = support::build_parsed(&parsed, 4, &[support::mdl_modules(), modules]);
    assert!(b.messages.is_empty(), "{:#?}", b.messages);
    for (engine, scale, tol) in [(EngineKind::Path, 1.0, 2e-3), (EngineKind::Classic, std::f32::consts::PI, 0.01)] {
        let settings = Settings { engine, spp: Some(4), ..Settings::default() };
        let (film, _) = support::render_world(&b.built.world, &b.built.shading, &settings);
        for (i, p) in film.rgba().into_iter().enumerate() {
            let want = 0.8 * if i % 4 < 2 { (-3.0f32).exp() } else { (-12.0f32).exp() };
            for (k, v) in p[..3].iter().enumerate() {
                let v = v / scale;
                assert!((v - want).abs() <= tol * want, "{engine:?}: pixel {i}, channel {k}: {v} vs {want}");
            }
        }
    }
}
