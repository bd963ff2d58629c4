//! The repository's complete Maya exports (`scenes/maya`) in both engines: their image
//! means agree within 2 % per channel on what both engines render, and where mental ray's
//! own engines differ the difference is the stated one.
//!
//! - The classic engine runs the camera's lens shaders on every sample (the 2017 export's
//!   `mia_exposure_simple`, gain 0.2 with compression), the path engine's film is linear
//!   (the exposure is applied when display images are written): the comparison is of
//!   linear images, the lens shader taken out.
//! - Both exports render with `finalgather off`: mental ray's classic engine then takes no
//!   light from the camera's environment and none bounced between surfaces; the path
//!   engine, like Iray, takes both. The comparison takes the environment's light out of
//!   the path engine (Iray's `environment_lighting_scale` 0: the camera still sees the
//!   sky) and bounds the classic image by the path engine's direct light alone and its
//!   direct light plus one bounce (see [`exports_agree`]).
//!
//! At 24², 64 samples a pixel (classic 4): the 2017 export classic 2.1528/1.9061/1.7291,
//! path direct 2.1342/1.8917/1.7219, one bounce 2.1405/1.9005/1.7321; the 2012 export
//! classic 0.05722/0.05737/0.05230, path direct 0.05666/0.05671/0.05099, one bounce
//! 0.05873/0.05764/0.05155.
//!
//! Slow check (96², 1024 samples a pixel): `cargo test -p render --release --test
//! maya_exports_agree -- --ignored`.

use crate::support;

use std::path::PathBuf;

use glam::Vec3A;
use render::integrator::PathSettings;
use render::{EngineKind, Settings};
use scene::values::AttrValue;
use shader::ShadingOptions;

/// The export `name` of `scenes/maya`, its text changed by `edit`, built as `mira render`
/// builds it at `res`² (textures from the scene's directory), without the environment's
/// light when `no_environment_light`.
fn build(name: &str, edit: &dyn Fn(String) -> String, res: u32, no_environment_light: bool) -> render::pipeline::Built {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/maya");
    let path = dir.join(name);
    let text = edit(std::fs::read_to_string(&path).expect("readable"));
    let parsed = mi::parse_str(&path.to_string_lossy(), &text);
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let mut diags = Vec::new();
    let mut scene = scene::Scene::build(&parsed, 0, &mut diags).expect("a scene");
    scene.camera.aspect = 1.0;
    scene.camera.resolution = (res, res);
    let options =
        ShadingOptions { search: shader::texture::SearchPath { dirs: vec![dir] }, ..ShadingOptions::default() };
    let mut built = render::pipeline::build_world(&scene, &options, &[]);
    assert!(built.world.warnings.is_empty(), "{name}: {:?}", built.world.warnings);
    if no_environment_light {
        built.world.options.attributes.insert("environment_lighting_scale".into(), AttrValue::Float(0.0));
    }
    built
}

/// The image mean of `built` rendered by `engine` at `spp` with at most `depth` scattering
/// events (the path engine).
fn mean(built: &render::pipeline::Built, engine: EngineKind, spp: u32, depth: u32) -> Vec3A {
    let path = PathSettings { max_depth: depth, ..PathSettings::default() };
    let settings = Settings { engine, spp: Some(spp), path, ..Settings::default() };
    let px = support::render_world(&built.world, &built.shading, &settings).0.rgba();
    px.iter().map(|p| Vec3A::new(p[0], p[1], p[2])).sum::<Vec3A>() / px.len() as f32
}

/// The 2017 export without its lens shader.
fn no_lens(text: String) -> String {
    text.replace("lens = \"mia_exposure_simple1\"", "")
}

/// Renders both exports at `res`² (classic 4 samples a pixel, path `spp`) and asserts,
/// per channel, the environment's light taken out of the path engine:
/// - the classic engine, which renders each export's direct light plus the reflections
///   its Maya materials trace (`reflectionLimit` 1), lies between the path engine's
///   direct light alone (one scattering event) and its direct light plus one bounce
///   (which holds those reflections and the first bounce of diffuse light), within
///   `tolerance`;
/// - the bounces after the first add less than a tenth;
/// - as written, the environment's light adds to the path engine's image.
fn exports_agree(res: u32, spp: u32, tolerance: f32) {
    let identity = |t: String| t;
    let cases: [(&str, &dyn Fn(String) -> String); 2] =
        [("maya2017_export.mi", &no_lens), ("maya2012_export.mi", &identity)];
    for (name, edit) in cases {
        let built = build(name, edit, res, true);
        let classic = mean(&built, EngineKind::Classic, 4, 8);
        let direct = mean(&built, EngineKind::Path, spp, 1);
        let one_bounce = mean(&built, EngineKind::Path, spp, 2);
        let bounced = mean(&built, EngineKind::Path, spp, 8);
        let written = mean(&build(name, edit, res, false), EngineKind::Path, spp, 8);
        println!(
            "{name}: classic {classic}; path without the environment's light: direct {direct}, one bounce \
             {one_bounce}, all {bounced}; path as written {written}"
        );
        for k in 0..3 {
            assert!(classic[k] > 0.02, "{name}: {classic}");
            assert!(
                classic[k] >= direct[k] * (1.0 - tolerance) && classic[k] <= one_bounce[k] * (1.0 + tolerance),
                "{name} channel {k}: classic {classic} vs path direct {direct}, one bounce {one_bounce}"
            );
            assert!(
                bounced[k] >= one_bounce[k] * 0.99 && bounced[k] < 1.1 * one_bounce[k],
                "{name}: {bounced} vs {one_bounce}"
            );
            assert!(written[k] >= bounced[k] * 0.99, "{name}: the environment's light adds: {written} vs {bounced}");
        }
    }
}

#[test]
fn the_maya_exports_agree_in_both_engines() {
    exports_agree(24, 64, 0.02);
}

/// [`the_maya_exports_agree_in_both_engines`] at 96² and 1024 samples a pixel.
#[test]
#[ignore]
fn the_maya_exports_agree_in_both_engines_closely() {
    exports_agree(96, 1024, 0.02);
}
