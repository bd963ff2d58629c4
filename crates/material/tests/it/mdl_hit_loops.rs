//! Loops whose control depends on the hit (tests/mdl/hit_loops.mdl), compiled once and run
//! at each hit: each against its closed form at several hits (within 1e-6 relative) — a
//! trip count read from a texture coordinate, `while`, `do`–`while`, nested loops, a
//! `break` and a `continue` under conditions of the hit, `continue` in a `switch` of the
//! hit, a struct carried through the turns, a `return` inside (early, nested, under an
//! `if` of the hit, in a loop of fixed count inside), a `break` of the hit out of a
//! `switch`, ten array elements read after a loop, a loop starting from another's results
//! (each loop run once per hit) — and an endless one stopped after its steps.

use crate::mdl_support;

use bsdf::Rgb;
use glam::Vec3A;
use material::{SurfaceMaterial, Varying};
use mdl_support::{close, compile_text, get};
use shader::State;

/// The radiance material `m` emits at texture coordinate u.
fn emitted(m: &SurfaceMaterial, u: f32) -> Rgb {
    let mut s = State { tex_count: 1, ..State::default() };
    s.tex_list[0] = Vec3A::new(u, 0.0, 0.0);
    let Varying::Evaluated(e) = &m.varying else { panic!("{} is not evaluated per hit", m.name) };
    let mut h = m.constant();
    e.0.apply(&s, &mut h);
    h.emission
}

/// `hit_loops::<material>`, compiled without a message.
fn material(name: &str) -> (material::mdl_modules::MdlMaterials, scene::Library) {
    let (mdl, lib, diags) = compile_text(&format!(r#"shader "m" "mdl::hit_loops::{name}" ()"#));
    assert!(diags.is_empty(), "{name}: {diags:#?}");
    (mdl, lib)
}

/// Checks `name`'s value at each (u, value) within 1e-6 relative.
fn check(name: &str, cases: &[(f32, f32)]) {
    let (mdl, lib) = material(name);
    let m = get(&mdl, &lib, "m");
    for &(u, want) in cases {
        let got = emitted(m, u);
        assert!(close(got, Rgb::splat(want), 1e-6 * want.abs().max(1.0)), "{name} at u {u}: {got:?} vs {want}");
    }
}

#[test]
fn a_trip_count_of_the_hit_gives_the_closed_form() {
    // n = floor(10 u) halvings: 2 (1 − 2^−n).
    let halving = |u: f32| {
        let n = (u * 10.0) as i32;
        2.0 * (1.0 - 0.5f32.powi(n))
    };
    check("halving", &[0.05, 0.35, 0.72, 0.99, 0.1].map(|u| (u, halving(u))));
    // Counting up to x: ⌈x⌉, 0 where x ≤ 0.
    check("counting", &[(-0.5, 0.0), (0.0, 0.0), (0.3, 1.0), (2.0, 2.0), (2.5, 3.0), (7.01, 8.0)]);
    // do–while doubles once even where the condition fails at once.
    check("doubles", &[(-3.0, 2.0), (0.5, 2.0), (2.0, 4.0), (5.0, 8.0), (100.0, 128.0)]);
    // Nested: n (n − 1) / 2 pairs.
    check("nested", &[(0.05, 0.0), (0.15, 0.0), (0.35, 3.0), (0.99, 36.0)]);
}

#[test]
fn break_and_continue_under_conditions_of_the_hit() {
    // The odd k ≤ min(x, 20): `continue` on even k, `break` past x.
    let odd = |x: f32| (1..=20).filter(|k| k % 2 == 1 && (*k as f32) <= x).sum::<i32>() as f32;
    check("odd", &[0.5, 1.0, 7.5, 9.0, 30.0].map(|x| (x, odd(x))));
    // `continue` in a switch of the hit: over k = 0..3, (k + m) % 3 = 0 skips, 1 adds 110,
    // 2 adds 101.
    let skip = |x: f32| (0..4).map(|k| [0.0, 110.0, 101.0][((k + x as i32) % 3) as usize]).sum::<f32>();
    check("skip", &[0.5, 1.5, 2.5, 3.5, 7.0].map(|x| (x, skip(x))));
}

#[test]
fn a_struct_is_carried_through_the_turns() {
    let (mdl, lib) = material("structs");
    let m = get(&mdl, &lib, "m");
    // a counts up to ⌈x⌉, b doubles as often.
    for (x, want) in [(0.0, Rgb::new(1.0, 1.0, 1.0)), (2.5, Rgb::new(8.0, 11.0, 8.0))] {
        let got = emitted(m, x);
        assert!(close(got, want, 1e-5), "x {x}: {got:?}");
    }
}

/// `while (x > 0) s += 1;` compiles (nothing tells when it is compiled that it never ends)
/// and, where it does not end, stops after the steps a loop may take, with the count its
/// turns reached: the documented fallback, never a hang.
#[test]
fn an_endless_loop_of_the_hit_stops_after_its_steps() {
    let (mdl, lib) = material("endless");
    let m = get(&mdl, &lib, "m");
    assert!(close(emitted(m, -1.0), Rgb::ZERO, 0.0));
    let got = emitted(m, 0.5).x;
    let limit = material::mdl_modules::hit_loop::MAX_LOOP_STEPS as f32;
    assert!(got >= 100.0 && got <= limit, "{got}");
}

#[test]
fn a_return_inside_a_loop_of_the_hit_ends_the_function_where_taken() {
    // The first k < ceil(10 u) with k k > 7 (k = 3, where 10 u > 3) returns 103; none
    // returns the count ceil(10 u).
    check("searching", &[(0.05, 1.0), (0.25, 3.0), (0.3, 3.0), (0.35, 103.0), (0.9, 103.0)]);
    // Nested: the first pair j < i < floor(10 u) with i j > 6 is (4, 2): 42, from n = 5.
    check("nested_returns", &[(0.0, 0.0), (0.25, -2.0), (0.45, -4.0), (0.55, 42.0), (0.95, 42.0)]);
    // Under an `if` of the hit: s = ceil(10 u) up to 3, else returns 40 (u > 0.5) or -4.
    check("early_return", &[(0.05, 1.0), (0.15, 2.0), (0.35, -4.0), (0.45, -4.0), (0.75, 40.0)]);
    // In a loop of fixed count inside: s = 4, j = 2 returns 42 where 10 u > 4, else -ceil(10 u).
    check("inner_known_return", &[(0.05, -1.0), (0.25, -3.0), (0.35, -4.0), (0.45, 42.0), (0.9, 42.0)]);
}

#[test]
fn a_break_of_the_hit_leaves_its_switch() {
    // Four turns of 100, odd k 1 each (2), even k below 10 u 11 each (k = 0, 2).
    check("switch_breaks", &[(0.0, 402.0), (0.15, 413.0), (0.2, 413.0), (0.55, 424.0)]);
    // k < ceil(10 u): k % 3 = 0 adds 11 where 2 k <= 10 u (else 0), 1 adds 1, 2 adds 1000.
    check("hit_switch_breaks", &[(0.25, 1012.0), (0.45, 1013.0), (0.75, 2025.0)]);
    // The `return` after a `break` of the hit runs only where the break is not taken.
    check("break_skips_return", &[(0.25, 7.0), (0.75, 9.0)]);
}

/// Loops of the hit carrying more than the small frame's 32 values run in a large one: 41
/// and 100 values, and a loop nested in one of 42 (its slots past the small frame).
#[test]
fn loops_of_the_hit_carry_up_to_255_values() {
    let ceil10 = |u: f32| (u * 10.0).ceil().max(0.0);
    check("forty", &[0.0, 0.05, 0.31, 0.99].map(|u| (u, ceil10(u))));
    check("wide_loop", &[0.0, 0.05, 0.31, 0.99].map(|u| (u, 99.0 * ceil10(u))));
    let nest = |u: f32| (0..(u * 10.0) as i32).map(|k| (k * (k + 1)) as f32).sum::<f32>();
    check("wide_nested", &[0.05, 0.15, 0.45, 0.99].map(|u| (u, nest(u))));
}

/// How many loops of the hit (no loop around) one hit of `m` at u runs.
fn runs_per_hit(m: &SurfaceMaterial, u: f32) -> u64 {
    let before = material::mdl_modules::hit_loop::loops_run();
    emitted(m, u);
    material::mdl_modules::hit_loop::loops_run() - before
}

/// Ten array elements filled in a loop of the hit and all read after it: the closed form
/// Σ (k + 1)(k² + 0.5) over k < floor(10 u), with the loop run once per hit (before, each
/// read re-ran it and the module was refused as too costly: 10 × 16 385 steps and more).
#[test]
fn ten_elements_read_after_a_loop_run_it_once() {
    let want = |u: f32| (0..(u * 10.0) as i32).map(|k| ((k + 1) * (k * k)) as f32 + 0.5 * (k + 1) as f32).sum::<f32>();
    let cases = [0.05, 0.25, 0.55, 0.99].map(|u| (u, want(u)));
    check("ten_read", &cases);
    let (mdl, lib) = material("ten_read");
    let m = get(&mdl, &lib, "m");
    for (u, _) in cases {
        assert_eq!(runs_per_hit(m, u), 1, "u {u}");
    }
}

/// A loop whose starting values and turns read another loop's results (n = floor(10 u)):
/// a + b s + t = n + 2^n + n² + (2^n − n) n + 2^n, each of the two loops run once per hit
/// (the first is not run again inside the second's frame).
#[test]
fn a_loop_starting_from_another_loops_results_runs_each_once() {
    let want = |u: f32| {
        let n = (u * 10.0) as i32 as f32;
        let p = n.exp2();
        (n + p + n * n) + (p - n) * n + p
    };
    let cases = [0.05, 0.15, 0.45, 0.99].map(|u| (u, want(u)));
    check("chained_loops", &cases);
    let (mdl, lib) = material("chained_loops");
    let m = get(&mdl, &lib, "m");
    for (u, _) in cases {
        assert_eq!(runs_per_hit(m, u), 2, "u {u}");
    }
}

/// What is not compiled in a loop of the hit — one carrying more values than it has slots
/// for (255), or nesting more than 16 loops of the hit past the small frame — is an error
/// at its `file:line:col`, naming the function; the material renders grey.
#[test]
fn a_loop_of_the_hit_carrying_too_many_values_is_an_error_at_its_line() {
    let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/mdl/hit_loops.mdl")).unwrap();
    // The 1-based line of the loop: the line before the first one holding `inside`.
    let at = |inside: &str| src.lines().position(|l| l.contains(inside)).unwrap();
    let (_, _, diags) = compile_text(r#"shader "m" "mdl::hit_loops::too_many" ()"#);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let line = format!("hit_loops.mdl:{}:5", at("for (int k = 0; k < 300; k++)"));
    let d = &diags[0];
    assert!(d.contains(&line) && d.contains("carries 301 values") && d.contains("`too_wide`"), "{d}");
    let (_, _, diags) = compile_text(r#"shader "m" "mdl::hit_loops::too_deep" ()"#);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let line = format!("hit_loops.mdl:{}:5", at("a[0] += 1.0;"));
    let d = &diags[0];
    assert!(d.contains(&line) && d.contains("nests 17 loops") && d.contains("`deep`"), "{d}");
}

/// What evaluating loops of the hit costs: 20 000 hits of `halving`, `nested` and
/// `structs` (small frames). Not a check — a workload to measure, e.g.
/// `valgrind --tool=callgrind target/debug/deps/it-… --ignored --exact
/// mdl_hit_loops::evaluation_workload` before and after a change to the loops' frames.
#[test]
#[ignore]
fn evaluation_workload() {
    let mut sum = 0.0f32;
    for name in ["halving", "nested", "structs"] {
        let (mdl, lib) = material(name);
        let m = get(&mdl, &lib, "m");
        for k in 0..20_000 {
            sum += emitted(m, std::hint::black_box((k % 100) as f32 / 100.0)).x;
        }
    }
    assert!(sum.is_finite());
}
