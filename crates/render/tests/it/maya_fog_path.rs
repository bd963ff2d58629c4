//! Maya's fogs as the camera's volume in both engines: the path engine applies them as
//! affine terms per path segment (`render::integrator`'s `fog` module), the classic engine
//! runs them as volume shaders; both against the formulas of `maya::fog`.

use render::EngineKind;

use crate::support::render_text;

/// A camera 4 above a plane showing the unlit colour 0.8 (a surfaceShader; `plane` false:
/// no plane, the rays leave the scene), looking straight down through the camera volume
/// `volume` with a field of view of 0.01 (every ray crosses 4 units within 2e-5 of it), at
/// 4×4 pixels, optionally lit by a point light of intensity 2 (no decay, no shadows) 1
/// beside the middle of the rays.
fn scene(volume: &str, light: bool, plane: bool) -> String {
    let lamp = if light {
        r#"light "lamp" "maya_pointlight" ("intensity" 2, "decayRate" 0) origin 0 0 0 end light
instance "lamp_inst" "lamp" transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 -2 0 1 end instance"#
    } else {
        ""
    };
    let members = match (light, plane) {
        (true, true) => r#" "plane_inst" "lamp_inst""#,
        (false, true) => r#" "plane_inst""#,
        (true, false) => r#" "lamp_inst""#,
        (false, false) => "",
    };
    format!(
        r#"
$include "mayabase.mi"
options "opt" samples 0 0 filter box 1 1 end options
shader "fog" {volume}
camera "cam" volume = "fog" focal 1 aperture 0.01 aspect 1 resolution 4 4 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 0 1 0  0 -1 0 0  0 0 -4 1 end instance
{lamp}
shader "flat" "maya_surfaceshader" ("outColor" 0.8 0.8 0.8)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material
object "plane" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst"{members} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Renders `text` in both engines (the path engine at 4 samples per pixel): their pixels,
/// after asserting that neither gave a warning about the fog.
fn both_engines(text: &str) -> [Vec<[f32; 4]>; 2] {
    [EngineKind::Classic, EngineKind::Path].map(|engine| {
        let (px, messages) = render_text(text, engine, Some(4));
        assert!(!messages.iter().any(|m| m.contains("fog")), "{engine:?}: {messages:?}");
        px
    })
}

/// The fogs over a plane 4 units away, in both engines, against the formulas (1e-3): a
/// black light fog without colour-based transparency leaves 0.8·exp(−density·4) with fast
/// drop-off; a coloured one covers each channel by α·c and, lit by a point light 1 from the
/// rays' middle, adds α·c·I; environment fog covers α = 4 / saturationDistance of colour c
/// and adds α·c, with useHeight only the 2 units between heights 1 and 3.
#[test]
fn both_engines_cover_a_plane_behind_maya_fogs_by_their_formulas() {
    let d = 0.2f32;
    let light_fog = |params: &str| format!(r#""maya_lightfog" ("density" {d}, {params})"#);
    let alpha = |through: f32| 1.0 - (-through).exp();
    let a = alpha(d * 4.0);
    let cases: Vec<(String, bool, [f32; 3])> = vec![
        (
            light_fog(r#""color" 0 0 0, "colorBasedTransparency" off, "fastDropOff" on"#),
            false,
            [0.8 * (-d * 4.0).exp(); 3],
        ),
        (light_fog(r#""color" 0 0 0, "colorBasedTransparency" off"#), false, [0.8 * (-d).exp(); 3]),
        (light_fog(r#""color" 1 0.5 0, "fastDropOff" on"#), false, [0.8 * (1.0 - a), 0.8 * (1.0 - 0.5 * a), 0.8]),
        (
            light_fog(r#""color" 1 0.5 0, "fastDropOff" on"#),
            true,
            [0.8 * (1.0 - a) + a * 2.0, 0.8 * (1.0 - 0.5 * a) + a * 0.5 * 2.0, 0.8],
        ),
        (
            r#""maya_envfog" ("color" 0.2 0.4 0.6, "saturationDistance" 10)"#.to_string(),
            false,
            [0.8 * (1.0 - 0.4 * 0.2) + 0.4 * 0.2, 0.8 * (1.0 - 0.4 * 0.4) + 0.4 * 0.4, 0.8 * (1.0 - 0.4 * 0.6) + 0.4 * 0.6],
        ),
        (
            r#""adskMayaEnvFog" ("color" 0 0 0, "colorBasedTransparency" off, "saturationDistance" 10, "useHeight" on, "minHeight" 1, "maxHeight" 3)"#.to_string(),
            false,
            [0.8 * (1.0 - 0.2); 3],
        ),
    ];
    for (volume, lit, want) in &cases {
        for (engine, px) in ["classic", "path"].iter().zip(both_engines(&scene(volume, *lit, true))) {
            for p in px {
                for c in 0..3 {
                    assert!(
                        (p[c] - want[c]).abs() < 1e-3,
                        "{engine}: {volume} (lit {lit}): pixel {p:?}, want {want:?}"
                    );
                }
                assert!((p[3] - 1.0).abs() < 1e-6, "{engine}: alpha {}", p[3]);
            }
        }
    }
}

/// Rays that leave the scene cross an infinite segment of fog: environment fog is
/// saturated there (α = 1), so both engines show its colour c with alpha the mean share
/// covered, mean(c) with colour-based transparency (1e-4).
#[test]
fn rays_leaving_the_scene_see_saturated_fog_in_both_engines() {
    let text = scene(r#""maya_envfog" ("color" 0.2 0.4 0.6, "saturationDistance" 10)"#, false, false);
    for (engine, px) in ["classic", "path"].iter().zip(both_engines(&text)) {
        for p in px {
            let want = [0.2, 0.4, 0.6, 0.4];
            for c in 0..4 {
                assert!((p[c] - want[c]).abs() < 1e-4, "{engine}: pixel {p:?}, want {want:?}");
            }
        }
    }
}

/// The Henyey–Greenstein phase normalised to 1 for isotropic scattering (as
/// `maya::physical_fog::phase`), written out here: g = 1 − lightScatter.
fn hg(light_scatter: f32, cos: f32) -> f32 {
    let g = 1.0 - light_scatter;
    (1.0 - g * g) / (1.0 + g * g - 2.0 * g * cos).powf(1.5)
}

/// envFog's physical fog over the plane 4 units below the camera, in both engines,
/// against the model's formulas (1e-3; see `maya::physical_fog`): one medium of scattering
/// σs = density·colour and absorption σa = density·opacity keeps T = exp(−τ) of the plane
/// and adds (1 − T)·σs/σt·S. Uniform: τ = σt·4, S what the point light gives the middle
/// of the ray (2), none without the light; atmospheric (half-life 2 above height 0, the
/// camera at 4): τ = σt·2/ln 2·(1 − 2^−2), S the sun (1.5, straight overhead, the ray
/// going down: the phase at cos θ = −1).
#[test]
fn both_engines_render_physical_fog_by_its_formulas() {
    let color = [1.0f32, 0.5, 0.25];
    let density = 0.2f32;
    let opacity = 0.5f32;
    let expect = |depth_scale: f32, shown: f32| -> [f32; 3] {
        color.map(|c| {
            let (st, ss) = (density * (c + opacity), density * c);
            let keep = (-st * depth_scale).exp();
            0.8 * keep + (1.0 - keep) * ss / st * shown
        })
    };
    let uniform = r#""maya_envfog" ("physicalFog" on, "fogType" 0, "fogDensity" 0.2, "fogColor" 1 0.5 0.25, "fogOpacity" 0.5 0.5 0.5)"#;
    let atmospheric = r#""adskMayaEnvFog" ("physicalFog" on, "fogType" 1, "fogDensity" 0.2, "fogColor" 1 0.5 0.25, "fogOpacity" 0.5 0.5 0.5, "fogMinHeight" 0, "fogMaxHeight" 2, "fogLightScatter" 0.5, "sunIntensity" 1.5, "sunElevation" 90)"#;
    let atmospheric_depth = 2.0 / std::f32::consts::LN_2 * (1.0 - 0.25);
    let cases = [
        (uniform, false, expect(4.0, 0.0)),
        (uniform, true, expect(4.0, 2.0)),
        (atmospheric, false, expect(atmospheric_depth, 1.5 * hg(0.5, -1.0))),
    ];
    for (volume, lit, want) in &cases {
        for (engine, px) in ["classic", "path"].iter().zip(both_engines(&scene(volume, *lit, true))) {
            for p in px {
                for c in 0..3 {
                    assert!(
                        (p[c] - want[c]).abs() < 1e-3,
                        "{engine}: {volume} (lit {lit}): pixel {p:?}, want {want:?}"
                    );
                }
            }
        }
    }
}

/// Maya's volumeFog through the volume sampler as the camera's volume, in both engines
/// (the sampler tells the path engine its terms: keep T, add `outColor`): an orthographic
/// camera 5 units from a plane of constant colour 0.8 0.5 0.3; density 0.2 over the 5
/// units crosses τ = 1, so the fog passes T = `transparency` and adds (1 − T) ⊙ (colour +
/// incandescence): plane ⊙ T + (1 − T) ⊙ shown within 1e-5; density 0.4 passes T².
#[test]
fn volume_fog_passes_its_transparency_per_unit_of_density() {
    let render = |density: f32| {
        let text = format!(
            r#"
$include "mayabase.mi"
options "opt" filter box 1 1 samples 0 0 end options
shader "vf" "maya_volumefog" ("color" 0.2 0.4 0.6, "transparency" 0.5 0.25 0.8, "incandescence" 0.1 0 0, "density" {density})
shader "sampler" "maya_volumesampler" ("volumeShader" = "vf.outColor")
camera "cam" focal infinity aperture 2 aspect 1 resolution 4 4 volume = "sampler" end camera
instance "cam_inst" "cam" end instance
shader "flat" "maya_surfaceshader" ("outColor" 0.8 0.5 0.3)
material "plane_mtl" "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material
object "plane" group -4 -4 -5  4 -4 -5  4 4 -5  -4 4 -5  v 0 v 1 v 2 v 3 c "plane_mtl" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#
        );
        both_engines(&text)
    };
    let plane = [0.8f32, 0.5, 0.3];
    let shown = [0.3f32, 0.4, 0.6];
    let transparency = [0.5f32, 0.25, 0.8];
    for (density, power) in [(0.2f32, 1), (0.4, 2)] {
        let want: [f32; 3] = std::array::from_fn(|c| {
            let t = transparency[c].powi(power);
            plane[c] * t + (1.0 - t) * shown[c]
        });
        for (engine, px) in ["classic", "path"].iter().zip(render(density)) {
            for p in px {
                for c in 0..3 {
                    assert!((p[c] - want[c]).abs() < 1e-5, "{engine}: density {density}: pixel {p:?}, want {want:?}");
                }
            }
        }
    }
}

/// volumeFog lit by its lights, scattering directionally: the camera's volume is the
/// volume sampler over an illuminated volumeFog (colour 1 0.5 0.25, transparency 0.5,
/// density 0.25 over the 4 units to the plane: T = 0.5), lit by the point light of
/// intensity 2 beside the middle of the rays (at right angles to them), whose light
/// crosses 1 unit of the fog on its way (mental ray's light rays pass the volume the lit
/// point is in: 0.5^0.25 of it arrives). With `lightScatter` s the fog shows colour × 2 ×
/// 0.5^0.25 × the Henyey–Greenstein phase of g = 1 − s at cos θ = 0, (1 − g²)/(1 +
/// g²)^1.5 (1 for s = 1): plane · T + (1 − T) · that, in both engines within 3e-3 (the
/// light ray's length is taken from the offset point the light loop shades, 0.7 % longer
/// than 1), and the engines within 1e-4 of each other.
#[test]
fn volume_fog_light_scatter_weights_its_lights_by_the_phase() {
    for scatter in [1.0f32, 0.5] {
        let fog = format!(
            r#""maya_volumesampler" ("volumeShader" = "vf.outColor")
shader "vf" "maya_volumefog" ("color" 1 0.5 0.25, "transparency" 0.5 0.5 0.5, "density" 0.25, "illuminated" on, "lightScatter" {scatter})"#
        );
        // The sampler refers to the fog defined after it: define the fog first instead.
        let text = scene(&fog, true, true).replacen(
            &format!("shader \"fog\" {fog}"),
            &format!(
                "shader \"vf\" \"maya_volumefog\" (\"color\" 1 0.5 0.25, \"transparency\" 0.5 0.5 0.5, \"density\" 0.25, \"illuminated\" on, \"lightScatter\" {scatter})\nshader \"fog\" \"maya_volumesampler\" (\"volumeShader\" = \"vf.outColor\")"
            ),
            1,
        );
        let g = 1.0 - scatter;
        let phase = (1.0 - g * g) / (1.0 + g * g).powf(1.5);
        let lit = 2.0 * 0.5f32.powf(0.25) * phase;
        let want = [1.0f32, 0.5, 0.25].map(|c| 0.8 * 0.5 + 0.5 * c * lit);
        let images = both_engines(&text);
        for (engine, px) in ["classic", "path"].iter().zip(&images) {
            for (p, q) in px.iter().zip(&images[0]) {
                for c in 0..3 {
                    assert!(
                        (p[c] - want[c]).abs() < 3e-3,
                        "{engine}: lightScatter {scatter}: pixel {p:?}, want {want:?}"
                    );
                    assert!((p[c] - q[c]).abs() < 1e-4, "{engine}: {p:?} vs classic {q:?}");
                }
            }
        }
    }
}

/// envFog's own clip distances (`distanceClipPlanes` 0): the fog fills the rays only
/// between `fogNearDistance` and `fogFarDistance` from the camera, in both engines
/// (1e-3). Simple fog, black, saturation 10, between 1 and 2.5 over the plane 4 away:
/// 1.5 units, 0.8 · (1 − 0.15); rays that leave the scene (no plane) are no longer
/// saturated: colour 0.2 0.4 0.6 covers 0.15 of black, 0.15 · c. Physical uniform fog
/// between 1 and 3: 2 units of it, 0.8 · exp(−2σt) + (1 − exp(−2σt)) · 0 (unlit).
/// The default (`distanceClipPlanes` 1, the camera's clip planes) fills all of the ray.
#[test]
fn env_fog_fills_the_ray_between_its_clip_distances() {
    let clip = r#""distanceClipPlanes" 0, "fogNearDistance" 1, "fogFarDistance" 2.5"#;
    let black =
        format!(r#""maya_envfog" ("color" 0 0 0, "colorBasedTransparency" off, "saturationDistance" 10, {clip})"#);
    let coloured = format!(r#""maya_envfog" ("color" 0.2 0.4 0.6, "saturationDistance" 10, {clip})"#);
    let physical = r#""maya_envfog" ("physicalFog" on, "fogType" 0, "fogDensity" 0.2, "fogColor" 1 0.5 0.25, "fogOpacity" 0.5 0.5 0.5, "distanceClipPlanes" 0, "fogNearDistance" 1, "fogFarDistance" 3)"#;
    let unclipped = r#""maya_envfog" ("color" 0 0 0, "colorBasedTransparency" off, "saturationDistance" 10, "fogNearDistance" 1, "fogFarDistance" 2.5)"#;
    let physical_want = [1.0f32, 0.5, 0.25].map(|c| 0.8 * (-0.2 * (c + 0.5) * 2.0f32).exp());
    let cases: [(&str, bool, [f32; 3]); 4] = [
        (&black, true, [0.8 * 0.85; 3]),
        (&coloured, false, [0.15 * 0.2, 0.15 * 0.4, 0.15 * 0.6]),
        (physical, true, physical_want),
        (unclipped, true, [0.8 * 0.6; 3]),
    ];
    for (volume, plane, want) in cases {
        for (engine, px) in ["classic", "path"].iter().zip(both_engines(&scene(volume, false, plane))) {
            for p in px {
                for c in 0..3 {
                    assert!((p[c] - want[c]).abs() < 1e-3, "{engine}: {volume}: pixel {p:?}, want {want:?}");
                }
            }
        }
    }
}

/// Physical fog's water (`fogType` 3, Water alone) over the plane 4 below the camera, in
/// both engines, against the model (1e-3; see `maya::physical_fog`): water below height
/// 2 of σs = 0.2·colour, σa = 0.2·0.5 keeps exp(−2σt) of the plane and adds the sun's
/// light (1.5, overhead, uniform scattering) dimmed with depth z as exp(−2z/4):
/// 1.5·σs·(1 − e^(−2(σt + ½)))/(σt + ½). With Water/Fog (`fogType` 4) a uniform fog of
/// density 0.1 (colour and opacity white) fills the 2 units above the water, and fog and
/// water are lit by the fog's lights (none here): both only keep.
#[test]
fn both_engines_render_physical_fog_water_by_its_formulas() {
    let water = r#""physicalFog" on, "waterDensity" 0.2, "waterColor" 1 0.5 0.25, "waterOpacity" 0.5 0.5 0.5, "waterLevel" 2, "waterDepth" 4, "waterLightDecay" 2, "sunIntensity" 1.5, "sunElevation" 90"#;
    let in_water = |c: f32| {
        let (ss, st) = (0.2 * c, 0.2 * (c + 0.5));
        (0.8 * (-2.0 * st).exp(), 1.5 * ss * (1.0 - (-2.0 * (st + 0.5)).exp()) / (st + 0.5))
    };
    let alone = [1.0f32, 0.5, 0.25].map(|c| {
        let (keep, add) = in_water(c);
        keep + add
    });
    // Above the water: σt = 0.1·(1 + 1) over 2 units, nothing scattered in (no light).
    let above = (-0.2f32 * 2.0).exp();
    let with_fog = [1.0f32, 0.5, 0.25].map(|c| above * in_water(c).0);
    let cases = [
        (
            format!(r#""maya_envfog" ({water}, "fogType" 3, "fogDensity" 0.1, "fogColor" 1 1 1, "fogOpacity" 1 1 1)"#),
            alone,
        ),
        (
            format!(r#""maya_envfog" ({water}, "fogType" 4, "fogDensity" 0.1, "fogColor" 1 1 1, "fogOpacity" 1 1 1)"#),
            with_fog,
        ),
    ];
    for (volume, want) in &cases {
        for (engine, px) in ["classic", "path"].iter().zip(both_engines(&scene(volume, false, true))) {
            for p in px {
                for c in 0..3 {
                    assert!((p[c] - want[c]).abs() < 1e-3, "{engine}: {volume}: pixel {p:?}, want {want:?}");
                }
            }
        }
    }
}
