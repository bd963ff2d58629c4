//! Moving triangles for the Rust backend: their vertices at keys spread evenly over the
//! shutter (a moving mesh's own keys, or a flattened moving instance's world-space ones),
//! in a binary BVH whose boxes move with what they hold. Each node keeps its box at the
//! start and at the end of an interval between keys, and a ray at shutter time t tests
//! the box interpolated to t (linear bounds, as Embree's motion-blur BVHs keep them):
//! since every vertex moves linearly over the interval, that box holds everything below
//! the node at t. A box over the whole shutter instead would be stretched by the whole
//! motion — for a mesh sliding further than its triangles are wide, every ray would test
//! most of it. Triangles are grouped by their key count, and each group has one tree per
//! interval between its keys.

use glam::{Vec3, Vec3A};
use rayon::prelude::*;

use crate::accel::{intersect_triangle, Hit};
use crate::ray::Ray;

/// Vertex positions at each key: `keys[j][i]` is vertex i at the j-th of the keys spread
/// evenly over the shutter (one key: it holds still). Borrowed where they are a mesh's own
/// (`position_keys`, which the BVH then reads in place), owned where they were made for it
/// (a placed instance's world-space keys).
pub(in crate::accel) type KeySet<'k> = std::borrow::Cow<'k, [Vec<Vec3A>]>;

/// A moving triangle: its vertices in key set `set`, its index in its mesh and its
/// instance.
#[derive(Clone, Copy, Debug)]
pub(in crate::accel) struct MovingTri {
    /// Its vertices, indices into each key of its set.
    pub v: [u32; 3],
    /// Its key set in [`MovingBvh::build`]'s `sets`.
    pub set: u32,
    /// Its index in its mesh.
    pub index: u32,
    /// Its instance.
    pub instance: u32,
}

/// Triangles a leaf holds at most.
const LEAF_TRIANGLES: usize = 4;

/// Bins of the binned surface-area split.
const BINS: usize = 12;

/// Triangles from which a node's two halves are built on two threads.
const PARALLEL_FROM: usize = 1 << 16;

/// Depth from which nodes are halved by count (bounding the depth, so that traversal's
/// stack of [`STACK`] entries cannot overflow: at most 64 + 32 levels).
const HALVE_FROM_DEPTH: usize = 64;

/// Traversal's stack entries.
const STACK: usize = 128;

/// A node: its box at the start (`lo0`, `hi0`) and at the end (`lo1`, `hi1`) of its tree's
/// interval. An inner node's first child follows it; `link` is how far past it the second
/// child is. A leaf (`count` > 0) holds `count` triangles from `link` on in its tree's
/// `prims`. 64 bytes.
#[derive(Clone, Copy, Default)]
#[repr(C)]
struct Node {
    lo0: [f32; 3],
    link: u32,
    hi0: [f32; 3],
    count: u32,
    lo1: [f32; 3],
    _pad0: u32,
    hi1: [f32; 3],
    _pad1: u32,
}

/// A box at the two ends of an interval: (lo0, hi0, lo1, hi1).
type Ends = [Vec3A; 4];

/// A triangle's box in the middle of an interval (low and high corners, packed: 24 bytes),
/// as the build keeps one a triangle.
type MidBox = [Vec3; 2];

/// The box holding nothing at either end.
const NO_ENDS: Ends = [Vec3A::INFINITY, Vec3A::NEG_INFINITY, Vec3A::INFINITY, Vec3A::NEG_INFINITY];

/// The boxes holding `a`'s and `b`'s at each end.
fn union(a: Ends, b: Ends) -> Ends {
    [a[0].min(b[0]), a[1].max(b[1]), a[2].min(b[2]), a[3].max(b[3])]
}

impl Node {
    /// A node of the boxes `ends`.
    fn with(ends: Ends, link: u32, count: u32) -> Node {
        Node {
            lo0: ends[0].to_array(),
            link,
            hi0: ends[1].to_array(),
            count,
            lo1: ends[2].to_array(),
            hi1: ends[3].to_array(),
            ..Node::default()
        }
    }

    /// Its boxes.
    fn ends(&self) -> Ends {
        [self.lo0.into(), self.hi0.into(), self.lo1.into(), self.hi1.into()]
    }
}

/// The BVH of one interval between keys.
struct Tree {
    /// Its nodes, the root first.
    nodes: Vec<Node>,
    /// Triangle indices into [`MovingBvh`]'s `tris`, in leaf order.
    prims: Vec<u32>,
    /// How far every box is widened at traversal, in the units of the positions: a
    /// millionth of the largest coordinate, several times the rounding of an
    /// interpolated box or vertex.
    pad: f32,
}

/// Moving triangles and their BVHs.
pub(in crate::accel) struct MovingBvh<'k> {
    sets: Vec<KeySet<'k>>,
    tris: Vec<MovingTri>,
    /// The triangles grouped by how many keys they have, each group with one tree per
    /// interval between its keys (intervals of shutter time 1 / its length): a set of many
    /// keys (a fast turn has up to 48 intervals) does not multiply the trees of the others.
    groups: Vec<Vec<Tree>>,
}

impl<'k> MovingBvh<'k> {
    /// The BVHs of `tris`, whose vertices are in `sets` (a triangle naming a set or vertex
    /// that is not there is left out); `None` without triangles.
    pub(in crate::accel) fn build(sets: Vec<KeySet<'k>>, mut tris: Vec<MovingTri>) -> Option<MovingBvh<'k>> {
        let vertices: Vec<usize> = sets.iter().map(|s| s.iter().map(Vec::len).min().unwrap_or(0)).collect();
        tris.retain(|t| vertices.get(t.set as usize).is_some_and(|&n| t.v.iter().all(|&i| (i as usize) < n)));
        if tris.is_empty() {
            return None;
        }
        let keys_of = |t: &MovingTri| sets[t.set as usize].len();
        let mut counts: Vec<usize> = tris.iter().map(keys_of).collect();
        counts.sort_unstable();
        counts.dedup();
        let groups: Vec<(usize, Vec<u32>)> = counts
            .into_iter()
            .map(|count| (count, (0..tris.len() as u32).filter(|&k| keys_of(&tris[k as usize]) == count).collect()))
            .collect();
        let mut bvh = MovingBvh { sets, tris, groups: Vec::new() };
        bvh.groups = groups
            .iter()
            .map(|(count, members)| {
                let intervals = count.saturating_sub(1).max(1);
                (0..intervals).map(|k| bvh.tree(members, k)).collect()
            })
            .collect();
        Some(bvh)
    }

    /// Bytes of the key sets it owns (borrowed ones are the world's geometry), its
    /// triangles and trees.
    pub(in crate::accel) fn heap_bytes(&self) -> usize {
        let owned = |set: &KeySet| match set {
            std::borrow::Cow::Owned(keys) => keys.iter().map(|k| std::mem::size_of_val(&k[..])).sum::<usize>(),
            std::borrow::Cow::Borrowed(_) => 0,
        };
        self.sets.iter().map(owned).sum::<usize>()
            + std::mem::size_of_val(&self.tris[..])
            + self
                .groups
                .iter()
                .flatten()
                .map(|t| std::mem::size_of_val(&t.nodes[..]) + std::mem::size_of_val(&t.prims[..]))
                .sum::<usize>()
    }

    /// The vertices of `t` at shutter time `time` (between keys, linearly).
    #[inline]
    fn at(&self, t: &MovingTri, time: f32) -> [Vec3A; 3] {
        let keys = &self.sets[t.set as usize];
        if keys.len() < 2 {
            return t.v.map(|i| keys[0][i as usize]);
        }
        let (j, f) = crate::motion::key_segment(keys.len(), time);
        let (a, b) = (&keys[j], &keys[j + 1]);
        t.v.map(|i| {
            let (a, b) = (a[i as usize], b[i as usize]);
            a + (b - a) * f
        })
    }

    /// The box of `t` at its keys `k` and `k + 1` (its one key twice if it has one), the
    /// ends of its group's interval `k`: read from the keys themselves, not from positions
    /// at the interval's end times, which f32 can put a rounding into the neighbouring
    /// interval (7/13 lands in interval 7 at 4.8e-7 of it), off by that fraction of the
    /// neighbouring interval's motion.
    fn ends(&self, t: &MovingTri, k: usize) -> Ends {
        let keys = &self.sets[t.set as usize];
        let corners = |key: &[Vec3A]| {
            let p = t.v.map(|i| key[i as usize]);
            (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]))
        };
        let (lo0, hi0) = corners(&keys[k.min(keys.len() - 1)]);
        let (lo1, hi1) = corners(&keys[(k + 1).min(keys.len() - 1)]);
        [lo0, hi0, lo1, hi1]
    }

    /// The tree over the triangles `members` (indices into `tris`, all of one key count)
    /// of the interval between their keys `k` and `k + 1`.
    fn tree(&self, members: &[u32], k: usize) -> Tree {
        let ends = |p: u32| self.ends(&self.tris[members[p as usize] as usize], k);
        // Each triangle's box in the middle of the interval and its centre, what splits are
        // chosen by, and its largest coordinate, in one read of its keys; the boxes at the
        // interval's ends are read again for the leaves.
        let (mids, (centres, largests)): (Vec<MidBox>, (Vec<Vec3>, Vec<f32>)) = (0..members.len() as u32)
            .into_par_iter()
            .map(|p| {
                let e = ends(p);
                let b = e.map(Vec3::from);
                let largest = b.iter().map(|c| c.abs().max_element()).fold(0.0f32, f32::max);
                let mid = [((e[0] + e[2]) * 0.5).into(), ((e[1] + e[3]) * 0.5).into()];
                (mid, ((b[0] + b[1] + b[2] + b[3]) * 0.25, largest))
            })
            .unzip();
        let largest = largests.into_iter().fold(0.0f32, f32::max);
        let builder = Builder { mids: &mids, centres: &centres, ends: &ends };
        let mut prims: Vec<u32> = (0..members.len() as u32).collect();
        let nodes = builder.build(&mut prims, 0, 0);
        for p in &mut prims {
            *p = members[*p as usize];
        }
        Tree { nodes, prims, pad: largest * 1e-6 }
    }

    /// The closest hit of `ray` among triangles that `accept` lets through, updating
    /// `best` (the hit's instance is `instance` if given, else the triangle's); returns the
    /// closest distance found (`ray.tmax` if none).
    pub(in crate::accel) fn closest(
        &self,
        ray: &Ray,
        instance: Option<u32>,
        accept: impl Fn(&MovingTri) -> bool,
        best: &mut Option<Hit>,
    ) -> f32 {
        let mut found = ray.tmax;
        self.traverse(ray, |t, tmax| {
            if !accept(t) {
                return tmax;
            }
            let [p0, p1, p2] = self.at(t, ray.time);
            if let Some((d, u, v)) = intersect_triangle(&Ray { tmax, ..*ray }, p0, p1, p2) {
                if d < found {
                    found = d;
                    *best = Some(Hit { t: d, instance: instance.unwrap_or(t.instance), prim: t.index, u, v });
                    return d;
                }
            }
            tmax
        });
        found
    }

    /// Whether `ray` hits a triangle that `accept` lets through.
    pub(in crate::accel) fn any(&self, ray: &Ray, accept: impl Fn(&MovingTri) -> bool) -> bool {
        let mut blocked = false;
        self.traverse(ray, |t, tmax| {
            if accept(t) {
                let [p0, p1, p2] = self.at(t, ray.time);
                if intersect_triangle(ray, p0, p1, p2).is_some() {
                    blocked = true;
                    return f32::NEG_INFINITY;
                }
            }
            tmax
        });
        blocked
    }

    /// Visits the triangles whose leaves' boxes at the ray's time `ray` meets within its
    /// reach, group by group, nearest box first; `visit` gets each triangle and the reach
    /// so far and returns the new reach (below `ray.tmin`: stop).
    #[inline]
    fn traverse(&self, ray: &Ray, mut visit: impl FnMut(&MovingTri, f32) -> f32) {
        let mut reach = ray.tmax;
        for trees in &self.groups {
            // The group's tree for the ray's time, and where in its interval that lies.
            let (k, f) = crate::motion::key_segment(trees.len() + 1, ray.time);
            if !self.traverse_tree(&trees[k], f, ray, &mut reach, &mut visit) {
                return;
            }
        }
    }

    /// [`MovingBvh::traverse`] in one tree, `f` (0…1) the ray's time in its interval;
    /// false where `visit` stopped it.
    #[inline]
    fn traverse_tree(
        &self,
        tree: &Tree,
        f: f32,
        ray: &Ray,
        reach: &mut f32,
        visit: &mut impl FnMut(&MovingTri, f32) -> f32,
    ) -> bool {
        let tiny = Vec3A::splat(1e-30);
        // A direction component of 0 taken as a tiny one of its sign: no 0 · ∞ below.
        let dir = Vec3A::select(ray.dir.abs().cmplt(tiny), tiny.copysign(ray.dir), ray.dir);
        let inv = dir.recip();
        let pad = Vec3A::splat(tree.pad);
        // The entry distance of node `n`'s box at the ray's time, if the ray meets it
        // within [tmin, reach].
        let enter = |n: &Node, reach: f32| -> Option<f32> {
            let e = n.ends();
            let lo = e[0] + (e[2] - e[0]) * f - pad;
            let hi = e[1] + (e[3] - e[1]) * f + pad;
            let (a, b) = ((lo - ray.origin) * inv, (hi - ray.origin) * inv);
            let near = a.min(b).max_element().max(ray.tmin);
            // Rounding of the slab distances: the far side a little further.
            let far = a.max(b).min_element() * (1.0 + 4.0 * f32::EPSILON);
            (near <= far.min(reach)).then_some(near)
        };
        let mut stack = [(0u32, 0.0f32); STACK];
        let mut depth = 0;
        let mut node = 0usize;
        if enter(&tree.nodes[0], *reach).is_none() {
            return true;
        }
        loop {
            let n = &tree.nodes[node];
            if n.count > 0 {
                let first = n.link as usize;
                for &p in &tree.prims[first..first + n.count as usize] {
                    *reach = visit(&self.tris[p as usize], *reach);
                    if *reach < ray.tmin {
                        return false;
                    }
                }
            } else {
                let (a, b) = (node + 1, node + n.link as usize);
                match (enter(&tree.nodes[a], *reach), enter(&tree.nodes[b], *reach)) {
                    (Some(ta), Some(tb)) => {
                        let (near, far, far_t) = if ta <= tb { (a, b, tb) } else { (b, a, ta) };
                        stack[depth] = (far as u32, far_t);
                        depth += 1;
                        node = near;
                        continue;
                    }
                    (Some(_), None) => {
                        node = a;
                        continue;
                    }
                    (None, Some(_)) => {
                        node = b;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // The next node on the stack that the ray can still reach.
            loop {
                if depth == 0 {
                    return true;
                }
                depth -= 1;
                let (next, near) = stack[depth];
                if near <= *reach {
                    node = next as usize;
                    break;
                }
            }
        }
    }
}

/// What a tree is built from: each triangle's box in the middle of the interval and the
/// centre of its boxes at the interval's ends, by which splits are chosen, and its boxes at
/// the ends, which the leaves are bounded by (worked out again from the keys for each leaf:
/// kept, they were 48 bytes a triangle for the whole build).
struct Builder<'a> {
    mids: &'a [MidBox],
    centres: &'a [Vec3],
    ends: &'a (dyn Fn(u32) -> Ends + Sync),
}

/// Half the surface area of the box from `lo` to `hi` (0 for an empty box).
fn half_area(lo: Vec3A, hi: Vec3A) -> f32 {
    let d = (hi - lo).max(Vec3A::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}

impl Builder<'_> {
    /// Triangle `p`'s boxes at the interval's ends.
    #[inline]
    fn ends(&self, p: u32) -> Ends {
        (self.ends)(p)
    }

    /// Triangle `p`'s box in the middle of the interval, (low, high).
    #[inline]
    fn mid(&self, p: u32) -> (Vec3A, Vec3A) {
        let [lo, hi] = self.mids[p as usize];
        (lo.into(), hi.into())
    }

    /// The centre of triangle `p`'s box in the middle of the interval, what splits are
    /// chosen by.
    #[inline]
    fn centre(&self, p: u32) -> Vec3A {
        self.centres[p as usize].into()
    }

    /// The nodes of the subtree over `prims` (which it reorders into leaf order; they
    /// start at `start` in the tree's `prims`), its root first.
    fn build(&self, prims: &mut [u32], start: usize, depth: usize) -> Vec<Node> {
        if prims.len() < PARALLEL_FROM {
            let mut nodes = Vec::with_capacity(2 * prims.len().div_ceil(LEAF_TRIANGLES));
            self.build_into(prims, start, depth, &mut nodes);
            return nodes;
        }
        let at = self.split(prims, depth);
        let (first, second) = prims.split_at_mut(at);
        let (a, b) = rayon::join(|| self.build(first, start, depth + 1), || self.build(second, start + at, depth + 1));
        let mut nodes = Vec::with_capacity(1 + a.len() + b.len());
        nodes.push(Node::with(union(a[0].ends(), b[0].ends()), 1 + a.len() as u32, 0));
        nodes.extend(a);
        nodes.extend(b);
        nodes
    }

    /// [`Builder::build`] on this thread, appending to `nodes`.
    fn build_into(&self, prims: &mut [u32], start: usize, depth: usize, nodes: &mut Vec<Node>) {
        let here = nodes.len();
        if prims.len() <= LEAF_TRIANGLES {
            let ends = prims.iter().fold(NO_ENDS, |e, &p| union(e, self.ends(p)));
            nodes.push(Node::with(ends, start as u32, prims.len() as u32));
            return;
        }
        nodes.push(Node::default());
        let at = self.split(prims, depth);
        let (first, second) = prims.split_at_mut(at);
        self.build_into(first, start, depth + 1, nodes);
        let link = nodes.len() - here;
        self.build_into(second, start + at, depth + 1, nodes);
        let ends = union(nodes[here + 1].ends(), nodes[here + link].ends());
        nodes[here] = Node::with(ends, link as u32, 0);
    }

    /// Reorders `prims` into two groups and returns where the second starts (neither
    /// empty): by the binned surface-area heuristic on the boxes in the middle of the
    /// interval along the longest side of their centres' box, or halved by count where
    /// that finds no split or the tree is deep.
    fn split(&self, prims: &mut [u32], depth: usize) -> usize {
        let half = prims.len() / 2;
        let (lo, hi) = prims
            .iter()
            .map(|&p| self.centre(p))
            .fold((Vec3A::INFINITY, Vec3A::NEG_INFINITY), |(lo, hi), c| (lo.min(c), hi.max(c)));
        let extent = hi - lo;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let spread = extent[axis];
        if depth >= HALVE_FROM_DEPTH || spread.is_nan() || spread <= 0.0 {
            return half;
        }
        let scale = BINS as f32 / extent[axis];
        let bin = |p: u32| (((self.centre(p)[axis] - lo[axis]) * scale) as usize).min(BINS - 1);
        let mut counts = [0usize; BINS];
        let mut boxes = [(Vec3A::INFINITY, Vec3A::NEG_INFINITY); BINS];
        for &p in prims.iter() {
            let k = bin(p);
            let (m_lo, m_hi) = self.mid(p);
            counts[k] += 1;
            boxes[k] = (boxes[k].0.min(m_lo), boxes[k].1.max(m_hi));
        }
        // Cost of each split after bin k: the left part's area × count + the right's.
        let mut right_cost = [0.0f32; BINS];
        let (mut r_box, mut r_count) = ((Vec3A::INFINITY, Vec3A::NEG_INFINITY), 0usize);
        for k in (1..BINS).rev() {
            r_box = (r_box.0.min(boxes[k].0), r_box.1.max(boxes[k].1));
            r_count += counts[k];
            right_cost[k] = half_area(r_box.0, r_box.1) * r_count as f32;
        }
        let (mut l_box, mut l_count) = ((Vec3A::INFINITY, Vec3A::NEG_INFINITY), 0usize);
        let mut best = (f32::INFINITY, 0);
        for k in 0..BINS - 1 {
            l_box = (l_box.0.min(boxes[k].0), l_box.1.max(boxes[k].1));
            l_count += counts[k];
            if l_count == 0 || l_count == prims.len() {
                continue;
            }
            let cost = half_area(l_box.0, l_box.1) * l_count as f32 + right_cost[k + 1];
            if cost < best.0 {
                best = (cost, k);
            }
        }
        if !best.0.is_finite() {
            return half;
        }
        // Those in bins up to the best first.
        let mut at = 0;
        for k in 0..prims.len() {
            if bin(prims[k]) <= best.1 {
                prims.swap(at, k);
                at += 1;
            }
        }
        at
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_numbers as numbers;
    use super::*;

    /// Triangles in a 100-unit cube in four key sets: two keys (sliding 30 units), three
    /// (turning about the cube's centre), four (a zigzag) and one (still).
    fn moving_triangles() -> (Vec<KeySet<'static>>, Vec<MovingTri>) {
        let mut rnd = numbers(0x5851_f42d_4c95_7f2d);
        let mut sets = Vec::new();
        let mut tris = Vec::new();
        for (set, keys) in [2usize, 3, 4, 1].into_iter().enumerate() {
            let count = 1_500;
            let mut base = Vec::new();
            for _ in 0..count {
                let c = Vec3A::new(rnd(), rnd(), rnd()) * 100.0;
                for _ in 0..3 {
                    base.push(c + (Vec3A::new(rnd(), rnd(), rnd()) - 0.5) * 4.0);
                }
            }
            let key = |j: usize| -> Vec<Vec3A> {
                let s = if keys == 1 { 0.0 } else { j as f32 / (keys - 1) as f32 };
                base.iter()
                    .map(|&p| match set {
                        0 => p + Vec3A::new(30.0 * s, 0.0, 0.0),
                        1 => {
                            let (sin, cos) = (1.2 * s).sin_cos();
                            let q = p - Vec3A::splat(50.0);
                            Vec3A::new(q.x * cos - q.z * sin, q.y, q.x * sin + q.z * cos) + Vec3A::splat(50.0)
                        }
                        2 => p + Vec3A::new(0.0, if j % 2 == 1 { 12.0 } else { 0.0 }, 3.0 * j as f32),
                        _ => p,
                    })
                    .collect()
            };
            sets.push(KeySet::Owned((0..keys).map(key).collect()));
            for k in 0..count as u32 {
                tris.push(MovingTri {
                    v: [3 * k, 3 * k + 1, 3 * k + 2],
                    set: set as u32,
                    index: k,
                    instance: set as u32,
                });
            }
        }
        (sets, tris)
    }

    /// The trees find, for 20,000 rays at spread shutter times from inside and outside the
    /// cube, the closest hit of all the triangles where they are at the ray's time (every
    /// triangle tested: the same distance bit for bit, the same triangle unless two lie at
    /// that very distance) and the same occlusion. The sets of 1, 2, 3 and 4 keys make four
    /// groups of 1, 1, 2 and 3 trees.
    #[test]
    fn moving_trees_find_what_every_triangle_finds() {
        let (sets, tris) = moving_triangles();
        let bvh = MovingBvh::build(sets, tris.clone()).expect("triangles");
        assert_eq!(bvh.groups.iter().map(Vec::len).collect::<Vec<_>>(), [1, 1, 2, 3]);
        let mut rnd = numbers(0x2545_f491_4f6c_dd1d);
        let (mut hits, mut blocked) = (0, 0);
        for k in 0..20_000 {
            let origin = Vec3A::new(rnd(), rnd(), rnd()) * 160.0 - 30.0;
            let dir = (Vec3A::new(rnd(), rnd(), rnd()) - 0.5).normalize();
            let time = if k % 10 == 0 { (k / 10 % 7) as f32 / 6.0 } else { rnd() };
            let ray =
                Ray { origin, dir, tmin: 1e-3, tmax: if k % 3 == 0 { 60.0 } else { f32::INFINITY }, mask: !0, time };
            let want = tris
                .iter()
                .filter_map(|t| {
                    let [p0, p1, p2] = bvh.at(t, time);
                    intersect_triangle(&ray, p0, p1, p2).map(|h| (h.0, t.instance, t.index))
                })
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let mut best = None;
            let found = bvh.closest(&ray, None, |_| true, &mut best);
            match (want, best) {
                (Some(w), Some(b)) => {
                    hits += 1;
                    assert_eq!(w.0.to_bits(), b.t.to_bits(), "{ray:?}");
                    assert_eq!(found.to_bits(), b.t.to_bits());
                }
                (None, None) => assert_eq!(found, ray.tmax),
                _ => panic!("{want:?} against {best:?} for {ray:?}"),
            }
            let any = bvh.any(&ray, |_| true);
            assert_eq!(any, want.is_some(), "{ray:?}");
            blocked += usize::from(any);
            // Only the still set let through: what its triangles alone find.
            let still = tris.iter().filter(|t| t.set == 3).any(|t| {
                let [p0, p1, p2] = bvh.at(t, time);
                intersect_triangle(&ray, p0, p1, p2).is_some()
            });
            assert_eq!(bvh.any(&ray, |t| t.set == 3), still);
        }
        assert!(hits > 1_500 && blocked == hits, "{hits} hits");
    }

    /// A triangle of 14 keys that holds still to key 7 and then jumps 10,000 units a key:
    /// rays down onto it (a thousandth inside its edges, and at its centroid) at every
    /// key's time and the floats either side (k/13 in f32 can round into the neighbouring
    /// interval) all hit it where it is, as testing it does. (Its boxes taken at the
    /// intervals' end times missed it at `prev_float(7/13)`: checked.)
    #[test]
    fn uneven_keys_are_bounded_at_every_time() {
        let keys: Vec<Vec<Vec3A>> = (0..14)
            .map(|j: usize| {
                let x = 1e4 * j.saturating_sub(7) as f32;
                vec![Vec3A::new(x, 0.0, 0.0), Vec3A::new(x + 1.0, 0.0, 0.0), Vec3A::new(x, 1.0, 0.0)]
            })
            .collect();
        let tri = MovingTri { v: [0, 1, 2], set: 0, index: 0, instance: 0 };
        let bvh = MovingBvh::build(vec![KeySet::Owned(keys)], vec![tri]).expect("a triangle");
        let mut tested = 0;
        for m in 0..=13 {
            let t = m as f32 / 13.0;
            for time in [f32::from_bits(t.to_bits().saturating_sub(1)), t, f32::from_bits(t.to_bits() + 1)] {
                if !(0.0..=1.0).contains(&time) {
                    continue;
                }
                let [p0, p1, p2] = bvh.at(&tri, time);
                // Points a thousandth inside the triangle's edges, and its centroid.
                for (u, v) in [(0.001, 0.3), (0.3, 0.001), (0.6, 0.399), (1.0 / 3.0, 1.0 / 3.0)] {
                    let target = p0 + (p1 - p0) * u + (p2 - p0) * v;
                    let origin = target + Vec3A::Z * 5.0;
                    let ray = Ray { origin, dir: -Vec3A::Z, tmin: 1e-3, tmax: f32::INFINITY, mask: !0, time };
                    // (Far along x the aim's rounding may put it just off an edge.)
                    let want = intersect_triangle(&ray, p0, p1, p2).map(|h| h.0);
                    if want.is_none() {
                        continue;
                    }
                    let mut best = None;
                    bvh.closest(&ray, None, |_| true, &mut best);
                    assert_eq!(best.map(|h| h.t), want, "time {time}, {u} {v}");
                    assert!(bvh.any(&ray, |_| true), "time {time}, {u} {v}");
                    tested += 1;
                }
            }
        }
        assert!(tested >= 140, "{tested} rays");
    }
}
