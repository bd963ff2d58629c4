//! Functions with statement bodies: local declarations, assignments (`=`, `+=`, …, `++`),
//! blocks, `if`/`else`, `switch`, `for`, `while`, `do`–`while`, `break`, `continue` and
//! `return`, run once per material instance by the [`Evaluator`] — the values they compute
//! are constants or, where they depend on the shading point, [`HitExpr`] trees evaluated at
//! each hit, exactly as for expression bodies.
//!
//! Control flow must be known when the material is compiled, with one exception: an `if`
//! whose condition depends on the hit runs both branches, each under its condition, and
//! joins what they assign with a per-hit choice (`c ? a : b`); a `return` in such a branch
//! is kept with its condition, and the function's value is the first of its returns whose
//! condition holds; a `switch` on an integer of the hit runs each case under the condition
//! that control reaches it; a `break` under a condition of the hit leaves a `switch` there
//! (the statements after it run under the opposite condition, and after the switch each
//! value is that where the first `break` whose condition holds left, else the switch's
//! end). A loop whose control depends on the hit — its condition, or a `break` or
//! `continue` under a condition of the hit — is compiled into a loop that runs at each hit
//! ([`super::statement_loops`], [`super::hit_loop`]); a `return` inside one leaves it like
//! a `break` that sets two carried values, [`RETURNED`] and [`RETURN_VALUE`].
//!
//! Every statement run counts one step, and a material instance runs at most
//! [`MAX_STEPS`] (the bound a per-hit expression may take, [`super::hit::MAX_HIT_NODES`]):
//! a loop that would run longer — an endless one — is an error naming the function at
//! the loop's line, never a hang. A value of the hit a body stores may nest at most
//! [`MAX_HIT_DEPTH`] operations deep (what the hit evaluator takes; a loop squaring a value
//! of the hit would otherwise build a tree deep enough to overflow the stack when
//! dropped): deeper is an error at the statement.

use std::collections::HashMap;
use std::sync::Arc;

use glam::Vec4;
use mdl_lang::ast::{AssignOp, BinaryOp, Scalar, Stmt, StmtKind, UnaryOp, VarDecl};
use mdl_lang::{Expr, ExprKind, Function, Resolution, Type};
use mi::Span;

use super::eval::{binary, hit_binary, kind, problem, Env, Eval, Evaluator, Problem};
use super::hit::{fold, BinOp, HitExpr, UnOp, MAX_HIT_DEPTH};
use super::value::{HitType, Value};

mod switch;

/// Most statements one material instance's statement bodies may run.
pub const MAX_STEPS: u64 = super::hit::MAX_HIT_NODES;

/// How a statement ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Flow {
    /// On to the next statement.
    Normal,
    /// `break`.
    Break,
    /// `continue`.
    Continue,
    /// Every path through it returned.
    Return,
}

/// A loop or `switch` the statements now run in.
pub(super) enum Nest {
    /// A loop whose turns run when the material is compiled, with the condition its turns
    /// run under.
    Loop(Option<Arc<HitExpr>>),
    /// A `switch`, with the condition its case runs under and where a `break` under a
    /// condition of the hit left it so far.
    Switch(Option<Arc<HitExpr>>, Vec<Exit>),
    /// The turn of a loop of the hit being compiled: where control left it so far.
    HitTurn(Vec<Exit>),
}

/// The local that holds whether a `return` inside a loop of the hit was taken (a bool).
pub(super) const RETURNED: u32 = u32::MAX;
/// The local that holds the value of a `return` inside a loop of the hit.
pub(super) const RETURN_VALUE: u32 = u32::MAX - 1;

/// Control leaving a turn of a loop of the hit by `break`, `continue` or `return` (a
/// `break` that sets [`RETURNED`] and [`RETURN_VALUE`]), or a `switch` by `break`.
pub(super) struct Exit {
    /// The condition under which it leaves (within the turn; `None`: always).
    pub guard: Option<Arc<HitExpr>>,
    /// `break` (or `return`), else `continue`.
    pub brk: bool,
    /// The parameters' values there.
    pub params: Vec<Value>,
    /// The locals' values there.
    pub locals: HashMap<u32, Value>,
}

/// One run of a function body.
pub(super) struct Run<'f> {
    /// The function (for messages and its return type).
    pub def: &'f Function,
    /// The condition of the hit under which the statements now run (`None`: always).
    pub guard: Option<Arc<HitExpr>>,
    /// The loops and switches around the statement running, innermost last.
    pub nest: Vec<Nest>,
    /// Set by a `break` or `continue` under a condition of the hit in a loop that runs when
    /// compiled: that loop's index in `nest`, which then compiles itself per hit.
    pub per_hit: Option<usize>,
    /// The values returned so far, each with the condition it was returned under, in order.
    pub returns: Vec<(Option<Arc<HitExpr>>, Value)>,
    /// How deep the values of the hit stored so far nest, by node (each kept alive here, so
    /// that its address names it): a new value's depth is measured down to them only.
    depths: HashMap<*const HitExpr, (Arc<HitExpr>, usize)>,
}

impl Run<'_> {
    /// Whether the statements now run under condition `g` (the same condition, not an equal
    /// one).
    fn under(&self, g: Option<&Arc<HitExpr>>) -> bool {
        match (g, &self.guard) {
            (None, None) => true,
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }

    /// Checks that the values of the hit in `v` nest at most [`MAX_HIT_DEPTH`] deep — deeper
    /// trees are refused when compiled, and dropping or comparing one recurses once per
    /// level — and remembers their depth. Measuring stops at values stored before, so
    /// the statements of a body cost about the nodes they build.
    pub(super) fn check_depth(&mut self, v: &Value, span: Span) -> Result<(), Problem> {
        let mut roots = Vec::new();
        hit_roots(v, &mut roots);
        for root in roots {
            let key = Arc::as_ptr(&root);
            if self.depths.contains_key(&key) {
                continue;
            }
            let depth = depth_of(&root, &self.depths).ok_or_else(|| {
                problem(
                    span,
                    format!(
                        "`{}` builds a value of the hit nested more than {MAX_HIT_DEPTH} operations deep",
                        self.def.name
                    ),
                )
            })?;
            self.depths.insert(key, (root, depth));
        }
        Ok(())
    }
}

/// The expressions of the hit in `v` (in structs and arrays too).
fn hit_roots(v: &Value, out: &mut Vec<Arc<HitExpr>>) {
    match v {
        Value::Hit(e, _) => out.push(e.clone()),
        Value::Struct(_, fields) => fields.iter().for_each(|(_, f)| hit_roots(f, out)),
        Value::Array(items) => items.iter().for_each(|x| hit_roots(x, out)),
        _ => {}
    }
}

/// The depth of `root` (leaves 1), counting the nodes in `known` at their depth; `None`
/// past [`MAX_HIT_DEPTH`]. Walks each new node once, without recursion.
fn depth_of(root: &Arc<HitExpr>, known: &HashMap<*const HitExpr, (Arc<HitExpr>, usize)>) -> Option<usize> {
    let mut done: HashMap<*const HitExpr, usize> = HashMap::new();
    let depth = |p: *const HitExpr, done: &HashMap<*const HitExpr, usize>| {
        known.get(&p).map(|(_, d)| *d).or_else(|| done.get(&p).copied())
    };
    let mut stack: Vec<(&HitExpr, bool)> = vec![(&**root, false)];
    while let Some((node, ready)) = stack.pop() {
        let key = std::ptr::from_ref(node);
        if depth(key, &done).is_some() {
            continue;
        }
        let operands = node.operands();
        if ready {
            let d = 1 + operands.iter().filter_map(|o| depth(Arc::as_ptr(o), &done)).max().unwrap_or(0);
            if d > MAX_HIT_DEPTH {
                return None;
            }
            done.insert(key, d);
        } else {
            stack.push((node, true));
            stack
                .extend(operands.into_iter().filter(|o| depth(Arc::as_ptr(o), &done).is_none()).map(|o| (&**o, false)));
        }
    }
    depth(Arc::as_ptr(root), &done)
}

pub(super) type Step = Result<Flow, Problem>;

/// A loop's parts: `for (…; cond; step) body`, `while (cond) body` (`test_first`), or
/// `do body while (cond)`.
pub(super) struct Loop<'s> {
    /// The condition (`None`: always).
    pub cond: Option<&'s Expr>,
    /// The body.
    pub body: &'s Stmt,
    /// What runs after each turn (`for`).
    pub step: Option<&'s Expr>,
    /// Whether the condition is tested before the first turn.
    pub test_first: bool,
}

impl Evaluator<'_> {
    /// The value of a call of `def`, whose body is the statements `body`, with bound `args`.
    pub(super) fn call_block(&mut self, def: &Function, body: &[Stmt], args: Vec<Value>, span: Span) -> Eval {
        let mut env = Env::with_params(args);
        let mut run =
            Run { def, guard: None, nest: Vec::new(), per_hit: None, returns: Vec::new(), depths: HashMap::new() };
        self.stmts(&mut run, body, &mut env)?;
        // The first return whose condition holds: the last one is what remains.
        let mut returns = run.returns.into_iter().rev();
        let Some((_, mut value)) = returns.next() else {
            return Err(problem(span, format!("`{}` ended without `return`", def.name)));
        };
        for (guard, v) in returns {
            value = match guard {
                None => v,
                Some(g) => select(&g, v, value).ok_or_else(|| {
                    problem(span, format!("`{}` returns values of different kinds by a condition of the hit", def.name))
                })?,
            };
        }
        Ok(value)
    }

    pub(super) fn stmts(&mut self, run: &mut Run, stmts: &[Stmt], env: &mut Env) -> Step {
        for s in stmts {
            let flow = self.stmt(run, s, env)?;
            if flow != Flow::Normal {
                return Ok(flow);
            }
        }
        Ok(Flow::Normal)
    }

    pub(super) fn stmt(&mut self, run: &mut Run, s: &Stmt, env: &mut Env) -> Step {
        self.steps += 1;
        let span = s.span;
        match &s.kind {
            StmtKind::Empty => Ok(Flow::Normal),
            StmtKind::Block(items) => self.stmts(run, items, env),
            StmtKind::Var(decls) => {
                for d in decls {
                    self.declare(run, d, env)?;
                }
                Ok(Flow::Normal)
            }
            StmtKind::Expr(e) => {
                self.effect(run, e, env)?;
                Ok(Flow::Normal)
            }
            StmtKind::Return(value) => {
                let v = match value {
                    Some(v) => convert(self.eval(v, env)?, &run.def.ret.ty),
                    None => return Err(problem(span, format!("`{}` returns no value", run.def.name))),
                };
                run.check_depth(&v, span)?;
                // Inside a loop of the hit: a `break` out of its turn that sets the return
                // slots (the loop hands the return on, see `statement_loops`).
                if let Some(at) = run.nest.iter().rposition(|n| matches!(n, Nest::HitTurn(_))) {
                    env.locals.insert(RETURN_VALUE, v);
                    env.locals.insert(RETURNED, Value::Bool(true));
                    let exit = Exit {
                        guard: run.guard.clone(),
                        brk: true,
                        params: env.params.clone(),
                        locals: env.locals.clone(),
                    };
                    if let Nest::HitTurn(exits) = &mut run.nest[at] {
                        exits.push(exit);
                    }
                    return Ok(Flow::Return);
                }
                run.returns.push((run.guard.clone(), v));
                Ok(Flow::Return)
            }
            StmtKind::Break => self.leave(run, true, env, span),
            StmtKind::Continue => self.leave(run, false, env, span),
            StmtKind::If { cond, then, otherwise } => match self.eval(cond, env)? {
                Value::Bool(true) => self.stmt(run, then, env),
                Value::Bool(false) => otherwise.as_ref().map_or(Ok(Flow::Normal), |o| self.stmt(run, o, env)),
                Value::Hit(c, _) => self.guarded_if(run, &c, then, otherwise.as_deref(), env, span),
                v => Err(problem(cond.span, format!("the condition of `if` is {}, not a bool", kind(&v)))),
            },
            StmtKind::While { cond, body } => {
                self.run_loop(run, &Loop { cond: Some(cond), body, step: None, test_first: true }, env, span)
            }
            StmtKind::DoWhile { body, cond } => {
                self.run_loop(run, &Loop { cond: Some(cond), body, step: None, test_first: false }, env, span)
            }
            StmtKind::For { init, cond, step, body } => {
                if let Some(init) = init {
                    self.stmt(run, init, env)?;
                }
                let lp = Loop { cond: cond.as_deref(), body, step: step.as_deref(), test_first: true };
                self.run_loop(run, &lp, env, span)
            }
            StmtKind::Switch { value, cases } => {
                let v = match self.eval(value, env)? {
                    Value::Int(i) | Value::Enum(_, i) => i,
                    Value::Hit(v, HitType::Int) => return self.guarded_switch(run, &v, cases, env, span),
                    v => return Err(problem(value.span, format!("`switch` on {} is not compiled", kind(&v)))),
                };
                let mut start = None;
                for (k, case) in cases.iter().enumerate() {
                    let Some(label) = &case.label else { continue };
                    match self.eval(label, env)? {
                        Value::Int(i) | Value::Enum(_, i) if i == v => {
                            start = Some(k);
                            break;
                        }
                        Value::Int(_) | Value::Enum(..) => {}
                        other => return Err(problem(label.span, format!("a `case` label that is {}", kind(&other)))),
                    }
                }
                let Some(start) = start.or_else(|| cases.iter().position(|c| c.label.is_none())) else {
                    return Ok(Flow::Normal);
                };
                // From the chosen label on, falling through the labels after it.
                let at = run.nest.len();
                let outer = run.guard.clone();
                run.nest.push(Nest::Switch(run.guard.clone(), Vec::new()));
                let mut flow = Ok(Flow::Normal);
                for case in &cases[start..] {
                    flow = self.stmts(run, &case.body, env);
                    if !matches!(flow, Ok(Flow::Normal)) {
                        break;
                    }
                }
                let exits = match run.nest.pop() {
                    Some(Nest::Switch(_, exits)) => exits,
                    _ => Vec::new(),
                };
                run.nest.truncate(at);
                run.guard = outer;
                let flow = match flow? {
                    Flow::Break => Flow::Normal,
                    flow => flow,
                };
                if exits.is_empty() {
                    return Ok(flow);
                }
                // Where a `break` of the hit left, control goes on after the switch.
                if flow != Flow::Normal {
                    let mut exits = exits;
                    let last = exits.pop().expect("an exit");
                    (env.params, env.locals) = (last.params, last.locals);
                    self.take_exits(run, exits, env, span)?;
                } else {
                    self.take_exits(run, exits, env, span)?;
                }
                Ok(Flow::Normal)
            }
        }
    }

    /// One more turn of the loop at `span`: an error once the instance has run
    /// [`MAX_STEPS`] statements.
    fn count_loop(&mut self, run: &Run, span: Span) -> Result<(), Problem> {
        self.steps += 1;
        if self.steps > MAX_STEPS {
            return Err(problem(
                span,
                format!(
                    "the loop in `{}` runs past {MAX_STEPS} steps, the most mira runs for a material \
                     (an endless loop?)",
                    run.def.name
                ),
            ));
        }
        Ok(())
    }

    /// A loop's condition: `None` where it depends on the hit.
    fn loop_condition(&mut self, cond: &Expr, env: &mut Env) -> Result<Option<bool>, Problem> {
        match self.eval(cond, env)? {
            Value::Bool(b) => Ok(Some(b)),
            Value::Hit(..) => Ok(None),
            v => Err(problem(cond.span, format!("a loop condition that is {}, not a bool", kind(&v)))),
        }
    }

    /// A loop: its turns run now while its control is known when the material is compiled;
    /// where it turns out to depend on the hit (its condition, or a `break` or `continue`
    /// under a condition of the hit), the loop starts again as a loop of the hit.
    fn run_loop(&mut self, run: &mut Run, lp: &Loop, env: &mut Env, span: Span) -> Step {
        let saved = (env.params.clone(), env.locals.clone(), run.returns.len());
        // Where the turn of a loop of the hit around records a `return` of this loop.
        let turn = run.nest.iter().rposition(|n| matches!(n, Nest::HitTurn(_)));
        let turn_exits = match turn.map(|t| &run.nest[t]) {
            Some(Nest::HitTurn(exits)) => exits.len(),
            _ => 0,
        };
        let at = run.nest.len();
        run.nest.push(Nest::Loop(run.guard.clone()));
        let turns = self.known_turns(run, lp, env, span);
        run.nest.truncate(at);
        match turns {
            Ok(Some(flow)) => return Ok(flow),
            Ok(None) => {}
            Err(_) if run.per_hit == Some(at) => run.per_hit = None,
            Err(e) => return Err(e),
        }
        (env.params, env.locals) = (saved.0, saved.1);
        run.returns.truncate(saved.2);
        if let Some(Nest::HitTurn(exits)) = turn.map(|t| &mut run.nest[t]) {
            exits.truncate(turn_exits);
        }
        self.hit_loop(run, lp, env, span)
    }

    /// The turns of a loop whose control is known now; `None` when its condition depends
    /// on the hit.
    fn known_turns(&mut self, run: &mut Run, lp: &Loop, env: &mut Env, span: Span) -> Result<Option<Flow>, Problem> {
        let mut first = true;
        loop {
            self.count_loop(run, span)?;
            if let (Some(cond), true) = (lp.cond, lp.test_first || !first) {
                match self.loop_condition(cond, env)? {
                    Some(true) => {}
                    Some(false) => return Ok(Some(Flow::Normal)),
                    None => return Ok(None),
                }
            }
            first = false;
            match self.stmt(run, lp.body, env)? {
                Flow::Break => return Ok(Some(Flow::Normal)),
                Flow::Return => return Ok(Some(Flow::Return)),
                Flow::Normal | Flow::Continue => {}
            }
            if let Some(step) = lp.step {
                self.effect(run, step, env)?;
            }
        }
    }

    /// `break` (`brk`) or `continue`: ends the loop's turn or the `switch` it belongs to.
    /// Under a condition of the hit, a turn of a loop of the hit records where control
    /// leaves; a loop compiled turn by turn is asked to compile itself per hit.
    fn leave(&mut self, run: &mut Run, brk: bool, env: &Env, span: Span) -> Step {
        let flow = if brk { Flow::Break } else { Flow::Continue };
        let word = if brk { "break" } else { "continue" };
        // `continue` belongs to the innermost loop, `break` to the innermost loop or switch.
        let Some(at) = run.nest.iter().rposition(|n| brk || !matches!(n, Nest::Switch(..))) else {
            return Ok(flow);
        };
        let guard = run.guard.clone();
        if let Nest::HitTurn(exits) = &mut run.nest[at] {
            exits.push(Exit { guard, brk, params: env.params.clone(), locals: env.locals.clone() });
            return Ok(flow);
        }
        let under = match &run.nest[at] {
            Nest::Loop(g) | Nest::Switch(g, _) => run.under(g.as_ref()),
            Nest::HitTurn(_) => false,
        };
        if under {
            return Ok(flow);
        }
        if let Nest::Switch(_, exits) = &mut run.nest[at] {
            // The switch joins the values where it was left after it (see `take_exits`).
            exits.push(Exit { guard, brk, params: env.params.clone(), locals: env.locals.clone() });
            return Ok(flow);
        }
        run.per_hit = Some(at);
        Err(problem(span, format!("`{word}` under a condition of the hit (in `{}`)", run.def.name)))
    }

    /// An `if` whose condition `c` depends on the hit: both branches run, each under its
    /// condition; what they assign is joined by `c`.
    fn guarded_if(
        &mut self,
        run: &mut Run,
        c: &Arc<HitExpr>,
        then: &Stmt,
        otherwise: Option<&Stmt>,
        env: &mut Env,
        span: Span,
    ) -> Step {
        let outer = run.guard.clone();
        let switch_exits = match run.nest.last() {
            Some(Nest::Switch(_, exits)) => exits.len(),
            _ => 0,
        };
        let flow = self.guarded_branches(run, c, then, otherwise, env, span)?;
        // Where a branch left the switch around by `break`, the statements after run only
        // where it did not.
        if let Some(Nest::Switch(_, exits)) = run.nest.last() {
            let gone = exits[switch_exits.min(exits.len())..]
                .iter()
                .map(|e| e.guard.clone().unwrap_or_else(|| Arc::new(HitExpr::Const(Vec4::ONE))))
                .reduce(|a, b| either(Some(&a), &b));
            if let Some(gone) = gone {
                run.guard = Some(both(outer.as_ref(), &fold(HitExpr::Unary(UnOp::Not, gone))));
            }
        }
        Ok(flow)
    }

    /// The two branches of [`Self::guarded_if`], each under its condition, joined by `c`.
    fn guarded_branches(
        &mut self,
        run: &mut Run,
        c: &Arc<HitExpr>,
        then: &Stmt,
        otherwise: Option<&Stmt>,
        env: &mut Env,
        span: Span,
    ) -> Step {
        let outer = run.guard.clone();
        let not_c = fold(HitExpr::Unary(UnOp::Not, c.clone()));
        let before = (env.params.clone(), env.locals.clone());
        run.guard = Some(both(outer.as_ref(), c));
        let taken = self.stmt(run, then, env);
        let then_env = (std::mem::take(&mut env.params), std::mem::take(&mut env.locals));
        (env.params, env.locals) = before;
        run.guard = Some(both(outer.as_ref(), &not_c));
        let other = match otherwise {
            Some(o) => self.stmt(run, o, env),
            None => Ok(Flow::Normal),
        };
        run.guard = outer;
        let (taken, other) = (taken?, other?);
        // A branch that ended (returned, or left a turn of a loop of the hit, which
        // recorded what it leaves with) leaves the other's values to the statements after.
        let ended = |f: Flow| f != Flow::Normal;
        match (taken, other) {
            (Flow::Return, Flow::Return) => Ok(Flow::Return),
            (a, b) if ended(a) && ended(b) => Ok(if a == Flow::Return { b } else { a }),
            (a, _) if ended(a) => Ok(Flow::Normal),
            (_, b) if ended(b) => {
                (env.params, env.locals) = then_env;
                Ok(Flow::Normal)
            }
            _ => {
                let (then_params, mut then_locals) = then_env;
                for (slot, t) in env.params.iter_mut().zip(then_params) {
                    *slot = join(c, t, std::mem::replace(slot, Value::Bool(false)), span)?;
                    run.check_depth(slot, span)?;
                }
                for (id, e) in env.locals.iter_mut() {
                    if let Some(t) = then_locals.remove(id) {
                        *e = join(c, t, std::mem::replace(e, Value::Bool(false)), span)?;
                        run.check_depth(e, span)?;
                    }
                }
                Ok(Flow::Normal)
            }
        }
    }

    /// Declares local `d` with its value (the type's default when none is written).
    fn declare(&mut self, run: &mut Run, d: &VarDecl, env: &mut Env) -> Result<(), Problem> {
        let v = match &d.init {
            Some(init) => convert(self.eval(init, env)?, &d.ty.ty),
            None => self.construct(&d.ty.ty, &[], env, d.span)?,
        };
        run.check_depth(&v, d.span)?;
        env.locals.insert(d.id, v);
        Ok(())
    }

    /// Runs `e` for its effect: an assignment, an increment, a sequence, or any expression.
    pub(super) fn effect(&mut self, run: &mut Run, e: &Expr, env: &mut Env) -> Result<(), Problem> {
        match &e.kind {
            ExprKind::Sequence(list) => {
                for x in list {
                    self.effect(run, x, env)?;
                }
            }
            ExprKind::Assign { op, target, value } => {
                let v = self.eval(value, env)?;
                let v = match op {
                    AssignOp::Set => v,
                    AssignOp::Compound(op) => combine(*op, &self.eval(target, env)?, &v, e.span)?,
                };
                self.assign(run, target, v, env)?;
            }
            ExprKind::Unary {
                op: op @ (UnaryOp::PreInc | UnaryOp::PostInc | UnaryOp::PreDec | UnaryOp::PostDec),
                operand,
            } => {
                let by = if matches!(op, UnaryOp::PreInc | UnaryOp::PostInc) { BinaryOp::Add } else { BinaryOp::Sub };
                let v = combine(by, &self.eval(operand, env)?, &Value::Int(1), e.span)?;
                self.assign(run, operand, v, env)?;
            }
            _ => {
                self.eval(e, env)?;
            }
        }
        Ok(())
    }

    /// Stores `v` in what `target` names: a parameter, a local, a member or element of one.
    fn assign(&mut self, run: &mut Run, target: &Expr, v: Value, env: &mut Env) -> Result<(), Problem> {
        let span = target.span;
        match &target.kind {
            ExprKind::Name(n) => {
                let slot = match n.res {
                    Resolution::Param(i) => env.params.get_mut(i),
                    Resolution::Local(id) => env.locals.get_mut(&id),
                    _ => None,
                };
                let slot = slot.ok_or_else(|| problem(span, format!("`{}` cannot be assigned to", n.name)))?;
                run.check_depth(&v, span)?;
                // An int stored in a float stays a float (MDL's implicit conversion).
                *slot = match (&*slot, v) {
                    (Value::Float(_), Value::Int(i)) => Value::Float(i as f64),
                    (_, v) => v,
                };
                Ok(())
            }
            ExprKind::Member { base, field } => {
                let whole = self.eval(base, env)?;
                let lane = "xyzw".find(field.as_str()).filter(|_| field.len() == 1);
                let updated = match (whole, lane) {
                    (Value::Struct(name, mut fields), _) => {
                        let f = fields
                            .iter_mut()
                            .find(|(f, _)| f == field)
                            .ok_or_else(|| problem(span, format!("struct `{name}` has no field `{field}`")))?;
                        f.1 = match (&f.1, v) {
                            (Value::Float(_), Value::Int(i)) => Value::Float(i as f64),
                            (_, v) => v,
                        };
                        Value::Struct(name, fields)
                    }
                    (whole, Some(i)) => with_lane(whole, i, v, span)?,
                    (whole, None) => {
                        return Err(problem(span, format!("`.{field}` of {} is not assigned", kind(&whole))))
                    }
                };
                self.assign(run, base, updated, env)
            }
            ExprKind::Index { base, index } => {
                let i = match self.eval(index, env)? {
                    Value::Int(i) if i >= 0 => i as usize,
                    Value::Hit(at, HitType::Int) => {
                        let whole = self.eval(base, env)?;
                        let updated = super::hit_index::assign(&whole, &at, &v).ok_or_else(|| {
                            problem(
                                span,
                                format!("{} is not assigned {} at an index of the hit", kind(&whole), kind(&v)),
                            )
                        })?;
                        return self.assign(run, base, updated, env);
                    }
                    other => {
                        return Err(problem(
                            index.span,
                            format!("an index that is {} is not assigned to", kind(&other)),
                        ))
                    }
                };
                let updated = match self.eval(base, env)? {
                    Value::Array(mut items) if i < items.len() => {
                        items[i] = v;
                        Value::Array(items)
                    }
                    m @ Value::Matrix { .. } => super::matrix::with_column(m.clone(), i, &v)
                        .or_else(|| super::state_space::with_column(&m, i, &v))
                        .ok_or_else(|| problem(span, format!("column {i} of a matrix is not assigned {}", kind(&v))))?,
                    whole => with_lane(whole, i, v, span)?,
                };
                self.assign(run, base, updated, env)
            }
            _ => Err(problem(span, "this expression cannot be assigned to")),
        }
    }
}

/// `a op b`, on constants or values of the hit.
fn combine(op: BinaryOp, a: &Value, b: &Value, span: Span) -> Eval {
    let r = if matches!(a, Value::Hit(..)) || matches!(b, Value::Hit(..)) {
        hit_binary(op, a, b)
    } else {
        binary(op, a, b)
    };
    r.ok_or_else(|| problem(span, format!("operator {op:?} on {} and {} is not evaluated", kind(a), kind(b))))
}

/// `v` as a value of type `ty` where MDL converts implicitly (an int where a float is
/// expected).
fn convert(v: Value, ty: &Type) -> Value {
    match (v, ty) {
        (Value::Int(i), Type::Scalar(Scalar::Float | Scalar::Double)) => Value::Float(i as f64),
        (v, _) => v,
    }
}

/// A vector (constant or of the hit) with lane `i` replaced by the scalar `v`.
fn with_lane(whole: Value, i: usize, v: Value, span: Span) -> Eval {
    if let (Value::Vector(mut lanes), Some(x)) = (whole.clone(), v.float()) {
        if i < lanes.len() {
            lanes[i] = x;
            return Ok(Value::Vector(lanes));
        }
    }
    let bad = || problem(span, format!("lane {i} of {} is not assigned", kind(&whole)));
    let ty =
        whole.hit_type().filter(|t| i < usize::from(t.width()) && matches!(t, HitType::Vector(_))).ok_or_else(bad)?;
    let (old, new) = (whole.to_hit().ok_or_else(bad)?, v.to_hit().ok_or_else(bad)?);
    let parts: Box<[(Arc<HitExpr>, u8)]> = (0..ty.width())
        .map(|k| if usize::from(k) == i { (new.clone(), 1) } else { (fold(HitExpr::Lane(old.clone(), k)), 1) })
        .collect();
    Ok(Value::from_hit(HitExpr::Compose(parts), ty))
}

/// `g && c` (`c` alone when there is no outer condition).
pub(super) fn both(g: Option<&Arc<HitExpr>>, c: &Arc<HitExpr>) -> Arc<HitExpr> {
    match g {
        None => c.clone(),
        Some(g) => fold(HitExpr::Binary(BinOp::And, g.clone(), c.clone())),
    }
}

/// `g || c` (`c` alone when there is no `g`).
pub(super) fn either(g: Option<&Arc<HitExpr>>, c: &Arc<HitExpr>) -> Arc<HitExpr> {
    match g {
        None => c.clone(),
        Some(g) => fold(HitExpr::Binary(BinOp::Or, g.clone(), c.clone())),
    }
}

/// `c ? a : b` per hit, for the value a name holds after the two branches of an `if`.
fn join(c: &Arc<HitExpr>, a: Value, b: Value, span: Span) -> Eval {
    let (ka, kb) = (kind(&a), kind(&b));
    select(c, a, b).ok_or_else(|| {
        problem(span, format!("an `if` of the hit that leaves {ka} or {kb} in one variable is not compiled"))
    })
}

/// `c ? a : b` per hit: equal values stay as they are, structs are chosen field by field,
/// matrices column by column, numbers, vectors and colours by a [`HitExpr::Select`].
pub(super) fn select(c: &Arc<HitExpr>, a: Value, b: Value) -> Option<Value> {
    if a == b {
        return Some(a);
    }
    match (a, b) {
        // A constant matrix and another matrix: column by column.
        (a, b) if matches!(a, Value::Matrix { .. }) || matches!(b, Value::Matrix { .. }) => {
            super::state_space::select(c, &a, &b)
        }
        (Value::Struct(n, fa), Value::Struct(m, fb)) if n == m && fa.len() == fb.len() => {
            let mut fields = Vec::with_capacity(fa.len());
            for ((name, x), (_, y)) in fa.into_iter().zip(fb) {
                fields.push((name, select(c, x, y)?));
            }
            Some(Value::Struct(n, fields))
        }
        (Value::Array(xa), Value::Array(xb)) if xa.len() == xb.len() => {
            let items: Option<Vec<Value>> = xa.into_iter().zip(xb).map(|(x, y)| select(c, x, y)).collect();
            Some(Value::Array(items?))
        }
        (a, b) => {
            let (ta, tb) = (a.hit_type()?, b.hit_type()?);
            let ty = if ta.width() >= tb.width() { ta } else { tb };
            Some(Value::from_hit(HitExpr::Select(c.clone(), a.to_hit()?, b.to_hit()?), ty))
        }
    }
}
