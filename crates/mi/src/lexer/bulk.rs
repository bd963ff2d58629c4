//! Fast paths for bulk data: numbers, indices and words read straight from the bytes
//! without building tokens, and binary blocks of a known length.

use super::number::parse_f32_simple;
use super::{is_delimiter, is_name_char, is_name_start, swar, Lexer, Tok};
use crate::diag::Diagnostic;
use crate::source::Span;

impl Lexer {
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
        if let Some((v, end)) = swar::f32_decimal(src, start) {
            if end == src.len() || is_delimiter(src[end]) {
                self.pos = end;
                return Ok(Some(v));
            }
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
        if let Some((v, end)) = swar::u32_digits(src, start) {
            if end == src.len() || is_delimiter(src[end]) {
                self.pos = end;
                return Ok(Some(v));
            }
        }
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
