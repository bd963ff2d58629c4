//! The typed syntax tree of one MDL module.
//!
//! A [`Module`] holds its version line, imports and declarations in source order. Materials
//! and functions keep their parameters with types and default expressions, and their bodies
//! as [`Expr`] / [`Stmt`] trees; the semantic pass fills in types and name
//! resolutions in place.

mod expr;
mod types;

use std::fmt;

use mi::{FileId, Span};

pub use expr::*;
pub use types::*;

/// A possibly qualified name: `x`, `df::specular_bsdf`, `::base::file_texture`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct QualName {
    /// Whether it starts with `::`.
    pub absolute: bool,
    /// The parts between `::` (at least one).
    pub parts: Vec<String>,
}

impl QualName {
    /// An unqualified name.
    pub fn simple(name: &str) -> QualName {
        QualName { absolute: false, parts: vec![name.to_string()] }
    }

    /// The last part (the name itself, without its module).
    pub fn last(&self) -> &str {
        self.parts.last().map_or("", String::as_str)
    }

    /// Whether it has a module qualifier.
    pub fn is_qualified(&self) -> bool {
        self.absolute || self.parts.len() > 1
    }

    /// The qualifier: every part but the last (`df` for `df::specular_bsdf`).
    pub fn qualifier(&self) -> &[String] {
        &self.parts[..self.parts.len().saturating_sub(1)]
    }
}

impl fmt::Display for QualName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.absolute {
            f.write_str("::")?;
        }
        f.write_str(&self.parts.join("::"))
    }
}

/// A parsed (and, after the semantic pass, checked) MDL module.
#[derive(Clone, Debug)]
pub struct Module {
    /// Absolute module name, `::pkg::module`.
    pub name: String,
    /// The source file it was read from.
    pub file: FileId,
    /// The `mdl X.Y;` version (major, minor) and where it was written.
    pub version: (u32, u32),
    /// Module annotations (`module [[ … ]];`).
    pub annotations: Vec<Annotation>,
    /// Import and `using` declarations, in order.
    pub imports: Vec<Import>,
    /// The declarations, in order.
    pub decls: Vec<Decl>,
    /// Whether this is one of mira's built-in standard modules (declarations without bodies
    /// are allowed there: they name what mira implements natively).
    pub builtin: bool,
}

impl Module {
    /// The material definitions, in order.
    pub fn materials(&self) -> impl Iterator<Item = &Function> {
        self.decls.iter().filter_map(|d| match d {
            Decl::Function(f) if f.is_material() => Some(f),
            _ => None,
        })
    }

    /// The function (non-material) definitions, in order.
    pub fn functions(&self) -> impl Iterator<Item = &Function> {
        self.decls.iter().filter_map(|d| match d {
            Decl::Function(f) if !f.is_material() => Some(f),
            _ => None,
        })
    }
}

/// The module part of an import: absolute (`::a::b`), relative to this module's package
/// (`.::b`, `..::b`) or weak-relative (`a::b`: the package first, then absolute).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ModulePath {
    /// Starts with `::`.
    pub absolute: bool,
    /// Number of leading `..` (parent package) steps; `.` counts as zero but sets `relative`.
    pub parents: u32,
    /// Written with a leading `.` or `..`.
    pub relative: bool,
    /// Module name parts after the prefix.
    pub parts: Vec<String>,
}

impl fmt::Display for ModulePath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.absolute {
            f.write_str("::")?;
        } else if self.relative {
            if self.parents == 0 {
                f.write_str(".::")?;
            }
            for _ in 0..self.parents {
                f.write_str("..::")?;
            }
        }
        f.write_str(&self.parts.join("::"))
    }
}

/// Which names an import brings.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ImportNames {
    /// `*`: every exported name.
    All,
    /// The listed names.
    Some(Vec<String>),
}

/// An `import`, `using … import` or `using alias = …` declaration.
#[derive(Clone, Debug)]
pub struct Import {
    /// What kind of import.
    pub kind: ImportKind,
    /// Written with `export` (re-exports the names; `using` only).
    pub exported: bool,
    /// Where the whole declaration was written.
    pub span: Span,
    /// The absolute name of the imported module, filled in by the loader.
    pub resolved: Option<String>,
}

/// The kinds of import declaration.
#[derive(Clone, Debug)]
pub enum ImportKind {
    /// `import ::m::name;` or `import ::m::*;`: names usable qualified (`m::name`).
    Import {
        /// The module.
        module: ModulePath,
        /// The names imported.
        names: ImportNames,
    },
    /// `using ::m import a, b;` or `using ::m import *;`: names usable unqualified.
    Using {
        /// The module.
        module: ModulePath,
        /// The names imported.
        names: ImportNames,
    },
    /// `using alias = ::m;`: `alias::x` names `::m::x`.
    Alias {
        /// The alias.
        alias: String,
        /// The module it stands for.
        module: ModulePath,
    },
}

impl ImportKind {
    /// The module it imports from.
    pub fn module(&self) -> &ModulePath {
        match self {
            ImportKind::Import { module, .. } | ImportKind::Using { module, .. } | ImportKind::Alias { module, .. } => {
                module
            }
        }
    }
}

/// A module-level declaration.
#[derive(Clone, Debug)]
pub enum Decl {
    /// A material or function definition.
    Function(Function),
    /// A struct type.
    Struct(StructDecl),
    /// An enum type.
    Enum(EnumDecl),
    /// A constant.
    Const(ConstDecl),
    /// A `typedef`.
    Typedef(TypedefDecl),
    /// An annotation declaration (`annotation name(params);`).
    Annotation(AnnotationDecl),
}

impl Decl {
    /// The declared name.
    pub fn name(&self) -> &str {
        match self {
            Decl::Function(f) => &f.name,
            Decl::Struct(s) => &s.name,
            Decl::Enum(e) => &e.name,
            Decl::Const(c) => &c.name,
            Decl::Typedef(t) => &t.name,
            Decl::Annotation(a) => &a.name,
        }
    }

    /// Whether it was declared with `export`.
    pub fn exported(&self) -> bool {
        match self {
            Decl::Function(f) => f.exported,
            Decl::Struct(s) => s.exported,
            Decl::Enum(e) => e.exported,
            Decl::Const(c) => c.exported,
            Decl::Typedef(t) => t.exported,
            Decl::Annotation(a) => a.exported,
        }
    }

    /// Where the name was written.
    pub fn span(&self) -> Span {
        match self {
            Decl::Function(f) => f.span,
            Decl::Struct(s) => s.span,
            Decl::Enum(e) => e.span,
            Decl::Const(c) => c.span,
            Decl::Typedef(t) => t.span,
            Decl::Annotation(a) => a.span,
        }
    }
}

/// A parameter of a material, function or annotation.
#[derive(Clone, Debug)]
pub struct Param {
    /// Its type.
    pub ty: TypeRef,
    /// Its name.
    pub name: String,
    /// The default value (may refer to earlier parameters).
    pub default: Option<Expr>,
    /// Annotations written after it.
    pub annotations: Vec<Annotation>,
    /// Where the name was written.
    pub span: Span,
}

/// The body of a material or function.
#[derive(Clone, Debug)]
pub enum Body {
    /// `= expression;` (every material; functions since MDL 1.?, accepted always).
    Expr(Expr),
    /// `{ statements }`.
    Block(Vec<Stmt>),
    /// No body (`;`): a built-in declaration that mira implements natively.
    Native,
}

/// A material variant `material v(*) = base(args);`: the base and the argument list.
#[derive(Clone, Debug)]
pub struct Variant {
    /// The base material as written.
    pub base: QualName,
    /// The base material's absolute module and name, after the semantic pass.
    pub resolved: Option<(String, String)>,
}

/// A material or function definition. A material is a function whose return type is
/// `material`; a variant's parameter list is its base's, with the defaults it sets.
#[derive(Clone, Debug)]
pub struct Function {
    /// Declared with `export`.
    pub exported: bool,
    /// Return type (`material` for materials).
    pub ret: TypeRef,
    /// The name.
    pub name: String,
    /// Parameters, in order.
    pub params: Vec<Param>,
    /// `uniform`/`varying` written after the parameter list (functions only).
    pub frequency: Frequency,
    /// Annotations of the definition.
    pub annotations: Vec<Annotation>,
    /// The body.
    pub body: Body,
    /// Set for `material v(*) = base(…)` variants (the body is then the call of the base).
    pub variant: Option<Variant>,
    /// Where the name was written.
    pub span: Span,
}

impl Function {
    /// Whether this defines a material.
    pub fn is_material(&self) -> bool {
        self.ret.ty == Type::Material
    }

    /// The parameter named `name` and its index.
    pub fn param(&self, name: &str) -> Option<(usize, &Param)> {
        self.params.iter().enumerate().find(|(_, p)| p.name == name)
    }

    /// The `anno::display_name` string, if annotated.
    pub fn display_name(&self) -> Option<&str> {
        self.annotations.iter().find(|a| a.name.last() == "display_name").and_then(Annotation::string_arg)
    }
}

/// A struct field.
#[derive(Clone, Debug)]
pub struct Field {
    /// Its type.
    pub ty: TypeRef,
    /// Its name.
    pub name: String,
    /// Its default value (used by the constructor when the argument is absent).
    pub default: Option<Expr>,
    /// Annotations.
    pub annotations: Vec<Annotation>,
    /// Where the name was written.
    pub span: Span,
}

/// `struct name { fields };`.
#[derive(Clone, Debug)]
pub struct StructDecl {
    /// Declared with `export`.
    pub exported: bool,
    /// The name.
    pub name: String,
    /// The fields, in order.
    pub fields: Vec<Field>,
    /// Annotations.
    pub annotations: Vec<Annotation>,
    /// Where the name was written.
    pub span: Span,
}

/// One value of an enum.
#[derive(Clone, Debug)]
pub struct EnumValue {
    /// Its name (in module scope).
    pub name: String,
    /// The value written after `=`, if any.
    pub init: Option<Expr>,
    /// The integer value (written, or one more than the previous).
    pub value: i64,
    /// Annotations.
    pub annotations: Vec<Annotation>,
    /// Where the name was written.
    pub span: Span,
}

/// `enum name { a = 0, b };`.
#[derive(Clone, Debug)]
pub struct EnumDecl {
    /// Declared with `export`.
    pub exported: bool,
    /// The name.
    pub name: String,
    /// The values, in order.
    pub values: Vec<EnumValue>,
    /// Annotations.
    pub annotations: Vec<Annotation>,
    /// Where the name was written.
    pub span: Span,
}

/// `const type name = value;`.
#[derive(Clone, Debug)]
pub struct ConstDecl {
    /// Declared with `export`.
    pub exported: bool,
    /// The type.
    pub ty: TypeRef,
    /// The name.
    pub name: String,
    /// The value.
    pub value: Expr,
    /// Annotations.
    pub annotations: Vec<Annotation>,
    /// Where the name was written.
    pub span: Span,
}

/// `typedef type name;`.
#[derive(Clone, Debug)]
pub struct TypedefDecl {
    /// Declared with `export`.
    pub exported: bool,
    /// The type it names.
    pub ty: TypeRef,
    /// The new name.
    pub name: String,
    /// Where the name was written.
    pub span: Span,
}

/// `annotation name(params);`.
#[derive(Clone, Debug)]
pub struct AnnotationDecl {
    /// Declared with `export`.
    pub exported: bool,
    /// The name.
    pub name: String,
    /// Its parameters.
    pub params: Vec<Param>,
    /// Where the name was written.
    pub span: Span,
}
