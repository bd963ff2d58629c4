//! Media that emit (MDL's `material_volume.emission_intensity`, the radiance added per unit
//! length): a slab one unit thick that absorbs and emits, seen head-on by an orthographic
//! camera with nothing behind it, shows ε·(1 − exp(−σa·d))/σa per channel — the emission
//! integrated along the way, attenuated — in both engines, within 1e-3.

use std::path::PathBuf;

use crate::support;

use render::{EngineKind, Settings};

/// The pixels of an orthographic view (8², looking down −z at the square x, y ∈ [−1, 1])
/// of a slab of `glowing_media::glowing_gel` with `params` (z from −3 to −2, x and y from
/// −3 to 3), in `engine`, 2 samples a pixel, no environment; and the messages.
fn render_slab(engine: EngineKind, params: &str) -> (Vec<[f32; 4]>, Vec<String>) {
    let text = format!(
        r#"$include "glowing_media.mdl"
options "opt" filter box 1 1 end options
camera "cam" focal infinity aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
shader "slab_mtl" "mdl::glowing_media::glowing_gel" ({params})
{}
instgroup "root" "cam_inst" "slab_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        crate::media::closed_box("slab", [-3.0, -3.0, -3.0], [3.0, 3.0, -2.0], "slab_mtl")
    );
    let parsed = mi::parse_str("t.mi", &text);
    let modules = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../material/tests/mdl"));
    let b = support::build_parsed(&parsed, 8, &[support::mdl_modules(), modules]);
    let settings = Settings { engine, spp: Some(2), ..Settings::default() };
    let (film, _) = support::render_world(&b.built.world, &b.built.shading, &settings);
    (film.rgba(), b.messages)
}

#[test]
fn an_emitting_slab_shows_its_attenuated_emission_in_both_engines() {
    let cases = [
        (r#""absorption" 0.5 1 2, "emission" 1 2 0.5"#, [0.5f32, 1.0, 2.0], [1.0f32, 2.0, 0.5]),
        // Without absorption the emission adds up along the unit thickness: ε·1.
        (r#""absorption" 0 0 0, "emission" 0.25 0.5 1"#, [0.0, 0.0, 0.0], [0.25, 0.5, 1.0]),
    ];
    for engine in [EngineKind::Path, EngineKind::Classic] {
        for (params, sigma, eps) in cases {
            let (px, messages) = render_slab(engine, params);
            assert!(messages.is_empty(), "{engine:?}: {messages:#?}");
            let want: Vec<f32> = (0..3)
                .map(|c| if sigma[c] > 0.0 { eps[c] * (1.0 - (-sigma[c]).exp()) / sigma[c] } else { eps[c] })
                .collect();
            for p in &px {
                for c in 0..3 {
                    assert!((p[c] - want[c]).abs() <= 1e-3 * want[c], "{engine:?} {params}: {p:?} vs {want:?}");
                }
            }
        }
    }
}
