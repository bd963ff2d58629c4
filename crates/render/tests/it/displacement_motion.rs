//! Displacement of meshes whose vertices move (`crate::displace::moving`): every motion
//! step displaced on the same finer triangles, measured by ray hits at the shutter's
//! opening and close, a closed moving mesh that stays closed, both engines rendering
//! the displaced surface where the motion has carried it, and a moving instance carrying
//! its displaced triangles rigidly.

use std::collections::HashMap;

use glam::Vec3A;
use render::accel::{self, Backend};
use render::ray::Ray;
use render::{EngineKind, Settings};

use crate::displacement::{build, constant_material};
use crate::support;

/// The unit square of `displacement::plane` whose four vertices carry the motion vector
/// `motion` (one motion step), under options `options`, its object carrying
/// `object_stmts`.
fn moving_plane(options: &str, body: &str, object_stmts: &str, motion: &str) -> String {
    format!(
        r#"
options "opt" {options} end options
camera "cam" focal 1 aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" transform 1 0 0 0 0 1 0 0 0 0 1 0 -0.5 -0.5 -3 1 end instance
{body}
object "square"
    {object_stmts}
    group
    0 0 0  1 0 0  1 1 0  0 1 0
    0 0 0  1 0 0  1 1 0  0 1 0
    {motion}
    v 0 t 4 m 8 v 1 t 5 m 8 v 2 t 6 m 8 v 3 t 7 m 8
    p 0 1 2 3
end group end object
instance "square_inst" "square" material "m" end instance
instgroup "root" "cam_inst" "square_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Where a ray from `from` along `dir` at shutter time `time` hits the world (Rust
/// backend): the distance.
fn hit_at(world: &render::World, from: Vec3A, dir: Vec3A, time: f32) -> Option<f32> {
    let bvh = accel::build(world, Backend::Rust);
    let mut ray = Ray::new(from, dir);
    ray.time = time;
    bvh.intersect(&ray).map(|h| h.t)
}

/// A plane displaced by the constant d = 0.375 whose vertices slide by (0.5, 0, 0.25)
/// over the shutter (`motion on shutter 0 1`): at the shutter's opening (time 0) the
/// surface is at height d over x ∈ (0, 1) and absent at x = 1.25; at its close (time 1)
/// it is at 0.25 + d over x ∈ (0.5, 1.5) and absent at x = 0.25 (1e-4), with the
/// object's own vertices and with 4 × 4 subdivision and the adaptive `length` form
/// alike. Undisplaced at the close it would be at 0.25, still at d.
#[test]
fn a_moving_plane_is_displaced_at_every_motion_step() {
    for approx in ["", "approximate displace regular parametric 2", "approximate displace length 0.3 0 4"] {
        let text = moving_plane("motion on shutter 0 1", &constant_material(0.375), approx, "0.5 0 0.25");
        let b = build(&text);
        assert!(!b.messages.iter().any(|m| m.contains("error") || m.contains("vertices move")), "{:?}", b.messages);
        let world = &b.built.world;
        let height =
            |x: f32, y: f32, time: f32| hit_at(world, Vec3A::new(x, y, 10.0), Vec3A::NEG_Z, time).map(|t| 10.0 - t);
        for (x, y) in [(0.1, 0.1), (0.5, 0.5), (0.9, 0.3), (0.25, 0.75)] {
            let h = height(x, y, 0.0).expect("hit at the opening");
            assert!((h - 0.375).abs() < 1e-4, "{approx}: opening ({x}, {y}) at {h}");
            let h = height(x + 0.5, y, 1.0).expect("hit at the close");
            assert!((h - 0.625).abs() < 1e-4, "{approx}: close ({x}, {y}) at {h}");
        }
        assert_eq!(height(1.25, 0.5, 0.0), None, "{approx}");
        assert_eq!(height(0.25, 0.5, 1.0), None, "{approx}");
    }
}

/// A closed tetrahedron whose vertices grow by half and slide 1 along x over the
/// shutter (each vertex's motion vector 0.5·p + (1, 0, 0)), displaced outwards by 0.05
/// and refined until every edge is at most 0.25 (`length 0.25`): every edge of the
/// displaced mesh is shared by exactly two triangles (one topology for both steps), and
/// at the shutter's opening, middle and close, rays from the tetrahedron's centre then in
/// 200 directions all hit its surface (no crack at any time), at least as far as the
/// undisplaced nearest face (0.25/√3 = 0.144 at the opening, 0.217 at the close).
#[test]
fn a_closed_moving_mesh_stays_closed_at_every_step() {
    let text = r#"
options "opt" motion on shutter 0 1 end options
camera "cam" focal 1 aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 0 -5 1 end instance
shader "lam" "mib_illum_lambert" ("diffuse" 1 1 1)
shader "disp" "maya_material_displace" ("displacement" 0.05)
material "m" = "lam" displace = "disp" end material
object "tet"
    approximate displace length 0.25 0 6
    group
    0 0 0  1 0 0  0 1 0  0 0 1
    1 0 0  1.5 0 0  1 0.5 0  1 0 0.5
    v 0 m 4 v 1 m 5 v 2 m 6 v 3 m 7
    p 0 2 1  p 0 1 3  p 0 3 2  p 1 2 3
end group end object
instance "tet_inst" "tet" material "m" end instance
instgroup "root" "cam_inst" "tet_inst" end instgroup
render "root" "cam_inst" "opt"
"#;
    let b = build(text);
    assert!(!b.messages.iter().any(|m| m.contains("error") || m.contains("vertices move")), "{:?}", b.messages);
    let world = &b.built.world;
    let mesh = &world.meshes[world.instances[0].mesh as usize];
    assert!(mesh.triangles.len() > 4 * 16, "{}", mesh.triangles.len());
    assert_eq!(mesh.position_keys.len(), 2, "one key per end of the motion step");
    let mut count: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    assert!(count.values().all(|&n| n == 2), "an edge not shared by two triangles");
    // The centre's distance to the nearest (slanted) face, x + y + z = 1: 0.25 / √3.
    let near = 0.25 / 3f32.sqrt();
    for time in [0.0f32, 0.5, 1.0] {
        let scale = 1.0 + 0.5 * time;
        let centre = Vec3A::splat(0.25) * scale + Vec3A::new(time, 0.0, 0.0);
        for k in 0..200 {
            // Directions spread over the sphere (a Fibonacci lattice).
            let z = 1.0 - (k as f32 + 0.5) / 100.0;
            let phi = k as f32 * 2.399_963;
            let r = (1.0 - z * z).sqrt();
            let dir = Vec3A::new(r * phi.cos(), r * phi.sin(), z);
            let t = hit_at(world, centre, dir, time).unwrap_or_else(|| panic!("time {time}: no hit along {dir}"));
            assert!(t >= near * scale, "time {time}: {dir} at {t}");
        }
    }
}

/// Both engines trace the displaced moving triangles: a square 3 below a 90° camera whose
/// vertices rise by 0.75 over the motion interval, displaced 1.5 towards the camera, seen
/// through a tiny shutter at the interval's end (`shutter 0.999 1`), stands 0.75 below
/// the camera and covers the middle 16/3 ≈ 5.33 pixels across at 8 × 8: pixels 2…5 are
/// fully covered and evenly lit (within 2 % of the lambert's π in the classic engine, 1
/// in the path engine), the pixels of columns 1 and 6 two thirds covered (± 0.05) and
/// column 0 empty — where the undisplaced moving square (2.25 below) or the displaced
/// square left where it starts (1.5 below) would leave columns 2 and 5 partly empty.
#[test]
fn both_engines_render_the_displaced_moving_surface() {
    let body = r#"light "sun" "mib_light_infinite" ("color" 3.14159265 3.14159265 3.14159265) direction 0 0 -1 end light
instance "sun_inst" "sun" end instance
shader "lam" "mib_illum_lambert" ("diffuse" 1 1 1, "lights" ["sun_inst"])
shader "disp" "maya_material_displace" ("displacement" 1.5)
material "m" = "lam" displace = "disp" end material"#;
    let text = moving_plane("filter box 1 1 motion on shutter 0.999 1", body, "", "0 0 0.75").replace(
        r#"instgroup "root" "cam_inst" "square_inst""#,
        r#"instgroup "root" "cam_inst" "sun_inst" "square_inst""#,
    );
    let b = build(&text);
    assert!(!b.messages.iter().any(|m| m.contains("error") || m.contains("vertices move")), "{:?}", b.messages);
    for (engine, spp, lambert) in [(EngineKind::Classic, 16, std::f32::consts::PI), (EngineKind::Path, 64, 1.0)] {
        let settings = Settings { engine, spp: Some(spp), ..Settings::default() };
        let px = support::render_world(&b.built.world, &b.built.shading, &settings).0.rgba();
        let middle = support::mean(&px, 8, (2, 6), (2, 6));
        assert!(middle.iter().all(|c| (c / lambert - 1.0).abs() < 0.02), "{engine:?}: {middle:?}");
        for columns in [(1, 2), (6, 7)] {
            let edge = support::mean(&px, 8, columns, (2, 6));
            assert!((edge[1] / middle[1] - 2.0 / 3.0).abs() < 0.05, "{engine:?}: edge {columns:?} {edge:?}");
        }
        let outside = support::mean(&px, 8, (0, 1), (0, 8));
        assert!(outside[1] < 1e-6, "{engine:?}: {outside:?}");
    }
}

/// An instance that moves (`motion transform`: +0.5 in x at the shutter's close) carries
/// its displaced triangles with it: the square displaced by the constant d = 0.375 stands
/// at height d over x ∈ (0, 1) at the opening and over x ∈ (0.5, 1.5) at the close
/// (1e-4), and is absent at x = 1.25 at the opening and at x = 0.25 at the close. The
/// displacement is evaluated once (as mental ray's tessellator calls the displacement
/// shader, once per vertex it makes) and moves rigidly with the instance.
#[test]
fn a_moving_instance_carries_its_displaced_surface() {
    let text = crate::displacement::plane("motion on shutter 0 1", &constant_material(0.375), "", "m").replace(
        r#"material "m" end instance"#,
        r#"material "m" motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -0.5 0 0 1 end instance"#,
    );
    assert!(text.contains("motion transform"), "{text}");
    let b = build(&text);
    assert!(!b.messages.iter().any(|m| m.contains("error")), "{:?}", b.messages);
    let world = &b.built.world;
    let height =
        |x: f32, y: f32, time: f32| hit_at(world, Vec3A::new(x, y, 10.0), Vec3A::NEG_Z, time).map(|t| 10.0 - t);
    for (x, y) in [(0.1, 0.1), (0.5, 0.5), (0.9, 0.3)] {
        let h = height(x, y, 0.0).expect("hit at the opening");
        assert!((h - 0.375).abs() < 1e-4, "opening ({x}, {y}) at {h}");
        let h = height(x + 0.5, y, 1.0).expect("hit at the close");
        assert!((h - 0.375).abs() < 1e-4, "close ({x}, {y}) at {h}");
    }
    assert_eq!(height(1.25, 0.5, 0.0), None);
    assert_eq!(height(0.25, 0.5, 1.0), None);
}

/// A moving instance's `view length 1` holds over the whole shutter: the square of
/// `displacement::plane` (displaced 0.25 towards the camera) rises from depth 2.75 at the
/// shutter's opening to 1.25 at its close (`motion transform`, `motion on shutter 0 1`,
/// a 64-pixel 90° camera). The criterion is measured where the instance stands at each of
/// its keys (the largest on-screen size over the shutter: see `displace::adaptive::View`),
/// so every edge spans at most one pixel diagonal at the close, seen at its middle's depth
/// there (1e-4), and at the opening; the same square standing still at the opening's
/// place, planned there alone, has an edge longer than a pixel diagonal at the close's
/// place (what planning at motion time 0 gave) and fewer than half the triangles.
#[test]
fn a_moving_instances_view_criteria_hold_over_the_shutter() {
    let approx = "approximate displace view length 1 0 8";
    let still = crate::displacement::plane("motion on shutter 0 1", &constant_material(0.25), approx, "m");
    let moving = still.replace(
        r#"material "m" end instance"#,
        r#"material "m" motion transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -1.5 1 end instance"#,
    );
    assert!(moving.contains("motion transform"), "{moving}");
    let built = |text: &str| support::build_parsed(&mi::parse_str("t.mi", text), 64, &[]);
    let (still, moving) = (built(&still), built(&moving));
    for b in [&still, &moving] {
        assert!(!b.messages.iter().any(|m| m.contains("error") || m.contains("warning")), "{:?}", b.messages);
    }
    // The largest edge, in pixel diagonals (as the criterion measures: world length ×
    // 64/2 ÷ the depth of its middle ÷ √2), of the instance's mesh placed at shutter time
    // `time` (`place`: the moving instance's placement there).
    let widest = |b: &support::BuiltScene, place: &render::world::InstanceData, time: f32| {
        let world = &b.built.world;
        let [inst] = &world.instances[..] else { panic!("one instance") };
        let to_world = place.object_to_world_at(time);
        let m = &world.meshes[inst.mesh as usize];
        let mut most = 0.0f32;
        for t in &m.triangles {
            for k in 0..3 {
                let (a, c) = (m.positions[t[k] as usize], m.positions[t[(k + 1) % 3] as usize]);
                let (a, c) = (to_world.transform_point3a(a.into()), to_world.transform_point3a(c.into()));
                let depth = world.camera.depth((a + c) * 0.5);
                most = most.max((a - c).length() * 32.0 / depth / std::f32::consts::SQRT_2);
            }
        }
        (most, m.triangles.len())
    };
    let place = &moving.built.world.instances[0];
    assert!(place.moves(), "the instance moves while the shutter is open");
    let depth_at = |time: f32| moving.built.world.camera.depth(place.object_to_world_at(time).translation);
    assert!((depth_at(0.0) - 3.0).abs() < 1e-4 && (depth_at(1.0) - 1.5).abs() < 1e-4);
    let (at_close, n_moving) = widest(&moving, place, 1.0);
    let (at_open, _) = widest(&moving, place, 0.0);
    assert!(at_close <= 1.0 + 1e-4 && at_open <= 1.0 + 1e-4, "{at_open} at the opening, {at_close} at the close");
    let (still_at_close, n_still) = widest(&still, place, 1.0);
    assert!(still_at_close > 1.0, "the still plan seen at the close: {still_at_close}");
    assert!(n_moving > 2 * n_still, "moving {n_moving}, still {n_still}");
}
