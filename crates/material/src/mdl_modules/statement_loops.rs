//! Compiling a loop of a statement body whose control depends on the hit into a
//! [`HitLoop`]: the variables the loop assigns (parameters and locals declared before it;
//! every number, vector and colour in them, in structs and arrays too) become slots, the
//! loop's condition and one turn of its body run once over those slots, and what the turn
//! leaves in each slot becomes the slot's next value. Inside the turn, a `break` or
//! `continue` under a condition of the hit records the values where control leaves
//! (`Exit`): a slot's value after the body is that of the first exit whose condition
//! holds, else the body's end; a `for` loop's step runs after the body and after a
//! `continue`, not after a `break`; a `break` taken ends the loop. A `return` inside is a
//! `break` that sets two more carried values (whether it returned, and its value); after
//! the loop, where it returned, the loop of the hit around leaves its turn the same way,
//! or, outside every loop of the hit, the function returns that value.

use std::collections::HashSet;
use std::sync::Arc;

use glam::Vec4;
use mdl_lang::ast::{Stmt, StmtKind, UnaryOp};
use mdl_lang::{Expr, ExprKind, Resolution};
use mi::Span;

use super::eval::{kind, problem, Env, Evaluator, Problem};
use super::hit::{cost_with, fold, HitExpr};
use super::hit_loop::{HitLoop, MAX_LARGE_NESTING, MAX_LOOP_SLOTS, SMALL_FRAME};
use super::state_space::{columns_of, matrix};
use super::statements::{both, Exit, Flow, Loop, Nest, Run, Step, RETURNED, RETURN_VALUE};
use super::value::{HitType, Value};

/// A variable a loop assigns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Var {
    /// Parameter `i`.
    Param(usize),
    /// Local `id`.
    Local(u32),
}

/// What the statements of a loop assign and declare.
#[derive(Default)]
struct Scan {
    /// Assigned (an assignment or increment of the name, or of a part of it).
    assigned: Vec<Var>,
    /// Locals declared inside.
    declared: HashSet<u32>,
    /// Whether a `return` is inside.
    returns: bool,
}

impl Scan {
    fn stmt(&mut self, s: &Stmt) {
        match &s.kind {
            StmtKind::Block(items) => items.iter().for_each(|s| self.stmt(s)),
            StmtKind::Var(decls) => self.declared.extend(decls.iter().map(|d| d.id)),
            StmtKind::Expr(e) => self.effect(e),
            StmtKind::If { then, otherwise, .. } => {
                self.stmt(then);
                if let Some(o) = otherwise {
                    self.stmt(o);
                }
            }
            StmtKind::For { init, step, body, .. } => {
                if let Some(init) = init {
                    self.stmt(init);
                }
                if let Some(step) = step {
                    self.effect(step);
                }
                self.stmt(body);
            }
            StmtKind::While { body, .. } | StmtKind::DoWhile { body, .. } => self.stmt(body),
            StmtKind::Switch { cases, .. } => cases.iter().flat_map(|c| &c.body).for_each(|s| self.stmt(s)),
            StmtKind::Return(_) => self.returns = true,
            _ => {}
        }
    }

    /// An expression run for its effect (as [`Evaluator::effect`] runs it).
    fn effect(&mut self, e: &Expr) {
        match &e.kind {
            ExprKind::Sequence(list) => list.iter().for_each(|x| self.effect(x)),
            ExprKind::Assign { target, .. } => self.target(target),
            ExprKind::Unary {
                op: UnaryOp::PreInc | UnaryOp::PostInc | UnaryOp::PreDec | UnaryOp::PostDec,
                operand,
            } => self.target(operand),
            _ => {}
        }
    }

    /// The variable an assignment to `e` (a name, or a member or element of one) changes.
    fn target(&mut self, e: &Expr) {
        match &e.kind {
            ExprKind::Member { base, .. } | ExprKind::Index { base, .. } => self.target(base),
            ExprKind::Name(n) => {
                let v = match n.res {
                    Resolution::Param(i) => Var::Param(i),
                    Resolution::Local(id) => Var::Local(id),
                    _ => return,
                };
                if !self.assigned.contains(&v) {
                    self.assigned.push(v);
                }
            }
            _ => {}
        }
    }
}

/// Where a carried variable's values sit: its value with each number, vector and colour
/// (and each column of a constant matrix) replaced by a slot.
#[derive(Clone, Debug)]
enum Shape {
    /// Slot `k`, holding a value of this type.
    Slot(u8, HitType),
    /// A constant matrix carried column by column: the columns' slots and their length.
    Matrix(Vec<u8>, u8),
    /// A struct: its type name and fields.
    Struct(String, Vec<(String, Shape)>),
    /// An array (a matrix of the hit is an array of its columns).
    Array(Vec<Shape>),
    /// A value the loop may not change (an enum, a texture…).
    Fixed(Value),
}

/// The shape of `v` with each number, vector and colour in it (and each column of a matrix)
/// the next slot (from `base + slots.len()`), whose initial value and type are pushed on
/// `slots`.
fn slotify(v: &Value, base: usize, slots: &mut Vec<(Arc<HitExpr>, HitType)>) -> Shape {
    let mut next = |e: Arc<HitExpr>, ty: HitType| {
        let k = (base + slots.len()).min(usize::from(u8::MAX)) as u8;
        slots.push((e, ty));
        k
    };
    match v {
        Value::Struct(name, fields) => {
            Shape::Struct(name.clone(), fields.iter().map(|(f, x)| (f.clone(), slotify(x, base, slots))).collect())
        }
        Value::Array(items) => Shape::Array(items.iter().map(|x| slotify(x, base, slots)).collect()),
        Value::Matrix { .. } => match columns_of(v) {
            Some((columns, rows)) => {
                Shape::Matrix(columns.into_iter().map(|c| next(c, HitType::Vector(rows))).collect(), rows)
            }
            None => Shape::Fixed(v.clone()),
        },
        Value::Enum(..) => Shape::Fixed(v.clone()),
        _ => match (v.hit_type(), v.to_hit()) {
            (Some(ty), Some(e)) => Shape::Slot(next(e, ty), ty),
            _ => Shape::Fixed(v.clone()),
        },
    }
}

/// The slots of `shape`, in order, as expressions.
fn slots_of(shape: &Shape, out: &mut Vec<Arc<HitExpr>>) {
    let slot = |k: &u8| Arc::new(HitExpr::Slot(*k));
    match shape {
        Shape::Slot(k, _) => out.push(slot(k)),
        Shape::Matrix(ks, _) => out.extend(ks.iter().map(slot)),
        Shape::Struct(_, fields) => fields.iter().for_each(|(_, f)| slots_of(f, out)),
        Shape::Array(items) => items.iter().for_each(|x| slots_of(x, out)),
        Shape::Fixed(_) => {}
    }
}

/// The values in `end` at the slots of `shape`, in order; `None` where `end` differs from
/// `shape` elsewhere (a struct of another kind, an array of another length, a texture
/// changed).
fn gather(shape: &Shape, end: &Value, out: &mut Vec<Arc<HitExpr>>) -> Option<()> {
    match (shape, end) {
        (Shape::Slot(..), _) => out.push(end.to_hit()?),
        (Shape::Matrix(ks, rows), m) => {
            let (columns, r) = columns_of(m)?;
            if columns.len() != ks.len() || r != *rows {
                return None;
            }
            out.extend(columns);
        }
        (Shape::Struct(n, fs), Value::Struct(m, gs)) if n == m && fs.len() == gs.len() => {
            for ((_, f), (_, g)) in fs.iter().zip(gs) {
                gather(f, g, out)?;
            }
        }
        (Shape::Array(a), Value::Array(b)) if a.len() == b.len() => {
            for (x, y) in a.iter().zip(b) {
                gather(x, y, out)?;
            }
        }
        // A matrix of the hit (an array of columns) that the turn made constant.
        (Shape::Array(a), m @ Value::Matrix { columns, .. }) if a.len() == usize::from(*columns) => {
            for (i, x) in a.iter().enumerate() {
                gather(x, &super::matrix::column(m, i)?, out)?;
            }
        }
        (Shape::Fixed(a), b) if a == b => {}
        _ => return None,
    }
    Some(())
}

/// `shape` with its slots replaced by `values`, in order (constants folded).
fn rebuild(shape: &Shape, values: &mut impl Iterator<Item = Arc<HitExpr>>) -> Value {
    match shape {
        Shape::Slot(k, ty) => {
            let v = values.next().unwrap_or_else(|| Arc::new(HitExpr::Slot(*k)));
            match v.constant() {
                Some(c) => Value::from_hit(HitExpr::Const(c), *ty),
                None => Value::Hit(v, *ty),
            }
        }
        Shape::Matrix(ks, rows) => {
            let columns = ks.iter().map(|k| values.next().unwrap_or_else(|| Arc::new(HitExpr::Slot(*k)))).collect();
            matrix(columns, *rows)
        }
        Shape::Struct(name, fields) => {
            Value::Struct(name.clone(), fields.iter().map(|(f, x)| (f.clone(), rebuild(x, values))).collect())
        }
        Shape::Array(items) => Value::Array(items.iter().map(|x| rebuild(x, values)).collect()),
        Shape::Fixed(v) => v.clone(),
    }
}

/// The values of the carried variables `vars` in `params` and `locals`, at their shapes.
fn leaves(
    vars: &[(Var, Shape)],
    params: &[Value],
    locals: &std::collections::HashMap<u32, Value>,
) -> Option<Vec<Arc<HitExpr>>> {
    let mut out = Vec::new();
    for (var, shape) in vars {
        let now = match var {
            Var::Param(i) => params.get(*i)?,
            Var::Local(id) => locals.get(id)?,
        };
        gather(shape, now, &mut out)?;
    }
    Some(out)
}

/// Puts each carried variable's value, rebuilt from `values`, into `env`.
fn store(vars: &[(Var, Shape)], values: &[Arc<HitExpr>], env: &mut Env) {
    let mut it = values.iter().cloned();
    for (var, shape) in vars {
        let v = rebuild(shape, &mut it);
        match var {
            Var::Param(i) => {
                if let Some(slot) = env.params.get_mut(*i) {
                    *slot = v;
                }
            }
            Var::Local(id) => {
                env.locals.insert(*id, v);
            }
        }
    }
}

/// `c ? a : b` per hit, or `a` where they are the same node.
fn choose(c: Option<&Arc<HitExpr>>, a: &Arc<HitExpr>, b: &Arc<HitExpr>) -> Arc<HitExpr> {
    match c {
        _ if Arc::ptr_eq(a, b) => a.clone(),
        None => a.clone(),
        Some(c) => fold(HitExpr::Select(c.clone(), a.clone(), b.clone())),
    }
}

/// What one turn of a loop of the hit compiles to.
struct Turn {
    cond: Arc<HitExpr>,
    next: Vec<Arc<HitExpr>>,
    exit: Arc<HitExpr>,
}

impl Evaluator<'_> {
    /// Compiles loop `lp` (at `span`) to run at each hit: the variables it assigns hold
    /// its values after it.
    pub(super) fn hit_loop(&mut self, run: &mut Run, lp: &Loop, env: &mut Env, span: Span) -> Step {
        let mut scan = Scan::default();
        scan.stmt(lp.body);
        if let Some(step) = lp.step {
            scan.effect(step);
        }
        // A `return` inside: whether it was taken and its value are carried as two more
        // variables, which the outermost loop of the hit around it hands on after it.
        let owner = scan.returns && !env.locals.contains_key(&RETURNED);
        if owner {
            let value = self.construct(&run.def.ret.ty, &[], env, span)?;
            env.locals.insert(RETURNED, Value::Bool(false));
            env.locals.insert(RETURN_VALUE, value);
        }
        if scan.returns {
            scan.assigned.extend([Var::Local(RETURNED), Var::Local(RETURN_VALUE)]);
        }
        let base = usize::from(self.slot_top);
        let mut slots = Vec::new();
        let mut vars: Vec<(Var, Shape)> = Vec::new();
        for var in scan.assigned {
            let now = match var {
                Var::Param(i) => env.params.get(i),
                Var::Local(id) if !scan.declared.contains(&id) => env.locals.get(&id),
                Var::Local(_) => None,
            };
            if let Some(now) = now {
                let shape = slotify(now, base, &mut slots);
                vars.push((var, shape));
            }
        }
        if base + slots.len() > MAX_LOOP_SLOTS {
            return Err(problem(
                span,
                format!(
                    "a loop of the hit in `{}` carries {} values, more than mira compiles ({MAX_LOOP_SLOTS}, loops \
                     around it included; a vector or colour is one)",
                    run.def.name,
                    slots.len()
                ),
            ));
        }
        let entry: HashSet<u32> = env.locals.keys().copied().collect();
        let placeholders: Vec<Arc<HitExpr>> = {
            let mut out = Vec::new();
            for (_, shape) in &vars {
                slots_of(shape, &mut out);
            }
            out
        };
        store(&vars, &placeholders, env);
        self.slot_top = (base + slots.len()) as u8;
        // The slots and levels of the loops of the hit nested in this one.
        let around = std::mem::replace(&mut self.loop_nest, (self.slot_top, 0));
        let outer = run.guard.take();
        run.nest.push(Nest::HitTurn(Vec::new()));
        let turn = self.hit_turn(run, lp, &vars, &placeholders, env, span);
        run.nest.pop();
        run.guard = outer;
        self.slot_top = base as u8;
        let (top, levels) = (self.loop_nest.0, self.loop_nest.1.saturating_add(1));
        self.loop_nest = (around.0.max(top), around.1.max(levels));
        let turn = turn?;
        if usize::from(top) > SMALL_FRAME && usize::from(levels) > MAX_LARGE_NESTING {
            return Err(problem(
                span,
                format!(
                    "`{}` nests {levels} loops of the hit in one another, carrying {top} values: more than mira \
                     runs ({MAX_LARGE_NESTING} deep once they carry more than {SMALL_FRAME} values)",
                    run.def.name
                ),
            ));
        }
        let cond = match &run.guard {
            Some(g) => both(Some(g), &turn.cond),
            None => turn.cond,
        };
        let mut turn_cost = 0u64;
        for e in turn.next.iter().chain([&cond, &turn.exit]) {
            turn_cost = turn_cost.saturating_add(cost_with(e, false).0);
        }
        let types: Vec<HitType> = slots.iter().map(|(_, t)| *t).collect();
        let l = Arc::new(HitLoop {
            base: base as u8,
            init: slots.into_iter().map(|(e, _)| e).collect(),
            cond,
            next: turn.next.into(),
            exit: turn.exit,
            test_first: lp.test_first,
            turn_cost,
            top,
        });
        let outs: Vec<Arc<HitExpr>> =
            (0..types.len()).map(|k| Arc::new(HitExpr::LoopOut(l.clone(), (base + k) as u8))).collect();
        env.locals.retain(|id, _| entry.contains(id));
        store(&vars, &outs, env);
        for (var, _) in &vars {
            let v = match var {
                Var::Param(i) => env.params.get(*i),
                Var::Local(id) => env.locals.get(id),
            };
            if let Some(v) = v.cloned() {
                run.check_depth(&v, span)?;
            }
        }
        if scan.returns {
            self.hand_on_return(run, env, owner);
        }
        Ok(Flow::Normal)
    }

    /// After a loop of the hit with a `return` inside: where it returned, the turn of the
    /// loop of the hit around leaves it too (a `break` with the return slots set), or
    /// (outside every loop of the hit, `owner`) the function returns its value.
    fn hand_on_return(&mut self, run: &mut Run, env: &mut Env, owner: bool) {
        let flag = env.locals.get(&RETURNED).and_then(Value::to_hit);
        let Some(flag) = flag.filter(|f| f.constant() != Some(Vec4::ZERO)) else {
            if owner {
                env.locals.remove(&RETURNED);
                env.locals.remove(&RETURN_VALUE);
            }
            return;
        };
        let guard = Some(both(run.guard.as_ref(), &flag));
        if owner {
            env.locals.remove(&RETURNED);
            if let Some(value) = env.locals.remove(&RETURN_VALUE) {
                run.returns.push((guard, value));
            }
            return;
        }
        let exit = Exit { guard, brk: true, params: env.params.clone(), locals: env.locals.clone() };
        if let Some(Nest::HitTurn(exits)) = run.nest.iter_mut().rev().find(|n| matches!(n, Nest::HitTurn(_))) {
            exits.push(exit);
        }
    }

    /// Runs the condition and one turn of `lp` over the slots (`placeholders`, the carried
    /// variables `vars` holding them in `env`).
    fn hit_turn(
        &mut self,
        run: &mut Run,
        lp: &Loop,
        vars: &[(Var, Shape)],
        placeholders: &[Arc<HitExpr>],
        env: &mut Env,
        span: Span,
    ) -> Result<Turn, Problem> {
        let name = run.def.name.clone();
        let changed = || {
            problem(
                span,
                format!(
                    "a loop of the hit in `{name}` changes a value that is not a number, vector or colour, or a \
                     struct's kind or an array's length"
                ),
            )
        };
        let cond = match lp.cond.map(|c| (c, self.eval(c, env))) {
            None => Arc::new(HitExpr::Const(Vec4::ONE)),
            Some((_, Ok(v @ (Value::Bool(_) | Value::Hit(..))))) => v.to_hit().ok_or_else(changed)?,
            Some((c, Ok(v))) => {
                return Err(problem(c.span, format!("a loop condition that is {}, not a bool", kind(&v))))
            }
            Some((_, Err(e))) => return Err(e),
        };
        let flow = self.stmt(run, lp.body, env)?;
        let Some(Nest::HitTurn(exits)) = run.nest.last_mut() else {
            return Err(problem(span, "a loop of the hit lost its turn"));
        };
        let exits: Vec<Exit> = std::mem::take(exits);
        // The values after the body: the first exit whose condition holds, else its end.
        let mut body = if flow == Flow::Normal {
            leaves(vars, &env.params, &env.locals).ok_or_else(changed)?
        } else {
            placeholders.to_vec()
        };
        // Whether the turn broke out: whether the first exit whose condition holds is a
        // `break` (an exit after another is reached only where that one's does not hold).
        let truth = |b: bool| Arc::new(HitExpr::Const(Vec4::splat(if b { 1.0 } else { 0.0 })));
        let mut broke = truth(false);
        for exit in exits.iter().rev() {
            let at = leaves(vars, &exit.params, &exit.locals).ok_or_else(changed)?;
            for (b, a) in body.iter_mut().zip(&at) {
                *b = choose(exit.guard.as_ref(), a, b);
            }
            broke = choose(exit.guard.as_ref(), &truth(exit.brk), &broke);
        }
        let broke = (broke.constant() != Some(Vec4::ZERO)).then_some(broke);
        let next = match lp.step {
            None => body,
            Some(step) => {
                store(vars, &body, env);
                self.effect(run, step, env)?;
                let stepped = leaves(vars, &env.params, &env.locals).ok_or_else(changed)?;
                // Where the turn broke out, the step does not run.
                match &broke {
                    None => stepped,
                    Some(c) => body.iter().zip(&stepped).map(|(b, s)| choose(Some(c), b, s)).collect(),
                }
            }
        };
        let exit = broke.unwrap_or_else(|| Arc::new(HitExpr::Const(Vec4::ZERO)));
        Ok(Turn { cond, next, exit })
    }
}
