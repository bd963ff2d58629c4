//! The printer's geometry half: objects, groups, free-form surfaces, subdivision surfaces,
//! approximations, trilists and hair, written back as `.mi` text.

use std::io::Write;

use super::{float, float32, num, quote, Printer};
use crate::ast::*;

impl Printer {
    pub(super) fn object(&mut self, o: &Object) {
        self.block_open("object", &o.name);
        for s in &o.stmts {
            self.stmt(s);
        }
        for b in &o.bases {
            self.line();
            self.w("basis");
            self.name(&b.name);
            if b.rational {
                self.sp("rational");
            }
            match &b.kind {
                BasisKind::Bezier(d) => self.sp(&format!("bezier {d}")),
                BasisKind::Taylor(d) => self.sp(&format!("taylor {d}")),
                BasisKind::Bspline(d) => self.sp(&format!("bspline {d}")),
                BasisKind::Cardinal => self.sp("cardinal"),
                BasisKind::Matrix { degree, step, values } => {
                    self.sp(&format!("matrix {degree} {step}"));
                    for v in values {
                        self.sp(&float(*v));
                    }
                }
            }
        }
        for g in &o.geometry {
            match g {
                Geometry::Group(g) => self.group(g, o.is_tagged()),
                Geometry::Trilist(t) => self.trilist(t),
                Geometry::Hair(h) => self.hair(h),
            }
        }
        self.block_close("object");
    }

    fn group(&mut self, g: &Group, tagged: bool) {
        self.line();
        self.w("group");
        if let Some(n) = &g.name {
            self.name(n);
        }
        if let Some(m) = g.merge {
            self.sp(&format!("merge {}", float(m)));
        }
        self.indent += 1;
        for v in &g.vectors {
            self.line();
            let _ = write!(self.out, "{} {} {}", float32(v[0]), float32(v[1]), float32(v[2]));
        }
        for (i, v) in g.vertices.iter().enumerate() {
            self.line();
            let _ = write!(self.out, "v {}", v.pos);
            if let Some(n) = v.normal {
                let _ = write!(self.out, " n {n}");
            }
            for a in g.vertex_attrs(i) {
                match a {
                    VertexAttr::Deriv { count, idx } => {
                        self.w(" d");
                        for i in &idx[..*count as usize] {
                            let _ = write!(self.out, " {i}");
                        }
                    }
                    VertexAttr::Tex { index, basis } => {
                        let _ = write!(self.out, " t {index}");
                        if let Some([u, v]) = basis {
                            let _ = write!(self.out, " {u} {v}");
                        }
                    }
                    VertexAttr::Motion(m) => {
                        let _ = write!(self.out, " m {m}");
                    }
                    VertexAttr::User(u) => {
                        let _ = write!(self.out, " u {u}");
                    }
                    VertexAttr::Feature { kind, arg } => {
                        self.w(match kind {
                            FeatureKind::Cusp => " cusp",
                            FeatureKind::Conic => " conic",
                            FeatureKind::Corner => " corner",
                            FeatureKind::Dart => " dart",
                        });
                        match arg {
                            Some(FeatureArg::Level(l)) => {
                                let _ = write!(self.out, " level {l}");
                            }
                            Some(FeatureArg::Value(v)) => {
                                let _ = write!(self.out, " {}", num(*v));
                            }
                            None => {}
                        }
                    }
                }
            }
        }
        let polys = &g.polygons;
        for (i, p) in polys.list.iter().enumerate() {
            self.line();
            self.w(match p.kind {
                PolygonKind::Convex => "c",
                PolygonKind::ConvexLegacy => "cp",
                PolygonKind::General => "p",
                PolygonKind::Strip => "strip",
                PolygonKind::Fan => "fan",
            });
            match p.material {
                PolygonMaterial::Inherit => {}
                PolygonMaterial::Named(m) => {
                    let q = quote(&polys.material_names[m as usize].text);
                    self.sp(&q);
                }
                PolygonMaterial::Label(l) => {
                    let _ = write!(self.out, " {l}");
                }
            }
            for (j, lp) in polys.loops(i).enumerate() {
                if j > 0 {
                    self.w(" hole");
                }
                for idx in lp {
                    let _ = write!(self.out, " {idx}");
                }
            }
        }
        for item in &g.items {
            match item {
                GroupItem::Subdivision(s) => self.subdivision(s, tagged),
                GroupItem::Ccmesh(c) => self.ccmesh(c),
                GroupItem::Curve(c) => {
                    self.line();
                    self.w("curve");
                    self.name(&c.name);
                    if c.rational {
                        self.sp("rational");
                    }
                    self.name(&c.basis);
                    self.knots(&c.params);
                    self.vertex_refs(&c.refs);
                    if let Some(sp) = &c.special {
                        self.sp("special");
                        self.special(sp);
                    }
                }
                GroupItem::SpaceCurve(s) => {
                    self.line();
                    self.w("space curve");
                    self.name(&s.name);
                    self.segments(&s.segments);
                }
                GroupItem::Surface(s) => self.surface(s),
                GroupItem::Connect(c) => {
                    self.line();
                    self.w("connect");
                    self.name(&c.first.0);
                    self.segments(std::slice::from_ref(&c.first.1));
                    self.name(&c.second.0);
                    self.segments(std::slice::from_ref(&c.second.1));
                }
                GroupItem::Approximate(a) => {
                    self.line();
                    self.approximation(a, true);
                }
            }
        }
        self.indent -= 1;
        self.line();
        self.w("end group");
    }

    fn face_material(&mut self, m: &FaceMaterial) {
        match m {
            FaceMaterial::Inherit => {}
            FaceMaterial::Named(n) => self.name(n),
            FaceMaterial::Label(l) => self.sp(&l.to_string()),
        }
    }

    fn derivatives(&mut self, ds: &[Derivative]) {
        for d in ds {
            self.line();
            self.w(&format!("derivative {}", d.order));
            if let Some(s) = d.space {
                self.w(&format!(" space {s}"));
            }
        }
    }

    fn subdivision(&mut self, s: &SubdivSurface, _tagged: bool) {
        self.line();
        self.w("subdivision surface");
        self.name(&s.name);
        self.indent += 1;
        if let Some(c) = &s.counts {
            self.line();
            self.w("polygon");
            for n in c {
                self.sp(&n.to_string());
            }
        }
        if let Some(ts) = &s.texture_space {
            self.line();
            self.w("texture space");
            self.arg(&Arg::Names(ts.clone()));
        }
        for f in &s.faces {
            self.line();
            self.w(if f.quad_keyword { "q" } else { "p" });
            self.face_material(&f.material);
            for i in &f.indices {
                self.sp(&i.to_string());
            }
            for e in &f.extras {
                match e {
                    FaceExtra::Crease { mask, values } => {
                        self.sp(&format!("crease {mask}"));
                        for v in values {
                            self.sp(&float(*v));
                        }
                    }
                    FaceExtra::Trim(m) => self.sp(&format!("trim {m}")),
                    FaceExtra::Hierarchy(h) => self.hira(h),
                }
            }
        }
        self.derivatives(&s.derivatives);
        self.indent -= 1;
        self.line();
        self.w("end subdivision surface");
    }

    fn hira(&mut self, body: &[Hira]) {
        self.sp("{");
        self.indent += 1;
        for h in body {
            self.line();
            match h {
                Hira::Material { child, material } => {
                    self.w(&format!("material {child}"));
                    self.face_material(material);
                }
                Hira::Detail { mask, indices } => {
                    self.w(&format!("detail {mask}"));
                    for i in indices {
                        self.sp(&i.to_string());
                    }
                }
                Hira::Crease { child, mask, values } => {
                    self.w(&format!("crease {child} {mask}"));
                    for v in values {
                        self.sp(&float(*v));
                    }
                }
                Hira::Trim { child, mask } => self.w(&format!("trim {child} {mask}")),
                Hira::Child { child, body } => {
                    self.w(&format!("child {child}"));
                    self.hira(body);
                }
            }
        }
        self.indent -= 1;
        self.line();
        self.w("}");
    }

    fn ccmesh(&mut self, c: &Ccmesh) {
        self.line();
        self.w("ccmesh");
        self.name(&c.name);
        self.sp(&format!("polygon {} vertex {}", c.polygon_count, c.vertex_count));
        self.indent += 1;
        let (mut start, mut cstart) = (0usize, 0usize);
        for f in &c.faces {
            self.line();
            self.w("p");
            match f.material {
                PolygonMaterial::Inherit => {}
                PolygonMaterial::Named(m) => {
                    let q = quote(&c.material_names[m as usize].text);
                    self.sp(&q);
                }
                PolygonMaterial::Label(l) => self.sp(&l.to_string()),
            }
            for i in &c.indices[start..f.end as usize] {
                self.sp(&i.to_string());
            }
            if f.has_crease {
                self.sp("crease");
                for v in &c.creases[cstart..f.crease_end as usize] {
                    self.sp(&float32(*v));
                }
            }
            start = f.end as usize;
            cstart = f.crease_end as usize;
        }
        self.derivatives(&c.derivatives);
        self.indent -= 1;
        self.line();
        self.w("end ccmesh");
    }

    fn knots(&mut self, params: &[f64]) {
        for p in params {
            // Knots must be written as floats: an integer would start the vertex list.
            self.sp(&float(*p));
        }
    }

    fn vertex_refs(&mut self, refs: &[VertexRef]) {
        for r in refs {
            self.sp(&r.index.to_string());
            match r.weight {
                Some((true, w)) => self.sp(&format!("w {}", float(w))),
                Some((false, w)) => self.sp(&float(w)),
                None => {}
            }
        }
    }

    fn segments(&mut self, segs: &[CurveSegment]) {
        for s in segs {
            self.name(&s.curve);
            self.sp(&float(s.t0));
            self.sp(&float(s.t1));
        }
    }

    fn special(&mut self, points: &[SpecialPoint]) {
        for p in points {
            match p {
                SpecialPoint::Vertex(i) => self.sp(&i.to_string()),
                SpecialPoint::MapsTo(a, b) => self.sp(&format!("{a} mapsto {b}")),
                SpecialPoint::Curve(s) => self.segments(std::slice::from_ref(s)),
            }
        }
    }

    fn surface_dir(&mut self, d: &SurfaceDir) {
        if d.rational {
            self.sp("rational");
        }
        self.name(&d.basis);
        if let Some((a, b)) = d.range {
            self.sp(&float(a));
            self.sp(&float(b));
        }
        self.knots(&d.params);
    }

    fn surface(&mut self, s: &Surface) {
        self.line();
        self.w("surface");
        self.name(&s.name);
        self.face_material(&s.material);
        self.indent += 1;
        self.line();
        self.surface_dir(&s.u);
        self.line();
        self.surface_dir(&s.v);
        self.line();
        self.vertex_refs(&s.refs);
        for e in &s.extras {
            self.line();
            match e {
                SurfaceExtra::Texture { volume, vector, u, v, refs } => {
                    if *volume {
                        self.sp("volume");
                    }
                    if *vector {
                        self.sp("vector");
                    }
                    self.sp("texture");
                    self.surface_dir(u);
                    self.surface_dir(v);
                    self.vertex_refs(refs);
                }
                SurfaceExtra::Derivative(n) => {
                    self.w("derivative");
                    for i in n {
                        self.sp(&i.to_string());
                    }
                }
                SurfaceExtra::Trim(segs) => {
                    self.w("trim");
                    self.segments(segs);
                }
                SurfaceExtra::Hole(segs) => {
                    self.w("hole");
                    self.segments(segs);
                }
                SurfaceExtra::Special(points) => {
                    self.w("special");
                    self.special(points);
                }
            }
        }
        self.indent -= 1;
    }

    pub(super) fn approximation(&mut self, a: &Approximation, with_keyword: bool) {
        for f in &a.flags {
            self.sp(f);
        }
        if with_keyword {
            self.sp("approximate");
        }
        if let Some(t) = a.target {
            self.sp(t);
        }
        for term in &a.technique {
            match term {
                ApproxTerm::Word(w) => self.sp(w),
                ApproxTerm::Num(n) => self.sp(&num(*n)),
                ApproxTerm::Percent => self.w("%"),
            }
        }
        for n in &a.names {
            self.name(n);
        }
        if a.all {
            self.sp("all");
        }
    }

    fn trilist(&mut self, t: &Trilist) {
        self.line();
        self.w(&format!("trilist vertex {}", t.vertex_count));
        for l in &t.layout {
            match l {
                LayoutItem::P => self.w(" p"),
                LayoutItem::N => self.w(" n"),
                LayoutItem::D => self.w(" d"),
                LayoutItem::D2 => self.w(" d2"),
                LayoutItem::M(k) | LayoutItem::B(k) => {
                    self.w(if matches!(l, LayoutItem::M(_)) { " m" } else { " b" });
                    if let Some(k) = k {
                        self.w(&format!(" {k}"));
                    }
                }
                LayoutItem::T(d) | LayoutItem::U(d) => {
                    self.w(if matches!(l, LayoutItem::T(_)) { " t" } else { " u" });
                    for x in d {
                        self.w(&format!(" {x}"));
                    }
                }
            }
        }
        self.indent += 1;
        self.line();
        self.w(&format!("triangle {}", t.triangle_count));
        if let Some(b) = t.border_count {
            self.w(&format!(" border {b}"));
        }
        if let Some((a, b)) = t.data_sizes {
            self.w(&format!(" data {a} {b}"));
        }
        self.line();
        self.w("[");
        let per_line = t.floats_per_line().max(1);
        self.indent += 1;
        for line in t.floats.chunks(per_line) {
            self.line();
            for (i, f) in line.iter().enumerate() {
                if i > 0 {
                    self.w(" ");
                }
                self.w(&float32(*f));
            }
        }
        self.indent -= 1;
        self.line();
        self.w("]");
        self.triangles(&t.triangles);
        if let Some(b) = &t.border {
            self.triangles(b);
        }
        if let Some((a, b)) = &t.triangle_data {
            self.line();
            self.w("triangle data");
            self.word_block(a);
            self.word_block(b);
        }
        if let Some(top) = &t.topology {
            self.line();
            self.w("topology");
            self.word_block(top);
        }
        self.indent -= 1;
        self.line();
        self.w("end trilist");
    }

    fn word_block(&mut self, words: &[u32]) {
        self.sp("[");
        for w in words {
            self.sp(&w.to_string());
        }
        self.sp("]");
    }

    fn triangles(&mut self, tris: &Triangles) {
        self.line();
        self.w("[");
        self.indent += 1;
        let mut materials = tris.materials.iter().flatten().peekable();
        for (i, tri) in tris.indices.chunks(3).enumerate() {
            self.line();
            while let Some((at, name)) = materials.next_if(|(at, _)| *at as usize <= i) {
                let _ = at;
                let q = quote(&name.text);
                self.w(&q);
                self.w(" ");
            }
            if let Some(labels) = &tris.labels {
                let _ = write!(self.out, "{} ", labels[i]);
            }
            let _ = write!(self.out, "{}", tri.iter().map(u32::to_string).collect::<Vec<_>>().join(" "));
        }
        self.indent -= 1;
        self.line();
        self.w("]");
    }

    fn hair(&mut self, h: &Hair) {
        self.line();
        self.w("hair");
        self.indent += 1;
        for s in &h.header {
            self.line();
            self.kw(s);
        }
        self.line();
        self.w(&format!("scalar [ {} ]", h.scalars.len()));
        for chunk in h.scalars.chunks(8) {
            self.line();
            self.w(&chunk.iter().map(|f| float32(*f)).collect::<Vec<_>>().join(" "));
        }
        self.line();
        self.w(&format!("hair [ {} ]", h.offsets.len()));
        for chunk in h.offsets.chunks(16) {
            self.line();
            self.w(&chunk.iter().map(u32::to_string).collect::<Vec<_>>().join(" "));
        }
        self.indent -= 1;
        self.line();
        self.w("end hair");
    }
}
