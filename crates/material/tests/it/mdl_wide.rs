//! Lobe sums wider than the compact `bsdf::Lobes` (tests/mdl/wide.mdl): a mix of three
//! layered parts — six lobes, three layer curves, three layer normals — compiles to a wide
//! sum whose value is exactly the weighted sum of its parts' values (each part compiled
//! alone to a compact sum), passes the white furnace (≤ 1) and samples its own density.

use crate::mdl_support;

use bsdf::testing::{albedo, chi_square, incidences, r2};
use bsdf::{Frame, Rgb};
use glam::Vec3A;
use material::{SurfaceMaterial, SurfaceModel};
use mdl_support::{compile_text, get};

/// The BSDF of `m` at a hit of shading normal `n` (world space), in the frame around it.
fn bsdf_at(m: &SurfaceMaterial, n: Vec3A) -> bsdf::Bsdf {
    m.model.bsdf_in(m.diffuse, Vec3A::Z, &Frame::from_normal(n))
}

/// A direction from two uniform numbers over the whole sphere.
fn sphere(u: glam::Vec2) -> Vec3A {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * u.y;
    Vec3A::new(r * phi.cos(), r * phi.sin(), z)
}

const SHADERS: &str = r#"shader "wide" "mdl::wide::wide" ()
shader "tinted" "mdl::wide::wide" ("tint" 0.9 0.5 0.2, "a" 0.5, "b" 0.2, "c" 0.3)
shader "coated" "mdl::wide::part_coated" ()
shader "curved" "mdl::wide::part_curved" ()
shader "translucent" "mdl::wide::part_translucent" ()
shader "coated_t" "mdl::wide::part_coated" ("tint" 0.9 0.5 0.2)
shader "curved_t" "mdl::wide::part_curved" ("tint" 0.9 0.5 0.2)
shader "translucent_t" "mdl::wide::part_translucent" ("tint" 0.9 0.5 0.2)"#;

#[test]
fn a_six_lobe_three_curve_three_normal_mix_is_a_wide_sum_of_its_parts() {
    let (mdl, lib, diags) = compile_text(SHADERS);
    assert!(diags.is_empty(), "{diags:#?}");
    let wide = get(&mdl, &lib, "wide");
    let SurfaceModel::MdlWide(sum) = &wide.model else { panic!("wide: {:?}", wide.model) };
    assert_eq!((sum.len(), sum.curve_count, sum.normal_count), (6, 3, 3));
    for part in ["coated", "curved", "translucent"] {
        let m = get(&mdl, &lib, part);
        assert!(matches!(m.model, SurfaceModel::MdlLobes(_)), "{part}: {:?}", m.model);
    }
    // f(ωo, ωi) of the mix = Σ wₖ fₖ over 2000 direction pairs on the whole sphere, at
    // two hits (the layer normals are world-space constants, placed in each hit's frame):
    // 1e-5 relative (plus 1e-6 absolute) — the same arithmetic, in another order.
    for (mix, parts, weights) in [
        ("wide", ["coated", "curved", "translucent"], [0.3, 0.3, 0.4]),
        ("tinted", ["coated_t", "curved_t", "translucent_t"], [0.5, 0.2, 0.3]),
    ] {
        for n in [Vec3A::Z, Vec3A::new(0.3, -0.2, 1.0).normalize()] {
            let b = bsdf_at(get(&mdl, &lib, mix), n);
            let p = parts.map(|name| bsdf_at(get(&mdl, &lib, name), n));
            let mut compared = 0;
            for i in 0..2000u32 {
                let (wo, wi) = (sphere(r2(2 * i)), sphere(r2(2 * i + 1)));
                let got = b.eval(wo, wi);
                let want = (0..3).fold(Rgb::ZERO, |s, k| s + p[k].eval(wo, wi) * weights[k]);
                let tol = 1e-5 * want.abs().max_element() + 1e-6;
                assert!((got - want).abs().max_element() <= tol, "{mix} at {n}: {got} vs {want} ({wo}, {wi})");
                compared += usize::from(want.max_element() > 0.0);
            }
            assert!(compared > 500, "{mix}: only {compared} pairs scatter");
        }
    }
}

/// White furnace (50 000 samples at three incidences): at most 1 (+0.5 % Monte Carlo),
/// more than half kept; chi-square of the sampled directions against the density.
#[test]
fn a_wide_sum_passes_the_white_furnace_and_samples_its_density() {
    let (mdl, lib, diags) = compile_text(SHADERS);
    assert!(diags.is_empty(), "{diags:#?}");
    let b = bsdf_at(get(&mdl, &lib, "wide"), Vec3A::Z);
    for wo in incidences() {
        let a = albedo(&b, wo, 50_000);
        assert!(a.max_element() <= 1.005 && a.min_element() > 0.5, "albedo {a:?} at {wo}");
        chi_square(&b, wo);
    }
}
