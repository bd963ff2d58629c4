//! Maya's `emitDiffuse` and `emitSpecular` in the path engine (`material::emission::maya::
//! LightLobes`, `crates/render/src/integrator/light_lobes.rs`): a light with `emitDiffuse`
//! off lights only the highlights (as the classic engine's `maya_analytic.rs`
//! `emit_diffuse_and_emit_specular`), one with `emitSpecular` off only the diffuse part.

use crate::support;
use crate::support::maya_view::{around_peak, mean, mean_and_error, pixels};

use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 32;

/// A blinn ground (colour 0.6 0.5 0.4, diffuse 0.8, eccentricity 0.3, roll-off 0.7,
/// specular 0.5) or, for `lambert`, a lambert of the same diffuse colour, under a point
/// light at (0.6, 2, 0) of intensity 1.5 with the light parameters `more`.
fn scene(lambert: bool, more: &str) -> String {
    let view = support::maya_view::top_down(SIDE);
    let material = if lambert {
        r#"shader "mat" "maya_lambert" ("color" 0.6 0.5 0.4, "diffuse" 0.8)"#
    } else {
        r#"shader "mat" "maya_blinn" ("color" 0.6 0.5 0.4, "diffuse" 0.8, "eccentricity" 0.3,
    "specularRollOff" 0.7, "specularColor" 0.5 0.5 0.5, "reflectivity" 0)"#
    };
    format!(
        r#"
$include "mayabase.mi"
{view}
light "l" "maya_pointlight" ("intensity" 1.5, "decayRate" 0{more}) origin 0.6 2 0 end light
instance "l_inst" "l" end instance
{material}
material "m" opaque "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
object "ground" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
instgroup "root" "cam_inst" "l_inst" "ground_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// With `emitDiffuse` off a lambert is black in the path engine (every pixel below 1e-6)
/// and a blinn shows its highlight alone: the 5 × 5 pixels about the classic engine's
/// peak agree with the classic engine's (their mean paired difference within 4 standard
/// errors + 1 % of the classic mean, per channel). With `emitSpecular` off the highlight
/// vanishes: the blinn's image mean equals the lambert's within 0.5 %, while with both on
/// its peak is more than 10 % above the lambert's there.
#[test]
fn emit_diffuse_and_emit_specular_pick_the_lobes_in_the_path_engine() {
    let off = r#", "emitDiffuse" off"#;
    for p in pixels(&scene(true, off), EngineKind::Path, 16) {
        assert!(p.max_element() < 1e-6, "a lambert under a specular-only light: {p}");
    }
    let text = scene(false, off);
    let (classic, path) = (pixels(&text, EngineKind::Classic, 16), pixels(&text, EngineKind::Path, 16));
    let ((col, row), _, c) = around_peak(SIDE, &path, &classic);
    assert!(c.x > 0.01, "the classic highlight: {c}");
    let mut diffs = Vec::new();
    for r in row - 2..=row + 2 {
        for k in col - 2..=col + 2 {
            diffs.push(path[r * SIDE + k] - classic[r * SIDE + k]);
        }
    }
    let (d, e) = mean_and_error(&diffs);
    println!("emitDiffuse off: peak at ({col}, {row}): classic {c}, path − classic {d} ± {e}");
    assert!(d.abs().cmple(4.0 * e + 0.01 * c).all(), "path − classic {d} ± {e} vs classic {c}");

    let lambert = pixels(&scene(true, ""), EngineKind::Path, 16);
    let dull = pixels(&scene(false, r#", "emitSpecular" off"#), EngineKind::Path, 16);
    let shiny = pixels(&scene(false, ""), EngineKind::Path, 16);
    let (ml, md) = (mean(&lambert), mean(&dull));
    println!("emitSpecular off: blinn mean {md}, lambert mean {ml}");
    assert!(((md - ml).abs()).cmple(0.005 * ml).all(), "{md} vs {ml}");
    let (_, peak, base) = around_peak(SIDE, &shiny, &shiny);
    let (_, lam, _) = around_peak(SIDE, &lambert, &shiny);
    println!("both on: blinn peak {peak}, lambert there {lam}");
    assert!(peak.x > 1.1 * lam.x && base == peak, "the highlight shows with both on: {peak} vs {lam}");
}
