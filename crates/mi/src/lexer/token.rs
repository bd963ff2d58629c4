//! Tokens: what the lexer produces (kinds, numbers' values, directives, spans).

use crate::source::Span;

/// What a token is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tok {
    /// An unquoted name or keyword; its text is the source bytes of the span.
    Name,
    /// A quoted string; the span covers the quotes. `escaped` says whether it holds a backslash.
    Str {
        /// Whether the string contains backslash escapes that must be decoded.
        escaped: bool,
    },
    /// An integer literal.
    Int(i64),
    /// A floating-point literal (or an integer too large for `i64`).
    Float(f64),
    /// A backquoted binary block; the span covers the backquotes. Its length is set by the
    /// grammar (12 bytes for a vector, 4 per word in trilist and hair blocks), so the parser
    /// may re-read it with [`Lexer::binary_exact`](super::Lexer::binary_exact) when the payload holds a backquote.
    Binary,
    /// A single-quoted hexadecimal byte string (`'0a1bff'`) of `data` elements and inline
    /// texture pixels; the span covers the quotes.
    ByteStr,
    /// `%` (percentages in `regular parametric 50% 50%` approximations).
    Percent,
    /// `(`
    LParen,
    /// `)`
    RParen,
    /// `[`
    LBracket,
    /// `]`
    RBracket,
    /// `{`
    LBrace,
    /// `}`
    RBrace,
    /// `,`
    Comma,
    /// `=`
    Equals,
    /// A `$` directive; the span covers its argument (if any).
    Directive(Directive),
    /// The body of a `$code … $end code` block; the span covers the text between the lines.
    CodeBlock,
    /// Start of an included file's tokens (index into the include table of the stream).
    IncludeBegin(u32),
    /// End of an included file's tokens.
    IncludeEnd,
    /// End of input.
    Eof,
}

/// A preprocessor directive recognised by the lexer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Directive {
    /// `$include "file"` (or `<file>` when `angle`).
    Include {
        /// Written with angle brackets: searched on the include path only.
        angle: bool,
    },
    /// `$ifdef var`
    IfDef,
    /// `$ifndef var`
    IfNDef,
    /// `$ifeq key value`
    IfEq,
    /// `$ifneq key value`
    IfNEq,
    /// `$elseifdef key`
    ElseIfDef,
    /// `$elseifeq key value`
    ElseIfEq,
    /// `$else`
    Else,
    /// `$endif`
    EndIf,
    /// `$lookup "{key}"`
    Lookup,
}

/// A token and where it is.
#[derive(Clone, Copy, Debug)]
pub struct Token {
    /// The kind (and value, for numbers).
    pub tok: Tok,
    /// Where it is.
    pub span: Span,
}

/// Where a conditional block being skipped ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SkipEnd {
    /// At a `$else`, `$elseifdef` or `$elseifeq` of the same level; the span covers the
    /// directive's arguments (empty for `$else`).
    Else(Directive, Span),
    /// At the matching `$endif`.
    EndIf,
}
