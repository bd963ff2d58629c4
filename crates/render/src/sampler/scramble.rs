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
//! arithmetic only). The refill of the kept sets ([`XorFinish`]) is written in AVX2
//! intrinsics instead, one 256-bit vector from the table's rows to the sampler's buffer:
//! compiled from plain code, LLVM split those eight lanes into pieces.
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

/// The rows of one pair of sets in the nibble table: row `[k][v]` holds the eight lanes
/// of the points whose index nibble `k` is `v` (the sampler's `NibbleTable`).
pub(super) type PairRows = [[[u32; 8]; 16]; 4];

/// The row of `rows` for nibble `k` of `nibbles` (the top 16 bits of the shuffled index).
#[inline(always)]
fn row(rows: &PairRows, nibbles: u32, k: usize) -> &[u32; 8] {
    &rows[k][((nibbles >> (4 * k)) & 15) as usize]
}

/// [`finish`] of the Sobol points that are the lane-wise XOR of four of a pair's rows
/// (two sets of four dimensions; one row a nibble of the shuffled index), in the best
/// build the CPU has: made once per sampler ([`XorFinish::detect`]) so that a refill asks
/// no feature question.
#[derive(Clone, Copy, Debug)]
pub(super) struct XorFinish {
    /// Whether the CPU has AVX2 (only ever true where it was detected; read on x86-64).
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    avx2: bool,
}

impl XorFinish {
    /// The build for this CPU.
    #[inline]
    pub(super) fn detect() -> XorFinish {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            return XorFinish { avx2: true };
        }
        XorFinish { avx2: false }
    }

    /// Writes to `out` the numbers of the points that are the XOR of the rows of `rows`
    /// for the four nibbles of `nibbles` under the scrambles `scramble`: with AVX2 in one
    /// 256-bit vector from the loads to the store (the compiler does not keep eight lanes
    /// of plain code in one vector reliably), else [`finish`] as [`dispatch`] builds it.
    /// The numbers are the same bit for bit either way.
    #[inline(always)]
    pub(super) fn run(self, rows: &PairRows, nibbles: u32, scramble: &[u32; 8], out: &mut [f32; 8]) {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is true only where `detect` found AVX2, the only precondition.
            unsafe { xor_finish_avx2(rows, nibbles, scramble, out) };
            return;
        }
        xor_finish_plain(rows, nibbles, scramble, out);
    }
}

/// [`XorFinish::run`] without AVX2: plain code, built by [`dispatch`].
#[inline(never)]
fn xor_finish_plain(rows: &PairRows, nibbles: u32, scramble: &[u32; 8], out: &mut [f32; 8]) {
    let r = [0, 1, 2, 3].map(|k| row(rows, nibbles, k));
    let mut sobol = [0u32; 8];
    for (lane, point) in sobol.iter_mut().enumerate() {
        *point = r[0][lane] ^ r[1][lane] ^ r[2][lane] ^ r[3][lane];
    }
    *out = dispatch(
        #[inline(always)]
        || finish(sobol, *scramble),
    );
}

/// Bytes that reverse the order of the four bytes of each 32-bit lane (`vpshufb` works
/// within each 128-bit half).
#[cfg(target_arch = "x86_64")]
const BYTE_SWAP: [u8; 32] =
    [3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12, 3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12];

/// The 4-bit reversal of each nibble value, as the high nibble of a byte (for a byte's low
/// nibble) and as its low nibble (for its high nibble), twice (one copy a 128-bit half).
#[cfg(target_arch = "x86_64")]
const NIBBLE_REVERSED_HIGH: [u8; 32] = [
    0x00, 0x80, 0x40, 0xc0, 0x20, 0xa0, 0x60, 0xe0, 0x10, 0x90, 0x50, 0xd0, 0x30, 0xb0, 0x70, 0xf0, 0x00, 0x80, 0x40,
    0xc0, 0x20, 0xa0, 0x60, 0xe0, 0x10, 0x90, 0x50, 0xd0, 0x30, 0xb0, 0x70, 0xf0,
];
#[cfg(target_arch = "x86_64")]
const NIBBLE_REVERSED_LOW: [u8; 32] =
    [0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15, 0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15];

/// [`XorFinish::run`] in AVX2 intrinsics: the XOR of the rows, `owen_scramble_rev`, the bit
/// reversal (bytes swapped, then each byte's nibbles reversed through two lookups) and the
/// conversion to [0, 1) (`u32_to_f32_norm`) of eight lanes.
///
/// # Safety
///
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn xor_finish_avx2(rows: &PairRows, nibbles: u32, scramble: &[u32; 8], out: &mut [f32; 8]) {
    use std::arch::x86_64::*;
    let rows = [0, 1, 2, 3].map(|k| row(rows, nibbles, k));
    // SAFETY (every load and store below): each pointer is to 32 readable (writable)
    // bytes: an array of eight `u32`/`f32` or a 32-byte constant; the unaligned forms.
    let (r0, r1, r2, r3, s) = unsafe {
        (
            _mm256_loadu_si256(rows[0].as_ptr().cast()),
            _mm256_loadu_si256(rows[1].as_ptr().cast()),
            _mm256_loadu_si256(rows[2].as_ptr().cast()),
            _mm256_loadu_si256(rows[3].as_ptr().cast()),
            _mm256_loadu_si256(scramble.as_ptr().cast()),
        )
    };
    let mut n = _mm256_xor_si256(_mm256_xor_si256(r0, r1), _mm256_xor_si256(r2, r3));
    // `sobol_burley::parts::owen_scramble_rev`, lane by lane.
    n = _mm256_xor_si256(n, _mm256_mullo_epi32(n, _mm256_set1_epi32(0x3d20_adea)));
    n = _mm256_add_epi32(n, s);
    n = _mm256_mullo_epi32(n, _mm256_or_si256(_mm256_srli_epi32::<16>(s), _mm256_set1_epi32(1)));
    n = _mm256_xor_si256(n, _mm256_mullo_epi32(n, _mm256_set1_epi32(0x0552_6c56)));
    n = _mm256_xor_si256(n, _mm256_mullo_epi32(n, _mm256_set1_epi32(0x53a2_2864)));
    // `reverse_bits`: the bytes in reverse order, then the bits of each byte.
    let (swap, high, low) = unsafe {
        (
            _mm256_loadu_si256(BYTE_SWAP.as_ptr().cast()),
            _mm256_loadu_si256(NIBBLE_REVERSED_HIGH.as_ptr().cast()),
            _mm256_loadu_si256(NIBBLE_REVERSED_LOW.as_ptr().cast()),
        )
    };
    n = _mm256_shuffle_epi8(n, swap);
    let nibble = _mm256_set1_epi8(0x0f);
    let low_nibbles = _mm256_and_si256(n, nibble);
    let high_nibbles = _mm256_and_si256(_mm256_srli_epi16::<4>(n), nibble);
    n = _mm256_or_si256(_mm256_shuffle_epi8(high, low_nibbles), _mm256_shuffle_epi8(low, high_nibbles));
    // `u32_to_f32_norm`: the top 23 bits as the mantissa of a number in [1, 2), less 1.
    let bits = _mm256_or_si256(_mm256_srli_epi32::<9>(n), _mm256_set1_epi32(0x3f80_0000));
    let numbers = _mm256_sub_ps(_mm256_castsi256_ps(bits), _mm256_set1_ps(1.0));
    unsafe { _mm256_storeu_ps(out.as_mut_ptr(), numbers) };
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
            // The same points as the XOR of four rows, through `XorFinish` (AVX2 where the
            // CPU has it) and the plain build.
            let rows = [s8, h8.map(u32::reverse_bits), s8.map(|v| v.rotate_left(7)), h8.map(|v| !v)];
            let point: [u32; 8] = std::array::from_fn(|i| rows[0][i] ^ rows[1][i] ^ rows[2][i] ^ rows[3][i]);
            let nibbles = sobol[0] >> 16;
            let mut table = [[[0u32; 8]; 16]; 4];
            for (k, row) in rows.iter().enumerate() {
                table[k][((nibbles >> (4 * k)) & 15) as usize] = *row;
            }
            let mut got = [0.0f32; 8];
            XorFinish::detect().run(&table, nibbles, &h8, &mut got);
            assert_eq!(got.map(f32::to_bits), finish(point, h8).map(f32::to_bits), "{rows:x?}");
            let mut plain = [0.0f32; 8];
            xor_finish_plain(&table, nibbles, &h8, &mut plain);
            assert_eq!(plain.map(f32::to_bits), got.map(f32::to_bits), "{rows:x?}");
        }
    }
}
