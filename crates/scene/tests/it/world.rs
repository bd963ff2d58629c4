//! The scene layer on the seed scene and on hand-computable cases.

use glam::{DVec3, Vec3};
use scene::{LightKind, MaterialSlot, Scene};

use crate::support::build;

fn cornell() -> Scene {
    build(include_str!("../../../../scenes/iray_cornell_box.mi")).0
}

/// Area of a polygon in the xz plane (shoelace).
fn shoelace(points: &[(f64, f64)]) -> f64 {
    let n = points.len();
    (0..n).map(|i| points[i].0 * points[(i + 1) % n].1 - points[(i + 1) % n].0 * points[i].1).sum::<f64>().abs() / 2.0
}

#[test]
fn cornell_camera() {
    let s = cornell();
    let c = &s.camera;
    assert!((c.position() - DVec3::new(278.0, 273.0, -800.0)).length() < 1e-9);
    assert!((c.forward() - DVec3::Z).length() < 1e-12);
    assert!((c.up() - DVec3::Y).length() < 1e-12);
    // 2·atan(0.025 / (2·0.035)) = 39.30°.
    assert!((c.fov_x().to_degrees() - 39.3076).abs() < 1e-3, "{}", c.fov_x().to_degrees());
    assert_eq!(c.resolution, (1024, 1024));
    assert_eq!(c.attributes["tm_tonemapper"].as_str(), Some("mia_exposure_photographic"));
}

#[test]
fn cornell_light() {
    let s = cornell();
    assert_eq!(s.lights.len(), 1);
    let l = &s.lights[0];
    assert_eq!(l.kind, LightKind::Point);
    assert!((l.position - DVec3::new(278.0, 548.8, 279.5)).length() < 1e-9);
    assert!((l.area_normal().unwrap() - DVec3::NEG_Y).length() < 1e-12, "faces down");
    assert!((l.area_size().unwrap() - 130.0 * 105.0).abs() < 1e-9);
    assert!(l.visible, "the instance says `visible on`");
}

#[test]
fn cornell_floor_holes_are_cut_exactly() {
    let s = cornell();
    let room = s.objects.iter().find(|o| o.name == "Room_obj").unwrap();
    let mesh = &room.geometry.mesh;
    let floor: f64 = mesh
        .triangles
        .iter()
        .filter(|t| t.iter().all(|&i| mesh.positions[i as usize].y == 0.0))
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_dvec3());
            // Floor triangles face up (+Y, into the room).
            assert!((b - a).cross(c - a).y > 0.0);
            0.5 * (b - a).cross(c - a).length()
        })
        .sum();
    let outer = shoelace(&[(552.8, 0.0), (0.0, 0.0), (0.0, 559.2), (549.6, 559.2)]);
    let hole1 = shoelace(&[(130.0, 65.0), (82.0, 225.0), (240.0, 272.0), (290.0, 114.0)]);
    let hole2 = shoelace(&[(423.0, 247.0), (265.0, 296.0), (314.0, 456.0), (472.0, 406.0)]);
    assert!((floor - (outer - hole1 - hole2)).abs() < 1e-2, "{floor} vs {}", outer - hole1 - hole2);
    // Ceiling: outer minus the light's hole.
    let ceiling: f64 = mesh
        .triangles
        .iter()
        .filter(|t| t.iter().all(|&i| mesh.positions[i as usize].y == 548.8))
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_dvec3());
            0.5 * (b - a).cross(c - a).length()
        })
        .sum();
    assert!((ceiling - (556.0 * 559.2 - 130.0 * 105.0)).abs() < 1e-2, "{ceiling}");
    // Labels 0, 1, 2 bound to white, green, red.
    let inst = s.instances.iter().find(|i| i.name == "Room_inst").unwrap();
    let names: Vec<&str> = mesh
        .slots
        .iter()
        .map(|slot| {
            let MaterialSlot::Label(l) = slot else { panic!() };
            let _ = l;
            &*s.materials[inst.materials[mesh.slots.iter().position(|x| x == slot).unwrap()].unwrap() as usize].name
        })
        .collect();
    assert_eq!(names, vec!["white", "green", "red"]);
}

/// World-space bounds of one instance.
fn instance_bounds(s: &Scene, name: &str) -> (DVec3, DVec3) {
    let inst = s.instances.iter().find(|i| i.name == name).unwrap();
    let mesh = &s.objects[inst.object as usize].geometry.mesh;
    let pts: Vec<DVec3> = mesh.positions.iter().map(|p| inst.object_to_world.transform_point3(p.as_dvec3())).collect();
    let lo = pts.iter().fold(DVec3::splat(f64::MAX), |a, p| a.min(*p));
    let hi = pts.iter().fold(DVec3::splat(f64::MIN), |a, p| a.max(*p));
    (lo, hi)
}

#[test]
fn cornell_subdivision_objects_sit_where_their_instances_say() {
    let s = cornell();
    // Subdiv_inst: world = (400 − x, y + 60, z + 85); the cage is [−10, 10]³ with the top
    // face's centre raised by the `detail` vector (0, 0, 4).
    let (lo, hi) = instance_bounds(&s, "Subdiv_inst");
    let centre = (lo + hi) * 0.5;
    assert!((centre.x - 400.0).abs() < 1e-3 && (centre.y - 60.0).abs() < 1e-3, "{lo} {hi}");
    assert!(lo.z > 75.0 - 1e-3 && hi.z < 85.0 + 14.0, "{lo} {hi}");
    assert!(lo.x > 390.0 && hi.x < 410.0);
    // Catmull_clark_mesh_inst: world = object + (465, 60, 95); the cage spans x ±20, y ±20, z 0..60.
    let (lo, hi) = instance_bounds(&s, "Catmull_clark_mesh_inst");
    assert!(lo.x >= 445.0 - 1e-3 && hi.x <= 485.0 + 1e-3 && lo.y >= 40.0 - 1e-3 && hi.y <= 80.0 + 1e-3, "{lo} {hi}");
    assert!(lo.z >= 95.0 - 1e-3 && hi.z <= 155.0 + 1e-3, "{lo} {hi}");
    // Fully creased caps stay flat: the cap faces lie on z = 95 and z = 155.
    assert!((lo.z - 95.0).abs() < 1e-3 && (hi.z - 155.0).abs() < 1e-3, "{lo} {hi}");
    let (lo, hi) = instance_bounds(&s, "Tall_block_inst");
    assert_eq!((lo.y, hi.y), (0.0, 330.0));
}

#[test]
fn nested_instances_compose_rotation_and_translation() {
    // inner: translate by (1, 0, 0) (world → object subtracts it); outer: rotate 90° about Z
    // (x → y). A vertex at the object's origin ends up at rotate(translate(0)) = (0, 1, 0).
    let text = "options \"o\" end options\ncamera \"c\" end camera\ninstance \"ci\" \"c\" end instance\n\
        object \"p\" group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 c 0 1 2 end group end object\n\
        instance \"inner\" \"p\" transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1 end instance\n\
        instgroup \"g\" \"inner\" end instgroup\n\
        instance \"outer\" \"g\" transform 0 -1 0 0  1 0 0 0  0 0 1 0  0 0 0 1 end instance\n\
        instgroup \"root\" \"ci\" \"outer\" end instgroup\nrender \"root\" \"ci\" \"o\"\n";
    let (s, _, _) = build(text);
    assert_eq!(s.instances.len(), 1);
    let inst = &s.instances[0];
    let w = inst.object_to_world.transform_point3(DVec3::ZERO);
    assert!((w - DVec3::new(0.0, 1.0, 0.0)).length() < 1e-12, "{w}");
    let w = inst.object_to_world.transform_point3(DVec3::X);
    assert!((w - DVec3::new(0.0, 2.0, 0.0)).length() < 1e-12, "{w}");
    assert!((inst.world_to_object * inst.object_to_world - glam::DMat4::IDENTITY).abs_diff_eq(glam::DMat4::ZERO, 1e-12));
}

#[test]
fn material_arrays_over_labels_and_out_of_range_labels() {
    let text = "options \"o\" end options\ncamera \"c\" end camera\ninstance \"ci\" \"c\" end instance\n\
        material \"a\" \"x\" () end material\nmaterial \"b\" \"x\" () end material\nmaterial \"n\" \"x\" () end material\n\
        object \"t\" tagged on group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 c 0 0 1 2 c 1 0 1 2 c 5 0 1 2 end group end object\n\
        object \"u\" group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 c \"n\" 0 1 2 c 0 1 2 c \"\" 0 1 2 end group end object\n\
        instance \"ti\" \"t\" material [ \"a\", \"b\" ] end instance\n\
        instance \"ui\" \"u\" material \"a\" end instance\n\
        instance \"uo\" \"u\" override material \"b\" end instance\n\
        instgroup \"root\" \"ci\" \"ti\" \"ui\" \"uo\" end instgroup\nrender \"root\" \"ci\" \"o\"\n";
    let (s, diags, _) = build(text);
    let mat = |inst: &str, tri: usize| {
        let i = s.instances.iter().find(|i| i.name == inst).unwrap();
        let mesh = &s.objects[i.object as usize].geometry.mesh;
        s.materials[i.materials[mesh.triangle_slots[tri] as usize].unwrap() as usize].name.clone()
    };
    assert_eq!([mat("ti", 0), mat("ti", 1), mat("ti", 2)], ["a", "b", "a"]);
    assert!(diags.iter().any(|d| !d.is_error() && d.message.contains("label 5 is beyond its 2 materials")));
    // Untagged: a face's own material wins, an unnamed face keeps the last name, `""` takes the instance's.
    assert_eq!([mat("ui", 0), mat("ui", 1), mat("ui", 2)], ["n", "n", "a"]);
    // `override`: the instance's material replaces the faces' own.
    assert_eq!([mat("uo", 0), mat("uo", 1), mat("uo", 2)], ["b", "b", "b"]);
}

#[test]
fn cube_subdivision_levels_and_creases_through_the_whole_pipeline() {
    let cube = |level: u32, crease: &str| {
        format!(
            "options \"o\" end options\ncamera \"c\" end camera\ninstance \"ci\" \"c\" end instance\n\
             object \"cube\" group\n -1 -1 -1\n 1 -1 -1\n -1 1 -1\n 1 1 -1\n -1 -1 1\n 1 -1 1\n -1 1 1\n 1 1 1\n\
             v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7\n subdivision surface \"s\"\n\
             p 0 2 3 1 {crease}\n p 4 5 7 6 {crease}\n p 0 1 5 4 {crease}\n p 2 6 7 3 {crease}\n p 0 4 6 2 {crease}\n p 1 3 7 5 {crease}\n\
             end subdivision surface\n approximate subdivision surface parametric {level} \"s\"\n end group end object\n\
             instance \"i\" \"cube\" end instance\ninstgroup \"root\" \"ci\" \"i\" end instgroup\nrender \"root\" \"ci\" \"o\"\n"
        )
    };
    let counts: Vec<usize> = (1..=4).map(|l| build(&cube(l, "")).0.objects[0].geometry.mesh.positions.len()).collect();
    assert_eq!(counts, vec![26, 98, 386, 1538]);
    let sharp = build(&cube(3, "crease 15 1 1 1 1")).0;
    let mesh = &sharp.objects[0].geometry.mesh;
    assert!(mesh.positions.iter().all(|p: &Vec3| (p.abs().max_element() - 1.0).abs() < 1e-5));
    assert!((mesh.area() - 24.0).abs() < 1e-3);
}

#[test]
fn unknown_references_are_errors_at_the_reference() {
    let text = "options \"o\" end options\ncamera \"c\" end camera\ninstance \"ci\" \"c\" end instance\n\
        instance \"x\" \"nothing\" end instance\ninstgroup \"root\" \"ci\" \"x\" \"ghost\" end instgroup\nrender \"root\" \"ci\" \"o\"\n";
    let parsed = mi::parse_str("t.mi", text);
    let mut diags = Vec::new();
    let _ = Scene::build(&parsed, 0, &mut diags);
    let errors: Vec<(u32, u32, String)> = diags
        .iter()
        .filter(|d| d.is_error())
        .map(|d| {
            let (l, c) = parsed.sources.file(d.span.file).line_col(d.span.lo);
            (l, c, d.message.clone())
        })
        .collect();
    assert_eq!(
        errors,
        vec![
            (4, 14, "unknown element 'nothing' in instance".to_string()),
            (5, 27, "unknown instance 'ghost'".to_string())
        ]
    );
    let parsed = mi::parse_str("t.mi", "options \"o\" end options\nrender \"root\" \"ci\" \"o\"\n");
    let mut diags = Vec::new();
    assert!(Scene::build(&parsed, 0, &mut diags).is_none());
    assert!(diags[0].message.contains("unknown camera instance 'ci'"));
}

#[test]
fn instgroup_cycles_are_errors() {
    let text = "options \"o\" end options\ncamera \"c\" end camera\ninstance \"ci\" \"c\" end instance\n\
        instgroup \"a\" \"ib\" end instgroup\ninstance \"ib\" \"b\" end instance\ninstgroup \"b\" \"ia\" end instgroup\n\
        instance \"ia\" \"a\" end instance\ninstgroup \"root\" \"ci\" \"ia\" end instgroup\nrender \"root\" \"ci\" \"o\"\n";
    let parsed = mi::parse_str("t.mi", text);
    let mut diags = Vec::new();
    let s = Scene::build(&parsed, 0, &mut diags).unwrap();
    assert!(s.instances.is_empty());
    assert!(diags.iter().any(|d| d.is_error() && d.message.contains("contains itself")), "{diags:?}");
}

#[test]
fn objects_instanced_twice_are_stored_once() {
    let (s, _, _) = build(include_str!("../../../../scenes/classic_spheres.mi"));
    let balls: Vec<_> = s.instances.iter().filter(|i| s.objects[i.object as usize].name == "ball").collect();
    assert_eq!(balls.len(), 2);
    assert_eq!(balls[0].object, balls[1].object);
    assert_eq!(s.objects.len(), 3);
    assert_eq!(s.unique_triangles(), 964);
    assert_eq!(s.instanced_triangles(), 1924);
    let spot = s.lights.iter().find(|l| l.name == "spot").unwrap();
    assert_eq!(spot.kind, LightKind::Spot);
    assert!((spot.spread - 0.866025).abs() < 1e-9);
}

#[test]
fn shader_references_must_name_shaders() {
    let text = "options \"o\" end options\ncamera \"c\" end camera\ninstance \"ci\" \"c\" end instance\n\
        shader \"tex\" \"mib_texture_lookup\" ()\n\
        shader \"mix\" \"mib_color_mix\" ( \"color_0\" = \"tex.out\", \"color_1\" = \"tex\", \"color_2\" = \"missing\" )\n\
        material \"m\" = \"mix\" = \"nowhere\" end material\n\
        instgroup \"root\" \"ci\" end instgroup\nrender \"root\" \"ci\" \"o\"\n";
    let parsed = mi::parse_str("t.mi", text);
    let mut diags = Vec::new();
    let _ = Scene::build(&parsed, 0, &mut diags);
    let mut errors: Vec<String> = diags.iter().filter(|d| d.is_error()).map(|d| d.message.clone()).collect();
    errors.sort();
    assert_eq!(errors, vec!["unknown shader 'missing'", "unknown shader 'nowhere'"]);
}

/// Binary vectors can hold NaN (found by the parser fuzzer): such triangles are left out
/// with a warning rather than reaching the acceleration structures.
#[test]
fn triangles_with_nonfinite_vertices_are_left_out() {
    let mut text = b"options \"o\" end options\ncamera \"c\" focal 1 aperture 1 aspect 1 resolution 8 8 end camera\n\
instance \"ci\" \"c\" end instance\nobject \"n\" group `"
        .to_vec();
    text.extend([0xffu8; 12]);
    text.extend_from_slice(
        b"` 0 0 -3 1 0 -3 1 1 -3 v 0 v 1 v 2 v 3 p 0 1 2 p 1 2 3 end group end object\n\
instance \"ni\" \"n\" end instance\ninstgroup \"root\" \"ci\" \"ni\" end instgroup\nrender \"root\" \"ci\" \"o\"\n",
    );
    let parsed = mi::parse_source(mi::Origin::Memory("nan.mi".into()), text, &mi::ReadOptions::default());
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let mut diags = Vec::new();
    let scene = Scene::build(&parsed, 0, &mut diags).expect("a scene");
    assert_eq!(scene.objects[0].geometry.mesh.triangles.len(), 1);
    assert!(scene.objects[0].geometry.mesh.triangles[0].iter().all(|&i| i != 0));
    assert_eq!(scene.objects[0].geometry.mesh.triangle_slots.len(), 1);

    // Infinities written as text reach the mesh and are caught there.
    let (scene, diags, _) = build(
        "options \"o\" end options\ncamera \"c\" focal 1 aperture 1 aspect 1 resolution 8 8 end camera\n\
instance \"ci\" \"c\" end instance\nobject \"t\" trilist vertex 4 p triangle 2 [ 1e999 0 -3 1 0 -3 1 1 -3 0 1 -3 ]\n\
[ 0 1 2 1 2 3 ] end trilist end object\ninstance \"ti\" \"t\" end instance\n\
instgroup \"root\" \"ci\" \"ti\" end instgroup\nrender \"root\" \"ci\" \"o\"\n",
    );
    assert_eq!(scene.objects[0].geometry.mesh.triangles, vec![[1, 2, 3]]);
    let warning = diags.iter().find(|d| d.message.contains("non-finite")).expect("a warning");
    assert!(warning.message.contains(" 1 triangle(s)"), "{}", warning.message);
}
