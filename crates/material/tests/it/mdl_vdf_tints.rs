//! Tints of vdfs in module materials (tests/mdl/vdf_tints.mdl): `df::tint(t, vdf)` scatters
//! σs·t with the vdf's phase function and absorbs σs·(1 − t), so the extinction σa + σs
//! is unchanged (t clamped to [0, 1] per channel); tints of mixes and nested tints
//! multiply, and a tinted mix keeps its lobes' mixture as its phase function; a tint that
//! varies over the surface is a warning at its module line.

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
    let lobes: Vec<(f32, f32)> = m.phase.lobes().iter().map(|(w, l)| (*w, l.g)).collect();
    assert_eq!(lobes.len(), 2, "{lobes:?}");
    for ((w, g), (want_w, want_g)) in lobes.iter().zip([(0.6, 0.8), (0.4, -0.4)]) {
        assert!((w - want_w).abs() < 1e-6 && (g - want_g).abs() < 1e-6, "{lobes:?}");
    }
}

#[test]
fn a_tint_that_varies_over_the_surface_is_a_warning_at_its_line() {
    let (mdl, lib, messages) = compile_text(r#"shader "v" "mdl::vdf_tints::varying_tint" ()"#);
    let line = include_str!("../mdl/vdf_tints.mdl")
        .lines()
        .position(|l| l.contains("df::tint(color(state::position().x)"))
        .expect("the module's varying tint")
        + 1;
    assert!(
        messages.iter().any(|m| m.contains("`df::tint` of a vdf") && m.contains(&format!("vdf_tints.mdl:{line}:"))),
        "a warning at vdf_tints.mdl:{line}: {messages:#?}"
    );
    let m = get(&mdl, &lib, "v").medium.expect("the volume still scatters");
    assert_eq!(m.phase.g, 0.0, "isotropically");
    assert!(close(m.sigma_s, Rgb::ONE, 1e-6), "{m:?}");
}
