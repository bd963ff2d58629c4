//! The Rust backend's BVH build: obvhs builds a binary BVH (PLOC, then reinsertion), which
//! is collapsed here into the 8-wide nodes [`WideBvh`] traverses.
//!
//! The collapse is the cost-optimal one of Ylitie, Karras and Laine (*Efficient Incoherent
//! Ray Traversal on GPUs Through Compressed Wide BVHs*, 2017), by the surface area
//! heuristic: for each binary node and each number of slots `i` (1–7) it may take in its
//! wide parent, the least cost of its subtree — one slot as a leaf (at most
//! [`LEAF_PRIMITIVES`] primitives) or as a wide node of its own, or its two children
//! sharing the slots — and then, from the root down, each wide node's children are the
//! binary nodes that least cost names. A wide node costs [`NODE_COST`] a unit of surface, a
//! primitive in a leaf [`PRIMITIVE_COST`] (the paper's figures). The children's boxes are
//! the binary nodes' `f32` boxes as they are: exact unions of the primitives' boxes, with
//! no quantization and no padding.
//!
//! Why not obvhs's own conversion (`bvh2_to_cwbvh`), which makes the same choice: it
//! quantizes each box to 8 bits a side for GPU memory (the boxes were then unpacked here
//! and padded outward, looser than the primitives' own), and it orders each node's children
//! by ray octant for its own traversal, where [`WideBvh`] enters the nearest first.

use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::bvh2::Bvh2;
use obvhs::ploc::PlocBuilder;
use obvhs::{Boundable, BvhBuildParams};

use super::wide::{WideBvh, WideNode};

/// The most primitives a leaf made of an inner binary node holds (a binary leaf holds what
/// it holds: one primitive, as PLOC builds them).
pub(super) const LEAF_PRIMITIVES: u32 = 3;

/// The cost of entering a wide node, per unit of its surface (half area).
const NODE_COST: f32 = 1.0;

/// The cost of testing a primitive in a leaf, per unit of the leaf's surface.
const PRIMITIVE_COST: f32 = 0.3;

/// Children of one wide node.
const WIDTH: usize = 8;

/// The least costs of a binary node's subtree given 1 to 7 slots of its wide parent.
type Costs = [f32; WIDTH - 1];

/// The 8-wide BVH of `primitives` and the order its leaves hold them in: leaf primitive
/// `i` (as traversal names it) is `primitives[order[i]]`. `params` gives PLOC's search and
/// the reinsertion's batch (obvhs's [`BvhBuildParams`]; its leaf size and pre-split are
/// not used).
pub(super) fn build_wide<T: Boundable>(primitives: &[T], params: BvhBuildParams) -> (WideBvh, Vec<u32>) {
    if primitives.is_empty() {
        return (WideBvh::default(), Vec::new());
    }
    let mut bvh2 = PlocBuilder::with_capacity(primitives.len()).build(
        params.ploc_search_distance,
        primitives,
        (0..primitives.len() as u32).collect(),
        params.sort_precision,
        params.search_depth_threshold,
    );
    ReinsertionOptimizer::default().run(&mut bvh2, params.reinsertion_batch_ratio, None);
    collapse(&bvh2)
}

/// The wide BVH of the binary `bvh2` (see the module) and its leaves' order of the
/// primitives (`bvh2`'s primitive indices, leaf by leaf).
pub(super) fn collapse(bvh2: &Bvh2) -> (WideBvh, Vec<u32>) {
    if bvh2.nodes.is_empty() {
        return (WideBvh::default(), Vec::new());
    }
    let plan = Plan::new(bvh2);
    let mut nodes = vec![WideNode::EMPTY];
    let mut order = Vec::with_capacity(bvh2.primitive_indices.len());
    let mut scratch = Vec::new();
    // The root is a wide node unless the whole tree is best one leaf.
    let root_children = if plan.is_leaf(0) { vec![0] } else { plan.children(0) };
    let mut pending = vec![(root_children, 0usize)];
    while let Some((children, at)) = pending.pop() {
        let mut node = WideNode::EMPTY;
        for (slot, &child) in children.iter().enumerate() {
            let bounds = bvh2.nodes[child].aabb();
            if plan.is_leaf(child) {
                let first = order.len();
                gather(bvh2, child, &mut order, &mut scratch);
                node.set_child(slot, bounds, first as u32, (order.len() - first) as u8);
            } else {
                // Its wide node is placed now, filled when popped.
                node.set_child(slot, bounds, nodes.len() as u32, 0);
                pending.push((plan.children(child), nodes.len()));
                nodes.push(WideNode::EMPTY);
            }
        }
        nodes[at] = node;
    }
    (WideBvh::with_nodes(nodes), order)
}

/// The least costs of every binary node's subtree (see the module), from which the wide
/// nodes are read off.
struct Plan<'b> {
    bvh2: &'b Bvh2,
    /// Per binary node: its least cost in 1–7 slots.
    costs: Vec<Costs>,
    /// Per binary node: the primitives beneath it.
    below: Vec<u32>,
}

impl<'b> Plan<'b> {
    /// The costs of every node of `bvh2`, children before parents.
    fn new(bvh2: &'b Bvh2) -> Plan<'b> {
        let binary = &bvh2.nodes;
        let mut plan = Plan { bvh2, costs: vec![[0.0; WIDTH - 1]; binary.len()], below: vec![0; binary.len()] };
        for n in children_first(bvh2) {
            let node = &binary[n];
            if node.is_leaf() {
                plan.below[n] = node.prim_count;
                plan.costs[n] = [plan.leaf_cost(n); WIDTH - 1];
                continue;
            }
            let [left, right] = halves(bvh2, n);
            plan.below[n] = plan.below[left] + plan.below[right];
            let mut costs = [plan.leaf_cost(n).min(plan.internal_cost(n)); WIDTH - 1];
            for slots in 2..WIDTH {
                costs[slots - 1] = costs[slots - 2].min(plan.shared(n, slots).0);
            }
            plan.costs[n] = costs;
        }
        plan
    }

    /// Node `n`'s least cost in `slots` slots (1–7).
    fn cost(&self, n: usize, slots: usize) -> f32 {
        self.costs[n][slots - 1]
    }

    /// The cost of `n` as one leaf: infinite for an inner node above
    /// [`LEAF_PRIMITIVES`] primitives.
    fn leaf_cost(&self, n: usize) -> f32 {
        let node = &self.bvh2.nodes[n];
        if !node.is_leaf() && self.below[n] > LEAF_PRIMITIVES {
            return f32::INFINITY;
        }
        node.aabb().half_area() * self.below[n] as f32 * PRIMITIVE_COST
    }

    /// The cost of inner node `n` as a wide node of its own (its children sharing eight
    /// slots).
    fn internal_cost(&self, n: usize) -> f32 {
        self.bvh2.nodes[n].aabb().half_area() * NODE_COST + self.shared(n, WIDTH).0
    }

    /// The least cost of inner node `n`'s two children sharing `slots` slots (2–8), and
    /// the slots its left child takes for it (the fewest of equal costs).
    fn shared(&self, n: usize, slots: usize) -> (f32, usize) {
        let [left, right] = halves(self.bvh2, n);
        let mut best = (f32::INFINITY, 1);
        for k in 1..slots {
            let cost = self.cost(left, k) + self.cost(right, slots - k);
            if cost < best.0 {
                best = (cost, k);
            }
        }
        best
    }

    /// Whether binary node `n` is best one leaf (a binary leaf always is).
    fn is_leaf(&self, n: usize) -> bool {
        self.bvh2.nodes[n].is_leaf() || self.leaf_cost(n) <= self.internal_cost(n)
    }

    /// The binary nodes the wide node of inner binary node `n` has as children: its two
    /// children's shares of eight slots, each opened as its least cost says.
    fn children(&self, n: usize) -> Vec<usize> {
        let mut children = Vec::with_capacity(WIDTH);
        self.share(n, WIDTH, &mut children);
        children
    }

    /// Appends to `out` the binary nodes that inner node `n`'s two children take `slots`
    /// slots as.
    fn share(&self, n: usize, slots: usize, out: &mut Vec<usize>) {
        let [left, right] = halves(self.bvh2, n);
        let (_, k) = self.shared(n, slots);
        self.take(left, k, out);
        self.take(right, slots - k, out);
    }

    /// Appends to `out` the binary nodes that node `n` takes (at most) `slots` slots as: `n`
    /// itself in one slot, or its children's shares where that costs less.
    fn take(&self, n: usize, slots: usize, out: &mut Vec<usize>) {
        let mut slots = slots;
        // The fewest slots that give `n`'s least cost in `slots`.
        while slots > 1 && self.cost(n, slots - 1) <= self.cost(n, slots) {
            slots -= 1;
        }
        if slots == 1 || self.bvh2.nodes[n].is_leaf() {
            out.push(n);
        } else {
            self.share(n, slots, out);
        }
    }
}

/// The two children of inner binary node `n`.
fn halves(bvh2: &Bvh2, n: usize) -> [usize; 2] {
    let first = bvh2.nodes[n].first_index as usize;
    [first, first + 1]
}

/// Appends the primitives beneath binary node `node`, leaf by leaf (left first), to `order`
/// (`pending`: an empty stack to use).
fn gather(bvh2: &Bvh2, node: usize, order: &mut Vec<u32>, pending: &mut Vec<usize>) {
    pending.push(node);
    while let Some(n) = pending.pop() {
        let b = &bvh2.nodes[n];
        let first = b.first_index as usize;
        if b.is_leaf() {
            order.extend_from_slice(&bvh2.primitive_indices[first..first + b.prim_count as usize]);
        } else {
            pending.extend([first + 1, first]);
        }
    }
}

/// The binary nodes in an order that puts every node after its children (iterative: a
/// degenerate tree may be deep).
fn children_first(bvh2: &Bvh2) -> Vec<usize> {
    let mut preorder = Vec::with_capacity(bvh2.nodes.len());
    let mut pending = vec![0usize];
    while let Some(n) = pending.pop() {
        preorder.push(n);
        if !bvh2.nodes[n].is_leaf() {
            pending.extend(halves(bvh2, n));
        }
    }
    preorder.reverse();
    preorder
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;
    use obvhs::aabb::Aabb;

    /// 5,000 boxes scattered through a cube and a few large ones: the collapse puts every
    /// primitive in one leaf, leaves hold at most three (or a binary leaf's count), inner
    /// nodes hold at least two children, nodes are full where the binary tree allows, and
    /// every child's box is the exact union of what is beneath it (bit for bit).
    #[test]
    fn the_collapse_keeps_every_primitive_in_an_exact_box() {
        let mut rnd = super::super::test_numbers(0x1234_5678_9abc_def0);
        let mut boxes: Vec<Aabb> = (0..5_000)
            .map(|_| {
                let c = Vec3A::new(rnd(), rnd(), rnd()) * 100.0;
                let half = Vec3A::new(rnd(), rnd(), rnd()) + 0.01;
                Aabb::new(c - half, c + half)
            })
            .collect();
        boxes.push(Aabb::new(Vec3A::splat(-10.0), Vec3A::splat(110.0)));
        boxes.push(Aabb::new(Vec3A::new(0.0, 0.0, 50.0), Vec3A::new(100.0, 100.0, 50.0)));
        let (bvh, order) = build_wide(&boxes, BvhBuildParams::medium_build());
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..boxes.len() as u32).collect::<Vec<_>>(), "each primitive once");
        let summary = bvh.check(&|leaf| boxes[order[leaf] as usize]);
        assert_eq!(summary.primitives, boxes.len());
        assert!(summary.largest_leaf <= LEAF_PRIMITIVES as usize, "{summary:?}");
        assert!(summary.fewest_children >= 2, "{summary:?}");
        // PLOC's tree is balanced enough that most nodes are full.
        assert!(summary.mean_children > 6.0, "{summary:?}");
        assert_eq!(bvh.root_box().min.to_array(), [-10.0; 3]);
        assert_eq!(bvh.root_box().max.to_array(), [110.0; 3]);
    }

    /// The collapse finds the least cost that obvhs's own implementation of the same
    /// collapse (`bvh2_to_cwbvh`, written independently from the paper) finds for the same
    /// binary tree: the two trees' costs, each from its nodes' and leaves' exact boxes,
    /// agree to a relative 1e-5 (sums of 10⁴ terms in different orders) — for scattered
    /// boxes, and for a thousand in a row (a deep, lopsided tree). The costs' bound on the
    /// collapse's own plan: the root's least cost is the built tree's.
    #[test]
    fn the_collapse_costs_what_obvhs_optimal_collapse_costs() {
        use obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh;
        let mut rnd = super::super::test_numbers(0x0f1e_2d3c_4b5a_6978);
        let scattered: Vec<Aabb> = (0..5_000)
            .map(|_| {
                let c = Vec3A::new(rnd(), rnd(), rnd()) * 100.0;
                let half = Vec3A::new(rnd(), rnd(), rnd()) * 2.0 + 0.01;
                Aabb::new(c - half, c + half)
            })
            .collect();
        let row: Vec<Aabb> = (0..1_000)
            .map(|k| {
                let x = 1.1f32.powi(k / 10) + k as f32;
                Aabb::new(Vec3A::new(x, 0.0, 0.0), Vec3A::new(x + 0.5, 1.0, 1.0))
            })
            .collect();
        for boxes in [scattered, row] {
            let params = BvhBuildParams::medium_build();
            let mut bvh2 = PlocBuilder::with_capacity(boxes.len()).build(
                params.ploc_search_distance,
                &boxes,
                (0..boxes.len() as u32).collect(),
                params.sort_precision,
                params.search_depth_threshold,
            );
            ReinsertionOptimizer::default().run(&mut bvh2, params.reinsertion_batch_ratio, None);
            let (ours, order) = collapse(&bvh2);
            let summary = ours.check(&|leaf| boxes[order[leaf] as usize]);
            let our_cost = summary.node_surface * f64::from(NODE_COST)
                + summary.leaf_surface_primitives * f64::from(PRIMITIVE_COST);
            let plan = Plan::new(&bvh2);
            let planned = f64::from(plan.internal_cost(0));
            assert!((our_cost - planned).abs() <= 1e-5 * planned, "built {our_cost}, planned {planned}");

            let theirs = bvh2_to_cwbvh(&bvh2, LEAF_PRIMITIVES, false, true);
            let exact = theirs.exact_node_aabbs.as_ref().expect("asked for");
            let mut their_cost = f64::from(exact[0].half_area() * NODE_COST);
            for node in &theirs.nodes {
                for slot in (0..8).filter(|&slot| !node.is_child_empty(slot)) {
                    if node.is_leaf(slot) {
                        let (first, count) = node.child_primitives(slot);
                        let leaf = (first..first + count)
                            .map(|i| boxes[theirs.primitive_indices[i as usize] as usize])
                            .fold(Aabb::empty(), |a, b| a.union(&b));
                        their_cost += f64::from(leaf.half_area() * PRIMITIVE_COST) * count as f64;
                    } else {
                        their_cost += f64::from(exact[node.child_node_index(slot) as usize].half_area() * NODE_COST);
                    }
                }
            }
            assert!((our_cost - their_cost).abs() <= 1e-5 * their_cost, "ours {our_cost}, obvhs's {their_cost}");
            assert_eq!(summary.nodes, theirs.nodes.len());
        }
    }

    /// One primitive, two, three and four: the root holds them as one leaf up to three,
    /// then opens; an empty list gives an empty BVH.
    #[test]
    fn small_trees_collapse_into_one_node() {
        for count in 1..=4u32 {
            let boxes: Vec<Aabb> = (0..count)
                .map(|k| Aabb::new(Vec3A::splat(k as f32 * 2.0), Vec3A::splat(k as f32 * 2.0 + 1.0)))
                .collect();
            let (bvh, order) = build_wide(&boxes, BvhBuildParams::medium_build());
            assert_eq!(order.len(), count as usize);
            let summary = bvh.check(&|leaf| boxes[order[leaf] as usize]);
            assert_eq!((summary.nodes, summary.primitives), (1, count as usize), "{count}: {summary:?}");
            let leaves = if count <= LEAF_PRIMITIVES { 1 } else { count as usize };
            assert_eq!(summary.leaves, leaves, "{count}: {summary:?}");
        }
        let (empty, order) = build_wide::<Aabb>(&[], BvhBuildParams::medium_build());
        assert!(order.is_empty() && empty == WideBvh::default());
    }
}
