//! Statements of function bodies: scopes, conditions, loops and `return` types.

use super::Checker;
use crate::ast::*;

impl Checker<'_> {
    /// Checks a block in a scope of its own.
    pub(super) fn block(&mut self, stmts: &mut [Stmt]) {
        let mark = self.locals.len();
        for s in stmts {
            self.stmt(s);
        }
        self.locals.truncate(mark);
    }

    fn condition(&mut self, cond: &mut Expr, what: &str) {
        if let Some(t) = self.expr(cond) {
            if !t.converts_to(&Type::BOOL) {
                self.error(cond.span, format!("the condition of `{what}` is of type `{t}`, expected `bool`"));
            }
        }
    }

    fn stmt(&mut self, s: &mut Stmt) {
        let span = s.span;
        match &mut s.kind {
            StmtKind::Block(items) => self.block(items),
            StmtKind::Var(decls) => {
                for d in decls {
                    self.var_decl(d);
                }
            }
            StmtKind::Expr(e) => {
                self.expr(e);
            }
            StmtKind::If { cond, then, otherwise } => {
                self.condition(cond, "if");
                self.scoped(then);
                if let Some(o) = otherwise {
                    self.scoped(o);
                }
            }
            StmtKind::For { init, cond, step, body } => {
                let mark = self.locals.len();
                if let Some(init) = init {
                    self.stmt(init);
                }
                if let Some(cond) = cond {
                    self.condition(cond, "for");
                }
                if let Some(step) = step {
                    self.expr(step);
                }
                self.loops += 1;
                self.scoped(body);
                self.loops -= 1;
                self.locals.truncate(mark);
            }
            StmtKind::While { cond, body } => {
                self.condition(cond, "while");
                self.loops += 1;
                self.scoped(body);
                self.loops -= 1;
            }
            StmtKind::DoWhile { body, cond } => {
                self.loops += 1;
                self.scoped(body);
                self.loops -= 1;
                self.condition(cond, "do … while");
            }
            StmtKind::Switch { value, cases } => {
                if let Some(t) = self.expr(value) {
                    if !matches!(t, Type::Scalar(Scalar::Int) | Type::Enum(_)) {
                        self.error(value.span, format!("a `switch` value is of type `{t}`, expected `int` or an enum"));
                    }
                }
                // `break` leaves a switch as it leaves a loop.
                self.loops += 1;
                let mark = self.locals.len();
                for case in cases {
                    if let Some(label) = &mut case.label {
                        self.expr(label);
                    }
                    for s in &mut case.body {
                        self.stmt(s);
                    }
                }
                self.locals.truncate(mark);
                self.loops -= 1;
            }
            StmtKind::Return(value) => {
                let ret = self.ret.clone();
                match (value, ret) {
                    (Some(v), Some(ret)) => {
                        self.expr(v);
                        self.expect_type(v, &ret, "the returned value");
                    }
                    (None, Some(ret)) => {
                        self.error(span, format!("`return` without a value in a function returning `{ret}`"))
                    }
                    (Some(v), None) => {
                        self.expr(v);
                    }
                    (None, None) => {}
                }
            }
            StmtKind::Break | StmtKind::Continue if self.loops == 0 => {
                self.error(span, "`break` or `continue` outside a loop");
            }
            StmtKind::Break | StmtKind::Continue | StmtKind::Empty => {}
        }
    }

    /// A statement in a scope of its own (the branch of an `if`, a loop body).
    fn scoped(&mut self, s: &mut Stmt) {
        let mark = self.locals.len();
        self.stmt(s);
        self.locals.truncate(mark);
    }
}
