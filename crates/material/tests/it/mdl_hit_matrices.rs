//! Matrices that vary over the surface in module materials (tests/mdl/hit_matrices.mdl):
//! a constant matrix with a scalar of the hit, the surface's frame as a matrix of the hit,
//! matrices, vectors and arrays indexed by integers of the hit, a matrix carried through a
//! loop of the hit and assigned at its counter, a `float4x4` carried through one and read
//! whole after it, and matrix parameters set from the `.mi`
//! file (a wrong shape an error at its `.mi` line), each at several hits against glam's
//! products of the same numbers (within 1e-5).

use crate::mdl_support;

use bsdf::Rgb;
use glam::{Mat2, Mat3, Mat4, Vec2, Vec3, Vec3A, Vec4};
use material::{SurfaceMaterial, Varying};
use mdl_support::{close, compile_text, get};
use shader::State;

/// The module's `M` (column-major, as MDL's constructor takes it).
fn m() -> Mat3 {
    Mat3::from_cols_array(&[1.0, 0.5, -0.25, 2.0, -1.0, 0.75, 0.5, 0.25, 1.5])
}

/// A hit at texture coordinate (u, v) and position `p`, normal `n`, texture derivatives
/// `du`, `dv`, looking along `d`.
fn hit(u: f32, v: f32, p: Vec3, n: Vec3, d: Vec3) -> State {
    let mut s = State {
        point: p.into(),
        normal: n.normalize().into(),
        normal_geom: n.normalize().into(),
        dir: d.normalize().into(),
        derivs: [Vec3A::new(1.0, 0.25, -0.5), Vec3A::new(-0.2, 1.0, 0.3)],
        tex_count: 1,
        ..State::default()
    };
    s.tex_list[0] = Vec3A::new(u, v, 0.0);
    s
}

/// The hits the tests use.
fn hits() -> Vec<State> {
    let d = Vec3::new(0.3, -0.4, -1.0);
    vec![
        hit(0.2, 0.9, Vec3::new(0.5, -1.5, 2.0), Vec3::new(0.2, 0.3, 1.0), d),
        hit(0.45, 0.1, Vec3::new(-2.0, 0.25, 1.0), Vec3::new(-0.5, 0.1, 0.8), d),
        hit(0.8, 0.5, Vec3::new(1.25, 3.0, -0.75), Vec3::new(0.0, -1.0, 0.4), -d),
    ]
}

/// The radiance the material emits at `state` (it must vary per hit).
fn emitted(m: &SurfaceMaterial, state: &State) -> Rgb {
    let Varying::Evaluated(e) = &m.varying else { panic!("{} is not evaluated per hit: {:?}", m.name, m.varying) };
    let mut h = m.constant();
    e.0.apply(state, &mut h);
    h.emission
}

/// Checks `shader` (a `.mi` shader line naming a `hit_matrices` material) against `want`
/// at every hit, within 1e-5 relative.
fn check(shader: &str, want: impl Fn(&State) -> Vec3) {
    let (mdl, lib, diags) = compile_text(shader);
    assert!(diags.is_empty(), "{shader}: {diags:#?}");
    let m = get(&mdl, &lib, "m");
    for s in hits() {
        let (got, w) = (emitted(m, &s), want(&s));
        let tol = 1e-5 * w.abs().max_element().max(1.0);
        assert!(close(got, Rgb::new(w.x, w.y, w.z), tol), "{shader} at {:?}: {got:?} vs {w}", s.tex_list[0]);
    }
}

/// A matrix of M and u, as the test computes it.
type Scaled = fn(Mat3, f32) -> Mat3;

/// The value a material shows at a hit, as the test computes it.
type Expected<'a> = Box<dyn Fn(&State) -> Vec3 + 'a>;

fn u_of(s: &State) -> f32 {
    s.tex_list[0].x
}

#[test]
fn a_constant_matrix_meets_a_scalar_of_the_hit_element_by_element() {
    fn ones() -> Mat3 {
        Mat3::from_cols_array(&[1.0; 9])
    }
    let cases: [(i32, Scaled); 9] = [
        (0, |m, u| m + ones() * u),
        (1, |m, u| m - ones() * u),
        (2, |m, u| ones() * u - m),
        (3, |m, u| m * u),
        (4, |m, u| m * u),
        (5, |m, u| m / u),
        (6, |m, u| Mat3::from_cols_array(&m.to_cols_array().map(|x| u / x))),
        (7, |m, u| -(m * u)),
        (8, |m, u| (m * u) * m),
    ];
    for (which, f) in cases {
        for k in 0..3 {
            check(&format!(r#"shader "m" "mdl::hit_matrices::with_scalar" ("which" {which}, "k" {k})"#), |s| {
                f(m(), u_of(s)).col(k)
            });
        }
    }
}

#[test]
fn matrices_vectors_and_arrays_are_indexed_by_integers_of_the_hit() {
    let ij = |s: &State| ((s.tex_list[0].x * 3.0) as usize, (s.tex_list[0].y * 3.0) as usize);
    let f = |s: &State| {
        let p = Vec3::from(s.point);
        Mat3::from_cols(p, p * 2.0, Vec3::from(s.normal))
    };
    let show = |x: f32| Vec3::new(x, 0.0, 0.0);
    let a = [Vec3::new(1.0, 2.0, 3.0), Vec3::new(-4.0, 5.0, -6.0), Vec3::new(7.0, -8.0, 9.0)];
    let cases: Vec<(i32, Expected)> = vec![
        (0, Box::new(|s| m().col(ij(s).0))),
        (1, Box::new(|s| Vec3::new(m().col(ij(s).0)[ij(s).1], m().col(ij(s).1).y, 0.0))),
        (2, Box::new(|s| f(s).col(ij(s).0))),
        (3, Box::new(|s| show(f(s).col(ij(s).0)[ij(s).1]))),
        (4, Box::new(|s| show([0.5, -1.5, 2.5][ij(s).0]))),
        (5, Box::new(|s| show(s.point[ij(s).0]))),
        (6, Box::new(|s| a[ij(s).0])),
    ];
    for (which, want) in cases {
        check(&format!(r#"shader "m" "mdl::hit_matrices::indexed" ("which" {which})"#), want);
    }
}

#[test]
fn the_surface_frame_is_a_matrix_of_the_hit() {
    let frame = |s: &State| {
        let (tu, tv) = mdl::texture::surface_tangents(s);
        Mat3::from_cols(tu.into(), tv.into(), Vec3::from(s.normal))
    };
    let d = |s: &State| Vec3::from(s.dir);
    check(r#"shader "m" "mdl::hit_matrices::frame" ("which" 0)"#, |s| frame(s) * Vec3::new(1.0, 2.0, 3.0));
    check(r#"shader "m" "mdl::hit_matrices::frame" ("which" 1)"#, |s| frame(s).transpose() * d(s));
    check(r#"shader "m" "mdl::hit_matrices::frame" ("which" 2)"#, |s| frame(s).transpose() * d(s));
    for k in 0..3 {
        check(&format!(r#"shader "m" "mdl::hit_matrices::frame" ("which" 3, "k" {k})"#), |s| {
            (frame(s) * frame(s).transpose()).col(k)
        });
    }
    // The frame is orthonormal: F · Fᵀ is the identity.
    let s = &hits()[0];
    assert!((frame(s) * frame(s).transpose()).abs_diff_eq(Mat3::IDENTITY, 1e-5));
}

#[test]
fn matrices_are_carried_through_loops_of_the_hit() {
    let n = |s: &State, by: f32| (u_of(s) * by) as i32;
    // The turn applied floor(10 u) times.
    check(r#"shader "m" "mdl::hit_matrices::looped" ("which" 0)"#, |s| {
        let a = 0.25 * n(s, 10.0) as f32;
        Vec3::new(a.cos(), a.sin(), 0.0)
    });
    // The columns below floor(4 u).
    check(r#"shader "m" "mdl::hit_matrices::looped" ("which" 1)"#, |s| {
        (0..n(s, 4.0)).map(|i| m().col(i as usize)).sum()
    });
    // Columns i + 1 assigned at the counter: n(n+1)/2; elements i²: Σ i².
    check(r#"shader "m" "mdl::hit_matrices::looped" ("which" 2)"#, |s| {
        let n = n(s, 4.0);
        Vec3::splat((n * (n + 1) / 2) as f32)
    });
    check(r#"shader "m" "mdl::hit_matrices::looped" ("which" 4)"#, |s| {
        Vec3::splat((0..n(s, 4.0)).map(|i| i * i).sum::<i32>() as f32)
    });
    // A matrix chosen by an `if` of the hit, one branch assigning a column of the hit.
    check(r#"shader "m" "mdl::hit_matrices::looped" ("which" 3)"#, |s| {
        let u = u_of(s);
        let chosen = if u > 0.5 { m() * 2.0 } else { Mat3::from_cols(m().x_axis, Vec3::splat(u), m().z_axis) };
        chosen * Vec3::ONE
    });
}

/// A `float4x4` carried through one loop of the hit and read whole after it (all four
/// columns: before loops ran once per evaluation, each read re-ran the loop and the
/// module was refused as too costly, 4 × 16 385 steps and more), against the closed form
/// N · Tⁿ: Tⁿ turns by 0.25 n about z and steps n along z. The loop runs once per hit.
#[test]
fn a_float4x4_carried_through_a_loop_is_read_whole() {
    let n_mat = Mat4::from_cols_array(&[
        1.0, 0.5, -0.25, 0.125, 2.0, -1.0, 0.75, 0.5, 0.5, 0.25, 1.5, -0.5, -1.0, 0.3, 0.2, 1.0,
    ]);
    let m = |s: &State| {
        let n = (u_of(s) * 10.0) as i32 as f32;
        let (sin, cos) = (0.25 * n).sin_cos();
        let t = Mat4::from_cols(
            Vec4::new(cos, sin, 0.0, 0.0),
            Vec4::new(-sin, cos, 0.0, 0.0),
            Vec4::Z,
            Vec4::new(0.0, 0.0, n, 1.0),
        );
        n_mat * t
    };
    let w = Vec4::new(1.0, 2.0, 3.0, 4.0);
    check(r#"shader "m" "mdl::hit_matrices::carried4" ("which" 0)"#, |s| (m(s) * w).truncate());
    check(r#"shader "m" "mdl::hit_matrices::carried4" ("which" 1)"#, |s| (m(s).transpose() * w).truncate());
    check(r#"shader "m" "mdl::hit_matrices::carried4" ("which" 2)"#, |s| {
        Vec3::new((m(s) * w).w, (m(s).transpose() * w).w, 0.0)
    });
    let (mdl, lib, _) = compile_text(r#"shader "m" "mdl::hit_matrices::carried4" ("which" 0)"#);
    let material = get(&mdl, &lib, "m");
    for s in hits() {
        let before = material::mdl_modules::hit_loop::loops_run();
        emitted(material, &s);
        assert_eq!(material::mdl_modules::hit_loop::loops_run() - before, 1, "at {:?}", s.tex_list[0]);
    }
}

#[test]
fn matrix_parameters_are_set_from_the_mi_file_column_after_column() {
    let nine: Vec<f32> = (1..=9).map(|x| x as f32 * 0.5 - 2.0).collect();
    let sixteen: Vec<f32> = (1..=16).map(|x| (x as f32 * 0.75).sin()).collect();
    let text = |v: &[f32]| v.iter().map(|x| format!("{x}")).collect::<Vec<_>>().join(" ");
    let m3 = Mat3::from_cols_slice(&nine);
    let m4 = Mat4::from_cols_slice(&sixteen);
    let mi = |which: i32| {
        format!(
            r#"shader "m" "mdl::hit_matrices::placed" ("m" {}, "t" {}, "which" {which})"#,
            text(&nine),
            text(&sixteen)
        )
    };
    // Constant where nothing varies.
    for (which, want) in [(0, m3 * Vec3::new(1.0, 2.0, 3.0)), (1, (m4 * Vec4::new(1.0, 2.0, 3.0, 1.0)).truncate())] {
        let (mdl, lib, diags) = compile_text(&mi(which));
        assert!(diags.is_empty(), "{diags:#?}");
        let mat = get(&mdl, &lib, "m");
        assert!(matches!(mat.varying, Varying::Constant), "which {which}: {:?}", mat.varying);
        let got = mat.constant().emission;
        assert!(close(got, Rgb::new(want.x, want.y, want.z), 1e-5), "which {which}: {got:?} vs {want}");
    }
    // Indexed per hit.
    check(&mi(2), |s| m3.col((u_of(s) * 3.0) as usize));
    // A function shader with a float2x2 parameter, connected to a material's parameter.
    let connected = r#"shader "f" "mdl::hit_matrices::applied" ("m" 0.5 -1 2 0.25, "v" 3 -2)
shader "m" "mdl::hit_matrices::shown" ("c" = "f")"#;
    let (mdl, lib, diags) = compile_text(connected);
    assert!(diags.is_empty(), "{diags:#?}");
    let r = Mat2::from_cols_array(&[0.5, -1.0, 2.0, 0.25]) * Vec2::new(3.0, -2.0);
    let got = get(&mdl, &lib, "m").constant().emission;
    assert!(close(got, Rgb::new(r.x, r.y, 0.0), 1e-5), "{got:?} vs {r}");
}

/// A matrix parameter given the wrong count of numbers is an error at its `.mi` line
/// naming the shape; the material renders grey.
#[test]
fn a_matrix_parameter_of_the_wrong_shape_is_an_error_at_its_mi_line() {
    let text = "\nshader \"m\" \"mdl::hit_matrices::placed\" (\"m\" 1 2 3 4)";
    let (_, _, diags) = compile_text(text);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let d = &diags[0];
    assert!(d.contains("t.mi:2:") && d.contains("'m'") && d.contains("float3x3") && d.contains("9 numbers"), "{d}");
}
