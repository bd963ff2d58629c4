//! The semantic pass: resolves every type and name of a module against its own declarations
//! and its imports, chooses overloads, fills in the types of expressions where they follow
//! simply, checks defaults, arguments and bodies against their declared types, and expands
//! material variants to full definitions. Errors are collected, each at its place.
//!
//! The module's declarations are worked on in a copy (`decls`) that always holds the latest
//! state, so that a declaration can read the already resolved ones before it.

mod call;
mod expr;
mod stmt;

use mi::{Diagnostic, Span};

use crate::ast::*;
use crate::module_table::ModuleTable;
use crate::std_modules::PRELUDE;
use crate::symbols::{declared, type_name, Scope, Symbol, SymbolKind};

/// Most errors reported for one module.
const MAX_ERRORS: usize = 50;

/// Checks `module` (whose imports are loaded in `set`) in place; returns the errors found.
pub(crate) fn check(module: &mut Module, set: &ModuleTable) -> Vec<Diagnostic> {
    let (own, _) = declared(module);
    let mut c = Checker {
        set,
        module_name: module.name.clone(),
        own,
        usings: Scope::new(),
        qualified: Vec::new(),
        decls: std::mem::take(&mut module.decls),
        diags: Vec::new(),
        locals: Vec::new(),
        ret: None,
        loops: 0,
        deferred: Vec::new(),
    };
    c.duplicates();
    c.imports(&module.imports);
    let mut annotations = std::mem::take(&mut module.annotations);
    c.annotations(&mut annotations);
    module.annotations = annotations;
    for i in 0..c.decls.len() {
        let mut d = c.decls[i].clone();
        c.resolve_decl_types(&mut d);
        c.decls[i] = d;
    }
    for i in 0..c.decls.len() {
        if matches!(&c.decls[i], Decl::Function(f) if f.variant.is_some()) {
            continue;
        }
        let mut d = c.decls[i].clone();
        c.check_decl(&mut d);
        c.decls[i] = d;
    }
    for i in 0..c.decls.len() {
        if let Decl::Function(f) = &c.decls[i] {
            if f.variant.is_some() {
                let mut f = f.clone();
                c.expand_variant(&mut f, i);
                c.decls[i] = Decl::Function(f);
            }
        }
    }
    module.decls = std::mem::take(&mut c.decls);
    c.diags.truncate(MAX_ERRORS);
    c.diags
}

/// Names usable with a qualifier, from one import.
struct QualifiedImport {
    /// The qualifier as it may be written (`df`, `nvidia::core_definitions`, an alias).
    qualifier: Vec<String>,
    /// The absolute module name.
    module: String,
    /// Which of its exports.
    names: ImportNames,
}

/// A local name in scope: a parameter or a declared variable.
#[derive(Clone, Debug)]
struct Local {
    name: String,
    res: Resolution,
    ty: Type,
    /// Whether its value may vary over the surface (see `Checker::varies`).
    varying: bool,
}

pub(crate) struct Checker<'a> {
    set: &'a ModuleTable,
    module_name: String,
    /// Every name the module declares.
    own: Scope,
    /// Names imported unqualified by `using`.
    usings: Scope,
    qualified: Vec<QualifiedImport>,
    /// The module's declarations, latest state.
    decls: Vec<Decl>,
    diags: Vec<Diagnostic>,
    /// Locals in scope, innermost last.
    locals: Vec<Local>,
    /// Return type of the function being checked.
    ret: Option<Type>,
    /// Depth of enclosing loops.
    loops: u32,
    /// Deferred array size symbols (`N` of `T[<N>]`) of the parameters read so far.
    deferred: Vec<String>,
}

impl Checker<'_> {
    fn error(&mut self, span: Span, message: impl Into<String>) {
        if self.diags.len() <= MAX_ERRORS {
            self.diags.push(Diagnostic::error(span, message));
        }
    }

    /// Two declarations of one name are an error, except overloaded functions.
    fn duplicates(&mut self) {
        let mut found = Vec::new();
        for (name, syms) in &self.own {
            let functions = syms.iter().all(|s| s.kind == SymbolKind::Function)
                || syms.iter().all(|s| s.kind == SymbolKind::Annotation);
            if syms.len() > 1 && !functions {
                let second = &syms[1];
                found.push((self.decls[second.decl].span(), name.clone()));
            }
        }
        found.sort_by_key(|(s, _)| s.lo);
        for (span, name) in found {
            self.error(span, format!("`{name}` is declared twice in this module"));
        }
    }

    /// Builds the tables of imported names and checks that imported names exist.
    fn imports(&mut self, imports: &[Import]) {
        for import in imports {
            let Some(target) = import.resolved.clone() else { continue };
            let Some(loaded) = self.set.loaded(&target) else { continue };
            let abs_parts: Vec<String> = target.trim_start_matches("::").split("::").map(str::to_string).collect();
            let (names, written) = match &import.kind {
                ImportKind::Import { names, module } | ImportKind::Using { names, module } => (names.clone(), module),
                ImportKind::Alias { alias, .. } => {
                    self.qualified.push(QualifiedImport {
                        qualifier: vec![alias.clone()],
                        module: target.clone(),
                        names: ImportNames::All,
                    });
                    continue;
                }
            };
            let mut names = names;
            if let ImportNames::Some(list) = &mut names {
                let mut values = Vec::new();
                for n in list.iter() {
                    let Some(syms) = loaded.exports.get(n) else {
                        let why = if loaded.declared.contains_key(n) { "does not export" } else { "has no" };
                        self.error(import.span, format!("module `{target}` {why} `{n}`"));
                        continue;
                    };
                    // Importing an enum type imports its values.
                    for sym in syms.iter().filter(|s| s.kind == SymbolKind::Enum) {
                        if let Some(Decl::Enum(e)) = self.set.decl(sym) {
                            values.extend(e.values.iter().map(|v| v.name.clone()));
                        }
                    }
                }
                list.extend(values);
            }
            if written.parts != abs_parts && !written.absolute {
                self.qualified.push(QualifiedImport {
                    qualifier: written.parts.clone(),
                    module: target.clone(),
                    names: names.clone(),
                });
            }
            self.qualified.push(QualifiedImport { qualifier: abs_parts, module: target.clone(), names: names.clone() });
            if let ImportKind::Using { .. } = import.kind {
                for (n, syms) in &loaded.exports {
                    let wanted = match &names {
                        ImportNames::All => true,
                        ImportNames::Some(list) => list.contains(n),
                    };
                    if wanted {
                        self.usings.entry(n.clone()).or_default().extend(syms.iter().cloned());
                    }
                }
            }
        }
    }

    /// The declaration a symbol points at (this module's latest state for its own).
    fn decl_of(&self, sym: &Symbol) -> Option<&Decl> {
        if sym.module == self.module_name {
            self.decls.get(sym.decl)
        } else {
            self.set.decl(sym)
        }
    }

    /// The symbols a (possibly qualified) module-level name denotes.
    fn lookup(&self, q: &QualName) -> Result<Vec<Symbol>, String> {
        let name = q.last();
        if !q.is_qualified() {
            for scope in [Some(&self.own), Some(&self.usings), self.set.loaded(PRELUDE).map(|m| &m.exports)] {
                if let Some(syms) = scope.and_then(|s| s.get(name)) {
                    if !syms.is_empty() {
                        return Ok(syms.clone());
                    }
                }
            }
            return Err(format!("unknown name `{name}`"));
        }
        let qualifier = q.qualifier();
        let joined = format!("::{}", qualifier.join("::"));
        if joined == self.module_name {
            return self.own.get(name).cloned().ok_or_else(|| format!("`{q}` is not declared in this module"));
        }
        let mut matched = None;
        let mut found = Vec::new();
        for import in &self.qualified {
            if import.qualifier.as_slice() != qualifier && !(q.absolute && import.module == joined) {
                continue;
            }
            matched = Some(import);
            let wanted = match &import.names {
                ImportNames::All => true,
                ImportNames::Some(list) => list.iter().any(|n| n == name),
            };
            if let (true, Some(m)) = (wanted, self.set.loaded(&import.module)) {
                if let Some(syms) = m.exports.get(name) {
                    for s in syms {
                        if !found.contains(s) {
                            found.push(s.clone());
                        }
                    }
                }
            }
        }
        match matched {
            None => Err(format!("module `{joined}` is not imported (add `import {joined}::*;`)")),
            Some(_) if found.is_empty() => {
                let module = matched.map_or(joined.clone(), |m| m.module.clone());
                Err(format!("`{q}`: module `{module}` has no exported `{name}` (or it is not imported)"))
            }
            Some(_) => Ok(found),
        }
    }

    /// Resolves user type names in `ty` to struct and enum types; reports unknown ones.
    fn resolve_type(&mut self, ty: &mut Type, span: Span) {
        self.resolve_type_depth(ty, span, 0);
    }

    fn resolve_type_depth(&mut self, ty: &mut Type, span: Span, depth: u32) {
        match ty {
            Type::Named(q) => {
                let syms = match self.lookup(q) {
                    Ok(s) => s,
                    Err(e) => {
                        self.error(span, e.replace("unknown name", "unknown type"));
                        return;
                    }
                };
                let sym = &syms[0];
                let decl_name = self.decl_of(sym).map(|d| d.name().to_string()).unwrap_or_default();
                *ty = match &sym.kind {
                    SymbolKind::Struct if sym.module == PRELUDE && decl_name == "material" => Type::Material,
                    SymbolKind::Struct => Type::Struct(type_name(&sym.module, &decl_name)),
                    SymbolKind::Enum => Type::Enum(type_name(&sym.module, &decl_name)),
                    SymbolKind::Typedef => {
                        let Some(Decl::Typedef(t)) = self.decl_of(sym) else { return };
                        let mut target = t.ty.ty.clone();
                        if depth < 16 {
                            self.resolve_type_depth(&mut target, span, depth + 1);
                        }
                        target
                    }
                    _ => {
                        let q = q.clone();
                        self.error(span, format!("`{q}` is not a type"));
                        return;
                    }
                };
            }
            Type::Array(elem, len) => {
                self.resolve_type_depth(elem, span, depth);
                if let ArrayLen::Named(q) = len {
                    if !q.is_qualified() && self.deferred.iter().any(|d| d == q.last()) {
                        return;
                    }
                    match self.lookup(q) {
                        Ok(syms) => {
                            let value = match self.decl_of(&syms[0]) {
                                Some(Decl::Const(c)) => match c.value.kind {
                                    ExprKind::Int(n) if n >= 0 => Some(n as u64),
                                    _ => None,
                                },
                                _ => {
                                    let q = q.clone();
                                    self.error(span, format!("array size `{q}` is not an integer constant"));
                                    return;
                                }
                            };
                            if let Some(n) = value {
                                *len = ArrayLen::Fixed(n);
                            }
                        }
                        Err(e) => self.error(span, e),
                    }
                }
            }
            _ => {}
        }
    }

    fn resolve_params(&mut self, params: &mut [Param]) {
        self.deferred.clear();
        for p in params.iter_mut() {
            let span = p.ty.span;
            self.resolve_type(&mut p.ty.ty, span);
            if let Type::Array(_, ArrayLen::Deferred(n)) = &p.ty.ty {
                self.deferred.push(n.clone());
            }
        }
    }

    fn resolve_decl_types(&mut self, d: &mut Decl) {
        match d {
            Decl::Function(f) => {
                let span = f.ret.span;
                self.resolve_type(&mut f.ret.ty, span);
                self.resolve_params(&mut f.params);
            }
            Decl::Struct(s) => {
                for field in &mut s.fields {
                    let span = field.ty.span;
                    self.resolve_type(&mut field.ty.ty, span);
                }
            }
            Decl::Const(c) => {
                let span = c.ty.span;
                self.resolve_type(&mut c.ty.ty, span);
            }
            Decl::Typedef(t) => {
                let span = t.ty.span;
                self.resolve_type(&mut t.ty.ty, span);
            }
            Decl::Annotation(a) => self.resolve_params(&mut a.params),
            Decl::Enum(_) => {}
        }
    }

    /// Checks `value` against `expected`, reporting `what` on a mismatch.
    fn expect_type(&mut self, value: &Expr, expected: &Type, what: &str) {
        if let Some(found) = &value.ty {
            if !found.converts_to(expected) {
                self.error(value.span, format!("{what} is of type `{found}`, expected `{expected}`"));
            }
        }
    }

    fn check_decl(&mut self, d: &mut Decl) {
        self.locals.clear();
        self.deferred.clear();
        match d {
            Decl::Const(c) => {
                self.expr(&mut c.value);
                let ty = c.ty.ty.clone();
                self.expect_type(&c.value, &ty, &format!("the value of constant `{}`", c.name));
                self.annotations(&mut c.annotations);
            }
            Decl::Struct(s) => {
                self.annotations(&mut s.annotations);
                for field in &mut s.fields {
                    if let Some(default) = &mut field.default {
                        self.expr(default);
                        let ty = field.ty.ty.clone();
                        self.expect_type(default, &ty, &format!("the default of field `{}`", field.name));
                    }
                    self.annotations(&mut field.annotations);
                }
            }
            Decl::Enum(e) => {
                self.annotations(&mut e.annotations);
                for v in &mut e.values {
                    self.annotations(&mut v.annotations);
                }
            }
            Decl::Typedef(_) => {}
            Decl::Annotation(a) => {
                self.params(&mut a.params);
            }
            Decl::Function(f) => self.function(f),
        }
        self.locals.clear();
    }

    /// Checks parameter defaults (each sees the parameters before it) and leaves every
    /// parameter in scope.
    fn params(&mut self, params: &mut [Param]) {
        for (i, p) in params.iter_mut().enumerate() {
            if let Some(default) = &mut p.default {
                self.expr(default);
                let ty = p.ty.ty.clone();
                self.expect_type(default, &ty, &format!("the default of parameter `{}`", p.name));
                if p.ty.frequency == Frequency::Uniform && self.varies(default) {
                    let message = format!("parameter `{}` is uniform, but its default varies over the surface", p.name);
                    self.error(default.span, message);
                }
            }
            self.annotations(&mut p.annotations);
            let varying = p.ty.frequency == Frequency::Varying;
            self.locals.push(Local { name: p.name.clone(), res: Resolution::Param(i), ty: p.ty.ty.clone(), varying });
            if let Type::Array(_, ArrayLen::Deferred(n)) = &p.ty.ty {
                if !self.locals.iter().any(|l| l.name == *n) {
                    let res = Resolution::ArraySize(i);
                    self.locals.push(Local { name: n.clone(), res, ty: Type::INT, varying: false });
                }
            }
        }
    }

    fn function(&mut self, f: &mut Function) {
        self.params(&mut f.params);
        self.annotations(&mut f.annotations);
        self.ret = Some(f.ret.ty.clone());
        match &mut f.body {
            Body::Expr(e) => {
                self.expr(e);
                if f.ret.ty == Type::Material {
                    if let Some(t) = &e.ty {
                        if *t != Type::Material {
                            let message = format!("the body of material `{}` is of type `{t}`, not a material", f.name);
                            self.error(e.span, message);
                        }
                    }
                } else {
                    let ret = f.ret.ty.clone();
                    self.expect_type(e, &ret, &format!("the body of `{}`", f.name));
                }
            }
            Body::Block(stmts) => self.block(stmts),
            Body::Native => {}
        }
        self.ret = None;
    }

    /// Resolves and checks annotation applications.
    fn annotations(&mut self, list: &mut [Annotation]) {
        for a in list {
            for arg in &mut a.args {
                self.expr(&mut arg.value);
            }
            match self.lookup(&a.name) {
                Ok(syms) => {
                    let sym = &syms[0];
                    if sym.kind != SymbolKind::Annotation {
                        let name = a.name.clone();
                        self.error(a.span, format!("`{name}` is not an annotation"));
                        continue;
                    }
                    let fits = syms.iter().any(|s| match self.decl_of(s) {
                        Some(Decl::Annotation(d)) => {
                            let required = d.params.iter().filter(|p| p.default.is_none()).count();
                            a.args.len() >= required && a.args.len() <= d.params.len()
                        }
                        _ => false,
                    });
                    if !fits {
                        let (name, n) = (a.name.clone(), a.args.len());
                        self.error(a.span, format!("annotation `{name}` does not take {n} argument(s)"));
                    }
                    let decl = self.decl_of(sym).map(|d| d.name().to_string()).unwrap_or_default();
                    a.res = Resolution::Annotation { module: sym.module.clone(), name: decl };
                }
                Err(e) => self.error(a.span, e.replace("unknown name", "unknown annotation")),
            }
        }
    }

    /// Expands `material v(*) = base(args)`: the parameters become the base's with the
    /// defaults `args` sets, the body a call of the base passing every parameter.
    fn expand_variant(&mut self, f: &mut Function, index: usize) {
        self.locals.clear();
        self.annotations(&mut f.annotations);
        let Body::Expr(Expr { kind: ExprKind::Call(call), span, .. }) = &mut f.body else { return };
        let span = *span;
        let base_name = call.callee.clone();
        let syms = match self.lookup(&base_name) {
            Ok(s) => s,
            Err(e) => return self.error(span, e),
        };
        let Some(sym) = syms.iter().find(|s| s.kind == SymbolKind::Material) else {
            return self.error(span, format!("the base `{base_name}` of variant `{}` is not a material", f.name));
        };
        if sym.module == self.module_name && sym.decl >= index {
            return self
                .error(span, format!("the base `{base_name}` of variant `{}` must be declared before it", f.name));
        }
        let Some(Decl::Function(base)) = self.decl_of(sym).cloned() else { return };
        let mut params = base.params.clone();
        for (i, arg) in call.args.iter_mut().enumerate() {
            let idx = match &arg.name {
                Some(n) => match base.param(n) {
                    Some((idx, _)) => idx,
                    None => {
                        self.error(arg.span, format!("material `{base_name}` has no parameter `{n}`"));
                        continue;
                    }
                },
                None if i < params.len() => i,
                None => {
                    self.error(arg.span, format!("too many arguments for material `{base_name}`"));
                    continue;
                }
            };
            self.expr(&mut arg.value);
            let ty = params[idx].ty.ty.clone();
            self.expect_type(&arg.value, &ty, &format!("the argument `{}`", params[idx].name));
            params[idx].default = Some(arg.value.clone());
        }
        let args = params
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let name = NameRef { name: QualName::simple(&p.name), res: Resolution::Param(i) };
                let value = Expr { kind: ExprKind::Name(name), span, ty: Some(p.ty.ty.clone()) };
                Arg { name: Some(p.name.clone()), value, span }
            })
            .collect();
        let res = Resolution::Material { module: sym.module.clone(), name: base.name.clone(), decl: sym.decl };
        let call = Call { callee: base_name, array: None, args, res };
        f.body = Body::Expr(Expr { kind: ExprKind::Call(call), span, ty: Some(Type::Material) });
        if let Some(v) = &mut f.variant {
            v.resolved = Some((sym.module.clone(), base.name.clone()));
        }
        f.params = params;
    }
}
