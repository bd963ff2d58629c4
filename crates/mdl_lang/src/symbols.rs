//! Symbol tables: what a name declared in a module is, and where its declaration lives.

use std::collections::HashMap;

use crate::ast::{Decl, Module};
use crate::std_modules::PRELUDE;

/// What a module-level name denotes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SymbolKind {
    /// A function (one overload).
    Function,
    /// A material definition.
    Material,
    /// A struct type.
    Struct,
    /// An enum type.
    Enum,
    /// A value of an enum (declared in the enum at `decl`).
    EnumValue {
        /// The value.
        value: i64,
    },
    /// A constant.
    Const,
    /// A typedef.
    Typedef,
    /// An annotation.
    Annotation,
}

/// A declared name: its kind and the declaration it comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Symbol {
    /// What it is.
    pub kind: SymbolKind,
    /// Absolute name of the module that declares it.
    pub module: String,
    /// Index of the declaration in that module's `decls`.
    pub decl: usize,
}

/// Names to symbols; overloaded functions have several.
pub type Scope = HashMap<String, Vec<Symbol>>;

/// The absolute name of a type declared as `name` in `module` (prelude types have no module
/// part: `material_surface`).
pub fn type_name(module: &str, name: &str) -> String {
    if module == PRELUDE {
        name.to_string()
    } else {
        format!("{module}::{name}")
    }
}

/// The names `module` declares: all of them, and those it exports (its own exported
/// declarations; re-exports by `export using` are added by the loader).
pub fn declared(module: &Module) -> (Scope, Scope) {
    let mut all = Scope::new();
    let mut exported = Scope::new();
    for (i, decl) in module.decls.iter().enumerate() {
        let mut add = |name: &str, kind: SymbolKind| {
            let sym = Symbol { kind, module: module.name.clone(), decl: i };
            if decl.exported() {
                exported.entry(name.to_string()).or_default().push(sym.clone());
            }
            all.entry(name.to_string()).or_default().push(sym);
        };
        match decl {
            Decl::Function(f) => {
                add(&f.name, if f.is_material() { SymbolKind::Material } else { SymbolKind::Function })
            }
            Decl::Struct(s) => add(&s.name, SymbolKind::Struct),
            Decl::Enum(e) => {
                add(&e.name, SymbolKind::Enum);
                for v in &e.values {
                    add(&v.name, SymbolKind::EnumValue { value: v.value });
                }
            }
            Decl::Const(c) => add(&c.name, SymbolKind::Const),
            Decl::Typedef(t) => add(&t.name, SymbolKind::Typedef),
            Decl::Annotation(a) => add(&a.name, SymbolKind::Annotation),
        }
    }
    (all, exported)
}
