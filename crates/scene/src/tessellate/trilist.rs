//! `trilist` to mesh: vertex lines split by their layout (`p n d d2 m b t u`), triangles
//! checked against the vertex count, labels or per-triangle materials as slots.
//!
//! Arrays moved out of the syntax tree ([`super::taken`]) become the mesh's own without a
//! copy where their layout allows: the index list its triangles (three indices a
//! triangle, as written), the vertex numbers its positions (the positions, first on each
//! line, moved to the front of the same array once the other columns are copied out).

use glam::Vec3;
use mi::ast::{LayoutItem, Triangles, Trilist};
use mi::Diagnostic;
use rayon::prelude::*;

use super::taken::TrilistArrays;
use crate::mesh::{MaterialSlot, Mesh, TexSpace};

/// Converts a trilist; errors (bad indices) point at the trilist.
pub fn trilist_mesh(list: &Trilist, name: &str, diags: &mut Vec<Diagnostic>) -> Option<Mesh> {
    trilist_mesh_with(list, None, name, diags)
}

/// [`trilist_mesh`] of a trilist whose vertex numbers and indices are `taken` (moved out
/// of the syntax tree, which then holds empty arrays), or, with `None`, are the tree's.
pub fn trilist_mesh_with(
    list: &Trilist,
    taken: Option<TrilistArrays>,
    name: &str,
    diags: &mut Vec<Diagnostic>,
) -> Option<Mesh> {
    let (mut owned_floats, owned_indices) = match taken {
        Some(a) => (Some(a.floats), Some(a.indices)),
        None => (None, None),
    };
    let floats: &[f32] = owned_floats.as_deref().unwrap_or(&list.floats);
    let mut mesh = Mesh::new(name);
    let per_line = list.floats_per_line();
    let n = list.vertex_count as usize;
    if per_line == 0 || floats.len() != n * per_line {
        diags.push(Diagnostic::error(list.span.start(), "trilist vertex data does not match its layout"));
        return None;
    }
    let mut offset = 0;
    for item in &list.layout {
        let width = item.floats();
        // On all threads (each vector where the numbers' line puts it).
        let column_with = |k: usize, f: fn(Vec3) -> Vec3| -> Vec<Vec3> {
            (0..n)
                .into_par_iter()
                .map(|v| {
                    let line = &floats[v * per_line + offset + 3 * k..];
                    f(Vec3::new(line[0], line[1], line[2]))
                })
                .collect()
        };
        let column = |k: usize| column_with(k, |v| v);
        match item {
            // Moved in place below when the numbers are owned (the layout starts with `p`).
            LayoutItem::P if owned_floats.is_some() && offset == 0 => {}
            LayoutItem::P => mesh.positions = column(0),
            LayoutItem::N => mesh.normals = column_with(0, Vec3::normalize_or_zero),
            LayoutItem::D => {
                let (du, dv) = (column(0), column(1));
                mesh.derivatives = du.into_iter().zip(dv).map(|(a, b)| [a, b]).collect();
            }
            LayoutItem::M(k) => {
                mesh.motion = column(0);
                mesh.motion_more = (1..k.unwrap_or(1).min(15) as usize).map(&column).collect();
            }
            LayoutItem::B(k) => {
                if k.unwrap_or(1) >= 2 {
                    let (bu, bv) = (column(0), column(1));
                    mesh.bump_basis = bu.into_iter().zip(bv).map(|(a, b)| [a, b]).collect();
                }
            }
            LayoutItem::T(dims) | LayoutItem::U(dims) => {
                let mut at = offset;
                for &d in dims {
                    let d = d as usize;
                    let coords = (0..n)
                        .map(|v| {
                            let line = &floats[v * per_line + at..v * per_line + at + d];
                            let mut c = [0.0f32; 3];
                            c[..d.min(3)].copy_from_slice(&line[..d.min(3)]);
                            Vec3::from_array(c)
                        })
                        .collect();
                    let space = TexSpace { dim: d.min(3) as u8, coords };
                    if matches!(item, LayoutItem::T(_)) {
                        mesh.textures.push(space);
                    } else {
                        mesh.user.push(space);
                    }
                    at += d;
                }
            }
            LayoutItem::D2 => {}
        }
        offset += width;
    }
    // The first `p` was skipped above (a later one, if any, has set the positions).
    let first_is_p = list.layout.first() == Some(&LayoutItem::P);
    if let Some(mut numbers) = owned_floats.take().filter(|_| first_is_p && mesh.positions.is_empty()) {
        mesh.positions = positions_in_place(&mut numbers, n, per_line);
    }
    let main = owned_indices.map_or(Indices::Tree(&list.triangles.indices), Indices::Owned);
    add_triangles(main, &list.triangles, &mut mesh, list, diags)?;
    if let Some(border) = &list.border {
        add_triangles(Indices::Tree(&border.indices), border, &mut mesh, list, diags)?;
    }
    // Quad-mesh Ptex: each triangle is a face of its own (3 sub-quads), in order.
    mesh.ptex_triangles = true;
    mesh.ptex_faces = u32::try_from(mesh.triangles.len()).ok().and_then(|t| t.checked_mul(3)).unwrap_or(u32::MAX);
    Some(mesh)
}

/// The positions of `n` vertex lines of `per_line` numbers each, the first three of each
/// line, made in the array of the numbers themselves: each line's position moved to the
/// front (line v's to `3v..3v + 3`, never past where line v starts, so nothing is
/// overwritten before it is read), the rest cut off and handed back to the allocator. A
/// copy only if the array cannot be reinterpreted (its capacity not a multiple of three).
fn positions_in_place(numbers: &mut Vec<f32>, n: usize, per_line: usize) -> Vec<Vec3> {
    for v in 1..n {
        numbers.copy_within(v * per_line..v * per_line + 3, 3 * v);
    }
    numbers.truncate(3 * n);
    numbers.shrink_to_fit();
    match bytemuck::allocation::try_cast_vec::<f32, Vec3>(std::mem::take(numbers)) {
        Ok(positions) => positions,
        Err((_, numbers)) => numbers.chunks_exact(3).map(Vec3::from_slice).collect(),
    }
}

/// A triangle index list: the syntax tree's, or moved out of it.
enum Indices<'a> {
    Tree(&'a [u32]),
    Owned(Vec<u32>),
}

impl Indices<'_> {
    fn as_slice(&self) -> &[u32] {
        match self {
            Indices::Tree(s) => s,
            Indices::Owned(v) => v,
        }
    }
}

fn add_triangles(
    indices: Indices,
    tris: &Triangles,
    mesh: &mut Mesh,
    list: &Trilist,
    diags: &mut Vec<Diagnostic>,
) -> Option<()> {
    let n = list.vertex_count;
    // Checked on all threads; the first bad index found again only for the message.
    let any_bad = indices.as_slice().par_chunks(1 << 16).any(|c| c.iter().any(|&i| i >= n));
    let first_bad = if any_bad { indices.as_slice().iter().find(|&&i| i >= n) } else { None };
    if let Some(&bad) = first_bad {
        diags.push(Diagnostic::error(
            list.span.start(),
            format!("trilist triangle uses vertex line {bad} but there are {n}"),
        ));
        return None;
    }
    let count = indices.as_slice().len() / 3;
    match indices {
        // The list becomes the triangles as it is (an incomplete last triangle cut off).
        Indices::Owned(mut v) if mesh.triangles.is_empty() => {
            v.truncate(3 * count);
            mesh.triangles = match bytemuck::allocation::try_cast_vec::<u32, [u32; 3]>(v) {
                Ok(triangles) => triangles,
                Err((_, v)) => v.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
            };
        }
        indices => mesh.triangles.extend(indices.as_slice().chunks_exact(3).map(|t| [t[0], t[1], t[2]])),
    }
    match (&tris.labels, &tris.materials) {
        (Some(labels), _) => {
            for &l in labels.iter().take(count) {
                let s = mesh.slot(MaterialSlot::Label(l));
                mesh.triangle_slots.push(s);
            }
        }
        (None, Some(materials)) => {
            let mut changes = materials.iter().peekable();
            let mut slot = mesh.slot(MaterialSlot::Inherit);
            for t in 0..count as u32 {
                while let Some((_, name)) = changes.next_if(|(at, _)| *at <= t) {
                    slot = mesh.slot(MaterialSlot::Named(name.text.clone()));
                }
                mesh.triangle_slots.push(slot);
            }
        }
        (None, None) if mesh.triangle_slots.is_empty() => {
            // Slot 0 (the mesh's only one so far) comes from zeroed memory the allocator
            // maps and nothing writes: pages no one touches cost no page faults.
            let s = mesh.slot(MaterialSlot::Inherit);
            mesh.triangle_slots = vec![s; count];
        }
        (None, None) => {
            let s = mesh.slot(MaterialSlot::Inherit);
            mesh.triangle_slots.extend(std::iter::repeat_n(s, count));
        }
    }
    Some(())
}
