//! Maya's bulge, cloth, fractal, mountain and water 2D textures and the contrast utility
//! in compiled scenes, under both name families: read through a surfaceShader (the
//! texture's colour is the pixel's) at settings where the documented behaviour gives a
//! known colour, and on a lambert's colour in the path engine's translation (the same
//! diffuse colour per hit as the classic shader). The shading point is the world origin,
//! normal +y, at the uv given to `support::maya::point`.

use crate::support;

use material::Varying;
use shader::Ctx;
use support::maya::{assert_rgb, compile, point, run, Compiled};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";

/// A scene whose material "m" shows `texture` (a `shader` statement named "tex")
/// through a surfaceShader of the family of `family` ("maya_" or "adskMaya").
fn scene(texture: &str, adsk: bool) -> Compiled {
    let (surface, engine) = if adsk {
        ("adskMayaSurfaceShader", "adskMayaShadingEngine")
    } else {
        ("maya_surfaceshader", "maya_shadingengine")
    };
    let c = compile(
        "",
        &format!(
            r#"{LIBS}{texture}
            shader "flat" "{surface}" ("outColor" = "tex.outColor")
            material "m" opaque "{engine}" ("surfaceShader" = "flat.outColor") end material"#
        ),
        &["m"],
        "",
    );
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    c
}

fn shade(texture: &str, adsk: bool, uv: [f32; 2]) -> glam::Vec4 {
    let c = scene(texture, adsk);
    run(&c, &Empty::default(), c.material("m"), point(uv)).color()
}

/// Both names of a texture: (maya_*, adskMaya*).
fn names(low: &str, camel: &str) -> [(String, bool); 2] {
    [(format!("maya_{low}"), false), (format!("adskMaya{camel}"), true)]
}

/// Bulge: 1 in the tile's middle, 0 on its frame (`uWidth`, `vWidth` wide), sin(π·0.25/0.9)
/// at u = 0.3 with a frame of 0.1 (1e-5); `colorGain` scales it.
#[test]
fn bulge_is_flat_on_its_frame_and_bulges_mid_tile() {
    for (name, adsk) in names("bulge", "Bulge") {
        let tex = format!(r#"shader "tex" "{name}" ("colorGain" 1 0.5 0.25)"#);
        assert_rgb(shade(&tex, adsk, [0.5, 0.5]), [1.0, 0.5, 0.25], 1e-5);
        assert_rgb(shade(&tex, adsk, [0.02, 0.5]), [0.0; 3], 1e-6);
        assert_rgb(shade(&tex, adsk, [0.5, 0.97]), [0.0; 3], 1e-6);
        let s = (std::f32::consts::PI * 0.25 / 0.9).sin();
        assert_rgb(shade(&tex, adsk, [0.3, 0.5]), [s, 0.5 * s, 0.25 * s], 1e-5);
    }
}

/// Cloth with its defaults (white u threads, grey v threads, black gap, widths 0.75): the
/// u thread on top at the crossing (¼, ¼), the v thread at (¾, ¼), the gap at (½, ½)
/// (1e-5); the thread widths at 0 leave only the gap colour.
#[test]
fn cloth_shows_its_threads_woven_over_the_gap() {
    for (name, adsk) in names("cloth", "Cloth") {
        let tex = format!(r#"shader "tex" "{name}" ("gapColor" 0.1 0.2 0.3, "vColor" 0.9 0.1 0.1)"#);
        assert_rgb(shade(&tex, adsk, [0.25, 0.25]), [1.0; 3], 1e-5);
        assert_rgb(shade(&tex, adsk, [0.75, 0.25]), [0.9, 0.1, 0.1], 1e-5);
        assert_rgb(shade(&tex, adsk, [0.5, 0.5]), [0.1, 0.2, 0.3], 1e-5);
        let none = format!(r#"shader "tex" "{name}" ("gapColor" 0.1 0.2 0.3, "uWidth" 0, "vWidth" 0)"#);
        assert_rgb(shade(&none, adsk, [0.25, 0.25]), [0.1, 0.2, 0.3], 1e-6);
    }
}

/// Fractal: amplitude 0 leaves ½ + threshold everywhere (1e-6), no levels likewise; with
/// the defaults a grey in [0, 1] that changes over the tile.
#[test]
fn fractal_sits_at_half_plus_threshold_without_amplitude_and_varies_with_it() {
    for (name, adsk) in names("fractal", "Fractal") {
        let flat = format!(r#"shader "tex" "{name}" ("amplitude" 0, "threshold" 0.2)"#);
        assert_rgb(shade(&flat, adsk, [0.3, 0.6]), [0.7; 3], 1e-6);
        let none = format!(r#"shader "tex" "{name}" ("levelMin" 3, "levelMax" 3)"#);
        assert_rgb(shade(&none, adsk, [0.3, 0.6]), [0.5; 3], 1e-6);
        let tex = format!(r#"shader "tex" "{name}" ()"#);
        let values: Vec<f32> = (0..8).map(|i| shade(&tex, adsk, [0.11 * i as f32 + 0.05, 0.37]).x).collect();
        assert!(values.iter().all(|v| (0.0..=1.0).contains(v)), "{values:?}");
        let spread = values.iter().cloned().fold(f32::MIN, f32::max) - values.iter().cloned().fold(f32::MAX, f32::min);
        assert!(spread > 0.05, "{values:?}");
    }
}

/// Mountain on level ground (amplitude 0, boundary 0: height ½): snow colour below a
/// snow altitude of 0.3, rock colour above one of 0.7, rock everywhere with a snow slope
/// of 0 (1e-5); its alpha is the height.
#[test]
fn mountain_snow_lies_above_its_altitude_on_gentle_slopes() {
    for (name, adsk) in names("mountain", "Mountain") {
        let tex = |extra: &str| {
            format!(
                r#"shader "tex" "{name}" ("amplitude" 0, "boundary" 0, "snowColor" 0.9 0.95 1, "rockColor" 0.3 0.2 0.1{extra})"#
            )
        };
        assert_rgb(shade(&tex(r#", "snowAltitude" 0.3"#), adsk, [0.3, 0.6]), [0.9, 0.95, 1.0], 1e-5);
        assert_rgb(shade(&tex(r#", "snowAltitude" 0.7"#), adsk, [0.3, 0.6]), [0.3, 0.2, 0.1], 1e-5);
        assert_rgb(shade(&tex(r#", "snowAltitude" 0.3, "snowSlope" 0"#), adsk, [0.3, 0.6]), [0.3, 0.2, 0.1], 1e-5);
    }
}

/// Water with one wave along +u (frequency 4, amplitude 0.1, no ripple): ½ + 0.1 cos(2π·4u)
/// (1e-5); no waves and no ripple time: still at ½; a ripple at ripple time 0.2 with
/// phase velocity 0 peaks at ½ + 0.05 on its ring 0.2 from the origin.
#[test]
fn water_waves_and_ripples_follow_their_formulas() {
    for (name, adsk) in names("water", "Water") {
        let wave = format!(r#"shader "tex" "{name}" ("numberOfWaves" 1, "waveAmplitude" 0.1)"#);
        assert_rgb(shade(&wave, adsk, [0.0, 0.3]), [0.6; 3], 1e-5);
        assert_rgb(shade(&wave, adsk, [0.125, 0.3]), [0.4; 3], 1e-5);
        let still = format!(r#"shader "tex" "{name}" ("numberOfWaves" 0)"#);
        assert_rgb(shade(&still, adsk, [0.3, 0.6]), [0.5; 3], 1e-6);
        let ripple = format!(r#"shader "tex" "{name}" ("numberOfWaves" 0, "rippleTime" 0.2, "phaseVelocity" 0)"#);
        assert_rgb(shade(&ripple, adsk, [0.7, 0.5]), [0.55; 3], 1e-5);
    }
}

/// Contrast on a connected colour: 0.25 and 0.75 with contrast 2 about bias ½ become
/// 0.125 and 0.875, the bias itself stays, contrast 0 gives the bias (1e-5).
#[test]
fn contrast_pushes_values_away_from_the_bias() {
    for (name, adsk) in [("maya_contrast", false), ("adskMayaContrast", true)] {
        let at = |params: &str| {
            shade(
                &format!(
                    r#"shader "c" "{name}" ({params})
                    shader "tex" "{}" ("outColor" = "c.outValue")"#,
                    if adsk { "adskMayaSurfaceShader" } else { "maya_surfaceshader" }
                ),
                adsk,
                [0.3, 0.6],
            )
        };
        assert_rgb(at(r#""value" 0.25 0.75 0.5"#), [0.125, 0.875, 0.5], 1e-5);
        assert_rgb(at(r#""value" 0.25 0.75 0.3, "contrast" 0 0 0, "bias" 0.4 0.4 0.4"#), [0.4; 3], 1e-5);
        assert_rgb(at(r#""value" 0.3 0.3 0.3, "contrast" 2 2 2, "bias" 0.3 0.3 0.3"#), [0.3; 3], 1e-5);
    }
}

/// A lambert coloured by each new texture: the path engine's translation gives the
/// classic shader's diffuse colour per hit (c·d under the unit light straight above,
/// 1e-5), at two points of the tile.
#[test]
fn the_path_engine_reads_the_new_textures_per_hit() {
    let sun = r#"light "sun" "maya_directionallight" ("intensity" 1) direction 0 -1 0 end light
        instance "sun_inst" "sun" end instance"#;
    for tex in [
        r#"shader "tex" "maya_bulge" ()"#,
        r#"shader "tex" "maya_cloth" ("vColor" 0.9 0.1 0.1)"#,
        r#"shader "tex" "maya_fractal" ()"#,
        r#"shader "tex" "maya_mountain" ()"#,
        r#"shader "tex" "maya_water" ()"#,
    ] {
        let c = compile(
            "",
            &format!(
                r#"{LIBS}{sun}
                {tex}
                shader "lam" "maya_lambert" ("color" = "tex.outColor", "diffuse" 0.5)
                material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#
            ),
            &["m"],
            "",
        );
        assert!(c.messages.is_empty(), "{tex}: {:#?}", c.messages);
        let (s, warnings) = material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("Maya");
        assert!(warnings.is_empty(), "{tex}: {warnings:?}");
        assert!(matches!(s.varying, Varying::Bindings(_)), "{tex}: {:?}", s.varying);
        let tracer = Empty::default();
        for uv in [[0.3, 0.6], [0.25, 0.25]] {
            let mut ctx = Ctx::new(&c.shading, &tracer, point(uv));
            let hit = s.at(&mut ctx);
            let classic = run(&c, &tracer, c.material("m"), point(uv)).color();
            for i in 0..3 {
                assert!(
                    (hit.diffuse[i] - classic[i]).abs() < 1e-5,
                    "{tex} {uv:?}: path {} classic {classic}",
                    hit.diffuse
                );
            }
        }
    }
}
