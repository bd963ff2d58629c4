//! rampShader's `transparency` and `incandescence` ramps by the view's facing ratio in
//! the path engine, as the classic shader reads them (`material::maya::ViewTransparency`,
//! `maya::ramp_shader`).

use crate::support;
use crate::support::maya_view::{ground_points, pixels, EYE};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 16;

/// The tilt of the plane about x: its normal (0, cos a, sin a), through the origin.
const TILT_DEG: f32 = 30.0;

/// The colour of the unlit surfaceShader plane behind (y = −30).
const BEHIND: Vec3A = Vec3A::new(0.2, 0.3, 0.4);

/// T(f) = 1 − f, grey; for the refracting plane (`refract`) 0.9 − 0.6 f, which is not
/// black at f = 1.
fn transparency(f: f32, refract: bool) -> Vec3A {
    Vec3A::splat(if refract { 0.9 - 0.6 * f } else { 1.0 - f })
}

/// incandescence(f): (1, 0.5, 0) at 0 to (0, 0.5, 1) at 1, linear.
fn incandescence(f: f32) -> Vec3A {
    Vec3A::new(1.0 - f, 0.5, f)
}

/// The classic shader's formula at facing ratio f with nothing lit (black colour ramp,
/// no highlight, no reflection): incandescence(f) ⊙ (1 − T(f)) + T(f) ⊙ behind.
fn shade(f: f32, refract: bool) -> Vec3A {
    let t = transparency(f, refract);
    incandescence(f) * (Vec3A::ONE - t) + t * BEHIND
}

/// `shade` at the facing ratio of each ray (or at 1: `head_on`) averaged over pixel
/// (`col`, `row`) (16 × 16 rays from the eye through the points the top-down view shows
/// at y = 0, each meeting the tilted plane).
fn formula(col: usize, row: usize, head_on: bool, refract: bool) -> Vec3A {
    let a = TILT_DEG.to_radians();
    let n = Vec3A::new(0.0, a.cos(), a.sin());
    let points: Vec<Vec3A> = ground_points(SIDE, col, row, 16).collect();
    let sum = points.iter().fold(Vec3A::ZERO, |s, p| {
        let d = (*p - EYE).normalize();
        s + shade(if head_on { 1.0 } else { n.dot(d).abs() }, refract)
    });
    sum / points.len() as f32
}

/// A ramp of `name` through `points` (position, value), linear.
fn ramp(name: &str, member: &str, points: &[(f32, &str)]) -> String {
    let items: Vec<String> = points
        .iter()
        .map(|(p, v)| format!(r#"{{ "{name}_Position" {p}, "{name}_{member}" {v}, "{name}_Interp" 1 }}"#))
        .collect();
    format!("[ {} ]", items.join(", "))
}

/// The rampShader plane tilted by [`TILT_DEG`] (facing ratios 0.45–0.99 over the image)
/// over the unlit plane of colour [`BEHIND`], seen from above; no light. With `refract`
/// the rampShader refracts (`refractions` on, index 1.5): the rays bend towards the
/// plane behind, whose colour is the same everywhere.
fn scene(refract: bool) -> String {
    let view = support::maya_view::top_down(SIDE);
    let a = TILT_DEG.to_radians();
    let w = Vec3A::new(0.0, -a.sin(), a.cos()) * 50.0;
    let corner = |sx: f32, sw: f32| {
        let p = Vec3A::new(50.0 * sx, 0.0, 0.0) + w * sw;
        format!("{} {} {}", p.x, p.y, p.z)
    };
    let mut corners = [corner(-1.5, -1.0), corner(1.5, -1.0), corner(0.0, 1.0)];
    if refract {
        // Facing the camera, so that the rays enter the index 1.5 (from its back they
        // would leave it and reflect totally beyond 41.8°).
        corners.swap(0, 1);
    }
    let corners = corners.join("  ");
    format!(
        r#"
$include "mayabase.mi"
{view}
shader "mat" "maya_rampshader" ("colorInput" 0, "diffuse" 0, "color" {color}, "specularity" 0,
    "reflectivity" {reflectivity}, "transparency" {transparency}, "incandescence" {incandescence}{refraction})
material "m" "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "plane" group {corners}  v 0 v 1 v 2 c "m" 0 1 2 end group end object
instance "plane_inst" "plane" end instance
shader "bg" "maya_surfaceshader" ("outColor" {bx} {by} {bz})
material "mb" opaque "maya_shadingengine" ("surfaceShader" = "bg.outColor") end material
object "under" group -1000 -30 1000  1000 -30 1000  1000 -30 -1000  -1000 -30 -1000
    v 0 v 1 v 2 v 3 c "mb" 0 1 2 3 end group end object
instance "under_inst" "under" end instance
instgroup "root" "cam_inst" "plane_inst" "under_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        color = ramp("color", "Color", &[(0.0, "0 0 0")]),
        reflectivity = ramp("reflectivity", "FloatValue", &[(0.0, "0")]),
        transparency = if refract {
            ramp("transparency", "Color", &[(0.0, "0.9 0.9 0.9"), (1.0, "0.3 0.3 0.3")])
        } else {
            ramp("transparency", "Color", &[(0.0, "1 1 1"), (1.0, "0 0 0")])
        },
        incandescence = ramp("incandescence", "Color", &[(0.0, "1 0.5 0"), (1.0, "0 0.5 1")]),
        bx = BEHIND.x,
        by = BEHIND.y,
        bz = BEHIND.z,
        refraction = if refract { r#", "refractions" on, "refractiveIndex" 1.5, "refractionLimit" 6"# } else { "" },
    )
}

/// A tilted rampShader plane whose transparency (1 − f, grey) and incandescence
/// ((1, 0.5, 0) → (0, 0.5, 1)) ramps run over the facing ratio f, over an unlit plane
/// of colour B: incandescence(f) ⊙ (1 − T(f)) + T(f) ⊙ B per ray. The classic engine
/// gives the formula at every pixel within 2 % of its brightest channel + 1e-3 (16
/// jittered samples against 16 × 16 points); the path engine (256 samples per pixel,
/// a stochastic cut-out) the formula's mean over each image row and over the image,
/// each within four standard errors (of the pixels' differences from the formula) +
/// 1e-3. Before, the path engine took both ramps at f = 1 — an opaque plane of
/// incandescence (0, 0.5, 1) — which differs from the formula's image mean by more
/// than 20 % in red and blue (asserted).
#[test]
fn ramp_shader_transparency_and_incandescence_follow_the_view_in_both_engines() {
    let text = scene(false);
    let want: Vec<Vec3A> = (0..SIDE * SIDE).map(|i| formula(i % SIDE, i / SIDE, false, false)).collect();
    let n = want.len() as f32;
    let want_mean = want.iter().fold(Vec3A::ZERO, |s, p| s + *p) / n;
    let head_on = (0..SIDE * SIDE).fold(Vec3A::ZERO, |s, i| s + formula(i % SIDE, i / SIDE, true, false)) / n;
    println!("formula mean {want_mean}, with the ramps at 1 {head_on}");
    for k in [0, 2] {
        assert!((want_mean[k] - head_on[k]).abs() > 0.2 * want_mean[k], "{want_mean} vs {head_on}");
    }
    for (i, p) in pixels(&text, EngineKind::Classic, 16).iter().enumerate() {
        let tol = 0.02 * want[i].max_element() + 1e-3;
        assert!((*p - want[i]).abs().max_element() < tol, "classic pixel {i}: {p} vs {}", want[i]);
    }
    let path = pixels(&text, EngineKind::Path, 256);
    let diffs: Vec<Vec3A> = path.iter().zip(&want).map(|(p, w)| *p - *w).collect();
    let check = |name: String, d: &[Vec3A]| {
        let m = d.len() as f32;
        let mean = d.iter().fold(Vec3A::ZERO, |s, x| s + *x) / m;
        let var = d.iter().fold(Vec3A::ZERO, |s, x| s + (*x - mean) * (*x - mean)) / (m - 1.0);
        let error = (var / m).powf(0.5);
        for k in 0..3 {
            assert!(mean[k].abs() < 4.0 * error[k] + 1e-3, "path {name}: off the formula by {mean} ± {error}");
        }
    };
    for row in 0..SIDE {
        check(format!("row {row}"), &diffs[row * SIDE..(row + 1) * SIDE]);
    }
    check("image".into(), &diffs);
}

/// The same tilted rampShader plane refracting (`refractions` on, index 1.5) with
/// T(f) = 0.9 − 0.6 f: the classic shader weighs its refraction ray by T(f) at each
/// ray's facing ratio, so over the uniform plane behind each ray shows
/// incandescence(f) ⊙ (1 − T(f)) + T(f) ⊙ B. Both engines give the formula at every
/// pixel within 2 % of its brightest channel + 1e-3 (the path engine's rays all hit the
/// plane and refract: no noise but the pixel's sample positions). Before, the path engine
/// took both ramps at f = 1 for a refracting rampShader (T = 0.3, incandescence
/// (0, 0.5, 1)), off the formula's image mean by more than 20 % in red (asserted).
#[test]
fn a_refracting_ramp_shader_weighs_its_refraction_by_the_facing_ratio_in_both_engines() {
    let text = scene(true);
    let want: Vec<Vec3A> = (0..SIDE * SIDE).map(|i| formula(i % SIDE, i / SIDE, false, true)).collect();
    let n = want.len() as f32;
    let want_mean = want.iter().fold(Vec3A::ZERO, |s, p| s + *p) / n;
    let head_on = (0..SIDE * SIDE).fold(Vec3A::ZERO, |s, i| s + formula(i % SIDE, i / SIDE, true, true)) / n;
    println!("formula mean {want_mean}, with the ramps at 1 {head_on}");
    assert!((want_mean.x - head_on.x).abs() > 0.2 * want_mean.x, "{want_mean} vs {head_on}");
    for (name, engine) in [("classic", EngineKind::Classic), ("path", EngineKind::Path)] {
        for (i, p) in pixels(&text, engine, 16).iter().enumerate() {
            let tol = 0.02 * want[i].max_element() + 1e-3;
            assert!((*p - want[i]).abs().max_element() < tol, "{name} pixel {i}: {p} vs {}", want[i]);
        }
    }
}

/// The incandescence E of the opaque lambert under the rampShader layer.
const UNDER: Vec3A = Vec3A::new(0.1, 0.6, 0.3);

/// The rampShader of the first test as the top layer of a layeredShader over an opaque
/// black lambert of incandescence E ([`UNDER`]): the classic layered shader composites the
/// rampShader's own colour incandescence(f) ⊙ (1 − T(f)) over the lambert by T(f) at each
/// ray's facing ratio, incandescence(f) ⊙ (1 − T(f)) + T(f) ⊙ E. Both engines give that
/// at every pixel within 2 % of its brightest channel + 1e-3 (the stack is opaque and
/// only emits: no noise but the pixel's sample positions). Before, the path engine took
/// the layer's ramps at f = 1 — incandescence (0, 0.5, 1) alone — off the formula's image
/// mean by more than 20 % in red and blue (asserted).
#[test]
fn a_ramp_shader_layer_follows_the_view_in_a_layered_shader_in_both_engines() {
    let text = scene(false).replace(r#"shader "mat" "maya_rampshader""#, r#"shader "ramp" "maya_rampshader""#).replace(
        r#"material "m" "maya_shadingengine""#,
        &format!(
            r#"shader "lower" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "incandescence" {} {} {})
shader "mat" "maya_layeredshader" ("inputs" [
    {{ "color" = "ramp.outColor", "transparency" = "ramp.outTransparency" }},
    {{ "color" = "lower.outColor", "transparency" = "lower.outTransparency" }} ])
material "m" "maya_shadingengine""#,
            UNDER.x, UNDER.y, UNDER.z
        ),
    );
    let layered = |f: f32| {
        let t = transparency(f, false);
        incandescence(f) * (Vec3A::ONE - t) + t * UNDER
    };
    // The formula at each of 16 × 16 rays over a pixel (or at f = 1: `head_on`).
    let formula = |col: usize, row: usize, head_on: bool| {
        let a = TILT_DEG.to_radians();
        let n = Vec3A::new(0.0, a.cos(), a.sin());
        let points: Vec<Vec3A> = ground_points(SIDE, col, row, 16).collect();
        points
            .iter()
            .fold(Vec3A::ZERO, |s, p| s + layered(if head_on { 1.0 } else { n.dot((*p - EYE).normalize()).abs() }))
            / points.len() as f32
    };
    let want: Vec<Vec3A> = (0..SIDE * SIDE).map(|i| formula(i % SIDE, i / SIDE, false)).collect();
    let n = want.len() as f32;
    let want_mean = want.iter().fold(Vec3A::ZERO, |s, p| s + *p) / n;
    let head_on = (0..SIDE * SIDE).fold(Vec3A::ZERO, |s, i| s + formula(i % SIDE, i / SIDE, true)) / n;
    println!("formula mean {want_mean}, with the ramps at 1 {head_on}");
    for k in [0, 2] {
        assert!((want_mean[k] - head_on[k]).abs() > 0.2 * want_mean[k], "{want_mean} vs {head_on}");
    }
    for (name, engine) in [("classic", EngineKind::Classic), ("path", EngineKind::Path)] {
        for (i, p) in pixels(&text, engine, 16).iter().enumerate() {
            let tol = 0.02 * want[i].max_element() + 1e-3;
            assert!((*p - want[i]).abs().max_element() < tol, "{name} pixel {i}: {p} vs {}", want[i]);
        }
    }
}
