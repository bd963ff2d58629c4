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
//! `"cpv"`, of `{ "name" …, "type" t, "size" n, "offset" k }`: the set's kind, its
//! component count and where it lies (the layout of NVIDIA's public mental ray sample
//! shader reading the block). A UV set (`"uvs"`) is a texture space, so its `offset` is
//! the texture space found by name. Custom data and colour sets are the object's user
//! vectors (`u` in a group's vertex, `u d…` in a trilist layout), custom data first: a
//! custom data entry's user vector is its `offset`, a colour set's its `offset` plus the
//! number of `"data"` entries (how Autodesk's own Bifrost shaders for
//! mental ray find a colour set in the block). The renderer hands shaders a hit
//! triangle's three user vectors ([`VertexData::User`], mental ray's `mi_tri_vectors`);
//! the set's value is them interpolated with the hit's barycentric coordinates, as
//! texture spaces are.

use glam::Vec3A;
use shader::user_data::member;
use shader::{Ctx, NodeId, Value, VertexData};

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

/// Where a per-vertex set lies among the hit object's vertex vectors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SetSource {
    /// Texture space `k` (`tex_list[k]`, interpolated at the hit by the renderer).
    TextureSpace(usize),
    /// User vector `k` of each vertex.
    UserVector(usize),
}

/// Where the per-vertex set `name` of family `set` lies on the hit object, from its
/// per-vertex nomenclature (texture spaces) or its older `maya_vertexdata` block (UV
/// sets in texture spaces, colour sets and custom data in user vectors); `None` if the
/// object has no such set.
pub fn locate(ctx: &Ctx, set: VertexSet, name: &str) -> Option<SetSource> {
    ctx.object_data().find_map(|d| match d.declaration.as_deref() {
        Some(NOMENCLATURE) => find_entry(d.member(set.member()), "index", name).map(SetSource::TextureSpace),
        Some(VERTEX_DATA) => {
            let (array, first) = match set {
                VertexSet::Uv => return find_entry(d.member("uvs"), "offset", name).map(SetSource::TextureSpace),
                VertexSet::Color => ("cpv", entry_count(d.member("data"))),
                VertexSet::Custom => ("data", 0),
            };
            find_entry(d.member(array), "offset", name).map(|k| SetSource::UserVector(first + k))
        }
        _ => None,
    })
}

/// The `index` member of the entry named `name` of `entries` (an array of structs).
fn find_entry(entries: Option<&Value>, index: &str, name: &str) -> Option<usize> {
    let Some(Value::Array(entries)) = entries else { return None };
    entries.iter().find_map(|e| match (member(e, "name"), member(e, index)) {
        (Some(Value::Str(n)), Some(Value::Int(k))) if &**n == name => usize::try_from(*k).ok(),
        _ => None,
    })
}

/// How many entries an array member has (0 when it is missing).
fn entry_count(entries: Option<&Value>) -> usize {
    match entries {
        Some(Value::Array(entries)) => entries.len(),
        _ => 0,
    }
}

/// The value of the per-vertex vectors at `source` at the hit: a texture space's
/// coordinate, or a user vector interpolated barycentrically over the hit triangle;
/// `None` if the hit geometry has no such space or vector.
pub fn value_at(ctx: &Ctx, source: SetSource) -> Option<Vec3A> {
    match source {
        SetSource::TextureSpace(k) => (k < ctx.state.tex_count).then(|| ctx.state.tex(k)),
        SetSource::UserVector(k) => {
            let [a, b, c] = ctx.tracer.triangle(&ctx.state, VertexData::User(k))?;
            let [wa, wb, wc] = ctx.state.bary;
            Some(a * wa + b * wb + c * wc)
        }
    }
}

/// Where the first of `names` (an array of strings) the hit object has in family `set`
/// lies.
fn first_set(ctx: &Ctx, set: VertexSet, names: &Value) -> Option<SetSource> {
    let Value::Array(names) = names else { return None };
    names.iter().find_map(|n| match n {
        Value::Str(n) => locate(ctx, set, n),
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
    let space = match first_set(ctx, VertexSet::Uv, &names) {
        Some(SetSource::TextureSpace(k)) => k,
        _ => 0,
    };
    let uv = ctx.state.tex(space);
    write_struct(out, &[("outUv", Value::Vector(Vec3A::new(uv.x, uv.y, 0.0)))]);
    true
}

maya_shader!(
    /// mentalrayVertexColors: `outColor` is the colour set of the first name in
    /// `cpvSets` the hit object has, interpolated at the hit (RGB of its texture space or,
    /// named by an older `maya_vertexdata` block, of its user vector);
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
    let color = match first_set(ctx, VertexSet::Color, &names).and_then(|source| value_at(ctx, source)) {
        Some(rgb) => rgba(rgb, alpha),
        None => ctx.color(n, 2),
    };
    write_struct(out, &[("outColor", Value::Color(color)), ("outAlpha", Value::Scalar(color.w))]);
    true
}
