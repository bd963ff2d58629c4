//! Objects and their geometry: groups (vectors, vertices, polygons, subdivision surfaces,
//! ccmeshes, free-form curves and surfaces), trilists and hair.
//!
//! Vectors, vertex lines, polygons and trilist data are read straight from the lexer
//! (no token objects), which is what lets million-polygon files parse at hundreds of MB/s.

use super::{PResult, Parser};
use crate::ast::*;
use crate::diag::Diagnostic;
use crate::grammar;
use crate::lexer::{Lexer, Tok};
use crate::source::Span;

/// Reserves room for `count` items of which each needs at least `min_bytes` of text, never
/// more than the rest of the file could hold: a hostile count cannot allocate unboundedly.
fn reserve_for<T>(v: &mut Vec<T>, count: usize, remaining_bytes: usize, min_bytes: usize) {
    v.reserve(count.min(remaining_bytes / min_bytes.max(1) + 1));
}

impl Parser {
    /// The lexer for a fast path, or an error if buffered tokens straddle an include.
    fn lexer(&mut self) -> PResult<&mut Lexer> {
        let span = self.peek()?.span;
        self.ts
            .fast_lexer()
            .ok_or_else(|| Diagnostic::error(span, "geometry data may not straddle an '$include' boundary"))
    }

    /// `object "name" … end object`.
    pub fn object(&mut self) -> PResult<Object> {
        let start = self.expect("object")?;
        self.ends.push("object");
        // The name is optional in the grammar: an object may start with its flags.
        let next = self.peek()?;
        let unnamed = next.tok == Tok::Name
            && (["group", "trilist", "hair", "basis", "end", "attribute"].iter().any(|w| self.is(&next, w))
                || self.match_rule(&[grammar::OBJECT])?.is_some());
        let name = if unnamed { Name { text: String::new(), span: next.span.start() } } else { self.name()? };
        let mut object = Object { name, stmts: Vec::new(), bases: Vec::new(), geometry: Vec::new(), span: start };
        loop {
            self.not_eof("object", start)?;
            if self.at_end("object")? {
                let end = self.expect_end("object")?;
                self.ends.pop();
                object.span = start.to(end);
                return Ok(object);
            }
            let t = self.peek()?;
            if self.is(&t, "group") {
                let tagged = object.is_tagged();
                object.geometry.push(Geometry::Group(self.group(tagged)?));
            } else if self.is(&t, "trilist") {
                let tagged = object.is_tagged();
                object.geometry.push(Geometry::Trilist(self.trilist(tagged)?));
            } else if self.is(&t, "hair") {
                object.geometry.push(Geometry::Hair(self.hair()?));
            } else if self.is(&t, "basis") {
                object.bases.push(self.basis()?);
            } else if self.is(&t, "attribute") {
                object.stmts.push(Stmt::Attribute(self.attribute()?));
            } else if self.at_approximate()? {
                let a = self.approximate_stmt()?;
                let span = a.span;
                object.stmts.push(Stmt::Kw(KwStmt { key: "approximate", args: vec![Arg::Approx(Box::new(a))], span }));
            } else if let Some(s) = self.kw_stmt(&[grammar::OBJECT])? {
                object.stmts.push(Stmt::Kw(s));
            } else {
                return Err(Diagnostic::error(t.span, format!("unknown object statement {}", self.describe(&t))));
            }
        }
    }

    /// `basis "name" [rational] bezier N | taylor N | bspline N | cardinal | matrix D S values…`
    fn basis(&mut self) -> PResult<Basis> {
        let start = self.expect("basis")?;
        let name = self.name()?;
        let rational = self.eat("rational")?;
        let t = self.peek()?;
        let kind = match self.bytes(&t) {
            b"bezier" => {
                self.bump()?;
                BasisKind::Bezier(self.int()?)
            }
            b"taylor" => {
                self.bump()?;
                BasisKind::Taylor(self.int()?)
            }
            b"bspline" => {
                self.bump()?;
                BasisKind::Bspline(self.int()?)
            }
            b"cardinal" => {
                self.bump()?;
                BasisKind::Cardinal
            }
            b"matrix" => {
                self.bump()?;
                let degree = self.int()?;
                let step = self.int()?;
                let mut values = Vec::new();
                while self.at_number()? {
                    values.push(self.float()?);
                }
                BasisKind::Matrix { degree, step, values }
            }
            _ => return self.expected("'bezier', 'bspline', 'taylor', 'cardinal' or 'matrix'"),
        };
        let end = self.peek()?.span;
        Ok(Basis { name, rational, kind, span: start.to(end.start()) })
    }

    // ----- group -----

    /// `group ["name"] [merge ε] … end group`.
    fn group(&mut self, tagged: bool) -> PResult<Group> {
        let start = self.expect("group")?;
        let mut group = Group::default();
        let next = self.peek()?;
        let unquoted_name = next.tok == Tok::Name
            && ![
                "v",
                "c",
                "cp",
                "p",
                "strip",
                "fan",
                "end",
                "subdivision",
                "ccmesh",
                "curve",
                "space",
                "surface",
                "connect",
                "merge",
                "approximate",
                "visible",
                "trace",
                "shadow",
                "caustic",
                "globillum",
            ]
            .iter()
            .any(|w| self.is(&next, w));
        if self.at_str()? || unquoted_name {
            group.name = Some(self.name()?);
        }
        if self.eat("merge")? {
            group.merge = Some(self.float()?);
        }
        loop {
            self.not_eof("group", start)?;
            let t = self.peek()?;
            match t.tok {
                Tok::Int(_) | Tok::Float(_) | Tok::Binary => {
                    self.vectors(&mut group.vectors)?;
                    continue;
                }
                Tok::Name => {}
                _ => return Err(Diagnostic::error(t.span, format!("unexpected {} in a group", self.describe(&t)))),
            }
            let word = self.bytes(&t).to_vec();
            match word.as_slice() {
                b"v" => self.vertices(&mut group)?,
                b"c" | b"cp" | b"p" | b"strip" | b"fan" => self.polygons(&mut group.polygons, tagged)?,
                b"end" if self.at_words("end group")? => {
                    let end = self.expect_end("group")?;
                    group.span = start.to(end);
                    return Ok(group);
                }
                b"subdivision" => group.items.push(GroupItem::Subdivision(self.subdivision(tagged)?)),
                b"ccmesh" => group.items.push(GroupItem::Ccmesh(self.ccmesh(tagged)?)),
                b"curve" => group.items.push(GroupItem::Curve(self.curve()?)),
                b"space" => group.items.push(GroupItem::SpaceCurve(self.space_curve()?)),
                b"surface" => group.items.push(GroupItem::Surface(self.surface(tagged)?)),
                b"connect" => group.items.push(GroupItem::Connect(self.connect()?)),
                _ if self.at_approximate()? => group.items.push(GroupItem::Approximate(self.approximate_stmt()?)),
                _ => return Err(Diagnostic::error(t.span, format!("unknown group statement {}", self.describe(&t)))),
            }
        }
    }

    /// A run of vectors: three numbers each, or 12-byte binary blocks.
    fn vectors(&mut self, out: &mut Vec<[f32; 3]>) -> PResult<()> {
        loop {
            let lx = self.lexer()?;
            while let Some(x) = lx.try_f32()? {
                let (Some(y), Some(z)) = (lx.try_f32()?, lx.try_f32()?) else {
                    return Err(at_lexer(lx, "a vector needs three numbers; the third is missing here"));
                };
                out.push([x, y, z]);
            }
            match self.peek()?.tok {
                Tok::Binary => out.push(self.binary_vector()?),
                Tok::Int(_) | Tok::Float(_) => {
                    // After a directive: read one generically, then go fast again.
                    let v = [self.float()? as f32, self.float()? as f32, self.float()? as f32];
                    out.push(v);
                }
                _ => return Ok(()),
            }
        }
    }

    /// A run of `v …` vertex lines.
    fn vertices(&mut self, group: &mut Group) -> PResult<()> {
        #[derive(Clone, Copy, PartialEq)]
        enum W {
            N,
            D,
            T,
            M,
            U,
            Feature(FeatureKind),
        }
        let lx = self.lexer()?;
        // The vertex being read: (position, normal); pushed when the next one starts.
        let mut current: Option<(u32, Option<u32>)> = None;
        loop {
            let (w, len) = match lx.peek_word() {
                Some(b"v") => {
                    if let Some((pos, normal)) = current {
                        group.vertices.push(Vertex { pos, normal, attrs_end: group.vertex_attrs.len() as u32 });
                    }
                    lx.skip_bytes(1);
                    current = Some((need_u32(lx, "a vector index after 'v'")?, None));
                    continue;
                }
                _ if current.is_none() => break,
                Some(b"n") => (W::N, 1),
                Some(b"d") => (W::D, 1),
                Some(b"t") => (W::T, 1),
                Some(b"m") => (W::M, 1),
                Some(b"u") => (W::U, 1),
                Some(b"cusp") => (W::Feature(FeatureKind::Cusp), 4),
                Some(b"conic") => (W::Feature(FeatureKind::Conic), 5),
                Some(b"corner") => (W::Feature(FeatureKind::Corner), 6),
                Some(b"dart") => (W::Feature(FeatureKind::Dart), 4),
                _ => break,
            };
            let Some((_, normal)) = current.as_mut() else { break };
            if w == W::N && normal.is_some() {
                break;
            }
            lx.skip_bytes(len);
            match w {
                W::N => *normal = Some(need_u32(lx, "a normal vector index after 'n'")?),
                W::D => {
                    let mut idx = [0u32; 5];
                    let mut count = 0;
                    while count < 5 {
                        let Some(i) = lx.try_u32()? else { break };
                        idx[count] = i;
                        count += 1;
                    }
                    if !matches!(count, 2 | 3 | 5) {
                        return Err(at_lexer(lx, "'d' takes 2, 3 or 5 vector indices"));
                    }
                    group.vertex_attrs.push(VertexAttr::Deriv { count: count as u8, idx });
                }
                W::T => {
                    let index = need_u32(lx, "a texture vector index after 't'")?;
                    let basis = match lx.try_u32()? {
                        Some(bu) => Some([bu, need_u32(lx, "the bump basis v vector index")?]),
                        None => None,
                    };
                    group.vertex_attrs.push(VertexAttr::Tex { index, basis });
                }
                W::M => group.vertex_attrs.push(VertexAttr::Motion(need_u32(lx, "a motion vector index after 'm'")?)),
                W::U => group.vertex_attrs.push(VertexAttr::User(need_u32(lx, "a user vector index after 'u'")?)),
                W::Feature(kind) => {
                    let arg = if lx.peek_word() == Some(b"level") {
                        lx.skip_bytes(5);
                        let t = lx.next_token()?;
                        match t.tok {
                            Tok::Int(v) => Some(FeatureArg::Level(v)),
                            _ => return Err(Diagnostic::error(t.span, "expected an integer after 'level'")),
                        }
                    } else if matches!(lx.peek_byte(), Some(b'0'..=b'9' | b'.' | b'-' | b'+')) {
                        let t = lx.next_token()?;
                        match t.tok {
                            Tok::Int(v) => Some(FeatureArg::Value(Num::Int(v))),
                            Tok::Float(v) => Some(FeatureArg::Value(Num::Float(v))),
                            _ => return Err(Diagnostic::error(t.span, "expected a number")),
                        }
                    } else {
                        None
                    };
                    group.vertex_attrs.push(VertexAttr::Feature { kind, arg });
                }
            }
        }
        if let Some((pos, normal)) = current {
            group.vertices.push(Vertex { pos, normal, attrs_end: group.vertex_attrs.len() as u32 });
        }
        Ok(())
    }

    /// A run of polygon statements.
    fn polygons(&mut self, polys: &mut Polygons, tagged: bool) -> PResult<()> {
        let file = self.peek()?.span.file;
        let lx = self.lexer()?;
        loop {
            let Some(word) = lx.peek_word() else { return Ok(()) };
            let word_len = word.len();
            let kind = match word {
                b"c" => PolygonKind::Convex,
                b"cp" => PolygonKind::ConvexLegacy,
                b"p" => PolygonKind::General,
                b"strip" => PolygonKind::Strip,
                b"fan" => PolygonKind::Fan,
                _ => return Ok(()),
            };
            let start = lx.pos;
            lx.skip_bytes(word_len);
            let material = if tagged {
                PolygonMaterial::Label(need_u32(lx, "the polygon's label (the object is tagged)")?)
            } else if matches!(lx.peek_byte(), Some(b'"')) {
                let t = lx.next_token()?;
                let b = &lx.src()[t.span.lo as usize + 1..t.span.hi as usize - 1];
                let text = match t.tok {
                    Tok::Str { escaped: true } => crate::lexer::unescape(b),
                    _ => crate::lexer::bytes_to_string(b.to_vec()),
                };
                let index = match polys.material_names.iter().rposition(|n| n.text == text) {
                    Some(i) => i,
                    None => {
                        polys.material_names.push(Name { text, span: t.span });
                        polys.material_names.len() - 1
                    }
                };
                PolygonMaterial::Named(index as u32)
            } else {
                PolygonMaterial::Inherit
            };
            polys.begin(kind, material, Offset(start as u32));
            loop {
                let before = polys.indices.len();
                while let Some(i) = lx.try_u32()? {
                    polys.indices.push(i);
                }
                if polys.indices.len() == before {
                    return Err(Diagnostic::error(
                        Span::new(file, start as u32, lx.pos as u32),
                        "polygon (or hole) has no vertex indices",
                    ));
                }
                polys.push_loop();
                if kind == PolygonKind::General && lx.peek_word() == Some(b"hole") {
                    lx.skip_bytes(4);
                    continue;
                }
                break;
            }
        }
    }

    /// A face's material: a label in tagged objects, else an optional name.
    fn face_material(&mut self, tagged: bool) -> PResult<FaceMaterial> {
        if tagged {
            return Ok(FaceMaterial::Label(self.uint("the face's label (the object is tagged)")?));
        }
        if self.at_str()? {
            return Ok(FaceMaterial::Named(self.name()?));
        }
        Ok(FaceMaterial::Inherit)
    }

    /// Non-negative integers while they come.
    fn indices(&mut self, out: &mut Vec<u32>) -> PResult<()> {
        while matches!(self.peek()?.tok, Tok::Int(_)) {
            out.push(self.uint("a vertex index")?);
        }
        Ok(())
    }

    /// Numbers while they come (crease sharpness values: one per set mask bit as a rule).
    fn floats_while(&mut self) -> PResult<Vec<f64>> {
        let mut v = Vec::new();
        while self.at_number()? {
            v.push(self.float()?);
        }
        Ok(v)
    }

    /// `derivative n [space m]` statements.
    fn derivatives(&mut self) -> PResult<Vec<Derivative>> {
        let mut out = Vec::new();
        while self.eat("derivative")? {
            let order = self.int()?;
            let space = if self.eat("space")? { Some(self.int()?) } else { None };
            out.push(Derivative { order, space });
        }
        Ok(out)
    }

    /// `subdivision surface "name" … end subdivision surface`.
    fn subdivision(&mut self, tagged: bool) -> PResult<SubdivSurface> {
        let start = self.expect("subdivision")?;
        self.expect("surface")?;
        let name = self.name()?;
        let mut surf = SubdivSurface {
            name,
            counts: None,
            texture_space: None,
            faces: Vec::new(),
            derivatives: Vec::new(),
            span: start,
        };
        loop {
            if self.eat("polygon")? {
                let mut counts = Vec::new();
                while matches!(self.peek()?.tok, Tok::Int(_)) && counts.len() < 4 {
                    counts.push(self.int()?);
                }
                surf.counts = Some(counts);
            } else if self.at_words("texture space")? {
                self.bump()?;
                self.bump()?;
                let mut spaces = Vec::new();
                if self.peek()?.tok == Tok::LBracket {
                    spaces = self.name_list()?;
                } else {
                    while self.at("vertex")? || self.at("face")? || self.at("subdivision")? {
                        spaces.push(self.name()?);
                        self.eat_tok(Tok::Comma)?;
                    }
                }
                surf.texture_space = Some(spaces);
            } else {
                break;
            }
        }
        loop {
            self.not_eof("subdivision surface", start)?;
            let t = self.peek()?;
            if self.is(&t, "p") || self.is(&t, "q") {
                self.bump()?;
                let material = self.face_material(tagged)?;
                let mut indices = Vec::new();
                self.indices(&mut indices)?;
                if indices.is_empty() {
                    return self.expected("the face's vertex indices");
                }
                let mut extras = Vec::new();
                loop {
                    if self.eat("crease")? {
                        let mask = self.uint("a crease edge mask")?;
                        let values = self.floats_while()?;
                        extras.push(FaceExtra::Crease { mask, values });
                    } else if self.eat("trim")? {
                        extras.push(FaceExtra::Trim(self.uint("a trim edge mask")?));
                    } else if self.peek()?.tok == Tok::LBrace {
                        extras.push(FaceExtra::Hierarchy(self.hierarchy()?));
                    } else {
                        break;
                    }
                }
                surf.faces.push(SubdivFace {
                    quad_keyword: self.is(&t, "q"),
                    material,
                    indices,
                    extras,
                    offset: Offset(t.span.lo),
                });
            } else if self.is(&t, "derivative") {
                surf.derivatives.extend(self.derivatives()?);
            } else if self.at_end("subdivision surface")? {
                let end = self.expect_end("subdivision surface")?;
                surf.span = start.to(end);
                return Ok(surf);
            } else {
                return Err(Diagnostic::error(
                    t.span,
                    format!("unknown subdivision surface statement {}", self.describe(&t)),
                ));
            }
        }
    }

    /// `{ … }`: a subdivision face's refinement hierarchy.
    fn hierarchy(&mut self) -> PResult<Vec<Hira>> {
        let open = self.expect_tok(Tok::LBrace, "'{'")?;
        self.enter(open)?;
        let mut body = Vec::new();
        loop {
            let t = self.peek()?;
            if t.tok == Tok::RBrace {
                self.bump()?;
                self.leave();
                return Ok(body);
            }
            let word = self.bytes(&t).to_vec();
            let item = match (t.tok, word.as_slice()) {
                (Tok::Name, b"material") => {
                    self.bump()?;
                    let child = self.int()?;
                    let material = if self.at_str()? {
                        FaceMaterial::Named(self.name()?)
                    } else {
                        FaceMaterial::Label(self.uint("a label")?)
                    };
                    Hira::Material { child, material }
                }
                (Tok::Name, b"detail") => {
                    self.bump()?;
                    let mask = self.uint("a detail vertex mask")?;
                    let mut indices = Vec::new();
                    self.indices(&mut indices)?;
                    Hira::Detail { mask, indices }
                }
                (Tok::Name, b"crease") => {
                    self.bump()?;
                    let child = self.int()?;
                    let mask = self.uint("a crease edge mask")?;
                    let values = self.floats_while()?;
                    Hira::Crease { child, mask, values }
                }
                (Tok::Name, b"trim") => {
                    self.bump()?;
                    let child = self.int()?;
                    let mask = self.uint("a trim edge mask")?;
                    Hira::Trim { child, mask }
                }
                (Tok::Name, b"child") => {
                    self.bump()?;
                    let child = self.int()?;
                    let body = self.hierarchy()?;
                    Hira::Child { child, body }
                }
                (Tok::Eof, _) => {
                    return Err(Diagnostic::error(open, "hierarchy is not closed by '}'")
                        .with_note(Some(t.span), "the file ends here"))
                }
                _ => {
                    return Err(Diagnostic::error(
                        t.span,
                        format!(
                            "expected 'detail', 'crease', 'trim', 'material', 'child' or '}}', found {}",
                            self.describe(&t)
                        ),
                    ))
                }
            };
            body.push(item);
        }
    }

    /// `ccmesh "name" polygon N vertex M … end ccmesh`.
    fn ccmesh(&mut self, tagged: bool) -> PResult<Ccmesh> {
        let start = self.expect("ccmesh")?;
        let name = self.name()?;
        self.expect("polygon")?;
        let polygon_count = self.uint("the polygon count")?;
        self.expect("vertex")?;
        let vertex_count = self.uint("the vertex reference count")?;
        let remaining = self.lexer()?.remaining();
        let mut mesh = Ccmesh {
            name,
            polygon_count,
            vertex_count,
            faces: Vec::new(),
            indices: Vec::new(),
            creases: Vec::new(),
            material_names: Vec::new(),
            derivatives: Vec::new(),
            span: start,
        };
        reserve_for(&mut mesh.faces, polygon_count as usize, remaining, 4);
        reserve_for(&mut mesh.indices, vertex_count as usize, remaining, 2);
        loop {
            self.not_eof("ccmesh", start)?;
            let t = self.peek()?;
            if self.is(&t, "p") {
                self.bump()?;
                let material = if tagged {
                    PolygonMaterial::Label(self.uint("the face's label (the object is tagged)")?)
                } else if self.at_str()? {
                    let n = self.name()?;
                    let i = match mesh.material_names.iter().rposition(|m| m.text == n.text) {
                        Some(i) => i,
                        None => {
                            mesh.material_names.push(n);
                            mesh.material_names.len() - 1
                        }
                    };
                    PolygonMaterial::Named(i as u32)
                } else {
                    PolygonMaterial::Inherit
                };
                let before = mesh.indices.len();
                self.indices(&mut mesh.indices)?;
                let count = mesh.indices.len() - before;
                if count == 0 {
                    return self.expected("the polygon's vertex indices");
                }
                let crease_at = self.peek()?.span;
                let has_crease = self.eat("crease")?;
                if has_crease {
                    // One sharpness per edge; files that give another count are read as
                    // written and warned about.
                    let before = mesh.creases.len();
                    while self.at_number()? {
                        mesh.creases.push(self.float()? as f32);
                    }
                    let given = mesh.creases.len() - before;
                    if given != count {
                        self.warn(crease_at, format!("ccmesh polygon has {count} edges but {given} crease values"));
                    }
                }
                mesh.faces.push(CcFace {
                    material,
                    end: mesh.indices.len() as u32,
                    crease_end: mesh.creases.len() as u32,
                    has_crease,
                    offset: Offset(t.span.lo),
                });
            } else if self.is(&t, "derivative") {
                mesh.derivatives.extend(self.derivatives()?);
            } else if self.at_end("ccmesh")? {
                let end = self.expect_end("ccmesh")?;
                mesh.span = start.to(end);
                if mesh.faces.len() != polygon_count as usize || mesh.indices.len() != vertex_count as usize {
                    self.warn(
                        start,
                        format!(
                            "ccmesh '{}' declares {} polygons and {} vertex references but holds {} and {}",
                            mesh.name.text,
                            polygon_count,
                            vertex_count,
                            mesh.faces.len(),
                            mesh.indices.len()
                        ),
                    );
                }
                return Ok(mesh);
            } else {
                return Err(Diagnostic::error(t.span, format!("unknown ccmesh statement {}", self.describe(&t))));
            }
        }
    }

    /// Knot values: float tokens only (an integer starts the vertex references).
    fn knots(&mut self) -> PResult<Vec<f64>> {
        let mut v = Vec::new();
        while let Tok::Float(x) = self.peek()?.tok {
            self.bump()?;
            v.push(x);
        }
        Ok(v)
    }

    /// Control-point references: `i`, `i weight`, `i w weight`.
    fn vertex_refs(&mut self) -> PResult<Vec<VertexRef>> {
        let mut refs = Vec::new();
        while matches!(self.peek()?.tok, Tok::Int(_)) {
            let index = self.uint("a vertex index")?;
            let weight = if self.at("w")? {
                self.bump()?;
                Some((true, self.float()?))
            } else if let Tok::Float(w) = self.peek()?.tok {
                self.bump()?;
                Some((false, w))
            } else {
                None
            };
            refs.push(VertexRef { index, weight });
        }
        Ok(refs)
    }

    /// `special` point list.
    fn special_points(&mut self) -> PResult<Vec<SpecialPoint>> {
        let mut points = Vec::new();
        loop {
            let t = self.peek()?;
            match t.tok {
                Tok::Int(_) => {
                    let i = self.uint("a vertex index")?;
                    if self.eat("mapsto")? {
                        points.push(SpecialPoint::MapsTo(i, self.uint("a vertex index")?));
                    } else {
                        points.push(SpecialPoint::Vertex(i));
                    }
                }
                Tok::Str { .. } => points.push(SpecialPoint::Curve(self.curve_segment()?)),
                _ => return Ok(points),
            }
        }
    }

    /// `"curve" t0 t1`
    fn curve_segment(&mut self) -> PResult<CurveSegment> {
        let curve = self.name()?;
        let t0 = self.float()?;
        let t1 = self.float()?;
        Ok(CurveSegment { curve, t0, t1 })
    }

    /// Curve segments while they come.
    fn curve_segments(&mut self) -> PResult<Vec<CurveSegment>> {
        let mut v = vec![self.curve_segment()?];
        while self.at_str()? {
            v.push(self.curve_segment()?);
        }
        Ok(v)
    }

    /// `curve "name" [rational] "basis" knots… refs… [special …]`
    fn curve(&mut self) -> PResult<Curve> {
        let start = self.expect("curve")?;
        let name = self.name()?;
        let rational = self.eat("rational")?;
        let basis = self.name()?;
        let params = self.knots()?;
        let refs = self.vertex_refs()?;
        let special = if self.eat("special")? { Some(self.special_points()?) } else { None };
        let end = self.peek()?.span;
        Ok(Curve { name, rational, basis, params, refs, special, span: start.to(end.start()) })
    }

    /// `space curve "name" "curve" t0 t1 …`
    fn space_curve(&mut self) -> PResult<SpaceCurve> {
        let start = self.expect("space")?;
        self.expect("curve")?;
        let name = self.name()?;
        let segments = self.curve_segments()?;
        let end = self.peek()?.span;
        Ok(SpaceCurve { name, segments, span: start.to(end.start()) })
    }

    /// `[rational] "basis" [min max] knots…`
    fn surface_dir(&mut self, ranged: bool) -> PResult<SurfaceDir> {
        let rational = self.eat("rational")?;
        let basis = self.name()?;
        let range = if ranged { Some((self.float()?, self.float()?)) } else { None };
        let params = self.knots()?;
        Ok(SurfaceDir { rational, basis, range, params })
    }

    /// `surface "name" mtl|label u v refs… extras…`
    fn surface(&mut self, tagged: bool) -> PResult<Surface> {
        let start = self.expect("surface")?;
        let name = self.name()?;
        let material = if matches!(self.peek()?.tok, Tok::Int(_)) {
            FaceMaterial::Label(self.uint("a label")?)
        } else {
            let _ = tagged;
            FaceMaterial::Named(self.name()?)
        };
        let u = self.surface_dir(true)?;
        let v = self.surface_dir(true)?;
        let refs = self.vertex_refs()?;
        let mut extras = Vec::new();
        loop {
            let t = self.peek()?;
            if self.is(&t, "volume") || self.is(&t, "vector") || self.is(&t, "texture") {
                let volume = self.eat("volume")?;
                let vector = self.eat("vector")?;
                self.expect("texture")?;
                let u = self.surface_dir(false)?;
                let v = self.surface_dir(false)?;
                let refs = self.vertex_refs()?;
                extras.push(SurfaceExtra::Texture { volume, vector, u, v, refs });
            } else if self.eat("derivative")? {
                let mut n = Vec::new();
                while n.len() < 2 && matches!(self.peek()?.tok, Tok::Int(_)) {
                    n.push(self.int()?);
                }
                extras.push(SurfaceExtra::Derivative(n));
            } else if self.eat("trim")? {
                extras.push(SurfaceExtra::Trim(self.curve_segments()?));
            } else if self.eat("hole")? {
                extras.push(SurfaceExtra::Hole(self.curve_segments()?));
            } else if self.eat("special")? {
                extras.push(SurfaceExtra::Special(self.special_points()?));
            } else {
                break;
            }
        }
        let end = self.peek()?.span;
        Ok(Surface { name, material, u, v, refs, extras, span: start.to(end.start()) })
    }

    /// `connect "s1" "c1" t0 t1 "s2" "c2" t0 t1`
    fn connect(&mut self) -> PResult<Connect> {
        let start = self.expect("connect")?;
        let s1 = self.name()?;
        let c1 = self.curve_segment()?;
        let s2 = self.name()?;
        let c2 = self.curve_segment()?;
        let end = self.peek()?.span;
        Ok(Connect { first: (s1, c1), second: (s2, c2), span: start.to(end.start()) })
    }

    // ----- trilist -----

    /// `trilist vertex N layout… triangle M … end trilist`.
    fn trilist(&mut self, tagged: bool) -> PResult<Trilist> {
        let start = self.expect("trilist")?;
        if self.at("vector")? {
            return Err(Diagnostic::error(
                start,
                "the mental ray 3.3 'trilist vector …' form is not read; use the 3.4 'trilist vertex …' form",
            ));
        }
        self.expect("vertex")?;
        let vertex_count = self.uint("the vertex line count")?;
        let mut layout = Vec::new();
        loop {
            let t = self.peek()?;
            let word = self.bytes(&t).to_vec();
            let item = match (t.tok, word.as_slice()) {
                (Tok::Name, b"p") => LayoutItem::P,
                (Tok::Name, b"n") => LayoutItem::N,
                (Tok::Name, b"d") => LayoutItem::D,
                (Tok::Name, b"d2") => LayoutItem::D2,
                (Tok::Name, b"m" | b"b") => {
                    self.bump()?;
                    let k = if matches!(self.peek()?.tok, Tok::Int(_)) { Some(self.uint("a count")?) } else { None };
                    layout.push(if word == b"m" { LayoutItem::M(k) } else { LayoutItem::B(k) });
                    continue;
                }
                (Tok::Name, b"t" | b"u") => {
                    self.bump()?;
                    let mut dims = Vec::new();
                    while matches!(self.peek()?.tok, Tok::Int(_)) {
                        dims.push(self.uint("a dimension")?);
                    }
                    layout.push(if word == b"t" { LayoutItem::T(dims) } else { LayoutItem::U(dims) });
                    continue;
                }
                _ => break,
            };
            self.bump()?;
            layout.push(item);
        }
        if layout.first() != Some(&LayoutItem::P) {
            return Err(Diagnostic::error(start, "a trilist vertex layout must start with 'p'"));
        }
        self.expect("triangle")?;
        let triangle_count = self.uint("the triangle count")?;
        let border_count = if self.eat("border")? { Some(self.uint("the border triangle count")?) } else { None };
        let data_sizes = if self.eat("data")? { Some((self.uint("a size")?, self.uint("a size")?)) } else { None };
        let mut list = Trilist {
            layout,
            vertex_count,
            triangle_count,
            border_count,
            data_sizes,
            floats: Vec::new(),
            triangles: Triangles::default(),
            border: None,
            triangle_data: None,
            topology: None,
            span: start,
        };
        let per_line = list.floats_per_line();
        let count =
            (vertex_count as usize).checked_mul(per_line).filter(|&n| n < u32::MAX as usize).ok_or_else(|| {
                Diagnostic::error(
                    start,
                    format!("trilist of {vertex_count} vertex lines of {per_line} numbers is too large"),
                )
            })?;
        // Vertex data.
        if self.eat("scalar")? {
            let t = self.bump()?;
            let span = self.binary_words(t, count, "vertex data")?;
            list.floats = be_f32s(self.ts.bytes(span));
        } else {
            let open = self.expect_tok(Tok::LBracket, "'[' or 'scalar' to start the vertex data")?;
            let remaining = self.lexer()?.remaining();
            if count > remaining / 2 + 1 {
                return Err(Diagnostic::error(
                    start,
                    format!("trilist declares {count} vertex numbers but only {remaining} bytes of the file are left"),
                ));
            }
            list.floats.reserve(count);
            self.float_block(&mut list.floats)?;
            if list.floats.len() != count {
                return Err(Diagnostic::error(
                    open,
                    format!(
                        "trilist vertex data holds {} numbers; {} lines of {} ({}) were declared",
                        list.floats.len(),
                        vertex_count,
                        per_line,
                        count
                    ),
                ));
            }
        }
        let at = self.peek()?.span;
        list.triangles = self.triangles(triangle_count, tagged, at)?;
        if let Some(n) = border_count {
            let at = self.peek()?.span;
            list.border = Some(self.triangles(n, tagged, at)?);
        }
        if self.at_words("triangle data")? {
            self.bump()?;
            self.bump()?;
            let (info, data) = data_sizes
                .map_or((None, None), |(i, d)| (Some(i as usize), (d as usize).checked_mul(triangle_count as usize)));
            let a = self.word_block(info)?;
            let b = self.word_block(data)?;
            list.triangle_data = Some((a, b));
        }
        if self.eat("topology")? {
            list.topology = Some(self.word_block((triangle_count as usize).checked_mul(3))?);
        }
        let end = self.expect_end("trilist")?;
        list.span = start.to(end);
        Ok(list)
    }

    /// `[ numbers… ]` read fast into `out` (the `[` already consumed).
    fn float_block(&mut self, out: &mut Vec<f32>) -> PResult<()> {
        loop {
            let lx = self.lexer()?;
            while let Some(x) = lx.try_f32()? {
                out.push(x);
            }
            let t = self.peek()?;
            match t.tok {
                Tok::RBracket => {
                    self.bump()?;
                    return Ok(());
                }
                Tok::Int(_) | Tok::Float(_) => out.push(self.float()? as f32),
                _ => return self.expected("a number or ']'"),
            }
        }
    }

    /// `[ integers… ]` read fast (the `[` not yet consumed); strings (per-triangle
    /// material names) are returned with the number of integers before them.
    fn int_block(&mut self, out: &mut Vec<u32>) -> PResult<Vec<(u32, Name)>> {
        self.expect_tok(Tok::LBracket, "'['")?;
        let mut names = Vec::new();
        loop {
            let lx = self.lexer()?;
            while let Some(x) = lx.try_u32()? {
                out.push(x);
            }
            let t = self.peek()?;
            match t.tok {
                Tok::RBracket => {
                    self.bump()?;
                    return Ok(names);
                }
                Tok::Int(_) => out.push(self.uint("a vertex index")?),
                Tok::Str { .. } => {
                    let n = self.name()?;
                    names.push((out.len() as u32, n));
                }
                _ => return self.expected("an integer or ']'"),
            }
        }
    }

    /// `[ ints ]` or `integer `…`` (of `words` words when known: the payload may then hold
    /// backquotes).
    fn word_block(&mut self, words: Option<usize>) -> PResult<Vec<u32>> {
        if self.eat("integer")? {
            let t = self.bump()?;
            if t.tok != Tok::Binary {
                return Err(Diagnostic::error(t.span, "expected a backquoted binary block"));
            }
            let payload = match words.and_then(|w| w.checked_mul(4)) {
                Some(len) => self.exact_binary(t, len)?,
                None => Span::new(t.span.file, t.span.lo + 1, t.span.hi - 1),
            };
            let bytes = self.ts.bytes(payload);
            if bytes.len() % 4 != 0 {
                return Err(Diagnostic::error(t.span, "binary block length is not a multiple of 4"));
            }
            return Ok(bytes.chunks_exact(4).map(|c| u32::from_be_bytes([c[0], c[1], c[2], c[3]])).collect());
        }
        let mut v = Vec::new();
        self.int_block(&mut v)?;
        Ok(v)
    }

    /// Reads a binary token as exactly `words` big-endian 32-bit words.
    fn binary_words(&mut self, t: crate::lexer::Token, words: usize, what: &str) -> PResult<Span> {
        self.exact_binary(t, words * 4)
            .map_err(|d| Diagnostic { message: format!("{} (trilist {what}: {words} words)", d.message), ..d })
    }

    /// The triangle section: `[ ints ]` (3 per triangle, or 4 with the label first, or
    /// with material names) or `integer `…` [integer `…`]`.
    fn triangles(&mut self, count: u32, tagged: bool, start: Span) -> PResult<Triangles> {
        let n = count as usize;
        if self.eat("integer")? {
            let t = self.bump()?;
            let span = self.binary_words(t, n * 3, "triangle indices")?;
            let indices = be_u32s(self.ts.bytes(span));
            let labels = if self.eat("integer")? {
                let t = self.bump()?;
                let span = self.binary_words(t, n, "triangle labels")?;
                Some(be_u32s(self.ts.bytes(span)))
            } else {
                None
            };
            return Ok(Triangles { indices, labels, materials: None });
        }
        let mut ints = Vec::new();
        let remaining = self.lexer()?.remaining();
        reserve_for(&mut ints, n.saturating_mul(if tagged { 4 } else { 3 }), remaining, 2);
        let names = self.int_block(&mut ints)?;
        if !names.is_empty() {
            if ints.len() != 3 * n {
                return Err(Diagnostic::error(
                    start,
                    format!("trilist declares {n} triangles but its index list holds {} indices", ints.len()),
                ));
            }
            let materials = names.into_iter().map(|(at, name)| (at / 3, name)).collect();
            return Ok(Triangles { indices: ints, labels: None, materials: Some(materials) });
        }
        if ints.len() == 3 * n && !(tagged && n == 0) {
            return Ok(Triangles { indices: ints, labels: None, materials: None });
        }
        if ints.len() == 4 * n {
            let mut labels = Vec::with_capacity(n);
            let mut indices = Vec::with_capacity(3 * n);
            for quad in ints.chunks_exact(4) {
                labels.push(quad[0]);
                indices.extend_from_slice(&quad[1..]);
            }
            return Ok(Triangles { indices, labels: Some(labels), materials: None });
        }
        Err(Diagnostic::error(
            start,
            format!(
                "trilist declares {n} triangles but its index list holds {} integers (expected {} or, with labels, {})",
                ints.len(),
                3 * n,
                4 * n
            ),
        ))
    }

    // ----- hair -----

    /// `hair … scalar [N] values… hair [K] offsets… end hair`.
    fn hair(&mut self) -> PResult<Hair> {
        let start = self.expect("hair")?;
        let mut header = Vec::new();
        while !self.at("scalar")? {
            self.not_eof("hair", start)?;
            match self.kw_stmt(&[grammar::HAIR])? {
                Some(s) => header.push(s),
                None => return self.expected("a hair statement or 'scalar'"),
            }
        }
        self.expect("scalar")?;
        let scalar_count = self.bracketed_count()?;
        let remaining = self.lexer()?.remaining();
        let mut scalars = Vec::new();
        if self.eat("binary")? {
            let t = self.bump()?;
            let span = self.exact_binary(t, scalar_count * 4)?;
            scalars = be_f32s(self.ts.bytes(span));
        } else {
            if scalar_count > remaining / 2 + 1 {
                return Err(Diagnostic::error(
                    start,
                    format!("hair declares {scalar_count} scalars but the file is shorter"),
                ));
            }
            scalars.reserve(scalar_count);
            for _ in 0..scalar_count {
                let lx = self.lexer()?;
                match lx.try_f32()? {
                    Some(x) => scalars.push(x),
                    None => scalars.push(self.float()? as f32),
                }
            }
        }
        self.expect("hair")?;
        let offset_count = self.bracketed_count()?;
        let mut offsets = Vec::new();
        if self.eat("binary")? {
            let t = self.bump()?;
            let span = self.exact_binary(t, offset_count * 4)?;
            offsets = be_u32s(self.ts.bytes(span));
        } else {
            reserve_for(&mut offsets, offset_count, remaining, 2);
            for _ in 0..offset_count {
                offsets.push(self.uint("a hair offset")?);
            }
        }
        let end = self.expect_end("hair")?;
        Ok(Hair { header, scalars, offsets, span: start.to(end) })
    }

    /// `[ N ]`
    fn bracketed_count(&mut self) -> PResult<usize> {
        self.expect_tok(Tok::LBracket, "'['")?;
        let n = self.uint("a count")? as usize;
        self.expect_tok(Tok::RBracket, "']'")?;
        Ok(n)
    }
}

/// Reads a non-negative integer through the fast path or fails with `what`.
fn need_u32(lx: &mut Lexer, what: &str) -> PResult<u32> {
    match lx.try_u32()? {
        Some(v) => Ok(v),
        None => Err(at_lexer(lx, &format!("expected {what}"))),
    }
}

/// An error at the lexer's current position.
fn at_lexer(lx: &mut Lexer, msg: &str) -> Diagnostic {
    lx.skip_trivia();
    let p = lx.pos as u32;
    Diagnostic::error(Span::new(lx.file, p, p + 1), msg)
}

fn be_f32s(bytes: &[u8]) -> Vec<f32> {
    bytes.chunks_exact(4).map(|c| f32::from_be_bytes([c[0], c[1], c[2], c[3]])).collect()
}

fn be_u32s(bytes: &[u8]) -> Vec<u32> {
    bytes.chunks_exact(4).map(|c| u32::from_be_bytes([c[0], c[1], c[2], c[3]])).collect()
}
