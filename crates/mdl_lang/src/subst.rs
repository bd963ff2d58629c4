//! Binding arguments to a definition and substituting them for its parameters: what a
//! compiler does to evaluate a material or function body for one instance or call.

use crate::ast::*;

/// Argument binding failed: the message names the parameter or argument.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BindError(pub String);

impl std::fmt::Display for BindError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BindError {}

impl Expr {
    /// A copy of this expression with every reference to parameter `i` replaced by `args[i]`
    /// (references past the end of `args` are kept). The arguments are inserted as they are:
    /// parameters inside them belong to the caller and are not substituted again.
    pub fn substitute_params(&self, args: &[Expr]) -> Expr {
        let mut e = self.clone();
        e.substitute_in_place(args);
        e
    }

    fn substitute_in_place(&mut self, args: &[Expr]) {
        match &mut self.kind {
            ExprKind::Name(NameRef { res: Resolution::Param(i), .. }) => {
                if let Some(a) = args.get(*i) {
                    *self = a.clone();
                }
            }
            ExprKind::Bool(_) | ExprKind::Int(_) | ExprKind::Float { .. } | ExprKind::Str(_) | ExprKind::Name(_) => {}
            ExprKind::Call(call) => {
                for a in &mut call.args {
                    a.value.substitute_in_place(args);
                }
            }
            ExprKind::Unary { operand, .. } => operand.substitute_in_place(args),
            ExprKind::Binary { lhs, rhs, .. } => {
                lhs.substitute_in_place(args);
                rhs.substitute_in_place(args);
            }
            ExprKind::Conditional { cond, then, otherwise } => {
                cond.substitute_in_place(args);
                then.substitute_in_place(args);
                otherwise.substitute_in_place(args);
            }
            ExprKind::Member { base, .. } => base.substitute_in_place(args),
            ExprKind::Index { base, index } => {
                base.substitute_in_place(args);
                index.substitute_in_place(args);
            }
            ExprKind::Let { decls, body } => {
                for d in decls {
                    if let Some(init) = &mut d.init {
                        init.substitute_in_place(args);
                    }
                }
                body.substitute_in_place(args);
            }
            ExprKind::Sequence(list) => {
                for e in list {
                    e.substitute_in_place(args);
                }
            }
            ExprKind::Assign { target, value, .. } => {
                target.substitute_in_place(args);
                value.substitute_in_place(args);
            }
        }
    }
}

impl Function {
    /// The value of every parameter for a call with `given` arguments (by parameter name):
    /// the given expression, or the default with the values of earlier parameters substituted.
    /// An unknown name, or a parameter with neither argument nor default, is an error.
    pub fn bind_args(&self, given: &[(&str, Expr)]) -> Result<Vec<Expr>, BindError> {
        for (name, _) in given {
            if self.param(name).is_none() {
                return Err(BindError(format!("`{}` has no parameter `{name}`", self.name)));
            }
        }
        let mut values: Vec<Expr> = Vec::with_capacity(self.params.len());
        for p in &self.params {
            let value = match given.iter().rev().find(|(n, _)| *n == p.name) {
                Some((_, e)) => e.clone(),
                None => match &p.default {
                    Some(d) => d.substitute_params(&values),
                    None => {
                        return Err(BindError(format!(
                            "parameter `{}` of `{}` has no default and is not given",
                            p.name, self.name
                        )))
                    }
                },
            };
            values.push(value);
        }
        Ok(values)
    }

    /// The body expression of a material or expression-bodied function with `given` arguments
    /// bound (see [`Function::bind_args`]). `None` for statement bodies and native definitions.
    pub fn instantiate(&self, given: &[(&str, Expr)]) -> Result<Option<Expr>, BindError> {
        let values = self.bind_args(given)?;
        Ok(match &self.body {
            Body::Expr(e) => Some(e.substitute_params(&values)),
            Body::Block(_) | Body::Native => None,
        })
    }
}
