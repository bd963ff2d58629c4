//! MDL participating media in the classic engine, against the path engine and closed
//! forms (materials of scenes/mdl/media.mdl; scene pieces from [`super::media`]):
//!
//! - a classic camera inside nested absorbing boxes sees through them as the path
//!   engine's does (exp(−1.5σa); exp(−4σa − 0.5));
//! - a thin slab of scattering medium lit by a point light from the side scatters light
//!   towards the camera: the classic engine's single scattering matches the single-scatter
//!   integral (quadrature in the test) and the path engine limited to single scattering;
//! - a light whose shader casts no shadows is still absorbed by the media on its way, and a
//!   surface with a shadow shader of its own is a medium boundary for shadow rays;
//! - a camera moving into a medium while the shutter is open is in it from where it
//!   crosses its surface (both engines);
//! - ten nested media, deeper than the refraction chain once held, are all remembered.

use std::f32::consts::PI;

use render::integrator::PathSettings;
use render::EngineKind;

use super::media::{
    assert_pixels, camera_in_gel_boxes, closed_box, nested_gel_shells, render_by, scene_with, wall,
    wall_through_the_slab, SIGMA_A,
};

/// Renders `text` with the classic engine at 4², `spp` samples: the pixels and every message.
fn classic(text: &str, spp: u32) -> (Vec<[f32; 4]>, Vec<String>) {
    render_by(EngineKind::Classic, text, 4, spp, PathSettings::default())
}

/// The mean of the pixels' RGB.
fn mean(px: &[[f32; 4]]) -> [f64; 3] {
    let mut sum = [0.0f64; 3];
    for p in px {
        for k in 0..3 {
            sum[k] += f64::from(p[k]);
        }
    }
    sum.map(|s| s / px.len() as f64)
}

#[test]
fn a_classic_camera_inside_a_medium_sees_through_it() {
    // As `media::a_camera_inside_a_medium_sees_through_it` for the path engine: a glow of
    // radiance 1 at distance 1.5 inside a gel box around the camera: exp(−1.5 σa); inside
    // that box and a second (σa 0.25) a glow outside both: exp(−4 σa − 0.5). Treated as
    // outside, the camera would see 1 and exp(−σa·4 + …) of the far side only.
    let (px, messages) = classic(&camera_in_gel_boxes(false), 4);
    assert!(messages.is_empty(), "{messages:#?}");
    eprintln!("classic camera in one box: {:?}", px[0]);
    assert_pixels(&px, SIGMA_A.map(|s| (-1.5 * s).exp()), 1e-3, "a wall inside the box");

    let (px, messages) = classic(&camera_in_gel_boxes(true), 4);
    assert!(messages.is_empty(), "{messages:#?}");
    eprintln!("classic camera in two boxes: {:?}", px[0]);
    assert_pixels(&px, SIGMA_A.map(|s| (-4.0 * s - 0.5).exp()), 1e-3, "a wall outside two boxes");
}

/// Scattering and absorption coefficients and asymmetry of the scattering slab.
const SIGMA_S: f64 = 0.5;
const SIGMA_A_SMOKE: f64 = 0.1;
const G: f64 = 0.3;
/// The point light's colour (no falloff: mental ray's `mib_light_point`) and position.
const LAMP: f64 = 10.0;
const LAMP_AT: [f64; 3] = [0.0, 4.0, -2.5];

/// A slab of `smoke` (z from −3 to −2, |x|, |y| ≤ 3) in front of the camera, nothing
/// behind it, lit by a point light above it (outside, 1 unit over its top face).
fn smoky_slab() -> String {
    let body = format!(
        r#"shader "slab_mtl" "mdl::media::smoke" ("scattering" {SIGMA_S} {SIGMA_S} {SIGMA_S}, "absorption" {SIGMA_A_SMOKE} {SIGMA_A_SMOKE} {SIGMA_A_SMOKE}, "bias" {G})
light "lamp" "mib_light_point" ("color" {LAMP} {LAMP} {LAMP}, "shadow" on) origin {} {} {} shadow on end light
instance "lamp_inst" "lamp" end instance
{}"#,
        LAMP_AT[0],
        LAMP_AT[1],
        LAMP_AT[2],
        closed_box("slab", [-3.0, -3.0, -3.0], [3.0, 3.0, -2.0], "slab_mtl"),
    );
    scene_with(&body, &["lamp_inst", "slab_inst"], 4)
}

/// The single-scatter integral along the camera's axis through the slab of [`smoky_slab`]
/// (the path engine's units: the light's colour as its irradiance, the phase function
/// normalised to 1): ∫₀¹ e^(−σt t) σs p(θ) E e^(−σt ℓ) dt, ℓ the light's way inside the slab
/// (the part of the way to the light below the slab's top face y = 3), by Simpson's rule.
fn single_scatter_integral() -> f64 {
    let sigma_t = SIGMA_S + SIGMA_A_SMOKE;
    let f = |t: f64| {
        let x = [0.0, 0.0, -2.0 - t];
        let v = [LAMP_AT[0] - x[0], LAMP_AT[1] - x[1], LAMP_AT[2] - x[2]];
        let r = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        // The camera ray travels along −z; light scattered towards the camera.
        let cos = -v[2] / r;
        let hg = (1.0 - G * G) / (4.0 * std::f64::consts::PI * (1.0 + G * G - 2.0 * G * cos).powf(1.5));
        let inside = r * (3.0 - x[1]) / v[1];
        (-sigma_t * t).exp() * SIGMA_S * hg * LAMP * (-sigma_t * inside).exp()
    };
    let n = 2000;
    let h = 1.0 / f64::from(n);
    let mut sum = f(0.0) + f(1.0);
    for i in 1..n {
        sum += f(f64::from(i) * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

#[test]
fn single_scattering_in_a_slab_matches_its_integral_and_the_path_engine() {
    // The slab scatters the lamp's light towards the camera; nothing else is seen. The
    // classic engine (equiangular and distance sampling towards the lamp, its light loop
    // and shadow rays through the slab) against the single-scatter integral within 1 %,
    // per pixel within 3 % (its pixels are π times the path engine's: mental ray's light
    // colours carry no 1/π). The path engine with two bounces (the slab's surface, then
    // one scattering in it) computes single scattering alone: within 2 % of the integral
    // and of the classic engine. Before, the classic engine saw black.
    let text = smoky_slab();
    let want = single_scatter_integral();
    let (px, messages) = classic(&text, 16);
    assert!(messages.is_empty(), "{messages:#?}");
    let c = mean(&px).map(|v| v / f64::from(PI));
    eprintln!("single scattering: classic / π {c:?}, integral {want}");
    for (k, c) in c.iter().enumerate() {
        assert!((c / want - 1.0).abs() < 0.01, "classic channel {k}: {c} vs {want}");
    }
    for p in &px {
        assert!((f64::from(p[0]) / f64::from(PI) / want - 1.0).abs() < 0.03, "classic pixel {p:?} vs {want}");
    }
    let single = PathSettings { max_depth: 2, rr_depth: 32, ..PathSettings::default() };
    let (px, messages) = render_by(EngineKind::Path, &text, 4, 2048, single);
    assert!(messages.is_empty(), "{messages:#?}");
    let p = mean(&px);
    eprintln!("single scattering: path {p:?}");
    for k in 0..3 {
        assert!((p[k] / want - 1.0).abs() < 0.02, "path channel {k}: {} vs {want}", p[k]);
        assert!((p[k] / c[k] - 1.0).abs() < 0.02, "path channel {k}: {} vs classic / π {}", p[k], c[k]);
    }
}

/// The classic engine's pixels of a white-ish matte wall (0.8) at z = −5 lit head-on by a
/// directional light of colour π through the gel slab (z from −3 to −2) and seen through
/// it; `light` holds the light's shader parameters and flags, `slab` the slab's material
/// statement(s), `extra` more objects and `instances` their instances.
fn classic_wall_through_the_slab(light: &str, slab: &str, extra: &str, instances: &[&str]) -> Vec<[f32; 4]> {
    classic_wall_with_options(light, slab, extra, instances, "")
}

/// [`classic_wall_through_the_slab`] with `options` added to the options block.
fn classic_wall_with_options(light: &str, slab: &str, extra: &str, instances: &[&str], options: &str) -> Vec<[f32; 4]> {
    let text = wall_through_the_slab(&format!(", {light}"), slab, extra, instances)
        .replace("filter box 1 1 end options", &format!("filter box 1 1 {options} end options"));
    let (px, messages) = classic(&text, 4);
    assert!(messages.is_empty(), "{messages:#?}");
    px.iter().map(|p| [p[0] / PI, p[1] / PI, p[2] / PI, p[3]]).collect()
}

#[test]
fn a_classic_light_without_shadows_is_still_absorbed_by_media() {
    // The light's shader casts no shadows: a black wall behind the camera does not block
    // it, but the slab still absorbs its light: the wall (÷ π) is 0.8 exp(−2σa), as in the
    // path engine (`media::a_light_without_shadows_is_still_absorbed_by_media`); before it
    // was 0.8 exp(−σa) (the light's way skipped the slab). Also with `shadow off` in the
    // options (the light's shader asks for shadows, none are traced).
    let blocker = crate::media::BLACK_WALL_BEHIND_CAMERA;
    let gel = r#"shader "slab_mtl" "mdl::media::tinted_gel" ()"#;
    let want = SIGMA_A.map(|s| 0.8 * (-2.0 * s).exp());
    let px =
        classic_wall_through_the_slab(r#""shadow" off) direction 0 0 -1 shadow off"#, gel, blocker, &["blocker_inst"]);
    eprintln!("classic, shadows off: {:?}", px[0]);
    assert_pixels(&px, want, 0.01, "shadows off, blocker");
    let on = r#""shadow" on) direction 0 0 -1 shadow on"#;
    let px = classic_wall_with_options(on, gel, blocker, &["blocker_inst"], "shadow off");
    eprintln!("classic, shadow off in the options: {:?}", px[0]);
    assert_pixels(&px, want, 0.01, "shadow off in the options, blocker");
    let px = classic_wall_through_the_slab(on, gel, blocker, &["blocker_inst"]);
    assert!(px.iter().all(|p| p[..3].iter().all(|&c| c == 0.0)), "shadows on, blocked: {:?}", px[0]);
}

#[test]
fn a_surface_with_a_shadow_shader_is_a_medium_boundary_for_shadow_rays() {
    // The gel slab's material has a shadow shader of its own (`mib_shadow_transparency`,
    // fully transparent): it filters the shadow ray instead of the boundary's tint, and the
    // ray still enters and leaves the gel there: the wall (÷ π) is 0.8 exp(−2σa) as
    // without the shader; before, the shadow ray passed the surface outside the medium
    // (0.8 exp(−σa)).
    let slab = r#"shader "gel" "mdl::media::tinted_gel" ()
material "slab_mtl" = "gel"
    shadow "mib_shadow_transparency" ("color" 1 1 1 1, "transp" 1 1 1 1, "mode" 3)
end material"#;
    let px = classic_wall_through_the_slab(r#""shadow" on) direction 0 0 -1 shadow on"#, slab, "", &[]);
    eprintln!("classic, shadow shader on the slab: {:?}", px[0]);
    assert_pixels(&px, SIGMA_A.map(|s| 0.8 * (-2.0 * s).exp()), 0.01, "shadow shader on the gel");
}

#[test]
fn a_camera_moving_into_a_medium_while_the_shutter_is_open_enters_it() {
    // The camera moves from z = 1 to z = −1 over the shutter, into a gel box (σa 0.5, 1, 2;
    // z from −4 to 0) holding a glow of radiance 1 at z = −1.5. Until shutter time ½ it is
    // outside and sees the glow through 1.5 units of gel; after, from inside, through
    // z_c + 1.5 = 2.5 − 2t. The mean over the shutter: ½ e^(−1.5σ) + (e^(−0.5σ) −
    // e^(−1.5σ)) / (2σ) per channel, in both engines within 1 %. A camera that kept the
    // media it started in would see the glow unattenuated for t > ½: ½ e^(−1.5σ) + ½.
    let body = format!(
        "shader \"glow_mtl\" \"mdl::media::glow\" ()\nshader \"box_mtl\" \"mdl::media::tinted_gel\" ()\n{}{}",
        closed_box("box", [-5.0, -5.0, -4.0], [5.0, 5.0, 0.0], "box_mtl"),
        wall("w", -1.5, "glow_mtl")
    );
    let text = scene_with(&body, &["box_inst", "w_inst"], 4)
        .replace("filter box 1 1 end options", "filter box 1 1 motion on shutter 0 1 end options")
        .replace(
            "instance \"cam_inst\" \"cam\" end instance",
            "instance \"cam_inst\" \"cam\" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -1 1\n    \
             motion transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 1 1 end instance",
        );
    let want = SIGMA_A.map(|s| 0.5 * (-1.5 * s).exp() + ((-0.5 * s).exp() - (-1.5 * s).exp()) / (2.0 * s));
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let (px, messages) = render_by(engine, &text, 4, 64, PathSettings::default());
        assert!(messages.is_empty(), "{messages:#?}");
        let m = mean(&px);
        eprintln!("camera moving into the gel, {engine:?}: {m:?}, want {want:?}");
        for k in 0..3 {
            let w = f64::from(want[k]);
            assert!((m[k] / w - 1.0).abs() < 0.01, "{engine:?} channel {k}: {} vs {w}", m[k]);
        }
    }
}

/// The classic engine's shadow rays in scenes with media and no shadow shaders walk
/// through `Tracer::boundary_hits` (each surface's distance and material only): along rays
/// through two nested boxes and the wall behind them it visits the same surfaces, at the
/// same distances (bit for bit) and of the same materials, as `shadow_hits` with its full
/// hit states, in both backends' answer of the world; and a walk stopped early stops.
#[test]
fn boundary_hits_visit_what_shadow_hits_visits() {
    use shader::Tracer;
    let text = format!(
        "$include \"media.mdl\"\noptions \"opt\" end options\ncamera \"cam\" end camera\ninstance \"cam_inst\" \"cam\" end instance\n\
         shader \"gel\" \"mdl::media::tinted_gel\" ()\nshader \"back_mtl\" \"mdl::media::glow\" ()\n{}{}{}\
         instgroup \"root\" \"cam_inst\" \"outer_inst\" \"inner_inst\" \"w_inst\" end instgroup\nrender \"root\" \"cam_inst\" \"opt\"\n",
        crate::media::closed_box("outer", [-3.0, -3.0, -4.0], [3.0, 3.0, -1.0], "gel"),
        crate::media::closed_box("inner", [-1.0, -1.0, -3.0], [1.0, 1.0, -2.0], "gel"),
        crate::media::closed_box("w", [-9.0, -9.0, -9.0], [9.0, 9.0, -8.0], "back_mtl"),
    );
    let parsed = mi::parse_str("t.mi", &text);
    let b = crate::support::build_parsed(&parsed, 4, &[crate::support::mdl_modules()]);
    let world = &b.built.world;
    for backend in [render::accel::Backend::Rust, render::accel::Backend::default_available()] {
        let accel = render::accel::build(world, backend);
        let tracer = render::tracer::SceneTracer::new(world, accel.as_ref());
        for dir in [glam::Vec3A::new(0.1, -0.05, -1.0), glam::Vec3A::new(-0.3, 0.2, -1.0)] {
            let ray = shader::State { org: glam::Vec3A::ZERO, dir: dir.normalize(), ..Default::default() };
            let (mut full, mut light) = (Vec::new(), Vec::new());
            tracer.shadow_hits(&ray, f32::INFINITY, &mut |h| {
                full.push((h.dist, h.material));
                true
            });
            tracer.boundary_hits(&ray, f32::INFINITY, &mut |d, m| {
                light.push((d, m));
                true
            });
            assert!(full.len() >= 5, "the rays cross the boxes and reach the wall: {full:?}");
            assert_eq!(light, full, "{backend:?} along {dir:?}");
            let mut visits = 0;
            tracer.boundary_hits(&ray, f32::INFINITY, &mut |_, _| {
                visits += 1;
                visits < 2
            });
            assert_eq!(visits, 2, "stops when asked");
        }
    }
}

/// Ten nested gel shells in the classic engine, more than its refraction chain once held
/// (eight: entering a ninth forgot the outermost, without a word). Shell i (σa below, from
/// the outside in) spans z from −30 + i to −4 − i in front of a glow at z = −35, so the
/// camera ray is in shell i for 2 units (1 on the way in, 1 on the way out) and in the
/// innermost for 8: exp(−2 · 0.5 − 8 · 0.01) = exp(−1.08) within 1e-3. A chain that forgot
/// the two outermost shells would miss their last units: exp(−0.93).
#[test]
fn ten_nested_media_keep_the_outermost_in_the_classic_engine() {
    let sigma = [0.1f32, 0.05, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.01];
    let (body, instances) = nested_gel_shells(&sigma, 20.0, -30.0, -35.0);
    let names: Vec<&str> = instances.iter().map(String::as_str).collect();
    // Twenty surfaces to cross: a refraction depth past that.
    let text = scene_with(&body, &names, 4).replace("filter box 1 1", "filter box 1 1 trace depth 64 64 128");
    let (px, messages) = classic(&text, 4);
    assert!(messages.is_empty(), "{messages:#?}");
    eprintln!("classic camera through ten shells: {:?}", px[0]);
    let inner = 2.0 * sigma[..9].iter().sum::<f32>() + 8.0 * sigma[9];
    assert!((inner - 1.08).abs() < 1e-5);
    assert_pixels(&px, [(-inner).exp(); 3], 1e-3, "ten shells");
}
