//! The standard declaration files mira carries, so that `$include "base.mi"` and friends
//! resolve on machines without a mental ray installation. Written from the public
//! documentation; see `crates/mi/std/README.md`.

/// (file name, text) of every built-in declaration file.
pub const FILES: &[(&str, &str)] = &[
    ("base.mi", include_str!("../std/base.mi")),
    ("physics.mi", include_str!("../std/physics.mi")),
    ("contour.mi", include_str!("../std/contour.mi")),
    ("architectural.mi", include_str!("../std/architectural.mi")),
    ("production.mi", include_str!("../std/production.mi")),
    ("mayabase.mi", include_str!("../std/mayabase.mi")),
    ("AdskShaderSDK.mi", include_str!("../std/AdskShaderSDK.mi")),
    ("MayaShaders.mi", include_str!("../std/MayaShaders.mi")),
    ("coreutil.mi", include_str!("../std/coreutil.mi")),
    ("object_light_phen.mi", include_str!("../std/object_light_phen.mi")),
    ("lookdevKitMR.mi", include_str!("../std/lookdevKitMR.mi")),
    ("syncolor_shaders.mi", include_str!("../std/syncolor_shaders.mi")),
];

/// The built-in file standing in for an include of `file_name`, if any.
pub fn builtin_name(file_name: &str) -> Option<&'static str> {
    FILES.iter().find(|(n, _)| n.eq_ignore_ascii_case(file_name)).map(|(n, _)| *n)
}

/// The text of built-in file `name`.
pub fn text(name: &str) -> Option<&'static str> {
    FILES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}
