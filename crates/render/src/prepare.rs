//! Stage 3, **prepare**: what an engine computes over the whole scene before its first
//! pixel — the path engine's environment (its importance table), the classic engine's
//! photon maps and final gather points. The acceleration structure, built before this by
//! [`crate::accel::build`], and the lights, translated with the world, are the other parts
//! of the preparation. Every one of these is the same for any thread count.

use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use shader::Shading;

use crate::accel::Accel;
use crate::engine::EngineKind;
use crate::environment::Environment;
use crate::fgcache::Prepass;
use crate::photons::PhotonStats;
use crate::prepass_file::SavedPrepass;
use crate::world::World;

/// What [`prepare`] computed for one render.
pub struct Prepared<'a> {
    /// The engine the preparation was for ([`EngineKind::Path`] when the classic engine
    /// was asked for without a shading to run).
    pub engine: EngineKind,
    /// The path engine's environment, when the scene has one.
    pub env: Option<Environment<'a>>,
    /// What the classic engine's photon pass did, if it ran (the maps themselves are kept
    /// in the shading).
    pub photons: Option<PhotonStats>,
    /// The classic engine's final gather points, when final gathering uses a cache.
    pub fg: Option<Prepass>,
    /// Time the final gather pre-pass took.
    pub fg_time: Duration,
    /// Time the whole stage took.
    pub time: Duration,
}

/// Prepares a render of `world` by `engine`. The classic engine needs the scene's compiled
/// `shading` (without it the path engine renders). `cancel` stops the pre-passes early
/// with what they have.
pub fn prepare<'a>(
    world: &'a World,
    accel: &'a dyn Accel,
    shading: Option<&'a Shading>,
    engine: EngineKind,
    cancel: &AtomicBool,
) -> Prepared<'a> {
    let start = Instant::now();
    let classic = match (engine, shading) {
        (EngineKind::Classic, Some(s)) => Some(s),
        _ => None,
    };
    // The path engine's environment, its importance grid tabulated now.
    let env = match (classic, shading) {
        (None, Some(s)) => Environment::of_scene(world, accel, s),
        _ => None,
    };
    // The classic engine's photon maps, then its final gather points, before the image.
    let photons = classic.and_then(|s| crate::photons::build(world, accel, s, cancel));
    let fg_start = Instant::now();
    let fg = classic.and_then(|s| crate::fgcache::prepass(world, accel, s, cancel));
    let fg_time = fg_start.elapsed();
    Prepared {
        engine: if classic.is_some() { EngineKind::Classic } else { EngineKind::Path },
        env,
        photons,
        fg,
        fg_time,
        time: start.elapsed(),
    }
}

/// Prepares a classic render from pre-passes saved by an earlier run
/// ([`crate::prepass_file`]) instead of computing them: the photon maps go into `shading`,
/// the final gather cache is rebuilt from the saved points (the same points in the same
/// order give the same cache). `None` when the photon maps of `shading` were already made
/// (a shading is prepared once).
pub fn prepare_saved<'a>(shading: &Shading, saved: SavedPrepass) -> Option<Prepared<'a>> {
    let start = Instant::now();
    if shading.photons.get().is_some() {
        return None;
    }
    let photons = saved.photons.map(|(maps, stats)| {
        let _ = shading.photons.set(maps);
        stats
    });
    let fg_start = Instant::now();
    let nearest = shading.finalgather.cache.and_then(|c| c.nearest());
    let fg = saved.fg.map(|(points, counts, eye_rays)| Prepass {
        cache: shader::fgcache::FgCache::new(points, nearest),
        counts,
        eye_rays,
    });
    Some(Prepared {
        engine: EngineKind::Classic,
        env: None,
        photons,
        fg,
        fg_time: fg_start.elapsed(),
        time: start.elapsed(),
    })
}
