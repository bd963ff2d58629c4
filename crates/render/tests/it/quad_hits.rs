//! Embree holds a large world's paired meshes as quads (pairs of triangles sharing an edge,
//! `render::mesh::quad_pairs`) and turns each quad hit back into the triangle's. Built that
//! way whatever its size (`EmbreeAccel::new_compact`), on a small height field whose
//! triangles are listed out of order, one in eight wound the other way (no neighbour can
//! pair with them) and one triangle alone, Embree finds what
//! the Rust backend finds — the same triangle (a ray grazing a shared edge may take either),
//! the distance within 1e-4 relative, the barycentrics within 1e-3 — and the same occlusion.

#![cfg(embree)]

use crate::support;

use render::accel::{self, Backend};
use render::mesh::quad_pairs;

/// Quads along each side of the field.
const SIDE: usize = 24;

/// The seed Cornell box with the field and a lone triangle inside it; with `more_kinds`,
/// the short block also a second time, 300 mm higher (its mesh then shared by two
/// instances: held by Embree as a scene of its own, instanced twice), and the tall block
/// sliding 30 mm along x while the shutter is open (a moving mesh used once).
fn world(more_kinds: bool) -> render::World {
    let mut vertices = String::new();
    for j in 0..=SIDE {
        for i in 0..=SIDE {
            let (x, z) = (60.0 + 440.0 * i as f32 / SIDE as f32, 60.0 + 440.0 * j as f32 / SIDE as f32);
            let y = 150.0 + 40.0 * (x / 23.0).sin() * (z / 31.0).cos();
            vertices.push_str(&format!("{x} {y} {z}\n"));
        }
    }
    let at = |i: usize, j: usize| j * (SIDE + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..SIDE {
        for i in 0..SIDE {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            triangles.push([a, c, b]);
            // Every fourth square's second triangle wound the other way: no pair for it.
            triangles.push(if (i + 2 * j) % 4 == 0 { [a, c, d] } else { [a, d, c] });
        }
    }
    // Out of order: a fixed stride through the list (coprime with its length).
    let n = triangles.len();
    let mut order: Vec<[usize; 3]> = (0..n).map(|k| triangles[(k * 389) % n]).collect();
    let lone = (SIDE + 1) * (SIDE + 1);
    vertices.push_str("300 380 300\n360 380 300\n300 380 360\n");
    order.push([lone, lone + 2, lone + 1]);
    let list: String = order.iter().map(|t| format!("{} {} {}\n", t[0], t[1], t[2])).collect();
    let mut extra = format!(
        "object \"Field_obj\"\n trilist vertex {} p triangle {}\n[\n{vertices}]\n[\n{list}]\n end trilist\nend object\n\
         instance \"Field_inst\" \"Field_obj\" end instance\n",
        lone + 3,
        order.len()
    );
    if more_kinds {
        // The instance transform maps world to object space: the copy stands 300 mm up.
        extra.push_str(
            "instance \"Short_block_up\" \"Short_block_obj\"\n material \"white\"\n transform 1 0 0 0 0 1 0 0 0 0 1 0 0 -300 0 1\nend instance\n",
        );
    }
    let mut text = include_str!("../../../../scenes/iray_cornell_box.mi").to_string();
    let root = text.find("instgroup").expect("the scene has a root group");
    text.insert_str(root, &extra);
    let list_end = text[root..].find("end instgroup").expect("closed root group") + root;
    text.insert_str(
        list_end,
        if more_kinds { "    \"Field_inst\"\n    \"Short_block_up\"\n" } else { "    \"Field_inst\"\n" },
    );
    if more_kinds {
        let tall = "instance \"Tall_block_inst\" \"Tall_block_obj\"\n";
        assert!(text.contains(tall));
        text = text.replace(tall, &format!("{tall}    motion transform 1 0 0 0 0 1 0 0 0 0 1 0 -30 0 0 1\n"));
        text = text.replace("options \"Options\"\n", "options \"Options\"\n    motion on\n    shutter 0 1\n");
    }
    let parsed = mi::parse_str("quad_hits.mi", &text);
    assert!(!parsed.diagnostics.has_errors(), "{:?}", parsed.diagnostics.list);
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("the scene builds");
    render::World::from_scene(&scene)
}

#[test]
fn embree_quad_hits_are_the_rust_backends_triangle_hits() {
    let mut world = world(false);
    let field = world.instances.len() as u32 - 1;
    let mesh = &mut world.meshes[world.instances[field as usize].mesh as usize];
    let count = mesh.triangles.len();
    let vertex_count = mesh.vertex_count();
    let pairs = quad_pairs::pair_in_place(&mut mesh.triangles, vertex_count).expect("pairs").pairs;
    mesh.quad_pairs = pairs;
    let lone = count - 2 * pairs as usize;
    assert!(lone > SIDE * SIDE / 4 && pairs > 0, "{pairs} pairs, {lone} lone");
    let quads = count - pairs as usize;
    let rust = accel::build(&world, Backend::Rust);
    let embree = render::accel::embree::EmbreeAccel::new_compact(&world);
    assert_eq!(embree.error(), 0);
    assert_eq!(embree.quad_count(), quads, "Embree holds the field as quads");
    let rays = support::rays::in_cornell_box(20_000, 0x9e37_79b9_7f4a_7c15);
    let agreement = support::backends::assert_agree(rust.as_ref(), &embree, &rays, field);
    assert!(agreement.on_instance > 2_000, "{} rays hit the field", agreement.on_instance);
    assert!(agreement.different <= rays.len() / 1000, "{} rays hit different triangles", agreement.different);
}

/// A hit's fields as bits, for comparing two backends' hits exactly.
fn bits(hit: Option<render::accel::Hit>) -> Option<(u32, u32, u32, u32, u32)> {
    hit.map(|h| (h.t.to_bits(), h.instance, h.prim, h.u.to_bits(), h.v.to_bits()))
}

/// The top-level geometry split by kind (as a large world is built, so that Embree builds
/// each kind's BVH on both threads: the box's triangles, the field's quads and, with more
/// kinds, the moving block's triangles and the shared block's instances, in two or four
/// scenes) hits what one scene holding them all hits, bit for bit, one ray at a time and in
/// batches (rays at spread shutter times), and blocks the same rays: the scenes are queried
/// in the order Embree queries one scene's BVHs.
#[test]
fn kinds_apart_hit_what_one_scene_hits() {
    use render::accel::Accel;
    for more_kinds in [false, true] {
        let mut world = world(more_kinds);
        let field =
            world.instances.iter().position(|i| world.meshes[i.mesh as usize].triangles.len() == 2 * SIDE * SIDE + 1);
        let field = field.expect("the field is placed") as u32;
        let mesh = &mut world.meshes[world.instances[field as usize].mesh as usize];
        let vertex_count = mesh.vertex_count();
        mesh.quad_pairs = quad_pairs::pair_in_place(&mut mesh.triangles, vertex_count).expect("pairs").pairs;
        let shared_mesh = world
            .instances
            .iter()
            .map(|i| i.mesh)
            .find(|&m| world.instances.iter().filter(|i| i.mesh == m).count() > 1);
        assert_eq!(shared_mesh.is_some(), more_kinds);
        let moving = world.instances.iter().position(|i| i.moves());
        assert_eq!(moving.is_some(), more_kinds);
        let apart = render::accel::embree::EmbreeAccel::new_compact(&world);
        let one = render::accel::embree::EmbreeAccel::new_compact_in_one_scene(&world);
        assert_eq!((apart.error(), one.error()), (0, 0));
        assert_eq!((apart.top_level_scenes(), one.top_level_scenes()), (if more_kinds { 4 } else { 2 }, 1));
        let mut rays = support::rays::in_cornell_box(20_000, 0x2545_f491_4f6c_dd1d);
        for (k, ray) in rays.iter_mut().enumerate() {
            ray.time = (k as f32 * 0.618_034).fract();
        }
        let (mut on_field, mut on_shared, mut on_moving, mut elsewhere) = (0, 0, 0, 0);
        for ray in &rays {
            let hit = apart.intersect(ray);
            assert_eq!(bits(hit), bits(one.intersect(ray)), "{ray:?}");
            assert_eq!(apart.occluded(ray), one.occluded(ray), "{ray:?}");
            match hit {
                Some(h) if h.instance == field => on_field += 1,
                Some(h) if Some(world.instances[h.instance as usize].mesh) == shared_mesh => on_shared += 1,
                Some(h) if Some(h.instance as usize) == moving => on_moving += 1,
                Some(_) => elsewhere += 1,
                None => {}
            }
        }
        assert!(on_field > 2_000 && elsewhere > 2_000, "{on_field} rays on the field, {elsewhere} elsewhere");
        assert!(!more_kinds || on_shared > 500, "{on_shared} rays on the shared block's two instances");
        assert!(!more_kinds || on_moving > 500, "{on_moving} rays on the moving block");
        let (mut hits_apart, mut hits_one) = (vec![None; rays.len()], vec![None; rays.len()]);
        apart.intersect_batch(&rays, &mut hits_apart);
        one.intersect_batch(&rays, &mut hits_one);
        assert!(hits_apart.iter().zip(&hits_one).all(|(a, b)| bits(*a) == bits(*b)));
        let (mut blocked_apart, mut blocked_one) = (vec![false; rays.len()], vec![false; rays.len()]);
        apart.occluded_batch(&rays, &mut blocked_apart);
        one.occluded_batch(&rays, &mut blocked_one);
        assert_eq!(blocked_apart, blocked_one);
    }
}
