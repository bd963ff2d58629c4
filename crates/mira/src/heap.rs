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
