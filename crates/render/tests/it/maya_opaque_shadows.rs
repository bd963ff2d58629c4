//! mental ray's `opaque` material flag in both engines: shadow rays stop at a material
//! marked `opaque` without its transparency or shadow shader (Maya's exports write it on
//! every shading group); unmarked, a transparent material lets T of the light through.

use crate::support;
use crate::support::maya_view::{mean_and_error, pixels};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 16;

/// The blocker's (coloured) transparency.
const T: Vec3A = Vec3A::new(0.6, 0.4, 0.2);

/// A lambert ground at y = 0 lit by a point light 3 above it (raytraced shadows, no
/// decay), seen from above; with `blocker` (`Some(marked)`) a black transparent Maya
/// lambert plane of transparency [`T`] at y = 1.5 between them, hidden from the camera
/// (`visible off`), its material marked `opaque` or not (with a shadow shader either way,
/// as Maya writes it).
fn scene(blocker: Option<bool>) -> String {
    let view = support::maya_view::top_down(SIDE);
    let blocker_text = match blocker {
        Some(marked) => format!(
            r#"shader "glass" "maya_lambert" ("color" 0 0 0, "diffuse" 1, "transparency" {} {} {})
material "g" {} "maya_shadingengine" ("surfaceShader" = "glass.outColor")
    shadow "maya_shadingengine" ("surfaceShader" = "glass.outColor") end material
object "blocker" group -5 1.5 5  5 1.5 5  5 1.5 -5  -5 1.5 -5  v 0 v 1 v 2 v 3 c "g" 0 1 2 3 end group end object
instance "blocker_inst" "blocker" visible off end instance"#,
            T.x,
            T.y,
            T.z,
            if marked { "opaque" } else { "" }
        ),
        None => String::new(),
    };
    let member = if blocker.is_some() { r#""blocker_inst""# } else { "" };
    format!(
        r#"
$include "mayabase.mi"
{view}
light "pt" "maya_pointlight" ("intensity" 2, "decayRate" 0, "useRayTraceShadows" on) origin 0 0 0 end light
instance "pt_inst" "pt" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 -3 0 1 end instance
shader "lam" "maya_lambert" ("color" 0.8 0.7 0.6, "diffuse" 1)
material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor")
    shadow "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
object "ground" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
{blocker_text}
instgroup "root" "cam_inst" "pt_inst" "ground_inst" {member} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The blocker marked `opaque` casts a black shadow in both engines (every pixel below
/// 1e-6), though its material is transparent and has a shadow shader; unmarked, the
/// ground receives T ⊙ the unblocked light: the classic engine's pixels are T ⊙ those
/// without the blocker within 1e-4 + 0.1 %, the path engine's image mean (64 samples per
/// pixel: its shadow rays pass the blocker by its coverage) T ⊙ the unblocked mean within
/// four standard errors + 1e-3 per channel. Before, the path engine let the marked
/// blocker's T through, and so did the classic
/// engine (it ran the shadow shader).
#[test]
fn an_opaque_material_blocks_shadow_rays_in_both_engines() {
    for engine in [EngineKind::Classic, EngineKind::Path] {
        let spp = if engine == EngineKind::Classic { 4 } else { 64 };
        let lit = pixels(&scene(None), engine, spp);
        let through = pixels(&scene(Some(false)), engine, spp);
        let marked = pixels(&scene(Some(true)), engine, spp);
        let (lit_mean, _) = mean_and_error(&lit);
        let (through_mean, through_error) = mean_and_error(&through);
        let (marked_mean, _) = mean_and_error(&marked);
        println!("{engine:?}: unblocked {lit_mean}, through the blocker {through_mean} ± {through_error}, opaque {marked_mean}");
        assert!(lit_mean.min_element() > 0.1, "{engine:?}: the ground is lit: {lit_mean}");
        for (i, p) in marked.iter().enumerate() {
            assert!(p.max_element() < 1e-6, "{engine:?}, pixel {i}: {p} behind an opaque blocker");
        }
        if engine == EngineKind::Classic {
            for (i, (p, l)) in through.iter().zip(&lit).enumerate() {
                let want = T * *l;
                assert!(
                    (*p - want).abs().max_element() < 1e-4 + 1e-3 * want.max_element(),
                    "pixel {i}: {p} vs T ⊙ {l}"
                );
            }
        } else {
            let want = T * lit_mean;
            for k in 0..3 {
                assert!(
                    (through_mean[k] - want[k]).abs() < 4.0 * through_error[k] + 1e-3,
                    "channel {k}: {through_mean} ± {through_error} vs T ⊙ unblocked {want}"
                );
            }
        }
    }
}
