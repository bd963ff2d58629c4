//! Object area lights against the equivalent rectangle in both engines, and
//! `mia_portal_light` over a window against final gathering through the open window.

use crate::support;

use bsdf::Rgb;
use render::light::{Output, Shape};
use render::{EngineKind, Settings};
use shader::Shading;

/// An orthographic camera looking down −Z at a 2×2 view (`res`² pixels) and a 4×4 plane
/// at z = −5 of material "plane_mtl"; `body` adds the rest, `extra` names instances.
fn scene(options: &str, camera: &str, body: &str, extra: &[&str], res: u32) -> String {
    let instances: String = extra.iter().map(|n| format!(" \"{n}\"")).collect();
    format!(
        r#"
options "opt" filter box 1 1 {options} end options
camera "cam" focal infinity aperture 2 aspect 1 resolution {res} {res} {camera} end camera
instance "cam_inst" "cam" end instance
{body}
object "plane" group
    -2 -2 -5  2 -2 -5  2 2 -5  -2 2 -5
    v 0 v 1 v 2 v 3
    c "plane_mtl" 0 1 2 3
end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "plane_inst"{instances} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Builds a scene: world, shading and diagnostics.
fn build(text: &str) -> (render::World, Shading, Vec<String>) {
    let support::Compiled { scene, shading, mut messages, .. } = support::compile(text);
    let world = render::World::from_scene(&scene);
    messages.extend(world.warnings.iter().cloned());
    (world, shading, messages)
}

fn render(world: &render::World, shading: &Shading, engine: EngineKind, spp: u32) -> Vec<[f32; 4]> {
    let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
    support::render_world(world, shading, &settings).0.rgba()
}

fn mean(px: &[[f32; 4]]) -> f32 {
    px.iter().map(|p| p[0]).sum::<f32>() / px.len() as f32
}

/// A unit-square light one unit above the plane, facing it: a rectangle, or the object
/// "lamp" (two triangles, invisible to every ray) named as the light's surface.
fn lamp_scene(shape: &str) -> String {
    let body = format!(
        r#"
light "L" "mib_light_point" ("color" 1 1 1, "shadow" on) origin 0 0 -4 {shape} end light
instance "L_inst" "L" end instance
material "plane_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1, "mode" 3) end material
object "lamp" group
    -0.5 -0.5 -4  0.5 -0.5 -4  0.5 0.5 -4  -0.5 0.5 -4
    v 0 v 1 v 2 v 3
    c "plane_mtl" 0 3 2 1
end group end object
instance "lamp_inst" "lamp" visible off shadow off trace off end instance"#
    );
    scene("samples 0 2", "", &body, &["L_inst", "lamp_inst"], 16)
}

#[test]
fn object_light_is_its_triangles_in_world_space() {
    let (world, shading, messages) = build(&lamp_scene(r#"object "lamp_inst" 4 4"#));
    assert!(messages.is_empty(), "{messages:?}");
    let Shape::Mesh(m) = &world.lights[0].shape else { panic!("{:?}", world.lights[0].shape) };
    assert_eq!(m.len(), 2);
    assert!((m.area() - 1.0).abs() < 1e-6);
    let q = glam::Vec3A::new(0.1, 0.2, -4.0);
    assert!((m.normal_at(q) - glam::Vec3A::NEG_Z).length() < 1e-6);
    assert!(matches!(shading.lights[0].shape, Some(Shape::Mesh(_))));
    // A missing instance is a warning, not a crash.
    let (world, _, messages) = build(&lamp_scene(r#"object "nothing" 4 4"#));
    assert!(world.lights.is_empty());
    assert!(messages.iter().any(|m| m.contains("no object instance 'nothing'")), "{messages:?}");
}

#[test]
fn object_light_matches_the_equivalent_rectangle_in_the_classic_engine() {
    let (wr, sr, m1) = build(&lamp_scene("rectangle 0 1 0 1 0 0 4 4"));
    let (wo, so, m2) = build(&lamp_scene(r#"object "lamp_inst" 4 4"#));
    assert!(m1.is_empty() && m2.is_empty(), "{m1:?} {m2:?}");
    let rect = render(&wr, &sr, EngineKind::Classic, 16);
    let obj = render(&wo, &so, EngineKind::Classic, 16);
    // Mean over the image within 0.5 %, every pixel within 0.02 (16 × 16 light samples
    // per pixel, two different but uniform point sets on the same square).
    let (a, b) = (mean(&rect), mean(&obj));
    eprintln!("classic: rectangle {a}, object {b}");
    assert!((a - b).abs() < 0.005 * a, "rectangle {a} vs object {b}");
    for (i, (p, q)) in rect.iter().zip(&obj).enumerate() {
        assert!((p[0] - q[0]).abs() < 0.02, "pixel {i}: {p:?} vs {q:?}");
    }
    // Straight below the centre: 0.5 × the mean cosine over the square, near 0.5 × 0.84.
    assert!(a > 0.1 && a < 0.5, "{a}");
}

#[test]
fn object_light_matches_the_equivalent_rectangle_in_the_path_engine() {
    // The same lights made physical (radiance 1, seen by rays), so that the path engine's
    // light sampling, intersection and MIS all see the triangles.
    let physical = |text: &str| {
        let (mut w, s, m) = build(text);
        assert!(m.is_empty(), "{m:?}");
        w.lights[0].output = Output::Radiance { l: Rgb::splat(1.0), two_sided: false };
        w.lights[0].visible = true;
        (w, s)
    };
    let (wr, sr) = physical(&lamp_scene("rectangle 0 1 0 1 0 0 4 4"));
    let (wo, so) = physical(&lamp_scene(r#"object "lamp_inst" 4 4"#));
    let rect = render(&wr, &sr, EngineKind::Path, 256);
    let obj = render(&wo, &so, EngineKind::Path, 256);
    let (a, b) = (mean(&rect), mean(&obj));
    eprintln!("path: rectangle {a}, object {b}");
    assert!((a - b).abs() < 0.01 * a, "rectangle {a} vs object {b}");
    // Quadrant means agree too (the light's position, not only its power).
    for quad in 0..4 {
        let pick = |px: &[[f32; 4]]| {
            let v: Vec<[f32; 4]> = px
                .iter()
                .enumerate()
                .filter(|(i, _)| ((i % 16) / 8) + 2 * ((i / 16) / 8) == quad)
                .map(|(_, p)| *p)
                .collect();
            mean(&v)
        };
        let (qa, qb) = (pick(&rect), pick(&obj));
        assert!((qa - qb).abs() < 0.02 * qa, "quadrant {quad}: {qa} vs {qb}");
    }
}

/// A 2×2×1 room on the plane (walls and ceiling black and invisible to the camera) whose
/// ceiling at z = −4 has a 1×1 window in the middle; white constant environment.
fn room(options: &str, lights: &str, extra: &[&str]) -> String {
    let body = format!(
        r#"{lights}
material "plane_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1, "mode" 3) end material
material "black" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0 0 0 1) end material
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
    let mut all = vec!["room_inst"];
    all.extend_from_slice(extra);
    scene(options, r#"environment "mib_color_mix" ("num" 0, "color_base" 1 1 1 1)"#, &body, &all, 16)
}

#[test]
fn portal_light_matches_final_gathering_through_the_open_window() {
    let fg = "samples 0 2 finalgather on finalgather accuracy 1024";
    let (wa, sa, ma) = build(&room(fg, "", &[]));
    assert!(ma.is_empty(), "{ma:?}");
    let open = render(&wa, &sa, EngineKind::Classic, 16);
    // The portal faces down into the room (edges x and −y: normal −z).
    let portal = r#"light "portal" "mia_portal_light" ("multiplier" 1) origin 0 0 -4 rectangle 1 0 0 0 -1 0 8 8 end light
instance "portal_inst" "portal" end instance"#;
    let (wb, sb, mb) = build(&room(fg, portal, &["portal_inst"]));
    // Only the path engine's translation complains (it has no portal lights).
    assert!(mb.iter().all(|m| m.contains("mia_portal_light")), "{mb:?}");
    let lit = render(&wb, &sb, EngineKind::Classic, 16);
    let (a, b) = (mean(&open), mean(&lit));
    eprintln!("open window {a}, portal {b}");
    assert!((a - b).abs() < 0.02 * a, "open window (final gather) {a} vs portal {b}");
    // Straight below the window's centre: ½ × π × the square's form factor 0.2394 from
    // one unit below its centre (base shaders: diffuse × irradiance, no 1/π).
    let want = 0.5 * std::f32::consts::PI * 0.23945;
    let centre: Vec<[f32; 4]> = [7 * 16 + 7, 7 * 16 + 8, 8 * 16 + 7, 8 * 16 + 8].iter().map(|&i| lit[i]).collect();
    let c = mean(&centre);
    eprintln!("portal centre {c}, analytic {want}");
    assert!((c - want).abs() < 0.02 * want, "portal centre {c} vs {want}");
}
