//! A large mesh (at least `render::mesh::LARGE_MESH_TRIANGLES` triangles, as the heavy
//! benchmark's sphere): the world keeps its vertex normals as 32-bit octahedral codes,
//! each within `render::octahedral::MAX_ANGLE_ERROR` of the scene's direction, and Embree
//! builds it compact (8-wide nodes over indexed leaves where the CPU has them) with the
//! hits the Rust backend finds.

use crate::support;

use glam::Vec3A;
use render::accel::{self, Backend};
use render::mesh::LARGE_MESH_TRIANGLES;
use render::pipeline::build_world_taking_meshes;
use shader::ShadingOptions;

/// Quads along each side of the height field: 2 × 501² = 502,002 triangles.
const SIDE: usize = 501;

/// The height field's surface y = 150 + 40 sin(x/23) cos(z/31) over x, z ∈ [60, 500] and
/// its unit normal at (x, z).
fn height_field(x: f32, z: f32) -> (f32, Vec3A) {
    let y = 150.0 + 40.0 * (x / 23.0).sin() * (z / 31.0).cos();
    let dy_dx = 40.0 / 23.0 * (x / 23.0).cos() * (z / 31.0).cos();
    let dy_dz = -40.0 / 31.0 * (x / 23.0).sin() * (z / 31.0).sin();
    (y, Vec3A::new(-dy_dx, 1.0, -dy_dz).normalize())
}

/// The seed Cornell box with the height field inside it (a trilist with vertex normals),
/// and the normals the file gives, vertex by vertex.
fn scene_text() -> (String, Vec<Vec3A>) {
    let mut vertices = String::with_capacity((SIDE + 1) * (SIDE + 1) * 64);
    let mut normals = Vec::new();
    for j in 0..=SIDE {
        for i in 0..=SIDE {
            let (x, z) = (60.0 + 440.0 * i as f32 / SIDE as f32, 60.0 + 440.0 * j as f32 / SIDE as f32);
            let (y, n) = height_field(x, z);
            vertices.push_str(&format!("{x} {y} {z} {} {} {}\n", n.x, n.y, n.z));
            normals.push(n);
        }
    }
    let mut triangles = String::with_capacity(SIDE * SIDE * 40);
    let at = |i: usize, j: usize| j * (SIDE + 1) + i;
    for j in 0..SIDE {
        for i in 0..SIDE {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            // Counter-clockwise seen from above (+y).
            triangles.push_str(&format!("{a} {c} {b} {a} {d} {c}\n"));
        }
    }
    let extra = format!(
        "object \"Field_obj\"\n trilist vertex {} p n triangle {}\n[\n{vertices}]\n[\n{triangles}]\n end trilist\nend object\n\
         instance \"Field_inst\" \"Field_obj\" end instance\n",
        (SIDE + 1) * (SIDE + 1),
        2 * SIDE * SIDE
    );
    let mut text = include_str!("../../../../scenes/iray_cornell_box.mi").to_string();
    let root = text.find("instgroup").expect("the scene has a root group");
    text.insert_str(root, &extra);
    let list_end = text[root..].find("end instgroup").expect("closed root group") + root;
    text.insert_str(list_end, "    \"Field_inst\"\n");
    (text, normals)
}

fn world() -> (render::World, Vec<Vec3A>) {
    let (text, normals) = scene_text();
    (world_of(&text), normals)
}

/// The world of a scene text built as the renderer builds it.
fn world_of(text: &str) -> render::World {
    let parsed = mi::parse_str("large_meshes.mi", text);
    assert!(!parsed.diagnostics.has_errors(), "{:?}", parsed.diagnostics.list);
    let mut diags = Vec::new();
    let mut scene = scene::Scene::build(&parsed, 0, &mut diags).expect("the scene builds");
    build_world_taking_meshes(&mut scene, &ShadingOptions::default(), &[]).world
}

/// The large mesh keeps its normals in 32 bits, each within the stated angle of the file's;
/// the box's small meshes keep theirs (none here) and no mesh loses its normals.
#[test]
fn a_large_mesh_keeps_its_normals_in_32_bits_within_the_stated_angle() {
    let (world, given) = world();
    let large: Vec<_> = world.meshes.iter().filter(|m| m.triangles.len() >= LARGE_MESH_TRIANGLES).collect();
    assert_eq!(large.len(), 1, "one large mesh");
    let mesh = large[0];
    // Interleaved with the positions: one 16-byte record a vertex.
    assert!(mesh.normals.is_empty() && mesh.normals_oct.is_empty() && mesh.has_normals());
    assert!(mesh.is_interleaved() && mesh.positions.is_empty() && mesh.vertices.len() == given.len());
    // The file's normals are printed to f32's shortest decimal: the stored direction is the
    // given one to about 1e-7; the bound's small slack covers that and f32 arithmetic.
    let mut worst = 0.0f32;
    for (i, n) in given.iter().enumerate() {
        let got = mesh.normal(i as u32);
        assert!((got.length() - 1.0).abs() < 1e-6);
        worst = worst.max(got.cross(*n).length().atan2(got.dot(*n)));
    }
    assert!(worst <= render::octahedral::MAX_ANGLE_ERROR + 1e-6, "largest error {worst} rad");
    assert!(world
        .meshes
        .iter()
        .filter(|m| m.triangles.len() < LARGE_MESH_TRIANGLES)
        .all(|m| m.normals_oct.is_empty() && !m.is_interleaved()));
}

/// Embree reads the large mesh's interleaved vertices (a float3 buffer with a 16-byte
/// stride) as it reads the same positions in a plain 12-byte-stride array: the same hits
/// bit for bit (instance, triangle, distance, barycentrics) and the same occlusion, on
/// 20,000 random rays. Tolerance: none (exact).
#[cfg(embree)]
#[test]
fn embree_reads_interleaved_vertices_as_plain_ones_bit_for_bit() {
    let (mut world, _) = world();
    let k = world.meshes.iter().position(|m| m.is_interleaved()).expect("an interleaved mesh");
    let interleaved = accel::build(&world, Backend::Embree);
    let hits = |a: &dyn accel::Accel, rays: &[render::ray::Ray]| {
        rays.iter()
            .map(|r| {
                (
                    a.intersect(r).map(|h| (h.instance, h.prim, h.t.to_bits(), h.u.to_bits(), h.v.to_bits())),
                    a.occluded(r),
                )
            })
            .collect::<Vec<_>>()
    };
    let rays = support::rays::in_cornell_box(20_000, 0x2545_f491_4f6c_dd1d);
    let got = hits(interleaved.as_ref(), &rays);
    drop(interleaved);
    let mut plain = world.meshes[k].to_plain();
    // Room past the end, so that Embree shares the array as it does a large mesh's.
    plain.positions.reserve_exact(1);
    world.meshes[k] = plain;
    let want = hits(accel::build(&world, Backend::Embree).as_ref(), &rays);
    let field = world.instances.len() as u32 - 1;
    assert!(got.iter().filter(|(h, _)| h.is_some_and(|h| h.0 == field)).count() > 2_000);
    assert!(got == want, "{} rays differ", got.iter().zip(&want).filter(|(a, b)| a != b).count());
}

/// Embree's compact build of the large mesh finds the Rust backend's hits (same triangle,
/// distance within 1e-4 relative, barycentrics within 1e-3; a ray grazing an edge two
/// triangles share may find either) and the same occlusion, on 20,000 random rays.
#[cfg(embree)]
#[test]
fn embree_compact_build_of_a_large_mesh_agrees_with_the_rust_backend() {
    let (world, _) = world();
    let rust = accel::build(&world, Backend::Rust);
    let embree = accel::build(&world, Backend::Embree);
    assert_eq!(embree.backend(), Backend::Embree);
    let rays = support::rays::in_cornell_box(20_000, 0x2545_f491_4f6c_dd1d);
    let field = world.instances.len() as u32 - 1;
    let agreement = support::backends::assert_agree(rust.as_ref(), embree.as_ref(), &rays, field);
    assert!(agreement.on_instance > 2_000, "{} rays hit the height field", agreement.on_instance);
    assert!(agreement.different <= rays.len() / 1000, "{} rays hit different triangles", agreement.different);
}

/// A large mesh's triangles are paired into quads for the acceleration structure
/// (`MeshData::quad_pairs`: nearly all of the height field's, each triangle a rotation of
/// one in the file); where a Ptex file was read — a triangle mesh's Ptex faces are its
/// triangles by index and corner — every triangle keeps the file's place and corners.
#[test]
fn a_large_mesh_pairs_its_triangles_unless_a_ptex_file_names_them() {
    let (text, _) = scene_text();
    let parsed = mi::parse_str("large_meshes.mi", &text);
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("the scene builds");
    let field = |world: &render::World| {
        let inst = world.instances.iter().max_by_key(|i| world.meshes[i.mesh as usize].triangles.len()).unwrap();
        world.meshes[inst.mesh as usize].clone()
    };
    let mut mdl = material::mdl_modules::MdlMaterials::default();
    let paired = field(&render::World::from_scene_with_mdl(&scene, None, &mdl));
    mdl.reads_ptex = true;
    let kept = field(&render::World::from_scene_with_mdl(&scene, None, &mdl));
    assert_eq!(kept.quad_pairs, 0);
    assert_eq!(kept.triangles.len(), 2 * SIDE * SIDE);
    let at = |i: usize, j: usize| (j * (SIDE + 1) + i) as u32;
    // The file's order: square by square, (a, c, b) then (a, d, c).
    for (k, tri) in kept.triangles.iter().enumerate().step_by(997) {
        let (square, second) = (k / 2, k % 2 == 1);
        let (i, j) = (square % SIDE, square / SIDE);
        let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        assert_eq!(*tri, if second { [a, d, c] } else { [a, c, b] }, "triangle {k}");
    }
    let pairs = paired.quad_pairs as usize;
    assert!(pairs * 2 >= paired.triangles.len() * 99 / 100, "{pairs} pairs of {} triangles", paired.triangles.len());
    let rotation_of_one =
        |t: [u32; 3]| kept.triangles.iter().any(|k| (0..3).any(|r| (0..3).all(|c| t[c] == k[(c + r) % 3])));
    for t in paired.triangles.iter().step_by(49_999) {
        assert!(rotation_of_one(*t), "{t:?} is a rotation of a triangle of the file");
    }
}

/// How far the moving field slides along +x while the shutter is open, mm.
const SLIDE: f32 = 40.0;

/// A large mesh on a moving instance is not flattened into world-space keys (a copy of
/// its vertices at each key and a motion-blur BVH: 609 MiB and 4–6 s to build for the heavy
/// scene's sphere) but instanced with its motion over one still BVH, and both backends hit
/// it where the motion puts it: on 20,000 random rays at random shutter times, Embree finds
/// the Rust backend's hits (as above) and every hit on the field lies on the height field
/// slid by `SLIDE · time` (within 0.02 mm in y: the flat triangles' largest sag under the
/// curved surface is ≈ 0.008 mm).
#[test]
fn a_moving_large_mesh_is_instanced_and_hit_where_its_motion_puts_it() {
    let (text, _) = scene_text();
    // The instance's transforms map world to object space: at time 1 the field stands SLIDE
    // further along +x.
    let moving = format!(
        "instance \"Field_inst\" \"Field_obj\" motion transform 1 0 0 0 0 1 0 0 0 0 1 0 {} 0 0 1 end instance",
        -SLIDE
    );
    let text = text
        .replace("instance \"Field_inst\" \"Field_obj\" end instance", &moving)
        .replace("options \"Options\"\n", "options \"Options\"\n    motion on\n    shutter 0 1\n");
    let world = world_of(&text);
    let field =
        world.instances.iter().position(|i| world.meshes[i.mesh as usize].triangles.len() >= LARGE_MESH_TRIANGLES);
    let field = field.expect("the field is placed");
    assert!(world.instances[field].moves() && !world.meshes[world.instances[field].mesh as usize].moves());
    assert!(!render::accel::flat_instances(&world)[field], "the moving large mesh keeps its own BVH");
    let mut rays = support::rays::in_cornell_box(20_000, 0x9e37_79b9_7f4a_7c15);
    for (k, ray) in rays.iter_mut().enumerate() {
        ray.time = (k as f32 * 0.618_034).fract();
    }
    let mut on_field = 0;
    for backend in [Backend::Rust, Backend::Embree] {
        let built = accel::build(&world, backend);
        for ray in &rays {
            let Some(hit) = built.intersect(ray) else { continue };
            if hit.instance as usize != field {
                continue;
            }
            on_field += 1;
            let p = ray.at(hit.t);
            let (y, _) = height_field(p.x - SLIDE * ray.time, p.z);
            assert!(
                (p.y - y).abs() < 0.02,
                "{backend:?}: hit at {p} (time {}) is {} mm off the field",
                ray.time,
                p.y - y
            );
        }
    }
    assert!(on_field > 4_000, "{on_field} hits on the field");
    #[cfg(embree)]
    {
        let rust = accel::build(&world, Backend::Rust);
        let embree = accel::build(&world, Backend::Embree);
        let agreement = support::backends::assert_agree(rust.as_ref(), embree.as_ref(), &rays, field as u32);
        assert!(agreement.on_instance > 2_000, "{} rays hit the moving field", agreement.on_instance);
        assert!(agreement.different <= rays.len() / 1000, "{} rays hit different triangles", agreement.different);
    }
}

/// The height field with a motion vector of `SLIDE` mm along +x on every vertex (it
/// deforms: the mesh's own vertices move while the shutter is open), placed once for each
/// of `lifts` (its instance raised that many mm).
fn deforming_world(lifts: &[f32]) -> render::World {
    let (text, _) = scene_text();
    let head = format!("trilist vertex {} p n triangle", (SIDE + 1) * (SIDE + 1));
    let rows_start = text.find(&head).expect("the field's trilist") + head.len();
    let rows_start = text[rows_start..].find("[\n").expect("its vertex rows") + rows_start + 2;
    let rows_end = text[rows_start..].find(']').expect("closed vertex rows") + rows_start;
    let rows: String = text[rows_start..rows_end].lines().map(|row| format!("{row} {SLIDE} 0 0\n")).collect();
    let text =
        format!("{}{rows}{}", &text[..rows_start], &text[rows_end..]).replace(&head, &head.replace(" n ", " n m "));
    // The instance transforms map world to object space: instance k stands lifts[k] up.
    let instances: String = lifts
        .iter()
        .enumerate()
        .map(|(k, lift)| {
            format!(
                "instance \"Field_inst{k}\" \"Field_obj\" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 {} 0 1 end instance\n",
                -lift
            )
        })
        .collect();
    let names: String = (0..lifts.len()).map(|k| format!("    \"Field_inst{k}\"\n")).collect();
    let text = text
        .replace("instance \"Field_inst\" \"Field_obj\" end instance\n", &instances)
        .replace("    \"Field_inst\"\n", &names)
        .replace("options \"Options\"\n", "options \"Options\"\n    motion on\n    shutter 0 1\n");
    world_of(&text)
}

/// A large mesh that deforms (motion vectors on its vertices, the heavy scene's sphere in
/// `tools/heavy_variants.py`'s `heavy_deform.mi`) has its triangles paired, and Embree holds
/// it as moving quads — in the top-level scene (placed once, at the identity: reading the
/// mesh's own keys; raised: world-space copies of them) or as a shared scene (placed
/// twice). Every hit on the field, by either backend, on 20,000 random rays at spread
/// shutter times, lies on the height field slid by `SLIDE · time` and raised by its
/// instance's lift (within 0.02 mm in y, as above); Embree finds the Rust backend's hits
/// (same triangle, distance within 1e-4 relative, barycentrics within 1e-3), and in the
/// placed-once worlds its top-level geometry split by kind hits what one scene holding it
/// all hits, bit for bit.
#[test]
fn a_deforming_large_mesh_is_held_as_moving_quads_and_hit_where_its_motion_puts_it() {
    let mut rays = support::rays::in_cornell_box(20_000, 0x9e37_79b9_7f4a_7c15);
    for (k, ray) in rays.iter_mut().enumerate() {
        ray.time = (k as f32 * 0.618_034).fract();
    }
    for lifts in [&[0.0][..], &[25.0], &[0.0, 200.0]] {
        let world = deforming_world(lifts);
        let fields: Vec<usize> = (0..world.instances.len())
            .filter(|&k| world.meshes[world.instances[k].mesh as usize].triangles.len() >= LARGE_MESH_TRIANGLES)
            .collect();
        assert_eq!(fields.len(), lifts.len());
        let mesh = &world.meshes[world.instances[fields[0]].mesh as usize];
        assert!(mesh.moves(), "the field deforms");
        assert!(2 * mesh.quad_pairs as usize >= mesh.triangles.len() * 99 / 100, "{} pairs", mesh.quad_pairs);
        let mut on_field = vec![0; lifts.len()];
        for backend in [Backend::Rust, Backend::Embree] {
            let built = accel::build(&world, backend);
            for ray in &rays {
                let Some(hit) = built.intersect(ray) else { continue };
                let Some(k) = fields.iter().position(|&f| f == hit.instance as usize) else { continue };
                on_field[k] += 1;
                let p = ray.at(hit.t);
                let (y, _) = height_field(p.x - SLIDE * ray.time, p.z);
                let off = p.y - lifts[k] - y;
                assert!(
                    off.abs() < 0.02,
                    "{backend:?}, lift {}: hit at {p} (time {}) is {off} mm off",
                    lifts[k],
                    ray.time
                );
            }
        }
        assert!(on_field.iter().all(|&n| n > 2_000), "{on_field:?} hits on the fields");
        #[cfg(embree)]
        {
            use render::accel::embree::EmbreeAccel;
            let rust = accel::build(&world, Backend::Rust);
            let embree = EmbreeAccel::new(&world);
            assert_eq!(embree.error(), 0);
            assert_eq!(embree.quad_count(), mesh.triangles.len() - mesh.quad_pairs as usize, "held as quads");
            for &field in &fields {
                let agreement = support::backends::assert_agree(rust.as_ref(), &embree, &rays, field as u32);
                assert!(agreement.on_instance > 1_000, "{} rays hit the field", agreement.on_instance);
                assert!(agreement.different <= rays.len() / 1000, "{} rays hit other triangles", agreement.different);
            }
            if lifts.len() == 1 {
                use render::accel::Accel;
                // The box's triangles and the field's moving quads.
                assert_eq!(embree.top_level_scenes(), 2);
                let one = EmbreeAccel::new_compact_in_one_scene(&world);
                let bits = |h: Option<accel::Hit>| {
                    h.map(|h| (h.t.to_bits(), h.instance, h.prim, h.u.to_bits(), h.v.to_bits()))
                };
                for ray in &rays {
                    assert_eq!(bits(embree.intersect(ray)), bits(one.intersect(ray)), "{ray:?}");
                    assert_eq!(embree.occluded(ray), one.occluded(ray), "{ray:?}");
                }
            }
        }
    }
}
