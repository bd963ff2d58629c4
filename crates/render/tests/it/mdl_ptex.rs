//! A module material that looks up a `texture_ptex` renders each triangle's Ptex face: a
//! square of two triangles given as `p` polygons (`p 0 1 2`, face 0; `p 0 2 3`, face 1: a
//! 3-vertex polygon keeps its vertex order, where ear clipping had started face 1 at another
//! vertex and turned its texels) seen and lit head-on so
//! that a Lambertian pixel is its albedo, in both engines (the classic engine's pixels π
//! times the path engine's, as in `mdl_textures3d`). The Ptex file is written here byte
//! by byte (zlib blocks stored uncompressed, by hand): face 0 one constant colour, face 1
//! four texels of resolution 2, where the hit's barycentrics on triangle 1 (u weighting
//! vertex 2, v vertex 3) put them in Ptex's triangle layout; the lookup interpolates
//! between them, so each pixel is checked against the lookup's range over it.

use crate::support;
use crate::support::scene_text::SceneText;
use material::mdl_modules::ptex::{reader, Ptex};
use render::{EngineKind, Settings};

/// `bytes` as a zlib stream of one stored (uncompressed) deflate block.
pub(crate) fn zlib_stored(bytes: &[u8]) -> Vec<u8> {
    let len = u16::try_from(bytes.len()).expect("a stored block holds up to 65535 bytes");
    let mut out = vec![0x78, 0x01, 0x01];
    out.extend(len.to_le_bytes());
    out.extend((!len).to_le_bytes());
    out.extend(bytes);
    let (mut a, mut b) = (1u32, 0u32);
    for &x in bytes {
        a = (a + u32::from(x)) % 65521;
        b = (b + a) % 65521;
    }
    out.extend((b << 16 | a).to_be_bytes());
    out
}

/// Face 0's constant colour.
const FACE0: [f32; 3] = [0.9, 0.6, 0.3];
/// Face 1's texels: 0, 1, 2 the upright small triangles at grid corners (0, 0), (1, 0),
/// (0, 1), 3 the inverted one.
const FACE1: [[f32; 3]; 4] = [[0.1, 0.2, 0.3], [0.4, 0.5, 0.6], [0.7, 0.8, 0.9], [0.25, 0.5, 0.75]];

/// One face the writer stores: its resolution (log2 along u, v) and its RGB texels (row
/// v = 0 first); one texel and `log2` (0, 0): flagged constant.
pub(crate) struct FaceSpec {
    pub(crate) log2: (u8, u8),
    pub(crate) texels: Vec<[f32; 3]>,
}

/// A Ptex file of `faces` (mesh type `mesh`: 0 triangles, 1 quads; RGB floats, no alpha,
/// one level), constant faces flagged in their face info, the others zipped (each
/// channel's plane in turn).
pub(crate) fn ptex_bytes(mesh: u32, faces: &[FaceSpec]) -> Vec<u8> {
    let floats = |v: &[f32]| v.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    let (mut infos, mut constants, mut words, mut blocks) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for f in faces {
        let constant = f.texels.len() == 1;
        infos.extend([f.log2.0, f.log2.1, 0, u8::from(constant)]);
        infos.extend([-1i32; 4].iter().flat_map(|a| a.to_le_bytes()));
        constants.extend(floats(&f.texels[0]));
        if constant {
            words.extend(0u32.to_le_bytes());
        } else {
            let planes: Vec<f32> = (0..3).flat_map(|c| f.texels.iter().map(move |t| t[c])).collect();
            let block = zlib_stored(&floats(&planes));
            words.extend((block.len() as u32 | 1 << 30).to_le_bytes());
            blocks.extend(block);
        }
    }
    let (zinfo, zconst, zwords) = (zlib_stored(&infos), zlib_stored(&constants), zlib_stored(&words));
    let level = (zwords.len() + blocks.len()) as u64;
    let mut out = b"Ptex".to_vec();
    // Version 1, the mesh type, float, no alpha, 3 channels, 1 level, the faces.
    for w in [1u32, mesh, 3] {
        out.extend(w.to_le_bytes());
    }
    out.extend((-1i32).to_le_bytes());
    out.extend(3u16.to_le_bytes());
    out.extend(1u16.to_le_bytes());
    for w in [faces.len() as u32, 40, zinfo.len() as u32, zconst.len() as u32, 16, 4] {
        out.extend(w.to_le_bytes());
    }
    out.extend(level.to_le_bytes());
    out.extend([0u8; 8]);
    out.extend([0u8; 40]);
    out.extend(zinfo);
    out.extend(zconst);
    out.extend(level.to_le_bytes());
    out.extend((zwords.len() as u32).to_le_bytes());
    out.extend((faces.len() as u32).to_le_bytes());
    out.extend(zwords);
    out.extend(blocks);
    out.extend([0u8; 8]);
    out
}

/// The triangle-mesh Ptex file: face 0 constant, face 1 of resolution 2 × 2.
fn ptex_file() -> Vec<u8> {
    ptex_bytes(0, &[FaceSpec { log2: (0, 0), texels: vec![FACE0] }, FaceSpec { log2: (1, 1), texels: FACE1.to_vec() }])
}

/// The colour the file gives at square point (x, y) ∈ [−1, 1]² (`Ptex::lookup`, the
/// lookup the material makes, interpolating between texels): face 0 below the diagonal at
/// barycentric u = (x − y)/2 (vertex 1, (1, −1)), v = (y + 1)/2 (vertex 2, (1, 1)), else
/// face 1 at u = (x + 1)/2 (vertex 2, (1, 1)), v = (y − x)/2 (vertex 3, (−1, 1)).
fn expected(ptex: &Ptex, x: f32, y: f32) -> [f32; 3] {
    let c = if y < x {
        ptex.lookup(0, (x - y) * 0.5, (y + 1.0) * 0.5, None, 0)
    } else {
        ptex.lookup(1, (x + 1.0) * 0.5, (y - x) * 0.5, None, 0)
    };
    [c.x, c.y, c.z]
}

pub(crate) const MODULE: &str = r#"mdl 1.7;
import ::df::*;
import ::tex::*;
export material faces() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: tex::lookup_color(texture_ptex("./faces.ptx")))));
"#;

/// A Ptex test's scene: `head` (the camera and its light, as [`SceneText::head_on`]),
/// shader "tinted" the test module's material `material`, the objects' text `objects`,
/// then an instance `{name}_inst` of material "tinted" for each of `names`, in order.
pub(crate) fn ptex_scene(head: SceneText, material: &str, objects: &str, names: &[&str]) -> String {
    let mut scene = head.text(&format!("shader \"tinted\" \"mdl::ptexmod::{material}\" ()")).text(objects);
    for name in names {
        scene = scene
            .text(&format!("instance \"{name}_inst\" \"{name}\" material \"tinted\" end instance"))
            .instance(&format!("{name}_inst"));
    }
    scene.build()
}

/// The square of two triangles, seen and lit head-on (as `support::lit_square`).
fn scene() -> String {
    ptex_scene(
        SceneText::head_on(8),
        "faces",
        r#"object "square" group
    -1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1
    v 0 v 1 v 2 v 3
    p 0 1 2
    p 0 2 3
end group end object"#,
        &["square"],
    )
}

/// The range (per channel, low and high) of `colour(px, x, y)` over pixel `k` of the 8 × 8
/// image and a margin of `margin` sixteenths of a pixel around it: pixel (px, py from the
/// top) covers x ∈ [−1 + px/4, −1 + (px + 1)/4], y likewise from the top, sampled every
/// 1/16 pixel. The margin: the lookup reads the pixel's footprint, anisotropic in face
/// units (on a 1 × 2 quad twice as long along u as along v even head-on), so where it spans
/// more than a texel its probes along the long axis reach past the sample's place.
fn lookup_range(k: usize, margin: i32, colour: impl Fn(f32, f32, f32) -> [f32; 3]) -> ([f32; 3], [f32; 3]) {
    let (px, py) = ((k % 8) as f32, (k / 8) as f32);
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for a in -margin..=16 + margin {
        for b in -margin..=16 + margin {
            let x = -1.0 + (px + a as f32 / 16.0) / 4.0;
            let y = 1.0 - (py + b as f32 / 16.0) / 4.0;
            let c = colour(px, x, y);
            for ch in 0..3 {
                lo[ch] = lo[ch].min(c[ch]);
                hi[ch] = hi[ch].max(c[ch]);
            }
        }
    }
    (lo, hi)
}

/// Asserts that pixel `k`'s colour `p` lies within `range` × `scale` per channel, within
/// 1e-4 × `scale`.
fn assert_within(engine: EngineKind, k: usize, p: &[f32; 4], (lo, hi): ([f32; 3], [f32; 3]), scale: f32) {
    for c in 0..3 {
        assert!(
            p[c] >= (lo[c] - 1e-4) * scale && p[c] <= (hi[c] + 1e-4) * scale,
            "{engine:?}, pixel {k}: {p:?} outside {lo:?} … {hi:?} × {scale}"
        );
    }
}

/// Every pixel (a box filter of one pixel: the mean of the colour over it) lies within
/// the range of the file's lookup over the pixel and half a pixel around it (the
/// footprint's reach: the path engine's is 2–3 pixels wide at the image's corners, and a
/// right triangle's barycentric axes turn it into an ellipse along a diagonal of the face,
/// aspect 2.6, read by probes along it), per channel, within 1e-4 (the classic engine's π
/// times); on face 0 (constant) the range is its colour, and on face 1 a misplaced texel
/// would leave the range.
#[test]
fn each_triangle_renders_its_ptex_faces_texels() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    std::fs::write(dir.join("faces.ptx"), ptex_file()).unwrap();
    let ptex = reader::read(&ptex_file()).expect("the test file").0;
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let parsed = mi::parse_str("t.mi", &scene());
        let built = support::build_parsed(&parsed, 8, std::slice::from_ref(&dir));
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        let settings = Settings { engine, spp: Some(4), ..Settings::default() };
        let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
        let scale = if engine == EngineKind::Classic { std::f32::consts::PI } else { 1.0 };
        let (mut constant, mut narrow) = (0, 0);
        for (k, p) in film.rgba().iter().enumerate() {
            // The footprint's reach (its ellipse in barycentric units is long along a
            // diagonal of the face even head-on: probes up to half a pixel out).
            assert_within(engine, k, p, lookup_range(k, 8, |_, x, y| expected(&ptex, x, y)), scale);
            let (lo, hi) = lookup_range(k, 0, |_, x, y| expected(&ptex, x, y));
            let spread = (0..3).map(|c| hi[c] - lo[c]).fold(0.0, f32::max);
            constant += usize::from(spread == 0.0);
            narrow += usize::from(spread > 0.0 && spread < 0.15);
        }
        assert!(constant >= 20 && narrow >= 4, "{engine:?}: {constant} constant and {narrow} narrow pixels");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The quad-mesh file's face 0 (the left quad, `c 0 1 4 5`: u along +x, v along +y):
/// 2 × 2 texels.
const QUAD0: [[f32; 3]; 4] = [[0.9, 0.1, 0.1], [0.1, 0.9, 0.1], [0.1, 0.1, 0.9], [0.8, 0.8, 0.2]];

/// Face 1 (the right quad, `p 3 4 1 2`: vertex 0 at the upper right, u along −x, v along
/// −y): 4 × 2 texels, each its own colour.
fn quad1() -> Vec<[f32; 3]> {
    (0..8).map(|t| [0.1 + 0.1 * t as f32, 0.8 - 0.1 * t as f32, 0.05 * t as f32]).collect()
}

/// The colour the file gives at square point (x, y) ∈ [−1, 1]² (`Ptex::lookup`,
/// interpolating between texels): the left quad's face 0 at u = x + 1, v = (y + 1)/2; the
/// right quad's face 1 at u = 1 − x, v = (1 − y)/2.
fn expected_quads(ptex: &Ptex, x: f32, y: f32) -> [f32; 3] {
    let c = if x < 0.0 {
        ptex.lookup(0, x + 1.0, (y + 1.0) / 2.0, None, 0)
    } else {
        ptex.lookup(1, 1.0 - x, (1.0 - y) / 2.0, None, 0)
    };
    [c.x, c.y, c.z]
}

/// Two quads side by side (and, out of view, a pentagon after them: faces 2–6, which the
/// file lacks: black, no warning).
pub(crate) fn quad_scene() -> String {
    ptex_scene(
        SceneText::head_on(8),
        "faces",
        r#"object "quads" group
    -1 -1 -1  0 -1 -1  1 -1 -1  1 1 -1  0 1 -1  -1 1 -1
    10 10 -1  11 10 -1  11.5 10.5 -1  11 11 -1  10 11 -1
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7 v 8 v 9 v 10
    c 0 1 4 5
    p 3 4 1 2
    p 6 7 8 9 10
end group end object"#,
        &["quads"],
    )
}

/// A quad-mesh Ptex file on two quads (one fanned `c` polygon, one ear-clipped `p` polygon
/// whose vertex 0 is its upper right corner): every pixel, on both triangles of each quad,
/// lies within the range of the file's lookup over the pixel within 1e-4 in both engines
/// (the classic engine's π times), the ranges narrow; the pentagon (now its sub-quads'
/// faces) is not warned of. The same with the quads displaced (`approximate displace
/// parametric 2`, by 0: each triangle split into 16 finer ones; and adaptively, `length
/// 0.05`, each triangle split unevenly into hundreds): the fine triangles keep their
/// quads' texels, within the same 1e-4, and nothing is warned of.
#[test]
fn each_quad_renders_its_quad_mesh_ptex_faces_texels() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_quads_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    let faces = [
        FaceSpec { log2: (1, 1), texels: QUAD0.to_vec() },
        FaceSpec { log2: (2, 1), texels: quad1() },
        FaceSpec { log2: (0, 0), texels: vec![[0.5; 3]] },
    ];
    std::fs::write(dir.join("faces.ptx"), ptex_bytes(1, &faces)).unwrap();
    let ptex = reader::read(&ptex_bytes(1, &faces)).expect("the quad file").0;
    // The same quads displaced (by 0, `parametric 2`: each triangle split into 16, which
    // keep their original's faces and places on them).
    let quads = quad_scene();
    let displaced = quads
        .replace(
            "shader \"tinted\" \"mdl::ptexmod::faces\" ()\n",
            "shader \"tinted\" \"mdl::ptexmod::faces\" ()\nshader \"disp\" \"maya_material_displace\" (\"displacement\" 0)\n\
             material \"m\" = \"tinted\" displace = \"disp\" end material\n",
        )
        .replace("object \"quads\" group", "object \"quads\"\n    approximate displace parametric 2\n    group")
        .replace("material \"tinted\" end instance", "material \"m\" end instance");
    let adaptive = displaced.replace("approximate displace parametric 2", "approximate displace length 0.05");
    for (engine, text) in [
        (EngineKind::Path, &quads),
        (EngineKind::Classic, &quads),
        (EngineKind::Path, &displaced),
        (EngineKind::Classic, &displaced),
        (EngineKind::Path, &adaptive),
        (EngineKind::Classic, &adaptive),
    ] {
        let parsed = mi::parse_str("t.mi", text);
        let built = support::build_parsed(&parsed, 8, std::slice::from_ref(&dir));
        let fine = built.built.world.meshes.iter().map(|m| m.triangles.len()).max().unwrap_or(0);
        if *text == quads || *text == displaced {
            assert_eq!(fine, if *text == quads { 7 } else { 7 * 16 }, "{engine:?}");
        } else {
            // Uneven: not 7 · 4^k.
            assert!(fine > 7 * 64 && !(0..8).any(|k| fine == 7 << (2 * k)), "{engine:?}: {fine} fine triangles");
        }
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        // Each quad's diagonal leaves whole texels on either side (the left quad's, from
        // (−1, −1) to (0, 1), has its upper left texel above, its lower right below).
        let settings = Settings { engine, spp: Some(4), ..Settings::default() };
        let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
        let scale = if engine == EngineKind::Classic { std::f32::consts::PI } else { 1.0 };
        let (mut inside, mut spread_sum) = (0, 0.0f32);
        for (k, p) in film.rgba().iter().enumerate() {
            // The seam x = 0 itself belongs to either quad: stay on the pixel's side.
            let (lo, hi) = lookup_range(k, 4, |px, x, y| {
                let x = if px == 3.0 {
                    x.min(-1e-4)
                } else if px == 4.0 {
                    x.max(1e-4)
                } else {
                    x
                };
                expected_quads(&ptex, x, y)
            });
            assert_within(engine, k, p, (lo, hi), scale);
            inside += 1;
            spread_sum += (0..3).map(|c| hi[c] - lo[c]).fold(0.0, f32::max);
        }
        // The ranges are narrow (a misplaced or turned face leaves them): a pixel spans at
        // most half a texel of either face (with the quarter-pixel margin the mean spread
        // measured 0.265; 0.3 allowed).
        assert!(inside == 64 && spread_sum / 64.0 < 0.3, "{engine:?}: mean spread {}", spread_sum / 64.0);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The pentagon `p 2 3 4 0 1` (its vertex 0 is the group's vertex 2) and the triangle
/// `c 5 6 7`, in polygon order, each polygon's vertices (x, y) in its own order.
const NGONS: [&[[f32; 2]]; 2] =
    [&[[-0.1, 0.3], [-0.5, 0.9], [-0.9, 0.3], [-0.9, -0.9], [-0.1, -0.9]], &[[0.1, -0.9], [0.9, -0.9], [0.5, 0.9]]];

/// A pentagon and a triangle in a quad-mesh file's mesh (faces 0–4 the pentagon's
/// sub-quads, 5–7 the triangle's), seen and lit head-on.
fn ngon_scene() -> String {
    ptex_scene(
        SceneText::head_on(32),
        "faces",
        r#"object "ngons" group
    -0.9 -0.9 -1  -0.1 -0.9 -1  -0.1 0.3 -1  -0.5 0.9 -1  -0.9 0.3 -1
    0.1 -0.9 -1  0.9 -0.9 -1  0.5 0.9 -1
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7
    p 2 3 4 0 1
    c 5 6 7
end group end object"#,
        &["ngons"],
    )
}

/// The constant colour of sub-quad face `f`.
fn sub_quad_colour(f: usize) -> [f32; 3] {
    [0.1 + 0.1 * f as f32, 0.9 - 0.1 * f as f32, 0.2 + 0.05 * (f % 3) as f32]
}

/// The Ptex face whose sub-quad region holds point (x, y), by Ptex's split (sub-quad i of
/// an n-gon: its vertex i, the midpoint of edge i → i+1, the vertex mean, the midpoint of
/// edge i−1 → i), each region tested as a counter-clockwise convex quadrilateral.
fn sub_quad_at(x: f32, y: f32) -> Option<usize> {
    let mut first = 0;
    for poly in NGONS {
        let n = poly.len();
        let mean = poly.iter().fold([0.0; 2], |a, p| [a[0] + p[0] / n as f32, a[1] + p[1] / n as f32]);
        let mid = |a: [f32; 2], b: [f32; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        for i in 0..n {
            let (prev, here, next) = (poly[(i + n - 1) % n], poly[i], poly[(i + 1) % n]);
            let quad = [here, mid(here, next), mean, mid(prev, here)];
            let inside = (0..4).all(|k| {
                let (a, b) = (quad[k], quad[(k + 1) % 4]);
                (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]) >= 0.0
            });
            if inside {
                return Some(first + i);
            }
        }
        first += n;
    }
    None
}

/// Checks a 32 × 32 render of the square [−1, 1]² (pixel rows from the top) whose regions
/// are constant colours: every pixel wholly inside one region (`region_at` equal at its
/// four corners, 1e-3 inside) is `colour(region)` within 1e-4 (the classic engine's π
/// times). Returns the regions seen.
pub(crate) fn assert_constant_regions<K: Copy + Eq + std::hash::Hash + std::fmt::Debug>(
    engine: EngineKind,
    pixels: &[[f32; 4]],
    region_at: impl Fn(f32, f32) -> Option<K>,
    colour: impl Fn(K) -> [f32; 3],
) -> std::collections::HashSet<K> {
    let scale = if engine == EngineKind::Classic { std::f32::consts::PI } else { 1.0 };
    let mut seen = std::collections::HashSet::new();
    for (k, p) in pixels.iter().enumerate() {
        let (px, py) = ((k % 32) as f32, (k / 32) as f32);
        let (x0, x1) = (-1.0 + px / 16.0 + 1e-3, -1.0 + (px + 1.0) / 16.0 - 1e-3);
        let (y0, y1) = (1.0 - (py + 1.0) / 16.0 + 1e-3, 1.0 - py / 16.0 - 1e-3);
        let corners = [region_at(x0, y0), region_at(x1, y0), region_at(x0, y1), region_at(x1, y1)];
        let Some(region) = corners[0] else { continue };
        if corners.iter().any(|c| *c != Some(region)) {
            continue;
        }
        seen.insert(region);
        let want = colour(region);
        for c in 0..3 {
            assert!(
                (p[c] - want[c] * scale).abs() <= 1e-4 * scale,
                "{engine:?}, pixel {k} ({region:?}): {p:?} vs {want:?} × {scale}"
            );
        }
    }
    seen
}

/// Ptex's sub-quads of n-gons: a pentagon (ear-clipped `p` polygon whose vertex 0 is not
/// the group's first) and a triangle (3 sub-quads) in a quad-mesh file whose eight faces
/// are distinct constant colours: every pixel wholly inside one sub-quad's region is that
/// face's colour within 1e-4 in both engines (the classic engine's π times), all eight are
/// seen, and no warning is given.
#[test]
fn each_ngon_renders_its_sub_quads_ptex_faces() {
    let dir = std::env::temp_dir().join(format!("mira_render_ptex_ngons_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    let faces: Vec<FaceSpec> = (0..8).map(|f| FaceSpec { log2: (0, 0), texels: vec![sub_quad_colour(f)] }).collect();
    std::fs::write(dir.join("faces.ptx"), ptex_bytes(1, &faces)).unwrap();
    for engine in [EngineKind::Path, EngineKind::Classic] {
        let parsed = mi::parse_str("t.mi", &ngon_scene());
        let built = support::build_parsed(&parsed, 32, std::slice::from_ref(&dir));
        assert!(built.messages.is_empty(), "{:#?}", built.messages);
        let settings = Settings { engine, spp: Some(4), ..Settings::default() };
        let (film, _) = support::render_world(&built.built.world, &built.built.shading, &settings);
        let seen = assert_constant_regions(engine, &film.rgba(), sub_quad_at, sub_quad_colour);
        assert_eq!(seen.len(), 8, "{engine:?}: pixels of every sub-quad");
    }
    std::fs::remove_dir_all(&dir).ok();
}
