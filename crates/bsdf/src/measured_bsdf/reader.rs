//! The reader of NVIDIA's MBSDF files (MDL's `bsdf_measurement` resources), a binary,
//! little-endian format: the line `NVIDIA ARC MBSDF V1`, metadata lines (skipped), then a
//! reflection block (tag line `MBSDF_DATA=` or `MBSDF_DATA_REFLECTION=`) and/or a
//! transmission block (tag line `MBSDF_DATA_TRANSMISSION=`). A block is three `u32`s —
//! the type (0: one scalar per grid point, 1: three, RGB), the resolution of θ (shared by
//! θ_in and θ_out) and of Δφ — and then res_θ² · res_φ · (1 or 3) `f32` BSDF values (1/sr),
//! θ_in outermost, Δφ innermost. Every count is checked against the bytes left in the file
//! before anything is allocated from it; every error names the byte offset it was found at.

use super::{MeasuredBsdf, Part};

/// The first line of every MBSDF file.
const MAGIC: &[u8] = b"NVIDIA ARC MBSDF V1\n";
/// The tag of a reflection block (the old form and the explicit one).
const REFLECTION_TAGS: [&[u8]; 2] = [b"MBSDF_DATA=\n", b"MBSDF_DATA_REFLECTION=\n"];
/// The tag of a transmission block.
const TRANSMISSION_TAG: &[u8] = b"MBSDF_DATA_TRANSMISSION=\n";

/// Most values one block may hold (32 Mi floats, 128 MiB; a 90 × 90 × 180 RGB grid has
/// 4.4 Mi): larger grids are refused rather than allocated.
pub const MAX_VALUES: u64 = 1 << 25;

/// Why a file could not be read: the byte offset and what was wrong there.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadError {
    /// Byte offset from the start of the file.
    pub offset: usize,
    /// What was wrong.
    pub message: String,
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "byte {}: {}", self.offset, self.message)
    }
}

/// A cursor over the file's bytes.
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Cursor<'_> {
    fn error(&self, at: usize, message: impl Into<String>) -> ReadError {
        ReadError { offset: at, message: message.into() }
    }

    /// The next line, its `\n` included; `None` at the end of the file (a last line
    /// without `\n` is returned as it is).
    fn line(&mut self) -> Option<&[u8]> {
        let rest = &self.bytes[self.at..];
        if rest.is_empty() {
            return None;
        }
        let len = rest.iter().position(|&b| b == b'\n').map_or(rest.len(), |p| p + 1);
        self.at += len;
        Some(&rest[..len])
    }

    fn u32(&mut self, what: &str) -> Result<u32, ReadError> {
        let Some(b) = self.bytes.get(self.at..self.at + 4) else {
            return Err(self.error(self.at, format!("the file ends inside the block's {what}")));
        };
        self.at += 4;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// One data block (after its tag line): its grid, negative values read as 0 (counted in
    /// `negatives`).
    fn block(&mut self, negatives: &mut usize) -> Result<Part, ReadError> {
        let start = self.at;
        let kind = self.u32("type")?;
        let channels = match kind {
            0 => 1,
            1 => 3,
            k => return Err(self.error(start, format!("unknown value type {k} (0: scalar, 1: RGB)"))),
        };
        let res_theta = self.u32("θ resolution")?;
        let res_phi = self.u32("φ resolution")?;
        if res_theta == 0 || res_phi == 0 {
            return Err(self.error(start + 4, format!("a resolution of 0 (θ {res_theta}, φ {res_phi})")));
        }
        let count = u64::from(res_theta)
            .checked_mul(u64::from(res_theta))
            .and_then(|n| n.checked_mul(u64::from(res_phi)))
            .and_then(|n| n.checked_mul(channels as u64))
            .unwrap_or(u64::MAX);
        if count > MAX_VALUES {
            return Err(self.error(
                start + 4,
                format!(
                    "a grid of {res_theta}² × {res_phi} × {channels} values, more than the {MAX_VALUES} mira reads"
                ),
            ));
        }
        let left = (self.bytes.len() - self.at) as u64;
        if count * 4 > left {
            return Err(self.error(
                self.at,
                format!("the file ends inside the block: {count} values need {} bytes, {left} are left", count * 4),
            ));
        }
        let mut values = Vec::with_capacity(count as usize);
        for (i, b) in self.bytes[self.at..self.at + count as usize * 4].chunks_exact(4).enumerate() {
            let v = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            if !v.is_finite() {
                return Err(self.error(self.at + 4 * i, format!("a value that is not a finite number ({v})")));
            }
            if v < 0.0 {
                *negatives += 1;
            }
            values.push(v.max(0.0));
        }
        self.at += count as usize * 4;
        Ok(Part::new(res_theta as usize, res_phi as usize, channels, values))
    }
}

/// Reads an MBSDF file's bytes: the measurement, and notes on what was approximated (the
/// number of negative values read as 0, as measurement noise gives). A file whose
/// metadata is followed by no block measures nothing (both parts absent), as the MDL SDK
/// reads it.
pub fn read(bytes: &[u8]) -> Result<(MeasuredBsdf, Vec<String>), ReadError> {
    let mut c = Cursor { bytes, at: 0 };
    if !bytes.starts_with(MAGIC) {
        return Err(c.error(0, "not an MBSDF file (no `NVIDIA ARC MBSDF V1` header line)"));
    }
    c.at = MAGIC.len();
    let mut negatives = 0;
    let mut tag = loop {
        match c.line() {
            None => return Ok((MeasuredBsdf { reflection: None, transmission: None }, Vec::new())),
            Some(l) if REFLECTION_TAGS.contains(&l) || l == TRANSMISSION_TAG => break l,
            Some(_) => {}
        }
    };
    let mut reflection = None;
    if REFLECTION_TAGS.contains(&tag) {
        reflection = Some(c.block(&mut negatives)?);
        let at = c.at;
        tag = match c.line() {
            None => b"",
            Some(l) if l == TRANSMISSION_TAG => l,
            Some(_) => return Err(c.error(at, "after the reflection block: no `MBSDF_DATA_TRANSMISSION=` line")),
        };
    }
    let mut transmission = None;
    if tag == TRANSMISSION_TAG {
        transmission = Some(c.block(&mut negatives)?);
        let at = c.at;
        if bytes[at..].iter().any(|b| !b.is_ascii_whitespace()) {
            return Err(c.error(at, "bytes after the transmission block"));
        }
    }
    let notes = if negatives > 0 { vec![format!("{negatives} negative values read as 0")] } else { Vec::new() };
    Ok((MeasuredBsdf { reflection, transmission }, notes))
}

/// One block an MBSDF file is written with ([`encode`]).
#[derive(Clone, Copy, Debug)]
pub struct Block<'a> {
    /// 1 (scalar) or 3 (RGB) values per grid point.
    pub channels: u32,
    /// Samples of θ.
    pub res_theta: u32,
    /// Samples of Δφ.
    pub res_phi: u32,
    /// The grid as the file lays it out (θ_in outermost, Δφ innermost).
    pub values: &'a [f32],
}

/// The bytes of an MBSDF file holding `reflection` and `transmission` (for tests and
/// tools; the counts are written as given, consistent or not).
pub fn encode(reflection: Option<Block<'_>>, transmission: Option<Block<'_>>) -> Vec<u8> {
    let mut out = MAGIC.to_vec();
    for (tag, block) in [(REFLECTION_TAGS[1], reflection), (TRANSMISSION_TAG, transmission)] {
        let Some(b) = block else { continue };
        out.extend_from_slice(tag);
        for n in [u32::from(b.channels == 3), b.res_theta, b.res_phi] {
            out.extend_from_slice(&n.to_le_bytes());
        }
        for v in b.values {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out
}
