//! The 8-wide BVH the Rust backend traverses: nodes whose eight children's boxes are plain
//! `f32` planes (made by [`super::collapse`] from a binary BVH), laid out so that one ray
//! tests four children in one SSE operation; children are entered nearest first.
//!
//! Why not obvhs's own wide BVH and traversal: its node layout is made for GPUs (80 bytes a
//! node, each box corner quantized to a byte and decoded on every visit), it visits
//! children in an order fixed by the ray's octant rather than by distance, and its box test
//! raises every entry distance to an absolute 1e-4 and computes it as a difference of
//! node-sized terms, which dropped flat boxes at a ray's origin (docs/performance.md,
//! movingbvh49, widebvh50). Here a box's entry and exit distances are
//! `(plane − origin) · (1 / direction)`, whose sign is exact, and the ray's own
//! `tmin`/`tmax` bound them.
//!
//! A leaf is a run of primitives (1–3) in the BVH's primitive order: the caller keeps its
//! primitives in that order (the triangles are sorted into it) and tests primitive `i` of
//! the run itself, through the callbacks of [`WideBvh::closest`] and [`WideBvh::any`].

use std::mem::MaybeUninit;

use glam::{Vec3A, Vec4};
use obvhs::aabb::Aabb;

/// One node: the boxes of up to eight children, in the BVH's space, as planes by side
/// (`planes[0]` the low sides, `planes[1]` the high), axis and lane (children 0–3, 4–7);
/// then what each child is. An empty slot's box is empty (low +∞, high −∞), and the
/// slots in use are a mask of their own, which every box test is masked by (a ray with a
/// NaN in it passes every box test).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub(super) struct WideNode {
    planes: [[[Vec4; 2]; 3]; 2],
    /// A leaf's first primitive, or an inner child's node index.
    child: [u32; 8],
    /// A leaf's primitive count (1–3); 0 for an inner child, [`EMPTY`] for an empty slot.
    count: [u8; 8],
    /// The slots in use, a bit a slot.
    occupied: u8,
}

/// The `count` of an empty slot.
const EMPTY: u8 = u8::MAX;

impl WideNode {
    /// A node without children.
    pub(super) const EMPTY: WideNode = WideNode {
        planes: [[[Vec4::INFINITY; 2]; 3], [[Vec4::NEG_INFINITY; 2]; 3]],
        child: [0; 8],
        count: [EMPTY; 8],
        occupied: 0,
    };

    /// Puts a child in `slot` (0–7): its box, and a leaf's first primitive and count (1–254)
    /// or, with `count` 0, an inner node's index.
    pub(super) fn set_child(&mut self, slot: usize, bounds: &Aabb, child: u32, count: u8) {
        debug_assert!(count != EMPTY);
        for axis in 0..3 {
            self.planes[0][axis][slot / 4][slot % 4] = bounds.min[axis];
            self.planes[1][axis][slot / 4][slot % 4] = bounds.max[axis];
        }
        self.child[slot] = child;
        self.count[slot] = count;
        self.occupied |= 1 << slot;
    }

    /// The box of the child in `slot`.
    fn child_box(&self, slot: usize) -> Aabb {
        let side = |side: usize| Vec3A::from_array([0, 1, 2].map(|axis| self.planes[side][axis][slot / 4][slot % 4]));
        Aabb::new(side(0), side(1))
    }

    /// How many of its children are inner nodes (the rest are leaves or empty).
    #[cfg(test)]
    pub(super) fn inner_children(&self) -> u32 {
        self.count.iter().filter(|&&count| count == 0).count() as u32
    }
}

/// An 8-wide BVH over primitives that its user keeps in the BVH's leaf order.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct WideBvh {
    nodes: Vec<WideNode>,
    /// Stack entries a traversal can need: a node pushes at most the eight children it
    /// enters and opens one of them, so seven stay a level, and the deepest inner node's
    /// eight: `7 · depth + 8`.
    stack_need: usize,
}

/// How a BVH is filled ([`WideBvh::check`]).
#[cfg(test)]
#[derive(Debug, Default)]
pub(super) struct TreeSummary {
    pub nodes: usize,
    pub leaves: usize,
    pub primitives: usize,
    pub largest_leaf: usize,
    pub fewest_children: usize,
    pub mean_children: f32,
    /// The surface (half area) of every node's box, the root's included.
    pub node_surface: f64,
    /// The surface of every leaf's box times its primitives.
    pub leaf_surface_primitives: f64,
}

/// A child waiting on the traversal stack, and the distance at which the ray enters it.
#[derive(Clone, Copy)]
struct Pending {
    child: u32,
    count: u32,
    enter: f32,
}

/// The ray as the box test reads it: the origin and the inverse direction splatted per
/// axis, which side of each axis it meets first, and its extent.
struct BoxRay {
    origin: [Vec4; 3],
    inverse: [Vec4; 3],
    /// 0 where the direction's component is positive (the low plane is met first), else 1.
    near: [usize; 3],
    tmin: Vec4,
}

impl BoxRay {
    fn new(origin: Vec3A, dir: Vec3A, tmin: f32) -> BoxRay {
        // A component of ±0 has an infinite inverse: see `test` for what that gives.
        let inv = dir.recip();
        let negative = inv.is_negative_bitmask() as usize;
        BoxRay {
            origin: [Vec4::splat(origin.x), Vec4::splat(origin.y), Vec4::splat(origin.z)],
            inverse: [Vec4::splat(inv.x), Vec4::splat(inv.y), Vec4::splat(inv.z)],
            near: [negative & 1, (negative >> 1) & 1, negative >> 2],
            tmin: Vec4::splat(tmin),
        }
    }

    /// Which children of `node` the ray enters before `tmax` (a bit a slot) and where.
    #[inline(always)]
    fn test(&self, node: &WideNode, tmax: f32) -> (u32, [Vec4; 2]) {
        let mut enter = [self.tmin; 2];
        let mut leave = [Vec4::splat(tmax); 2];
        for axis in 0..3 {
            let near = &node.planes[self.near[axis]][axis];
            let far = &node.planes[1 - self.near[axis]][axis];
            for half in 0..2 {
                // Where the direction's component is ±0 the distances are ±∞, or NaN
                // (0·∞) for a plane through the origin, which leaves the bounds as they
                // were: a ray lying in a box's plane counts as inside that slab.
                enter[half] = raise(enter[half], (near[half] - self.origin[axis]) * self.inverse[axis]);
                leave[half] = lower(leave[half], (far[half] - self.origin[axis]) * self.inverse[axis]);
            }
        }
        let widen = Vec4::splat(WIDEN);
        let mask = enter[0].cmple(leave[0] * widen).bitmask() | (enter[1].cmple(leave[1] * widen).bitmask() << 4);
        (mask & u32::from(node.occupied), enter)
    }
}

/// `bound` raised to `distance` in each lane where that is larger; `bound` where `distance`
/// is NaN.
#[inline(always)]
fn raise(bound: Vec4, distance: Vec4) -> Vec4 {
    // On x86 glam's `max` is SSE's (or, without SSE, a compare), which returns its second
    // operand when either is NaN: one instruction. Elsewhere (NEON's max returns the NaN)
    // the same by a compare and a select.
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    return distance.max(bound);
    #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
    return Vec4::select(distance.cmpgt(bound), distance, bound);
}

/// `bound` lowered to `distance` in each lane where that is smaller; `bound` where
/// `distance` is NaN (as [`raise`]).
#[inline(always)]
fn lower(bound: Vec4, distance: Vec4) -> Vec4 {
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    return distance.min(bound);
    #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
    return Vec4::select(distance.cmplt(bound), distance, bound);
}

/// How much further than a box's exit distance, and than the nearest hit so far, a box
/// still counts as reached (a relative 2⁻²⁰, eight units in the last place). A triangle's
/// distance is computed another way than its box's and may come out a few units in the
/// last place nearer: without the margin a box entered at 0.0038140984 was passed over for
/// a hit at 0.0038140982 in another, though its own triangle lay at 0.003814098.
const WIDEN: f32 = 1.0 + 1.0 / (1 << 20) as f32;

/// Room for [`LOCAL_STACK`] entries on the thread's stack; deeper trees use the heap.
const LOCAL_STACK: usize = 256;

/// A traversal stack of fixed capacity, which the traversal never exceeds (see
/// `WideBvh::stack_need`; the tree's depth is known). Its
/// entries are left unwritten until pushed: clearing an array of 256 on every query would
/// cost a tenth of a small scene's traversal.
struct Stack<const N: usize> {
    items: [MaybeUninit<Pending>; N],
    len: usize,
}

impl<const N: usize> Stack<N> {
    fn new() -> Stack<N> {
        Stack { items: [MaybeUninit::uninit(); N], len: 0 }
    }
}

/// What the traversal needs of a stack.
trait PendingStack {
    fn push(&mut self, entry: Pending);
    fn pop(&mut self) -> Option<Pending>;
    /// The last `n` entries pushed.
    fn top(&mut self, n: usize) -> &mut [Pending];
}

impl<const N: usize> PendingStack for Stack<N> {
    #[inline(always)]
    fn push(&mut self, entry: Pending) {
        // Panics rather than writing past the end (never: see `WideBvh::stack_need`).
        self.items[self.len] = MaybeUninit::new(entry);
        self.len += 1;
    }

    #[inline(always)]
    #[allow(unsafe_code)]
    fn pop(&mut self) -> Option<Pending> {
        self.len = self.len.checked_sub(1)?;
        // SAFETY: entries below `len` were written by `push`.
        Some(unsafe { self.items[self.len].assume_init() })
    }

    #[inline(always)]
    #[allow(unsafe_code)]
    fn top(&mut self, n: usize) -> &mut [Pending] {
        let from = self.len - n;
        let top = &mut self.items[from..self.len];
        // SAFETY: entries below `len` were written by `push`; `MaybeUninit<T>` has `T`'s layout.
        unsafe { &mut *(top as *mut [MaybeUninit<Pending>] as *mut [Pending]) }
    }
}

impl PendingStack for Vec<Pending> {
    fn push(&mut self, entry: Pending) {
        Vec::push(self, entry);
    }

    fn pop(&mut self) -> Option<Pending> {
        Vec::pop(self)
    }

    fn top(&mut self, n: usize) -> &mut [Pending] {
        let from = self.len() - n;
        &mut self[from..]
    }
}

impl WideBvh {
    /// A BVH of `nodes` (the root first).
    pub(super) fn with_nodes(nodes: Vec<WideNode>) -> WideBvh {
        let stack_need = if nodes.is_empty() { 0 } else { 7 * depth_below(&nodes, 0) + 8 };
        WideBvh { nodes, stack_need }
    }

    /// Bytes of its nodes.
    pub(super) fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(&self.nodes[..])
    }

    /// The box of everything in it: the union of its root's children's boxes (empty for an
    /// empty BVH).
    pub(super) fn root_box(&self) -> Aabb {
        let Some(root) = self.nodes.first() else { return Aabb::empty() };
        (0..8)
            .filter(|&slot| root.occupied & (1 << slot) != 0)
            .map(|slot| root.child_box(slot))
            .fold(Aabb::empty(), |a, b| a.union(&b))
    }

    /// One BVH over `parts` (1 to 8 BVHs, none empty, each with the number of primitives
    /// given), whose leaves name the parts' primitives one part after another: a root whose
    /// children are the parts' roots, then each part's nodes in their order, their inner
    /// children and leaves moved by where the part's nodes and primitives now start.
    pub(super) fn join(parts: Vec<(WideBvh, usize)>) -> WideBvh {
        assert!(!parts.is_empty() && parts.len() <= 8 && parts.iter().all(|(p, _)| !p.nodes.is_empty()));
        let mut nodes = Vec::with_capacity(1 + parts.iter().map(|(p, _)| p.nodes.len()).sum::<usize>());
        nodes.push(WideNode::EMPTY);
        let mut root = WideNode::EMPTY;
        let mut primitive_base = 0u32;
        for (slot, (part, primitives)) in parts.into_iter().enumerate() {
            let node_base = nodes.len() as u32;
            root.set_child(slot, &part.root_box(), node_base, 0);
            nodes.extend(part.nodes.iter().map(|node| {
                let mut moved = *node;
                for (child, &count) in moved.child.iter_mut().zip(&node.count) {
                    match count {
                        EMPTY => {}
                        0 => *child += node_base,
                        _ => *child += primitive_base,
                    }
                }
                moved
            }));
            primitive_base += primitives as u32;
        }
        nodes[0] = root;
        WideBvh::with_nodes(nodes)
    }

    /// For tests: checks that every child's box is, bit for bit, the union of the boxes of
    /// the primitives beneath it (`primitive_box` of a leaf's primitive), and tells how the
    /// tree is filled.
    #[cfg(test)]
    pub(super) fn check(&self, primitive_box: &dyn Fn(usize) -> Aabb) -> TreeSummary {
        let mut summary = TreeSummary { nodes: self.nodes.len(), fewest_children: 8, ..TreeSummary::default() };
        let mut children = 0;
        // Each node's exact box, children before parents: nodes are placed after their parent.
        let mut exact = vec![Aabb::empty(); self.nodes.len()];
        for (n, node) in self.nodes.iter().enumerate().rev() {
            let slots: Vec<usize> = (0..8).filter(|&slot| node.occupied & (1 << slot) != 0).collect();
            children += slots.len();
            summary.fewest_children = summary.fewest_children.min(slots.len());
            for slot in slots {
                let (child, count) = (node.child[slot] as usize, usize::from(node.count[slot]));
                let inside = if count == 0 {
                    assert!(child > n, "node {n}'s child {child} is placed after it");
                    summary.node_surface += f64::from(exact[child].half_area());
                    exact[child]
                } else {
                    summary.leaves += 1;
                    summary.primitives += count;
                    summary.largest_leaf = summary.largest_leaf.max(count);
                    let leaf = (child..child + count).map(primitive_box).fold(Aabb::empty(), |a, b| a.union(&b));
                    summary.leaf_surface_primitives += f64::from(leaf.half_area()) * count as f64;
                    leaf
                };
                let stored = node.child_box(slot);
                assert_eq!(
                    (stored.min.to_array(), stored.max.to_array()),
                    (inside.min.to_array(), inside.max.to_array()),
                    "node {n} slot {slot}"
                );
                exact[n] = exact[n].union(&inside);
            }
        }
        if let Some(root) = exact.first() {
            summary.node_surface += f64::from(root.half_area());
        }
        summary.mean_children = children as f32 / self.nodes.len().max(1) as f32;
        summary
    }

    /// The root node (for tests).
    #[cfg(test)]
    pub(super) fn root(&self) -> &WideNode {
        &self.nodes[0]
    }

    /// Visits the leaves `origin + t·dir` enters for t in [`tmin`, `reach`], nearest box
    /// first, calling `test(primitive, reach)` for each of their primitives; `test` returns
    /// the new reach (the distance of a hit it accepted, else `reach`), and boxes beyond it
    /// are skipped. Returns the final reach.
    #[inline]
    pub(super) fn closest(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        tmin: f32,
        reach: f32,
        test: impl FnMut(usize, f32) -> f32,
    ) -> f32 {
        // A ray with a NaN or an infinity in it meets nothing (its box tests would pass).
        if self.nodes.is_empty() || !(origin.is_finite() && dir.is_finite()) {
            return reach;
        }
        let ray = BoxRay::new(origin, dir, tmin);
        if self.stack_need <= LOCAL_STACK {
            self.closest_with(&ray, reach, test, &mut Stack::<LOCAL_STACK>::new())
        } else {
            self.closest_with(&ray, reach, test, &mut Vec::with_capacity(self.stack_need))
        }
    }

    /// Whether `test(primitive)` holds for a primitive of a leaf that `origin + t·dir`
    /// enters for t in [`tmin`, `tmax`] (it stops at the first that does).
    #[inline]
    pub(super) fn any(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32, test: impl FnMut(usize) -> bool) -> bool {
        if self.nodes.is_empty() || !(origin.is_finite() && dir.is_finite()) {
            return false;
        }
        let ray = BoxRay::new(origin, dir, tmin);
        if self.stack_need <= LOCAL_STACK {
            self.any_with(&ray, tmax, test, &mut Stack::<LOCAL_STACK>::new())
        } else {
            self.any_with(&ray, tmax, test, &mut Vec::with_capacity(self.stack_need))
        }
    }

    #[inline(always)]
    fn closest_with(
        &self,
        ray: &BoxRay,
        mut reach: f32,
        mut test: impl FnMut(usize, f32) -> f32,
        stack: &mut impl PendingStack,
    ) -> f32 {
        let mut node = 0;
        loop {
            let (mask, enter) = ray.test(&self.nodes[node], reach);
            let children = &self.nodes[node];
            // One child entered (`count_ones` is no instruction on baseline x86-64).
            if mask != 0 && mask & (mask - 1) == 0 {
                let slot = mask.trailing_zeros() as usize;
                if children.count[slot] == 0 {
                    node = children.child[slot] as usize;
                    continue;
                }
                let first = children.child[slot] as usize;
                for primitive in first..first + usize::from(children.count[slot]) {
                    reach = test(primitive, reach);
                }
            } else if mask != 0 {
                let enter: [f32; 8] = lanes(enter);
                let mut left = mask;
                let mut pushed = 0;
                while left != 0 {
                    let slot = left.trailing_zeros() as usize;
                    left &= left - 1;
                    stack.push(Pending {
                        child: children.child[slot],
                        count: children.count[slot].into(),
                        enter: enter[slot],
                    });
                    pushed += 1;
                }
                // Nearest on top: insertion sort of the few just pushed, farthest first.
                let top = stack.top(pushed);
                for i in 1..top.len() {
                    let mut j = i;
                    while j > 0 && top[j - 1].enter < top[j].enter {
                        top.swap(j - 1, j);
                        j -= 1;
                    }
                }
            }
            // The next inner node to open, testing the leaves popped on the way.
            loop {
                let Some(next) = stack.pop() else { return reach };
                if next.enter > reach * WIDEN {
                    continue;
                }
                if next.count == 0 {
                    node = next.child as usize;
                    break;
                }
                let first = next.child as usize;
                for primitive in first..first + next.count as usize {
                    reach = test(primitive, reach);
                }
            }
        }
    }

    #[inline(always)]
    fn any_with(
        &self,
        ray: &BoxRay,
        tmax: f32,
        mut test: impl FnMut(usize) -> bool,
        stack: &mut impl PendingStack,
    ) -> bool {
        let mut node = 0;
        loop {
            let children = &self.nodes[node];
            let (mut left, _) = ray.test(children, tmax);
            while left != 0 {
                let slot = left.trailing_zeros() as usize;
                left &= left - 1;
                let count = u32::from(children.count[slot]);
                if count == 0 {
                    stack.push(Pending { child: children.child[slot], count, enter: 0.0 });
                    continue;
                }
                let first = children.child[slot] as usize;
                if (first..first + count as usize).any(&mut test) {
                    return true;
                }
            }
            let Some(next) = stack.pop() else { return false };
            node = next.child as usize;
        }
    }
}

/// The eight lanes of two vectors.
#[inline(always)]
fn lanes(enter: [Vec4; 2]) -> [f32; 8] {
    let [a, b] = enter.map(|v| v.to_array());
    [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]
}

/// Levels of inner nodes below `node` (0 for a node whose children are all leaves).
fn depth_below(nodes: &[WideNode], node: usize) -> usize {
    // Iterative: a degenerate tree may be deep.
    let mut deepest = 0;
    let mut pending = vec![(node, 0)];
    while let Some((n, depth)) = pending.pop() {
        deepest = deepest.max(depth);
        let children = &nodes[n];
        for slot in 0..8 {
            if children.count[slot] == 0 {
                pending.push((children.child[slot] as usize, depth + 1));
            }
        }
    }
    deepest
}

#[cfg(test)]
mod tests {
    use super::super::test_numbers as numbers;
    use super::super::{triangle_bvh, MeshBvh, Tri};
    use super::*;
    use crate::ray::Ray;
    use obvhs::BvhBuildParams;

    /// 3,000 small triangles in a 100-unit cube, and 60 stacked planes (two triangles
    /// each, 0.5 apart along z, every one in an axis plane: flat boxes).
    fn triangles() -> Vec<Tri> {
        let mut tris = super::super::test_scattered_triangles(0x0bad_5eed_1234_5678, 3_000, 2.0, 0);
        for plane in 0..60u32 {
            let z = 20.0 + 0.5 * plane as f32;
            let v = |x: f32, y: f32| Vec3A::new(x, y, z);
            let index = 2 * plane;
            tris.push(Tri::new(v(10.0, 10.0), v(90.0, 10.0), v(90.0, 90.0), index, 1));
            tris.push(Tri::new(v(10.0, 10.0), v(90.0, 90.0), v(10.0, 90.0), index + 1, 1));
        }
        tris
    }

    /// The nearest hit of `ray` over every triangle (the last of equals, as the BVH's
    /// callbacks accept a hit at the reach), and whether any hit is in range.
    fn every_triangle(tris: &[Tri], ray: &Ray) -> (Option<(f32, u32, u32)>, bool) {
        let mut best = None;
        let mut reach = ray.tmax;
        for t in tris {
            if let Some((d, _, _)) = t.hit(&Ray { tmax: reach, ..*ray }) {
                best = Some((d, t.instance, t.index));
                reach = d;
            }
        }
        (best, tris.iter().any(|t| t.hit(ray).is_some()))
    }

    /// The BVH's nearest hit and occlusion for `ray`, on the stack of the size given.
    fn traced(bvh: &MeshBvh, ray: &Ray, on_heap: bool) -> (Option<(f32, u32, u32)>, bool) {
        let mut best = None;
        let test = |id: usize, reach: f32| match bvh.tris[id].hit(&Ray { tmax: reach, ..*ray }) {
            Some((d, _, _)) => {
                best = Some((d, bvh.tris[id].instance, bvh.tris[id].index));
                d
            }
            None => reach,
        };
        let any = |id: usize| bvh.tris[id].hit(ray).is_some();
        let blocked = if on_heap {
            let boxes = BoxRay::new(ray.origin, ray.dir, ray.tmin);
            bvh.bvh.closest_with(&boxes, ray.tmax, test, &mut Vec::new());
            bvh.bvh.any_with(&boxes, ray.tmax, any, &mut Vec::new())
        } else {
            bvh.bvh.closest(ray.origin, ray.dir, ray.tmin, ray.tmax, test);
            bvh.bvh.any(ray.origin, ray.dir, ray.tmin, ray.tmax, any)
        };
        (best, blocked)
    }

    /// The BVH finds what testing every triangle finds — the same nearest distance bit for
    /// bit, the same triangle unless two lie at that distance, the same occlusion, on the
    /// fixed stack and on the heap — for 12,000 rays: from anywhere towards the cube;
    /// restarted 1e-6–1e-3 before one of the stacked planes they were aimed at (a flat box
    /// right at the origin: obvhs's traversal dropped such boxes); along the axes, with
    /// negative zeros in the direction; and with a short reach.
    #[test]
    fn the_wide_bvh_finds_what_every_triangle_finds() {
        let tris = triangles();
        let bvh = triangle_bvh(tris.clone(), BvhBuildParams::medium_build());
        assert!(bvh.bvh.stack_need <= LOCAL_STACK && bvh.bvh.nodes.len() > 100, "{} nodes", bvh.bvh.nodes.len());
        let mut rnd = numbers(0x2545_f491_4f6c_dd1d);
        let (mut hits, mut blocked, mut planes, mut other_triangle) = (0, 0, 0, 0);
        for k in 0..12_000 {
            let target = Vec3A::new(rnd(), rnd(), rnd()) * 100.0;
            let origin = Vec3A::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 300.0 + 50.0;
            let mut ray = Ray::new(origin, target - origin);
            match k % 4 {
                1 => {
                    // Restarted just before the plane it meets first.
                    let z = 20.0 + 0.5 * (rnd() * 60.0).floor();
                    let point = Vec3A::new(10.0 + 80.0 * rnd(), 10.0 + 80.0 * rnd(), z);
                    let dir = Vec3A::new(rnd() - 0.5, rnd() - 0.5, 0.2 + rnd()).normalize();
                    ray = Ray::new(point - dir * (1e-6 + 1e-3 * rnd()), dir);
                    planes += 1;
                }
                2 => {
                    // Along an axis, either way; the other components ±0.
                    let axis = (rnd() * 3.0) as usize % 3;
                    let mut dir = Vec3A::new(-0.0, 0.0, -0.0);
                    dir[axis] = if rnd() < 0.5 { -1.0 } else { 1.0 };
                    ray = Ray::new(Vec3A::new(rnd(), rnd(), rnd()) * 100.0, dir);
                }
                3 => ray.tmax = 5.0 * rnd(),
                _ => {}
            }
            let want = every_triangle(&tris, &ray);
            for on_heap in [false, true] {
                let got = traced(&bvh, &ray, on_heap);
                assert_eq!(want.0.map(|h| h.0.to_bits()), got.0.map(|h| h.0.to_bits()), "{ray:?}");
                assert_eq!(want.1, got.1, "{ray:?}");
                other_triangle += usize::from(want.0.map(|h| (h.1, h.2)) != got.0.map(|h| (h.1, h.2)));
            }
            hits += usize::from(want.0.is_some());
            blocked += usize::from(want.1);
        }
        assert!(hits > 5_000 && blocked > 5_000 && planes == 3_000, "{hits} hits, {blocked} blocked");
        assert!(other_triangle <= 4, "{other_triangle} rays hit another triangle at the same distance");
    }

    /// Every child's box contains every vertex of every triangle beneath it, and every
    /// triangle is in one leaf — for the triangles of [`triangles`], and for two far apart,
    /// where the quantized boxes of obvhs's wide BVH (which this BVH was unpacked from
    /// until widebvh51) put a low side at 0.3125 for a vertex at 0.3.
    #[test]
    fn child_boxes_contain_their_triangles() {
        let far = vec![
            Tri::new(
                Vec3A::new(-999_423.7, 0.0, 0.0),
                Vec3A::new(-999_000.0, 1.0, 0.0),
                Vec3A::new(-999_000.0, 0.0, 1.0),
                0,
                0,
            ),
            Tri::new(Vec3A::new(0.3, 0.0, 0.0), Vec3A::new(0.5, 1.0, 0.0), Vec3A::new(0.5, 0.0, 1.0), 1, 0),
        ];
        boxes_contain_their_triangles(triangles());
        boxes_contain_their_triangles(far);
    }

    fn boxes_contain_their_triangles(tris: Vec<Tri>) {
        let bvh = triangle_bvh(tris, BvhBuildParams::medium_build());
        let nodes = &bvh.bvh.nodes;
        // The triangles beneath a child: its leaf's, or those of every leaf below its node.
        let beneath = |node: &WideNode, slot: usize| {
            let mut found = Vec::new();
            let mut pending = vec![(node.child[slot], node.count[slot])];
            while let Some((child, count)) = pending.pop() {
                if count == 0 {
                    let inner = &nodes[child as usize];
                    pending
                        .extend((0..8).filter(|&s| inner.count[s] != EMPTY).map(|s| (inner.child[s], inner.count[s])));
                } else {
                    found.extend(child as usize..child as usize + usize::from(count));
                }
            }
            found
        };
        let mut in_leaves = 0;
        for node in nodes {
            for slot in (0..8).filter(|&slot| node.count[slot] != EMPTY) {
                let lo = Vec3A::from_array([0, 1, 2].map(|a| node.planes[0][a][slot / 4][slot % 4]));
                let hi = Vec3A::from_array([0, 1, 2].map(|a| node.planes[1][a][slot / 4][slot % 4]));
                for t in beneath(node, slot) {
                    for p in bvh.tris[t].corners() {
                        assert!(p.cmpge(lo).all() && p.cmple(hi).all(), "{p} outside {lo}…{hi}");
                    }
                }
                in_leaves += usize::from(node.count[slot]);
            }
        }
        assert_eq!(in_leaves, bvh.tris.len(), "every triangle in one leaf");
    }

    /// A ray lying in a flat box's plane (its origin on the plane, its direction's
    /// component across it +0 or −0) enters the box where it crosses its other sides,
    /// and one beside the box misses it (fails with the operands of the distances' `max`
    /// and `min` swapped: NaN then wins).
    #[test]
    fn a_ray_in_a_flat_box_plane_enters_it() {
        let mut node = WideNode {
            planes: [[[Vec4::INFINITY; 2]; 3], [[Vec4::NEG_INFINITY; 2]; 3]],
            child: [0; 8],
            count: [EMPTY; 8],
            occupied: 1,
        };
        for (axis, (lo, hi)) in [(0.0, 10.0), (0.0, 10.0), (5.0, 5.0)].into_iter().enumerate() {
            node.planes[0][axis][0].x = lo;
            node.planes[1][axis][0].x = hi;
        }
        node.count[0] = 1;
        for z in [0.0, -0.0] {
            for (origin, enters) in [(Vec3A::new(-1.0, 5.0, 5.0), true), (Vec3A::new(-1.0, 11.0, 5.0), false)] {
                let ray = BoxRay::new(origin, Vec3A::new(1.0, 0.0, z), 0.0);
                let (mask, enter) = ray.test(&node, f32::INFINITY);
                assert_eq!(mask == 1, enters, "{origin} {z}");
                if enters {
                    assert_eq!(enter[0].x, 1.0);
                }
            }
        }
    }

    /// A deep tree — 300 triangles nested like Russian dolls, each 0.8 of the last, which
    /// PLOC can only pair one level at a time — is opened level by level by rays from where
    /// the smallest is nearest, finding what testing every triangle finds; the tree is
    /// deeper than the fixed stack allows, so its traversal takes the heap stack.
    #[test]
    fn a_deep_tree_finds_what_every_triangle_finds() {
        let tris: Vec<Tri> = (0..300u32)
            .map(|k| {
                let scale = 0.8f32.powi(k as i32);
                let v = |x: f32, y: f32, z: f32| Vec3A::new(x, y, z + 0.1) * scale;
                Tri::new(v(-1.0, -1.0, 0.5), v(1.0, -1.0, -0.5), v(0.0, 1.0, 0.0), k, 0)
            })
            .collect();
        let bvh = triangle_bvh(tris.clone(), BvhBuildParams::medium_build());
        let depth = (bvh.bvh.stack_need - 8) / 7;
        assert!(bvh.bvh.stack_need > LOCAL_STACK, "depth {depth}");
        let mut rnd = numbers(7);
        let mut hits = 0;
        for _ in 0..2_000 {
            // From below, where the smallest triangle is the nearest: every level is opened.
            let origin = Vec3A::new(rnd() - 0.5, rnd() - 0.5, -2.0) * Vec3A::new(1e-3, 1e-3, 1.0);
            let target = Vec3A::new(rnd() - 0.5, rnd() - 0.5, 0.0) * 1e-4;
            let ray = Ray::new(origin, target - origin);
            let want = every_triangle(&tris, &ray);
            let got = traced(&bvh, &ray, false);
            assert_eq!(want.0.map(|h| h.0.to_bits()), got.0.map(|h| h.0.to_bits()), "{ray:?}");
            assert_eq!(want.1, got.1);
            hits += usize::from(got.0.is_some());
        }
        assert!(hits > 1_000, "{hits} hits");
    }

    /// A chain of `depth` nodes under the root, each entering seven leaves and, nearest
    /// (last in slot order), the next node, the last node eight leaves: the stack holds
    /// `7 · depth + 8` entries at its fullest, 260 at depth 36 — past the fixed 256 — and
    /// every leaf is visited once by both queries, at depths on both sides of that.
    #[test]
    fn the_fullest_stack_fits() {
        for depth in 34..=38u32 {
            let nodes: Vec<WideNode> = (0..=depth)
                .map(|level| {
                    let mut node = WideNode {
                        planes: [[[Vec4::splat(-1.0); 2]; 3], [[Vec4::splat(1.0); 2]; 3]],
                        child: std::array::from_fn(|slot| 8 * level + slot as u32),
                        count: [1; 8],
                        occupied: 0xff,
                    };
                    if level < depth {
                        (node.child[7], node.count[7]) = (level + 1, 0);
                    }
                    node
                })
                .collect();
            let bvh = WideBvh::with_nodes(nodes);
            assert_eq!(bvh.stack_need, 7 * depth as usize + 8);
            let (origin, dir) = (Vec3A::new(0.0, 0.0, -5.0), Vec3A::Z);
            let mut seen = Vec::new();
            bvh.closest(origin, dir, 0.0, f32::INFINITY, |leaf, reach| {
                seen.push(leaf);
                reach
            });
            let mut tested = 0;
            assert!(!bvh.any(origin, dir, 0.0, f32::INFINITY, |_| {
                tested += 1;
                false
            }));
            seen.sort_unstable();
            let leaves: Vec<usize> = (0..=depth as usize)
                .flat_map(|level| (8 * level..8 * level + 8).filter(move |&l| l % 8 != 7 || level == depth as usize))
                .collect();
            assert_eq!((seen, tested), (leaves.clone(), leaves.len()), "depth {depth}");
        }
    }

    /// Rays with a NaN or an infinity in their origin or direction, or without a
    /// direction, meet nothing and test no primitive (a NaN passes every box test; the
    /// empty slots of a node of few children were then taken for leaves of 255).
    #[test]
    fn broken_rays_meet_nothing() {
        let tris: Vec<Tri> = triangles().into_iter().take(5).collect();
        let bvh = triangle_bvh(tris, BvhBuildParams::medium_build());
        let nan = Vec3A::splat(f32::NAN);
        for (origin, dir) in [
            (nan, Vec3A::Z),
            (Vec3A::ZERO, nan),
            (Vec3A::ZERO, Vec3A::new(f32::INFINITY, 0.0, 0.0)),
            (Vec3A::new(f32::NEG_INFINITY, 0.0, 0.0), Vec3A::X),
            (Vec3A::ZERO, Vec3A::ZERO.normalize()),
        ] {
            let mut tested = 0;
            bvh.bvh.closest(origin, dir, 0.0, f32::INFINITY, |_, reach| {
                tested += 1;
                reach
            });
            assert!(!bvh.bvh.any(origin, dir, 0.0, f32::INFINITY, |_| {
                tested += 1;
                true
            }));
            assert_eq!(tested, 0, "{origin} {dir}");
        }
    }
}
