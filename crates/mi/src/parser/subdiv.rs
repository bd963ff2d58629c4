//! Subdivision surfaces (`subdivision surface … end subdivision surface`, with their
//! hierarchies) and ccmeshes inside a group.

use super::geometry::reserve_for;
use super::{PResult, Parser};
use crate::ast::*;
use crate::diag::Diagnostic;
use crate::lexer::Tok;

impl Parser {
    /// `subdivision surface "name" … end subdivision surface`.
    pub(super) fn subdivision(&mut self, tagged: bool) -> PResult<SubdivSurface> {
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
    pub(super) fn ccmesh(&mut self, tagged: bool) -> PResult<Ccmesh> {
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
}
