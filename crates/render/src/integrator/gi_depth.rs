//! mental ray's `"gi depth"` string option (GI "Next", `scene::Options::gi_depth`) as the
//! path engine's depth: `"gi depth" n` with `"gi" on` allows n indirect bounces, so a path
//! traces at most n + 1 rays (the camera ray, whose hit takes its direct light, then one
//! ray per bounce). The bound counts every scattering event after the first, whatever its
//! kind (mira's path engine has one depth). `"gi rays"` changes nothing here: a path tracer
//! follows one ray per bounce (see `scene::options::modes`).

use super::PathSettings;

impl PathSettings {
    /// These settings with the scene's `"gi depth"` as the depth where `"gi" on` sets it
    /// (`max_depth` = indirect bounces + 1); unchanged otherwise.
    pub fn with_scene_options(self, options: &scene::Options) -> PathSettings {
        match options.gi_depth() {
            Some(bounces) => PathSettings { max_depth: bounces.saturating_add(1), ..self },
            None => self,
        }
    }
}
