//! Environment lighting in the path engine: a white furnace (a Lambert sphere in a constant
//! environment has radiance albedo × L everywhere), MIS on and off agreeing, importance
//! sampling of a bright region against cosine sampling, and `mia_portal_light` over a
//! window against the environment through the open window.

use crate::support;

use bsdf::Rgb;
use glam::Vec3A;
use render::environment::{Environment, Source};
use render::integrator::{constant_materials, plain_materials, trace_path, PathScene, PathSettings};
use render::ray::RayCounts;
use render::sampler::{pixel_seed, Sampler};
use render::{EngineKind, Settings};
use shader::Shading;

/// An orthographic camera at the origin looking down −Z at a 2×2 view (`res`² pixels),
/// the camera's environment `env`; `body` holds the rest, `extra` names its instances.
fn scene(env: &str, body: &str, extra: &[&str], res: u32) -> String {
    let instances: String = extra.iter().map(|n| format!(" \"{n}\"")).collect();
    format!(
        r#"
options "opt" filter box 1 1 end options
camera "cam" focal infinity aperture 2 aspect 1 resolution {res} {res} {env} end camera
instance "cam_inst" "cam" end instance
{body}
instgroup "root" "cam_inst"{instances} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// A white constant environment of radiance `l`.
fn constant_env(l: f32) -> String {
    format!(r#"environment "mib_color_mix" ("num" 0, "color_base" {l} {l} {l} 1)"#)
}

/// Builds a scene: world, shading and diagnostics.
fn build(text: &str) -> (render::World, Shading, Vec<String>) {
    let support::Compiled { scene, shading, mut messages, .. } = support::compile(text);
    let world = render::World::from_scene_shaded(&scene, Some(&shading));
    messages.extend(world.warnings.iter().cloned());
    (world, shading, messages)
}

fn render(world: &render::World, shading: &Shading, spp: u32, mis: bool) -> Vec<[f32; 4]> {
    let path = PathSettings { mis, ..PathSettings::default() };
    let settings = Settings { engine: EngineKind::Path, spp: Some(spp), path, ..Settings::default() };
    support::render_world(world, shading, &settings).0.rgba()
}

fn mean(px: &[[f32; 4]]) -> f32 {
    px.iter().map(|p| p[0]).sum::<f32>() / px.len() as f32
}

/// A UV sphere of radius `r` at (0, 0, −5) with material "ball_mtl", as `.mi` text.
pub(crate) fn ball(r: f32) -> String {
    let (rings, segments) = (48, 96);
    let mut v = String::new();
    for i in 0..=rings {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = std::f32::consts::TAU * j as f32 / segments as f32;
            let (x, y, z) = (theta.sin() * phi.cos() * r, theta.sin() * phi.sin() * r, theta.cos() * r - 5.0);
            v += &format!("{x} {y} {z}\n");
        }
    }
    let count = (rings + 1) * segments;
    let refs: String = (0..count).map(|i| format!("v {i} ")).collect();
    let mut polys = String::new();
    for i in 0..rings {
        for j in 0..segments {
            let a = i * segments + j;
            let b = i * segments + (j + 1) % segments;
            let (c, d) = (a + segments, b + segments);
            // Outward-facing (counter-clockwise seen from outside).
            polys += &format!("c \"ball_mtl\" {a} {c} {d} {b}\n");
        }
    }
    format!(
        "object \"ball\" group\n{v}{refs}\n{polys}end group end object\ninstance \"ball_inst\" \"ball\" end instance\n"
    )
}

const LAMBERT_HALF: &str =
    r#"material "ball_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1) end material"#;

#[test]
fn white_furnace_sphere_is_albedo_times_the_environment() {
    let body = format!("{LAMBERT_HALF}\n{}", ball(1.0));
    let (world, shading, messages) = build(&scene(&constant_env(2.0), &body, &["ball_inst"], 16));
    assert!(messages.is_empty(), "{messages:?}");
    let px = render(&world, &shading, 64, true);
    let (mut inside, mut n) = (0.0, 0);
    for (i, p) in px.iter().enumerate() {
        let (x, y) = ((i % 16) as f32 / 8.0 - 1.0 + 1.0 / 16.0, (i / 16) as f32 / 8.0 - 1.0 + 1.0 / 16.0);
        let r = (x * x + y * y).sqrt();
        if r > 1.1 {
            // The camera sees the environment itself.
            assert!((p[0] - 2.0).abs() < 1e-5 && p[3] == 1.0, "background pixel {i}: {p:?}");
        } else if r < 0.85 {
            // A convex Lambert surface sees only the environment: albedo × L exactly.
            assert!((p[0] - 1.0).abs() < 0.05, "sphere pixel {i}: {p:?}");
            inside += p[0];
            n += 1;
        }
    }
    let m = inside / n as f32;
    eprintln!("white furnace: sphere mean {m} (exact 1.0) over {n} pixels");
    assert!((m - 1.0).abs() < 0.01, "sphere mean {m}");
}

#[test]
fn mis_on_and_off_agree_under_an_environment() {
    // The sphere in a constant environment from the shader graph (light sampling and BSDF
    // sampling both find it).
    let env = &constant_env(1.0);
    let body = format!("{LAMBERT_HALF}\n{}", ball(1.0));
    let (world, shading, _) = build(&scene(env, &body, &["ball_inst"], 16));
    let on = mean(&render(&world, &shading, 128, true));
    let off = mean(&render(&world, &shading, 128, false));
    eprintln!("MIS on {on}, off {off}");
    assert!((on - off).abs() < 0.01 * on, "MIS on {on} vs off {off}");
}

/// A dim blue sky with a bright disc of radius 8° around `centre`.
fn bright_spot(centre: Vec3A) -> Environment<'static> {
    Environment::new(Source::Function(Box::new(move |d: Vec3A| {
        if d.dot(centre) > 0.99 {
            Rgb::splat(200.0)
        } else {
            Rgb::new(0.2, 0.3, 0.5)
        }
    })))
}

/// Renders the plane with `env` through [`trace_path`] (`res`² pixels, `spp` each); the
/// pixel values' mean and variance.
pub(crate) fn plane_stats(world: &render::World, env: &Environment, res: u32, spp: u32) -> (f64, f64) {
    let accel = render::accel::build(world, render::Backend::default_available());
    let settings = PathSettings::default();
    let constants = constant_materials(world);
    let plain = plain_materials(world, None);
    let scene =
        PathScene { world, accel: accel.as_ref(), shading: None, env: Some(env), constants: &constants, plain: &plain };
    let mut values = Vec::new();
    for y in 0..res {
        for x in 0..res {
            let mut sum = 0.0f64;
            for index in 0..spp {
                let mut sampler = Sampler::new(pixel_seed(x, y, 7), index);
                let _ = sampler.next_2d();
                let ray = world.camera.ray(x as f32 + 0.5, y as f32 + 0.5);
                let mut counts = RayCounts::default();
                let r = trace_path(&scene, ray, &Default::default(), &mut sampler, &settings, &mut counts);
                sum += f64::from(r.radiance.x);
            }
            values.push(sum / f64::from(spp));
        }
    }
    let m = values.iter().sum::<f64>() / values.len() as f64;
    let var = values.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (values.len() - 1) as f64;
    (m, var)
}

#[test]
fn importance_sampling_beats_cosine_sampling_on_a_bright_region() {
    // A large Lambert plane (albedo 0.5) facing the camera, +Z up; the environment's bright
    // disc 40° from the normal. Radiance everywhere: 0.5/π × E, E = 0.2 π + 199.8 · n·c ·
    // π (1 − 0.99²) (the disc lies wholly above the horizon; only the red channel is read).
    let body = r#"material "ball_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1) end material
object "plane" group
    -50 -50 -5  50 -50 -5  50 50 -5  -50 50 -5
    v 0 v 1 v 2 v 3
    c "ball_mtl" 0 1 2 3
end group end object
instance "plane_inst" "plane" end instance"#;
    let (world, _, messages) = build(&scene("", body, &["plane_inst"], 16));
    assert!(messages.is_empty(), "{messages:?}");
    let centre = Vec3A::new(40f32.to_radians().sin(), 0.0, 40f32.to_radians().cos());
    let exact = 0.5 / std::f64::consts::PI
        * (0.2 * std::f64::consts::PI + 199.8 * f64::from(centre.z) * std::f64::consts::PI * (1.0 - 0.99 * 0.99));
    let sampled = bright_spot(centre);
    let mut cosine = bright_spot(centre);
    cosine.sampled = false;
    let (m_imp, v_imp) = plane_stats(&world, &sampled, 16, 16);
    let (m_cos, v_cos) = plane_stats(&world, &cosine, 16, 16);
    eprintln!(
        "plane radiance {exact:.4}: importance sampling {m_imp:.4} (pixel variance {v_imp:.5}), cosine sampling {m_cos:.4} (pixel variance {v_cos:.5}) at 16 spp"
    );
    assert!((m_imp - exact).abs() < 0.01 * exact, "importance sampled {m_imp} vs {exact}");
    assert!((m_cos - exact).abs() < 5.0 * (v_cos / 256.0).sqrt(), "cosine sampled {m_cos} vs {exact}");
    assert!(v_imp * 10.0 < v_cos, "variance {v_imp} (importance) vs {v_cos} (cosine)");
}

/// A 2×2×1 room on a floor at z = −5 (walls and ceiling black and invisible to the camera)
/// whose ceiling at z = −4 has a 1×1 window in the middle; white constant environment.
fn room(lights: &str, extra: &[&str]) -> String {
    let body = format!(
        r#"{lights}
material "floor_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1) end material
material "black" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0 0 0 1) end material
object "floor" group
    -2 -2 -5  2 -2 -5  2 2 -5  -2 2 -5
    v 0 v 1 v 2 v 3
    c "floor_mtl" 0 1 2 3
end group end object
instance "floor_inst" "floor" end instance
object "room" group
    -1 -1 -4  1 -1 -4  1 1 -4  -1 1 -4
    -0.5 -0.5 -4  0.5 -0.5 -4  0.5 0.5 -4  -0.5 0.5 -4
    -1 -1 -5  1 -1 -5  1 1 -5  -1 1 -5
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7 v 8 v 9 v 10 v 11
    c "black" 0 1 5 4
    c "black" 1 2 6 5
    c "black" 2 3 7 6
    c "black" 3 0 4 7
    c "black" 8 9 1 0
    c "black" 9 10 2 1
    c "black" 10 11 3 2
    c "black" 11 8 0 3
end group end object
instance "room_inst" "room" visible off end instance"#
    );
    let mut all = vec!["floor_inst", "room_inst"];
    all.extend_from_slice(extra);
    scene(&constant_env(1.0), &body, &all, 16)
}

const PORTAL: &str = r#"light "portal" "mia_portal_light" ("multiplier" 1) origin 0 0 -4 rectangle 1 0 0 0 -1 0 8 8 end light
instance "portal_inst" "portal" end instance"#;

/// The floor pixels inside the room (the camera sees the floor through the invisible
/// ceiling; the room spans the middle 8×8 pixels).
fn room_floor(px: &[[f32; 4]]) -> Vec<[f32; 4]> {
    px.iter()
        .enumerate()
        .filter(|(i, _)| (4..12).contains(&(i % 16)) && (4..12).contains(&(i / 16)))
        .map(|(_, p)| *p)
        .collect()
}

#[test]
fn portal_light_matches_the_environment_through_the_open_window() {
    let (wa, sa, ma) = build(&room("", &[]));
    assert!(ma.is_empty(), "{ma:?}");
    let (wb, sb, mb) = build(&room(PORTAL, &["portal_inst"]));
    assert!(mb.is_empty(), "{mb:?}");
    assert!(wb.lights.len() == 1 && wb.lights[0].is_portal());
    let open = room_floor(&render(&wa, &sa, 256, true));
    let full = render(&wb, &sb, 256, true);
    let lit = room_floor(&full);
    let (a, b) = (mean(&open), mean(&lit));
    eprintln!("room floor: open window {a}, portal {b}");
    // Counting the environment twice (portal and sky) would double it.
    assert!((a - b).abs() < 0.03 * a, "open window {a} vs portal {b}");
    // Straight below the window's centre: albedo × the square's form factor 0.23945 from
    // one unit below its centre.
    let want = 0.5 * 0.23945;
    let centre: Vec<[f32; 4]> = [7 * 16 + 7, 7 * 16 + 8, 8 * 16 + 7, 8 * 16 + 8].iter().map(|&i| full[i]).collect();
    let c = mean(&centre);
    eprintln!("portal centre {c}, analytic {want}");
    assert!((c - want).abs() < 0.03 * want, "portal centre {c} vs {want}");
    // Without MIS the same.
    let off = mean(&room_floor(&render(&wb, &sb, 256, false)));
    assert!((off - b).abs() < 0.03 * b, "portal without MIS {off} vs {b}");
    // A reversed portal faces the sky: rays from the room cross it from behind, so it
    // neither lights the room nor takes the sky's place — the open window again.
    let reversed = room(&PORTAL.replace(r#""multiplier" 1"#, r#""multiplier" 1, "reverse" on"#), &["portal_inst"]);
    let (wr, sr, _) = build(&reversed);
    let back = mean(&room_floor(&render(&wr, &sr, 256, true)));
    assert!((back - a).abs() < 0.03 * a, "reversed portal {back} vs open window {a}");
    // A portal with twice the multiplier brings twice the light (the sky is not added).
    let double = room(&PORTAL.replace(r#""multiplier" 1"#, r#""multiplier" 2"#), &["portal_inst"]);
    let (wd, sd, _) = build(&double);
    let twice = mean(&room_floor(&render(&wd, &sd, 256, true)));
    assert!((twice - 2.0 * b).abs() < 0.03 * 2.0 * b, "multiplier 2: {twice} vs 2 × {b}");
}

#[test]
fn iray_environment_function_lights_and_scales() {
    // No camera environment: the options name the shader, and its intensity multiplies it.
    let text = r#"
shader "env" "mib_color_mix" ("num" 0, "color_base" 0.5 0.5 0.5 1)
options "opt" filter box 1 1
    attribute string "environment_function" "env"
    attribute scalar "environment_function_intensity" 2
end options
camera "cam" focal infinity aperture 2 aspect 1 resolution 4 4 end camera
instance "cam_inst" "cam" end instance
instgroup "root" "cam_inst" end instgroup
render "root" "cam_inst" "opt"
"#;
    let (world, shading, messages) = build(text);
    assert!(messages.is_empty(), "{messages:?}");
    for p in render(&world, &shading, 1, true) {
        assert!((p[0] - 1.0).abs() < 1e-6, "{p:?}");
    }
    // A name that is no shader: a warning and no environment, not a crash.
    let (world, shading, messages) =
        build(&text.replace(r#""environment_function" "env""#, r#""environment_function" "nope""#));
    assert!(messages.iter().any(|m| m.contains("environment_function")), "{messages:?}");
    assert!(render(&world, &shading, 1, true).iter().all(|p| p[0] == 0.0));
}
