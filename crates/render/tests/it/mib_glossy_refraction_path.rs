//! mental ray's `mib_glossy_refraction` in the path engine (`material`'s
//! `reader::mib_glossy_refraction`, `bsdf::MibGlossyRefraction`) against the classic
//! engine: a pane refracting a two-tone floor, sharp (against `mib_refract`) and glossy.
//! (Maya's `refractionLimit` counting its transmissions: `maya_limit_classic_glossy`.)

use crate::support;
use crate::support::maya_view::{pixels, pixels_warned};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 16;

/// A pane at y = 0 (facing up, material "g" given by `pane`: a whole `material … end
/// material`) over a floor at y = −3 glowing 1 for x < 0 and 0.2 for x > 0 (Maya
/// lamberts of colour 0 and that incandescence), seen from above (`top_down`, 2 samples
/// per pixel). Refraction through a horizontal plane keeps a ray's azimuth, so every
/// pixel sees one side of the floor: the seam lies between columns 7 and 8.
fn over_two_tone(pane: &str) -> String {
    let view = support::maya_view::top_down(SIDE).replace("samples 0 2", "samples 2 2");
    support::two_tone::scene(&view, pane, "pane", 0.0, -3.0)
}

/// A `mib_glossy_refraction` pane of `ior` 1.5, `refraction_color` (0.9, 0.7, 0.5), the
/// default view-angle curve (1 → 0.6 by (1 − cos θ)^5) and spreads `spread`.
fn glossy_pane(spread: f32) -> String {
    format!(
        r#"material "g" "mib_glossy_refraction" ("refraction_color" 0.9 0.7 0.5, "ior" 1.5, "samples" 64,
    "u_spread" {spread}, "v_spread" {spread}) end material"#
    )
}

/// Spreads → 0 are `mib_refract`: the path engine's image of a sharp pane (spreads 0 and
/// 10⁻⁴, weights 1) equals the classic engine's of a `mib_refract` pane of the same
/// colour and index (transmission (0.9, 0.7, 0.5) ⊙ the floor's side) at every pixel
/// within 1e-3 per channel; the same pane's classic image too.
#[test]
fn the_sharp_limit_is_mib_refract() {
    let refract = over_two_tone(
        r#"shader "black" "mib_color_mix" ("num" 0, "color_base" 0 0 0 1)
material "g" "mib_refract" ("input" = "black", "refract" 0.9 0.7 0.5, "ior" 1.5) end material"#,
    );
    // (The path engine's translation, which this render does not use, warns about `mib_refract`.)
    let want = pixels_warned(&refract, EngineKind::Classic, 4, "path integrator");
    for (i, p) in want.iter().enumerate() {
        let side = if i % SIDE < SIDE / 2 { 1.0 } else { 0.2 };
        let t = Vec3A::new(0.9, 0.7, 0.5) * side;
        assert!((*p - t).abs().max_element() < 1e-3, "mib_refract pixel {i}: {p} vs {t}");
    }
    for spread in [0.0f32, 1e-4] {
        let sharp =
            over_two_tone(&glossy_pane(spread).replace(
                "\"samples\" 64",
                "\"samples\" 64, \"refraction_base_weight\" 1, \"refraction_edge_weight\" 1",
            ));
        for engine in [EngineKind::Path, EngineKind::Classic] {
            for (i, (p, w)) in pixels(&sharp, engine, 4).iter().zip(&want).enumerate() {
                assert!((*p - *w).abs().max_element() < 1e-3, "{engine:?} spread {spread}, pixel {i}: {p} vs {w}");
            }
        }
    }
}

/// The path engine's image of a glossy pane (`ior` 1.5, the default view-angle curve)
/// over the two-tone floor agrees with the classic engine's (64 glossy rays per sample):
/// the image mean and the means of its left and right halves (the bright and the dim
/// side, blurred across the seam) within 2 %, spreads 0.05 and 0.3.
#[test]
fn the_path_engine_agrees_with_the_classic_glossy_refraction() {
    for spread in [0.05f32, 0.3] {
        support::two_tone::assert_path_agrees_with_classic(&over_two_tone(&glossy_pane(spread)), SIDE, spread);
    }
}
