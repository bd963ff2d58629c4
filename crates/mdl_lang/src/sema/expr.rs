//! Expressions: names, operators, member access, indexing, `let`, assignment.

use super::{Checker, Local};
use crate::ast::*;
use crate::symbols::SymbolKind;

impl Checker<'_> {
    /// Resolves the names in `e`, checks what can be checked, and records its type.
    pub(super) fn expr(&mut self, e: &mut Expr) -> Option<Type> {
        let span = e.span;
        let ty = match &mut e.kind {
            ExprKind::Bool(_) => Some(Type::BOOL),
            ExprKind::Int(_) => Some(Type::INT),
            ExprKind::Float { double, .. } => Some(if *double { Type::DOUBLE } else { Type::FLOAT }),
            ExprKind::Str(_) => Some(Type::String),
            ExprKind::Name(n) => self.name(n, span),
            ExprKind::Call(call) => self.call(call, span),
            ExprKind::Unary { op, operand } => {
                let t = self.expr(operand);
                match (op, t) {
                    (UnaryOp::Not, _) => Some(Type::BOOL),
                    (_, Some(t)) if is_arithmetic(&t) => Some(t),
                    (op, Some(t)) => {
                        self.error(span, format!("operator `{}` is not defined for `{t}`", unary_text(*op)));
                        None
                    }
                    (_, None) => None,
                }
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let (op, l, r) = (*op, self.expr(lhs), self.expr(rhs));
                self.binary(op, l, r, span)
            }
            ExprKind::Conditional { cond, then, otherwise } => {
                if let Some(c) = self.expr(cond) {
                    if !c.converts_to(&Type::BOOL) {
                        self.error(cond.span, format!("the condition of `?:` is of type `{c}`, expected `bool`"));
                    }
                }
                let (a, b) = (self.expr(then), self.expr(otherwise));
                match (a, b) {
                    (Some(a), Some(b)) if b.converts_to(&a) => Some(a),
                    (Some(a), Some(b)) if a.converts_to(&b) => Some(b),
                    (Some(a), Some(b)) => {
                        self.error(span, format!("the branches of `?:` have different types, `{a}` and `{b}`"));
                        None
                    }
                    _ => None,
                }
            }
            ExprKind::Member { base, field } => {
                let t = self.expr(base);
                let field = field.clone();
                t.and_then(|t| self.member(&t, &field, span))
            }
            ExprKind::Index { base, index } => {
                let t = self.expr(base);
                if let Some(i) = self.expr(index) {
                    if !i.converts_to(&Type::INT) {
                        self.error(index.span, format!("an index is of type `{i}`, expected `int`"));
                    }
                }
                match t {
                    Some(t) => match t.element() {
                        Some(elem) if !matches!(t, Type::Color) => Some(elem),
                        _ => {
                            self.error(span, format!("a value of type `{t}` cannot be indexed"));
                            None
                        }
                    },
                    None => None,
                }
            }
            ExprKind::Let { decls, body } => {
                let mark = self.locals.len();
                for d in decls.iter_mut() {
                    self.var_decl(d);
                }
                let t = self.expr(body);
                self.locals.truncate(mark);
                t
            }
            ExprKind::Sequence(list) => {
                let mut last = None;
                for e in list {
                    last = self.expr(e);
                }
                last
            }
            ExprKind::Assign { op, target, value } => {
                let (t, v) = (self.expr(target), self.expr(value));
                if !is_assignable(target) {
                    self.error(target.span, "only variables, their fields and elements can be assigned to");
                }
                if let (Some(t), Some(v)) = (&t, &v) {
                    if *op == AssignOp::Set && !v.converts_to(t) {
                        self.error(value.span, format!("cannot assign a value of type `{v}` to one of type `{t}`"));
                    }
                }
                t
            }
        };
        e.ty = ty.clone();
        ty
    }

    /// Declares a local (in a `let` or a statement) after checking its initialiser.
    pub(super) fn var_decl(&mut self, d: &mut VarDecl) {
        let span = d.ty.span;
        self.resolve_type(&mut d.ty.ty, span);
        if let Some(init) = &mut d.init {
            self.expr(init);
            let ty = d.ty.ty.clone();
            self.expect_type(init, &ty, &format!("the initial value of `{}`", d.name));
        }
        self.annotations(&mut d.annotations);
        let varying = d.init.as_ref().is_some_and(|e| self.varies(e));
        if varying && d.ty.frequency == Frequency::Uniform {
            let span = d.init.as_ref().map_or(d.span, |e| e.span);
            self.error(span, format!("`{}` is uniform, but its initial value varies over the surface", d.name));
        }
        let (name, res, ty) = (d.name.clone(), Resolution::Local(d.id), d.ty.ty.clone());
        self.locals.push(Local { name, res, ty, varying });
    }

    /// Whether the value of a checked expression may vary over the surface: it calls a
    /// function declared `varying` (the `state::` functions), reads a `varying` parameter, or
    /// a local initialised from such a value. Parameters without a modifier count as uniform,
    /// so that this never reports a uniform value as varying.
    pub(super) fn varies(&self, e: &Expr) -> bool {
        let mut varying_lets = Vec::new();
        self.varies_in(e, &mut varying_lets)
    }

    fn varies_in(&self, e: &Expr, varying_lets: &mut Vec<u32>) -> bool {
        match &e.kind {
            ExprKind::Bool(_) | ExprKind::Int(_) | ExprKind::Float { .. } | ExprKind::Str(_) => false,
            ExprKind::Name(n) => match &n.res {
                Resolution::Local(id) if varying_lets.contains(id) => true,
                Resolution::Param(_) | Resolution::Local(_) => {
                    self.locals.iter().rev().find(|l| l.res == n.res).is_some_and(|l| l.varying)
                }
                _ => false,
            },
            ExprKind::Call(call) => {
                let declared_varying = match &call.res {
                    Resolution::Function { module, decl, .. } => {
                        let decl = if *module == self.module_name {
                            self.decls.get(*decl)
                        } else {
                            self.set.module(module).and_then(|m| m.decls.get(*decl))
                        };
                        matches!(decl, Some(Decl::Function(f)) if f.frequency == Frequency::Varying)
                    }
                    _ => false,
                };
                declared_varying || call.args.iter().any(|a| self.varies_in(&a.value, varying_lets))
            }
            ExprKind::Unary { operand, .. } => self.varies_in(operand, varying_lets),
            ExprKind::Binary { lhs, rhs, .. } => self.varies_in(lhs, varying_lets) || self.varies_in(rhs, varying_lets),
            ExprKind::Conditional { cond, then, otherwise } => {
                self.varies_in(cond, varying_lets)
                    || self.varies_in(then, varying_lets)
                    || self.varies_in(otherwise, varying_lets)
            }
            ExprKind::Member { base, .. } => self.varies_in(base, varying_lets),
            ExprKind::Index { base, index } => {
                self.varies_in(base, varying_lets) || self.varies_in(index, varying_lets)
            }
            ExprKind::Let { decls, body } => {
                for d in decls {
                    if d.init.as_ref().is_some_and(|i| self.varies_in(i, varying_lets)) {
                        varying_lets.push(d.id);
                    }
                }
                self.varies_in(body, varying_lets)
            }
            ExprKind::Sequence(list) => list.iter().any(|x| self.varies_in(x, varying_lets)),
            ExprKind::Assign { value, .. } => self.varies_in(value, varying_lets),
        }
    }

    fn name(&mut self, n: &mut NameRef, span: mi::Span) -> Option<Type> {
        if !n.name.is_qualified() {
            if let Some(local) = self.locals.iter().rev().find(|l| l.name == n.name.last()) {
                n.res = local.res.clone();
                return Some(local.ty.clone());
            }
        }
        let syms = match self.lookup(&n.name) {
            Ok(s) => s,
            Err(e) => {
                self.error(span, e);
                return None;
            }
        };
        let sym = syms[0].clone();
        let decl_name = self.decl_of(&sym).map(|d| d.name().to_string()).unwrap_or_default();
        match (&sym.kind, self.decl_of(&sym)) {
            (SymbolKind::Const, Some(Decl::Const(c))) => {
                let ty = c.ty.ty.clone();
                n.res = Resolution::Constant { module: sym.module.clone(), name: decl_name };
                Some(ty)
            }
            (SymbolKind::EnumValue { value }, Some(Decl::Enum(e))) => {
                let enum_type = crate::symbols::type_name(&sym.module, &e.name);
                n.res = Resolution::EnumValue { enum_type: enum_type.clone(), value: *value };
                Some(Type::Enum(enum_type))
            }
            (SymbolKind::Function | SymbolKind::Material, _) => {
                let name = n.name.clone();
                self.error(span, format!("`{name}` is a function or material: call it with `(…)`"));
                None
            }
            _ => {
                let name = n.name.clone();
                self.error(span, format!("`{name}` is not a value"));
                None
            }
        }
    }

    fn member(&mut self, t: &Type, field: &str, span: mi::Span) -> Option<Type> {
        match t {
            Type::Vector(s, n) => {
                let index = ["x", "y", "z", "w"].iter().position(|c| *c == field);
                match index {
                    Some(i) if i < *n as usize => Some(Type::Scalar(*s)),
                    _ => {
                        self.error(span, format!("`{t}` has no component `{field}`"));
                        None
                    }
                }
            }
            Type::Struct(name) => self.struct_field(name, field, span),
            Type::Material => self.struct_field("material", field, span),
            Type::Named(_) => None,
            _ => {
                self.error(span, format!("a value of type `{t}` has no field `{field}`"));
                None
            }
        }
    }

    fn struct_field(&mut self, struct_name: &str, field: &str, span: mi::Span) -> Option<Type> {
        let fields = self.struct_fields(struct_name)?;
        match fields.iter().find(|(n, _)| n == field) {
            Some((_, t)) => Some(t.clone()),
            None => {
                self.error(span, format!("struct `{struct_name}` has no field `{field}`"));
                None
            }
        }
    }

    /// The fields (name, type) of the struct of absolute type name `name`.
    pub(super) fn struct_fields(&self, name: &str) -> Option<Vec<(String, Type)>> {
        let (module, local) = crate::module_table::split_type_name(name);
        let decl = if module == self.module_name {
            self.decls.iter().find_map(|d| match d {
                Decl::Struct(s) if s.name == local => Some(s),
                _ => None,
            })
        } else {
            self.set.struct_decl(name)
        }?;
        Some(decl.fields.iter().map(|f| (f.name.clone(), f.ty.ty.clone())).collect())
    }

    fn binary(&mut self, op: BinaryOp, l: Option<Type>, r: Option<Type>, span: mi::Span) -> Option<Type> {
        if matches!(op, BinaryOp::And | BinaryOp::Or) {
            return Some(Type::BOOL);
        }
        let (l, r) = (l?, r?);
        let text = binary_text(op);
        for t in [&l, &r] {
            let comparable = matches!(op, BinaryOp::Eq | BinaryOp::Ne) && matches!(t, Type::String);
            if !is_arithmetic(t) && !comparable {
                self.error(span, format!("operator `{text}` is not defined for `{t}`"));
                return None;
            }
        }
        if op.is_boolean() {
            return Some(Type::BOOL);
        }
        let result = match (&l, &r) {
            (a, b) if b.converts_to(a) => Some(a.clone()),
            (a, b) if a.converts_to(b) => Some(b.clone()),
            (a, b) if a.is_numeric_scalar() => Some(b.clone()),
            (a, b) if b.is_numeric_scalar() => Some(a.clone()),
            (Type::Matrix(s, c, r), Type::Vector(_, n)) if op == BinaryOp::Mul && c == n => Some(Type::Vector(*s, *r)),
            (Type::Vector(_, n), Type::Matrix(s, c, r)) if op == BinaryOp::Mul && r == n => Some(Type::Vector(*s, *c)),
            (Type::Matrix(s, _, r), Type::Matrix(_, c, _)) if op == BinaryOp::Mul => Some(Type::Matrix(*s, *c, *r)),
            _ => None,
        };
        if result.is_none() {
            self.error(span, format!("operator `{text}` cannot combine `{l}` and `{r}`"));
        }
        result
    }
}

/// Whether operators apply to values of this type (numbers, vectors, matrices, colours,
/// enums and bools).
fn is_arithmetic(t: &Type) -> bool {
    matches!(t, Type::Scalar(_) | Type::Vector(..) | Type::Matrix(..) | Type::Color | Type::Enum(_))
}

fn is_assignable(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Name(n) => matches!(n.res, Resolution::Local(_) | Resolution::Param(_)),
        ExprKind::Member { base, .. } | ExprKind::Index { base, .. } => is_assignable(base),
        _ => false,
    }
}

fn unary_text(op: UnaryOp) -> &'static str {
    match op {
        UnaryOp::Neg => "-",
        UnaryOp::Plus => "+",
        UnaryOp::Not => "!",
        UnaryOp::BitNot => "~",
        UnaryOp::PreInc | UnaryOp::PostInc => "++",
        UnaryOp::PreDec | UnaryOp::PostDec => "--",
    }
}

fn binary_text(op: BinaryOp) -> &'static str {
    match op {
        BinaryOp::Mul => "*",
        BinaryOp::Div => "/",
        BinaryOp::Rem => "%",
        BinaryOp::Add => "+",
        BinaryOp::Sub => "-",
        BinaryOp::Shl => "<<",
        BinaryOp::Shr => ">>",
        BinaryOp::UShr => ">>>",
        BinaryOp::Lt => "<",
        BinaryOp::Le => "<=",
        BinaryOp::Gt => ">",
        BinaryOp::Ge => ">=",
        BinaryOp::Eq => "==",
        BinaryOp::Ne => "!=",
        BinaryOp::BitAnd => "&",
        BinaryOp::BitXor => "^",
        BinaryOp::BitOr => "|",
        BinaryOp::And => "&&",
        BinaryOp::Or => "||",
    }
}
