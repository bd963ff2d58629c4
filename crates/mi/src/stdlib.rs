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
];

/// The built-in file standing in for an include of `file_name`, if any.
pub fn builtin_name(file_name: &str) -> Option<&'static str> {
    FILES.iter().find(|(n, _)| n.eq_ignore_ascii_case(file_name)).map(|(n, _)| *n)
}

/// The text of built-in file `name`.
pub fn text(name: &str) -> Option<&'static str> {
    FILES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}
