//! The highlight (`emitSpecular`) of a Maya volume light with `emitAmbient` in the path
//! engine against the classic engine: the classic Maya materials add it as a light from
//! the volume light's direction lights the highlight, the path engine through the
//! material's reflection lobes alone.

use crate::support;

use render::{EngineKind, Settings};

/// The image's side in pixels.
const SIDE: usize = 24;

/// A blinn ground (colour 0.6 0.5 0.4, diffuse 0.8, eccentricity `eccentricity`,
/// specularColor 0.5) seen from 4 above at `SIDE`² pixels (x and z in ±2.4), lit by a
/// sphere volume light of radius 4 centred 1 above its middle (intensity 0.7,
/// `emitAmbient` on) with the more parameters `more` (", name value" pairs).
fn ground(eccentricity: f32, more: &str) -> String {
    let view = support::maya_view::top_down(SIDE);
    format!(
        r#"
$include "mayabase.mi"
{view}
light "vol" "maya_volumelight" ("intensity" 0.7, "lightShape" 1, "emitAmbient" on{more}) origin 0 0 0 end light
instance "vol_inst" "vol" transform 0.25 0 0 0  0 0.25 0 0  0 0 0.25 0  0 -0.25 0 1 end instance
shader "bl" "maya_blinn" ("color" 0.6 0.5 0.4, "diffuse" 0.8, "eccentricity" {eccentricity},
    "specularColor" 0.5 0.5 0.5, "reflectivity" 0)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "bl.outColor") end material
object "ground" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
instgroup "root" "cam_inst" "vol_inst" "ground_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The image mean (rgb) of `text` rendered by `engine` (`spp` samples per pixel),
/// asserting the path engine took the light as an ambient one without a message.
fn mean(text: &str, engine: EngineKind, spp: u32) -> [f32; 3] {
    let (scene, shading) = support::build_clean(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    assert_eq!((world.lights.len(), world.ambient.len()), (0, 1));
    let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
    let px = support::render_world(&world, &shading, &settings).0.rgba();
    let mut m = [0.0f32; 3];
    for p in &px {
        for k in 0..3 {
            m[k] += p[k] / px.len() as f32;
        }
    }
    m
}

/// With `emitSpecular` on (its default) the blinn ground shows the light's highlight in
/// both engines: the image means agree within 0.5 % per channel, and the highlight adds
/// more than 3 % to each channel (the classic mean with `emitSpecular` off is that much
/// lower, so leaving it out would fail the comparison). Eccentricities 0.3 (Maya's
/// default) and 0.5; with raytraced shadows on (nothing casts them) the same.
#[test]
fn a_volume_light_with_emit_ambient_lights_the_highlight_in_both_engines() {
    for (eccentricity, more) in [(0.3, ""), (0.5, ""), (0.3, r#", "useRayTraceShadows" on"#)] {
        let text = ground(eccentricity, more);
        let classic = mean(&text, EngineKind::Classic, 4);
        let path = mean(&text, EngineKind::Path, 16);
        let dull = mean(&ground(eccentricity, &format!(r#"{more}, "emitSpecular" off"#)), EngineKind::Classic, 4);
        println!(
            "eccentricity {eccentricity}{more}: classic {classic:?}, path {path:?}, classic without highlight {dull:?}"
        );
        for k in 0..3 {
            assert!(classic[k] / dull[k] > 1.03, "the highlight shows: {classic:?} vs {dull:?}");
            assert!((path[k] / classic[k] - 1.0).abs() < 0.005, "path {path:?} vs classic {classic:?}");
        }
    }
}
