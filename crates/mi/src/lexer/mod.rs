//! The lexer: bytes of one file to tokens, plus fast paths for bulk geometry data.
//!
//! Lexical rules (mental ray manual, "Scene description language"): `#` starts a comment
//! that runs to the end of the line (`#:` pragma comments included); strings are double
//! quoted with backslash escapes; unquoted names are letters, digits, `_`, `.` and `:` not
//! starting with a digit; numbers are integers or floats in every form exporters write
//! (`1.`, `.5`, `-2.5e-05`); backquotes enclose raw binary bytes. Lines starting with `$`
//! are preprocessor directives, which the lexer recognises and [`crate::preprocess`] acts on.

use crate::text::SourceText;

use crate::diag::Diagnostic;
use crate::source::{FileId, Span};

mod bulk;
mod directive;
mod number;
mod parallel;
mod swar;
mod token;

pub use directive::directive_args;
#[cfg(test)]
pub(crate) use parallel::with_limits;
pub use parallel::PARALLEL_FROM_BYTES;
pub use token::{Directive, SkipEnd, Tok, Token};

/// The lexer for one source file.
#[derive(Clone, Debug)]
pub struct Lexer {
    /// The file being read.
    pub file: FileId,
    src: SourceText,
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

impl Lexer {
    /// A lexer at the start of `src` (after a UTF-8 byte-order mark, if there is one).
    pub fn new(file: FileId, src: impl Into<SourceText>) -> Lexer {
        let src = src.into();
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
}

#[cfg(test)]
mod tests {
    use super::number::parse_f32_simple;
    use super::*;

    fn lex_all(text: &str) -> Vec<Tok> {
        let mut lx = Lexer::new(FileId(0), std::sync::Arc::<[u8]>::from(text.as_bytes()));
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
        let mut lx = Lexer::new(FileId(0), std::sync::Arc::<[u8]>::from(text.as_bytes()));
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
        let mut lx = Lexer::new(FileId(0), std::sync::Arc::<[u8]>::from(&b"$include <base.mi>\n$ifdef \"x\"\n"[..]));
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
        let mut lx = Lexer::new(FileId(0), std::sync::Arc::<[u8]>::from(&text[..]));
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
        let mut lx = Lexer::new(FileId(0), std::sync::Arc::<[u8]>::from(&b"1. -2.5e-1 .5 # c\n 7 v 3 4"[..]));
        let mut v = Vec::new();
        while let Some(x) = lx.try_f32().unwrap() {
            v.push(x);
        }
        assert_eq!(v, vec![1.0, -0.25, 0.5, 7.0]);
        assert_eq!(lx.next_token().unwrap().tok, Tok::Name);
        assert_eq!(lx.try_u32().unwrap(), Some(3));
        let mut lx = Lexer::new(FileId(0), std::sync::Arc::<[u8]>::from(&b"`a`b` x"[..]));
        let span = lx.binary_exact(3).unwrap();
        assert_eq!((span.lo, span.hi), (1, 4));
        let mut lx = Lexer::new(FileId(0), std::sync::Arc::<[u8]>::from(&b"`ab"[..]));
        assert!(lx.binary_exact(8).unwrap_err().message.contains("cut short"));
    }
}
