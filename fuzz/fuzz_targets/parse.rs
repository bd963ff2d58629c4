//! Fuzz target for the `.mi` parser.
//!
//! Feeds arbitrary bytes to `mi::parse_source` and checks that it never panics, hangs or
//! blows up in memory, that every diagnostic renders, and that a file that parses without
//! errors round-trips: `parse(print(parse(x))) == parse(x)` with no errors the second time.
//!
//! `$include` of a real path would read the file system: include paths are empty, and the
//! fuzzer must be run from an empty working directory (relative includes of a `Memory`
//! origin resolve against the current directory). The built-in standard declaration files
//! (`base.mi`, …) are still used, as in a normal read.

#![no_main]

use libfuzzer_sys::fuzz_target;

fn options() -> mi::ReadOptions {
    mi::ReadOptions { include_paths: vec![], builtin_declarations: true, max_errors: 50 }
}

fuzz_target!(|data: &[u8]| {
    let options = options();
    let first = mi::parse_source(mi::Origin::Memory("fuzz.mi".into()), data.to_vec(), &options);

    // Every diagnostic must render against the sources it points into.
    for d in &first.diagnostics.list {
        let _ = d.render(&first.sources);
    }
    let _ = first.diagnostics.render(&first.sources);

    if first.diagnostics.has_errors() {
        return;
    }

    // Round trip: the printed tree parses again, without errors, to the same tree.
    let text = mi::print(&first.items);
    let second = mi::parse_source(mi::Origin::Memory("fuzz.mi".into()), text.clone(), &options);
    if second.diagnostics.has_errors() {
        panic!(
            "printed text does not parse:\n{}\n--- printed text ---\n{}",
            second.diagnostics.render(&second.sources),
            String::from_utf8_lossy(&text)
        );
    }
    // NaN (possible in binary data) has no text form: the printer writes it as -1e999. The
    // trees then differ only in those numbers, and printing the second tree gives the same
    // text.
    let nan_only = || text.windows(5).any(|w| w == b"1e999") && mi::print(&second.items) == text;
    if first.items != second.items && !nan_only() {
        panic!(
            "trees differ after printing\n--- printed text ---\n{}\n--- first ---\n{:#?}\n--- second ---\n{:#?}",
            String::from_utf8_lossy(&text),
            first.items,
            second.items
        );
    }
});
