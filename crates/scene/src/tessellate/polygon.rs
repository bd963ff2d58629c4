//! Polygon groups to triangles: `c`/`cp` (convex, fanned), `p` (any simple polygon with any
//! number of holes, ear-clipped), `strip` and `fan`.
//!
//! Counter-clockwise seen from the front is the front face, so every triangle keeps the
//! winding of its polygon's outline. Ear clipping works in the plane of the polygon: the
//! outline's Newell normal picks the projection, and triangles that come out clockwise in
//! that projection are flipped.

use glam::{DVec3, Vec3};
use mi::ast::{Group, PolygonKind, PolygonMaterial, VertexAttr};
use mi::{Diagnostic, Span};

use crate::mesh::{ptex_quads, MaterialSlot, Mesh, TexSpace};

/// Reusable buffers for triangulating many polygons.
#[derive(Default)]
pub struct Triangulator {
    earcut: earcut::Earcut<f64>,
    points: Vec<[f64; 2]>,
    holes: Vec<u32>,
    out: Vec<u32>,
    loop_vertices: Vec<u32>,
}

/// A group whose vertices name vectors it does not have (the diagnostic is reported).
#[derive(Debug)]
pub struct BadVertices;

/// The vertices of a group as mesh vertices (no faces yet). Fails on a vector index out of
/// range, pointing at the group.
pub fn group_vertices(group: &Group, mesh: &mut Mesh, diags: &mut Vec<Diagnostic>) -> Result<(), BadVertices> {
    let nvec = group.vectors.len();
    let span = group.span;
    let vector = |i: u32, what: &str, diags: &mut Vec<Diagnostic>| -> Result<Vec3, BadVertices> {
        match group.vectors.get(i as usize) {
            Some(v) => Ok(Vec3::from_array(*v)),
            None => {
                diags.push(Diagnostic::error(
                    span.start(),
                    format!("{what} index {i} is out of range: the group has {nvec} vectors"),
                ));
                Err(BadVertices)
            }
        }
    };
    let n = group.vertices.len();
    mesh.positions.reserve(n);
    let has_normals = group.vertices.iter().any(|v| v.normal.is_some());
    for (i, v) in group.vertices.iter().enumerate() {
        mesh.positions.push(vector(v.pos, "vertex position", diags)?);
        if has_normals {
            let normal = match v.normal {
                Some(ni) => vector(ni, "normal", diags)?.normalize_or_zero(),
                None => Vec3::ZERO,
            };
            mesh.normals.push(normal);
        }
        let mut tex = 0;
        let mut user = 0;
        let mut motion_step = 0usize;
        for attr in group.vertex_attrs(i) {
            match *attr {
                VertexAttr::Tex { index, basis } => {
                    set_space(&mut mesh.textures, tex, i, n, vector(index, "texture vector", diags)?);
                    if let (Some([bu, bv]), 0) = (basis, tex) {
                        let b = [vector(bu, "bump basis", diags)?, vector(bv, "bump basis", diags)?];
                        mesh.bump_basis.resize(n, [Vec3::ZERO; 2]);
                        mesh.bump_basis[i] = b;
                    }
                    tex += 1;
                }
                VertexAttr::User(index) => {
                    set_space(&mut mesh.user, user, i, n, vector(index, "user vector", diags)?);
                    user += 1;
                }
                VertexAttr::Motion(index) => {
                    let m = vector(index, "motion vector", diags)?;
                    if motion_step == 0 {
                        mesh.motion.resize(n, Vec3::ZERO);
                        mesh.motion[i] = m;
                    } else if motion_step < MAX_MOTION_STEPS {
                        if mesh.motion_more.len() < motion_step {
                            mesh.motion_more.resize(motion_step, Vec::new());
                        }
                        let more = &mut mesh.motion_more[motion_step - 1];
                        more.resize(n, Vec3::ZERO);
                        more[i] = m;
                    }
                    motion_step += 1;
                }
                VertexAttr::Deriv { count, idx } if count == 2 || count == 5 => {
                    mesh.derivatives.resize(n, [Vec3::ZERO; 2]);
                    mesh.derivatives[i] = [vector(idx[0], "derivative", diags)?, vector(idx[1], "derivative", diags)?];
                }
                _ => {}
            }
        }
    }
    Ok(())
}

/// Most motion vectors a vertex carries (mental ray's `motion steps` limit).
const MAX_MOTION_STEPS: usize = 15;

/// Stores coordinate `value` of vertex `i` (of `n`) in texture space `space`.
fn set_space(spaces: &mut Vec<TexSpace>, space: usize, i: usize, n: usize, value: Vec3) {
    if spaces.len() <= space {
        spaces.resize(space + 1, TexSpace { dim: 3, coords: Vec::new() });
    }
    let s = &mut spaces[space];
    s.dim = 3;
    if s.coords.len() < n {
        s.coords.resize(n, Vec3::ZERO);
    }
    s.coords[i] = value;
}

/// Triangulates the polygons of `group` into `mesh` (whose first vertices are the group's,
/// starting at `base`). Polygons with bad indices or degenerate outlines are skipped with a
/// diagnostic.
pub fn triangulate_polygons(
    group: &Group,
    mesh: &mut Mesh,
    base: u32,
    tri: &mut Triangulator,
    diags: &mut Vec<Diagnostic>,
) {
    let polys = &group.polygons;
    let nverts = group.vertices.len() as u32;
    let file = group.span.file;
    let mut slot_of_material: Vec<Option<u32>> = vec![None; polys.material_names.len()];
    let mut last_named: Option<u32> = None;
    // Quad-mesh Ptex faces: a table per triangle only where some polygon is a quad, an
    // n-gon or has holes; a group of lone triangles (3-vertex polygons, strips, fans) has
    // none (its triangle t's faces are 3t … 3t + 2) unless one of them is left out.
    let with_table = !mesh.triangles.is_empty()
        || mesh.ptex_faces != 0
        || (0..polys.list.len()).any(|pi| !matches!(ptex_form(group, pi), PtexForm::Lone | PtexForm::NoFace));
    if with_table {
        mesh.materialize_ptex_triangles();
        mesh.ptex_quads.resize(mesh.triangles.len(), ptex_quads::NONE);
    } else {
        mesh.ptex_triangles = true;
    }
    for (pi, poly) in polys.list.iter().enumerate() {
        let form = ptex_form(group, pi);
        let face = mesh.ptex_faces;
        let outline_len = polys.loops(pi).next().map_or(0, |l| l.len() as u32);
        let faces = match form {
            PtexForm::Quad(_) | PtexForm::Ngon { one_quad: true, .. } => 1,
            PtexForm::Ngon { .. } => outline_len,
            PtexForm::Lone => outline_len.saturating_sub(2).saturating_mul(3),
            PtexForm::NoFace => 0,
        };
        mesh.ptex_faces = face.saturating_add(faces);
        let at = Span::new(file, poly.offset.0, poly.offset.0 + 1);
        let slot = match poly.material {
            PolygonMaterial::Label(l) => mesh.slot(MaterialSlot::Label(l)),
            PolygonMaterial::Named(m) => {
                let s = *slot_of_material[m as usize].get_or_insert_with(|| {
                    let name = &polys.material_names[m as usize].text;
                    mesh.slot(if name.is_empty() { MaterialSlot::Inherit } else { MaterialSlot::Named(name.clone()) })
                });
                last_named = Some(s);
                s
            }
            // A polygon without a material keeps the one named last in the group.
            PolygonMaterial::Inherit => last_named.unwrap_or_else(|| mesh.slot(MaterialSlot::Inherit)),
        };
        let mut loops = polys.loops(pi);
        let outline = loops.next().unwrap_or(&[]);
        if let Some(&bad) = polys.indices_of(pi).iter().find(|&&i| i >= nverts) {
            diags.push(Diagnostic::error(at, format!("polygon uses vertex {bad} but the group has {nverts} vertices")));
            continue;
        }
        let before = mesh.triangles.len();
        match poly.kind {
            PolygonKind::Convex | PolygonKind::ConvexLegacy if polys.loops(pi).count() == 1 => {
                for k in 1..outline.len().saturating_sub(1) {
                    mesh.triangles.push([outline[0], outline[k], outline[k + 1]].map(|v| v + base));
                }
            }
            PolygonKind::Strip => {
                for k in 0..outline.len().saturating_sub(2) {
                    let t = if k % 2 == 0 {
                        [outline[k], outline[k + 1], outline[k + 2]]
                    } else {
                        [outline[k + 1], outline[k], outline[k + 2]]
                    };
                    mesh.triangles.push(t.map(|v| v + base));
                }
            }
            PolygonKind::Fan => {
                for k in 1..outline.len().saturating_sub(1) {
                    mesh.triangles.push([outline[0], outline[k], outline[k + 1]].map(|v| v + base));
                }
            }
            _ => {
                let loops: Vec<&[u32]> = polys.loops(pi).collect();
                if !tri.triangulate(&loops, mesh, base) {
                    diags.push(Diagnostic::warning(at, "degenerate polygon (no area or invalid coordinates) skipped"));
                }
            }
        }
        if outline.len() < 3 {
            diags.push(Diagnostic::warning(at, format!("polygon with {} vertices skipped", outline.len())));
        }
        let added = mesh.triangles.len() - before;
        mesh.triangle_slots.extend(std::iter::repeat_n(slot, added));
        // A group of lone triangles stays without a table while each polygon's triangles
        // are its faces' (3 each, in order); else the table is written out from here.
        if mesh.ptex_triangles && (added as u64 * 3 != u64::from(faces) || before as u64 * 3 != u64::from(face)) {
            mesh.ptex_triangles = false;
            mesh.ptex_quads = (0..before as u32)
                .map(|t| t.checked_mul(3).map_or(ptex_quads::NONE, ptex_quads::encode_triangle))
                .collect();
        }
        if !mesh.ptex_triangles {
            ptex_codes(form, face, base, at, mesh, before);
        }
    }
}

/// What a polygon is to a quad-mesh Ptex file.
#[derive(Clone, Copy)]
enum PtexForm<'a> {
    /// A quad (without holes): one face; its outline.
    Quad([u32; 4]),
    /// Triangles each a polygon of its own (a 3-vertex polygon without holes, a strip, a
    /// fan): 3 faces each.
    Lone,
    /// An n-gon (n ≠ 4) or a polygon with holes: its outer boundary's n sub-quads, or of a
    /// 4-vertex boundary with holes one quad face.
    Ngon { outline: &'a [u32], one_quad: bool, holed: bool },
    /// Fewer than 3 vertices: no face.
    NoFace,
}

/// The quad-mesh Ptex form of polygon `pi` of `group`.
fn ptex_form(group: &Group, pi: usize) -> PtexForm<'_> {
    let polys = &group.polygons;
    let mut loops = polys.loops(pi);
    let outline = loops.next().unwrap_or(&[]);
    let holed = loops.next().is_some();
    if outline.len() < 3 {
        return PtexForm::NoFace;
    }
    match polys.list[pi].kind {
        PolygonKind::Strip | PolygonKind::Fan => PtexForm::Lone,
        _ if holed => PtexForm::Ngon { outline, one_quad: outline.len() == 4, holed },
        _ if outline.len() == 3 => PtexForm::Lone,
        _ => match <[u32; 4]>::try_from(outline) {
            Ok(q) => PtexForm::Quad(q),
            Err(_) => PtexForm::Ngon { outline, one_quad: false, holed },
        },
    }
}

/// Appends to `mesh.ptex_quads` the packed values of the triangles `before..` of a
/// polygon (its vertices from mesh vertex `base`, at `at` in the file) of form `form` and
/// first face id `face`, and an n-gon's outline to `mesh.ptex_ngons`.
fn ptex_codes(form: PtexForm, face: u32, base: u32, at: Span, mesh: &mut Mesh, before: usize) {
    let added = mesh.triangles.len() - before;
    match form {
        PtexForm::Quad(q) => {
            let codes: Vec<u32> =
                ptex_quads::quad_triangles(face, q.map(|v| v + base), &mesh.triangles[before..]).collect();
            mesh.ptex_quads.extend(codes);
        }
        PtexForm::Lone => {
            let first = |k: u32| k.checked_mul(3).and_then(|f| f.checked_add(face));
            mesh.ptex_quads
                .extend((0..added as u32).map(|k| first(k).map_or(ptex_quads::NONE, ptex_quads::encode_triangle)));
        }
        PtexForm::Ngon { outline, one_quad, holed } => {
            let fits = outline.len() <= ptex_quads::MAX_NGON_VERTICES && face <= ptex_quads::MAX_NGON_FACE;
            if holed && mesh.ptex_holed.is_none() {
                mesh.ptex_holed = Some(at);
            }
            if fits && added > 0 {
                if !holed {
                    // (Kept from when the n-gon's outline was rebuilt from its triangles.)
                    starts_at(&mut mesh.triangles[before..], outline[0] + base);
                }
                let vertices: Vec<u32> = outline.iter().map(|v| v + base).collect();
                mesh.ptex_ngons.push(face, &vertices, one_quad);
                mesh.ptex_quads.resize(mesh.triangles.len(), ptex_quads::encode_ngon(face));
            } else {
                mesh.ptex_quads.resize(mesh.triangles.len(), ptex_quads::NONE);
                if !fits && added > 0 && mesh.ptex_unmapped.is_none() {
                    mesh.ptex_unmapped = Some((at, outline.len()));
                }
            }
        }
        PtexForm::NoFace => mesh.ptex_quads.resize(mesh.triangles.len(), ptex_quads::NONE),
    }
}

/// Makes the polygon's triangles `tris` start with `v0` (the polygon's vertex 0, which an
/// n-gon's Ptex sub-quads are numbered from): the first triangle that has it moved to the
/// front, its vertices turned (winding kept) to begin there. `false` if none has it.
fn starts_at(tris: &mut [[u32; 3]], v0: u32) -> bool {
    let Some(t) = tris.iter().position(|t| t.contains(&v0)) else { return false };
    tris.swap(0, t);
    while tris[0][0] != v0 {
        tris[0].rotate_left(1);
    }
    true
}

impl Triangulator {
    /// Ear-clips a polygon given as loops of mesh-relative vertex indices (outline first,
    /// then holes) and appends counter-clockwise triangles. Returns `false` if the polygon
    /// is degenerate.
    pub fn triangulate(&mut self, loops: &[&[u32]], mesh: &mut Mesh, base: u32) -> bool {
        let pos = |i: u32| mesh.positions[(i + base) as usize].as_dvec3();
        let outline = loops[0];
        if outline.len() < 3 {
            return false;
        }
        // Newell normal of the outline.
        let mut normal = DVec3::ZERO;
        for k in 0..outline.len() {
            let (a, b) = (pos(outline[k]), pos(outline[(k + 1) % outline.len()]));
            normal += DVec3::new((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
        }
        if !normal.is_finite() || normal.length_squared() == 0.0 {
            return false;
        }
        // A lone triangle is its own triangulation: keep its vertex order (ear clipping
        // may start at another vertex, which turns per-face parametrisations such as Ptex's).
        if let [outline] = loops {
            if outline.len() == 3 {
                if outline.iter().any(|&i| !pos(i).is_finite()) {
                    return false;
                }
                mesh.triangles.push([outline[0], outline[1], outline[2]].map(|i| i + base));
                return true;
            }
        }
        let n = normal.normalize();
        let u = n.any_orthonormal_vector();
        let v = n.cross(u);
        self.points.clear();
        self.holes.clear();
        self.loop_vertices.clear();
        for (li, lp) in loops.iter().enumerate() {
            if li > 0 {
                self.holes.push(self.points.len() as u32);
            }
            for &i in lp.iter() {
                let p = pos(i);
                if !p.is_finite() {
                    return false;
                }
                self.points.push([p.dot(u), p.dot(v)]);
                self.loop_vertices.push(i);
            }
        }
        self.earcut.earcut(self.points.iter().copied(), &self.holes, &mut self.out);
        if self.out.is_empty() {
            return false;
        }
        for t in self.out.chunks_exact(3) {
            let [a, b, c] = [t[0] as usize, t[1] as usize, t[2] as usize];
            let (pa, pb, pc) = (self.points[a], self.points[b], self.points[c]);
            let cross = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0]);
            let [ia, ib, ic] = [a, b, c].map(|k| self.loop_vertices[k] + base);
            mesh.triangles.push(if cross >= 0.0 { [ia, ib, ic] } else { [ia, ic, ib] });
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh_of(points: &[[f32; 3]]) -> Mesh {
        let mut m = Mesh::new("t");
        m.positions = points.iter().map(|p| Vec3::from_array(*p)).collect();
        m
    }

    fn signed_area_z(m: &Mesh) -> f64 {
        m.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.positions[i as usize].as_dvec3());
                0.5 * (b - a).cross(c - a).z
            })
            .sum()
    }

    #[test]
    fn square_with_two_holes_has_the_right_area_and_winding() {
        // 10×10 square (CCW seen from +Z) with a 2×2 and a 1×3 hole.
        let mut m = mesh_of(&[
            [0., 0., 0.],
            [10., 0., 0.],
            [10., 10., 0.],
            [0., 10., 0.],
            [1., 1., 0.],
            [3., 1., 0.],
            [3., 3., 0.],
            [1., 3., 0.],
            [5., 5., 0.],
            [5., 8., 0.],
            [6., 8., 0.],
            [6., 5., 0.],
        ]);
        let mut tri = Triangulator::default();
        let loops: [&[u32]; 3] = [&[0, 1, 2, 3], &[4, 5, 6, 7], &[8, 9, 10, 11]];
        assert!(tri.triangulate(&loops, &mut m, 0));
        assert!((m.area() - (100.0 - 4.0 - 3.0)).abs() < 1e-9);
        // Every triangle faces +Z like the outline.
        assert!((signed_area_z(&m) - 93.0).abs() < 1e-9);
        assert!(m.triangles.iter().all(|t| {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            (b - a).cross(c - a).z > 0.0
        }));
        // n + 2h - 2 triangles for a polygon with n vertices and h holes.
        assert_eq!(m.triangles.len(), 12 + 4 - 2);
    }

    #[test]
    fn clockwise_outline_stays_clockwise() {
        let mut m = mesh_of(&[[0., 0., 0.], [0., 1., 0.], [1., 1., 0.], [1., 0., 0.]]);
        let mut tri = Triangulator::default();
        assert!(tri.triangulate(&[&[0, 1, 2, 3]], &mut m, 0));
        assert!((signed_area_z(&m) + 1.0).abs() < 1e-9, "faces -Z");
    }

    #[test]
    fn concave_polygon_in_a_tilted_plane() {
        // An L shape in the plane x = y, area 3.
        let s = std::f32::consts::FRAC_1_SQRT_2;
        let l = [[0., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 2.], [0., 2.]];
        let pts: Vec<[f32; 3]> = l.iter().map(|[a, b]| [a * s, a * s, *b]).collect();
        let mut m = mesh_of(&pts);
        let mut tri = Triangulator::default();
        assert!(tri.triangulate(&[&[0, 1, 2, 3, 4, 5]], &mut m, 0));
        assert!((m.area() - 3.0).abs() < 1e-5);
        assert_eq!(m.triangles.len(), 4);
    }

    /// A triangle keeps its vertex order exactly, whichever way it winds (exact indices).
    #[test]
    fn a_triangle_keeps_its_vertex_order() {
        let mut m = mesh_of(&[[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]]);
        let mut tri = Triangulator::default();
        for t in [[1u32, 2, 3], [2, 3, 1], [3, 1, 2], [3, 2, 1], [2, 1, 3], [1, 3, 2]] {
            m.triangles.clear();
            assert!(tri.triangulate(&[&t], &mut m, 0));
            assert_eq!(m.triangles, vec![t]);
        }
        // With a base offset too.
        let mut m = mesh_of(&[[9., 9., 9.], [0., 0., 0.], [1., 0., 0.], [0., 1., 0.]]);
        assert!(tri.triangulate(&[&[1, 2, 0]], &mut m, 1));
        assert_eq!(m.triangles, vec![[2, 3, 1]]);
    }

    #[test]
    fn degenerate_polygons_are_refused() {
        let mut m = mesh_of(&[[0., 0., 0.], [1., 1., 1.], [2., 2., 2.]]);
        let mut tri = Triangulator::default();
        assert!(!tri.triangulate(&[&[0, 1, 2]], &mut m, 0));
        let mut m = mesh_of(&[[0., 0., 0.], [f32::INFINITY, 1., 1.], [2., 0., 2.]]);
        assert!(!tri.triangulate(&[&[0, 1, 2]], &mut m, 0));
    }
}
