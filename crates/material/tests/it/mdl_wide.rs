//! Lobe sums wider than the compact `bsdf::Lobes` (tests/mdl/wide.mdl): a mix of three
//! layered parts — six lobes, three layer curves, three layer normals — compiles to a wide
//! sum whose value is exactly the weighted sum of its parts' values (each part compiled
//! alone to a compact sum), passes the white furnace (≤ 1) and samples its own density.

use crate::mdl_support;

use bsdf::testing::{albedo, chi_square, incidences, r2};
use bsdf::{Frame, Rgb};
use glam::Vec3A;
use material::{SurfaceMaterial, SurfaceModel, Varying};
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

/// A hit at texture coordinate (u, ½) of shading normal `n`.
fn hit_at(u: f32, n: Vec3A) -> shader::State {
    let mut s = shader::State { tex_count: 1, normal: n, normal_geom: n, dir: -n, ..shader::State::default() };
    s.tex_list[0] = Vec3A::new(u, 0.5, 0.0);
    s
}

/// The BSDF of `m` lowered at hit `s` (its per-hit parts evaluated there).
fn bsdf_at_hit(m: &SurfaceMaterial, s: &shader::State) -> bsdf::Bsdf {
    let Varying::Evaluated(hit) = &m.varying else { panic!("{} does not vary: {:?}", m.name, m.varying) };
    let mut h = m.constant();
    hit.0.apply(s, &mut h);
    h.model.bsdf_in(h.diffuse, -s.dir, &Frame::from_normal(s.normal))
}

/// A wide mix whose first weight is the texture's u is lowered at each hit into the
/// thread's ring of wide sums (`material::wide_slots`, no allocation per hit): at u = 0.5
/// and 0.2 its BSDF is the constant mix with that weight, value for value (bit for bit),
/// also after the ring came round (18 hits in between).
#[test]
fn a_wide_mix_that_varies_per_hit_is_the_constant_mix_at_each_point() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "varying" "mdl::wide::wide_varying" ()
shader "w05" "mdl::wide::wide" ("a" 0.5)
shader "w02" "mdl::wide::wide" ("a" 0.2)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let varying = get(&mdl, &lib, "varying");
    let Varying::Evaluated(hit) = &varying.varying else { panic!("{:?}", varying.varying) };
    let mut h = varying.constant();
    hit.0.apply(&hit_at(0.5, Vec3A::Z), &mut h);
    assert!(matches!(*h.model, SurfaceModel::MdlWideAt(_)), "{:?}", h.model);
    let n = Vec3A::new(0.3, -0.2, 1.0).normalize();
    for round in 0..3 {
        for (u, name) in [(0.5, "w05"), (0.2, "w02")] {
            let b = bsdf_at_hit(varying, &hit_at(u, n));
            let c = bsdf_at(get(&mdl, &lib, name), n);
            for i in 0..500u32 {
                let (wo, wi) = (sphere(r2(2 * i)), sphere(r2(2 * i + 1)));
                assert_eq!(b.eval(wo, wi), c.eval(wo, wi), "round {round}, u = {u}");
                assert_eq!(b.pdf(wo, wi), c.pdf(wo, wi), "round {round}, u = {u}");
            }
        }
        // Other hits in between: the ring comes round to the same slots.
        for k in 0..18 {
            drop(bsdf_at_hit(varying, &hit_at(k as f32 / 18.0, n)));
        }
    }
}

/// Heap allocations per hit of the varying wide mix, for valgrind: `MIRA_WIDE_HITS` hits
/// (default 1000), each lowered and its BSDF evaluated once. Run the test binary as
/// `MIRA_WIDE_HITS=1000 valgrind --tool=memcheck target/debug/deps/it-<hash> --ignored
/// --exact mdl_wide::hits_of_a_varying_wide_mix --test-threads=1` and again with 11000:
/// the difference in "total heap usage" over 10,000 is the allocations per hit.
#[test]
#[ignore]
fn hits_of_a_varying_wide_mix() {
    let hits: u32 = std::env::var("MIRA_WIDE_HITS").ok().and_then(|v| v.parse().ok()).unwrap_or(1000);
    let (mdl, lib, diags) = compile_text(r#"shader "varying" "mdl::wide::wide_varying" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let varying = get(&mdl, &lib, "varying");
    let mut sum = Rgb::ZERO;
    for k in 0..hits {
        let b = bsdf_at_hit(varying, &hit_at(k as f32 / hits as f32, Vec3A::Z));
        sum += b.eval(Vec3A::new(0.0, 0.6, 0.8), Vec3A::new(0.6, 0.0, 0.8));
    }
    assert!(sum.max_element() > 0.0);
}
