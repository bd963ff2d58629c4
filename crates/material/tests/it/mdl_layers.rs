//! Direction-dependent layers in module materials (tests/mdl/layers.mdl): `custom_curve_layer`
//! and its colour form, `fresnel_layer` over a non-diffuse base, `thin_film`,
//! `directional_factor`, `backscattering_glossy_reflection_bsdf` and `sheen_bsdf`'s
//! energy-compensated base compile from MDL text to lobe sums with curves; each passes the
//! standard BSDF checks (reciprocity, albedo bound, chi-square), and those with a white
//! Lambertian base a white furnace within 1 %.

use crate::mdl_support;

use bsdf::testing::{albedo, incidences, standard_checks};
use bsdf::{CurveKind, Lobe, Lobes, Rgb};
use glam::Vec3A;
use material::{SurfaceMaterial, SurfaceModel};
use mdl_support::{compile_text, get};

const SHADERS: &str = r#"shader "coat" "mdl::layers::clear_coat" ()
shader "black_coat" "mdl::layers::clear_coat" ("base_tint" 0 0 0)
shader "curve" "mdl::layers::color_curve" ()
shader "fg" "mdl::layers::fresnel_over_glossy" ()
shader "film" "mdl::layers::film" ()
shader "film0" "mdl::layers::film" ("thickness" 0)
shader "tinted" "mdl::layers::tinted_factor" ()
shader "retro" "mdl::layers::retro" ()
shader "velvet" "mdl::layers::white_velvet" ()
shader "velvet_smooth" "mdl::layers::white_velvet" ("roughness" 0.2)
shader "tinted_coat" "mdl::layers::tinted_coat" ()"#;

fn lobes(m: &SurfaceMaterial) -> Lobes {
    let SurfaceModel::MdlLobes(l) = &m.model else { panic!("{}: {:?}", m.name, m.model) };
    **l
}

fn lossless(m: &SurfaceMaterial) {
    for wo in incidences() {
        let a = albedo(&m.bsdf(wo), wo, 50_000);
        assert!((a - Rgb::ONE).abs().max_element() <= 0.01, "{}: albedo {a:?} at {wo:?}", m.name);
    }
}

#[test]
fn direction_dependent_layers_compile_to_lobe_sums_that_pass_the_standard_checks() {
    let (mdl, lib, diags) = compile_text(SHADERS);
    assert!(diags.is_empty(), "{diags:#?}");
    for name in ["coat", "curve", "fg", "film", "tinted", "retro", "velvet", "velvet_smooth", "tinted_coat"] {
        let m = get(&mdl, &lib, name);
        let l = lobes(m);
        standard_checks(&m.bsdf(Vec3A::Z), 1.01, name);
        assert!(l.count >= 1, "{name}");
    }
    // A tinted Fresnel coat keeps its tint (no warning; the blue channel reflects most).
    let tc = lobes(get(&mdl, &lib, "tinted_coat"));
    assert_eq!(tc.part(0).0, Rgb::new(0.2, 0.4, 0.8));
    assert_eq!(tc.curves[0].kind, CurveKind::Fresnel { ior: 1.5 });
    // The clear coat is a mirror under Schlick's curve over a Lambertian base.
    let coat = lobes(get(&mdl, &lib, "coat"));
    assert_eq!(coat.parts().map(|p| p.1).collect::<Vec<_>>(), vec![Lobe::Mirror, Lobe::Diffuse(0.0)]);
    assert_eq!(coat.curves[0].kind, CurveKind::Schlick { normal: Rgb::splat(0.04), grazing: Rgb::ONE, exponent: 5.0 });
    // Over a black base only the coat reflects: exactly R(cos θo) = 0.04 + 0.96 (1 − cos θo)^5.
    let black = get(&mdl, &lib, "black_coat");
    for wo in incidences() {
        let a = albedo(&black.bsdf(wo), wo, 1000).x;
        let r = 0.04 + 0.96 * (1.0 - wo.z).powi(5);
        assert!((a - r).abs() < 1e-5, "{a} vs {r} at {wo:?}");
    }
    // The backscattering lobe: half of 0.8, the base half of 0.5.
    let retro = lobes(get(&mdl, &lib, "retro"));
    assert_eq!(retro.part(0).0, Rgb::splat(0.4));
    assert!(matches!(retro.part(0).1, Lobe::Backscatter(_)));
    // The directional factor is orange head-on, white at grazing: its curve at the half vector.
    let tinted = get(&mdl, &lib, "tinted");
    let b = tinted.bsdf(Vec3A::Z);
    let f = b.eval(Vec3A::Z, Vec3A::Z);
    assert!((f.y / f.x - 0.5).abs() < 1e-4 && (f.z / f.x - 0.2).abs() < 1e-4, "{f:?}");
}

#[test]
fn white_bases_under_curves_films_and_sheen_pass_the_white_furnace() {
    let (mdl, lib, diags) = compile_text(SHADERS);
    assert!(diags.is_empty(), "{diags:#?}");
    for name in ["coat", "film", "film0", "velvet", "velvet_smooth"] {
        lossless(get(&mdl, &lib, name));
    }
    // The film colours the coat; with no thickness it is the bare Fresnel layer.
    let film = lobes(get(&mdl, &lib, "film"));
    let r = film.curves[0].kind.eval(1.0);
    assert!(r.max_element() - r.min_element() > 0.01, "{r:?}");
    let bare = lobes(get(&mdl, &lib, "film0")).curves[0].kind;
    for c in [1.0, 0.7, 0.3] {
        let (a, b) = (bare.eval(c), CurveKind::Fresnel { ior: 1.5 }.eval(c));
        assert!((a - b).abs().max_element() < 1e-5, "{a:?} vs {b:?}");
    }
}

/// A film changes the Fresnel terms under it: on `color_fresnel_layer`, through a `tint`
/// and on a `custom_curve_layer` of normal reflectivity 0.04 (read as the Fresnel layer of
/// index 1.5) it gives the same Airy curve as on `fresnel_layer` of index 1.5 (1e-5 at
/// five angles), each over a white base lossless (1 %); a film over a diffuse lobe (no
/// Fresnel term) leaves it a Lambertian lobe of its tint, without a warning.
#[test]
fn a_film_applies_to_every_fresnel_form_and_leaves_the_rest_unchanged() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "film" "mdl::layers::film" ()
shader "color_fresnel" "mdl::layers::film_color_fresnel" ()
shader "through_tint" "mdl::layers::film_through_tint" ()
shader "on_curve" "mdl::layers::film_on_curve" ()
shader "on_diffuse" "mdl::layers::film_on_diffuse" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let reference = lobes(get(&mdl, &lib, "film")).curves[0].kind;
    for name in ["color_fresnel", "through_tint", "on_curve"] {
        let m = get(&mdl, &lib, name);
        let l = lobes(m);
        assert_eq!(l.curve_count, 1, "{name}");
        assert!(matches!(l.curves[0].kind, CurveKind::ThinFilm { .. }), "{name}: {:?}", l.curves[0].kind);
        for c in [1.0, 0.8, 0.5, 0.3, 0.1] {
            let (a, b) = (l.curves[0].kind.eval(c), reference.eval(c));
            assert!((a - b).abs().max_element() < 1e-5, "{name} at cos {c}: {a:?} vs {b:?}");
        }
        lossless(m);
        standard_checks(&m.bsdf(Vec3A::Z), 1.01, name);
    }
    let m = get(&mdl, &lib, "on_diffuse");
    assert_eq!(m.model, SurfaceModel::Lambert);
    assert!((m.diffuse - Rgb::splat(0.6)).abs().max_element() < 1e-6);
}

/// `spot_edf` (exponent e, spread π) emits 10 · (e + 2)/2π · cosᵉθ W·m⁻²·sr⁻¹ at θ from
/// the normal (the cosine lobe normalized to the intensity), within 1e-3 relative; a
/// narrow spread cuts it at spread/2 and rescales the angle; exponent 0 over the
/// hemisphere is `diffuse_edf`'s 10/π; a global frame points it along the frame's z axis.
#[test]
fn spot_emission_follows_the_spot_law() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "s4" "mdl::layers::spot" ()
shader "s0" "mdl::layers::spot" ("exponent" 0)
shader "narrow" "mdl::layers::spot" ("exponent" 1, "spread" 1.0)
shader "g" "mdl::layers::global_spot" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let dir = |t: f32| Vec3A::new(t.sin(), 0.0, t.cos());
    let radiance = |m: &SurfaceMaterial, n: Vec3A, d: Vec3A| {
        m.emission.x * m.emission_shape.as_ref().unwrap().factor(n, None, d).x
    };
    let s4 = get(&mdl, &lib, "s4");
    for t in [0.0f32, 0.3, 0.7, 1.2, 1.5] {
        let expected = 10.0 * 6.0 / std::f32::consts::TAU * t.cos().powi(4);
        let l = radiance(s4, Vec3A::Z, dir(t));
        assert!((l - expected).abs() <= 1e-3 * expected.max(1e-3), "θ {t}: {l} vs {expected}");
    }
    assert_eq!(radiance(s4, Vec3A::Z, -Vec3A::Z), 0.0);
    let s0 = get(&mdl, &lib, "s0");
    let l = radiance(s0, Vec3A::Z, dir(1.0));
    assert!((l - 10.0 / std::f32::consts::PI).abs() < 1e-3 * l, "{l}");
    // Narrow: cos(θ π / 1) inside θ < 0.5; N from an independent Simpson rule of
    // 2π ∫ cos(θπ) cos θ sin θ dθ over [0, 0.5].
    let narrow = get(&mdl, &lib, "narrow");
    let n = 1000;
    let f = |t: f64| (t * std::f64::consts::PI).cos() * t.cos() * t.sin();
    let h = 0.5 / n as f64;
    let simpson: f64 = (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * f(i as f64 * h)
        })
        .sum::<f64>()
        * h
        / 3.0;
    let norm = 1.0 / (std::f64::consts::TAU * simpson);
    for t in [0.0f32, 0.2, 0.45] {
        let expected = 10.0 * norm as f32 * (t * std::f32::consts::PI).cos();
        let l = radiance(narrow, Vec3A::Z, dir(t));
        assert!((l - expected).abs() <= 1e-3 * expected, "narrow θ {t}: {l} vs {expected}");
    }
    assert_eq!(radiance(narrow, Vec3A::Z, dir(0.55)), 0.0);
    // Global: along −y, whatever the normal (as long as the direction leaves the front).
    let g = get(&mdl, &lib, "g");
    let n = Vec3A::new(0.0, -1.0, 1.0).normalize();
    let on_axis = radiance(g, n, -Vec3A::Y);
    assert!((on_axis - 10.0 * 4.0 / std::f32::consts::TAU).abs() < 1e-3 * on_axis, "{on_axis}");
    assert!(radiance(g, n, Vec3A::Z) < 1e-6 * on_axis);
}
