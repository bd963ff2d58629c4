//! `mia_material`'s glossy interpolation (`refl_interpolate`) in the classic engine: a
//! glossy floor reflecting a sky with a low sun renders to the same values as without
//! interpolation, within the noise, and smoother from pixel to pixel.

use crate::support;

use render::EngineKind;

const RES: usize = 48;

/// Renders the floor scene with interpolation `on` or off: the pixels (RGBA, rows from
/// the top).
fn render(interpolate: bool) -> Vec<[f32; 4]> {
    let text = format!(
        r#"options "opt" filter box 1 1 samples 0 0 end options
camera "cam" focal 1 aperture 1.2 aspect 1 resolution {RES} {RES}
    environment "mia_physicalsky" ("y_is_up" on, "sun_direction" 0.3 0.25 -1, "horizon_blur" 0)
end camera
instance "cam_inst" "cam" end instance
material "floor" "mia_material_x" (
    "diffuse_weight" 0, "reflectivity" 1, "refl_color" 1 1 1, "refl_gloss" 0.5,
    "refl_gloss_samples" 4, "brdf_fresnel" off, "brdf_0_degree_refl" 1, "brdf_90_degree_refl" 1,
    "refl_interpolate" {}, "intr_grid_density" 2, "indirect_multiplier" 0)
end material
object "plane" group
    -40 -1 -60  40 -1 -60  40 -1 0.5  -40 -1 0.5
    v 0 v 1 v 2 v 3 c "floor" 0 3 2 c "floor" 0 2 1
end group end object
instance "plane_inst" "plane" end instance
instgroup "root" "cam_inst" "plane_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        if interpolate { "on" } else { "off" }
    );
    let (pixels, messages) = support::render_text(&text, EngineKind::Classic, None);
    assert!(messages.is_empty(), "{messages:?}");
    pixels
}

fn luminance(p: [f32; 4]) -> f32 {
    0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]
}

/// Rows of the floor well below the horizon (row RES/2) and above the image's bottom.
fn floor_rows() -> std::ops::Range<usize> {
    RES / 2 + 6..RES
}

/// Mean squared difference of horizontally adjacent floor pixels' luminance, relative to
/// the squared mean: the image's pixel-to-pixel noise (the floor's true image changes
/// slowly along a row).
fn roughness(img: &[[f32; 4]]) -> f32 {
    let (mut sq, mut sum, mut count) = (0.0f64, 0.0f64, 0u32);
    for y in floor_rows() {
        for x in 0..RES - 1 {
            let (a, b) = (luminance(img[y * RES + x]), luminance(img[y * RES + x + 1]));
            sq += f64::from((a - b) * (a - b));
            sum += f64::from(a);
            count += 1;
        }
    }
    let mean = sum / f64::from(count);
    (sq / f64::from(count) / (mean * mean)) as f32
}

#[test]
fn interpolation_agrees_within_noise_and_is_smoother() {
    let plain = render(false);
    let smooth = render(true);
    // Agreement: the mean of every block of 8 × 6 floor pixels, within 4 standard errors
    // of the plain block's mean (its pixels' spread / √48) plus 1 %.
    let rows: Vec<usize> = floor_rows().collect();
    for band in rows.chunks(6).filter(|b| b.len() == 6) {
        for x0 in (0..RES).step_by(8) {
            let px = |img: &[[f32; 4]]| -> Vec<f32> {
                band.iter()
                    .flat_map(|&y| (x0..x0 + 8).map(move |x| (y, x)))
                    .map(|(y, x)| luminance(img[y * RES + x]))
                    .collect()
            };
            let (a, b) = (px(&plain), px(&smooth));
            let n = a.len() as f32;
            let (ma, mb) = (a.iter().sum::<f32>() / n, b.iter().sum::<f32>() / n);
            let var = a.iter().map(|v| (v - ma) * (v - ma)).sum::<f32>() / (n - 1.0);
            let se = (var / n).sqrt();
            assert!((ma - mb).abs() < 4.0 * se + 0.01 * ma, "block ({x0}, {}): {ma} vs {mb} (se {se})", band[0]);
        }
    }
    // Smoother: the pixel-to-pixel noise falls to at most half.
    let (r0, r1) = (roughness(&plain), roughness(&smooth));
    eprintln!("pixel-to-pixel roughness: plain {r0:.5}, interpolated {r1:.5}");
    assert!(r1 < 0.5 * r0, "plain {r0}, interpolated {r1}");
}
