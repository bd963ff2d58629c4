//! Values: shader lists and calls, parameter values, declarations, gui token trees.

use super::{PResult, Parser};
use crate::ast::*;
use crate::diag::Diagnostic;
use crate::lexer::Tok;
use crate::source::Span;

/// Words that name a declared parameter type (the first word of a two-word type included).
const TYPE_WORDS: &[&str] = &[
    "boolean",
    "integer",
    "scalar",
    "string",
    "color",
    "vector",
    "transform",
    "shader",
    "data",
    "light",
    "material",
    "geometry",
    "lightprofile",
    "spectrum",
    "struct",
    "array",
];

impl Parser {
    /// Whether a shader list item starts here: `=`, or a name followed by `(`.
    pub fn at_shader_item(&mut self) -> PResult<bool> {
        let t = self.peek()?;
        Ok(match t.tok {
            Tok::Equals => true,
            Tok::Str { .. } | Tok::Name => self.peek_at(1)?.tok == Tok::LParen,
            _ => false,
        })
    }

    /// A shader list: one or more items in a row.
    pub fn shader_list(&mut self) -> PResult<ShaderList> {
        let mut items = vec![self.shader_item()?];
        while self.at_shader_item()? {
            items.push(self.shader_item()?);
        }
        Ok(ShaderList(items))
    }

    /// One shader list item.
    pub fn shader_item(&mut self) -> PResult<ShaderItem> {
        let t = self.peek()?;
        if t.tok == Tok::Equals {
            self.bump()?;
            if self.at("incremental")? || self.at("shader")? {
                let incremental = self.eat("incremental")?;
                self.expect("shader")?;
                let name = self.name()?;
                self.enter(t.span)?;
                let list = self.shader_list();
                self.leave();
                return Ok(ShaderItem::Define { incremental, name, list: list? });
            }
            return Ok(ShaderItem::Ref(self.name()?));
        }
        if !matches!(t.tok, Tok::Str { .. } | Tok::Name) || self.peek_at(1)?.tok != Tok::LParen {
            return self.expected("a shader: \"declaration\" ( parameters ) or = \"name\"");
        }
        let decl = self.name()?;
        let (params, end) = self.params()?;
        Ok(ShaderItem::Call { span: decl.span.to(end), decl, params })
    }

    /// `( param, param, … )` (a trailing comma allowed); returns the span of `)`.
    pub fn params(&mut self) -> PResult<(Vec<Param>, Span)> {
        let open = self.expect_tok(Tok::LParen, "'('")?;
        self.enter(open)?;
        let mut params = Vec::new();
        loop {
            let t = self.peek()?;
            match t.tok {
                Tok::RParen => {
                    self.bump()?;
                    self.leave();
                    return Ok((params, t.span));
                }
                Tok::Eof => {
                    return Err(Diagnostic::error(open, "parameter list is not closed by ')'")
                        .with_note(Some(t.span), "the file ends here"))
                }
                _ => {}
            }
            params.push(self.param()?);
            let t = self.peek()?;
            match t.tok {
                Tok::Comma => {
                    self.bump()?;
                }
                Tok::RParen => {}
                Tok::Eof => {
                    return Err(Diagnostic::error(open, "parameter list is not closed by ')'")
                        .with_note(Some(t.span), "the file ends here"))
                }
                _ => return self.expected("',' or ')' after a parameter value"),
            }
        }
    }

    /// `"name" [colorprofile "p"] value…`
    pub fn param(&mut self) -> PResult<Param> {
        let name = self.name()?;
        let colorprofile = if self.at("colorprofile")? && matches!(self.peek_at(1)?.tok, Tok::Str { .. }) {
            self.bump()?;
            Some(self.name()?)
        } else {
            None
        };
        let value = self.value_seq()?;
        let end = self.peek()?.span;
        Ok(Param { span: name.span.to(end.start()), name, colorprofile, value })
    }

    /// Values up to `,`, `)`, `]` or `}`: one value, a tuple of numbers, or a sequence.
    pub fn value_seq(&mut self) -> PResult<Value> {
        let first = self.value_atom()?;
        let mut rest = Vec::new();
        while !matches!(self.peek()?.tok, Tok::Comma | Tok::RParen | Tok::RBracket | Tok::RBrace | Tok::Eof) {
            rest.push(self.value_atom()?);
        }
        if rest.is_empty() {
            return Ok(first);
        }
        let mut all = vec![first];
        all.extend(rest);
        let nums: Option<Vec<Num>> = all.iter().map(|v| if let Value::Num(n) = v { Some(*n) } else { None }).collect();
        Ok(match nums {
            Some(nums) => Value::Tuple(nums),
            None => Value::Seq(all),
        })
    }

    /// One value.
    pub fn value_atom(&mut self) -> PResult<Value> {
        let t = self.peek()?;
        match t.tok {
            Tok::Int(v) => {
                self.bump()?;
                Ok(Value::Num(Num::Int(v)))
            }
            Tok::Float(v) => {
                self.bump()?;
                Ok(Value::Num(Num::Float(v)))
            }
            Tok::Name => {
                if let Some(b) = self.try_bool()? {
                    return Ok(Value::Bool(b));
                }
                if self.eat("null")? {
                    return Ok(Value::Null);
                }
                Ok(Value::Str(self.name()?))
            }
            Tok::Str { .. } => Ok(Value::Str(self.name()?)),
            Tok::Equals => {
                if self.peek_at(1).map(|n| self.is(&n, "interface"))? {
                    self.bump()?;
                    self.bump()?;
                    return Ok(Value::Interface(self.name()?));
                }
                let after = self.peek_at(1)?;
                if self.is(&after, "shader") || self.is(&after, "incremental") {
                    return Ok(Value::Define(Box::new(self.shader_item()?)));
                }
                self.bump()?;
                Ok(Value::Connect(self.name()?))
            }
            Tok::LBrace => {
                self.bump()?;
                self.enter(t.span)?;
                let mut fields = Vec::new();
                loop {
                    if self.eat_tok(Tok::RBrace)? {
                        break;
                    }
                    if self.peek()?.tok == Tok::Eof {
                        return Err(Diagnostic::error(t.span, "struct value is not closed by '}'"));
                    }
                    fields.push(self.param()?);
                    if !self.eat_tok(Tok::Comma)? && self.peek()?.tok != Tok::RBrace {
                        return self.expected("',' or '}' in a struct value");
                    }
                }
                self.leave();
                Ok(Value::Struct(fields))
            }
            Tok::LBracket => {
                self.bump()?;
                self.enter(t.span)?;
                let mut elems = Vec::new();
                loop {
                    if self.eat_tok(Tok::RBracket)? {
                        break;
                    }
                    if self.peek()?.tok == Tok::Eof {
                        return Err(Diagnostic::error(t.span, "array value is not closed by ']'"));
                    }
                    let v = self.value_seq()?;
                    // `[ "a" "b" ]` without commas: a list of names, not one sequence.
                    match v {
                        Value::Seq(vs) if vs.iter().all(|v| matches!(v, Value::Str(_))) => elems.extend(vs),
                        v => elems.push(v),
                    }
                    if !self.eat_tok(Tok::Comma)? && self.peek()?.tok != Tok::RBracket {
                        return self.expected("',' or ']' in an array value");
                    }
                }
                self.leave();
                Ok(Value::Array(elems))
            }
            Tok::Binary => {
                let v = self.binary_vector()?;
                Ok(Value::Tuple(v.iter().map(|&x| Num::Float(f64::from(x))).collect()))
            }
            _ => self.expected("a value"),
        }
    }

    /// A value in a statement (string options, attributes): a boolean, a string, a
    /// connection, or a run of numbers.
    pub fn stmt_value(&mut self) -> PResult<Value> {
        let t = self.peek()?;
        match t.tok {
            Tok::Int(_) | Tok::Float(_) => {
                let mut nums = vec![self.num()?];
                while self.at_number()? {
                    nums.push(self.num()?);
                }
                Ok(if nums.len() == 1 { Value::Num(nums[0]) } else { Value::Tuple(nums) })
            }
            Tok::Name => match self.try_bool()? {
                Some(b) => Ok(Value::Bool(b)),
                None if self.at("null")? => {
                    self.bump()?;
                    Ok(Value::Null)
                }
                None => self.expected("a value"),
            },
            Tok::Str { .. } | Tok::Equals | Tok::LBracket | Tok::LBrace | Tok::Binary => self.value_atom(),
            _ => self.expected("a value"),
        }
    }

    /// A 12-byte backquoted big-endian vector.
    pub fn binary_vector(&mut self) -> PResult<[f32; 3]> {
        let t = self.bump()?;
        let span = self.exact_binary(t, 12)?;
        let b = self.ts.bytes(span);
        let f = |i: usize| f32::from_be_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
        Ok([f(0), f(4), f(8)])
    }

    /// Re-reads a binary token as exactly `len` payload bytes; returns the payload span.
    pub fn exact_binary(&mut self, t: crate::lexer::Token, len: usize) -> PResult<Span> {
        if t.tok != Tok::Binary {
            return Err(Diagnostic::error(
                t.span,
                format!("expected a backquoted binary block, found {}", self.describe(&t)),
            ));
        }
        let payload = (t.span.hi - t.span.lo - 2) as usize;
        if payload == len {
            return Ok(Span::new(t.span.file, t.span.lo + 1, t.span.hi - 1));
        }
        // The payload holds a backquote (or the block is malformed): read it by count.
        let src_len = self.ts.sources.file(t.span.file).bytes.len();
        let close = t.span.lo as usize + 1 + len;
        let bytes = &self.ts.sources.file(t.span.file).bytes;
        if close >= src_len || bytes[close] != b'`' {
            return Err(Diagnostic::error(
                t.span,
                format!("binary block should hold {len} bytes, but holds {payload}"),
            ));
        }
        self.ts.reposition(t.span.file, close + 1);
        Ok(Span::new(t.span.file, t.span.lo + 1, close as u32))
    }

    /// `gui ["name"] [( … )] { … }`
    pub fn gui(&mut self) -> PResult<Gui> {
        let start = self.expect("gui")?;
        let name = if self.at_str()? { Some(self.name()?) } else { None };
        let mut body = Vec::new();
        loop {
            let t = self.peek()?;
            match t.tok {
                Tok::LParen => body.push(self.token_tree()?),
                Tok::LBrace => {
                    body.push(self.token_tree()?);
                    break;
                }
                _ => return self.expected("'{' to start the gui block"),
            }
        }
        let end = self.peek()?.span;
        Ok(Gui { name, body, span: start.to(end.start()) })
    }

    /// A bracketed token tree.
    pub fn token_tree(&mut self) -> PResult<TokenTree> {
        let open = self.bump()?;
        let close = match open.tok {
            Tok::LParen => Tok::RParen,
            Tok::LBracket => Tok::RBracket,
            Tok::LBrace => Tok::RBrace,
            _ => return Err(Diagnostic::error(open.span, "expected '(', '[' or '{'")),
        };
        self.enter(open.span)?;
        let mut items = Vec::new();
        loop {
            let t = self.peek()?;
            let atom = match t.tok {
                tok if tok == close => {
                    self.bump()?;
                    break;
                }
                Tok::LParen | Tok::LBracket | Tok::LBrace => {
                    items.push(self.token_tree()?);
                    continue;
                }
                Tok::Name => Atom::Word(self.text_of(&t)),
                Tok::Str { .. } => Atom::Str(self.text_of(&t)),
                Tok::Int(v) => Atom::Num(Num::Int(v)),
                Tok::Float(v) => Atom::Num(Num::Float(v)),
                Tok::Comma => Atom::Comma,
                Tok::Equals => Atom::Equals,
                Tok::Percent => Atom::Percent,
                Tok::Eof => {
                    return Err(Diagnostic::error(open.span, "bracket is not closed")
                        .with_note(Some(t.span), "the file ends here"))
                }
                _ => return Err(Diagnostic::error(t.span, format!("unexpected {} here", self.describe(&t)))),
            };
            self.bump()?;
            items.push(TokenTree::Atom(atom));
        }
        self.leave();
        Ok(match close {
            Tok::RParen => TokenTree::Paren(items),
            Tok::RBracket => TokenTree::Bracket(items),
            _ => TokenTree::Brace(items),
        })
    }

    /// Whether a parameter type starts here.
    fn at_type(&mut self) -> PResult<bool> {
        let t = self.peek()?;
        Ok(t.tok == Tok::Name && TYPE_WORDS.iter().any(|w| self.is(&t, w)))
    }

    /// A parameter type (not `struct`/`array`, which carry names).
    fn simple_type(&mut self) -> PResult<ParamType> {
        let t = self.peek()?;
        let ty = match self.bytes(&t) {
            b"boolean" => ParamType::Boolean,
            b"integer" => ParamType::Integer,
            b"scalar" => ParamType::Scalar,
            b"string" => ParamType::String,
            b"color" => ParamType::Color,
            b"vector" => ParamType::Vector,
            b"transform" => ParamType::Transform,
            b"shader" => ParamType::Shader,
            b"data" => ParamType::Data,
            b"light" => ParamType::Light,
            b"material" => ParamType::Material,
            b"geometry" => ParamType::Geometry,
            b"lightprofile" => ParamType::Lightprofile,
            b"spectrum" => ParamType::Spectrum,
            _ => return self.expected("a parameter type"),
        };
        self.bump()?;
        if matches!(ty, ParamType::Color | ParamType::Scalar | ParamType::Vector) && self.at("texture")? {
            let next = self.peek_at(1)?;
            // `color texture "t"` is a texture type; `color texture` alone names a parameter.
            if matches!(next.tok, Tok::Str { .. } | Tok::Name) {
                self.bump()?;
                return Ok(match ty {
                    ParamType::Color => ParamType::ColorTexture,
                    ParamType::Scalar => ParamType::ScalarTexture,
                    _ => ParamType::VectorTexture,
                });
            }
        }
        Ok(ty)
    }

    /// A return type: a type or `struct { type "name", … }`.
    fn return_type(&mut self) -> PResult<ParamType> {
        if self.at("struct")? {
            let start = self.bump()?.span;
            let open = self.expect_tok(Tok::LBrace, "'{'")?;
            self.enter(open)?;
            let fields = self.param_decls(Tok::RBrace)?;
            self.leave();
            let _ = start;
            return Ok(ParamType::Struct(fields));
        }
        self.simple_type()
    }

    /// Parameter declarations up to `close` (consumed); commas between, trailing allowed.
    pub fn param_decls(&mut self, close: Tok) -> PResult<Vec<ParamDecl>> {
        let mut decls = Vec::new();
        loop {
            if self.eat_tok(close)? {
                return Ok(decls);
            }
            if self.peek()?.tok == Tok::Eof {
                return self.expected("the end of the parameter declarations");
            }
            decls.push(self.param_decl()?);
            if !self.eat_tok(Tok::Comma)? && self.peek()?.tok != close {
                return self.expected("',' between parameter declarations");
            }
        }
    }

    /// `type "name" [default value…]`, `struct "name" { … }`, `array …`.
    fn param_decl(&mut self) -> PResult<ParamDecl> {
        let start = self.peek()?.span;
        self.enter(start)?;
        let (ty, name) = if self.at("array")? {
            self.bump()?;
            let inner = self.param_decl()?;
            let ty = ParamType::Array(Box::new(inner.ty));
            self.leave();
            return Ok(ParamDecl { ty, name: inner.name, default: inner.default, span: start.to(inner.span) });
        } else if self.at("struct")? {
            self.bump()?;
            let name = self.name()?;
            let open = self.expect_tok(Tok::LBrace, "'{'")?;
            self.enter(open)?;
            let fields = self.param_decls(Tok::RBrace)?;
            self.leave();
            (ParamType::Struct(fields), name)
        } else {
            let ty = self.simple_type()?;
            (ty, self.name()?)
        };
        let default = if self.eat("default")? { Some(self.value_seq()?) } else { None };
        self.leave();
        let end = self.peek()?.span;
        Ok(ParamDecl { ty, name, default, span: start.to(end.start()) })
    }

    /// `declare shader|phenomenon|data … end declare`, or the old `declare type "name" (…)`.
    pub fn declaration(&mut self) -> PResult<Declaration> {
        let start = self.expect("declare")?;
        let (kind, legacy) = if self.eat("shader")? {
            (DeclKind::Shader, false)
        } else if self.eat("phenomenon")? {
            (DeclKind::Phenomenon, false)
        } else if self.at("data")? && !matches!(self.peek_at(1)?.tok, Tok::Name) {
            self.bump()?;
            (DeclKind::Data, false)
        } else {
            (DeclKind::Shader, true)
        };
        let ret = if self.at_type()? { Some(self.return_type()?) } else { None };
        let name = self.name()?;
        self.expect_tok(Tok::LParen, "'(' to start the parameter declarations")?;
        let params = self.param_decls(Tok::RParen)?;
        let mut body = Vec::new();
        if legacy {
            // The old form has no requirements and no `end declare`; accept one if present.
            let end = if self.at_end("declare")? { self.expect_end("declare")? } else { name.span };
            return Ok(Declaration { kind, legacy, ret, name, params, body, span: start.to(end) });
        }
        self.ends.push("declare");
        let tables: &[&'static [crate::grammar::Rule]] = match kind {
            DeclKind::Phenomenon => &[crate::grammar::DECLARATION, crate::grammar::PHENOMENON],
            _ => &[crate::grammar::DECLARATION],
        };
        loop {
            self.not_eof("declare", start)?;
            if self.at_end("declare")? {
                let end = self.expect_end("declare")?;
                return Ok(Declaration { kind, legacy, ret, name, params, body, span: start.to(end) });
            }
            let t = self.peek()?;
            if self.is(&t, "gui") {
                body.push(DeclItem::Gui(self.gui()?));
                continue;
            }
            if kind == DeclKind::Phenomenon {
                let item = if self.is(&t, "shader") {
                    Some(Item::Shader(self.shader_def()?))
                } else if self.is(&t, "material") {
                    Some(Item::Material(self.material()?))
                } else if self.is(&t, "light") && !self.at_words("light shadow")? {
                    Some(Item::Light(self.block("light", crate::grammar::LIGHT)?))
                } else if self.is(&t, "instance") {
                    Some(Item::Instance(self.instance()?))
                } else {
                    None
                };
                if let Some(item) = item {
                    body.push(DeclItem::Item(item));
                    continue;
                }
            }
            match self.kw_stmt(tables)? {
                Some(stmt) => body.push(DeclItem::Kw(stmt)),
                None => {
                    return Err(Diagnostic::error(
                        t.span,
                        format!("unknown keyword {} in a declaration", self.describe(&t)),
                    ))
                }
            }
        }
    }

    /// `shader "name" shader_list`
    pub fn shader_def(&mut self) -> PResult<ShaderDef> {
        let start = self.expect("shader")?;
        let name = self.name()?;
        let list = self.shader_list()?;
        let end = self.peek()?.span;
        Ok(ShaderDef { name, list, span: start.to(end.start()) })
    }
}
