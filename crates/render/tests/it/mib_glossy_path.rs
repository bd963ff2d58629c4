//! mental ray's `mib_glossy_reflection` in the path engine (`material`'s `reader::mib_glossy`,
//! `bsdf::MibGlossy`) against the classic engine and closed forms: the image of a glossy
//! ground reflecting a two-tone ceiling, and Maya's `reflectionLimit` counting its rays
//! (`render::integrator::levels`) in the two-reflector scene of
//! `maya_limit_classic_glossy`.

use crate::support;
use crate::support::maya_view::{mean_and_error, pixels};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 8;

/// A `mib_glossy_reflection` ground (no base material, `reflection_color` and
/// `environment_color` 1, weights 1, 16 samples spread by `spread` radians) under a Maya
/// mirror ceiling (phongE without a highlight, reflectivity r, incandescence e,
/// `reflectionLimit` `limit`) at y = 5, the camera between them looking down.
fn two_reflectors(limit: u32, spread: f32, e: f32, r: f32) -> String {
    let view = support::maya_view::top_down(SIDE).replace("end options", "trace depth 8 8 16 end options");
    format!(
        r#"
$include "mayabase.mi"
{view}
material "g" opaque "mib_glossy_reflection" ("reflection_color" 1 1 1,
    "environment_color" 1 1 1, "reflection_base_weight" 1, "reflection_edge_weight" 1,
    "samples" 16, "single_env_sample" off, "u_spread" {spread}, "v_spread" {spread}) end material
shader "mat" "maya_phongE" ("color" 0 0 0, "diffuse" 0, "whiteness" 0 0 0, "specularColor" 1 1 1,
    "reflectivity" {r}, "reflectionLimit" {limit}, "incandescence" {e} {e} {e})
material "m" opaque "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "ground" group -500 0 500  500 0 500  500 0 -500  -500 0 -500  v 0 v 1 v 2 v 3 c "g" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
object "ceiling" group -500 5 500  500 5 500  500 5 -500  -500 5 -500  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ceiling_inst" "ceiling" end instance
instgroup "root" "cam_inst" "ground_inst" "ceiling_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
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
    let view = support::maya_view::top_down(16).replace("samples 0 2", "samples 2 2");
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
        support::two_tone::assert_path_agrees_with_classic(&two_tone(spread), 16, spread);
    }
}
