//! Malformed MDL is answered with an error at the right line and column.
//!
//! Each case marks the expected place with `@@` in its text; the marker is removed before
//! the text is read, and the first error must be there and contain the expected words.

use std::path::PathBuf;

use mdl_lang::{load_module, MdlSearchPath, ModuleSet};

/// The text without its `@@` marker, and the marker's 1-based line and column.
fn mark(text: &str) -> (String, u32, u32) {
    let at = text.find("@@").expect("case has a @@ marker");
    let before = &text[..at];
    let line = before.matches('\n').count() as u32 + 1;
    let col = before.rsplit('\n').next().unwrap().chars().count() as u32 + 1;
    (text.replacen("@@", "", 1), line, col)
}

fn check(case: &str, expected: &str) {
    let (text, line, col) = mark(case);
    let mut set = ModuleSet::new(MdlSearchPath::new());
    let err = match set.load_source("::case", &text) {
        Ok(_) => panic!("no error for:\n{text}"),
        Err(e) => e,
    };
    let p = err.first();
    assert_eq!(p.file, "case.mdl");
    assert!(p.message.contains(expected), "message `{}` lacks `{expected}`\n{err}", p.message);
    assert_eq!((p.line, p.col), (line, col), "wrong place for `{}`:\n{err}", p.message);
    // The rendering has the location, the source line and a caret under the column.
    let header = format!("case.mdl:{line}:{col}: error: ");
    assert!(err.rendered.starts_with(&header), "{}", err.rendered);
    let caret_line = err.rendered.lines().nth(2).unwrap();
    assert_eq!(caret_line.find('^'), Some(4 + col as usize - 1), "{}", err.rendered);
}

#[test]
fn missing_version_line() {
    check("@@import ::df::*;\n", "expected the version line");
}

#[test]
fn unsupported_version() {
    check("mdl @@2.0;\n", "MDL version 2.0 is not supported");
}

#[test]
fn unterminated_string() {
    check(
        "mdl 1.7;\nimport ::anno::*;\nexport material m() [[ anno::display_name(@@\"open) ]] = material();\n",
        "unterminated string",
    );
}

#[test]
fn unexpected_character() {
    check("mdl 1.7;\nexport float f() = 1.0 @@$ 2.0;\n", "unexpected character `$`");
}

#[test]
fn missing_semicolon_after_material() {
    check("mdl 1.7;\nexport material m() = material()\n@@export material n() = material();\n", "expected `;`");
}

#[test]
fn declarative_is_named_as_unsupported() {
    check("mdl 1.7;\nexport @@declarative struct s { float a; };\n", "a `declarative` definition is not supported yet");
}

#[test]
fn quoted_module_names_are_named_as_unsupported() {
    check("mdl 1.8;\nusing m = @@\"my module\";\n", "quoted (Unicode) module names are not supported yet");
}

#[test]
fn switch_on_a_string() {
    check(
        "mdl 1.7;\nexport int f(string s)\n{\n    switch (@@s) { case 0: return 1; }\n    return 0;\n}\n",
        "a `switch` value is of type `string`",
    );
}

#[test]
fn case_outside_a_switch() {
    check("mdl 1.7;\nexport int f(int x)\n{\n    @@case 1: return 0;\n}\n", "`case` or `default` outside a `switch`");
}

#[test]
fn cast_operator_is_named_as_unsupported() {
    check("mdl 1.7;\nexport float f(int x) = @@cast<float>(x);\n", "the `cast<T>(…)` operator is not supported yet");
}

#[test]
fn unknown_df_function() {
    check(
        "mdl 1.7;\nimport ::df::*;\nexport material m() = material(\n  surface: material_surface(scattering: @@df::diffuse_bsdf()));\n",
        "module `::df` has no exported `diffuse_bsdf`",
    );
}

#[test]
fn unknown_name() {
    check(
        "mdl 1.7;\nimport ::df::*;\nexport material m(color tint = color(1.0)) = material(\n  surface: material_surface(scattering: df::diffuse_reflection_bsdf(tint: @@tnt)));\n",
        "unknown name `tnt`",
    );
}

#[test]
fn module_not_imported() {
    check(
        "mdl 1.7;\nexport float f() = @@base::architectural_gloss_to_rough(0.5);\n",
        "module `::base` is not imported",
    );
}

#[test]
fn default_of_wrong_type() {
    check(
        "mdl 1.7;\nexport material m(color tint = @@\"red\") = material();\n",
        "is of type `string`, expected `color`",
    );
}

#[test]
fn unknown_named_argument() {
    check(
        "mdl 1.7;\nimport ::df::*;\nexport material m() = material(surface: material_surface(\n    scattering: @@df::diffuse_reflection_bsdf(tnt: color(1.0))));\n",
        "there is no parameter `tnt`",
    );
}

#[test]
fn argument_of_wrong_type() {
    check(
        "mdl 1.7;\nimport ::df::*;\nexport bsdf b() = @@df::diffuse_reflection_bsdf(roughness: \"very\");\n",
        "argument `roughness` is of type `string`, expected `float`",
    );
}

#[test]
fn material_body_is_not_a_material() {
    check(
        "mdl 1.7;\nimport ::df::*;\nexport material m() =\n    @@df::diffuse_reflection_bsdf();\n",
        "the body of material `m` is of type `bsdf`",
    );
}

#[test]
fn declared_twice() {
    check("mdl 1.7;\nexport const float A = 1.0;\nexport const float @@A = 2.0;\n", "`A` is declared twice");
}

#[test]
fn unclosed_block() {
    check("mdl 1.7;\nexport float f()\n@@{\n    return 1.0;\n", "`{` without a matching `}`");
}

#[test]
fn positional_after_named_argument() {
    check(
        "mdl 1.7;\nimport ::df::*;\nexport bsdf b() = df::diffuse_reflection_bsdf(tint: color(1.0), @@0.5);\n",
        "positional argument after a named argument",
    );
}

#[test]
fn break_outside_loop() {
    check("mdl 1.7;\nexport float f()\n{\n    @@break;\n    return 1.0;\n}\n", "outside a loop");
}

#[test]
fn unknown_annotation() {
    check(
        "mdl 1.7;\nimport ::anno::*;\nexport material m() [[ @@anno::colour(\"x\") ]] = material();\n",
        "module `::anno` has no exported `colour`",
    );
}

#[test]
fn operator_on_a_bsdf() {
    check(
        "mdl 1.7;\nimport ::df::*;\nexport bsdf b() = @@df::diffuse_reflection_bsdf() * 2.0;\n",
        "operator `*` is not defined for `bsdf`",
    );
}

#[test]
fn missing_required_argument() {
    check(
        "mdl 1.7;\nimport ::df::*;\nexport bsdf b() = @@df::simple_glossy_bsdf(tint: color(1.0));\n",
        "parameter `roughness_u` has no default",
    );
}

#[test]
fn variant_of_a_function() {
    check("mdl 1.7;\nexport float f() = 1.0;\nexport material v(*) = @@f();\n", "is not a material");
}

#[test]
fn unknown_vector_component() {
    check("mdl 1.7;\nexport float f(float2 v) = @@v.z;\n", "`float2` has no component `z`");
}

#[test]
fn import_of_a_name_the_module_lacks() {
    check("mdl 1.7;\n@@import ::df::glossy_bsdf;\n", "module `::df` has no `glossy_bsdf`");
}

fn modules_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/modules")
}

#[test]
fn missing_module_is_reported_at_its_import() {
    let search = MdlSearchPath::for_scene(Some(&modules_dir()), &[], None);
    let err = load_module("::missing_import", &search).unwrap_err();
    let p = err.first();
    assert!(p.file.ends_with("missing_import.mdl"), "{err}");
    assert_eq!((p.line, p.col), (6, 1), "{err}");
    assert!(p.message.contains("module `::no_such::place` not found: no no_such/place.mdl in"), "{err}");
}

#[test]
fn import_cycle_is_reported_at_the_import_closing_it() {
    let search = MdlSearchPath::for_scene(Some(&modules_dir()), &[], None);
    let err = load_module("::cycle_a", &search).unwrap_err();
    let p = err.first();
    assert!(p.file.ends_with("cycle_b.mdl"), "{err}");
    assert_eq!((p.line, p.col), (4, 1), "{err}");
    assert!(p.message.contains("import cycle: ::cycle_a imports ::cycle_b imports ::cycle_a"), "{err}");
}

#[test]
fn module_asked_for_by_name_and_not_found() {
    let err = load_module("::nowhere", &MdlSearchPath::new()).unwrap_err();
    assert_eq!(err.first().line, 0);
    assert!(err.to_string().contains("module `::nowhere` not found"), "{err}");
}

#[test]
fn varying_value_for_a_uniform_parameter() {
    check(
        "mdl 1.7;\nimport ::df::*;\nimport ::state::*;\nexport edf e() = df::spot_edf(@@exponent: state::normal().x);\n",
        "parameter `exponent` of `df::spot_edf` is uniform, but this value varies",
    );
}

#[test]
fn varying_default_of_a_uniform_parameter() {
    check(
        "mdl 1.7;\nimport ::state::*;\nexport float f(uniform float3 n = @@state::normal()) = n.x;\n",
        "parameter `n` is uniform, but its default varies",
    );
}

#[test]
fn varying_local_flows_into_a_uniform_parameter() {
    check(
        "mdl 1.7;\nimport ::df::*;\nimport ::state::*;\n\
         export edf e() = let float x = state::position().y; in df::spot_edf(@@exponent: x * 2.0);\n",
        "parameter `exponent` of `df::spot_edf` is uniform",
    );
}

#[test]
fn enum_value_that_is_not_constant() {
    check(
        "mdl 1.7;\nimport ::math::*;\nexport enum e { a = 1, b = @@math::max(1, 2) };\n",
        "enum value is not a constant integer expression",
    );
}
