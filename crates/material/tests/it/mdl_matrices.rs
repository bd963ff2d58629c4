//! Constant matrices in module materials (tests/mdl/matrices.mdl): built from numbers and
//! from columns, indexed, multiplied with matrices and with vectors on either side,
//! transposed, compared, scaled, assigned column by column, and a constant rotation and
//! scale applied to the hit's position, each against glam's products (within 1e-6).

use crate::mdl_support;

use bsdf::Rgb;
use glam::{Mat2, Mat3, Mat4, Vec2, Vec3, Vec3A, Vec4};
use material::{SurfaceMaterial, Varying};
use mdl_support::{close, compile_text, get};
use shader::State;

/// The module's `A` (column-major, as MDL's constructor takes it).
fn a() -> Mat4 {
    Mat4::from_cols_array(&[0.5, -1.0, 0.25, 2.0, 1.5, 0.75, -0.5, 0.0, -0.25, 1.0, 2.0, 0.5, 1.0, 0.0, -1.5, 0.25])
}

/// The module's `B`, built from columns.
fn b() -> Mat4 {
    Mat4::from_cols(
        Vec4::new(1.0, 0.5, -2.0, 0.0),
        Vec4::new(0.0, 1.25, 0.5, -1.0),
        Vec4::new(-0.75, 0.0, 1.0, 2.0),
        Vec4::new(0.5, 0.25, -0.5, 1.0),
    )
}

/// The radiance the material emits at `state` (its constant where nothing varies).
fn emitted(m: &SurfaceMaterial, state: &State) -> Rgb {
    let mut h = m.constant();
    match &m.varying {
        Varying::Constant => {}
        Varying::Evaluated(e) => e.0.apply(state, &mut h),
        other => panic!("{} is neither constant nor evaluated per hit: {other:?}", m.name),
    }
    h.emission
}

/// `constants`' value for `which`, column `k`: (x, y, z) and (w, 0, 0).
fn shown(which: i32, k: i32) -> (Rgb, Rgb) {
    let mut out = [Rgb::ZERO; 2];
    for (w, slot) in out.iter_mut().enumerate() {
        let text = format!(
            r#"shader "m" "mdl::matrices::constants" ("which" {which}, "k" {k}, "w" {})"#,
            if w == 1 { "on" } else { "off" }
        );
        let (mdl, lib, diags) = compile_text(&text);
        assert!(diags.is_empty(), "which {which} k {k}: {diags:#?}");
        *slot = emitted(get(&mdl, &lib, "m"), &State::default());
    }
    (out[0], out[1])
}

fn assert_shows(which: i32, k: i32, want: Vec4) {
    let (xyz, w) = shown(which, k);
    let (want_xyz, want_w) = (Rgb::new(want.x, want.y, want.z), Rgb::new(want.w, 0.0, 0.0));
    assert!(close(xyz, want_xyz, 1e-6), "which {which} k {k}: {xyz:?} vs {want_xyz:?}");
    assert!(close(w, want_w, 1e-6), "which {which} k {k}: w {w:?} vs {want_w:?}");
}

#[test]
fn a_product_of_constant_4x4_matrices_is_the_matrix_product() {
    let p = a() * b();
    for k in 0..4 {
        assert_shows(0, k, p.col(k as usize));
    }
    // Not the product taken lane by lane (what the matrices' old vector form gave).
    assert!((p.x_axis - a().x_axis * b().x_axis).abs().max_element() > 0.1);
}

#[test]
fn constant_matrices_times_vectors_on_either_side() {
    let m3 = Mat3::from_cols_array(&[1.0, 0.5, -0.25, 2.0, -1.0, 0.75, 0.5, 0.25, 1.5]);
    let v3 = Vec3::new(0.5, -1.5, 2.0);
    let m2 = Mat2::from_cols_array(&[0.75, -0.5, 1.25, 2.0]);
    let v2 = Vec2::new(-1.0, 0.5);
    assert_shows(1, 0, (m3 * v3).extend(0.0));
    // A row vector times the matrix: the transpose times the column vector.
    assert_shows(2, 0, Vec4::new((m2.transpose() * v2).x, (m2.transpose() * v2).y, 0.0, 0.0));
    assert_shows(9, 0, (m3.transpose() * v3).extend(0.0));
    assert_shows(10, 0, Vec4::new((m2 * v2).x, (m2 * v2).y, 0.0, 0.0));
    assert_shows(11, 0, (v3 * 2.0).extend(0.0));
}

#[test]
fn constant_matrices_are_indexed_transposed_compared_and_scaled() {
    let (a, b) = (a(), b());
    let scaled = a * 2.0 - a / 2.0 + Mat4::from_cols_array(&[1.0; 16]) + a * 0.5;
    for k in 0..4 {
        let c = k as usize;
        assert_shows(3, k, a.transpose().col(c));
        assert_shows(4, k, a.col(c));
        assert_shows(6, k, b.col(c));
        assert_shows(7, k, scaled.col(c));
    }
    assert_shows(5, 0, Vec4::new(a.col(1).z, a.col(3).x, a.col(2).w, 0.0));
    assert_shows(8, 0, Vec4::new(1.0, 1.0, 0.0, 0.0));
}

#[test]
fn a_constant_matrix_is_assigned_column_by_column() {
    let mut m = b();
    m.z_axis = a().x_axis;
    m.w_axis.y = 7.0;
    for k in 0..4 {
        assert_shows(12, k, m.col(k as usize));
    }
}

/// The constant matrices meet the hit: times its position on either side, chosen by a
/// condition of the hit, and a matrix built from columns of the hit.
#[test]
fn a_constant_turn_and_scale_applies_to_the_hit_position() {
    let (turn, scale) = (Mat3::from_rotation_z(0.5), Mat3::from_diagonal(Vec3::new(0.5, 1.5, 0.75)));
    let t = turn * scale;
    for p in [Vec3::new(0.3, -0.7, 0.9), Vec3::new(-0.4, 0.6, 0.2)] {
        let state = State { point: Vec3A::from(p), ..State::default() };
        let chosen = if p.x > 0.0 { turn } else { scale };
        let built = Mat3::from_cols(p, p * 2.0, Vec3::Z);
        let cases = [(0, t * p), (1, t.transpose() * p), (2, chosen * p), (3, built * Vec3::new(1.0, 0.5, 2.0))];
        for (which, want) in cases {
            let text = format!(r#"shader "m" "mdl::matrices::turned" ("which" {which})"#);
            let (mdl, lib, diags) = compile_text(&text);
            assert!(diags.is_empty(), "which {which}: {diags:#?}");
            let m = get(&mdl, &lib, "m");
            assert!(matches!(m.varying, Varying::Evaluated(_)), "the position is read per hit");
            let got = emitted(m, &state);
            assert!(close(got, Rgb::new(want.x, want.y, want.z), 1e-6), "which {which} at {p}: {got:?} vs {want:?}");
        }
    }
}
