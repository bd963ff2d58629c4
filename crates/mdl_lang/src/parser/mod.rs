//! Parser: tokens to a [`Module`] tree. The first error ends parsing and is returned as a
//! [`Diagnostic`] at the offending token.
//!
//! Declarations are read here; types and annotations in `types`, expressions in `expr`,
//! statements in `stmt`.

mod expr;
mod stmt;
mod types;

use mi::{Diagnostic, FileId, Span};

use crate::ast::*;
use crate::lexer::{tokenize, Token, TokenKind};

/// Words MDL reserves for constructs mira does not read yet: meeting one is an error naming it.
const UNSUPPORTED: &[(&str, &str)] = &[
    ("cast", "the `cast<T>(…)` operator"),
    ("auto", "an `auto` declaration"),
    ("declarative", "a `declarative` definition"),
    ("operator", "operator overloading"),
    ("namespace", "a `namespace` block"),
    ("goto", "`goto`"),
];

/// Parses the text of module `name` (absolute, `::a::b`) held in `file`.
///
/// `builtin` allows declarations without a body (for mira's built-in standard modules).
pub fn parse_module(name: &str, file: FileId, bytes: &[u8], builtin: bool) -> Result<Module, Diagnostic> {
    let tokens = tokenize(file, bytes)?;
    let mut p = Parser { tokens, pos: 0, builtin, next_local: 0, depth: 0, src: bytes.to_vec() };
    p.module(name, file)
}

/// Parser state: the token list and a cursor.
pub(crate) struct Parser {
    tokens: Vec<Token>,
    pos: usize,
    builtin: bool,
    /// Next id for a local declaration within the current definition.
    next_local: u32,
    /// Current nesting depth of expressions and statements.
    depth: u32,
    /// The source text (for the version number as written).
    src: Vec<u8>,
}

type PResult<T> = Result<T, Diagnostic>;

impl Parser {
    fn peek(&self) -> &TokenKind {
        &self.tokens[self.pos].kind
    }

    fn peek_at(&self, ahead: usize) -> &TokenKind {
        let i = (self.pos + ahead).min(self.tokens.len() - 1);
        &self.tokens[i].kind
    }

    fn span(&self) -> Span {
        self.tokens[self.pos].span
    }

    fn prev_span(&self) -> Span {
        self.tokens[self.pos.saturating_sub(1)].span
    }

    fn bump(&mut self) -> Token {
        let t = self.tokens[self.pos].clone();
        if self.pos + 1 < self.tokens.len() {
            self.pos += 1;
        }
        t
    }

    fn is_punct(&self, p: &str) -> bool {
        matches!(self.peek(), TokenKind::Punct(q) if *q == p)
    }

    fn is_punct_at(&self, ahead: usize, p: &str) -> bool {
        matches!(self.peek_at(ahead), TokenKind::Punct(q) if *q == p)
    }

    fn is_word(&self, w: &str) -> bool {
        matches!(self.peek(), TokenKind::Ident(s) if s == w)
    }

    fn eat_punct(&mut self, p: &str) -> bool {
        if self.is_punct(p) {
            self.bump();
            true
        } else {
            false
        }
    }

    fn eat_word(&mut self, w: &str) -> bool {
        if self.is_word(w) {
            self.bump();
            true
        } else {
            false
        }
    }

    /// A description of the current token for "expected X, found Y" messages.
    fn found(&self) -> String {
        match self.peek() {
            TokenKind::Ident(s) => format!("`{s}`"),
            TokenKind::Int(i) => format!("the number {i}"),
            TokenKind::Float { value, .. } => format!("the number {value}"),
            TokenKind::Str(_) => "a string".to_string(),
            TokenKind::Punct(p) => format!("`{p}`"),
            TokenKind::Eof => "the end of the file".to_string(),
        }
    }

    fn error<T>(&self, message: impl Into<String>) -> PResult<T> {
        Err(Diagnostic::error(self.span(), message))
    }

    fn expected<T>(&self, what: &str) -> PResult<T> {
        self.error(format!("expected {what}, found {}", self.found()))
    }

    fn expect_punct(&mut self, p: &str) -> PResult<Span> {
        if self.is_punct(p) {
            Ok(self.bump().span)
        } else {
            self.expected(&format!("`{p}`"))
        }
    }

    /// Reports the construct if the current word is one mira does not support yet.
    fn check_unsupported(&self) -> PResult<()> {
        if let TokenKind::Ident(w) = self.peek() {
            if let Some((_, what)) = UNSUPPORTED.iter().find(|(k, _)| k == w) {
                return self.error(format!("{what} is not supported yet"));
            }
        }
        Ok(())
    }

    /// An identifier (not a reserved word).
    fn ident(&mut self, what: &str) -> PResult<(String, Span)> {
        self.check_unsupported()?;
        match self.peek().clone() {
            TokenKind::Ident(s) if !is_keyword(&s) => Ok((s, self.bump().span)),
            _ => self.expected(what),
        }
    }

    fn module(&mut self, name: &str, file: FileId) -> PResult<Module> {
        let version = self.version()?;
        let mut module = Module {
            name: name.to_string(),
            file,
            version,
            annotations: Vec::new(),
            imports: Vec::new(),
            decls: Vec::new(),
            builtin: self.builtin,
        };
        while *self.peek() != TokenKind::Eof {
            if self.eat_punct(";") {
                continue;
            }
            let start = self.span();
            if self.is_word("module") {
                self.bump();
                module.annotations.extend(self.annotations()?.unwrap_or_default());
                self.expect_punct(";")?;
                continue;
            }
            let exported = self.eat_word("export");
            if self.is_word("import") || self.is_word("using") {
                let imports = self.import(exported, start)?;
                module.imports.extend(imports);
                continue;
            }
            let decl = self.declaration(exported)?;
            module.decls.push(decl);
        }
        Ok(module)
    }

    /// `mdl 1.7;`.
    fn version(&mut self) -> PResult<(u32, u32)> {
        if !self.is_word("mdl") {
            return self.expected("the version line `mdl X.Y;` at the start of the module");
        }
        self.bump();
        let at = self.span();
        let written = String::from_utf8_lossy(&self.src[at.lo as usize..at.hi as usize]).into_owned();
        let version = match self.peek() {
            TokenKind::Float { double: false, .. } | TokenKind::Int(_) => {
                let (major, minor) = written.split_once('.').unwrap_or((&written, "0"));
                let minor = if minor.is_empty() { "0" } else { minor };
                (major.parse::<u32>().ok(), minor.parse::<u32>().ok())
            }
            _ => return self.expected("a version number such as `1.7`"),
        };
        self.bump();
        let version = match version {
            (Some(1), Some(minor)) => (1, minor),
            _ => {
                return Err(Diagnostic::error(
                    at,
                    format!("MDL version {written} is not supported (mira reads MDL 1.x)"),
                ))
            }
        };
        self.expect_punct(";")?;
        Ok(version)
    }

    /// A module path for an import: `::a::b`, `.::a`, `..::..::a`, `a::b`; a trailing `::*`
    /// is left for the caller.
    fn module_path(&mut self) -> PResult<ModulePath> {
        let mut path = ModulePath { absolute: false, parents: 0, relative: false, parts: Vec::new() };
        if self.eat_punct("::") {
            path.absolute = true;
        } else if self.is_punct(".") {
            path.relative = true;
            loop {
                if self.eat_punct(".") {
                    if self.eat_punct(".") {
                        path.parents += 1;
                    }
                    self.expect_punct("::")?;
                } else {
                    break;
                }
            }
        }
        if matches!(self.peek(), TokenKind::Str(_)) {
            return self.error("quoted (Unicode) module names are not supported yet");
        }
        loop {
            if self.is_punct("*") {
                break;
            }
            let (part, _) = self.ident("a module name")?;
            path.parts.push(part);
            if self.is_punct("::") {
                self.bump();
            } else {
                break;
            }
        }
        Ok(path)
    }

    fn import(&mut self, exported: bool, start: Span) -> PResult<Vec<Import>> {
        if self.eat_word("import") {
            if exported {
                return Err(Diagnostic::error(start, "`export import` is not MDL: use `export using … import`"));
            }
            // `import ::a::b::*, ::c::d;`: each item is a module path ending in `*` or a name.
            let mut kinds = Vec::new();
            loop {
                let item_start = self.span();
                let mut path = self.module_path()?;
                let names = if self.eat_punct("*") {
                    ImportNames::All
                } else {
                    let Some(name) = path.parts.pop() else {
                        return Err(Diagnostic::error(item_start, "expected a module name to import"));
                    };
                    if path.parts.is_empty() {
                        return Err(Diagnostic::error(
                            item_start,
                            format!(
                                "`import {name}` names no module: write `import ::module::{name};` or `::module::*`"
                            ),
                        ));
                    }
                    ImportNames::Some(vec![name])
                };
                kinds.push(ImportKind::Import { module: path, names });
                if !self.eat_punct(",") {
                    break;
                }
            }
            self.expect_punct(";")?;
            let span = start.to(self.prev_span());
            return Ok(kinds.into_iter().map(|kind| Import { kind, exported, span, resolved: None }).collect());
        }
        // `using`.
        self.bump();
        if matches!(self.peek(), TokenKind::Ident(_)) && self.is_punct_at(1, "=") {
            let (alias, _) = self.ident("an alias name")?;
            self.expect_punct("=")?;
            let module = self.module_path()?;
            self.expect_punct(";")?;
            let kind = ImportKind::Alias { alias, module };
            return Ok(vec![Import { kind, exported, span: start.to(self.prev_span()), resolved: None }]);
        }
        let module = self.module_path()?;
        if !self.eat_word("import") {
            return self.expected("`import` after the module name of `using`");
        }
        let names = if self.eat_punct("*") {
            ImportNames::All
        } else {
            let mut names = vec![self.ident("a name to import")?.0];
            while self.eat_punct(",") {
                names.push(self.ident("a name to import")?.0);
            }
            ImportNames::Some(names)
        };
        self.expect_punct(";")?;
        let kind = ImportKind::Using { module, names };
        Ok(vec![Import { kind, exported, span: start.to(self.prev_span()), resolved: None }])
    }

    fn declaration(&mut self, exported: bool) -> PResult<Decl> {
        self.check_unsupported()?;
        if self.eat_word("struct") {
            return self.struct_decl(exported);
        }
        if self.eat_word("enum") {
            return self.enum_decl(exported);
        }
        if self.eat_word("typedef") {
            let ty = self.type_ref()?;
            let (name, span) = self.ident("a type name")?;
            self.expect_punct(";")?;
            return Ok(Decl::Typedef(TypedefDecl { exported, ty, name, span }));
        }
        if self.eat_word("annotation") {
            let (name, span) = self.ident("an annotation name")?;
            let params = self.params(false)?.unwrap_or_default();
            self.annotations()?;
            self.expect_punct(";")?;
            return Ok(Decl::Annotation(AnnotationDecl { exported, name, params, span }));
        }
        if self.is_word("const") {
            return self.const_decl(exported);
        }
        if matches!(self.peek(), TokenKind::Ident(_)) || self.is_punct("::") {
            let ret = self.type_ref()?;
            let (name, span) = self.ident("a name for the definition")?;
            if self.is_punct("(") {
                return self.function(exported, ret, name, span);
            }
            return Err(Diagnostic::error(
                span,
                format!("module-level variable `{name}`: only `const` declarations and definitions are allowed here"),
            ));
        }
        self.expected("a declaration (material, function, struct, enum, const, import)")
    }

    fn const_decl(&mut self, exported: bool) -> PResult<Decl> {
        let ty = self.type_ref()?;
        let (name, span) = self.ident("a constant name")?;
        let value = if self.eat_punct("=") {
            self.expr_no_assign()?
        } else if self.is_punct("(") {
            // `const float3 v(1, 2, 3);` constructs the value.
            self.constructor_init(&ty.ty)?
        } else {
            return self.expected("`=` and the constant's value");
        };
        let annotations = self.annotations()?.unwrap_or_default();
        if self.is_punct(",") {
            return self.error("several constants in one declaration are not supported yet");
        }
        self.expect_punct(";")?;
        Ok(Decl::Const(ConstDecl { exported, ty, name, value, annotations, span }))
    }

    fn struct_decl(&mut self, exported: bool) -> PResult<Decl> {
        // `material` and its parts are declared in mira's built-in prelude as structs.
        let (name, span) = match self.peek().clone() {
            TokenKind::Ident(s) if self.builtin && s == "material" => (s, self.bump().span),
            _ => self.ident("a struct name")?,
        };
        let annotations = self.annotations()?.unwrap_or_default();
        self.expect_punct("{")?;
        let mut fields = Vec::new();
        while !self.eat_punct("}") {
            let ty = self.type_ref()?;
            let (fname, fspan) = self.ident("a field name")?;
            let default = if self.eat_punct("=") { Some(self.expr()?) } else { None };
            let fannos = self.annotations()?.unwrap_or_default();
            self.expect_punct(";")?;
            fields.push(Field { ty, name: fname, default, annotations: fannos, span: fspan });
        }
        self.expect_punct(";")?;
        Ok(Decl::Struct(StructDecl { exported, name, fields, annotations, span }))
    }

    fn enum_decl(&mut self, exported: bool) -> PResult<Decl> {
        let (name, span) = self.ident("an enum name")?;
        let annotations = self.annotations()?.unwrap_or_default();
        self.expect_punct("{")?;
        let mut values: Vec<EnumValue> = Vec::new();
        loop {
            if self.eat_punct("}") {
                break;
            }
            let (vname, vspan) = self.ident("an enum value name")?;
            let init = if self.eat_punct("=") { Some(self.expr_no_assign()?) } else { None };
            let value = match &init {
                Some(e) => const_int(e, &values).ok_or_else(|| {
                    Diagnostic::error(
                        e.span,
                        "enum value is not a constant integer expression mira can evaluate \
                         (integers, earlier values of the enum, + - * / % << >> & | ^ ~)",
                    )
                })?,
                None => values.last().map_or(Ok(0), |v| {
                    v.value.checked_add(1).ok_or_else(|| Diagnostic::error(vspan, "enum value overflows"))
                })?,
            };
            let vannos = self.annotations()?.unwrap_or_default();
            values.push(EnumValue { name: vname, init, value, annotations: vannos, span: vspan });
            if !self.eat_punct(",") {
                self.expect_punct("}")?;
                break;
            }
        }
        if values.is_empty() {
            return Err(Diagnostic::error(span, format!("enum `{name}` has no values")));
        }
        self.expect_punct(";")?;
        Ok(Decl::Enum(EnumDecl { exported, name, values, annotations, span }))
    }

    /// `( params )`; `(*)` (a variant) gives `None` when `allow_star`.
    fn params(&mut self, allow_star: bool) -> PResult<Option<Vec<Param>>> {
        self.expect_punct("(")?;
        if allow_star && self.is_punct("*") && self.is_punct_at(1, ")") {
            self.bump();
            self.bump();
            return Ok(None);
        }
        let mut params = Vec::new();
        if self.eat_punct(")") {
            return Ok(Some(params));
        }
        loop {
            let ty = self.type_ref()?;
            let (name, span) = self.ident("a parameter name")?;
            if params.iter().any(|p: &Param| p.name == name) {
                return Err(Diagnostic::error(span, format!("parameter `{name}` is declared twice")));
            }
            let default = if self.eat_punct("=") { Some(self.expr_no_assign()?) } else { None };
            let annotations = self.annotations()?.unwrap_or_default();
            params.push(Param { ty, name, default, annotations, span });
            if self.eat_punct(")") {
                break;
            }
            if !self.eat_punct(",") {
                return self.expected("`,` or `)` after a parameter");
            }
        }
        Ok(Some(params))
    }

    fn function(&mut self, exported: bool, ret: TypeRef, name: String, span: Span) -> PResult<Decl> {
        self.next_local = 0;
        let is_material = ret.ty == Type::Material;
        let params = self.params(is_material)?;
        let frequency = if self.eat_word("uniform") {
            Frequency::Uniform
        } else if self.eat_word("varying") {
            Frequency::Varying
        } else {
            Frequency::Auto
        };
        let annotations = self.annotations()?.unwrap_or_default();
        let body = if self.eat_punct("=") {
            let e = self.expr_no_assign()?;
            self.expect_punct(";")?;
            Body::Expr(e)
        } else if self.is_punct("{") {
            if is_material {
                return self
                    .error(format!("material `{name}` has a statement body: a material's body is `= expression;`"));
            }
            let open = self.bump().span;
            Body::Block(self.block_items(open)?)
        } else if self.is_punct(";") && self.builtin {
            self.bump();
            Body::Native
        } else if self.is_punct(";") {
            return self.error(format!("`{name}` is declared without a body (prototypes are not supported yet)"));
        } else {
            return self.expected("`=` or `{` and the body of the definition");
        };
        let (params, variant) = match params {
            Some(p) => (p, None),
            None => {
                let Body::Expr(Expr { kind: ExprKind::Call(call), .. }) = &body else {
                    return Err(Diagnostic::error(
                        span,
                        format!("variant `{name}(*)` must be a call of its base material"),
                    ));
                };
                if call.array.is_some() {
                    return Err(Diagnostic::error(
                        span,
                        format!("variant `{name}(*)` must be a call of its base material"),
                    ));
                }
                (Vec::new(), Some(Variant { base: call.callee.clone(), resolved: None }))
            }
        };
        Ok(Decl::Function(Function { exported, ret, name, params, frequency, annotations, body, variant, span }))
    }

    fn new_local(&mut self) -> u32 {
        self.next_local += 1;
        self.next_local - 1
    }
}

/// MDL keywords that can never be a name.
fn is_keyword(word: &str) -> bool {
    matches!(
        word,
        "mdl"
            | "import"
            | "using"
            | "export"
            | "module"
            | "let"
            | "in"
            | "if"
            | "else"
            | "for"
            | "while"
            | "do"
            | "return"
            | "break"
            | "continue"
            | "switch"
            | "case"
            | "default"
            | "struct"
            | "enum"
            | "typedef"
            | "const"
            | "uniform"
            | "varying"
            | "true"
            | "false"
            | "material"
            | "annotation"
    ) || UNSUPPORTED.iter().any(|(k, _)| *k == word)
}

/// The value of a constant integer expression: literals, earlier values of the same enum
/// (`known`), parentheses and the integer operators (`+ - * / % << >> & | ^ ~`, unary `-`).
/// `None` for anything else, including overflow and division by zero.
fn const_int(e: &Expr, known: &[EnumValue]) -> Option<i64> {
    match &e.kind {
        ExprKind::Int(i) => Some(*i),
        ExprKind::Name(n) if !n.name.is_qualified() => known.iter().find(|v| v.name == n.name.last()).map(|v| v.value),
        ExprKind::Unary { op, operand } => {
            let v = const_int(operand, known)?;
            match op {
                UnaryOp::Neg => v.checked_neg(),
                UnaryOp::Plus => Some(v),
                UnaryOp::BitNot => Some(!v),
                _ => None,
            }
        }
        ExprKind::Binary { op, lhs, rhs } => {
            let (a, b) = (const_int(lhs, known)?, const_int(rhs, known)?);
            let shift = u32::try_from(b).ok().filter(|s| *s < 64);
            match op {
                BinaryOp::Add => a.checked_add(b),
                BinaryOp::Sub => a.checked_sub(b),
                BinaryOp::Mul => a.checked_mul(b),
                BinaryOp::Div => a.checked_div(b),
                BinaryOp::Rem => a.checked_rem(b),
                BinaryOp::Shl => shift.and_then(|s| a.checked_shl(s)),
                BinaryOp::Shr => shift.and_then(|s| a.checked_shr(s)),
                BinaryOp::BitAnd => Some(a & b),
                BinaryOp::BitOr => Some(a | b),
                BinaryOp::BitXor => Some(a ^ b),
                _ => None,
            }
        }
        _ => None,
    }
}
