//! Module materials that look up a `texture_cube` and a `texture_3d` (DDS files the test
//! writes byte by byte beside its module) render their texture's colour: a square lit
//! head-on so that a Lambertian pixel is its albedo ([`support::lit_square`]), tinted by
//! the cube map along the shading normal (+z: the +z face's colour) and by the volume at
//! its centre (the mean of its eight voxels), in both engines (the classic engine's pixels
//! π times the path engine's: mental ray's base lights carry no 1/π, see `mdl_classic`).

use crate::support;
use render::{EngineKind, Settings};

/// The DDS header (magic and 124 bytes) of a `w` × `h` × `d` texture with `pixel_format`
/// (32 bytes), `caps2` (cube faces, volume) and `flags` added to the required ones.
fn header(w: u32, h: u32, d: u32, pixel_format: [u32; 8], caps2: u32, flags: u32) -> Vec<u8> {
    let mut words = vec![124, 0x1 | 0x2 | 0x4 | 0x1000 | flags, h, w, 0, d, 1];
    words.extend([0; 11]);
    words.extend(pixel_format);
    words.extend([0x1000 | 0x8, caps2, 0, 0, 0]);
    let mut out = b"DDS ".to_vec();
    out.extend(words.iter().flat_map(|w| w.to_le_bytes()));
    out
}

const MODULE: &str = r#"mdl 1.7;
import ::df::*;
import ::tex::*;
import ::state::*;
export material cube() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: tex::lookup_color(texture_cube("./faces.dds"), state::normal()))));
export material volume() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: tex::lookup_color(texture_3d("./voxels.dds"), float3(0.5)))));
"#;

/// Writes the module and its textures into a directory of their own: a cube map of 1 × 1
/// faces (8-bit BGRA; +z (0.2, 0.4, 0.6), the others black) and 2 × 2 × 2 voxels
/// (32-bit float RGBA, voxel n of the file (n/8, 0.5, 1 − n/8)).
fn fixtures() -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("mira_render_tex3d_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("textures3d.mdl"), MODULE).unwrap();
    let argb = [32, 0x41, 0, 32, 0x00ff_0000, 0x0000_ff00, 0x0000_00ff, 0xff00_0000];
    let mut cube = header(1, 1, 0, argb, 0xfe00, 0);
    for face in 0..6 {
        let [r, g, b] = if face == 4 { [51u8, 102, 153] } else { [0; 3] };
        cube.extend([b, g, r, 255]);
    }
    std::fs::write(dir.join("faces.dds"), cube).unwrap();
    let dx10 = [32, 0x4, u32::from_le_bytes(*b"DX10"), 0, 0, 0, 0, 0];
    let mut volume = header(2, 2, 2, dx10, 0x20_0000, 0x80_0000);
    volume.extend([2u32, 4, 0, 1, 0].iter().flat_map(|w| w.to_le_bytes()));
    for n in 0..8 {
        let t = n as f32 / 8.0;
        volume.extend([t, 0.5, 1.0 - t, 1.0].iter().flat_map(|f| f.to_le_bytes()));
    }
    std::fs::write(dir.join("voxels.dds"), volume).unwrap();
    dir
}

#[test]
fn module_materials_render_their_cube_and_volume_texture_colours() {
    let dir = fixtures();
    // The volume's centre weighs its eight voxels alike: red 3.5/8, green ½, blue 4.5/8.
    for (shader, want) in [("cube", [0.2f32, 0.4, 0.6]), ("volume", [3.5 / 8.0, 0.5, 4.5 / 8.0])] {
        for engine in [EngineKind::Path, EngineKind::Classic] {
            let body = format!(r#"shader "tinted" "mdl::textures3d::{shader}" ()"#);
            let parsed = mi::parse_str("t.mi", &support::lit_square(&body, "tinted"));
            let built = support::build_parsed(&parsed, 8, std::slice::from_ref(&dir));
            assert!(built.messages.is_empty(), "{:#?}", built.messages);
            let settings = Settings { engine, spp: Some(4), ..Settings::default() };
            let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
            let scale = if engine == EngineKind::Classic { std::f32::consts::PI } else { 1.0 };
            for p in film.rgba() {
                for k in 0..3 {
                    // 8-bit texels: 51/255 = 0.2 exactly, 102/255 = 0.4, 153/255 = 0.6.
                    let want = want[k] * scale;
                    assert!((p[k] - want).abs() <= 1e-4 * scale, "{shader}, {engine:?}: {p:?} vs {want}");
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
