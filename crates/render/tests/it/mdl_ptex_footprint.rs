//! The filter width each engine hands a `texture_ptex` lookup: the pixel's footprint at
//! the hit in face units (the classic engine's ray footprint, the path engine's camera
//! footprint; `material::mdl_modules::ptex::footprint`), which picks the face's reduced
//! level. A triangle-mesh Ptex file written here byte by byte (zlib blocks stored,
//! uncompressed): every face of 8 × 8 texels, a fine checker of 0.2 and 0.8, its reduced
//! levels (4 × 4, 2 × 2) and its average all 0.5. A Lambertian material of that colour
//! seen and lit head-on (a pixel is its albedo in the path engine, π times in the classic
//! engine).
//!
//! What is asserted: a grid of 512 such triangles, two faces to a pixel, renders 0.5 in
//! every pixel within 1e-3 (level 0 would give values up to 0.8); the same file seen
//! from so close that the image spans 2e-6 scene units around one texel's centroid renders
//! that texel (0.8, then 0.2 at another) within 1e-4; each image is the same bit for bit
//! on one thread and on three.

use crate::mdl_ptex::{ptex_scene, zlib_stored};
use crate::support;
use crate::support::scene_text::SceneText;
use render::{EngineKind, Settings};

/// Level 0's texel `t` of a face (8 × 8 square image, row v = 0 first): 0.8 where its
/// row and column add up odd, else 0.2.
fn checker(t: usize) -> f32 {
    if (t % 8 + t / 8) % 2 == 1 {
        0.8
    } else {
        0.2
    }
}

/// A triangle-mesh Ptex file of `faces` faces (one float channel, no adjacency): level 0
/// the checker, levels 1 and 2 (Ptex's reduction order is face order here: one
/// resolution) and each face's average 0.5.
fn ptex_file(faces: usize) -> Vec<u8> {
    let floats = |v: &[f32]| v.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    let mut infos = Vec::new();
    for _ in 0..faces {
        infos.extend([3u8, 3, 0, 0]);
        infos.extend([-1i32; 4].iter().flat_map(|a| a.to_le_bytes()));
    }
    let constants = floats(&vec![0.5; faces]);
    let level0: Vec<f32> = (0..64).map(checker).collect();
    let levels: Vec<Vec<u8>> = [level0, vec![0.5; 16], vec![0.5; 4]]
        .iter()
        .map(|texels| {
            let block = zlib_stored(&floats(texels));
            let word = (block.len() as u32 | 1 << 30).to_le_bytes();
            let mut data = zlib_stored(&word.repeat(faces));
            for _ in 0..faces {
                data.extend(&block);
            }
            data
        })
        .collect();
    let (zinfo, zconst) = (zlib_stored(&infos), zlib_stored(&constants));
    let words_len = zlib_stored(&vec![0u8; 4 * faces]).len() as u32;
    let level_size: u64 = levels.iter().map(|l| l.len() as u64).sum();
    let mut out = b"Ptex".to_vec();
    // Version 1, triangles, float, no alpha, 1 channel, 3 levels.
    for w in [1u32, 0, 3] {
        out.extend(w.to_le_bytes());
    }
    out.extend((-1i32).to_le_bytes());
    out.extend(1u16.to_le_bytes());
    out.extend(3u16.to_le_bytes());
    for w in [faces as u32, 40, zinfo.len() as u32, zconst.len() as u32, 48, 4] {
        out.extend(w.to_le_bytes());
    }
    out.extend(level_size.to_le_bytes());
    out.extend([0u8; 8]);
    out.extend([0u8; 40]);
    out.extend(zinfo);
    out.extend(zconst);
    for l in &levels {
        out.extend((l.len() as u64).to_le_bytes());
        out.extend(words_len.to_le_bytes());
        out.extend((faces as u32).to_le_bytes());
    }
    for l in &levels {
        out.extend(l);
    }
    out.extend([0u8; 8]);
    out
}

const MODULE: &str = r#"mdl 1.7;
import ::df::*;
import ::tex::*;
export material faces() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: tex::lookup_color(texture_ptex("./checker.ptx")))));
"#;

/// The scene: the camera (aperture `aperture`, focal 1, 8 × 8 pixels, at the origin
/// looking down −z) and the object `object`, lit head-on.
fn scene(aperture: f64, object: &str) -> String {
    let head = SceneText::head_on(8).camera(&format!("focal 1 aperture {aperture} aspect 1"));
    ptex_scene(head, "faces", object, &["mesh"])
}

/// A grid of `n` × `n` squares over [−1, 1]² at z = −1, each two triangles (`p a b c`,
/// `p a c d`), shifted by (`dx`, `dy`).
fn grid(n: usize, dx: f64, dy: f64) -> String {
    let mut text = String::from("object \"mesh\" group\n");
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (-1.0 + 2.0 * i as f64 / n as f64, -1.0 + 2.0 * j as f64 / n as f64);
            text += &format!("{} {} -1\n", x + dx, y + dy);
        }
    }
    for k in 0..(n + 1) * (n + 1) {
        text += &format!("v {k} ");
    }
    text += "\n";
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            text += &format!("p {a} {b} {c}\np {a} {c} {d}\n");
        }
    }
    text + "end group end object"
}

/// The pixels of `text` rendered by `engine` on `threads` threads (4 samples a pixel).
fn render(dir: &std::path::Path, text: &str, engine: EngineKind, threads: usize) -> Vec<[f32; 4]> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a thread pool");
    pool.install(|| {
        let parsed = mi::parse_str("t.mi", text);
        let built = support::build_parsed(&parsed, 8, &[dir.to_path_buf()]);
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        let settings = Settings { engine, spp: Some(4), ..Settings::default() };
        support::render_world(&built.built.world, &built.built.shading, &settings).0.rgba()
    })
}

/// Renders `text` in both engines on one and three threads: asserts the two are the same
/// bit for bit and every pixel is `want` (the classic engine's π times) within `tol`.
fn assert_renders(dir: &std::path::Path, text: &str, want: f32, tol: f32) {
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let one = render(dir, text, engine, 1);
        let three = render(dir, text, engine, 3);
        let bits = |p: &[[f32; 4]]| p.iter().flat_map(|c| c.map(f32::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(&one), bits(&three), "{engine:?}: one thread against three");
        let scale = if engine == EngineKind::Classic { std::f32::consts::PI } else { 1.0 };
        for (k, p) in one.iter().enumerate() {
            for c in &p[..3] {
                assert!((c / scale - want).abs() <= tol, "{engine:?}, pixel {k}: {p:?}, not {want} × {scale}");
            }
        }
    }
}

/// Far: 512 triangles (face side 1/8) under 8 × 8 pixels of 1/4 — a footprint of two faces
/// picks each face's average: 0.5 everywhere (1e-3). Near: the centroid of texel (2, 1)
/// (0.8) of triangle 0 (`p 0 1 2`, u along +x, v along the diagonal) at the centre of an
/// image 2e-6 across, then of texel (1, 1) (0.2): that texel (1e-4).
#[test]
fn a_footprint_picks_the_average_far_away_and_level_zero_up_close() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_footprint_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    std::fs::write(dir.join("checker.ptx"), ptex_file(512)).unwrap();
    assert_renders(&dir, &scene(2.0, &grid(16, 0.0, 0.0)), 0.5, 1e-3);
    // Triangle 0 of a single square over [−1, 1]²: barycentric (u, v) is the point
    // (−1 + 2u + 2v, −1 + 2v); a texel (i, j)'s centroid is ((i + ⅓)/8, (j + ⅓)/8).
    for ((i, j), want) in [((2.0, 1.0), 0.8), ((1.0, 1.0), 0.2)] {
        let (u, v) = ((i + 1.0 / 3.0) / 8.0, (j + 1.0 / 3.0) / 8.0);
        let (x, y) = (-1.0 + 2.0 * u + 2.0 * v, -1.0 + 2.0 * v);
        assert_renders(&dir, &scene(2e-6, &grid(1, -x, -y)), want, 1e-4);
    }
    std::fs::remove_dir_all(&dir).ok();
}
