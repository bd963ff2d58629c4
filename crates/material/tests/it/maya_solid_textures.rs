//! Maya's snow, rock, leather, granite and volumeNoise 3D textures (and the 2D noise's Billow cells) in compiled scenes, read through a surfaceShader (the
//! texture's colour is the pixel's), under both name families. The shading point is the
//! world origin, normal +y (see `support::maya::point`).

use crate::support;

use support::maya::{assert_rgb, compile, point, run, Compiled};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";

/// A scene whose material shows `texture` (a `shader` statement named "tex") through a
/// surfaceShader.
fn scene(texture: &str) -> Compiled {
    let c = compile(
        "",
        &format!(
            r#"{LIBS}{texture}
            shader "flat" "maya_surfaceshader" ("outColor" = "tex.outColor")
            material "m" opaque "maya_shadingengine" ("surfaceShader" = "flat.outColor") end material"#
        ),
        &["m"],
        "",
    );
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    c
}

fn shade(c: &Compiled) -> glam::Vec4 {
    run(c, &Empty::default(), c.material("m"), point([0.3, 0.6])).color()
}

/// A placement matrix (`.mi` rows) turning the world about z by `deg` degrees: the
/// world's +y normal lies `deg` from the placement's +Y.
fn turned(deg: f32) -> String {
    let (s, c) = deg.to_radians().sin_cos();
    format!("{c} {s} 0 0  {} {c} 0 0  0 0 1 0  0 0 0 1", -s)
}

/// Snow with its defaults (white snow on a 0.5 grey surface, threshold 0.5 = 45°,
/// depthDecay 5: full snow up to 27°, none from 45°): level ground is white, the 45°
/// slope the surface colour exactly, 36° halfway, 60° the surface colour; thickness 0.4
/// on level ground 40 % snow; threshold 1 keeps snow off a 10° slope.
#[test]
fn snow_covers_the_slopes_flatter_than_its_threshold() {
    for name in ["maya_snow", "adskMayaSnow"] {
        let at = |deg: f32, extra: &str| {
            shade(&scene(&format!(r#"shader "tex" "{name}" ("placementMatrix" {}{extra})"#, turned(deg))))
        };
        assert_rgb(at(0.0, ""), [1.0; 3], 1e-5);
        assert_rgb(at(20.0, ""), [1.0; 3], 1e-5);
        assert_rgb(at(36.0, ""), [0.75; 3], 1e-3);
        assert_rgb(at(45.0, ""), [0.5; 3], 1e-3);
        assert_rgb(at(60.0, ""), [0.5; 3], 1e-5);
        assert_rgb(at(0.0, r#", "thickness" 0.4"#), [0.7; 3], 1e-5);
        assert_rgb(at(10.0, r#", "threshold" 1"#), [0.5; 3], 1e-5);
        // Its own colours, and the alpha is the snow's share.
        let c = at(36.0, r#", "snowColor" 1 0 0, "surfaceColor" 0 0 1"#);
        assert_rgb(c, [0.5, 0.0, 0.5], 1e-3);
    }
}

/// Rock: mixRatio 0 shows color1 (black by default) everywhere, 1 color2 (white), at
/// several points; the default mix lies between, the same at the same point in two
/// compilations, and depends on the point.
#[test]
fn rock_mix_ratio_and_its_default_grains() {
    for name in ["maya_rock", "adskMayaRock"] {
        for (mix, want) in [(0.0, 0.0), (1.0, 1.0)] {
            for offset in ["0 0 0", "0.0031 0.0172 0.0047", "0.37 0.21 0.9"] {
                let c = scene(&format!(
                    r#"shader "tex" "{name}" ("mixRatio" {mix}, "placementMatrix" 1 0 0 0  0 1 0 0  0 0 1 0  {offset} 1)"#
                ));
                assert_rgb(shade(&c), [want; 3], 1e-6);
            }
        }
        let grey = |offset: &str| {
            let c = scene(&format!(
                r#"shader "tex" "{name}" ("color1" 0.2 0.2 0.2, "color2" 0.8 0.8 0.8,
                    "placementMatrix" 1 0 0 0  0 1 0 0  0 0 1 0  {offset} 1)"#
            ));
            shade(&c).x
        };
        let values: Vec<f32> =
            ["0.0031 0.0172 0.0047", "0.0131 0.0042 0.0081", "0.0213 0.0093 0.0011"].iter().map(|o| grey(o)).collect();
        for v in &values {
            assert!((0.2..=0.8).contains(v), "{values:?}");
        }
        assert_eq!(values[0], grey("0.0031 0.0172 0.0047"), "deterministic");
        assert!(values.iter().any(|v| (v - values[0]).abs() > 1e-3), "the grains vary: {values:?}");
    }
}

/// A placement that moves the shading point (the world origin) to `at` in placement space.
fn moved_to(at: [f32; 3]) -> String {
    format!("1 0 0 0  0 1 0 0  0 0 1 0  {} {} {} 1", at[0], at[1], at[2])
}

/// Leather on a regular lattice of unit cells (randomness 0, cellSize 1) with even cells
/// (spottyness 0): at a cell's centre its default cellColor, halfway between two centres
/// (the crease, threshold 0.83) its default creaseColor; threshold 0 a quarter of the
/// way: the even blend.
#[test]
fn leather_cells_and_creases_on_a_regular_lattice() {
    for name in ["maya_leather", "adskMayaLeather"] {
        let at = |p: [f32; 3], extra: &str| {
            shade(&scene(&format!(
                r#"shader "tex" "{name}" ("randomness" 0, "cellSize" 1, "spottyness" 0,
                    "placementMatrix" {}{extra})"#,
                moved_to(p)
            )))
        };
        let (cell, crease) = ([0.373, 0.157, 0.059], [0.235, 0.118, 0.0]);
        assert_rgb(at([2.5, 0.5, -1.5], ""), cell, 1e-5);
        assert_rgb(at([3.0, 0.5, -1.5], ""), crease, 1e-5);
        let half: Vec<f32> = (0..3).map(|i| 0.5 * (cell[i] + crease[i])).collect();
        assert_rgb(at([2.75, 0.5, -1.5], r#", "threshold" 0"#), [half[0], half[1], half[2]], 1e-4);
        // Creases off: packed cells still meet where the spheres touch.
        assert_rgb(at([3.0, 0.5, -1.5], r#", "creases" off"#), crease, 1e-5);
    }
}

/// Granite on a regular lattice (randomness 0, cellSize 1, spottyness 0): a cell's centre
/// shows one of the three colours exactly, the crease between two the filler colour; with
/// mixRatio 1 no cell is color1 (black), with 0 none is color3.
#[test]
fn granite_cells_take_one_of_three_colours_in_the_filler() {
    for name in ["maya_granite", "adskMayaGranite"] {
        let at = |p: [f32; 3], mix: f32| {
            shade(&scene(&format!(
                r#"shader "tex" "{name}" ("randomness" 0, "cellSize" 1, "spottyness" 0, "mixRatio" {mix},
                    "placementMatrix" {})"#,
                moved_to(p)
            )))
        };
        let colours = [[0.0, 0.0, 0.0], [0.549, 0.784, 0.392], [0.627, 0.824, 0.824]];
        for mix in [0.0, 1.0] {
            for k in 0..6 {
                let c = at([k as f32 + 0.5, 0.5, 0.5], mix);
                let i = colours.iter().position(|w| (0..3).all(|j| (c[j] - w[j]).abs() < 1e-5));
                assert!(i.is_some(), "{c}");
                assert_ne!(i, Some(if mix == 0.0 { 2 } else { 0 }), "mixRatio {mix}: {c}");
            }
        }
        assert_rgb(at([1.0, 0.5, 0.5], 0.5), [0.588, 0.294, 0.196], 1e-5);
    }
}

/// volumeNoise at a point on the noise's lattice (the origin, or (0.25, 0.5, 0.25)
/// through `origin`): every octave is 0 there, so Perlin noise (noiseType 0) shows its
/// mean 0.5 + threshold, and Billow (the default type) of density 0 (no blobs) its
/// threshold; with scale 2 the point (0.25, 0.5, 0.25) is read at half of it, still on
/// the lattice.
#[test]
fn volume_noise_on_its_lattice_shows_its_threshold() {
    for name in ["maya_volumenoise", "adskMayaVolumeNoise"] {
        let at = |extra: &str| shade(&scene(&format!(r#"shader "tex" "{name}" ("threshold" 0.2{extra})"#)));
        assert_rgb(at(r#", "noiseType" 0"#), [0.7; 3], 1e-6);
        assert_rgb(at(r#", "density" 0"#), [0.2; 3], 1e-6);
        assert_rgb(at(r#", "noiseType" 0, "origin" -0.25 -0.5 -0.25"#), [0.7; 3], 1e-6);
        assert_rgb(at(r#", "noiseType" 0, "origin" -0.25 -0.5 -0.25, "scale" 2 2 2"#), [0.7; 3], 1e-6);
        // Off the lattice the value moves, within [0, 1].
        let v = at(r#", "noiseType" 0, "origin" -0.0173 -0.0311 -0.0057"#).x;
        assert!((0.0..=1.0).contains(&v) && (v - 0.7).abs() > 1e-4, "{v}");
    }
}

/// Billow's cells through the declarations' new parameters, one octave, blobs on the
/// cell centres (`randomness` 0) of equal peaks (`spottyness` 0): volumeNoise read at
/// q · 8 = (0.6, 0.5, 0.5), 0.1 from a centre (t = 0.1 / 0.75), gives the default Fast
/// curve (1 − t)² = 0.751111 and Linear 1 − t = 0.866667; the 2D noise at uv (0.3, 0.6),
/// frequency 10 and time 0.5 (the point moved to the cell centre (3.5, 6.5)) gives
/// Linear's peak 1 and Bubble's 0 (+ threshold 0.2); density 0 the threshold alone
/// (1e-5).
#[test]
fn billow_cells_show_their_falloff() {
    let one = r#""depthMax" 1, "randomness" 0, "spottyness" 0"#;
    for name in ["maya_volumenoise", "adskMayaVolumeNoise"] {
        let at = |extra: &str| {
            let origin = r#""origin" -0.075 -0.0625 -0.0625"#;
            shade(&scene(&format!(r#"shader "tex" "{name}" ({one}, {origin}{extra})"#)))
        };
        assert_rgb(at(""), [0.751111; 3], 1e-5);
        assert_rgb(at(r#", "falloff" 0"#), [0.866667; 3], 1e-5);
        assert_rgb(at(r#", "density" 0, "threshold" 0.3"#), [0.3; 3], 1e-6);
    }
    for name in ["maya_noise", "adskMayaNoise"] {
        let at = |extra: &str| {
            shade(&scene(&format!(r#"shader "tex" "{name}" ({one}, "frequency" 10, "time" 0.5{extra})"#)))
        };
        assert_rgb(at(r#", "falloff" 0"#), [1.0; 3], 1e-5);
        assert_rgb(at(r#", "falloff" 3, "threshold" 0.2"#), [0.2; 3], 1e-5);
        assert_rgb(at(r#", "density" 0, "threshold" 0.4"#), [0.4; 3], 1e-6);
    }
}

/// Brownian and cloud under both name families, where their colour does not depend on
/// the noise: brownian of no octaves is ½ grey (× `colorGain`), a cloud of contrast 0 the
/// two colours' average; with the defaults both stay within their colours and repeat.
#[test]
fn brownian_and_cloud_in_compiled_scenes() {
    for (brownian, cloud) in [("maya_brownian", "maya_cloud"), ("adskMayaBrownian", "adskMayaCloud")] {
        let c = scene(&format!(r#"shader "tex" "{brownian}" ("octaves" 0, "colorGain" 0.8 0.6 0.4)"#));
        assert_rgb(shade(&c), [0.4, 0.3, 0.2], 1e-6);
        let c = scene(&format!(r#"shader "tex" "{cloud}" ("color1" 0.9 0.1 0.3, "color2" 0.1 0.5 0.7, "contrast" 0)"#));
        assert_rgb(shade(&c), [0.5, 0.3, 0.5], 1e-6);
        // Defaults: grey brownian and a white-to-black cloud, in range and repeatable.
        for tex in [brownian, cloud] {
            let c = scene(&format!(r#"shader "tex" "{tex}" ()"#));
            let v = shade(&c);
            assert!((0.0..=1.0).contains(&v.x) && v.x == v.y && v.y == v.z, "{tex}: {v}");
            assert_eq!(v, shade(&c));
        }
    }
}

/// Crater and stucco under both name families at their documented extremes (1e-5): a
/// balance beyond the noise's range shows crater's channel1 alone (or, negative,
/// channel3), an unbounded melt their average (1e-3); stucco with shaker 0 is channel2
/// everywhere, with a huge shaker channel1. With the defaults each shows a mix of its own
/// channels' colours (red, green, blue for crater; red and blue for stucco), repeatably.
#[test]
fn crater_and_stucco_in_compiled_scenes() {
    let channels = r#""channel1" 0.9 0.1 0.2, "channel2" 0.1 0.8 0.3, "channel3" 0.2 0.3 0.7"#;
    for (crater, stucco) in [("maya_crater", "maya_stucco"), ("adskMayaCrater", "adskMayaStucco")] {
        let at = |params: &str| shade(&scene(&format!(r#"shader "tex" "{crater}" ({channels}{params})"#)));
        assert_rgb(at(r#", "balance" 3"#), [0.9, 0.1, 0.2], 1e-5);
        assert_rgb(at(r#", "balance" -3"#), [0.2, 0.3, 0.7], 1e-5);
        assert_rgb(at(r#", "melt" 1e6"#), [0.4, 0.4, 0.4], 1e-3);
        let c = scene(&format!(r#"shader "tex" "{crater}" ()"#));
        let v = shade(&c);
        assert!((v.x + v.y + v.z - 1.0).abs() < 1e-5 && v.min_element() >= 0.0, "{crater}: {v}");
        assert_eq!(v, shade(&c));

        let at = |params: &str| {
            shade(&scene(&format!(
                r#"shader "tex" "{stucco}" ("channel1" 0.9 0.1 0.2, "channel2" 0.1 0.8 0.3{params})"#
            )))
        };
        assert_rgb(at(r#", "shaker" 0"#), [0.1, 0.8, 0.3], 1e-5);
        assert_rgb(at(r#", "shaker" 1e12"#), [0.9, 0.1, 0.2], 1e-5);
        let c = scene(&format!(r#"shader "tex" "{stucco}" ()"#));
        let v = shade(&c);
        assert!(v.y == 0.0 && (v.x + v.z - 1.0).abs() < 1e-5, "{stucco}: {v}");
        assert_eq!(v, shade(&c));
    }
}
