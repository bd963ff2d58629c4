//! Loading modules: finding a module's source (built in, or on the [`MdlSearchPath`]),
//! parsing it, loading its imports recursively, checking it, and keeping every loaded module
//! in a table looked up by absolute name.

use std::ops::Deref;
use std::path::Path;

use mi::{Diagnostic, Origin, SourceMap, Span};

use crate::ast::{Decl, ImportKind, ImportNames, Module, ModulePath};
use crate::error::Error;
use crate::module_table::{absolute, LoadedModule, ModuleTable};
use crate::parser::parse_module;
use crate::search_path::MdlSearchPath;
use crate::std_modules::{std_module, PRELUDE};
use crate::symbols::{declared, Symbol, SymbolKind};

/// Largest module file mira reads, in bytes.
const MAX_MODULE_SIZE: u64 = 64 << 20;

/// Every module loaded so far, with the sources they were read from.
#[derive(Debug)]
pub struct ModuleSet {
    search: MdlSearchPath,
    sources: SourceMap,
    table: ModuleTable,
}

/// A set is read like the table of its loaded modules (`set.material("::m::matte")`).
impl Deref for ModuleSet {
    type Target = ModuleTable;

    fn deref(&self) -> &ModuleTable {
        &self.table
    }
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

impl ModuleSet {
    /// An empty set that finds modules on `search` (and the built-in ones).
    pub fn new(search: MdlSearchPath) -> ModuleSet {
        ModuleSet { search, sources: SourceMap::new(), table: ModuleTable::default() }
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
            Ok(i) => Ok(&self.table.at(i).module),
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
        if let Some(&i) = self.table.position(&name) {
            return Ok(&self.table.at(i).module);
        }
        let bytes = read_module(path).map_err(Error::unlocated)?;
        let mut stack = Vec::new();
        match self.finish(&name, Origin::Disk(path.to_path_buf()), bytes, false, &mut stack) {
            Ok(i) => Ok(&self.table.at(i).module),
            Err(fail) => Err(self.error(fail)),
        }
    }

    /// Loads module `name` from `text` held in memory (its imports come from the search path).
    pub fn load_source(&mut self, name: &str, text: &str) -> Result<&Module, Error> {
        let name = absolute(name);
        if self.table.contains(&name) || std_module(&name).is_some() {
            return Err(Error::unlocated(format!("module `{name}` is already loaded")));
        }
        let file = format!("{}.mdl", name.trim_start_matches("::").replace("::", "/"));
        let mut stack = Vec::new();
        match self.finish(&name, Origin::Memory(file), text.as_bytes().to_vec(), false, &mut stack) {
            Ok(i) => Ok(&self.table.at(i).module),
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
        if let Some(&i) = self.table.position(name) {
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
        let diags = crate::sema::check(&mut module, &self.table);
        if !diags.is_empty() {
            return Err(Fail::Located(diags));
        }
        let (declared, mut exports) = declared(&module);
        for import in &module.imports {
            if let (true, ImportKind::Using { names, .. }, Some(target)) =
                (import.exported, &import.kind, &import.resolved)
            {
                let Some(from) = self.table.loaded(target).map(|m| &m.exports) else { continue };
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
        Ok(self.table.insert(name, LoadedModule { module, declared, exports }))
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
            if self.table.contains(&candidate)
                || std_module(&candidate).is_some()
                || self.search.find(&candidate).is_some()
            {
                return Ok(candidate);
            }
        }
        Ok(joined(&[]))
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
}
