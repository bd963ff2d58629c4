//! Round trip: `parse(print(parse(f))) == parse(f)` for every scene shipped in the
//! repository and every test file, and for any directory named by `MI_CORPUS` (a local
//! corpus of real files: `MI_CORPUS=/path/to/corpus cargo test -p mi --test it roundtrip::`).

use std::path::{Path, PathBuf};

fn mi_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            mi_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "mi") {
            out.push(p);
        }
    }
}

/// Parses `path`, prints the tree, parses the text again in the same directory (so that
/// includes resolve alike) and compares the trees.
fn round_trip(path: &Path) -> Result<(), String> {
    let options = mi::ReadOptions::default();
    let first = mi::parse_file(path, &options).map_err(|e| e.to_string())?;
    if first.diagnostics.has_errors() {
        // Files with errors (missing includes of other products) are not compared.
        return Ok(());
    }
    let text = mi::print(&first.items);
    let origin = mi::Origin::Disk(path.with_file_name("__roundtrip__.mi"));
    let second = mi::parse_source(origin, text.clone(), &options);
    if second.diagnostics.has_errors() {
        return Err(format!(
            "{}: printed text does not parse:\n{}",
            path.display(),
            second.diagnostics.render(&second.sources)
        ));
    }
    if first.items != second.items {
        let dump = std::env::temp_dir().join("mira-roundtrip.mi");
        let _ = std::fs::write(&dump, &text);
        return Err(format!(
            "{}: trees differ after printing (printed text in {}):\n{}",
            path.display(),
            dump.display(),
            first_difference(&first.items, &second.items)
        ));
    }
    Ok(())
}

/// The first differing item of two trees, both sides shown.
fn first_difference(a: &[mi::Item], b: &[mi::Item]) -> String {
    if a.len() != b.len() {
        return format!("{} items before, {} after", a.len(), b.len());
    }
    for (x, y) in a.iter().zip(b) {
        if x != y {
            if let (mi::Item::Include(ix), mi::Item::Include(iy)) = (x, y) {
                return first_difference(&ix.items, &iy.items);
            }
            let (dx, dy) = (format!("{x:?}"), format!("{y:?}"));
            let at = dx.bytes().zip(dy.bytes()).position(|(p, q)| p != q).unwrap_or(0);
            let from = at.saturating_sub(200);
            return format!(
                "before: …{}…\nafter:  …{}…",
                &dx[from..(at + 200).min(dx.len())],
                &dy[from..(at + 200).min(dy.len())]
            );
        }
    }
    String::from("(no difference found)")
}

#[test]
fn repository_scenes_round_trip() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = Vec::new();
    mi_files(&root.join("scenes"), &mut files);
    mi_files(&root.join("crates/mi/tests/data"), &mut files);
    assert!(files.len() >= 2, "scenes are missing");
    let failures: Vec<String> = files.iter().filter_map(|f| round_trip(f).err()).collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn builtin_declarations_round_trip() {
    for (name, text) in mi::stdlib::FILES {
        let first = mi::parse_str(name, text);
        assert!(!first.diagnostics.has_errors(), "{name}: {}", first.diagnostics.render(&first.sources));
        let printed = mi::print(&first.items);
        let second = mi::parse_str(name, std::str::from_utf8(&printed).unwrap());
        assert!(!second.diagnostics.has_errors(), "{name} printed: {}", second.diagnostics.render(&second.sources));
        assert!(first.items == second.items, "{name}: trees differ after printing");
    }
}

#[test]
fn corpus_round_trips() {
    let Some(dir) = std::env::var_os("MI_CORPUS") else { return };
    let mut files = Vec::new();
    mi_files(Path::new(&dir), &mut files);
    let failures: Vec<String> = files.iter().filter_map(|f| round_trip(f).err()).collect();
    assert!(failures.is_empty(), "{} of {} files:\n{}", failures.len(), files.len(), failures.join("\n"));
}

/// Fuzz finding 4 (`fuzz/seeds/parse/found-4.mi`, the parse target's 68 k-th execution in
/// issue 15's campaign): a `$lookup` key holding a quote was printed with a backslash
/// escape, which the preprocessor (reading the directive's line as written) kept. Keys with
/// quotes, `#` and backslashes now print back to the same tree.
#[test]
fn lookup_keys_round_trip() {
    for text in [
        "$lookup \"{key}\"\n",
        "$lookup EY}R\"MG{\"\n",
        "$lookup a\"b#c\n",
        "$lookup \"a#b\" # comment\n",
        "$lookup back\\slash\n",
    ]
    .map(str::as_bytes)
    .into_iter()
    .chain([&include_bytes!("../../../../fuzz/seeds/parse/found-4.mi")[..]])
    {
        let first = mi::parse_source(mi::Origin::Memory("l.mi".into()), text.to_vec(), &Default::default());
        let printed = mi::print(&first.items);
        let second = mi::parse_source(mi::Origin::Memory("l.mi".into()), printed.clone(), &Default::default());
        assert_eq!(
            first.items,
            second.items,
            "{:?} printed as {:?}",
            String::from_utf8_lossy(text),
            String::from_utf8_lossy(&printed)
        );
    }
}

/// Fuzz finding 5 (`fuzz/seeds/parse/found-5.mi`, issue 15's second parse campaign): an
/// instgroup's members were printed after its statements, so a flag attribute without a
/// value (`attribute hide`) took the first quoted member as its value. Members are now
/// printed first.
#[test]
fn instgroup_members_after_a_bare_flag_attribute_round_trip() {
    for text in [
        &b"instgroup \"g\"\n    attribute hide\n    a \"b\"\nend instgroup\n"[..],
        &include_bytes!("../../../../fuzz/seeds/parse/found-5.mi")[..],
    ] {
        let first = mi::parse_source(mi::Origin::Memory("g.mi".into()), text.to_vec(), &Default::default());
        assert!(!first.diagnostics.has_errors(), "{}", first.diagnostics.render(&first.sources));
        let printed = mi::print(&first.items);
        let second = mi::parse_source(mi::Origin::Memory("g.mi".into()), printed.clone(), &Default::default());
        assert_eq!(first.items, second.items, "printed as {:?}", String::from_utf8_lossy(&printed));
    }
}
