//! Errors of loading MDL modules, each located at `file:line:col` where it has a place.

use std::fmt;

use mi::{Diagnostic, SourceMap};

/// One problem found in an MDL module.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Problem {
    /// The file's name as shown in messages (a path, or `<builtin>/df.mdl`); empty when the
    /// problem has no place (a module asked for by name that is not on the search path).
    pub file: String,
    /// 1-based line (0 without a place).
    pub line: u32,
    /// 1-based column in characters (0 without a place).
    pub col: u32,
    /// The message: one line, lower case, no trailing period.
    pub message: String,
}

/// Loading a module failed: the problems found, and their rendering with source excerpts
/// (`file:line:col: error: message`, the line, a caret), the form `.mi` errors take.
#[derive(Clone, Debug)]
pub struct Error {
    /// The problems, in the order found.
    pub problems: Vec<Problem>,
    /// All of them rendered for a terminal.
    pub rendered: String,
}

impl Error {
    /// An error from diagnostics located in `sources`.
    pub fn from_diagnostics(diags: &[Diagnostic], sources: &SourceMap) -> Error {
        let mut problems = Vec::new();
        let mut rendered = String::new();
        for d in diags {
            let file = sources.file(d.span.file);
            let (line, col) = file.line_col(d.span.lo);
            problems.push(Problem { file: file.name(), line, col, message: d.message.clone() });
            rendered.push_str(&d.render(sources));
        }
        Error { problems, rendered }
    }

    /// An error with no place in any source.
    pub fn unlocated(message: impl Into<String>) -> Error {
        let message = message.into();
        Error {
            rendered: format!("error: {message}\n"),
            problems: vec![Problem { file: String::new(), line: 0, col: 0, message }],
        }
    }

    /// The first problem (there is always one).
    pub fn first(&self) -> &Problem {
        &self.problems[0]
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.rendered.trim_end())
    }
}

impl std::error::Error for Error {}
