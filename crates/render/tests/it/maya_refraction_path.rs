//! Maya's raytraced refraction in the path engine: a material with `refractions` on
//! shows T ⊙ what the ray bent by Snell's law with `refractiveIndex` finds (no Fresnel),
//! within `refractionLimit` refractions, past which the ray passes straight — as the
//! classic shader traces a refraction ray, else a transparency ray (`maya::material`'s
//! `behind`; `bsdf::MayaGlossy::refraction`).

use crate::support;
use crate::support::maya_view::pixels;

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 32;

/// Half the side of the ground the image shows (x and z in ±`HALF` at y = 0).
const HALF: f32 = 2.4;

/// The camera's height above the slab's top (`support::maya_view::top_down`).
const EYE_Y: f32 = 4.0;

/// The slab's thickness (top at y = 0, bottom at y = −`THICK`) and the backdrop's depth
/// (y = −`BACK`).
const THICK: f32 = 1.5;
const BACK: f32 = 3.0;

/// `refractiveIndex`.
const IOR: f32 = 1.5;

/// The backdrop's strips: `STRIPS` unlit surfaceShaders side by side along x, each
/// `STRIP` wide, from x = −`STRIPS`·`STRIP`/2.
const STRIPS: usize = 16;
const STRIP: f32 = 0.6;

/// The colour of strip `k` (all different in every channel pair).
fn strip_colour(k: usize) -> Vec3A {
    let f = k as f32 / (STRIPS - 1) as f32;
    Vec3A::new(0.1 + 0.8 * f, 0.9 - 0.8 * f, if k % 2 == 0 { 0.2 } else { 0.7 })
}

/// The strip at `x` on the backdrop, `None` off its ends.
fn strip_at(x: f32) -> Option<usize> {
    let u = (x + STRIPS as f32 * STRIP / 2.0) / STRIP;
    (u >= 0.0 && u < STRIPS as f32).then_some(u as usize)
}

/// The slab's material "mat": a black lambert, or (`ramp`) a black rampShader without
/// highlight or reflection, of transparency `t`, `refractions` on, index [`IOR`] and
/// `refractionLimit` `limit`.
fn slab_shader(ramp: bool, t: Vec3A, limit: u32) -> String {
    let refraction = format!(r#""refractions" on, "refractiveIndex" {IOR}, "refractionLimit" {limit}"#);
    if !ramp {
        return format!(
            r#"shader "mat" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "transparency" {} {} {}, {refraction})"#,
            t.x, t.y, t.z
        );
    }
    let ramp = |name: &str, member: &str, value: &str| {
        format!(
            r#"[ {{ "{name}_Position" 0, "{name}_{member}" {value}, "{name}_Interp" 1 }},
    {{ "{name}_Position" 1, "{name}_{member}" {value}, "{name}_Interp" 1 }} ]"#
        )
    };
    format!(
        r#"shader "mat" "maya_rampshader" ("colorInput" 0, "diffuse" 0, "color" {}, "specularity" 0,
    "reflectivity" {}, "transparency" {}, {refraction})"#,
        ramp("color", "Color", "0 0 0"),
        ramp("reflectivity", "FloatValue", "0"),
        ramp("transparency", "Color", &format!("{} {} {}", t.x, t.y, t.z)),
    )
}

/// A slab of the material `shader` ([`slab_shader`]; its top at y = 0 facing up, its
/// bottom at y = −`THICK` facing down) over the strips at y = −`BACK`, seen from above;
/// no lights.
fn scene(shader: &str) -> String {
    faces(shader, "mat", false)
}

/// The shaders `shaders` on two faces over the strips at y = −`BACK`, seen from above,
/// no lights: the top (y = 0, facing up) of the shader "mat", the bottom (y = −`THICK`,
/// facing up when `bottom_up`, else down) of the shader `bottom`.
fn faces(shaders: &str, bottom: &str, bottom_up: bool) -> String {
    let (z0, z1) = if bottom_up { (5, -5) } else { (-5, 5) };
    let view = support::maya_view::top_down(SIDE);
    let mut strips = String::new();
    let mut names = String::new();
    for k in 0..STRIPS {
        let c = strip_colour(k);
        let (x0, x1) = (
            -(STRIPS as f32) * STRIP / 2.0 + k as f32 * STRIP,
            -(STRIPS as f32) * STRIP / 2.0 + (k + 1) as f32 * STRIP,
        );
        strips += &format!(
            r#"shader "bg{k}" "maya_surfaceshader" ("outColor" {} {} {})
material "mb{k}" opaque "maya_shadingengine" ("surfaceShader" = "bg{k}.outColor") end material
object "strip{k}" group {x0} -{BACK} 5  {x1} -{BACK} 5  {x1} -{BACK} -5  {x0} -{BACK} -5  v 0 v 1 v 2 v 3 c "mb{k}" 0 1 2 3 end group end object
instance "strip{k}_inst" "strip{k}" end instance
"#,
            c.x, c.y, c.z
        );
        names += &format!(" \"strip{k}_inst\"");
    }
    format!(
        r#"
$include "mayabase.mi"
{view}
{shaders}
material "m" "maya_shadingengine" ("surfaceShader" = "mat.outColor")
    shadow "maya_shadingengine" ("surfaceShader" = "mat.outColor") end material
material "m2" "maya_shadingengine" ("surfaceShader" = "{bottom}.outColor")
    shadow "maya_shadingengine" ("surfaceShader" = "{bottom}.outColor") end material
object "top" group -5 0 5  5 0 5  5 0 -5  -5 0 -5  v 0 v 1 v 2 v 3 c "m" 0 1 2 3 end group end object
instance "top_inst" "top" end instance
object "bottom" group -5 -{THICK} {z0}  5 -{THICK} {z0}  5 -{THICK} {z1}  -5 -{THICK} {z1}  v 0 v 1 v 2 v 3 c "m2" 0 1 2 3 end group end object
instance "bottom_inst" "bottom" end instance
{strips}
instgroup "root" "cam_inst" "top_inst" "bottom_inst"{names} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The strip the camera ray through the slab's top at (x, z) finds, bent by Snell's law
/// at the first `limit` of the slab's two faces and straight through the others: the
/// ray's horizontal run is tan θ per unit of depth, θ the incidence at the top inside
/// the slab when the top refracts (sin θt = sin θi / η) and θi below the slab when the
/// bottom refracts back out (parallel faces) or the ray never bent.
fn strip_seen(x: f32, z: f32, limit: u32) -> Option<usize> {
    let r = (x * x + z * z).sqrt();
    let tan_i = r / EYE_Y;
    let sin_t = (tan_i / (1.0 + tan_i * tan_i).sqrt()) / IOR;
    let tan_t = sin_t / (1.0 - sin_t * sin_t).sqrt();
    let (inside, below) = match limit {
        0 => (tan_i, tan_i),
        1 => (tan_t, tan_t),
        _ => (tan_t, tan_i),
    };
    let run = inside * THICK + below * (BACK - THICK);
    strip_at(if r > 0.0 { x + x / r * run } else { x })
}

/// The strip all of 16 × 16 sub-points over pixel (`col`, `row`) and a margin of a tenth
/// of a pixel see through the slab with `limit`, `None` when the pixel straddles a
/// strip's edge.
fn pure_strip(limit: u32, col: usize, row: usize) -> Option<usize> {
    const SUB: usize = 16;
    let pixel = 2.0 * HALF / SIDE as f32;
    // Sub-points over the pixel and a tenth of a pixel around it, its edges included.
    let at = |a: usize| -0.1 + 1.2 * a as f32 / (SUB - 1) as f32;
    let mut seen = None;
    for a in 0..SUB {
        for b in 0..SUB {
            let x = -HALF + (col as f32 + at(a)) * pixel;
            let z = -HALF + (row as f32 + at(b)) * pixel;
            let k = strip_seen(x, z, limit)?;
            if seen.is_some_and(|s| s != k) {
                return None;
            }
            seen = Some(k);
        }
    }
    seen
}

/// The formula's colour of pixel (`col`, `row`) when it lies within one strip
/// ([`pure_strip`]): T² ⊙ its colour (two faces of transparency T).
fn pure_pixel(t: Vec3A, limit: u32, col: usize, row: usize) -> Option<Vec3A> {
    pure_strip(limit, col, row).map(|k| t * t * strip_colour(k))
}

/// A slab (lambert and rampShader alike) of index 1.5 and transparency
/// T = (0.9, 0.7, 0.5) over strips of sixteen colours, `refractionLimit` 0, 1 and 2: the
/// camera sees T² ⊙ the strip the ray finds straight through (0), bent at the top only
/// (1: the bottom passes it straight, past the limit) or bent in and back out, displaced
/// sideways (2). At every pixel that lies within one strip by the formula (16 × 16
/// sub-points, a 0.1-pixel margin), both engines give the formula within 1e-3 per
/// channel (no noise: the slab's only lobe is the delta refraction); at ≥ 15 % of those
/// pixels another limit's ray through the pixel's centre finds another strip, so the
/// engines follow the limit. Before, the path engine let the rays through straight at
/// every limit, by the transparency's mean.
#[test]
fn a_refracting_slab_bends_the_rays_within_the_refraction_limit_in_both_engines() {
    let t = Vec3A::new(0.9, 0.7, 0.5);
    for (ramp, limit) in [false, true].into_iter().flat_map(|r| [(r, 0u32), (r, 1), (r, 2)]) {
        let text = scene(&slab_shader(ramp, t, limit));
        let classic = pixels(&text, EngineKind::Classic, 4);
        let path = pixels(&text, EngineKind::Path, 16);
        let (mut pure, mut differ) = (0, 0);
        for i in 0..SIDE * SIDE {
            let (col, row) = (i % SIDE, i / SIDE);
            let Some(want) = pure_pixel(t, limit, col, row) else { continue };
            pure += 1;
            // What the other limits' rays find through the pixel's centre.
            let centre = |l: u32| {
                let pixel = 2.0 * HALF / SIDE as f32;
                let (x, z) = (-HALF + (col as f32 + 0.5) * pixel, -HALF + (row as f32 + 0.5) * pixel);
                strip_seen(x, z, l).map_or(Vec3A::ZERO, |k| t * t * strip_colour(k))
            };
            if [0u32, 1, 2].into_iter().filter(|&l| l != limit).any(|l| (centre(l) - want).abs().max_element() > 0.01) {
                differ += 1;
            }
            for (name, got) in [("classic", classic[i]), ("path", path[i])] {
                assert!(
                    (got - want).abs().max_element() < 1e-3,
                    "ramp {ramp}, limit {limit}, {name} pixel ({col}, {row}): {got} vs formula {want}"
                );
            }
        }
        println!("ramp {ramp}, limit {limit}: {pure} pixels within one strip, {differ} differ from the other limits'");
        assert!(pure * 3 >= SIDE * SIDE, "ramp {ramp}, limit {limit}: only {pure} pixels within one strip");
        assert!(
            differ * 100 >= pure * 15,
            "ramp {ramp}, limit {limit}: only {differ} of {pure} pixels tell the limits apart"
        );
    }
}

/// A slab of a layeredShader of three lamberts (black, `diffuse` 0): on top a
/// non-refracting one of incandescence E and grey transparency T0 = 0.4, then one that
/// refracts (index 1.5, T1 = (0.9, 0.7, 0.5), `refractionLimit` 0, 1, 2), then an opaque
/// white-incandescent one. The refracting layer shows through its transparency what its
/// refraction ray finds and hides the layers below it (`maya::layered_shader`'s reading):
/// each face shows a = E ⊙ (1 − T0) and b = T0 ⊙ T1 of what lies behind it along the
/// bent ray, so a pixel within one strip shows a + b ⊙ (a + b ⊙ strip). Both engines
/// give that within 1e-3 per channel at every such pixel (no noise: the stack's only
/// lobe is the delta refraction of weight b). Before, the classic engine took the
/// refracted share out again as if it were the straight one and showed the white layer,
/// and the path engine let the rays through straight.
#[test]
fn a_layered_shader_layer_refracts_and_hides_the_layers_below_in_both_engines() {
    let (e, t0, t1) = (Vec3A::new(0.3, 0.2, 0.1), 0.4f32, Vec3A::new(0.9, 0.7, 0.5));
    let (a, b) = (e * (1.0 - t0), t0 * t1);
    for limit in [0u32, 1, 2] {
        let shader = format!(
            r#"shader "l0" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "incandescence" {} {} {}, "transparency" {t0} {t0} {t0})
shader "l1" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "transparency" {} {} {},
    "refractions" on, "refractiveIndex" {IOR}, "refractionLimit" {limit})
shader "l2" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "incandescence" 1 1 1)
shader "mat" "maya_layeredshader" ("inputs" [
    {{ "color" = "l0.outColor", "transparency" = "l0.outTransparency" }},
    {{ "color" = "l1.outColor", "transparency" = "l1.outTransparency" }},
    {{ "color" = "l2.outColor", "transparency" = "l2.outTransparency" }} ])"#,
            e.x, e.y, e.z, t1.x, t1.y, t1.z
        );
        let text = scene(&shader);
        let classic = pixels(&text, EngineKind::Classic, 4);
        let path = pixels(&text, EngineKind::Path, 16);
        let mut pure = 0;
        for i in 0..SIDE * SIDE {
            let (col, row) = (i % SIDE, i / SIDE);
            let Some(k) = pure_strip(limit, col, row) else { continue };
            pure += 1;
            let want = a + b * (a + b * strip_colour(k));
            for (name, got) in [("classic", classic[i]), ("path", path[i])] {
                assert!(
                    (got - want).abs().max_element() < 1e-3,
                    "limit {limit}, {name} pixel ({col}, {row}): {got} vs formula {want}"
                );
            }
        }
        println!("limit {limit}: {pure} pixels within one strip");
        assert!(pure * 3 >= SIDE * SIDE, "limit {limit}: only {pure} pixels within one strip");
    }
}

/// The strip the camera ray through (x, z) at y = 0 finds when it passes the top
/// straight and the bottom bends it entering an index [`IOR`] (`bent`) or passes it
/// straight.
fn strip_past_bottom(x: f32, z: f32, bent: bool) -> Option<usize> {
    let r = (x * x + z * z).sqrt();
    let tan_i = r / EYE_Y;
    let sin_t = (tan_i / (1.0 + tan_i * tan_i).sqrt()) / IOR;
    let below = if bent { sin_t / (1.0 - sin_t * sin_t).sqrt() } else { tan_i };
    let run = tan_i * THICK + below * (BACK - THICK);
    strip_at(if r > 0.0 { x + x / r * run } else { x })
}

/// Maya's `refractionLimit` counts the transparency rays of other materials, as mental
/// ray's refraction level does: a fully transparent lambert (T = 1, no refraction: a
/// transparency ray in the classic engine, a cut-out every ray passes in the path engine)
/// at y = 0 over a refracting lambert plane (index 1.5, T = (0.9, 0.7, 0.5), facing up)
/// at y = −1.5 over the strips. With `refractionLimit` 0 and 1 the lower plane is reached
/// at refraction level 1 and passes the ray straight; with 2 it bends it. At every pixel
/// within one strip by the formula (16 × 16 sub-points, 0.1-pixel margin) both engines
/// give T ⊙ that strip's colour within 1e-3 per channel (no noise), and at ≥ 15 % of
/// them limits 1 and 2 find different strips. Before, the path engine counted only its
/// own refractions and bent the ray at limit 1.
#[test]
fn the_refraction_limit_counts_other_materials_transparency_rays_in_both_engines() {
    refraction_limit_past_the_top(None);
}

/// [`the_refraction_limit_counts_other_materials_transparency_rays_in_both_engines`]
/// with the top plane's material `top` (a whole `material … end material`, named "m") in
/// place of the transparent lambert's (when given), in both engines.
pub(crate) fn refraction_limit_past_the_top(top: Option<&str>) {
    let t = Vec3A::new(0.9, 0.7, 0.5);
    let shaders = format!(
        r#"shader "mat" "maya_lambert" ("color" 0 0 0, "diffuse" 0, "transparency" 1 1 1)
{}"#,
        slab_shader(false, t, 0)
            .replace(r#""refractionLimit" 0"#, r#""refractionLimit" LIMIT"#)
            .replace(r#""mat""#, r#""low""#)
    );
    for limit in [0u32, 1, 2] {
        let mut text = faces(&shaders.replace("LIMIT", &limit.to_string()), "low", true);
        if let Some(top) = top {
            let start = text.find("material \"m\" ").expect("material m");
            let end = start + text[start..].find("end material").expect("its end") + "end material".len();
            text.replace_range(start..end, top);
        }
        let classic = pixels(&text, EngineKind::Classic, 4);
        let path = pixels(&text, EngineKind::Path, 16);
        let (mut pure, mut differ) = (0, 0);
        let pixel = 2.0 * HALF / SIDE as f32;
        for i in 0..SIDE * SIDE {
            let (col, row) = (i % SIDE, i / SIDE);
            // Every sub-point over the pixel (and a tenth of a pixel around) in one strip.
            let at = |a: usize| -0.1 + 1.2 * a as f32 / 15.0;
            let strips: Option<Vec<usize>> = (0..16 * 16)
                .map(|j| {
                    let (x, z) = (-HALF + (col as f32 + at(j % 16)) * pixel, -HALF + (row as f32 + at(j / 16)) * pixel);
                    strip_past_bottom(x, z, limit >= 2)
                })
                .collect();
            let Some(k) = strips.filter(|s| s.iter().all(|k| *k == s[0])).map(|s| s[0]) else { continue };
            pure += 1;
            let centre = (-HALF + (col as f32 + 0.5) * pixel, -HALF + (row as f32 + 0.5) * pixel);
            if strip_past_bottom(centre.0, centre.1, true) != strip_past_bottom(centre.0, centre.1, false) {
                differ += 1;
            }
            let want = t * strip_colour(k);
            for (name, got) in [("classic", classic[i]), ("path", path[i])] {
                assert!(
                    (got - want).abs().max_element() < 1e-3,
                    "limit {limit}, {name} pixel ({col}, {row}): {got} vs formula {want}"
                );
            }
        }
        println!("limit {limit}: {pure} pixels within one strip, {differ} tell bent from straight");
        assert!(pure * 3 >= SIDE * SIDE, "limit {limit}: only {pure} pixels within one strip");
        assert!(differ * 100 >= pure * 15, "limit {limit}: only {differ} of {pure} pixels tell the limits apart");
    }
}
