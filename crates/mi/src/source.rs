//! Source files and positions: every syntax node points back into the text it came from.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use crate::text::SourceText;

/// Index of a file in a [`SourceMap`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FileId(pub u32);

/// A byte range `lo..hi` in one source file.
///
/// Spans never take part in equality: two syntax trees are equal when they say the same
/// thing, wherever it was written. This is what makes `parse(print(tree)) == tree` testable.
#[derive(Clone, Copy, Debug, Default, Eq)]
pub struct Span {
    /// The file the bytes belong to.
    pub file: FileId,
    /// Offset of the first byte.
    pub lo: u32,
    /// Offset one past the last byte.
    pub hi: u32,
}

impl PartialEq for Span {
    fn eq(&self, _other: &Span) -> bool {
        true
    }
}

impl Span {
    /// A span from `lo` to `hi` in `file`.
    pub fn new(file: FileId, lo: u32, hi: u32) -> Span {
        Span { file, lo, hi }
    }

    /// The span covering both `self` and `other` (which must be in the same file).
    pub fn to(self, other: Span) -> Span {
        Span { file: self.file, lo: self.lo.min(other.lo), hi: self.hi.max(other.hi) }
    }

    /// The empty span at the start of this one.
    pub fn start(self) -> Span {
        Span { file: self.file, lo: self.lo, hi: self.lo }
    }
}

/// Largest source file mira reads, in bytes: spans store 32-bit offsets.
pub const MAX_FILE_SIZE: u64 = u32::MAX as u64 - 1;

/// Where a source file came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Origin {
    /// A file on disk (the path as it was opened).
    Disk(PathBuf),
    /// One of the standard declaration files that mira carries (`base.mi`, …).
    Builtin(&'static str),
    /// Text handed to the parser directly (tests, standard input); the name is for messages.
    Memory(String),
}

/// One source file: its bytes and where lines start.
#[derive(Debug)]
pub struct SourceFile {
    /// Where the text came from.
    pub origin: Origin,
    /// The raw bytes (a `.mi` file may hold binary blocks, so this is not `str`); a big file
    /// read from disk is mapped (see [`crate::text`]).
    pub bytes: SourceText,
    line_starts: OnceLock<Vec<u32>>,
    /// Whether [`SourceMap::release_text`] freed `bytes` (to be read again from disk).
    released: bool,
}

impl SourceFile {
    /// The name used in diagnostics.
    pub fn name(&self) -> String {
        match &self.origin {
            Origin::Disk(p) => p.display().to_string(),
            Origin::Builtin(n) => format!("<builtin>/{n}"),
            Origin::Memory(n) => n.clone(),
        }
    }

    /// The directory that relative `$include`s of this file are looked up in first.
    pub fn dir(&self) -> Option<&Path> {
        match &self.origin {
            Origin::Disk(p) => p.parent(),
            _ => None,
        }
    }

    fn line_starts(&self) -> &[u32] {
        self.line_starts.get_or_init(|| {
            let mut starts = vec![0u32];
            starts.extend(memchr::memchr_iter(b'\n', &self.bytes).map(|i| i as u32 + 1));
            starts
        })
    }

    /// 1-based line and column (in characters) of byte `offset`.
    pub fn line_col(&self, offset: u32) -> (u32, u32) {
        let starts = self.line_starts();
        let line = starts.partition_point(|&s| s <= offset).saturating_sub(1);
        let start = starts[line] as usize;
        let end = (offset as usize).min(self.bytes.len());
        let col = String::from_utf8_lossy(&self.bytes[start..end.max(start)]).chars().count();
        (line as u32 + 1, col as u32 + 1)
    }

    /// The text of 1-based line `line`, without its line break.
    pub fn line_text(&self, line: u32) -> String {
        let starts = self.line_starts();
        let Some(&start) = starts.get(line.saturating_sub(1) as usize) else {
            return String::new();
        };
        let end = starts.get(line as usize).map_or(self.bytes.len(), |&e| e as usize);
        let text = &self.bytes[start as usize..end];
        let text = text.strip_suffix(b"\n").unwrap_or(text);
        let text = text.strip_suffix(b"\r").unwrap_or(text);
        String::from_utf8_lossy(text).into_owned()
    }
}

/// All files read while parsing one scene: the main file and everything it includes.
#[derive(Debug, Default)]
pub struct SourceMap {
    files: Vec<SourceFile>,
}

impl SourceMap {
    /// An empty map.
    pub fn new() -> SourceMap {
        SourceMap::default()
    }

    /// Adds a file and returns its id.
    pub fn add(&mut self, origin: Origin, bytes: impl Into<SourceText>) -> FileId {
        let id = FileId(self.files.len() as u32);
        self.files.push(SourceFile { origin, bytes: bytes.into(), line_starts: OnceLock::new(), released: false });
        id
    }

    /// Frees the text of the files read from disk that are at least `min_bytes` long (once
    /// parsed, a big geometry file's text is not needed until a message quotes it);
    /// returns the bytes freed. Their [`SourceFile::bytes`] are empty until
    /// [`SourceMap::restore_text`] reads them again.
    pub fn release_text(&mut self, min_bytes: usize) -> usize {
        let mut freed = 0;
        for f in &mut self.files {
            if matches!(f.origin, Origin::Disk(_)) && !f.released && f.bytes.len() >= min_bytes {
                freed += f.bytes.len();
                f.bytes = SourceText::from(Vec::new());
                f.line_starts = OnceLock::new();
                f.released = true;
            }
        }
        freed
    }

    /// Whether some file's text was released.
    pub fn has_released_text(&self) -> bool {
        self.files.iter().any(|f| f.released)
    }

    /// Reads the released files again from disk, so that messages can quote them. A file
    /// that cannot be read (or changed length) since is left empty, and the error says which.
    pub fn restore_text(&mut self) -> Result<(), String> {
        let mut problems = Vec::new();
        for f in &mut self.files {
            let Origin::Disk(path) = &f.origin else { continue };
            if !f.released {
                continue;
            }
            match read_source(path) {
                Ok(bytes) => {
                    f.bytes = bytes;
                    f.line_starts = OnceLock::new();
                    f.released = false;
                }
                Err(e) => problems.push(format!("{}: {e}", path.display())),
            }
        }
        if problems.is_empty() {
            Ok(())
        } else {
            Err(format!("cannot read again to quote it: {}", problems.join("; ")))
        }
    }

    /// The file with this id.
    pub fn file(&self, id: FileId) -> &SourceFile {
        &self.files[id.0 as usize]
    }

    /// Every file, in the order they were read.
    pub fn files(&self) -> impl Iterator<Item = (FileId, &SourceFile)> {
        self.files.iter().enumerate().map(|(i, f)| (FileId(i as u32), f))
    }

    /// The bytes a span covers.
    pub fn slice(&self, span: Span) -> &[u8] {
        &self.file(span.file).bytes[span.lo as usize..span.hi as usize]
    }

    /// `file:line:col` of the start of a span.
    pub fn location(&self, span: Span) -> String {
        let file = self.file(span.file);
        let (line, col) = file.line_col(span.lo);
        format!("{}:{}:{}", file.name(), line, col)
    }

    /// The names of the files read from disk that changed there while they were mapped
    /// (see [`SourceText::changed_on_disk`]).
    pub fn changed_on_disk(&self) -> Vec<String> {
        self.files.iter().filter(|f| f.bytes.changed_on_disk()).map(|f| f.name()).collect()
    }
}

/// Reads a source file, refusing files too large for 32-bit spans; files of
/// [`crate::text::MAP_FROM_BYTES`] or more are mapped rather than read.
pub fn read_source(path: &Path) -> Result<SourceText, String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        // A device such as /dev/zero never ends; a directory has no text.
        return Err(if meta.is_dir() { "is a directory".into() } else { "is not a regular file".into() });
    }
    if meta.len() > MAX_FILE_SIZE {
        return Err(format!("file is {} bytes; mira reads .mi files up to 4 GiB", meta.len()));
    }
    SourceText::open(path, meta.len()).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Released text is gone (empty bytes), only for disk files at or above the size, and
    /// read back byte for byte with its lines and columns by `restore_text`.
    #[test]
    fn released_text_is_read_again_from_disk() {
        let dir = std::env::temp_dir().join(format!("mi-release-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("big.mi");
        let text = b"line one\nline two\r\nthird".to_vec();
        std::fs::write(&path, &text).unwrap();
        let mut map = SourceMap::new();
        let big = map.add(Origin::Disk(path.clone()), read_source(&path).unwrap());
        let memory = map.add(Origin::Memory("m.mi".into()), text.clone());
        assert_eq!(&*map.file(big).bytes, &text[..], "read_source reads the whole file");
        assert_eq!(map.release_text(8), text.len(), "only the disk file is released");
        assert!(map.file(big).bytes.is_empty() && map.has_released_text());
        assert_eq!(&*map.file(memory).bytes, &text[..]);
        map.restore_text().unwrap();
        assert!(!map.has_released_text());
        assert_eq!(&*map.file(big).bytes, &text[..]);
        assert_eq!(map.file(big).line_col(13), (2, 5));
        assert_eq!(map.file(big).line_text(2), "line two");
        // Too small to release; a vanished file is an error naming it.
        assert_eq!(map.release_text(1 << 20), 0);
        map.release_text(1);
        std::fs::remove_file(&path).unwrap();
        let e = map.restore_text().unwrap_err();
        assert!(e.contains("big.mi"), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn line_and_column_are_one_based() {
        let mut map = SourceMap::new();
        let id = map.add(Origin::Memory("t.mi".into()), b"ab\ncd\r\nef".to_vec());
        let f = map.file(id);
        assert_eq!(f.line_col(0), (1, 1));
        assert_eq!(f.line_col(1), (1, 2));
        assert_eq!(f.line_col(3), (2, 1));
        assert_eq!(f.line_col(7), (3, 1));
        assert_eq!(f.line_text(2), "cd");
        assert_eq!(f.line_text(3), "ef");
        assert_eq!(map.location(Span::new(id, 8, 9)), "t.mi:3:2");
    }

    #[test]
    fn columns_count_characters_not_bytes() {
        let mut map = SourceMap::new();
        let id = map.add(Origin::Memory("u.mi".into()), "\"é\" x".as_bytes().to_vec());
        assert_eq!(map.file(id).line_col(5), (1, 5));
    }
}
