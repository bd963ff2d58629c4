//! Bulk number lists read on several threads: a bracketed list of plain numbers (a
//! trilist's vertex data or triangle indices) is cut at line breaks into pieces that the
//! rayon pool parses at once, each number exactly as the one-at-a-time fast paths
//! ([`Lexer::try_f32`], [`Lexer::try_u32`]) read it, appended in order to the output.
//!
//! A list holding anything but numbers, whitespace and comments (a material name, a
//! directive, a malformed number) is left to the one-at-a-time path, which reads it or
//! reports the error at its place: the parallel path only ever answers "read it all" or
//! "not mine".

use rayon::prelude::*;

use super::number::parse_f32_simple;
use super::{is_delimiter, swar, Lexer};

/// Lists of at least this many bytes are read in parallel (smaller ones are not worth a
/// thread's wake-up).
pub const PARALLEL_FROM_BYTES: usize = 1 << 20;

/// Bytes of text per piece (about 40 000 floats of a trilist's vertex lines).
const PIECE_BYTES: usize = 256 << 10;

/// Pieces read per round; their numbers are appended to the output before the next round,
/// so the pieces' own buffers stay small whatever the list's size.
const PIECES_PER_ROUND: usize = 64;

impl Lexer {
    /// Reads the rest of a bracketed list of numbers (the `[` consumed) as `f32`, its `]`
    /// included, appending to `out`, when the list is long and holds nothing but numbers and
    /// comments. Returns `false`, having consumed nothing, otherwise.
    pub fn f32_list_parallel(&mut self, out: &mut Vec<f32>) -> bool {
        self.list_parallel(out)
    }

    /// [`Lexer::f32_list_parallel`] for non-negative integers that fit `u32` (indices).
    pub fn u32_list_parallel(&mut self, out: &mut Vec<u32>) -> bool {
        self.list_parallel(out)
    }

    /// Reads the rest of a long bracketed list of `T` in parallel pieces, appending to `out`:
    /// `true` with the list and its `]` consumed, or `false` with nothing consumed.
    fn list_parallel<T: PieceNumber>(&mut self, out: &mut Vec<T>) -> bool {
        let start = self.pos;
        let Some(end) = list_end(&self.src[start..]).map(|e| start + e) else { return false };
        let (from_bytes, piece_bytes) = limits();
        if end - start < from_bytes {
            return false;
        }
        let pieces = pieces(&self.src[start..end], piece_bytes);
        let base = self.src.as_ptr() as usize;
        // The numbers go into zeroed memory the allocator maps fresh and no one has touched
        // (each number takes at least two bytes of text, a digit and a delimiter, so the
        // list holds at most half its length plus one): the pieces' numbers are copied into
        // it on the pool, which faults its pages in on both threads instead of on this one
        // (speed43: the heavy scene's 96 MB of vertex numbers and indices, 24 k page faults,
        // were the serial part of its parse). The pages past the numbers are never touched
        // and are handed back at the end.
        let room = (end - start) / 2 + 1;
        // Where the system refuses that much address space (strict overcommit, a list
        // near the memory's size), the one-at-a-time path reads the list instead of the
        // allocation aborting the process.
        if Vec::<T>::new().try_reserve_exact(room).is_err() {
            return false;
        }
        let mut numbers: Vec<T> = vec![T::ZERO; room];
        let mut written = 0;
        // One buffer per piece of a round, kept from round to round: their pages are
        // faulted in once, not once a round.
        let mut buffers: Vec<Vec<T>> = Vec::new();
        buffers.resize_with(pieces.len().min(PIECES_PER_ROUND), Vec::new);
        for round in pieces.chunks(PIECES_PER_ROUND) {
            let all_read = round.par_iter().zip(buffers[..round.len()].par_iter_mut()).all(|(piece, buffer)| {
                buffer.clear();
                buffer.reserve(piece.len() / 4);
                parse_piece(piece, buffer)
            });
            if !all_read {
                return false;
            }
            written = copy_parallel(&mut numbers, written, &buffers[..round.len()]);
            // The text read so far is not needed again (unless a message quotes it or the
            // serial path re-reads the list): a mapped file's pages go back to the page cache.
            if let Some(last) = round.last() {
                self.src.release_pages(start..last.as_ptr() as usize - base + last.len());
            }
        }
        numbers.truncate(written);
        if out.is_empty() {
            numbers.shrink_to_fit();
            *out = numbers;
        } else {
            out.extend_from_slice(&numbers);
        }
        self.pos = end + 1;
        true
    }
}

/// Copies the `buffers`' numbers in order into `numbers` from index `at` on, on the rayon
/// pool (each buffer into its own slice), and returns the index past them. Should the
/// numbers not fit (they always do: see [`Lexer::list_parallel`]), `numbers` grows.
fn copy_parallel<T: PieceNumber>(numbers: &mut Vec<T>, at: usize, buffers: &[Vec<T>]) -> usize {
    let total: usize = buffers.iter().map(Vec::len).sum();
    if numbers.len() < at + total {
        numbers.resize(at + total, T::ZERO);
    }
    let mut rest = &mut numbers[at..at + total];
    let mut slots = Vec::with_capacity(buffers.len());
    for buffer in buffers {
        let (slot, tail) = rest.split_at_mut(buffer.len());
        slots.push(slot);
        rest = tail;
    }
    slots.into_par_iter().zip(buffers.par_iter()).for_each(|(slot, buffer)| slot.copy_from_slice(buffer));
    at + total
}

/// Offset of the `]` that closes a list starting at `text[0]`, skipping comments; `None`
/// when the text ends first or a `[` (a nested list: not a plain number list) comes first.
fn list_end(text: &[u8]) -> Option<usize> {
    let mut i = 0;
    loop {
        i += memchr::memchr3(b']', b'#', b'[', &text[i..])?;
        match text[i] {
            b']' => return Some(i),
            b'#' => i += memchr::memchr(b'\n', &text[i..])?,
            _ => return None,
        }
    }
}

/// The list length from which lists are read in parallel and the bytes per piece:
/// [`PARALLEL_FROM_BYTES`] and [`PIECE_BYTES`], or in unit tests what [`with_limits`] set.
fn limits() -> (usize, usize) {
    #[cfg(test)]
    return LIMITS.with(std::cell::Cell::get);
    #[cfg(not(test))]
    (PARALLEL_FROM_BYTES, PIECE_BYTES)
}

#[cfg(test)]
thread_local! {
    static LIMITS: std::cell::Cell<(usize, usize)> = const { std::cell::Cell::new((PARALLEL_FROM_BYTES, PIECE_BYTES)) };
}

/// Runs `f` (on this thread) with lists of at least `from_bytes` read in parallel, in
/// pieces of about `piece_bytes`: `usize::MAX` reads every list serially, small pieces
/// put piece boundaries everywhere.
#[cfg(test)]
pub(crate) fn with_limits<R>(from_bytes: usize, piece_bytes: usize, f: impl FnOnce() -> R) -> R {
    let before = LIMITS.with(|l| l.replace((from_bytes, piece_bytes.max(1))));
    let result = f();
    LIMITS.with(|l| l.set(before));
    result
}

/// `text` cut into pieces of about `piece_bytes`, each ending just after a line break
/// (numbers and comments never span one) or at the end.
fn pieces(text: &[u8], piece_bytes: usize) -> Vec<&[u8]> {
    let mut out = Vec::with_capacity(text.len() / piece_bytes + 1);
    let mut at = 0;
    while at < text.len() {
        let cut = at + piece_bytes;
        let end = if cut >= text.len() {
            text.len()
        } else {
            memchr::memchr(b'\n', &text[cut..]).map_or(text.len(), |i| cut + i + 1)
        };
        out.push(&text[at..end]);
        at = end;
    }
    out
}

/// Skips whitespace and comments from `i`; the offset of the next byte (or the end).
#[inline]
fn skip_trivia(text: &[u8], mut i: usize) -> usize {
    while let Some(&b) = text.get(i) {
        match b {
            b' ' | b'\t' | b'\n' | b'\r' | 0x0c => i += 1,
            b'#' => match memchr::memchr(b'\n', &text[i..]) {
                Some(k) => i += k + 1,
                None => return text.len(),
            },
            _ => break,
        }
    }
    i
}

/// Whether a number ending at `end` is cut off properly: by the end of the piece (a line
/// break or the list's `]` follows it in the file) or by a delimiter.
#[inline]
fn ends_at(text: &[u8], end: usize) -> bool {
    end == text.len() || is_delimiter(text[end])
}

/// A number type the piece readers read: a fast path for the common short form (SWAR), a
/// full reader for the rest, both exactly as the one-at-a-time lexer reads the type.
trait PieceNumber: Send + Sync + Copy {
    /// Zero, whose bits are all zero (so that a vector of them is memory mapped fresh).
    const ZERO: Self;
    /// The short form at `text[i..]` (SWAR), with the offset past it; `None` when it is
    /// not there (the number may still be read by [`PieceNumber::general`]). The caller
    /// checks that the number is properly cut off.
    fn fast(text: &[u8], i: usize) -> Option<(Self, usize)>;
    /// The number at `text[i..]` read in full, with the offset past it; `None` when no
    /// number properly cut off is there.
    fn general(text: &[u8], i: usize) -> Option<(Self, usize)>;
}

impl PieceNumber for f32 {
    const ZERO: f32 = 0.0;
    #[inline(always)]
    fn fast(text: &[u8], i: usize) -> Option<(f32, usize)> {
        swar::f32_decimal(text, i)
    }
    #[inline(always)]
    fn general(text: &[u8], i: usize) -> Option<(f32, usize)> {
        parse_f32_general(text, i)
    }
}

impl PieceNumber for u32 {
    const ZERO: u32 = 0;
    #[inline(always)]
    fn fast(text: &[u8], i: usize) -> Option<(u32, usize)> {
        swar::u32_digits(text, i)
    }
    #[inline(always)]
    fn general(text: &[u8], i: usize) -> Option<(u32, usize)> {
        parse_u32_general(text, i)
    }
}

/// Reads a piece holding only numbers of type `T` (floats as [`Lexer::try_f32`] reads
/// them, or non-negative integers that fit `u32` as [`Lexer::try_u32`] does), whitespace
/// and comments; `false` at anything else. Kept out of line, one copy per type, as the
/// two readers it replaced were (inlined into the pool's closure it runs ~1.4 % more
/// instructions).
#[inline(never)]
fn parse_piece<T: PieceNumber>(text: &[u8], out: &mut Vec<T>) -> bool {
    let mut i = skip_trivia(text, 0);
    while i < text.len() {
        let (v, end) = match T::fast(text, i) {
            Some((v, end)) if ends_at(text, end) => (v, end),
            _ => match T::general(text, i) {
                Some(read) => read,
                None => return false,
            },
        };
        out.push(v);
        i = skip_trivia(text, end);
    }
    true
}

/// The number at `text[i..]` read as [`Lexer::try_f32`] reads it (the short decimal fast
/// path, else the full parser), with the offset past it; `None` when no number properly
/// cut off is there.
#[inline(never)]
fn parse_f32_general(text: &[u8], i: usize) -> Option<(f32, usize)> {
    let signed = matches!(text[i], b'-' | b'+');
    let first = if signed { text.get(i + 1) } else { Some(&text[i]) };
    if !matches!(first, Some(b'0'..=b'9' | b'.')) {
        return None;
    }
    let rest = &text[i..];
    match parse_f32_simple(rest) {
        Some((v, len)) if ends_at(text, i + len) => Some((v, i + len)),
        _ => match fast_float2::parse_partial::<f32, _>(rest) {
            Ok((v, len)) if ends_at(text, i + len) => Some((v, i + len)),
            _ => None,
        },
    }
}

/// The integer at `text[i..]` read digit by digit, with the offset past it; `None` when
/// no integer that fits `u32` and is properly cut off is there.
#[inline(never)]
fn parse_u32_general(text: &[u8], i: usize) -> Option<(u32, usize)> {
    let start = i;
    let mut i = i;
    let mut v: u64 = 0;
    while let Some(&d) = text.get(i) {
        if !d.is_ascii_digit() {
            break;
        }
        v = v * 10 + u64::from(d - b'0');
        if v > u64::from(u32::MAX) {
            return None;
        }
        i += 1;
    }
    if i == start || !ends_at(text, i) {
        return None;
    }
    Some((v as u32, i))
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::source::FileId;

    fn lexer(text: &str) -> Lexer {
        Lexer::new(FileId(0), Arc::<[u8]>::from(text.as_bytes()))
    }

    /// Vertex lines in every form exporters write, with comments and blank lines, longer
    /// than the parallel threshold, closed by `]`.
    fn float_list(lines: usize) -> String {
        let forms = ["0.136563", "-12.5", "1.", ".5", "-2.5e-05", "1E+3", "7", "-0", "3.4028236e38", "1e-50"];
        let mut s = String::new();
        for i in 0..lines {
            let a = forms[i % forms.len()];
            let b = (i as f64 * 0.001 - 17.0).to_string();
            let c = format!("{}.{:03}", i % 997, i % 1000);
            s.push_str(&format!("{a} {b}\t{c}\n"));
            if i % 5000 == 0 {
                s.push_str("# a comment with ] and [ in it\n\n");
            }
        }
        s.push_str("]\nend trilist\n");
        s
    }

    /// The same numbers, read one at a time by the serial fast path.
    fn serial_f32(text: &str) -> Vec<f32> {
        let mut lx = lexer(text);
        let mut out = Vec::new();
        while let Some(x) = lx.try_f32().unwrap() {
            out.push(x);
        }
        out
    }

    #[test]
    fn parallel_floats_equal_the_serial_path_bit_for_bit() {
        let text = float_list(120_000);
        assert!(text.len() > 2 * PARALLEL_FROM_BYTES, "the list must span several pieces");
        let mut lx = lexer(&text);
        let mut out = vec![42.0];
        assert!(lx.f32_list_parallel(&mut out));
        let serial = serial_f32(&text);
        assert_eq!(serial.len(), 3 * 120_000);
        assert_eq!(out.len(), serial.len() + 1, "appends after what was there");
        assert!(out[1..].iter().zip(&serial).all(|(a, b)| a.to_bits() == b.to_bits()));
        // The `]` is consumed; the lexer stands before `end trilist`.
        assert_eq!(lx.peek_word(), Some(&b"end"[..]));
    }

    /// The densest list (one digit and one delimiter a number) fills the fresh memory the
    /// numbers go into to its last slot, and a list read into an empty vector is handed
    /// over without the unused room.
    #[test]
    fn the_densest_list_fits_and_keeps_no_spare_room() {
        let lines = 400_000;
        let mut text = String::new();
        for i in 0..lines {
            text.push_str(&format!("{} {} {}\n", i % 10, (i / 10) % 10, (i / 100) % 10));
        }
        text.push_str("]\nend trilist\n");
        let list_bytes = text.find(']').unwrap();
        assert_eq!(list_bytes, 6 * lines, "two bytes a number");
        for read_as_u32 in [false, true] {
            let mut lx = lexer(&text);
            let expect = |i: usize| [i % 10, (i / 10) % 10, (i / 100) % 10];
            if read_as_u32 {
                let mut out = Vec::new();
                assert!(lx.u32_list_parallel(&mut out));
                assert_eq!(out.len(), 3 * lines);
                assert_eq!(out.capacity(), out.len());
                assert!(out
                    .chunks_exact(3)
                    .enumerate()
                    .all(|(i, c)| expect(i).iter().zip(c).all(|(&e, &v)| e as u32 == v)));
            } else {
                let mut out = Vec::new();
                assert!(lx.f32_list_parallel(&mut out));
                assert_eq!(out.len(), 3 * lines);
                assert_eq!(out.capacity(), out.len());
                assert!(out
                    .chunks_exact(3)
                    .enumerate()
                    .all(|(i, c)| expect(i).iter().zip(c).all(|(&e, &v)| e as f32 == v)));
            }
            assert_eq!(lx.peek_word(), Some(&b"end"[..]));
        }
    }

    /// Buffers of any lengths, empty ones among them, land in order from the given index,
    /// and numbers that do not fit make the vector grow.
    #[test]
    fn copies_land_in_order_and_grow_when_short() {
        let buffers: Vec<Vec<u32>> = (0..70u32).map(|b| (0..(b * 7) % 23).map(|k| b * 1000 + k).collect()).collect();
        let expected: Vec<u32> = buffers.iter().flatten().copied().collect();
        let mut numbers = vec![7u32; 5 + expected.len()];
        assert_eq!(copy_parallel(&mut numbers, 5, &buffers), 5 + expected.len());
        assert_eq!(&numbers[..5], &[7; 5]);
        assert_eq!(&numbers[5..], &expected[..]);
        let mut short = vec![1u32; 3];
        assert_eq!(copy_parallel(&mut short, 2, &buffers), 2 + expected.len());
        assert_eq!(&short[..2], &[1, 1]);
        assert_eq!(&short[2..], &expected[..]);
    }

    #[test]
    fn parallel_indices_equal_the_serial_path() {
        let mut text = String::new();
        for i in 0..300_000u32 {
            text.push_str(&format!("{} {} {}\n", i, i.wrapping_mul(2_654_435_761) % 1_000_000, u32::MAX - i));
        }
        text.push_str("] x");
        let mut lx = lexer(&text);
        let mut out = Vec::new();
        assert!(lx.u32_list_parallel(&mut out));
        let mut serial = Vec::new();
        let mut s = lexer(&text);
        while let Some(x) = s.try_u32().unwrap() {
            serial.push(x);
        }
        assert_eq!(out, serial);
        assert_eq!(lx.peek_word(), Some(&b"x"[..]));
    }

    /// Anything but plain numbers leaves the list to the serial path, untouched.
    #[test]
    fn lists_with_anything_else_are_not_taken() {
        let base = float_list(100_000);
        let cut = base.len() / 2;
        let cut = cut + base[cut..].find('\n').unwrap() + 1;
        for intruder in ["\"mat\" ", "$ifdef x\n", "1.5x ", "`abc` ", "[ ", "- ", "1e "] {
            let text = format!("{}{intruder}{}", &base[..cut], &base[cut..]);
            let mut lx = lexer(&text);
            let mut out = vec![1.0];
            assert!(!lx.f32_list_parallel(&mut out), "{intruder:?} was taken");
            assert_eq!((out.len(), lx.pos), (1, 0), "{intruder:?}: something was consumed");
        }
        let mut ints = String::from("1 2 3\n").repeat(200_000);
        ints.push_str("4294967296 ]");
        let mut out = Vec::new();
        assert!(
            !lexer(&ints).u32_list_parallel(&mut out) && out.is_empty(),
            "an index past u32 is the serial path's error"
        );
        // Short lists and unclosed lists are not taken either.
        assert!(!lexer("1 2 3 ]").f32_list_parallel(&mut Vec::new()));
        assert!(!lexer(&base[..base.len() - 14]).f32_list_parallel(&mut Vec::new()));
    }

    /// A malformed number deep in a long trilist is reported where it is, as before.
    #[test]
    fn an_error_in_a_long_list_points_at_its_line() {
        let lines = 100_000;
        let mut text = format!("object \"o\"\ntrilist vertex {lines} p\ntriangle 1\n[\n");
        for i in 0..lines {
            text.push_str(if i == 90_000 { "1.0 2.0q 3.0\n" } else { "1.0 2.0 3.0\n" });
        }
        text.push_str("]\n[ 0 1 2 ]\nend trilist\nend object\n");
        assert!(text.len() > PARALLEL_FROM_BYTES);
        let parsed = crate::parse_str("big.mi", &text);
        let error = parsed.diagnostics.list.iter().find(|d| d.is_error()).expect("an error");
        let at = error.span.lo as usize;
        let line = text[..at].matches('\n').count() + 1;
        assert_eq!(line, 4 + 90_000 + 1, "{}", error.message);
        assert!(error.message.contains("malformed number"), "{}", error.message);
    }

    /// Single-thread speed of the piece readers on a real scene's trilist (the file named by
    /// `MI_PARSE_TIMING`, e.g. the heavy bench scene): `cargo test -p mi --release --lib
    /// piece_reader_speed -- --ignored --nocapture`.
    #[test]
    #[ignore = "a measurement, not a check: needs MI_PARSE_TIMING=<scene.mi>"]
    fn piece_reader_speed() {
        let Ok(path) = std::env::var("MI_PARSE_TIMING") else { return };
        let text = std::fs::read(path).unwrap();
        let open = text.windows(8).position(|w| w == b"trilist\n").unwrap();
        let v0 = open + memchr::memchr(b'[', &text[open..]).unwrap() + 1;
        let v1 = v0 + list_end(&text[v0..]).unwrap();
        let t0 = v1 + 1 + memchr::memchr(b'[', &text[v1 + 1..]).unwrap() + 1;
        let t1 = t0 + list_end(&text[t0..]).unwrap();
        for _ in 0..3 {
            let clock = std::time::Instant::now();
            let mut floats = Vec::<f32>::with_capacity((v1 - v0) / 4);
            assert!(parse_piece(&text[v0..v1], &mut floats));
            let f = clock.elapsed();
            let clock = std::time::Instant::now();
            let mut ints = Vec::<u32>::with_capacity((t1 - t0) / 4);
            assert!(parse_piece(&text[t0..t1], &mut ints));
            let u = clock.elapsed();
            // The digit-by-digit readers alone (the pieces' readers before the SWAR paths).
            let clock = std::time::Instant::now();
            let mut serial = Vec::with_capacity(floats.len());
            let (piece, mut i) = (&text[v0..v1], skip_trivia(&text[v0..v1], 0));
            while i < piece.len() {
                let (v, end) = parse_f32_general(piece, i).unwrap();
                serial.push(v);
                i = skip_trivia(piece, end);
            }
            let sf = clock.elapsed();
            let clock = std::time::Instant::now();
            let mut serial_ints = Vec::with_capacity(ints.len());
            let (piece, mut i) = (&text[t0..t1], skip_trivia(&text[t0..t1], 0));
            while i < piece.len() {
                let (v, end) = parse_u32_general(piece, i).unwrap();
                serial_ints.push(v);
                i = skip_trivia(piece, end);
            }
            let su = clock.elapsed();
            assert_eq!(serial_ints, ints);
            assert!(
                serial.iter().zip(&floats).all(|(a, b)| a.to_bits() == b.to_bits()) && serial.len() == floats.len()
            );
            let ns = |t: std::time::Duration, n: usize| t.as_secs_f64() * 1e9 / n as f64;
            println!(
                "{} floats: {:.2} ns each (digit by digit {:.2}); {} indices: {:.2} ns each (digit by digit {:.2})",
                floats.len(),
                ns(f, floats.len()),
                ns(sf, floats.len()),
                ints.len(),
                ns(u, ints.len()),
                ns(su, ints.len()),
            );
        }
    }
}
