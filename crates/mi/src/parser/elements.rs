//! Elements other than objects: options, camera, light (and the other keyword blocks),
//! material, texture, instance, instgroup, data, registry, spectrum.

use super::{PResult, Parser};
use crate::ast::*;
use crate::diag::Diagnostic;
use crate::grammar::{self, Rule};
use crate::lexer::Tok;

impl Parser {
    /// `keyword "name" statements… end keyword` for options, camera, light, lightprofile,
    /// assembly, colorprofile.
    pub fn block(&mut self, keyword: &'static str, table: &'static [Rule]) -> PResult<Block> {
        let start = self.expect(keyword)?;
        self.ends.push(keyword);
        let name = self.name()?;
        let mut stmts = Vec::new();
        loop {
            self.not_eof(keyword, start)?;
            if self.at_end(keyword)? {
                let end = self.expect_end(keyword)?;
                self.ends.pop();
                return Ok(Block { name, stmts, span: start.to(end) });
            }
            stmts.push(self.block_stmt(keyword, table)?);
        }
    }

    /// One statement inside a keyword block.
    fn block_stmt(&mut self, keyword: &str, table: &'static [Rule]) -> PResult<Stmt> {
        let t = self.peek()?;
        if self.is(&t, "attribute") {
            return Ok(Stmt::Attribute(self.attribute()?));
        }
        match keyword {
            "options" if matches!(t.tok, Tok::Str { .. }) => {
                let name = self.name()?;
                let value = self.stmt_value()?;
                return Ok(Stmt::StringOption { name, value });
            }
            "light" if self.at_shader_item()? => return Ok(Stmt::Shaders(self.shader_list()?)),
            "camera" if self.is(&t, "output") => return Ok(Stmt::Output(self.output()?)),
            "camera" if self.is(&t, "framebuffer") => return Ok(Stmt::Framebuffer(self.framebuffer()?)),
            _ => {}
        }
        match self.kw_stmt(&[table])? {
            Some(s) => Ok(Stmt::Kw(s)),
            None => Err(Diagnostic::error(t.span, format!("unknown {keyword} statement {}", self.describe(&t)))),
        }
    }

    /// `output …` in a camera.
    fn output(&mut self) -> PResult<Output> {
        let start = self.expect("output")?;
        let colorprofile = if self.at("colorprofile")? {
            self.bump()?;
            Some(self.name()?)
        } else {
            None
        };
        let done = |p: &mut Parser, types, kind| -> PResult<Output> {
            let end = p.peek()?.span;
            Ok(Output { colorprofile: colorprofile.clone(), types, kind, span: start.to(end.start()) })
        };
        if self.at_shader_item()? {
            let list = self.shader_list()?;
            return done(self, None, OutputKind::Shader(list));
        }
        if !self.at_str()? {
            return done(self, None, OutputKind::Clear);
        }
        let first = self.name()?;
        if self.at_shader_item()? {
            let list = self.shader_list()?;
            return done(self, Some(first), OutputKind::Shader(list));
        }
        let (types, format) = if self.at_str()? { (Some(first), self.name()?) } else { (None, first) };
        let mut options = Vec::new();
        if let Some(s) = self.kw_stmt(&[grammar::OUTPUT_PARAMS])? {
            options.push(s);
        }
        if !self.at_str()? {
            // `output "format" "file"` read as types + format: shift.
            if options.is_empty() {
                if let Some(types) = types {
                    return done(self, None, OutputKind::File { format: types, options, file: format });
                }
            }
            return self.expected("the output file name");
        }
        let file = self.name()?;
        done(self, types, OutputKind::File { format, options, file })
    }

    /// `framebuffer "name" field…` (no `end`: fields run until another statement).
    fn framebuffer(&mut self) -> PResult<Framebuffer> {
        let start = self.expect("framebuffer")?;
        let name = self.name()?;
        let mut fields = Vec::new();
        loop {
            let t = self.peek()?;
            if self.is(&t, "attribute") {
                fields.push(Stmt::Attribute(self.attribute()?));
                continue;
            }
            let Some(rule) = self.match_rule(&[grammar::FRAMEBUFFER])? else { break };
            // `field 1` is the camera's field statement, `field "name"` the buffer's.
            if rule.key == "field" && !matches!(self.peek_at(1)?.tok, Tok::Str { .. }) {
                break;
            }
            fields.push(Stmt::Kw(self.kw_stmt_by(rule)?));
        }
        let end = self.peek()?.span;
        Ok(Framebuffer { name, fields, span: start.to(end.start()) })
    }

    /// `material "name" … end material`.
    pub fn material(&mut self) -> PResult<Material> {
        let start = self.expect("material")?;
        self.ends.push("material");
        let name = self.name()?;
        let mut shaders: Option<ShaderList> = None;
        let mut stmts = Vec::new();
        loop {
            self.not_eof("material", start)?;
            if self.at_end("material")? {
                let end = self.expect_end("material")?;
                self.ends.pop();
                return Ok(Material { name, shaders, stmts, span: start.to(end) });
            }
            let t = self.peek()?;
            if self.at_shader_item()? {
                let list = self.shader_list()?;
                match &mut shaders {
                    Some(existing) => existing.0.extend(list.0),
                    None => shaders = Some(list),
                }
            } else if self.is(&t, "attribute") {
                stmts.push(Stmt::Attribute(self.attribute()?));
            } else if let Some(s) = self.kw_stmt(&[grammar::MATERIAL])? {
                stmts.push(Stmt::Kw(s));
            } else {
                return Err(Diagnostic::error(t.span, format!("unknown material statement {}", self.describe(&t))));
            }
        }
    }

    /// `[flags] color|scalar|vector texture "name" [colorprofile "p"] source`.
    pub fn texture(&mut self) -> PResult<Texture> {
        let start = self.peek()?.span;
        let mut flags = Vec::new();
        while let Some(s) = self.kw_stmt(&[grammar::TEXTURE_FLAGS])? {
            flags.push(s);
        }
        let t = self.peek()?;
        let kind = match self.bytes(&t) {
            b"color" => TextureKind::Color,
            b"scalar" => TextureKind::Scalar,
            b"vector" => TextureKind::Vector,
            _ => return self.expected("'color texture', 'scalar texture' or 'vector texture'"),
        };
        self.bump()?;
        self.expect("texture")?;
        let name = self.name()?;
        let colorprofile = if self.at("colorprofile")? {
            self.bump()?;
            Some(self.name()?)
        } else {
            None
        };
        let source = if self.at_shader_item()? {
            TextureSource::Shader(self.shader_list()?)
        } else if self.peek()?.tok == Tok::LBracket {
            let dims = self.int_bracket(2, 3)?;
            let mut pieces = Vec::new();
            while self.peek()?.tok == Tok::ByteStr {
                pieces.push(self.byte_string()?);
            }
            TextureSource::Pixels { dims, pieces }
        } else {
            let file = self.name()?;
            let mut filetype = Vec::new();
            while filetype.len() < 2 && self.at_str()? {
                filetype.push(self.name()?);
            }
            let size = if self.peek()?.tok == Tok::LBracket { Some(self.int_bracket(2, 3)?) } else { None };
            TextureSource::File { file, filetype, size }
        };
        let end = self.peek()?.span;
        Ok(Texture { name, kind, flags, colorprofile, source, span: start.to(end.start()) })
    }

    /// `[ int int [int] ]`
    fn int_bracket(&mut self, min: usize, max: usize) -> PResult<Vec<i64>> {
        self.expect_tok(Tok::LBracket, "'['")?;
        let mut v = Vec::new();
        while v.len() < max && matches!(self.peek()?.tok, Tok::Int(_)) {
            v.push(self.int()?);
        }
        if v.len() < min {
            return self.expected(&format!("{min} integers"));
        }
        self.expect_tok(Tok::RBracket, "']'")?;
        Ok(v)
    }

    /// A single-quoted hexadecimal byte string.
    pub(crate) fn byte_string(&mut self) -> PResult<Vec<u8>> {
        let t = self.bump()?;
        let raw = self.bytes(&t);
        let digits: Vec<u8> = raw[1..raw.len() - 1].iter().copied().filter(|b| !b.is_ascii_whitespace()).collect();
        if digits.len() % 2 != 0 {
            return Err(Diagnostic::error(t.span, "byte string has an odd number of hexadecimal digits"));
        }
        let hex = |b: u8| match b {
            b'0'..=b'9' => Some(b - b'0'),
            b'a'..=b'f' => Some(b - b'a' + 10),
            b'A'..=b'F' => Some(b - b'A' + 10),
            _ => None,
        };
        digits
            .chunks(2)
            .map(|p| match (hex(p[0]), hex(p[1])) {
                (Some(h), Some(l)) => Ok(h << 4 | l),
                _ => Err(Diagnostic::error(t.span, "byte string holds a character that is not a hexadecimal digit")),
            })
            .collect()
    }

    /// `instance "name" ["element"] [geometry shader…] … end instance`.
    pub fn instance(&mut self) -> PResult<Instance> {
        let start = self.expect("instance")?;
        self.ends.push("instance");
        let name = self.name()?;
        let target = if self.eat("geometry")? {
            InstanceTarget::Geometry(self.shader_list()?)
        } else if self.at_str()? {
            InstanceTarget::Element(self.name()?)
        } else if self.peek()?.tok == Tok::Name
            && !self.at("end")?
            && !self.at("attribute")?
            && self.match_rule(&[grammar::INSTANCE])?.is_none()
        {
            // An unquoted element name.
            InstanceTarget::Element(self.name()?)
        } else {
            InstanceTarget::None
        };
        let mut stmts = Vec::new();
        let mut params = None;
        loop {
            self.not_eof("instance", start)?;
            if self.at_end("instance")? {
                let end = self.expect_end("instance")?;
                self.ends.pop();
                return Ok(Instance { name, target, stmts, params, span: start.to(end) });
            }
            let t = self.peek()?;
            if t.tok == Tok::LParen {
                params = Some(self.params()?.0);
            } else if self.is(&t, "attribute") {
                stmts.push(Stmt::Attribute(self.attribute()?));
            } else if let Some(s) = self.kw_stmt(&[grammar::INSTANCE])? {
                stmts.push(Stmt::Kw(s));
            } else {
                return Err(Diagnostic::error(t.span, format!("unknown instance statement {}", self.describe(&t))));
            }
        }
    }

    /// `instgroup "name" … members… end instgroup`.
    pub fn instgroup(&mut self) -> PResult<Instgroup> {
        let start = self.expect("instgroup")?;
        self.ends.push("instgroup");
        let name = self.name()?;
        let mut stmts = Vec::new();
        let mut members = Vec::new();
        loop {
            self.not_eof("instgroup", start)?;
            if self.at_end("instgroup")? {
                let end = self.expect_end("instgroup")?;
                self.ends.pop();
                return Ok(Instgroup { name, stmts, members, span: start.to(end) });
            }
            let t = self.peek()?;
            if matches!(t.tok, Tok::Str { .. }) {
                members.push(self.name()?);
            } else if self.is(&t, "attribute") {
                stmts.push(Stmt::Attribute(self.attribute()?));
            } else if let Some(s) = self.kw_stmt(&[grammar::INSTGROUP])? {
                stmts.push(Stmt::Kw(s));
            } else if t.tok == Tok::Name {
                members.push(self.name()?);
            } else {
                return Err(Diagnostic::error(
                    t.span,
                    format!("expected an instance name, found {}", self.describe(&t)),
                ));
            }
        }
    }

    /// `data "name" [tag N] (size [ 'hex'… ] | "file" | "decl" (params))`.
    pub fn data(&mut self) -> PResult<Data> {
        let start = self.expect("data")?;
        let name = self.name()?;
        let tag = if self.eat("tag")? { Some(self.int()?) } else { None };
        let body = if matches!(self.peek()?.tok, Tok::Int(_)) {
            let size = self.int()?;
            let open = self.expect_tok(Tok::LBracket, "'['")?;
            let mut pieces = Vec::new();
            let mut total = 0i64;
            loop {
                let t = self.peek()?;
                match t.tok {
                    Tok::RBracket => {
                        self.bump()?;
                        break;
                    }
                    Tok::ByteStr => {
                        let piece = self.byte_string()?;
                        total += piece.len() as i64;
                        pieces.push(piece);
                    }
                    Tok::Eof => return Err(Diagnostic::error(open, "data bytes are not closed by ']'")),
                    _ => return self.expected("a byte string in 'single quotes' or ']'"),
                }
            }
            // An empty list is how exporters reserve data filled in later.
            if total != size && !pieces.is_empty() {
                self.warn(start, format!("data '{}' declares {size} bytes but holds {total}", name.text));
            }
            DataBody::Bytes { size, pieces }
        } else if self.peek_at(1)?.tok == Tok::LParen {
            let decl = self.name()?;
            let (params, _) = self.params()?;
            DataBody::Params { decl, params }
        } else {
            DataBody::File(self.name()?)
        };
        let end = self.peek()?.span;
        Ok(Data { name, tag, body, span: start.to(end.start()) })
    }

    /// `registry "{key}" field "value"… end registry`.
    pub fn registry(&mut self) -> PResult<Registry> {
        let start = self.expect("registry")?;
        self.ends.push("registry");
        let key = self.name()?;
        let mut entries = Vec::new();
        loop {
            self.not_eof("registry", start)?;
            if self.at_end("registry")? {
                let end = self.expect_end("registry")?;
                self.ends.pop();
                if let Some((_, v)) = entries.iter().rev().find(|(f, _): &&(Name, Name)| f.text == "value") {
                    let k = key.text.trim_start_matches('{').trim_end_matches('}').to_string();
                    let v = v.text.clone();
                    self.ts.set_registry(&k, &v);
                }
                return Ok(Registry { key, entries, span: start.to(end) });
            }
            let field = self.name()?;
            let value = self.name()?;
            entries.push((field, value));
        }
    }

    /// `spectrum "name" wavelength value … end spectrum`.
    pub fn spectrum(&mut self) -> PResult<Spectrum> {
        let start = self.expect("spectrum")?;
        self.ends.push("spectrum");
        let name = self.name()?;
        let mut values = Vec::new();
        while self.at_number()? {
            values.push(self.float()?);
        }
        let end = self.expect_end("spectrum")?;
        self.ends.pop();
        Ok(Spectrum { name, values, span: start.to(end) })
    }
}
