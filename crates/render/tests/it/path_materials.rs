//! Materials the path engine reads through the scene's shader graph: parameters connected
//! to MDL `::base` file textures and normal maps on MDL materials, mental ray texture
//! shaders and cutouts on `mia_material`, and the built-in BSDFs of a material's `bsdf`
//! slot. Each scene is a square seen head-on, lit head-on by a directional light
//! of irradiance π, so that a Lambertian pixel's value is its albedo (times the cosine to
//! a bent normal); the expected values follow from the texels.

use crate::support;

use render::EngineKind;
use shader::{Shading, ShadingOptions};
use support::QUADRANTS;

/// Renders `body` (materials, shaders) before the lit square of [`support::lit_square`],
/// whose instance takes `material`, with the path engine at 8×8: the pixels (RGBA, rows
/// from the top) and the diagnostics.
fn render(body: &str, material: &str, spp: u32) -> (Vec<[f32; 4]>, Vec<String>) {
    support::render_text(&support::lit_square(body, material), EngineKind::Path, Some(spp))
}

/// Pixels whose footprints lie inside one texel block (away from block edges, where
/// bilinear filtering blends): (x, y from the top, expected RGB).
const INSIDE: [(usize, usize, [f32; 3]); 4] =
    [(1, 6, [1.0, 0.0, 0.0]), (6, 6, [0.0, 1.0, 0.0]), (1, 1, [0.0, 0.0, 1.0]), (6, 1, [1.0, 1.0, 1.0])];

fn assert_rgb(got: [f32; 4], want: [f32; 3], tol: f32, what: &str) {
    for k in 0..3 {
        assert!((got[k] - want[k]).abs() <= tol, "{what}: got {got:?}, want {want:?} (±{tol})");
    }
}

#[test]
fn mdl_file_texture_drives_the_base_colour() {
    let body = format!(
        r#"{QUADRANTS}
shader "uvw" "mdl::base::coordinate_source(::base::texture_coordinate_system,int)" ("texture_space" 0)
shader "tex" "mdl::base::file_texture" ("texture" "quadrants", "uvw" = "uvw")
shader "mat" "mdl::nvidia::core_definitions::flex_material" ("base_color" = "tex.tint", "reflectivity" 0)"#
    );
    let (px, messages) = render(&body, "mat", 16);
    assert!(messages.is_empty(), "{messages:#?}");
    for (x, y, want) in INSIDE {
        assert_rgb(px[y * 8 + x], want, 1e-3, &format!("pixel ({x}, {y})"));
    }
}

#[test]
fn mdl_coordinate_transform_moves_the_texture() {
    // Translating the coordinates by (½, ½) (the texture repeats) shows each pixel the
    // diagonally opposite block.
    let body = format!(
        r#"{QUADRANTS}
shader "move" "mdl::base::rotation_translation_scale" ("translation" 0.5 0.5 0)
shader "uvw" "mdl::base::transform_coordinate" ("transform" = "move")
shader "tex" "mdl::base::file_texture" ("texture" "quadrants", "uvw" = "uvw")
shader "mat" "mdl::nvidia::core_definitions::diffuse" ("diffuse_color" = "tex")"#
    );
    let (px, messages) = render(&body, "mat", 4);
    assert!(messages.is_empty(), "{messages:#?}");
    for (x, y, _) in INSIDE {
        let opposite = INSIDE.iter().find(|(ox, oy, _)| *ox == 7 - x && *oy == 7 - y).unwrap().2;
        assert_rgb(px[y * 8 + x], opposite, 1e-3, &format!("pixel ({x}, {y})"));
    }
}

#[test]
fn mdl_tangent_space_normal_map_bends_the_shading_normal() {
    // One texel (0.854, 0.5, 0.854): tangent-space normal (0.707, 0, 0.707) after 2t − 1,
    // a 45° lean along u. Lit head-on, a white Lambertian surface gives cos 45°.
    let body = r#"color texture "lean" [ 1 1 ] 'da80da'
shader "n" "mdl::base::tangent_space_normal_texture" ("texture" "lean")
shader "mat" "mdl::nvidia::core_definitions::diffuse" ("diffuse_color" 1 1 1, "normal" = "n")"#;
    let (px, messages) = render(body, "mat", 4);
    assert!(messages.is_empty(), "{messages:#?}");
    // 0xda = 218 → 2·218/255 − 1 = 0.7098; 0x80 → 0.0039: the normal (0.7098, 0.0039, 0.7098)
    // normalised gives cos = 0.70709.
    let t = |b: f32| 2.0 * b / 255.0 - 1.0;
    let n = glam::Vec3::new(t(218.0), t(128.0), t(218.0)).normalize();
    for (i, p) in px.iter().enumerate() {
        assert_rgb(*p, [n.z; 3], 2e-3, &format!("pixel {i}"));
    }
}

#[test]
fn mia_material_reads_connected_textures_and_cuts_out() {
    // diffuse from a texture lookup; the left half cut out by a texture of opacity.
    let body = format!(
        r#"{QUADRANTS}
color texture "half" [ 4 1 ] '000000' '000000' 'ffffff' 'ffffff'
shader "coord" "mib_texture_vector" ("select" 0)
shader "diffuse_tex" "mib_texture_lookup" ("tex" "quadrants", "coord" = "coord")
shader "cut_tex" "mib_texture_lookup" ("tex" "half", "coord" = "coord")
material "m" "mia_material" ("diffuse" = "diffuse_tex", "reflectivity" 0, "diffuse_roughness" 0,
    "cutout_opacity" = "cut_tex") end material"#
    );
    let (px, messages) = render(&body, "m", 16);
    assert!(messages.is_empty(), "{messages:#?}");
    for (x, y, want) in INSIDE {
        let p = px[y * 8 + x];
        if x < 4 {
            assert_eq!(p, [0.0; 4], "pixel ({x}, {y}) is cut out");
        } else {
            assert_rgb(p, want, 1e-3, &format!("pixel ({x}, {y})"));
            assert_eq!(p[3], 1.0);
        }
    }
}

#[test]
fn builtin_bsdf_slot_renders_its_bsdf() {
    // A Lambertian built-in BSDF of reflectance (0.2, 0.4, 0.6): radiance ρ·E/π = ρ.
    let body = r#"shader "lb" "builtin_bsdf_lambert" ("diffuse" 0.2 0.4 0.6)
material "b" bsdf = "lb" end material"#;
    let (px, messages) = render(body, "b", 4);
    assert!(messages.is_empty(), "{messages:#?}");
    for (i, p) in px.iter().enumerate() {
        assert_rgb(*p, [0.2, 0.4, 0.6], 1e-3, &format!("pixel {i}"));
    }
}

#[test]
fn add_emission_units_give_the_radiance_of_the_square() {
    // The square has area 4. A Lambertian emitter of radiance L: flux πL·A, peak intensity
    // L·A, exitance πL, luminance L. Each unit below is chosen to give L = 1.
    for (unit, intensity) in [("lumen", 4.0 * std::f32::consts::PI), ("candela", 4.0), ("nit", 1.0)] {
        let body = format!(
            r#"shader "glow" "mdl::nvidia::core_definitions::add_emission" ("intensity" {intensity}, "unit" "{unit}")"#
        );
        let (px, messages) = render(&body, "glow", 1);
        assert!(messages.is_empty(), "{unit}: {messages:#?}");
        assert_rgb(px[27], [1.0; 3], 1e-4, unit);
    }
    let body =
        r#"shader "glow" "mdl::nvidia::core_definitions::add_emission" ("intensity" 3.14159265, "unit" "lumen_m2")"#;
    assert_rgb(render(body, "glow", 1).0[27], [1.0; 3], 1e-4, "lumen_m2");
}

#[test]
fn an_mdl_light_material_is_a_known_shader() {
    // The light's shader list names an MDL material: no graph node, but no unknown shader.
    let text = r#"
shader "Light_def" "mdl::nvidia::core_definitions::light_omni" ("intensity" 42)
light "lamp" = "Light_def" origin 0 0 0 end light
instance "lamp_inst" "lamp" end instance
camera "cam" resolution 4 4 end camera
instance "cam_inst" "cam" end instance
instgroup "root" "cam_inst" "lamp_inst" end instgroup
options "opt" end options
render "root" "cam_inst" "opt"
"#;
    let parsed = mi::parse_str("t.mi", text);
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    let (_, shade_diags) = Shading::build(&scene, &ShadingOptions::default(), &material::registry());
    let messages: Vec<String> = shade_diags.iter().map(|d| d.render(&parsed.sources)).collect();
    assert!(messages.is_empty(), "{messages:#?}");
}

#[test]
fn mdl_blend_color_layers_and_bump_map() {
    // Base 0.2; a blend layer of 1 at weight ½ → 0.6; a multiply layer of 0.5 → 0.3.
    let body = r#"shader "layers" "mdl::base::blend_color_layers" (
    "layers" [ { "layer_color" 1 1 1, "weight" 0.5, "mode" "color_layer_blend" },
               { "layer_color" 0.5 0.5 0.5, "weight" 1, "mode" "color_layer_multiply" } ],
    "base" 0.2 0.2 0.2)
shader "mat" "mdl::nvidia::core_definitions::diffuse" ("diffuse_color" = "layers.tint")"#;
    let (px, messages) = render(body, "mat", 1);
    assert!(messages.is_empty(), "{messages:#?}");
    assert_rgb(px[27], [0.3; 3], 1e-5, "blended");

    // Heights 0, ¼, ½, ¾ along u (one texel = ¼): one texel's rise is 64/255, so the normal
    // leans to normalize(−64/255, 0, 1) and a white surface lit head-on gives its z.
    let body = r#"color texture "ramp" [ 4 1 ] '000000' '404040' '808080' 'c0c0c0'
shader "bump" "mdl::base::file_bump_texture" ("texture" "ramp")
shader "mat" "mdl::nvidia::core_definitions::diffuse" ("diffuse_color" 1 1 1, "normal" = "bump")"#;
    let (px, messages) = render(body, "mat", 4);
    assert!(messages.is_empty(), "{messages:#?}");
    let rise = 64.0f32 / 255.0;
    let want = 1.0 / (1.0 + rise * rise).sqrt();
    for x in 1..5 {
        assert_rgb(px[3 * 8 + x], [want; 3], 2e-3, &format!("pixel ({x}, 3)"));
    }
}

#[test]
fn unified_material_reads_a_connected_texture() {
    // The unified material is no mental ray shader: no warning, and its connected base
    // colour is followed (a white dielectric-free, metal-free surface is Lambertian).
    let body = format!(
        r#"{QUADRANTS}
shader "tex" "mdl::base::file_texture" ("texture" "quadrants")
shader "mat" "unified_material" ("base_color" = "tex.tint", "specular" 0)"#
    );
    let (px, messages) = render(&body, "mat", 16);
    assert!(messages.is_empty(), "{messages:#?}");
    for (x, y, want) in INSIDE {
        assert_rgb(px[y * 8 + x], want, 0.02, &format!("pixel ({x}, {y})"));
    }
}
