//! `texture_3d` and `texture_cube` in module materials: DDS files the tests write byte by
//! byte (the header as the DDS format documents it, independent of the reader), looked up
//! through `tex::` functions of a module written beside them.
//!
//! The volume: 2×2×2 voxels of known values, looked up at voxel centres, between them and
//! at the volume's side with each wrap mode (trilinear interpolation between centres at
//! (i + ½)/2, v = 0 at the slices' bottom row); sizes, validity and voxel reads. The cube
//! map: one colour per face, a lookup along each axis gives that face's colour, and a
//! texel of one face is where the cube-map convention puts it.

use std::path::PathBuf;

use bsdf::Rgb;
use glam::Vec3A;
use material::{SurfaceMaterial, Varying};
use shader::State;

use crate::mdl_support::{close, compile_text_with, get};

/// The DDS header (magic and 124 bytes) of a `w` × `h` × `d` texture (`d` > 1: a volume)
/// with `pixel_format` (32 bytes) and `caps2`.
fn header(w: u32, h: u32, d: u32, pixel_format: [u32; 8], caps2: u32) -> Vec<u8> {
    let volume = d > 1;
    // CAPS | HEIGHT | WIDTH | PIXELFORMAT (| DEPTH).
    let flags = 0x1 | 0x2 | 0x4 | 0x1000 | if volume { 0x80_0000 } else { 0 };
    let mut words = vec![124, flags, h, w, 0, if volume { d } else { 0 }, 1];
    words.extend([0; 11]);
    words.extend(pixel_format);
    // TEXTURE (| COMPLEX for cube maps and volumes), caps2, caps3, caps4, reserved.
    let complex = if volume || caps2 != 0 { 0x8 } else { 0 };
    words.extend([0x1000 | complex, caps2, 0, 0, 0]);
    let mut out = b"DDS ".to_vec();
    out.extend(words.iter().flat_map(|w| w.to_le_bytes()));
    out
}

/// A volume of RGBA `f32` voxels (DX10 header, `R32G32B32A32_FLOAT`) in file order.
pub(crate) fn volume_file(w: u32, h: u32, d: u32, voxels: &[[f32; 4]]) -> Vec<u8> {
    // FOURCC "DX10".
    let dx10 = [32, 0x4, u32::from_le_bytes(*b"DX10"), 0, 0, 0, 0, 0];
    let mut out = header(w, h, d, dx10, if d > 1 { 0x20_0000 } else { 0 });
    // DXGI format 2 (R32G32B32A32_FLOAT), dimension 4 (3D) or 3 (2D), no flags, 1 element.
    out.extend([2u32, if d > 1 { 4 } else { 3 }, 0, 1, 0].iter().flat_map(|w| w.to_le_bytes()));
    out.extend(voxels.iter().flatten().flat_map(|f| f.to_le_bytes()));
    out
}

/// A cube map of `n` × `n` faces of 8-bit BGRA texels (legacy header, A8R8G8B8), faces
/// +x, −x, +y, −y, +z, −z, rows top to bottom.
fn cube_file(n: u32, faces: &[Vec<[u8; 3]>; 6]) -> Vec<u8> {
    // RGB | ALPHAPIXELS, 32 bits, masks R, G, B, A.
    let argb = [32, 0x41, 0, 32, 0x00ff_0000, 0x0000_ff00, 0x0000_00ff, 0xff00_0000];
    let mut out = header(n, n, 1, argb, 0x200 | 0xfc00);
    for face in faces {
        for [r, g, b] in face {
            out.extend([*b, *g, *r, 255]);
        }
    }
    out
}

/// Voxel (i, j, k) of the test volume (j = 0 the bottom row): red linear in i and j,
/// green in k, blue a corner spike.
fn voxel(i: usize, j: usize, k: usize) -> [f32; 4] {
    let spike = if (i, j, k) == (1, 1, 1) { 0.8 } else { 0.1 };
    [0.1 + 0.2 * i as f32 + 0.3 * j as f32, 0.2 + 0.5 * k as f32, spike, 1.0]
}

const MODULE: &str = r#"mdl 1.7;
import ::df::*;
import ::tex::*;
import ::state::*;

export material vol(uniform texture_3d tex = texture_3d("./vol.dds"), uniform tex::wrap_mode wrap = tex::wrap_repeat)
  = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: tex::lookup_color(tex, state::position(), wrap, wrap, wrap))));

export material vol_sizes(uniform texture_3d tex = texture_3d("./sizes.dds")) = material(surface: material_surface(
    scattering: df::diffuse_reflection_bsdf(tint: color(0.1 * tex::width(tex), 0.1 * tex::height(tex), 0.1 * tex::depth(tex)))));

export material vol_valid(uniform texture_3d tex = texture_3d()) = material(surface: material_surface(
    scattering: df::diffuse_reflection_bsdf(tint: tex::texture_isvalid(tex) ? color(1.0) : color(0.25))));

export material vol_texel() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: tex::texel_color(texture_3d("./vol.dds"), int3(1, 0, 1)))));

export material vol_float(uniform texture_3d tex = texture_3d("./vol.dds")) = material(surface: material_surface(
    scattering: df::diffuse_reflection_bsdf(tint: color(tex::lookup_float(tex, state::position())))));

export material cube(uniform texture_cube tex = texture_cube("./cube.dds")) = material(surface: material_surface(
    scattering: df::diffuse_reflection_bsdf(tint: tex::lookup_color(tex, state::normal()))));

export material cube_size() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: color(0.1 * tex::width(texture_cube("./cube.dds")), 0.1 * tex::height(texture_cube("./cube.dds")), 0.0))));

export material ptex() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(
    tint: tex::lookup_color(texture_ptex("./x.ptx")))));
"#;

/// One colour per cube face (+x red, −x green, +y blue, −y yellow, +z magenta, −z cyan),
/// the +z face's top-left texel grey.
const FACE_COLOURS: [[u8; 3]; 6] = [[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 0], [255, 0, 255], [0, 255, 255]];

/// A directory of test `test` holding the test module (`textures3d.mdl`) and its DDS files.
fn fixtures(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mira_mdl_tex3d_{}_{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("textures3d.mdl"), MODULE).unwrap();
    // File order: slice k, rows from the top (j = 1 first), columns i.
    let mut voxels = Vec::new();
    for k in 0..2 {
        for j in [1, 0] {
            for i in 0..2 {
                voxels.push(voxel(i, j, k));
            }
        }
    }
    std::fs::write(dir.join("vol.dds"), volume_file(2, 2, 2, &voxels)).unwrap();
    std::fs::write(dir.join("sizes.dds"), volume_file(3, 2, 4, &[[0.0; 4]; 24])).unwrap();
    let mut faces: [Vec<[u8; 3]>; 6] = FACE_COLOURS.map(|c| vec![c; 4]);
    faces[4][0] = [128, 128, 128];
    std::fs::write(dir.join("cube.dds"), cube_file(2, &faces)).unwrap();
    dir
}

/// Compiles the shaders of `text(dir)` with test `test`'s fixtures (in `dir`) on the search
/// path, expecting no message; the fixtures are removed (the compiled materials hold what
/// they read).
fn compiled(
    test: &str,
    text: impl Fn(&std::path::Path) -> String,
) -> (material::mdl_modules::MdlMaterials, scene::Library) {
    let dir = fixtures(test);
    let (mdl, lib, diags) = compile_text_with(&text(&dir), std::slice::from_ref(&dir));
    std::fs::remove_dir_all(&dir).ok();
    assert!(diags.is_empty(), "{diags:#?}");
    (mdl, lib)
}

/// The diffuse colour of `m` at position `p` with normal `n`.
fn at(m: &SurfaceMaterial, p: Vec3A, n: Vec3A) -> Rgb {
    let mut h = m.constant();
    if let Varying::Evaluated(hit) = &m.varying {
        let s = State { point: p, normal: n, normal_geom: n, dir: -n, ..State::default() };
        hit.0.apply(&s, &mut h);
    }
    h.diffuse
}

/// The trilinear value of the test volume at texture coordinate `c` inside the voxel
/// centres' box [¼, ¾]³, computed from the voxels directly.
fn trilinear(c: [f32; 3]) -> Rgb {
    let t = c.map(|x| (x * 2.0 - 0.5).clamp(0.0, 1.0));
    let mut sum = [0.0f32; 3];
    for (i, j, k) in (0..8).map(|n| (n & 1, n >> 1 & 1, n >> 2 & 1)) {
        let w = [i, j, k].iter().zip(t).map(|(&b, t)| if b == 1 { t } else { 1.0 - t }).product::<f32>();
        let v = voxel(i, j, k);
        for ch in 0..3 {
            sum[ch] += w * v[ch];
        }
    }
    Rgb::new(sum[0], sum[1], sum[2])
}

#[test]
fn a_volume_is_looked_up_trilinearly_at_centres_and_between_them() {
    let (mdl, lib) = compiled("centres", |_| r#"shader "v" "mdl::textures3d::vol" ()"#.into());
    let m = get(&mdl, &lib, "v");
    assert!(matches!(m.varying, Varying::Evaluated(_)), "a lookup at the hit varies");
    let mut points = Vec::new();
    // The eight voxel centres: each voxel's own value (v = ¼ is the bottom row, j = 0).
    for n in 0..8 {
        let (i, j, k) = (n & 1, n >> 1 & 1, n >> 2 & 1);
        points.push([0.25 + 0.5 * i as f32, 0.25 + 0.5 * j as f32, 0.25 + 0.5 * k as f32]);
    }
    // Midpoints between centres along each axis, a face centre and the volume's centre.
    points.extend([[0.5, 0.25, 0.25], [0.25, 0.5, 0.75], [0.75, 0.75, 0.5], [0.5, 0.5, 0.25], [0.5, 0.5, 0.5]]);
    for c in points {
        let got = at(m, Vec3A::from(c), Vec3A::Z);
        let want = trilinear(c);
        assert!(close(got, want, 1e-5), "at {c:?}: {got:?} vs {want:?}");
    }
    // The voxel centres are the voxels themselves, read in the file's order.
    assert!(close(at(m, Vec3A::new(0.75, 0.75, 0.75), Vec3A::Z), Rgb::new(0.6, 0.7, 0.8), 1e-6));
    assert!(close(at(m, Vec3A::new(0.25, 0.25, 0.25), Vec3A::Z), Rgb::new(0.1, 0.2, 0.1), 1e-6));
}

#[test]
fn a_volume_wraps_by_its_modes_at_its_sides() {
    let (mdl, lib) = compiled("wraps", |_| {
        r#"shader "repeat" "mdl::textures3d::vol" ()
shader "clamp" "mdl::textures3d::vol" ("wrap" "wrap_clamp")
shader "mirror" "mdl::textures3d::vol" ("wrap" "wrap_mirrored_repeat")
shader "clip" "mdl::textures3d::vol" ("wrap" "wrap_clip")"#
            .into()
    });
    let c = |name: &str, p: [f32; 3]| at(get(&mdl, &lib, name), Vec3A::from(p), Vec3A::Z);
    // u = 0 at the centres' v and w: half way between voxel 0 and its neighbour beyond the
    // side (voxel 1 repeated; voxel 0 itself clamped and mirrored).
    let (v0, v1) = (voxel(0, 0, 0), voxel(1, 0, 0));
    let (p, q) = (Rgb::new(v0[0], v0[1], v0[2]), Rgb::new(v1[0], v1[1], v1[2]));
    assert!(close(c("repeat", [0.0, 0.25, 0.25]), (p + q) * 0.5, 1e-5));
    assert!(close(c("clamp", [0.0, 0.25, 0.25]), p, 1e-5));
    assert!(close(c("mirror", [0.0, 0.25, 0.25]), p, 1e-5));
    assert!(close(c("clip", [0.0, 0.25, 0.25]), p, 1e-5));
    // Outside [0, 1): repeated a period on, mirrored back, clamped to the side, clipped black.
    assert!(close(c("repeat", [1.25, 0.25, 0.25]), p, 1e-5));
    assert!(close(c("mirror", [1.25, 0.25, 0.25]), q, 1e-5));
    assert!(close(c("clamp", [-3.0, 0.25, 0.25]), p, 1e-5));
    assert!(close(c("clip", [-0.1, 0.25, 0.25]), Rgb::ZERO, 0.0));
    assert!(close(c("clip", [0.25, 0.25, 1.0]), Rgb::ZERO, 0.0));
}

#[test]
fn volume_sizes_validity_and_voxel_reads() {
    let (mdl, lib) = compiled("sizes", |_| {
        r#"shader "sizes" "mdl::textures3d::vol_sizes" ()
shader "invalid" "mdl::textures3d::vol_valid" ()
shader "valid" "mdl::textures3d::vol_valid" ("tex" "vol.dds")
shader "texel" "mdl::textures3d::vol_texel" ()
shader "float" "mdl::textures3d::vol_float" ()"#
            .into()
    });
    let c = |name: &str| get(&mdl, &lib, name).diffuse;
    assert!(close(c("sizes"), Rgb::new(0.3, 0.2, 0.4), 1e-6), "3 × 2 × 4: {:?}", c("sizes"));
    assert!(close(c("invalid"), Rgb::splat(0.25), 0.0));
    assert!(close(c("valid"), Rgb::ONE, 0.0));
    let v = voxel(1, 0, 1);
    assert!(close(c("texel"), Rgb::new(v[0], v[1], v[2]), 1e-6), "{:?}", c("texel"));
    // `lookup_float` is the red channel.
    let f = at(get(&mdl, &lib, "float"), Vec3A::new(0.75, 0.75, 0.25), Vec3A::Z);
    assert!(close(f, Rgb::splat(voxel(1, 1, 0)[0]), 1e-6), "{f:?}");
    // A `.mi` parameter naming the file by its absolute path reads the same volume.
    let (mdl, lib) = compiled("absolute", |dir| {
        format!(r#"shader "abs" "mdl::textures3d::vol" ("tex" "{}")"#, dir.join("vol.dds").display())
    });
    let got = at(get(&mdl, &lib, "abs"), Vec3A::new(0.5, 0.5, 0.5), Vec3A::Z);
    assert!(close(got, trilinear([0.5; 3]), 1e-5), "{got:?}");
}

#[test]
fn a_cube_map_gives_each_face_along_its_axis() {
    let (mdl, lib) = compiled("cube", |_| {
        r#"shader "cube" "mdl::textures3d::cube" ()
shader "size" "mdl::textures3d::cube_size" ()"#
            .into()
    });
    let m = get(&mdl, &lib, "cube");
    let axes = [Vec3A::X, -Vec3A::X, Vec3A::Y, -Vec3A::Y, Vec3A::Z, -Vec3A::Z];
    for (face, axis) in axes.into_iter().enumerate() {
        let [r, g, b] = FACE_COLOURS[face].map(|c| f32::from(c) / 255.0);
        // Off the face's centre (which the grey texel of +z shares) towards its +u side.
        let off = if face == 4 { Vec3A::new(1.0, -1.0, 0.0) } else { Vec3A::ZERO };
        let got = at(m, Vec3A::ZERO, axis * 2.0 + off);
        assert!(close(got, Rgb::new(r, g, b), 1e-6), "face {face}: {got:?}");
    }
    // +z's top-left texel (first row, first column) is towards −x, +y on that face.
    let grey = at(m, Vec3A::ZERO, Vec3A::new(-0.5, 0.5, 1.0));
    assert!(close(grey, Rgb::splat(128.0 / 255.0), 1e-6), "{grey:?}");
    assert!(close(get(&mdl, &lib, "size").diffuse, Rgb::new(0.2, 0.2, 0.0), 1e-6));
}

#[test]
fn unreadable_3d_cube_and_ptex_textures_are_errors_at_their_module_line() {
    let dir = fixtures("errors");
    std::fs::write(dir.join("not_dds.mdl"), "mdl 1.7;\nimport ::df::*;\nimport ::tex::*;\nexport material m() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(\n    tint: tex::lookup_color(texture_cube(\"./vol.dds\"), float3(1.0)))));\n").unwrap();
    let (_, _, diags) = compile_text_with(
        r#"shader "p" "mdl::textures3d::ptex" ()
shader "c" "mdl::not_dds::m" ()"#,
        std::slice::from_ref(&dir),
    );
    assert_eq!(diags.len(), 2, "{diags:#?}");
    let ptex = diags.iter().find(|d| d.contains("Ptex")).expect("a Ptex message");
    assert!(ptex.contains("textures3d.mdl:29:") && ptex.contains("'p'"), "{ptex}");
    let cube = diags.iter().find(|d| d.contains("cube map")).expect("a cube map message");
    assert!(cube.contains("not_dds.mdl:5:29") && cube.contains("not a cube map") && cube.contains("'c'"), "{cube}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A cube map from an image of a horizontal cross (8 × 6 texels, faces of 2 × 2: −x, +z,
/// +x, −z in the middle row, +y above +z, −y below it), named by a `.mi` `color texture`
/// element: each face along its axis, and the +y face's top-left texel (the cross's
/// texel (2, 0)) towards (−x, +y, −z) as the cube-map convention puts it.
#[test]
fn a_cube_map_from_a_horizontal_cross() {
    let mut cross = image::RgbImage::new(8, 6);
    let cells = [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (3, 1)];
    for (face, (cx, cy)) in cells.iter().enumerate() {
        for (x, y) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            cross.put_pixel(cx * 2 + x, cy * 2 + y, image::Rgb(FACE_COLOURS[face]));
        }
    }
    cross.put_pixel(2, 0, image::Rgb([128, 128, 128]));
    let (mdl, lib) = compiled("cross", |dir| {
        let file = dir.join("cross.png");
        cross.save(&file).unwrap();
        format!(
            "color texture \"crossed\" \"{}\"\nshader \"cube\" \"mdl::textures3d::cube\" (\"tex\" \"crossed\")",
            file.display()
        )
    });
    let m = get(&mdl, &lib, "cube");
    let axes = [Vec3A::X, -Vec3A::X, Vec3A::Y, -Vec3A::Y, Vec3A::Z, -Vec3A::Z];
    for (face, axis) in axes.into_iter().enumerate() {
        let [r, g, b] = FACE_COLOURS[face].map(|c| f32::from(c) / 255.0);
        // Off the +y face's centre, away from its grey texel.
        let off = if face == 2 { Vec3A::new(0.5, 0.0, 0.5) } else { Vec3A::ZERO };
        let got = at(m, Vec3A::ZERO, axis + off);
        assert!(close(got, Rgb::new(r, g, b), 1e-6), "face {face}: {got:?}");
    }
    let grey = at(m, Vec3A::ZERO, Vec3A::new(-0.5, 1.0, -0.5));
    assert!(close(grey, Rgb::splat(128.0 / 255.0), 1e-6), "{grey:?}");
}

/// A binary PPM (P6) of `w` × `h` 8-bit RGB texels, rows top to bottom, written byte by
/// byte as the Netpbm format documents it.
fn ppm(w: usize, h: usize, texels: &[[u8; 3]]) -> Vec<u8> {
    assert_eq!(texels.len(), w * h);
    let mut out = format!("P6\n{w} {h}\n255\n").into_bytes();
    out.extend(texels.iter().flatten());
    out
}

/// The directions towards each face's centre and, slightly inside, its four corners
/// (face, direction, whether it is the corner of the face's first row and column, as
/// the cube-map convention orients it).
fn centres_and_corners() -> Vec<(usize, Vec3A, bool)> {
    // Per face: the axis, and the directions of its s and t (first column, first row at −).
    let frames = [
        (Vec3A::X, -Vec3A::Z, -Vec3A::Y),
        (-Vec3A::X, Vec3A::Z, -Vec3A::Y),
        (Vec3A::Y, Vec3A::X, Vec3A::Z),
        (-Vec3A::Y, Vec3A::X, -Vec3A::Z),
        (Vec3A::Z, Vec3A::X, -Vec3A::Y),
        (-Vec3A::Z, -Vec3A::X, -Vec3A::Y),
    ];
    let mut out = Vec::new();
    for (face, (axis, s, t)) in frames.into_iter().enumerate() {
        out.push((face, axis * 3.0, false));
        for (a, b) in [(-0.97, -0.97), (0.97, -0.97), (-0.97, 0.97), (0.97, 0.97)] {
            out.push((face, axis + s * a + t * b, a < 0.0 && b < 0.0));
        }
    }
    out
}

/// Checks cube map material `m` against [`FACE_COLOURS`]: each face's centre direction
/// gives its colour, each corner direction its face's colour, except the first texel of
/// face `marked`, which is grey.
fn check_faces(m: &SurfaceMaterial, marked: usize) {
    for (face, dir, first) in centres_and_corners() {
        let want = if first && face == marked { [128; 3] } else { FACE_COLOURS[face] };
        let [r, g, b] = want.map(|c| f32::from(c) / 255.0);
        let got = at(m, Vec3A::ZERO, dir);
        assert!(close(got, Rgb::new(r, g, b), 1e-5), "face {face} towards {dir}: {got:?}");
    }
}

/// A vertical cross (12 × 16 texels, faces of 4 × 4: +y on top, −x, +z, +x in the middle
/// row, −y below +z, −z at the bottom turned by 180°): each face's centre and corners give
/// its colour, and −z's first texel by the convention (towards +x, +y) is stored at the
/// last row and column of the bottom cell.
#[test]
fn a_cube_map_from_a_vertical_cross() {
    let n = 4;
    let mut texels = vec![[0u8; 3]; 3 * n * 4 * n];
    let cells = [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (1, 3)];
    for (face, (cx, cy)) in cells.iter().enumerate() {
        for (x, y) in (0..n * n).map(|i| (i % n, i / n)) {
            texels[(cy * n + y) * 3 * n + cx * n + x] = FACE_COLOURS[face];
        }
    }
    texels[(3 * n + n - 1) * 3 * n + n + n - 1] = [128; 3];
    let (mdl, lib) = compiled("vcross", |dir| {
        std::fs::write(dir.join("vcross.ppm"), ppm(3 * n, 4 * n, &texels)).unwrap();
        r#"shader "cube" "mdl::textures3d::cube" ("tex" "vcross.ppm")"#.into()
    });
    check_faces(get(&mdl, &lib, "cube"), 5);
}

/// Writes six face images `stem_px.ppm` … `stem_nz.ppm` into `dir`, each `sizes[face]`
/// texels square of its [`FACE_COLOURS`] colour, the +x face's first texel grey.
fn write_faces(dir: &std::path::Path, stem: &str, sizes: [usize; 6]) {
    for (face, suffix) in ["px", "nx", "py", "ny", "pz", "nz"].into_iter().enumerate() {
        let n = sizes[face];
        let mut texels = vec![FACE_COLOURS[face]; n * n];
        if face == 0 {
            texels[0] = [128; 3];
        }
        std::fs::write(dir.join(format!("{stem}_{suffix}.ppm")), ppm(n, n, &texels)).unwrap();
    }
}

/// Six face images `sky_px.ppm` … `sky_nz.ppm` (4 × 4 each) stand for `sky.ppm`, which
/// does not exist, named by a `.mi` parameter and by a module: each face's centre and
/// corners give its colour, the +x image's first texel is the convention's (towards
/// +y, +z on that face).
#[test]
fn a_cube_map_from_six_face_images() {
    let module = "mdl 1.7;\nimport ::df::*;\nimport ::tex::*;\nimport ::state::*;\n\
        export material m() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(\n    \
        tint: tex::lookup_color(texture_cube(\"./sky.ppm\"), state::normal()))));\n";
    let (mdl, lib) = compiled("faces", |dir| {
        write_faces(dir, "sky", [4; 6]);
        std::fs::write(dir.join("faces.mdl"), module).unwrap();
        "shader \"mi\" \"mdl::textures3d::cube\" (\"tex\" \"sky.ppm\")\nshader \"mdl\" \"mdl::faces::m\" ()".into()
    });
    check_faces(get(&mdl, &lib, "mi"), 0);
    check_faces(get(&mdl, &lib, "mdl"), 0);
}

/// Six face images of unequal sizes, or a missing one, are an error at the module line
/// naming the cube map, naming the offending face file.
#[test]
fn six_face_images_of_unequal_sizes_are_an_error_at_their_line() {
    let dir = fixtures("faces_bad");
    write_faces(&dir, "bad", [4, 4, 4, 4, 4, 2]);
    write_faces(&dir, "part", [4; 6]);
    std::fs::remove_file(dir.join("part_ny.ppm")).unwrap();
    std::fs::write(
        dir.join("faces_bad.mdl"),
        "mdl 1.7;\nimport ::df::*;\nimport ::tex::*;\n\
         export material m() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(\n    \
         tint: tex::lookup_color(texture_cube(\"./bad.ppm\"), float3(1.0)))));\n\
         export material p() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf(\n    \
         tint: tex::lookup_color(texture_cube(\"./part.ppm\"), float3(1.0)))));\n",
    )
    .unwrap();
    let (_, _, diags) = compile_text_with(
        "shader \"m\" \"mdl::faces_bad::m\" ()\nshader \"p\" \"mdl::faces_bad::p\" ()",
        std::slice::from_ref(&dir),
    );
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(diags.len(), 2, "{diags:#?}");
    let sizes = diags.iter().find(|d| d.contains("'m'")).expect("a message for 'm'");
    assert!(sizes.contains("faces_bad.mdl:5:29") && sizes.contains("bad_nz.ppm") && sizes.contains("2×2"), "{sizes}");
    let part = diags.iter().find(|d| d.contains("'p'")).expect("a message for 'p'");
    assert!(part.contains("faces_bad.mdl:7:29") && part.contains("part_ny.ppm"), "{part}");
}

/// A DDS cube map of 4 × 4 faces with its full mip chain (4, 2, 1 texels a side, each
/// face's chain stored after it): the faces are read from level 0 (the coarser levels
/// are black), each face's centre and corners giving its colour, +z's first texel grey.
#[test]
fn a_dds_cube_map_with_mip_levels_reads_level_0() {
    let n = 4u32;
    let argb = [32, 0x41, 0, 32, 0x00ff_0000, 0x0000_ff00, 0x0000_00ff, 0xff00_0000];
    let mut file = header(n, n, 1, argb, 0x200 | 0xfc00);
    // Flags | MIPMAPCOUNT, the count 3, caps | MIPMAP (byte offsets 8, 28 and 108).
    let word = |file: &[u8], at: usize| u32::from_le_bytes(file[at..at + 4].try_into().unwrap());
    let flags = word(&file, 8) | 0x2_0000;
    let caps = word(&file, 108) | 0x40_0000;
    file[8..12].copy_from_slice(&flags.to_le_bytes());
    file[28..32].copy_from_slice(&3u32.to_le_bytes());
    file[108..112].copy_from_slice(&caps.to_le_bytes());
    for (face, [r, g, b]) in FACE_COLOURS.into_iter().enumerate() {
        for i in 0..n * n {
            let [r, g, b] = if face == 4 && i == 0 { [128; 3] } else { [r, g, b] };
            file.extend([b, g, r, 255]);
        }
        // Levels 1 and 2: 2 × 2 and 1 × 1 black texels.
        file.extend(std::iter::repeat_n(0u8, 4 * (4 + 1)));
    }
    let (mdl, lib) = compiled("mips", |dir| {
        std::fs::write(dir.join("mips.dds"), &file).unwrap();
        r#"shader "cube" "mdl::textures3d::cube" ("tex" "mips.dds")"#.into()
    });
    check_faces(get(&mdl, &lib, "cube"), 4);
}
