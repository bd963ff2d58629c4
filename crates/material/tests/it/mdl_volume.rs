//! MDL `material_volume` lowered to the path engine's medium: absorption and scattering
//! coefficients (per metre, one scene unit), `df::anisotropic_vdf`'s directional bias as the
//! Henyey–Greenstein g, the default `vdf()` isotropic, an unsupported vdf warned at its line
//! in the module, thin-walled materials and volumes that do nothing without a medium.
//! The module is scenes/mdl/media.mdl.

use crate::mdl_support;

use bsdf::Rgb;
use mdl_support::{close, compile_text, get};

#[test]
fn volume_coefficients_and_the_vdf_become_the_medium() {
    let (mdl, lib, messages) = compile_text(
        r#"$include "media.mdl"
shader "gel" "mdl::media::tinted_gel" ()
shader "smoke" "mdl::media::smoke" ("scattering" 0.5 1 2, "absorption" 0.1 0 0.3, "bias" 0.6)
shader "back" "mdl::media::smoke" ("bias" -0.4)
shader "milky" "mdl::media::milky_glass" ()
shader "clear" "mdl::media::smoke" ("scattering" 0 0 0)
shader "glow" "mdl::media::glow" ()
"#,
    );
    assert!(messages.is_empty(), "{messages:#?}");
    let gel = get(&mdl, &lib, "gel").medium.expect("the gel has a medium");
    assert!(close(gel.sigma_a, Rgb::new(0.5, 1.0, 2.0), 1e-6) && gel.sigma_s == Rgb::ZERO, "{gel:?}");
    assert!(get(&mdl, &lib, "gel").has_inside(), "light enters the gel");
    assert_eq!(get(&mdl, &lib, "gel").model.index_matched(), Some(Rgb::ONE), "ior 1: an index-matched boundary");
    let smoke = get(&mdl, &lib, "smoke").medium.expect("the smoke has a medium");
    assert!(close(smoke.sigma_s, Rgb::new(0.5, 1.0, 2.0), 1e-6), "{smoke:?}");
    assert!(close(smoke.sigma_a, Rgb::new(0.1, 0.0, 0.3), 1e-6), "{smoke:?}");
    assert!((smoke.phase.g - 0.6).abs() < 1e-6, "{smoke:?}");
    assert!((get(&mdl, &lib, "back").medium.expect("a medium").phase.g + 0.4).abs() < 1e-6);
    let milky = get(&mdl, &lib, "milky");
    assert!(
        milky.medium.is_some() && milky.model.index_matched().is_none(),
        "glass of ior 1.5 is no index-matched boundary"
    );
    assert_eq!(get(&mdl, &lib, "clear").medium, None, "a volume that neither absorbs nor scatters is no medium");
    assert_eq!(get(&mdl, &lib, "glow").medium, None, "no volume");
}

#[test]
fn the_default_vdf_is_isotropic_and_thin_walled_materials_have_no_medium() {
    let (mdl, lib, messages) = compile_text(
        "$include \"media.mdl\"\nshader \"thick\" \"mdl::media::haze\" ()\nshader \"thin\" \"mdl::media::haze\" (\"thin\" on)\n",
    );
    assert!(messages.is_empty(), "{messages:#?}");
    let thick = get(&mdl, &lib, "thick").medium.expect("a medium");
    assert_eq!(thick.phase.g, 0.0, "vdf() scatters isotropically");
    assert!(close(thick.sigma_s, Rgb::splat(2.0), 1e-6));
    assert_eq!(get(&mdl, &lib, "thin").medium, None, "a thin-walled material has no inside");
}

/// `df::fog_vdf()` (scenes/mdl/media.mdl's `fog`) scatters by the approximate Mie phase
/// function of 8 µm droplets (MDL's default diameter), without a warning: the medium's
/// phase function is `bsdf::phase::fog_lobes(8)`'s blend exactly; `fog_vdf(particle_size:
/// 10.0)` in a normalized mix with a tinted Henyey–Greenstein lobe (the public MDL SDK
/// test module's `vol_vdf_mix`, crates/material/tests/mdl/fog_mix.mdl) keeps all three lobes, weighted 0.3 and 0.7 × the fog's
/// own weights, and its mean cosine is the weighted sum of theirs (1e-5).
#[test]
fn fog_vdf_scatters_by_its_mie_approximation() {
    let (mdl, lib, messages) = compile_text("$include \"media.mdl\"\nshader \"fog\" \"mdl::media::fog\" ()\n");
    assert!(messages.is_empty(), "{messages:#?}");
    let fog = get(&mdl, &lib, "fog").medium.expect("the fog scatters");
    assert_eq!(fog.phase, bsdf::Phase::mixture_of(&bsdf::phase::fog_lobes(8.0)));
    assert!(fog.phase.g > 0.85 && fog.phase.g < 0.87, "{fog:?}");
    let (mdl, lib, messages) =
        compile_text("$include \"fog_mix.mdl\"\nshader \"m\" \"mdl::fog_mix::vol_vdf_mix\" ()\n");
    assert!(messages.is_empty(), "{messages:#?}");
    let m = get(&mdl, &lib, "m").medium.expect("a medium");
    let fog = bsdf::phase::fog_lobes(10.0);
    let lobes: Vec<(Rgb, bsdf::phase::Draine)> = m.phase.lobes().collect();
    assert_eq!(lobes.len(), 3, "{m:?}");
    assert!((lobes[0].0.x - 0.3).abs() < 1e-6 && lobes[0].1.g == 0.5 && lobes[0].1.alpha == 0.0, "{lobes:?}");
    for (k, (w, l)) in fog.iter().enumerate() {
        assert!((lobes[k + 1].0.x - 0.7 * w).abs() < 1e-6 && lobes[k + 1].1 == *l, "{lobes:?}");
    }
    let want = 0.3 * 0.5 + 0.7 * fog.iter().map(|(w, l)| w * l.mean_cosine()).sum::<f32>();
    assert!((m.phase.g - want).abs() < 1e-5, "{} vs {want}", m.phase.g);
}

/// A scene (no MDL modules compiled) of the shader statements `shaders`, each of the
/// `materials` they define on a triangle of its own.
fn triangle_scene(shaders: &str, materials: &[&str]) -> scene::Scene {
    let faces: String = materials.iter().map(|m| format!(" c \"{m}\" 0 1 2")).collect();
    let text = format!(
        r#"{shaders}options "o" end options
camera "c" end camera
instance "ci" "c" end instance
object "tri" group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2{faces} end group end object
instance "ti" "tri" end instance
instgroup "root" "ci" "ti" end instgroup
render "root" "ci" "o"
"#
    );
    let parsed = mi::parse_str("t.mi", &text);
    let mut diags = Vec::new();
    scene::Scene::build(&parsed, 0, &mut diags).expect("a scene")
}

/// The material `name` of `scene` translated natively (no compiled MDL), asserting no
/// warning.
fn translated(scene: &scene::Scene, name: &str) -> material::SurfaceMaterial {
    let m = scene.materials.iter().find(|m| m.name == name).unwrap_or_else(|| panic!("no material {name}"));
    let (surface, warnings) = material::translate(m, &scene.library, None);
    assert!(warnings.is_empty(), "{warnings:?}");
    surface
}

/// `core_definitions::flex_material` (translated natively): a transparent, thick material
/// absorbs σa = −ln(volume_color) / base_thickness inside; the default volume colour 1
/// and a thin-walled one give no medium.
#[test]
fn flex_material_volume_colour_becomes_absorption() {
    let scene = triangle_scene(
        r#"
shader "flex" "mdl::nvidia::core_definitions::flex_material" ("transparency" 1, "volume_color" 0.5 0.25 1, "base_thickness" 0.2)
shader "plain" "mdl::nvidia::core_definitions::flex_material" ("transparency" 1)
shader "thin" "mdl::nvidia::core_definitions::flex_material" ("transparency" 1, "volume_color" 0.5 0.5 0.5, "thin_walled" on)
"#,
        &["flex", "plain", "thin"],
    );
    let medium = |name: &str| translated(&scene, name).medium;
    let flex = medium("flex").expect("a medium");
    let want = Rgb::new(-(0.5f32.ln()), -(0.25f32.ln()), 0.0) / 0.2;
    assert!(close(flex.sigma_a, want, 1e-5) && flex.sigma_s == Rgb::ZERO, "{flex:?} vs σa {want:?}");
    assert_eq!(medium("plain"), None);
    assert_eq!(medium("thin"), None);
}

/// `core_definitions::thick_glass` (translated natively) as NVIDIA defines it: the glass
/// body absorbs σa = −ln(glass_color) / base_thickness, the surface transmits tinted by
/// `transmission_color` (ior 1: an index-matched boundary of that tint); a thickness of 0
/// and a clear glass colour give no medium; `thin_glass` has none.
#[test]
fn thick_glass_colour_becomes_absorption() {
    let scene = triangle_scene(
        r#"
shader "thick" "mdl::nvidia::core_definitions::thick_glass" ("glass_color" 0.5 0.25 0.8, "base_thickness" 0.2, "transmission_color" 0.9 0.8 0.7, "ior" 1)
shader "default" "mdl::nvidia::core_definitions::thick_glass" ()
shader "flat" "mdl::nvidia::core_definitions::thick_glass" ("glass_color" 0.5 0.5 0.5, "base_thickness" 0)
shader "clear" "mdl::nvidia::core_definitions::thick_glass" ("glass_color" 1 1 1)
shader "thin" "mdl::nvidia::core_definitions::thin_glass" ("glass_color" 0.5 0.5 0.5)
"#,
        &["thick", "default", "flat", "clear", "thin"],
    );
    let surface = |name: &str| translated(&scene, name);
    let thick = surface("thick");
    let medium = thick.medium.expect("a medium");
    let want = Rgb::new(-(0.5f32.ln()), -(0.25f32.ln()), -(0.8f32.ln())) / 0.2;
    assert!(close(medium.sigma_a, want, 1e-5) && medium.sigma_s == Rgb::ZERO, "{medium:?} vs σa {want:?}");
    assert!(thick.has_inside(), "light enters thick glass");
    let tint = thick.model.index_matched().expect("ior 1: index-matched");
    assert!(close(tint, Rgb::new(0.9, 0.8, 0.7), 1e-6), "the surface's tint is the transmission colour: {tint:?}");
    let default = surface("default").medium.expect("the default glass colour 0.95 absorbs");
    assert!(close(default.sigma_a, Rgb::splat(-(0.95f32.ln()) / 0.1), 1e-5), "{default:?}");
    assert_eq!(surface("flat").medium, None, "base_thickness 0: no absorption");
    assert_eq!(surface("clear").medium, None, "a clear glass colour absorbs nothing");
    assert_eq!(surface("thin").medium, None, "thin glass has no inside");
}

/// Mixes of vdfs lowered to one medium: the mix's weight W per channel scales the
/// scattering (σs·W; σs·(1 − W) is absorbed, the extinction unchanged) and g is the mean of
/// the lobes' g weighted by their scattering. media.mdl's `smoke_mix` mixes g 0.8 and
/// g −0.4: weights 0.5 + 0.5 scatter all (g 0.2), 0.75 + 0.75 are normalized to the same,
/// 0.3 + 0.2 scatter half (g (0.3·0.8 − 0.2·0.4)/0.5 = 0.32); `tinted_smoke_mix` clamps
/// colour weights (0.6, 0.8, 1) + (0.6, 0.4, 0.2) to (0.6, 0.8, 1) + (0.4, 0.2, 0): all
/// scattered, each channel by its own mixture of the two lobes (those weights; mean
/// cosines 0.3, 0.4, 0.5, their mean g 0.4).
#[test]
fn vdf_mixes_become_one_medium() {
    let (mdl, lib, messages) = compile_text(
        r#"$include "media.mdl"
shader "even" "mdl::media::smoke_mix" ()
shader "over" "mdl::media::smoke_mix" ("forward" 0.75, "backward" 0.75)
shader "half" "mdl::media::smoke_mix" ("scattering" 2 2 2, "forward" 0.3, "backward" 0.2)
shader "tinted" "mdl::media::tinted_smoke_mix" ("scattering" 1 2 3)
"#,
    );
    assert!(messages.is_empty(), "{messages:#?}");
    let medium = |name: &str| get(&mdl, &lib, name).medium.unwrap_or_else(|| panic!("{name} has a medium"));
    for name in ["even", "over"] {
        let m = medium(name);
        assert!(close(m.sigma_s, Rgb::splat(2.0), 1e-6) && close(m.sigma_a, Rgb::ZERO, 1e-6), "{name}: {m:?}");
        assert!((m.phase.g - 0.2).abs() < 1e-6, "{name}: {m:?}");
    }
    let half = medium("half");
    assert!(close(half.sigma_s, Rgb::ONE, 1e-6) && close(half.sigma_a, Rgb::ONE, 1e-6), "{half:?}");
    assert!((half.phase.g - 0.32).abs() < 1e-6, "{half:?}");
    let tinted = medium("tinted");
    assert!(
        close(tinted.sigma_s, Rgb::new(1.0, 2.0, 3.0), 1e-6) && close(tinted.sigma_a, Rgb::ZERO, 1e-6),
        "{tinted:?}"
    );
    assert!((tinted.phase.g - 0.4).abs() < 1e-6, "{tinted:?}");
    assert!(tinted.phase.is_chromatic(), "{tinted:?}");
    let lobes: Vec<(Rgb, f32)> = tinted.phase.lobes().map(|(w, l)| (w, l.g)).collect();
    assert_eq!(lobes.len(), 2, "{lobes:?}");
    for ((w, g), (want_w, want_g)) in lobes.iter().zip([(Rgb::new(0.6, 0.8, 1.0), 0.5), (Rgb::new(0.4, 0.2, 0.0), 0.0)])
    {
        assert!(close(*w, want_w, 1e-6) && (g - want_g).abs() < 1e-6, "{lobes:?}");
    }
}
