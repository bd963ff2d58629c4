//! The last steps of a set of four Sobol dimensions: Burley's hashed Owen scramble of the
//! bit-reversed points, the bit reversal back and the conversion to numbers in [0, 1) —
//! exactly `sobol_burley::parts::owen_scramble_int4_rev(..).reverse_bits().to_f32_norm()`
//! — and the choice of instructions they run with.
//!
//! The scramble's four 32-bit multiplies per lane are one instruction each with SSE4.1's
//! `pmulld`, which a baseline x86-64 build may not use (sobol_burley then emulates them
//! with SSE2 shuffles), and the bit reversal is two nibble lookups with SSSE3's `pshufb`
//! instead of five mask-and-shift rounds. So on x86-64 the sampler's set computation is
//! also compiled for SSE4.1 (which implies SSSE3) and for AVX2 (eight lanes a vector: the
//! sampler makes two sets at once), and [`dispatch`] picks the best build the CPU has at
//! run time (SSE4.1: every x86-64 CPU since about 2008; AVX2: since about 2013): the binary
//! still runs on any x86-64, and the numbers are the same bit for bit either way (integer
//! arithmetic only).
#![allow(unsafe_code)]

use sobol_burley::parts;

/// Scrambles the bit-reversed Sobol points `sobol_rev` (one dimension per lane) with the
/// hashed scrambles `scramble`, reverses their bits and turns them into numbers in [0, 1),
/// lane by lane in plain integer code, which the compiler turns into the vector
/// instructions of whatever target features its caller is built for.
#[inline(always)]
pub(super) fn finish<const N: usize>(sobol_rev: [u32; N], scramble: [u32; N]) -> [f32; N] {
    let mut out = [0.0; N];
    for ((o, &n), &s) in out.iter_mut().zip(&sobol_rev).zip(&scramble) {
        *o = parts::u32_to_f32_norm(parts::owen_scramble_rev(n, s).reverse_bits());
    }
    out
}

/// Runs `work` (which should inline [`finish`]) built for AVX2 (eight 32-bit lanes a
/// vector) or SSE4.1 when the CPU has it, else built for the binary's baseline target.
#[inline(always)]
pub(super) fn dispatch<R>(work: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2 (checked just above), the only precondition of
        // `with_avx2`.
        return unsafe { with_avx2(work) };
    }
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("sse4.1") {
        // SAFETY: the CPU has SSE4.1 (checked just above), the only precondition of
        // `with_sse41`.
        return unsafe { with_sse41(work) };
    }
    work()
}

/// Calls `work`, inlined into a function built with AVX2 (and the SSE4.1 it implies).
///
/// # Safety
///
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn with_avx2<R>(work: impl FnOnce() -> R) -> R {
    work()
}

/// Calls `work`, inlined into a function built with SSE4.1 (and the SSSE3 it implies).
///
/// # Safety
///
/// The CPU must support SSE4.1.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "sse4.1")]
#[inline]
unsafe fn with_sse41<R>(work: impl FnOnce() -> R) -> R {
    work()
}

#[cfg(test)]
mod tests {
    use super::*;
    use sobol_burley::parts::Int4;

    /// Inputs spread over all 32 bits: a SplitMix64 stream.
    fn words(n: usize) -> Vec<[u32; 4]> {
        let mut z = 0x0123_4567_89ab_cdefu64;
        let mut next = move || {
            z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut x = z;
            x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            (x ^ (x >> 31)) as u32
        };
        (0..n).map(|_| [next(), next(), next(), next()]).collect()
    }

    /// [`finish`] in the baseline build and in the SSE4.1 build (where the CPU has it)
    /// gives sobol_burley's numbers bit for bit, edge values included.
    #[test]
    fn both_builds_give_sobol_burleys_numbers() {
        let mut inputs = words(20_000);
        inputs.push([0, u32::MAX, 1, 0x8000_0000]);
        inputs.push([u32::MAX; 4]);
        inputs.push([0; 4]);
        for pair in inputs.windows(2) {
            let (sobol, scramble) = (pair[0], pair[1]);
            let want = parts::owen_scramble_int4_rev(Int4::from(sobol), Int4::from(scramble))
                .reverse_bits()
                .to_f32_norm()
                .map(f32::to_bits);
            assert_eq!(finish(sobol, scramble).map(f32::to_bits), want, "{sobol:x?} {scramble:x?}");
            assert_eq!(dispatch(|| finish(sobol, scramble)).map(f32::to_bits), want, "{sobol:x?} {scramble:x?}");
            #[cfg(target_arch = "x86_64")]
            if std::is_x86_feature_detected!("sse4.1") {
                // SAFETY: checked just above.
                let got = unsafe { with_sse41(|| finish(sobol, scramble)) };
                assert_eq!(got.map(f32::to_bits), want, "{sobol:x?} {scramble:x?}");
            }
            #[cfg(target_arch = "x86_64")]
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: checked just above.
                let got = unsafe { with_avx2(|| finish(sobol, scramble)) };
                assert_eq!(got.map(f32::to_bits), want, "{sobol:x?} {scramble:x?}");
            }
            // Eight lanes at once (two sets): each half as four lanes give it.
            let (s8, h8) = ([sobol, scramble].concat(), [scramble, sobol].concat());
            let (s8, h8): ([u32; 8], [u32; 8]) = (s8.try_into().unwrap(), h8.try_into().unwrap());
            let mut want8 = finish(sobol, scramble).to_vec();
            want8.extend(finish(scramble, sobol));
            let got8 = dispatch(|| finish(s8, h8));
            assert_eq!(got8.map(f32::to_bits).to_vec(), want8.iter().map(|v| v.to_bits()).collect::<Vec<_>>());
        }
    }
}
