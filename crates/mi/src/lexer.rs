//! The lexer: bytes of one file to tokens, plus fast paths for bulk geometry data.
//!
//! Lexical rules (mental ray manual, "Scene description language"): `#` starts a comment
//! that runs to the end of the line (`#:` pragma comments included); strings are double
//! quoted with backslash escapes; unquoted names are letters, digits, `_`, `.` and `:` not
//! starting with a digit; numbers are integers or floats in every form exporters write
//! (`1.`, `.5`, `-2.5e-05`); backquotes enclose raw binary bytes. Lines starting with `$`
//! are preprocessor directives, which the lexer recognises and [`crate::preprocess`] acts on.

use std::sync::Arc;

use crate::diag::Diagnostic;
use crate::source::{FileId, Span};

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
    /// may re-read it with [`Lexer::binary_exact`] when the payload holds a backquote.
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

/// The lexer for one source file.
#[derive(Clone, Debug)]
pub struct Lexer {
    /// The file being read.
    pub file: FileId,
    src: Arc<[u8]>,
    /// Offset of the next unread byte.
    pub pos: usize,
}

fn is_name_start(b: u8) -> bool {
    b.is_ascii_alphabetic() || b == b'_' || b == b':'
}

fn is_name_char(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_' || b == b'.' || b == b':'
}

/// Whether a byte may directly follow a number or name.
fn is_delimiter(b: u8) -> bool {
    matches!(
        b,
        b' ' | b'\t'
            | b'\n'
            | b'\r'
            | 0x0c
            | b'('
            | b')'
            | b'['
            | b']'
            | b'{'
            | b'}'
            | b','
            | b'='
            | b'#'
            | b'"'
            | b'`'
            | b'\''
            | b'%'
    )
}

/// Decodes the body of a quoted string (without the quotes): `\"` and `\\` are the only
/// escapes (as the mental ray manual documents); any other backslash is kept with the
/// character after it, so Windows paths such as `"C:\textures\new"` survive. Bytes that
/// are not UTF-8 (Windows code-page names) are read as Latin-1, which keeps distinct names
/// distinct.
pub fn unescape(body: &[u8]) -> String {
    let mut out = Vec::with_capacity(body.len());
    let mut i = 0;
    while i < body.len() {
        let b = body[i];
        if b == b'\\' && matches!(body.get(i + 1), Some(b'"' | b'\\')) {
            out.push(body[i + 1]);
            i += 2;
        } else {
            out.push(b);
            i += 1;
        }
    }
    bytes_to_string(out)
}

/// Text of bytes: UTF-8 when valid, else Latin-1 (every byte one character).
pub fn bytes_to_string(bytes: Vec<u8>) -> String {
    match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => e.into_bytes().iter().map(|&b| b as char).collect(),
    }
}

/// Exact powers of ten as `f32` (all representable).
const POW10_F32: [f32; 11] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10];

/// Parses the common short decimal forms (`-12.5`, `0.136563`, `1e-5`) exactly: when the
/// decimal mantissa fits 24 bits and the power of ten is at most 10, one `f32` multiply or
/// divide of exact operands rounds correctly (Clinger's fast path). Returns `None` for
/// anything else, which the general parser then handles.
#[inline]
fn parse_f32_simple(s: &[u8]) -> Option<(f32, usize)> {
    let mut i = 0;
    let neg = match s.first() {
        Some(b'-') => {
            i = 1;
            true
        }
        Some(b'+') => {
            i = 1;
            false
        }
        _ => false,
    };
    let mut mantissa: u32 = 0;
    let mut digits = 0u32;
    let mut exp10: i32 = 0;
    while let Some(&d) = s.get(i) {
        if !d.is_ascii_digit() {
            break;
        }
        mantissa = mantissa.checked_mul(10)?.checked_add(u32::from(d - b'0'))?;
        digits += 1;
        i += 1;
    }
    if s.get(i) == Some(&b'.') {
        i += 1;
        while let Some(&d) = s.get(i) {
            if !d.is_ascii_digit() {
                break;
            }
            mantissa = mantissa.checked_mul(10)?.checked_add(u32::from(d - b'0'))?;
            exp10 -= 1;
            digits += 1;
            i += 1;
        }
    }
    if digits == 0 {
        return None;
    }
    if matches!(s.get(i), Some(b'e' | b'E')) {
        let mut j = i + 1;
        let eneg = match s.get(j) {
            Some(b'-') => {
                j += 1;
                true
            }
            Some(b'+') => {
                j += 1;
                false
            }
            _ => false,
        };
        let mut e: i32 = 0;
        let first = j;
        while let Some(&d) = s.get(j) {
            if !d.is_ascii_digit() || e > 1000 {
                break;
            }
            e = e * 10 + i32::from(d - b'0');
            j += 1;
        }
        if j == first {
            return None;
        }
        exp10 += if eneg { -e } else { e };
        i = j;
    }
    if mantissa > 1 << 24 || !(-10..=10).contains(&exp10) {
        return None;
    }
    let m = mantissa as f32;
    let v = if exp10 < 0 { m / POW10_F32[(-exp10) as usize] } else { m * POW10_F32[exp10 as usize] };
    Some((if neg { -v } else { v }, i))
}

/// The arguments of a directive whose span runs from its `$`: the text after the word.
pub fn directive_args(directive_text: &[u8]) -> &[u8] {
    let word_end =
        directive_text.iter().skip(1).position(|b| !b.is_ascii_alphabetic()).map_or(directive_text.len(), |i| i + 1);
    let rest = &directive_text[word_end..];
    // Drop a trailing comment.
    let mut in_string = false;
    for (i, &b) in rest.iter().enumerate() {
        match b {
            b'"' => in_string = !in_string,
            b'#' if !in_string => return rest[..i].trim_ascii(),
            _ => {}
        }
    }
    rest.trim_ascii()
}

/// Parses an integer literal's bytes (optional sign, decimal digits); `None` on overflow.
fn parse_int(s: &[u8]) -> Option<i64> {
    let (neg, digits) = match s.first() {
        Some(b'-') => (true, &s[1..]),
        Some(b'+') => (false, &s[1..]),
        _ => (false, s),
    };
    let mut v: i64 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        v = v.checked_mul(10)?.checked_add(i64::from(d - b'0'))?;
    }
    Some(if neg { -v } else { v })
}

impl Lexer {
    /// A lexer at the start of `src` (after a UTF-8 byte-order mark, if there is one).
    pub fn new(file: FileId, src: Arc<[u8]>) -> Lexer {
        let pos = if src.starts_with(&[0xef, 0xbb, 0xbf]) { 3 } else { 0 };
        Lexer { file, src, pos }
    }

    /// The whole source.
    pub fn src(&self) -> &[u8] {
        &self.src
    }

    fn span(&self, lo: usize, hi: usize) -> Span {
        Span::new(self.file, lo as u32, hi as u32)
    }

    fn err(&self, lo: usize, hi: usize, msg: impl Into<String>) -> Diagnostic {
        Diagnostic::error(self.span(lo, hi), msg)
    }

    /// Bytes left after the current position.
    pub fn remaining(&self) -> usize {
        self.src.len() - self.pos
    }

    /// Skips whitespace and comments.
    #[inline]
    pub fn skip_trivia(&mut self) {
        let src = &*self.src;
        let mut pos = self.pos;
        while let Some(&b) = src.get(pos) {
            match b {
                b' ' | b'\t' | b'\n' | b'\r' | 0x0c => pos += 1,
                b'#' => match memchr::memchr(b'\n', &src[pos..]) {
                    Some(i) => pos += i + 1,
                    None => pos = src.len(),
                },
                _ => break,
            }
        }
        self.pos = pos;
    }

    /// The next token.
    pub fn next_token(&mut self) -> Result<Token, Diagnostic> {
        self.skip_trivia();
        let start = self.pos;
        let Some(&b) = self.src.get(start) else {
            return Ok(Token { tok: Tok::Eof, span: self.span(start, start) });
        };
        let single = |lexer: &mut Lexer, tok| {
            lexer.pos += 1;
            Ok(Token { tok, span: lexer.span(start, start + 1) })
        };
        match b {
            b'(' => single(self, Tok::LParen),
            b')' => single(self, Tok::RParen),
            b'[' => single(self, Tok::LBracket),
            b']' => single(self, Tok::RBracket),
            b'{' => single(self, Tok::LBrace),
            b'}' => single(self, Tok::RBrace),
            b',' => single(self, Tok::Comma),
            b'=' => single(self, Tok::Equals),
            b'%' => single(self, Tok::Percent),
            b'\'' => {
                let Some(len) = memchr::memchr(b'\'', &self.src[start + 1..]) else {
                    return Err(self.err(start, start + 1, "byte string is not closed by a single quote"));
                };
                self.pos = start + 1 + len + 1;
                Ok(Token { tok: Tok::ByteStr, span: self.span(start, self.pos) })
            }
            b'"' => self.lex_string(start),
            b'`' => {
                let Some(len) = memchr::memchr(b'`', &self.src[start + 1..]) else {
                    return Err(self.err(start, start + 1, "binary block is not closed by a backquote"));
                };
                self.pos = start + 1 + len + 1;
                Ok(Token { tok: Tok::Binary, span: self.span(start, self.pos) })
            }
            b'$' => self.lex_directive(start),
            b'0'..=b'9' | b'.' | b'-' | b'+' => self.lex_number(start),
            b if is_name_start(b) => {
                let mut end = start + 1;
                while end < self.src.len() && is_name_char(self.src[end]) {
                    end += 1;
                }
                self.pos = end;
                if end < self.src.len() && !is_delimiter(self.src[end]) {
                    return Err(self.bad_char(end));
                }
                Ok(Token { tok: Tok::Name, span: self.span(start, end) })
            }
            _ => Err(self.bad_char(start)),
        }
    }

    fn bad_char(&self, at: usize) -> Diagnostic {
        let b = self.src[at];
        let what = if b.is_ascii_graphic() { format!("'{}'", b as char) } else { format!("byte 0x{b:02x}") };
        self.err(at, at + 1, format!("unexpected character {what}"))
    }

    fn lex_string(&mut self, start: usize) -> Result<Token, Diagnostic> {
        let src = &*self.src;
        let mut i = start + 1;
        let mut escaped = false;
        loop {
            match memchr::memchr2(b'"', b'\\', &src[i..]) {
                None => return Err(self.err(start, start + 1, "string is not closed by a double quote")),
                Some(k) => {
                    i += k;
                    if src[i] == b'\\' {
                        escaped = true;
                        i += 2;
                        if i > src.len() {
                            return Err(self.err(start, start + 1, "string is not closed by a double quote"));
                        }
                    } else {
                        break;
                    }
                }
            }
        }
        self.pos = i + 1;
        Ok(Token { tok: Tok::Str { escaped }, span: self.span(start, i + 1) })
    }

    /// Length of the number literal at `start`, or `None` if none is there.
    fn scan_number(&self, start: usize) -> Option<(usize, bool)> {
        let s = &self.src[start..];
        let mut i = 0;
        if matches!(s.first(), Some(b'-' | b'+')) {
            i = 1;
        }
        let digits = |mut i: usize| {
            while i < s.len() && s[i].is_ascii_digit() {
                i += 1;
            }
            i
        };
        let int_end = digits(i);
        let mut mantissa_digits = int_end - i;
        i = int_end;
        let mut float = false;
        if s.get(i) == Some(&b'.') {
            float = true;
            let frac_end = digits(i + 1);
            mantissa_digits += frac_end - i - 1;
            i = frac_end;
        }
        if mantissa_digits == 0 {
            return None;
        }
        if matches!(s.get(i), Some(b'e' | b'E')) {
            let mut j = i + 1;
            if matches!(s.get(j), Some(b'-' | b'+')) {
                j += 1;
            }
            let exp_end = digits(j);
            if exp_end > j {
                float = true;
                i = exp_end;
            }
        }
        Some((i, float))
    }

    fn lex_number(&mut self, start: usize) -> Result<Token, Diagnostic> {
        let Some((len, float)) = self.scan_number(start) else {
            return Err(self.bad_char(start));
        };
        let end = start + len;
        if end < self.src.len() && !is_delimiter(self.src[end]) {
            let mut stop = end;
            while stop < self.src.len() && !is_delimiter(self.src[stop]) {
                stop += 1;
            }
            let text = String::from_utf8_lossy(&self.src[start..stop]).into_owned();
            return Err(self.err(start, stop, format!("malformed number '{text}'")));
        }
        self.pos = end;
        let text = &self.src[start..end];
        let tok = match (float, if float { None } else { parse_int(text) }) {
            (false, Some(v)) => Tok::Int(v),
            _ => match fast_float2::parse::<f64, _>(text) {
                Ok(v) => Tok::Float(v),
                Err(_) => return Err(self.err(start, end, "malformed number")),
            },
        };
        Ok(Token { tok, span: self.span(start, end) })
    }

    fn lex_directive(&mut self, start: usize) -> Result<Token, Diagnostic> {
        let mut end = start + 1;
        while end < self.src.len() && self.src[end].is_ascii_alphabetic() {
            end += 1;
        }
        let word = &self.src[start + 1..end];
        self.pos = end;
        let directive = match word {
            b"include" => return self.lex_include_path(start),
            b"code" => return self.lex_code_block(start),
            b"ifdef" => Directive::IfDef,
            b"ifndef" => Directive::IfNDef,
            b"ifeq" => Directive::IfEq,
            b"ifneq" => Directive::IfNEq,
            b"elseifdef" => Directive::ElseIfDef,
            b"elseifeq" => Directive::ElseIfEq,
            b"else" => Directive::Else,
            b"endif" => Directive::EndIf,
            b"lookup" => Directive::Lookup,
            _ => {
                let w = String::from_utf8_lossy(word);
                return Err(self.err(start, end, format!("unknown directive '${w}'")));
            }
        };
        // The arguments: the rest of the line up to a comment, trimmed.
        let line_end = memchr::memchr(b'\n', &self.src[end..]).map_or(self.src.len(), |i| end + i);
        let mut arg_end = line_end;
        let mut in_string = false;
        for (i, &b) in self.src[end..line_end].iter().enumerate() {
            match b {
                b'"' => in_string = !in_string,
                b'#' if !in_string => {
                    arg_end = end + i;
                    break;
                }
                _ => {}
            }
        }
        let args = &self.src[end..arg_end];
        let lo = end + (args.len() - args.trim_ascii_start().len());
        let hi = (arg_end - (args.len() - args.trim_ascii_end().len())).max(lo);
        self.pos = line_end;
        let needs_args = !matches!(directive, Directive::Else | Directive::EndIf);
        if needs_args && lo == hi {
            return Err(self.err(start, end, format!("'${}' needs a name", String::from_utf8_lossy(word))));
        }
        // The span runs from `$` to the end of the arguments; see [`directive_args`].
        Ok(Token { tok: Tok::Directive(directive), span: self.span(start, hi.max(end)) })
    }

    /// Skips spaces and tabs (not line breaks).
    fn skip_blanks(&mut self) {
        while matches!(self.src.get(self.pos), Some(b' ' | b'\t')) {
            self.pos += 1;
        }
    }

    fn lex_include_path(&mut self, start: usize) -> Result<Token, Diagnostic> {
        self.skip_blanks();
        let p = self.pos;
        let (close, angle) = match self.src.get(p) {
            Some(b'"') => (b'"', false),
            Some(b'<') => (b'>', true),
            _ => return Err(self.err(start, p, "'$include' needs a file name in \"quotes\" or <angle brackets>")),
        };
        let line_end = memchr::memchr(b'\n', &self.src[p + 1..]).map_or(self.src.len(), |i| p + 1 + i);
        let Some(len) = memchr::memchr(close, &self.src[p + 1..line_end]) else {
            return Err(self.err(p, p + 1, "include file name is not closed on its line"));
        };
        self.pos = p + 1 + len + 1;
        Ok(Token { tok: Tok::Directive(Directive::Include { angle }), span: self.span(p + 1, p + 1 + len) })
    }

    /// `$code ["name"]` then raw lines up to a line starting with `$end code`.
    fn lex_code_block(&mut self, start: usize) -> Result<Token, Diagnostic> {
        let body_start = memchr::memchr(b'\n', &self.src[self.pos..]).map_or(self.src.len(), |i| self.pos + i + 1);
        let mut line = body_start;
        while line < self.src.len() {
            let next = memchr::memchr(b'\n', &self.src[line..]).map_or(self.src.len(), |i| line + i + 1);
            let text = self.src[line..next].trim_ascii_start();
            if let Some(rest) = text.strip_prefix(b"$end") {
                if rest.trim_ascii_start().starts_with(b"code") {
                    self.pos = next;
                    return Ok(Token { tok: Tok::CodeBlock, span: self.span(body_start, line) });
                }
            }
            line = next;
        }
        Err(self.err(start, start + 5, "'$code' block has no '$end code'"))
    }

    /// Skips the lines of a conditional branch that is not taken, up to the `$else`,
    /// `$elseifdef`, `$elseifeq` or `$endif` that belongs to it (nested conditionals are
    /// skipped whole). With `stop_at_else` false, the other branches are skipped too, up to
    /// the `$endif`. Returns `None` when the file ends first.
    pub fn skip_conditional(&mut self, stop_at_else: bool) -> Option<SkipEnd> {
        let mut depth = 0u32;
        let mut line = self.pos;
        while line < self.src.len() {
            let next = memchr::memchr(b'\n', &self.src[line..]).map_or(self.src.len(), |i| line + i + 1);
            let raw = &self.src[line..next];
            let text = raw.trim_ascii_start();
            if text.first() == Some(&b'$') {
                let word_len = text[1..].iter().position(|b| !b.is_ascii_alphabetic()).map_or(text.len() - 1, |i| i);
                let word = &text[1..1 + word_len];
                // The span runs from `$` to the end of the line, like a directive token's.
                let dollar = line + (raw.len() - text.len());
                let args_span = self.span(dollar, dollar + text.trim_ascii_end().len());
                match word {
                    b"ifdef" | b"ifndef" | b"ifeq" | b"ifneq" => depth += 1,
                    b"endif" if depth == 0 => {
                        self.pos = next;
                        return Some(SkipEnd::EndIf);
                    }
                    b"endif" => depth -= 1,
                    b"else" | b"elseifdef" | b"elseifeq" if depth == 0 && stop_at_else => {
                        self.pos = next;
                        let d = match word {
                            b"else" => Directive::Else,
                            b"elseifdef" => Directive::ElseIfDef,
                            _ => Directive::ElseIfEq,
                        };
                        return Some(SkipEnd::Else(d, args_span));
                    }
                    _ => {}
                }
            }
            line = next;
        }
        self.pos = self.src.len();
        None
    }

    // ----- fast paths for bulk data -----

    /// Reads one number as `f32` if one is next (after whitespace and comments).
    #[inline]
    pub fn try_f32(&mut self) -> Result<Option<f32>, Diagnostic> {
        self.skip_trivia();
        let start = self.pos;
        let src = &*self.src;
        match src.get(start) {
            Some(b'0'..=b'9' | b'.') => {}
            Some(b'-' | b'+') if matches!(src.get(start + 1), Some(b'0'..=b'9' | b'.')) => {}
            _ => return Ok(None),
        }
        if let Some((v, len)) = parse_f32_simple(&src[start..]) {
            if start + len == src.len() || is_delimiter(src[start + len]) {
                self.pos = start + len;
                return Ok(Some(v));
            }
        }
        match fast_float2::parse_partial::<f32, _>(&src[start..]) {
            Ok((v, len)) if start + len == src.len() || is_delimiter(src[start + len]) => {
                self.pos = start + len;
                Ok(Some(v))
            }
            _ => {
                // Let the general path produce the right message.
                self.lex_number(start).map(|t| match t.tok {
                    Tok::Int(i) => Some(i as f32),
                    Tok::Float(f) => Some(f as f32),
                    _ => None,
                })
            }
        }
    }

    /// Reads one non-negative integer if one is next (after whitespace and comments).
    #[inline]
    pub fn try_u32(&mut self) -> Result<Option<u32>, Diagnostic> {
        self.skip_trivia();
        let start = self.pos;
        let src = &*self.src;
        let mut i = start;
        let mut v: u64 = 0;
        while let Some(&d) = src.get(i) {
            if !d.is_ascii_digit() {
                break;
            }
            v = v * 10 + u64::from(d - b'0');
            if v > u64::from(u32::MAX) {
                return Err(self.err(start, i + 1, "index is too large"));
            }
            i += 1;
        }
        if i == start {
            return match src.get(start) {
                Some(b'-' | b'+' | b'.') => Err(self.err(start, start + 1, "expected a non-negative integer")),
                _ => Ok(None),
            };
        }
        if i < src.len() && !is_delimiter(src[i]) {
            return Err(self.err(start, i + 1, "expected a non-negative integer"));
        }
        self.pos = i;
        Ok(Some(v as u32))
    }

    /// The unquoted word next (after whitespace and comments), without consuming it.
    #[inline]
    pub fn peek_word(&mut self) -> Option<&[u8]> {
        self.skip_trivia();
        let src = &*self.src;
        let start = self.pos;
        if !src.get(start).is_some_and(|&b| is_name_start(b)) {
            return None;
        }
        let mut end = start + 1;
        while end < src.len() && is_name_char(src[end]) {
            end += 1;
        }
        Some(&src[start..end])
    }

    /// Consumes `len` bytes (a word just returned by [`Lexer::peek_word`]).
    #[inline]
    pub fn skip_bytes(&mut self, len: usize) {
        self.pos += len;
    }

    /// Whether the next significant byte is `b` (does not consume it).
    #[inline]
    pub fn peek_byte(&mut self) -> Option<u8> {
        self.skip_trivia();
        self.src.get(self.pos).copied()
    }

    /// Reads a backquoted block of exactly `len` payload bytes (the payload may contain
    /// backquotes). The opening backquote must be next.
    pub fn binary_exact(&mut self, len: usize) -> Result<Span, Diagnostic> {
        self.skip_trivia();
        let start = self.pos;
        if self.src.get(start) != Some(&b'`') {
            return Err(self.err(start, start + 1, "expected a backquoted binary block"));
        }
        let close = start + 1 + len;
        if close >= self.src.len() {
            return Err(self.err(
                start,
                start + 1,
                format!("binary block is cut short: {} bytes expected, the file ends first", len),
            ));
        }
        if self.src[close] != b'`' {
            let actual = memchr::memchr(b'`', &self.src[start + 1..]).map(|i| i.to_string());
            return Err(self.err(
                start,
                start + 1,
                format!(
                    "binary block should hold {} bytes but {}",
                    len,
                    actual.map_or("is not closed".to_string(), |n| format!("its closing backquote comes after {n}"))
                ),
            ));
        }
        self.pos = close + 1;
        Ok(self.span(start + 1, close))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lex_all(text: &str) -> Vec<Tok> {
        let mut lx = Lexer::new(FileId(0), Arc::from(text.as_bytes()));
        let mut out = Vec::new();
        loop {
            let t = lx.next_token().expect("lexes");
            if t.tok == Tok::Eof {
                return out;
            }
            out.push(t.tok);
        }
    }

    fn lex_err(text: &str) -> Diagnostic {
        let mut lx = Lexer::new(FileId(0), Arc::from(text.as_bytes()));
        loop {
            match lx.next_token() {
                Err(e) => return e,
                Ok(t) if t.tok == Tok::Eof => panic!("no error in {text:?}"),
                Ok(_) => {}
            }
        }
    }

    #[test]
    fn numbers_in_every_exporter_form() {
        assert_eq!(
            lex_all("1 -2 1. .5 -2.5e-05 +3 1e3 -.25 6.02E+23"),
            vec![
                Tok::Int(1),
                Tok::Int(-2),
                Tok::Float(1.0),
                Tok::Float(0.5),
                Tok::Float(-2.5e-5),
                Tok::Int(3),
                Tok::Float(1000.0),
                Tok::Float(-0.25),
                Tok::Float(6.02e23)
            ]
        );
    }

    #[test]
    fn huge_integer_becomes_float() {
        assert_eq!(lex_all("99999999999999999999"), vec![Tok::Float(1e20)]);
    }

    #[test]
    fn names_strings_punctuation_and_comments() {
        let toks = lex_all("options \"o\" # comment\n#: pragma\n(a, b) [ ] { } = `xyz` '0aff' 50%");
        assert_eq!(
            toks,
            vec![
                Tok::Name,
                Tok::Str { escaped: false },
                Tok::LParen,
                Tok::Name,
                Tok::Comma,
                Tok::Name,
                Tok::RParen,
                Tok::LBracket,
                Tok::RBracket,
                Tok::LBrace,
                Tok::RBrace,
                Tok::Equals,
                Tok::Binary,
                Tok::ByteStr,
                Tok::Int(50),
                Tok::Percent
            ]
        );
    }

    #[test]
    fn string_escapes() {
        assert_eq!(lex_all(r#""a\"b""#), vec![Tok::Str { escaped: true }]);
        assert_eq!(unescape(br#"a\"b\\c"#), "a\"b\\c");
        assert_eq!(unescape(br#"C:\textures\new\x.map"#), r"C:\textures\new\x.map");
        assert_eq!(unescape(b"Mat\xe9riau"), "Mat\u{e9}riau");
    }

    #[test]
    fn malformed_input_gives_positioned_errors() {
        let e = lex_err("samples 1x2");
        assert_eq!((e.span.lo, e.span.hi), (8, 11));
        assert!(e.message.contains("malformed number"), "{}", e.message);
        let e = lex_err("x \"open");
        assert_eq!(e.span.lo, 2);
        let e = lex_err("a ` binary");
        assert_eq!(e.span.lo, 2);
        let e = lex_err("a @");
        assert!(e.message.contains("'@'"));
        let e = lex_err("$frobnicate");
        assert!(e.message.contains("unknown directive"));
        let e = lex_err("- 1");
        assert_eq!(e.span.lo, 0);
    }

    #[test]
    fn directives() {
        let mut lx = Lexer::new(FileId(0), Arc::from(&b"$include <base.mi>\n$ifdef \"x\"\n"[..]));
        let t = lx.next_token().unwrap();
        assert_eq!(t.tok, Tok::Directive(Directive::Include { angle: true }));
        assert_eq!(&lx.src()[t.span.lo as usize..t.span.hi as usize], b"base.mi");
        let t = lx.next_token().unwrap();
        assert_eq!(t.tok, Tok::Directive(Directive::IfDef));
        assert_eq!(directive_args(&lx.src()[t.span.lo as usize..t.span.hi as usize]), b"\"x\"");
    }

    #[test]
    fn code_block_is_skipped_raw() {
        let toks = lex_all("$code\n int x = \"; # `\n$end code\nlink \"base.so\"");
        assert_eq!(toks, vec![Tok::CodeBlock, Tok::Name, Tok::Str { escaped: false }]);
    }

    #[test]
    fn conditional_skipping_handles_nesting() {
        let text = b"a\n$ifdef y\n$else\n$endif\n$else\nb\n$endif\nc";
        let mut lx = Lexer::new(FileId(0), Arc::from(&text[..]));
        lx.pos = 2;
        assert!(matches!(lx.skip_conditional(true), Some(SkipEnd::Else(Directive::Else, _))));
        assert_eq!(lx.next_token().unwrap().span.lo, 30); // `b`
    }

    #[test]
    fn simple_float_path_agrees_with_the_general_parser() {
        let samples = [
            "0",
            "1.",
            ".5",
            "-0.136563",
            "549.6",
            "1e-5",
            "-2.5e-05",
            "16777216",
            "0.1",
            "3.4028235e10",
            "7e-10",
            "123456.7",
            "0.000001",
            "9.999999",
            "-0",
            "+4.25",
        ];
        for s in samples {
            let general: f32 = fast_float2::parse(s).unwrap();
            if let Some((v, len)) = parse_f32_simple(s.as_bytes()) {
                assert_eq!(len, s.len(), "{s}");
                assert_eq!(v.to_bits(), general.to_bits(), "{s}");
            }
        }
        // A systematic sweep of short decimals.
        for m in (0..2_000_000u32).step_by(7) {
            for e in [-7, -3, 0, 2] {
                let s = format!("{m}e{e}");
                let general: f32 = fast_float2::parse(&s).unwrap();
                let (v, _) = parse_f32_simple(s.as_bytes()).unwrap();
                assert_eq!(v.to_bits(), general.to_bits(), "{s}");
            }
        }
    }

    #[test]
    fn fast_paths_read_numbers_and_binary() {
        let mut lx = Lexer::new(FileId(0), Arc::from(&b"1. -2.5e-1 .5 # c\n 7 v 3 4"[..]));
        let mut v = Vec::new();
        while let Some(x) = lx.try_f32().unwrap() {
            v.push(x);
        }
        assert_eq!(v, vec![1.0, -0.25, 0.5, 7.0]);
        assert_eq!(lx.next_token().unwrap().tok, Tok::Name);
        assert_eq!(lx.try_u32().unwrap(), Some(3));
        let mut lx = Lexer::new(FileId(0), Arc::from(&b"`a`b` x"[..]));
        let span = lx.binary_exact(3).unwrap();
        assert_eq!((span.lo, span.hi), (1, 4));
        let mut lx = Lexer::new(FileId(0), Arc::from(&b"`ab"[..]));
        assert!(lx.binary_exact(8).unwrap_err().message.contains("cut short"));
    }
}
