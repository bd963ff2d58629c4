//! `mi`: the mental ray and Iray `.mi` scene language.
//!
//! Reads `.mi` text into a syntax tree ([`ast`]) that keeps every node's source position,
//! following `$include`s (with mira's built-in standard declaration files standing in for
//! missing `base.mi`, `architectural.mi`, …) and conditionals; prints trees back as `.mi`
//! text ([`print()`]); and reports problems as [`Diagnostic`]s that point at file, line and
//! column. Nothing here gives the scene a meaning: that is the `scene` crate's job.
//!
//! ```
//! let parsed = mi::parse_str("scene.mi", "options \"opt\" samples 0 2 end options");
//! assert!(!parsed.diagnostics.has_errors());
//! assert_eq!(parsed.items.len(), 1);
//! ```

pub mod ast;
pub mod diag;
pub mod grammar;
pub mod lexer;
#[cfg(test)]
mod parallel_trees;
mod parser;
pub mod preprocess;
mod printer;
#[cfg(unix)]
mod sigbus;
pub mod source;
pub mod stats;
pub mod stdlib;
pub mod text;

use std::path::Path;

pub use ast::Item;
pub use diag::{Diagnostic, Diagnostics, Severity};
pub use preprocess::{IncludeRecord, IncludeTarget, ReadOptions};
pub use printer::print;
pub use source::{FileId, Origin, SourceMap, Span};

/// A parsed scene file: its items, the sources they point into, and what went wrong.
#[derive(Debug)]
pub struct Parsed {
    /// The top-level items, `$include`d files nested as [`ast::Item::Include`].
    pub items: Vec<Item>,
    /// Every file read.
    pub sources: SourceMap,
    /// Errors and warnings, in the order found.
    pub diagnostics: Diagnostics,
    /// Every `$include` met, in order.
    pub includes: Vec<IncludeRecord>,
}

/// Failure to read the main file at all (errors inside it are [`Diagnostics`]).
#[derive(Debug, thiserror::Error)]
#[error("cannot read {path}: {message}")]
pub struct ReadError {
    /// The file.
    pub path: String,
    /// Why.
    pub message: String,
}

/// Parses a `.mi` file from disk.
pub fn parse_file(path: &Path, options: &ReadOptions) -> Result<Parsed, ReadError> {
    let bytes = source::read_source(path).map_err(|message| ReadError { path: path.display().to_string(), message })?;
    Ok(parse_source(Origin::Disk(path.to_path_buf()), bytes, options))
}

/// Parses `.mi` text held in memory; `name` is used in messages.
pub fn parse_str(name: &str, text: &str) -> Parsed {
    parse_source(Origin::Memory(name.to_string()), text.as_bytes().to_vec(), &ReadOptions::default())
}

/// Parses `.mi` bytes from any origin (a `Vec<u8>`, an `Arc<[u8]>` or a mapped
/// [`text::SourceText`] the parser shares without copying). A mapped file that changed on
/// disk while it was read gives an error (its text may be a mix of old and new).
pub fn parse_source(origin: Origin, bytes: impl Into<text::SourceText>, options: &ReadOptions) -> Parsed {
    let bytes: text::SourceText = bytes.into();
    let mut sources = SourceMap::new();
    let too_big = bytes.len() as u64 > source::MAX_FILE_SIZE;
    let root = sources.add(origin, if too_big { text::SourceText::from(Vec::new()) } else { bytes });
    let stream = preprocess::TokenStream::new(sources, root, options.clone());
    let mut parser = parser::Parser::new(stream, options.max_errors);
    let items = parser.items(parser::Until::Eof);
    let mut diagnostics = Diagnostics::default();
    if too_big {
        diagnostics.push(Diagnostic::error(Span::default(), "file is larger than 4 GiB"));
    }
    // Preprocessor and parser diagnostics, in source order of discovery.
    let mut all = parser.ts.diags;
    all.extend(parser.diags);
    all.sort_by_key(|d| (d.span.file, d.span.lo));
    diagnostics.list.extend(all);
    if diagnostics.error_count() >= options.max_errors {
        let last = diagnostics.list.last().map_or(Span::default(), |d| d.span);
        diagnostics.push(Diagnostic::error(last, "too many errors; stopped reading"));
    }
    for name in parser.ts.sources.changed_on_disk() {
        diagnostics.push(Diagnostic::error(
            Span::default(),
            format!("{name} changed on disk while it was being read; read it again once it is written"),
        ));
    }
    Parsed { items, sources: parser.ts.sources, diagnostics, includes: parser.ts.includes }
}
