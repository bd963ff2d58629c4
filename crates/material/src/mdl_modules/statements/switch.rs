//! A `switch` on an integer of the hit, and the join after a `switch` left by `break`s of
//! the hit. Interface: [`Evaluator::guarded_switch`] runs the cases of such a `switch`
//! under the condition that control reaches each and joins what they assign;
//! [`Evaluator::take_exits`] gives the values after a `switch` from its recorded
//! [`Exit`]s and its end. Both are called from the statement runner in [`super`].

use std::sync::Arc;

use glam::Vec4;
use mdl_lang::ast::SwitchCase;
use mi::Span;

use super::super::eval::{kind, problem, Env, Evaluator, Problem};
use super::super::hit::{fold, BinOp, HitExpr, UnOp};
use super::super::value::Value;
use super::{both, either, join, Exit, Flow, Nest, Run, Step};

impl Evaluator<'_> {
    /// A `switch` on an integer `v` of the hit: each case's statements run under the
    /// condition that control reaches them (its label matches, or the case before falls
    /// through, and no `break` left before), and what they assign is joined by it.
    pub(super) fn guarded_switch(
        &mut self,
        run: &mut Run,
        v: &Arc<HitExpr>,
        cases: &[SwitchCase],
        env: &mut Env,
        span: Span,
    ) -> Step {
        let mut labels = Vec::with_capacity(cases.len());
        for case in cases {
            labels.push(match &case.label {
                None => None,
                Some(label) => match self.eval(label, env)? {
                    Value::Int(i) | Value::Enum(_, i) => Some(i),
                    other => return Err(problem(label.span, format!("a `case` label that is {}", kind(&other)))),
                },
            });
        }
        let equals =
            |l: i64| fold(HitExpr::Binary(BinOp::Eq, v.clone(), Arc::new(HitExpr::Const(Vec4::splat(l as f32)))));
        let any_label = labels.iter().flatten().map(|l| equals(*l)).reduce(|a, b| either(Some(&a), &b));
        let no_label = match any_label {
            Some(a) => fold(HitExpr::Unary(UnOp::Not, a)),
            None => Arc::new(HitExpr::Const(Vec4::ONE)),
        };
        let outer = run.guard.clone();
        // Control that left by `break` (None: none), and control falling into the next case.
        let (mut left, mut through): (Option<Arc<HitExpr>>, Option<Arc<HitExpr>>) = (None, None);
        let mut taken = Vec::new();
        for (case, label) in cases.iter().zip(labels) {
            let matched = label.map_or_else(|| no_label.clone(), equals);
            let mut reached = either(through.as_ref(), &matched);
            if let Some(l) = &left {
                reached = both(Some(&reached), &fold(HitExpr::Unary(UnOp::Not, l.clone())));
            }
            let before = (env.params.clone(), env.locals.clone());
            run.guard = Some(both(outer.as_ref(), &reached));
            let at = run.nest.len();
            run.nest.push(Nest::Switch(run.guard.clone(), Vec::new()));
            let flow = self.stmts(run, &case.body, env);
            if let Some(Nest::Switch(_, exits)) = run.nest.pop() {
                // Control that left by a `break` of the hit goes on after the switch only.
                for e in &exits {
                    let g = e.guard.clone().unwrap_or_else(|| Arc::new(HitExpr::Const(Vec4::ONE)));
                    left = Some(either(left.as_ref(), &g));
                }
                taken.extend(exits);
            }
            run.nest.truncate(at);
            run.guard = outer.clone();
            match flow? {
                // Every path that came here returned, or left the turn of a loop of the hit
                // (`continue`, recorded there): the others keep what they had.
                Flow::Return | Flow::Continue => {
                    (env.params, env.locals) = before;
                    through = None;
                }
                flow => {
                    let (params, locals) = before;
                    for (slot, old) in env.params.iter_mut().zip(params) {
                        *slot = join(&reached, std::mem::replace(slot, Value::Bool(false)), old, span)?;
                        run.check_depth(slot, span)?;
                    }
                    for (id, old) in locals {
                        if let Some(slot) = env.locals.get_mut(&id) {
                            *slot = join(&reached, std::mem::replace(slot, Value::Bool(false)), old, span)?;
                            run.check_depth(slot, span)?;
                        }
                    }
                    if flow == Flow::Break {
                        left = Some(either(left.as_ref(), &reached));
                        through = None;
                    } else {
                        through = Some(reached);
                    }
                }
            }
        }
        self.take_exits(run, taken, env, span)?;
        Ok(Flow::Normal)
    }

    /// The values after a `switch` left by `break`s of the hit (`exits`, in order) and its
    /// end (`env`): those of the first exit whose condition holds, else the end's.
    pub(super) fn take_exits(
        &mut self,
        run: &mut Run,
        exits: Vec<Exit>,
        env: &mut Env,
        span: Span,
    ) -> Result<(), Problem> {
        for exit in exits.into_iter().rev() {
            let Some(g) = exit.guard else {
                (env.params, env.locals) = (exit.params, exit.locals);
                continue;
            };
            for (slot, at) in env.params.iter_mut().zip(exit.params) {
                *slot = join(&g, at, std::mem::replace(slot, Value::Bool(false)), span)?;
                run.check_depth(slot, span)?;
            }
            for (id, slot) in env.locals.iter_mut() {
                if let Some(at) = exit.locals.get(id) {
                    *slot = join(&g, at.clone(), std::mem::replace(slot, Value::Bool(false)), span)?;
                    run.check_depth(slot, span)?;
                }
            }
        }
        Ok(())
    }
}
