//! Maya's fogs and volumeFog in a material's `volume` (a shading group's volume shader
//! inside its objects), in both engines: the classic engine runs the volume on the rays
//! inside the object (entered by the transparency ray), the path engine applies its
//! affine terms on the stretches of a path inside it (`render::integrator`'s `fog`).

use render::EngineKind;

use crate::support::render_text;

/// A camera 4 above a plane showing the unlit colour 0.8 0.5 0.3, looking straight down
/// with a field of view of 0.01 at 4×4 pixels, through a fully transparent box (a Maya
/// lambert of transparency 1) from height 1 to 3 whose material's volume is `volume` (the
/// shader lines `shaders` define the nodes it names); the camera's volume is
/// `camera_volume` (empty: none). Every ray crosses 2 units of the box.
fn scene(shaders: &str, volume: &str, camera_volume: &str) -> String {
    format!(
        r#"
$include "mayabase.mi"
options "opt" samples 0 0 filter box 1 1 end options
{shaders}
camera "cam" {camera_volume} focal 1 aperture 0.01 aspect 1 resolution 4 4 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 0 1 0  0 -1 0 0  0 0 -4 1 end instance
shader "flat" "maya_surfaceshader" ("outColor" 0.8 0.5 0.3)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material
object "plane" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance
shader "clear" "maya_lambert" ("transparency" 1 1 1)
material "box_m" "maya_shadingengine" ("surfaceShader" = "clear.outColor")
    volume {volume}
end material
object "box" group
    -1 1 -1  1 1 -1  1 3 -1  -1 3 -1  -1 1 1  1 1 1  1 3 1  -1 3 1
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7
    c "box_m" 0 3 2 1
    c "box_m" 4 5 6 7
    c "box_m" 0 1 5 4
    c "box_m" 3 7 6 2
    c "box_m" 0 4 7 3
    c "box_m" 1 2 6 5
end group end object
instance "box_inst" "box" end instance
instgroup "root" "cam_inst" "plane_inst" "box_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Renders `text` in both engines (the path engine at 4 samples per pixel): their pixels,
/// after asserting that neither gave a warning about a fog.
fn both_engines(text: &str) -> [Vec<[f32; 4]>; 2] {
    [EngineKind::Classic, EngineKind::Path].map(|engine| {
        let (px, messages) = render_text(text, engine, Some(4));
        assert!(!messages.iter().any(|m| m.to_ascii_lowercase().contains("fog")), "{engine:?}: {messages:?}");
        px
    })
}

/// Asserts every pixel of both engines' images of `text` equals `want` (RGB) within 1e-3.
fn assert_both(text: &str, want: [f32; 3], case: &str) {
    for (engine, px) in ["classic", "path"].iter().zip(both_engines(text)) {
        for p in px {
            for c in 0..3 {
                assert!((p[c] - want[c]).abs() < 1e-3, "{engine}: {case}: pixel {p:?}, want {want:?}");
            }
        }
    }
}

const PLANE: [f32; 3] = [0.8, 0.5, 0.3];

/// A light fog, an environment fog (through Maya's volume sampler and directly) and a
/// volumeFog in the box's material, in both engines, against the formulas over the 2 units
/// inside the box (1e-3): light fog of density 0.2 with fast drop-off covers α = 1 −
/// exp(−0.4) of each channel by its colour c; environment fog α = 2 / saturationDistance
/// of c, adding α·c; volumeFog of density 0.5 crosses τ = 1, passing T = `transparency`
/// and adding (1 − T) ⊙ (colour + incandescence).
#[test]
fn both_engines_apply_a_fog_inside_the_object_whose_material_holds_it() {
    let a = 1.0 - (-0.4f32).exp();
    let light_fog = [PLANE[0] * (1.0 - a), PLANE[1] * (1.0 - 0.5 * a), PLANE[2]];
    let env = [0.2f32, 0.4, 0.6];
    let env_fog: [f32; 3] = std::array::from_fn(|c| PLANE[c] * (1.0 - 0.2 * env[c]) + 0.2 * env[c]);
    let t = [0.5f32, 0.25, 0.8];
    let shown = [0.3f32, 0.4, 0.6];
    let volume_fog: [f32; 3] = std::array::from_fn(|c| PLANE[c] * t[c] + (1.0 - t[c]) * shown[c]);
    let cases = [
        (
            r#"shader "lf" "maya_lightfog" ("color" 1 0.5 0, "density" 0.2, "fastDropOff" on)"#,
            r#""maya_volumesampler" ("volumeShader" = "lf")"#,
            light_fog,
        ),
        (
            r#"shader "ef" "maya_envfog" ("color" 0.2 0.4 0.6, "saturationDistance" 10)"#,
            r#""adskMayaVolumeSampler" ("volumeShader" = "ef")"#,
            env_fog,
        ),
        ("", r#""maya_envfog" ("color" 0.2 0.4 0.6, "saturationDistance" 10)"#, env_fog),
        (
            r#"shader "vf" "maya_volumefog" ("color" 0.2 0.4 0.6, "transparency" 0.5 0.25 0.8, "incandescence" 0.1 0 0, "density" 0.5)"#,
            r#""maya_volumesampler" ("volumeShader" = "vf.outColor")"#,
            volume_fog,
        ),
    ];
    for (shaders, volume, want) in cases {
        assert_both(&scene(shaders, volume, ""), want, volume);
    }
}

/// The camera's fog outside the box and the box's fog inside it, in both engines: the
/// camera's environment fog (saturation 20, black, no colour-based transparency) covers
/// the unit above the box and the unit below it, 1/20 each, the box's light fog the 2
/// units inside (1e-3).
#[test]
fn the_camera_fog_covers_what_lies_outside_a_fog_object() {
    let shaders = r#"shader "lf" "maya_lightfog" ("color" 0 0 0, "colorBasedTransparency" off, "density" 0.2, "fastDropOff" on)
shader "cam_fog" "maya_envfog" ("color" 0 0 0, "colorBasedTransparency" off, "saturationDistance" 20)"#;
    let text = scene(shaders, r#""maya_volumesampler" ("volumeShader" = "lf")"#, r#"volume = "cam_fog""#);
    let inside = (-0.4f32).exp();
    let want: [f32; 3] = std::array::from_fn(|c| PLANE[c] * 0.95 * inside * 0.95);
    assert_both(&text, want, "camera and box fogs");
}

/// Lights seen from inside a volumeFog: a white lambert plane (diffuse 1) inside a
/// transparent box from height −1 to 3 filled with volumeFog (transparency 0.5, density
/// 0.5, black: it adds nothing), lit by a point light of intensity 1 without decay 2
/// above the plane, seen from 4 above. mental ray's light ray crosses the fog to the
/// lit point (2 units: T = 0.5^1) and the eye ray 3 units (0.5^1.5): both engines give
/// 1 · 0.5 · 0.5^1.5 (1e-3).
#[test]
fn lights_shine_through_the_volume_fog_a_lit_point_is_seen_in() {
    let text = r#"
$include "mayabase.mi"
options "opt" samples 0 0 filter box 1 1 end options
camera "cam" focal 1 aperture 0.01 aspect 1 resolution 4 4 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 0 1 0  0 -1 0 0  0 0 -4 1 end instance
light "lamp" "maya_pointlight" ("intensity" 1, "decayRate" 0) origin 0 0 0 end light
instance "lamp_inst" "lamp" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 -2 0 1 end instance
shader "white" "maya_lambert" ("color" 1 1 1, "diffuse" 1)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "white.outColor") end material
object "plane" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "plane_inst" "plane" end instance
shader "clear" "maya_lambert" ("transparency" 1 1 1)
shader "vf" "maya_volumefog" ("color" 0 0 0, "transparency" 0.5 0.5 0.5, "density" 0.5)
material "box_m" "maya_shadingengine" ("surfaceShader" = "clear.outColor")
    volume "maya_volumesampler" ("volumeShader" = "vf.outColor")
end material
object "box" group
    -4 -1 -4  4 -1 -4  4 3 -4  -4 3 -4  -4 -1 4  4 -1 4  4 3 4  -4 3 4
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7
    c "box_m" 0 3 2 1
    c "box_m" 4 5 6 7
    c "box_m" 0 1 5 4
    c "box_m" 3 7 6 2
    c "box_m" 0 4 7 3
    c "box_m" 1 2 6 5
end group end object
instance "box_inst" "box" end instance
instgroup "root" "cam_inst" "lamp_inst" "plane_inst" "box_inst" end instgroup
render "root" "cam_inst" "opt"
"#;
    let want = 0.5 * 0.5f32.powf(1.5);
    assert_both(text, [want; 3], "lit inside volumeFog");
}
