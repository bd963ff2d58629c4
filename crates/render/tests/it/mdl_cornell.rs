//! A mental ray 3.12 MDL scene (scenes/mdl/cornell_mdl.mi): walls of a user module's `matte`
//! material, an object light of `physical_light`, the dialect's string options. The
//! automatic engine choice takes the path engine, and the path engine renders red and
//! green walls lit by the lamp's flux.
//!
//! Also `physical_light` on a rectangle over a Lambertian MDL plane against the analytic
//! irradiance of a square source, and a module material painted by a texture (evaluated at
//! each hit) against its texels.

use crate::support;

use std::path::PathBuf;

use render::{EngineKind, Settings};
use shader::Shading;
use support::scene_text::{translate, SceneText};
use support::{mean, QUADRANTS};

/// Renders the parsed scene with the path engine at `res`², `spp` samples: the pixels,
/// every message and whether the scene by itself would render in the classic engine.
/// `extra` directories are searched for MDL modules after the scene's.
fn render_parsed(parsed: &mi::Parsed, res: u32, spp: u32, extra: &[PathBuf]) -> (Vec<[f32; 4]>, Vec<String>, bool) {
    render_parsed_with(parsed, res, spp, extra, EngineKind::Path)
}

/// [`render_parsed`] with `engine`.
fn render_parsed_with(
    parsed: &mi::Parsed,
    res: u32,
    spp: u32,
    extra: &[PathBuf],
    engine: EngineKind,
) -> (Vec<[f32; 4]>, Vec<String>, bool) {
    let b = support::build_parsed(parsed, res, extra);
    let classic = Shading::wants_classic(&b.scene);
    let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
    let (film, _) = support::render_world(&b.built.world, &b.built.shading, &settings);
    (film.rgba(), b.messages, classic)
}

#[test]
fn cornell_box_of_mdl_modules_has_red_and_green_walls_in_the_path_engine() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/mdl/cornell_mdl.mi");
    let parsed = mi::parse_file(std::path::Path::new(path), &mi::ReadOptions::default()).expect("the scene reads");
    let res = 32usize;
    let (px, messages, classic) = render_parsed(&parsed, res as u32, 32, &[]);
    assert!(messages.is_empty(), "{messages:#?}");
    assert!(!classic, "the automatic engine choice must take the path engine for MDL materials");
    // The camera sees the box's opening: x = 0 (red) fills the left columns, x = 10
    // (green) the right ones, the back wall the middle.
    let left = mean(&px, res, (0, 3), (10, 22));
    let right = mean(&px, res, (res - 3, res), (10, 22));
    let back = mean(&px, res, (12, 20), (9, 14));
    eprintln!("left {left:?} right {right:?} back {back:?}");
    assert!(left[0] > 0.05 && left[0] > 4.0 * left[1] && left[0] > 4.0 * left[2], "left wall {left:?}");
    assert!(right[1] > 0.05 && right[1] > 4.0 * right[0] && right[1] > 4.0 * right[2], "right wall {right:?}");
    // The back wall is white (0.7) but takes colour from the side walls: neutral within 40 %.
    let grey = (back[0] + back[1] + back[2]) / 3.0;
    assert!(grey > 0.05 && back.iter().all(|c| (c - grey).abs() < 0.4 * grey), "back wall {back:?}");
}

/// An exporter's helper shader that no library declares, on the material of the lamp's
/// geometry (an emitter): a warning names it at its `.mi` line, and the scene renders as it
/// does without it — the object light keeps its flux (the back wall within 5 % of the
/// original scene's, 32², 32 spp, same seed), the walls keep their colours.
#[test]
fn an_undeclared_helper_shader_on_the_emitter_warns_and_keeps_the_light() {
    let dir = support::mdl_modules();
    let original = std::fs::read_to_string(dir.join("cornell_mdl.mi")).expect("the scene");
    let lamp = "    p \"white\" 0 1 2 3\nend group end object\ninstance \"lamp_inst\"";
    assert!(original.contains(lamp), "the scene's lamp geometry changed");
    let helper = original.replace(
        lamp,
        "    p \"lamp_mtl\" 0 1 2 3\nend group end object\n\
         shader \"lamp_helper\" \"adsk_light_helper\" (\"intensity\" 3)\n\
         material \"lamp_mtl\" = \"lamp_helper\" end material\n\
         instance \"lamp_inst\"",
    );
    let tmp = std::env::temp_dir().join(format!("mira_helper_emitter_{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let file = tmp.join("cornell_helper.mi");
    std::fs::write(&file, &helper).unwrap();
    let read = mi::ReadOptions { include_paths: vec![dir.clone()], ..mi::ReadOptions::default() };
    let parsed = mi::parse_file(&file, &read).expect("the scene reads");
    let res = 32usize;
    let (px, messages, classic) = render_parsed(&parsed, res as u32, 32, std::slice::from_ref(&dir));
    std::fs::remove_dir_all(&tmp).ok();
    assert!(!classic, "still the path engine");
    assert!(
        messages.iter().any(|m| m.contains("adsk_light_helper") && m.contains("cornell_helper.mi:")),
        "a warning naming the helper and its line: {messages:#?}"
    );
    let base = mi::parse_file(&dir.join("cornell_mdl.mi"), &mi::ReadOptions::default()).expect("the scene reads");
    let (px0, _, _) = render_parsed(&base, res as u32, 32, &[]);
    let back = mean(&px, res, (12, 20), (9, 14));
    let back0 = mean(&px0, res, (12, 20), (9, 14));
    for k in 0..3 {
        assert!((back[k] - back0[k]).abs() <= 0.05 * back0[k], "back wall {back:?} against {back0:?}");
    }
    let left = mean(&px, res, (0, 3), (10, 22));
    assert!(left[0] > 4.0 * left[1] && left[0] > 4.0 * left[2], "left wall still red: {left:?}");
}

/// The view of the analytic-irradiance tests: `$include "export_multi.mdl"`, options
/// `filter box 1 1 {options}`, an orthographic camera 0.2 units wide at 4² pixels at
/// z = 1 looking down −z, and the shader "grey" (`export_multi::matte`, tint 0.5). The
/// caller adds the lights and [`MDL_PLANE`].
fn mdl_plane_view(options: &str) -> SceneText {
    SceneText::new()
        .include("export_multi.mdl")
        .options(&format!("filter box 1 1 {options}"))
        .camera("focal infinity aperture 0.2 aspect 1")
        .resolution(4)
        .camera_transform(&translate(0.0, 0.0, -1.0))
        .text(r#"shader "grey" "mdl::export_multi::matte" ("tint" 0.5 0.5 0.5)"#)
}

/// The object "plane" of shader "grey" (100 × 100 at z = −5, facing +z) and its
/// instance "plane_inst".
const MDL_PLANE: &str = r#"object "plane" group
    -50 -50 -5  50 -50 -5  50 50 -5  -50 50 -5
    v 0 v 1 v 2 v 3
    p "grey" 0 1 2 3
end group end object
instance "plane_inst" "plane" end instance"#;

/// The `.mi` text of [`mdl_plane_view`] with `options` under a 1 × 1 `physical_light`
/// rectangle "lamp" of flux 100 at z = −3 facing down, over [`MDL_PLANE`].
pub(crate) fn rectangle_lamp_over_mdl_plane(options: &str) -> String {
    mdl_plane_view(options)
        .light("lamp", r#""physical_light" ("color" 100 100 100) origin 0 0 -3 rectangle 1 0 0 0 -1 0 4 4"#, None)
        .text(MDL_PLANE)
        .instance("plane_inst")
        .build()
}

/// The irradiance at distance `h` below the centre of a Lambertian square of side `s` and
/// radiance `l`, facing it (midpoint rule, 200² cells).
fn square_irradiance(l: f64, s: f64, h: f64) -> f64 {
    let n = 200;
    let cell = s / n as f64;
    let mut e = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = -s / 2.0 + (i as f64 + 0.5) * cell;
            let y = -s / 2.0 + (j as f64 + 0.5) * cell;
            let r2 = x * x + y * y + h * h;
            e += l * (h * h / r2) / r2 * cell * cell;
        }
    }
    e
}

#[test]
fn physical_light_rectangle_over_an_mdl_plane_gives_the_analytic_irradiance() {
    // A 1 × 1 physical_light of flux 100, facing down 2 units above a plane of matte tint
    // 0.5, seen from above by an orthographic camera. The scene's "light relative scale"
    // 0.5 does not dim it: mental ray scales only what legacy (non-BSDF) shaders receive.
    let text = rectangle_lamp_over_mdl_plane("\"light relative scale\" 0.5");
    let parsed = mi::parse_str("t.mi", &text);
    let (px, messages, _) = render_parsed(&parsed, 4, 256, &[support::mdl_modules()]);
    assert!(messages.is_empty(), "{messages:#?}");
    // Radiance of the square: flux / (π A) = 100 / π; the plane reflects 0.5 / π of the
    // irradiance. The camera sees a 0.2-wide patch below the centre: irradiance varies
    // by under 1 % over it.
    let e = square_irradiance(100.0 / std::f64::consts::PI, 1.0, 2.0);
    let want = (0.5 / std::f64::consts::PI * e) as f32;
    let got = mean(&px, 4, (0, 4), (0, 4));
    eprintln!("plane radiance {got:?}, analytic {want}");
    for c in got {
        assert!((c - want).abs() < 0.03 * want, "{c} vs {want}");
    }
}

/// A square seen head-on at `res`², lit head-on by a directional light of irradiance π (a
/// Lambertian pixel's value is its albedo), with shader `shader` of scenes/mdl/painted.mdl.
fn painted_square(shader: &str, res: u32) -> (Vec<[f32; 4]>, Vec<String>) {
    painted_square_with(shader, res, EngineKind::Path)
}

/// [`painted_square`] rendered by `engine`.
fn painted_square_with(shader: &str, res: u32, engine: EngineKind) -> (Vec<[f32; 4]>, Vec<String>) {
    let text = support::lit_square(&format!("{QUADRANTS}\n{shader}"), "mat");
    let parsed = mi::parse_str("t.mi", &text);
    let (px, messages, _) = render_parsed_with(&parsed, res, 16, &[support::mdl_modules()], engine);
    (px, messages)
}

#[test]
fn a_module_material_painted_by_a_texture_shows_its_texels_in_the_path_engine() {
    // Pixels whose footprints lie inside one texel block: (x, y from the top, RGB).
    let inside = [(1, 6, [1.0, 0.0, 0.0]), (6, 6, [0.0, 1.0, 0.0]), (1, 1, [0.0, 0.0, 1.0]), (6, 1, [1.0, 1.0, 1.0])];
    for shader in [
        r#"shader "mat" "mdl::painted::painted" ("tex" "quadrants")"#,
        r#"shader "mat" "mdl::painted::looked_up" ("tex" "quadrants")"#,
    ] {
        let (px, messages) = painted_square(shader, 8);
        assert!(messages.is_empty(), "{messages:#?}");
        for (x, y, want) in inside {
            let got = px[y * 8 + x];
            assert!((0..3).all(|k| (got[k] - want[k]).abs() <= 1e-3), "{shader}: pixel ({x}, {y}) {got:?} vs {want:?}");
        }
    }
    // Tiled twice, at 16×16: pixels whose footprints stay half a texel inside a block of
    // either tile (x, y from the top): the blue top-left block in both tiles, white and green.
    let (px, messages) = painted_square(r#"shader "mat" "mdl::painted::painted" ("tex" "quadrants", "tiles" 2)"#, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    let blue = [0.0, 0.0, 1.0];
    for (x, y, want) in
        [(1usize, 9usize, blue), (9, 9, blue), (1, 1, blue), (5, 9, [1.0, 1.0, 1.0]), (5, 13, [0.0, 1.0, 0.0])]
    {
        let got = px[y * 16 + x];
        assert!((0..3).all(|k| (got[k] - want[k]).abs() <= 1e-3), "tiled: pixel ({x}, {y}) {got:?} vs {want:?}");
    }
}

#[test]
fn the_classic_engine_shades_module_materials_with_their_compiled_colour() {
    // mental ray's base lights carry no 1/π: a Lambertian module material of colour c under
    // a head-on light of colour π shows π·c. A constant module matte shows its tint; a
    // textured one, shaded through its compiled BSDF per hit, its texels (pixels whose
    // footprints lie inside one block, as in the path engine's test above).
    let pi = std::f32::consts::PI;
    let (px, messages) = painted_square_with(
        r#"$include "export_multi.mdl"
shader "mat" "mdl::export_multi::matte" ("tint" 0.5 0.25 0)"#,
        4,
        EngineKind::Classic,
    );
    assert!(messages.iter().all(|m| !m.contains("grey")), "{messages:#?}");
    let got = mean(&px, 4, (0, 4), (0, 4));
    let want = [0.5, 0.25, 0.0];
    assert!((0..3).all(|k| (got[k] - pi * want[k]).abs() <= 1e-3), "matte: {got:?} vs π·{want:?}");
    let (px, messages) =
        painted_square_with(r#"shader "mat" "mdl::painted::painted" ("tex" "quadrants")"#, 8, EngineKind::Classic);
    assert!(messages.iter().all(|m| !m.contains("grey")), "{messages:#?}");
    for (x, y, want) in
        [(1, 6, [1.0, 0.0, 0.0]), (6, 6, [0.0, 1.0, 0.0]), (1, 1, [0.0, 0.0, 1.0]), (6, 1, [1.0, 1.0, 1.0])]
    {
        let got = px[y * 8 + x];
        assert!((0..3).all(|k| (got[k] - pi * want[k]).abs() <= 1e-3), "pixel ({x}, {y}) {got:?} vs π·{want:?}");
    }
}

/// `physical_light` on an *object* light: a 1 × 1 quad (an object whose instance the camera
/// does not see) of flux 100 emits as a Lambertian square of radiance 100/π (the scene's
/// "light relative scale" 0.5 does not reach the MDL plane, a BSDF material), like the
/// `rectangle` light above: the plane below shows the analytic irradiance within 3 %
/// (4², 256 spp).
#[test]
fn physical_light_object_light_over_an_mdl_plane_gives_the_analytic_irradiance() {
    let text = mdl_plane_view("\"light relative scale\" 0.5")
        .text(
            r#"object "lamp" group
    -0.5 -0.5 -3  -0.5 0.5 -3  0.5 0.5 -3  0.5 -0.5 -3
    v 0 v 1 v 2 v 3
    p "grey" 0 1 2 3
end group end object
instance "lamp_inst" "lamp" visible off shadow off end instance"#,
        )
        .light("lamp_light", r#""physical_light" ("color" 100 100 100) origin 0 0 -3 object "lamp_inst" 4 4"#, None)
        .instance("lamp_inst")
        .text(MDL_PLANE)
        .instance("plane_inst")
        .build();
    let parsed = mi::parse_str("t.mi", &text);
    let (px, messages, _) = render_parsed(&parsed, 4, 256, &[support::mdl_modules()]);
    assert!(messages.is_empty(), "{messages:#?}");
    let e = square_irradiance(100.0 / std::f64::consts::PI, 1.0, 2.0);
    let want = (0.5 / std::f64::consts::PI * e) as f32;
    let got = mean(&px, 4, (0, 4), (0, 4));
    eprintln!("plane radiance {got:?}, analytic {want}");
    for c in got {
        assert!((c - want).abs() < 0.03 * want, "{c} vs {want}");
    }
}

/// The Cornell box's lamp gives the floor the direct light of its flux: with one bounce
/// (direct light only) a floor patch the block does not shadow (4 × 4 pixels around
/// (7, 0, −3)) shows 0.7/π × the irradiance of a Lambertian 2 × 2 square of radiance
/// 700 / (π · 4) = 55.70 at 9.9 units above (the scene's "light relative scale" 0.318 does
/// not dim the light on its MDL walls), within 1 %
/// (64², 64 spp: 4e-5 measured; the irradiance by the midpoint rule over the lamp at 4 × 4 points of each
/// pixel). The light's energy in the box as mental ray 3.12 scenes state it.
#[test]
fn cornell_box_lamp_lights_the_floor_with_its_flux() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/mdl/cornell_mdl.mi");
    let parsed = mi::parse_file(std::path::Path::new(path), &mi::ReadOptions::default()).expect("the scene reads");
    let b = support::build_parsed(&parsed, 64, &[]);
    assert!(b.messages.is_empty(), "{:#?}", b.messages);
    let path_settings = render::integrator::PathSettings { max_depth: 1, ..Default::default() };
    let settings = Settings { engine: EngineKind::Path, spp: Some(64), path: path_settings, ..Settings::default() };
    let (film, _) = support::render_world(&b.built.world, &b.built.shading, &settings);
    let px = film.rgba();
    let radiance = 700.0 / (std::f64::consts::PI * 4.0);
    // The irradiance at floor point (x, 0, z) from the lamp [4, 6] × [−6, −4] at y = 9.9.
    let irradiance = |x: f64, z: f64| {
        let n = 40;
        let cell = 2.0 / n as f64;
        let mut e = 0.0;
        for i in 0..n {
            for j in 0..n {
                let (lx, lz) = (4.0 + (i as f64 + 0.5) * cell, -6.0 + (j as f64 + 0.5) * cell);
                let r2 = (lx - x).powi(2) + 9.9f64.powi(2) + (lz - z).powi(2);
                e += radiance * 9.9 * 9.9 / (r2 * r2) * cell * cell;
            }
        }
        e
    };
    // The camera at (5, 5, 9.5) looks down −z with a field of 2 · atan(0.5).
    let floor = |u: f64, v: f64| {
        let (dx, dy) = ((u / 64.0 * 2.0 - 1.0) * 0.5, (1.0 - v / 64.0 * 2.0) * 0.5);
        let t = 5.0 / -dy;
        (5.0 + t * dx, 9.5 - t)
    };
    let (mut got, mut want) = ([0.0f32; 3], 0.0);
    for y in 56..60 {
        for x in 40..44 {
            for k in 0..3 {
                got[k] += px[y * 64 + x][k] / 16.0;
            }
            for s in 0..16 {
                let (u, v) = (x as f64 + (s % 4) as f64 / 4.0 + 0.125, y as f64 + (s / 4) as f64 / 4.0 + 0.125);
                let (fx, fz) = floor(u, v);
                want += 0.7 / std::f64::consts::PI * irradiance(fx, fz) / 256.0;
            }
        }
    }
    eprintln!("floor {got:?}, direct light {want}");
    for c in got {
        assert!((f64::from(c) - want).abs() <= 0.01 * want, "{c} vs {want}");
    }
}
