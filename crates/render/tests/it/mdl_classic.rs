//! Module materials in the classic engine: shaded through the same compiled BSDF the path
//! engine uses (`baselib::bsdf_material`), lit by the classic light loop and traced rays.
//!
//! - A glossy module material on a square under a directional light: the classic engine's
//!   pixels are π times the path engine's (mental ray's base lights carry no 1/π; a single
//!   square has no indirect light), glossy highlight included.
//! - The module Cornell box (scenes/mdl/cornell_mdl.mi's geometry, lamp and walls, "light
//!   relative scale" 1): the classic engine without final gathering against the path engine
//!   limited to direct light agree on the walls' colours, up to the engines' factor π
//!   (the classic light loop's light colours carry no 1/π, as mental ray's).
//! - A module floor lit only by a module material's emission (`diffuse_edf`) through final
//!   gathering: the same pixels in both engines (radiance, no light convention between
//!   them), and the floor's value is ρ · E / π of the emitter's radiance.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use render::integrator::PathSettings;
use render::{EngineKind, Settings};
use shader::{Shading, ShadingOptions};

/// Renders `text` at `res`², `spp` samples with `engine` (and path settings `path`), MDL
/// modules from scenes/mdl: the pixels and every message.
fn render(text: &str, res: u32, spp: u32, engine: EngineKind, path: PathSettings) -> (Vec<[f32; 4]>, Vec<String>) {
    let parsed = mi::parse_str("t.mi", text);
    let modules = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/mdl"));
    let mut messages: Vec<String> = parsed.diagnostics.list.iter().map(|d| d.render(&parsed.sources)).collect();
    let mut diags = Vec::new();
    let mut scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    scene.camera.resolution = (res, res);
    let (mut shading, shade_diags) = Shading::build(&scene, &ShadingOptions::default(), &material::registry());
    diags.extend(shade_diags);
    let search = material::mdl_modules::search_path(&scene.library, &[modules]);
    let (mdl, mdl_diags) = material::mdl_modules::compile(&scene.library, search);
    diags.extend(mdl_diags);
    material::module_stand_ins(&mut shading, &scene, &mdl);
    messages.extend(diags.iter().map(|d| d.render(&parsed.sources)));
    let world = render::World::from_scene_with_mdl(&scene, Some(&shading), &mdl);
    messages.extend(world.warnings.iter().cloned());
    let accel = render::accel::build(&world, render::Backend::default_available());
    let settings = Settings { engine, spp: Some(spp), path, ..Settings::default() };
    let (film, _) = render::render(&world, accel.as_ref(), Some(&shading), &settings, &AtomicBool::new(false), &|_| {});
    (film.rgba(), messages)
}

/// The mean colour of the pixels in columns `x0..x1` and rows `y0..y1` of a `res`-wide image.
fn mean(px: &[[f32; 4]], res: usize, (x0, x1): (usize, usize), (y0, y1): (usize, usize)) -> [f32; 3] {
    let mut sum = [0.0; 3];
    for y in y0..y1 {
        for x in x0..x1 {
            for k in 0..3 {
                sum[k] += px[y * res + x][k];
            }
        }
    }
    sum.map(|s| s / ((x1 - x0) * (y1 - y0)) as f32)
}

#[test]
fn a_glossy_module_material_shades_through_its_bsdf_in_the_classic_engine() {
    // The camera looks down −z at a square at z = −1, the light shines along −z: the
    // glossy layer's highlight faces the camera.
    let text = r#"
$include "export_multi.mdl"
options "opt" filter box 1 1 end options
light "sun" "mib_light_infinite" ("color" 3.14159265 3.14159265 3.14159265) direction 0 0 -1 end light
instance "sun_inst" "sun" end instance
camera "cam" focal 1 aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
shader "mat" "mdl::export_multi::glossy" ("tint" 0.5 0.25 0.1, "roughness" 0.5)
object "square" group
    -1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1
    v 0 v 1 v 2 v 3
    p 0 1 2 3
end group end object
instance "square_inst" "square" material "mat" end instance
instgroup "root" "cam_inst" "sun_inst" "square_inst" end instgroup
render "root" "cam_inst" "opt"
"#;
    let (classic, messages) = render(text, 8, 16, EngineKind::Classic, PathSettings::default());
    assert!(messages.is_empty(), "{messages:#?}");
    let (path, _) = render(text, 8, 16, EngineKind::Path, PathSettings::default());
    let pi = std::f32::consts::PI;
    for (x, y) in [(3, 3), (4, 4), (1, 6), (6, 1)] {
        let (c, p) = (classic[y * 8 + x], path[y * 8 + x]);
        for k in 0..3 {
            // Both engines evaluate the same BSDF at the same directions (pixel positions
            // jitter alike); 1 % covers the classic engine's light-loop arithmetic.
            assert!(
                (c[k] - pi * p[k]).abs() <= 0.01 * pi * p[k] + 1e-4,
                "pixel ({x}, {y}) channel {k}: {c:?} vs π·{p:?}"
            );
        }
    }
    // The highlight is there: the middle is brighter than the diffuse part alone (the
    // stand-in's Lambertian of the tint showed π·tint·(1 − coat) at most).
    let middle = classic[4 * 8 + 4];
    assert!(middle[2] > pi * 0.1 * 1.2, "no glossy highlight in the classic engine: {middle:?}");
}

#[test]
fn the_module_cornell_box_agrees_between_the_engines_on_its_walls() {
    let source = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/mdl/cornell_mdl.mi"))
        .expect("the scene");
    // Direct light only in both engines: the classic engine without final gathering (the
    // dialect's string options removed), the path engine with one scattering event and
    // light sampling alone; the lamp's flux unscaled in both.
    let text: String = source
        .lines()
        .filter(|l| !l.contains("\"progressive") && !l.contains("\"gi\"") && !l.contains("light relative scale"))
        .collect::<Vec<_>>()
        .join("\n");
    let res = 24usize;
    let (classic, messages) = render(&text, res as u32, 64, EngineKind::Classic, PathSettings::default());
    assert!(messages.iter().all(|m| !m.contains("grey")), "{messages:#?}");
    let direct = PathSettings { max_depth: 1, rr_depth: 1, mis: false };
    let pi = std::f32::consts::PI;
    let (path, _) = render(&text, res as u32, 64, EngineKind::Path, direct);
    // Regions (columns, rows from the top) inside the red, green and back walls.
    for (name, cols, rows) in [("red", (0, 3), (8, 16)), ("green", (21, 24), (8, 16)), ("back", (9, 15), (3, 8))] {
        let (c, p) = (mean(&classic, res, cols, rows), mean(&path, res, cols, rows));
        let (lc, lp) = (c[0] + c[1] + c[2], p[0] + p[1] + p[2]);
        assert!(lp > 0.01, "{name}: the path engine's wall is dark: {p:?}");
        // The classic light loop's units are mental ray's (light colours without 1/π, for
        // `physical_light` too): π times the path engine's. 6 %: both estimates carry the
        // area light's sampling noise at 64 samples.
        assert!((lc - pi * lp).abs() <= 0.06 * pi * lp, "{name} wall: classic {c:?} vs π·path {p:?}");
        // The same colour: each channel's share agrees.
        for k in 0..3 {
            assert!((c[k] / lc - p[k] / lp).abs() <= 0.02, "{name} wall's colour: classic {c:?} vs path {p:?}");
        }
    }
}

#[test]
fn an_mdl_emitter_lights_a_module_floor_alike_in_both_engines() {
    // The camera at the origin looks down −z at a matte floor (ρ = 0.5) at z = −1; a large
    // emitter (radiant exitance 10, radiance 10/π) at z = +0.5 faces it from behind the
    // camera and fills nearly all of the floor's sky: the floor shows ρ/π · E with
    // E = π · 10/π · (1 − ε), ε ≈ 1.5²/(50² + 1.5²) ≈ 9e-4, so 10ρ/π ≈ 1.590.
    let text = r#"
$include "export_multi.mdl"
options "opt" filter box 1 1 finalgather on finalgather accuracy 128 end options
camera "cam" focal 1 aperture 0.5 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
shader "floor_mat" "mdl::export_multi::matte" ("tint" 0.5 0.5 0.5, "roughness" 0)
shader "lamp_mat" "mdl::export_multi::emitter" ("intensity" 10)
object "floor" group
    -50 -50 -1  50 -50 -1  50 50 -1  -50 50 -1
    v 0 v 1 v 2 v 3
    p 0 1 2 3
end group end object
instance "floor_inst" "floor" material "floor_mat" end instance
object "lamp" group
    -50 -50 0.5  -50 50 0.5  50 50 0.5  50 -50 0.5
    v 0 v 1 v 2 v 3
    p 0 1 2 3
end group end object
instance "lamp_inst" "lamp" material "lamp_mat" end instance
instgroup "root" "cam_inst" "floor_inst" "lamp_inst" end instgroup
render "root" "cam_inst" "opt"
"#;
    let (classic, messages) = render(text, 8, 4, EngineKind::Classic, PathSettings::default());
    assert!(messages.is_empty(), "{messages:#?}");
    let (path, _) = render(text, 8, 16, EngineKind::Path, PathSettings::default());
    let (c, p) = (mean(&classic, 8, (0, 8), (0, 8)), mean(&path, 8, (0, 8), (0, 8)));
    let want = 10.0 * 0.5 / std::f32::consts::PI;
    for k in 0..3 {
        // Both are Monte Carlo estimates of a nearly uniform sky (final gathering: 128
        // rays a point, interpolated; the path engine: 16 samples a pixel): 3 %.
        assert!((c[k] - want).abs() <= 0.03 * want, "classic {c:?} vs {want}");
        assert!((p[k] - want).abs() <= 0.03 * want, "path {p:?} vs {want}");
        assert!((c[k] - p[k]).abs() <= 0.03 * want, "classic {c:?} vs path {p:?}");
    }
}
