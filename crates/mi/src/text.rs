//! The bytes of one source file: held on the heap, or mapped read-only from the file on disk.
//!
//! A big scene file (a 4 M-triangle trilist is about 180 MiB of text) is mapped rather than
//! copied: its pages then belong to the file (clean, shared with the page cache, dropped by
//! the kernel under pressure), and the parser hands back the pages of a long number list it
//! has read ([`SourceText::release_pages`]), so that the text and the numbers read from it are
//! not both resident at the end of the parse. A released page is read again from the file if
//! it is touched again (a message quoting a line, a list re-read by the serial path).
//!
//! A mapped file that is truncated while mapped would raise `SIGBUS` on the lost pages; the
//! `sigbus` guard (a private module) puts zero pages there instead and marks the map, and
//! [`SourceText::changed_on_disk`] then reports it (as it reports a file whose length or
//! modification time changed), so that the parse is refused with a message rather than
//! aborting the process.

use std::fmt;
use std::ops::{Deref, Range};
use std::path::Path;
use std::sync::Arc;

/// Files at least this long (bytes) are mapped instead of read; smaller ones are read onto
/// the heap (a map costs a system call and a page-table entry per page for no gain).
pub const MAP_FROM_BYTES: u64 = 1 << 20;

/// Bytes of a source file, shared cheaply between the source map and the lexers.
#[derive(Clone)]
pub struct SourceText(Repr);

#[derive(Clone)]
enum Repr {
    Heap(Arc<[u8]>),
    #[cfg(unix)]
    Mapped(Arc<mapped::MappedFile>),
}

impl SourceText {
    /// Reads `path` of `len` bytes (its length by metadata): mapped when it is long enough
    /// and the platform allows, read onto the heap otherwise.
    pub(crate) fn open(path: &Path, len: u64) -> std::io::Result<SourceText> {
        #[cfg(unix)]
        if len >= MAP_FROM_BYTES {
            if let Some(m) = mapped::MappedFile::open(path, len)? {
                return Ok(SourceText(Repr::Mapped(Arc::new(m))));
            }
        }
        read_heap(path, len as usize).map(|b| SourceText(Repr::Heap(b)))
    }

    /// Whether the bytes are mapped from a file (rather than held on the heap).
    pub fn is_mapped(&self) -> bool {
        match &self.0 {
            Repr::Heap(_) => false,
            #[cfg(unix)]
            Repr::Mapped(_) => true,
        }
    }

    /// Lets the kernel drop the resident pages wholly inside byte range `range` (of a mapped
    /// file; nothing for heap bytes). The bytes stay readable: a page touched again is read
    /// back from the file. Returns the bytes released.
    pub fn release_pages(&self, range: Range<usize>) -> usize {
        match &self.0 {
            Repr::Heap(_) => 0,
            #[cfg(unix)]
            Repr::Mapped(m) => m.release(range),
        }
    }

    /// The bytes as a shared heap buffer: the same buffer for heap bytes, a copy of a map.
    pub fn shared_bytes(&self) -> Arc<[u8]> {
        match &self.0 {
            Repr::Heap(b) => b.clone(),
            #[cfg(unix)]
            Repr::Mapped(m) => Arc::from(m.bytes()),
        }
    }

    /// Whether a mapped file changed on disk since it was mapped (it shrank under the map,
    /// or its length or modification time differ): its bytes may then be a mix of old and
    /// new text. Always `false` for heap bytes.
    pub fn changed_on_disk(&self) -> bool {
        match &self.0 {
            Repr::Heap(_) => false,
            #[cfg(unix)]
            Repr::Mapped(m) => m.changed(),
        }
    }
}

impl Deref for SourceText {
    type Target = [u8];
    fn deref(&self) -> &[u8] {
        match &self.0 {
            Repr::Heap(b) => b,
            #[cfg(unix)]
            Repr::Mapped(m) => m.bytes(),
        }
    }
}

impl AsRef<[u8]> for SourceText {
    fn as_ref(&self) -> &[u8] {
        self
    }
}

impl fmt::Debug for SourceText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = if self.is_mapped() { "mapped" } else { "heap" };
        write!(f, "SourceText({kind}, {} bytes)", self.len())
    }
}

impl From<Arc<[u8]>> for SourceText {
    fn from(b: Arc<[u8]>) -> SourceText {
        SourceText(Repr::Heap(b))
    }
}

impl From<Vec<u8>> for SourceText {
    fn from(b: Vec<u8>) -> SourceText {
        SourceText(Repr::Heap(b.into()))
    }
}

impl From<&[u8]> for SourceText {
    fn from(b: &[u8]) -> SourceText {
        SourceText(Repr::Heap(b.into()))
    }
}

/// The bytes of the file at `path`, `len` long by its metadata, read straight into the
/// shared buffer the source map keeps (a `Vec` turned into an `Arc<[u8]>` would be copied,
/// holding the text twice for a moment). A file whose length changed meanwhile is read
/// whole the ordinary way.
fn read_heap(path: &Path, len: usize) -> std::io::Result<Arc<[u8]>> {
    use std::io::Read;
    let mut file = std::fs::File::open(path)?;
    // `repeat_n` knows its length: the Arc is allocated once, at its final size.
    let mut bytes: Arc<[u8]> = std::iter::repeat_n(0u8, len).collect();
    let whole = match Arc::get_mut(&mut bytes) {
        Some(buf) => file.read_exact(buf).is_ok() && file.read(&mut [0u8; 1])? == 0,
        None => false,
    };
    if whole {
        Ok(bytes)
    } else {
        drop(bytes);
        Ok(std::fs::read(path)?.into())
    }
}

#[cfg(unix)]
#[allow(unsafe_code)]
mod mapped {
    use std::ops::Range;
    use std::path::Path;
    use std::time::SystemTime;

    use memmap2::{Mmap, MmapOptions, UncheckedAdvice};

    use crate::sigbus;

    /// A read-only private map of a whole file, registered with the `SIGBUS` guard.
    pub(super) struct MappedFile {
        // Fields drop in order: the guard is lifted before the map goes.
        guard: sigbus::Registration,
        map: Mmap,
        file: std::fs::File,
        len: u64,
        modified: Option<SystemTime>,
    }

    impl MappedFile {
        /// Maps `path` (expected `len` bytes long). `None` when the map cannot be made
        /// safely (the guard cannot be installed or has no free slot, the length changed):
        /// the caller then reads the file instead.
        pub(super) fn open(path: &Path, len: u64) -> std::io::Result<Option<MappedFile>> {
            let file = std::fs::File::open(path)?;
            let meta = file.metadata()?;
            if meta.len() != len || !meta.is_file() {
                return Ok(None);
            }
            // SAFETY: the map is read-only and private (`MAP_PRIVATE`, `PROT_READ`), so this
            // process never writes through it. What `Mmap` cannot promise by itself is that
            // no other process changes the file meanwhile: a page lost to truncation is
            // covered by the SIGBUS guard registered below before any byte is read (zero
            // bytes instead of a signal), and a change of contents is caught after the
            // parse by `changed` (length, modification time, guard flag), which refuses the
            // parse. The bytes are plain `u8`s: any value is valid.
            let map = match unsafe { MmapOptions::new().len(len as usize).map_copy_read_only(&file) } {
                Ok(m) => m,
                Err(_) => return Ok(None),
            };
            let Some(guard) = sigbus::Registration::new(map.as_ptr() as usize, map.len()) else {
                return Ok(None);
            };
            Ok(Some(MappedFile { guard, map, file, len, modified: meta.modified().ok() }))
        }

        pub(super) fn bytes(&self) -> &[u8] {
            &self.map
        }

        pub(super) fn release(&self, range: Range<usize>) -> usize {
            let page = sigbus::page_size();
            let lo = range.start.div_ceil(page) * page;
            let hi = (range.end.min(self.map.len()) / page) * page;
            if hi <= lo {
                return 0;
            }
            // SAFETY: `MADV_DONTNEED` on a private file map whose pages this process never
            // wrote only drops them from the page tables: a later read faults them in again
            // from the file, with the same bytes, so every `&[u8]` into the map stays valid.
            match unsafe { self.map.unchecked_advise_range(UncheckedAdvice::DontNeed, lo, hi - lo) } {
                Ok(()) => hi - lo,
                Err(_) => 0,
            }
        }

        pub(super) fn changed(&self) -> bool {
            if self.guard.faulted() {
                return true;
            }
            match self.file.metadata() {
                Ok(meta) => meta.len() != self.len || meta.modified().ok() != self.modified,
                Err(_) => true,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_file(name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("mi-text-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    }

    /// A big file is mapped, reads the same bytes as the file, and still reads them after
    /// its pages were released.
    #[test]
    fn mapped_text_survives_released_pages() {
        let bytes: Vec<u8> = (0..3 * MAP_FROM_BYTES as usize).map(|i| (i % 251) as u8).collect();
        let path = temp_file("big.bin", &bytes);
        let text = SourceText::open(&path, bytes.len() as u64).unwrap();
        assert_eq!(text.is_mapped(), cfg!(unix));
        assert_eq!(&*text, &bytes[..]);
        let released = text.release_pages(1..bytes.len() - 1);
        if cfg!(unix) {
            // Whole pages strictly inside the range: all but the first and last page.
            let page = crate::sigbus::page_size();
            assert_eq!(released, ((bytes.len() - 1) / page - 1) * page);
        }
        assert_eq!(&*text, &bytes[..], "released pages read back from the file");
        assert!(!text.changed_on_disk());
        std::fs::remove_dir_all(path.parent().unwrap()).ok();
    }

    /// A mapped file cut short under the map does not kill the process: the lost bytes
    /// read as zeros and the text reports the change.
    #[cfg(unix)]
    #[test]
    fn truncated_mapped_file_reads_zeros_and_reports_the_change() {
        let len = 2 * MAP_FROM_BYTES as usize;
        let path = temp_file("cut.bin", &vec![b'x'; len]);
        let text = SourceText::open(&path, len as u64).unwrap();
        assert!(text.is_mapped());
        let file = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
        file.set_len(4096).unwrap();
        let tail = &text[len - 10..];
        assert_eq!(tail, &[0u8; 10][..], "a page past the new end reads as zeros");
        assert!(text.changed_on_disk());
        std::fs::remove_dir_all(path.parent().unwrap()).ok();
    }

    /// Small files are read onto the heap, where releasing pages does nothing.
    #[test]
    fn small_files_are_read_onto_the_heap() {
        let path = temp_file("small.mi", b"options \"o\" end options\n");
        let text = SourceText::open(&path, 24).unwrap();
        assert!(!text.is_mapped());
        assert_eq!(text.release_pages(0..24), 0);
        assert_eq!(&*text, b"options \"o\" end options\n");
        std::fs::remove_dir_all(path.parent().unwrap()).ok();
    }
}
