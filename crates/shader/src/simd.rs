//! Which vector units the CPU has, for integer sample-number code built once more for
//! them: AVX2 (eight 32-bit lanes a vector) and SSE4.1 (whose `pmulld` does a 32-bit
//! multiply in one instruction, and SSSE3's `pshufb` a bit reversal in two nibble
//! lookups), where the binary's baseline x86-64 build (SSE2) emulates both with shuffles
//! and five mask-and-shift rounds. A function built with `#[target_feature]` runs only
//! after these say yes; integer arithmetic only, so every build gives the same bits (see
//! [`crate::site::SitePairs::pairs8`]). The path engine's sampler does the same in
//! `render::sampler::scramble`.

/// Whether the CPU has AVX2 (cached by the standard library after the first call).
#[cfg(target_arch = "x86_64")]
#[inline]
pub fn has_avx2() -> bool {
    std::is_x86_feature_detected!("avx2")
}

/// Whether the CPU has SSE4.1 (cached by the standard library after the first call).
#[cfg(target_arch = "x86_64")]
#[inline]
pub fn has_sse41() -> bool {
    std::is_x86_feature_detected!("sse4.1")
}
