//! Syntax of `object`s: flags, free-form bases, and the geometry blocks (`group` with its
//! vector, vertex, polygon, subdivision-surface, ccmesh and free-form statements, `trilist`,
//! `hair`).
//!
//! Bulk data is stored flat (one array of indices for all polygons of a group, one array of
//! floats for a trilist) so that reading a million polygons costs a few large allocations,
//! not millions of small ones.

use super::{KwStmt, Name, Num, Stmt};
use crate::source::Span;

/// A byte offset in the file of the enclosing element. Like [`Span`], it never takes part
/// in equality.
#[derive(Clone, Copy, Debug, Default, Eq)]
pub struct Offset(pub u32);

impl PartialEq for Offset {
    fn eq(&self, _other: &Offset) -> bool {
        true
    }
}

/// `object "name" … end object`.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// Object name.
    pub name: Name,
    /// Flags (`visible on`, `tagged`, `shadow 3`, …), attributes and object-level
    /// `approximate` statements.
    pub stmts: Vec<Stmt>,
    /// Free-form bases (`basis "b" bspline 3`).
    pub bases: Vec<Basis>,
    /// The geometry blocks.
    pub geometry: Vec<Geometry>,
    /// The whole element.
    pub span: Span,
}

impl Object {
    /// Whether the object says `tagged` (`tagged on`): its faces carry integer labels.
    pub fn is_tagged(&self) -> bool {
        self.stmts.iter().rev().find_map(|s| match s {
            Stmt::Kw(k) if k.key == "tagged" => Some(!matches!(k.args.first(), Some(super::Arg::Bool(false)))),
            _ => None,
        }) == Some(true)
    }
}

/// A geometry block of an object.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// `group … end group`
    Group(Group),
    /// `trilist … end trilist`
    Trilist(Trilist),
    /// `hair … end hair`
    Hair(Hair),
}

/// `basis "name" [rational] bezier N | taylor N | bspline N | cardinal | matrix …`.
#[derive(Clone, Debug, PartialEq)]
pub struct Basis {
    /// Basis name.
    pub name: Name,
    /// Rational (weighted) control points.
    pub rational: bool,
    /// The basis type.
    pub kind: BasisKind,
    /// The whole statement.
    pub span: Span,
}

/// A free-form basis type.
#[derive(Clone, Debug, PartialEq)]
pub enum BasisKind {
    /// `bezier degree`
    Bezier(i64),
    /// `taylor degree`
    Taylor(i64),
    /// `bspline degree`
    Bspline(i64),
    /// `cardinal`
    Cardinal,
    /// `matrix degree step values…`
    Matrix {
        /// Degree.
        degree: i64,
        /// Step size.
        step: i64,
        /// The (degree+1)² basis matrix values.
        values: Vec<f64>,
    },
}

/// `group ["name"] [merge ε] … end group`: vectors, vertices and the faces built on them.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Group {
    /// Optional group name.
    pub name: Option<Name>,
    /// `merge ε`, if given.
    pub merge: Option<f64>,
    /// The vector list: positions, normals, texture coordinates, motion… (object space).
    pub vectors: Vec<[f32; 3]>,
    /// The vertices, each indexing the vector list.
    pub vertices: Vec<Vertex>,
    /// The extra references of all vertices (see [`Vertex::attrs_end`]).
    pub vertex_attrs: Vec<VertexAttr>,
    /// All polygons (`c`, `cp`, `p`, `strip`, `fan`).
    pub polygons: Polygons,
    /// Subdivision surfaces, ccmeshes, free-form curves and surfaces, `connect`s and
    /// approximations, in order.
    pub items: Vec<GroupItem>,
    /// The whole block.
    pub span: Span,
}

impl Group {
    /// The extra references (normal aside) of vertex `i`.
    pub fn vertex_attrs(&self, i: usize) -> &[VertexAttr] {
        let start = if i == 0 { 0 } else { self.vertices[i - 1].attrs_end as usize };
        &self.vertex_attrs[start..self.vertices[i].attrs_end as usize]
    }
}

/// `v pos [n normal] …`: one vertex of a group.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex {
    /// Index of its position in the vector list.
    pub pos: u32,
    /// Index of its normal, if given.
    pub normal: Option<u32>,
    /// End of its extra references in [`Group::vertex_attrs`] (they start where the
    /// previous vertex's end).
    pub attrs_end: u32,
}

/// A vertex reference other than position and normal, or a vertex feature flag.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VertexAttr {
    /// `d du dv`, `d duu dvv duv` or `d du dv duu dvv duv`: derivative vectors (2, 3 or 5).
    Deriv {
        /// How many indices were given.
        count: u8,
        /// The indices.
        idx: [u32; 5],
    },
    /// `t tex [bu bv]`: a texture coordinate, optionally with bump basis vectors.
    Tex {
        /// The texture vector.
        index: u32,
        /// The bump basis u and v vectors.
        basis: Option<[u32; 2]>,
    },
    /// `m motion`: a motion vector.
    Motion(u32),
    /// `u user`: a user vector.
    User(u32),
    /// `cusp`, `conic`, `corner`, `dart` (subdivision vertex features).
    Feature {
        /// Which feature.
        kind: FeatureKind,
        /// `level n` (mental ray 3) or a bare sharpness value (older files).
        arg: Option<FeatureArg>,
    },
}

/// A subdivision vertex feature.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FeatureKind {
    /// `cusp`
    Cusp,
    /// `conic`
    Conic,
    /// `corner`
    Corner,
    /// `dart`
    Dart,
}

/// The argument of a vertex feature.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FeatureArg {
    /// `level n`
    Level(i64),
    /// A bare number (older files).
    Value(Num),
}

/// The polygons of a group, stored flat.
///
/// Polygon `i` owns loops `list[i].first_loop .. list[i + 1].first_loop` (the last one up
/// to `loop_starts.len() - 1`); its first loop is the outline, the others are holes. Loop
/// `j` holds vertex indices `indices[loop_starts[j] .. loop_starts[j + 1]]`.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Polygons {
    /// One entry per polygon.
    pub list: Vec<Polygon>,
    /// Start of each loop in `indices`, plus a final entry equal to `indices.len()`.
    pub loop_starts: Vec<u32>,
    /// Vertex indices of all loops.
    pub indices: Vec<u32>,
    /// Material names used by polygons, each stored once.
    pub material_names: Vec<Name>,
}

impl Polygons {
    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// The loops of polygon `i`: outline first, then holes.
    pub fn loops(&self, i: usize) -> impl Iterator<Item = &[u32]> + '_ {
        let first = self.list[i].first_loop as usize;
        let end = self.list.get(i + 1).map_or(self.loop_starts.len().saturating_sub(1), |p| p.first_loop as usize);
        (first..end).map(move |j| &self.indices[self.loop_starts[j] as usize..self.loop_starts[j + 1] as usize])
    }

    /// All vertex indices of polygon `i` (outline and holes).
    pub fn indices_of(&self, i: usize) -> &[u32] {
        let first = self.list[i].first_loop as usize;
        let end = self.list.get(i + 1).map_or(self.loop_starts.len().saturating_sub(1), |p| p.first_loop as usize);
        &self.indices[self.loop_starts[first] as usize..self.loop_starts[end] as usize]
    }

    /// Starts a polygon; add its loops with [`Polygons::push_loop`].
    pub fn begin(&mut self, kind: PolygonKind, material: PolygonMaterial, offset: Offset) {
        if self.loop_starts.is_empty() {
            self.loop_starts.push(0);
        }
        let first_loop = (self.loop_starts.len() - 1) as u32;
        self.list.push(Polygon { kind, material, first_loop, offset });
    }

    /// Ends the current loop (its indices have been pushed to `indices`).
    pub fn push_loop(&mut self) {
        self.loop_starts.push(self.indices.len() as u32);
    }
}

/// One polygon statement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Polygon {
    /// `c`, `cp`, `p`, `strip` or `fan`.
    pub kind: PolygonKind,
    /// Its material or label.
    pub material: PolygonMaterial,
    /// Index of its first loop in [`Polygons::loop_starts`].
    pub first_loop: u32,
    /// Where the statement starts.
    pub offset: Offset,
}

/// The polygon statement keyword.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PolygonKind {
    /// `c`: convex.
    Convex,
    /// `cp`: convex (legacy spelling).
    ConvexLegacy,
    /// `p`: general (concave, possibly with holes).
    General,
    /// `strip`: triangle strip.
    Strip,
    /// `fan`: triangle fan.
    Fan,
}

/// What a face says about its material.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PolygonMaterial {
    /// Nothing written: the previous or the instance's material.
    Inherit,
    /// A material name, by index into the name table of the enclosing list.
    Named(u32),
    /// A label (tagged objects): indexes the instance's material array.
    Label(u32),
}

/// Everything in a group after its vertices, other than polygons.
#[derive(Clone, Debug, PartialEq)]
pub enum GroupItem {
    /// `subdivision surface … end subdivision surface`
    Subdivision(SubdivSurface),
    /// `ccmesh … end ccmesh`
    Ccmesh(Ccmesh),
    /// `curve "name" …`
    Curve(Curve),
    /// `space curve "name" …`
    SpaceCurve(SpaceCurve),
    /// `surface "name" …`
    Surface(Surface),
    /// `connect …`
    Connect(Connect),
    /// `approximate …`
    Approximate(Approximation),
}

/// A face material or label written inline (subdivision surfaces, free-form surfaces).
#[derive(Clone, Debug, PartialEq)]
pub enum FaceMaterial {
    /// Nothing written.
    Inherit,
    /// A material name.
    Named(Name),
    /// A label.
    Label(u32),
}

/// `subdivision surface "name" … end subdivision surface`: a hierarchical subdivision surface.
#[derive(Clone, Debug, PartialEq)]
pub struct SubdivSurface {
    /// Surface name.
    pub name: Name,
    /// `polygon n n n n`: allocation hints (base triangles, hierarchy triangles, base quads,
    /// hierarchy quads).
    pub counts: Option<Vec<i64>>,
    /// `texture space [ face|subdivision|vertex, … ]`.
    pub texture_space: Option<Vec<Name>>,
    /// The base faces.
    pub faces: Vec<SubdivFace>,
    /// `derivative n [space m]` requests.
    pub derivatives: Vec<Derivative>,
    /// The whole block.
    pub span: Span,
}

/// `derivative n [space m]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Derivative {
    /// 1 or 2.
    pub order: i64,
    /// The texture space the derivatives follow.
    pub space: Option<i64>,
}

/// A base face of a subdivision surface.
#[derive(Clone, Debug, PartialEq)]
pub struct SubdivFace {
    /// Written as `q` (old quad keyword) rather than `p`.
    pub quad_keyword: bool,
    /// Material or label.
    pub material: FaceMaterial,
    /// Vertex indices (3 or 4, sometimes more).
    pub indices: Vec<u32>,
    /// Creases, trims and refinement hierarchy, in order.
    pub extras: Vec<FaceExtra>,
    /// Where it starts.
    pub offset: Offset,
}

/// Something attached to a subdivision face.
#[derive(Clone, Debug, PartialEq)]
pub enum FaceExtra {
    /// `crease mask value…`: bit i of the mask creases edge i; one sharpness per set bit.
    Crease {
        /// Edge mask.
        mask: u32,
        /// Sharpness per set bit.
        values: Vec<f64>,
    },
    /// `trim mask`: trimmed edges.
    Trim(u32),
    /// `{ … }`: the refinement hierarchy of this face.
    Hierarchy(Vec<Hira>),
}

/// One statement of a subdivision face's refinement hierarchy.
#[derive(Clone, Debug, PartialEq)]
pub enum Hira {
    /// `material child "mtl"|label`
    Material {
        /// Child face index.
        child: i64,
        /// Material or label.
        material: FaceMaterial,
    },
    /// `detail mask index…`: moves the refined vertices selected by `mask` by the given
    /// vectors.
    Detail {
        /// Which refined vertices (bit k = vertex k).
        mask: u32,
        /// One vector index per set bit.
        indices: Vec<u32>,
    },
    /// `crease child mask value…`
    Crease {
        /// Child face index.
        child: i64,
        /// Edge mask.
        mask: u32,
        /// Sharpness per set bit.
        values: Vec<f64>,
    },
    /// `trim child mask`
    Trim {
        /// Child face index.
        child: i64,
        /// Edge mask.
        mask: u32,
    },
    /// `child n { … }`: the hierarchy below child `n`.
    Child {
        /// Child face index.
        child: i64,
        /// Its statements.
        body: Vec<Hira>,
    },
}

/// `ccmesh "name" polygon N vertex M … end ccmesh`: a Catmull–Clark mesh, stored flat.
#[derive(Clone, Debug, PartialEq)]
pub struct Ccmesh {
    /// Mesh name.
    pub name: Name,
    /// Declared polygon count.
    pub polygon_count: u32,
    /// Declared total number of vertex references.
    pub vertex_count: u32,
    /// The polygons.
    pub faces: Vec<CcFace>,
    /// Vertex indices of all faces.
    pub indices: Vec<u32>,
    /// Edge sharpness values of the faces that have a `crease` list.
    pub creases: Vec<f32>,
    /// Material names used by faces, each stored once.
    pub material_names: Vec<Name>,
    /// `derivative n [space m]` requests.
    pub derivatives: Vec<Derivative>,
    /// The whole block.
    pub span: Span,
}

/// One ccmesh polygon: indices `indices[prev.end .. end]`; creases
/// `creases[prev.crease_end .. crease_end]` (empty without a `crease` list).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CcFace {
    /// Material or label.
    pub material: PolygonMaterial,
    /// End of its indices.
    pub end: u32,
    /// End of its crease values.
    pub crease_end: u32,
    /// Whether a `crease` list was written.
    pub has_crease: bool,
    /// Where it starts.
    pub offset: Offset,
}

/// A control-point reference of a free-form curve or surface: `i`, `i weight` or `i w weight`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexRef {
    /// Vertex index.
    pub index: u32,
    /// Rational weight, and whether it was written with the `w` keyword.
    pub weight: Option<(bool, f64)>,
}

/// `curve "name" [rational] "basis" params… refs… [special …]`: a trimming curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// Curve name.
    pub name: Name,
    /// Rational.
    pub rational: bool,
    /// Basis name.
    pub basis: Name,
    /// Parameter (knot) values.
    pub params: Vec<f64>,
    /// Control points.
    pub refs: Vec<VertexRef>,
    /// `special` points.
    pub special: Option<Vec<SpecialPoint>>,
    /// The whole statement.
    pub span: Span,
}

/// A `special` point of a curve or surface.
#[derive(Clone, Debug, PartialEq)]
pub enum SpecialPoint {
    /// A vertex index.
    Vertex(u32),
    /// `i mapsto j`
    MapsTo(u32, u32),
    /// `"curve" t0 t1` (surfaces only)
    Curve(CurveSegment),
}

/// `"curve" t0 t1`: a parameter range of a curve.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveSegment {
    /// Curve name.
    pub curve: Name,
    /// Start parameter.
    pub t0: f64,
    /// End parameter.
    pub t1: f64,
}

/// `space curve "name" "curve" t0 t1 …`.
#[derive(Clone, Debug, PartialEq)]
pub struct SpaceCurve {
    /// Space curve name.
    pub name: Name,
    /// Its segments.
    pub segments: Vec<CurveSegment>,
    /// The whole statement.
    pub span: Span,
}

/// One parametric direction of a free-form surface: `[rational] "basis" [min max] params…`.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceDir {
    /// Rational.
    pub rational: bool,
    /// Basis name.
    pub basis: Name,
    /// Parameter range (absent for texture surfaces).
    pub range: Option<(f64, f64)>,
    /// Knot values.
    pub params: Vec<f64>,
}

/// `surface "name" mtl|label u-direction v-direction refs… extras…`.
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    /// Surface name.
    pub name: Name,
    /// Material or label.
    pub material: FaceMaterial,
    /// The u direction.
    pub u: SurfaceDir,
    /// The v direction.
    pub v: SurfaceDir,
    /// Control points.
    pub refs: Vec<VertexRef>,
    /// Texture surfaces, derivatives, trims, holes and special points, in order.
    pub extras: Vec<SurfaceExtra>,
    /// The whole statement.
    pub span: Span,
}

/// Something attached to a free-form surface.
#[derive(Clone, Debug, PartialEq)]
pub enum SurfaceExtra {
    /// `[volume] [vector] texture u-dir v-dir refs…`
    Texture {
        /// `volume` written.
        volume: bool,
        /// `vector` written.
        vector: bool,
        /// u direction.
        u: SurfaceDir,
        /// v direction.
        v: SurfaceDir,
        /// Texture vertices.
        refs: Vec<VertexRef>,
    },
    /// `derivative [n [m]]`
    Derivative(Vec<i64>),
    /// `trim "curve" t0 t1 …`
    Trim(Vec<CurveSegment>),
    /// `hole "curve" t0 t1 …`
    Hole(Vec<CurveSegment>),
    /// `special …`
    Special(Vec<SpecialPoint>),
}

/// `connect "s1" "c1" t0 t1 "s2" "c2" t0 t1`: surface continuity along curves.
#[derive(Clone, Debug, PartialEq)]
pub struct Connect {
    /// First surface and curve segment.
    pub first: (Name, CurveSegment),
    /// Second surface and curve segment.
    pub second: (Name, CurveSegment),
    /// The whole statement.
    pub span: Span,
}

/// `[flags] approximate [target] technique… ["name"…|all]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Approximation {
    /// `visible`, `trace`, `shadow`, `caustic`, `globillum` written before `approximate`.
    pub flags: Vec<&'static str>,
    /// What it applies to (`surface`, `displace`, `subdivision surface`, `ccmesh`, …);
    /// `None` for polygons.
    pub target: Option<&'static str>,
    /// The technique words and numbers in order.
    pub technique: Vec<ApproxTerm>,
    /// The elements it applies to.
    pub names: Vec<Name>,
    /// Ends with `all` (options).
    pub all: bool,
    /// The whole statement.
    pub span: Span,
}

/// One term of an approximation technique.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ApproxTerm {
    /// A technique word (`parametric`, `length`, `view`, …).
    Word(&'static str),
    /// A number.
    Num(Num),
    /// `%`
    Percent,
}

/// `trilist … end trilist`: a triangle list with per-vertex data lines.
#[derive(Clone, Debug, PartialEq)]
pub struct Trilist {
    /// The per-vertex layout (`p n t 2`).
    pub layout: Vec<LayoutItem>,
    /// Number of vertex lines.
    pub vertex_count: u32,
    /// Number of triangles.
    pub triangle_count: u32,
    /// `border N`: number of border triangles.
    pub border_count: Option<u32>,
    /// `data info size`: sizes of the per-triangle data.
    pub data_sizes: Option<(u32, u32)>,
    /// All vertex lines, `vertex_count × floats_per_line` values.
    pub floats: Vec<f32>,
    /// The triangles.
    pub triangles: Triangles,
    /// The border triangles.
    pub border: Option<Triangles>,
    /// `triangle data`: info and data words.
    pub triangle_data: Option<(Vec<u32>, Vec<u32>)>,
    /// `topology`: adjacency words.
    pub topology: Option<Vec<u32>>,
    /// The whole block.
    pub span: Span,
}

impl Trilist {
    /// Floats per vertex line of this layout.
    pub fn floats_per_line(&self) -> usize {
        self.layout.iter().map(LayoutItem::floats).sum()
    }
}

/// One entry of a trilist vertex layout.
#[derive(Clone, Debug, PartialEq)]
pub enum LayoutItem {
    /// `p`: position.
    P,
    /// `n`: normal.
    N,
    /// `d`: first derivatives.
    D,
    /// `d2`: second derivatives.
    D2,
    /// `m [k]`: k motion vectors.
    M(Option<u32>),
    /// `b [k]`: k bump basis vectors.
    B(Option<u32>),
    /// `t d…`: texture spaces of these dimensions.
    T(Vec<u32>),
    /// `u d…`: user spaces of these dimensions.
    U(Vec<u32>),
}

impl LayoutItem {
    /// How many floats this entry takes per vertex line.
    pub fn floats(&self) -> usize {
        match self {
            LayoutItem::P | LayoutItem::N => 3,
            LayoutItem::D => 6,
            LayoutItem::D2 => 9,
            LayoutItem::M(k) | LayoutItem::B(k) => 3 * k.unwrap_or(1) as usize,
            LayoutItem::T(d) | LayoutItem::U(d) => d.iter().map(|&x| x as usize).sum(),
        }
    }
}

/// The triangles of a trilist.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Triangles {
    /// Three vertex-line indices per triangle.
    pub indices: Vec<u32>,
    /// One label per triangle (tagged objects).
    pub labels: Option<Vec<u32>>,
    /// Per-triangle material names: (first triangle, material), in order.
    pub materials: Option<Vec<(u32, Name)>>,
}

/// `hair … end hair`: hair curves.
#[derive(Clone, Debug, PartialEq)]
pub struct Hair {
    /// Header statements (`material`, `radius`, `degree`, `hair t 3`, `vertex radius`, …).
    pub header: Vec<KwStmt>,
    /// The flat scalar array: per hair, its per-hair data then its vertices.
    pub scalars: Vec<f32>,
    /// Start offset of each hair in `scalars`, plus the end.
    pub offsets: Vec<u32>,
    /// The whole block.
    pub span: Span,
}
