use super::*;

/// The point at barycentrics (u, v) of a triangle of `points`.
fn on_triangle(points: &[[f32; 2]], tri: [u32; 3], u: f32, v: f32) -> [f32; 2] {
    let w = [1.0 - u - v, u, v];
    let mut out = [0.0; 2];
    for (k, &i) in tri.iter().enumerate() {
        out[0] += w[k] * points[i as usize][0];
        out[1] += w[k] * points[i as usize][1];
    }
    out
}

/// The point at the quad's (u, v) as Embree splits it.
fn on_quad(points: &[[f32; 2]], q: [u32; 4], u: f32, v: f32) -> [f32; 2] {
    if u + v <= 1.0 {
        on_triangle(points, [q[0], q[1], q[3]], u, v)
    } else {
        on_triangle(points, [q[2], q[3], q[1]], 1.0 - u, 1.0 - v)
    }
}

/// A 3 × 2 grid of squares, each split into two triangles along alternating diagonals
/// and listed out of order, plus one triangle sharing no edge.
fn grid() -> (Vec<[f32; 2]>, Vec<[u32; 3]>) {
    let mut points = Vec::new();
    for j in 0..3 {
        for i in 0..4 {
            points.push([i as f32, j as f32]);
        }
    }
    points.extend([[10.0, 10.0], [11.0, 10.0], [10.0, 11.0]]);
    let at = |i: u32, j: u32| j * 4 + i;
    let mut tris = Vec::new();
    for j in 0..2 {
        for i in 0..3 {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if (i + j) % 2 == 0 {
                tris.extend([[a, b, c], [a, c, d]]);
            } else {
                tris.extend([[b, c, d], [d, a, b]]);
            }
        }
    }
    // All first halves, the lone triangle, then the second halves backwards.
    let mut order: Vec<[u32; 3]> = tris.iter().step_by(2).copied().collect();
    order.push([12, 13, 14]);
    order.extend(tris.iter().skip(1).step_by(2).rev().copied());
    (points, order)
}

/// Whether `a` is `b` rotated (the same corners in the same cyclic order).
fn is_rotation(a: [u32; 3], b: [u32; 3]) -> bool {
    (0..3).any(|r| (0..3).all(|k| a[k] == b[(k + r) % 3]))
}

#[test]
fn the_new_order_holds_every_triangle_once_with_its_winding() {
    let (points, before) = grid();
    let mut after = before.clone();
    let pairing = pair_in_place(&mut after, points.len()).unwrap();
    let (pairs, order) = (pairing.pairs, pairing.order());
    let mut seen = vec![0; before.len()];
    for (i, &was) in order.iter().enumerate() {
        seen[was as usize] += 1;
        assert!(is_rotation(after[i], before[was as usize]), "{:?} from {:?}", after[i], before[was as usize]);
    }
    assert!(seen.iter().all(|&n| n == 1), "{seen:?}");
    // Greedy pairing may pair across squares and strand a triangle or two; the far
    // triangle has no neighbour: of 13 triangles at least 5 pairs, the far one alone.
    assert!(pairs >= 5, "{pairs} pairs");
    assert!(after[2 * pairs as usize..].contains(&[12, 13, 14]));
}

#[test]
fn a_quad_hit_is_the_same_point_on_its_triangle() {
    let (points, mut tris) = grid();
    let pairs = pair_in_place(&mut tris, points.len()).unwrap().pairs;
    let quads = quads(&tris, pairs);
    assert_eq!(quads.len(), tris.len() - pairs as usize);
    for (q, &quad) in quads.iter().enumerate() {
        for iu in 0..=16 {
            for iv in 0..=16 {
                let (u, v) = (iu as f32 / 16.0, iv as f32 / 16.0);
                if quad[2] == quad[3] && u + v > 1.0 {
                    continue; // outside a lone triangle
                }
                let want = on_quad(&points, quad, u, v);
                let (t, tu, tv) = triangle_hit(pairs, q as u32, u, v);
                let got = on_triangle(&points, tris[t as usize], tu, tv);
                assert!(tu >= 0.0 && tv >= 0.0 && tu + tv <= 1.0 + 1e-6, "({tu}, {tv})");
                for k in 0..2 {
                    assert!((got[k] - want[k]).abs() <= 1e-5, "quad {q} at ({u}, {v}): {got:?} against {want:?}");
                }
            }
        }
    }
}

/// A 200 × 200 grid whose squares' first triangles are all listed before all their second
/// ones (as the heavy benchmark's sphere lists each face's upward triangles before its
/// downward ones): nearly every triangle still finds its partner.
#[test]
fn far_apart_partners_pair_up() {
    let side = 200u32;
    let at = |i: u32, j: u32| j * (side + 1) + i;
    let (mut first, mut second) = (Vec::new(), Vec::new());
    for j in 0..side {
        for i in 0..side {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            first.push([a, b, c]);
            second.push([a, c, d]);
        }
    }
    first.extend(second);
    let pairs = pair_in_place(&mut first, ((side + 1) * (side + 1)) as usize).unwrap().pairs;
    let lone = first.len() - 2 * pairs as usize;
    assert!(lone * 100 <= first.len(), "{lone} of {} triangles alone", first.len());
}

#[test]
fn neighbours_wound_the_other_way_and_bad_indices_are_not_paired() {
    // Two triangles over one edge, the second flipped: both stay lone.
    let mut tris = vec![[0, 1, 2], [1, 2, 3]];
    assert_eq!(pair_in_place(&mut tris, 4).unwrap().pairs, 0);
    assert_eq!(tris, [[0, 1, 2], [1, 2, 3]]);
    let mut bad = vec![[0, 1, 7]];
    assert!(pair_in_place(&mut bad, 4).is_none());
}

/// Thousands of copies of one triangle (every corner shared by all of them, none wound the
/// other way): none pairs, and each looks through a bounded number of the others.
#[test]
fn a_vertex_shared_by_every_triangle_pairs_none() {
    let mut tris = vec![[0, 1, 2]; 50_000];
    assert_eq!(pair_in_place(&mut tris, 3).unwrap().pairs, 0);
    assert!(tris.iter().all(|&t| t == [0, 1, 2]));
}

/// The pairing as it was first written, one thread throughout: a triangle's partner found
/// the same way, the pairs collected, then written with the lone triangles after them.
/// What [`pair_in_place`] must give at any thread count.
fn serial_pairing(triangles: &mut [[u32; 3]], vertex_count: usize) -> (u32, Vec<u32>) {
    let incident = Incidence::with_parts(triangles, vertex_count, 1);
    let mut paired = vec![false; triangles.len()];
    let mut pairs = Vec::new();
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
            let (v0, v1, v3) = (tri[(edge + 2) % 3], tri[edge], tri[(edge + 1) % 3]);
            pairs.push(([v0, v1, v3], [other[(m + 2) % 3], v3, v1], t as u32, s as u32));
        }
    }
    let lone: Vec<([u32; 3], u32)> =
        triangles.iter().enumerate().filter(|&(t, _)| !paired[t]).map(|(t, &tri)| (tri, t as u32)).collect();
    let count = pairs.len() as u32;
    let mut order = Vec::new();
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
    (count, order)
}

/// Meshes that exercise the pairing: the grid, a field listed out of order with some
/// triangles flipped (several pieces of [`PIECE`]), a fan around one vertex (every
/// triangle at it), two hubs whose every triangle spans the edge between them (listed one
/// way round, then the other: partners past [`MAX_CANDIDATES`] of them are not looked at),
/// copies of one triangle, degenerate triangles, and triangles listed twice, once each way.
fn test_meshes() -> Vec<(&'static str, Vec<[u32; 3]>, usize)> {
    let (points, grid) = grid();
    let side = 190u32;
    let at = |i: u32, j: u32| j * (side + 1) + i;
    let mut field = Vec::new();
    for j in 0..side {
        for i in 0..side {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            field.extend([[a, b, c], [a, c, d]]);
        }
    }
    // A fixed shuffle (an odd stride through the list) and every seventh flipped.
    let count = field.len();
    let mut field: Vec<[u32; 3]> = (0..count).map(|k| field[(k * 7919) % count]).collect();
    for tri in field.iter_mut().step_by(7) {
        tri.swap(1, 2);
    }
    let fan: Vec<[u32; 3]> = (1..3000).map(|i| [0, i, i + 1]).collect();
    let mut hubs: Vec<[u32; 3]> = (0..1000).map(|k| [0, 1, 2 + k]).collect();
    hubs.extend((0..1000).map(|k| [1, 0, 1002 + k]));
    let mut odd = vec![[0, 1, 2], [2, 1, 0], [3, 3, 4], [4, 3, 3], [1, 0, 5], [0, 2, 1], [5, 0, 1], [1, 2, 0]];
    odd.extend((0..200).map(|k| [k % 6, (k * 5 + 1) % 6, (k * 3 + 2) % 6]));
    vec![
        ("grid", grid, points.len()),
        ("field", field, ((side + 1) * (side + 1)) as usize),
        ("fan", fan, 3001),
        ("hubs", hubs, 2002),
        ("copies", vec![[0, 1, 2]; 40_000], 3),
        ("odd", odd, 6),
    ]
}

#[test]
fn the_pairing_is_the_serial_one_at_any_thread_count() {
    for (name, mesh, vertex_count) in test_meshes() {
        let mut expected = mesh.clone();
        let (pairs, order) = serial_pairing(&mut expected, vertex_count);
        for threads in [1, 2, 3, 5, 8] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a pool");
            let mut tris = mesh.clone();
            let pairing = pool.install(|| pair_in_place(&mut tris, vertex_count)).expect("pairs");
            assert_eq!(pairing.pairs, pairs, "{name}, {threads} threads");
            assert!(tris == expected, "{name}, {threads} threads: triangles differ");
            let values: Vec<u32> = (0..mesh.len() as u32).map(|t| t.wrapping_mul(0x9e37_79b9)).collect();
            let reordered = pool.install(|| pairing.reorder(&values));
            assert!(pool.install(|| pairing.order()) == order, "{name}, {threads} threads: order differs");
            assert!(
                reordered.iter().zip(&order).all(|(&v, &t)| v == values[t as usize]),
                "{name}, {threads} threads: values not carried with their triangles"
            );
        }
        // The fan pairs within its windows, the copies not at all.
        match name {
            "fan" => assert!(pairs > 1000, "fan: {pairs} pairs"),
            "copies" => assert_eq!(pairs, 0),
            "hubs" => assert!(pairs > 0 && pairs as usize <= MAX_CANDIDATES, "hubs: {pairs} pairs"),
            _ => {}
        }
    }
}
