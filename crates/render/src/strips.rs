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
//!
//! A render that stops on the clock (`--time`, the scene's progressive max time) gives the
//! first strip the pre-passes' time and its share (by rows) of the rest, and every later
//! strip stops at the samples per pixel the first one reached
//! ([`Settings::stop_at_samples`]): the strips fit together, and the whole takes about the
//! limit when rows cost alike. Such a file is not the one-film render's (nor are two
//! one-film renders stopped by the clock each other's).
//!
//! Memory: a strip's film holds its rows; what the pre-passes made is shared by all strips
//! and grows with the image, not the strip: the final gather points (at most one per grid
//! position of the pre-pass, see [`crate::fgcache`]) and the photon maps (as many photons
//! as the scene asks for).

use std::ops::Range;
use std::time::Duration;

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

/// The settings strip `index` of `strips` renders with: its rows, and how it stops when
/// `settings` or the scene's `options` (progressive max time) stop on the clock. The first strip stops
/// at `prepass_time` (what the pre-passes took, counted in the render's time) plus its
/// share by kept rows of what is left of the limit; later strips stop at `first_spp`, the
/// samples per pixel the first one reached (see the module documentation).
pub fn strip_settings(
    options: &scene::Options,
    settings: &Settings,
    strips: &[Strip],
    index: usize,
    prepass_time: Duration,
    first_spp: u32,
) -> Settings {
    let strip = &strips[index.min(strips.len().saturating_sub(1))];
    let mut s = Settings { rows: Some(strip.render.clone()), ..settings.clone() };
    let scene_limit = options.progressive.max_time.and_then(|t| Duration::try_from_secs_f64(t).ok());
    let Some(limit) = settings.max_time.or(scene_limit) else {
        return s;
    };
    if index == 0 {
        let height = strips.last().map_or(1, |l| l.keep.end).max(1);
        let share = f64::from(strip.keep.end - strip.keep.start) / f64::from(height);
        s.max_time = Some(prepass_time + limit.saturating_sub(prepass_time).mul_f64(share));
    } else {
        s.stop_at_samples = Some(first_spp.max(1));
    }
    s
}

/// Why a farm part cannot be rendered in strips.
pub const PART_PROBLEM: &str = "a farm part is not rendered in strips (a part is rendered in one film of the whole \
                                image and written whole to its part file); render an image too large for one film \
                                in strips in one process";

/// Why `world` cannot be rendered in strips with `settings`, if it cannot: a stop that looks
/// at the whole image (the path engine's convergence test), or a farm part (a part's film
/// is the whole image's, with only its rows sampled; it is written whole to its part file).
pub fn problem(world: &World, settings: &Settings) -> Option<String> {
    let prog = &world.options.progressive;
    if settings.part.is_some() {
        return Some(PART_PROBLEM.into());
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

    /// Under a time limit the first strip gets the pre-passes' time and its share of the
    /// rest, the later ones the first one's samples and no clock; without one, only rows.
    #[test]
    fn a_time_limit_is_shared_by_rows_then_fixed_in_samples() {
        let options = scene::Options::default();
        let f = scene::options::Filter { kind: scene::options::FilterKind::Box, width: 1.0, height: 1.0, clip: false };
        let s = strips(100, 25, EngineKind::Path, &PixelFilter::new(&f), 4);
        let timed = Settings { max_time: Some(Duration::from_secs(10)), ..Settings::default() };
        let first = strip_settings(&options, &timed, &s, 0, Duration::from_secs(2), 0);
        assert_eq!(first.max_time, Some(Duration::from_secs(4)), "2 s of pre-passes + 8 s / 4");
        assert_eq!((first.stop_at_samples, first.rows), (None, Some(0..25)));
        let later = strip_settings(&options, &timed, &s, 3, Duration::from_secs(2), 37);
        assert_eq!((later.stop_at_samples, later.rows), (Some(37), Some(s[3].render.clone())));
        // Pre-passes over the limit leave the first strip no time: it stops after a pass.
        let late = strip_settings(&options, &timed, &s, 0, Duration::from_secs(30), 0);
        assert_eq!(late.max_time, Some(Duration::from_secs(30)));
        let plain = strip_settings(&options, &Settings::default(), &s, 2, Duration::from_secs(2), 5);
        assert_eq!((plain.max_time, plain.stop_at_samples, plain.rows), (None, None, Some(s[2].render.clone())));
    }
}
