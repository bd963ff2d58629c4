use super::*;

/// Each vertex's triangles by a plain scan: every triangle in order, once per corner at
/// the vertex.
fn rows_by_scan(triangles: &[[u32; 3]], vertex_count: usize) -> Vec<Vec<u32>> {
    let mut rows = vec![Vec::new(); vertex_count];
    for (t, tri) in triangles.iter().enumerate() {
        for &i in tri {
            rows[i as usize].push(t as u32);
        }
    }
    rows
}

/// A small mesh with what a table must get right: vertices no triangle touches (the
/// first, the last and one between), a triangle with one vertex twice and one with it
/// three times, a vertex shared by many triangles, and indices out of triangle order.
fn awkward_mesh() -> (Vec<[u32; 3]>, usize) {
    let vertex_count = 40;
    let mut tris = vec![[5, 5, 9], [7, 7, 7]];
    let mut state = 0x2545_f491_4f6c_dd1du64;
    for _ in 0..300 {
        let mut tri = [0u32; 3];
        for i in &mut tri {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            // Vertices 1..=38 but not 20; vertex 3 in about a third of the triangles.
            let v = 1 + (state % 38) as u32;
            *i = if v == 20 { 3 } else { v };
        }
        tris.push(tri);
    }
    (tris, vertex_count)
}

#[test]
fn rows_list_each_vertexs_triangles_in_order_at_any_number_of_parts() {
    let (tris, vertex_count) = awkward_mesh();
    let expected = rows_by_scan(&tris, vertex_count);
    assert!(expected[0].is_empty() && expected[20].is_empty() && expected[39].is_empty());
    assert_eq!(expected[7][..3], [1, 1, 1]);
    // One part up to more parts than vertices (the last parts then hold none).
    for parts in [1, 2, 3, 4, 7, 16, 41, 64] {
        let table = Incidence::with_parts(&tris, vertex_count, parts);
        for (v, row) in expected.iter().enumerate() {
            assert_eq!(table.of(v as u32), &row[..], "vertex {v} with {parts} parts");
        }
    }
}

#[test]
fn the_pools_table_is_the_serial_one() {
    let (tris, vertex_count) = awkward_mesh();
    let serial = Incidence::with_parts(&tris, vertex_count, 1);
    for threads in [1, 2, 3, 8] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a pool");
        let table = pool.install(|| Incidence::new(&tris, vertex_count));
        assert_eq!(table.start, serial.start, "{threads} threads");
        assert_eq!(table.list, serial.list, "{threads} threads");
    }
}

#[test]
fn empty_meshes_have_empty_rows() {
    let table = Incidence::with_parts(&[], 5, 2);
    assert!((0..5).all(|v| table.of(v).is_empty()));
    let none = Incidence::with_parts(&[], 0, 3);
    assert!(none.into_storage().is_empty());
}
