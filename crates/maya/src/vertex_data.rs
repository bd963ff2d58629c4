//! Per-vertex data by name: Maya's per-vertex nomenclature and the nodes that read UV
//! sets and colour sets by the names Maya gives them.
//!
//! mental ray for Maya (2010 and later) attaches to each exported mesh a user data element
//! of the declaration `"PerVertexNomenclature"` that names the mesh's texture spaces:
//! `"tex"` (UV sets), `"cpv"` (colour-per-vertex sets, RGB) and `"cudpv"` (custom data per
//! vertex), each an array of `{ "name" …, "index" k }` where `k` is the texture space
//! (`tex_list[k]`) holding that set. The renderer interpolates every texture space
//! barycentrically at the hit, so a set found by name is the per-vertex data interpolated
//! at the hit point.
//!
//! Older exports (Maya 8.5–2009) attach instead a `"maya_vertexdata"` data element (magic
//! 1298749048, 'MiVx') with three arrays, `"data"` (custom per-vertex data), `"uvs"` and
//! `"cpv"`, of `{ "name" …, "type" t, "size" n, "offset" k }`: the set's vector kind, its
//! component count and its index among the vectors of that kind (the layout of NVIDIA's
//! public mental ray sample shader reading the block). A UV set (`"uvs"`) is a texture
//! space, so its `offset` is the texture space found by name. Colour sets and custom data
//! of that form live in the object's user vectors (`u` in a vertex), which mira's renderer
//! does not keep: those names are not found (the reading nodes' defaults apply).

use glam::Vec3A;
use shader::user_data::member;
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::values::{rgba, write_struct};

/// The declaration name of Maya's per-vertex nomenclature data.
pub const NOMENCLATURE: &str = "PerVertexNomenclature";

/// Which family of per-vertex data a name is looked up in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexSet {
    /// UV sets (`"tex"`).
    Uv,
    /// Colour-per-vertex sets (`"cpv"`).
    Color,
    /// Custom data per vertex (`"cudpv"`).
    Custom,
}

impl VertexSet {
    fn member(self) -> &'static str {
        match self {
            VertexSet::Uv => "tex",
            VertexSet::Color => "cpv",
            VertexSet::Custom => "cudpv",
        }
    }
}

/// The declaration name of the older exports' vertex data block.
pub const VERTEX_DATA: &str = "maya_vertexdata";

/// The texture space that holds the per-vertex set `name` of family `set` on the hit
/// object, from its per-vertex nomenclature or, for UV sets, its older `maya_vertexdata`
/// block; `None` if the object has no such set.
pub fn texture_space(ctx: &Ctx, set: VertexSet, name: &str) -> Option<usize> {
    ctx.object_data().find_map(|d| {
        let (array, index) = match d.declaration.as_deref() {
            Some(NOMENCLATURE) => (set.member(), "index"),
            Some(VERTEX_DATA) if set == VertexSet::Uv => ("uvs", "offset"),
            _ => return None,
        };
        let Some(Value::Array(entries)) = d.member(array) else { return None };
        entries.iter().find_map(|e| match (member(e, "name"), member(e, index)) {
            (Some(Value::Str(n)), Some(Value::Int(k))) if &**n == name => usize::try_from(*k).ok(),
            _ => None,
        })
    })
}

/// The first of `names` (an array of strings) the hit object has in family `set`, as
/// its texture space.
fn first_space(ctx: &Ctx, set: VertexSet, names: &Value) -> Option<usize> {
    let Value::Array(names) = names else { return None };
    names.iter().find_map(|n| match n {
        Value::Str(n) => texture_space(ctx, set, n),
        _ => None,
    })
}

maya_shader!(
    /// uvChooser: `outUv` is the UV set of the first name in `uvSets` the hit object
    /// has (its texture space interpolated at the hit); the first texture space when
    /// none matches (what Maya renders for a mesh without the named set).
    UVCHOOSER,
    ADSK_UVCHOOSER,
    "maya_uvchooser",
    "adskMayaUvChooser",
    &["uvSets"],
    uv_chooser
);

fn uv_chooser(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let names = ctx.eval(n, 0);
    let space = first_space(ctx, VertexSet::Uv, &names).unwrap_or(0);
    let uv = ctx.state.tex(space);
    write_struct(out, &[("outUv", Value::Vector(Vec3A::new(uv.x, uv.y, 0.0)))]);
    true
}

maya_shader!(
    /// mentalrayVertexColors: `outColor` is the colour set of the first name in
    /// `cpvSets` the hit object has, interpolated at the hit (RGB of its texture space);
    /// `outAlpha` 1 (exports carry RGB only), 0 with `invertAlpha`. Without a matching
    /// set: `defaultColor` and its alpha.
    VERTEXCOLORS,
    ADSK_VERTEXCOLORS,
    "maya_vertexcolors",
    "adskMayaVertexColors",
    &["cpvSets", "invertAlpha", "defaultColor"],
    vertex_colors
);

fn vertex_colors(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let names = ctx.eval(n, 0);
    let alpha = if ctx.bool(n, 1) { 0.0 } else { 1.0 };
    let color = match first_space(ctx, VertexSet::Color, &names) {
        Some(space) if space < ctx.state.tex_count => rgba(ctx.state.tex(space), alpha),
        _ => ctx.color(n, 2),
    };
    write_struct(out, &[("outColor", Value::Color(color)), ("outAlpha", Value::Scalar(color.w))]);
    true
}
