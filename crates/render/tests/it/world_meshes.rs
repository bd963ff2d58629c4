//! The world stage's two ways to the renderer's meshes: copying the scene's arrays
//! (`pipeline::build_world`) and moving them (`pipeline::build_world_taking_meshes`, what
//! `mira render` does) build the same world; and Embree reads a mesh's packed 12-byte
//! vertices in place or, when the vector has no room past its end, from a copy, with the
//! same hits either way.

use crate::support;

use render::accel::{self, Backend};
use render::pipeline::{build_world, build_world_taking_meshes, Built};
use shader::ShadingOptions;

/// The seed Cornell box (trilists and polygons, identity placements) with an object area
/// light whose triangles the light reads from the scene's meshes, and a trilist with
/// vertex normals.
fn scene_text() -> String {
    let mut text = include_str!("../../../../scenes/iray_cornell_box.mi").to_string();
    let extra = r#"
light "Lamp_lgt" "mib_light_point" ("color" 1 1 1) origin 0 0 0 object "Lamp_inst" 2 2 end light
instance "Lamp_light_inst" "Lamp_lgt" end instance
object "Lamp_obj"
    trilist vertex 4 p n triangle 2
    [
        200 540 200  0 -1 0
        350 540 200  0 -1 0.1
        350 540 350  0.1 -1 0
        200 540 350  0 -1 0
    ]
    [ 0 1 2  0 2 3 ]
    end trilist
end object
instance "Lamp_inst" "Lamp_obj" visible off shadow off end instance
"#;
    // The extra objects go before the root group, which lists them.
    let root = text.find("instgroup").expect("the scene has a root group");
    text.insert_str(root, extra);
    let list_end = text[root..].find("end instgroup").expect("closed root group") + root;
    text.insert_str(list_end, "    \"Lamp_light_inst\"\n    \"Lamp_inst\"\n");
    text
}

fn parse_scene(text: &str) -> scene::Scene {
    let parsed = mi::parse_str("world_meshes.mi", text);
    assert!(!parsed.diagnostics.has_errors(), "{:?}", parsed.diagnostics.list);
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("the scene builds");
    assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}");
    scene
}

fn world_pair() -> (Built, Built, scene::Scene) {
    let text = scene_text();
    let copied = build_world(&parse_scene(&text), &ShadingOptions::default(), &[]);
    let mut scene = parse_scene(&text);
    let taken = build_world_taking_meshes(&mut scene, &ShadingOptions::default(), &[]);
    (copied, taken, scene)
}

#[test]
fn moving_the_meshes_builds_the_world_copying_them_builds() {
    let (copied, taken, scene) = world_pair();
    let (a, b) = (&copied.world, &taken.world);
    assert_eq!(a.meshes.len(), b.meshes.len());
    assert!(a.meshes.iter().any(|m| !m.normals.is_empty()), "the lamp's trilist has normals");
    for (m, n) in a.meshes.iter().zip(&b.meshes) {
        assert_eq!(m.positions, n.positions);
        assert_eq!(m.normals, n.normals);
        assert_eq!(m.triangles, n.triangles);
        assert_eq!(m.slots, n.slots);
        assert_eq!(m.textures, n.textures);
        assert_eq!(m.user, n.user);
        // Room for one vertex past the end, for Embree's 16-byte loads.
        assert!(n.positions.capacity() > n.positions.len());
    }
    assert_eq!(a.instances.len(), b.instances.len());
    for (i, j) in a.instances.iter().zip(&b.instances) {
        assert_eq!((i.mesh, &i.materials, i.object_to_world), (j.mesh, &j.materials, j.object_to_world));
    }
    assert_eq!(a.warnings, b.warnings);
    // The object light was made from the scene's meshes before they moved.
    assert_eq!(a.lights.len(), b.lights.len());
    let mesh_lights = |w: &render::World| {
        w.lights
            .iter()
            .filter_map(|l| match &l.shape {
                render::light::Shape::Mesh(m) => Some((m.len(), m.area())),
                _ => None,
            })
            .collect::<Vec<_>>()
    };
    let lamp = mesh_lights(a);
    assert_eq!(lamp.len(), 1, "one object light");
    assert_eq!(lamp[0].0, 2);
    assert!((lamp[0].1 - 150.0 * 150.0).abs() < 1e-2, "area {}", lamp[0].1);
    assert_eq!(lamp, mesh_lights(b));
    // The scene's object meshes are left empty.
    assert!(scene.objects.iter().all(|o| o.geometry.mesh.triangles.is_empty() && o.geometry.mesh.positions.is_empty()));
}

#[test]
fn embree_hits_are_the_same_with_the_vertices_shared_or_copied() {
    if !Backend::Embree.available() {
        return;
    }
    let (_, shared, _) = world_pair();
    let (_, mut copied, _) = world_pair();
    // Vectors with no room past their end: Embree gets a padded copy of their vertices.
    for m in &mut copied.world.meshes {
        let mut exact = Vec::with_capacity(m.positions.len());
        exact.extend_from_slice(&m.positions);
        assert_eq!(exact.capacity(), exact.len());
        m.positions = exact;
    }
    let (a, b) = (accel::build(&shared.world, Backend::Embree), accel::build(&copied.world, Backend::Embree));
    let mut hits = 0;
    for ray in support::rays::in_cornell_box(4000, 0x2545_f491_4f6c_dd1d) {
        let (h, k) = (a.intersect(&ray), b.intersect(&ray));
        assert_eq!(h, k, "ray {ray:?}");
        assert_eq!(a.occluded(&ray), b.occluded(&ray));
        hits += usize::from(h.is_some());
    }
    // The box is open at the front only.
    assert!(hits > 2000, "rays from inside the box hit it: {hits} of 4000");
}
