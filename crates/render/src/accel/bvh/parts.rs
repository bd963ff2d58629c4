//! The BVH of many triangles (a large world's flattened instances, or a large shared mesh),
//! built in parts on all threads and joined under one root. Much of a build runs on one
//! thread (obvhs's conversion to its 8-wide BVH was most of the heavy scene's 5–7 s build
//! in one piece); parts of about half a million triangles each are built side by side, each
//! sorting its own piece of the triangles into its leaf order, and the joined BVH is
//! traversed as one (a root node over the parts' roots), so rays cost what they did.

use glam::Vec3A;
use obvhs::BvhBuildParams;
use rayon::prelude::*;

use super::{sort_into_bvh, triangle_bvh, MeshBvh, Tri, WideBvh};

/// Triangles a part: a world with at least twice as many flattened triangles is built in
/// parts (at most [`MAX_PARTS`]). Each part being built holds ≈ 210 bytes a triangle of
/// obvhs's scratch (docs/performance.md, rustmem49), so parts of half a million keep
/// two threads' builds near 200 MiB.
pub(super) const PART_TRIANGLES: usize = 1 << 19;

/// At most this many parts: the children of one 8-wide root node.
const MAX_PARTS: usize = 8;

/// The BVH of the triangles `tris` (none if there are none): in parts of about
/// `part_triangles` where there are at least twice as many. The parts depend on the
/// triangles only, never on the thread count, so a scene gives the same hits on any machine
/// and at any thread count.
pub(super) fn bvh_in_parts(
    mut tris: Vec<Tri>,
    params: BvhBuildParams,
    part_triangles: usize,
) -> Option<MeshBvh<'static>> {
    if tris.is_empty() {
        return None;
    }
    if tris.len() < 2 * part_triangles {
        return Some(triangle_bvh(tris, params));
    }
    // Triangles large against the world (a room's walls) would stretch whichever part they
    // joined over the whole world: they make a part of their own, first.
    let (lo, hi) = tris.par_iter().map(triangle_box).reduce(empty_box, union);
    let limit = (hi - lo).max_element() / 16.0;
    let mut large = 0;
    for k in 0..tris.len() {
        let (t_lo, t_hi) = triangle_box(&tris[k]);
        if (t_hi - t_lo).max_element() > limit {
            tris.swap(large, k);
            large += 1;
        }
    }
    let (large_tris, rest) = tris.split_at_mut(large);
    let most = if large > 0 { MAX_PARTS - 1 } else { MAX_PARTS };
    let wanted = rest.len().div_ceil(part_triangles).clamp(1, most);
    let mut pieces = vec![large_tris];
    pieces.extend(split(rest, wanted));
    // A world of large triangles only leaves no rest (and one without leaves no large part).
    pieces.retain(|piece| !piece.is_empty());
    if pieces.len() == 1 {
        // The one piece is every triangle.
        return Some(triangle_bvh(tris, params));
    }
    // Each part puts its piece in its own leaf order, so the pieces, one after the other,
    // are the joined BVH's triangles as they are.
    let parts: Vec<(WideBvh, usize)> =
        pieces.into_par_iter().map(|piece| (sort_into_bvh(piece, params), piece.len())).collect();
    assert_eq!(parts.iter().map(|(_, n)| n).sum::<usize>(), tris.len(), "the parts hold every triangle once");
    Some(MeshBvh { bvh: WideBvh::join(parts), tris, moving: None })
}

/// The box of a triangle's vertices, (min, max).
fn triangle_box(t: &Tri) -> (Vec3A, Vec3A) {
    let [p0, p1, p2] = t.corners();
    (p0.min(p1).min(p2), p0.max(p1).max(p2))
}

/// A box that holds nothing.
fn empty_box() -> (Vec3A, Vec3A) {
    (Vec3A::INFINITY, Vec3A::NEG_INFINITY)
}

/// The box holding two boxes.
fn union(a: (Vec3A, Vec3A), b: (Vec3A, Vec3A)) -> (Vec3A, Vec3A) {
    (a.0.min(b.0), a.1.max(b.1))
}

/// `piece` split into `count` pieces of (nearly) equal size, each split in two
/// ([`cut`]) with as many triangles on each side as pieces are to come of it.
fn split(piece: &mut [Tri], count: usize) -> Vec<&mut [Tri]> {
    if count <= 1 {
        return vec![piece];
    }
    let before = count / 2;
    let (first, second) = cut(piece, piece.len() * before / count);
    let (mut a, b) = rayon::join(|| split(first, before), || split(second, count - before));
    a.extend(b);
    a
}

/// `piece` cut in two with `at` triangles in the first, those whose centroids come first
/// along the longest side of their box (ties broken by instance and triangle, so the cut is
/// one whatever the order the triangles came in).
fn cut(piece: &mut [Tri], at: usize) -> (&mut [Tri], &mut [Tri]) {
    let centroid = |t: &Tri| {
        let [p0, p1, p2] = t.corners();
        p0 + p1 + p2
    };
    let (lo, hi) = piece.iter().map(|t| (centroid(t), centroid(t))).fold(empty_box(), union);
    let extent = hi - lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    if at > 0 && at < piece.len() {
        piece.select_nth_unstable_by(at, |a, b| {
            centroid(a)[axis]
                .total_cmp(&centroid(b)[axis])
                .then(a.instance.cmp(&b.instance))
                .then(a.index.cmp(&b.index))
        });
    }
    piece.split_at_mut(at)
}

#[cfg(test)]
mod tests {
    use super::super::test_numbers as numbers;
    use super::*;
    use crate::ray::Ray;

    /// 20,000 small triangles scattered through a 100-unit cube, and 6 large ones (the
    /// cube's faces, two triangles each on three sides) that make a part of their own.
    fn triangles() -> Vec<Tri> {
        let mut tris = super::super::test_scattered_triangles(0x5851_f42d_4c95_7f2d, 20_000, 1.0, 1);
        let v = |x: f32, y: f32, z: f32| Vec3A::new(x, y, z) * 100.0;
        let faces = [
            (v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(1.0, 1.0, 0.0), v(0.0, 1.0, 0.0)),
            (v(0.0, 0.0, 0.0), v(0.0, 1.0, 0.0), v(0.0, 1.0, 1.0), v(0.0, 0.0, 1.0)),
            (v(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0), v(1.0, 0.0, 1.0), v(1.0, 0.0, 0.0)),
        ];
        for (k, (a, b, c, d)) in faces.into_iter().enumerate() {
            let index = 2 * k as u32;
            tris.push(Tri::new(a, b, c, index, 0));
            tris.push(Tri::new(a, c, d, index + 1, 0));
        }
        tris
    }

    /// The closest hit of `ray` in `bvh` as (distance, instance, triangle), and whether
    /// anything blocks it, found as the renderer finds them.
    fn trace(bvh: &MeshBvh, ray: &Ray) -> (Option<(f32, u32, u32)>, bool) {
        let mut best = None;
        bvh.bvh.closest(ray.origin, ray.dir, ray.tmin, ray.tmax, |id, reach| {
            let t = &bvh.tris[id];
            match t.hit(&Ray { tmax: reach, ..*ray }) {
                Some((d, _, _)) => {
                    best = Some((d, t.instance, t.index));
                    d
                }
                None => reach,
            }
        });
        let blocked = bvh.bvh.any(ray.origin, ray.dir, ray.tmin, ray.tmax, |id| bvh.tris[id].hit(ray).is_some());
        (best, blocked)
    }

    /// Built in parts and joined — the small triangles in 8 parts or 3 (an odd count: cuts
    /// at a third), or, with the cube's faces, the faces apart and the rest in 7 parts or 3
    /// — the BVH holds every triangle once and finds what the BVH built whole finds: on
    /// 20,000 rays from inside and outside the cube, the same closest distance bit for bit
    /// (the nearest of the same triangle tests), the same triangle unless two lie at that
    /// very distance, and the same occlusion.
    #[test]
    fn joined_parts_find_what_one_bvh_finds() {
        for (faces, part_triangles, parts) in [(false, 2_000, 8), (true, 2_000, 8), (false, 7_000, 3), (true, 7_000, 4)]
        {
            let mut tris = triangles();
            if !faces {
                tris.retain(|t| t.instance == 1);
            }
            joined_parts_agree(tris, parts, part_triangles);
        }
    }

    fn joined_parts_agree(tris: Vec<Tri>, parts: u32, part_triangles: usize) {
        let params = BvhBuildParams::medium_build();
        let whole = triangle_bvh(tris.clone(), params);
        let joined = bvh_in_parts(tris.clone(), params, part_triangles).expect("triangles");
        assert_eq!(joined.bvh.root().inner_children(), parts, "parts under the root");
        let mut seen: Vec<(u32, u32)> = joined.tris.iter().map(|t| (t.instance, t.index)).collect();
        seen.sort_unstable();
        let mut given: Vec<(u32, u32)> = tris.iter().map(|t| (t.instance, t.index)).collect();
        given.sort_unstable();
        assert_eq!(seen, given, "every triangle once");
        let mut rnd = numbers(0x2545_f491_4f6c_dd1d);
        let (mut hits, mut blocked, mut other_triangle) = (0, 0, 0);
        for k in 0..20_000 {
            let origin = if k % 2 == 0 {
                Vec3A::new(rnd(), rnd(), rnd()) * 100.0
            } else {
                Vec3A::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 400.0
            };
            let target = Vec3A::new(rnd(), rnd(), rnd()) * 100.0;
            let mut ray = Ray::new(origin, target - origin);
            ray.tmax = if k % 3 == 0 { 0.5 } else { f32::INFINITY };
            let (want, want_blocked) = trace(&whole, &ray);
            let (got, got_blocked) = trace(&joined, &ray);
            assert_eq!(want.map(|h| h.0.to_bits()), got.map(|h| h.0.to_bits()), "{ray:?}");
            assert_eq!(want_blocked, got_blocked, "{ray:?}");
            hits += usize::from(got.is_some());
            blocked += usize::from(got_blocked);
            other_triangle += usize::from(want.map(|h| (h.1, h.2)) != got.map(|h| (h.1, h.2)));
        }
        assert!(hits > 3_000 && blocked > 3_000, "{hits} hits, {blocked} blocked");
        assert!(other_triangle <= 2, "{other_triangle} rays hit another triangle at the same distance");
    }

    /// Worlds of large triangles only, and of large ones and a single small one, build (no
    /// empty part; a one-triangle part joined), hold every triangle once, and find the
    /// nearest of all the triangle tests: 2,000 rays from 400 units away aimed into the
    /// cube, the joined BVH's closest distance bit for bit the least over every triangle.
    /// (Rays starting a hair from a stacked plane, which obvhs's own traversal missed, are
    /// `wide::tests::the_wide_bvh_finds_what_every_triangle_finds`' second kind.)
    #[test]
    fn large_triangles_alone_or_with_one_small_one_build() {
        let faces: Vec<Tri> = triangles().into_iter().filter(|t| t.instance == 0).collect();
        let mut large_only = Vec::new();
        for copy in 0..400 {
            // Each copy shifted a tenth along the diagonal: no two at the same distance.
            let shift = glam::Vec3::splat(0.1 * copy as f32);
            large_only.extend(faces.iter().map(|t| Tri {
                p0: t.p0 + shift,
                p1: t.p1 + shift,
                p2: t.p2 + shift,
                index: t.index + 6 * copy,
                ..*t
            }));
        }
        let mut with_small = large_only.clone();
        with_small.push(triangles()[0]);
        let params = BvhBuildParams::medium_build();
        for (tris, parts) in [(large_only, 0), (with_small, 2)] {
            let joined = bvh_in_parts(tris.clone(), params, 1_000).expect("triangles");
            // One part is built whole (its root a node of the obvhs layout, not a join).
            if parts > 0 {
                assert_eq!(joined.bvh.root().inner_children(), parts);
            }
            let mut seen: Vec<u32> = joined.tris.iter().map(|t| t.index + 100_000 * t.instance).collect();
            seen.sort_unstable();
            let mut given: Vec<u32> = tris.iter().map(|t| t.index + 100_000 * t.instance).collect();
            given.sort_unstable();
            assert_eq!(seen, given, "every triangle once");
            let mut rnd = numbers(0x9e37_79b9_7f4a_7c15);
            let mut hits = 0;
            for _ in 0..2_000 {
                let away = Vec3A::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize_or(Vec3A::X) * 400.0;
                let origin = Vec3A::splat(50.0) + away;
                let ray = Ray::new(origin, Vec3A::new(rnd(), rnd(), rnd()) * 100.0 - origin);
                let nearest = tris.iter().filter_map(|t| t.hit(&ray)).map(|h| h.0).min_by(f32::total_cmp);
                let (got, _) = trace(&joined, &ray);
                assert_eq!(nearest.map(f32::to_bits), got.map(|h| h.0.to_bits()), "{ray:?}");
                hits += usize::from(got.is_some());
            }
            assert!(hits > 1_000, "{hits} hits");
        }
    }

    /// Fewer than twice a part's triangles: built whole, as before parts.
    #[test]
    fn a_small_world_is_built_whole() {
        let params = BvhBuildParams::medium_build();
        let tris = triangles();
        let one = bvh_in_parts(tris.clone(), params, tris.len()).expect("triangles");
        let whole = triangle_bvh(tris.clone(), params);
        assert!(one.bvh == whole.bvh && one.tris.iter().zip(&whole.tris).all(|(a, b)| a.index == b.index));
    }
}
