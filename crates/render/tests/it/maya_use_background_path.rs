//! Maya's useBackground as a shadow-catching matte in both engines, against the closed
//! form: a ground plane with the matte under a point light, an opaque strip between
//! them, over a constant background B. Unshadowed ground shows B, shadowed ground
//! B (1 − shadowMask), and `reflectivity` r × `specularColor` s adds r s ⊙ B where the
//! mirror ray sees the background (`crates/maya/src/matte.rs`,
//! `crates/render/src/integrator/matte.rs`).

use crate::support;
use crate::support::maya_view::{ground_points, mean_and_error, pixels};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 16;

/// The background.
const BACKGROUND: Vec3A = Vec3A::new(0.2, 0.4, 0.6);

/// The ground seen from above with the matte of `shadowMask` `mask`, `reflectivity`
/// `r` and white `specularColor`, a point light at (−1, 3, 0) with raytraced shadows and
/// an opaque strip at y = 1.5 over x ∈ [−0.5, 0.5]: it shadows the ground over
/// x ∈ [0, 2] and hides it from the camera over x ∈ [−0.8, 0.8]; the mirror rays of the
/// ground seen at |x| > 0.4 miss it.
fn scene(mask: f32, r: f32) -> String {
    let view = support::maya_view::top_down(SIDE).replace("end camera", r#"environment = "sky" end camera"#);
    let b = BACKGROUND;
    format!(
        r#"
$include "mayabase.mi"
shader "sky" "mib_color_mix" ("num" 0, "color_base" {} {} {} 1)
{view}
light "l" "maya_pointlight" ("intensity" 1, "useRayTraceShadows" on) origin -1 3 0 end light
instance "l_inst" "l" end instance
shader "bg" "maya_usebackground" ("shadowMask" {mask}, "reflectivity" {r}, "specularColor" 1 1 1)
material "m" "maya_shadingengine" ("surfaceShader" = "bg.outColor") end material
shader "lam" "maya_lambert" ()
material "blocker" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material
object "ground" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "ground_inst" "ground" end instance
object "strip" group -0.5 1.5 5  0.5 1.5 5  0.5 1.5 -5  -0.5 1.5 -5  v 0 v 1 v 2 v 3 c "blocker" 0 1 2 3 end group end object
instance "strip_inst" "strip" end instance
instgroup "root" "cam_inst" "l_inst" "ground_inst" "strip_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        b.x, b.y, b.z
    )
}

/// The pixels of `px` whose ground point (the pixel's centre) has x in `range`.
fn columns(px: &[Vec3A], range: std::ops::Range<f32>) -> Vec<Vec3A> {
    let mut out = Vec::new();
    for row in 0..SIDE {
        for col in 0..SIDE {
            let centre = ground_points(SIDE, col, row, 1).next().expect("a point");
            if range.contains(&centre.x) {
                out.push(px[row * SIDE + col]);
            }
        }
    }
    out
}

/// shadowMask 0.8, reflectivity 0 and 0.5: in both engines the unshadowed ground
/// (x ∈ [−2.4, −1]) is B (1 + r) and the shadowed ground (x ∈ [1, 1.8]) B (1 − 0.8 + r),
/// each region's mean within 4 standard errors + 1e-3 per channel.
#[test]
fn the_matte_shows_the_background_and_catches_the_shadow_in_both_engines() {
    for r in [0.0, 0.5] {
        let text = scene(0.8, r);
        for (engine, spp) in [(EngineKind::Classic, 4), (EngineKind::Path, 16)] {
            let px = pixels(&text, engine, spp);
            for (range, want) in [(-2.4..-1.0, BACKGROUND * (1.0 + r)), (1.0..1.8, BACKGROUND * (0.2 + r))] {
                let region = columns(&px, range.clone());
                assert!(region.len() >= 2 * SIDE, "{engine:?}: {} pixels in {range:?}", region.len());
                let (m, e) = mean_and_error(&region);
                println!("{engine:?} r {r} x in {range:?}: {m} ± {e}, want {want}");
                let off = (m - want).abs();
                let bound = 4.0 * e + Vec3A::splat(1e-3);
                assert!(off.cmple(bound).all(), "{engine:?} r {r} x in {range:?}: {m} ± {e} vs {want}");
            }
        }
    }
}
