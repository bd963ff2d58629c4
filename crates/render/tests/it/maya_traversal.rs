//! The AdskShaderSDK's scene DAG traversal shader, `adskTraversal` (declared in mira's
//! built-in `AdskShaderSDK.mi` from the SDK's `adskTraversal.h`: one instance parameter,
//! the tag `passEncoding`): a Maya export naming it in its options and giving an
//! instance its parameter reads without a message and renders as without them in both
//! engines (mira renders no per-pass frame buffers, which the encoding steers).

use crate::support;

use std::path::PathBuf;

use render::{EngineKind, Settings};

/// The repository's Maya 2017 export, with `traversal "adskTraversal"` in its options and
/// a `passEncoding` (its camera's frame-buffer data) among the cube instance's parameters
/// when `traversal`, read and built at 8²: the pixels of `engine` (4 samples a pixel) and
/// every message.
fn render(traversal: bool, engine: EngineKind) -> (Vec<[f32; 4]>, Vec<String>) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/maya");
    let path = dir.join("maya2017_export.mi");
    let mut text = std::fs::read_to_string(&path).expect("readable");
    if traversal {
        let options = "\tstate = \"miDefaultOptions:state\"\n";
        let params = "\t( \"miLabel\" 2 )\n";
        assert_eq!((text.matches(options).count(), text.matches(params).count()), (1, 1));
        // On the same line, so that the messages' line numbers stay.
        text = text.replace(options, "\tstate = \"miDefaultOptions:state\" traversal \"adskTraversal\"\n");
        text = text.replace(params, "\t( \"miLabel\" 2, \"passEncoding\" \"perspShape:fbdata\" )\n");
    }
    let parsed = mi::parse_str(&path.to_string_lossy(), &text);
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let built = support::build_parsed(&parsed, 8, &[]);
    let settings = Settings { engine, spp: Some(4), ..Settings::default() };
    let film = support::render_world(&built.built.world, &built.built.shading, &settings).0;
    (film.rgba(), built.messages)
}

/// With the traversal shader and an instance's `passEncoding`, both engines give the
/// same pixels bit for bit and the same messages as the export without them (the
/// declaration's own test: `maya` `tests::the_sdk_traversal_shader_is_declared_as_its_header_gives_it`).
#[test]
fn the_sdk_traversal_shader_reads_and_leaves_the_image() {
    for engine in [EngineKind::Classic, EngineKind::Path] {
        let (plain, plain_messages) = render(false, engine);
        let (with, with_messages) = render(true, engine);
        assert!(plain.iter().any(|p| p[0] > 0.01), "{engine:?}: the export renders");
        assert_eq!(with, plain, "{engine:?}: the traversal shader changes no pixel");
        assert_eq!(with_messages, plain_messages, "{engine:?}: and adds no message");
    }
}
