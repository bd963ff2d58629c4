//! mental ray's `mib_glossy_reflection` in the path engine (`material`'s `reader::mib_glossy`,
//! `bsdf::MibGlossy`) against the classic engine and closed forms: the image of a glossy
//! ground reflecting a two-tone ceiling, and Maya's `reflectionLimit` counting its rays
//! (`render::integrator::levels`) in the two-reflector scene of
//! `maya_limit_classic_glossy`.

use crate::support;
use crate::support::maya_view::{mean, mean_and_error, pixels};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 8;

/// A `mib_glossy_reflection` ground (no base material, `reflection_color` and
/// `environment_color` 1, weights 1, 16 samples spread by `spread` radians) under a Maya
/// mirror ceiling (phongE without a highlight, reflectivity r, incandescence e,
/// `reflectionLimit` `limit`) at y = 5, the camera between them looking down.
fn two_reflectors(limit: u32, spread: f32, e: f32, r: f32) -> String {
    let ground = format!(
        r#"material "g" opaque "mib_glossy_reflection" ("reflection_color" 1 1 1,
    "environment_color" 1 1 1, "reflection_base_weight" 1, "reflection_edge_weight" 1,
    "samples" 16, "single_env_sample" off, "u_spread" {spread}, "v_spread" {spread}) end material"#
    );
    support::maya_view::under_a_mirror(SIDE, "trace depth 8 8 16", &ground, "g", 500, limit, e, r)
}

/// Two facing reflectors: the glossy ground G (no base, reflection colour 1) and the Maya
/// mirror ceiling C (reflectivity r = 0.5, incandescence e = 0.25, `reflectionLimit` L).
/// At reflection level k the ground shows G(k) = C(k + 1), the ceiling C(k) = e + r·G(k + 1)
/// while k < L, else e: the camera's ground shows e·(1 + r + … + r^⌊L/2⌋) (e for L = 0
/// and 1, e·(1 + r) for L = 2, e·(1 + r + r²) for L = 4; the ceiling is uniform, so the
/// spread does not change it). The classic engine gives it at every pixel within 1e-4;
/// the path engine, which counts a sample of the glossy lobe as a reflection as the
/// classic shader casts reflection rays, in its image mean within 1e-3 plus four
/// standard errors (spread 0: a mirror, every path the same but for Russian roulette;
/// spread 0.1).
/// Were the glossy bounces not counted, L = 1 would give e·(1 + r).
#[test]
fn reflection_limit_counts_mib_glossy_reflection_samples_in_the_path_engine() {
    let (r, e) = (0.5f32, 0.25f32);
    for spread in [0.0f32, 0.1] {
        for limit in [0u32, 1, 2, 4] {
            let want = e * (0..=limit / 2).map(|k| r.powi(k as i32)).sum::<f32>();
            let text = two_reflectors(limit, spread, e, r);
            for (i, p) in pixels(&text, EngineKind::Classic, 1).iter().enumerate() {
                assert!(
                    (*p - Vec3A::splat(want)).abs().max_element() < 1e-4,
                    "spread {spread}, L = {limit}, classic pixel {i}: {p} vs {want}"
                );
            }
            let (m, error) = mean_and_error(&pixels(&text, EngineKind::Path, 32));
            println!("spread {spread}, L = {limit}: path {m} ± {error}, formula {want}");
            for k in 0..3 {
                assert!(
                    (m[k] - want).abs() < 4.0 * error[k] + 1e-3,
                    "spread {spread}, L = {limit}: path {m} ± {error} vs {want}"
                );
            }
        }
    }
}

/// A glossy ground (no base, `reflection_color` = `environment_color` 0.8, the default
/// view-angle curve 0.6 → 1 by (1 − cos θ)^5, spread `spread`) under a ceiling at y = 5
/// glowing 1 for x < 0 and 0.2 for x > 0 (Maya lambert of colour 0 and that
/// incandescence), seen from above.
fn two_tone(spread: f32) -> String {
    let view = support::two_tone::view(16);
    let material = format!(
        r#"material "g" opaque "mib_glossy_reflection" ("reflection_color" 0.8 0.8 0.8,
    "environment_color" 0.8 0.8 0.8, "samples" 64, "single_env_sample" off, "u_spread" {spread}, "v_spread" {spread}) end material"#
    );
    support::two_tone::scene(&view, &material, "ground", 0.0, 5.0)
}

/// The path engine's image of [`two_tone`] agrees with the classic engine's (64 glossy
/// rays per sample): the image mean and the means of its left and right halves (the
/// bright and the dim reflection, blurred across x = 0) within 2 %, spreads 0.05 and 0.3.
#[test]
fn the_path_engine_agrees_with_the_classic_glossy_reflection() {
    for spread in [0.05f32, 0.3] {
        support::two_tone::assert_path_agrees_with_classic(&two_tone(spread), 16, &format!("spread {spread}"));
    }
}

/// A glossy ground of `reflection_color` = `environment_color` 0.8 (weights 1, spread
/// `spread`) whose `environment` is the constant (0.3, 0.6, 0.9), under nothing but the
/// camera's constant environment 1, seen from above.
fn own_environment(spread: f32) -> String {
    let view = support::maya_view::top_down(4).replace("end camera", "environment = \"camera_env\" end camera");
    format!(
        r#"
shader "camera_env" "mib_color_mix" ("num" 0, "color_base" 1 1 1 1)
shader "glossy_env" "mib_color_mix" ("num" 0, "color_base" 0.3 0.6 0.9 1)
{view}
material "g" opaque "mib_glossy_reflection" ("reflection_color" 0.8 0.8 0.8,
    "environment_color" 0.8 0.8 0.8, "reflection_base_weight" 1, "reflection_edge_weight" 1,
    "samples" 16, "single_env_sample" off, "u_spread" {spread}, "v_spread" {spread},
    "environment" "glossy_env") end material
object "ground" group -500 0 500  500 0 500  500 0 -500  -500 0 -500  v 0 v 1 v 2 v 3 c "g" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
instgroup "root" "cam_inst" "ground_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// `mib_glossy_reflection`'s own `environment` is what its reflections see where they
/// leave the scene, in both engines: a mirror (spread 0) and a mirror-like lobe (spread
/// 0.01) of colour 0.8 show 0.8 × the shader's constant environment (0.3, 0.6, 0.9), not
/// the camera's (1), at every pixel within 1e-3.
#[test]
fn the_glossy_reflections_own_environment_is_seen_in_its_reflections() {
    let want = Vec3A::new(0.3, 0.6, 0.9) * 0.8;
    for spread in [0.0f32, 0.01] {
        let text = own_environment(spread);
        for engine in [EngineKind::Classic, EngineKind::Path] {
            for (i, p) in pixels(&text, engine, 8).iter().enumerate() {
                assert!((*p - want).abs().max_element() < 1e-3, "spread {spread}, {engine:?} pixel {i}: {p} vs {want}");
            }
        }
    }
}

/// [`two_tone`] with anisotropic spreads (0.4 along `u_axis` `axis`, 0.03 across it).
fn two_tone_anisotropic(axis: &str) -> String {
    two_tone(0.4).replace(r#""v_spread" 0.4"#, &format!(r#""v_spread" 0.03, "u_axis" {axis}"#))
}

/// `u_axis` in the path engine agrees with the classic shader's: the two-tone ceiling
/// reflected by spreads 0.4 along `u_axis` and 0.03 across it, with the axis across the
/// ceiling's seam (x; the bright and dim halves blur into each other) and along it (z; the
/// seam stays sharp): the path engine's image mean and the means of its halves within 2 %
/// of the classic engine's (64 glossy rays per sample) for each axis, while the classic
/// halves of the two axes differ by over 10 % (the axis matters).
#[test]
fn u_axis_lays_the_spreads_alike_in_both_engines() {
    let mut classic_right = Vec::new();
    for axis in ["1 0 0", "0 0 1"] {
        let text = two_tone_anisotropic(axis);
        assert!(text.contains("u_axis"), "{text}");
        let classic = support::two_tone::assert_path_agrees_with_classic(&text, 16, &format!("u_axis {axis}"));
        classic_right.push(support::two_tone::half_mean(&classic, 16, false).x);
    }
    assert!(
        (classic_right[0] - classic_right[1]).abs() > 0.1 * classic_right[1],
        "the axis changes the blur across the seam: right halves {classic_right:?}"
    );
}

/// A mirror-like ground (`reflection_color` 0.8, `environment_color` `env_color`, weights
/// 1, spread `spread`, `extra` parameters) under a ceiling at y = 5 glowing 1 (a Maya
/// lambert of colour 0, incandescence 1) where `ceiling`, in the camera's constant
/// environment (0.3, 0.6, 0.9), seen from above (the camera at y = 4).
fn reach_scene(spread: f32, env_color: &str, extra: &str, ceiling: bool) -> String {
    let view = support::maya_view::top_down(8).replace("end camera", "environment = \"camera_env\" end camera");
    let (object, instance) = if ceiling {
        (
            r#"object "ceiling" group -500 5 500  500 5 500  500 5 -500  -500 5 -500  v 0 v 1 v 2 v 3 c "c" 0 1 2 3 end group end object
instance "ceiling_inst" "ceiling" end instance"#,
            r#" "ceiling_inst""#,
        )
    } else {
        ("", "")
    };
    format!(
        r#"
$include "mayabase.mi"
shader "camera_env" "mib_color_mix" ("num" 0, "color_base" 0.3 0.6 0.9 1)
{view}
material "g" opaque "mib_glossy_reflection" ("reflection_color" 0.8 0.8 0.8,
    "environment_color" {env_color}, "reflection_base_weight" 1, "reflection_edge_weight" 1,
    "samples" 16, "single_env_sample" off, "u_spread" {spread}, "v_spread" {spread}{extra}) end material
shader "glow" "maya_lambert" ("color" 0 0 0, "incandescence" 1 1 1)
material "c" opaque "maya_shadingengine" ("surfaceShader" = "glow.outColor") end material
object "ground" group -500 0 500  500 0 500  500 0 -500  -500 0 -500  v 0 v 1 v 2 v 3 c "g" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
{object}
instgroup "root" "cam_inst" "ground_inst"{instance} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// `max_distance`: the glossy rays of a ground whose ceiling lies 5 away or farther take
/// the environment past `max_distance` 3, as the classic shader's do (its rays stop
/// there): a mirror (spread 0) and a spread-0.01 lobe show 0.8 × the environment (0.3,
/// 0.6, 0.9) at every pixel within 1e-3 in both engines (without the limit they show
/// 0.8 × the ceiling's 1, checked the same way). With `max_distance` 10 and `falloff` 2
/// or 1 a hit at d fades towards the environment by (d / 10)^falloff: the path engine's
/// image mean within 2 % of the classic engine's, and between the two images above.
#[test]
fn glossy_rays_past_max_distance_take_the_environment() {
    let env = Vec3A::new(0.3, 0.6, 0.9) * 0.8;
    let ceiling = Vec3A::splat(0.8);
    for spread in [0.0f32, 0.01] {
        for (extra, want) in [(r#", "max_distance" 3"#, env), ("", ceiling)] {
            let text = reach_scene(spread, "0.8 0.8 0.8", extra, true);
            for engine in [EngineKind::Classic, EngineKind::Path] {
                for (i, p) in pixels(&text, engine, 8).iter().enumerate() {
                    assert!(
                        (*p - want).abs().max_element() < 1e-3,
                        "spread {spread}{extra}, {engine:?} pixel {i}: {p} vs {want}"
                    );
                }
            }
        }
        for falloff in [2.0f32, 1.0] {
            let text =
                reach_scene(spread, "0.8 0.8 0.8", &format!(r#", "max_distance" 10, "falloff" {falloff}"#), true);
            let (c, p) = (mean(&pixels(&text, EngineKind::Classic, 8)), mean(&pixels(&text, EngineKind::Path, 8)));
            println!("spread {spread}, falloff {falloff}: classic {c}, path {p}");
            assert!(
                (p - c).abs().max_element() <= 0.02 * c.max_element(),
                "falloff {falloff}: path {p} vs classic {c}"
            );
            assert!(c.x > env.x + 0.05 && c.x < ceiling.x - 0.05, "a fade between the two: {c}");
        }
    }
}

/// `environment_color` weighs what the glossy rays take from the environment,
/// `reflection_color` what they find, in both engines: a mirror (spread 0) and a
/// spread-0.01 lobe of `reflection_color` 0.8, or (0.8, 0, 0.8) (green: the environment
/// alone), and `environment_color` (0.2, 0.4, 1) show (0.2, 0.4, 1) ⊙ the environment
/// (0.3, 0.6, 0.9) under the open sky and past `max_distance` 3 below the ceiling, and
/// `reflection_color` × the ceiling's 1 below it without a limit: at every pixel within
/// 1e-3.
#[test]
fn environment_color_weighs_the_environment_in_both_engines() {
    let env = Vec3A::new(0.2, 0.4, 1.0) * Vec3A::new(0.3, 0.6, 0.9);
    for (reflection, seen) in [("0.8 0.8 0.8", Vec3A::splat(0.8)), ("0.8 0 0.8", Vec3A::new(0.8, 0.0, 0.8))] {
        for spread in [0.0f32, 0.01] {
            for (extra, ceiling, want) in [("", false, env), (r#", "max_distance" 3"#, true, env), ("", true, seen)] {
                let text = reach_scene(spread, "0.2 0.4 1", extra, ceiling)
                    .replace(r#""reflection_color" 0.8 0.8 0.8"#, &format!(r#""reflection_color" {reflection}"#));
                for engine in [EngineKind::Classic, EngineKind::Path] {
                    for (i, p) in pixels(&text, engine, 8).iter().enumerate() {
                        assert!(
                            (*p - want).abs().max_element() < 1e-3,
                            "reflection {reflection}, spread {spread}{extra}, ceiling {ceiling}, {engine:?} pixel {i}: \
                             {p} vs {want}"
                        );
                    }
                }
            }
        }
    }
}
