//! The renderer's meshes made from the scene's: the arrays the world keeps, moved out
//! of the scene or copied.

use glam::Vec3A;

use crate::mesh::MeshData;

/// A copy of the arrays of `m` that the renderer keeps (see [`mesh_data`]; its quad-mesh
/// Ptex faces only where `quad_ptex`).
pub(super) fn copy_of_rendered_arrays(m: &scene::Mesh, quad_ptex: bool) -> scene::Mesh {
    scene::Mesh {
        positions: m.positions.clone(),
        normals: m.normals.clone(),
        textures: m.textures.clone(),
        user: m.user.clone(),
        bump_basis: m.bump_basis.clone(),
        triangles: m.triangles.clone(),
        triangle_slots: m.triangle_slots.clone(),
        ptex_quads: if quad_ptex { m.ptex_quads.clone() } else { Vec::new() },
        ptex_triangles: quad_ptex && m.ptex_triangles,
        ptex_ngons: if quad_ptex { m.ptex_ngons.clone() } else { Default::default() },
        ptex_refined: if quad_ptex { m.ptex_refined.clone() } else { Default::default() },
        // The slot table itself is small; `mesh_data` reads its length.
        slots: m.slots.clone(),
        motion: m.motion.clone(),
        motion_more: m.motion_more.clone(),
        ..scene::Mesh::default()
    }
}

/// The renderer's form of a scene mesh: its position, normal, triangle and slot arrays are
/// moved out of `m`, not copied (a large mesh's normals then packed to 32 bits,
/// [`MeshData::pack_normals_if_large`], and interleaved with its positions,
/// [`MeshData::interleave`]). Its quad-mesh Ptex faces are moved out of `m`
/// and kept only where `quad_ptex` (the scene reads a quad-mesh Ptex file), else dropped:
/// no bytes per triangle.
pub(super) fn mesh_data(m: &mut scene::Mesh, quad_ptex: bool) -> MeshData {
    let mut positions = std::mem::take(&mut m.positions);
    // Room for one more vertex past the end: Embree reads the last vertex of a shared
    // 12-byte-stride buffer with a 16-byte load (a large vector grows in place).
    positions.reserve_exact(1);
    let slots = std::mem::take(&mut m.triangle_slots);
    // Taken either way: where not kept, the scene's copy is freed too (a mesh the world
    // takes no longer holds it).
    if quad_ptex {
        // A mesh of lone triangles gets its table only here (4 bytes a triangle).
        m.materialize_ptex_triangles();
    }
    let quads = std::mem::take(&mut m.ptex_quads);
    let keep_quads = quad_ptex && quads.len() == m.triangles.len();
    let mut ngons = std::mem::take(&mut m.ptex_ngons);
    let mut refined = std::mem::take(&mut m.ptex_refined);
    if keep_quads {
        ngons.prepare(&positions);
    } else {
        ngons = Default::default();
        refined = Default::default();
    }
    let mut mesh = MeshData {
        positions,
        normals: std::mem::take(&mut m.normals),
        normals_oct: Vec::new(),
        vertices: Vec::new(),
        textures: m.textures.iter().map(|t| t.coords.iter().map(|c| Vec3A::from(*c)).collect()).collect(),
        // Moved, not copied: the vectors keep the scene's packed form.
        user: m.user.iter_mut().map(|u| std::mem::take(&mut u.coords)).collect(),
        bump_basis: m.bump_basis.iter().map(|[u, v]| [Vec3A::from(*u), Vec3A::from(*v)]).collect(),
        triangles: std::mem::take(&mut m.triangles),
        // One slot for every triangle (the common case) is stored as none. A mesh of one
        // distinct slot has every triangle's 0 without reading them (a large trilist's
        // zeroed slots are never touched: no page faults).
        slots: if m.slots.len() <= 1 || slots.iter().all(|&s| s == 0) { Vec::new() } else { slots },
        ptex_quads: if keep_quads { quads } else { Vec::new() },
        ptex_ngons: ngons,
        ptex_refined: refined,
        ptex_split: None,
        hair: None,
        motion: m.motion.iter().map(|v| Vec3A::from(*v)).collect(),
        motion_more: m.motion_more.iter().map(|k| k.iter().map(|v| Vec3A::from(*v)).collect()).collect(),
        position_keys: Vec::new(),
        quad_pairs: 0,
        sharp: 0.0,
    };
    if mesh.triangles.len() >= crate::mesh::LARGE_MESH_TRIANGLES {
        // Positions and packed normals in one 16-byte record a vertex: a hit's normals
        // come in the cache lines its positions are read from (the same bytes as before).
        mesh.interleave();
    }
    // Those not interleaved (motion, Ptex faces).
    mesh.pack_normals_if_large();
    mesh
}
