//! Rendering one part of an image (for a render farm): which rows part K of N owns, which it
//! must render so that its owned pixels come out bit for bit as in a one-process render,
//! and the checks that such a split is possible.
//!
//! Parts are pixel rows, not sample-index ranges: a pixel's accumulators are f64 sums in
//! sample order, and adding two partial sums rounds differently from adding the samples
//! one by one, so only whole pixels merge bit-exactly.
//!
//! - The **path engine** ([`Split::Interleaved`]): row y belongs to part `y mod N + 1`.
//!   Pixels are independent (each samples its own filter footprint), so a part renders
//!   exactly its rows, and interleaving gives every part the same mix of cheap and costly
//!   rows (sky, walls, light).
//! - The **classic engine** ([`Split::Spans`]): part K owns the contiguous rows
//!   `⌊(K−1)·H/N⌋ … ⌊K·H/N⌋`. Its samples are splatted over the pixel filter's footprint,
//!   and the adaptive sampler compares each pixel with its four neighbours after the first
//!   pass, so a part also renders a halo of `⌈filter radius⌉ + 1` rows on each side (their
//!   samples reach its rows; their first-pass colours decide its rows' sample counts).
//!   Interleaved rows would make the halo the whole image.
//!
//! Pre-passes (photon maps, final gather points, the environment's importance table) are
//! computed by every part over the whole image, or read from a file that `mira prepass`
//! wrote once ([`crate::prepass_file`]); they are deterministic for any thread count, so
//! every part's copy is the same.

use crate::engine::EngineKind;

/// Part `index` of `count` (1 ≤ index ≤ count).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Part {
    /// Which part, from 1.
    pub index: u32,
    /// How many parts.
    pub count: u32,
}

impl Part {
    /// Parses `K/N`.
    pub fn parse(s: &str) -> Result<Part, String> {
        let bad = || format!("'{s}' is not a part: give K/N with 1 ≤ K ≤ N, e.g. 2/4");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let index: u32 = k.trim().parse().map_err(|_| bad())?;
        let count: u32 = n.trim().parse().map_err(|_| bad())?;
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Part { index, count })
    }
}

impl std::fmt::Display for Part {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// How an image is cut into parts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Split {
    /// Row y to part `y mod N + 1` (the path engine).
    Interleaved,
    /// Contiguous spans of rows, each rendered with a halo (the classic engine).
    Spans,
}

impl Split {
    /// The split an engine's parts use.
    pub fn for_engine(engine: EngineKind) -> Split {
        match engine {
            EngineKind::Path => Split::Interleaved,
            EngineKind::Classic => Split::Spans,
        }
    }

    /// The split's name in part files.
    pub fn name(self) -> &'static str {
        match self {
            Split::Interleaved => "interleaved-rows",
            Split::Spans => "row-spans",
        }
    }

    /// The split named `name`.
    pub fn from_name(name: &str) -> Option<Split> {
        [Split::Interleaved, Split::Spans].into_iter().find(|s| s.name() == name)
    }

    /// The rows (from the top) that `part` owns in an image `height` rows high, in order.
    pub fn owned_rows(self, part: Part, height: u32) -> Vec<u32> {
        let (k, n) = (part.index - 1, part.count.max(1));
        match self {
            Split::Interleaved => (0..height).filter(|y| y % n == k).collect(),
            Split::Spans => {
                let (a, b) = span(part, height);
                (a..b).collect()
            }
        }
    }

    /// Which rows `part` renders: its own and, for [`Split::Spans`], `halo` rows on each
    /// side.
    pub fn rendered_rows(self, part: Part, height: u32, halo: u32) -> Vec<bool> {
        let mut on = vec![false; height as usize];
        match self {
            Split::Interleaved => {
                for y in self.owned_rows(part, height) {
                    on[y as usize] = true;
                }
            }
            Split::Spans => {
                let (a, b) = span(part, height);
                if a < b {
                    let lo = a.saturating_sub(halo);
                    let hi = (b + halo).min(height);
                    on[lo as usize..hi as usize].fill(true);
                }
            }
        }
        on
    }
}

/// Rows `[a, b)` of a span part.
fn span(part: Part, height: u32) -> (u32, u32) {
    let (k, n, h) = (u64::from(part.index - 1), u64::from(part.count.max(1)), u64::from(height));
    ((k * h / n) as u32, ((k + 1) * h / n) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every row is owned by exactly one part, for both splits, even and uneven counts.
    #[test]
    fn parts_cover_every_row_once() {
        for split in [Split::Interleaved, Split::Spans] {
            for (h, n) in [(32, 4), (31, 3), (5, 7), (1, 1), (100, 6)] {
                let mut owners = vec![0u32; h as usize];
                for k in 1..=n {
                    for y in split.owned_rows(Part { index: k, count: n }, h) {
                        owners[y as usize] += 1;
                    }
                }
                assert!(owners.iter().all(|&c| c == 1), "{split:?} h={h} n={n}: {owners:?}");
            }
        }
    }

    /// A span part renders its rows and `halo` rows around them, clipped to the image.
    #[test]
    fn span_halo_is_clipped() {
        let on = Split::Spans.rendered_rows(Part { index: 2, count: 3 }, 30, 2);
        let rows: Vec<usize> = (0..30).filter(|&y| on[y]).collect();
        assert_eq!(rows, (8..22).collect::<Vec<_>>());
        let first = Split::Spans.rendered_rows(Part { index: 1, count: 3 }, 30, 2);
        assert_eq!((0..30).filter(|&y| first[y]).count(), 12);
    }

    #[test]
    fn parses_parts() {
        assert_eq!(Part::parse("2/4"), Ok(Part { index: 2, count: 4 }));
        for bad in ["0/4", "5/4", "x/4", "3", "1/0"] {
            assert!(Part::parse(bad).is_err(), "{bad}");
        }
        assert_eq!(Split::from_name(Split::Spans.name()), Some(Split::Spans));
    }
}
