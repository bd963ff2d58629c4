//! A volume inside glass whose sum is lowered at each hit into a wide shared lobe sum
//! (crates/material/tests/mdl/rough_transmission.mdl's `varying_rough_glass`: five rough
//! glass lobes, one of roughness varying with the position): the path engine tracks the
//! medium through it as through a compact sum.

use std::path::Path;

use crate::media::{slab_scene, SIGMA_A};
use crate::support;
use render::{EngineKind, Settings};

/// Renders `text` (4² pixels, 256 samples, 16 bounces) with the test modules and
/// `scenes/mdl`: the pixels and every message.
fn render(text: &str) -> (Vec<[f32; 4]>, Vec<String>) {
    let parsed = mi::parse_str("t.mi", text);
    let modules = [support::mdl_modules(), Path::new(env!("CARGO_MANIFEST_DIR")).join("../material/tests/mdl")];
    let b = support::build_parsed(&parsed, 4, &modules);
    let path = render::integrator::PathSettings { max_depth: 16, ..Default::default() };
    let settings = Settings { engine: EngineKind::Path, spp: Some(256), path, ..Settings::default() };
    let (film, _) = support::render_world(&b.built.world, &b.built.shading, &settings);
    (film.rgba(), b.messages)
}

/// A glow behind a slab (1 unit thick) of the varying rough glass absorbing σa = (0.5, 1,
/// 2) per unit, 256 samples a pixel. Each path either crosses the slab or is reflected (a
/// choice by Fresnel, the same for the three channels), so in every pixel channel k over
/// channel 0 is exp(−(σa_k − σa_0)) within 2 % (measured: 0.34 %: the rough lobes' paths differ in length), and the image's mean
/// over that of the same slab without absorption is exp(−σa) within 2 % (measured 0.5 %;
/// the count of paths through differs by noise between the two renders, ±0.6 % at one
/// sigma; the rough lobes tilt paths by a few degrees: lengths within 0.5 %; light
/// reflected twice inside, F² ≈ 0.2 %, goes 3 units). Untracked, both ratios are 1.
#[test]
fn a_medium_inside_per_hit_wide_glass_absorbs_beer_lambert() {
    let glow = r#"shader "back_mtl" "mdl::media::glow" ()"#;
    let glass =
        |a: &str| format!(r#"shader "slab_mtl" "mdl::rough_transmission::varying_rough_glass" ("absorption" {a})"#);
    let (px, messages) = render(&slab_scene(&glass("0.5 1 2"), glow, "", 4));
    assert!(messages.is_empty(), "{messages:#?}");
    let (clear, messages) = render(&slab_scene(&glass("0 0 0"), glow, "", 4));
    assert!(messages.is_empty(), "{messages:#?}");
    for p in &px {
        for k in 1..3 {
            let (got, want) = (p[k] / p[0], (SIGMA_A[0] - SIGMA_A[k]).exp());
            assert!((got - want).abs() <= 0.02 * want, "channel {k} over 0: {got} vs {want}: {p:?}");
        }
    }
    let mean = |px: &[[f32; 4]], k: usize| px.iter().map(|p| p[k]).sum::<f32>() / px.len() as f32;
    assert!(mean(&clear, 1) > 0.8, "the clear glass lets the glow through: {clear:?}");
    for (k, sigma) in SIGMA_A.iter().enumerate() {
        let (got, want) = (mean(&px, k) / mean(&clear, k), (-sigma).exp());
        assert!((got - want).abs() <= 0.02 * want, "channel {k}: {got} vs exp(−{sigma}) = {want}");
    }
}
