//! Participating media in the path engine, with materials of scenes/mdl/media.mdl: an
//! absorbing slab behind an index-matched boundary transmits exp(−σa·d) per channel (seen
//! through, and on the shadow rays of a light behind it), and a purely scattering sphere
//! (albedo 1, chromatic coefficients, forward and backward Henyey–Greenstein) under a
//! uniform white environment is a white furnace. The stack of media: a camera inside
//! nested media, five nested shells, cut-out surfaces that are no boundary, lights without
//! shadows that media still absorb; `thick_glass`'s absorption.

use crate::support;

use render::{EngineKind, Settings};

/// Renders `text` (which includes media.mdl) with the path engine at `res`², `spp` samples
/// per pixel, `max_depth` bounces: the pixels and every message.
pub(crate) fn render(text: &str, res: u32, spp: u32, max_depth: u32) -> (Vec<[f32; 4]>, Vec<String>) {
    render_with(text, res, spp, render::integrator::PathSettings { max_depth, ..Default::default() })
}

/// [`render`] with the path engine's settings `path`.
fn render_with(text: &str, res: u32, spp: u32, path: render::integrator::PathSettings) -> (Vec<[f32; 4]>, Vec<String>) {
    render_by(EngineKind::Path, text, res, spp, path)
}

/// [`render_with`] by `engine`.
pub(crate) fn render_by(
    engine: EngineKind,
    text: &str,
    res: u32,
    spp: u32,
    path: render::integrator::PathSettings,
) -> (Vec<[f32; 4]>, Vec<String>) {
    let parsed = mi::parse_str("t.mi", text);
    let b = support::build_parsed(&parsed, res, &[support::mdl_modules()]);
    let settings = Settings { engine, spp: Some(spp), path, ..Settings::default() };
    let (film, _) = support::render_world(&b.built.world, &b.built.shading, &settings);
    (film.rgba(), b.messages)
}

/// A closed box from `lo` to `hi` of material `material` as `.mi` text (object `name`),
/// each face counter-clockwise seen from outside.
pub(crate) fn closed_box(name: &str, lo: [f32; 3], hi: [f32; 3], material: &str) -> String {
    let corner = |i: usize| {
        [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ]
    };
    // Faces −x, +x, −y, +y, −z, +z by corner index (bit 0: x, bit 1: y, bit 2: z).
    let faces = [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]];
    // The faces point outwards: their normals (right-handed, counter-clockwise) leave the box.
    let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0, (lo[2] + hi[2]) / 2.0];
    for f in faces {
        let [a, b, c] = [corner(f[0]), corner(f[1]), corner(f[2])];
        let (u, v) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
        let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        let out = (0..3).map(|k| n[k] * (a[k] - centre[k])).sum::<f32>();
        assert!(out > 0.0, "face {f:?} of the box faces inwards");
    }
    let vertices: String = (0..8).map(|i| corner(i).map(|c| c.to_string()).join(" ") + "\n").collect();
    let polygons: String =
        faces.iter().map(|f| format!("p \"{material}\" {} {} {} {}\n", f[0], f[1], f[2], f[3])).collect();
    format!(
        "object \"{name}\" group\n{vertices}v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7\n{polygons}end group end object\n\
         instance \"{name}_inst\" \"{name}\" end instance\n"
    )
}

/// A camera at the origin looking down −z (field of view 0.6°, `res`² pixels) at a slab of
/// `slab` material one unit thick (z from −3 to −2) in front of `behind` (a 100 × 100 quad
/// at z = −5 facing the camera); `extra` (lights) is added to the scene.
pub(crate) fn slab_scene(slab: &str, behind: &str, extra: &str, res: u32) -> String {
    format!(
        r#"$include "media.mdl"
options "opt" filter box 1 1 end options
camera "cam" focal 1 aperture 0.01 aspect 1 resolution {res} {res} end camera
instance "cam_inst" "cam" end instance
{slab}
{behind}
{extra}
{}
object "back" group
    -50 -50 -5  50 -50 -5  50 50 -5  -50 50 -5
    v 0 v 1 v 2 v 3
    p "back_mtl" 0 1 2 3
end group end object
instance "back_inst" "back" end instance
instgroup "root" "cam_inst" "slab_inst" "back_inst" {} end instgroup
render "root" "cam_inst" "opt"
"#,
        closed_box("slab", [-3.0, -3.0, -3.0], [3.0, 3.0, -2.0], "slab_mtl"),
        if extra.is_empty() { "" } else { "\"sun_inst\"" },
    )
}

/// σa of the test's gel per channel (per metre = scene unit).
pub(crate) const SIGMA_A: [f32; 3] = [0.5, 1.0, 2.0];

#[test]
fn an_absorbing_slab_transmits_beer_lambert_per_channel() {
    // A glow of radiance 1 behind a slab 1 unit thick: the camera sees exp(−σa) per
    // channel (the rays are within 0.3° of the slab's normal: path lengths within 2e-5).
    let glow = r#"shader "back_mtl" "mdl::media::glow" ()"#;
    let gel = r#"shader "slab_mtl" "mdl::media::tinted_gel" ()"#;
    let (px, messages) = render(&slab_scene(gel, glow, "", 4), 4, 4, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    let clear = r#"shader "slab_mtl" "mdl::media::tinted_gel" ("absorption" 0 0 0)"#;
    let (px_clear, messages) = render(&slab_scene(clear, glow, "", 4), 4, 4, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    for (p, q) in px.iter().zip(&px_clear) {
        for k in 0..3 {
            let want = (-SIGMA_A[k]).exp();
            assert!((p[k] - want).abs() <= 1e-3 * want, "channel {k}: {} vs exp(−{}) = {want}", p[k], SIGMA_A[k]);
            assert!((q[k] - 1.0).abs() <= 1e-3, "the clear slab lets the glow through: {q:?}");
        }
    }
}

#[test]
fn shadow_rays_through_an_index_matched_absorbing_slab_carry_its_transmittance() {
    // A white matte plane (0.8) lit head-on through the slab by a directional light of
    // irradiance π, seen through the slab: 0.8 × exp(−σa)² per channel — once on the way
    // to the camera, once on the shadow ray (the plane's other bounces find nothing).
    let matte = r#"$include "export_multi.mdl"
shader "back_mtl" "mdl::export_multi::matte" ("tint" 0.8 0.8 0.8)"#;
    let sun = r#"light "sun" "mib_light_infinite" ("color" 3.14159265 3.14159265 3.14159265) direction 0 0 -1 end light
instance "sun_inst" "sun" end instance"#;
    let gel = r#"shader "slab_mtl" "mdl::media::tinted_gel" ()"#;
    let (px, messages) = render(&slab_scene(gel, matte, sun, 4), 4, 4, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    for p in &px {
        for k in 0..3 {
            let want = 0.8 * (-2.0 * SIGMA_A[k]).exp();
            assert!((p[k] - want).abs() <= 2e-3 * want, "channel {k}: {} vs 0.8 exp(−2·{}) = {want}", p[k], SIGMA_A[k]);
        }
    }
}

#[test]
fn a_flex_material_reaches_its_volume_colour_after_its_base_thickness() {
    // core_definitions' flex_material: σa = −ln(volume_color) / base_thickness, so light
    // crossing the 1-unit slab keeps volume_color^(1 / base_thickness) = volume_color².
    let glow = r#"shader "back_mtl" "mdl::media::glow" ()"#;
    let flex = r#"shader "slab_mtl" "mdl::nvidia::core_definitions::flex_material" ("transparency" 1, "ior" 1, "reflectivity" 0, "reflection_roughness" 0, "volume_color" 0.5 0.25 0.8, "base_thickness" 0.5)"#;
    let (px, messages) = render(&slab_scene(flex, glow, "", 4), 4, 4, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    for p in &px {
        for (k, c) in [0.5f32, 0.25, 0.8].into_iter().enumerate() {
            let want = c * c;
            assert!((p[k] - want).abs() <= 1e-3 * want, "channel {k}: {} vs {c}² = {want}", p[k]);
        }
    }
}

#[test]
fn thick_glass_reaches_its_glass_colour_after_its_base_thickness() {
    // core_definitions' thick_glass: σa = −ln(glass_color) / base_thickness inside, the
    // surface tinted by transmission_color where light enters; a 1-unit slab of index 1
    // lets 0.9 × glass_color^(1 / 0.5) through. A matte wall (0.8) lit through it by a
    // directional light (irradiance π): the same again on the shadow rays.
    let glass = r#"shader "slab_mtl" "mdl::nvidia::core_definitions::thick_glass" ("ior" 1, "glass_color" 0.5 0.25 0.8, "base_thickness" 0.5, "transmission_color" 0.9 0.9 0.9)"#;
    let through = [0.5f32, 0.25, 0.8].map(|c| 0.9 * c * c);
    let glow = r#"shader "back_mtl" "mdl::media::glow" ()"#;
    let (px, messages) = render(&slab_scene(glass, glow, "", 4), 4, 4, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    assert_pixels(&px, through, 1e-3, "a glow behind thick glass");
    let matte = r#"$include "export_multi.mdl"
shader "back_mtl" "mdl::export_multi::matte" ("tint" 0.8 0.8 0.8)"#;
    let sun = r#"light "sun" "mib_light_infinite" ("color" 3.14159265 3.14159265 3.14159265) direction 0 0 -1 end light
instance "sun_inst" "sun" end instance"#;
    let (px, messages) = render(&slab_scene(glass, matte, sun, 4), 4, 4, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    assert_pixels(&px, through.map(|t| 0.8 * t * t), 2e-3, "a wall lit and seen through thick glass");
}

/// A UV sphere of radius 1 at (0, 0, −5) of material "ball_mtl" (outward faces), as `.mi`
/// text.
fn ball() -> String {
    let (rings, segments) = (48, 96);
    let mut v = String::new();
    for i in 0..=rings {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = std::f32::consts::TAU * j as f32 / segments as f32;
            v += &format!("{} {} {}\n", theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos() - 5.0);
        }
    }
    let refs: String = (0..(rings + 1) * segments).map(|i| format!("v {i} ")).collect();
    let mut polys = String::new();
    for i in 0..rings {
        for j in 0..segments {
            let a = i * segments + j;
            let b = i * segments + (j + 1) % segments;
            polys += &format!("c \"ball_mtl\" {a} {} {} {b}\n", a + segments, b + segments);
        }
    }
    format!(
        "object \"ball\" group\n{v}{refs}\n{polys}end group end object\ninstance \"ball_inst\" \"ball\" end instance\n"
    )
}

#[test]
fn a_purely_scattering_sphere_is_a_white_furnace() {
    // Albedo 1 in every channel: under a uniform environment of radiance 1 every pixel of
    // the sphere is 1 (light is only redistributed). Grey σs = 2 (optical radius 2),
    // forward and backward scattering, 64 samples; coloured σs = 0.5, 1, 2 (the chromatic
    // free flights) at 256 samples. 24² pixels (orthographic, 2 × 2 view), bounces up to
    // 256; the mean over the pixels well inside the disc within 1 % per channel, each grey
    // pixel within 0.4.
    for (scattering, bias, spp) in [("2 2 2", 0.7f32, 64u32), ("2 2 2", -0.4, 64), ("0.5 1 2", 0.3, 256)] {
        let shader = format!(r#"shader "ball_mtl" "mdl::media::smoke" ("scattering" {scattering}, "bias" {bias})"#);
        let disc = furnace_disc(&shader, spp);
        let grey = scattering == "2 2 2";
        let (mut sum, n) = ([0.0f64; 3], disc.len());
        for (i, p) in &disc {
            for k in 0..3 {
                assert!(!grey || (p[k] - 1.0).abs() < 0.4, "σs {scattering}, g {bias}: pixel {i} {p:?}");
                sum[k] += f64::from(p[k]);
            }
        }
        let mean = sum.map(|s| s / n as f64);
        eprintln!("white furnace, σs {scattering}, g {bias}, {spp} spp: {mean:?} over {n} pixels");
        assert!(mean.iter().all(|m| (m - 1.0).abs() < 0.01), "σs {scattering}, g {bias}: mean {mean:?}");
    }
}

#[test]
fn forward_scattering_sends_a_backlight_towards_the_camera() {
    // A thin smoke slab (σs = 0.05, 1 unit thick) lit from behind by a directional light
    // of irradiance π shining towards the camera, nothing else in the scene: the camera
    // sees light scattered forward by 0°. Single scattering gives
    // L = E σs p(cos 0) d e^(−σt d) (p the Henyey–Greenstein density); multiple scattering
    // adds a few per cent. Only the ~5 % of paths that scatter see the light, so 8192
    // samples per pixel (4² pixels: about 6500 scattering events, 1.2 % noise): with g = 0.5
    // the image is within [0.97, 1.10] × single scattering; with g = −0.5 (the same light
    // scattered backwards is 27× weaker) under a tenth of it.
    let scene = |bias: f32| {
        format!(
            r#"$include "media.mdl"
options "opt" filter box 1 1 end options
camera "cam" focal 1 aperture 0.01 aspect 1 resolution 4 4 end camera
instance "cam_inst" "cam" end instance
shader "slab_mtl" "mdl::media::smoke" ("scattering" 0.05 0.05 0.05, "bias" {bias})
light "sun" "mib_light_infinite" ("color" 3.14159265 3.14159265 3.14159265) direction 0 0 1 end light
instance "sun_inst" "sun" end instance
{}
instgroup "root" "cam_inst" "sun_inst" "slab_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
            closed_box("slab", [-3.0, -3.0, -3.0], [3.0, 3.0, -2.0], "slab_mtl")
        )
    };
    let hg = |g: f32| (1.0 - g * g) / (4.0 * std::f32::consts::PI * (1.0 - g).powi(3));
    let (sigma, d) = (0.05f32, 1.0f32);
    let single = |g: f32| std::f32::consts::PI * sigma * hg(g) * d * (-sigma * d).exp();
    let (px, messages) = render(&scene(0.5), 4, 8192, 64);
    assert!(messages.is_empty(), "{messages:#?}");
    let forward = px.iter().map(|p| p[0]).sum::<f32>() / px.len() as f32;
    let (px, _) = render(&scene(-0.5), 4, 8192, 64);
    let backward = px.iter().map(|p| p[0]).sum::<f32>() / px.len() as f32;
    eprintln!("forward {forward} (single scattering {}), backward {backward} ({})", single(0.5), single(-0.5));
    let ratio = forward / single(0.5);
    assert!((0.97..=1.10).contains(&ratio), "forward {forward} vs single scattering {}", single(0.5));
    assert!(backward < forward / 10.0, "backward {backward} vs forward {forward}");
}

/// A scene of a camera at the origin looking down −z (field of view 0.6°, `res`²
/// pixels) with `body` (shaders, objects, lights) and the instances `instances`.
pub(crate) fn scene_with(body: &str, instances: &[&str], res: u32) -> String {
    let list: String = instances.iter().map(|i| format!(" \"{i}\"")).collect();
    format!(
        r#"$include "media.mdl"
$include "export_multi.mdl"
options "opt" filter box 1 1 end options
camera "cam" focal 1 aperture 0.01 aspect 1 resolution {res} {res} end camera
instance "cam_inst" "cam" end instance
{body}
instgroup "root" "cam_inst"{list} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// A 100 × 100 quad at depth `z` facing +z (the camera) of material `material`.
pub(crate) fn wall(name: &str, z: f32, material: &str) -> String {
    format!(
        "object \"{name}\" group\n-50 -50 {z}  50 -50 {z}  50 50 {z}  -50 50 {z}\nv 0 v 1 v 2 v 3\n\
         p \"{material}\" 0 1 2 3\nend group end object\ninstance \"{name}_inst\" \"{name}\" end instance\n"
    )
}

/// Asserts every pixel is `want` per channel within relative `tol`.
pub(crate) fn assert_pixels(px: &[[f32; 4]], want: [f32; 3], tol: f32, what: &str) {
    for p in px {
        for k in 0..3 {
            assert!((p[k] - want[k]).abs() <= tol * want[k], "{what}: channel {k}: {} vs {}", p[k], want[k]);
        }
    }
}

/// The scene (4² pixels) of a camera at the origin inside a closed gel box of [`SIGMA_A`]
/// (x, y in ±5, z from −4 to 4): with `outer` false, a glow of radiance 1 inside it at
/// z = −1.5; with `outer` true, inside it and a second box around it (σa = 0.25; x, y in
/// ±10, z from −6 to 6), a glow at z = −8 outside both.
pub(crate) fn camera_in_gel_boxes(outer: bool) -> String {
    let inner = closed_box("inner", [-5.0, -5.0, -4.0], [5.0, 5.0, 4.0], "inner_mtl");
    let glow = r#"shader "glow_mtl" "mdl::media::glow" ()
shader "inner_mtl" "mdl::media::tinted_gel" ()"#;
    if !outer {
        return scene_with(&format!("{glow}\n{inner}{}", wall("w", -1.5, "glow_mtl")), &["inner_inst", "w_inst"], 4);
    }
    let outer = closed_box("outer", [-10.0, -10.0, -6.0], [10.0, 10.0, 6.0], "outer_mtl");
    scene_with(
        &format!(
            "{glow}\nshader \"outer_mtl\" \"mdl::media::tinted_gel\" (\"absorption\" 0.25 0.25 0.25)\n{inner}{outer}{}",
            wall("w", -8.0, "glow_mtl")
        ),
        &["inner_inst", "outer_inst", "w_inst"],
        4,
    )
}

#[test]
fn a_camera_inside_a_medium_sees_through_it() {
    // The camera inside a closed gel box (σa = 0.5, 1, 2; z from −4 to 4) sees a glow of
    // radiance 1 inside it at distance 1.5: exp(−1.5 σa) per channel. Inside that box and
    // a second one around it (σa = 0.25; z from −6 to 6), a glow at z = −8 outside both:
    // exp(−4 σa − 2 · 0.25), the camera's media found by rays from its position.
    let (px, messages) = render(&camera_in_gel_boxes(false), 4, 4, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    assert_pixels(&px, SIGMA_A.map(|s| (-1.5 * s).exp()), 1e-3, "a wall inside the box");

    let (px, messages) = render(&camera_in_gel_boxes(true), 4, 4, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    assert_pixels(&px, SIGMA_A.map(|s| (-4.0 * s - 0.5).exp()), 1e-3, "a wall outside two boxes");
}

/// Nested shells of grey gel in front of a glow, as a scene body (see [`scene_with`]) and
/// its instances' names: shell i has absorption `sigma[i]` (per scene unit), spans x and
/// y in ±(`half` − i) and z from `far` + i to −4 − i, and the glow is a wall at `glow_z`.
/// A camera ray down −z is in shell i for 2 units and in the innermost for
/// −4 − `far` − 2·(n − 1).
pub(crate) fn nested_gel_shells(sigma: &[f32], half: f32, far: f32, glow_z: f32) -> (String, Vec<String>) {
    let mut body = String::from("shader \"glow_mtl\" \"mdl::media::glow\" ()\n");
    let mut instances = Vec::new();
    for (i, s) in sigma.iter().enumerate() {
        let f = i as f32;
        body += &format!("shader \"shell{i}_mtl\" \"mdl::media::tinted_gel\" (\"absorption\" {s} {s} {s})\n");
        body += &closed_box(
            &format!("shell{i}"),
            [-half + f, -half + f, far + f],
            [half - f, half - f, -4.0 - f],
            &format!("shell{i}_mtl"),
        );
        instances.push(format!("shell{i}_inst"));
    }
    body += &wall("w", glow_z, "glow_mtl");
    instances.push("w_inst".into());
    (body, instances)
}

#[test]
fn five_nested_media_keep_the_outermost() {
    // Five nested gel shells (σa 0.3, 0.2, 0.1, 0.15, 0.05 from the outside in; shell i
    // spans z from −20 + i to −4 − i) in front of a glow at z = −25: the camera ray is in
    // shell i for 2 units (1 in, 1 out) and in the innermost for 8:
    // exp(−2(0.3 + 0.2 + 0.1 + 0.15) − 8 · 0.05) = exp(−1.9). A stack that forgot the
    // outermost would miss its last unit: exp(−1.6).
    let sigma = [0.3f32, 0.2, 0.1, 0.15, 0.05];
    let (body, instances) = nested_gel_shells(&sigma, 10.0, -20.0, -25.0);
    let names: Vec<&str> = instances.iter().map(String::as_str).collect();
    // No Russian roulette: every path crosses all ten surfaces, so the image is exact.
    let path = render::integrator::PathSettings { max_depth: 32, rr_depth: 32, ..Default::default() };
    let (px, messages) = render_with(&scene_with(&body, &names, 4), 4, 4, path);
    assert!(messages.is_empty(), "{messages:#?}");
    let want = (-1.9f32).exp();
    assert_pixels(&px, [want; 3], 1e-3, "five shells");
}

/// A white matte wall at z = −5 lit head-on by a directional light (irradiance π, `shadow`
/// its shadow flag) through the gel slab (z from −3 to −2); `extra` adds objects,
/// `instances` their instances. The pixels of a render at 4², 4 samples.
fn lit_through_the_slab(shadow: &str, extra: &str, instances: &[&str]) -> (Vec<[f32; 4]>, Vec<String>) {
    let light = format!(") direction 0 0 -1 shadow {shadow}");
    render(&wall_through_the_slab(&light, GEL_SLAB, extra, instances), 4, 4, 16)
}

/// The slab's material statement for [`wall_through_the_slab`]: the gel of [`SIGMA_A`].
pub(crate) const GEL_SLAB: &str = r#"shader "slab_mtl" "mdl::media::tinted_gel" ()"#;

/// The scene (4² pixels) of a white-ish matte wall (0.8) at z = −5 lit head-on by a
/// directional light `sun` of colour π through the slab (z from −3 to −2) and seen
/// through it: `light` continues the light's statement after its colour parameter (more
/// parameters, the closing parenthesis, direction and flags), `slab` is the slab's
/// material statement(s) (`slab_mtl`), `extra` more objects and `instances` their
/// instances.
pub(crate) fn wall_through_the_slab(light: &str, slab: &str, extra: &str, instances: &[&str]) -> String {
    let body = format!(
        r#"shader "matte_mtl" "mdl::export_multi::matte" ("tint" 0.8 0.8 0.8)
{slab}
light "sun" "mib_light_infinite" ("color" 3.14159265 3.14159265 3.14159265{light} end light
instance "sun_inst" "sun" end instance
{}{}{extra}"#,
        closed_box("slab", [-3.0, -3.0, -3.0], [3.0, 3.0, -2.0], "slab_mtl"),
        wall("w", -5.0, "matte_mtl")
    );
    let mut all = vec!["sun_inst", "slab_inst", "w_inst"];
    all.extend_from_slice(instances);
    scene_with(&body, &all, 4)
}

/// A black wall at z = 1 (behind a camera looking down −z from z = 0 or so), facing the
/// scene's lights: it blocks any light that casts shadows through it.
pub(crate) const BLACK_WALL_BEHIND_CAMERA: &str = r#"shader "black_mtl" "mdl::export_multi::matte" ("tint" 0 0 0)
object "blocker" group
    -50 -50 1  -50 50 1  50 50 1  50 -50 1
    v 0 v 1 v 2 v 3
    p "black_mtl" 0 1 2 3
end group end object
instance "blocker_inst" "blocker" end instance
"#;

#[test]
fn a_light_without_shadows_is_still_absorbed_by_media() {
    // `shadow off`: a black wall behind the camera (z = 1, facing the light) does not block
    // the light, but the gel slab still absorbs it: 0.8 exp(−2σa) as with shadows on and
    // no wall (once to the camera, once on the light's way); with shadows on the wall
    // blocks it: 0.
    let blocker = BLACK_WALL_BEHIND_CAMERA;
    let want = SIGMA_A.map(|s| 0.8 * (-2.0 * s).exp());
    let (px, messages) = lit_through_the_slab("off", blocker, &["blocker_inst"]);
    assert!(messages.is_empty(), "{messages:#?}");
    assert_pixels(&px, want, 2e-3, "shadow off, blocker");
    let (px, _) = lit_through_the_slab("on", "", &[]);
    assert_pixels(&px, want, 2e-3, "shadow on, no blocker");
    let (px, _) = lit_through_the_slab("on", blocker, &["blocker_inst"]);
    assert!(px.iter().all(|p| p[..3].iter().all(|&c| c == 0.0)), "shadow on, blocked: {:?}", px[0]);
}

#[test]
fn a_cut_out_surface_inside_a_medium_is_no_boundary() {
    // A closed box of a strongly absorbing gel (σa = 4) whose surface is entirely cut out
    // sits inside the slab (z from −2.7 to −2.3): neither the camera's rays nor the
    // light's shadow rays enter it, so the wall keeps 0.8 exp(−2σa) of the slab alone.
    let cut = format!(
        "shader \"cut_mtl\" \"mdl::media::cutout_gel\" (\"opacity\" 0)\n{}",
        closed_box("cut", [-2.0, -2.0, -2.7], [2.0, 2.0, -2.3], "cut_mtl")
    );
    let (px, messages) = lit_through_the_slab("on", &cut, &["cut_inst"]);
    assert!(messages.is_empty(), "{messages:#?}");
    assert_pixels(&px, SIGMA_A.map(|s| 0.8 * (-2.0 * s).exp()), 2e-3, "cut out box in the slab");
}

#[test]
fn both_engines_absorb_alike_in_a_slab() {
    // The classic engine attenuates rays inside an MDL medium by Beer–Lambert (a volume
    // shader of extinction): through the gel slab (σa = 0.5, 1, 2; 1 unit) it sees the glow
    // as the path engine does, exp(−σa) per channel, the two within 1 %.
    let glow = r#"shader "back_mtl" "mdl::media::glow" ()"#;
    let gel = r#"shader "slab_mtl" "mdl::media::tinted_gel" ()"#;
    let text = slab_scene(gel, glow, "", 4);
    let (path, messages) = render(&text, 4, 4, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    let (classic, messages) = render_by(EngineKind::Classic, &text, 4, 4, Default::default());
    assert!(messages.is_empty(), "{messages:#?}");
    eprintln!("absorbing slab: classic {:?}, path {:?}", classic[0], path[0]);
    for (c, p) in classic.iter().zip(&path) {
        for k in 0..3 {
            let want = (-SIGMA_A[k]).exp();
            assert!((p[k] - want).abs() <= 1e-3 * want, "path, channel {k}: {} vs {want}", p[k]);
            assert!((c[k] - p[k]).abs() <= 0.01 * p[k], "channel {k}: classic {} vs path {}", c[k], p[k]);
        }
    }
}

/// The white furnace of [`a_purely_scattering_sphere_is_a_white_furnace`] with the
/// sphere's material `shader` (a `.mi` shader line for `ball_mtl`), `spp` samples, bounces
/// up to 256 (orthographic, 24², the square x, y ∈ [−1, 1] under a uniform environment of
/// radiance 1): the pixels well inside the sphere's disc (centres within 0.85 of its
/// axis) with their indices, asserting no message.
fn furnace_disc(shader: &str, spp: u32) -> Vec<(usize, [f32; 4])> {
    let text = format!(
        r#"$include "media.mdl"
options "opt" filter box 1 1 end options
camera "cam" focal infinity aperture 2 aspect 1 resolution 24 24
    environment "mib_color_mix" ("num" 0, "color_base" 1 1 1 1)
end camera
instance "cam_inst" "cam" end instance
{shader}
{}
instgroup "root" "cam_inst" "ball_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        ball()
    );
    let (px, messages) = render(&text, 24, spp, 256);
    assert!(messages.is_empty(), "{messages:#?}");
    let inside = |i: usize| {
        let (x, y) = ((i % 24) as f32 / 12.0 - 1.0 + 1.0 / 24.0, (i / 24) as f32 / 12.0 - 1.0 + 1.0 / 24.0);
        (x * x + y * y).sqrt() < 0.85
    };
    px.into_iter().enumerate().filter(|(i, _)| inside(*i)).collect()
}

/// The mean over the pixels of [`furnace_disc`].
fn furnace_mean(shader: &str, spp: u32) -> [f64; 3] {
    let disc = furnace_disc(shader, spp);
    let mut sum = [0.0f64; 3];
    for (_, p) in &disc {
        for k in 0..3 {
            sum[k] += f64::from(p[k]);
        }
    }
    sum.map(|s| s / disc.len() as f64)
}

#[test]
fn a_mix_of_vdfs_that_scatters_all_is_a_white_furnace() {
    // media.mdl's `smoke_mix` (σs 2, lobes g 0.8 and g −0.4 weighted 0.5 each: their
    // mixture as the phase function, albedo 1) and `tinted_smoke_mix` (σs 0.5, 1, 2; clamped colour weights summing
    // to 1 per channel) and `chromatic_smoke_mix` (σs 0.5, 1, 2; each channel its own
    // mixture of a forward and a backward lobe: a chromatic phase function) only
    // redistribute the uniform environment's light: the mean within 1 % per channel (256
    // samples, for the chromatic free flights and phase sampling). Weights summing to 0.5 absorb half of each scattering: the
    // sphere (optical radius 2) is darker by far — under 0.8.
    for shader in [
        r#"shader "ball_mtl" "mdl::media::smoke_mix" ()"#,
        r#"shader "ball_mtl" "mdl::media::tinted_smoke_mix" ("scattering" 0.5 1 2)"#,
        r#"shader "ball_mtl" "mdl::media::chromatic_smoke_mix" ()"#,
    ] {
        let mean = furnace_mean(shader, 256);
        eprintln!("white furnace, {shader}: {mean:?}");
        assert!(mean.iter().all(|m| (m - 1.0).abs() < 0.01), "{shader}: mean {mean:?}");
    }
    let lossy = furnace_mean(r#"shader "ball_mtl" "mdl::media::smoke_mix" ("forward" 0.3, "backward" 0.2)"#, 16);
    eprintln!("half-weighted vdf mix: {lossy:?}");
    assert!(lossy.iter().all(|m| *m < 0.8), "a mix of weight 0.5 absorbs: {lossy:?}");
}

#[test]
fn both_engines_light_a_wall_through_an_absorbing_slab_alike() {
    // The classic engine's shadow rays cross the gel's index-matched boundary and keep
    // exp(−σa·d) inside, as the path engine's: the matte wall lit head-on through the slab
    // and seen through it is 0.8 exp(−2σa) per channel in both, the classic engine's pixels
    // π times the path engine's (mental ray's lights carry no 1/π), within 1 %. Without
    // the slab's absorption on the shadow rays the classic wall would be exp(σa) brighter.
    let (path, messages) = lit_through_the_slab("on", "", &[]);
    assert!(messages.is_empty(), "{messages:#?}");
    let text = wall_through_the_slab(r#", "shadow" on) direction 0 0 -1 shadow on"#, GEL_SLAB, "", &[]);
    let (classic, messages) = render_by(EngineKind::Classic, &text, 4, 4, Default::default());
    assert!(messages.is_empty(), "{messages:#?}");
    eprintln!("wall lit through the slab: classic {:?} / π, path {:?}", classic[0], path[0]);
    let want = SIGMA_A.map(|s| 0.8 * (-2.0 * s).exp());
    assert_pixels(&path, want, 2e-3, "path engine");
    for (c, p) in classic.iter().zip(&path) {
        for k in 0..3 {
            let c = c[k] / std::f32::consts::PI;
            assert!((c - p[k]).abs() <= 0.01 * p[k], "channel {k}: classic {c} (/π) vs path {}", p[k]);
        }
    }
}
