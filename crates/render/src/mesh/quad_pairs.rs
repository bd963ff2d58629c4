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
//! later neighbour (of the first [`MAX_CANDIDATES`] past it at the edge's end) across one of its edges (edges `(1, 2)`, `(2, 0)`, `(0, 1)` in turn), and only
//! neighbours wound the same way (the shared edge runs the other way in them).

/// The most triangles at a vertex a triangle looks through for its partner (a usual mesh
/// has fewer than a dozen at any vertex).
const MAX_CANDIDATES: usize = 64;

/// Reorders `triangles` (vertex indices into `vertex_count` vertices) as pairs sharing an
/// edge, then the rest in their order, and returns the number of pairs and the new order
/// (`order[i]`: the index before of the triangle now at i). `None`, leaving them as they
/// are, when an index is out of range or the mesh is too large to index its corners in
/// 32 bits.
pub fn pair_in_place(triangles: &mut [[u32; 3]], vertex_count: usize) -> Option<(u32, Vec<u32>)> {
    if triangles.len() >= u32::MAX as usize / 3 || triangles.iter().flatten().any(|&i| i as usize >= vertex_count) {
        return None;
    }
    let incident = Incidence::new(triangles, vertex_count);
    let mut paired = vec![false; triangles.len()];
    let mut pairs: Vec<([u32; 3], [u32; 3], u32, u32)> = Vec::with_capacity(triangles.len() / 2);
    for t in 0..triangles.len() {
        if paired[t] {
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
                if paired[s] {
                    return None;
                }
                let other = &triangles[s];
                (0..3).find(|&m| other[m] == to && other[(m + 1) % 3] == from).map(|m| (edge, s, m))
            })
        });
        if let Some((edge, s, m)) = found {
            paired[t] = true;
            paired[s] = true;
            let other = triangles[s];
            // v1 = tri[edge], v3 = tri[edge + 1], v0 = tri[edge + 2]; v2 = other[m + 2].
            let (v0, v1, v3) = (tri[(edge + 2) % 3], tri[edge], tri[(edge + 1) % 3]);
            let v2 = other[(m + 2) % 3];
            pairs.push(([v0, v1, v3], [v2, v3, v1], t as u32, s as u32));
        }
    }
    drop(incident);
    let mut order = Vec::with_capacity(triangles.len());
    let mut lone = Vec::new();
    for (t, tri) in triangles.iter().enumerate() {
        if !paired[t] {
            lone.push((*tri, t as u32));
        }
    }
    let count = pairs.len() as u32;
    let mut at = 0;
    for (first, second, t, s) in pairs {
        triangles[at] = first;
        triangles[at + 1] = second;
        order.extend([t, s]);
        at += 2;
    }
    for (tri, t) in lone {
        triangles[at] = tri;
        order.push(t);
        at += 1;
    }
    Some((count, order))
}

/// The quads of triangles ordered by [`pair_in_place`] with `pairs` pairs: `(v0, v1, v2,
/// v3)` of each pair, then each lone triangle as `(a, b, c, c)`.
pub fn quads(triangles: &[[u32; 3]], pairs: u32) -> Vec<[u32; 4]> {
    let paired = 2 * pairs as usize;
    let mut out = Vec::with_capacity(pairs as usize + triangles.len() - paired);
    for pair in triangles[..paired].chunks_exact(2) {
        let ([v0, v1, v3], [v2, _, _]) = (pair[0], pair[1]);
        out.push([v0, v1, v2, v3]);
    }
    out.extend(triangles[paired..].iter().map(|&[a, b, c]| [a, b, c, c]));
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

/// Which triangles touch each vertex (compressed rows: `start[v]..start[v + 1]` of `list`).
struct Incidence {
    start: Vec<u32>,
    list: Vec<u32>,
}

impl Incidence {
    fn new(triangles: &[[u32; 3]], vertex_count: usize) -> Incidence {
        let mut start = vec![0u32; vertex_count + 1];
        for tri in triangles {
            for &i in tri {
                start[i as usize + 1] += 1;
            }
        }
        for v in 0..vertex_count {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut list = vec![0u32; 3 * triangles.len()];
        for (t, tri) in triangles.iter().enumerate() {
            for &i in tri {
                list[fill[i as usize] as usize] = t as u32;
                fill[i as usize] += 1;
            }
        }
        Incidence { start, list }
    }

    fn of(&self, vertex: u32) -> &[u32] {
        &self.list[self.start[vertex as usize] as usize..self.start[vertex as usize + 1] as usize]
    }
}

#[cfg(test)]
#[path = "quad_pairs_tests.rs"]
mod tests;
