//! The `::base` functions mira compiles from its own MDL bodies (statement bodies in
//! crates/mdl_lang/std/base.mdl; tests/mdl/base_conversions.mdl): glossiness and
//! anisotropy conversions, Abbe and Sellmeier indices, volume coefficients, normal
//! blending and the spherical environment, each at points worked out by hand.

use crate::mdl_support;

use bsdf::Rgb;
use glam::Vec3A;
use material::{SurfaceMaterial, Varying};
use mdl_support::{close, compile_text, get};
use shader::State;

/// The radiance `m` emits at `state` (its constant where nothing varies).
fn emitted(m: &SurfaceMaterial, state: &State) -> Rgb {
    let mut h = m.constant();
    if let Varying::Evaluated(e) = &m.varying {
        e.0.apply(state, &mut h);
    }
    h.emission
}

/// A shading point with normal +z, tangents +x and +y, looking along `dir`.
fn point(dir: Vec3A) -> State {
    State { normal: Vec3A::Z, normal_geom: Vec3A::Z, derivs: [Vec3A::X, Vec3A::Y], dir, ..State::default() }
}

/// `base_conversions::<material>` with `params` at `state`, with no message.
fn value(material: &str, params: &str, state: &State) -> Rgb {
    let (mdl, lib, diags) = compile_text(&format!(r#"shader "m" "mdl::base_conversions::{material}" ({params})"#));
    assert!(diags.is_empty(), "{material} {params}: {diags:#?}");
    emitted(get(&mdl, &lib, "m"), state)
}

fn constant(material: &str, params: &str) -> Rgb {
    value(material, params, &point(-Vec3A::Z))
}

#[test]
fn glossiness_converts_to_roughness() {
    // sqrt(2 · 2^(−4 − 14 g)): g = 0.5 gives sqrt(2^−10) = 1/32; a mirror at g = 1.
    for (g, r) in [(0.5f32, 1.0 / 32.0), (0.0, (2.0f32 * 2f32.powi(-4)).sqrt()), (1.0, 0.0)] {
        let got = constant("arch_rough", &format!(r#""g" {g}"#));
        assert!(close(got, Rgb::splat(r), 1e-7), "g {g}: {got:?}");
    }
    assert!(close(constant("gloss_rough", r#""g" 0.25"#), Rgb::splat(0.75), 1e-7));
}

#[test]
fn anisotropy_converts_to_two_roughnesses_and_a_turned_tangent() {
    let cases = [
        // v = u / (1 − anisotropy).
        (r#""anisotropy" 0.5"#, Rgb::new(0.5, 1.0, 0.0)),
        (r#""anisotropy" 1"#, Rgb::new(0.5, 5000.0, 0.0)),
        // mia: a ratio 4 splits by its square root 2, a ratio 1/16 by its fourth root.
        (r#""mia" on, "anisotropy" 4"#, Rgb::new(1.0, 0.25, 0.0)),
        (r#""mia" on, "anisotropy" 0.0625"#, Rgb::new(0.25, 1.0, 0.0)),
        // A quarter turn about +z takes +x to −(z × x) = −y; an eighth halfway.
        (r#""tangent" on, "rotation" 0.25"#, Rgb::new(0.0, -1.0, 0.0)),
        (r#""tangent" on, "rotation" 0.125"#, Rgb::new(0.5f32.sqrt(), -(0.5f32.sqrt()), 0.0)),
        (r#""tangent" on"#, Rgb::new(1.0, 0.0, 0.0)),
    ];
    for (params, want) in cases {
        let got = constant("aniso", params);
        assert!(close(got, want, 1e-4 * want.max_element().max(1.0)), "{params}: {got:?} vs {want:?}");
    }
}

#[test]
fn spectral_indices_follow_abbe_and_sellmeier() {
    // Abbe number 50, n_D 1.5: slope 0.5 / (50 · (486.1 − 656.3)) per nm from 589.2 nm.
    let slope = 0.5f32 / (50.0 * (486.1 - 656.3));
    let want = Rgb::new(1.5 + slope * 110.8, 1.5 + slope * (546.0 - 589.2), 1.5 + slope * (435.8 - 589.2));
    let got = constant("abbe", r#""v" 50"#);
    assert!(close(got, want, 1e-6), "{got:?} vs {want:?}");
    assert!(got.x < 1.5 && got.z > 1.5, "blue bends more");
    assert!(close(constant("abbe", r#""v" 0"#), Rgb::splat(1.5), 0.0));
    // Sellmeier at 0.7, 0.5461, 0.4358 µm with the defaults (their C₁ = 0.2 µm² puts a
    // resonance at 0.447 µm: blue's n² is negative and reads as 1).
    let (b, c) = ([1.04f64, 0.23, 1.01], [0.006f64, 0.2, 103.56]);
    let n = |l: f64| {
        let l2 = l * l;
        let n2 = 1.0 + (0..3).map(|i| b[i] * l2 / (l2 - c[i])).sum::<f64>();
        if n2 >= 0.0 {
            n2.sqrt() as f32
        } else {
            1.0
        }
    };
    let want = Rgb::new(n(0.7), n(0.5461), n(0.4358));
    let got = constant("sellmeier", "");
    assert!(close(got, want, 1e-5), "{got:?} vs {want:?}");
    assert!(got.z == 1.0 && (1.5..1.7).contains(&got.x), "{got:?}");
    // BK7's own C (0.0060, 0.0200, 103.56 µm²): 1.5131 red, 1.5187 green, 1.5266 blue
    // (Schott's catalogue values for BK7 at 706.5, 546.1 and 435.8 nm, near these).
    let got =
        constant("sellmeier", r#""b" 1.03961212 0.231792344 1.01046945, "c" 0.00600069867 0.0200179144 103.560653"#);
    assert!(close(got, Rgb::new(1.5131, 1.5187, 1.5267), 2e-4), "{got:?}");
    // n² < 0 at all three wavelengths (1 − 5 l²/(l² − 0.1) < −5) reads as 1.
    let got = constant("sellmeier", r#""b" 0 0 -5, "c" 0 0 0.1"#);
    assert!(close(got, Rgb::splat(1.0), 0.0), "{got:?}");
}

#[test]
fn a_volume_coefficient_leaves_its_tint_after_its_distance() {
    // exp(−σ d) = tint.
    let got = constant("coefficient", r#""tint" 0.5 0.25 1, "d" 2"#);
    let want = Rgb::new(0.5f32.ln() / -2.0, 0.25f32.ln() / -2.0, 0.0);
    assert!(close(got, want, 1e-6), "{got:?}");
    assert!(close(constant("coefficient", r#""d" 0"#), Rgb::ZERO, 0.0));
}

#[test]
fn blended_normals_compose_their_tilts() {
    let tilt = |deg: f32| {
        let r = deg.to_radians();
        format!("{} 0 {}", r.sin(), r.cos())
    };
    let s = point(-Vec3A::Z);
    // Two 30° tilts about y make one of 60°; either alone passes through unchanged.
    let cases = [
        (format!(r#""b" {}, "d" {}"#, tilt(30.0), tilt(30.0)), 60f32),
        (format!(r#""d" {}"#, tilt(30.0)), 30.0),
        (format!(r#""b" {}"#, tilt(-20.0)), -20.0),
        // The detail's weight 0: the base alone.
        (format!(r#""b" {}, "d" {}, "wd" 0"#, tilt(30.0), tilt(45.0)), 30.0),
    ];
    for (params, deg) in cases {
        let got = value("blended", &params, &s);
        let r = deg.to_radians();
        assert!(close(got, Rgb::new(r.sin(), 0.0, r.cos()), 1e-5), "{params}: {got:?}");
    }
}

#[test]
fn the_spherical_environment_is_seen_along_the_ray() {
    // quad.ppm: red, green on the top row (v > 0.5), blue, white below. Directions to
    // the texel centres: longitude π(2u − 1), latitude π/2 (2v − 1).
    let h = 0.5f32.sqrt();
    for (dir, want) in [
        (Vec3A::new(0.0, h, -h), Rgb::new(1.0, 0.0, 0.0)),
        (Vec3A::new(0.0, h, h), Rgb::new(0.0, 1.0, 0.0)),
        (Vec3A::new(0.0, -h, -h), Rgb::new(0.0, 0.0, 1.0)),
        (Vec3A::new(0.0, -h, h), Rgb::ONE),
    ] {
        let got = value("sky", "", &point(dir));
        assert!(close(got, want, 1e-4), "{dir:?}: {got:?}");
    }
}

/// Tile-by-tile variation of `tile_texture`: at each of the 16 tile centres the tint is
/// the tile colour times 1 + the tile's variation (mira's pattern,
/// `material::mdl_modules::tiles`), clamped to [0, 1], or the grout's where the tile is
/// missing; mono 1 on a tile, 0 on a missing one; the variation differs between tiles.
#[test]
fn tiles_vary_tile_by_tile() {
    use material::mdl_modules::tiles::Tiling;
    let tiling = |missing: f32, variation: f32| Tiling {
        rows: 4.0,
        columns: 4.0,
        grout_width: 0.02,
        grout_height: 0.02,
        grout_roughness: 0.0,
        missing_tile_amount: missing,
        brightness_variation: variation,
        seed: 2.284,
        special_row_index: 1,
        special_row_width_factor: 1.0,
        special_column_index: 1,
        special_column_height_factor: 1.0,
        odd_row_offset: 0.5,
        random_row_offset: 0.0,
    };
    let tile = Rgb::new(0.6, 0.4, 0.2);
    let at = |u: f32, v: f32| {
        let mut s = point(-Vec3A::Z);
        s.tex_count = 1;
        s.tex_list[0] = Vec3A::new(u, v, 0.0);
        s
    };
    let centres: Vec<(f32, f32)> = (0..16)
        .map(|k| {
            let (r, c) = (k / 4, k % 4);
            let shift = if r % 2 == 1 { 0.5 } else { 0.0 };
            ((c as f32 + 0.5 - shift).rem_euclid(4.0) / 4.0, (r as f32 + 0.5) / 4.0)
        })
        .collect();
    let mut seen = Vec::new();
    for &(u, v) in &centres {
        let got = value("tiled", "", &at(u, v));
        let var = tiling(0.0, 0.5).sample(u, v).variation;
        let want = (tile * (1.0 + var)).clamp(Rgb::ZERO, Rgb::ONE);
        assert!(close(got, want, 1e-6), "({u}, {v}): {got:?} vs {want:?}");
        assert!(var.abs() <= 0.5);
        seen.push(var);
    }
    assert!(seen.iter().any(|v| (v - seen[0]).abs() > 0.01), "{seen:?}");
    // Half the tiles missing: the grout's blue and mono 0 there, the tile colour and 1 else.
    let mut missing = 0;
    for &(u, v) in &centres {
        let gone = !tiling(0.5, 0.0).sample(u, v).in_tile;
        missing += usize::from(gone);
        let want = if gone { Rgb::new(0.0, 0.0, 1.0) } else { tile };
        assert!(close(value("tiled", r#""missing" 0.5, "variation" 0"#, &at(u, v)), want, 1e-6));
        let mono = value("tiled_mono", r#""missing" 0.5"#, &at(u, v));
        assert!(close(mono, Rgb::splat(if gone { 0.0 } else { 1.0 }), 0.0), "{mono:?}");
    }
    assert!((1..16).contains(&missing), "{missing} of 16 missing");
    // All missing: grout everywhere.
    assert!(close(value("tiled", r#""missing" 1"#, &at(0.125, 0.125)), Rgb::new(0.0, 0.0, 1.0), 0.0));
}

/// `gradient3_bump_texture` of the default linear gradient (grey = u): the normal leans
/// towards +u as n + scale · tangent_u (the height's slope is 1), flat across v.
#[test]
fn a_gradient_bump_leans_along_its_slope() {
    let (mdl, lib, diags) = compile_text(r#"shader "m" "mdl::base_conversions::gradient_bumped" ("scale" 0.5)"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let m = get(&mdl, &lib, "m");
    let Varying::Evaluated(e) = &m.varying else { panic!("not per hit") };
    for (u, v) in [(0.3f32, 0.4f32), (0.7, 0.1)] {
        let mut s = point(-Vec3A::Z);
        s.tex_count = 1;
        s.tex_list[0] = Vec3A::new(u, v, 0.0);
        let mut h = m.constant();
        e.0.apply(&s, &mut h);
        let n = h.normal.expect("a bent normal");
        let want = Vec3A::new(0.5, 0.0, 1.0).normalize();
        assert!((n - want).length() < 1e-3, "({u}, {v}): {n:?}");
    }
}

/// `blackbody_emission` (`math::blackbody`): luminance 1; at 2856 K the chromaticity of
/// CIE illuminant A (x 0.44757, y 0.40745, a Planckian radiator by definition); the blend
/// picks between the two temperatures; temperatures below 500 K read as 500 K.
#[test]
fn a_black_body_has_unit_luminance_and_the_planckian_chromaticity() {
    // Linear Rec. 709 → XYZ (D65), the standard matrix.
    let xyz = |c: Rgb| {
        Vec3A::new(
            0.4124 * c.x + 0.3576 * c.y + 0.1805 * c.z,
            0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z,
            0.0193 * c.x + 0.1192 * c.y + 0.9505 * c.z,
        )
    };
    let a = constant("black_body", "");
    let v = xyz(a);
    assert!((v.y - 1.0).abs() < 1e-3, "Y {}", v.y);
    let sum = v.x + v.y + v.z;
    assert!((v.x / sum - 0.44757).abs() < 2e-3 && (v.y / sum - 0.40745).abs() < 2e-3, "{a:?}: xy {v:?}");
    assert!(a.x > a.y && a.y > a.z, "warm: {a:?}");
    // Blended all the way: the second temperature, bluer.
    let b = constant("black_body", r#""blend" 1"#);
    assert!(close(b, constant("black_body", r#""t1" 6500"#), 1e-6), "{b:?}");
    assert!(b.z / b.x > a.z / a.x);
    assert!(close(constant("black_body", r#""t1" 100"#), constant("black_body", r#""t1" 500"#), 0.0));
}
