//! Whole scenes read with long number lists in parallel (pieces of every size) and serially
//! give the same syntax trees and the same messages: random meshes in both dialects'
//! forms (`trilist` lists and `group` vector lines), malformed numbers placed at the
//! start, middle, piece boundaries and end of a long list, and lists the file cuts short.

use std::fmt::Write;

use crate::ast::{Geometry, Item};
use crate::lexer::with_limits;
use crate::Parsed;

/// A small deterministic generator (xorshift64).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// A number written in one of the forms exporters use (short decimals, long ones,
/// exponents, `1.`, `.5`, integers, signs).
fn number(rng: &mut Rng) -> String {
    let x = (rng.below(2_000_000) as f64 - 1_000_000.0) / 997.0;
    match rng.below(10) {
        0..=3 => format!("{x:.3}"),
        4 => format!("{x:.6}"),
        5 => format!("{:e}", x as f32),
        6 => format!("{}.", x as i64),
        7 => format!(".{}", rng.below(100_000)),
        8 => format!("{}", x as f32),
        _ => format!("{:+.9}", x / 1e3),
    }
}

/// Whitespace between numbers: mostly a space, sometimes a line break, a comment, CRLF,
/// tabs or a blank line.
fn gap(rng: &mut Rng) -> &'static str {
    match rng.below(40) {
        0 => "\n# a comment with ] and [ and 1.5x in it\n",
        1 => "\r\n",
        2 => "\t \t",
        3 => "\n\n",
        4..=11 => "\n",
        _ => " ",
    }
}

/// What a generated scene holds, read independently of the parser (`str::parse`, which
/// rounds correctly as every path of the lexer does).
#[derive(Default)]
struct Expected {
    trilist_floats: Vec<u32>,
    indices: Vec<u32>,
    group_vectors: Vec<u32>,
}

/// A scene with a `trilist` of `vertices` lines (layout `p n t 2`) and as many triangles,
/// and a `group` polygon mesh of `vertices` vector lines.
fn mesh_scene(seed: u64, vertices: usize) -> (String, Expected) {
    let mut rng = Rng(seed | 1);
    let mut expected = Expected::default();
    let mut s =
        format!("object \"tri\"\n  visible on\n  trilist vertex {vertices} p n t 2\n  triangle {vertices}\n  [\n");
    for _ in 0..vertices * 8 {
        let x = number(&mut rng);
        expected.trilist_floats.push(x.parse::<f32>().unwrap().to_bits());
        s.push_str(&x);
        s.push_str(gap(&mut rng));
    }
    s.push_str("]\n[");
    for _ in 0..vertices * 3 {
        let i = match rng.below(4) {
            0 => rng.below(10),
            1 => rng.below(10_000_000),
            2 => rng.below(u64::from(u32::MAX) + 1),
            _ => rng.below(vertices.max(1) as u64),
        } as u32;
        expected.indices.push(i);
        let _ = write!(s, "{}{i}", gap(&mut rng));
    }
    s.push_str(" ]\n  end trilist\nend object\n\nobject \"poly\"\n  visible on\n  group\n");
    for _ in 0..vertices {
        for k in 0..3 {
            let x = number(&mut rng);
            expected.group_vectors.push(x.parse::<f32>().unwrap().to_bits());
            s.push_str(&x);
            s.push_str(if k == 2 { "\n" } else { " " });
        }
    }
    for k in 0..vertices {
        let _ = writeln!(s, "v {k}");
    }
    for k in 0..vertices.saturating_sub(2) {
        let _ = writeln!(s, "p {} {} {}", k, k + 1, k + 2);
    }
    s.push_str("  end group\nend object\n");
    (s, expected)
}

/// The ways a list is read: serially, in parallel in pieces of a few lines (boundaries
/// everywhere), of a few kilobytes, and as shipped.
const WAYS: [(usize, usize); 4] = [(usize::MAX, 1), (0, 40), (0, 4096), (crate::lexer::PARALLEL_FROM_BYTES, 256 << 10)];

fn parse_with(way: (usize, usize), text: &str) -> Parsed {
    with_limits(way.0, way.1, || crate::parse_str("mesh.mi", text))
}

/// The messages as a reader sees them: where (file, line, column) and what.
fn messages(parsed: &Parsed) -> Vec<String> {
    parsed
        .diagnostics
        .list
        .iter()
        .map(|d| format!("{}: {} {:?} {:?}", parsed.sources.location(d.span), d.message, d.span, d.notes))
        .collect()
}

#[test]
fn parallel_and_serial_reads_give_identical_trees() {
    for (seed, vertices) in [(1, 0), (2, 1), (3, 7), (4, 300), (5, 5_000), (6, 40_000)] {
        let (text, expected) = mesh_scene(seed, vertices);
        let serial = parse_with(WAYS[0], &text);
        assert_eq!(messages(&serial), Vec::<String>::new(), "{vertices} vertices");
        let tree = format!("{:?}", serial.items);
        for way in &WAYS[1..] {
            let parsed = parse_with(*way, &text);
            assert_eq!(messages(&parsed), Vec::<String>::new(), "{vertices} vertices, {way:?}");
            // Debug prints every float in its shortest round-trip form: equal text, equal bits.
            assert!(format!("{:?}", parsed.items) == tree, "{vertices} vertices, {way:?}: the trees differ");
        }
        // And the numbers are the right ones (independent reader).
        let geometry: Vec<&Geometry> = serial
            .items
            .iter()
            .filter_map(|i| if let Item::Object(o) = i { Some(&o.geometry) } else { None })
            .flatten()
            .collect();
        let [Geometry::Trilist(tri), Geometry::Group(group)] = geometry[..] else { panic!("{geometry:?}") };
        assert!(tri.floats.iter().map(|f| f.to_bits()).eq(expected.trilist_floats.iter().copied()));
        assert_eq!(tri.triangles.indices, expected.indices);
        assert!(group.vectors.iter().flatten().map(|f| f.to_bits()).eq(expected.group_vectors.iter().copied()));
    }
}

/// A long trilist with `bad` in place of the `at`-th vertex number (or, past the vertex
/// numbers, of an index).
fn with_bad_token(text_numbers: usize, at: usize, bad: &str) -> String {
    let mut s = format!("object \"o\"\ntrilist vertex {} p\ntriangle 1\n[\n", text_numbers / 3);
    for k in 0..text_numbers {
        s.push_str(if k == at { bad } else { ["12.5", "-0.125", "3"][k % 3] });
        s.push_str(if k % 3 == 2 { "\n" } else { " " });
    }
    s.push_str("]\n[ 0 1 2 ]\nend trilist\nend object\n");
    s
}

#[test]
fn malformed_numbers_are_reported_where_the_serial_reader_reports_them() {
    let numbers = 30_000;
    // Piece boundaries of the 40-byte pieces fall after a line break: the first and last
    // numbers of a line are a piece's first and last numbers somewhere.
    let places = [0, 1, 2, 3, 5, numbers / 2, numbers / 2 + 2, numbers / 2 + 3, numbers - 3, numbers - 1];
    for bad in ["1.5x", "1e", "-", "--1", "1..2", ".", "\"mat\"", "1.0.0", "0x10"] {
        for &at in &places {
            let text = with_bad_token(numbers, at, bad);
            let serial = parse_with(WAYS[0], &text);
            let expected = messages(&serial);
            assert!(serial.diagnostics.has_errors(), "{bad:?} at {at}: no error");
            // The message points at the bad token's line and column.
            let line = 5 + at / 3;
            let column = 1 + (0..at % 3).map(|k| ["12.5 ", "-0.125 ", "3"][k].len()).sum::<usize>();
            assert!(expected[0].starts_with(&format!("mesh.mi:{line}:{column}")), "{bad:?} at {at}: {}", expected[0]);
            for way in &WAYS[1..] {
                assert_eq!(messages(&parse_with(*way, &text)), expected, "{bad:?} at {at}, {way:?}");
            }
        }
    }
    // Indices: too large for u32, signed, fractional, in the middle and at the end.
    for bad in ["4294967296", "-1", "2.5", "7x"] {
        for at in [0, 1, 6_000, 11_999] {
            let mut text = String::from("object \"o\"\ntrilist vertex 3 p\ntriangle 4000\n[ 0 0 0 1 0 0 0 1 0 ]\n[\n");
            for k in 0..12_000 {
                let index = if k == at { bad.to_string() } else { (k % 3).to_string() };
                let _ = write!(text, "{index}{}", if k % 3 == 2 { "\n" } else { " " });
            }
            text.push_str("]\nend trilist\nend object\n");
            let expected = messages(&parse_with(WAYS[0], &text));
            assert!(!expected.is_empty(), "{bad:?} at {at}: no error");
            let line = 6 + at / 3;
            assert!(expected[0].starts_with(&format!("mesh.mi:{line}:")), "{bad:?} at {at}: {}", expected[0]);
            for way in &WAYS[1..] {
                assert_eq!(messages(&parse_with(*way, &text)), expected, "{bad:?} at {at}, {way:?}");
            }
        }
    }
}

#[test]
fn a_list_the_file_cuts_short_is_an_error_in_every_way() {
    let (text, _) = mesh_scene(9, 5_000);
    let vertex_end = text.find("]\n[").unwrap();
    // Cut in the vertex numbers (mid-number, after a line), and in the indices.
    for cut in [vertex_end / 2, vertex_end / 2 + 3, vertex_end - 1, vertex_end + 10, text.len() / 2] {
        let cut_text = &text[..cut];
        let serial = parse_with(WAYS[0], cut_text);
        assert!(serial.diagnostics.has_errors(), "cut at {cut}: no error");
        let expected = messages(&serial);
        for way in &WAYS[1..] {
            assert_eq!(messages(&parse_with(*way, cut_text)), expected, "cut at {cut}, {way:?}");
        }
    }
}
