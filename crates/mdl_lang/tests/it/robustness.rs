//! No input makes the front end panic: random bytes, random token soup, every prefix of the
//! test modules, and very deep nesting all end in `Ok` or an `Error`.

use std::path::PathBuf;

use mdl_lang::{MdlSearchPath, ModuleSet};
use proptest::prelude::*;

fn modules_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/modules")
}

/// Loads `text` as a fresh module named after `n` in `set`; returns whether it loaded.
fn try_load(set: &mut ModuleSet, n: usize, text: &str) -> bool {
    set.load_source(&format!("::fuzz_{n}"), text).is_ok()
}

const TOKENS: &[&str] = &[
    "mdl 1.7;",
    "import",
    "using",
    "export",
    "material",
    "let",
    "in",
    "{",
    "}",
    "(",
    ")",
    "[",
    "]",
    "[[",
    "]]",
    ";",
    ",",
    ":",
    "::",
    "=",
    "==",
    "?",
    "+",
    "*",
    "-",
    "<",
    ">",
    ".",
    "df",
    "::df::*",
    "color",
    "float",
    "float3",
    "bsdf",
    "int",
    "x",
    "tint",
    "1.0",
    "2",
    "\"s\"",
    "struct",
    "enum",
    "if",
    "else",
    "for",
    "while",
    "return",
    "material_surface",
    "surface",
    "scattering",
    "df::diffuse_reflection_bsdf",
    "uniform",
    "const",
    "anno::hidden",
    "(*)",
    "typedef",
    "annotation",
    "module",
    "true",
    "switch",
    "..",
    "\n",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        let mut set = ModuleSet::new(MdlSearchPath::new());
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let _ = set.load_source("::fuzz", &text);
        let prefixed = format!("mdl 1.7;\n{text}");
        let _ = set.load_source("::fuzz2", &prefixed);
    }

    #[test]
    fn random_token_soup_never_panics(picks in proptest::collection::vec(0..TOKENS.len(), 0..80)) {
        let mut set = ModuleSet::new(MdlSearchPath::new());
        let mut text = String::from("mdl 1.7;\nimport ::df::*;\n");
        for p in picks {
            text.push_str(TOKENS[p]);
            text.push(' ');
        }
        let _ = set.load_source("::soup", &text);
    }
}

#[test]
fn every_prefix_of_every_test_module_loads_or_fails_cleanly() {
    let search = MdlSearchPath::for_scene(Some(&modules_dir()), &[], None);
    let mut set = ModuleSet::new(search);
    let mut n = 0;
    let (mut files, mut complete) = (0, 0);
    for entry in std::fs::read_dir(modules_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "mdl") {
            continue;
        }
        files += 1;
        let text = std::fs::read_to_string(&path).unwrap();
        let cuts = (0..text.len()).step_by(3).chain([text.len()]);
        for cut in cuts.filter(|&c| text.is_char_boundary(c)) {
            n += 1;
            let ok = try_load(&mut set, n, &text[..cut]);
            if cut == text.len() && ok {
                complete += 1;
            }
        }
    }
    assert!(n > 1000, "{n} prefixes tried");
    // Whole texts load, but for the two of an import cycle and the one with a missing import.
    assert_eq!(complete, files - 3, "{complete} of {files} whole modules loaded");
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    let mut set = ModuleSet::new(MdlSearchPath::new());
    let deep = format!("mdl 1.7;\nexport float f() = {}1.0{};\n", "(".repeat(100_000), ")".repeat(100_000));
    let err = set.load_source("::deep", &deep).unwrap_err();
    assert!(err.first().message.contains("nested too deeply"), "{err}");
    let minus = format!("mdl 1.7;\nexport float f() = {}1.0;\n", "-".repeat(100_000));
    assert!(set.load_source("::minus", &minus).is_err());
    let blocks = format!("mdl 1.7;\nexport float f() {}return 1.0;{}\n", "{".repeat(100_000), "}".repeat(100_000));
    assert!(set.load_source("::blocks", &blocks).is_err());
    let lets = format!("mdl 1.7;\nexport float f() = {}1.0;\n", "let float x = 1.0; in ".repeat(50_000));
    assert!(set.load_source("::lets", &lets).is_err());
}

/// A long chain of operators (`1.0 + 1.0 + …`, `v.x.x.x…`, `a[0][0]…`) builds a tree as deep
/// as the chain is long without any nesting in the text: each operator counts as a level,
/// so 100 000 of them are an error at the operator past the limit (the chain loaded before,
/// and the passes over its tree, and dropping it, overflowed the stack), and a chain of 150
/// still loads.
#[test]
fn long_operator_chains_are_an_error_not_a_stack_overflow() {
    let mut set = ModuleSet::new(MdlSearchPath::new());
    for (name, body) in [
        ("sum", format!("1.0{}", " + 1.0".repeat(100_000))),
        ("member", format!("float3(1.0){}", ".x".repeat(100_000))),
        ("index", format!("float3(1.0){}", "[0]".repeat(100_000))),
    ] {
        let text = format!("mdl 1.7;\nexport float f() = {body};\n");
        let err = set.load_source(&format!("::{name}"), &text).unwrap_err();
        assert!(err.first().message.contains("expression is nested too deeply"), "{name}: {err}");
    }
    let ok = format!("mdl 1.7;\nexport float f() = 1.0{};\n", " + 1.0".repeat(150));
    assert!(set.load_source("::ok", &ok).is_ok());
}
