//! The physical sun and sky in the classic engine, end to end: a camera environment
//! `mia_physicalsky` seen above the horizon and a ground plane lit by `mia_physicalsun`,
//! half of it in the shadow of an invisible card.

use crate::support;

use render::EngineKind;

/// Renders `text` with the classic engine: the pixels (RGBA, rows from the top) and the
/// diagnostics.
fn render(text: &str) -> (Vec<[f32; 4]>, Vec<String>) {
    support::render_text(text, EngineKind::Classic, None)
}

/// Y up: a 90° camera at the origin looking down −Z; the sun 45° up behind it; a grey
/// plane at y = −1 in front; a card at y = 0 over x < 0 that is invisible to the camera
/// but casts a shadow on the left half of the plane.
const SCENE: &str = r#"
options "opt" filter box 1 1 samples 0 0 end options
light "sun" "mia_physicalsun" ("y_is_up" on) direction 0 -0.70710678 -0.70710678 end light
instance "sun_inst" "sun" end instance
camera "cam" focal 1 aperture 2 aspect 1 resolution 16 16
    environment "mia_physicalsky" ("sun" "sun_inst", "y_is_up" on, "horizon_blur" 0)
end camera
instance "cam_inst" "cam" end instance
material "grey" "mib_illum_lambert" ("diffuse" 0.5 0.5 0.5 1, "mode" 0, "lights" ["sun_inst"]) end material
object "plane" group
    -20 -1 -40  20 -1 -40  20 -1 1  -20 -1 1
    v 0 v 1 v 2 v 3 c "grey" 0 3 2 1
end group end object
instance "plane_inst" "plane" end instance
object "card" visible off group
    -20 0 -40  0 0 -40  0 0 1  -20 0 1
    v 0 v 1 v 2 v 3 c "grey" 0 3 2 1
end group end object
instance "card_inst" "card" end instance
instgroup "root" "cam_inst" "sun_inst" "plane_inst" "card_inst" end instgroup
render "root" "cam_inst" "opt"
"#;

fn luminance(p: [f32; 4]) -> f32 {
    0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]
}

#[test]
fn physical_sky_above_the_horizon_and_sunlit_plane_with_a_shadow() {
    let (pixels, messages) = render(SCENE);
    assert!(messages.is_empty(), "{messages:?}");
    let at = |x: usize, y: usize| pixels[y * 16 + x];
    // The sky (upper half): blue, opaque, in the default units (luminance × π × 1e-4:
    // between 0.3 and 10).
    for y in 0..7 {
        for x in [1, 8, 14] {
            let p = at(x, y);
            assert!(p[2] > p[0], "sky pixel ({x}, {y}) is not blue: {p:?}");
            assert!((0.3..10.0).contains(&luminance(p)), "sky pixel ({x}, {y}): {p:?}");
            assert!((p[3] - 1.0).abs() < 1e-6);
        }
    }
    // Brighter towards the horizon (row 7 is 3.6° up, row 0 43°).
    assert!(luminance(at(8, 7)) > 1.5 * luminance(at(8, 0)), "{:?} {:?}", at(8, 7), at(8, 0));
    // The plane: lit on the right (x > 0), shadowed on the left. Lit: 0.5 × the sun's
    // illuminance (≈ 9.3e4 lux × 1e-4) × cos 45° ≈ 3.3 in luminance.
    for y in [10, 12, 15] {
        let (lit, dark) = (at(12, y), at(3, y));
        assert!((2.5..4.0).contains(&luminance(lit)), "lit ({y}): {lit:?}");
        assert!(luminance(dark) < 0.01 * luminance(lit), "shadow ({y}): {dark:?} vs {lit:?}");
        // Sunlight through a clear atmosphere is warm: r > b.
        assert!(lit[0] > lit[2], "{lit:?}");
    }
}
