//! `mdl_lang`: a front end for NVIDIA's Material Definition Language, MDL 1.x.
//!
//! MDL modules are text files (`a/b.mdl` holds module `::a::b`) that declare materials,
//! functions, structs, enums and constants, and import each other. This crate reads them:
//!
//! - [`lexer`] and [`parser`]: source text to a syntax tree ([`ast`]), every node with its
//!   span; errors are `file:line:col` with a caret, as `.mi` errors are ([`mi::Diagnostic`]).
//! - [`MdlSearchPath`]: the directories modules are looked up in (beside the scene, `-M DIR`,
//!   `MDL_PATHS`).
//! - [`ModuleSet`] / [`load_module`]: loads a module and its imports recursively (cycles and
//!   missing modules are errors at the import), with the standard modules (`::df`, `::base`,
//!   `::math`, `::tex`, `::state`, `::anno`, `::limits`, `::nvidia::core_definitions`) built in
//!   as declarations ([`std_modules`]); the set reads as the [`ModuleTable`] of the checked
//!   modules (lookups of materials, functions, structs, enums), which the semantic pass reads
//!   too.
//! - the semantic pass (run by the loader on every module): resolves names across imports,
//!   chooses overloads,
//!   types expressions where simple, checks defaults and arguments, expands material
//!   variants; the tree it leaves is what a material compiler evaluates, binding arguments
//!   with [`Function::bind_args`] / [`Function::instantiate`], and tells which
//!   sub-expressions depend on the shading point ([`HitDependence`]).
//!
//! What mira does not read yet (`cast<>`, quoted module names, …) is an error that
//! names the construct and its line, never a silent default.
//!
//! ```
//! let mut set = mdl_lang::ModuleSet::new(mdl_lang::MdlSearchPath::new());
//! set.load_source("::m", "mdl 1.7; import ::df::*;
//!     export material matte(color tint = color(0.8)) =
//!         material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(tint: tint)));")
//!     .unwrap();
//! let matte = set.material("::m::matte").unwrap();
//! assert_eq!(matte.params[0].name, "tint");
//! ```

pub mod ast;
mod error;
mod frequency;
pub mod lexer;
mod module_set;
mod module_table;
pub mod parser;
mod search_path;
mod sema;
pub mod std_modules;
mod subst;
pub mod symbols;

pub use ast::{Body, Decl, Expr, ExprKind, Function, Module, Param, QualName, Resolution, Type};
pub use error::{Error, Problem};
pub use frequency::HitDependence;
pub use module_set::{load_module, split_mi_name, ModuleSet};
pub use module_table::{LoadedModule, ModuleTable};
pub use search_path::MdlSearchPath;
pub use subst::BindError;

/// A material definition (a [`Function`] whose return type is `material`).
pub type Material = Function;
