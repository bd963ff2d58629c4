//! Final gathering on Maya's materials in the classic engine: they divide its irradiance by
//! π (mental ray for Maya since Maya 6; `irradianceColor` scales what is left), where the
//! base library's materials add diffuse ⊙ irradiance as the manual's example does (see
//! `model.rs`). Under a uniform sky of radiance L every gather ray returns L, so the
//! irradiance is exactly π·L and a lambert shows c·d·L — what the path engine's Lambertian
//! of albedo c·d gives under the same sky. The shading point is the origin, normal +y.

use crate::support;

use support::maya::{assert_rgb, compile_with_camera, point, run, Compiled};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";

/// Radiance of the uniform sky (its `mib_color_mix` base colour).
const SKY: f32 = 0.25;

/// `material` (shaders ending in material "m") under the grey sky, with final gathering on
/// (accuracy 1024: 64 gather rays at an eye hit).
fn under_sky(material: &str) -> Compiled {
    let camera = r#"environment = "sky""#;
    let body = format!(
        r#"{LIBS}shader "sky" "mib_color_mix" ("num" 0, "color_base" {SKY} {SKY} {SKY} 1)
        {material}"#
    );
    let c = compile_with_camera(camera, "finalgather on finalgather accuracy 1024", &body, &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    c
}

fn shade(c: &Compiled) -> glam::Vec4 {
    let tracer = Empty::default();
    let color = run(c, &tracer, c.material("m"), point([0.0, 0.0])).color();
    let rays = tracer.rays.borrow();
    assert!(rays.iter().any(|(t, _)| *t == shader::RayType::Finalgather), "no final gather ray was cast");
    color
}

#[test]
fn a_lambert_under_a_uniform_sky_shows_its_albedo_times_the_sky() {
    let c = under_sky(
        r#"shader "lam" "maya_lambert" ("color" 0.5 0.6 0.7, "diffuse" 0.8)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#,
    );
    // c·d·L, no π: 1e-5 (the gather's mean of identical radiances is exact).
    assert_rgb(shade(&c), [0.5 * 0.8 * SKY, 0.6 * 0.8 * SKY, 0.7 * 0.8 * SKY], 1e-5);
}

#[test]
fn irradiance_color_scales_the_gathered_light_per_channel() {
    let c = under_sky(
        r#"shader "bl" "maya_blinn" ("color" 1 1 1, "diffuse" 1, "irradianceColor" 2 0.5 0,
            "specularColor" 0 0 0, "reflectivity" 0)
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "bl.outColor") end material"#,
    );
    assert_rgb(shade(&c), [2.0 * SKY, 0.5 * SKY, 0.0], 1e-5);
}

#[test]
fn a_ramp_shader_takes_the_gathered_light_over_pi_with_its_colour_at_one() {
    // Light-angle input: the ambient and final-gather light take the colour at 1.
    let c = under_sky(
        r#"shader "rs" "maya_rampshader" ("colorInput" 0, "diffuse" 0.5,
            "color" [ { "color_Position" 0, "color_Color" 0 0 0, "color_Interp" 1 },
                      { "color_Position" 1, "color_Color" 0.8 0.6 0.4, "color_Interp" 1 } ])
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "rs.outColor") end material"#,
    );
    assert_rgb(shade(&c), [0.8 * 0.5 * SKY, 0.6 * 0.5 * SKY, 0.4 * 0.5 * SKY], 1e-5);
}
