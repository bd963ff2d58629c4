//! A module material wider than mira's compact lobe sum (crates/material/tests/mdl/wide.mdl:
//! a mix of three layered parts, six lobes, three layer curves, three layer normals) in
//! the path engine: a plane of it, lit from above and (through its diffuse transmission)
//! from below by emitters that reflect nothing, renders as the weighted sum of the plane's
//! images with each part alone. The image is linear in the plane's BSDF here (every path
//! scatters once, at the plane), so the two differ by Monte Carlo noise only.

use std::path::Path;

use crate::support;
use render::{EngineKind, Settings};

const RES: usize = 8;

/// Renders `text` in the path engine at `RES`² pixels, `spp` samples: the pixels' RGB and
/// the messages.
fn render_text(text: &str, spp: u32) -> (Vec<[f32; 3]>, Vec<String>) {
    let parsed = mi::parse_str("wide.mi", text);
    let modules = [Path::new(env!("CARGO_MANIFEST_DIR")).join("../material/tests/mdl")];
    let built = support::build_parsed(&parsed, RES as u32, &modules);
    let settings = Settings { engine: EngineKind::Path, spp: Some(spp), ..Settings::default() };
    let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
    (film.rgba().iter().map(|p| [p[0], p[1], p[2]]).collect(), built.messages)
}

/// The plane z = −5 of shader `plane` seen by an orthographic camera looking down −Z at
/// x, y ∈ [−1, 1]; a lamp above it off to the side (facing down, out of view) and one
/// under it (facing up, hidden by the plane).
fn scene(plane: &str) -> String {
    format!(
        r#"options "opt" filter box 1 1 end options
shader "top" "mdl::wide::lamp" ("intensity" 4 4 4)
shader "bottom" "mdl::wide::lamp" ("intensity" 2 3 4)
shader "plane" {plane}
object "above" group
    1.5 -1.5 -3  1.5 1.5 -3  2.5 1.5 -2  2.5 -1.5 -2
    v 0 v 1 v 2 v 3
    p "top" 0 1 2 3
end group end object
object "below" group
    -3 -3 -7  -3 3 -7  3 3 -7  3 -3 -7
    v 0 v 1 v 2 v 3
    p "bottom" 3 2 1 0
end group end object
object "ground" group
    -4 -4 -5  4 -4 -5  4 4 -5  -4 4 -5
    v 0 v 1 v 2 v 3
    p "plane" 0 1 2 3
end group end object
instance "above_inst" "above" end instance
instance "below_inst" "below" end instance
instance "ground_inst" "ground" end instance
camera "cam" focal infinity aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
instgroup "root" "cam_inst" "above_inst" "below_inst" "ground_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

fn mean(px: &[[f32; 3]]) -> [f32; 3] {
    let n = px.len() as f32;
    [0, 1, 2].map(|c| px.iter().map(|p| p[c]).sum::<f32>() / n)
}

/// The wide mix (weights 0.3, 0.3, 0.4, tint (0.9, 0.5, 0.2)) against 0.3 · coated +
/// 0.3 · curved + 0.4 · translucent, each rendered alone, 4096 samples a pixel: the image
/// means within 0.5 % per channel and every pixel within 5 % of the mean (measured: means
/// 0.03 %, worst pixel 2.0 %; at 1024 samples 0.2 % and 7.5 %, at 256 0.2 % and 8 %: the
/// pixels' difference is noise, shrinking with the samples); each part alone differs from
/// the mix by more than 10 %, so the comparison sees the parts' weights.
#[test]
fn a_wide_lobe_sum_renders_as_the_weighted_sum_of_its_parts() {
    let spp = 4096;
    let (wide, messages) = render_text(&scene(r#""mdl::wide::wide" ("tint" 0.9 0.5 0.2)"#), spp);
    assert!(messages.is_empty(), "{messages:#?}");
    let mut sum = vec![[0.0f32; 3]; RES * RES];
    let mut parts = Vec::new();
    for (name, w) in [("part_coated", 0.3), ("part_curved", 0.3), ("part_translucent", 0.4)] {
        let (px, messages) = render_text(&scene(&format!(r#""mdl::wide::{name}" ("tint" 0.9 0.5 0.2)"#)), spp);
        assert!(messages.is_empty(), "{name}: {messages:#?}");
        for (s, p) in sum.iter_mut().zip(&px) {
            for c in 0..3 {
                s[c] += w * p[c];
            }
        }
        parts.push((name, mean(&px)));
    }
    let (m, s) = (mean(&wide), mean(&sum));
    for c in 0..3 {
        assert!((m[c] - s[c]).abs() <= 0.005 * s[c], "channel {c}: mix {m:?}, sum of parts {s:?}");
        for (name, p) in &parts {
            assert!((p[c] - m[c]).abs() > 0.1 * m[c], "{name} alone {p:?} is the mix {m:?}");
        }
    }
    for (i, (a, b)) in wide.iter().zip(&sum).enumerate() {
        for c in 0..3 {
            assert!((a[c] - b[c]).abs() <= 0.05 * s[c], "pixel {i} channel {c}: {a:?} vs {b:?} (mean {s:?})");
        }
    }
}
