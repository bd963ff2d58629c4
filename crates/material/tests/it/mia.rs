//! `mia_material` in the classic engine against values worked out from the author's
//! formulas (the test scenes' light `key` has colour (0.8, 0.6, 0.4), straight above).

use crate::support;

use glam::Vec3A;
use shader::{RayType, Value};
use support::{assert_color, compile, point, run, Empty};

fn lit() -> shader::State {
    point(Vec3A::Y, -Vec3A::Y)
}

/// Seen straight down under a light straight above, with gloss ½: diffuse level
/// 0.5 × (1 − 0.6 × 0.2) = 0.44, highlight π Σ w_k f_k with f_k = (16/d_k)²/(4π) at the
/// peak: (256/6 + 64/3 + 16/2)/4 = 18, times the reflection level 0.12.
#[test]
fn defaults_with_half_gloss_seen_head_on() {
    let c = compile(r#"material "m" "mia_material_x" ("refl_gloss" 0.5) end material"#, &["m"]);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let tracer = Empty::default();
    let (v, _, _) = run(&c, &tracer, c.material("m"), lit());
    let k = 0.44 + 18.0 * 0.12;
    assert_color(v.member("result").unwrap().color(), [0.8 * k, 0.6 * k, 0.4 * k, 1.0], 1e-4);
    assert_color(v.member("diffuse_level").unwrap().color(), [0.44, 0.44, 0.44, 1.0], 1e-6);
    assert_color(v.member("refl_level").unwrap().color(), [0.12, 0.12, 0.12, 1.0], 1e-6);
    assert_color(v.member("spec_raw").unwrap().color(), [0.8 * 18.0, 0.6 * 18.0, 0.4 * 18.0, 1.0], 1e-3);
    // 8 glossy reflection rays for an eye hit.
    let kinds: Vec<RayType> = tracer.rays.borrow().iter().map(|r| r.0).collect();
    assert_eq!(kinds.iter().filter(|k| **k == RayType::Reflect).count(), 8);
    // The legacy interface returns the same colour.
    let c2 = compile(r#"material "m" "mia_material" ("refl_gloss" 0.5) end material"#, &["m"]);
    let (v2, _, _) = run(&c2, &Empty::default(), c2.material("m"), lit());
    assert_color(v2.color(), v.member("result").unwrap().color().to_array(), 1e-4);
}

#[test]
fn outputs_connect_by_member_name() {
    let c = compile(
        r#"shader "mia" "mia_material_x" ("diffuse" 1 0 0, "reflectivity" 0)
           material "m" "mib_color_average" ("input" = "mia.diffuse_result", "factor" 3) end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), lit());
    // diffuse (1, 0, 0) × light (0.8, 0.6, 0.4): only red, 0.8; averaged × 3.
    assert!((v.color().x - 0.8).abs() < 1e-5, "{}", v.color().x);
}

#[test]
fn metal_mode_tints_the_highlight_by_the_diffuse_colour() {
    let c = compile(
        r#"material "m" "mia_material_x" ("diffuse" 1 0.5 0, "refl_gloss" 0.5, "refl_is_metal" on) end material"#,
        &["m"],
    );
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), lit());
    let spec = v.member("spec_level").unwrap().color();
    assert_color(spec, [0.12, 0.06, 0.0, 1.0], 1e-6);
}

#[test]
fn cutouts_show_what_is_behind_and_let_light_through() {
    let c = compile(r#"material "m" "mia_material_x" ("cutout_opacity" 0) end material"#, &["m"]);
    let tracer = Empty::default();
    let (v, _, _) = run(&c, &tracer, c.material("m"), lit());
    assert_eq!(v.member("result").unwrap().color(), glam::Vec4::ZERO);
    assert_eq!(tracer.rays.borrow()[0].0, RayType::Transparent);
    // As a shadow shader: fully cut out, all light passes.
    let mut s = lit();
    s.ray_type = RayType::Shadow;
    let mut ctx = shader::Ctx::new(&c.shading, &tracer, s);
    let mut light = Value::Color(glam::Vec4::new(0.5, 0.5, 0.5, 1.0));
    assert!(ctx.run_list(c.material("m"), &mut light));
    assert_eq!(light.color(), glam::Vec4::new(0.5, 0.5, 0.5, 1.0));
}

#[test]
fn transparent_shadows_take_the_reflection_share_out() {
    let c = compile(
        r#"material "m" "mia_material_x" ("transparency" 1, "refr_color" 1 0.5 0.25, "reflectivity" 0.5,
            "brdf_0_degree_refl" 0.2) end material"#,
        &["m"],
    );
    let mut s = lit();
    s.ray_type = RayType::Shadow;
    let tracer = Empty::default();
    let mut ctx = shader::Ctx::new(&c.shading, &tracer, s);
    let mut light = Value::Color(glam::Vec4::ONE);
    ctx.run_list(c.material("m"), &mut light);
    // Head on: reflection 0.5 × 0.2 = 0.1 takes 10 % of the transparency.
    assert_color(light.color(), [0.9, 0.45, 0.225, 1.0], 1e-6);
}

#[test]
fn translucency_is_lit_from_behind() {
    let c = compile(
        r#"material "m" "mia_material_x" ("diffuse_weight" 0, "reflectivity" 0, "transparency" 1,
            "refr_translucency" on, "refr_trans_color" 1 1 1, "refr_trans_weight" 1) end material"#,
        &["m"],
    );
    // A surface facing down, the light above it: lit only from behind.
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), point(-Vec3A::Y, Vec3A::Y));
    assert_color(v.member("tran_result").unwrap().color(), [0.8, 0.6, 0.4, 1.0], 1e-5);
    assert_color(v.member("refr_level").unwrap().color(), [0.0, 0.0, 0.0, 1.0], 1e-6);
}
