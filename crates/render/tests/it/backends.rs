//! Both acceleration backends give the same hits on the same rays (when mira is built with
//! Embree; otherwise only the Rust backend is checked against brute force).

use crate::support;

use glam::Vec3A;
use render::accel::{self, intersect_triangle, Backend};
use render::ray::Ray;
use render::World;

fn cornell() -> World {
    let parsed = mi::parse_str("cb.mi", include_str!("../../../../scenes/iray_cornell_box.mi"));
    let mut diags = Vec::new();
    World::from_scene(&scene::Scene::build(&parsed, 0, &mut diags).unwrap())
}

/// The closest hit by testing every triangle of every instance.
fn brute_force(world: &World, ray: &Ray) -> Option<(u32, u32, f32)> {
    let mut best: Option<(u32, u32, f32)> = None;
    for (i, inst) in world.instances.iter().enumerate() {
        let mesh = &world.meshes[inst.mesh as usize];
        let local = Ray {
            origin: inst.world_to_object.transform_point3a(ray.origin),
            dir: inst.world_to_object.transform_vector3a(ray.dir),
            ..*ray
        };
        for (p, t) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = t.map(|k| mesh.position(k));
            if let Some((d, _, _)) = intersect_triangle(&local, a, b, c) {
                if best.is_none_or(|x| d < x.2) {
                    best = Some((i as u32, p as u32, d));
                }
            }
        }
    }
    best
}

#[test]
fn rust_backend_matches_brute_force() {
    let world = cornell();
    let bvh = accel::build(&world, Backend::Rust);
    let mut mismatches = 0;
    let rays = support::rays::in_cornell_box(4000, 0x853c_49e6_748f_ea9b);
    for ray in &rays {
        let a = bvh.intersect(ray).map(|h| (h.instance, h.prim, h.t));
        let b = brute_force(&world, ray);
        match (a, b) {
            (Some(a), Some(b)) if a.0 == b.0 && a.1 == b.1 && (a.2 - b.2).abs() <= 1e-3 * b.2 => {}
            (None, None) => {}
            _ => mismatches += 1,
        }
        assert_eq!(bvh.occluded(ray), b.is_some());
    }
    assert_eq!(mismatches, 0);
}

/// Rays straight along an axis with negative zeros in the other components, as a negated
/// vector gives them (−(0, 0, −1) = (−0, −0, 1)): both backends and brute force agree.
#[test]
fn axis_rays_with_negative_zeros_hit() {
    let world = cornell();
    let backends: Vec<_> = [Backend::Rust, Backend::default_available()].map(|b| accel::build(&world, b)).into();
    let axes = [Vec3A::X, Vec3A::Y, Vec3A::Z];
    let mut hits = 0;
    for k in 0..200 {
        let o = Vec3A::new(30.0 + 2.5 * k as f32, 15.0 + 2.6 * k as f32, 20.0 + 2.7 * k as f32);
        for axis in axes {
            for sign in [1.0, -1.0] {
                let dir = Vec3A::select(axis.cmpne(Vec3A::ZERO), sign * axis, Vec3A::splat(-0.0));
                let ray = Ray::new(o, dir);
                assert!(ray.dir.to_array().iter().any(|c| *c == 0.0 && c.is_sign_negative()));
                // (A ray may cross the diagonal shared by a quad's two triangles: compare the
                // instance and the distance, not the triangle.)
                let want = brute_force(&world, &ray);
                hits += want.is_some() as u32;
                for b in &backends {
                    let got = b.intersect(&ray);
                    let same = match (got, want) {
                        (Some(g), Some(w)) => g.instance == w.0 && (g.t - w.2).abs() <= 1e-3 * w.2,
                        (g, w) => g.is_none() && w.is_none(),
                    };
                    assert!(same, "{:?} {ray:?}: {got:?} vs {want:?}", b.backend());
                    assert_eq!(b.occluded(&ray), want.is_some());
                }
            }
        }
    }
    assert!(hits > 800, "{hits} of 1200 rays hit");
}

/// Hits right at a ray's origin are found: rays that reached a surface of the Cornell box
/// (its walls and blocks flattened into world space, and the short block placed a second
/// time, 300 mm up, so that its mesh is shared and entered through the top-level BVH) are
/// started again 1e-6 to 1e-3 mm before the point they hit, and the Rust backend finds
/// what testing every triangle finds: the same instance, the distance within 1e-6 relative
/// plus 2e-4 mm (the rounding of a distance from a point 300–500 mm from the origin, where
/// the flattened triangles and brute force's object-space ones differ in their last bits;
/// a missed surface puts the next one millimetres away), and the same occlusion. obvhs's node test dropped boxes the ray leaves within 1e-4 of its
/// origin, so that such rays went through flat boxes (a wall's) to whatever lay behind
/// (it fails with the traversal ray not moved back: checked).
#[test]
fn hits_right_at_the_origin_are_found() {
    let mut text = include_str!("../../../../scenes/iray_cornell_box.mi").to_string();
    let root = text.find("instgroup").expect("the scene has a root group");
    text.insert_str(
        root,
        "instance \"Short_block_up\" \"Short_block_obj\"\n material \"white\"\n transform 1 0 0 0 0 1 0 0 0 0 1 0 0 -300 0 1\nend instance\n",
    );
    let list_end = text[root..].find("end instgroup").expect("closed root group") + root;
    text.insert_str(list_end, "    \"Short_block_up\"\n");
    let parsed = mi::parse_str("near.mi", &text);
    let mut diags = Vec::new();
    let world = World::from_scene(&scene::Scene::build(&parsed, 0, &mut diags).unwrap());
    let shared =
        world.instances.iter().filter(|i| world.instances.iter().filter(|j| j.mesh == i.mesh).count() > 1).count();
    assert_eq!(shared, 2, "the short block's mesh is placed twice");
    let bvh = accel::build(&world, Backend::Rust);
    let (mut near, mut on_shared) = (0, 0);
    for (k, ray) in support::rays::in_cornell_box(3000, 0x9e37_79b9_7f4a_7c15).iter().enumerate() {
        let Some((_, _, t)) = brute_force(&world, ray) else { continue };
        let back = [1e-6, 1e-5, 5e-5, 9e-5, 2e-4, 1e-3][k % 6];
        let start = Ray { origin: ray.at(t) - ray.dir * back, tmin: 0.0, tmax: f32::INFINITY, ..*ray };
        let want = brute_force(&world, &start);
        let got = bvh.intersect(&start);
        match (got, want) {
            (Some(g), Some(w)) => {
                assert!(g.instance == w.0 && (g.t - w.2).abs() <= 1e-6 * w.2 + 2e-4, "{start:?}: {g:?} vs {w:?}");
                near += usize::from(w.2 < 1e-4);
                on_shared += usize::from(
                    world.instances.iter().filter(|i| i.mesh == world.instances[w.0 as usize].mesh).count() > 1,
                );
            }
            (g, w) => assert!(g.is_none() && w.is_none(), "{start:?}: {g:?} vs {w:?}"),
        }
        assert_eq!(bvh.occluded(&start), want.is_some(), "{start:?}");
    }
    assert!(near > 1_000 && on_shared > 50, "{near} hits within 1e-4, {on_shared} on the shared block");
}

#[cfg(embree)]
#[test]
fn embree_and_rust_backends_agree() {
    let world = cornell();
    let rust = accel::build(&world, Backend::Rust);
    let embree = accel::build(&world, Backend::Embree);
    assert_eq!(embree.backend(), Backend::Embree);
    let rays = support::rays::in_cornell_box(20_000, 0x853c_49e6_748f_ea9b);
    let mut different = 0;
    for ray in &rays {
        let (a, b) = (rust.intersect(ray), embree.intersect(ray));
        match (a, b) {
            (Some(a), Some(b)) => {
                // Same triangle at the same distance; rays that graze a shared edge may pick
                // either neighbour, and the distances then agree too.
                if (a.instance, a.prim) != (b.instance, b.prim) {
                    different += 1;
                }
                assert!((a.t - b.t).abs() <= 1e-4 * a.t.max(1.0), "{a:?} vs {b:?}");
                assert!(
                    (a.u - b.u).abs() < 1e-3 && (a.v - b.v).abs() < 1e-3
                        || (a.instance, a.prim) != (b.instance, b.prim)
                );
            }
            (None, None) => {}
            _ => panic!("one backend hit and the other missed: {a:?} {b:?} for {ray:?}"),
        }
        assert_eq!(rust.occluded(ray), embree.occluded(ray));
    }
    assert!(different <= rays.len() / 1000, "{different} rays hit different triangles");
}

/// Embree's stream kernel (`EmbreeAccel::intersect_stream`, the measurement hook of
/// `benches/wavefront.rs`), with either coherence flag, finds what the one-ray query finds
/// for 5,000 scattered rays in the Cornell box, given all at once and in uneven pieces:
/// the same instance and triangle (at most 1 ray in 1,000 grazing a shared edge may take
/// the neighbour) and the same distance within 1e-4 relative.
#[cfg(embree)]
#[test]
fn embree_stream_matches_single_rays() {
    let world = cornell();
    let embree = render::accel::embree::EmbreeAccel::new(&world);
    let rays = support::rays::in_cornell_box(5_000, 0x2545_f491_4f6c_dd1d);
    let single: Vec<_> = rays.iter().map(|r| accel::Accel::intersect(&embree, r)).collect();
    assert!(single.iter().filter(|h| h.is_some()).count() > rays.len() / 2, "most rays hit the box");
    for coherent in [false, true] {
        for piece in [rays.len(), 7, 1] {
            let mut stream = vec![None; rays.len()];
            for (r, h) in rays.chunks(piece).zip(stream.chunks_mut(piece)) {
                embree.intersect_stream(r, h, coherent);
            }
            let mut different = 0;
            for (a, b) in single.iter().zip(&stream) {
                match (a, b) {
                    (Some(a), Some(b)) => {
                        different += usize::from((a.instance, a.prim) != (b.instance, b.prim));
                        assert!((a.t - b.t).abs() <= 1e-4 * a.t.max(1.0), "{a:?} vs {b:?}");
                    }
                    (None, None) => {}
                    _ => panic!("the stream and the one-ray query disagree: {a:?} {b:?}"),
                }
            }
            assert!(different <= rays.len() / 1000, "{different} rays hit other triangles");
        }
    }
}

/// Occlusion asked for a batch of rays (as the light loop asks for a light's samples: from
/// one point, up to a distance, in groups of every size up to 19, which Embree traces as
/// packets of eight) answers each ray as the one-ray query does, on both backends; the
/// rays include blocked and free ones.
#[test]
fn batched_occlusion_matches_single_rays() {
    let world = cornell();
    // Points other than the rays' origins (the same generator, further on).
    let targets = support::rays::in_cornell_box(660, 0x853c_49e6_748f_ea9b).split_off(60);
    for backend in [Backend::Rust, Backend::default_available()] {
        let accel = accel::build(&world, backend);
        let (mut blocked_count, mut free_count, mut at) = (0, 0, 0);
        for (k, from) in support::rays::in_cornell_box(60, 0x853c_49e6_748f_ea9b).iter().enumerate() {
            let n = 1 + k % 19;
            let batch: Vec<Ray> = targets[at..at + n]
                .iter()
                .map(|t| {
                    let d = t.origin - from.origin;
                    Ray { tmax: d.length() * 0.999, ..Ray::new(from.origin, d.normalize()) }
                })
                .collect();
            at = (at + n) % (targets.len() - 20);
            let mut blocked = vec![false; n];
            accel.occluded_batch(&batch, &mut blocked);
            for (ray, b) in batch.iter().zip(&blocked) {
                assert_eq!(*b, accel.occluded(ray), "{backend:?} {ray:?}");
                if *b {
                    blocked_count += 1;
                } else {
                    free_count += 1;
                }
            }
        }
        assert!(blocked_count > 50 && free_count > 50, "{backend:?}: {blocked_count} blocked, {free_count} free");
    }
}

/// Closest hits asked for a batch of rays (as the path engine asks for a row's camera
/// rays, which Embree traces as packets of eight) are, bit for bit, the one-ray query's:
/// the camera's rays through a 48² grid of the image (coherent packets), then random rays
/// in groups of every size up to 19 (incoherent ones, and partial packets), on both
/// backends. The one allowed difference: a ray through the edge two triangles share
/// (within 1e-5 of an edge in both hits, at the same distance within 1e-5) may find either
/// triangle — Embree's packet and one-ray kernels break such exact ties in their own
/// orders (one camera ray of 4.2 M in the 256², 64-spp render of the bench's Cornell box).
#[test]
fn batched_intersection_matches_single_rays() {
    let world = cornell();
    let cam = &world.camera;
    let mut camera_rays = Vec::new();
    for y in 0..48 {
        for x in 0..48 {
            let (fx, fy) = ((x as f32 + 0.37) / 48.0, (y as f32 + 0.61) / 48.0);
            camera_rays.push(cam.ray_at(fx * cam.width as f32, fy * cam.height as f32, 0.0));
        }
    }
    let random = support::rays::in_cornell_box(1200, 0x9e37_79b9_7f4a_7c15);
    for backend in [Backend::Rust, Backend::default_available()] {
        let accel = accel::build(&world, backend);
        let mut groups: Vec<&[Ray]> = camera_rays.chunks(8).collect();
        let mut at = 0;
        for n in (1..=19).cycle() {
            if at + n > random.len() {
                break;
            }
            groups.push(&random[at..at + n]);
            at += n;
        }
        let (mut hit_count, mut miss_count, mut ties) = (0, 0, 0);
        for batch in groups {
            let mut hits = vec![None; batch.len()];
            accel.intersect_batch(batch, &mut hits);
            for (ray, h) in batch.iter().zip(&hits) {
                let single = accel.intersect(ray);
                let bits = |h: Option<render::accel::Hit>| {
                    h.map(|h| (h.t.to_bits(), h.instance, h.prim, h.u.to_bits(), h.v.to_bits()))
                };
                let edge = |h: render::accel::Hit| h.u.min(h.v).min(1.0 - h.u - h.v) < 1e-5;
                let tie = match (*h, single) {
                    (Some(a), Some(b)) => (a.t - b.t).abs() <= 1e-5 * a.t && edge(a) && edge(b),
                    _ => false,
                };
                assert!(bits(*h) == bits(single) || tie, "{backend:?} {ray:?}: {h:?} vs {single:?}");
                ties += usize::from(bits(*h) != bits(single));
                if h.is_some() {
                    hit_count += 1;
                } else {
                    miss_count += 1;
                }
            }
        }
        // The camera sees the open front of the box past its walls, so some rays miss.
        assert!(hit_count > 1000 && miss_count > 50, "{backend:?}: {hit_count} hits, {miss_count} misses");
        assert!(ties <= 2, "{backend:?}: {ties} edge ties broken differently");
    }
}

/// Every field of a ray reaches Embree's one-ray queries (the query wrapper writes the
/// ray as three 16-byte groups, speed36): on 2,000 random rays in the Cornell box, Embree
/// and the Rust backend agree (distance within 1e-4 relative, occlusion exactly) when the
/// ray starts past its first hit (`tmin`: the next surface is found), when it ends just
/// short of it (`tmax` at 0.999 of the distance: nothing), and when its mask shares no
/// bit with the instances' (nothing hit or blocked).
#[cfg(embree)]
#[test]
fn embree_reads_every_ray_field() {
    let world = cornell();
    let rust = accel::build(&world, Backend::Rust);
    let embree = accel::build(&world, Backend::Embree);
    let (mut second_hits, mut first_hits) = (0, 0);
    for ray in &support::rays::in_cornell_box(2_000, 0x6a09_e667_f3bc_c908) {
        let Some(first) = rust.intersect(ray) else { continue };
        first_hits += 1;
        let past = Ray { tmin: first.t * 1.001, ..*ray };
        let short = Ray { tmax: first.t * 0.999, ..*ray };
        let masked = Ray { mask: 1 << 30, ..*ray };
        match (rust.intersect(&past), embree.intersect(&past)) {
            (Some(a), Some(b)) => {
                second_hits += 1;
                assert!((a.t - b.t).abs() <= 1e-4 * a.t, "{a:?} vs {b:?} for {past:?}");
            }
            (None, None) => {}
            (a, b) => panic!("past the first hit: {a:?} vs {b:?} for {past:?}"),
        }
        assert_eq!(embree.occluded(&past), rust.occluded(&past), "{past:?}");
        assert_eq!(embree.intersect(&short), None, "{short:?}");
        assert!(!embree.occluded(&short) && !rust.occluded(&short), "{short:?}");
        assert_eq!(embree.intersect(&masked), None, "{masked:?}");
        assert!(!embree.occluded(&masked), "{masked:?}");
    }
    assert!(first_hits > 1_500 && second_hits > 300, "{first_hits} first hits, {second_hits} second hits");
}

/// Both backends report the bytes of what they built (`--stats`' `geometry:` line): the
/// Rust BVH counts its own arrays, at least its world-space triangle copies (three
/// 16-byte points a triangle); Embree's memory monitor reports what the device holds after
/// the build, within a few kilobytes a triangle of this small scene (its block sizes).
#[test]
fn backends_report_their_memory() {
    let world = cornell();
    let triangles = world.instanced_triangles() as u64;
    assert!(triangles > 0);
    let rust = accel::build(&world, Backend::Rust).memory().expect("the Rust BVH counts its arrays");
    assert!(rust.counted);
    assert!(rust.bytes >= 48 * triangles, "{} bytes for {triangles} triangles", rust.bytes);
    assert!(rust.bytes <= 1024 * triangles, "{} bytes for {triangles} triangles", rust.bytes);
    #[cfg(embree)]
    {
        let embree = accel::build(&world, Backend::Embree).memory().expect("Embree's monitor reports");
        assert!(!embree.counted);
        assert!(embree.bytes >= 16 * triangles, "{} bytes for {triangles} triangles", embree.bytes);
        assert!(embree.bytes <= 4096 * triangles, "{} bytes for {triangles} triangles", embree.bytes);
    }
}

/// A ray without a direction (from a point to itself) or with a subnormal one, far beside
/// the scene and not towards it, finds nothing and blocks nothing on either backend,
/// without a panic (the Rust backend moves its traversal's start back by a distance that grows as
/// the direction shrinks: it is bounded).
#[test]
fn rays_without_a_direction_find_nothing() {
    let world = cornell();
    for backend in [Backend::Rust, Backend::default_available()] {
        let built = accel::build(&world, backend);
        for dir in [Vec3A::ZERO, Vec3A::new(1e-41, 0.0, 0.0), Vec3A::new(0.0, -1e-40, 1e-41)] {
            // Beside the box, looking away from it or along it.
            for origin in [Vec3A::new(5000.0, 100.0, 100.0), Vec3A::new(9000.0, -40.0, 300.0)] {
                let ray = Ray { origin, dir, tmin: 0.0, tmax: f32::INFINITY, mask: !0, time: 0.0 };
                assert!(built.intersect(&ray).is_none(), "{backend:?} {ray:?}");
                assert!(!built.occluded(&ray), "{backend:?} {ray:?}");
            }
        }
    }
}
