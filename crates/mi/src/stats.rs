//! Syntax-level statistics of a parsed file: what `mira check` summarises.

use std::collections::{BTreeMap, BTreeSet};

use crate::ast::*;

/// Counts of what a file (and everything it includes) contains.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Elements and commands by keyword (`object`, `instance`, `declare`, …).
    pub elements: BTreeMap<&'static str, usize>,
    /// Polygon statements in groups.
    pub polygons: usize,
    /// Triangles those polygons make (n-gon with h holes: n − 2 + 2h).
    pub polygon_triangles: usize,
    /// Triangles of trilists.
    pub trilist_triangles: usize,
    /// Base faces of subdivision surfaces and ccmeshes.
    pub subdivision_faces: usize,
    /// Hair strands.
    pub hairs: usize,
    /// Free-form surfaces.
    pub surfaces: usize,
    /// Declaration names of every shader called (`"mib_illum_phong" (…)`).
    pub shaders_used: BTreeSet<String>,
    /// Names declared by `declare`.
    pub declared: BTreeSet<String>,
    /// Files included (including built-in declaration files and MDL modules).
    pub includes: usize,
}

impl Stats {
    /// Statistics of `items`, included files counted in.
    pub fn of(items: &[Item]) -> Stats {
        let mut s = Stats::default();
        s.items(items);
        s
    }

    /// Total triangles: polygons after triangulation plus trilists.
    pub fn triangles(&self) -> usize {
        self.polygon_triangles + self.trilist_triangles
    }

    fn count(&mut self, kind: &'static str) {
        *self.elements.entry(kind).or_insert(0) += 1;
    }

    fn items(&mut self, items: &[Item]) {
        for item in items {
            self.item(item);
        }
    }

    fn item(&mut self, item: &Item) {
        match item {
            Item::Options(b) => {
                self.count("options");
                self.stmts(&b.stmts);
            }
            Item::Camera(b) => {
                self.count("camera");
                self.stmts(&b.stmts);
            }
            Item::Light(b) => {
                self.count("light");
                self.stmts(&b.stmts);
            }
            Item::Lightprofile(_) => self.count("lightprofile"),
            Item::Assembly(_) => self.count("assembly"),
            Item::Colorprofile(_) => self.count("colorprofile"),
            Item::Spectrum(_) => self.count("spectrum"),
            Item::Gui(_) => self.count("gui"),
            Item::Material(m) => {
                self.count("material");
                if let Some(l) = &m.shaders {
                    self.shader_list(l);
                }
                self.stmts(&m.stmts);
            }
            Item::Texture(t) => {
                self.count("texture");
                if let TextureSource::Shader(l) = &t.source {
                    self.shader_list(l);
                }
            }
            Item::Object(o) => {
                self.count("object");
                for g in &o.geometry {
                    self.geometry(g);
                }
            }
            Item::Instance(i) => {
                self.count("instance");
                if let InstanceTarget::Geometry(l) = &i.target {
                    self.shader_list(l);
                }
                self.stmts(&i.stmts);
            }
            Item::Instgroup(_) => self.count("instgroup"),
            Item::Shader(s) => {
                self.count("shader");
                self.shader_list(&s.list);
            }
            Item::Declare(d) => {
                self.count("declare");
                self.declared.insert(d.name.text.clone());
                for b in &d.body {
                    if let DeclItem::Item(i) = b {
                        self.item(i);
                    }
                }
            }
            Item::Data(d) => {
                self.count("data");
                if let DataBody::Params { params, .. } = &d.body {
                    self.params(params);
                }
            }
            Item::Namespace(ns) => {
                self.count("namespace");
                self.items(&ns.items);
            }
            Item::Modified { item, .. } => self.item(item),
            Item::Delete(_) => self.count("delete"),
            Item::Render(_) => self.count("render"),
            Item::Include(inc) => {
                self.includes += 1;
                self.items(&inc.items);
            }
            Item::Registry(_) => self.count("registry"),
            Item::Command(_) => self.count("command"),
        }
    }

    fn stmts(&mut self, stmts: &[Stmt]) {
        for s in stmts {
            match s {
                Stmt::Kw(k) => {
                    for a in &k.args {
                        match a {
                            Arg::Shaders(l) | Arg::ShaderArray(l) => self.shader_list(l),
                            _ => {}
                        }
                    }
                }
                Stmt::Shaders(l) => self.shader_list(l),
                Stmt::Output(o) => {
                    if let OutputKind::Shader(l) = &o.kind {
                        self.shader_list(l);
                    }
                }
                _ => {}
            }
        }
    }

    fn shader_list(&mut self, list: &ShaderList) {
        for item in &list.0 {
            match item {
                ShaderItem::Call { decl, params, .. } => {
                    self.shaders_used.insert(decl.text.clone());
                    self.params(params);
                }
                ShaderItem::Ref(_) => {}
                ShaderItem::Define { list, .. } => self.shader_list(list),
            }
        }
    }

    fn params(&mut self, params: &[Param]) {
        for p in params {
            self.value(&p.value);
        }
    }

    fn value(&mut self, v: &Value) {
        match v {
            Value::Define(item) => self.shader_list(&ShaderList(vec![(**item).clone()])),
            Value::Struct(fields) => self.params(fields),
            Value::Array(vs) | Value::Seq(vs) => {
                for v in vs {
                    self.value(v);
                }
            }
            _ => {}
        }
    }

    fn geometry(&mut self, g: &Geometry) {
        match g {
            Geometry::Group(g) => {
                self.polygons += g.polygons.len();
                for i in 0..g.polygons.len() {
                    let (mut verts, mut holes) = (0usize, 0usize);
                    for (j, lp) in g.polygons.loops(i).enumerate() {
                        verts += lp.len();
                        holes += usize::from(j > 0);
                    }
                    self.polygon_triangles += (verts + 2 * holes).saturating_sub(2);
                }
                for item in &g.items {
                    match item {
                        GroupItem::Subdivision(s) => self.subdivision_faces += s.faces.len(),
                        GroupItem::Ccmesh(c) => self.subdivision_faces += c.faces.len(),
                        GroupItem::Surface(_) => self.surfaces += 1,
                        _ => {}
                    }
                }
            }
            Geometry::Trilist(t) => self.trilist_triangles += t.triangles.indices.len() / 3,
            Geometry::Hair(h) => self.hairs += h.offsets.len().saturating_sub(1),
        }
    }
}
