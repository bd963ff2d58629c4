//! Groups: vectors, vertex lines, polygons (plain, strips and fans), their face
//! materials, and the statements groups share with subdivision surfaces (`derivative`).
//!
//! Vectors, vertex lines and polygons are read straight from the lexer (no token objects).

use super::geometry::{at_lexer, need_u32};
use super::{PResult, Parser};
use crate::ast::*;
use crate::diag::Diagnostic;
use crate::lexer::Tok;
use crate::source::Span;

impl Parser {
    /// `group ["name"] [merge ε] … end group`.
    pub(super) fn group(&mut self, tagged: bool) -> PResult<Group> {
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
    pub(super) fn face_material(&mut self, tagged: bool) -> PResult<FaceMaterial> {
        if tagged {
            return Ok(FaceMaterial::Label(self.uint("the face's label (the object is tagged)")?));
        }
        if self.at_str()? {
            return Ok(FaceMaterial::Named(self.name()?));
        }
        Ok(FaceMaterial::Inherit)
    }

    /// Non-negative integers while they come.
    pub(super) fn indices(&mut self, out: &mut Vec<u32>) -> PResult<()> {
        while matches!(self.peek()?.tok, Tok::Int(_)) {
            out.push(self.uint("a vertex index")?);
        }
        Ok(())
    }

    /// Numbers while they come (crease sharpness values: one per set mask bit as a rule).
    pub(super) fn floats_while(&mut self) -> PResult<Vec<f64>> {
        let mut v = Vec::new();
        while self.at_number()? {
            v.push(self.float()?);
        }
        Ok(v)
    }

    /// `derivative n [space m]` statements.
    pub(super) fn derivatives(&mut self) -> PResult<Vec<Derivative>> {
        let mut out = Vec::new();
        while self.eat("derivative")? {
            let order = self.int()?;
            let space = if self.eat("space")? { Some(self.int()?) } else { None };
            out.push(Derivative { order, space });
        }
        Ok(out)
    }
}
