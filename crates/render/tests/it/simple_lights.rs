//! Light shaders the classic light loop evaluates in place ([`shader::light::SimpleLight`]:
//! `mib_light_point`, `mib_light_spot` and `mib_light_infinite` with constant parameters)
//! give the image their shader calls give, bit for bit.

use crate::support;

use std::sync::atomic::AtomicBool;

use render::accel::{self, Backend};
use render::{EngineKind, Settings};

/// A 4×4 floor at z = −5 under a 0.6×0.6 card at z = −4, seen from above by an
/// orthographic camera, lit by a 1×1 rectangle light at z = −3 (4×4 samples, with the
/// statements `kind` adds) whose shader `shader` has the parameters `params`; `extra` adds
/// statements.
fn scene(shader: &str, kind: &str, params: &str, extra: &str) -> String {
    format!(
        r#"
options "opt" filter box 1 1 samples 0 2 shadow on end options
camera "cam" focal infinity aperture 4 aspect 1 resolution 24 24 end camera
instance "cam_inst" "cam" end instance
{extra}
light "L" "{shader}" ({params})
    origin 0 0 -3 {kind} rectangle 1 0 0  0 1 0  4 4
end light
instance "L_inst" "L" end instance
material "floor_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1, "mode" 3) end material
object "floor" group
    -2 -2 -5  2 -2 -5  2 2 -5  -2 2 -5
    -0.3 -0.3 -4  0.3 -0.3 -4  0.3 0.3 -4  -0.3 0.3 -4
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7
    c "floor_mtl" 0 1 2 3
    c "floor_mtl" 4 5 6 7
end group end object
instance "floor_inst" "floor" end instance
instgroup "root" "cam_inst" "L_inst" "floor_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// For a point light with a linear distance ramp (the floor reaches past its `stop`) and a
/// shadow `factor` of 0.3, one with hard shadows, and a spot light (pointing down, spread
/// cosine 0.8, inner `cone` 0.9: the floor reaches past its cone) with `factor` 0.3: the
/// light evaluated in place and the same light whose `color` comes from a shader
/// (`mib_color_mix` handing back its base colour: the shader then runs per sample) render
/// bit-identical images on each backend, with a penumbra or falloff and (ramp, spot) an
/// unlit rim among the pixels (so every branch was compared), and without ramp or cone the
/// same shadow-ray count.
#[test]
fn lights_evaluated_in_place_equal_their_shader_calls() {
    let mix = r#"shader "base" "mib_color_mix" ("num" 0, "color_base" 1 0.8 0.6 1)"#;
    let settings = Settings { engine: EngineKind::Classic, spp: Some(4), ..Settings::default() };
    let point = "mib_light_point";
    let spot = ("mib_light_spot", "direction 0 0 -1 spread 0.8");
    for (shader, kind, rest) in [
        (point, "", r#""shadow" on, "factor" 0.3, "atten" on, "start" 1.5, "stop" 2.6"#),
        (point, "", r#""shadow" on, "factor" 0"#),
        (spot.0, spot.1, r#""shadow" on, "factor" 0.3, "cone" 0.9"#),
    ] {
        let rimmed = rest.contains("atten") || rest.contains("cone");
        for backend in [Backend::Rust, Backend::Embree].into_iter().filter(|b| b.available()) {
            let mut images = Vec::new();
            for (color, extra, simple) in [("\"color\" 1 0.8 0.6 1", "", true), ("\"color\" = \"base\"", mix, false)] {
                let text = scene(shader, kind, &format!("{color}, {rest}"), extra);
                let support::Compiled { scene, shading, messages, .. } = support::compile(&text);
                assert_eq!(shading.simple_light(0).is_some(), simple, "{messages:?}");
                let world = render::World::from_scene(&scene);
                let accel = accel::build(&world, backend);
                let (film, stats) =
                    render::render(&world, accel.as_ref(), Some(&shading), &settings, &AtomicBool::new(false), &|_| {});
                images.push((film.rgba(), stats.shadow_rays));
            }
            let bits = |px: &[[f32; 4]]| px.iter().flat_map(|p| p.map(f32::to_bits)).collect::<Vec<_>>();
            assert_eq!(bits(&images[0].0), bits(&images[1].0), "{backend:?} {rest}");
            if !rimmed {
                // (With a ramp or a cone, the shader's first sample at a point goes alone
                // and the loop traces the rest ahead, some of them where no light arrives.)
                assert_eq!(images[0].1, images[1].1, "{backend:?} {rest}: shadow rays");
            }
            let red: Vec<f32> = images[0].0.iter().map(|p| p[0]).collect();
            let (lo, hi) = red.iter().fold((f32::MAX, f32::MIN), |(lo, hi), &r| (lo.min(r), hi.max(r)));
            let between = red.iter().filter(|&&r| r > lo + 0.05 * (hi - lo) && r < hi - 0.05 * (hi - lo)).count();
            assert!(hi > 0.0 && between >= 8, "{backend:?} {rest}: lo {lo} hi {hi}, {between} pixels between");
            if rimmed {
                assert_eq!(lo, 0.0, "{backend:?} {rest}: the ramp's stop or the cone leaves the rim unlit");
            }
        }
    }
}
