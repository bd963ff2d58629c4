//! Loading modules: finding a module's source (built in, or on the [`MdlSearchPath`]),
//! parsing it, loading its imports recursively, checking it, and keeping every loaded module
//! in a table looked up by absolute name.

use std::collections::HashMap;
use std::path::Path;

use mi::{Diagnostic, Origin, SourceMap, Span};

use crate::ast::{Decl, EnumDecl, Function, ImportKind, ImportNames, Module, ModulePath, Resolution, StructDecl};
use crate::error::Error;
use crate::parser::parse_module;
use crate::search_path::MdlSearchPath;
use crate::std_modules::{std_module, PRELUDE};
use crate::symbols::{declared, Scope, Symbol, SymbolKind};

/// Largest module file mira reads, in bytes.
const MAX_MODULE_SIZE: u64 = 64 << 20;

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

/// Every module loaded so far, with the sources they were read from.
#[derive(Debug)]
pub struct ModuleSet {
    search: MdlSearchPath,
    sources: SourceMap,
    modules: Vec<LoadedModule>,
    index: HashMap<String, usize>,
}

/// Why loading stopped, before it becomes an [`Error`].
pub(crate) enum Fail {
    /// Problems with places in the sources.
    Located(Vec<Diagnostic>),
    /// A problem without a place.
    Unlocated(String),
}

/// Loads module `name` (`::a::b`, or `a::b` meaning the same) and everything it imports.
pub fn load_module(name: &str, search: &MdlSearchPath) -> Result<ModuleSet, Error> {
    let mut set = ModuleSet::new(search.clone());
    set.load(name)?;
    Ok(set)
}

/// The absolute form of a module or qualified name: a leading `::` added if missing.
fn absolute(name: &str) -> String {
    if name.starts_with("::") {
        name.to_string()
    } else {
        format!("::{name}")
    }
}

impl ModuleSet {
    /// An empty set that finds modules on `search` (and the built-in ones).
    pub fn new(search: MdlSearchPath) -> ModuleSet {
        ModuleSet { search, sources: SourceMap::new(), modules: Vec::new(), index: HashMap::new() }
    }

    /// The search path.
    pub fn search_path(&self) -> &MdlSearchPath {
        &self.search
    }

    /// Every source file read (for rendering diagnostics).
    pub fn sources(&self) -> &SourceMap {
        &self.sources
    }

    /// Loads module `name` and its imports (a module already loaded is not read again).
    pub fn load(&mut self, name: &str) -> Result<&Module, Error> {
        let name = absolute(name);
        let mut stack = Vec::new();
        match self.load_inner(&name, None, &mut stack) {
            Ok(i) => Ok(&self.modules[i].module),
            Err(fail) => Err(self.error(fail)),
        }
    }

    /// Loads the module in file `path` (as `$include "x.mdl"` does): its name is the file's stem
    /// (`::x`), and its directory is added to the end of the search path for its imports.
    pub fn load_file(&mut self, path: &Path) -> Result<&Module, Error> {
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        let name = format!("::{stem}");
        if MdlSearchPath::relative_file(&name).is_none() {
            return Err(Error::unlocated(format!("{}: the file name is not an MDL module name", path.display())));
        }
        if let Some(dir) = path.parent() {
            let dir = if dir.as_os_str().is_empty() { Path::new(".") } else { dir };
            self.search.push(dir);
        }
        if let Some(&i) = self.index.get(&name) {
            return Ok(&self.modules[i].module);
        }
        let bytes = read_module(path).map_err(Error::unlocated)?;
        let mut stack = Vec::new();
        match self.finish(&name, Origin::Disk(path.to_path_buf()), bytes, false, &mut stack) {
            Ok(i) => Ok(&self.modules[i].module),
            Err(fail) => Err(self.error(fail)),
        }
    }

    /// Loads module `name` from `text` held in memory (its imports come from the search path).
    pub fn load_source(&mut self, name: &str, text: &str) -> Result<&Module, Error> {
        let name = absolute(name);
        if self.index.contains_key(&name) || std_module(&name).is_some() {
            return Err(Error::unlocated(format!("module `{name}` is already loaded")));
        }
        let file = format!("{}.mdl", name.trim_start_matches("::").replace("::", "/"));
        let mut stack = Vec::new();
        match self.finish(&name, Origin::Memory(file), text.as_bytes().to_vec(), false, &mut stack) {
            Ok(i) => Ok(&self.modules[i].module),
            Err(fail) => Err(self.error(fail)),
        }
    }

    fn error(&self, fail: Fail) -> Error {
        match fail {
            Fail::Located(diags) => Error::from_diagnostics(&diags, &self.sources),
            Fail::Unlocated(message) => Error::unlocated(message),
        }
    }

    fn load_inner(&mut self, name: &str, from: Option<Span>, stack: &mut Vec<String>) -> Result<usize, Fail> {
        if let Some(&i) = self.index.get(name) {
            return Ok(i);
        }
        let fail = |message: String| match from {
            Some(span) => Fail::Located(vec![Diagnostic::error(span, message)]),
            None => Fail::Unlocated(message),
        };
        if let Some(pos) = stack.iter().position(|m| m == name) {
            let mut cycle: Vec<&str> = stack[pos..].iter().map(String::as_str).collect();
            cycle.push(name);
            return Err(fail(format!("import cycle: {}", cycle.join(" imports "))));
        }
        let builtin = std_module(name);
        let on_path = match builtin {
            Some(m) if !m.overridable => None,
            _ => self.search.find(name),
        };
        let (origin, bytes, is_builtin) = match (on_path, builtin) {
            (Some(path), _) => {
                let bytes = read_module(&path).map_err(fail)?;
                (Origin::Disk(path), bytes, false)
            }
            (None, Some(m)) => (Origin::Builtin(m.file), m.text.as_bytes().to_vec(), true),
            (None, None) => {
                let file = MdlSearchPath::relative_file(name).map_or_else(String::new, |p| p.display().to_string());
                let dirs: Vec<String> = self.search.dirs().iter().map(|d| d.display().to_string()).collect();
                let searched = if dirs.is_empty() { "an empty search path".to_string() } else { dirs.join(", ") };
                return Err(fail(format!("module `{name}` not found: no {file} in {searched}")));
            }
        };
        self.finish(name, origin, bytes, is_builtin, stack)
    }

    /// Parses, loads the imports of, checks and records module `name`.
    fn finish(
        &mut self,
        name: &str,
        origin: Origin,
        bytes: Vec<u8>,
        builtin: bool,
        stack: &mut Vec<String>,
    ) -> Result<usize, Fail> {
        let file = self.sources.add(origin, bytes);
        let text = self.sources.file(file).bytes.clone();
        let mut module = parse_module(name, file, &text, builtin).map_err(|d| Fail::Located(vec![d]))?;
        stack.push(name.to_string());
        let result = self.load_imports(&mut module, stack);
        stack.pop();
        result?;
        let diags = crate::sema::check(&mut module, self);
        if !diags.is_empty() {
            return Err(Fail::Located(diags));
        }
        let (declared, mut exports) = declared(&module);
        for import in &module.imports {
            if let (true, ImportKind::Using { names, .. }, Some(target)) =
                (import.exported, &import.kind, &import.resolved)
            {
                let from = &self.modules[self.index[target]].exports;
                let mut wanted: Vec<String> = match names {
                    ImportNames::All => from.keys().cloned().collect(),
                    ImportNames::Some(list) => list.clone(),
                };
                // Re-exporting an enum type re-exports its values.
                let enums: Vec<&Symbol> = wanted
                    .iter()
                    .filter_map(|n| from.get(n))
                    .flatten()
                    .filter(|s| s.kind == SymbolKind::Enum)
                    .collect();
                let values: Vec<String> = enums
                    .into_iter()
                    .filter_map(|s| match self.decl(s) {
                        Some(Decl::Enum(e)) => Some(e.values.iter().map(|v| v.name.clone())),
                        _ => None,
                    })
                    .flatten()
                    .collect();
                wanted.extend(values);
                for n in wanted {
                    if let Some(syms) = from.get(&n) {
                        let entry = exports.entry(n).or_default();
                        for s in syms {
                            if !entry.contains(s) {
                                entry.push(s.clone());
                            }
                        }
                    }
                }
            }
        }
        let i = self.modules.len();
        self.modules.push(LoadedModule { module, declared, exports });
        self.index.insert(name.to_string(), i);
        Ok(i)
    }

    fn load_imports(&mut self, module: &mut Module, stack: &mut Vec<String>) -> Result<(), Fail> {
        // The prelude (the material types) is imported by every module but itself and `::state`,
        // which the prelude imports.
        if module.name != PRELUDE && module.name != "::state" {
            self.load_inner(PRELUDE, None, stack)?;
        }
        for import in &mut module.imports {
            let target = self.resolve_path(&module.name, import.kind.module(), import.span)?;
            self.load_inner(&target, Some(import.span), stack)?;
            import.resolved = Some(target);
        }
        Ok(())
    }

    /// The absolute module name an import path in module `current` denotes.
    fn resolve_path(&self, current: &str, path: &ModulePath, at: Span) -> Result<String, Fail> {
        let mut package: Vec<&str> = current.trim_start_matches("::").split("::").collect();
        package.pop();
        let joined = |prefix: &[&str]| {
            let mut all: Vec<&str> = prefix.to_vec();
            all.extend(path.parts.iter().map(String::as_str));
            format!("::{}", all.join("::"))
        };
        if path.parts.is_empty() {
            return Err(Fail::Located(vec![Diagnostic::error(at, "import names no module")]));
        }
        if path.absolute {
            return Ok(joined(&[]));
        }
        if path.relative {
            for _ in 0..path.parents {
                if package.pop().is_none() {
                    return Err(Fail::Located(vec![Diagnostic::error(
                        at,
                        format!("`{path}` goes above the top of the package hierarchy from `{current}`"),
                    )]));
                }
            }
            return Ok(joined(&package));
        }
        // Weak relative: the current package first, then the top level.
        if !package.is_empty() {
            let candidate = joined(&package);
            if self.index.contains_key(&candidate)
                || std_module(&candidate).is_some()
                || self.search.find(&candidate).is_some()
            {
                return Ok(candidate);
            }
        }
        Ok(joined(&[]))
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

/// Reads a module file, refusing unreasonably large ones.
fn read_module(path: &Path) -> Result<Vec<u8>, String> {
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    if meta.len() > MAX_MODULE_SIZE {
        return Err(format!("{} is larger than {} MiB", path.display(), MAX_MODULE_SIZE >> 20));
    }
    std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))
}

/// The MDL module and item a `.mi` shader name refers to: `mdl::a::b::matte` or
/// `mdl::a::b::matte(color,float)` (Iray's form with a signature) gives `("::a::b", "matte")`.
/// `None` for a name without the `mdl::` prefix or without a module part.
pub fn split_mi_name(name: &str) -> Option<(String, String)> {
    let rest = name.strip_prefix("mdl::")?;
    let rest = rest.split_once('(').map_or(rest, |(n, _)| n);
    let (module, item) = rest.trim_start_matches("::").rsplit_once("::")?;
    if module.is_empty() || item.is_empty() {
        return None;
    }
    Some((format!("::{module}"), item.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mi_shader_names_split_into_module_and_item() {
        let split = |n| split_mi_name(n);
        assert_eq!(split("mdl::export_multi::matte"), Some(("::export_multi".into(), "matte".into())));
        assert_eq!(
            split("mdl::nvidia::core_definitions::flex_material(color,float)"),
            Some(("::nvidia::core_definitions".into(), "flex_material".into()))
        );
        assert_eq!(split("mdl::::m::x"), Some(("::m".into(), "x".into())));
        assert_eq!(split("mdl::matte"), None);
        assert_eq!(split("mib_illum_lambert"), None);
    }

    #[test]
    fn type_names_split_into_module_and_name() {
        assert_eq!(split_type_name("::base::texture_return"), ("::base", "texture_return"));
        assert_eq!(split_type_name("material_surface"), (PRELUDE, "material_surface"));
    }
}
