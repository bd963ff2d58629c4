//! Structural equality of [`HitExpr`]s that share subexpressions. A module's `let` values
//! and function parameters used more than once make the expressions directed acyclic
//! graphs: forty chained squares `b = a·a, c = b·b, …` are 41 nodes but 2^41 paths. A
//! comparison that follows every path (the derived one) takes exponential time on two
//! separately built copies of such a graph; this one compares each pair of nodes at most
//! once, without recursion (deep trees do not use the stack), so its work is at most the
//! number of distinct node pairs met — the number of nodes for two copies of one graph.

use std::collections::HashSet;
use std::ptr;

use std::sync::Arc;

use super::hit::HitExpr;

impl PartialEq for HitExpr {
    fn eq(&self, other: &HitExpr) -> bool {
        compare(self, other).0
    }
}

/// Whether `a` and `b` compute the same thing node for node, and how many pairs of nodes
/// were compared to find out (each distinct pair once; a node compared with itself is
/// equal without looking inside).
pub fn compare(a: &HitExpr, b: &HitExpr) -> (bool, usize) {
    if ptr::eq(a, b) {
        return (true, 0);
    }
    let mut seen: HashSet<(*const HitExpr, *const HitExpr)> = HashSet::new();
    let mut work: Vec<(&HitExpr, &HitExpr)> = vec![(a, b)];
    while let Some((x, y)) = work.pop() {
        if ptr::eq(x, y) || !seen.insert((ptr::from_ref(x), ptr::from_ref(y))) {
            // The same node, or a pair already compared (or being compared: any difference
            // inside it ends the whole comparison).
            continue;
        }
        if !same_node(x, y) {
            return (false, seen.len());
        }
        let (xs, ys) = (x.operands(), y.operands());
        if xs.len() != ys.len() {
            return (false, seen.len());
        }
        work.extend(xs.into_iter().zip(ys).map(|(p, q)| (&**p, &**q)));
    }
    (true, seen.len())
}

/// Whether two nodes are the same operation with the same constants, their operands
/// aside.
fn same_node(x: &HitExpr, y: &HitExpr) -> bool {
    use HitExpr as H;
    match (x, y) {
        (H::Const(a), H::Const(b)) => a == b,
        (H::State(a), H::State(b)) => a == b,
        (H::Unary(a, _), H::Unary(b, _)) => a == b,
        (H::Binary(a, ..), H::Binary(b, ..)) => a == b,
        (H::Select(..), H::Select(..)) => true,
        (H::Math(f, a), H::Math(g, b)) => f == g && a.len() == b.len(),
        (H::Lane(_, i), H::Lane(_, j)) => i == j,
        (H::Compose(a), H::Compose(b)) => a.len() == b.len() && a.iter().zip(b.iter()).all(|(p, q)| p.1 == q.1),
        (H::Transform { matrix: m, point: p, .. }, H::Transform { matrix: n, point: q, .. }) => m == n && p == q,
        (
            H::Lookup { image: i, wrap: w, clip: c, crop: r, .. },
            H::Lookup { image: j, wrap: v, clip: d, crop: s, .. },
        ) => i == j && w == v && c == d && r == s,
        (H::Texel { image: i, .. }, H::Texel { image: j, .. }) => i == j,
        (H::Lookup3d { volume: a, wrap: w, crop: r, .. }, H::Lookup3d { volume: b, wrap: v, crop: s, .. }) => {
            Arc::ptr_eq(a, b) && w == v && r == s
        }
        (H::Texel3d { volume: a, .. }, H::Texel3d { volume: b, .. }) => Arc::ptr_eq(a, b),
        (H::LookupCube { cube: a, .. }, H::LookupCube { cube: b, .. }) => Arc::ptr_eq(a, b),
        (H::LookupPtex { ptex: a, channel: c }, H::LookupPtex { ptex: b, channel: d }) => Arc::ptr_eq(a, b) && c == d,
        (H::Pattern(p, _), H::Pattern(q, _)) => p == q,
        (H::Sky(p, _), H::Sky(q, _)) => p == q,
        (H::Bump { height: h, factor: f, delta: d, .. }, H::Bump { height: k, factor: g, delta: e, .. }) => {
            h == k && f == g && d == e
        }
        (H::Slot(a), H::Slot(b)) => a == b,
        (H::LoopOut(l, a), H::LoopOut(m, b)) => a == b && **l == **m,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::Vec4;

    use super::*;
    use crate::mdl_modules::hit::{fold, BinOp, MathFn, StateFn};

    /// `depth` chained squares of `start`: depth + 1 nodes, 2^(depth+1) − 1 paths.
    fn squares(start: StateFn, depth: usize) -> Arc<HitExpr> {
        let mut e = fold(HitExpr::State(start));
        for _ in 0..depth {
            e = fold(HitExpr::Binary(BinOp::Mul, e.clone(), e));
        }
        e
    }

    /// Two copies of a 60-level chain of squares (2^61 paths each) built apart: equal after
    /// comparing each of the 61 pairs of nodes once; copies differing at the bottom are
    /// unequal after the same 61; a difference at the top ends at the first pair.
    #[test]
    fn shared_graphs_are_compared_once_per_pair_of_nodes() {
        let (a, b) = (squares(StateFn::Position, 60), squares(StateFn::Position, 60));
        assert!(!Arc::ptr_eq(&a, &b));
        assert_eq!(compare(&a, &b), (true, 61));
        assert!(*a == *b);
        let other = squares(StateFn::Normal, 60);
        assert_eq!(compare(&a, &other), (false, 61));
        assert!(*a != *other);
        let top = fold(HitExpr::Binary(BinOp::Add, a.clone(), a.clone()));
        assert_eq!(compare(&top, &b), (false, 1));
        assert_eq!(compare(&a, &a), (true, 0));
    }

    /// What tells nodes apart: constants, operators, functions, lanes and arity.
    #[test]
    fn nodes_differ_by_their_constants_and_operations() {
        let u = fold(HitExpr::State(StateFn::TextureCoordinate(0)));
        let c = |v: f32| Arc::new(HitExpr::Const(Vec4::splat(v)));
        let mul = |k: f32| HitExpr::Binary(BinOp::Mul, u.clone(), c(k));
        assert!(mul(2.0) == mul(2.0));
        assert!(mul(2.0) != mul(3.0));
        assert!(mul(2.0) != HitExpr::Binary(BinOp::Add, u.clone(), c(2.0)));
        let f = |g: MathFn| HitExpr::Math(g, Box::new([u.clone()]));
        assert!(f(MathFn::Sin) == f(MathFn::Sin));
        assert!(f(MathFn::Sin) != f(MathFn::Cos));
        assert!(HitExpr::Lane(u.clone(), 0) != HitExpr::Lane(u.clone(), 1));
        assert!(HitExpr::Compose(Box::new([(u.clone(), 2)])) != HitExpr::Compose(Box::new([(u.clone(), 3)])));
        assert!(HitExpr::State(StateFn::TextureCoordinate(0)) != HitExpr::State(StateFn::TextureCoordinate(1)));
    }
}
