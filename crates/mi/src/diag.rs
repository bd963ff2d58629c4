//! Diagnostics: errors and warnings that point at a place in a `.mi` file.
//!
//! Rendered as `file:line:col: error: message`, then the source line and a caret under the
//! column, the form compilers use and editors understand.

use std::fmt::Write as _;

use crate::source::{SourceMap, Span};

/// How bad a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// Something mira read but will ignore or interpret in a documented way.
    Warning,
    /// The file is not valid; the element it concerns is not usable.
    Error,
}

/// One message about a place in the source.
#[derive(Clone, Debug)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// What the message is about.
    pub span: Span,
    /// One line, lower case, no trailing period.
    pub message: String,
    /// Further lines, each optionally pointing somewhere else (e.g. "included from here").
    pub notes: Vec<(Option<Span>, String)>,
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic { severity: Severity::Error, span, message: message.into(), notes: Vec::new() }
    }

    /// A warning at `span`.
    pub fn warning(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic { severity: Severity::Warning, span, message: message.into(), notes: Vec::new() }
    }

    /// Adds a note line.
    pub fn with_note(mut self, span: Option<Span>, note: impl Into<String>) -> Diagnostic {
        self.notes.push((span, note.into()));
        self
    }

    /// Whether this is an error.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// The `file:line:col: error: message` header, the source line and a caret, and notes.
    pub fn render(&self, sources: &SourceMap) -> String {
        let mut out = String::new();
        let kind = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let _ = writeln!(out, "{}: {}: {}", sources.location(self.span), kind, self.message);
        excerpt(&mut out, sources, self.span);
        for (span, note) in &self.notes {
            match span {
                Some(span) => {
                    let _ = writeln!(out, "{}: note: {}", sources.location(*span), note);
                    excerpt(&mut out, sources, *span);
                }
                None => {
                    let _ = writeln!(out, "  note: {note}");
                }
            }
        }
        out
    }
}

/// Writes the source line of `span` and a caret line under its start (and its extent on the line).
fn excerpt(out: &mut String, sources: &SourceMap, span: Span) {
    let file = sources.file(span.file);
    let (line, col) = file.line_col(span.lo);
    let text = file.line_text(line);
    if text.len() > 400 {
        return; // a binary block or a minified line: the location says enough
    }
    let printable: String = text.chars().map(|c| if c.is_control() && c != '\t' { ' ' } else { c }).collect();
    let _ = writeln!(out, "    {printable}");
    let indent: String = printable.chars().take(col as usize - 1).map(|c| if c == '\t' { '\t' } else { ' ' }).collect();
    let (end_line, end_col) = file.line_col(span.hi.max(span.lo));
    let width = if end_line == line && end_col > col { (end_col - col) as usize } else { 1 };
    let _ = writeln!(
        out,
        "    {indent}{}",
        "^".repeat(width.min(printable.chars().count().saturating_sub(col as usize - 1)).max(1))
    );
}

/// Diagnostics collected while reading a scene.
#[derive(Clone, Debug, Default)]
pub struct Diagnostics {
    /// In the order they were found.
    pub list: Vec<Diagnostic>,
}

impl Diagnostics {
    /// Whether any error was reported.
    pub fn has_errors(&self) -> bool {
        self.list.iter().any(Diagnostic::is_error)
    }

    /// Number of errors.
    pub fn error_count(&self) -> usize {
        self.list.iter().filter(|d| d.is_error()).count()
    }

    /// Number of warnings.
    pub fn warning_count(&self) -> usize {
        self.list.len() - self.error_count()
    }

    /// Adds one.
    pub fn push(&mut self, d: Diagnostic) {
        self.list.push(d);
    }

    /// All of them rendered, one after another.
    pub fn render(&self, sources: &SourceMap) -> String {
        self.list.iter().map(|d| d.render(sources)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::Origin;

    #[test]
    fn renders_location_line_and_caret() {
        let mut map = SourceMap::new();
        let id = map.add(Origin::Memory("scene.mi".into()), b"options \"o\"\n  samples x 2\nend options\n".to_vec());
        let d = Diagnostic::error(Span::new(id, 22, 23), "expected an integer");
        assert_eq!(d.render(&map), "scene.mi:2:11: error: expected an integer\n      samples x 2\n              ^\n");
    }
}
