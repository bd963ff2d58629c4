//! What renders that are put together must share: the settings of a farm part's image and
//! of a pre-pass file, as `key=value` text, and the hash a pre-pass file is keyed by.

use render::accel::Backend;

/// The settings of a render as `key=value` lines: what parts of one image must share.
pub(super) fn settings_text(
    settings: &render::Settings,
    size: (u32, u32),
    backend: Backend,
    fg_rays: Option<u32>,
) -> String {
    format!(
        "engine={:?}\nresolution={}x{}\nspp={:?}\nseed={}\nfg_rays={:?}\naccel={:?}\npath={:?}\nband={}",
        settings.engine, size.0, size.1, settings.spp, settings.seed, fg_rays, backend, settings.path, settings.band
    )
}

/// The settings the classic engine's pre-passes depend on, as `key=value` lines: what a
/// pre-pass file must have been computed with (the scene itself is in the hash beside it).
pub fn prepass_settings_text(
    frame: usize,
    size: (u32, u32),
    seed: u32,
    fg_rays: Option<u32>,
    backend: Backend,
) -> String {
    format!("frame={frame}\nresolution={}x{}\nseed={seed}\nfg_rays={fg_rays:?}\naccel={backend:?}", size.0, size.1)
}

/// The hash a pre-pass file is keyed by: the scene's text and the files it reads.
pub fn prepass_scene_hash(text_hash: u64, inputs_hash: u64) -> u64 {
    let mut h = render::pipeline::Fnv::new();
    h.write(&text_hash.to_le_bytes());
    h.write(&inputs_hash.to_le_bytes());
    h.finish()
}
