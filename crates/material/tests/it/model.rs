//! The shader model: declarations and instances, lazy and cached evaluation, shader lists,
//! phenomena, light lists, and what goes wrong with line and column.

use crate::support;

use glam::Vec3A;
use shader::{RayType, Value};
use support::{assert_color, compile, point, run, Empty};

/// A surface at the origin facing the light straight above, seen from straight above.
fn lit() -> shader::State {
    point(Vec3A::Y, -Vec3A::Y)
}

#[test]
fn lambert_under_a_point_light_is_exact() {
    let c = compile(
        r#"material "m" "mib_illum_lambert" ("ambience" 0.1 0.1 0.1 1, "ambient" 1 0.5 0 1,
            "diffuse" 0.5 0.5 0.5 1, "mode" 0, "lights" ["key_inst"]) end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), lit());
    // ambience ⊙ ambient + diffuse ⊙ light · cos 0; no 1/π, no distance falloff.
    assert_color(v.color(), [0.1 + 0.4, 0.05 + 0.3, 0.2, 1.0], 1e-6);
    // Tilted 60° away from the light: cos 60° = ½.
    let n = Vec3A::new(60f32.to_radians().sin(), 60f32.to_radians().cos(), 0.0);
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), point(n, -n));
    assert_color(v.color(), [0.1 + 0.2, 0.05 + 0.15, 0.1, 1.0], 1e-6);
}

#[test]
fn phong_highlight_peak_and_falloff() {
    let c = compile(
        r#"material "m" "mib_illum_phong" ("diffuse" 0.5 0.5 0.5 1, "specular" 1 1 1 1, "exponent" 40,
            "mode" 0, "lights" ["key_inst"]) end material"#,
        &["m"],
    );
    // Seen straight down, the mirror direction points at the light: highlight 1.
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), lit());
    assert_color(v.color(), [0.8 * 1.5, 0.6 * 1.5, 0.4 * 1.5, 1.0], 1e-5);
    // Seen 10° off: the highlight falls to cos(10°)^40.
    let a = 10f32.to_radians();
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), point(Vec3A::Y, Vec3A::new(a.sin(), -a.cos(), 0.0)));
    let s = a.cos().powf(40.0);
    assert_color(v.color(), [0.4 + 0.8 * s, 0.3 + 0.6 * s, 0.2 + 0.4 * s, 1.0], 1e-5);
}

#[test]
fn twosided_runs_only_the_side_it_returns() {
    let c = compile(
        r#"shader "front_c" "mib_color_average" ("input" 1 1 1 1, "factor" 0.25)
           shader "back_c" "mib_color_average" ("input" 1 1 1 1, "factor" 0.75)
           material "two" "mib_twosided" ("front" = "front_c", "back" = "back_c") end material"#,
        &["two"],
    );
    let (v, log, _) = run(&c, &Empty::default(), c.material("two"), lit());
    assert_eq!(v.color().x, 0.25);
    let names = c.names(&log);
    assert!(names.contains(&"front_c".to_string()) && !names.contains(&"back_c".to_string()), "{names:?}");
    let mut back = lit();
    back.inv_normal = true;
    let (v, log, _) = run(&c, &Empty::default(), c.material("two"), back);
    assert_eq!(v.color().x, 0.75);
    assert!(!c.names(&log).contains(&"front_c".to_string()));
}

#[test]
fn refract_evaluates_its_input_only_when_it_shows() {
    let body = |refract: &str| {
        format!(
            r#"shader "under" "mib_color_average" ("input" 1 1 1 1, "factor" 0.5)
               material "glass" "mib_refract" ("input" = "under", "refract" {refract}, "ior" 1.5) end material"#
        )
    };
    // Fully transparent: the input is not run; one refraction ray is cast.
    let c = compile(&body("1 1 1 1"), &["glass"]);
    let tracer = Empty::default();
    let (_, log, _) = run(&c, &tracer, c.material("glass"), lit());
    assert!(!c.names(&log).contains(&"under".to_string()));
    assert_eq!(tracer.rays.borrow().iter().map(|r| r.0).collect::<Vec<_>>(), [RayType::Refract]);
    // Opaque: only the input, no ray.
    let c = compile(&body("0 0 0 0"), &["glass"]);
    let tracer = Empty::default();
    let (v, log, _) = run(&c, &tracer, c.material("glass"), lit());
    assert!(c.names(&log).contains(&"under".to_string()));
    assert!(tracer.rays.borrow().is_empty());
    assert_eq!(v.color().x, 0.5);
    // Half: both, blended per component (the ray saw black).
    let c = compile(&body("0.5 0.5 0.5 0.5"), &["glass"]);
    let (v, _, _) = run(&c, &Empty::default(), c.material("glass"), lit());
    assert_color(v.color(), [0.25; 4], 1e-6);
}

#[test]
fn refract_reflects_totally_past_the_critical_angle() {
    // Leaving glass (relative index 1/1.5): critical angle asin(1/1.5) = 41.81°.
    let c = compile(r#"material "out" "mib_refract" ("refract" 1 1 1 1, "ior" 0.666667) end material"#, &["out"]);
    for (deg, kind) in [(40.0f32, RayType::Refract), (43.0, RayType::Reflect)] {
        let a = deg.to_radians();
        let dir = Vec3A::new(a.sin(), -a.cos(), 0.0);
        let tracer = Empty::default();
        run(&c, &tracer, c.material("out"), point(Vec3A::Y, dir));
        let rays = tracer.rays.borrow();
        assert_eq!(rays.len(), 1);
        assert_eq!(rays[0].0, kind, "{deg}°");
        let d = rays[0].1;
        if kind == RayType::Reflect {
            assert!((d - Vec3A::new(a.sin(), a.cos(), 0.0)).length() < 1e-5, "{d}");
        } else {
            // Snell: sin θt = 1.5 sin θi.
            assert!((d.x - 1.5 * a.sin()).abs() < 1e-5 && d.y < 0.0, "{d}");
        }
    }
}

#[test]
fn a_texture_read_twice_in_one_call_runs_once() {
    let c = compile(
        r#"shader "tex" "mib_color_average" ("input" 0.3 0.3 0.3 1, "factor" 1)
           material "m" "mib_illum_lambert" ("ambience" 1 1 1 1, "ambient" = "tex", "diffuse" = "tex",
               "mode" 0, "lights" ["key_inst"]) end material"#,
        &["m"],
    );
    let (v, log, _) = run(&c, &Empty::default(), c.material("m"), lit());
    assert_eq!(c.names(&log).iter().filter(|n| *n == "tex").count(), 1);
    assert_color(v.color(), [0.3 + 0.3 * 0.8, 0.3 + 0.3 * 0.6, 0.3 + 0.3 * 0.4, 1.0], 1e-6);
}

/// A bump map over a procedural texture reads it at three positions, flushing the cache in
/// between: the texture runs three times, and the normal tilts by the height differences.
#[test]
fn bump_mapping_flushes_the_cache_between_lookups() {
    let c = compile(
        r#"shader "where" "mib_texture_vector" ("select" -11)
           shader "stripes" "mib_texture_checkerboard" ("coord" = "where", "xsize" 0.5, "ysize" 2, "zsize" 2,
               "color000" 0 0 0 1, "color100" 1 1 1 1)
           material "m"
               "mib_passthrough_bump_map" ("u" 1 0 0, "v" 0 0 1, "coord" 0.4995 0.2 0, "step" 0.001 0.001 0,
                   "factor" 1, "tex" "stripes")
               "mib_illum_lambert" ("diffuse" 1 1 1 1, "mode" 0, "lights" ["key_inst"])
           end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let (v, log, state) = run(&c, &Empty::default(), c.material("m"), lit());
    let names = c.names(&log);
    assert_eq!(names.iter().filter(|n| *n == "stripes").count(), 3, "{names:?}");
    // Along u the height steps from 0 to 1 (the mean of the white colour): N = (0,1,0) + 1·(1,0,0).
    let n = Vec3A::new(1.0, 1.0, 0.0).normalize();
    assert!((state.normal - n).length() < 1e-5, "{}", state.normal);
    // The shader after it in the list sees the bumped normal.
    assert_color(v.color(), [0.8 * n.y, 0.6 * n.y, 0.4 * n.y, 1.0], 1e-5);
}

#[test]
fn phenomena_expand_with_their_interface() {
    let c = compile(
        r#"declare phenomenon color "tinted" (color "tint", scalar "gain")
               shader "avg" "mib_color_average" ("input" = interface "tint", "factor" = interface "gain")
               root = "avg"
           end declare
           material "m" "tinted" ("tint" 0.3 0.6 0.9 1, "gain" 2) end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), lit());
    assert_color(v.color(), [1.2; 4], 1e-6);
}

#[test]
fn connection_cycles_are_errors_not_stack_overflows() {
    let c = compile(
        r#"shader "a" "mib_color_average" ("input" = "b", "factor" 1)
           shader "b" "mib_color_average" ("input" = "a", "factor" 1)
           material "m" "mib_illum_lambert" ("diffuse" = "a") end material"#,
        &["m"],
    );
    assert!(c.messages.iter().any(|m| m.contains("error: shader connections form a cycle")), "{:?}", c.messages);
    // What remains still runs.
    run(&c, &Empty::default(), c.material("m"), lit());
}

/// A chain of 50 000 connected shaders (a hostile file) is an error at the depth limit, not
/// a stack overflow while building or running it.
#[test]
fn connection_chains_deeper_than_the_limit_are_errors_not_stack_overflows() {
    let n = 50_000;
    let mut body = String::from("shader \"s0\" \"mib_color_average\" (\"input\" 1 1 1 1, \"factor\" 1)\n");
    for i in 1..n {
        body += &format!("shader \"s{i}\" \"mib_color_average\" (\"input\" = \"s{}\", \"factor\" 1)\n", i - 1);
    }
    body += &format!("material \"m\" \"mib_illum_lambert\" (\"diffuse\" = \"s{}\") end material", n - 1);
    let c = compile(&body, &["m"]);
    // The scene layer reports the chain where it starts; the shader model, compiling it
    // anyway, stops at the same limit.
    let limit = shader::graph::MAX_NESTING;
    assert_eq!(limit as usize, scene::shader_graph::MAX_SHADER_DEPTH);
    let errors: Vec<_> = c.messages.iter().filter(|m| m.contains("error:")).collect();
    assert_eq!(errors.len(), 2, "{errors:?}");
    assert!(errors[0].contains(&format!("mira evaluates chains of at most {limit}")), "{errors:?}");
    assert!(errors[1].contains(&format!("nest more than {limit} deep")), "{errors:?}");
    // What was built runs.
    run(&c, &Empty::default(), c.material("m"), lit());
}

#[test]
fn unknown_parameters_and_type_mismatches_warn_at_line_and_column() {
    let c = compile(
        "material \"m\" \"mib_illum_lambert\" (\n    \"difuse\" 1 1 1,\n    \"mode\" \"all\") end material",
        &["m"],
    );
    let unknown = c.messages.iter().find(|m| m.contains("has no parameter 'difuse'")).expect("a warning");
    let mode = c.messages.iter().find(|m| m.contains("expected an integer")).expect("a warning");
    // The header takes six lines; the body starts on line 7.
    assert!(unknown.starts_with("test.mi:8:5: warning:"), "{unknown}");
    assert!(mode.starts_with("test.mi:9:5: warning:"), "{mode}");
}

#[test]
fn omitted_parameters_take_declared_defaults() {
    // mib_amb_occlusion declares samples 16 and bright 1 1 1 1: with nothing around, all
    // 16 probes see nothing and the result is `bright`.
    let c = compile(r#"material "m" "mib_amb_occlusion" () end material"#, &["m"]);
    let tracer = Empty::default();
    let (v, _, _) = run(&c, &tracer, c.material("m"), lit());
    assert_color(v.color(), [1.0; 4], 0.0);
    assert_eq!(tracer.rays.borrow().len(), 16);
}

#[test]
fn light_modes_select_lights() {
    let body = |mode: u32, list: &str| {
        format!(
            r#"light "fill" "mib_light_point" ("color" 0.1 0.1 0.1) origin 0 0 0 end light
               instance "fill_inst" "fill" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 -10 0 1 end instance
               material "m" "mib_illum_lambert" ("diffuse" 1 1 1 1, "mode" {mode}, "lights" [{list}]) end material"#
        )
    };
    let red = |mode, list| {
        let c = compile(&body(mode, list), &["m"]);
        assert!(c.messages.is_empty(), "{:?}", c.messages);
        run(&c, &Empty::default(), c.material("m"), lit()).0.color().x
    };
    assert!((red(0, "\"key_inst\"") - 0.8).abs() < 1e-6);
    assert!((red(0, "\"key_inst\", \"fill_inst\"") - 0.9).abs() < 1e-6);
    assert!((red(0, "") - 0.0).abs() < 1e-6, "mode 0 with no lights: none");
    assert!((red(1, "\"fill_inst\"") - 0.1).abs() < 1e-6);
    assert!((red(2, "\"key_inst\"") - 0.1).abs() < 1e-6, "exclusive");
    assert!((red(4, "") - 0.9).abs() < 1e-6, "instance mode without a list: all");
}

#[test]
fn spot_light_cone_falls_off_linearly_in_the_cosine() {
    let c = compile(
        r#"light "spot" "mib_light_spot" ("color" 1 1 1, "cone" 0.9) origin 0 0 0 direction 0 -1 0 spread 0.8 end light
           instance "spot_inst" "spot" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 -10 0 1 end instance
           material "m" "mib_illum_lambert" ("diffuse" 1 1 1 1, "mode" 0, "lights" ["spot_inst"]) end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    // A point whose direction from the light makes cos 0.85 with the axis: half way from
    // the cone (0.9) to the spread (0.8).
    let cos: f32 = 0.85;
    let x = 10.0 * (1.0 - cos * cos).sqrt() / cos;
    let mut s = lit();
    s.point = Vec3A::new(x, 0.0, 0.0);
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), s);
    // × N·L = cos as well.
    assert!((v.color().x - 0.5 * cos).abs() < 1e-5, "{}", v.color().x);
}

#[test]
fn final_gathering_returns_irradiance_not_divided_by_pi() {
    // Under a uniform environment of radiance 0.25, the irradiance is π · 0.25, and the
    // base shaders add diffuse ⊙ irradiance as mental ray did. Accuracy 1024 gives 64
    // gather rays per eye hit.
    let c = support::compile_with(
        "finalgather on finalgather accuracy 1024",
        r#"environment = "sky""#,
        r#"shader "sky" "mib_color_mix" ("num" 0, "color_base" 0.25 0.25 0.25 1)
           material "m" "mib_illum_lambert" ("diffuse" 0.5 0.5 0.5 1, "mode" 0) end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let tracer = Empty::default();
    let (v, _, _) = run(&c, &tracer, c.material("m"), lit());
    assert_eq!(tracer.rays.borrow().len(), 64);
    assert!(tracer.rays.borrow().iter().all(|(t, d)| *t == RayType::Finalgather && d.y > 0.0));
    assert_color(
        v.color(),
        [0.5 * std::f32::consts::PI * 0.25; 3].into_iter().chain([1.0]).collect::<Vec<_>>().try_into().unwrap(),
        1e-5,
    );
}

#[test]
fn the_scenes_checker_chain_picks_the_octant_colour() {
    let c = compile(
        r#"shader "uv" "mib_texture_vector" ("select" 0, "selspace" 0)
           shader "tiles" "mib_texture_remap" ("input" = "uv", "repeat" 8 8 1)
           shader "checker" "mib_texture_checkerboard" ("coord" = "tiles", "xsize" 0.5, "ysize" 0.5, "zsize" 0.5,
               "color000" 0.1 0.1 0.1 1, "color110" 0.9 0.9 0.9 1)
           material "m" "mib_color_average" ("input" = "checker", "factor" 1) end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let at = |u: f32, v: f32| {
        let mut s = lit();
        s.tex_list[0] = Vec3A::new(u, v, 0.0);
        s.tex_count = 1;
        run(&c, &Empty::default(), c.material("m"), s).0.color().x
    };
    // (0.07, 0.2) · 8 = (0.56, 1.6) → (0.56, 0.6) in its tile: x and y past the split.
    assert!((at(0.07, 0.2) - 0.9).abs() < 1e-6);
    // (0.02, 0.02) · 8 = (0.16, 0.16): the first colour.
    assert!((at(0.02, 0.02) - 0.1).abs() < 1e-6);
}

#[test]
fn colour_mix_layers_in_order() {
    let c = compile(
        r#"material "m" "mib_color_mix" ("num" 3, "mode_0" 1, "mode_1" 2, "mode_2" 4,
               "weight_0" 0.5, "weight_1" 0.25, "weight_2" 2,
               "color_0" 1 0 0 1, "color_1" 0 1 0 1, "color_2" 0.5 0.5 0.5 1, "color_base" 0 0 1 1) end material"#,
        &["m"],
    );
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), lit());
    // mix ½ red over blue: (0.5, 0, 0.5, 1); add ¼ green: (0.5, 0.25, 0.5, 1.25);
    // multiply by grey · 2 = 1·(0.5, 0.5, 0.5, 1)·2.
    assert_color(v.color(), [0.5, 0.25, 0.5, 2.5], 1e-6);
    assert_eq!(Value::Null.color().x, 0.0);
}

#[test]
fn physical_light_falls_off_with_the_inverse_square() {
    let c = compile(
        r#"light "bulb" "physical_light" ("color" 1256.637 1256.637 1256.637) origin 0 0 0 end light
           instance "bulb_inst" "bulb" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 -10 0 1 end instance
           material "m" "mib_illum_lambert" ("diffuse" 1 1 1 1, "mode" 0, "lights" ["bulb_inst"]) end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    // 400π / (4π · 10²) = 1 at the point below it.
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), lit());
    assert!((v.color().x - 1.0).abs() < 1e-4, "{}", v.color().x);
}

#[test]
fn depth_of_field_rays_meet_at_the_focal_plane() {
    let c = support::compile_with(
        "",
        r#"lens "physical_lens_dof" ("plane" 3, "radius" 0.2)"#,
        r#"material "m" "mib_illum_lambert" () end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    // The camera sits at z = 5 looking down −Z; the focal plane is at z = 2.
    let eye = Vec3A::new(0.0, 0.0, 5.0);
    let dir = Vec3A::new(0.1, 0.05, -1.0).normalize();
    let focus = eye + dir * (3.0 / -dir.z);
    for i in 0..8 {
        let mut s = point(Vec3A::Z, dir);
        s.org = eye;
        s.point = eye;
        s.sample_index = i;
        // As the renderer runs it: the lens shader's own eye rays go on past it.
        s.lens_next = 1;
        let tracer = Empty::default();
        run(&c, &tracer, c.shading.lens[0], s);
        let (kind, d) = tracer.rays.borrow()[0];
        let o = tracer.origins.borrow()[0];
        assert_eq!(kind, RayType::Eye);
        assert!((o - eye).length() <= 0.2 + 1e-5 && (o.z - 5.0).abs() < 1e-5, "lens point {o}");
        let t = (focus.z - o.z) / d.z;
        assert!((o + d * t - focus).length() < 1e-4, "misses the focus point");
    }
}
