//! Cube maps written as ordinary images render: a vertical cross (3n × 4n, −z turned by
//! 180° at the bottom) and six face images `sky_px.ppm` … `sky_nz.ppm` (standing for the
//! absent `sky.ppm`), looked up by a module environment along the direction: in both
//! engines the view straight down −Z shows the −z face and three mirrors show the +z, +y
//! and +y faces (their reflections (0, sin 2α, cos 2α) for α = 15°, 30°, 45°), within 1e-4
//! of the faces' 8-bit colours. (Orientations within faces, texel by texel, are tested in
//! `crates/material/tests/it/mdl_textures3d.rs`.)

use crate::mdl_environment::{mirrors, module_dir, scene};
use crate::support;

use render::{EngineKind, Settings};

/// Each face's colour: +x, −x, +y, −y, +z, −z.
const FACES: [[u8; 3]; 6] = [[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 0], [51, 102, 153], [255, 0, 255]];

const MODULE: &str = r#"mdl 1.7;
import ::tex::*;
import ::state::*;
export color cross_env() = tex::lookup_color(texture_cube("./vcross.ppm"), state::direction());
export color faces_env() = tex::lookup_color(texture_cube("./sky.ppm"), state::direction());
"#;

/// A binary PPM of `w` × `h` texels.
fn ppm(w: usize, h: usize, texels: &[[u8; 3]]) -> Vec<u8> {
    let mut out = format!("P6\n{w} {h}\n255\n").into_bytes();
    out.extend(texels.iter().flatten());
    out
}

#[test]
fn cube_maps_from_a_vertical_cross_and_six_face_images_render() {
    let dir = module_dir("cube_forms");
    std::fs::write(dir.join("cubes.mdl"), MODULE).unwrap();
    let n = 4;
    // The vertical cross's cells (column, row) of +x, −x, +y, −y, +z, −z.
    let cells = [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (1, 3)];
    let mut cross = vec![[0u8; 3]; 3 * n * 4 * n];
    for (face, (cx, cy)) in cells.iter().enumerate() {
        for (x, y) in (0..n * n).map(|i| (i % n, i / n)) {
            cross[(cy * n + y) * 3 * n + cx * n + x] = FACES[face];
        }
    }
    std::fs::write(dir.join("vcross.ppm"), ppm(3 * n, 4 * n, &cross)).unwrap();
    for (face, suffix) in ["px", "nx", "py", "ny", "pz", "nz"].into_iter().enumerate() {
        std::fs::write(dir.join(format!("sky_{suffix}.ppm")), ppm(n, n, &vec![FACES[face]; n * n])).unwrap();
    }
    let (body, names, _) = mirrors();
    // Column 0: −Z (the −z face); columns 1–3: +z, +y, +y.
    let seen = [FACES[5], FACES[4], FACES[2], FACES[2]];
    for function in ["cross_env", "faces_env"] {
        let text = scene(&format!("environment \"mdl::cubes::{function}\" ()"), "", &body, &names, 4);
        let parsed = mi::parse_str("t.mi", &text);
        let built = support::build_parsed(&parsed, 4, std::slice::from_ref(&dir));
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        for engine in [EngineKind::Path, EngineKind::Classic] {
            let settings = Settings { engine, spp: Some(4), ..Settings::default() };
            let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
            for (i, p) in film.rgba().iter().enumerate() {
                let want = seen[i % 4].map(|c| f32::from(c) / 255.0);
                for k in 0..3 {
                    assert!((p[k] - want[k]).abs() <= 1e-4, "{function}, {engine:?}: pixel {i} {p:?} vs {want:?}");
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
