//! Which expressions depend on the shading point: what a material compiler evaluates per hit,
//! as opposed to once per material instance.
//!
//! A value depends on the hit when it calls a function declared `varying` (the `state::`
//! functions: position, normal, texture coordinates, …), or a function or constructor whose
//! body, or the default of an argument left out, does. Texture lookups are per hit exactly
//! when their coordinates are. Parameters not yet replaced by arguments count as fixed:
//! substitute the instance's arguments first ([`crate::Function::instantiate`]).

use std::collections::HashMap;

use crate::ast::*;
use crate::module_set::ModuleSet;

/// Deepest chain of calls followed; deeper ones count as depending on the hit.
const MAX_CALL_DEPTH: u32 = 64;

/// An analysis over one [`ModuleSet`], remembering what it found for each definition called
/// with each pattern of per-hit arguments.
pub struct HitDependence<'a> {
    set: &'a ModuleSet,
    memo: HashMap<(String, usize, Vec<bool>), bool>,
    depth: u32,
}

/// What the names of one body stand for: whether each parameter, and each local, varies.
#[derive(Default)]
struct Env {
    params: Vec<bool>,
    locals: HashMap<u32, bool>,
}

impl<'a> HitDependence<'a> {
    /// A fresh analysis of expressions resolved against `set`.
    pub fn new(set: &'a ModuleSet) -> HitDependence<'a> {
        HitDependence { set, memo: HashMap::new(), depth: 0 }
    }

    /// Whether the value of `e` (resolved against this set, outside any definition) depends
    /// on the shading point.
    pub fn varies(&mut self, e: &Expr) -> bool {
        self.expr(e, &mut Env::default())
    }

    fn expr(&mut self, e: &Expr, env: &mut Env) -> bool {
        match &e.kind {
            ExprKind::Bool(_) | ExprKind::Int(_) | ExprKind::Float { .. } | ExprKind::Str(_) => false,
            ExprKind::Name(n) => match n.res {
                Resolution::Param(i) => env.params.get(i).copied().unwrap_or(false),
                Resolution::Local(id) => env.locals.get(&id).copied().unwrap_or(false),
                _ => false,
            },
            ExprKind::Call(call) => self.call(call, env),
            ExprKind::Unary { operand, .. } => self.expr(operand, env),
            ExprKind::Binary { lhs, rhs, .. } => {
                let (a, b) = (self.expr(lhs, env), self.expr(rhs, env));
                a || b
            }
            ExprKind::Conditional { cond, then, otherwise } => {
                let (a, b, c) = (self.expr(cond, env), self.expr(then, env), self.expr(otherwise, env));
                a || b || c
            }
            ExprKind::Member { base, .. } => self.expr(base, env),
            ExprKind::Index { base, index } => {
                let (a, b) = (self.expr(base, env), self.expr(index, env));
                a || b
            }
            ExprKind::Let { decls, body } => {
                for d in decls {
                    let v = d.init.as_ref().is_some_and(|i| self.expr(i, env));
                    env.locals.insert(d.id, v);
                }
                self.expr(body, env)
            }
            ExprKind::Sequence(list) => list.iter().any(|x| self.expr(x, env)),
            ExprKind::Assign { target, value, .. } => {
                let v = self.expr(value, env);
                if let (true, ExprKind::Name(NameRef { res: Resolution::Local(id), .. })) = (v, &target.kind) {
                    env.locals.insert(*id, true);
                }
                v
            }
        }
    }

    /// Whether each argument given to `params` (in `call`) or each default left in place
    /// varies; defaults see the values of earlier parameters.
    fn bound(&mut self, params: &[(String, Option<Expr>)], call: &Call, env: &mut Env) -> Vec<bool> {
        let mut given: Vec<Option<bool>> = vec![None; params.len()];
        for (i, a) in call.args.iter().enumerate() {
            let idx = match &a.name {
                Some(n) => params.iter().position(|(p, _)| p == n),
                None => Some(i),
            };
            let v = self.expr(&a.value, env);
            match idx.and_then(|k| given.get_mut(k)) {
                Some(slot) => *slot = Some(v),
                None if v => given.push(Some(true)),
                None => {}
            }
        }
        let mut inner = Env::default();
        for (k, (_, default)) in params.iter().enumerate() {
            let v = match given[k] {
                Some(v) => v,
                None => default.as_ref().is_some_and(|d| self.expr(d, &mut inner)),
            };
            inner.params.push(v);
        }
        inner.params
    }

    fn call(&mut self, call: &Call, env: &mut Env) -> bool {
        match &call.res {
            Resolution::Function { module, decl, .. } | Resolution::Material { module, decl, .. } => {
                let Some(f) = self.set.definition(&call.res) else { return true };
                let params: Vec<(String, Option<Expr>)> =
                    f.params.iter().map(|p| (p.name.clone(), p.default.clone())).collect();
                let args = self.bound(&params, call, env);
                if f.frequency == Frequency::Varying {
                    return true;
                }
                let key = (module.clone(), *decl, args.clone());
                if let Some(&v) = self.memo.get(&key) {
                    return v;
                }
                if self.depth >= MAX_CALL_DEPTH {
                    return true;
                }
                // A recursive call (not MDL) meets this provisional answer.
                self.memo.insert(key.clone(), false);
                self.depth += 1;
                let mut inner = Env { params: args.clone(), locals: HashMap::new() };
                let v = match &f.body {
                    Body::Expr(e) => self.expr(e, &mut inner),
                    Body::Block(stmts) => stmts.iter().any(|s| self.stmt(s, &mut inner)),
                    Body::Native => args.iter().any(|&a| a),
                };
                self.depth -= 1;
                self.memo.insert(key, v);
                v
            }
            Resolution::Constructor(Type::Struct(name)) => self.construct(name, call, env),
            Resolution::Constructor(Type::Material) => self.construct("material", call, env),
            _ => call.args.iter().any(|a| self.expr(&a.value, env)),
        }
    }

    /// A struct constructor: its arguments, and the defaults of the fields left out.
    fn construct(&mut self, name: &str, call: &Call, env: &mut Env) -> bool {
        let Some(s) = self.set.struct_decl(name) else {
            return call.args.iter().any(|a| self.expr(&a.value, env));
        };
        let fields: Vec<(String, Option<Expr>)> =
            s.fields.iter().map(|f| (f.name.clone(), f.default.clone())).collect();
        self.bound(&fields, call, env).iter().any(|&v| v)
    }

    /// Whether anything a statement computes varies (a conservative answer for a body).
    fn stmt(&mut self, s: &Stmt, env: &mut Env) -> bool {
        match &s.kind {
            StmtKind::Block(items) => items.iter().any(|x| self.stmt(x, env)),
            StmtKind::Var(decls) => decls.iter().fold(false, |acc, d| {
                let v = d.init.as_ref().is_some_and(|i| self.expr(i, env));
                env.locals.insert(d.id, v);
                v || acc
            }),
            StmtKind::Expr(e) => self.expr(e, env),
            StmtKind::If { cond, then, otherwise } => {
                let c = self.expr(cond, env);
                let t = self.stmt(then, env);
                let o = otherwise.as_ref().is_some_and(|o| self.stmt(o, env));
                c || t || o
            }
            StmtKind::For { init, cond, step, body } => {
                let i = init.as_ref().is_some_and(|s| self.stmt(s, env));
                let c = cond.as_ref().is_some_and(|e| self.expr(e, env));
                let st = step.as_ref().is_some_and(|e| self.expr(e, env));
                let b = self.stmt(body, env);
                i || c || st || b
            }
            StmtKind::While { cond, body } | StmtKind::DoWhile { body, cond } => {
                let c = self.expr(cond, env);
                let b = self.stmt(body, env);
                c || b
            }
            StmtKind::Switch { value, cases } => {
                let mut v = self.expr(value, env);
                for case in cases {
                    for s in &case.body {
                        v |= self.stmt(s, env);
                    }
                }
                v
            }
            StmtKind::Return(Some(e)) => self.expr(e, env),
            StmtKind::Return(None) | StmtKind::Break | StmtKind::Continue | StmtKind::Empty => false,
        }
    }
}

impl ModuleSet {
    /// Whether `e` depends on the shading point (see [`HitDependence`]); one query.
    pub fn varies_per_hit(&self, e: &Expr) -> bool {
        HitDependence::new(self).varies(e)
    }
}
