//! Short decimal numbers read eight bytes at a time ("SIMD within a register"): the digit
//! runs of `358.479`, `-0.41582` or `13392` are found and converted without a branch per
//! digit. These are fast paths only: each answers `None` for anything outside its simple
//! form (an exponent, nine or more digits, fewer than eight bytes left to load), and the
//! caller then reads the number the general way, so the values are those of
//! [`super::number::parse_f32_simple`] bit for bit.

use super::number::POW10_F32;

/// `0x30` (`'0'`) in every byte.
const ZEROS: u64 = 0x3030_3030_3030_3030;

/// The high bit of every byte.
const HIGH_BITS: u64 = 0x8080_8080_8080_8080;

/// The eight bytes at `text[at..at + 8]` as a little-endian word (the first byte lowest);
/// `None` when fewer than eight bytes are left.
#[inline(always)]
fn load8(text: &[u8], at: usize) -> Option<u64> {
    let bytes: [u8; 8] = text.get(at..at + 8)?.try_into().ok()?;
    Some(u64::from_le_bytes(bytes))
}

/// The number of ASCII digits `word` starts with (its lowest bytes first), 0 to 8.
#[inline(always)]
fn leading_digits(word: u64) -> u32 {
    // A byte gets its high bit here if it is above '9' (the add carries into bit 7) or
    // below '0' (the subtraction wraps). Carries and borrows only run towards higher
    // bytes, and a digit byte produces neither, so the lowest flagged byte is exactly the
    // first byte that is not a digit; bytes above it may be flagged wrongly, never read.
    let above = word.wrapping_add(0x4646_4646_4646_4646);
    let below = word.wrapping_sub(ZEROS);
    ((above | below) & HIGH_BITS).trailing_zeros() / 8
}

/// The value of the first `n` (1 to 7) digits of `word` (its lowest bytes first).
#[inline(always)]
fn digits_value(word: u64, n: u32) -> u32 {
    debug_assert!((1..8).contains(&n));
    // The `n` digits moved to the top bytes; the bytes below become leading zeros.
    let d = (word.wrapping_sub(ZEROS)) << (8 * (8 - n));
    // Pairs, then fours, then all eight (each byte of `d` is 0..=9 after the shift).
    let d = (d.wrapping_mul(10) + (d >> 8)) & 0x00FF_00FF_00FF_00FF;
    let d = (d.wrapping_mul(100) + (d >> 16)) & 0x0000_FFFF_0000_FFFF;
    (d.wrapping_mul(10_000) + (d >> 32)) as u32
}

/// Reads the unsigned integer at `text[at..]` of one to seven digits. Returns its value
/// and the offset just past it; `None` (read it the general way) when no digit is there,
/// eight or more digits are, or fewer than eight bytes are left. The byte after the
/// digits is not checked.
#[inline(always)]
pub(super) fn u32_digits(text: &[u8], at: usize) -> Option<(u32, usize)> {
    let word = load8(text, at)?;
    let n = leading_digits(word);
    if n == 0 || n == 8 {
        return None;
    }
    Some((digits_value(word, n), at + n as usize))
}

/// Reads the number at `text[at..]` of the form `[-+]digits[.digits]` (or `[-+].digits`)
/// with at most seven digits on each side (a mantissa of at most 2²⁴), as an `f32`, exactly as
/// [`super::number::parse_f32_simple`] does. Returns the value and the offset just past
/// the number; `None` (read it the general way) for any other form or when a load would
/// pass the end of `text`. The byte after the number is not checked (an `e` there means an
/// exponent: the caller must then read it the general way).
#[inline(always)]
pub(super) fn f32_decimal(text: &[u8], at: usize) -> Option<(f32, usize)> {
    let sign = *text.get(at)?;
    let neg = sign == b'-';
    let mut i = at + usize::from(neg || sign == b'+');
    let word = load8(text, i)?;
    let int_digits = leading_digits(word);
    if int_digits == 8 {
        return None;
    }
    let int_value = if int_digits == 0 { 0 } else { digits_value(word, int_digits) };
    i += int_digits as usize;
    let (mut mantissa, mut frac_digits) = (u64::from(int_value), 0);
    if text.get(i) == Some(&b'.') {
        i += 1;
        let word = load8(text, i)?;
        frac_digits = leading_digits(word);
        if frac_digits == 8 {
            return None;
        }
        if frac_digits > 0 {
            mantissa =
                mantissa * u64::from(POW10_U32[frac_digits as usize]) + u64::from(digits_value(word, frac_digits));
            i += frac_digits as usize;
        }
    }
    // The general fast path's limits: some digit, a mantissa of at most 2^24 (exact in
    // `f32`); the power of ten (at most 7 here) is always within its table.
    if int_digits + frac_digits == 0 || mantissa > 1 << 24 {
        return None;
    }
    let m = mantissa as f32;
    let v = if frac_digits > 0 { m / POW10_F32[frac_digits as usize] } else { m * POW10_F32[0] };
    Some((if neg { -v } else { v }, i))
}

/// Powers of ten up to 10^7 as `u32`.
const POW10_U32: [u32; 8] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000, 10_000_000];

#[cfg(test)]
mod tests {
    use super::super::is_delimiter;
    use super::super::number::parse_f32_simple;
    use super::*;

    /// Every number form with its padding: the fast path agrees with the general one
    /// (value bits and length) whenever it answers and a delimiter follows (as its callers
    /// require), and answers for the common forms.
    #[test]
    fn decimals_equal_the_general_fast_path() {
        let mut answered = 0;
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let chars = b"0123456789.-+eE x\n]";
        for _ in 0..400_000 {
            let r = next();
            let len = 1 + (r % 14) as usize;
            let mut s: Vec<u8> = (0..len)
                .map(|k| {
                    let pick = (r >> (8 + 4 * k)) as usize;
                    // Mostly digits, so that well-formed numbers are common.
                    if pick % 4 != 0 {
                        b'0' + (pick / 4 % 10) as u8
                    } else {
                        chars[pick / 4 % chars.len()]
                    }
                })
                .collect();
            s.extend_from_slice(b" 1234567\n");
            // The callers take the fast answer only when a delimiter follows it.
            if let Some((v, end)) = f32_decimal(&s, 0).filter(|&(_, end)| is_delimiter(s[end])) {
                answered += 1;
                let (w, wend) = parse_f32_simple(&s).expect("the general fast path reads it too");
                assert_eq!((v.to_bits(), end), (w.to_bits(), wend), "{:?}", String::from_utf8_lossy(&s));
            }
        }
        assert!(answered > 50_000, "only {answered} answered");
        for (text, value) in [
            ("358.479", 358.479f32),
            ("-0.41582", -0.41582),
            ("+12.5", 12.5),
            (".5", 0.5),
            ("1.", 1.0),
            ("-0", -0.0),
            ("9999999", 9_999_999.0),
            ("1.6777216", 1.677_721_6),
        ] {
            let padded = format!("{text} 1234567\n");
            let (v, end) = f32_decimal(padded.as_bytes(), 0).unwrap_or_else(|| panic!("{text:?} not read"));
            assert_eq!((v.to_bits(), end), (value.to_bits(), text.len()), "{text:?}");
        }
        // Left to the general path: too long, too large, no digits, too near the end.
        for text in [
            "16777216 ",
            "12345678.5 ",
            "0.12345678 ",
            "16777217 ",
            "1.6777217 ",
            ". x      ",
            "- 1      ",
            "-.x      ",
            "1.5",
        ] {
            assert_eq!(f32_decimal(text.as_bytes(), 0), None, "{text:?}");
        }
    }

    #[test]
    fn integers_of_one_to_seven_digits() {
        for n in 1..8u32 {
            for v in [0u32, 1, 7, 10u32.pow(n - 1), 10u32.pow(n) - 1, 1_234_567 % 10u32.pow(n)] {
                let text = format!("{v:0n$} 99999999", n = n as usize);
                assert_eq!(u32_digits(text.as_bytes(), 0), Some((v, n as usize)), "{text:?}");
            }
        }
        for text in ["12345678 ", "x1234567 ", " 1234567 ", "123"] {
            assert_eq!(u32_digits(text.as_bytes(), 0), None, "{text:?}");
        }
        // A byte above the first non-digit never matters: `/` and `:` are the neighbours
        // of the digits, 0x80 and 0xff the extremes.
        for stop in [b'/', b':', 0x80, 0xff, b'\n', 0] {
            let mut text = b"4096".to_vec();
            text.extend([stop, b'9', b'9', b'9', b'9']);
            assert_eq!(u32_digits(&text, 0), Some((4096, 4)), "stop byte {stop:#x}");
        }
    }
}
