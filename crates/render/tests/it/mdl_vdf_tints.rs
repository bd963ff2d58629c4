//! A tinted vdf in the path engine (crates/material/tests/mdl/vdf_tints.mdl): a tint of 0
//! scatters nothing and absorbs all of the scattering coefficient, so a slab of it one unit
//! thick in front of a glow of radiance 1 shows Beer–Lambert's exp(−(σa + σs)) per channel
//! — and the same slab untinted shows more (its scattering sends light on).

use std::path::PathBuf;

use crate::support;

use render::{EngineKind, Settings};

/// A camera at the origin looking down −z (field of view 0.6°, 4² pixels) through a slab
/// of `slab` one unit thick (z from −3 to −2, an index-matched box) at a glow of radiance
/// 1 (z = −5): the pixels and every message, 16 samples, 16 bounces.
fn render_slab(slab: &str) -> (Vec<[f32; 4]>, Vec<String>) {
    let glow = r#"shader "back_mtl" "mdl::media::glow" ()"#;
    let slab = format!("shader \"slab_mtl\" {slab}");
    let text = format!("$include \"vdf_tints.mdl\"\n{}", crate::media::slab_scene(&slab, glow, "", 4));
    let parsed = mi::parse_str("t.mi", &text);
    let modules = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../material/tests/mdl"));
    let b = support::build_parsed(&parsed, 4, &[support::mdl_modules(), modules]);
    let path = render::integrator::PathSettings { max_depth: 16, ..Default::default() };
    let settings = Settings { engine: EngineKind::Path, spp: Some(16), path, ..Settings::default() };
    let (film, _) = support::render_world(&b.built.world, &b.built.shading, &settings);
    (film.rgba(), b.messages)
}

/// Tint 0: exp(−(σa + σs)) = exp(−(0.1, 0.2, 0.3) − (0.5, 1, 1.5)) within 1e-3 (the rays
/// are within 0.3° of the slab's normal: path lengths within 2e-5); untinted, the same
/// coefficients let more than that through in every channel (scattered light goes on).
#[test]
fn a_slab_of_a_vdf_tinted_black_transmits_beer_lambert_of_its_extinction() {
    let sigma_t = [0.6f32, 1.2, 1.8];
    let black = r#""mdl::vdf_tints::tinted" ("tint" 0 0 0, "scattering" 0.5 1 1.5, "absorption" 0.1 0.2 0.3)"#;
    let (px, messages) = render_slab(black);
    assert!(messages.is_empty(), "{messages:#?}");
    let white = r#""mdl::vdf_tints::tinted" ("tint" 1 1 1, "scattering" 0.5 1 1.5, "absorption" 0.1 0.2 0.3)"#;
    let (px_white, messages) = render_slab(white);
    assert!(messages.is_empty(), "{messages:#?}");
    for p in &px {
        for k in 0..3 {
            let want = (-sigma_t[k]).exp();
            assert!((p[k] - want).abs() <= 1e-3 * want, "channel {k}: {} vs exp(−{}) = {want}", p[k], sigma_t[k]);
        }
    }
    let mean = |px: &[[f32; 4]], k: usize| px.iter().map(|p| p[k]).sum::<f32>() / px.len() as f32;
    for k in 0..3 {
        assert!(
            mean(&px_white, k) > 1.05 * mean(&px, k),
            "channel {k}: untinted {} vs black {}",
            mean(&px_white, k),
            mean(&px, k)
        );
    }
}
