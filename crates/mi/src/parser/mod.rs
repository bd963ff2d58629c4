//! The recursive-descent parser: tokens to [`crate::ast`].
//!
//! One token of look-ahead suffices almost everywhere; keyword statements look a few tokens
//! ahead to match multi-word keywords (`finalgather trace depth`). Bulk geometry (vectors,
//! trilist data) is read through the lexer's fast paths when nothing is buffered. Errors
//! carry the span of the offending token; after an error the parser skips to the end of
//! the element it was in and carries on, so one run reports several independent errors.

mod elements;
mod freeform;
mod geometry;
mod group;
mod hair;
mod stmt;
mod subdiv;
mod trilist;
mod values;

use crate::ast::*;
use crate::diag::Diagnostic;
use crate::lexer::{unescape, Directive, Tok, Token};
use crate::preprocess::TokenStream;
use crate::source::Span;

pub(crate) type PResult<T> = Result<T, Diagnostic>;

/// How deeply values, shader lists, hierarchies and namespaces may nest.
pub const MAX_NESTING: u32 = 128;

/// Keywords that start a top-level item.
const TOP_LEVEL: &[&str] = &[
    "options",
    "camera",
    "light",
    "material",
    "texture",
    "object",
    "instance",
    "instgroup",
    "shader",
    "declare",
    "data",
    "lightprofile",
    "assembly",
    "colorprofile",
    "spectrum",
    "gui",
    "namespace",
    "incremental",
    "private",
    "session",
    "delete",
    "render",
    "registry",
    "color",
    "scalar",
    "vector",
    "local",
    "filter",
    "writable",
    "link",
    "code",
    "system",
    "verbose",
    "echo",
    "memory",
    "version",
    "min",
    "max",
    "debug",
    "set",
    "touch",
    "call",
    "root",
];

/// The recursive-descent reader of a preprocessed token stream into the syntax tree.
pub(crate) struct Parser {
    /// The tokens, includes expanded.
    pub ts: TokenStream,
    /// The messages so far, in order of reading.
    pub diags: Vec<Diagnostic>,
    depth: u32,
    max_errors: usize,
    /// `end` keywords of the elements being parsed, outermost first (for recovery).
    ends: Vec<&'static str>,
}

fn is_marker(tok: Tok) -> bool {
    matches!(tok, Tok::IncludeBegin(_) | Tok::IncludeEnd)
}

impl Parser {
    /// A parser of `ts` that gives up after `max_errors` errors (at least one).
    pub fn new(ts: TokenStream, max_errors: usize) -> Parser {
        Parser { ts, diags: Vec::new(), depth: 0, max_errors: max_errors.max(1), ends: Vec::new() }
    }

    // ----- tokens -----

    /// The `n`-th token ahead, include markers skipped (but left in place).
    pub fn peek_at(&mut self, n: usize) -> PResult<Token> {
        let mut seen = 0;
        let mut i = 0;
        loop {
            let t = self.ts.peek_raw(i)?;
            if !is_marker(t.tok) {
                if seen == n {
                    return Ok(t);
                }
                seen += 1;
            }
            i += 1;
        }
    }

    /// The next token, include markers skipped.
    pub fn peek(&mut self) -> PResult<Token> {
        self.peek_at(0)
    }

    /// Takes the next token (include markers before it are dropped: an include inside an
    /// element is read as if its text stood there).
    pub fn bump(&mut self) -> PResult<Token> {
        loop {
            let t = self.ts.next_raw()?;
            if !is_marker(t.tok) {
                return Ok(t);
            }
        }
    }

    /// The source bytes of a token.
    pub fn bytes(&self, t: &Token) -> &[u8] {
        self.ts.bytes(t.span)
    }

    /// Whether `t` is the unquoted word `w`.
    pub fn is(&self, t: &Token, w: &str) -> bool {
        t.tok == Tok::Name && self.bytes(t) == w.as_bytes()
    }

    /// Whether the next token is the unquoted word `w`.
    pub fn at(&mut self, w: &str) -> PResult<bool> {
        let t = self.peek()?;
        Ok(self.is(&t, w))
    }

    /// Whether the next tokens are the unquoted words of `words` (space separated).
    pub fn at_words(&mut self, words: &str) -> PResult<bool> {
        for (i, w) in words.split(' ').enumerate() {
            let t = self.peek_at(i)?;
            if !self.is(&t, w) {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// Consumes the word `w` if it is next.
    pub fn eat(&mut self, w: &str) -> PResult<bool> {
        if self.at(w)? {
            self.bump()?;
            return Ok(true);
        }
        Ok(false)
    }

    /// Consumes the token if it is `tok`.
    pub fn eat_tok(&mut self, tok: Tok) -> PResult<bool> {
        if self.peek()?.tok == tok {
            self.bump()?;
            return Ok(true);
        }
        Ok(false)
    }

    /// A description of a token for messages.
    pub fn describe(&self, t: &Token) -> String {
        let text = |p: &Parser| {
            let b = p.bytes(t);
            let s = String::from_utf8_lossy(&b[..b.len().min(40)]).into_owned();
            if b.len() > 40 {
                format!("{s}…")
            } else {
                s
            }
        };
        match t.tok {
            Tok::Name => format!("'{}'", text(self)),
            Tok::Str { .. } => format!("string {}", text(self)),
            Tok::Int(_) | Tok::Float(_) => format!("number {}", text(self)),
            Tok::Binary => "a binary block".into(),
            Tok::ByteStr => "a byte string".into(),
            Tok::Eof | Tok::IncludeEnd => "the end of the file".into(),
            Tok::CodeBlock => "a '$code' block".into(),
            Tok::Directive(_) => "a directive".into(),
            Tok::IncludeBegin(_) => "'$include'".into(),
            _ => format!("'{}'", text(self)),
        }
    }

    /// An error "expected X, found Y" at the next token.
    pub fn expected<T>(&mut self, what: &str) -> PResult<T> {
        let t = self.peek()?;
        Err(Diagnostic::error(t.span, format!("expected {what}, found {}", self.describe(&t))))
    }

    /// Consumes the word `w` or fails.
    pub fn expect(&mut self, w: &str) -> PResult<Span> {
        let t = self.peek()?;
        if self.is(&t, w) {
            self.bump()?;
            return Ok(t.span);
        }
        self.expected(&format!("'{w}'"))
    }

    /// Consumes `tok` or fails.
    pub fn expect_tok(&mut self, tok: Tok, what: &str) -> PResult<Span> {
        let t = self.peek()?;
        if t.tok == tok {
            self.bump()?;
            return Ok(t.span);
        }
        self.expected(what)
    }

    /// Consumes `end` followed by the words of `what`.
    pub fn expect_end(&mut self, what: &str) -> PResult<Span> {
        let start = self.expect("end")?;
        let mut last = start;
        for w in what.split(' ') {
            last = self.expect(w)?;
        }
        Ok(start.to(last))
    }

    /// Whether `end` followed by the words of `what` is next.
    pub fn at_end(&mut self, what: &str) -> PResult<bool> {
        let t = self.peek()?;
        if !self.is(&t, "end") {
            return Ok(false);
        }
        for (i, w) in what.split(' ').enumerate() {
            let t = self.peek_at(i + 1)?;
            if !self.is(&t, w) {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// Fails with a clear message if the file ends inside a block.
    pub fn not_eof(&mut self, block: &str, start: Span) -> PResult<()> {
        let t = self.peek()?;
        if t.tok == Tok::Eof {
            return Err(Diagnostic::error(start, format!("'{block}' is not closed by 'end {block}'"))
                .with_note(Some(t.span), "the file ends here"));
        }
        Ok(())
    }

    /// Text of a name or string token.
    pub fn text_of(&self, t: &Token) -> String {
        match t.tok {
            Tok::Str { escaped } => {
                let b = self.bytes(t);
                let body = &b[1..b.len() - 1];
                if escaped {
                    unescape(body)
                } else {
                    crate::lexer::bytes_to_string(body.to_vec())
                }
            }
            _ => crate::lexer::bytes_to_string(self.bytes(t).to_vec()),
        }
    }

    /// Whether the next token is a quoted string.
    pub fn at_str(&mut self) -> PResult<bool> {
        Ok(matches!(self.peek()?.tok, Tok::Str { .. }))
    }

    /// A string or unquoted name.
    pub fn name(&mut self) -> PResult<Name> {
        let t = self.peek()?;
        match t.tok {
            Tok::Str { .. } | Tok::Name => {
                self.bump()?;
                Ok(Name { text: self.text_of(&t), span: t.span })
            }
            _ => self.expected("a name in \"quotes\""),
        }
    }

    /// An integer.
    pub fn int(&mut self) -> PResult<i64> {
        let t = self.peek()?;
        match t.tok {
            Tok::Int(v) => {
                self.bump()?;
                Ok(v)
            }
            _ => self.expected("an integer"),
        }
    }

    /// A non-negative integer that fits 32 bits (counts, indices, labels).
    pub fn uint(&mut self, what: &str) -> PResult<u32> {
        let t = self.peek()?;
        match t.tok {
            Tok::Int(v) if (0..=i64::from(u32::MAX)).contains(&v) => {
                self.bump()?;
                Ok(v as u32)
            }
            Tok::Int(v) => Err(Diagnostic::error(t.span, format!("{what} {v} is out of range"))),
            _ => self.expected(what),
        }
    }

    /// A number (integer or float) as `f64`.
    pub fn float(&mut self) -> PResult<f64> {
        let t = self.peek()?;
        match t.tok {
            Tok::Int(v) => {
                self.bump()?;
                Ok(v as f64)
            }
            Tok::Float(v) => {
                self.bump()?;
                Ok(v)
            }
            _ => self.expected("a number"),
        }
    }

    /// A number kept as written.
    pub fn num(&mut self) -> PResult<Num> {
        let t = self.peek()?;
        match t.tok {
            Tok::Int(v) => {
                self.bump()?;
                Ok(Num::Int(v))
            }
            Tok::Float(v) => {
                self.bump()?;
                Ok(Num::Float(v))
            }
            _ => self.expected("a number"),
        }
    }

    /// Whether the next token is a number.
    pub fn at_number(&mut self) -> PResult<bool> {
        Ok(matches!(self.peek()?.tok, Tok::Int(_) | Tok::Float(_)))
    }

    /// `on`/`off`/`true`/`false` if next.
    pub fn try_bool(&mut self) -> PResult<Option<bool>> {
        let t = self.peek()?;
        if t.tok != Tok::Name {
            return Ok(None);
        }
        let v = match self.bytes(&t) {
            b"on" | b"true" => true,
            b"off" | b"false" => false,
            _ => return Ok(None),
        };
        self.bump()?;
        Ok(Some(v))
    }

    /// Enters a nested construct, failing past [`MAX_NESTING`].
    pub fn enter(&mut self, span: Span) -> PResult<()> {
        self.depth += 1;
        if self.depth > MAX_NESTING {
            return Err(Diagnostic::error(span, format!("nesting deeper than {MAX_NESTING} levels")));
        }
        Ok(())
    }

    /// Leaves a nested construct.
    pub fn leave(&mut self) {
        self.depth -= 1;
    }

    /// A warning.
    pub fn warn(&mut self, span: Span, message: impl Into<String>) {
        self.diags.push(Diagnostic::warning(span, message));
    }

    // ----- items -----

    fn error_count(&self) -> usize {
        self.diags.iter().chain(self.ts.diags.iter()).filter(|d| d.is_error()).count()
    }

    /// Parses items up to the end of the file (or of the included file, or `end namespace`).
    pub fn items(&mut self, until: Until) -> Vec<Item> {
        let mut items = Vec::new();
        loop {
            if self.error_count() >= self.max_errors {
                return items;
            }
            let t = match self.ts.peek_raw(0) {
                Ok(t) => t,
                Err(d) => {
                    // The stream has already stepped past the bad bytes.
                    self.diags.push(d);
                    continue;
                }
            };
            match t.tok {
                Tok::Eof => {
                    if let Until::Namespace(start) = until {
                        self.diags.push(Diagnostic::error(start, "'namespace' is not closed by 'end namespace'"));
                    }
                    return items;
                }
                Tok::IncludeEnd => {
                    let _ = self.ts.next_raw();
                    if until == Until::IncludeEnd {
                        return items;
                    }
                }
                Tok::IncludeBegin(index) => {
                    let _ = self.ts.next_raw();
                    self.depth += 1;
                    let inner = self.items(Until::IncludeEnd);
                    self.depth -= 1;
                    let rec = self.ts.includes[index as usize].clone();
                    items.push(Item::Include(Include {
                        path: Name { text: rec.path, span: rec.span },
                        angle: rec.angle,
                        target: rec.target,
                        items: inner,
                    }));
                }
                Tok::CodeBlock => {
                    let _ = self.ts.next_raw();
                    let text = String::from_utf8_lossy(self.bytes(&t)).into_owned();
                    items.push(Item::Command(Command::CodeBlock { text, span: t.span }));
                }
                _ => {
                    if let Until::Namespace(_) = until {
                        match self.at_end("namespace") {
                            Ok(true) => {
                                let _ = self.expect_end("namespace");
                                return items;
                            }
                            Ok(false) => {}
                            Err(d) => {
                                self.diags.push(d);
                                continue;
                            }
                        }
                    }
                    self.ends.clear();
                    match self.item() {
                        Ok(item) => items.push(item),
                        Err(d) => {
                            self.diags.push(d);
                            self.recover();
                        }
                    }
                }
            }
        }
    }

    /// Skips to the end of the element an error was found in (or to the next line that
    /// starts with a top-level keyword).
    fn recover(&mut self) {
        let end = self.ends.first().copied();
        self.ends.clear();
        loop {
            let t = match self.ts.peek_raw(0) {
                Ok(t) => t,
                Err(_) => continue,
            };
            match t.tok {
                Tok::Eof | Tok::IncludeEnd | Tok::IncludeBegin(_) => return,
                Tok::Name => {
                    if let Some(end) = end {
                        if self.is(&t, "end") && self.at_words(&format!("end {end}")).unwrap_or(false) {
                            for _ in 0..=end.split(' ').count() {
                                let _ = self.ts.next_raw();
                            }
                            return;
                        }
                    } else if self.starts_line(&t) && TOP_LEVEL.iter().any(|k| self.is(&t, k)) {
                        return;
                    }
                }
                _ => {}
            }
            let _ = self.ts.next_raw();
        }
    }

    /// Whether only blanks precede the token on its line.
    fn starts_line(&self, t: &Token) -> bool {
        let src = &self.ts.sources.file(t.span.file).bytes;
        src[..t.span.lo as usize].iter().rev().take_while(|&&b| b != b'\n').all(|b| b.is_ascii_whitespace())
    }

    /// One top-level item.
    fn item(&mut self) -> PResult<Item> {
        let t = self.peek()?;
        match t.tok {
            Tok::Name => {}
            Tok::Directive(Directive::Lookup) => {
                self.bump()?;
                let args = crate::lexer::directive_args(self.bytes(&t));
                let key = Name { text: String::from_utf8_lossy(args).trim_matches('"').to_string(), span: t.span };
                return Ok(Item::Command(Command::Kw(KwStmt {
                    key: "$lookup",
                    args: vec![Arg::Name(key)],
                    span: t.span,
                })));
            }
            _ => {
                return Err(Diagnostic::error(
                    t.span,
                    format!("expected an element or command, found {}", self.describe(&t)),
                ))
            }
        }
        let word = self.bytes(&t).to_vec();
        let item = match word.as_slice() {
            b"incremental" | b"private" | b"session" => {
                let mut prefixes = Vec::new();
                loop {
                    let p = self.peek()?;
                    if self.is(&p, "incremental") || self.is(&p, "private") {
                        self.bump()?;
                        let key = if self.is(&p, "incremental") { "incremental" } else { "private" };
                        prefixes.push(KwStmt { key, args: Vec::new(), span: p.span });
                    } else if self.is(&p, "session") {
                        self.bump()?;
                        self.expect("depth")?;
                        let n = self.int()?;
                        prefixes.push(KwStmt { key: "session depth", args: vec![Arg::Int(n)], span: p.span });
                    } else {
                        break;
                    }
                }
                let inner = self.item()?;
                Item::Modified { prefixes, item: Box::new(inner) }
            }
            b"options" => Item::Options(self.block("options", crate::grammar::OPTIONS)?),
            b"camera" => Item::Camera(self.block("camera", crate::grammar::CAMERA)?),
            b"light" => Item::Light(self.block("light", crate::grammar::LIGHT)?),
            b"lightprofile" => Item::Lightprofile(self.block("lightprofile", crate::grammar::LIGHTPROFILE)?),
            b"assembly" => Item::Assembly(self.block("assembly", crate::grammar::ASSEMBLY)?),
            b"colorprofile" => Item::Colorprofile(self.block("colorprofile", crate::grammar::COLORPROFILE)?),
            b"spectrum" => Item::Spectrum(self.spectrum()?),
            b"material" => Item::Material(self.material()?),
            b"local" | b"filter" | b"writable" | b"color" | b"scalar" | b"vector" => Item::Texture(self.texture()?),
            b"object" => Item::Object(self.object()?),
            b"instance" => Item::Instance(self.instance()?),
            b"instgroup" => Item::Instgroup(self.instgroup()?),
            b"shader" => Item::Shader(self.shader_def()?),
            b"declare" => Item::Declare(self.declaration()?),
            b"data" => Item::Data(self.data()?),
            b"gui" => Item::Gui(self.gui()?),
            b"namespace" => {
                self.bump()?;
                let name = self.name()?;
                self.enter(t.span)?;
                let items = self.items(Until::Namespace(t.span));
                self.leave();
                Item::Namespace(Namespace { name, items, span: t.span })
            }
            b"delete" => {
                self.bump()?;
                Item::Delete(self.name()?)
            }
            b"render" => {
                self.bump()?;
                let root = self.name()?;
                let camera = self.name()?;
                let options = self.name()?;
                let span = t.span.to(options.span);
                Item::Render(Render { root, camera, options, span })
            }
            b"registry" => Item::Registry(self.registry()?),
            b"set" => {
                // The variable is recorded before anything after it is looked at: the next
                // line may be a conditional that tests it.
                self.bump()?;
                let var = self.name()?;
                self.ts.set_var(&var.text, "");
                let mut args = vec![Arg::Name(var.clone())];
                let mut end = var.span;
                if self.at_str()? {
                    let value = self.name()?;
                    self.ts.set_var(&var.text, &value.text);
                    end = value.span;
                    args.push(Arg::Name(value));
                }
                Item::Command(Command::Kw(KwStmt { key: "set", args, span: t.span.to(end) }))
            }
            b"frame" => {
                return Err(Diagnostic::error(
                    t.span,
                    "the mental ray 1 'frame … end frame' form is obsolete and not read by mira",
                ))
            }
            _ => {
                let Some(stmt) = self.kw_stmt(&[crate::grammar::COMMANDS])? else {
                    return Err(Diagnostic::error(
                        t.span,
                        format!("unknown keyword {}: expected an element or command", self.describe(&t)),
                    ));
                };
                Item::Command(Command::Kw(stmt))
            }
        };
        Ok(item)
    }
}

/// What ends a list of items.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Until {
    /// The end of the main file.
    Eof,
    /// The end of an included file.
    IncludeEnd,
    /// `end namespace` (the span of `namespace`).
    Namespace(Span),
}
