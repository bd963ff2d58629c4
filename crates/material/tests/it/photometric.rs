//! `mia_photometric_light` against hand-computed illuminance: a white Lambert material
//! (`mib_illum_lambert` returns light colour × diffuse × cos) straight below the light.

use crate::support;

use std::f32::consts::PI;

use glam::Vec3A;
use support::{compile, point, run, Empty};

/// The red channel lit by a light `shader` standing `height` scene units above the point.
fn lit_by(shader: &str, height: f32, extra: &str) -> f32 {
    let body = format!(
        r#"{extra}
           light "l" {shader} origin 0 0 0 end light
           instance "l_inst" "l" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 -{height} 0 1 end instance
           material "m" "mib_illum_lambert" ("diffuse" 1 1 1 1, "mode" 1, "lights" ["l_inst"]) end material"#
    );
    let c = compile(&body, &["m"]);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), point(Vec3A::Y, -Vec3A::Y));
    v.color().x
}

fn mia(params: &str) -> String {
    format!(r#""mia_photometric_light" ({params})"#)
}

#[test]
fn candela_and_lumen_modes_fall_off_with_the_square_of_metres() {
    // 1000 cd at 2 m: 250 lx.
    let e = lit_by(&mia(r#""manual_peak_intensity_cd" 1000"#), 2.0, "");
    assert!((e - 250.0).abs() < 1e-3, "{e}");
    // The same 2 m written as 200 cm.
    let e = lit_by(&mia(r#""manual_peak_intensity_cd" 1000, "units_to_meter_scale" 0.01"#), 200.0, "");
    assert!((e - 250.0).abs() < 1e-3, "{e}");
    // 4000 lm spread isotropically: 4000 / 4π cd, at 2 m.
    let e = lit_by(&mia(r#""intensity_mode" 1, "manual_flux_lm" 4000"#), 2.0, "");
    assert!((e - 4000.0 / (4.0 * PI) / 4.0).abs() < 1e-3, "{e}");
    // Colour, multiplier and cm2_factor (divides).
    let e = lit_by(
        &mia(r#""manual_peak_intensity_cd" 1000, "multiplier" 2, "color" 0.5 0.5 0.5, "cm2_factor" 2"#),
        2.0,
        "",
    );
    assert!((e - 125.0).abs() < 1e-3, "{e}");
    assert_eq!(lit_by(&mia(r#""on" off, "manual_peak_intensity_cd" 1000"#), 2.0, ""), 0.0);
    // A spot around local −Z sends nothing sideways (the point lies along local −Y).
    assert_eq!(
        lit_by(&mia(r#""manual_peak_intensity_cd" 1000, "distribution_mode" 1, "spotlight_cosine_bias" 2"#), 2.0, ""),
        0.0
    );
}

#[test]
fn ies_mode_takes_intensity_and_shape_from_the_profile() {
    // Quadrant-symmetric profile: local −Y is vertical 90°, horizontal 270° → the 90°
    // column, 80 cd; at 2 m, 20 lx.
    let dir = std::env::temp_dir().join(format!("mira_mia_ies_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("quad.ies");
    std::fs::write(
        &file,
        "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 2 1 2 0 0 0\n1 1 10\n0 90 180\n0 90\n100 40 0\n100 80 0\n",
    )
    .unwrap();
    let profile = format!(r#"lightprofile "quad" format ies file "{}" end lightprofile"#, file.display());
    let e = lit_by(&mia(r#""intensity_mode" 2, "distribution_mode" 2, "profile" "quad""#), 2.0, &profile);
    assert!((e - 20.0).abs() < 1e-3, "{e}");
    // A manual peak of 1000 cd keeps the profile's shape: 800 cd sideways.
    let e = lit_by(&mia(r#""manual_peak_intensity_cd" 1000, "distribution_mode" 2, "profile" "quad""#), 2.0, &profile);
    assert!((e - 200.0).abs() < 1e-2, "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
