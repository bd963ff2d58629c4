//! Maya's ramp texture's wave and noise attributes in compiled scenes, under both name
//! families: the ramp is read through a surfaceShader (its colour is the pixel's) at the
//! world origin, normal +y, at the uv given to `support::maya::point`. The formulas are
//! in `crates/maya/src/ramp_texture.rs`.

use crate::support;

use support::maya::{assert_rgb, compile, point, run, Compiled};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";

/// A scene whose material "m" shows a ramp of `type` with `entries` and `extra`
/// parameters through a surfaceShader of the family chosen by `adsk`.
fn scene(ramp_type: i32, entries: &str, extra: &str, adsk: bool) -> Compiled {
    let (ramp, surface, engine) = if adsk {
        ("adskMayaRamp", "adskMayaSurfaceShader", "adskMayaShadingEngine")
    } else {
        ("maya_ramp", "maya_surfaceshader", "maya_shadingengine")
    };
    let c = compile(
        "",
        &format!(
            r#"{LIBS}shader "tex" "{ramp}" ("type" {ramp_type}, "interpolation" 1,
                "colorEntryList" [ {entries} ]{extra})
            shader "flat" "{surface}" ("outColor" = "tex.outColor")
            material "m" opaque "{engine}" ("surfaceShader" = "flat.outColor") end material"#
        ),
        &["m"],
        "",
    );
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    c
}

fn shade(c: &Compiled, uv: [f32; 2]) -> glam::Vec4 {
    run(c, &Empty::default(), c.material("m"), point(uv)).color()
}

/// Black at 0 to white at 1: the colour is the ramp position.
const GREY: &str = r#"{ "position" 0, "color" 0 0 0 }, { "position" 1, "color" 1 1 1 }"#;

/// uWave 0.1 on a U ramp: the position is u − 0.1 sin(2π v) (0.4 at (0.5, 0.25),
/// 0.3 − 0.1 sin(0.2π) at (0.3, 0.1)); vWave 0.2 on a V ramp: v + 0.2 sin(2π u) (0.7 at
/// (0.25, 0.5)), within 1e-5.
#[test]
fn ramp_waves_move_the_position_by_their_sine() {
    for adsk in [false, true] {
        let u = scene(1, GREY, r#", "uWave" 0.1"#, adsk);
        assert_rgb(shade(&u, [0.5, 0.25]), [0.4; 3], 1e-5);
        let want = 0.3 - 0.1 * (0.2 * std::f32::consts::PI).sin();
        assert_rgb(shade(&u, [0.3, 0.1]), [want; 3], 1e-5);
        let v = scene(0, GREY, r#", "vWave" 0.2"#, adsk);
        assert_rgb(shade(&v, [0.25, 0.5]), [0.7; 3], 1e-5);
    }
}

/// Every wave and noise amount written as 0 (frequencies changed) gives today's ramp
/// exactly, at 40 points of a three-colour diagonal ramp.
#[test]
fn ramp_without_noise_equals_the_plain_ramp() {
    let entries =
        r#"{ "position" 0, "color" 1 0 0 }, { "position" 0.5, "color" 0 1 0 }, { "position" 1, "color" 0 0 1 }"#;
    for adsk in [false, true] {
        let plain = scene(2, entries, "", adsk);
        let zero = scene(
            2,
            entries,
            r#", "uWave" 0, "vWave" 0, "noise" 0, "noiseFreq" 3, "hueNoise" 0, "satNoise" 0, "valNoise" 0,
            "hueNoiseFreq" 2, "satNoiseFreq" 2, "valNoiseFreq" 2"#,
            adsk,
        );
        for i in 0..40 {
            let uv = [0.025 * i as f32, (0.37 + 0.061 * i as f32).fract()];
            assert_eq!(shade(&plain, uv), shade(&zero, uv), "at {uv:?}");
        }
    }
}

/// Noise 0.05 on a U ramp moves the position by at most 0.05 (1e-5), and somewhere by more
/// than 0.005.
#[test]
fn ramp_noise_offsets_the_position_within_its_amount() {
    let c = scene(1, GREY, r#", "noise" 0.05"#, false);
    let mut largest = 0.0f32;
    for i in 0..100 {
        let uv = [0.2 + 0.006 * i as f32, (0.13 + 0.0077 * i as f32).fract()];
        let d = (shade(&c, uv).x - uv[0]).abs();
        assert!(d <= 0.05 + 1e-5, "at {uv:?}: moved {d}");
        largest = largest.max(d);
    }
    assert!(largest > 0.005, "{largest}");
}

/// Hue, saturation and value noise on a one-colour ramp (0.5, 0.35, 0.25: hue 20°, sat
/// 0.5, val 0.5, far from the clamps): over a 24 × 24 grid of the tile the mean colour stays
/// within 0.015 of the ramp's colour per channel, the colour does vary (some channel's
/// spread over the grid above 0.05), and a second compile gives the same values bit for
/// bit.
#[test]
fn hsv_noise_keeps_the_mean_colour_and_is_deterministic() {
    let one = r#"{ "position" 0, "color" 0.5 0.35 0.25 }"#;
    for (extra, adsk) in [
        (r#", "hueNoise" 0.05"#, false),
        (r#", "satNoise" 0.2"#, true),
        (r#", "valNoise" 0.2, "valNoiseFreq" 1"#, false),
        (r#", "hueNoise" 0.03, "satNoise" 0.1, "valNoise" 0.1"#, true),
    ] {
        let (a, b) = (scene(0, one, extra, adsk), scene(0, one, extra, adsk));
        let mut sum = glam::Vec3::ZERO;
        let (mut lo, mut hi) = (glam::Vec3::splat(f32::MAX), glam::Vec3::splat(f32::MIN));
        let n = 24;
        for i in 0..n {
            for j in 0..n {
                let uv = [(i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32];
                let c = shade(&a, uv);
                assert_eq!(c, shade(&b, uv), "{extra} at {uv:?}");
                let c = c.truncate();
                sum += c;
                lo = lo.min(c);
                hi = hi.max(c);
            }
        }
        let mean = sum / (n * n) as f32;
        let want = glam::Vec3::new(0.5, 0.35, 0.25);
        assert!((mean - want).abs().max_element() < 0.015, "{extra}: mean {mean}");
        assert!((hi - lo).max_element() > 0.05, "{extra}: spread {lo} .. {hi}");
    }
}
