//! `texture_ptex` in module materials: Ptex files the tests write byte by byte (the layout
//! as the Ptex format documents it, written here independently of the reader: header,
//! extension header, zlib face infos and constant values, level info, level 0's zlib face
//! data headers and face blocks, the meta-data barrier), with zlib blocks both stored
//! (compression level 0: uncompressed) and compressed.
//!
//! What is asserted: every texel of every data type (uint8, uint16, half, float) and
//! channel count (1–4) reads back as its value (integers scaled to [0, 1]) within 1e-6,
//! at the centroid of its small triangle (Ptex's triangle layout); constant, diff-zipped
//! and tiled faces; a two-triangle mesh's hits (face = triangle index, barycentrics)
//! through a compiled module material give each face's texel within 1e-6; so do a
//! quad-mesh file's faces at hits on both triangles of a quad (face id and quad corners
//! from `State::ptex_quad`), 1e-6; hostile files
//! (bad magic, truncated anywhere, absurd resolutions, corrupt bytes anywhere) are errors
//! naming the byte offset, never a panic.

use std::io::Write;
use std::path::PathBuf;

use bsdf::Rgb;
use material::mdl_modules::ptex::{reader, MeshType, Ptex};
use material::{SurfaceMaterial, Varying};
use shader::State;

use crate::mdl_support::{close, compile_text_with, get};

/// A face the writer stores: its resolution (log2 u, v) and how.
#[derive(Clone)]
pub(crate) struct Face {
    pub(crate) log2: (i8, i8),
    /// Stored element values, texels row by row (v = 0 first), channels interleaved: the
    /// integers of 8- and 16-bit files, the numbers of half and float files.
    pub(crate) texels: Vec<f64>,
    pub(crate) how: How,
}

#[derive(Clone, Copy, PartialEq)]
pub(crate) enum How {
    /// Flagged constant in the face info; the value in the constant block only.
    ConstantInfo,
    /// A constant block in level 0.
    ConstantBlock,
    /// Zipped texel planes.
    Zipped,
    /// Zipped planes of differences (8- and 16-bit types).
    DiffZipped,
    /// Tiles of 2^(log2 − 1) a side, each zipped.
    Tiled,
}

/// The bytes of one element `x` of data type `dt`.
pub(crate) fn elem(dt: u32, x: f64) -> Vec<u8> {
    match dt {
        0 => vec![x as u8],
        1 => (x as u16).to_le_bytes().to_vec(),
        2 => half::f16::from_f64(x).to_le_bytes().to_vec(),
        _ => (x as f32).to_le_bytes().to_vec(),
    }
}

/// The value the reader should give for stored element `x` of data type `dt`.
pub(crate) fn expected(dt: u32, x: f64) -> f32 {
    match dt {
        0 => (x / 255.0) as f32,
        1 => (x / 65535.0) as f32,
        2 => half::f16::from_f64(x).to_f32(),
        _ => x as f32,
    }
}

pub(crate) fn zlib(bytes: &[u8], level: u32) -> Vec<u8> {
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::new(level));
    z.write_all(bytes).unwrap();
    z.finish().unwrap()
}

/// The planar block of `w` × `h` interleaved `texels` (each channel's plane in turn),
/// as differences when `diff`.
fn planes(dt: u32, channels: usize, texels: &[f64], diff: bool) -> Vec<u8> {
    let mut out = Vec::new();
    for c in 0..channels {
        for t in texels.chunks(channels) {
            out.extend(elem(dt, t[c]));
        }
    }
    if diff {
        match dt {
            0 => {
                let mut prev = 0u8;
                for b in out.iter_mut() {
                    let v = *b;
                    *b = v.wrapping_sub(prev);
                    prev = v;
                }
            }
            1 => {
                let mut prev = 0u16;
                for p in out.chunks_exact_mut(2) {
                    let v = u16::from_le_bytes([p[0], p[1]]);
                    p.copy_from_slice(&v.wrapping_sub(prev).to_le_bytes());
                    prev = v;
                }
            }
            _ => panic!("differences of 8- and 16-bit types only"),
        }
    }
    out
}

/// A Ptex file of `faces` (mesh type 0 triangles, 1 quads; data type `dt`; `channels`),
/// zlib blocks written at compression `level` (0: stored, uncompressed); no adjacency,
/// no reduced levels.
pub(crate) fn ptex_file(mesh: u32, dt: u32, channels: u16, faces: &[Face], level: u32) -> Vec<u8> {
    ptex_file_full(mesh, dt, channels, faces, level, &[], &[])
}

/// Face `f`'s data block and its encoding (`None` for a face flagged constant).
fn face_block(dt: u32, n: usize, f: &Face, level: u32) -> Option<(u32, Vec<u8>)> {
    let pixel = |values: &[f64]| values.iter().flat_map(|x| elem(dt, *x)).collect::<Vec<u8>>();
    let (w, h) = (1usize << f.log2.0, 1usize << f.log2.1);
    Some(match f.how {
        How::ConstantInfo => return None,
        How::ConstantBlock => (0u32, pixel(&f.texels[..n])),
        How::Zipped | How::DiffZipped => {
            let diff = f.how == How::DiffZipped;
            (u32::from(diff) + 1, zlib(&planes(dt, n, &f.texels, diff), level))
        }
        How::Tiled => {
            let (tu, tv) = (f.log2.0 - 1, f.log2.1 - 1);
            let (tw, th) = (1usize << tu, 1usize << tv);
            let mut words = Vec::new();
            let mut tiles = Vec::new();
            for ty in 0..h / th {
                for tx in 0..w / tw {
                    let mut tile = Vec::new();
                    for y in 0..th {
                        let row = (ty * th + y) * w + tx * tw;
                        tile.extend_from_slice(&f.texels[row * n..(row + tw) * n]);
                    }
                    let z = zlib(&planes(dt, n, &tile, false), level);
                    words.extend((z.len() as u32 | 1 << 30).to_le_bytes());
                    tiles.extend(z);
                }
            }
            let zw = zlib(&words, level);
            let mut block = vec![tu as u8, tv as u8];
            block.extend((zw.len() as u32).to_le_bytes());
            block.extend(zw);
            block.extend(tiles);
            (3, block)
        }
    })
}

/// One level's data: the zlib block of its faces' data headers (a face flagged constant:
/// a header of size 0), then their blocks.
fn level_data(dt: u32, n: usize, faces: &[Face], level: u32) -> Vec<u8> {
    let mut words = Vec::new();
    let mut data = Vec::new();
    for f in faces {
        match face_block(dt, n, f, level) {
            Some((encoding, block)) => {
                words.extend((block.len() as u32 | encoding << 30).to_le_bytes());
                data.extend(block);
            }
            None => words.extend(0u32.to_le_bytes()),
        }
    }
    let mut out = zlib(&words, level);
    out.extend(data);
    out
}

/// A Ptex file as [`ptex_file`], with per face its adjacent faces and their edges
/// (`adjacency`; empty: none) and reduced levels 1, 2, … (`reduced`: each level's faces
/// in the order the file stores them, Ptex's reduction order).
pub(crate) fn ptex_file_full(
    mesh: u32,
    dt: u32,
    channels: u16,
    faces: &[Face],
    level: u32,
    adjacency: &[([i32; 4], [u8; 4])],
    reduced: &[Vec<Face>],
) -> Vec<u8> {
    ptex_file_sub_faces(mesh, dt, channels, faces, level, adjacency, reduced, &[])
}

/// [`ptex_file_full`] with the faces numbered in `sub_faces` flagged sub-faces (Ptex's
/// face info flag 8).
#[allow(clippy::too_many_arguments)]
pub(crate) fn ptex_file_sub_faces(
    mesh: u32,
    dt: u32,
    channels: u16,
    faces: &[Face],
    level: u32,
    adjacency: &[([i32; 4], [u8; 4])],
    reduced: &[Vec<Face>],
    sub_faces: &[usize],
) -> Vec<u8> {
    let n = channels as usize;
    let pixel = |values: &[f64]| values.iter().flat_map(|x| elem(dt, *x)).collect::<Vec<u8>>();
    let mut infos = Vec::new();
    let mut constants = Vec::new();
    for (id, f) in faces.iter().enumerate() {
        let (adjfaces, adjedges) = adjacency.get(id).copied().unwrap_or(([-1; 4], [0; 4]));
        let edges = adjedges.iter().enumerate().fold(0u8, |b, (k, e)| b | e << (2 * k));
        let flags = u8::from(f.how == How::ConstantInfo) | if sub_faces.contains(&id) { 8 } else { 0 };
        infos.extend([f.log2.0 as u8, f.log2.1 as u8, edges, flags]);
        infos.extend(adjfaces.iter().flat_map(|a| a.to_le_bytes()));
        // The constant block: a constant face's value, else the face's average.
        let count = f.texels.len() / n;
        let average: Vec<f64> = (0..n).map(|c| f.texels.chunks(n).map(|t| t[c]).sum::<f64>() / count as f64).collect();
        constants.extend(pixel(if f.how == How::ConstantInfo { &f.texels[..n] } else { &average }));
    }
    let mut levels = vec![level_data(dt, n, faces, level)];
    levels.extend(reduced.iter().map(|faces| level_data(dt, n, faces, level)));
    let zinfo = zlib(&infos, level);
    let zconst = zlib(&constants, level);
    let level_size: u64 = levels.iter().map(|l| l.len() as u64).sum();
    let mut out = b"Ptex".to_vec();
    for w in [1u32, mesh, dt] {
        out.extend(w.to_le_bytes());
    }
    out.extend((-1i32).to_le_bytes());
    out.extend(channels.to_le_bytes());
    out.extend((levels.len() as u16).to_le_bytes());
    let info_size = 16 * levels.len() as u32;
    for w in [faces.len() as u32, 40, zinfo.len() as u32, zconst.len() as u32, info_size, 4] {
        out.extend(w.to_le_bytes());
    }
    out.extend(level_size.to_le_bytes());
    out.extend([0u32, 0].iter().flat_map(|w| w.to_le_bytes()));
    assert_eq!(out.len(), 64);
    out.extend([0u8; 40]);
    out.extend(zinfo);
    out.extend(zconst);
    let counts = std::iter::once(faces.len()).chain(reduced.iter().map(Vec::len));
    for (data, count) in levels.iter().zip(counts) {
        out.extend((data.len() as u64).to_le_bytes());
        out.extend((header_zip_len(data, count) as u32).to_le_bytes());
        out.extend((count as u32).to_le_bytes());
    }
    for data in &levels {
        out.extend(data);
    }
    out.extend([0u8; 8]);
    out
}

/// The length of the zlib stream at the start of `data` (a level's data headers of
/// `count` faces).
fn header_zip_len(data: &[u8], count: usize) -> usize {
    let mut z = flate2::Decompress::new(true);
    let mut out = vec![0u8; 4 * count];
    z.decompress(data, &mut out, flate2::FlushDecompress::Finish).unwrap();
    z.total_in() as usize
}

/// Stored value of texel `t`, channel `c` of a face: varied per face, texel and channel,
/// within range of every data type (< 251).
pub(crate) fn value(face: usize, t: usize, c: usize) -> f64 {
    ((1 + face * 61 + t * 13 + c * 5) % 251) as f64
}

pub(crate) fn zipped_face(face: usize, log2: i8, channels: usize, how: How) -> Face {
    let count = 1usize << (2 * log2);
    let texels = (0..count).flat_map(|t| (0..channels).map(move |c| value(face, t, c))).collect();
    Face { log2: (log2, log2), texels, how }
}

/// The centroid (barycentric u, v) of the small triangle stored as texel `t` of a
/// triangle face of resolution `n` (Ptex's layout: the upright ones in the lower left
/// half of the square image, the inverted ones mirrored into its upper right half).
pub(crate) fn centroid(n: usize, t: usize) -> (f32, f32) {
    let (x, y) = (t % n, t / n);
    let nf = n as f32;
    if x + y < n {
        ((x as f32 + 1.0 / 3.0) / nf, (y as f32 + 1.0 / 3.0) / nf)
    } else {
        // Stored at (n − 1 − j, n − 1 − i) for the inverted triangle at corner (i + 1, j + 1).
        let (i, j) = (n - 1 - y, n - 1 - x);
        ((i as f32 + 2.0 / 3.0) / nf, (j as f32 + 2.0 / 3.0) / nf)
    }
}

pub(crate) fn read(bytes: &[u8]) -> Ptex {
    reader::read(bytes).unwrap_or_else(|e| panic!("{e}")).0
}

#[test]
fn every_data_type_and_channel_count_reads_back_at_each_small_triangle() {
    for dt in 0..4 {
        for channels in 1..=4usize {
            for level in [0, 6] {
                let faces = [zipped_face(0, 1, channels, How::Zipped), zipped_face(1, 2, channels, How::Zipped)];
                let ptex = read(&ptex_file(0, dt, channels as u16, &faces, level));
                assert_eq!((ptex.mesh, ptex.channels, ptex.faces.len()), (MeshType::Triangle, channels, 2));
                for (id, f) in faces.iter().enumerate() {
                    let n = 1usize << f.log2.0;
                    for t in 0..n * n {
                        let (u, v) = centroid(n, t);
                        let got = ptex.texel(id as u32, u, v).expect("a texel");
                        assert_eq!(got.len(), channels);
                        for (c, g) in got.iter().enumerate() {
                            let want = expected(dt, value(id, t, c));
                            assert!(
                                (g - want).abs() <= 1e-6,
                                "type {dt}, {channels} channels, level {level}, face {id}, texel {t}, channel {c}: \
                                 {g} vs {want}"
                            );
                        }
                    }
                }
                assert!(ptex.texel(2, 0.1, 0.1).is_none(), "no face 2");
            }
        }
    }
}

#[test]
fn constant_diff_zipped_and_tiled_faces() {
    for dt in [0, 1] {
        let faces = [
            Face { log2: (0, 0), texels: vec![7.0, 9.0], how: How::ConstantInfo },
            Face { log2: (2, 1), texels: vec![11.0, 13.0], how: How::ConstantInfo },
            Face { log2: (1, 1), texels: vec![17.0, 19.0], how: How::ConstantBlock },
            zipped_face(3, 2, 2, How::DiffZipped),
            zipped_face(4, 2, 2, How::Tiled),
        ];
        // A quad mesh: texel (⌊u w⌋, ⌊v h⌋).
        let ptex = read(&ptex_file(1, dt, 2, &faces, 6));
        assert_eq!(ptex.mesh, MeshType::Quad);
        for (id, f) in faces.iter().enumerate() {
            let (w, h) = (1usize << f.log2.0, 1usize << f.log2.1);
            for t in 0..w * h {
                let (u, v) = (((t % w) as f32 + 0.5) / w as f32, ((t / w) as f32 + 0.5) / h as f32);
                let stored = match f.how {
                    How::ConstantInfo | How::ConstantBlock => &f.texels[..2],
                    _ => &f.texels[t * 2..t * 2 + 2],
                };
                let got = ptex.texel(id as u32, u, v).expect("a texel");
                assert_eq!(got.len(), 2);
                for (g, s) in got.iter().zip(stored) {
                    let want = expected(dt, *s);
                    assert!((g - want).abs() <= 1e-6, "type {dt}, face {id}, texel {t}: {g} vs {want}");
                }
            }
        }
    }
}

/// The two-triangle test texture (triangle mesh, RGB floats): face 0 of resolution 2
/// (four small triangles), face 1 constant.
fn two_triangles() -> (Vec<u8>, Vec<Face>) {
    let faces = vec![
        Face {
            log2: (1, 1),
            // Texels 0, 1, 2 upright ((0, 0), (1, 0), (0, 1)); texel 3 the inverted one.
            texels: vec![0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.25, 0.5, 0.75],
            how: How::Zipped,
        },
        Face { log2: (0, 0), texels: vec![0.9, 0.6, 0.3], how: How::ConstantInfo },
    ];
    (ptex_file(0, 3, 3, &faces, 6), faces)
}

const MODULE: &str = r#"mdl 1.7;
import ::df::*;
import ::tex::*;

export material pt(uniform texture_ptex tex = texture_ptex("./two.ptx")) = material(surface: material_surface(
    scattering: df::diffuse_reflection_bsdf(tint: tex::lookup_color(tex))));

export material pt_green(uniform texture_ptex tex = texture_ptex("./two.ptx")) = material(surface: material_surface(
    scattering: df::diffuse_reflection_bsdf(tint: color(tex::lookup_float(tex, 1)))));

export material pt_valid(uniform texture_ptex tex = texture_ptex()) = material(surface: material_surface(
    scattering: df::diffuse_reflection_bsdf(tint: tex::texture_isvalid(tex) ? color(1.0) : color(0.25))));

export material pt_quad() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: tex::lookup_color(texture_ptex("./quad.ptx")))));

export material pt_bad() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: tex::lookup_color(texture_ptex("./bad.ptx")))));
"#;

/// A directory of test `test` holding the module (`ptexmod.mdl`) and its Ptex files.
fn fixtures(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mira_mdl_ptex_{}_{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ptexmod.mdl"), MODULE).unwrap();
    std::fs::write(dir.join("two.ptx"), two_triangles().0).unwrap();
    std::fs::write(dir.join("quad.ptx"), quad_faces().0).unwrap();
    let mut bad = two_triangles().0;
    bad.truncate(100);
    std::fs::write(dir.join("bad.ptx"), bad).unwrap();
    dir
}

/// The diffuse colour of `m` at a hit of triangle `prim` at barycentric (`u`, `v`) (the
/// weights of its second and third vertices).
fn at(m: &SurfaceMaterial, prim: u32, u: f32, v: f32) -> Rgb {
    let mut h = m.constant();
    if let Varying::Evaluated(hit) = &m.varying {
        let n = glam::Vec3A::Z;
        let s = State { prim, bary: [1.0 - u - v, u, v], normal: n, normal_geom: n, dir: -n, ..State::default() };
        hit.0.apply(&s, &mut h);
    }
    h.diffuse
}

#[test]
fn a_two_triangle_mesh_gives_each_faces_texel_at_its_hits() {
    let dir = fixtures("hits");
    let (mdl, lib, diags) = compile_text_with(
        r#"shader "pt" "mdl::ptexmod::pt" ()
shader "green" "mdl::ptexmod::pt_green" ()
shader "invalid" "mdl::ptexmod::pt_valid" ()
shader "valid" "mdl::ptexmod::pt_valid" ("tex" "two.ptx")"#,
        std::slice::from_ref(&dir),
    );
    std::fs::remove_dir_all(&dir).ok();
    assert!(diags.is_empty(), "{diags:#?}");
    let m = get(&mdl, &lib, "pt");
    assert!(matches!(m.varying, Varying::Evaluated(_)), "a Ptex lookup varies with the hit");
    let rgb = |t: &[f64]| Rgb::new(t[0] as f32, t[1] as f32, t[2] as f32);
    let (_, faces) = two_triangles();
    // Triangle 0 (interpolated between texels, the default filter): each small
    // triangle's texel at its centroid; the face's corners their texel (no texels around
    // them but theirs); a grid vertex the mean of the texels around it.
    let points: [((f32, f32), &[usize]); 9] = [
        ((1.0 / 6.0, 1.0 / 6.0), &[0]),
        ((4.0 / 6.0, 1.0 / 6.0), &[1]),
        ((1.0 / 6.0, 4.0 / 6.0), &[2]),
        ((2.0 / 6.0, 2.0 / 6.0), &[3]),
        ((0.0, 0.0), &[0]),
        ((1.0, 0.0), &[1]),
        ((0.0, 1.0), &[2]),
        ((0.5, 0.0), &[0, 1, 3]),
        ((0.5, 0.5), &[1, 2, 3]),
    ];
    for ((u, v), texels) in points {
        let got = at(m, 0, u, v);
        let sum = texels.iter().fold(Rgb::ZERO, |s, &t| s + rgb(&faces[0].texels[t * 3..t * 3 + 3]));
        let want = sum * (1.0 / texels.len() as f32);
        assert!(close(got, want, 1e-6), "triangle 0 at ({u}, {v}): {got:?} vs the mean of texels {texels:?} {want:?}");
    }
    // Triangle 1: its constant value everywhere on it.
    for (u, v) in [(0.2, 0.2), (0.9, 0.05), (0.0, 1.0), (1.0 / 3.0, 1.0 / 3.0)] {
        let got = at(m, 1, u, v);
        assert!(close(got, rgb(&faces[1].texels), 1e-6), "triangle 1 at ({u}, {v}): {got:?}");
    }
    // A triangle the file has no face for is black.
    assert!(close(at(m, 2, 0.3, 0.3), Rgb::ZERO, 0.0));
    // `lookup_float(tex, 1)`: channel 1 (green).
    let g = at(get(&mdl, &lib, "green"), 0, 2.0 / 6.0, 2.0 / 6.0);
    assert!(close(g, Rgb::splat(0.5), 1e-6), "{g:?}");
    assert!(close(get(&mdl, &lib, "invalid").diffuse, Rgb::splat(0.25), 0.0));
    assert!(close(get(&mdl, &lib, "valid").diffuse, Rgb::ONE, 0.0));
}

/// The quad-mesh test texture (RGB floats): face 0 of 4 × 2 texels, each its own colour;
/// face 1 constant.
fn quad_faces() -> (Vec<u8>, Vec<Face>) {
    let texels = (0..8).flat_map(|t| [0.1 * t as f64, 0.05 + 0.1 * t as f64, 0.9 - 0.1 * t as f64]).collect();
    let faces = vec![
        Face { log2: (2, 1), texels, how: How::Zipped },
        Face { log2: (0, 0), texels: vec![0.3, 0.6, 0.9], how: How::ConstantInfo },
    ];
    (ptex_file(1, 3, 3, &faces, 6), faces)
}

/// A quad-mesh file through a compiled material: a hit on either triangle of a quad (cut
/// along the diagonal from vertex 0: corners 0, 1, 2 and 0, 2, 3; or along the other:
/// 1, 2, 3 and 1, 3, 0) at the barycentrics of each texel's centre reads that texel of the
/// quad's face, and near its corners the file's lookup at that point of the face (1e-6);
/// the constant face everywhere; a triangle of no quad is black.
#[test]
fn a_quad_mesh_file_gives_each_quads_texel_at_its_hits() {
    use scene::mesh::ptex_quads::{encode, face_uv, CORNER_UV};
    let dir = fixtures("quads");
    let (mdl, lib, diags) = compile_text_with(r#"shader "q" "mdl::ptexmod::pt_quad" ()"#, std::slice::from_ref(&dir));
    std::fs::remove_dir_all(&dir).ok();
    assert!(diags.is_empty(), "{diags:#?}");
    let m = get(&mdl, &lib, "q");
    let Varying::Evaluated(hit) = &m.varying else { panic!("a Ptex lookup varies with the hit") };
    let (bytes, faces) = quad_faces();
    let file = material::mdl_modules::ptex::reader::read(&bytes).expect("the quad file").0;
    let colour = |face: u32, bary: [f32; 3], corners: [u8; 3]| {
        let mut h = m.constant();
        let n = glam::Vec3A::Z;
        let s = State {
            prim: 99,
            bary,
            ptex_quad: face_uv(encode(face, corners), bary),
            normal: n,
            normal_geom: n,
            dir: -n,
            ..State::default()
        };
        hit.0.apply(&s, &mut h);
        h.diffuse
    };
    // The barycentrics of quad point (u, v) on the triangle of quad corners `corners`
    // (solved from the corners' (u, v)), if it lies on it.
    let bary_of = |corners: [u8; 3], u: f32, v: f32| -> Option<[f32; 3]> {
        let [a, b, c] = corners.map(|k| CORNER_UV[k as usize]);
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let b1 = ((u - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (v - a[1])) / det;
        let b2 = ((b[0] - a[0]) * (v - a[1]) - (u - a[0]) * (b[1] - a[1])) / det;
        let b0 = 1.0 - b1 - b2;
        (b0 >= 0.0 && b1 >= 0.0 && b2 >= 0.0).then_some([b0, b1, b2])
    };
    let splits = [[[0, 1, 2], [0, 2, 3]], [[1, 2, 3], [1, 3, 0]]];
    for split in splits {
        let mut on = [0; 2];
        for t in 0..8 {
            // Texel t's centre, and points near its corners (inset by a tenth of a texel).
            let (i, j) = ((t % 4) as f32, (t / 4) as f32);
            for (du, dv) in [(0.5, 0.5), (0.1, 0.1), (0.9, 0.1), (0.1, 0.9), (0.9, 0.9)] {
                let (u, v) = ((i + du) / 4.0, (j + dv) / 2.0);
                // At a texel's centre the texel itself; elsewhere the file's interpolating
                // lookup at (u, v) of face 0, which the hit must reach through its corners.
                let want = if (du, dv) == (0.5, 0.5) {
                    Rgb::new(
                        faces[0].texels[t * 3] as f32,
                        faces[0].texels[t * 3 + 1] as f32,
                        faces[0].texels[t * 3 + 2] as f32,
                    )
                } else {
                    let c = file.lookup(0, u, v, None, 0);
                    Rgb::new(c.x, c.y, c.z)
                };
                for (half, corners) in split.iter().enumerate() {
                    let Some(bary) = bary_of(*corners, u, v) else { continue };
                    on[half] += 1;
                    let got = colour(0, bary, *corners);
                    assert!(close(got, want, 1e-6), "{corners:?} at ({u}, {v}): {got:?} vs texel {t} {want:?}");
                }
            }
        }
        assert!(on[0] > 10 && on[1] > 10, "{split:?}: points on both triangles {on:?}");
        for bary in [[1.0, 0.0, 0.0], [0.2, 0.3, 0.5]] {
            let got = colour(1, bary, split[1]);
            assert!(close(got, Rgb::new(0.3, 0.6, 0.9), 1e-6), "{got:?}");
        }
    }
    // A hit without a quad face (`ptex_quad` none) and a face the file lacks are black.
    let mut h = m.constant();
    hit.0.apply(&State { prim: 0, bary: [0.3, 0.3, 0.4], ..State::default() }, &mut h);
    assert!(close(h.diffuse, Rgb::ZERO, 0.0), "{:?}", h.diffuse);
    assert!(close(colour(2, [0.3, 0.3, 0.4], [0, 1, 2]), Rgb::ZERO, 0.0));
}

#[test]
fn broken_ptex_files_are_errors_at_their_module_line() {
    let dir = fixtures("errors");
    let (_, _, diags) = compile_text_with(
        r#"shader "q" "mdl::ptexmod::pt_quad" ()
shader "b" "mdl::ptexmod::pt_bad" ()"#,
        std::slice::from_ref(&dir),
    );
    std::fs::remove_dir_all(&dir).ok();
    // The quad-mesh file reads.
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let bad = diags.iter().find(|d| d.contains("truncated")).expect("a truncation message");
    assert!(bad.contains("ptexmod.mdl:18:") && bad.contains("bad.ptx:") && bad.contains("'b'"), "{bad}");
}

#[test]
fn bad_magic_absurd_resolutions_and_truncations_are_errors_at_their_offset() {
    let (good, _) = two_triangles();
    let mut magic = good.clone();
    magic[0..4].copy_from_slice(b"PNG\0");
    let e = reader::read(&magic).unwrap_err();
    assert_eq!(e.offset, 0, "{e}");
    assert!(e.message.contains("not a Ptex file"), "{e}");

    // A face of 2^40 × 2^40 texels: refused at the face infos (byte 104) before any
    // texel is read.
    let mut faces = two_triangles().1;
    faces[0].log2 = (40, 40);
    let e = reader::read(&ptex_file(0, 3, 3, &faces, 0)).unwrap_err();
    assert_eq!(e.offset, 64 + 40, "{e}");
    assert!(e.message.contains("face 0") && e.message.contains("2^40"), "{e}");
    // 2^15 × 2^15 faces are within a side's limit but not the total.
    faces[0].log2 = (15, 15);
    let e = reader::read(&ptex_file(0, 3, 3, &faces, 0)).unwrap_err();
    assert!(e.offset == 104 && e.message.contains("more than"), "{e}");
    // Absurd counts in the header.
    let mut many = good.clone();
    many[24..28].copy_from_slice(&u32::MAX.to_le_bytes());
    let e = reader::read(&many).unwrap_err();
    assert!(e.offset == 24 && e.message.contains("faces"), "{e}");
    let mut none = good.clone();
    none[20..22].copy_from_slice(&0u16.to_le_bytes());
    assert_eq!(reader::read(&none).unwrap_err().offset, 20);

    // Truncated anywhere before the meta-data barrier (the last eight bytes, which mira
    // does not read): an error whose offset is inside the file, at the part cut; cut in
    // face 0's texel block, the error is at that block.
    for len in 0..good.len() - 8 {
        let e = reader::read(&good[..len]).expect_err("a truncated file");
        assert!(e.offset <= len as u64, "cut at {len}: {e}");
        assert!(e.message.contains("truncated") || e.message.contains("zlib"), "cut at {len}: {e}");
    }
    let face0_block = good.len() - 8 - block_len(&good);
    let e = reader::read(&good[..good.len() - 10]).unwrap_err();
    assert_eq!(e.offset, face0_block as u64, "{e}");
    assert!(e.message.contains("face 0"), "{e}");

    // Every byte changed: an error or a texture, never a panic.
    for at in 0..good.len() {
        for x in [0x00, 0xff, 0x80] {
            let mut bytes = good.clone();
            bytes[at] ^= x | 1;
            let _ = reader::read(&bytes);
        }
    }
}

/// The size of the only texel block of the two-triangle file (face 0's): level 0's size
/// less its zipped headers, read from the file's level info.
fn block_len(file: &[u8]) -> usize {
    let info_at = 64
        + 40
        + u32::from_le_bytes(file[32..36].try_into().unwrap()) as usize
        + u32::from_le_bytes(file[36..40].try_into().unwrap()) as usize;
    let level = u64::from_le_bytes(file[info_at..info_at + 8].try_into().unwrap()) as usize;
    let headers = u32::from_le_bytes(file[info_at + 8..info_at + 12].try_into().unwrap()) as usize;
    level - headers
}

/// Face edits appended after the file's sections (the extension header's edit position 0:
/// read to the end of the file) replace a face's info, constant value and data: face 1
/// (constant) becomes a zipped face of resolution 2, face 0 a constant face (1e-6).
#[test]
fn face_edits_replace_faces() {
    let (mut file, _) = two_triangles();
    let floats = |v: &[f64]| v.iter().flat_map(|x| (*x as f32).to_le_bytes()).collect::<Vec<u8>>();
    let edit = |face: u32, log2: u8, flags: u8, constant: &[f64], data: Option<Vec<u8>>| {
        let mut body = face.to_le_bytes().to_vec();
        body.extend([log2, log2, 0, flags]);
        body.extend([-1i32; 4].iter().flat_map(|a| a.to_le_bytes()));
        let word = data.as_ref().map_or(0, |d| d.len() as u32 | 1 << 30);
        body.extend(word.to_le_bytes());
        body.extend(floats(constant));
        body.extend(data.unwrap_or_default());
        let mut out = vec![0u8];
        out.extend((body.len() as u32).to_le_bytes());
        out.extend(body);
        out
    };
    let texels: Vec<f64> = (0..12).map(|k| 0.05 * k as f64).collect();
    let data = zlib(&planes(3, 3, &texels, false), 6);
    file.extend(edit(1, 1, 0, &[0.0; 3], Some(data)));
    file.extend(edit(0, 0, 1, &[0.125, 0.25, 0.375], None));
    let ptex = read(&file);
    for t in 0..4 {
        let (u, v) = centroid(2, t);
        let got = ptex.texel(1, u, v).expect("a texel");
        for (c, g) in got.iter().enumerate() {
            assert!((g - texels[t * 3 + c] as f32).abs() <= 1e-6, "texel {t}: {got:?}");
        }
    }
    assert_eq!(ptex.texel(0, 0.9, 0.05), Some(&[0.125f32, 0.25, 0.375][..]));
    // An edit of a face the file lacks is an error at the edit.
    let at = file.len();
    file.extend(edit(9, 0, 1, &[0.0; 3], None));
    let e = reader::read(&file).unwrap_err();
    assert!(e.offset == at as u64 + 5 && e.message.contains("face 9"), "{e}");
}

/// The reduced levels of one square face of `side` × `side` texels (`side` a power of two),
/// box-reduced down to 2 × 2, one face per level, in the file's level order.
pub(crate) fn reduced_levels(texels: &[f64], side: usize) -> Vec<Vec<Face>> {
    let mut levels = Vec::new();
    let (mut values, mut side) = (texels.to_vec(), side);
    while side > 2 {
        values = reduce(&values, side);
        side /= 2;
        let log2 = side.trailing_zeros() as i8;
        levels.push(vec![Face { log2: (log2, log2), texels: values.clone(), how: How::Zipped }]);
    }
    levels
}

/// The 2 × 2 box reduction of an n × n image.
pub(crate) fn reduce(values: &[f64], n: usize) -> Vec<f64> {
    let m = n / 2;
    (0..m * m)
        .map(|t| {
            let (x, y) = (2 * (t % m), 2 * (t / m));
            (values[y * n + x] + values[y * n + x + 1] + values[(y + 1) * n + x] + values[(y + 1) * n + x + 1]) / 4.0
        })
        .collect()
}
