//! A catalogue of malformed files: each gives an error at the right line and column, and
//! none makes the parser panic, hang or allocate without bound.

use std::path::PathBuf;

/// The first error of `text` as (line, column, message).
fn first_error(text: &[u8]) -> (u32, u32, String) {
    let parsed = mi::parse_source(mi::Origin::Memory("bad.mi".into()), text.to_vec(), &mi::ReadOptions::default());
    let d = parsed.diagnostics.list.iter().find(|d| d.is_error()).unwrap_or_else(|| {
        panic!("no error for {:?}", String::from_utf8_lossy(text));
    });
    let (line, col) = parsed.sources.file(d.span.file).line_col(d.span.lo);
    // Rendering must work for every diagnostic.
    let rendered = d.render(&parsed.sources);
    assert!(rendered.starts_with(&format!("bad.mi:{line}:{col}: error: ")), "{rendered}");
    (line, col, d.message.clone())
}

fn check(text: &str, line: u32, col: u32, needle: &str) {
    let (l, c, msg) = first_error(text.as_bytes());
    assert!(msg.contains(needle), "message {msg:?} should contain {needle:?}");
    assert_eq!((l, c), (line, col), "position of {msg:?}");
}

#[test]
fn truncated_block() {
    check("options \"o\"\n    samples 0 2\n", 1, 1, "'options' is not closed by 'end options'");
    check("object \"o\"\n group\n 0 0 0\n", 2, 2, "'group' is not closed");
}

#[test]
fn truncated_parameter_list() {
    check("shader \"s\" \"mib_illum_phong\" (\"diffuse\" 1 0", 1, 30, "parameter list is not closed");
}

#[test]
fn bad_numbers() {
    check("camera \"c\"\n    focal 0.03x5\nend camera", 2, 11, "malformed number '0.03x5'");
    check("options \"o\"\n    samples 1e 2\nend options", 2, 13, "malformed number");
    check("options \"o\"\n    samples 1.5 2\nend options", 2, 13, "expected an integer");
}

#[test]
fn unknown_keywords() {
    check("options \"o\"\n  frobnicate on\nend options", 2, 3, "unknown options statement 'frobnicate'");
    check("blah \"x\"", 1, 1, "unknown keyword 'blah'");
    check("camera \"c\"\n focal 1\n stereo 2\nend camera", 3, 2, "unknown camera statement 'stereo'");
    check("object \"o\"\n group\n 0 0 0\n v 0\n k 0\n end group\nend object", 5, 2, "unknown group statement 'k'");
}

#[test]
fn unbalanced_brackets() {
    check("shader \"s\" \"x\" (\"a\" [1, 2)", 1, 26, "expected ',' or ']'");
    check("shader \"s\" \"x\" (\"a\" {\"b\" 1)", 1, 27, "expected ',' or '}'");
    check("shader \"s\" \"x\" \"a\" 1)", 1, 12, "expected a shader");
}

#[test]
fn unterminated_strings_and_blocks() {
    check("options \"o\n", 1, 9, "string is not closed");
    check("object \"o\" group\n `\x00\x01", 2, 2, "binary block is not closed");
    check("data \"d\" 4 [ '0a0b", 1, 14, "byte string is not closed");
    check("$code\nint x;\n", 1, 1, "'$code' block has no '$end code'");
}

#[test]
fn binary_blocks_cut_short() {
    let mut text = b"object \"o\"\n trilist vertex 2 p\n triangle 0\n scalar `".to_vec();
    text.extend_from_slice(&[0u8; 8]);
    text.extend_from_slice(b"`\n [ ]\n end trilist\nend object\n");
    let (l, c, msg) = first_error(&text);
    assert!(msg.contains("should hold 24 bytes"), "{msg}");
    assert_eq!((l, c), (4, 9));
}

#[test]
fn conditionals_out_of_place() {
    check("$endif\n", 1, 1, "'$endif' without");
    check("$else\n", 1, 1, "'$else' without");
    check("$ifdef \"x\"\noptions \"o\" end options\n", 1, 1, "not closed by '$endif'");
}

#[test]
fn huge_counts_fail_cleanly() {
    check(
        "object \"o\" trilist vertex 1000000000000 p triangle 1 [ ] [ ] end trilist end object",
        1,
        27,
        "out of range",
    );
    check(
        "object \"o\" trilist vertex 4000000000 p n t 3 triangle 1 [ 0 ] [ 0 0 0 ] end trilist end object",
        1,
        12,
        "too large",
    );
    check(
        "object \"o\" trilist vertex 100000000 p triangle 1 [ 0 ] [ 0 0 0 ] end trilist end object",
        1,
        12,
        "bytes of the file are left",
    );
    check("object \"o\" hair scalar [ 3000000000 ] 1 2 hair [ 2 ] 0 1 end hair end object", 1, 12, "file is shorter");
    // Counts that are only hints are checked against what is there, with a warning.
    let parsed = mi::parse_str(
        "bad.mi",
        "object \"o\" group 0 0 0 v 0 ccmesh \"c\" polygon 4000000000 vertex 4000000000 p 0 end ccmesh end group end object",
    );
    assert!(!parsed.diagnostics.has_errors());
    assert!(parsed.diagnostics.list[0].message.contains("declares 4000000000 polygons"));
    check("options \"o\" samples 99999999999999999999 end options", 1, 21, "expected an integer");
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    let deep = format!("shader \"s\" \"x\" (\"a\" {} 1 {})", "[".repeat(100_000), "]".repeat(100_000));
    let (_, _, msg) = first_error(deep.as_bytes());
    assert!(msg.contains("nesting deeper"), "{msg}");
    let ns = "namespace \"n\"\n".repeat(10_000);
    let (_, _, msg) = first_error(ns.as_bytes());
    assert!(msg.contains("nesting deeper"), "{msg}");
    let hira = format!(
        "object \"o\" group 0 0 0 v 0 subdivision surface \"s\" p 0 0 0 {{ {} }} end subdivision surface end group end object",
        "child 0 {".repeat(50_000)
    );
    let (_, _, msg) = first_error(hira.as_bytes());
    assert!(msg.contains("nesting deeper"), "{msg}");
}

#[test]
fn errors_in_one_element_do_not_hide_the_next() {
    let text = "options \"o\"\n  bogus 1\nend options\ncamera \"c\"\n  focal x\nend camera\nrender \"r\" \"c\" \"o\"\n";
    let parsed = mi::parse_str("bad.mi", text);
    let errors: Vec<_> = parsed.diagnostics.list.iter().filter(|d| d.is_error()).collect();
    assert_eq!(errors.len(), 2, "{}", parsed.diagnostics.render(&parsed.sources));
    assert!(matches!(parsed.items.last(), Some(mi::Item::Render(_))));
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mira-test-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn include_loops_are_errors() {
    let dir = temp_dir("loop");
    std::fs::write(dir.join("a.mi"), "$include \"b.mi\"\n").unwrap();
    std::fs::write(dir.join("b.mi"), "options \"o\" end options\n$include \"a.mi\"\n").unwrap();
    let parsed = mi::parse_file(&dir.join("a.mi"), &mi::ReadOptions::default()).unwrap();
    let d = parsed.diagnostics.list.iter().find(|d| d.is_error()).expect("an error");
    assert!(d.message.contains("include loop"), "{}", d.message);
    assert!(d.message.contains("a.mi -> ") && d.message.contains("b.mi"), "{}", d.message);
    let (line, col) = parsed.sources.file(d.span.file).line_col(d.span.lo);
    assert!(parsed.sources.file(d.span.file).name().ends_with("b.mi"));
    assert_eq!((line, col), (2, 11));
}

#[test]
fn missing_include_names_the_file() {
    let dir = temp_dir("missing");
    std::fs::write(dir.join("s.mi"), "$include \"base.mi\"\n$include \"vrayBase.mi\"\n").unwrap();
    let parsed = mi::parse_file(&dir.join("s.mi"), &mi::ReadOptions::default()).unwrap();
    let errors: Vec<_> = parsed.diagnostics.list.iter().filter(|d| d.is_error()).collect();
    assert_eq!(
        errors.len(),
        1,
        "base.mi is built in; only vrayBase.mi (a plug-in library mira does not ship) is missing"
    );
    assert!(errors[0].message.contains("cannot find include file 'vrayBase.mi'"));
    assert_eq!(parsed.sources.file(errors[0].span.file).line_col(errors[0].span.lo), (2, 11));
}

#[test]
fn random_bytes_never_panic() {
    // A deterministic sweep of mutated real text: truncations at every length and byte flips.
    let base = include_str!("../../../../scenes/iray_cornell_box.mi").as_bytes();
    for len in (0..base.len()).step_by(7) {
        let _ = mi::parse_source(mi::Origin::Memory("t.mi".into()), base[..len].to_vec(), &mi::ReadOptions::default());
    }
    let mut state = 0x2545_f491_4f6c_dd1du64;
    for _ in 0..300 {
        let mut text = base.to_vec();
        for _ in 0..8 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let at = (state % text.len() as u64) as usize;
            let alphabet = b"\"`'[]{}()=,#$%.-0123456789\n abcv";
            text[at] = alphabet[(state >> 40) as usize % alphabet.len()];
        }
        let parsed = mi::parse_source(mi::Origin::Memory("t.mi".into()), text, &mi::ReadOptions::default());
        for d in &parsed.diagnostics.list {
            let _ = d.render(&parsed.sources);
        }
    }
}

/// Fuzz finding 3: a registry value that names itself eight times doubles the text on every
/// round; expansion stops at a size cap and the include fails with a short message.
#[test]
fn self_multiplying_registry_value_is_capped() {
    let text = "registry \"{A}\" value \"{A}{A}{A}{A}{A}{A}{A}{A}\" end registry\n$include \"{A}\"\n";
    let (line, col, msg) = first_error(text.as_bytes());
    assert_eq!((line, col), (2, 11));
    assert!(msg.starts_with("cannot find include file") && msg.len() < 400, "{msg}");
}

/// Fuzz finding 4: including a built-in declaration file again adds nothing, and costs
/// nothing (it used to be read and parsed on every include).
#[test]
fn built_in_declaration_files_are_read_once() {
    let text = "$include \"base.mi\"\n".repeat(1000);
    let parsed = mi::parse_source(mi::Origin::Memory("many.mi".into()), text.into_bytes(), &mi::ReadOptions::default());
    assert!(parsed.diagnostics.list.iter().all(|d| !d.is_error()));
    let declares: usize = parsed
        .items
        .iter()
        .map(|i| match i {
            mi::ast::Item::Include(inc) => inc.items.iter().filter(|i| matches!(i, mi::ast::Item::Declare(_))).count(),
            _ => 0,
        })
        .sum();
    let once = mi::parse_str("base.mi", mi::stdlib::text("base.mi").unwrap()).items.len();
    assert_eq!(declares, once);
}
