//! Maya's file texture filter attributes (`filterType`, `filter`, `filterOffset`) in
//! compiled scenes, under both name families, on PNG images the tests write: the file is
//! read through a surfaceShader (its colour is the pixel's) at the world origin, normal
//! +y, at the uv given to `support::maya::point`. The kernels are in
//! `crates/maya/src/file_filter.rs`.

use crate::support;

use support::maya::{compile, point, run, Compiled};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";

/// Writes an n × n 8-bit grey PNG whose pixel (x, y) (y down, as files store rows) is
/// `f(x, y)`, and returns its path.
fn write_png(name: &str, n: u32, f: impl Fn(u32, u32) -> u8) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("mira_maya_file_filter_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let img = image::GrayImage::from_fn(n, n, |x, y| image::Luma([f(x, y)]));
    let path = dir.join(name);
    img.save(&path).unwrap();
    path
}

/// A scene showing `path` through a file texture with `params`.
fn scene(path: &std::path::Path, params: &str, adsk: bool) -> Compiled {
    let (file, surface, engine) = if adsk {
        ("adskMayaFile", "adskMayaSurfaceShader", "adskMayaShadingEngine")
    } else {
        ("maya_file", "maya_surfaceshader", "maya_shadingengine")
    };
    let c = compile(
        "",
        &format!(
            r#"{LIBS}local color texture "img" "{}"
            shader "tex" "{file}" ("fileTextureName" "img"{params})
            shader "flat" "{surface}" ("outColor" = "tex.outColor")
            material "m" opaque "{engine}" ("surfaceShader" = "flat.outColor") end material"#,
            path.display()
        ),
        &["m"],
        "",
    );
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    c
}

fn shade(c: &Compiled, uv: [f32; 2]) -> f32 {
    run(c, &Empty::default(), c.material("m"), point(uv)).color().x
}

/// filterType 0 (off) reads the texel the point lies in, exactly (1e-6), even between
/// texel centres and with a filterOffset, where the default (quadratic) filter at width 0
/// interpolates bilinearly (the mean of two texels half way between their centres).
#[test]
fn filter_off_keeps_exact_texel_values() {
    let path = write_png("ramp8.png", 8, |x, y| (x * 8 + y * 28) as u8);
    // Texel (x, y) counted from the bottom: file row 7 − y.
    let texel = |x: u32, y: u32| (x * 8 + (7 - y) * 28) as f32 / 255.0;
    for adsk in [false, true] {
        let off = scene(&path, r#", "filterType" 0, "filterOffset" 0.2"#, adsk);
        for (u, v) in [(0.01, 0.01), (0.26, 0.49), (0.74, 0.51), (0.99, 0.99), (0.5, 0.3)] {
            let want = texel((u * 8.0) as u32, (v * 8.0) as u32);
            let got = shade(&off, [u, v]);
            assert!((got - want).abs() < 1e-6, "({u}, {v}): {got} vs {want}");
        }
        let default = scene(&path, "", adsk);
        let got = shade(&default, [2.0 / 8.0, 0.5 / 8.0]);
        let want = 0.5 * (texel(1, 0) + texel(2, 0));
        assert!((got - want).abs() < 1e-6, "bilinear: {got} vs {want}");
    }
    std::fs::remove_file(&path).ok();
}

/// A 32 × 32 checker of 4-texel squares seen at width 0 (no ray footprint here) blurred
/// by filterOffset 0 … 0.25 (0 … 8 texels): the contrast between the centres of a white
/// and a black square starts at 1 (1e-6), never rises (by more than 1e-4) as the offset
/// grows while it is above 0.1 (wider, a kernel as wide as the checker's period rings),
/// and gets under 0.3, for every filter type but off; off keeps it at 1.
#[test]
fn filter_offset_blurs_a_checker_monotonically() {
    let path = write_png("checker32.png", 32, |x, y| if (x / 4 + y / 4) % 2 == 0 { 255 } else { 0 });
    for (kind, adsk) in [(1, false), (2, true), (3, false), (4, true), (5, false)] {
        let mut last = f32::INFINITY;
        for i in 0..=10 {
            if last < 0.1 {
                break;
            }
            let offset = 0.025 * i as f32;
            let c = scene(&path, &format!(r#", "filterType" {kind}, "filterOffset" {offset}"#), adsk);
            let contrast = (shade(&c, [2.0 / 32.0, 2.0 / 32.0]) - shade(&c, [6.0 / 32.0, 2.0 / 32.0])).abs();
            if i == 0 {
                assert!((contrast - 1.0).abs() < 1e-6, "type {kind}: {contrast}");
            }
            assert!(contrast <= last + 1e-4, "type {kind}, offset {offset}: {contrast} after {last}");
            last = contrast;
        }
        assert!(last < 0.3, "type {kind}: {last}");
    }
    let off = scene(&path, r#", "filterType" 0, "filterOffset" 0.25"#, false);
    let contrast = (shade(&off, [2.0 / 32.0, 2.0 / 32.0]) - shade(&off, [6.0 / 32.0, 2.0 / 32.0])).abs();
    assert!((contrast - 1.0).abs() < 1e-6, "off: {contrast}");
    std::fs::remove_file(&path).ok();
}
