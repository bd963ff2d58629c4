//! A layeredShader that rays pass through (its layers' transparencies do not multiply to
//! black) in the path engine: its hits carry the stack's colours divided by its coverage,
//! as a transparent lambert's do, so that over all rays it shows what the classic
//! layeredShader composites (`material::maya`'s layeredShader, `maya::layered_shader`).

use crate::support;
use crate::support::maya_view::{mean_and_error, pixels};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 16;

/// The colour of the unlit plane behind.
const BEHIND: Vec3A = Vec3A::new(0.2, 0.3, 0.4);

/// Two black lamberts of incandescence `ea` and `eb` and grey transparencies `ta` and
/// `tb` stacked in a layeredShader on the plane y = 0, over the unlit plane of colour
/// [`BEHIND`] at y = −1, seen from above; no light.
fn scene(ea: Vec3A, ta: f32, eb: Vec3A, tb: f32) -> String {
    let view = support::maya_view::top_down(SIDE);
    format!(
        r#"
$include "mayabase.mi"
{view}
shader "a" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "incandescence" {} {} {}, "transparency" {ta} {ta} {ta})
shader "b" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "incandescence" {} {} {}, "transparency" {tb} {tb} {tb})
shader "stack" "maya_layeredshader" ("inputs" [
    {{ "color" = "a.outColor", "transparency" = "a.outTransparency" }},
    {{ "color" = "b.outColor", "transparency" = "b.outTransparency" }} ])
material "m" "maya_shadingengine" ("surfaceShader" = "stack.outColor") end material
object "top" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "top_inst" "top" end instance
shader "bg" "maya_surfaceshader" ("outColor" {} {} {})
material "mb" opaque "maya_shadingengine" ("surfaceShader" = "bg.outColor") end material
object "back" group -50 -1 50  50 -1 50  50 -1 -50  -50 -1 -50  v 0 v 1 v 2 v 3 c "mb" 0 1 2 3 end group end object
instance "back_inst" "back" end instance
instgroup "root" "cam_inst" "top_inst" "back_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        ea.x, ea.y, ea.z, eb.x, eb.y, eb.z, BEHIND.x, BEHIND.y, BEHIND.z
    )
}

/// Two half-transparent incandescent lamberts stacked over an unlit plane B: the classic
/// layeredShader shows Ea·(1 − Ta) + Ta·Eb·(1 − Tb) + Ta·Tb·B at every pixel (within
/// 1e-4), and the path engine, which lets a quarter of the rays through, that in its
/// image mean within four standard errors + 1e-3. Before, its hits carried the stack's
/// colours undivided by the coverage 0.75: a mean off by a quarter of the stack's own
/// share (asserted to exceed the tolerance).
#[test]
fn a_transparent_layered_stack_shows_its_layers_and_what_lies_behind_in_both_engines() {
    let (ea, ta, eb, tb) = (Vec3A::new(0.8, 0.4, 0.1), 0.5, Vec3A::new(0.1, 0.5, 0.9), 0.5);
    let own = ea * (1.0 - ta) + ta * eb * (1.0 - tb);
    let want = own + ta * tb * BEHIND;
    let before = own * (1.0 - ta * tb) + ta * tb * BEHIND;
    let text = scene(ea, ta, eb, tb);
    for (i, p) in pixels(&text, EngineKind::Classic, 4).iter().enumerate() {
        assert!((*p - want).abs().max_element() < 1e-4, "classic pixel {i}: {p} vs {want}");
    }
    let (mean, error) = mean_and_error(&pixels(&text, EngineKind::Path, 64));
    println!("path {mean} ± {error}, formula {want}, undivided {before}");
    for k in 0..3 {
        let tol = 4.0 * error[k] + 1e-3;
        assert!((mean[k] - want[k]).abs() < tol, "path mean {mean} ± {error} vs formula {want}");
        assert!((before[k] - want[k]).abs() > tol, "channel {k}: the undivided stack is within the tolerance");
    }
}
