//! Tints of vdfs in module materials (tests/mdl/vdf_tints.mdl): `df::tint(t, vdf)` scatters
//! σs·t with the vdf's phase function and absorbs σs·(1 − t), so the extinction σa + σs
//! is unchanged (t clamped to [0, 1] per channel); tints of mixes and nested tints
//! multiply, and a tinted mix keeps its lobes' mixture as its phase function; a tint that
//! varies over the surface is evaluated where a path enters the object.

use crate::mdl_support;

use bsdf::Rgb;
use mdl_support::{close, compile_text, get};

#[test]
fn a_tinted_vdf_scatters_its_share_and_absorbs_the_rest() {
    let (mdl, lib, messages) = compile_text(
        r#"shader "tinted" "mdl::vdf_tints::tinted" ()
shader "over" "mdl::vdf_tints::tinted" ("tint" 1.5 -1 0.5, "bias" -0.3)
shader "mix" "mdl::vdf_tints::tinted_mix" ()"#,
    );
    assert!(messages.is_empty(), "{messages:#?}");
    let medium = |name: &str| get(&mdl, &lib, name).medium.unwrap_or_else(|| panic!("{name} has a medium"));
    // σs = 2 · (0.5, 0.25, 1), σa = 0.1 + 2 · (0.5, 0.75, 0), g 0.6.
    let m = medium("tinted");
    assert!(close(m.sigma_s, Rgb::new(1.0, 0.5, 2.0), 1e-6), "{m:?}");
    assert!(close(m.sigma_a, Rgb::new(1.1, 1.6, 0.1), 1e-6), "{m:?}");
    assert!((m.phase.g - 0.6).abs() < 1e-6, "{m:?}");
    // Clamped to (1, 0, 0.5): σs (2, 0, 1), σa (0.1, 2.1, 1.1), g −0.3.
    let m = medium("over");
    assert!(close(m.sigma_s, Rgb::new(2.0, 0.0, 1.0), 1e-6), "{m:?}");
    assert!(close(m.sigma_a, Rgb::new(0.1, 2.1, 1.1), 1e-6), "{m:?}");
    assert!((m.phase.g + 0.3).abs() < 1e-6, "{m:?}");
    // The mix scatters 0.5 (g (0.3·0.8 − 0.2·0.4)/0.5 = 0.32), tinted by 0.5 and then by
    // (0.8, 1, 1): σs = 2 · 0.25 · (0.8, 1, 1), the rest of 2 absorbed.
    let m = medium("mix");
    assert!(close(m.sigma_s, Rgb::new(0.4, 0.5, 0.5), 1e-6), "{m:?}");
    assert!(close(m.sigma_a, Rgb::new(1.6, 1.5, 1.5), 1e-6), "{m:?}");
    assert!((m.phase.g - 0.32).abs() < 1e-6, "{m:?}");
    // Its phase function is the two lobes' mixture, weighted 0.6 and 0.4 (what each
    // scatters), not one lobe of their mean cosine.
    let lobes: Vec<(Rgb, f32)> = m.phase.lobes().map(|(w, l)| (w, l.g)).collect();
    assert_eq!(lobes.len(), 2, "{lobes:?}");
    assert!(!m.phase.is_chromatic(), "grey weights: {m:?}");
    for ((w, g), (want_w, want_g)) in lobes.iter().zip([(0.6, 0.8), (0.4, -0.4)]) {
        assert!(close(*w, Rgb::splat(want_w), 1e-6) && (g - want_g).abs() < 1e-6, "{lobes:?}");
    }
}

/// A tint that varies over the surface (`color(state::position().x)`) gives no warning:
/// the volume is evaluated where a path enters the object. Entered at x = 0.3 it scatters
/// σs·0.3 and absorbs σs·0.7 (σs 1, g 0.5); at x = 2 the tint clamps to 1; at x = −1 to
/// 0 (all absorbed); within 1e-6. The material's constant medium is the volume at the
/// default point (the origin: all absorbed).
#[test]
fn a_tint_that_varies_over_the_surface_is_evaluated_where_a_path_enters() {
    let (mdl, lib, messages) = compile_text(r#"shader "v" "mdl::vdf_tints::varying_tint" ()"#);
    assert!(messages.is_empty(), "{messages:#?}");
    let m = get(&mdl, &lib, "v");
    assert!(m.varying_medium.is_some(), "{m:?}");
    let default = m.medium.expect("a medium at the default point");
    assert!(close(default.sigma_s, Rgb::ZERO, 1e-6) && close(default.sigma_a, Rgb::ONE, 1e-6), "{default:?}");
    for (x, tint) in [(0.3f32, 0.3f32), (2.0, 1.0), (-1.0, 0.0)] {
        let state = shader::State { point: glam::Vec3A::new(x, 0.5, -2.0), ..Default::default() };
        let at = m.medium_at(&state).expect("a medium");
        assert!(close(at.sigma_s, Rgb::splat(tint), 1e-6), "x {x}: {at:?}");
        assert!(close(at.sigma_a, Rgb::splat(1.0 - tint), 1e-6), "x {x}: {at:?}");
        if tint > 0.0 {
            assert!((at.phase.g - 0.5).abs() < 1e-6, "x {x}: {at:?}");
        }
    }
}
