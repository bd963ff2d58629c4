//! Types as written (`uniform color`, `float[<N>]`, `::base::texture_return`), qualified names
//! and annotation blocks `[[ … ]]`.

use super::{PResult, Parser};
use crate::ast::*;
use crate::lexer::TokenKind;

impl Parser {
    /// A qualified name: `a`, `a::b`, `::a::b`.
    pub(super) fn qual_name(&mut self, what: &str) -> PResult<QualName> {
        let absolute = self.eat_punct("::");
        let mut parts = vec![self.name_part(what)?];
        while self.is_punct("::") && matches!(self.peek_at(1), TokenKind::Ident(_)) {
            self.bump();
            parts.push(self.name_part(what)?);
        }
        Ok(QualName { absolute, parts })
    }

    /// One part of a qualified name; `material` counts as a name here (it names a type and
    /// its constructor).
    fn name_part(&mut self, what: &str) -> PResult<String> {
        if self.is_word("material") {
            self.bump();
            return Ok("material".to_string());
        }
        Ok(self.ident(what)?.0)
    }

    /// A type with its modifiers: `[const] [uniform|varying] name [array]`.
    pub(super) fn type_ref(&mut self) -> PResult<TypeRef> {
        let start = self.span();
        let constant = self.eat_word("const");
        let frequency = if self.eat_word("uniform") {
            Frequency::Uniform
        } else if self.eat_word("varying") {
            Frequency::Varying
        } else {
            Frequency::Auto
        };
        self.check_unsupported()?;
        if !(matches!(self.peek(), TokenKind::Ident(_)) || self.is_punct("::")) {
            return self.expected("a type");
        }
        let name = self.qual_name("a type name")?;
        let mut ty = named_type(name);
        if self.is_punct("[") && !self.is_punct_at(1, "[") {
            let len = self.array_len()?;
            ty = Type::Array(Box::new(ty), len);
        }
        if self.is_punct("[") && !self.is_punct_at(1, "[") {
            return self.error("arrays of arrays are not MDL");
        }
        Ok(TypeRef { frequency, constant, ty, span: start.to(self.prev_span()) })
    }

    /// `[]`, `[<N>]`, `[3]` or `[SIZE]` after a type name.
    pub(super) fn array_len(&mut self) -> PResult<ArrayLen> {
        self.expect_punct("[")?;
        if self.eat_punct("]") {
            return Ok(ArrayLen::Unsized);
        }
        if self.eat_punct("<") {
            let (symbol, _) = self.ident("a size symbol for a deferred-size array")?;
            self.expect_punct(">")?;
            self.expect_punct("]")?;
            return Ok(ArrayLen::Deferred(symbol));
        }
        let len = match self.peek().clone() {
            TokenKind::Int(n) if n >= 0 => {
                self.bump();
                ArrayLen::Fixed(n as u64)
            }
            TokenKind::Int(_) => return self.error("array size is negative"),
            TokenKind::Ident(_) | TokenKind::Punct("::") => ArrayLen::Named(self.qual_name("an array size")?),
            _ => return self.expected("an array size (an integer, a constant name, `<N>` or nothing)"),
        };
        if !self.is_punct("]") {
            return self.error(
                "array sizes must be an integer literal or a constant name (expressions are not supported yet)",
            );
        }
        self.bump();
        Ok(len)
    }

    /// An annotation block `[[ a(…), b(…) ]]`, if one starts here.
    pub(super) fn annotations(&mut self) -> PResult<Option<Vec<Annotation>>> {
        if !(self.is_punct("[") && self.is_punct_at(1, "[")) {
            return Ok(None);
        }
        self.bump();
        self.bump();
        let mut list = Vec::new();
        loop {
            if self.is_punct("]") {
                break;
            }
            let start = self.span();
            let name = self.qual_name("an annotation name")?;
            let args = if self.is_punct("(") { self.call_args()? } else { Vec::new() };
            list.push(Annotation { name, args, res: Resolution::Unresolved, span: start.to(self.prev_span()) });
            if !self.eat_punct(",") {
                break;
            }
        }
        if !(self.is_punct("]") && self.is_punct_at(1, "]")) {
            return self.expected("`]]` closing the annotation block");
        }
        self.bump();
        self.bump();
        Ok(Some(list))
    }

    /// Whether a declaration `type name …` starts here (tried without consuming anything).
    pub(super) fn at_declaration(&mut self) -> bool {
        if self.is_word("const") || self.is_word("uniform") || self.is_word("varying") {
            return true;
        }
        let save = self.pos;
        let ok = self.type_ref().is_ok() && matches!(self.peek(), TokenKind::Ident(w) if !super::is_keyword(w));
        self.pos = save;
        ok
    }
}

/// The type a name denotes: a built-in type, or a user name for the semantic pass.
pub(super) fn named_type(name: QualName) -> Type {
    if !name.is_qualified() {
        if let Some(t) = Type::builtin(name.last()) {
            return t;
        }
    }
    Type::Named(name)
}
