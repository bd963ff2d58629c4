//! Rendering an image too large for one film as strips of rows, one after the other, each
//! in a film of its own rows (see [`crate::render::Settings::rows`]), so that memory is
//! bounded by a strip, not the image.
//!
//! A strip's kept rows come out bit for bit as in a one-film render, for the reasons a
//! farm part's do (see [`crate::part`]): pixels take the same samples (their seeds depend on
//! the image position), and
//!
//! - the **path engine**'s pixels are independent: a strip renders exactly its rows;
//! - the **classic engine** splats samples over the filter's footprint and compares each
//!   pixel with its four neighbours after its first pass, so a strip also renders a halo
//!   of `⌈filter radius⌉ + 1` rows on each side that it does not keep. The halo's first row
//!   is moved up to a multiple of the band height, so that the bands whose splats reach a
//!   kept row, and the order their sums are added in, are the one-film render's.

use std::ops::Range;

use crate::engine::EngineKind;
use crate::filter::PixelFilter;
use crate::render::Settings;
use crate::world::World;

/// One strip: the rows it keeps and the rows it renders (the kept ones and the halo).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Strip {
    /// Image rows written from this strip.
    pub keep: Range<u32>,
    /// Image rows rendered (a film of these rows; contains `keep`).
    pub render: Range<u32>,
}

/// Strips of `rows` kept rows (the last one shorter) covering an image of `height` rows,
/// rendered by `engine` with `filter`, in bands of `band` rows (the settings' `band`).
pub fn strips(height: u32, rows: u32, engine: EngineKind, filter: &PixelFilter, band: u32) -> Vec<Strip> {
    let rows = rows.max(1);
    let band = band.max(1);
    let halo = match engine {
        EngineKind::Path => 0,
        EngineKind::Classic => filter.radius().1.ceil() as u32 + 1,
    };
    (0..height.div_ceil(rows))
        .map(|i| {
            let keep = i * rows..((i + 1) * rows).min(height);
            let first = keep.start.saturating_sub(halo) / band * band;
            let last = (keep.end + halo).min(height);
            Strip { render: first..last, keep }
        })
        .collect()
}

/// Why `world` cannot be rendered in strips with `settings`, if it cannot: a stop that looks
/// at the clock (strips stopped by it would hold different sample counts) or at the whole
/// image (the path engine's convergence test), or a farm part.
pub fn problem(world: &World, settings: &Settings) -> Option<String> {
    let prog = &world.options.progressive;
    if settings.part.is_some() {
        return Some("a farm part is not rendered in strips".into());
    }
    if settings.max_time.is_some() {
        return Some("strips cannot stop on a time limit (they would differ in samples); drop --time".into());
    }
    if let Some(t) = prog.max_time {
        return Some(format!(
            "the scene stops rendering after {t} s (progressive max time), and strips stopped by the clock do not fit \
             together"
        ));
    }
    if settings.engine == EngineKind::Path && settings.spp.is_none() && prog.quality_enabled {
        return Some("the scene stops the path engine by its convergence over the whole image, which no strip can see; give --spp".into());
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_cover_the_image_once_with_aligned_halos() {
        let f =
            scene::options::Filter { kind: scene::options::FilterKind::Gauss, width: 3.0, height: 3.0, clip: false };
        let filter = PixelFilter::new(&f);
        let ry = filter.radius().1.ceil() as u32;
        let s = strips(100, 16, EngineKind::Classic, &filter, 4);
        assert_eq!(s.len(), 7);
        let mut next = 0;
        for strip in &s {
            assert_eq!(strip.keep.start, next);
            next = strip.keep.end;
            assert_eq!(strip.render.start % 4, 0);
            assert!(strip.render.start + ry < strip.keep.start || strip.render.start == 0);
            assert!(strip.render.end >= (strip.keep.end + ry + 1).min(100));
        }
        assert_eq!(next, 100);
        let p = strips(100, 16, EngineKind::Path, &filter, 4);
        assert!(p.iter().all(|s| s.keep == s.render));
    }
}
