//! Big scene files are mapped from disk rather than read onto the heap (`mi::text`): parsing
//! one gives the same tree as parsing the same bytes from memory, an error in one quotes
//! its line (the pages the parser handed back are read again from the file), and a mapped
//! file cut short under the parser gives an error, not a crash.

use std::path::PathBuf;

/// A trilist object of `vertices` position lines and `vertices / 2` triangles (the vertex
/// list is over 1 MiB, so it is read by the parallel path, which releases its pages), with
/// vertex line `bad` (if any) written `1.25 -3.5x 0.125`. Vertex `i` is on line `5 + i`.
fn big_trilist(vertices: usize, bad: Option<usize>) -> String {
    let triangles = vertices / 2;
    let mut text = format!("object \"big\"\n  trilist vertex {vertices} p\n  triangle {triangles}\n  [\n");
    for i in 0..vertices {
        if Some(i) == bad {
            text.push_str("1.25 -3.5x 0.125\n");
        } else {
            text.push_str(&format!("{} {} {}\n", i as f32 * 0.5, -(i as f32) * 0.25, (i % 7) as f32 + 0.125));
        }
    }
    text.push_str("  ]\n  [\n");
    for t in 0..triangles {
        text.push_str(&format!("{} {} {}\n", t, (t + 1) % vertices, (t + 2) % vertices));
    }
    text.push_str("  ]\n  end trilist\nend object\n");
    text
}

fn temp_file(name: &str, text: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mi-mapped-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The tree read from a mapped file equals the tree read from the same bytes in memory,
/// and the vertex numbers are the ones written.
#[test]
fn a_mapped_file_parses_like_a_buffer() {
    let text = big_trilist(200_000, None);
    assert!(text.len() as u64 > 2 * mi::text::MAP_FROM_BYTES);
    let path = temp_file("same.mi", text.as_bytes());
    let mapped = mi::parse_file(&path, &mi::ReadOptions::default()).unwrap();
    let (_, root) = mapped.sources.files().next().unwrap();
    assert_eq!(root.bytes.is_mapped(), cfg!(unix), "a {} byte file is mapped", text.len());
    assert!(!mapped.diagnostics.has_errors(), "{}", mapped.diagnostics.render(&mapped.sources));
    let buffered =
        mi::parse_source(mi::Origin::Memory("same.mi".into()), text.clone().into_bytes(), &mi::ReadOptions::default());
    assert!(!buffered.sources.files().next().unwrap().1.bytes.is_mapped());
    assert_eq!(mapped.items, buffered.items);
    // The bytes are still all there after the parser released the list's pages.
    assert_eq!(&*root.bytes, text.as_bytes());
    std::fs::remove_dir_all(path.parent().unwrap()).ok();
}

/// A malformed number deep in a mapped list: the parallel path gives the list up after
/// releasing the pages it read, the serial path reads them again and reports the number at
/// its line, and the message quotes that line.
#[test]
fn an_error_in_a_mapped_file_quotes_its_line() {
    let bad = 150_000;
    let text = big_trilist(200_000, Some(bad));
    let path = temp_file("bad.mi", text.as_bytes());
    let parsed = mi::parse_file(&path, &mi::ReadOptions::default()).unwrap();
    assert_eq!(parsed.sources.files().next().unwrap().1.bytes.is_mapped(), cfg!(unix));
    let d = parsed.diagnostics.list.iter().find(|d| d.is_error()).expect("the bad number is an error");
    let (line, _) = parsed.sources.file(d.span.file).line_col(d.span.lo);
    assert_eq!(line as usize, 5 + bad, "{}", d.message);
    let rendered = d.render(&parsed.sources);
    assert!(rendered.contains(&format!("bad.mi:{line}:")), "{rendered}");
    assert!(rendered.contains("\n    1.25 -3.5x 0.125\n"), "the line is quoted: {rendered}");
    std::fs::remove_dir_all(path.parent().unwrap()).ok();
}

/// A mapped file truncated before it is parsed: the lost pages read as zeros (no `SIGBUS`)
/// and the parse ends with an error saying the file changed on disk.
#[cfg(unix)]
#[test]
fn a_file_cut_short_under_the_map_is_an_error_not_a_crash() {
    let text = big_trilist(200_000, None);
    let path = temp_file("cut.mi", text.as_bytes());
    let bytes = mi::source::read_source(&path).unwrap();
    assert!(bytes.is_mapped());
    std::fs::OpenOptions::new().write(true).open(&path).unwrap().set_len(1 << 16).unwrap();
    let parsed = mi::parse_source(mi::Origin::Disk(path.clone()), bytes, &mi::ReadOptions::default());
    let changed =
        parsed.diagnostics.list.iter().find(|d| d.message.contains("changed on disk while it was being read"));
    assert!(changed.is_some_and(|d| d.is_error()), "{}", parsed.diagnostics.render(&parsed.sources));
    std::fs::remove_dir_all(path.parent().unwrap()).ok();
}
