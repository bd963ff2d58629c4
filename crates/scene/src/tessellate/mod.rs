//! Objects to geometry: every group, trilist and subdivision surface of an object becomes
//! part of one triangle [`Mesh`]; hair blocks become [`HairGeometry`].
//!
//! Subdivision surfaces and ccmeshes are refined by the level their `approximate …
//! parametric N` statement gives ([`DEFAULT_SUBDIVISION_LEVELS`] without one), at most as
//! many levels as keep the face count under [`MAX_SUBDIVISION_FACES`]; their triangles keep
//! their control faces' quad-mesh Ptex faces ([`crate::mesh::ptex_refined`]). Free-form surfaces
//! (Bézier, NURBS, … with trims and texture surfaces) are tessellated by [`freeform`]. The
//! shapes of mental ray's geometry shaders (`mib_geo_sphere`, …) are made by [`procedural`].

pub mod freeform;
pub mod hair;
pub mod polygon;
pub mod procedural;
pub mod subdiv;
pub mod taken;
pub mod trilist;

use glam::DVec3;
use mi::ast::{
    ApproxTerm, Approximation, Arg, Ccmesh, FaceExtra, FaceMaterial, FeatureKind, Geometry, Group, GroupItem, Hira,
    Object, PolygonMaterial, Stmt, SubdivSurface, VertexAttr,
};
use mi::Diagnostic;
use rayon::prelude::*;

use crate::mesh::ptex_quads::MAX_NGON_VERTICES;
use crate::mesh::{HairGeometry, MaterialSlot, Mesh};
use subdiv::{Cage, SHARP};

/// Subdivision levels when no approximation is given.
pub const DEFAULT_SUBDIVISION_LEVELS: u32 = 2;

/// Most faces a subdivision surface may refine to; deeper requests are reduced, with a
/// warning.
pub const MAX_SUBDIVISION_FACES: u64 = 8 << 20;

/// Sharpness, in subdivision levels, of a crease value of 1 (values are 0…1; 1 and above
/// is sharp at every level, as exporters write fully sharp creases).
pub const CREASE_LEVELS_PER_UNIT: f64 = 10.0;

/// The geometry of one object.
#[derive(Clone, Debug, Default)]
pub struct ObjectGeometry {
    /// All triangles of the object (empty mesh if it has none).
    pub mesh: Mesh,
    /// Its hair blocks.
    pub hair: Vec<HairGeometry>,
}

/// Tessellates an object. Problems in one geometry block are reported and that block is
/// skipped; the rest of the object still comes out.
pub fn tessellate(object: &Object, diags: &mut Vec<Diagnostic>) -> ObjectGeometry {
    tessellate_with(object, &taken::TakenTrilists::default(), diags)
}

/// [`tessellate`], the object's trilists' arrays that were moved out of the syntax tree
/// into `taken` moved on into the mesh.
pub fn tessellate_with(object: &Object, taken: &taken::TakenTrilists, diags: &mut Vec<Diagnostic>) -> ObjectGeometry {
    let name = &object.name.text;
    let mut out = ObjectGeometry { mesh: Mesh::new(name), hair: Vec::new() };
    let object_approx: Vec<&Approximation> = object
        .stmts
        .iter()
        .filter_map(|s| match s {
            Stmt::Kw(k) if k.key == "approximate" => match k.args.first() {
                Some(Arg::Approx(a)) => Some(&**a),
                _ => None,
            },
            _ => None,
        })
        .collect();
    let mut tri = polygon::Triangulator::default();
    for g in &object.geometry {
        match g {
            Geometry::Group(group) => {
                if let Some(mesh) = group_mesh(group, name, &object.bases, &object_approx, &mut tri, diags) {
                    out.mesh.append(mesh);
                }
            }
            Geometry::Trilist(list) => {
                let arrays = taken.take(list);
                if arrays.is_none() && taken.was_handed_out(list) {
                    // Ruled out by `TakenTrilists::take_from`; never an empty mesh in silence.
                    diags.push(Diagnostic::error(
                        list.span.start(),
                        format!("object '{name}': this trilist's data was already used by another tessellation"),
                    ));
                    continue;
                }
                if let Some(mesh) = trilist::trilist_mesh_with(list, arrays, name, diags) {
                    out.mesh.append(mesh);
                }
            }
            Geometry::Hair(h) => out.hair.extend(hair::hair_geometry(h, name, diags)),
        }
    }
    drop_nonfinite(&mut out, object.name.span, diags);
    out
}

/// Removes triangles with a NaN or infinite vertex (binary vectors can hold any bits) and
/// hairs with such points: nothing downstream could place them.
fn drop_nonfinite(out: &mut ObjectGeometry, span: mi::Span, diags: &mut Vec<Diagnostic>) {
    let mesh = &mut out.mesh;
    // Checked on all threads first: a large mesh's positions are usually all finite.
    if !mesh.positions.par_iter().all(|p| p.is_finite()) {
        let finite: Vec<bool> = mesh.positions.iter().map(|p| p.is_finite()).collect();
        let before = mesh.triangles.len();
        let keep: Vec<bool> = mesh.triangles.iter().map(|t| t.iter().all(|&i| finite[i as usize])).collect();
        if keep.contains(&false) {
            // Lone triangles' face ids follow their index: kept with the triangles.
            mesh.materialize_ptex_triangles();
        }
        let mut k = keep.iter();
        mesh.triangles.retain(|_| *k.next().expect("one flag per triangle"));
        let mut k = keep.iter();
        mesh.triangle_slots.retain(|_| *k.next().expect("one flag per triangle"));
        if mesh.ptex_quads.len() == keep.len() {
            let mut k = keep.iter();
            mesh.ptex_quads.retain(|_| *k.next().expect("one flag per triangle"));
        }
        let dropped = before - mesh.triangles.len();
        if dropped == 0 {
            return;
        }
        diags.push(Diagnostic::warning(
            span,
            format!("object '{}': {} triangle(s) with a non-finite vertex position are left out", mesh.name, dropped),
        ));
    }
    for h in &mut out.hair {
        let bad = h.points.iter().any(|p| !p.is_finite()) || h.radii.iter().any(|r| !r.is_finite());
        if bad {
            diags.push(Diagnostic::warning(
                span,
                format!("object '{}': hair with non-finite points or radii is left out", h.name),
            ));
            h.points.clear();
            h.radii.clear();
            h.starts.clear();
            h.hair_scalars.clear();
            h.vertex_scalars.clear();
        }
    }
}

/// A group's polygons, subdivision surfaces and free-form surfaces as one mesh.
fn group_mesh(
    group: &Group,
    name: &str,
    bases: &[mi::ast::Basis],
    object_approx: &[&Approximation],
    tri: &mut polygon::Triangulator,
    diags: &mut Vec<Diagnostic>,
) -> Option<Mesh> {
    let mut mesh = Mesh::new(name);
    polygon::group_vertices(group, &mut mesh, diags).ok()?;
    let vertex_count = mesh.positions.len();
    if group.polygons.is_empty() {
        // Only surfaces use the vertices: the mesh gets its own refined vertices.
        mesh.positions.clear();
        mesh.normals.clear();
        mesh.textures.clear();
        mesh.user.clear();
        mesh.motion.clear();
        mesh.motion_more.clear();
        mesh.derivatives.clear();
        mesh.bump_basis.clear();
    } else {
        polygon::triangulate_polygons(group, &mut mesh, 0, tri, diags);
    }
    let approximations: Vec<&Approximation> = group
        .items
        .iter()
        .filter_map(|i| if let GroupItem::Approximate(a) = i { Some(a) } else { None })
        .chain(object_approx.iter().copied())
        .collect();
    for item in &group.items {
        let (surface_name, target, cage) = match item {
            GroupItem::Subdivision(s) => {
                (&s.name, "subdivision surface", subdivision_cage(s, group, vertex_count, &mut mesh, diags))
            }
            GroupItem::Ccmesh(c) => (&c.name, "ccmesh", ccmesh_cage(c, group, vertex_count, &mut mesh, diags)),
            _ => continue,
        };
        let Some(cage) = cage else { continue };
        let requested = approximations
            .iter()
            .filter(|a| {
                a.target == Some(target) && (a.names.is_empty() || a.names.iter().any(|n| n.text == surface_name.text))
            })
            .find_map(|a| parametric_levels(a))
            .unwrap_or(DEFAULT_SUBDIVISION_LEVELS);
        let mut levels = requested;
        while levels > 0 && cage.faces_after(levels) > MAX_SUBDIVISION_FACES {
            levels -= 1;
        }
        if levels < requested {
            diags.push(Diagnostic::warning(
                surface_name.span,
                format!(
                    "{target} '{}': {requested} levels would make too many faces; using {levels}",
                    surface_name.text
                ),
            ));
        }
        // The cage's face slots index `mesh.slots`, which the refined mesh shares.
        let mut refined = subdiv::subdivided_mesh(&cage, levels, name);
        refined.slots = mesh.slots.clone();
        // Its triangles carry their cage faces' quad-mesh Ptex faces, numbered after the
        // group's polygons; where they could not be (a control face of too many vertices
        // left unrefined, numbers beyond the packing), warned of where such a file is read.
        let mut unmapped = false;
        if levels == 0 {
            if let Some(n) = (0..cage.face_count()).map(|f| cage.face(f).len()).find(|&n| n > MAX_NGON_VERTICES) {
                mesh.ptex_unmapped = mesh.ptex_unmapped.or(Some((surface_name.span, n)));
                unmapped = true;
            }
        } else if refined.ptex_refined.is_empty() {
            mesh.ptex_surface = mesh.ptex_surface.or(Some((surface_name.span, target)));
            unmapped = true;
        }
        let first = mesh.triangles.len();
        mesh.append(refined);
        // Face ids or refined numbers past what the packing holds (many surfaces in one
        // object) leave triangles without a face: say so rather than render them black
        // silently.
        if !unmapped && mesh.ptex_quads.get(first..).is_some_and(|codes| codes.contains(&crate::mesh::ptex_quads::NONE))
        {
            mesh.ptex_surface = mesh.ptex_surface.or(Some((surface_name.span, target)));
        }
    }
    let before = mesh.triangles.len();
    freeform::group_surfaces(group, bases, &approximations, &mut mesh, diags);
    if mesh.triangles.len() > before {
        mesh.ptex_surface = mesh.ptex_surface.or(Some((group.span, "free-form surface")));
    }
    Some(mesh)
}

/// The subdivision level of an approximation (`parametric N`, `regular parametric N`).
fn parametric_levels(a: &Approximation) -> Option<u32> {
    let terms = &a.technique;
    let at = terms.iter().position(|t| *t == ApproxTerm::Word("parametric"))?;
    match terms.get(at + 1) {
        Some(ApproxTerm::Num(n)) => Some(n.as_f64().clamp(0.0, 16.0) as u32),
        _ => None,
    }
}

/// Slot of an inline face material.
fn face_slot(mesh: &mut Mesh, m: &FaceMaterial, last: &mut Option<u32>) -> u32 {
    match m {
        FaceMaterial::Label(l) => mesh.slot(MaterialSlot::Label(*l)),
        FaceMaterial::Named(n) => {
            let s =
                mesh.slot(if n.text.is_empty() { MaterialSlot::Inherit } else { MaterialSlot::Named(n.text.clone()) });
            *last = Some(s);
            s
        }
        FaceMaterial::Inherit => last.unwrap_or_else(|| mesh.slot(MaterialSlot::Inherit)),
    }
}

/// The group's vertices as a cage (positions and texture spaces; faces added by the caller).
fn base_cage(group: &Group) -> Cage {
    let mut cage = Cage::default();
    let mut spaces = 0;
    for (i, v) in group.vertices.iter().enumerate() {
        let p = group.vectors.get(v.pos as usize).copied().unwrap_or_default();
        cage.positions.push(DVec3::new(p[0].into(), p[1].into(), p[2].into()));
        let mut k = 0;
        for a in group.vertex_attrs(i) {
            match *a {
                VertexAttr::Tex { index, .. } => {
                    if cage.textures.len() <= k {
                        cage.textures.resize(k + 1, vec![DVec3::ZERO; group.vertices.len()]);
                        spaces = spaces.max(k + 1);
                    }
                    let t = group.vectors.get(index as usize).copied().unwrap_or_default();
                    cage.textures[k][i] = DVec3::new(t[0].into(), t[1].into(), t[2].into());
                    k += 1;
                }
                VertexAttr::Feature { kind: FeatureKind::Corner, arg } => {
                    let sharpness = match arg {
                        Some(mi::ast::FeatureArg::Level(l)) if l > 0 => l as f64,
                        _ => SHARP,
                    };
                    cage.corners.insert(i as u32, sharpness);
                }
                _ => {}
            }
        }
    }
    cage
}

fn crease_levels(value: f64) -> f64 {
    if value >= 1.0 {
        SHARP
    } else {
        (value * CREASE_LEVELS_PER_UNIT).max(0.0)
    }
}

fn check_indices(indices: &[u32], vertex_count: usize, span: mi::Span, diags: &mut Vec<Diagnostic>) -> bool {
    match indices.iter().find(|&&i| i as usize >= vertex_count) {
        Some(&bad) => {
            diags.push(Diagnostic::error(
                span,
                format!("face uses vertex {bad} but the group has {vertex_count} vertices"),
            ));
            false
        }
        None => true,
    }
}

/// The control cage of a `subdivision surface`, with its creases and level-1 details.
fn subdivision_cage(
    s: &SubdivSurface,
    group: &Group,
    vertex_count: usize,
    mesh: &mut Mesh,
    diags: &mut Vec<Diagnostic>,
) -> Option<Cage> {
    let mut cage = base_cage(group);
    let mut last = None;
    for face in &s.faces {
        let span = mi::Span::new(s.span.file, face.offset.0, face.offset.0 + 1);
        if face.indices.len() < 3 || !check_indices(&face.indices, vertex_count, span, diags) {
            continue;
        }
        let slot = face_slot(mesh, &face.material, &mut last);
        let f = cage.face_count();
        cage.push_face(&face.indices, slot);
        let k = face.indices.len();
        for extra in &face.extras {
            match extra {
                FaceExtra::Crease { mask, values } => {
                    let mut vals = values.iter();
                    for bit in 0..k.min(32) {
                        if mask & (1 << bit) != 0 {
                            let v = vals.next().copied().unwrap_or(1.0);
                            let (a, b) = (face.indices[bit], face.indices[(bit + 1) % k]);
                            cage.creases.insert((a.min(b), a.max(b)), crease_levels(v));
                        }
                    }
                }
                FaceExtra::Hierarchy(h) => {
                    for item in h {
                        if let Hira::Detail { mask, indices } = item {
                            let offsets = indices
                                .iter()
                                .map(|&i| {
                                    let v = group.vectors.get(i as usize).copied().unwrap_or_default();
                                    DVec3::new(v[0].into(), v[1].into(), v[2].into())
                                })
                                .collect();
                            cage.details.push((f as u32, *mask, offsets));
                        }
                    }
                }
                FaceExtra::Trim(_) => {}
            }
        }
    }
    (cage.face_count() > 0).then_some(cage)
}

/// The control cage of a `ccmesh`.
fn ccmesh_cage(
    c: &Ccmesh,
    group: &Group,
    vertex_count: usize,
    mesh: &mut Mesh,
    diags: &mut Vec<Diagnostic>,
) -> Option<Cage> {
    let mut cage = base_cage(group);
    let (mut start, mut cstart) = (0usize, 0usize);
    let mut slot_of_name: Vec<Option<u32>> = vec![None; c.material_names.len()];
    let mut last = None;
    for face in &c.faces {
        let indices = &c.indices[start..face.end as usize];
        let creases = &c.creases[cstart..face.crease_end as usize];
        start = face.end as usize;
        cstart = face.crease_end as usize;
        let span = mi::Span::new(c.span.file, face.offset.0, face.offset.0 + 1);
        if indices.len() < 3 || !check_indices(indices, vertex_count, span, diags) {
            continue;
        }
        let slot = match face.material {
            PolygonMaterial::Label(l) => mesh.slot(MaterialSlot::Label(l)),
            PolygonMaterial::Named(m) => {
                let s = *slot_of_name[m as usize]
                    .get_or_insert_with(|| mesh.slot(MaterialSlot::Named(c.material_names[m as usize].text.clone())));
                last = Some(s);
                s
            }
            PolygonMaterial::Inherit => last.unwrap_or_else(|| mesh.slot(MaterialSlot::Inherit)),
        };
        cage.push_face(indices, slot);
        let k = indices.len();
        for (e, &v) in creases.iter().enumerate().take(k) {
            if v > 0.0 {
                let (a, b) = (indices[e], indices[(e + 1) % k]);
                cage.creases.insert((a.min(b), a.max(b)), crease_levels(f64::from(v)));
            }
        }
    }
    (cage.face_count() > 0).then_some(cage)
}
