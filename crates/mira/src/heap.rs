//! The C heap's settings for a renderer that frees big arrays (glibc only).
//!
//! glibc's `malloc` serves an allocation of at least its mmap threshold (128 KiB at start)
//! from a mapping of its own, returned to the system when freed; but each such block freed
//! raises the threshold to the block's size (up to 32 MiB), after which blocks of up to that
//! size come from the arenas, where freed space at an arena's top stays resident. Loading a
//! big scene frees many such blocks (the parser's growing lists, the syntax tree), and on
//! the 4 M-triangle heavy scene one of the mesh's vertex arrays (23 MB) then came from a
//! thread's arena, whose top kept about 18 MiB of freed space resident through Embree's
//! build and the render (256², 16 spp: peak 282–287 MB with the moving threshold, 261–263
//! MB fixed). A fixed threshold keeps every big block in a mapping of its own.
#![allow(unsafe_code)]

/// The mmap threshold mira fixes: glibc's own starting value, 128 KiB.
pub const MMAP_THRESHOLD_BYTES: i32 = 128 << 10;

/// Fixes the C heap's mmap threshold at [`MMAP_THRESHOLD_BYTES`] (which also stops glibc
/// from moving it and the trim threshold). Call once at start, before other threads.
pub fn fix_mmap_threshold() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` only changes the allocator's parameters; it is called before any
    // other thread exists, with a parameter and value glibc documents.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD_BYTES);
    }
}

#[cfg(all(test, target_os = "linux", target_env = "gnu"))]
mod tests {
    use super::*;

    /// Bytes glibc holds in mappings of their own (mmapped chunks), all threads.
    fn mapped_bytes() -> usize {
        // SAFETY: `mallinfo2` only reads the allocator's counters.
        unsafe { libc::mallinfo2() }.hblkhd
    }

    /// With the threshold fixed, an 8 MiB block is a mapping of its own even right after a
    /// 30 MiB block was freed (which, with glibc's moving threshold, raises the threshold to
    /// 30 MiB and puts the next 8 MiB block in an arena, where its pages stay resident
    /// after it is freed). Other test threads may free mappings meanwhile, so the
    /// allocation is tried a few times: one try that sees the 8 MiB mapped is the property.
    #[test]
    fn big_blocks_stay_mappings_after_a_bigger_one_is_freed() {
        fix_mmap_threshold();
        const BLOCK: usize = 8 << 20;
        let seen = (0..5).any(|_| {
            let big = std::hint::black_box(vec![1u8; 30 << 20]);
            drop(big);
            let before = mapped_bytes();
            let block = std::hint::black_box(vec![1u8; BLOCK]);
            let grew = mapped_bytes().saturating_sub(before);
            drop(block);
            grew >= BLOCK
        });
        assert!(seen, "an 8 MiB block after a freed 30 MiB one was not given a mapping of its own");
    }
}
