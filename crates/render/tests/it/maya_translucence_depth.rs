//! A Maya lambert's `translucenceDepth` D (mira's reading of Maya's reference,
//! `maya::material`): light from behind reaching a point whose shadow ray leaves the
//! object's own geometry after a stretch s inside it keeps the fraction max(1 − s/D, 0)
//! of what the material's transparency stops. A slab of thickness s (top face y = 0 seen
//! from above, bottom face y = −s, outward normals) lit by a unit directional light
//! travelling straight up shows c · t · (1 − s/D) with `translucenceFocus` 0, in both
//! engines (the path engine's shadow rays read it as the classic engine's do).

use crate::support;
// `path_pixels(text, spp, depth)`: paths of at most `depth` rays (1: direct light only, as
// the classic engine without final gathering).
use crate::support::maya_view::{mean, path_pixels_to_depth as path_pixels, pixels};

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 8;

/// The slab's colour c.
const COLOR: Vec3A = Vec3A::new(0.6, 0.5, 0.4);

/// The slab's `translucence` t.
const T: f32 = 0.7;

/// The bits of `px`, for exact comparisons.
fn bits(px: &[Vec3A]) -> Vec<u32> {
    px.iter().flat_map(|p| p.to_array().map(f32::to_bits)).collect()
}

/// The slab of thickness `thick` with `translucenceDepth` `depth` and `transparency`
/// `transparency` (grey); `split`: its bottom face is a separate object (another
/// occluder, not the slab's own geometry).
fn scene(thick: f32, depth: f32, transparency: f32, split: bool) -> String {
    let lambert = format!(
        r#"shader "mat" "maya_lambert" ("color" {} {} {}, "diffuse" 0.8, "translucence" {T}, "translucenceFocus" 0,
  "translucenceDepth" {depth}, "transparency" {transparency} {transparency} {transparency})"#,
        COLOR.x, COLOR.y, COLOR.z
    );
    scene_with(thick, split, &lambert)
}

/// The slab of thickness `thick` (`split` as for [`scene`]) whose material "m" shows
/// the shader "mat" that `shaders` declares (with any others it needs).
fn scene_with(thick: f32, split: bool, shaders: &str) -> String {
    let view = support::maya_view::top_down(SIDE);
    let y = -thick;
    let top = "v 0 v 1 v 2 v 3 c \"m\" 0 1 2 3";
    let (objects, instances) = if split {
        (
            format!(
                r#"object "top" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  {top} end group end object
instance "top_inst" "top" end instance
object "bottom" group -5 {y} -5  5 {y} -5  5 {y} 5  -5 {y} 5  {top} end group end object
instance "bottom_inst" "bottom" end instance"#
            ),
            r#""top_inst" "bottom_inst""#,
        )
    } else {
        (
            format!(
                r#"object "slab" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  -5 {y} -5  5 {y} -5  5 {y} 5  -5 {y} 5
  v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7 c "m" 0 1 2 3 c "m" 4 5 6 7 end group end object
instance "slab_inst" "slab" end instance"#
            ),
            r#""slab_inst""#,
        )
    };
    format!(
        r#"
$include "mayabase.mi"
{view}
light "l" "maya_directionallight" ("intensity" 1, "useRayTraceShadows" on) direction 0 1 0 end light
instance "l_inst" "l" end instance
{shaders}
material "m" "maya_shadingengine" ("surfaceShader" = "mat.outColor")
  shadow "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
{objects}
instgroup "root" "cam_inst" "l_inst" {instances} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Classic engine, opaque slab: every pixel is c · t · (1 − s/D) within 1e-3 per
/// channel for s/D = 0.1, 0.25, 0.6 and 0 past the depth (s/D = 1.5). D = 0 and a
/// bottom face that is another object (whatever D) block the light as before: those
/// images are bit-identical to each other (and black), also for a slab of transparency
/// 0.3 (the plain filter by T). Before, the slab's own bottom face stopped all the light.
#[test]
fn translucence_depth_lets_light_through_the_own_object_falling_off_linearly() {
    for (thick, depth) in [(0.1f32, 1.0f32), (0.5, 2.0), (0.3, 0.5), (0.75, 0.5)] {
        let px = pixels(&scene(thick, depth, 0.0, false), EngineKind::Classic, 4);
        let want = COLOR * T * (1.0 - thick / depth).max(0.0);
        for p in &px {
            assert!((*p - want).abs().max_element() < 1e-3, "s {thick} D {depth}: {p} vs {want}");
        }
    }
    for transparency in [0.0f32, 0.3] {
        let zero = pixels(&scene(0.25, 0.0, transparency, false), EngineKind::Classic, 4);
        let other = pixels(&scene(0.25, 2.0, transparency, true), EngineKind::Classic, 4);
        assert_eq!(bits(&zero), bits(&other), "transparency {transparency}: D 0 vs another occluder");
        if transparency == 0.0 {
            assert!(zero.iter().all(|p| *p == Vec3A::ZERO), "{:?}", &zero[..4]);
        }
    }
}

/// Path engine, direct light (paths of one ray, as the classic engine without final
/// gathering; longer paths add the light the slab's faces scatter inside it), opaque
/// slab: every pixel is c · t · (1 − s/D) within 2 % of it (0 past the depth: below
/// 1e-6) and the classic engine's pixel within 2 %, for the four slabs of the classic
/// test. Transparency 0.3 (the passage T + (1 − T)(1 − s/D), the top face's colour faded
/// by 1 − T, and T of the bottom face's c · t · (1 − T) seen through it): the image mean
/// of either engine is the closed form's within 2 % per channel (the path engine passes
/// the top face by chance: 64 samples per pixel). D = 0 and a bottom face that is another
/// object (D = 2) give bit-identical images with full-length paths, opaque and with
/// transparency 0.3 (the plain filter, as before). Before, the path engine warned and its
/// opaque slab was black with one-ray paths.
#[test]
fn the_path_engine_reads_translucence_depth_as_the_classic_engine() {
    for (thick, depth) in [(0.1f32, 1.0f32), (0.5, 2.0), (0.3, 0.5), (0.75, 0.5)] {
        let kept = (1.0 - thick / depth).max(0.0);
        let text = scene(thick, depth, 0.0, false);
        let path = path_pixels(&text, 4, 1);
        let classic = pixels(&text, EngineKind::Classic, 4);
        let want = COLOR * T * kept;
        println!("s {thick} D {depth}: path {} classic {} want {want}", path[0], classic[0]);
        for (p, c) in path.iter().zip(&classic) {
            if want == Vec3A::ZERO {
                assert!(p.max_element() < 1e-6 && c.max_element() < 1e-6, "s {thick} D {depth}: {p} {c}");
                continue;
            }
            for k in 0..3 {
                assert!((p[k] / want[k] - 1.0).abs() < 0.02, "s {thick} D {depth}: {p} vs {want}");
                assert!((p[k] / c[k] - 1.0).abs() < 0.02, "s {thick} D {depth}: {p} vs classic {c}");
            }
        }
        let transparency = 0.3;
        let text = scene(thick, depth, transparency, false);
        let path = mean(&path_pixels(&text, 64, 1));
        let classic = mean(&pixels(&text, EngineKind::Classic, 4));
        let fade = 1.0 - transparency;
        let want = COLOR * T * fade * (transparency + fade * kept) + COLOR * T * fade * transparency;
        println!("T {transparency} s {thick} D {depth}: path {path} classic {classic} want {want}");
        for k in 0..3 {
            assert!((path[k] / want[k] - 1.0).abs() < 0.02, "T 0.3 s {thick} D {depth}: {path} vs {want}");
            assert!((classic[k] / want[k] - 1.0).abs() < 0.02, "T 0.3 s {thick} D {depth}: {classic} vs {want}");
        }
    }
    for transparency in [0.0f32, 0.3] {
        let zero = path_pixels(&scene(0.25, 0.0, transparency, false), 4, 16);
        let other = path_pixels(&scene(0.25, 2.0, transparency, true), 4, 16);
        assert_eq!(bits(&zero), bits(&other), "transparency {transparency}: D 0 vs another occluder");
    }
}

/// A rampShader slab (light-angle input; colour ramp A at 0 to B at 1, linear;
/// `diffuse` 0.8, `translucence` t; `translucenceDepth` `depth`; transparency ramp the
/// grey `transparency`).
fn ramp_slab(thick: f32, depth: f32, transparency: f32) -> String {
    let ramp = format!(
        r#"shader "mat" "maya_rampshader" ("colorInput" 0, "diffuse" 0.8, "translucence" {T}, "translucenceDepth" {depth},
    "color" [ {{ "color_Position" 0, "color_Color" {} {} {}, "color_Interp" 1 }},
              {{ "color_Position" 1, "color_Color" 0.1 0.2 0.9, "color_Interp" 1 }} ],
    "transparency" [ {{ "transparency_Position" 0, "transparency_Color" {transparency} {transparency} {transparency}, "transparency_Interp" 1 }} ])"#,
        COLOR.x, COLOR.y, COLOR.z
    );
    scene_with(thick, false, &ramp)
}

/// Classic engine, rampShader (light-angle input) read as the lambert family: a light
/// straight behind the top face (cos θ = −1) gives C(0) ⊙ L · t = c · t through the
/// slab's own geometry, so every pixel is c · t · (1 − s/D) within 1e-3 per channel for
/// s/D = 0.1, 0.25, 0.6 and 0 past the depth; with transparency 0.3 every pixel is
/// c · t · (1 − T)(T + (1 − T)(1 − s/D)) + T · (the bottom face's c · t · (1 − T)) within
/// 1e-3. D = 0 is the plain filter by T: black when opaque. Before, rampShader ignored
/// `translucenceDepth` and its opaque slab was black.
#[test]
fn ramp_shader_translucence_depth_lets_light_through_the_own_object() {
    for (thick, depth) in [(0.1f32, 1.0f32), (0.5, 2.0), (0.3, 0.5), (0.75, 0.5)] {
        let kept = (1.0 - thick / depth).max(0.0);
        let px = pixels(&ramp_slab(thick, depth, 0.0), EngineKind::Classic, 4);
        let want = COLOR * T * kept;
        for p in &px {
            assert!((*p - want).abs().max_element() < 1e-3, "s {thick} D {depth}: {p} vs {want}");
        }
        let tr = 0.3;
        let px = pixels(&ramp_slab(thick, depth, tr), EngineKind::Classic, 4);
        let fade = 1.0 - tr;
        let want = COLOR * T * fade * (tr + fade * kept) + COLOR * T * fade * tr;
        for p in &px {
            assert!((*p - want).abs().max_element() < 1e-3, "T 0.3 s {thick} D {depth}: {p} vs {want}");
        }
    }
    let black = pixels(&ramp_slab(0.25, 0.0, 0.0), EngineKind::Classic, 4);
    assert!(black.iter().all(|p| *p == Vec3A::ZERO), "{:?}", &black[..4]);
}

/// A layeredShader slab: on top the translucent lambert (c, t, `translucenceFocus` 0,
/// `translucenceDepth` `depth`, opaque), below it a lambert of transparency
/// 0.5 with no translucence.
fn layered_slab(thick: f32, depth: f32) -> String {
    let stack = format!(
        r#"shader "a" "maya_lambert" ("color" {} {} {}, "diffuse" 0.8, "translucence" {T}, "translucenceFocus" 0,
  "translucenceDepth" {depth})
shader "b" "maya_lambert" ("color" 0.2 0.7 0.3, "diffuse" 0.8, "transparency" 0.5 0.5 0.5)
shader "mat" "maya_layeredshader" ("inputs" [
    {{ "color" = "a.outColor", "transparency" = "a.outTransparency" }},
    {{ "color" = "b.outColor", "transparency" = "b.outTransparency" }} ])"#,
        COLOR.x, COLOR.y, COLOR.z
    );
    scene_with(thick, false, &stack)
}

/// A layeredShader carries its translucent layer's `translucenceDepth` in both engines:
/// the classic stack multiplies its layers' shadow transparencies, the translucent
/// layer's T + (1 − T)·max(1 − s/D, 0) among them, and the path engine passes the same
/// (`material::maya::translucent_passage` over the layers' passages). An
/// opaque translucent top layer over a layer of transparency 0.5: every pixel is
/// c · t · 0.5 · (1 − s/D) — per pixel within 1e-3 (classic) and, direct light, within
/// 2 % of it and of the classic pixel (path; 0 past the depth: below 1e-6; measured
/// equal to 1e-7). Before, the path engine's stack left the depth out and was black.
/// (Transparent and several translucent layers: the next test.)
#[test]
fn a_layered_shader_carries_its_layers_translucence_depth() {
    for (thick, depth) in [(0.1f32, 1.0f32), (0.5, 2.0), (0.3, 0.5), (0.75, 0.5)] {
        let kept = (1.0 - thick / depth).max(0.0);
        let text = layered_slab(thick, depth);
        let path = path_pixels(&text, 4, 1);
        let classic = pixels(&text, EngineKind::Classic, 4);
        let want = COLOR * T * 0.5 * kept;
        println!("stack s {thick} D {depth}: path {} classic {} want {want}", path[0], classic[0]);
        for (p, c) in path.iter().zip(&classic) {
            assert!((*c - want).abs().max_element() < 1e-3, "s {thick} D {depth}: classic {c} vs {want}");
            if want == Vec3A::ZERO {
                assert!(p.max_element() < 1e-6, "s {thick} D {depth}: {p}");
                continue;
            }
            for k in 0..3 {
                assert!((p[k] / want[k] - 1.0).abs() < 0.02, "s {thick} D {depth}: {p} vs {want}");
                assert!((p[k] / c[k] - 1.0).abs() < 0.02, "s {thick} D {depth}: {p} vs classic {c}");
            }
        }
    }
}

/// The path engine's rampShader passes light from behind as the classic one: a
/// transmission lobe giving C(0) · t for a light straight behind (light-angle input: the
/// classic C((1 + cos θ)/2) ⊙ L · t at cos θ = −1; other angles: the next test) and its
/// `translucenceDepth` in shadow rays. Direct light (paths
/// of one ray), the slabs of the classic test lit from behind: opaque, every pixel is
/// c · t · (1 − s/D) within 2 % of it and of the classic pixel (0 past the depth: below
/// 1e-6); with transparency 0.3, for D > 0 and D = 0 (the plain filter by T), the image
/// mean is the classic one's and the closed form's within 2 % per channel (256 samples
/// per pixel: the top face is passed by chance). Lit from the front, the opaque slab shows
/// C(1) · (d + t) (the light-angle input's front, as before) per pixel within 2 % of it
/// and of the classic pixel. Before, the path engine's rampShader let no light through
/// from behind (black where the classic slab shows c · t · (1 − s/D)).
#[test]
fn the_path_engine_reads_ramp_shader_translucence_as_the_classic_engine() {
    let close = |name: &str, p: Vec3A, want: Vec3A| {
        for k in 0..3 {
            assert!((p[k] / want[k] - 1.0).abs() < 0.02, "{name}: {p} vs {want}");
        }
    };
    for (thick, depth) in [(0.1f32, 1.0f32), (0.5, 2.0), (0.3, 0.5), (0.75, 0.5)] {
        let kept = (1.0 - thick / depth).max(0.0);
        let text = ramp_slab(thick, depth, 0.0);
        let path = path_pixels(&text, 4, 1);
        let classic = pixels(&text, EngineKind::Classic, 4);
        let want = COLOR * T * kept;
        println!("ramp s {thick} D {depth}: path {} classic {} want {want}", path[0], classic[0]);
        for (p, c) in path.iter().zip(&classic) {
            if want == Vec3A::ZERO {
                assert!(p.max_element() < 1e-6, "s {thick} D {depth}: {p}");
                continue;
            }
            close(&format!("s {thick} D {depth}"), *p, want);
            close(&format!("s {thick} D {depth} classic"), *p, *c);
        }
    }
    let tr = 0.3;
    let fade = 1.0 - tr;
    for (thick, depth) in [(0.25f32, 0.0f32), (0.3, 0.5), (0.5, 2.0)] {
        let kept = if depth > 0.0 { (1.0 - thick / depth).max(0.0) } else { 0.0 };
        let text = ramp_slab(thick, depth, tr);
        let path = mean(&path_pixels(&text, 256, 1));
        let classic = mean(&pixels(&text, EngineKind::Classic, 4));
        let want = COLOR * T * fade * (tr + fade * kept) + COLOR * T * fade * tr;
        println!("ramp T {tr} s {thick} D {depth}: path {path} classic {classic} want {want}");
        close(&format!("T {tr} s {thick} D {depth}"), path, want);
        close(&format!("T {tr} s {thick} D {depth} classic"), path, classic);
    }
    let front = ramp_slab(0.3, 0.5, 0.0).replace("direction 0 1 0", "direction 0 -1 0");
    let path = path_pixels(&front, 4, 1);
    let classic = pixels(&front, EngineKind::Classic, 4);
    let want = Vec3A::new(0.1, 0.2, 0.9) * (0.8 + T);
    println!("ramp lit from the front: path {} classic {} want {want}", path[0], classic[0]);
    for (p, c) in path.iter().zip(&classic) {
        close("front", *p, want);
        close("front classic", *p, *c);
    }
}

/// A layeredShader slab: on top the lambert "a" (c, t, focus 0, `translucenceDepth`
/// `da`, transparency `ta`), below it the lambert "b" (colour [`B`], `translucence`
/// `tb`, focus 0, `translucenceDepth` `db`, transparency 0.5).
fn stack_slab(thick: f32, ta: f32, da: f32, tb: f32, db: f32) -> String {
    let stack = format!(
        r#"shader "a" "maya_lambert" ("color" {} {} {}, "diffuse" 0.8, "translucence" {T}, "translucenceFocus" 0,
  "translucenceDepth" {da}, "transparency" {ta} {ta} {ta})
shader "b" "maya_lambert" ("color" {} {} {}, "diffuse" 0.8, "translucence" {tb}, "translucenceFocus" 0,
  "translucenceDepth" {db}, "transparency" 0.5 0.5 0.5)
shader "mat" "maya_layeredshader" ("inputs" [
    {{ "color" = "a.outColor", "transparency" = "a.outTransparency" }},
    {{ "color" = "b.outColor", "transparency" = "b.outTransparency" }} ])"#,
        COLOR.x, COLOR.y, COLOR.z, B.x, B.y, B.z
    );
    scene_with(thick, false, &stack)
}

/// The lower layer's colour in [`stack_slab`].
const B: Vec3A = Vec3A::new(0.2, 0.7, 0.3);

/// The classic stack of [`stack_slab`] lit from behind, its closed form: each face's lit
/// colour L = (1 − T_a) · c · t + T_a · 0.5 · B · t_b (the layers' translucence by their
/// shares), the top face lit through the slab by the stack's passage
/// (T_a + (1 − T_a) k_a) · (0.5 + 0.5 k_b), k = max(1 − s/D, 0) (0 for D = 0 or no
/// translucence), and the bottom face, lit directly, seen through the top by T_a · 0.5.
fn stack_closed_form(thick: f32, ta: f32, da: f32, tb: f32, db: f32) -> Vec3A {
    let kept = |t: f32, d: f32| if d > 0.0 && t > 0.0 { (1.0 - thick / d).max(0.0) } else { 0.0 };
    let lit = COLOR * T * (1.0 - ta) + B * tb * ta * 0.5;
    let passage = (ta + (1.0 - ta) * kept(T, da)) * (0.5 + 0.5 * kept(tb, db));
    lit * passage + lit * ta * 0.5
}

/// A transparent translucent layer, and two translucent layers, in the path engine's
/// stack as in the classic one. The classic image is the closed form
/// ([`stack_closed_form`]) per pixel within 1e-3; the path engine's image mean (direct
/// light, 2048 samples per pixel: the stack is passed by chance, the standard error of the
/// mean ≤ 0.5 %; measured within 0.2 % at 4096) is the classic one's within 2 % per channel, for D = 0, D inside the slab and D past it. Cases: the top
/// layer of transparency 0.3 translucent over an untranslucent one; both translucent
/// (t_b = 0.5) with depths of their own. Before, the path engine's transparent
/// translucent layer was ~13 % off (its translucence not divided by the stack's
/// coverage) and a second translucent layer's light and depth were left out (warned).
#[test]
fn a_layered_shader_carries_every_layers_translucence_in_the_path_engine() {
    let cases = [
        // (s, T_a, D_a, t_b, D_b)
        (0.3f32, 0.3f32, 0.0f32, 0.0f32, 0.0f32),
        (0.3, 0.3, 0.5, 0.0, 0.0),
        (0.5, 0.3, 2.0, 0.0, 0.0),
        (0.75, 0.3, 0.5, 0.0, 0.0),
        (0.3, 0.3, 0.0, 0.5, 0.0),
        (0.3, 0.3, 0.5, 0.5, 1.0),
        (0.5, 0.6, 2.0, 0.5, 0.8),
        (0.3, 0.0, 1.0, 0.5, 0.6),
    ];
    for (thick, ta, da, tb, db) in cases {
        let name = format!("s {thick} T_a {ta} D_a {da} t_b {tb} D_b {db}");
        let text = stack_slab(thick, ta, da, tb, db);
        let want = stack_closed_form(thick, ta, da, tb, db);
        let classic = pixels(&text, EngineKind::Classic, 4);
        for c in &classic {
            assert!((*c - want).abs().max_element() < 1e-3, "{name}: classic {c} vs {want}");
        }
        let classic = mean(&classic);
        let (path, error) = support::maya_view::mean_and_error(&path_pixels(&text, 2048, 1));
        println!("{name}: path {path} ± {error} classic {classic} want {want}");
        for k in 0..3 {
            assert!((path[k] / classic[k] - 1.0).abs() < 0.02, "{name}: path {path} vs classic {classic}");
        }
    }
}

/// The path engine's rampShader passes light from behind at every angle as the classic
/// one: under the light-angle input the classic shader adds t · C((1 + cos θ)/2) ⊙ L for a
/// light behind (no cosine factor), which the path lobe reads from the ramp's own knots
/// (`bsdf::maya_highlight::translucence::LightAngle`). The opaque slab (s = 0.1, D = 1) lit from behind at θ = 0°, 30° and 60°
/// from the normal (direct light, 4 samples per pixel): the path image's mean is the
/// classic one's within 2 % per channel, and every path pixel the closed form
/// t · C((1 − cos θ)/2) · (1 − s/(D cos θ)) within 2 %. Before, the path lobe was
/// Lambertian, t · C(0) · cos θ: 37 % darker than the classic at 60° (red).
#[test]
fn the_path_engine_follows_ramp_shader_translucence_at_every_light_angle() {
    let (thick, depth) = (0.1f32, 1.0f32);
    let b = Vec3A::new(0.1, 0.2, 0.9);
    for degrees in [0.0f32, 30.0, 60.0] {
        let (sin, cos) = degrees.to_radians().sin_cos();
        let text = ramp_slab(thick, depth, 0.0).replace("direction 0 1 0", &format!("direction {sin} {cos} 0"));
        let path = path_pixels(&text, 4, 1);
        let classic = mean(&pixels(&text, EngineKind::Classic, 4));
        let x = 0.5 * (1.0 - cos);
        let want = (COLOR * (1.0 - x) + b * x) * T * (1.0 - thick / (depth * cos));
        let m = mean(&path);
        println!("ramp behind at {degrees}°: path {m} classic {classic} want {want}");
        for k in 0..3 {
            assert!((m[k] / classic[k] - 1.0).abs() < 0.02, "{degrees}°: path {m} vs classic {classic}");
        }
        for p in &path {
            for k in 0..3 {
                assert!((p[k] / want[k] - 1.0).abs() < 0.02, "{degrees}°: {p} vs {want}");
            }
        }
    }
}

/// An opaque rampShader slab (light-angle input, `diffuse` 0.8, `translucence` `t`,
/// `translucenceDepth` `depth`) whose colour ramp has the points `points` (position,
/// colour; linear).
fn ramp_slab_points(thick: f32, depth: f32, t: f32, points: &[(f32, Vec3A)]) -> String {
    let points: Vec<String> = points
        .iter()
        .map(|(x, c)| format!(r#"{{ "color_Position" {x}, "color_Color" {} {} {}, "color_Interp" 1 }}"#, c.x, c.y, c.z))
        .collect();
    let ramp = format!(
        r#"shader "mat" "maya_rampshader" ("colorInput" 0, "diffuse" 0.8, "translucence" {t}, "translucenceDepth" {depth},
    "color" [ {} ])"#,
        points.join(",\n    ")
    );
    scene_with(thick, false, &ramp)
}

/// The linear ramp through `points` (sorted by position) at `x`.
fn ramp_at(points: &[(f32, Vec3A)], x: f32) -> Vec3A {
    let k = points.iter().rposition(|(p, _)| *p <= x).unwrap_or(0).min(points.len() - 2);
    let ((x0, c0), (x1, c1)) = (points[k], points[k + 1]);
    c0 + (c1 - c0) * ((x - x0) / (x1 - x0)).clamp(0.0, 1.0)
}

/// The path engine's rampShader follows a colour ramp with a knot inside [0, ½] (at ¼:
/// (0.6, 0.5, 0.4) at 0, (0.9, 0.2, 0.1) at ¼, (0.1, 0.2, 0.9) at 1), read from behind
/// from the ramp's own knots (`bsdf::maya_highlight::translucence::LightAngle`). The opaque slab (s = 0.1, D = 1)
/// lit from behind at θ = 0°, 30°, 45° and 60° (the knot) from the normal (direct light,
/// 4 samples per pixel): the path image's mean is the classic one's within 2 % per
/// channel, and every path pixel the closed form t · C((1 − cos θ)/2) · (1 − s/(D cos θ))
/// within 2 %. Before, the lobe read the ramp's chord over [0, ½]: at 60° it gave the
/// mean of C(0) and C(½) where the ramp has its knot, red 31 % dark and green 75 %
/// bright.
#[test]
fn the_path_engine_follows_a_ramp_with_a_knot_lit_from_behind() {
    let (thick, depth) = (0.1f32, 1.0f32);
    let points = [(0.0, COLOR), (0.25, Vec3A::new(0.9, 0.2, 0.1)), (1.0, Vec3A::new(0.1, 0.2, 0.9))];
    for degrees in [0.0f32, 30.0, 45.0, 60.0] {
        let (sin, cos) = degrees.to_radians().sin_cos();
        let text =
            ramp_slab_points(thick, depth, T, &points).replace("direction 0 1 0", &format!("direction {sin} {cos} 0"));
        let path = path_pixels(&text, 4, 1);
        let classic = mean(&pixels(&text, EngineKind::Classic, 4));
        let want = ramp_at(&points, 0.5 * (1.0 - cos)) * T * (1.0 - thick / (depth * cos));
        let m = mean(&path);
        println!("knotted ramp behind at {degrees}°: path {m} classic {classic} want {want}");
        for k in 0..3 {
            assert!((m[k] / classic[k] - 1.0).abs() < 0.02, "{degrees}°: path {m} vs classic {classic}");
        }
        for p in &path {
            for k in 0..3 {
                assert!((p[k] / want[k] - 1.0).abs() < 0.02, "{degrees}°: {p} vs {want}");
            }
        }
    }
}

/// A 5-knot and a 7-knot colour ramp (4 and 5 knots in [0, ½], the rest past it), smooth
/// (2) and spline (3) segments: position, colour, Maya interpolation.
fn many_knots() -> [Vec<(f32, Vec3A, i32)>; 2] {
    let c = |r: f32, g: f32, b: f32| Vec3A::new(r, g, b);
    [
        vec![
            (0.05, c(0.9, 0.2, 0.4), 2),
            (0.18, c(0.1, 0.7, 0.3), 3),
            (0.31, c(0.6, 0.1, 0.9), 2),
            (0.47, c(0.3, 0.9, 0.2), 3),
            (0.72, c(1.1, 0.4, 0.6), 2),
        ],
        vec![
            (0.0, c(0.2, 0.5, 0.8), 3),
            (0.08, c(0.9, 0.1, 0.2), 2),
            (0.15, c(0.4, 0.8, 0.1), 3),
            (0.26, c(0.7, 0.3, 0.5), 2),
            (0.39, c(0.1, 0.6, 0.9), 3),
            (0.55, c(0.8, 0.8, 0.3), 2),
            (0.9, c(0.3, 0.2, 0.7), 3),
        ],
    ]
}

/// The path engine's rampShader follows colour ramps of many knots with smooth and spline
/// segments (`bsdf::maya_highlight::translucence::LightAngle`, each ramp's knots interned):
/// the 5- and 7-knot ramps of [`many_knots`] on the opaque slab (s = 0.1, D = 1,
/// `translucence` [`T`]) lit from behind at θ = 0°, 25°, 50° and 65° (direct light, 4
/// samples per pixel): the path image's mean and the means of its halves are the classic
/// ones' within 2 % per channel, and the classic mean is the closed form
/// t · C((1 − cos θ)/2) · (1 − s/(D cos θ)) (C read as `maya::utility::curve_at`) within
/// 1e-3. Before, a ramp of more than 3 knots in [0, ½] was read at 4 points, linearly
/// between (warned).
#[test]
fn the_path_engine_follows_ramps_of_many_knots_lit_from_behind() {
    let (thick, depth) = (0.1f32, 1.0f32);
    for knots in many_knots() {
        let points: Vec<String> = knots
            .iter()
            .map(|(x, c, i)| {
                format!(r#"{{ "color_Position" {x}, "color_Color" {} {} {}, "color_Interp" {i} }}"#, c.x, c.y, c.z)
            })
            .collect();
        let ramp = format!(
            r#"shader "mat" "maya_rampshader" ("colorInput" 0, "diffuse" 0.8, "translucence" {T}, "translucenceDepth" {depth},
    "color" [ {} ])"#,
            points.join(",\n    ")
        );
        for degrees in [0.0f32, 25.0, 50.0, 65.0] {
            let (sin, cos) = degrees.to_radians().sin_cos();
            let text = scene_with(thick, false, &ramp).replace("direction 0 1 0", &format!("direction {sin} {cos} 0"));
            let path = path_pixels(&text, 4, 1);
            let classic = pixels(&text, EngineKind::Classic, 4);
            let want = maya::utility::curve_at(&knots, 0.5 * (1.0 - cos)) * T * (1.0 - thick / (depth * cos));
            let name = format!("{} knots, {degrees}°", knots.len());
            assert!((mean(&classic) - want).abs().max_element() < 1e-3, "{name}: classic {} vs {want}", mean(&classic));
            for (what, c, p) in [
                ("image", mean(&classic), mean(&path)),
                (
                    "left half",
                    support::two_tone::half_mean(&classic, SIDE, true),
                    support::two_tone::half_mean(&path, SIDE, true),
                ),
                (
                    "right half",
                    support::two_tone::half_mean(&classic, SIDE, false),
                    support::two_tone::half_mean(&path, SIDE, false),
                ),
            ] {
                println!("{name}, {what}: path {p} classic {c}");
                for k in 0..3 {
                    assert!((p[k] / c[k] - 1.0).abs() < 0.02, "{name}, {what}: path {p} vs classic {c}");
                }
            }
        }
    }
}

/// A rampShader whose light from behind passes more than it receives: `translucence`
/// 0.9 and a ramp (0.9, 0.8, 0.3) at 0 to (0.9, 0.6, 0.5) at 1, so t · (C(0) + C(½)) =
/// (1.62, 1.35, 0.63) and the lobe's albedo 2∫t · C((1 − u)/2) du is the same, above 1 in
/// red and green. Lit from behind at 0° and 60° (opaque slab, s = 0.1, D = 1, direct
/// light): the path image mean is the classic one's within 2 % per channel and every path
/// pixel the closed form within 2 %. Before, the lobe's albedo was capped at 1 per
/// channel: red 38 % dark at 0°.
#[test]
fn a_ramp_passing_more_than_it_receives_matches_the_classic_engine() {
    let (thick, depth, t) = (0.1f32, 1.0f32, 0.9f32);
    let points = [(0.0, Vec3A::new(0.9, 0.8, 0.3)), (1.0, Vec3A::new(0.9, 0.6, 0.5))];
    for degrees in [0.0f32, 60.0] {
        let (sin, cos) = degrees.to_radians().sin_cos();
        let text =
            ramp_slab_points(thick, depth, t, &points).replace("direction 0 1 0", &format!("direction {sin} {cos} 0"));
        let path = path_pixels(&text, 4, 1);
        let classic = mean(&pixels(&text, EngineKind::Classic, 4));
        let want = ramp_at(&points, 0.5 * (1.0 - cos)) * t * (1.0 - thick / (depth * cos));
        let m = mean(&path);
        println!("bright ramp behind at {degrees}°: path {m} classic {classic} want {want}");
        for k in 0..3 {
            assert!((m[k] / classic[k] - 1.0).abs() < 0.02, "{degrees}°: path {m} vs classic {classic}");
        }
        for p in &path {
            for k in 0..3 {
                assert!((p[k] / want[k] - 1.0).abs() < 0.02, "{degrees}°: {p} vs {want}");
            }
        }
    }
}

/// The transparency ramp of [`view_stack_slab`]'s top layer at facing ratio `f`: 0.9 at 0
/// to 0.2 at 0.75, linear, 0.2 up to 1 (the eye rays of [`SIDE`]-pixel top-down views all
/// meet the top face at f ≥ 0.76, where it is 0.2).
fn view_ramp(f: f32) -> f32 {
    0.2 + 0.7 * ((0.75 - f) / 0.75).max(0.0)
}

/// A layeredShader slab (s = 0.1) whose top layer follows the view: a rampShader
/// (light-angle input, colour ramp the constant c, `translucence` t, `translucenceDepth`
/// 0.5, transparency ramp [`view_ramp`]) over an opaque lambert (colour [`B`],
/// `translucence` 0.5, focus 0, `translucenceDepth` 1).
fn view_stack_slab() -> String {
    let stack = format!(
        r#"shader "a" "maya_rampshader" ("colorInput" 0, "diffuse" 0.8, "translucence" {T}, "translucenceDepth" 0.5,
    "color" [ {{ "color_Position" 0, "color_Color" {} {} {}, "color_Interp" 1 }} ],
    "transparency" [ {{ "transparency_Position" 0, "transparency_Color" 0.9 0.9 0.9, "transparency_Interp" 1 }},
                     {{ "transparency_Position" 0.75, "transparency_Color" 0.2 0.2 0.2, "transparency_Interp" 1 }} ])
shader "b" "maya_lambert" ("color" {} {} {}, "diffuse" 0.8, "translucence" 0.5, "translucenceFocus" 0,
  "translucenceDepth" 1, "transparency" 0 0 0)
shader "mat" "maya_layeredshader" ("inputs" [
    {{ "color" = "a.outColor", "transparency" = "a.outTransparency" }},
    {{ "color" = "b.outColor", "transparency" = "b.outTransparency" }} ])"#,
        COLOR.x, COLOR.y, COLOR.z, B.x, B.y, B.z
    );
    scene_with(0.1, false, &stack)
}

/// A stack whose rampShader layer's transparency follows the view passes shadow rays by
/// that layer's transparency at the shadow ray's facing ratio in both engines: the classic
/// rampShader reads its ramp at the shadow ray's |N·D| and the stack multiplies its layers'
/// passages; the path engine's passage reads each layer's table there
/// (`material::maya::TranslucentLayer`). [`view_stack_slab`] lit from behind at θ = 50°
/// and 65° from the normal: every classic pixel is the closed form
/// ((1 − T_e) · c · t + T_e · B · 0.5 · cos θ) · (T_s + (1 − T_s) k_a) · k_b within 1e-3
/// per channel (T_e = 0.2 the eye rays' transparency, T_s = [`view_ramp`]`(cos θ)` the
/// shadow ray's, k = max(1 − s/(D cos θ), 0), D_a = 0.5, D_b = 1), and the path image mean
/// (direct light, 16 samples per pixel: the stack is opaque) is the classic one's within
/// 2 % per channel. Before, the path passage read the ramp layer at facing ratio 1
/// (T = 0.2): 4 % dark at 50° and 19 % at 65°.
#[test]
fn a_stack_whose_ramp_layer_follows_the_view_passes_shadow_rays_at_their_facing_ratio() {
    let (thick, te) = (0.1f32, 0.2f32);
    for degrees in [50.0f32, 65.0] {
        let (sin, cos) = degrees.to_radians().sin_cos();
        let text = view_stack_slab().replace("direction 0 1 0", &format!("direction {sin} {cos} 0"));
        let kept = |d: f32| (1.0 - thick / (d * cos)).max(0.0);
        let ts = view_ramp(cos);
        let lit = COLOR * T * (1.0 - te) + B * 0.5 * cos * te;
        let want = lit * (ts + (1.0 - ts) * kept(0.5)) * kept(1.0);
        let classic = pixels(&text, EngineKind::Classic, 4);
        for c in &classic {
            assert!((*c - want).abs().max_element() < 1e-3, "{degrees}°: classic {c} vs {want}");
        }
        let classic = mean(&classic);
        let path = mean(&path_pixels(&text, 16, 1));
        println!("view-following stack behind at {degrees}°: path {path} classic {classic} want {want}");
        for k in 0..3 {
            assert!((path[k] / classic[k] - 1.0).abs() < 0.02, "{degrees}°: path {path} vs classic {classic}");
        }
    }
}
