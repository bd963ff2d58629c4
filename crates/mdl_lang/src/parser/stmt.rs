//! Statements of function bodies: blocks, declarations, expressions, `if`, loops, `return`.

use mi::{Diagnostic, Span};

use super::{PResult, Parser};
use crate::ast::*;
use crate::lexer::TokenKind;

impl Parser {
    /// The statements of a block whose `{` (at `open`) was just read, through its `}`.
    pub(super) fn block_items(&mut self, open: Span) -> PResult<Vec<Stmt>> {
        let mut items = Vec::new();
        loop {
            if self.eat_punct("}") {
                return Ok(items);
            }
            if *self.peek() == TokenKind::Eof {
                return Err(Diagnostic::error(open, "block is not closed: `{` without a matching `}`"));
            }
            items.push(self.statement()?);
        }
    }

    fn statement(&mut self) -> PResult<Stmt> {
        self.depth += 1;
        if self.depth > 200 {
            return self.error("statements are nested too deeply");
        }
        let r = self.statement_inner();
        self.depth -= 1;
        r
    }

    fn statement_inner(&mut self) -> PResult<Stmt> {
        self.check_unsupported()?;
        let start = self.span();
        let kind = if self.eat_punct(";") {
            StmtKind::Empty
        } else if self.is_punct("{") {
            let open = self.bump().span;
            StmtKind::Block(self.block_items(open)?)
        } else if self.eat_word("if") {
            let cond = self.paren_cond("if")?;
            let then = Box::new(self.statement()?);
            let otherwise = if self.eat_word("else") { Some(Box::new(self.statement()?)) } else { None };
            StmtKind::If { cond, then, otherwise }
        } else if self.eat_word("while") {
            let cond = self.paren_cond("while")?;
            StmtKind::While { cond, body: Box::new(self.statement()?) }
        } else if self.eat_word("do") {
            let body = Box::new(self.statement()?);
            if !self.eat_word("while") {
                return self.expected("`while` after the body of `do`");
            }
            let cond = self.paren_cond("do … while")?;
            self.expect_punct(";")?;
            StmtKind::DoWhile { body, cond }
        } else if self.eat_word("switch") {
            self.switch()?
        } else if self.is_word("case") || self.is_word("default") {
            return self.error("`case` or `default` outside a `switch`");
        } else if self.eat_word("for") {
            self.for_loop()?
        } else if self.eat_word("return") {
            let value = if self.is_punct(";") { None } else { Some(Box::new(self.expr()?)) };
            self.expect_punct(";")?;
            StmtKind::Return(value)
        } else if self.eat_word("break") {
            self.expect_punct(";")?;
            StmtKind::Break
        } else if self.eat_word("continue") {
            self.expect_punct(";")?;
            StmtKind::Continue
        } else if self.is_word("else") {
            return self.error("`else` without a matching `if`");
        } else if self.at_declaration() {
            StmtKind::Var(self.var_decls(true)?)
        } else {
            let e = self.expr()?;
            if self.is_punct(",") {
                return self.error("the comma operator is not supported yet");
            }
            self.expect_punct(";")?;
            StmtKind::Expr(Box::new(e))
        };
        Ok(Stmt { kind, span: start.to(self.prev_span()) })
    }

    /// `( expression )` after `if`/`while`.
    fn paren_cond(&mut self, what: &str) -> PResult<Box<Expr>> {
        if !self.is_punct("(") {
            return self.expected(&format!("`(` and the condition of `{what}`"));
        }
        self.bump();
        let cond = self.expr()?;
        self.expect_punct(")")?;
        Ok(Box::new(cond))
    }

    /// `(value) { case …: … }` after `switch`.
    fn switch(&mut self) -> PResult<StmtKind> {
        let value = self.paren_cond("switch")?;
        let open = self.expect_punct("{")?;
        let mut cases: Vec<SwitchCase> = Vec::new();
        loop {
            if self.eat_punct("}") {
                return Ok(StmtKind::Switch { value, cases });
            }
            let start = self.span();
            let label = if self.eat_word("case") {
                Some(self.expr_no_assign()?)
            } else if self.eat_word("default") {
                if cases.iter().any(|c| c.label.is_none()) {
                    return Err(Diagnostic::error(start, "a second `default` in one `switch`"));
                }
                None
            } else if *self.peek() == TokenKind::Eof {
                return Err(Diagnostic::error(open, "`switch` block is not closed: `{` without a matching `}`"));
            } else {
                return self.expected("`case` or `default` in a `switch`");
            };
            self.expect_punct(":")?;
            let mut body = Vec::new();
            while !(self.is_word("case") || self.is_word("default") || self.is_punct("}")) {
                if *self.peek() == TokenKind::Eof {
                    return Err(Diagnostic::error(open, "`switch` block is not closed: `{` without a matching `}`"));
                }
                body.push(self.statement()?);
            }
            cases.push(SwitchCase { label, body, span: start });
        }
    }

    /// `for (init; cond; step) body` after `for`.
    fn for_loop(&mut self) -> PResult<StmtKind> {
        self.expect_punct("(")?;
        let init = if self.is_punct(";") {
            self.bump();
            None
        } else if self.at_declaration() {
            let start = self.span();
            let decls = self.var_decls(true)?;
            Some(Box::new(Stmt { kind: StmtKind::Var(decls), span: start.to(self.prev_span()) }))
        } else {
            let e = self.expr()?;
            let span = e.span;
            self.expect_punct(";")?;
            Some(Box::new(Stmt { kind: StmtKind::Expr(Box::new(e)), span }))
        };
        let cond = if self.is_punct(";") { None } else { Some(Box::new(self.expr()?)) };
        self.expect_punct(";")?;
        let step = if self.is_punct(")") {
            None
        } else {
            let first = self.expr()?;
            if self.is_punct(",") {
                let mut list = vec![first];
                while self.eat_punct(",") {
                    list.push(self.expr()?);
                }
                let span = list[0].span.to(list[list.len() - 1].span);
                Some(Box::new(Expr::new(ExprKind::Sequence(list), span)))
            } else {
                Some(Box::new(first))
            }
        };
        self.expect_punct(")")?;
        let body = Box::new(self.statement()?);
        Ok(StmtKind::For { init, cond, step, body })
    }
}
