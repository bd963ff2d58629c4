//! Built-in BSDFs in a material's `bsdf` slot, shaded by the classic engine: against the
//! base shaders they correspond to (the key light of the test scenes has colour
//! (0.8, 0.6, 0.4) and stands straight above the origin).

use crate::support;

use glam::Vec3A;
use shader::{Color, State};
use support::{assert_color, compile_with, point, run, Compiled, Empty};

fn scene(body: &str, materials: &[&str]) -> Compiled {
    let c = compile_with(
        "",
        r#"environment = "envsh""#,
        &format!(r#"shader "envsh" "mib_color_mix" ("color_base" 0.2 0.3 0.4 1) {body}"#),
        materials,
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    c
}

fn shade(c: &Compiled, name: &str, state: State) -> Color {
    run(c, &Empty::default(), c.material(name), state).0.color()
}

/// A point whose normal leans 30° from the light, seen along −normal.
fn leaning() -> State {
    let t = 30f32.to_radians();
    let n = Vec3A::new(t.sin(), t.cos(), 0.0);
    point(n, -n)
}

#[test]
fn lambert_bsdf_material_shades_as_mib_illum_lambert() {
    let c = scene(
        r#"shader "lb" "builtin_bsdf_lambert" ("diffuse" 0.5 0.4 0.3 1, "mode" 0, "lights" ["key_inst"])
           material "b" bsdf = "lb" end material
           material "r" "mib_illum_lambert" ("diffuse" 0.5 0.4 0.3 1, "mode" 0, "lights" ["key_inst"]) end material"#,
        &["b", "r"],
    );
    for s in [point(Vec3A::Y, -Vec3A::Y), leaning()] {
        let want = shade(&c, "r", s.clone());
        let got = shade(&c, "b", s);
        assert_color(got, want.to_array(), 1e-6);
    }
    // Straight above: diffuse ⊙ light colour (ρ/π · cos · π·c).
    assert_color(shade(&c, "b", point(Vec3A::Y, -Vec3A::Y)), [0.4, 0.24, 0.12, 1.0], 1e-6);
}

#[test]
fn phong_bsdf_highlight_at_the_mirror_direction() {
    // wo = wi = N: f = ρd/π + ρs (n+2)/(2π); shaded π f c.
    let c = scene(
        r#"shader "pb" "builtin_bsdf_phong" ("diffuse" 0.2 0.2 0.2 1, "glossy" 0.1 0.1 0.1 1, "exponent" 8,
               "mode" 0, "lights" ["key_inst"])
           material "b" bsdf = "pb" end material"#,
        &["b"],
    );
    let k = 0.2 + 0.1 * (8.0 + 2.0) / 2.0;
    assert_color(shade(&c, "b", point(Vec3A::Y, -Vec3A::Y)), [0.8 * k, 0.6 * k, 0.4 * k, 1.0], 1e-5);
}

#[test]
fn mirror_bsdf_reflects_as_mib_reflect() {
    let c = scene(
        r#"shader "mb" "builtin_bsdf_mirror" ("reflection" 0.9 0.8 0.7 1)
           material "b" bsdf = "mb" end material
           material "r" "mib_reflect" ("reflect" 0.9 0.8 0.7 1) end material"#,
        &["b", "r"],
    );
    let want = shade(&c, "r", leaning());
    let got = shade(&c, "b", leaning());
    assert_color(got, [want.x, want.y, want.z, 1.0], 1e-6);
    assert_color(got, [0.9 * 0.2, 0.8 * 0.3, 0.7 * 0.4, 1.0], 1e-6);
    // The mirror casts exactly one ray, along the mirror direction.
    let tracer = Empty::default();
    run(&c, &tracer, c.material("b"), leaning());
    let rays = tracer.rays.borrow();
    assert_eq!(rays.len(), 1);
    let s = leaning();
    let m = s.dir - 2.0 * s.dir.dot(s.normal) * s.normal;
    assert!((rays[0].1 - m).length() < 1e-6);
}
