//! mental ray's rendering-mode string options (`scene::options::modes`, as mental ray
//! documented them): `"environment lighting mode"` decides whether the environment is a
//! light of the path engine (sampled directly) or only seen by the rays that leave the
//! scene; `"progressive" on` and `"gi" on` take the path engine in the automatic engine
//! choice; `"light relative scale"` leaves the light on BSDF (MDL) materials unchanged.

use crate::support;
use crate::support::scene_text::SceneText;

use render::integrator::PathSettings;
use render::{EngineKind, Settings};

/// An orthographic camera (a 2 × 2 view, `res`² pixels) looking down −Z at a Lambert plane
/// of albedo 0.5 that faces it and fills the left half of the view, under a constant
/// environment of radiance 2 and nothing else; `options` go into the options block.
fn plane_under_environment(options: &str, res: u32) -> String {
    SceneText::new()
        .options(&format!("filter box 1 1 {options}"))
        .camera(r#"focal infinity aperture 2 aspect 1 environment "mib_color_mix" ("num" 0, "color_base" 2 2 2 1)"#)
        .resolution(res)
        .text(
            r#"material "half" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1) end material
object "plane" group
    -50 -50 -5  0 -50 -5  0 50 -5  -50 50 -5
    v 0 v 1 v 2 v 3
    p "half" 0 1 2 3
end group end object
instance "plane_inst" "plane" end instance"#,
        )
        .instance("plane_inst")
        .build()
}

/// Direct light only: one scattering event, light sampling alone.
const DIRECT: PathSettings = PathSettings { max_depth: 1, rr_depth: 1, mis: false };

/// Renders `text` with the path engine at `spp` samples per pixel: pixels and messages.
fn render_path(text: &str, spp: u32, path: PathSettings) -> (Vec<[f32; 4]>, Vec<String>) {
    let support::Compiled { scene, shading, mut messages, .. } = support::compile(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    messages.extend(world.warnings.iter().cloned());
    let settings = Settings { engine: EngineKind::Path, spp: Some(spp), path, ..Settings::default() };
    (support::render_world(&world, &shading, &settings).0.rgba(), messages)
}

/// The plane's pixels (left half) and the environment's (right half) of an 8² render.
fn halves(px: &[[f32; 4]]) -> (Vec<[f32; 4]>, Vec<[f32; 4]>) {
    let (plane, sky): (Vec<_>, Vec<_>) = px.iter().enumerate().partition(|(i, _)| i % 8 < 4);
    (plane.into_iter().map(|(_, p)| *p).collect(), sky.into_iter().map(|(_, p)| *p).collect())
}

fn mean_red(px: &[[f32; 4]]) -> f32 {
    px.iter().map(|p| p[0]).sum::<f32>() / px.len() as f32
}

/// `"environment lighting mode" "off"`: in direct light (one bounce, light sampling) the
/// plane is black, exactly, while the camera still sees the environment (2, within 1e-5).
/// `"light"`, and no option at all (the same image bit for bit): the plane shows
/// albedo × L = 0.5 × 2 = 1 (its irradiance 2π), within 3 % (8², 1024 spp: the uniform
/// sphere samples of a constant environment leave a standard error of 0.7 %).
#[test]
fn environment_lighting_off_is_no_light_and_light_is_sampled() {
    let (off, messages) = render_path(&plane_under_environment("\"environment lighting mode\" \"off\"", 8), 64, DIRECT);
    assert!(messages.is_empty(), "{messages:#?}");
    let (plane, sky) = halves(&off);
    assert!(plane.iter().all(|p| p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0), "lit plane: {plane:?}");
    assert!(sky.iter().all(|p| (0..3).all(|k| (p[k] - 2.0).abs() < 1e-5)), "environment: {sky:?}");

    let (light, messages) =
        render_path(&plane_under_environment("\"environment lighting mode\" \"light\"", 8), 1024, DIRECT);
    assert!(messages.is_empty(), "{messages:#?}");
    let (plane, sky) = halves(&light);
    let m = mean_red(&plane);
    eprintln!("environment light: plane {m} (analytic 1)");
    assert!((m - 1.0).abs() < 0.03, "plane {m} vs 1");
    assert!(sky.iter().all(|p| (p[0] - 2.0).abs() < 1e-5), "environment: {sky:?}");
    let (absent, _) = render_path(&plane_under_environment("", 8), 1024, DIRECT);
    assert_eq!(absent, light, "no option lights as \"light\" does");
}

/// With `"environment lighting mode" "off"` the environment still reaches the plane through
/// the rays that leave it (global illumination, the path engine's full paths): under a
/// constant environment cosine-sampled rays give albedo × L = 1 at every sample, within
/// 1e-4 (8², 16 spp).
#[test]
fn environment_lighting_off_is_seen_by_rays_that_leave_the_scene() {
    let text = plane_under_environment("\"environment lighting mode\" \"off\" \"gi\" on", 8);
    let (px, messages) = render_path(&text, 16, PathSettings::default());
    assert!(messages.is_empty(), "{messages:#?}");
    let (plane, _) = halves(&px);
    assert!(plane.iter().all(|p| (p[0] - 1.0).abs() < 1e-4), "plane: {plane:?}");
}

/// A mode mira does not know (neither "off" nor "light") is read as "light", with a warning
/// at the option.
#[test]
fn an_unknown_environment_lighting_mode_warns() {
    let text = plane_under_environment("\"environment lighting mode\" \"automatic\"", 4);
    let messages = support::compile(&text).messages;
    assert!(
        messages.iter().any(|m| m.contains("t.mi:2:30: warning: \"environment lighting mode\" is neither")),
        "{messages:#?}"
    );
}

/// The automatic engine choice: a scene of mental ray shaders renders classic, unless its
/// options ask for mental ray's progressive rendering, GI "Next" or iray rendering mode
/// (`"progressive" on`, `"gi" on`, `"iray" on`: mental ray's manual, iray.html, switches
/// iray on by a scene option; Maya writes `"iray"`); an engine asked for is kept.
#[test]
fn progressive_and_gi_next_take_the_path_engine() {
    for (options, want) in [
        ("", EngineKind::Classic),
        ("\"progressive\" off \"gi\" off \"iray\" off", EngineKind::Classic),
        ("\"progressive\" on", EngineKind::Path),
        ("\"gi\" on", EngineKind::Path),
        ("\"iray\" on", EngineKind::Path),
    ] {
        // (Declared, as `base.mi` declares it: a shader the scene declares is mental ray's.)
        let declared = format!(
            "declare shader color \"mib_illum_lambert\" (color \"ambient\", color \"diffuse\") end declare\n{}",
            plane_under_environment(options, 4)
        );
        let (scene, _) = support::build_clean(&declared);
        assert_eq!(render::pipeline::choose_engine(&scene, None), want, "options {options}");
        assert_eq!(render::pipeline::choose_engine(&scene, Some(EngineKind::Classic)), EngineKind::Classic);
    }
}

/// `"light relative scale"` dims what legacy shaders receive, not the light on BSDF
/// materials: an MDL plane under a `physical_light` renders the same image, bit for bit,
/// with the option at 0.5 and without it (and is lit).
#[test]
fn light_relative_scale_leaves_mdl_materials_unchanged() {
    let render = |options: &str| {
        let parsed = mi::parse_str("t.mi", &crate::mdl_cornell::rectangle_lamp_over_mdl_plane(options));
        let b = support::build_parsed(&parsed, 4, &[support::mdl_modules()]);
        assert!(b.messages.is_empty(), "{:#?}", b.messages);
        let settings = Settings { engine: EngineKind::Path, spp: Some(16), ..Settings::default() };
        support::render_world(&b.built.world, &b.built.shading, &settings).0.rgba()
    };
    let scaled = render("\"light relative scale\" 0.5");
    let plain = render("");
    assert!(scaled.iter().all(|p| p[0] > 0.0), "{scaled:?}");
    assert_eq!(scaled, plain);
}

/// A camera and a point light at the centre of a closed UV sphere of radius 1 (24 rings, 48
/// segments) of Lambert albedo 0.5; `options` go into the options block. Every point of the
/// wall is lit alike, so its radiance after direct light, L0, is the same everywhere, and a
/// wall of uniform radiance L irradiates every point of the inside with πL: each indirect
/// bounce adds albedo times the radiance of the bounce before.
fn sphere_around_light(options: &str) -> String {
    let (rings, segments) = (24u32, 48u32);
    let mut verts = String::new();
    let mut vrefs = String::new();
    let mut polys = String::new();
    let mut n = 0u32;
    let mut push = |p: [f64; 3], verts: &mut String, vrefs: &mut String| {
        verts.push_str(&format!("    {} {} {}\n", p[0], p[1], p[2]));
        vrefs.push_str(&format!("v {n} "));
        n += 1;
        n - 1
    };
    let top = push([0.0, 1.0, 0.0], &mut verts, &mut vrefs);
    let mut ring_ids = Vec::new();
    for i in 1..rings {
        let theta = std::f64::consts::PI * f64::from(i) / f64::from(rings);
        let ids: Vec<u32> = (0..segments)
            .map(|j| {
                let phi = std::f64::consts::TAU * f64::from(j) / f64::from(segments);
                push([theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()], &mut verts, &mut vrefs)
            })
            .collect();
        ring_ids.push(ids);
    }
    let bottom = push([0.0, -1.0, 0.0], &mut verts, &mut vrefs);
    for j in 0..segments as usize {
        let k = (j + 1) % segments as usize;
        polys.push_str(&format!("    p \"wall\" {top} {} {}\n", ring_ids[0][j], ring_ids[0][k]));
        for r in 0..ring_ids.len() - 1 {
            let (a, b) = (&ring_ids[r], &ring_ids[r + 1]);
            polys.push_str(&format!("    p \"wall\" {} {} {} {}\n", a[j], b[j], b[k], a[k]));
        }
        let last = &ring_ids[ring_ids.len() - 1];
        polys.push_str(&format!("    p \"wall\" {bottom} {} {}\n", last[k], last[j]));
    }
    SceneText::new()
        .options(&format!("filter box 1 1 {options}"))
        .light("lamp", r#""mib_light_point" ("color" 1 1 1) origin 0 0 0"#, None)
        .text(&format!(
            r#"material "wall" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1) end material
object "ball" group
{verts}    {vrefs}
{polys}end group end object
instance "ball_inst" "ball" end instance"#
        ))
        .instance("ball_inst")
        .build()
}

/// `"gi depth"` with `"gi" on` bounds the indirect bounces. Inside the lit sphere
/// (`sphere_around_light`, albedo ρ = 0.5) the wall's radiance after n bounces is
/// L0 (1 + ρ + … + ρⁿ): `"gi depth" 0` renders L0 (direct light alone: ρ/π under the light
/// of intensity 1 at distance 1, within 2 %), `"gi depth" 1`
/// 1.5 L0 within 2 %, and `"gi" on` without `"gi depth"` the path engine's default depth
/// (16 rays, 15 bounces: L0 (1 − ρ¹⁶)/(1 − ρ) ≈ 2 L0) within 2 % (8², 256 spp; Russian
/// roulette past the third bounce leaves a standard error under 0.5 %). `"gi depth" 1`
/// without `"gi" on` is not GI "Next" and keeps the default depth (the same image bit for
/// bit as no option).
#[test]
fn gi_depth_bounds_the_indirect_bounces() {
    let mean = |options: &str, spp: u32| {
        let (px, messages) = render_path(&sphere_around_light(options), spp, PathSettings::default());
        assert!(messages.is_empty(), "{messages:#?}");
        mean_red(&px)
    };
    let l0 = mean("\"gi\" on \"gi depth\" 0", 4);
    // (The wall's direct radiance ρ I/(π R²) = 0.5/π, within 2 %: the flat facets are a
    // little nearer the light than R.)
    let direct = 0.5 / std::f32::consts::PI;
    assert!((l0 - direct).abs() < 0.02 * direct, "direct light {l0} vs {direct}");
    let one = mean("\"gi\" on \"gi depth\" 1", 64);
    eprintln!("gi depth 1: {one} = {} L0 (analytic 1.5)", one / l0);
    assert!((one / l0 - 1.5).abs() < 0.03, "gi depth 1: {} L0 vs 1.5", one / l0);
    let full = mean("\"gi\" on", 256);
    let expect = (1.0 - 0.5f32.powi(16)) / 0.5;
    eprintln!("gi default depth: {full} = {} L0 (analytic {expect})", full / l0);
    assert!((full / l0 - expect).abs() < 0.02 * expect, "default depth: {} L0 vs {expect}", full / l0);
    let (no_gi, _) = render_path(&sphere_around_light("\"gi depth\" 1"), 16, PathSettings::default());
    let (plain, _) = render_path(&sphere_around_light(""), 16, PathSettings::default());
    assert_eq!(no_gi, plain, "\"gi depth\" without \"gi\" on changes nothing");
}

/// `"gi rays"` is read but changes nothing in the path engine: a warning at the option says
/// so, and the image is the same bit for bit as without it.
#[test]
fn gi_rays_warns_and_leaves_the_image() {
    let text = sphere_around_light("\"gi\" on \"gi depth\" 1 \"gi rays\" 64");
    let messages = support::compile(&text).messages;
    assert!(
        messages.iter().any(|m| m.contains("t.mi:2:51: warning: \"gi rays\" does not change mira's path engine")),
        "{messages:#?}"
    );
    let (px, _) = {
        let support::Compiled { scene, shading, .. } = support::compile(&text);
        let world = render::World::from_scene_shaded(&scene, Some(&shading));
        let settings = Settings { engine: EngineKind::Path, spp: Some(4), ..Settings::default() };
        (support::render_world(&world, &shading, &settings).0.rgba(), ())
    };
    let (plain, _) = render_path(&sphere_around_light("\"gi\" on \"gi depth\" 1"), 4, PathSettings::default());
    assert_eq!(px, plain);
}

/// `"gi depth" 0` (direct light alone) keeps the whole direct light of a light that is found
/// both ways (MIS): at the last vertex light sampling takes all of it, as no scattered ray
/// follows. The plane under the constant environment shows albedo × L = 1 within 3 % (8²,
/// 1024 spp, MIS on; as `environment_lighting_off_is_no_light_and_light_is_sampled`).
#[test]
fn gi_depth_zero_keeps_the_whole_direct_light() {
    let text = plane_under_environment("\"gi\" on \"gi depth\" 0", 8);
    let (px, messages) = render_path(&text, 1024, PathSettings::default());
    assert!(messages.is_empty(), "{messages:#?}");
    let (plane, _) = halves(&px);
    let m = mean_red(&plane);
    eprintln!("gi depth 0 under the environment: {m} (analytic 1)");
    assert!((m - 1.0).abs() < 0.03, "plane {m} vs 1");
}
