//! The MDL material compiler: `.mi` instances of materials from modules on the search path
//! (tests/mdl/mixes.mdl, scenes/mdl/) become path-engine materials. Each test checks the
//! compiled model against what the MDL expression means (weights, defaults, overrides),
//! and the mixers and layerers pass a white furnace (`bsdf::testing::albedo`).

use crate::mdl_support;

use std::path::Path;

use bsdf::Rgb;
use glam::Vec3A;
use material::mdl_modules::compile;
use material::SurfaceModel;
use mdl_lang::MdlSearchPath;
use mdl_support::{close, compile_text, dirs, get};

/// Directions of incidence for the furnace (local frame, z up).
fn incidences() -> [Vec3A; 3] {
    [Vec3A::Z, Vec3A::new(0.6, 0.0, 0.8), Vec3A::new(0.0, 0.95, 0.312_25).normalize()]
}

#[test]
fn matte_instances_override_the_defaults() {
    let (mdl, lib, diags) = compile_text(
        r#"$include "export_multi.mdl"
shader "red" "mdl::export_multi::matte" ("tint" 0.5 0 0, "roughness" 0)
shader "rough" "mdl::export_multi::matte" ("roughness" 0.3)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let red = get(&mdl, &lib, "red");
    assert_eq!(red.model, SurfaceModel::Lambert);
    assert!(close(red.diffuse, Rgb::new(0.5, 0.0, 0.0), 1e-6), "{:?}", red.diffuse);
    // The default tint (0.8) and an Oren–Nayar roughness.
    let rough = get(&mdl, &lib, "rough");
    assert_eq!(rough.model, SurfaceModel::OrenNayar(0.3));
    assert!(close(rough.diffuse, Rgb::splat(0.8), 1e-6));
}

#[test]
fn let_material_reads_its_overridden_parameters() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "p" "mdl::let_material::plaster" ("base" 0.8 0.8 0.8, "dirt" 0.5, "gloss" 0.4)
shader "s" "mdl::let_material::shade" ("level" 0.25)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    // dirty = 0.8 · (1 − 0.5) = 0.4; rough = 1 − 0.4 = 0.6; gloss 0.4 ≤ 0.5 gives the glossy
    // layer (α = 0.6²) weight 0.1, so the diffuse base keeps 0.9 of it: 0.36.
    let p = get(&mdl, &lib, "p");
    assert!(close(p.diffuse, Rgb::splat(0.36), 1e-6), "{:?}", p.diffuse);
    let SurfaceModel::Lobes(l) = &p.model else { panic!("{:?}", p.model) };
    assert!(close(l.diffuse.albedo, Rgb::splat(0.36), 1e-6) && close(l.reflect, Rgb::splat(0.1), 1e-6));
    assert!((l.reflect_ggx.alpha_x - 0.36).abs() < 1e-6);
    assert_eq!(l.diffuse, bsdf::OrenNayar::new(l.diffuse.albedo, 0.6), "Oren–Nayar σ = rough");
    let s = get(&mdl, &lib, "s");
    assert!(close(s.diffuse, Rgb::splat(0.25), 1e-6), "{:?}", s.diffuse);
}

#[test]
fn a_three_module_import_chain_compiles() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "coat" "mdl::chain::top::red_coat" ()
shader "plain" "mdl::chain::top::plain" ("r" 0.2)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    // red_coat: a gloss (weight 1) specular coat of IOR 1.5 over the bottom module's
    // rough diffuse of tint (0.8, 0.1, 0.1).
    let coat = get(&mdl, &lib, "coat");
    let SurfaceModel::Unified(u) = &coat.model else { panic!("{:?}", coat.model) };
    let p = u.params();
    assert!(
        close(p.base_color, Rgb::new(0.8, 0.1, 0.1), 1e-6) && p.ior == 1.5 && p.specular == 1.0 && p.roughness == 0.0
    );
    let plain = get(&mdl, &lib, "plain");
    assert_eq!(plain.model, SurfaceModel::OrenNayar(0.2));
    assert!(close(plain.diffuse, Rgb::splat(0.5), 1e-6));
}

#[test]
fn mixes_normalize_and_clamp_their_weights_and_pass_the_white_furnace() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "n" "mdl::mixes::normalized" ()
shader "c" "mdl::mixes::clamped" ()
shader "k" "mdl::mixes::coloured" ("level" 0.5)
shader "l" "mdl::mixes::layered" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    // 0.7 + 0.6 of white, normalized: albedo 1 (lossless).
    let n = get(&mdl, &lib, "n");
    assert!(close(n.diffuse, Rgb::ONE, 1e-6), "{:?}", n.diffuse);
    // Clamped: 0.7 red + 0.3 green.
    let c = get(&mdl, &lib, "c");
    assert!(close(c.diffuse, Rgb::new(0.7, 0.3, 0.0), 1e-6), "{:?}", c.diffuse);
    // Per channel: red 1 + 1 → ½ each: ½ + ¼; green 0.5 + 1 → ⅓, ⅔: ⅓ + ⅓; blue 0 + 0.25·0.5; times 0.5.
    let k = get(&mdl, &lib, "k");
    let want = Rgb::new(0.75, 2.0 / 3.0, 0.125) * 0.5;
    assert!(close(k.diffuse, want, 1e-6), "{:?} vs {want:?}", k.diffuse);
    // A quarter red over three quarters blue.
    let l = get(&mdl, &lib, "l");
    assert!(close(l.diffuse, Rgb::new(0.25, 0.0, 0.75), 1e-6), "{:?}", l.diffuse);
    for (name, m, lossless) in
        [("normalized", n, true), ("clamped", c, false), ("coloured", k, false), ("layered", l, false)]
    {
        for wo in incidences() {
            let a = bsdf::testing::albedo(&m.bsdf(wo), wo, 20_000);
            assert!(a.max_element() <= 1.0 + 0.01, "{name}: albedo {a:?} at {wo:?}");
            if lossless {
                assert!((a - Rgb::ONE).abs().max_element() <= 0.01, "{name}: albedo {a:?} at {wo:?}");
            }
        }
    }
}

#[test]
fn glass_metal_and_cutouts_compile_to_their_families() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "g" "mdl::mixes::glass" ("ior" 1.33)
shader "t" "mdl::mixes::glass" ("thin" on)
shader "m" "mdl::mixes::metal" ()
shader "leaf" "mdl::mixes::leaf" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let g = get(&mdl, &lib, "g");
    let SurfaceModel::Unified(u) = &g.model else { panic!("{:?}", g.model) };
    assert!(u.params().spec_trans == 1.0 && u.params().ior == 1.33 && !u.params().thin);
    assert!(g.has_inside());
    let t = get(&mdl, &lib, "t");
    assert!(!t.has_inside(), "thin-walled glass has no inside");
    // Thin glass is lossless: what it does not reflect passes.
    for wo in incidences() {
        let a = bsdf::testing::albedo(&t.bsdf(wo), wo, 20_000);
        assert!((a - Rgb::ONE).abs().max_element() <= 0.01, "thin glass: albedo {a:?} at {wo:?}");
    }
    // The GGX lobe weighted by its tint (MDL's glossy BSDFs have no Fresnel term).
    let m = get(&mdl, &lib, "m");
    let SurfaceModel::Lobes(l) = &m.model else { panic!("{:?}", m.model) };
    assert!(l.reflect_ggx.alpha_x == 0.04 && l.reflect_ggx.alpha_y == 0.04);
    assert!(close(l.reflect, Rgb::new(0.9, 0.6, 0.3), 1e-6) && l.diffuse.albedo == Rgb::ZERO);
    for wo in incidences() {
        let a = bsdf::testing::albedo(&m.bsdf(wo), wo, 20_000);
        assert!(a.max_element() <= 1.01, "metal: albedo {a:?}");
    }
    let leaf = get(&mdl, &lib, "leaf");
    assert_eq!(leaf.opacity, 0.25);
}

#[test]
fn emission_is_radiance_from_the_exitance() {
    let (mdl, lib, diags) =
        compile_text(r#"shader "e" "mdl::export_multi::emitter" ("tint" 1 0.5 0.25, "intensity" 20)"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let e = get(&mdl, &lib, "e");
    // Radiant exitance 20 · tint of a Lambertian emitter: radiance 20 · tint / π.
    let want = Rgb::new(1.0, 0.5, 0.25) * 20.0 / std::f32::consts::PI;
    assert!(close(e.emission, want, 1e-5) && !e.emission_over_area, "{:?}", e.emission);
}

#[test]
fn parameter_errors_are_reported_at_the_mi_line() {
    let (mdl, lib, diags) = compile_text(
        r#"$include "export_multi.mdl"
shader "bad" "mdl::export_multi::matte" ("tint" "red",
    "shine" 1)"#,
    );
    assert_eq!(diags.len(), 2, "{diags:#?}");
    assert!(
        diags[0].contains("t.mi:2:") && diags[0].contains("'tint'") && diags[0].contains("expected a colour"),
        "{}",
        diags[0]
    );
    assert!(diags[1].contains("t.mi:3:") && diags[1].contains("no parameter 'shine'"), "{}", diags[1]);
    let bad = get(&mdl, &lib, "bad");
    assert_eq!(bad.diffuse, Rgb::splat(0.5), "rendered grey");
}

#[test]
fn what_is_not_compiled_is_named_with_its_module_line() {
    let (mdl, lib, diags) = compile_text(r#"shader "p" "mdl::textured::noisy" ()"#);
    // At the .mi instance, naming the module's line.
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let d = &diags[0];
    assert!(d.contains("t.mi:1:") && d.contains("textured.mdl:51:") && d.contains("Ptex"), "{d}");
    assert_eq!(get(&mdl, &lib, "p").diffuse, Rgb::splat(0.5), "rendered grey");
}

#[test]
fn missing_modules_and_materials_are_reported() {
    let (_, _, diags) = compile_text(
        r#"shader "a" "mdl::no_such_module::m" ()
shader "b" "mdl::export_multi::no_such_material" ()"#,
    );
    assert_eq!(diags.len(), 2, "{diags:#?}");
    assert!(
        diags.iter().any(|d| d.contains("t.mi:1:") && d.contains("`::no_such_module` could not be loaded")),
        "{diags:#?}"
    );
    assert!(diags.iter().any(|d| d.contains("t.mi:2:") && d.contains("exports no `no_such_material`")), "{diags:#?}");
}

#[test]
fn a_module_matte_equals_the_native_core_definitions_diffuse() {
    let (mdl, lib, diags) = compile_text(
        r#"$include "export_multi.mdl"
shader "module" "mdl::export_multi::matte" ("tint" 0.5 0.25 0, "roughness" 0.2)
shader "native" "mdl::nvidia::core_definitions::diffuse" ("diffuse_color" 0.5 0.25 0, "roughness" 0.2)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let module = get(&mdl, &lib, "module");
    let native =
        scene::Material { name: "native".into(), kind: scene::MaterialKind::Shader(lib.shaders["native"].clone()) };
    let (native, w) = material::translate_with(&native, &lib, None, Some(&mdl));
    assert!(w.is_empty(), "{w:?}");
    assert_eq!(module.model, native.model);
    assert_eq!(module.diffuse, native.diffuse);
}

#[test]
fn a_core_definitions_module_on_the_search_path_replaces_the_native_translation() {
    let text = r#"shader "d" "mdl::nvidia::core_definitions::diffuse" ()
options "o" end options
camera "test_cam" end camera
instance "ci" "test_cam" end instance
instgroup "root" "ci" end instgroup
render "root" "ci" "o"
"#;
    let parsed = mi::parse_str("t.mi", text);
    let scene = scene::Scene::build(&parsed, 0, &mut Vec::new()).expect("a scene");
    let d = scene::Material { name: "d".into(), kind: scene::MaterialKind::Shader(scene.library.shaders["d"].clone()) };
    // Without it: mira's own `diffuse` (default colour 0.8), nothing compiled.
    let (mdl, diags) = compile(&scene.library, MdlSearchPath::for_scene(None, &dirs(), None));
    assert!(diags.is_empty() && mdl.is_empty(), "{diags:?}");
    let (native, _) = material::translate_with(&d, &scene.library, None, Some(&mdl));
    assert_eq!(native.diffuse, Rgb::splat(0.8));
    // With tests/override/nvidia/core_definitions.mdl (its `diffuse` defaults to 0.25).
    let over = Path::new(env!("CARGO_MANIFEST_DIR")).join("../mdl_lang/tests/override");
    let (mdl, diags) = compile(&scene.library, MdlSearchPath::for_scene(None, &[over], None));
    assert!(diags.is_empty() && mdl.len() == 1, "{diags:?}");
    let (replaced, _) = material::translate_with(&d, &scene.library, None, Some(&mdl));
    assert_eq!(replaced.diffuse, Rgb::splat(0.25));
}

#[test]
fn a_connected_parameter_is_a_warning_and_takes_its_default() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "tex" "mdl::base::file_texture" ()
shader "m" "mdl::export_multi::matte" ("tint" = "tex.tint", "roughness" 0.1)"#,
    );
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert!(
        diags[0].contains("t.mi:2:") && diags[0].contains("warning") && diags[0].contains("'tex.tint'"),
        "{}",
        diags[0]
    );
    let m = get(&mdl, &lib, "m");
    assert_eq!(m.diffuse, Rgb::splat(0.8));
    assert_eq!(m.model, SurfaceModel::OrenNayar(0.1));
}

#[test]
fn layers_of_glossy_and_diffuse_transmission_are_lobe_sums_that_pass_the_white_furnace() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "gl" "mdl::mixes::glossy_over_diffuse" ()
shader "tr" "mdl::mixes::translucent" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let gl = get(&mdl, &lib, "gl");
    let SurfaceModel::Lobes(l) = &gl.model else { panic!("{:?}", gl.model) };
    assert!(close(l.reflect, Rgb::splat(0.3), 1e-6) && close(l.diffuse.albedo, Rgb::splat(0.7), 1e-6));
    let tr = get(&mdl, &lib, "tr");
    let SurfaceModel::Lobes(t) = &tr.model else { panic!("{:?}", tr.model) };
    assert!(close(t.transl, Rgb::splat(0.5), 1e-6) && close(t.diffuse.albedo, Rgb::splat(0.5), 1e-6));
    for wo in incidences() {
        // GGX single scattering loses a little energy at α = 0.25: at most 1; the diffuse
        // reflection and transmission halves together are lossless.
        let a = bsdf::testing::albedo(&gl.bsdf(wo), wo, 50_000);
        assert!(a.max_element() <= 1.01 && a.min_element() >= 0.9, "glossy over diffuse: {a:?} at {wo:?}");
        let a = bsdf::testing::albedo(&tr.bsdf(wo), wo, 50_000);
        assert!((a - Rgb::ONE).abs().max_element() <= 0.01, "diffuse reflection + transmission: {a:?} at {wo:?}");
    }
}

#[test]
fn beckmann_ward_two_roughnesses_and_sheen_are_general_lobe_sums_that_pass_the_white_furnace() {
    use bsdf::beckmann::Beckmann;
    use bsdf::microfacet::Ggx;
    use bsdf::Lobe;
    let (mdl, lib, diags) = compile_text(
        r#"shader "b" "mdl::lobes::beckmann_over_diffuse" ()
shader "g" "mdl::lobes::two_glossy" ()
shader "v" "mdl::lobes::velvet" ()
shader "w" "mdl::lobes::ward_over_diffuse" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let lobes = |name: &str| {
        let m = get(&mdl, &lib, name);
        let SurfaceModel::MdlLobes(l) = &m.model else { panic!("{name}: {:?}", m.model) };
        (m, l.parts().collect::<Vec<_>>())
    };
    // Layer weight 0.4 on the Beckmann lobe; the base keeps 0.6 of its 0.5.
    let (b, parts) = lobes("b");
    assert_eq!(
        parts,
        vec![(Rgb::splat(0.4), Lobe::Beckmann(Beckmann::new(0.3, 0.3))), (Rgb::splat(0.3), Lobe::Diffuse(0.0))]
    );
    assert!(close(b.diffuse, Rgb::splat(0.3), 1e-6));
    let (g, parts) = lobes("g");
    assert_eq!(
        parts,
        vec![(Rgb::splat(0.5), Lobe::Ggx(Ggx::isotropic(0.05))), (Rgb::splat(0.5), Lobe::Ggx(Ggx::isotropic(0.4)))]
    );
    // The sheen of the tint over the diffuse base tinted by ½: 0.5 · tint.
    let (v, parts) = lobes("v");
    let tint = Rgb::new(0.8, 0.2, 0.3);
    assert_eq!(parts, vec![(tint, Lobe::Sheen(0.4)), (tint * 0.5, Lobe::Diffuse(0.0))]);
    let (w, parts) = lobes("w");
    assert_eq!(
        parts,
        vec![(Rgb::splat(0.5), Lobe::Ward(Beckmann::new(0.2, 0.1))), (Rgb::splat(0.25), Lobe::Diffuse(0.0))]
    );
    for (name, m) in [("beckmann", b), ("two glossy", g), ("velvet", v), ("ward", w)] {
        for wo in incidences() {
            let a = bsdf::testing::albedo(&m.bsdf(wo), wo, 20_000);
            assert!(a.max_element() <= 1.01, "{name}: albedo {a:?} at {wo:?}");
        }
    }
}

/// A mix of five distinct lobes, one more than the compact `bsdf::Lobes` holds: a wide sum
/// of the five, no warning; seventeen, one more than a wide sum holds: its diffuse part
/// (0.5/17) with a warning that says the sum is full, not that the BSDFs are unknown.
#[test]
fn a_sum_past_the_lobe_limit_is_wide_then_says_so() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "five" "mdl::lobes::five_lobes" ()
shader "seventeen" "mdl::lobes::seventeen_lobes" ()"#,
    );
    let m = get(&mdl, &lib, "five");
    let SurfaceModel::MdlWide(l) = &m.model else { panic!("five: {:?}", m.model) };
    assert_eq!(l.len(), 5);
    assert!(close(m.diffuse, Rgb::splat(0.1), 1e-6), "{:?}", m.diffuse);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let want =
        format!("needs more than the {} lobes and {} layer curves", bsdf::lobes::WIDE_LOBES, bsdf::lobes::WIDE_CURVES);
    assert!(diags[0].contains(&want) && diags[0].contains("t.mi:2:"), "{}", diags[0]);
    let m = get(&mdl, &lib, "seventeen");
    assert_eq!(m.model, SurfaceModel::Lambert);
    assert!(close(m.diffuse, Rgb::splat(0.5 / 17.0), 1e-6), "{:?}", m.diffuse);
}

/// A `$include`d module that does not load — malformed, or on no directory of the search
/// path — is a warning at the `$include`'s line naming the module's own `file:line:col`
/// even when no shader uses it (it used to pass unnoticed); one a shader uses is reported
/// at that shader, once.
#[test]
fn an_included_module_that_does_not_load_is_reported_at_its_include() {
    let dir = std::env::temp_dir().join(format!("mira-mdl-bad-include-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("broken.mdl"),
        "mdl 1.7;\nimport ::df::*;\nexport material m() = material(\n    surface: material_surface(scattering: df::no_such_bsdf()));\n",
    )
    .unwrap();
    let (_, _, diags) = mdl_support::compile_text_with(
        r#"$include "broken.mdl"
$include "absent.mdl"
$include "broken.mdl""#,
        std::slice::from_ref(&dir),
    );
    assert_eq!(diags.len(), 2, "{diags:#?}");
    assert!(
        diags.iter().any(|d| d.contains("t.mi:1:")
            && d.contains("`::broken` could not be loaded")
            && d.contains("broken.mdl:4:")),
        "{diags:#?}"
    );
    assert!(diags.iter().any(|d| d.contains("t.mi:2:") && d.contains("`::absent` could not be loaded")), "{diags:#?}");
    let (_, _, diags) = mdl_support::compile_text_with(
        r#"$include "broken.mdl"
shader "s" "mdl::broken::m" ()"#,
        std::slice::from_ref(&dir),
    );
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert!(diags[0].contains("t.mi:2:") && diags[0].contains("renders grey"), "{}", diags[0]);
}

/// `material_emission(diffuse_edf(), intensity, mode)`: a radiant exitance E gives radiance
/// E/π; a power Φ (`intensity_power`) gives Φ/π, marked to be divided by the area of all
/// triangles of the material when the scene is built (the division `add_emission`'s
/// `lumen` shares, `crates/render/tests/it/path_materials.rs`); 1e-6.
#[test]
fn emission_intensity_modes_give_radiance_or_power() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "exitance" "mdl::emission_modes::lamp" ("intensity" 2 4 6)
shader "power" "mdl::emission_modes::lamp" ("intensity" 2 4 6, "mode" "intensity_power")"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let want = Rgb::new(2.0, 4.0, 6.0) / std::f32::consts::PI;
    let e = get(&mdl, &lib, "exitance");
    assert!(close(e.emission, want, 1e-6) && !e.emission_over_area, "{:?}", e.emission);
    let p = get(&mdl, &lib, "power");
    assert!(close(p.emission, want, 1e-6) && p.emission_over_area, "{:?}", p.emission);
}
