//! layeredShader stacks the path engine mixes per channel and per hit, against the
//! classic layeredShader (`material::maya`'s layeredShader and `view_layers`,
//! `maya::layered_shader`): a coloured transparency weights the layers per channel, and
//! a stack with a view-dependent rampShader layer over a refracting lambert follows each
//! hit's facing ratio.

use crate::support;
use crate::support::maya_view::{mean, mean_and_error, pixels};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 16;

/// The colour of the unlit plane behind.
const BEHIND: Vec3A = Vec3A::new(0.2, 0.3, 0.4);

/// The stack `layers` (shader statements, then the `inputs` elements) on a plane
/// through the origin tilted 30° about x (facing ratios 0.45–0.99 over the image) over
/// the unlit plane of colour [`BEHIND`] at y = −30, seen from above; no light.
fn scene(shaders: &str, inputs: &str) -> String {
    let view = support::maya_view::top_down(SIDE);
    let a = 30f32.to_radians();
    let w = Vec3A::new(0.0, -a.sin(), a.cos()) * 50.0;
    let corner = |sx: f32, sw: f32| {
        let p = Vec3A::new(50.0 * sx, 0.0, 0.0) + w * sw;
        format!("{} {} {}", p.x, p.y, p.z)
    };
    // Facing the camera, so that refracted rays enter the index (see
    // `maya_ramp_transparency_path`).
    let corners = [corner(1.5, -1.0), corner(-1.5, -1.0), corner(0.0, 1.0)].join("  ");
    format!(
        r#"
$include "mayabase.mi"
{view}
{shaders}
shader "stack" "maya_layeredshader" ("inputs" [ {inputs} ])
material "m" "maya_shadingengine" ("surfaceShader" = "stack.outColor") end material
object "plane" group {corners}  v 0 v 1 v 2 c "m" 0 1 2 end group end object
instance "plane_inst" "plane" end instance
shader "bg" "maya_surfaceshader" ("outColor" {} {} {})
material "mb" opaque "maya_shadingengine" ("surfaceShader" = "bg.outColor") end material
object "under" group -1000 -30 1000  1000 -30 1000  1000 -30 -1000  -1000 -30 -1000
    v 0 v 1 v 2 v 3 c "mb" 0 1 2 3 end group end object
instance "under_inst" "under" end instance
instgroup "root" "cam_inst" "plane_inst" "under_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        BEHIND.x, BEHIND.y, BEHIND.z
    )
}

/// The `inputs` element of the material `name`.
fn layer(name: &str) -> String {
    format!(r#"{{ "color" = "{name}.outColor", "transparency" = "{name}.outTransparency" }}"#)
}

/// The path engine's image mean against the classic engine's, per channel within 2 %.
fn agree(name: &str, text: &str) {
    let classic = mean(&pixels(text, EngineKind::Classic, 4));
    let (path, error) = mean_and_error(&pixels(text, EngineKind::Path, 64));
    println!("{name}: classic {classic}, path {path} ± {error}");
    for k in 0..3 {
        assert!(classic[k] > 0.02, "{name}: classic {classic}");
        assert!((path[k] / classic[k] - 1.0).abs() < 0.02, "{name}: path {path} vs classic {classic}");
    }
}

/// An incandescent black lambert of transparency (0.1, 0.5, 0.9) over one of grey
/// transparency 0.4, over the unlit plane B: the classic stack shows, per channel,
/// Ea ⊙ (1 − Ta) + Ta ⊙ Eb · 0.6 + Ta · 0.4 ⊙ B at every pixel (within 1e-4); the path
/// engine's image mean is the classic one within 2 % per channel. Weighted by the mean
/// transparency (0.5) instead, the red and blue channels were off by 10–40 %.
#[test]
fn a_coloured_transparency_weights_the_layers_per_channel() {
    let (ea, eb) = (Vec3A::new(0.8, 0.6, 0.4), Vec3A::new(0.3, 0.5, 0.9));
    let ta = Vec3A::new(0.1, 0.5, 0.9);
    let shaders = format!(
        r#"shader "a" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "incandescence" {} {} {}, "transparency" {} {} {})
shader "b" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "incandescence" {} {} {}, "transparency" 0.4 0.4 0.4)"#,
        ea.x, ea.y, ea.z, ta.x, ta.y, ta.z, eb.x, eb.y, eb.z
    );
    let text = scene(&shaders, &format!("{}, {}", layer("a"), layer("b")));
    let want = ea * (Vec3A::ONE - ta) + ta * eb * 0.6 + ta * 0.4 * BEHIND;
    for (i, p) in pixels(&text, EngineKind::Classic, 4).iter().enumerate() {
        assert!((*p - want).abs().max_element() < 1e-4, "classic pixel {i}: {p} vs {want}");
    }
    agree("coloured transparency", &text);
}

/// A rampShader layer whose transparency runs 1 − f and incandescence (1, 0.5, 0) →
/// (0, 0.5, 1) over the facing ratio f, over a lambert that refracts (index 1.5,
/// transparency 0.5, incandescence (0.2, 0.6, 0.3)), over the unlit plane B: the path
/// engine's image mean is the classic layeredShader's within 2 % per channel. Read at
/// f = 1 (an opaque top layer, the refraction unseen) it was off by far more.
#[test]
fn a_refracting_stack_follows_the_view_of_its_ramp_layers() {
    let ramp = |name: &str, member: &str, points: &[(f32, &str)]| {
        let items: Vec<String> = points
            .iter()
            .map(|(p, v)| format!(r#"{{ "{name}_Position" {p}, "{name}_{member}" {v}, "{name}_Interp" 1 }}"#))
            .collect();
        format!("[ {} ]", items.join(", "))
    };
    let shaders = format!(
        r#"shader "a" "maya_rampshader" ("colorInput" 0, "diffuse" 0, "color" {}, "specularity" 0,
    "transparency" {}, "incandescence" {})
shader "b" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "incandescence" 0.2 0.6 0.3, "transparency" 0.5 0.5 0.5,
    "refractions" on, "refractiveIndex" 1.5, "refractionLimit" 6)"#,
        ramp("color", "Color", &[(0.0, "0 0 0")]),
        ramp("transparency", "Color", &[(0.0, "1 1 1"), (1.0, "0 0 0")]),
        ramp("incandescence", "Color", &[(0.0, "1 0.5 0"), (1.0, "0 0.5 1")]),
    );
    agree("refracting stack", &scene(&shaders, &format!("{}, {}", layer("a"), layer("b"))));
}
