//! What the test files share.

use scene::Scene;

/// The scene of `.mi` text `text` (frame 0), its diagnostics and the parse: the text parses
/// without errors and the scene builds without any.
pub fn build(text: &str) -> (Scene, Vec<mi::Diagnostic>, mi::Parsed) {
    let parsed = mi::parse_str("t.mi", text);
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let mut diags = Vec::new();
    let scene = Scene::build(&parsed, 0, &mut diags);
    let errors: Vec<String> = diags.iter().filter(|d| d.is_error()).map(|d| d.render(&parsed.sources)).collect();
    assert!(errors.is_empty(), "{}", errors.join("\n"));
    (scene.expect("a scene"), diags, parsed)
}
