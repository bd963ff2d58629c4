//! Maya's vectorProduct matrix operations in compiled scenes, under both name families:
//! the node's `output` shown through a surfaceShader at the shading point of
//! `support::maya::point`, against Maya's row-vector convention worked out by hand
//! (1e-5).

use crate::support;

use support::maya::{assert_rgb, compile, point, run};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";

/// Rows (0, 1, 0), (2, 0, 0), (0, 0, 1) and the translation (1, 2, 3): Maya (like mental
/// ray) multiplies a row vector on the left, so [x y z]·M = (2y, x, z) and a point gains
/// the translation. Its 3 × 3 part is not symmetric: M·v would give (y, 2x, z).
const MATRIX: &str = "0 1 0 0  2 0 0 0  0 0 1 0  1 2 3 1";

/// The vectorProduct's output for `operation` on input1 (0.5, 0.125, 0.25).
fn product(operation: i32, normalize: bool, adsk: bool) -> glam::Vec4 {
    let (vp, surface, engine) = if adsk {
        ("adskMayaVectorProduct", "adskMayaSurfaceShader", "adskMayaShadingEngine")
    } else {
        ("maya_vectorproduct", "maya_surfaceshader", "maya_shadingengine")
    };
    let normalize = if normalize { "on" } else { "off" };
    let c = compile(
        "",
        &format!(
            r#"{LIBS}shader "vp" "{vp}" ("operation" {operation}, "input1" 0.5 0.125 0.25, "matrix" {MATRIX},
                "normalizeOutput" {normalize})
            shader "flat" "{surface}" ("outColor" = "vp.output")
            material "m" opaque "{engine}" ("surfaceShader" = "flat.outColor") end material"#
        ),
        &["m"],
        "",
    );
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    run(&c, &Empty::default(), c.material("m"), point([0.5, 0.5])).color()
}

/// Vector matrix product (3): [0.5 0.125 0.25]·M = (0.25, 0.5, 0.25), no translation;
/// point matrix product (4): that plus (1, 2, 3); normalizeOutput: the vector product
/// over its length √0.375.
#[test]
fn vector_and_point_matrix_products_use_row_vectors() {
    for adsk in [false, true] {
        assert_rgb(product(3, false, adsk), [0.25, 0.5, 0.25], 1e-5);
        assert_rgb(product(4, false, adsk), [1.25, 2.5, 3.25], 1e-5);
        let l = 0.375f32.sqrt();
        assert_rgb(product(3, true, adsk), [0.25 / l, 0.5 / l, 0.25 / l], 1e-5);
    }
}
