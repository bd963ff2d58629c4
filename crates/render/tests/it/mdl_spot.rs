//! MDL `df::spot_edf` in both engines: a camera looking at a module material's spot
//! emitter 60° off its axis sees the spot law's radiance, intensity · (e + 2)/2π · cosᵉ 60°
//! (the module is crates/material/tests/mdl/layers.mdl); from behind it sees nothing.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use render::{EngineKind, Settings};
use shader::{Shading, ShadingOptions};

/// Renders `text` with `engine` at 8×8 pixels, 4 samples: the pixels and messages.
fn render_text(text: &str, engine: EngineKind) -> (Vec<[f32; 4]>, Vec<String>) {
    let parsed = mi::parse_str("spot.mi", text);
    let mut messages: Vec<String> = parsed.diagnostics.list.iter().map(|d| d.render(&parsed.sources)).collect();
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    let (mut shading, shade_diags) = Shading::build(&scene, &ShadingOptions::default(), &material::registry());
    diags.extend(shade_diags);
    let modules: Vec<PathBuf> = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("../material/tests/mdl")];
    let search = material::mdl_modules::search_path(&scene.library, &modules);
    let (mdl, mdl_diags) = material::mdl_modules::compile(&scene.library, search);
    diags.extend(mdl_diags);
    // The classic engine shades module materials through their compiled BSDF.
    material::module_stand_ins(&mut shading, &scene, &mdl);
    messages.extend(diags.iter().map(|d| d.render(&parsed.sources)));
    let world = render::World::from_scene_with_mdl(&scene, Some(&shading), &mdl);
    messages.extend(world.warnings.iter().cloned());
    let accel = render::accel::build(&world, render::Backend::default_available());
    let settings = Settings { engine, spp: Some(4), ..Settings::default() };
    let (film, _) = render::render(&world, accel.as_ref(), Some(&shading), &settings, &AtomicBool::new(false), &|_| {});
    (film.rgba(), messages)
}

/// A quad through (0, 0, −5) whose normal (0, sin 60°, cos 60°) is 60° from the camera's
/// view direction back along +z, of material `shader`; a camera at the origin looking
/// down −z with a field of view of 0.6°.
fn scene(shader: &str) -> String {
    format!(
        r#"options "opt" filter box 1 1 end options
shader "emitter" {shader}
object "quad" group
    -2 -1 -3.267949  2 -1 -3.267949  2 1 -6.732051  -2 1 -6.732051
    v 0 v 1 v 2 v 3
    p "emitter" 0 1 2 3
end group end object
instance "quad_inst" "quad" end instance
camera "cam" focal 1 aperture 0.01 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" end instance
instgroup "root" "cam_inst" "quad_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

#[test]
fn a_spot_emitter_seen_60_degrees_off_its_axis_follows_the_spot_law() {
    for (shader, expected) in [
        // e = 4 over the hemisphere: 10 · 6/2π · 0.5⁴.
        (r#""mdl::layers::spot" ()"#, 10.0 * 6.0 / std::f32::consts::TAU * 0.0625),
        // e = 0: the Lambertian 10/π whatever the angle.
        (r#""mdl::layers::spot" ("exponent" 0)"#, 10.0 / std::f32::consts::PI),
    ] {
        for engine in [EngineKind::Path, EngineKind::Classic] {
            let (px, messages) = render_text(&scene(shader), engine);
            assert!(messages.is_empty(), "{messages:#?}");
            // The centre pixels (their directions within ±0.04° of the axis).
            let centre: f32 = [27usize, 28, 35, 36].iter().map(|&i| px[i][0]).sum::<f32>() / 4.0;
            assert!((centre - expected).abs() <= 1e-3 * expected, "{engine:?} {shader}: {centre} vs {expected}");
            assert!((px[36][1] - px[36][0]).abs() < 1e-6, "grey");
        }
    }
}

/// The same emitter turned away (its normal 120° from the view direction, the quad's
/// vertices in the other order): a spot sends nothing behind its surface in either engine.
#[test]
fn a_spot_emitter_seen_from_behind_is_dark_in_both_engines() {
    let text = scene(r#""mdl::layers::spot" ()"#).replace("p \"emitter\" 0 1 2 3", "p \"emitter\" 3 2 1 0");
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let (px, messages) = render_text(&text, engine);
        assert!(messages.is_empty(), "{messages:#?}");
        assert!(px[36][0].abs() < 1e-6, "{engine:?}: {:?}", px[36]);
    }
}
