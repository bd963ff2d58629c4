//! Module materials whose expressions depend on the shading point (tests/mdl/textured.mdl):
//! `state::` values, `tex::` lookups, `::base` textures and `::math` are compiled once and
//! evaluated at each hit. Each test sets up shading points and checks the material there
//! against what the expression means: the texels of tests/mdl/quad.ppm (2×2: red, green on
//! the top row, blue, white on the bottom; v grows upwards), ramps and facing ratios.

use crate::mdl_support;

use bsdf::Rgb;
use glam::Vec3A;
use material::{SurfaceMaterial, SurfaceModel, Varying};
use mdl_support::{close, compile_text, get};
use shader::State;

/// A shading point with texture coordinate (u, v), normal +z and a ray along `dir`.
fn point(u: f32, v: f32, dir: Vec3A, position: Vec3A) -> State {
    let mut s = State {
        tex_count: 1,
        normal: Vec3A::Z,
        normal_geom: Vec3A::Z,
        dir: dir.normalize(),
        point: position,
        ..State::default()
    };
    s.tex_list[0] = Vec3A::new(u, v, 0.0);
    s
}

fn uv(u: f32, v: f32) -> State {
    point(u, v, -Vec3A::Z, Vec3A::ZERO)
}

/// The material at `state`: diffuse colour, model, emission, opacity.
fn at(m: &SurfaceMaterial, state: &State) -> (Rgb, SurfaceModel, Rgb, f32) {
    let Varying::Evaluated(hit) = &m.varying else { panic!("{} is not evaluated per hit: {:?}", m.name, m.varying) };
    let mut h = m.constant();
    hit.0.apply(state, &mut h);
    (h.diffuse, h.model.into_owned(), h.emission, h.opacity)
}

const RED: Rgb = Rgb::new(1.0, 0.0, 0.0);
const GREEN: Rgb = Rgb::new(0.0, 1.0, 0.0);
const BLUE: Rgb = Rgb::new(0.0, 0.0, 1.0);

#[test]
fn a_texture_lookup_gives_the_texel_under_the_coordinate() {
    let (mdl, lib, diags) = compile_text(r#"shader "t" "mdl::textured::looked_up" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let t = get(&mdl, &lib, "t");
    // Texel centres; the lookup repeats outside [0, 1).
    for (u, v, want) in
        [(0.25, 0.25, BLUE), (0.75, 0.25, Rgb::ONE), (0.25, 0.75, RED), (0.75, 0.75, GREEN), (1.25, -0.75, BLUE)]
    {
        let (diffuse, model, _, _) = at(t, &uv(u, v));
        assert!(close(diffuse, want, 1e-6), "({u}, {v}): {diffuse:?} vs {want:?}");
        assert_eq!(model, SurfaceModel::Lambert);
    }
    // Halfway between the two bottom texels: their mean (bilinear).
    let (mid, _, _, _) = at(t, &uv(0.5, 0.25));
    assert!(close(mid, Rgb::new(0.5, 0.5, 1.0), 1e-6), "{mid:?}");
}

#[test]
fn a_texture_named_by_the_mi_file_is_read() {
    let (mdl, lib, diags) = compile_text(
        r#"color texture "q" "quad.ppm"
shader "t" "mdl::textured::looked_up" ("tex" "q")
shader "missing" "mdl::textured::looked_up" ("tex" "no_such.png")"#,
    );
    // The missing file is a warning at its parameter; its lookups are black.
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert!(diags[0].contains("t.mi:3:") && diags[0].contains("no_such.png"), "{}", diags[0]);
    let (red, _, _, _) = at(get(&mdl, &lib, "t"), &uv(0.25, 0.75));
    assert!(close(red, RED, 1e-6), "{red:?}");
    let missing = get(&mdl, &lib, "missing");
    assert_eq!(missing.varying, Varying::Constant, "a lookup of nothing is a constant");
    assert_eq!(missing.diffuse, Rgb::ZERO);
}

#[test]
fn file_texture_reads_a_tiled_coordinate_and_scales_its_tint() {
    let (mdl, lib, diags) = compile_text(r#"shader "t" "mdl::textured::tiled" ("scale" 0.5 0.25 1)"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let t = get(&mdl, &lib, "t");
    // Scaled by 2: (0.125, 0.125) reads texel (0.25, 0.25), blue; (0.625, 0.375) reads
    // (1.25, 0.75) → (0.25, 0.75), red. Tint = texel · scale.
    let (blue, model, _, _) = at(t, &uv(0.125, 0.125));
    assert!(close(blue, Rgb::new(0.0, 0.0, 1.0), 1e-6), "{blue:?}");
    let (red, _, _, _) = at(t, &uv(0.625, 0.375));
    assert!(close(red, Rgb::new(0.5, 0.0, 0.0), 1e-6), "{red:?}");
    // roughness = (width + height) · 0.05 = 0.2: tex::width/height are constants.
    assert_eq!(model, SurfaceModel::OrenNayar(0.2));
}

#[test]
fn a_ramp_weights_a_glossy_layer_per_hit_and_passes_the_white_furnace() {
    let (mdl, lib, diags) = compile_text(r#"shader "r" "mdl::textured::ramp" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let r = get(&mdl, &lib, "r");
    for (u, v) in [(0.3, 0.25), (0.9, 0.6), (1.5, 1.0)] {
        let (_, model, _, _) = at(r, &uv(u, v));
        let SurfaceModel::Lobes(l) = &model else { panic!("{model:?}") };
        // Glossy weight v over a diffuse base of saturate(u): the base keeps 1 − v of it.
        let base = (u.min(1.0)) * (1.0 - v);
        assert!(close(l.diffuse.albedo, Rgb::splat(base), 1e-6), "({u}, {v}): {:?}", l.diffuse.albedo);
        assert!(close(l.reflect, Rgb::splat(v), 1e-6), "({u}, {v}): {:?}", l.reflect);
        assert_eq!(l.reflect_ggx.alpha_x, 0.2);
        let lowered = SurfaceMaterial { model: model.clone(), ..SurfaceMaterial::lambert("r", Rgb::ZERO) };
        for wo in [Vec3A::Z, Vec3A::new(0.6, 0.0, 0.8)] {
            let a = bsdf::testing::albedo(&lowered.bsdf(wo), wo, 20_000);
            assert!(a.max_element() <= 1.01, "({u}, {v}): albedo {a:?} at {wo:?}");
        }
    }
}

#[test]
fn state_values_drive_the_tint_and_the_cutout() {
    let (mdl, lib, diags) = compile_text(r#"shader "f" "mdl::textured::facing" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let f = get(&mdl, &lib, "f");
    assert!(f.may_cut_out(None));
    // |n · d| = 0.8 for a ray (0.6, 0, −0.8) onto +z; opaque where x > 0, cut out elsewhere.
    let (tint, _, _, opacity) = at(f, &point(0.0, 0.0, Vec3A::new(0.6, 0.0, -0.8), Vec3A::new(1.0, 0.0, 0.0)));
    assert!(close(tint, Rgb::splat(0.8), 1e-6) && opacity == 1.0, "{tint:?} {opacity}");
    let (tint, _, _, opacity) = at(f, &point(0.0, 0.0, -Vec3A::Z, Vec3A::new(-1.0, 0.0, 0.0)));
    assert!(close(tint, Rgb::ONE, 1e-6) && opacity == 0.0, "{tint:?} {opacity}");
}

#[test]
fn math_of_constants_stays_a_constant_material() {
    let (mdl, lib, diags) = compile_text(r#"shader "c" "mdl::textured::constant_math" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let c = get(&mdl, &lib, "c");
    // smoothstep(0, 1, ¼) = 3/16 − 2/64 = 0.15625.
    assert_eq!(c.varying, Varying::Constant);
    assert_eq!(c.model, SurfaceModel::Lambert);
    assert!(close(c.diffuse, Rgb::splat(0.15625), 1e-6), "{:?}", c.diffuse);
}

#[test]
fn a_textured_emission_is_radiance_per_hit() {
    let (mdl, lib, diags) = compile_text(r#"shader "g" "mdl::textured::glowing" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let g = get(&mdl, &lib, "g");
    // A Lambertian emitter of exitance E (the texel) has radiance E/π.
    let (_, _, emission, _) = at(g, &uv(0.75, 0.75));
    assert!(close(emission, GREEN / std::f32::consts::PI, 1e-6), "{emission:?}");
}

#[test]
fn a_parameter_connected_to_an_mdl_function_shader_is_evaluated_per_hit() {
    let (mdl, lib, diags) = compile_text(
        r#"color texture "q" "quad.ppm"
shader "uvw" "mdl::base::coordinate_source(::base::texture_coordinate_system,int)" ("texture_space" 0)
shader "tex" "mdl::base::file_texture" ("texture" "q", "uvw" = "uvw", "color_scale" 0.5 0.5 0.5)
shader "m" "mdl::export_multi::matte" ("tint" = "tex.tint", "roughness" 0)
shader "whole" "mdl::export_multi::matte" ("tint" = "tex")"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    // The texel times color_scale; a whole texture_return connected to a colour is its tint.
    for name in ["m", "whole"] {
        let (red, _, _, _) = at(get(&mdl, &lib, name), &uv(0.25, 0.75));
        assert!(close(red, RED * 0.5, 1e-6), "{name}: {red:?}");
        let (white, _, _, _) = at(get(&mdl, &lib, name), &uv(0.75, 0.25));
        assert!(close(white, Rgb::splat(0.5), 1e-6), "{name}: {white:?}");
    }
}

#[test]
fn a_tangent_space_normal_map_bends_the_normal_per_hit() {
    let (mdl, lib, diags) = compile_text(r#"shader "n" "mdl::textured::normal_mapped" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let n = get(&mdl, &lib, "n");
    let Varying::Evaluated(hit) = &n.varying else { panic!("{:?}", n.varying) };
    // Without surface derivatives the tangents are the frame around the normal (+z).
    let frame = bsdf::Frame::from_normal(Vec3A::Z);
    // Texel t maps to 2t − 1: white (1, 1, 1) leans along +u and +v with z = 1; red
    // (1, 0, 0) along +u and −v with z = −1, clamped to 0.
    for (u, v, want) in [
        (0.75, 0.25, (frame.tangent + frame.bitangent + Vec3A::Z).normalize()),
        (0.25, 0.75, (frame.tangent - frame.bitangent).normalize()),
    ] {
        let mut h = n.constant();
        hit.0.apply(&uv(u, v), &mut h);
        let got = h.normal.expect("a bent normal");
        assert!((got - want).length() < 1e-5, "({u}, {v}): {got:?} vs {want:?}");
    }
}

/// A module whose two tints are the same 40-level chain of squares built by two calls
/// (41 values, 2^41 paths each; tests/mdl/shared.mdl): compiling it compares the two
/// graphs pair of nodes by pair of nodes (not path by path, which would not finish) and
/// then refuses the material for its evaluation cost, with the count. The 12-level
/// chain compiles and gives u^4096.
#[test]
fn shared_subexpressions_built_twice_compile_in_bounded_time() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "hostile" "mdl::shared::twice_built" ()
shader "modest" "mdl::shared::twice_built_modest" ()"#,
    );
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert!(diags[0].contains("steps to evaluate"), "{}", diags[0]);
    assert_eq!(get(&mdl, &lib, "hostile").varying, Varying::Constant);
    let modest = get(&mdl, &lib, "modest");
    let u: f32 = 0.9999;
    let (diffuse, model, _, _) = at(modest, &uv(u, 0.5));
    let want = f64::from(u).powi(4096) as f32;
    assert!(close(diffuse, Rgb::splat(want), 1e-3), "{diffuse:?} vs {want}");
    assert_eq!(model, SurfaceModel::Lambert);
}
