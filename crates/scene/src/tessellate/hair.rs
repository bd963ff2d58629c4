//! `hair` blocks to curves. Each hair's scalars start with its per-hair data (normal,
//! motion, texture, user, radius, in that order, as declared by `hair n|m|t|u|radius`),
//! followed by its vertices: a position and the per-vertex data declared by
//! `vertex n|m|t|u|radius`, in the same order.

use glam::Vec3;
use mi::ast::{Arg, Hair};
use mi::Diagnostic;

use crate::mesh::{HairGeometry, MaterialSlot};

/// Sizes of the per-hair and per-vertex records.
#[derive(Default)]
struct Layout {
    normal: usize,
    motion: usize,
    tex: usize,
    user: usize,
    radius: usize,
}

impl Layout {
    fn size(&self) -> usize {
        self.normal + self.motion + self.tex + self.user + self.radius
    }
}

/// Converts a hair block; errors point at it.
pub fn hair_geometry(hair: &Hair, name: &str, diags: &mut Vec<Diagnostic>) -> Option<HairGeometry> {
    let mut per_hair = Layout::default();
    let mut per_vertex = Layout::default();
    let mut radius = 1.0f32;
    let mut degree = 1u8;
    let mut slot = MaterialSlot::Inherit;
    for s in &hair.header {
        let int = |i: usize| match s.args.get(i) {
            Some(Arg::Int(v)) => (*v).clamp(0, 1 << 20) as usize,
            _ => 1,
        };
        match s.key {
            "radius" => {
                if let Some(Arg::Float(r)) = s.args.first() {
                    radius = *r as f32;
                }
            }
            "degree" => degree = if int(0) == 3 { 3 } else { 1 },
            "material" => {
                if let Some(Arg::Name(n)) = s.args.first() {
                    slot = MaterialSlot::Named(n.text.clone());
                }
            }
            "hair n" => per_hair.normal = 3,
            "hair m" => per_hair.motion = 3 * int(0),
            "hair t" => per_hair.tex = int(0),
            "hair u" => per_hair.user = int(0),
            "hair radius" => per_hair.radius = 1,
            "vertex n" => per_vertex.normal = 3,
            "vertex m" => per_vertex.motion = 3 * int(0),
            "vertex t" => per_vertex.tex = int(0),
            "vertex u" => per_vertex.user = int(0),
            "vertex radius" => per_vertex.radius = 1,
            _ => {}
        }
    }
    let fail = |diags: &mut Vec<Diagnostic>, msg: String| {
        diags.push(Diagnostic::error(hair.span.start(), msg));
        None
    };
    let offsets = &hair.offsets;
    if offsets.len() < 2 {
        return Some(HairGeometry { name: name.to_string(), degree, slot, ..HairGeometry::default() });
    }
    let mut geo = HairGeometry { name: name.to_string(), degree, slot, starts: vec![0], ..HairGeometry::default() };
    let vsize = 3 + per_vertex.size();
    for h in 0..offsets.len() - 1 {
        let (start, end) = (offsets[h] as usize, offsets[h + 1] as usize);
        if start > end || end > hair.scalars.len() {
            return fail(
                diags,
                format!("hair {h} has scalars {start}..{end} but only {} are given", hair.scalars.len()),
            );
        }
        let data = &hair.scalars[start..end];
        if data.len() < per_hair.size() || (data.len() - per_hair.size()) % vsize != 0 {
            return fail(
                diags,
                format!(
                    "hair {h} holds {} scalars, which is not {} per hair plus {} per vertex",
                    data.len(),
                    per_hair.size(),
                    vsize
                ),
            );
        }
        let hair_radius = if per_hair.radius == 1 { data[per_hair.size() - 1] } else { radius };
        geo.hair_scalars.extend_from_slice(&data[per_hair.normal + per_hair.motion..][..per_hair.tex]);
        for vertex in data[per_hair.size()..].chunks_exact(vsize) {
            geo.points.push(Vec3::new(vertex[0], vertex[1], vertex[2]));
            let r = if per_vertex.radius == 1 { vertex[vsize - 1] } else { hair_radius };
            geo.radii.push(r);
            geo.vertex_scalars
                .extend_from_slice(&vertex[3 + per_vertex.normal + per_vertex.motion..][..per_vertex.tex]);
        }
        geo.starts.push(geo.points.len() as u32);
    }
    Some(geo)
}
