//! `mia_physicalsky` as a lens shader with `visibility_distance` in the classic engine: a
//! wall at the 10 % distance is blended 90 % into the sky's haze colour of each
//! direction; rays that miss see the sky unchanged.

use crate::support;

use glam::Vec3A;
use mia::aerial::{aerial_transmittance, haze_color};
use mia::sky::PhysicalSky;
use render::EngineKind;

/// Renders `text` with the classic engine: the pixels (RGBA, rows from the top).
fn render(text: &str) -> Vec<[f32; 4]> {
    let (pixels, messages) = support::render_text(text, EngineKind::Classic, None);
    assert!(messages.is_empty(), "{messages:?}");
    pixels
}

/// The sky's parameters (Y up, the sun 40° up to the upper right, behind the camera).
const SKY: &str = r#""y_is_up" on, "sun_direction" 0.5 0.6427876 0.58, "haze" 2, "horizon_blur" 0"#;

/// A 16 × 16 camera at the origin looking down −Z with a 11.4° field (film 0.2 wide at
/// focal length 1), the sky as environment and, with `visibility` > 0, as lens shader;
/// with `wall`, a wall of constant colour (0.2, 0.5, 0.1) at z = −30 fills the view.
fn scene(visibility: f32, wall: bool) -> String {
    let lens = if visibility > 0.0 {
        format!("lens \"mia_physicalsky\" ({SKY}, \"visibility_distance\" {visibility})")
    } else {
        String::new()
    };
    let wall = if wall {
        r#"material "paint" "mib_illum_lambert" ("ambience" 0.2 0.5 0.1 1, "ambient" 1 1 1 1, "diffuse" 0 0 0 1, "mode" 0, "lights" []) end material
object "wall" group
    -20 -20 -30  20 -20 -30  20 20 -30  -20 20 -30
    v 0 v 1 v 2 v 3 c "paint" 0 1 2 c "paint" 0 2 3
end group end object
instance "wall_inst" "wall" end instance
instgroup "root" "cam_inst" "wall_inst" end instgroup"#
    } else {
        r#"instgroup "root" "cam_inst" end instgroup"#
    };
    format!(
        r#"options "opt" filter box 1 1 samples 0 0 end options
camera "cam" focal 1 aperture 0.2 aspect 1 resolution 16 16
    environment "mia_physicalsky" ({SKY})
    {lens}
end camera
instance "cam_inst" "cam" end instance
{wall}
render "root" "cam_inst" "opt"
"#
    )
}

/// The sky of [`SKY`] as mira's model.
fn sky() -> PhysicalSky {
    PhysicalSky {
        y_is_up: true,
        sun_direction: Vec3A::new(0.5, 0.642_787_6, 0.58),
        haze: 2.0,
        horizon_blur: 0.0,
        ..PhysicalSky::default()
    }
}

/// The world direction through the centre of pixel (x, y).
fn pixel_dir(x: usize, y: usize) -> Vec3A {
    let u = ((x as f32 + 0.5) / 16.0 - 0.5) * 0.2;
    let v = (0.5 - (y as f32 + 0.5) / 16.0) * 0.2;
    Vec3A::new(u, v, -1.0).normalize()
}

#[test]
fn a_wall_at_the_visibility_distance_is_ninety_percent_haze() {
    let plain = render(&scene(0.0, true));
    let misted = render(&scene(30.0, true));
    let sky = sky();
    let paint = [0.2, 0.5, 0.1];
    for (x, y) in [(7, 7), (8, 8), (2, 3), (13, 12), (8, 1), (6, 14)] {
        let i = y * 16 + x;
        // Without the lens shader: the wall's own colour, exactly.
        for k in 0..3 {
            assert!((plain[i][k] - paint[k]).abs() < 1e-6, "{:?}", plain[i]);
        }
        // With it: the wall's colour × T + haze × (1 − T); T = 0.1 on the optical axis,
        // 0.1^(1/cos) off it (0.098 at the corners of this narrow view).
        let d = pixel_dir(x, y);
        let t = aerial_transmittance(30.0 / -d.z, 30.0);
        assert!((0.097..=0.1).contains(&t), "{t}");
        let haze = haze_color(&sky, d);
        for k in 0..3 {
            let want = paint[k] * t + haze[k] * (1.0 - t);
            // Within 1 % (the sample lies anywhere in the pixel; haze and distance change
            // little across one).
            assert!(
                (misted[i][k] - want).abs() < 0.01 * want,
                "pixel ({x}, {y}) channel {k}: {:?} vs {want}",
                misted[i]
            );
        }
        assert!((misted[i][3] - 1.0).abs() < 1e-6);
    }
    // The haze dominates: the misted wall is the bright, near-white horizon sky of a hazy
    // day (luminance ≈ 2 in the default units), not the dark green paint (0.41).
    let lum = |p: [f32; 4]| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    for i in [16 + 8, 14 * 16 + 8] {
        assert!(lum(misted[i]) > 3.0 * lum(plain[i]), "{:?} {:?}", misted[i], plain[i]);
    }
}

#[test]
fn rays_that_miss_see_the_sky_unchanged() {
    let without = render(&scene(0.0, false));
    let with = render(&scene(30.0, false));
    for (a, b) in without.iter().zip(&with) {
        for k in 0..4 {
            assert!((a[k] - b[k]).abs() <= 1e-6 * a[k].abs().max(1.0), "{a:?} {b:?}");
        }
    }
    // And half the distance leaves √0.1 of the wall.
    let half = render(&scene(60.0, true));
    let d = pixel_dir(8, 8);
    let t = aerial_transmittance(30.0 / -d.z, 60.0);
    assert!((t - 0.1f32.sqrt()).abs() < 0.003, "{t}");
    let want = 0.5 * t + haze_color(&sky(), d).y * (1.0 - t);
    assert!((half[8 * 16 + 8][1] - want).abs() < 0.01 * want, "{:?} {want}", half[8 * 16 + 8]);
}
