//! mira's built-in standard modules: declarations (no bodies) of the MDL standard library,
//! written as MDL text in `crates/mdl_lang/std/`, and the language prelude (the `material`
//! struct and its parts).

/// Absolute name of the prelude: the types built into the language, visible everywhere.
pub const PRELUDE: &str = "::<builtin>";

/// A built-in module: its absolute name, the file name used in messages, and its text.
#[derive(Clone, Copy, Debug)]
pub struct StdModule {
    /// Absolute module name (`::df`).
    pub name: &'static str,
    /// The name shown in diagnostics (`df.mdl`).
    pub file: &'static str,
    /// The MDL source.
    pub text: &'static str,
    /// Whether a module of the same name on the search path is read instead.
    pub overridable: bool,
}

/// Every built-in module.
pub const STD_MODULES: &[StdModule] = &[
    StdModule { name: PRELUDE, file: "prelude.mdl", text: include_str!("../std/prelude.mdl"), overridable: false },
    StdModule { name: "::anno", file: "anno.mdl", text: include_str!("../std/anno.mdl"), overridable: false },
    StdModule { name: "::limits", file: "limits.mdl", text: include_str!("../std/limits.mdl"), overridable: false },
    StdModule { name: "::math", file: "math.mdl", text: include_str!("../std/math.mdl"), overridable: false },
    StdModule { name: "::state", file: "state.mdl", text: include_str!("../std/state.mdl"), overridable: false },
    StdModule { name: "::tex", file: "tex.mdl", text: include_str!("../std/tex.mdl"), overridable: false },
    StdModule { name: "::df", file: "df.mdl", text: include_str!("../std/df.mdl"), overridable: false },
    StdModule { name: "::scene", file: "scene.mdl", text: include_str!("../std/scene.mdl"), overridable: false },
    StdModule { name: "::std", file: "std.mdl", text: include_str!("../std/std.mdl"), overridable: false },
    StdModule { name: "::base", file: "base.mdl", text: include_str!("../std/base.mdl"), overridable: false },
    StdModule {
        name: "::nvidia::core_definitions",
        file: "nvidia/core_definitions.mdl",
        text: include_str!("../std/nvidia/core_definitions.mdl"),
        overridable: true,
    },
];

/// The built-in module of this absolute name.
pub fn std_module(name: &str) -> Option<&'static StdModule> {
    STD_MODULES.iter().find(|m| m.name == name)
}
