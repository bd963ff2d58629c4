//! Each base shader against its formula, with values worked out by hand (the light `key`
//! of the test scenes has colour (0.8, 0.6, 0.4) and stands straight above the point).

use crate::support;

use std::f32::consts::PI;

use glam::Vec3A;
use shader::{State, Value};
use support::{assert_color, compile, point, run, Compiled, Empty};

/// A 2×2 texture: bottom row red, green; top row blue, white.
const QUAD: &str = r#"color texture "quad" [ 2 2 ] 'ff0000' '00ff00' '0000ff' 'ffffff'"#;

fn lit() -> State {
    point(Vec3A::Y, -Vec3A::Y)
}

/// Compiles `body` with one material "m" and runs it at `state`.
fn eval(body: &str, state: State) -> (Value, State, Compiled) {
    let c = compile(body, &["m"]);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let (v, _, s) = run(&c, &Empty::default(), c.material("m"), state);
    (v, s, c)
}

fn color(body: &str, state: State) -> [f32; 4] {
    eval(body, state).0.color().to_array()
}

fn close(got: [f32; 4], want: [f32; 4], tol: f32) {
    assert_color(glam::Vec4::from_array(got), want, tol);
}

#[test]
fn blinn_and_cook_torrance_at_the_mirror_direction() {
    // H = N: D = 1/(4m²), G = 1, F = ((n−1)/(n+1))²; value F·D·G/(π N·V N·L).
    let f = |n: f32| ((n - 1.0) / (n + 1.0)).powi(2) / (4.0 * 0.25 * PI);
    let blinn = color(
        r#"material "m" "mib_illum_blinn" ("specular" 1 1 1 1, "roughness" 0.5, "ior" 1.5, "mode" 0,
            "lights" ["key_inst"]) end material"#,
        lit(),
    );
    close(blinn, [0.8 * f(1.5), 0.6 * f(1.5), 0.4 * f(1.5), 1.0], 1e-6);
    let ct = color(
        r#"material "m" "mib_illum_cooktorr" ("specular" 1 1 1 1, "roughness" 0.5, "ior" 1.5 2 0.5, "mode" 0,
            "lights" ["key_inst"]) end material"#,
        lit(),
    );
    // ior below 1 is taken as 1: no reflection in blue.
    close(ct, [0.8 * f(1.5), 0.6 * f(2.0), 0.0, 1.0], 1e-6);
}

#[test]
fn ward_isotropic_peak() {
    // At H = N the exponent is 0: 1/(4π α²) with α = 1/shiny, times N·L = 1.
    let v = color(
        r#"material "m" "mib_illum_ward" ("glossy" 1 1 1 1, "shiny_u" 5, "shiny_v" 5, "mode" 0,
            "lights" ["key_inst"]) end material"#,
        lit(),
    );
    let peak = 25.0 / (4.0 * PI);
    close(v, [0.8 * peak, 0.6 * peak, 0.4 * peak, 1.0], 1e-5);
    // ward_deriv takes its directions from the surface; isotropic, it is the same.
    let mut s = lit();
    s.derivs = [Vec3A::X, Vec3A::Z];
    let d = color(
        r#"material "m" "mib_illum_ward_deriv" ("glossy" 1 1 1 1, "shiny_u" 5, "shiny_v" 5, "mode" 0,
            "lights" ["key_inst"]) end material"#,
        s,
    );
    close(d, v, 1e-6);
}

#[test]
fn hair_is_opaque_at_the_root_and_clear_at_the_tip() {
    let body = r#"material "m" "mib_illum_hair" ("ambience" 0.1 0.1 0.1 1, "ambient" 1 1 1 1, "diffuse" 1 1 1 1,
        "specular" 0.5 0.5 0.5 1, "exponent" 10, "mode" 0, "lights" ["key_inst"]) end material"#;
    let mut root = lit();
    root.derivs[0] = Vec3A::X;
    root.bary = [0.5, 0.0, 0.5];
    // Root: diffuse halved, tangent across the light: the diffuse normal is N (cos 1), the
    // highlight sin(t, H)^10 = 1.
    close(color(body, root.clone()), [0.1 + 0.4 + 0.4, 0.1 + 0.3 + 0.3, 0.1 + 0.2 + 0.2, 1.0], 1e-5);
    let mut tip = root;
    tip.bary = [0.0, 1.0, 0.0];
    // Tip: alpha 0, so what lies behind (nothing) shows.
    close(color(body, tip), [0.0; 4], 1e-6);
}

#[test]
fn transparency_opacity_and_continue_blend_with_what_lies_behind() {
    let input = r#"shader "in" "mib_color_average" ("input" 1 1 1 1, "factor" 0.8)"#;
    // Nothing behind: the traced colour is transparent black.
    for (decl, param, want) in [
        ("mib_transparency", "transp", 0.8 * 0.75),
        ("mib_continue", "transp", 0.8 * 0.75),
        ("mib_opacity", "opacity", 0.8 * 0.25),
    ] {
        let v = color(
            &format!(r#"{input} material "m" "{decl}" ("input" = "in", "{param}" 0.25 0.25 0.25 0.25) end material"#),
            lit(),
        );
        close(v, [want; 4], 1e-6);
    }
}

#[test]
fn dielectric_blends_by_its_scalar_refract() {
    let v = color(
        r#"material "m" "mib_dielectric" ("input" 0.4 0.4 0.4 1, "absorb" 0.5 0.5 0.5, "refract" 0.5, "ior" 1.5) end material"#,
        lit(),
    );
    close(v, [0.2, 0.2, 0.2, 0.5], 1e-6);
}

#[test]
fn refraction_index_enters_from_outside() {
    let c = compile(
        r#"shader "ri" "mib_refraction_index" ("mtl_ior" 1.5)
           material "m" "mib_refract" ("refract" 1 1 1 1, "ior" = "ri.ior") end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let mut s = lit();
    s.material = Some(0);
    let tracer = Empty::default();
    let (_, _, state) = run(&c, &tracer, c.material("m"), s);
    // Entering: index 1.5 over 1; straight down, the ray goes on straight.
    assert_eq!((state.ior_in, state.ior), (1.0, 1.5));
    let rays = tracer.rays.borrow();
    assert!((rays[0].1 - -Vec3A::Y).length() < 1e-6);
}

#[test]
fn texture_lookups() {
    let mut s = lit();
    s.tex_list[0] = Vec3A::new(0.125, 0.2, 0.0);
    s.tex_count = 1;
    // lookup2 scales the coordinate by `factor`: (0.25, 0.4), i.e. texel position
    // (0, 0.3): the left column, 70% red (bottom) and 30% blue (top).
    let v = color(&format!(r#"{QUAD} material "m" "mib_texture_lookup2" ("tex" "quad", "factor" 2) end material"#), s);
    close(v, [0.7, 0.0, 0.3, 1.0], 1e-5);
    // filter_lookup at a texel centre returns the texel.
    let v = color(
        &format!(r#"{QUAD} material "m" "mib_texture_filter_lookup" ("tex" "quad", "coord" 0.75 0.75 0) end material"#),
        lit(),
    );
    close(v, [1.0; 4], 1e-6);
    // Outside [0, 1)²: transparent black.
    let v = color(
        &format!(r#"{QUAD} material "m" "mib_texture_lookup" ("tex" "quad", "coord" 1.2 0.5 0) end material"#),
        lit(),
    );
    close(v, [0.0; 4], 0.0);
}

#[test]
fn rotate_and_bump_basis() {
    let c = compile(
        r#"shader "rot" "mib_texture_rotate" ("input" 1 0 0, "angle" 0.5)
           shader "basis" "mib_bump_basis" ("project" 2)
           material "m" "mib_color_average" ("input" = "rot.u", "factor" 1) end material
           material "n" "mib_color_average" ("input" = "rot.v", "factor" 1) end material
           material "b" "mib_color_average" ("input" = "basis.v", "factor" 1) end material"#,
        &["m", "n", "b"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    // θ = 0.5 · ¼ turn = 45° about N = +Y, from u = X, v = N × u = −Z.
    let h = 0.5f32.sqrt();
    let avg = |v: Vec3A| (v.x + v.y + v.z) / 3.0;
    let (u, _, _) = run(&c, &Empty::default(), c.material("m"), lit());
    assert!((u.color().x - avg(Vec3A::new(h, 0.0, -h))).abs() < 1e-6);
    let (v, _, _) = run(&c, &Empty::default(), c.material("n"), lit());
    assert!((v.color().x - avg(Vec3A::new(-h, 0.0, -h))).abs() < 1e-6);
    let (b, _, _) = run(&c, &Empty::default(), c.material("b"), lit());
    assert!((b.color().x - 1.0 / 3.0).abs() < 1e-6, "xy projection: v = +Y");
}

#[test]
fn bump_map_returns_the_new_normal_and_bump_map2_restores_it() {
    let (v, state, _) = eval(
        &format!(
            r#"{QUAD} material "m" "mib_bump_map" ("u" 1 0 0, "v" 0 0 1, "coord" 0.5 0.25 0, "step" 0.5 0 0,
                "factor" 1, "tex" "quad") end material"#
        ),
        lit(),
    );
    // Heights (mean of r, g, b): red ⅓ at u = 0.5 (between red and green: ⅓ both); one
    // step along u wraps to the same mix: no slope in u; v step 0.001: nearly flat.
    assert!((v.vector() - state.normal).length() < 1e-6);
    assert!(state.normal.y > 0.99);
    let (v, state, _) = eval(
        &format!(
            r#"{QUAD} material "m" "mib_bump_map2" ("factor" 5, "scale" 1, "tex" "quad", "color" 0.1 0.2 0.3 1) end material"#
        ),
        lit(),
    );
    close(v.color().to_array(), [0.1, 0.2, 0.3, 1.0], 0.0);
    assert_eq!(state.normal, Vec3A::Y);
}

#[test]
fn procedural_textures() {
    let at = |decl: &str, coord: &str| {
        color(
            &format!(
                r#"material "m" "{decl}" ("coord" {coord}, "radius" 0.5, "fgcolor" 1 1 1 1, "bgcolor" 0 0 0 1) end material"#
            ),
            lit(),
        )[0]
    };
    assert_eq!(at("mib_texture_polkadot", "0.3 0.3 5"), 1.0);
    assert_eq!(at("mib_texture_polkadot", "0.4 0.4 0"), 0.0);
    assert_eq!(at("mib_texture_polkasphere", "0.3 0.3 0.1"), 1.0);
    assert_eq!(at("mib_texture_polkasphere", "0.3 0.3 0.3"), 0.0);
    let w = color(
        r#"material "m" "mib_texture_wave" ("coord" 0.25 0 0.5, "amplitude_x" 7, "amplitude_y" 0.2, "amplitude_z" 0.1,
            "offset" 0.5) end material"#,
        lit(),
    );
    close(w, [0.6; 4], 1e-5);
    let t = color(
        r#"shader "t" "mib_texture_turbulence" ("coord" 0.3 0.4 0.5, "polar_dim" 2)
           material "m" "mib_color_average" ("input" = "t", "factor" 1) end material"#,
        lit(),
    );
    let expect = baselib::procedural::turbulence_value(Vec3A::new(0.3, 0.4, 0.5), 0.0, 0.0, 0.0, 0, 2);
    assert!((t[0] - expect).abs() < 1e-6 && (0.0..=1.0).contains(&expect));
}

#[test]
fn colour_conversions() {
    let input = "\"input\" 0.2 0.4 0.6 0.5";
    let c = |decl: &str| color(&format!(r#"material "m" "{decl}" ({input}, "factor" 2) end material"#), lit());
    close(c("mib_color_alpha"), [1.0; 4], 1e-6);
    close(c("mib_color_average"), [0.8; 4], 1e-6);
    close(c("mib_color_intensity"), [2.0 * (0.299 * 0.2 + 0.587 * 0.4 + 0.114 * 0.6); 4], 1e-6);
    let ramp = |x: f32| {
        color(
            &format!(
                r#"material "m" "mib_color_interpolate" ("input" {x}, "num" 3, "weight_1" 0.25,
                    "color_0" 0 0 0 0, "color_1" 1 1 1 1, "color_2" 0 0 0 0) end material"#
            ),
            lit(),
        )[0]
    };
    assert!((ramp(0.125) - 0.5).abs() < 1e-6 && (ramp(0.625) - 0.5).abs() < 1e-6 && ramp(0.25) == 1.0);
    let spread = color(
        r#"shader "sp" "mib_color_spread" ("input" 0.2 0.4 0.6 0.5, "num" 2, "mode_0" 0, "mode_1" 2, "weight_0" 1 0.5 1 1)
           material "m" "mib_color_average" ("input" = "sp.out_1", "factor" 1) end material"#,
        lit(),
    );
    // Mode 2 is (a + r + g)/3 in mental ray's code; weight 1 is the second packed number.
    close(spread, [(0.5 + 0.2 + 0.4) / 3.0 * 0.5; 4], 1e-6);
}

#[test]
fn light_attenuation_and_photometric_falloff() {
    let lambert = r#"material "m" "mib_illum_lambert" ("diffuse" 1 1 1 1, "mode" 0, "lights" ["l_inst"]) end material"#;
    let light = |shader: &str, extra: &str| {
        color(
            &format!(
                r#"light "l" {shader} origin 0 0 0 {extra} end light
                   instance "l_inst" "l" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 -10 0 1 end instance
                   {lambert}"#
            ),
            lit(),
        )[0]
    };
    assert!((light(r#""mib_light_point" ("color" 1 1 1, "atten" on, "start" 5, "stop" 15)"#, "") - 0.5).abs() < 1e-6);
    assert_eq!(light(r#""mib_light_point" ("color" 1 1 1, "atten" on, "start" 5, "stop" 8)"#, ""), 0.0);
    assert!((light(r#""mib_light_photometric" ("color" 100 100 100)"#, "exponent 2") - 1.0).abs() < 1e-5);
    // Outside start…stop the falloff is not applied at all.
    assert!(
        (light(r#""mib_light_photometric" ("color" 2 2 2, "start" 1, "stop" 5)"#, "exponent 2") - 2.0).abs() < 1e-6
    );
}

#[test]
fn environment_lookups() {
    let mut s = lit();
    s.raster = glam::Vec2::new(2.0, 6.0);
    // 8×8 image: raster (2, 6) → (0.25, 0.75) → the blue texel.
    let v = color(&format!(r#"{QUAD} material "m" "mib_lookup_background" ("tex" "quad") end material"#), s);
    close(v, [0.0, 0.0, 1.0, 1.0], 1e-3);
    // Cube: straight up (+y) from the centre meets face 5, whose texture is tex_pz.
    let v = color(
        &format!(
            r#"{QUAD} material "m" "mib_lookup_cube6" ("point" 0 0 0, "dir" 0 1 0, "size" 2 2 2, "tex_pz" "quad") end material"#
        ),
        lit(),
    );
    close(v, [0.5, 0.5, 0.5, 1.0], 1e-6);
    // cube1: face 5 of six side by side: u = (0.5 + 5)/6 = 11/12, texel position 4/3:
    // ⅔ of the right column, ⅓ of the left (wrapping), half way up.
    let v = color(
        &format!(
            r#"{QUAD} material "m" "mib_lookup_cube1" ("point" 0 0 0, "dir" 0 1 0, "size" 2 2 2, "tex" "quad") end material"#
        ),
        lit(),
    );
    close(v, [0.5, 2.0 / 3.0, 0.5, 1.0], 1e-6);
    // Cylinder: from the axis along +x: angle 0, height 0 → (0, 0.5).
    let mut s = lit();
    s.point = Vec3A::ZERO;
    s.dir = Vec3A::X;
    let v = color(&format!(r#"{QUAD} material "m" "mib_lookup_cylindrical" ("tex" "quad") end material"#), s);
    close(v, [0.5, 0.5, 0.5, 1.0], 1e-6);
}

#[test]
fn fast_occlusion_and_stencil() {
    let v = color(r#"material "m" "mib_fast_occlusion" ("bright" 0.9 0.8 0.7 1) end material"#, lit());
    close(v, [0.9, 0.8, 0.7, 1.0], 0.0);
    let c = support::compile_with(
        "",
        r#"lens "mib_lens_stencil" ("ceiling" 1, "floor_color" 1 0.5 0 1, "stencil" "half")"#,
        r#"scalar texture "half" [ 1 1 ] '80'
           material "m" "mib_illum_lambert" () end material"#,
        &["m"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let mut s = lit();
    s.lens_next = 1;
    let (v, _, _) = run(&c, &Empty::default(), c.shading.lens[0], s);
    // s = 128/255: s·(black eye ray) + (1 − s)·floor colour.
    let k = 1.0 - 128.0 / 255.0;
    close(v.color().to_array(), [k, 0.5 * k, 0.0, 0.0], 1e-6);
}

#[test]
fn photometric_light_follows_its_ies_profile() {
    // Quadrant-symmetric type C profile: vertical 0, 90, 180; horizontal 0 and 90 with 40
    // and 80 cd sideways (peak 100 at the nadir). The light stands at world (0, 10, 0) and
    // lights the point below it, so the direction is local −Y: vertical 90°, horizontal
    // 270°, which folds onto the 90° column: 80 / 100 of the colour.
    let dir = std::env::temp_dir().join(format!("mira_base_ies_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("quad.ies");
    std::fs::write(
        &file,
        "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 2 1 2 0 0 0\n1 1 10\n0 90 180\n0 90\n100 40 0\n100 80 0\n",
    )
    .unwrap();
    let lambert = r#"material "m" "mib_illum_lambert" ("diffuse" 1 1 1 1, "mode" 0, "lights" ["l_inst"]) end material"#;
    let light = |params: &str, statement: &str| {
        color(
            &format!(
                r#"lightprofile "quad" format ies file "{}" end lightprofile
                   light "l" "mib_light_photometric" ("color" 100 100 100{params}) origin 0 0 0 exponent 2 {statement} end light
                   instance "l_inst" "l" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 -10 0 1 end instance
                   {lambert}"#,
                file.display()
            ),
            lit(),
        )[0]
    };
    assert!((light(r#", "profile" "quad""#, "") - 0.8).abs() < 1e-5);
    // The light's own `lightprofile` statement stands in for an unset parameter.
    assert!((light("", r#"lightprofile "quad""#) - 0.8).abs() < 1e-5);
    assert!((light("", "") - 1.0).abs() < 1e-5);
    let _ = std::fs::remove_dir_all(&dir);
}
