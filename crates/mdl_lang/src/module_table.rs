//! The table of loaded modules: each checked module with its symbol tables, looked up by
//! absolute name, and the lookups a compiler needs (materials, functions, structs, enums).
//! The loader ([`crate::ModuleSet`]) fills it; the semantic pass reads the modules already in it.

use std::collections::HashMap;

use crate::ast::{Decl, EnumDecl, Function, Module, Resolution, StructDecl};
use crate::std_modules::PRELUDE;
use crate::symbols::{Scope, Symbol};

/// A loaded, checked module and its symbol tables.
#[derive(Debug)]
pub struct LoadedModule {
    /// The checked tree.
    pub module: Module,
    /// Every name it declares.
    pub declared: Scope,
    /// The names other modules may import from it (its exported declarations and re-exports).
    pub exports: Scope,
}

/// Every module loaded so far, by absolute name, in the order loading finished.
#[derive(Debug, Default)]
pub struct ModuleTable {
    modules: Vec<LoadedModule>,
    index: HashMap<String, usize>,
}

/// The absolute form of a module or qualified name: a leading `::` added if missing.
pub(crate) fn absolute(name: &str) -> String {
    if name.starts_with("::") {
        name.to_string()
    } else {
        format!("::{name}")
    }
}

impl ModuleTable {
    /// Records module `name` (absolute); returns its position.
    pub(crate) fn insert(&mut self, name: &str, loaded: LoadedModule) -> usize {
        let i = self.modules.len();
        self.modules.push(loaded);
        self.index.insert(name.to_string(), i);
        i
    }

    /// The position of module `name` (absolute), if loaded.
    pub(crate) fn position(&self, name: &str) -> Option<&usize> {
        self.index.get(name)
    }

    /// Whether module `name` (absolute) is loaded.
    pub(crate) fn contains(&self, name: &str) -> bool {
        self.index.contains_key(name)
    }

    /// The module at position `i`.
    pub(crate) fn at(&self, i: usize) -> &LoadedModule {
        &self.modules[i]
    }

    /// A loaded module by absolute name (`::a::b`; `a::b` is accepted too).
    pub fn module(&self, name: &str) -> Option<&Module> {
        self.loaded(name).map(|m| &m.module)
    }

    /// A loaded module with its symbol tables.
    pub fn loaded(&self, name: &str) -> Option<&LoadedModule> {
        self.index.get(&absolute(name)).map(|&i| &self.modules[i])
    }

    /// Every loaded module, in the order loading finished (imports before importers).
    pub fn modules(&self) -> impl Iterator<Item = &Module> {
        self.modules.iter().map(|m| &m.module)
    }

    /// The declaration a symbol points at.
    pub fn decl(&self, sym: &Symbol) -> Option<&Decl> {
        self.module(&sym.module)?.decls.get(sym.decl)
    }

    /// The exported symbols named `qualified` (`::m::name` or `m::name`).
    pub fn exported(&self, qualified: &str) -> &[Symbol] {
        let q = absolute(qualified);
        let Some((module, name)) = q.rsplit_once("::") else {
            return &[];
        };
        self.loaded(module).and_then(|m| m.exports.get(name)).map_or(&[], Vec::as_slice)
    }

    /// The exported material `qualified` (`::m::matte`), following re-exports.
    pub fn material(&self, qualified: &str) -> Option<&Function> {
        self.exported(qualified).iter().find_map(|s| match self.decl(s) {
            Some(Decl::Function(f)) if f.is_material() => Some(f),
            _ => None,
        })
    }

    /// The exported overloads of function `qualified` (`::math::lerp`), in declaration order.
    pub fn functions(&self, qualified: &str) -> Vec<&Function> {
        self.exported(qualified)
            .iter()
            .filter_map(|s| match self.decl(s) {
                Some(Decl::Function(f)) if !f.is_material() => Some(f),
                _ => None,
            })
            .collect()
    }

    /// The definition a call's resolution ([`Resolution::Function`] or [`Resolution::Material`])
    /// points at.
    pub fn definition(&self, res: &Resolution) -> Option<&Function> {
        let (module, decl) = match res {
            Resolution::Function { module, decl, .. } | Resolution::Material { module, decl, .. } => (module, *decl),
            _ => return None,
        };
        match self.module(module)?.decls.get(decl)? {
            Decl::Function(f) => Some(f),
            _ => None,
        }
    }

    /// The struct of absolute type name `name` (`::base::texture_return`, `material_surface`).
    pub fn struct_decl(&self, name: &str) -> Option<&StructDecl> {
        let (module, local) = split_type_name(name);
        self.module(module)?.decls.iter().find_map(|d| match d {
            Decl::Struct(s) if s.name == local => Some(s),
            _ => None,
        })
    }

    /// The enum of absolute type name `name` (`::df::scatter_mode`, `intensity_mode`).
    pub fn enum_decl(&self, name: &str) -> Option<&EnumDecl> {
        let (module, local) = split_type_name(name);
        self.module(module)?.decls.iter().find_map(|d| match d {
            Decl::Enum(e) if e.name == local => Some(e),
            _ => None,
        })
    }
}

/// The module and local name of an absolute type name; names without a module are the
/// prelude's.
pub(crate) fn split_type_name(name: &str) -> (&str, &str) {
    match name.rsplit_once("::") {
        Some((m, n)) if !m.is_empty() => (m, n),
        _ => (PRELUDE, name.trim_start_matches("::")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn type_names_split_into_module_and_name() {
        assert_eq!(split_type_name("::base::texture_return"), ("::base", "texture_return"));
        assert_eq!(split_type_name("material_surface"), (PRELUDE, "material_surface"));
    }
}
