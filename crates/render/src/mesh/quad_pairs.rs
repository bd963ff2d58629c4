//! A large mesh's triangles ordered as quads for the acceleration structure: pairs of
//! triangles that share an edge first, each pair one quad whose diagonal is that edge,
//! then the triangles left alone.
//!
//! Embree splits a quad `(v0, v1, v2, v3)` into the triangles `(v0, v1, v3)` and
//! `(v2, v3, v1)` and reports a hit's `(u, v)` in the quad's parameter square (`v0` at
//! (0, 0), `v1` (1, 0), `v2` (1, 1), `v3` (0, 1)). [`pair_in_place`] writes pair k as the
//! mesh's triangles 2k = `(v0, v1, v3)` and 2k + 1 = `(v2, v3, v1)` (each a rotation of the
//! triangle as given: its winding kept), so a quad hit names its triangle and barycentrics
//! with no table ([`triangle_hit`]): quad k < pairs is triangle 2k at `(u, v)` or, past the
//! diagonal (u + v > 1), triangle 2k + 1 at `(1 − u, 1 − v)`; a quad k ≥ pairs is the lone
//! triangle `pairs + k`, given as a quad whose last two corners coincide.
//!
//! The pairing is greedy in triangle order, each triangle taking the first unpaired
//! later neighbour (of the first [`MAX_CANDIDATES`] past it at the edge's end) across one
//! of its edges (edges `(1, 2)`, `(2, 0)`, `(0, 1)` in turn), and only neighbours wound the
//! same way (the shared edge runs the other way in them). That pass is serial; the
//! vertex → triangles table it reads ([`super::incidence`]) and the new order are built on
//! the pool's threads, with the same result at any thread count.

use super::incidence::Incidence;
use rayon::prelude::*;

/// The most triangles at a vertex a triangle looks through for its partner (a usual mesh
/// has fewer than a dozen at any vertex).
const MAX_CANDIDATES: usize = 64;

/// Triangles per piece of the parallel passes over the triangles (the pairing records how
/// many pairs and lone triangles come before each piece).
const PIECE: usize = 1 << 15;

/// [`Pairing::partner`] of the second triangle of a pair whose shared edge is the first's
/// edge 0 (edge e: `SECOND - e`); values from 1 up are firsts' partners + 1.
const SECOND: u32 = u32::MAX;

/// How [`pair_in_place`] paired a mesh's triangles: the count, and per triangle of the
/// order before, its role, from which other arrays of one entry a triangle are put in the
/// new order ([`Pairing::reorder`]).
pub struct Pairing {
    /// Pairs made: the first 2 × `pairs` triangles of the new order.
    pub pairs: u32,
    /// Per triangle before: 0 alone, s + 1 the first of a pair with s, [`SECOND`] − e the
    /// second of a pair across the first's edge e.
    partner: Vec<u32>,
    /// Per piece of [`PIECE`] triangles before: the pairs whose first comes before it and
    /// the lone triangles before it.
    before: Vec<(u32, u32)>,
}

/// Reorders `triangles` (vertex indices into `vertex_count` vertices) as pairs sharing an
/// edge, then the rest in their order, and returns how ([`Pairing`]). `None`, leaving
/// them as they are, when an index is out of range or the mesh is too large to index its
/// corners in 32 bits. The vertex → triangles table, the new order and the permutation
/// are built on the current rayon pool; the greedy pass between them is serial. The
/// result is the same at any thread count.
pub fn pair_in_place(triangles: &mut Vec<[u32; 3]>, vertex_count: usize) -> Option<Pairing> {
    if triangles.len() >= u32::MAX as usize / 3 || !indices_below(triangles, vertex_count) {
        return None;
    }
    let incident = Incidence::new(triangles, vertex_count);
    let pairing = pair_greedily(triangles, &incident);
    // The new order written over the table's list (as many triangles, its pages already
    // touched), then the old one freed.
    let mut reordered = incident.into_storage();
    let before = &triangles[..];
    pairing.scatter(
        &mut reordered,
        |t, out| *out = before[t],
        |t, s, out| {
            let edge = (SECOND - pairing.partner[s]) as usize;
            let (tri, other) = (before[t], before[s]);
            let (from, to) = (tri[edge], tri[(edge + 1) % 3]);
            // The corner of `other` where it runs the edge back (as the greedy pass found it).
            let m = (0..3).find(|&m| other[m] == to && other[(m + 1) % 3] == from).unwrap_or(0);
            // v1 = tri[edge], v3 = tri[edge + 1], v0 = tri[edge + 2]; v2 = other[m + 2].
            let (v0, v1, v3) = (tri[(edge + 2) % 3], tri[edge], tri[(edge + 1) % 3]);
            let v2 = other[(m + 2) % 3];
            *out = [[v0, v1, v3], [v2, v3, v1]];
        },
    );
    *triangles = reordered;
    Some(pairing)
}

/// Whether every index of `triangles` is below `vertex_count` (checked on all threads).
fn indices_below(triangles: &[[u32; 3]], vertex_count: usize) -> bool {
    triangles.par_chunks(PIECE).all(|c| c.iter().flatten().all(|&i| (i as usize) < vertex_count))
}

/// The greedy pairing in triangle order: each triangle not yet paired takes the first
/// unpaired later neighbour (of the first [`MAX_CANDIDATES`] past it at the edge's end)
/// across one of its edges (`(1, 2)`, `(2, 0)`, `(0, 1)` in turn) wound the same way.
fn pair_greedily(triangles: &[[u32; 3]], incident: &Incidence) -> Pairing {
    let n = triangles.len();
    // Zeroed pages, touched on all threads before the serial pass reads and writes them.
    let mut partner = vec![0u32; n];
    partner.par_chunks_mut(PIECE).for_each(|c| c.fill(0));
    let mut before = Vec::with_capacity(n.div_ceil(PIECE));
    let (mut pairs, mut lone) = (0u32, 0u32);
    for t in 0..n {
        if t % PIECE == 0 {
            before.push((pairs, lone));
        }
        if partner[t] != 0 {
            continue;
        }
        let tri = triangles[t];
        let found = (0..3).find_map(|k| {
            let edge = (k + 1) % 3;
            let (from, to) = (tri[edge], tri[(edge + 1) % 3]);
            if from == to {
                return None;
            }
            // A neighbour wound the same way runs the edge from `to` to `from`.
            // The triangles past t at `to`, the first few of them: a vertex shared by a
            // great many triangles (a hostile file's) costs no more than a usual one.
            let around = incident.of(to);
            let past = &around[around.partition_point(|&s| s as usize <= t)..];
            past.iter().take(MAX_CANDIDATES).find_map(|&s| {
                let s = s as usize;
                if partner[s] != 0 {
                    return None;
                }
                let other = &triangles[s];
                (0..3).any(|m| other[m] == to && other[(m + 1) % 3] == from).then_some((edge, s))
            })
        });
        match found {
            Some((edge, s)) => {
                partner[t] = s as u32 + 1;
                partner[s] = SECOND - edge as u32;
                pairs += 1;
            }
            None => lone += 1,
        }
    }
    Pairing { pairs, partner, before }
}

impl Pairing {
    /// The new order: `order[i]` is the index before of the triangle now at i.
    pub fn order(&self) -> Vec<u32> {
        let mut order = vec![0u32; self.partner.len()];
        self.scatter(&mut order, |t, out| *out = t as u32, |t, s, out| *out = [t as u32, s as u32]);
        order
    }

    /// `values`, one a triangle in the order before, in the new order (on all threads).
    pub fn reorder(&self, values: &[u32]) -> Vec<u32> {
        debug_assert_eq!(values.len(), self.partner.len(), "one value a triangle");
        let mut out = vec![0u32; values.len()];
        self.scatter(&mut out, |t, out| *out = values[t], |t, s, out| *out = [values[t], values[s]]);
        out
    }

    /// Writes each triangle's entry of the new order into `out` (one a triangle), piece
    /// by piece on all threads: `lone(t, entry)` for a lone triangle t and `pair(t, s,
    /// two entries)` for a pair's first t and second s.
    fn scatter<T: Send>(
        &self,
        out: &mut [T],
        lone: impl Fn(usize, &mut T) + Sync,
        pair: impl Fn(usize, usize, &mut [T; 2]) + Sync,
    ) {
        let n = self.partner.len();
        let (mut pairs_out, mut lone_out) = out.split_at_mut(2 * self.pairs as usize);
        let mut pieces = Vec::with_capacity(self.before.len());
        for (c, &(p, l)) in self.before.iter().enumerate() {
            let (p_next, l_next) =
                self.before.get(c + 1).copied().unwrap_or((self.pairs, (n - 2 * self.pairs as usize) as u32));
            let (mine, rest) = pairs_out.split_at_mut(2 * (p_next - p) as usize);
            pairs_out = rest;
            let (mine_lone, rest) = lone_out.split_at_mut((l_next - l) as usize);
            lone_out = rest;
            pieces.push((c, mine, mine_lone));
        }
        pieces.into_par_iter().for_each(|(c, pair_slots, lone_slots)| {
            let (mut pair_slots, mut lone_slots) = (pair_slots.chunks_exact_mut(2), lone_slots.iter_mut());
            for t in c * PIECE..((c + 1) * PIECE).min(n) {
                match self.partner[t] {
                    0 => lone(t, lone_slots.next().expect("a lone slot")),
                    v if v < SECOND - 2 => {
                        let slots: &mut [T; 2] = pair_slots.next().expect("a pair slot").try_into().expect("two slots");
                        pair(t, (v - 1) as usize, slots);
                    }
                    _ => {}
                }
            }
        });
    }
}

/// The quads of triangles ordered by [`pair_in_place`] with `pairs` pairs: `(v0, v1, v2,
/// v3)` of each pair, then each lone triangle as `(a, b, c, c)`.
pub fn quads(triangles: &[[u32; 3]], pairs: u32) -> Vec<[u32; 4]> {
    let paired = 2 * pairs as usize;
    let mut out = Vec::with_capacity(pairs as usize + triangles.len() - paired);
    triangles[..paired]
        .par_chunks_exact(2)
        .map(|pair| {
            let ([v0, v1, v3], [v2, _, _]) = (pair[0], pair[1]);
            [v0, v1, v2, v3]
        })
        .collect_into_vec(&mut out);
    out.par_extend(triangles[paired..].par_iter().map(|&[a, b, c]| [a, b, c, c]));
    out
}

/// The triangle and its barycentrics (of its second and third vertex) of a hit on quad
/// `quad` at the quad's `(u, v)`, for triangles ordered with `pairs` pairs.
#[inline(always)]
pub fn triangle_hit(pairs: u32, quad: u32, u: f32, v: f32) -> (u32, f32, f32) {
    if quad >= pairs {
        (quad + pairs, u, v)
    } else if u + v > 1.0 {
        (2 * quad + 1, 1.0 - u, 1.0 - v)
    } else {
        (2 * quad, u, v)
    }
}

#[cfg(test)]
#[path = "quad_pairs_tests.rs"]
mod tests;
