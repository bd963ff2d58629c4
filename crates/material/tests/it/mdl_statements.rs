//! Functions with statement bodies in module materials (tests/mdl/statements.mdl): each
//! construct against a value worked out by hand — a `for` loop summing a series, a
//! `while` loop (Collatz steps), `do`–`while`, a `switch` on an enum with fall-through,
//! `break`/`continue`, lanes assigned with compound operators, an `if` and a `switch` of the hit with a
//! `return` in one branch — and an endless loop refused at its line (loops of the hit:
//! `mdl_hit_loops.rs`).

use crate::mdl_support;

use bsdf::Rgb;
use glam::Vec3A;
use material::{SurfaceMaterial, Varying};
use mdl_support::{close, compile_text, get};
use shader::State;

/// The radiance material `m` emits at `state` (its constant where nothing varies).
fn emitted(m: &SurfaceMaterial, state: &State) -> Rgb {
    let mut h = m.constant();
    if let Varying::Evaluated(e) = &m.varying {
        e.0.apply(state, &mut h);
    }
    h.emission
}

/// The constant radiance of `statements::<material>` with `params` (no message, nothing
/// evaluated per hit).
fn constant(material: &str, params: &str) -> Rgb {
    let (mdl, lib, diags) = compile_text(&format!(r#"shader "m" "mdl::statements::{material}" ({params})"#));
    assert!(diags.is_empty(), "{material} {params}: {diags:#?}");
    let m = get(&mdl, &lib, "m");
    assert!(matches!(m.varying, Varying::Constant), "{material}: folded to a constant");
    m.constant().emission
}

#[test]
fn loops_fold_to_their_hand_computed_values() {
    let series = |n: i32| (1..=n).map(|k| 1.0 / (k * k) as f32).sum::<f32>();
    for n in [0, 1, 4, 50] {
        let got = constant("series_sum", &format!(r#""n" {n}"#));
        assert!(close(got, Rgb::splat(series(n)), 1e-6), "series({n}): {got:?}");
    }
    assert!(close(constant("series_sum", r#""n" 4"#), Rgb::splat(1.0 + 0.25 + 1.0 / 9.0 + 0.0625), 1e-6));
    // 6 → 3 → 10 → 5 → 16 → 8 → 4 → 2 → 1; 27 takes 111 steps.
    for (n, steps) in [(1, 0.0), (6, 8.0), (27, 111.0)] {
        let got = constant("collatz", &format!(r#""n" {n}"#));
        assert!(close(got, Rgb::splat(steps), 0.0), "collatz({n}): {got:?}");
    }
    // `do … while` runs its body once even for 0.
    for (n, d) in [(0, 1.0), (9, 1.0), (12345, 5.0)] {
        assert!(close(constant("digit_count", &format!(r#""n" {n}"#)), Rgb::splat(d), 0.0), "digits({n})");
    }
    // `continue` skips the even numbers, `break` stops at n.
    for (n, s) in [(0, 0.0), (7, 9.0), (10, 25.0)] {
        assert!(close(constant("odd_sum_below", &format!(r#""n" {n}"#)), Rgb::splat(s), 0.0), "odd_sum({n})");
    }
}

#[test]
fn a_switch_on_an_enum_takes_its_case_and_falls_through() {
    for (s, want) in [
        ("shade_red", Rgb::new(1.0, 0.0, 0.0)),
        // No `break` after green: blue's case adds its blue.
        ("shade_green", Rgb::new(0.0, 1.0, 1.0)),
        ("shade_blue", Rgb::new(0.0, 0.0, 1.0)),
    ] {
        let got = constant("picked", &format!(r#""s" "{s}""#));
        assert!(close(got, want, 0.0), "{s}: {got:?}");
    }
}

#[test]
fn lanes_take_compound_assignments() {
    // (0, 2, 0) → x += 1 → z = 4 → × 3 = (3, 6, 12) → z − 1 → x / 2.
    assert!(close(constant("lane_values", ""), Rgb::new(1.5, 6.0, 11.0), 1e-6));
}

/// An `if` whose condition depends on the hit runs both branches: what they assign is
/// chosen per hit, and the `return` in one branch wins where its condition holds.
#[test]
fn an_if_of_the_hit_joins_its_branches_per_hit() {
    let (mdl, lib, diags) = compile_text(r#"shader "m" "mdl::statements::height_tint" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let m = get(&mdl, &lib, "m");
    assert!(matches!(m.varying, Varying::Evaluated(_)));
    for (x, y, want) in [
        (0.7, 0.9, Rgb::new(1.0, 0.0, 0.07)),
        (0.2, 0.9, Rgb::new(0.0, 0.0, 1.0)),
        (0.2, 0.1, Rgb::new(0.2, 0.2, 0.201)),
    ] {
        let s = State { point: Vec3A::new(x, y, 0.0), ..State::default() };
        let got = emitted(m, &s);
        assert!(close(got, want, 1e-6), "({x}, {y}): {got:?} vs {want:?}");
    }
}

/// The line of the first occurrence of `text` in statements.mdl (1-based).
fn line_of(text: &str) -> usize {
    let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/mdl/statements.mdl")).unwrap();
    src.lines().position(|l| l.contains(text)).expect("in the module") + 1
}

#[test]
fn an_endless_loop_is_refused_at_its_line() {
    let (mdl, lib, diags) = compile_text(r#"shader "m" "mdl::statements::endless" ()"#);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let line = line_of("while (true)");
    let at = format!("statements.mdl:{line}:");
    assert!(diags[0].contains(&at) && diags[0].contains("`forever`") && diags[0].contains("65536"), "{}", diags[0]);
    // Rendered grey.
    assert!(get(&mdl, &lib, "m").constant().emission == Rgb::ZERO);
    // A loop whose condition depends on the hit runs at each hit (tests/it/mdl_hit_loops.rs).
    let (mdl, lib, diags) = compile_text(r#"shader "m" "mdl::statements::loop_of_the_hit" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    for (x, want) in [(0.5, 1.0), (3.0, 3.0), (3.2, 4.0)] {
        let got = emitted(get(&mdl, &lib, "m"), &State { point: Vec3A::new(x, 0.0, 0.0), ..State::default() });
        assert!(close(got, Rgb::splat(want), 1e-6 * want), "x {x}: {got:?}");
    }
}

/// A `switch` on an integer of the hit: each case taken where its label matches, falling
/// through without `break`, returning from one case, the default elsewhere.
#[test]
fn a_switch_of_the_hit_takes_each_case_where_it_matches() {
    let (mdl, lib, diags) = compile_text(r#"shader "m" "mdl::statements::case_of_the_hit" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let m = get(&mdl, &lib, "m");
    assert!(matches!(m.varying, Varying::Evaluated(_)));
    // int(x) truncates towards zero: −0.5 is case 0, −1.5 the default.
    for (x, want) in [(0.5, 10.0), (-0.5, 10.0), (1.7, 25.0), (2.5, 5.0), (3.99, 99.0), (7.5, 1.0), (-1.5, 1.0)] {
        let s = State { point: Vec3A::new(x, 0.0, 0.0), ..State::default() };
        let got = emitted(m, &s);
        // Within float rounding of π · value / π.
        assert!(close(got, Rgb::splat(want), 1e-6 * want), "x {x}: {got:?} vs {want}");
    }
}

/// A loop that builds a value of the hit deeper than the hit evaluator takes is refused at
/// the assignment, naming the function, before the tree grows past it.
#[test]
fn a_loop_building_too_deep_a_value_of_the_hit_is_refused() {
    let (_, _, diags) = compile_text(r#"shader "m" "mdl::statements::too_deep" ()"#);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let at = format!("statements.mdl:{}:", line_of("x = -(x * 1.0001);"));
    assert!(diags[0].contains(&at) && diags[0].contains("`deep`") && diags[0].contains("1024"), "{}", diags[0]);
}
