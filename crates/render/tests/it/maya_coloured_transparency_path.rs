//! Maya's transparency per channel in the path engine: a coloured transparency T lets
//! through T ⊙ what lies behind (camera and shadow rays alike), and a fully transparent
//! material still shows its highlight and reflection, which Maya adds on top of the
//! transparency (`material::maya`'s cut-out tint and least coverage; `maya::material`).

use crate::support;
use crate::support::maya_view::{mean_and_error, pixels};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 16;

/// Half the side of the ground the image shows (x and z in ±`HALF` at y = 0).
const HALF: f32 = 2.4;

/// The camera's position (`support::maya_view::top_down`).
const EYE: Vec3A = Vec3A::new(0.0, 4.0, 0.0);

/// The directional light's direction (x, y; normalised in the scene) and intensity.
const LIGHT: (f32, f32) = (0.25, -0.968);
const INTENSITY: f32 = 1.2;

/// A Maya ground at y = 0 whose shader is `material` (named "mat"), over a plane at
/// y = −1 whose shader is `under` (named "bg"), under the directional light, seen from
/// above at `SIDE`² pixels; the light casts raytraced shadows.
fn scene(material: &str, under: &str) -> String {
    let view = support::maya_view::top_down(SIDE);
    let d = Vec3A::new(LIGHT.0, LIGHT.1, 0.0).normalize();
    format!(
        r#"
$include "mayabase.mi"
{view}
light "l" "maya_directionallight" ("intensity" {INTENSITY}, "useRayTraceShadows" on) direction {} {} 0 end light
instance "l_inst" "l" end instance
{material}
material "m" "maya_shadingengine" ("surfaceShader" = "mat.outColor")
    shadow "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "ground" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
{under}
material "mb" opaque "maya_shadingengine" ("surfaceShader" = "bg.outColor") end material
object "under" group -5 -1 5  5 -1 5  5 -1 -5  -5 -1 -5  v 0 v 1 v 2 v 3 c "mb" 0 1 2 3 end group end object
instance "under_inst" "under" end instance
instgroup "root" "cam_inst" "l_inst" "ground_inst" "under_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        d.x, d.y
    )
}

/// The cosine of the light's angle to the ground's normal.
fn cos_light() -> f32 {
    -Vec3A::new(LIGHT.0, LIGHT.1, 0.0).normalize().y
}

/// A lambert of transparency (1, 0.5, 0), colour c = (0.5, 0, 0.7) and diffuse 1 over
/// a white lambert, both under the light: what the camera sees is, per channel,
/// (1 − T) ⊙ c·I·cos θ + T ⊙ (T ⊙ I·cos θ) — the plane below is lit through the
/// transparent one, whose shadow filters the light by T too. The classic engine gives
/// it at every pixel within 1e-3; the path engine's image mean within four standard
/// errors of its 256 pixels (1 024 samples each) plus 1e-3 (measured: see the output).
/// Before, the path engine let the mean of T, ½, through in every channel: red would
/// have been 0.58 instead of 1.16.
#[test]
fn a_coloured_transparency_filters_each_channel_in_both_engines() {
    let t = Vec3A::new(1.0, 0.5, 0.0);
    // No green in c: with it the planes would pass light between them in green, which
    // the path engine's indirect light carries and the classic engine (no final
    // gathering) does not.
    let c = Vec3A::new(0.5, 0.0, 0.7);
    let text = scene(
        &format!(
            r#"shader "mat" "maya_lambert" ("color" {} {} {}, "diffuse" 1, "transparency" {} {} {})"#,
            c.x, c.y, c.z, t.x, t.y, t.z
        ),
        r#"shader "bg" "maya_lambert" ("color" 1 1 1, "diffuse" 1)"#,
    );
    let lit = INTENSITY * cos_light();
    let want = (Vec3A::ONE - t) * c * lit + t * t * lit;
    for (i, p) in pixels(&text, EngineKind::Classic, 1).iter().enumerate() {
        assert!((*p - want).abs().max_element() < 1e-3, "classic pixel {i}: {p} vs formula {want}");
    }
    let (mean, error) = mean_and_error(&pixels(&text, EngineKind::Path, 1024));
    println!("path {mean} ± {error}, formula {want}");
    for k in 0..3 {
        assert!((mean[k] - want[k]).abs() < 4.0 * error[k] + 1e-3, "channel {k}: path {mean} ± {error} vs {want}");
    }
}

/// The classic formula of a fully transparent blinn (specularColor s = 0.5, eccentricity
/// 0.3, roll-off 0.7, reflectivity r = 0.4, `reflectedColor` R, `reflectionRolloff` on)
/// over an unlit plane of colour B, averaged over the ground under pixel (`col`, `row`)
/// (16 × 16 points): s·I·H(n, v, l) + r·s·F(N·V)·R + B.
fn transparent_blinn(reflected: Vec3A, behind: Vec3A, col: usize, row: usize) -> Vec3A {
    const SUB: usize = 16;
    let pixel = 2.0 * HALF / SIDE as f32;
    let l = -Vec3A::new(LIGHT.0, LIGHT.1, 0.0).normalize();
    let mut sum = Vec3A::ZERO;
    for a in 0..SUB {
        for b in 0..SUB {
            let x = -HALF + (col as f32 + (a as f32 + 0.5) / SUB as f32) * pixel;
            let z = -HALF + (row as f32 + (b as f32 + 0.5) / SUB as f32) * pixel;
            let v = (EYE - Vec3A::new(x, 0.0, z)).normalize();
            let highlight = 0.5 * maya::specular::blinn(Vec3A::Y, v, l, 0.3, 0.7) * INTENSITY;
            sum += Vec3A::splat(highlight) + 0.4 * 0.5 * maya::specular::schlick(0.7, v.y) * reflected;
        }
    }
    sum / (SUB * SUB) as f32 + behind
}

/// A blinn of transparency 1 (colour 0.6 0.5 0.4: faded away) over an unlit
/// surfaceShader plane: Maya shows its highlight and its reflection of `reflectedColor`
/// on top of the plane. The classic engine gives the formula at every pixel within 1 %;
/// the path engine the formula's mean over the 3 × 3 pixels about the highlight's peak
/// (the highlight more than half of it) and over the image, each within four standard
/// errors plus 0.5 %. Before, the path engine showed neither (a warning said so).
#[test]
fn a_fully_transparent_blinn_shows_its_highlight_in_both_engines() {
    let reflected = Vec3A::new(0.3, 0.2, 0.1);
    let behind = Vec3A::new(0.2, 0.3, 0.4);
    let text = scene(
        &format!(
            r#"shader "mat" "maya_blinn" ("color" 0.6 0.5 0.4, "diffuse" 1, "eccentricity" 0.3, "specularRollOff" 0.7,
    "specularColor" 0.5 0.5 0.5, "reflectivity" 0.4, "reflectedColor" {} {} {}, "transparency" 1 1 1)"#,
            reflected.x, reflected.y, reflected.z
        ),
        &format!(r#"shader "bg" "maya_surfaceshader" ("outColor" {} {} {})"#, behind.x, behind.y, behind.z),
    );
    let want: Vec<Vec3A> = (0..SIDE * SIDE).map(|i| transparent_blinn(reflected, behind, i % SIDE, i / SIDE)).collect();
    for (i, (got, want)) in pixels(&text, EngineKind::Classic, 4).iter().zip(&want).enumerate() {
        assert!(((*got - *want).abs() / *want).max_element() < 0.01, "classic pixel {i}: {got} vs formula {want}");
    }
    let path = pixels(&text, EngineKind::Path, 1024);
    let peak = (0..want.len()).max_by(|&a, &b| want[a].x.total_cmp(&want[b].x)).expect("pixels");
    let (row, col) = ((peak / SIDE).clamp(1, SIDE - 2), (peak % SIDE).clamp(1, SIDE - 2));
    let block: Vec<usize> = (row - 1..=row + 1).flat_map(|r| (col - 1..=col + 1).map(move |k| r * SIDE + k)).collect();
    let mean = |img: &[Vec3A], ids: &[usize]| ids.iter().fold(Vec3A::ZERO, |m, &i| m + img[i]) / ids.len() as f32;
    let all: Vec<usize> = (0..want.len()).collect();
    for (name, ids) in [("peak", &block), ("image", &all)] {
        let (got, expect) = (mean(&path, ids), mean(&want, ids));
        // The standard error of the path engine's mean from its pixels' deviations.
        let dev: Vec<Vec3A> = ids.iter().map(|&i| path[i] - want[i]).collect();
        let (_, error) = mean_and_error(&dev);
        println!("{name}: path {got} ± {error}, formula {expect}");
        if name == "peak" {
            assert!(expect.x - behind.x > expect.x / 2.0, "the peak is a highlight: {expect}");
        }
        for k in 0..3 {
            assert!(
                (got[k] - expect[k]).abs() < 4.0 * error[k] + 0.005 * expect[k],
                "{name}, channel {k}: path {got} ± {error} vs formula {expect}"
            );
        }
    }
}
