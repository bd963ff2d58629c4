//! Lights that move with their instances while the shutter is open, in the classic engine:
//! the light loop samples them, and their light shaders (spot cone, shadows) see them,
//! where they are at each sample's shutter time. Each case is the time average of an
//! irradiance worked out by hand, seen through a 0.02-wide orthographic view of the lit
//! plane's patch around the origin.

use crate::support;

use std::sync::atomic::AtomicBool;

use render::{Backend, EngineKind, Settings};

/// A scene: an orthographic 4×4 view down onto the plane z = 0 around the origin, a light
/// `light` (its definition) placed by its instance's `placement`, and `extra` (objects and
/// their instances, listed in `extra_instances`).
fn scene(light: &str, placement: &str, extra: &str, extra_instances: &str) -> String {
    format!(
        r#"
options "opt" filter box 1 1 motion on shutter 0 1 shadow on end options
camera "cam" focal infinity aperture 0.02 aspect 1 resolution 4 4 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
{light}
instance "l_inst" "l" {placement} end instance
material "m" "mib_illum_lambert" ("diffuse" 1 1 1, "lights" ["l_inst"]) end material
object "plane" group
    -10 -10 0  10 -10 0  10 10 0  -10 10 0
    v 0 v 1 v 2 v 3
    c "m" 0 1 2 3
end group end object
instance "plane_inst" "plane" material "m" end instance
{extra}
instgroup "root" "cam_inst" "l_inst" "plane_inst" {extra_instances} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The mean red of the classic engine's image of `text` at 64 samples per pixel, on each
/// backend compiled in; also checks that the world says nothing about moving lights.
fn mean_red(text: &str) -> Vec<(Backend, f32)> {
    let c = support::compile(text);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let world = render::World::from_scene_shaded(&c.scene, Some(&c.shading));
    assert!(!world.warnings.iter().any(|w| w.contains("moves")), "{:?}", world.warnings);
    [Backend::Rust, Backend::Embree]
        .into_iter()
        .filter(|b| b.available())
        .map(|backend| {
            let accel = render::accel::build(&world, backend);
            let settings = Settings { engine: EngineKind::Classic, spp: Some(64), ..Settings::default() };
            let (film, _) =
                render::render(&world, accel.as_ref(), Some(&c.shading), &settings, &AtomicBool::new(false), &|_| {});
            (backend, film.rgba().iter().map(|p| p[0]).sum::<f32>() / 16.0)
        })
        .collect()
}

/// A light at height 1 standing still over the origin.
const STILL: &str = "transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -1 1";
/// A light at height 1 sliding from x = −1 to x = 1 over the shutter (instance transforms
/// are world → light space).
const SLIDING: &str =
    "transform 1 0 0 0  0 1 0 0  0 0 1 0  1 0 -1 1  motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 -1 1";

/// `mib_light_point` without attenuation does not fall off with distance, so a point light
/// at height h = 1 lights the origin with I·cos θ = I·h/d; sliding from x = −1 to 1 it
/// gives the average (1/2)∫ h/√(h² + x²) dx = asinh(1) = 0.88137 of what it gives standing
/// over the origin (before, the classic engine rendered it standing at x = 1: 1/√2).
/// Within 0.005.
#[test]
fn a_sliding_point_light_lights_with_its_time_average() {
    let light = r#"light "l" "mib_light_point" ("color" 1 1 1) origin 0 0 0 end light"#;
    let still = mean_red(&scene(light, STILL, "", ""));
    let moving = mean_red(&scene(light, SLIDING, "", ""));
    for ((backend, s), (_, m)) in still.into_iter().zip(moving) {
        assert!(s > 0.0, "{s}");
        let ratio = m / s;
        eprintln!("{backend:?}: sliding point light {ratio} vs asinh(1) = {}", 1.0f32.asinh());
        assert!((ratio - 1.0f32.asinh()).abs() < 0.005, "{backend:?}: {ratio}");
    }
}

/// Shadow rays go to the light where it is: a blocker at height 0.5 over x < −0.1 hides
/// the sliding light from the origin while the light is at x < −0.2, so the average is
/// (1/2)(asinh(1) + asinh(0.2)) = 0.54003 of the still light's (the view's patch is
/// symmetric about the origin, where the blocked part moves linearly). Within 0.006.
#[test]
fn shadows_fall_from_where_the_light_is() {
    let light = r#"light "l" "mib_light_point" ("color" 1 1 1, "shadow" on) origin 0 0 0 end light"#;
    let blocker = r#"
object "blocker" group
    -10 -10 0.5  -0.1 -10 0.5  -0.1 10 0.5  -10 10 0.5
    v 0 v 1 v 2 v 3
    c "m" 0 1 2 3
end group end object
instance "blocker_inst" "blocker" material "m" end instance
"#;
    let still = mean_red(&scene(light, STILL, blocker, "\"blocker_inst\""));
    let moving = mean_red(&scene(light, SLIDING, blocker, "\"blocker_inst\""));
    let want = 0.5 * (1.0f32.asinh() + 0.2f32.asinh());
    for ((backend, s), (_, m)) in still.into_iter().zip(moving) {
        let ratio = m / s;
        eprintln!("{backend:?}: shadowed sliding light {ratio} vs {want}");
        assert!((ratio - want).abs() < 0.006, "{backend:?}: {ratio}");
    }
}

/// Area samples come from the moved shape: a 0.05-wide square light sliding like the
/// point light gives the point light's average within 0.006 (the square changes the
/// irradiance by far less than that at distance ≥ 1).
#[test]
fn a_sliding_area_light_samples_its_moved_shape() {
    let light = r#"light "l" "mib_light_point" ("color" 1 1 1) origin 0 0 0
        rectangle 0.05 0 0  0 0.05 0  4 4 end light"#;
    let still = mean_red(&scene(light, STILL, "", ""));
    let moving = mean_red(&scene(light, SLIDING, "", ""));
    for ((backend, s), (_, m)) in still.into_iter().zip(moving) {
        let ratio = m / s;
        eprintln!("{backend:?}: sliding square light {ratio} vs asinh(1) = {}", 1.0f32.asinh());
        assert!((ratio - 1.0f32.asinh()).abs() < 0.006, "{backend:?}: {ratio}");
    }
}

/// A spot light turns with its instance: at height 1 over the origin, pointing down and
/// turning about the y axis from −45° to +45° over the shutter, with a hard edge at 22.5°
/// (`cone` = `spread` = cos 22.5°), it lights the origin (at normal incidence, so with the
/// full I) only while its axis is within 22.5° of straight down: half the shutter. Within
/// 0.02 (the view's patch is 0.6° wide as seen from the light).
#[test]
fn a_turning_spot_light_lights_while_it_points_at_the_point() {
    let spread = 22.5f32.to_radians().cos();
    let light = format!(
        r#"light "l" "mib_light_spot" ("color" 1 1 1, "cone" {spread}) origin 0 0 0 direction 0 0 -1
        spread {spread} end light"#
    );
    // World → light space: the light at height 1 turned by −45° or +45° about y.
    let turned = |deg: f32| {
        let (s, c) = deg.to_radians().sin_cos();
        // Light → world is R_y(deg) then +1 in z; world → light is its inverse.
        let m = glam::Mat4::from_translation(glam::Vec3::Z) * glam::Mat4::from_rotation_y(s.atan2(c));
        m.inverse().to_cols_array().map(|v| format!("{v}")).join(" ")
    };
    let placement = format!("transform {} motion transform {}", turned(-45.0), turned(45.0));
    let still = mean_red(&scene(&light, STILL, "", ""));
    let moving = mean_red(&scene(&light, &placement, "", ""));
    for ((backend, s), (_, m)) in still.into_iter().zip(moving) {
        assert!(s > 0.0, "{s}");
        let ratio = m / s;
        eprintln!("{backend:?}: turning spot {ratio} vs 0.5");
        assert!((ratio - 0.5).abs() < 0.02, "{backend:?}: {ratio}");
    }
}

/// A 0.05-wide square (two triangles, facing down, invisible to every ray) at height 1
/// centred at x = −1, and its instance (with `placement`).
fn lamp(placement: &str) -> String {
    format!(
        r#"
object "lamp" group
    -1.025 -0.025 1  -0.975 -0.025 1  -0.975 0.025 1  -1.025 0.025 1
    v 0 v 1 v 2 v 3
    c "m" 0 3 2 1
end group end object
instance "lamp_inst" "lamp" visible off shadow off trace off {placement} end instance
"#
    )
}

/// The light of an object light over the lamp's triangles (4×4 samples).
const OBJECT_LIGHT: &str =
    r#"light "l" "mib_light_point" ("color" 1 1 1) origin 0 0 0 object "lamp_inst" 4 4 end light"#;

/// The light instance standing where the lamp is at time 0 (x = −1, height 1).
const AT_LAMP: &str = "transform 1 0 0 0  0 1 0 0  0 0 1 0  1 0 -1 1";
/// That light instance sliding 2 units right over the shutter.
const AT_LAMP_SLIDING: &str =
    "transform 1 0 0 0  0 1 0 0  0 0 1 0  1 0 -1 1  motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 -1 1";
/// The lamp's geometry instance sliding 2 units right over the shutter.
const LAMP_SLIDING: &str = "motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -2 0 0 1";

/// An `object` area light's triangles move with a moving light instance and with their
/// own geometry instance: the lamp sliding from x = −1 to 1 at height 1 lights the origin
/// like the sliding point light, with asinh(1) = 0.88137 of what it gives standing over
/// it (the still lamp moved to x = 0), within 0.006. Left at x = −1 (the old behaviour)
/// it would give 1/√2.
#[test]
fn a_sliding_object_light_lights_with_its_time_average() {
    let over = lamp("transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1");
    let still = mean_red(&scene(OBJECT_LIGHT, AT_LAMP, &over, "\"lamp_inst\""));
    for (light, placement) in [(AT_LAMP_SLIDING, ""), (AT_LAMP, LAMP_SLIDING)] {
        let moving = mean_red(&scene(OBJECT_LIGHT, light, &lamp(placement), "\"lamp_inst\""));
        for ((backend, s), (_, m)) in still.iter().zip(&moving) {
            assert!(*s > 0.0, "{s}");
            let ratio = m / s;
            eprintln!("{backend:?}: sliding object light {ratio} vs asinh(1) = {}", 1.0f32.asinh());
            assert!((ratio - 1.0f32.asinh()).abs() < 0.006, "{backend:?} {light} {placement}: {ratio}");
        }
    }
}

/// The path engine's mean red of `text` (a 4×4 view) with its first light made physical
/// (radiance 1 from the lamp's underside), 64 samples per pixel; asserts that nothing was
/// said on reading the scene and that no warning kept an object light still.
fn physical_mean_red(text: &str) -> f32 {
    let c = support::compile(text);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let mut world = render::World::from_scene_shaded(&c.scene, Some(&c.shading));
    let still = |w: &String| w.contains("moves") || w.contains("object light");
    assert!(!world.warnings.iter().any(still), "{:?}", world.warnings);
    world.lights[0].output = render::light::Output::Radiance { l: bsdf::Rgb::splat(1.0), two_sided: false };
    let settings = Settings { engine: EngineKind::Path, spp: Some(64), ..Settings::default() };
    let (film, _) = support::render_world(&world, &c.shading, &settings);
    film.rgba().iter().map(|p| p[0]).sum::<f32>() / 16.0
}

/// The path engine samples and hits a moving object light where it is too: made physical
/// (radiance 1 from the lamp's underside), the lamp gives the origin an irradiance
/// L·A·cos θ·cos θ′/d² = L·A/(1 + x²)² at x, so sliding from −1 to 1 it gives
/// ½∫ dx/(1 + x²)² = ¼ + π/8 = 0.64270 of what it gives standing over the origin, within
/// 0.01 (64 samples per pixel, one light sample each).
#[test]
fn the_path_engine_samples_a_sliding_object_light_where_it_is() {
    let over = lamp("transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1");
    let still = physical_mean_red(&scene(OBJECT_LIGHT, AT_LAMP, &over, "\"lamp_inst\""));
    let want = 0.25 + std::f32::consts::PI / 8.0;
    for (light, placement) in [(AT_LAMP_SLIDING, ""), (AT_LAMP, LAMP_SLIDING)] {
        let moving = physical_mean_red(&scene(OBJECT_LIGHT, light, &lamp(placement), "\"lamp_inst\""));
        let ratio = moving / still;
        eprintln!("path: sliding object light {ratio} vs {want}");
        assert!((ratio - want).abs() < 0.01, "{light} {placement}: {ratio}");
    }
}

/// The lamp of [`lamp`] (instance "lamp_inst", still) whose four vertices carry the motion
/// vector (2, 0, 0): its triangles slide from x = −1 to 1 by their own vertex motion.
const LAMP_VERTICES_SLIDING: &str = r#"
object "lamp" group
    -1.025 -0.025 1  -0.975 -0.025 1  -0.975 0.025 1  -1.025 0.025 1
    2 0 0
    v 0 m 4 v 1 m 4 v 2 m 4 v 3 m 4
    c "m" 0 3 2 1
end group end object
instance "lamp_inst" "lamp" visible off shadow off trace off end instance
"#;

/// Two instances of the lamp of [`lamp`]: "lamp_a" sliding from x = −1 to 1, "lamp_b"
/// from x = 1 to −1, so that at each time they stand at ±x.
const TWO_LAMPS_CROSSING: &str = r#"
object "lamp" group
    -1.025 -0.025 1  -0.975 -0.025 1  -0.975 0.025 1  -1.025 0.025 1
    v 0 v 1 v 2 v 3
    c "m" 0 3 2 1
end group end object
instance "lamp_a" "lamp" visible off shadow off trace off
    motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -2 0 0 1 end instance
instance "lamp_b" "lamp" visible off shadow off trace off
    transform 1 0 0 0  0 1 0 0  0 0 1 0  -2 0 0 1  motion transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1
end instance
"#;

/// An object light over every instance of the object "lamp" (4×4 samples).
const OBJECT_LIGHT_ALL_LAMPS: &str =
    r#"light "l" "mib_light_point" ("color" 1 1 1) origin 0 0 0 object "lamp" 4 4 end light"#;

/// Asserts that building the world of `text` says nothing about object lights (the
/// warnings that used to keep deforming object lights still).
fn no_object_light_warning(text: &str) {
    let c = support::compile(text);
    let world = render::World::from_scene_shaded(&c.scene, Some(&c.shading));
    assert!(!world.warnings.iter().any(|w| w.contains("object light")), "{:?}", world.warnings);
}

/// Object lights whose triangles change shape over the shutter follow the geometry, in
/// the classic engine: a lamp whose vertices slide x = −1 → 1 by their motion vectors
/// lights the origin with asinh(1) = 0.88137 of the lamp standing over it (within 0.006)
/// and like the lamp slid by its instance (within 0.006); two instances of one lamp
/// crossing (x = −1 → 1 and 1 → −1; the light averages over both, each at the same
/// cosine) give asinh(1) too. Kept where they are at the shutter's opening (before) they
/// would give 1/√2 = 0.707.
#[test]
fn deforming_object_lights_follow_their_geometry() {
    let over = lamp("transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1");
    let still = mean_red(&scene(OBJECT_LIGHT, AT_LAMP, &over, "\"lamp_inst\""));
    let by_instance = mean_red(&scene(OBJECT_LIGHT, AT_LAMP, &lamp(LAMP_SLIDING), "\"lamp_inst\""));
    let vertices = scene(OBJECT_LIGHT, AT_LAMP, LAMP_VERTICES_SLIDING, "\"lamp_inst\"");
    let crossing = scene(OBJECT_LIGHT_ALL_LAMPS, AT_LAMP, TWO_LAMPS_CROSSING, "\"lamp_a\" \"lamp_b\"");
    no_object_light_warning(&vertices);
    no_object_light_warning(&crossing);
    let by_vertices = mean_red(&vertices);
    let crossing = mean_red(&crossing);
    let want = 1.0f32.asinh();
    for (((backend, s), (_, i)), ((_, v), (_, x))) in
        still.iter().zip(&by_instance).zip(by_vertices.iter().zip(&crossing))
    {
        assert!(*s > 0.0, "{s}");
        let (i, v, x) = (i / s, v / s, x / s);
        eprintln!("{backend:?}: vertices sliding {v}, instance sliding {i}, two crossing {x} vs asinh(1) = {want}");
        assert!((v - want).abs() < 0.006, "{backend:?} vertices: {v}");
        assert!((v - i).abs() < 0.006, "{backend:?} vertices {v} vs instance {i}");
        assert!((x - want).abs() < 0.006, "{backend:?} crossing: {x}");
    }
}

/// The same in the path engine, made physical (radiance 1 from the lamps' undersides): the
/// lamp sliding by its vertices gives ¼ + π/8 = 0.64270 of the lamp over the origin
/// (within 0.01, as the lamp slid by its instance), and the two crossing lamps, each
/// giving that, twice it, 1.28540 (within 0.02).
#[test]
fn the_path_engine_follows_deforming_object_lights() {
    let over = lamp("transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1");
    let still = physical_mean_red(&scene(OBJECT_LIGHT, AT_LAMP, &over, "\"lamp_inst\""));
    let want = 0.25 + std::f32::consts::PI / 8.0;
    let vertices = physical_mean_red(&scene(OBJECT_LIGHT, AT_LAMP, LAMP_VERTICES_SLIDING, "\"lamp_inst\"")) / still;
    let crossing =
        physical_mean_red(&scene(OBJECT_LIGHT_ALL_LAMPS, AT_LAMP, TWO_LAMPS_CROSSING, "\"lamp_a\" \"lamp_b\"")) / still;
    eprintln!("path: vertices sliding {vertices} vs {want}; two crossing {crossing} vs {}", 2.0 * want);
    assert!((vertices - want).abs() < 0.01, "vertices: {vertices}");
    assert!((crossing - 2.0 * want).abs() < 0.02, "crossing: {crossing}");
}

/// A deforming object light's triangles at a key of its geometry are that key's, bit for
/// bit: the lamp's vertices at x = −0.376 carry the motion vector (1.376, 0, 0), which puts
/// them at x = 1 at the shutter's close, where interpolating between the two keys gives
/// 0.99999994. The light's last key holds the world's geometry at its last key exactly
/// (both backends and both engines read the geometry from those keys).
#[test]
fn a_deforming_light_holds_its_geometry_keys_bit_for_bit() {
    let lamp = r#"
object "lamp" group
    -0.376 -0.025 1  -0.326 -0.025 1  -0.326 0.025 1  -0.376 0.025 1
    1.376 0 0
    v 0 m 4 v 1 m 4 v 2 m 4 v 3 m 4
    c "m" 0 3 2 1
end group end object
instance "lamp_inst" "lamp" visible off shadow off trace off end instance
"#;
    let c = support::compile(&scene(OBJECT_LIGHT, AT_LAMP, lamp, "\"lamp_inst\""));
    let world = render::World::from_scene_shaded(&c.scene, Some(&c.shading));
    let light = world.light_meshes.iter().flatten().next().expect("a deforming light");
    let inst = world.instances.iter().find(|i| !world.meshes[i.mesh as usize].position_keys.is_empty()).expect("lamp");
    let mesh = &world.meshes[inst.mesh as usize];
    let geometry = render::world::world_key_positions(inst, mesh);
    assert_eq!((light.key_count(), geometry.len()), (2, 2));
    for (j, key) in geometry.iter().enumerate() {
        let want: Vec<[glam::Vec3A; 3]> = mesh.triangles.iter().map(|t| t.map(|v| key[v as usize])).collect();
        assert_eq!(light.key(j), &want[..], "key {j}");
    }
    assert_eq!(geometry[1][0].x, 1.0, "the vertex the test is about");
}
