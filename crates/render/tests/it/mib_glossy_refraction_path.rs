//! mental ray's `mib_glossy_refraction` in the path engine (`material`'s
//! `reader::mib_glossy_refraction`, `bsdf::MibGlossyRefraction`) against the classic
//! engine: a pane refracting a two-tone floor, sharp (against `mib_refract`) and glossy.
//! (Maya's `refractionLimit` counting its transmissions: `maya_limit_classic_glossy`.)

use crate::support;
use crate::support::maya_view::{mean, pixels, pixels_warned};

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
    let view = support::two_tone::view(SIDE);
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
        support::two_tone::assert_path_agrees_with_classic(
            &over_two_tone(&glossy_pane(spread)),
            SIDE,
            &format!("spread {spread}"),
        );
    }
}

/// A pane of `mib_glossy_refraction` (`ior` 1.5, `refraction_color` 0.8, spread 0.2, the
/// default view-angle curve, no top material) at y = 0 facing up (the camera sees its
/// front) or down (its back) over the two-tone floor (`floor`) or nothing, with, where
/// `back` is given, a back material of that colour (`mib_illum_lambert` lit by all
/// lights), reversed where `reverse`; lit by a Maya directional light of intensity 1
/// without shadows travelling along (2, `light_y`, 0) (63° from the normal: the glossy
/// lobe does not reach it, as the classic shader's rays find no light).
fn pane(back: Option<&str>, reverse: bool, up: bool, floor: bool, light_y: f32) -> String {
    let view = support::two_tone::view(SIDE);
    let back_params = back.map_or(String::new(), |_| {
        format!(r#", "back_material" "back", "render_reverse_of_back_material" {}"#, if reverse { "on" } else { "off" })
    });
    let back_colour = back.unwrap_or("0 0 0");
    let material = format!(
        r#"light "sun" "maya_directionallight" ("intensity" 1, "useRayTraceShadows" off) direction 2 {light_y} 0 end light
instance "sun_inst" "sun" end instance
shader "back" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" {back_colour} 1, "mode" 3)
material "g" "mib_glossy_refraction" ("refraction_color" 0.8 0.8 0.8, "ior" 1.5,
    "samples" 64, "u_spread" 0.2, "v_spread" 0.2{back_params}) end material"#
    );
    support::two_tone::facing(&view, &material, (0.0, up), floor.then_some(-3.0), "\"sun_inst\"")
}

/// `back_material` in the path engine, against the classic engine and the closed form: a
/// pane seen from the back (facing down) and from the front (facing up) with a back
/// material of colour b = (0.1, 0.3, 0.6) lit from the back's side (a light from above,
/// over the two-tone floor the pane refracts) and, reversed, from the front's side (a
/// light from below; no floor, whose glow would light the back material in the path
/// engine only: the classic `mib_illum_lambert` takes direct light alone). Seen from the
/// back, the back material adds b·cos θ (θ = 63.4°, the light's angle to the normal) to
/// the classic image mean within 1e-3 (its glossy rays' noise moves with the samples the
/// back material takes), and the path engine's image mean with it less its mean without
/// it (the same seed) is that within 2 % of its largest channel; seen from the front it
/// adds nothing in either engine (1e-6 classic, bit for bit path). (The
/// difference takes out the light the path engine's next-event estimation finds through
/// the glossy lobe, which the classic shader's rays never see: ≈ 0.04 grey from the back
/// here.)
#[test]
fn the_back_material_is_seen_from_the_back_in_both_engines() {
    let cos = 1.0 / 5.0f32.sqrt();
    let added = Vec3A::new(0.1, 0.3, 0.6) * cos;
    for up in [false, true] {
        for (reverse, light_y) in [(false, -1.0f32), (true, 1.0)] {
            let floor = !reverse;
            let with = pane(Some("0.1 0.3 0.6"), reverse, up, floor, light_y);
            let without = pane(None, reverse, up, floor, light_y);
            let want = if up { Vec3A::ZERO } else { added };
            let classic =
                mean(&pixels(&with, EngineKind::Classic, 4)) - mean(&pixels(&without, EngineKind::Classic, 4));
            let tol = if up { 1e-6 } else { 1e-3 };
            assert!((classic - want).abs().max_element() < tol, "up {up}, reverse {reverse}: classic {classic}");
            let path = mean(&pixels(&with, EngineKind::Path, 64)) - mean(&pixels(&without, EngineKind::Path, 64));
            println!(
                "facing up {up}, reverse {reverse}: the back material adds {path} in the path engine, {want} classic"
            );
            if up {
                assert_eq!(path, Vec3A::ZERO, "seen from the front");
            } else {
                assert!((path - want).abs().max_element() <= 0.02 * want.max_element(), "{path} vs {want}");
            }
        }
    }
}

/// A black back material changes nothing in the path engine: the pane's image (seen from
/// either side) with a back material of colour 0, reversed or not, equals the image
/// without one bit for bit.
#[test]
fn a_black_back_material_changes_nothing() {
    for up in [false, true] {
        let without = pixels(&pane(None, false, up, true, -1.0), EngineKind::Path, 4);
        for reverse in [false, true] {
            let black = pixels(&pane(Some("0 0 0"), reverse, up, true, -1.0), EngineKind::Path, 4);
            assert!(without == black, "facing up {up}, reverse {reverse}");
        }
    }
}
