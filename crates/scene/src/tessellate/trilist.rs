//! `trilist` to mesh: vertex lines split by their layout (`p n d d2 m b t u`), triangles
//! checked against the vertex count, labels or per-triangle materials as slots.

use glam::Vec3;
use mi::ast::{LayoutItem, Triangles, Trilist};
use mi::Diagnostic;

use crate::mesh::{MaterialSlot, Mesh, TexSpace};

/// Converts a trilist; errors (bad indices) point at the trilist.
pub fn trilist_mesh(list: &Trilist, name: &str, diags: &mut Vec<Diagnostic>) -> Option<Mesh> {
    let mut mesh = Mesh::new(name);
    let per_line = list.floats_per_line();
    let n = list.vertex_count as usize;
    if per_line == 0 || list.floats.len() != n * per_line {
        diags.push(Diagnostic::error(list.span.start(), "trilist vertex data does not match its layout"));
        return None;
    }
    mesh.positions.reserve(n);
    let mut offset = 0;
    for item in &list.layout {
        let width = item.floats();
        let column = |k: usize| -> Vec<Vec3> {
            (0..n)
                .map(|v| {
                    let line = &list.floats[v * per_line + offset + 3 * k..];
                    Vec3::new(line[0], line[1], line[2])
                })
                .collect()
        };
        match item {
            LayoutItem::P => mesh.positions = column(0),
            LayoutItem::N => mesh.normals = column(0).into_iter().map(Vec3::normalize_or_zero).collect(),
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
                            let line = &list.floats[v * per_line + at..v * per_line + at + d];
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
    add_triangles(&list.triangles, &mut mesh, list, diags)?;
    if let Some(border) = &list.border {
        add_triangles(border, &mut mesh, list, diags)?;
    }
    Some(mesh)
}

fn add_triangles(tris: &Triangles, mesh: &mut Mesh, list: &Trilist, diags: &mut Vec<Diagnostic>) -> Option<()> {
    let n = list.vertex_count;
    if let Some(&bad) = tris.indices.iter().find(|&&i| i >= n) {
        diags.push(Diagnostic::error(
            list.span.start(),
            format!("trilist triangle uses vertex line {bad} but there are {n}"),
        ));
        return None;
    }
    let count = tris.indices.len() / 3;
    mesh.triangles.extend(tris.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]));
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
        (None, None) => {
            let s = mesh.slot(MaterialSlot::Inherit);
            mesh.triangle_slots.extend(std::iter::repeat_n(s, count));
        }
    }
    Some(())
}
