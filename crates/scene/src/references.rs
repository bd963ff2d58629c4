//! Checks that every shader reference written in a shader list (`= "name"`) or parameter
//! (`= "name"`, `= "name.member"`) names a shader that exists.

use mi::ast::{Param, ShaderItem, ShaderList, Stmt, Value};
use mi::Diagnostic;

use crate::names::{Def, Table};

/// Reports unknown shader references in the elements of `table`.
pub fn check(table: &Table, diags: &mut Vec<Diagnostic>) {
    let mut checker = Checker { table, diags };
    for (_, e) in table.elements.iter() {
        let scope = e.scope.as_str();
        match &e.def {
            Def::Shader(defs) => defs.iter().for_each(|d| checker.list(&d.list, scope)),
            Def::Material(defs) => {
                for m in defs {
                    if let Some(l) = &m.shaders {
                        checker.list(l, scope);
                    }
                    checker.stmts(&m.stmts, scope);
                }
            }
            Def::Light(blocks) | Def::Camera(blocks) | Def::Options(blocks) => {
                blocks.iter().for_each(|b| checker.stmts(&b.stmts, scope))
            }
            _ => {}
        }
    }
}

struct Checker<'t, 'a, 'd> {
    table: &'t Table<'a>,
    diags: &'d mut Vec<Diagnostic>,
}

impl Checker<'_, '_, '_> {
    fn stmts(&mut self, stmts: &[Stmt], scope: &str) {
        for s in stmts {
            match s {
                Stmt::Shaders(l) => self.list(l, scope),
                Stmt::Kw(k) => {
                    for a in &k.args {
                        if let mi::ast::Arg::Shaders(l) | mi::ast::Arg::ShaderArray(l) = a {
                            self.list(l, scope);
                        }
                    }
                }
                Stmt::Output(o) => {
                    if let mi::ast::OutputKind::Shader(l) = &o.kind {
                        self.list(l, scope);
                    }
                }
                _ => {}
            }
        }
    }

    fn list(&mut self, list: &ShaderList, scope: &str) {
        for item in &list.0 {
            match item {
                ShaderItem::Ref(name) => self.shader(&name.text, name.span, scope, false),
                ShaderItem::Call { params, .. } => self.params(params, scope),
                ShaderItem::Define { list, .. } => self.list(list, scope),
            }
        }
    }

    fn params(&mut self, params: &[Param], scope: &str) {
        for p in params {
            self.value(&p.value, scope);
        }
    }

    fn value(&mut self, v: &Value, scope: &str) {
        match v {
            Value::Connect(name) => self.shader(&name.text, name.span, scope, true),
            Value::Define(item) => self.list(&ShaderList(vec![(**item).clone()]), scope),
            Value::Struct(fields) => self.params(fields, scope),
            Value::Array(vs) | Value::Seq(vs) => vs.iter().for_each(|v| self.value(v, scope)),
            _ => {}
        }
    }

    /// `name` (or, for connections, `shader.member`) must be a named shader.
    fn shader(&mut self, name: &str, span: mi::Span, scope: &str, member: bool) {
        let found = |n: &str| self.table.get(n, scope).is_some_and(|(_, e)| matches!(e.def, Def::Shader(_)));
        if found(name) {
            return;
        }
        if member {
            if let Some((base, _)) = name.rsplit_once('.') {
                if found(base) {
                    return;
                }
            }
        }
        let message = match self.table.get(name, scope) {
            Some((_, e)) => format!("'{name}' is a {}, not a shader", e.def.kind()),
            None => format!("unknown shader '{name}'"),
        };
        self.diags.push(Diagnostic::error(span, message));
    }
}
