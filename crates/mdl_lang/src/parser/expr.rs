//! Expressions, by precedence climbing over MDL's (C's) operator classes.

use mi::Diagnostic;

use super::{PResult, Parser};
use crate::ast::*;
use crate::lexer::TokenKind;

/// Deepest nesting of expressions read (hostile input must not overflow the stack).
const MAX_DEPTH: u32 = 200;

impl Parser {
    /// A full expression including assignment (statement context).
    pub(super) fn expr(&mut self) -> PResult<Expr> {
        let target = self.expr_no_assign()?;
        let op = match self.peek() {
            TokenKind::Punct("=") => AssignOp::Set,
            TokenKind::Punct(p) if p.len() >= 2 && p.ends_with('=') && !matches!(*p, "==" | "!=" | "<=" | ">=") => {
                match BinaryOp::from_punct(&p[..p.len() - 1]) {
                    Some(op) => AssignOp::Compound(op),
                    None => return Ok(target),
                }
            }
            _ => return Ok(target),
        };
        self.bump();
        let value = self.nested(Parser::expr)?;
        let span = target.span.to(value.span);
        Ok(Expr::new(ExprKind::Assign { op, target: Box::new(target), value: Box::new(value) }, span))
    }

    /// An expression without assignment: `?:` and everything that binds tighter.
    pub(super) fn expr_no_assign(&mut self) -> PResult<Expr> {
        let cond = self.binary(1)?;
        if !self.eat_punct("?") {
            return Ok(cond);
        }
        let then = self.nested(Parser::expr_no_assign)?;
        self.expect_punct(":")?;
        let otherwise = self.nested(Parser::expr_no_assign)?;
        let span = cond.span.to(otherwise.span);
        Ok(Expr::new(
            ExprKind::Conditional { cond: Box::new(cond), then: Box::new(then), otherwise: Box::new(otherwise) },
            span,
        ))
    }

    /// Runs `f` one nesting level deeper, failing cleanly past [`MAX_DEPTH`].
    fn nested<T>(&mut self, f: impl FnOnce(&mut Parser) -> PResult<T>) -> PResult<T> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return self.error("expression is nested too deeply");
        }
        let r = f(self);
        self.depth -= 1;
        r
    }

    fn binary(&mut self, min_prec: u8) -> PResult<Expr> {
        let mut lhs = self.unary()?;
        // Each operator of a chain (`a + b + c …`) puts the tree one level deeper on its
        // left, as nesting does: counted as nesting, so that no chain makes a tree deeper
        // than MAX_DEPTH (every later pass over the tree, and dropping it, recurses).
        let depth = self.depth;
        while let Some(op) = self.binary_op(min_prec) {
            self.bump();
            self.deeper()?;
            let rhs = self.nested(|p| p.binary(op.precedence() + 1))?;
            let span = lhs.span.to(rhs.span);
            lhs = Expr::new(ExprKind::Binary { op, lhs: Box::new(lhs), rhs: Box::new(rhs) }, span);
        }
        self.depth = depth;
        Ok(lhs)
    }

    /// One level deeper for an operator that wraps the tree so far (a chain of binary
    /// operators, member accesses, indices): an error past [`MAX_DEPTH`].
    fn deeper(&mut self) -> PResult<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return self
                .error("expression is nested too deeply (more than 200 levels, counting each operator of a chain)");
        }
        Ok(())
    }

    /// The binary operator at the cursor if it binds at least as tightly as `min_prec`.
    fn binary_op(&self, min_prec: u8) -> Option<BinaryOp> {
        match self.peek() {
            TokenKind::Punct(p) => BinaryOp::from_punct(p).filter(|op| op.precedence() >= min_prec),
            _ => None,
        }
    }

    fn unary(&mut self) -> PResult<Expr> {
        let op = match self.peek() {
            TokenKind::Punct("-") => Some(UnaryOp::Neg),
            TokenKind::Punct("+") => Some(UnaryOp::Plus),
            TokenKind::Punct("!") => Some(UnaryOp::Not),
            TokenKind::Punct("~") => Some(UnaryOp::BitNot),
            TokenKind::Punct("++") => Some(UnaryOp::PreInc),
            TokenKind::Punct("--") => Some(UnaryOp::PreDec),
            _ => None,
        };
        if let Some(op) = op {
            let start = self.bump().span;
            let operand = self.nested(Parser::unary)?;
            let span = start.to(operand.span);
            return Ok(Expr::new(ExprKind::Unary { op, operand: Box::new(operand) }, span));
        }
        let mut e = self.primary()?;
        let depth = self.depth;
        loop {
            if self.is_punct(".") || self.is_punct("[") || self.is_punct("++") || self.is_punct("--") {
                self.deeper()?;
            }
            if self.eat_punct(".") {
                let (field, fspan) = self.ident("a field name after `.`")?;
                let span = e.span.to(fspan);
                e = Expr::new(ExprKind::Member { base: Box::new(e), field }, span);
            } else if self.is_punct("[") && !self.is_punct_at(1, "[") {
                self.bump();
                let index = self.nested(Parser::expr_no_assign)?;
                let end = self.expect_punct("]")?;
                let span = e.span.to(end);
                e = Expr::new(ExprKind::Index { base: Box::new(e), index: Box::new(index) }, span);
            } else if self.is_punct("++") || self.is_punct("--") {
                let op = if self.is_punct("++") { UnaryOp::PostInc } else { UnaryOp::PostDec };
                let end = self.bump().span;
                let span = e.span.to(end);
                e = Expr::new(ExprKind::Unary { op, operand: Box::new(e) }, span);
            } else if self.is_punct("(") {
                return self.error("only names can be called (a call of an expression is not MDL)");
            } else {
                self.depth = depth;
                return Ok(e);
            }
        }
    }

    fn primary(&mut self) -> PResult<Expr> {
        self.check_unsupported()?;
        let span = self.span();
        let literal = match self.peek().clone() {
            TokenKind::Int(i) => Some(ExprKind::Int(i)),
            TokenKind::Float { value, double } => Some(ExprKind::Float { value, double }),
            TokenKind::Str(s) => Some(ExprKind::Str(s)),
            TokenKind::Ident(w) if w == "true" || w == "false" => Some(ExprKind::Bool(w == "true")),
            _ => None,
        };
        if let Some(mut kind) = literal {
            self.bump();
            // Adjacent string literals are joined, as in C.
            while let (ExprKind::Str(joined), TokenKind::Str(next)) = (&mut kind, self.peek()) {
                joined.push_str(next);
                self.bump();
            }
            return Ok(Expr::new(kind, span.to(self.prev_span())));
        }
        if self.eat_punct("(") {
            let inner = self.nested(Parser::expr_no_assign)?;
            if self.is_punct(",") {
                return self.error("the comma operator is not supported yet");
            }
            let end = self.expect_punct(")")?;
            return Ok(Expr { span: span.to(end), ..inner });
        }
        if self.is_word("let") {
            return self.let_expr();
        }
        if !(matches!(self.peek(), TokenKind::Ident(_)) || self.is_punct("::")) {
            return self.expected("an expression");
        }
        let name = self.qual_name("a name")?;
        // Array constructor `T[](…)`, `T[3](…)`, `T[N](…)`.
        let array_ctor = self.is_punct("[")
            && ((self.is_punct_at(1, "]") && self.is_punct_at(2, "("))
                || (matches!(self.peek_at(1), TokenKind::Int(_) | TokenKind::Ident(_))
                    && self.is_punct_at(2, "]")
                    && self.is_punct_at(3, "(")));
        let array = if array_ctor { Some(self.array_len()?) } else { None };
        if self.is_punct("(") {
            let args = self.call_args()?;
            let span = span.to(self.prev_span());
            let call = Call { callee: name, array, args, res: Resolution::Unresolved };
            return Ok(Expr::new(ExprKind::Call(call), span));
        }
        let span = span.to(self.prev_span());
        Ok(Expr::new(ExprKind::Name(NameRef { name, res: Resolution::Unresolved }), span))
    }

    /// `( a, b, name: c )`: positional arguments first, then named ones.
    pub(super) fn call_args(&mut self) -> PResult<Vec<Arg>> {
        self.expect_punct("(")?;
        let mut args: Vec<Arg> = Vec::new();
        if self.eat_punct(")") {
            return Ok(args);
        }
        loop {
            let start = self.span();
            let name = match self.peek().clone() {
                TokenKind::Ident(n) if self.is_punct_at(1, ":") => {
                    self.bump();
                    self.bump();
                    Some(n)
                }
                _ => None,
            };
            if name.is_none() && args.iter().any(|a| a.name.is_some()) {
                return self.error("positional argument after a named argument");
            }
            if let Some(n) = &name {
                if args.iter().any(|a| a.name.as_ref() == Some(n)) {
                    return Err(Diagnostic::error(start, format!("argument `{n}` is given twice")));
                }
            }
            let value = self.nested(Parser::expr_no_assign)?;
            args.push(Arg { name, span: start.to(value.span), value });
            if self.eat_punct(")") {
                return Ok(args);
            }
            if !self.eat_punct(",") {
                return self.expected("`,` or `)` in the argument list");
            }
        }
    }

    /// `let decl in e` or `let { decls } in e`.
    fn let_expr(&mut self) -> PResult<Expr> {
        let start = self.bump().span;
        let mut decls = Vec::new();
        if self.eat_punct("{") {
            while !self.eat_punct("}") {
                if *self.peek() == TokenKind::Eof {
                    return self.expected("`}` closing the `let` declarations");
                }
                decls.extend(self.var_decls(true)?);
            }
        } else {
            decls.extend(self.var_decls(false)?);
        }
        if decls.is_empty() {
            return Err(Diagnostic::error(start, "`let` without declarations"));
        }
        if !self.eat_word("in") {
            return self.expected("`in` after the `let` declarations");
        }
        let body = self.nested(Parser::expr_no_assign)?;
        let span = start.to(body.span);
        Ok(Expr::new(ExprKind::Let { decls, body: Box::new(body) }, span))
    }

    /// `type a = …, b(…), c;` — the terminating `;` is required when `needs_semicolon`,
    /// optional otherwise (a single `let` declaration before `in`).
    pub(super) fn var_decls(&mut self, needs_semicolon: bool) -> PResult<Vec<VarDecl>> {
        let ty = self.type_ref()?;
        let mut decls = Vec::new();
        loop {
            let (name, span) = self.ident("a variable name")?;
            let init = if self.eat_punct("=") {
                Some(self.nested(Parser::expr_no_assign)?)
            } else if self.is_punct("(") {
                // `float3 v(1, 2, 3);` constructs the value.
                Some(self.constructor_init(&ty.ty)?)
            } else {
                None
            };
            let annotations = self.annotations()?.unwrap_or_default();
            let id = self.new_local();
            decls.push(VarDecl { ty: ty.clone(), name, init, id, annotations, span });
            if !self.eat_punct(",") {
                break;
            }
        }
        if needs_semicolon {
            self.expect_punct(";")?;
        } else {
            self.eat_punct(";");
        }
        Ok(decls)
    }
}

impl Parser {
    /// The argument list of a constructor-style initialisation `T name(args)`, as a call of
    /// the constructor of `ty`.
    pub(super) fn constructor_init(&mut self, ty: &Type) -> PResult<Expr> {
        let start = self.span();
        let args = self.call_args()?;
        let (callee, array) = type_callee(ty);
        let call = Call { callee, array, args, res: Resolution::Unresolved };
        Ok(Expr::new(ExprKind::Call(call), start.to(self.prev_span())))
    }
}

/// The name of a type's constructor (`float3`, `::m::s`) and, for arrays, the length.
fn type_callee(ty: &Type) -> (QualName, Option<ArrayLen>) {
    match ty {
        Type::Named(q) => (q.clone(), None),
        Type::Array(elem, len) => (type_callee(elem).0, Some(len.clone())),
        t => (QualName::simple(&t.to_string()), None),
    }
}
