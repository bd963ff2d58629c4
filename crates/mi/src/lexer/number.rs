//! Number literals: scanning them, and parsing integers and floats (with an exact fast
//! path for the short decimal forms exporters write).

use super::{is_delimiter, Lexer, Tok, Token};
use crate::diag::Diagnostic;

/// Exact powers of ten as `f32` (all representable).
pub(super) const POW10_F32: [f32; 11] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10];

/// Parses the common short decimal forms (`-12.5`, `0.136563`, `1e-5`) exactly: when the
/// decimal mantissa fits 24 bits and the power of ten is at most 10, one `f32` multiply or
/// divide of exact operands rounds correctly (Clinger's fast path). Returns `None` for
/// anything else, which the general parser then handles.
#[inline]
pub(super) fn parse_f32_simple(s: &[u8]) -> Option<(f32, usize)> {
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

    pub(super) fn lex_number(&mut self, start: usize) -> Result<Token, Diagnostic> {
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
}
