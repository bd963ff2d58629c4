//! Lexer: MDL source bytes to tokens, each with the byte span it came from.
//!
//! MDL's lexical rules follow C: identifiers, decimal/octal/hexadecimal integers, floating
//! literals with an optional `f`/`d` suffix, double-quoted strings with C escapes, `//` and
//! `/* */` comments. Keywords are returned as identifiers; the parser decides what they mean.
//! `[[` and `]]` are not tokens of their own (nested indexing `a[b[0]]` would break them): the
//! parser reads annotation brackets as two single brackets.

use mi::{Diagnostic, FileId, Span};

/// What a token is.
#[derive(Clone, Debug, PartialEq)]
pub enum TokenKind {
    /// An identifier or keyword.
    Ident(String),
    /// An integer literal (decimal, octal with a leading `0`, or hexadecimal `0x`).
    Int(i64),
    /// A floating-point literal; `double` is true for a `d`/`D` suffix.
    Float {
        /// The value.
        value: f64,
        /// Whether the literal was written as a `double` (`1.0d`).
        double: bool,
    },
    /// A string literal with escapes replaced.
    Str(String),
    /// Punctuation or an operator, as written (`::`, `(`, `+=`, `>>>`, …).
    Punct(&'static str),
    /// The end of the file.
    Eof,
}

/// One token and where it is.
#[derive(Clone, Debug)]
pub struct Token {
    /// What it is.
    pub kind: TokenKind,
    /// The bytes it covers.
    pub span: Span,
}

/// Punctuation, longest first so that the first match is the longest one.
const PUNCTS: &[&str] = &[
    ">>>=", ">>>", "<<=", ">>=", "::", "++", "--", "&&", "||", "==", "!=", "<=", ">=", "<<", ">>", "+=", "-=", "*=",
    "/=", "%=", "&=", "|=", "^=", "(", ")", "[", "]", "{", "}", ";", ",", ".", ":", "?", "=", "<", ">", "+", "-", "*",
    "/", "%", "!", "~", "&", "|", "^", "@",
];

/// Splits `bytes` (the text of file `file`) into tokens, ending with [`TokenKind::Eof`].
///
/// The first lexical error ends lexing: an unterminated string or comment, a character MDL
/// does not use, an integer too large for 64 bits.
pub fn tokenize(file: FileId, bytes: &[u8]) -> Result<Vec<Token>, Diagnostic> {
    let mut lexer = Lexer { file, bytes, pos: 0 };
    let mut tokens = Vec::new();
    loop {
        let token = lexer.next()?;
        let end = token.kind == TokenKind::Eof;
        tokens.push(token);
        if end {
            return Ok(tokens);
        }
    }
}

struct Lexer<'a> {
    file: FileId,
    bytes: &'a [u8],
    pos: usize,
}

impl Lexer<'_> {
    fn span(&self, lo: usize, hi: usize) -> Span {
        Span::new(self.file, lo as u32, hi as u32)
    }

    fn peek(&self, ahead: usize) -> u8 {
        self.bytes.get(self.pos + ahead).copied().unwrap_or(0)
    }

    fn skip_space_and_comments(&mut self) -> Result<(), Diagnostic> {
        loop {
            match (self.peek(0), self.peek(1)) {
                (b' ' | b'\t' | b'\r' | b'\n' | 0x0c | 0x0b, _) => self.pos += 1,
                (b'/', b'/') => {
                    while self.pos < self.bytes.len() && self.bytes[self.pos] != b'\n' {
                        self.pos += 1;
                    }
                }
                (b'/', b'*') => {
                    let start = self.pos;
                    self.pos += 2;
                    loop {
                        if self.pos + 1 >= self.bytes.len() {
                            return Err(Diagnostic::error(
                                self.span(start, start + 2),
                                "unterminated comment: `/*` without a closing `*/`",
                            ));
                        }
                        if self.bytes[self.pos] == b'*' && self.bytes[self.pos + 1] == b'/' {
                            self.pos += 2;
                            break;
                        }
                        self.pos += 1;
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    fn next(&mut self) -> Result<Token, Diagnostic> {
        self.skip_space_and_comments()?;
        let start = self.pos;
        if self.pos >= self.bytes.len() {
            return Ok(Token { kind: TokenKind::Eof, span: self.span(start, start) });
        }
        let c = self.bytes[self.pos];
        let kind = if c.is_ascii_alphabetic() || c == b'_' {
            while self.peek(0).is_ascii_alphanumeric() || self.peek(0) == b'_' {
                self.pos += 1;
            }
            TokenKind::Ident(String::from_utf8_lossy(&self.bytes[start..self.pos]).into_owned())
        } else if c.is_ascii_digit() || (c == b'.' && self.peek(1).is_ascii_digit()) {
            self.number()?
        } else if c == b'"' {
            self.string()?
        } else if let Some(p) = PUNCTS.iter().find(|p| self.bytes[self.pos..].starts_with(p.as_bytes())) {
            self.pos += p.len();
            TokenKind::Punct(p)
        } else {
            let ch = String::from_utf8_lossy(&self.bytes[start..(start + 4).min(self.bytes.len())])
                .chars()
                .next()
                .unwrap_or('?');
            let shown = if ch.is_control() || ch == char::REPLACEMENT_CHARACTER {
                format!("byte 0x{c:02x}")
            } else {
                format!("`{ch}`")
            };
            return Err(Diagnostic::error(self.span(start, start + 1), format!("unexpected character {shown}")));
        };
        Ok(Token { kind, span: self.span(start, self.pos) })
    }

    fn number(&mut self) -> Result<TokenKind, Diagnostic> {
        let start = self.pos;
        if self.peek(0) == b'0' && matches!(self.peek(1), b'x' | b'X') {
            self.pos += 2;
            let digits = self.pos;
            while self.peek(0).is_ascii_hexdigit() {
                self.pos += 1;
            }
            let text = std::str::from_utf8(&self.bytes[digits..self.pos]).unwrap_or("");
            return match i64::from_str_radix(text, 16) {
                Ok(v) => Ok(TokenKind::Int(v)),
                Err(_) if text.is_empty() => {
                    Err(Diagnostic::error(self.span(start, self.pos), "hexadecimal literal `0x` has no digits"))
                }
                Err(_) => Err(Diagnostic::error(self.span(start, self.pos), "integer literal is too large")),
            };
        }
        while self.peek(0).is_ascii_digit() {
            self.pos += 1;
        }
        let mut is_float = false;
        if self.peek(0) == b'.' && self.peek(1) != b'.' {
            is_float = true;
            self.pos += 1;
            while self.peek(0).is_ascii_digit() {
                self.pos += 1;
            }
        }
        if matches!(self.peek(0), b'e' | b'E') {
            let sign = usize::from(matches!(self.peek(1), b'+' | b'-'));
            if self.peek(1 + sign).is_ascii_digit() {
                is_float = true;
                self.pos += 1 + sign;
                while self.peek(0).is_ascii_digit() {
                    self.pos += 1;
                }
            } else {
                return Err(Diagnostic::error(
                    self.span(start, self.pos + 1),
                    "exponent of a float literal has no digits",
                ));
            }
        }
        let text = std::str::from_utf8(&self.bytes[start..self.pos]).unwrap_or("0");
        let suffix = self.peek(0);
        if matches!(suffix, b'f' | b'F' | b'd' | b'D') {
            self.pos += 1;
            let value =
                text.parse::<f64>().map_err(|_| Diagnostic::error(self.span(start, self.pos), "malformed number"))?;
            return Ok(TokenKind::Float { value, double: matches!(suffix, b'd' | b'D') });
        }
        if self.peek(0).is_ascii_alphabetic() || self.peek(0) == b'_' {
            return Err(Diagnostic::error(
                self.span(start, self.pos + 1),
                "a number runs into a name (missing space?)",
            ));
        }
        if is_float {
            let value =
                text.parse::<f64>().map_err(|_| Diagnostic::error(self.span(start, self.pos), "malformed number"))?;
            return Ok(TokenKind::Float { value, double: false });
        }
        let parsed = if text.len() > 1 && text.starts_with('0') {
            if text.bytes().any(|b| b > b'7') {
                return Err(Diagnostic::error(self.span(start, self.pos), "octal literal has a digit 8 or 9"));
            }
            i64::from_str_radix(&text[1..], 8)
        } else {
            text.parse::<i64>()
        };
        parsed
            .map(TokenKind::Int)
            .map_err(|_| Diagnostic::error(self.span(start, self.pos), "integer literal is too large"))
    }

    fn string(&mut self) -> Result<TokenKind, Diagnostic> {
        let start = self.pos;
        self.pos += 1;
        let mut out: Vec<u8> = Vec::new();
        loop {
            let Some(&c) = self.bytes.get(self.pos) else {
                return Err(Diagnostic::error(self.span(start, start + 1), "unterminated string literal"));
            };
            match c {
                b'"' => {
                    self.pos += 1;
                    break;
                }
                b'\n' => {
                    return Err(Diagnostic::error(
                        self.span(start, start + 1),
                        "unterminated string literal (line break)",
                    ))
                }
                b'\\' => {
                    let esc = self.peek(1);
                    let esc_start = self.pos;
                    self.pos += 2;
                    match esc {
                        b'n' => out.push(b'\n'),
                        b't' => out.push(b'\t'),
                        b'r' => out.push(b'\r'),
                        b'a' => out.push(7),
                        b'b' => out.push(8),
                        b'f' => out.push(12),
                        b'v' => out.push(11),
                        b'\\' | b'"' | b'\'' | b'?' => out.push(esc),
                        b'x' | b'u' | b'U' => {
                            let max = match esc {
                                b'x' => 2,
                                b'u' => 4,
                                _ => 8,
                            };
                            let digits = self.pos;
                            while self.pos - digits < max && self.peek(0).is_ascii_hexdigit() {
                                self.pos += 1;
                            }
                            let text = std::str::from_utf8(&self.bytes[digits..self.pos]).unwrap_or("");
                            let code = u32::from_str_radix(text, 16).ok().and_then(char::from_u32);
                            let Some(ch) = code else {
                                return Err(Diagnostic::error(
                                    self.span(esc_start, self.pos),
                                    "malformed escape sequence in string",
                                ));
                            };
                            let mut buf = [0u8; 4];
                            out.extend_from_slice(ch.encode_utf8(&mut buf).as_bytes());
                        }
                        b'0'..=b'7' => {
                            self.pos -= 1;
                            let digits = self.pos;
                            while self.pos - digits < 3 && matches!(self.peek(0), b'0'..=b'7') {
                                self.pos += 1;
                            }
                            let text = std::str::from_utf8(&self.bytes[digits..self.pos]).unwrap_or("0");
                            out.push(u32::from_str_radix(text, 8).unwrap_or(0).min(255) as u8);
                        }
                        _ => {
                            return Err(Diagnostic::error(
                                self.span(esc_start, (esc_start + 2).min(self.bytes.len())),
                                "unknown escape sequence in string",
                            ))
                        }
                    }
                }
                _ => {
                    out.push(c);
                    self.pos += 1;
                }
            }
        }
        match String::from_utf8(out) {
            Ok(s) => Ok(TokenKind::Str(s)),
            Err(_) => Err(Diagnostic::error(self.span(start, self.pos), "string literal is not valid UTF-8")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(text: &str) -> Vec<TokenKind> {
        tokenize(FileId(0), text.as_bytes()).unwrap().into_iter().map(|t| t.kind).collect()
    }

    #[test]
    fn numbers_in_all_forms() {
        assert_eq!(
            kinds("1 0x1F 017 1.5 .5 2. 1e3 2.5f 3d"),
            vec![
                TokenKind::Int(1),
                TokenKind::Int(31),
                TokenKind::Int(15),
                TokenKind::Float { value: 1.5, double: false },
                TokenKind::Float { value: 0.5, double: false },
                TokenKind::Float { value: 2.0, double: false },
                TokenKind::Float { value: 1000.0, double: false },
                TokenKind::Float { value: 2.5, double: false },
                TokenKind::Float { value: 3.0, double: true },
                TokenKind::Eof,
            ]
        );
    }

    #[test]
    fn punctuation_takes_the_longest_match() {
        assert_eq!(
            kinds("a::b>>>=c"),
            vec![
                TokenKind::Ident("a".into()),
                TokenKind::Punct("::"),
                TokenKind::Ident("b".into()),
                TokenKind::Punct(">>>="),
                TokenKind::Ident("c".into()),
                TokenKind::Eof
            ]
        );
    }

    #[test]
    fn strings_and_comments() {
        assert_eq!(
            kinds("\"a\\n\\x41\" // c\n /* x */ b"),
            vec![TokenKind::Str("a\nA".into()), TokenKind::Ident("b".into()), TokenKind::Eof]
        );
    }

    #[test]
    fn errors_point_at_the_culprit() {
        let e = tokenize(FileId(0), b"a \"open").unwrap_err();
        assert_eq!((e.span.lo, e.span.hi), (2, 3));
        let e = tokenize(FileId(0), b"x /* y").unwrap_err();
        assert_eq!(e.span.lo, 2);
        let e = tokenize(FileId(0), b"a $").unwrap_err();
        assert!(e.message.contains("`$`"), "{}", e.message);
    }
}
