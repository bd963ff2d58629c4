//! `mira render` writes the files of `output` statements in mental ray's formats: an SGI
//! `rgb` file (8- and 16-bit) with the same pixels as the PNG of the same render, a depth
//! `zt` file holding the quad's distance, and `-o` choosing the format by extension.

use std::path::{Path, PathBuf};
use std::process::Command;

/// An orthographic 2×2 view at 8×6 pixels onto a grey (0.5 linear) quad at z = −5 that
/// covers its lower half, with the given `output` statements.
fn scene(outputs: &str) -> String {
    format!(
        r#"
options "opt" filter box 1 1 end options
camera "cam" focal infinity aperture 2 aspect 1.3333333 resolution 8 6
    {outputs}
end camera
instance "cam_inst" "cam" end instance
material "m" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 0.5 0.5 0.5) end material
object "quad" group
    -2 -2 -5  2 -2 -5  2 0 -5  -2 0 -5
    v 0 v 1 v 2 v 3
    c "m" 0 1 2 3
end group end object
instance "quad_inst" "quad" end instance
instgroup "root" "cam_inst" "quad_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Renders `outputs` (`DIR` standing for a fresh directory) with `extra` arguments; the
/// directory and what mira printed on stderr.
fn render(tag: &str, outputs: &str, extra: &[&str]) -> (PathBuf, String) {
    let dir = std::env::temp_dir().join(format!("mira-formats-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let outputs = outputs.replace("DIR", dir.to_str().unwrap());
    let mi = dir.join("s.mi");
    std::fs::write(&mi, scene(&outputs)).unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_mira"))
        .args(["render", "--spp", "4", "--engine", "classic", mi.to_str().unwrap()])
        .args(extra)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr).to_string();
    assert!(run.status.success(), "{stderr}");
    (dir, stderr)
}

/// Reads an SGI file (header per the SGI image format: magic 474, storage, bytes per
/// channel, dimension, x, y, z sizes; RLE rows bottom first through the offset table) into
/// (width, height, channels, bytes per channel, samples top row first).
fn read_sgi(path: &Path) -> (usize, usize, usize, usize, Vec<u16>) {
    let d = std::fs::read(path).unwrap();
    let be16 = |at: usize| u16::from_be_bytes([d[at], d[at + 1]]);
    let be32 = |at: usize| u32::from_be_bytes([d[at], d[at + 1], d[at + 2], d[at + 3]]) as usize;
    assert_eq!(be16(0), 474, "SGI magic");
    assert_eq!(d[2], 1, "RLE storage");
    let bpc = d[3] as usize;
    let (w, h, z) = (be16(6) as usize, be16(8) as usize, be16(10) as usize);
    let value = |at: usize| if bpc == 1 { d[at] as u16 } else { be16(at) };
    let mut out = vec![0u16; w * h * z];
    for c in 0..z {
        for y in 0..h {
            let mut at = be32(512 + 4 * (y + c * h));
            let mut x = 0;
            loop {
                let p = value(at);
                at += bpc;
                let n = (p & 0x7f) as usize;
                if n == 0 {
                    break;
                }
                for _ in 0..n {
                    out[((h - 1 - y) * w + x) * z + c] = value(at);
                    x += 1;
                    if p & 0x80 != 0 {
                        at += bpc;
                    }
                }
                if p & 0x80 == 0 {
                    at += bpc;
                }
            }
            assert_eq!(x, w, "row {y} of channel {c}");
        }
    }
    (w, h, z, bpc, out)
}

/// 8-bit code of the sRGB encoding of a linear value.
fn srgb8(v: f32) -> f32 {
    (1.055 * v.powf(1.0 / 2.4) - 0.055) * 255.0
}

#[test]
fn an_rgb_output_writes_an_sgi_file_with_the_pngs_pixels() {
    let (dir, _) = render(
        "sgi",
        r#"output "rgb" "rgb" "DIR/square.sgi"
    output "rgba_16" "rgb" "DIR/square16.sgi"
    output "rgb" "png" "DIR/square.png"
    output "z" "zt" "DIR/square.zt""#,
        &[],
    );
    let (w, h, z, bpc, sgi) = read_sgi(&dir.join("square.sgi"));
    assert_eq!((w, h, z, bpc), (8, 6, 3, 1));
    let png = image::open(dir.join("square.png")).unwrap().to_rgb8().into_raw();
    assert_eq!(sgi, png.iter().map(|v| *v as u16).collect::<Vec<_>>(), "SGI and PNG pixels");
    // The quad (lower three rows) is sRGB(0.5); the background above is black.
    let quad = srgb8(0.5);
    for (i, v) in sgi.iter().enumerate() {
        let row = i / (3 * w);
        if row >= 3 {
            assert!((*v as f32 - quad).abs() <= 1.0, "pixel {i}: {v} vs {quad}");
        } else {
            assert_eq!(*v, 0, "background pixel {i}");
        }
    }

    let (_, _, z16, bpc16, wide) = read_sgi(&dir.join("square16.sgi"));
    assert_eq!((z16, bpc16), (4, 2));
    for (k, v) in wide.iter().enumerate().filter(|(k, _)| k / (4 * w) >= 3) {
        let want = if k % 4 == 3 { 65535.0 } else { srgb8(0.5) * 257.0 };
        assert!((*v as f32 - want).abs() <= 257.0, "16-bit sample {k}: {v} vs {want}");
    }

    // zt: 8-byte header, big-endian floats, bottom row first: 5 on the quad, 0 above it.
    let zt = std::fs::read(dir.join("square.zt")).unwrap();
    assert_eq!(zt.len(), 8 + 4 * 8 * 6);
    assert_eq!(&zt[2..6], &[0, 8, 0, 6]);
    let depth: Vec<f32> = zt[8..].chunks(4).map(|b| f32::from_be_bytes(b.try_into().unwrap())).collect();
    for (i, d) in depth.iter().enumerate() {
        let want = if i / 8 < 3 { 5.0 } else { 0.0 };
        assert!((d - want).abs() < 1e-4, "depth {i} (bottom row first): {d}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn dash_o_chooses_the_format_by_extension() {
    let dir = std::env::temp_dir().join(format!("mira-formats-o-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("x.sgi");
    render("o", "", &["-o", out.to_str().unwrap()]);
    let (w, h, z, bpc, _) = read_sgi(&out);
    assert_eq!((w, h, z, bpc), (8, 6, 4, 1), "colour with alpha, 8-bit");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn unsupported_formats_are_warned_about_by_file_name() {
    let (dir, stderr) = render(
        "warn",
        r#"output "rgba" "qntpal" "DIR/x.qnt"
    output "z" "png" "DIR/z.png""#,
        &[],
    );
    assert!(stderr.contains("warning: mira does not write 'qntpal' files") && stderr.contains("x.qnt"), "{stderr}");
    assert!(stderr.contains("'png' files do not hold the 'z' frame buffer ('") && stderr.contains("z.png"), "{stderr}");
    assert!(!dir.join("z.png").exists());
    // Nothing else asked: the scene's EXR is written instead, the Quantel file is not.
    assert!(!dir.join("x.qnt").exists());
    assert!(dir.join("s.exr").exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn file_framebuffers_write_their_buffers() {
    let (dir, _) = render(
        "fb",
        r#"framebuffer "main" datatype "rgba_16" primary on filetype "rgb" filename "DIR/main.sgi"
    framebuffer "depth" datatype "z" filtering off filetype "exr" filename "DIR/depth.exr"
    framebuffer "depth2" datatype "z" filetype "zt" filename "DIR/depth.zt""#,
        &[],
    );
    let (w, h, z, bpc, main) = read_sgi(&dir.join("main.sgi"));
    assert_eq!((w, h, z, bpc), (8, 6, 4, 2));
    // Alpha: 1 on the quad (lower rows), 0 above.
    for (i, a) in main.iter().skip(3).step_by(4).enumerate() {
        assert_eq!(*a, if i / w >= 3 { 65535 } else { 0 }, "alpha of pixel {i}");
    }
    // The depth EXR holds the one channel Z: 5 on the quad, 0 above (rows top first).
    let image = exr::prelude::read_all_flat_layers_from_file(dir.join("depth.exr")).unwrap();
    let channels = &image.layer_data[0].channel_data.list;
    assert_eq!(channels.len(), 1);
    assert_eq!(channels[0].name.to_string(), "Z");
    let depth: Vec<f32> = channels[0].sample_data.values_as_f32().collect();
    for (i, d) in depth.iter().enumerate() {
        assert!((d - if i / w >= 3 { 5.0 } else { 0.0 }).abs() < 1e-4, "depth {i}: {d}");
    }
    let zt = std::fs::read(dir.join("depth.zt")).unwrap();
    let zt: Vec<f32> = zt[8..].chunks(4).map(|b| f32::from_be_bytes(b.try_into().unwrap())).collect();
    // zt rows run bottom first: the same values, rows reversed.
    let flipped: Vec<f32> = depth.chunks(w).rev().flatten().copied().collect();
    assert_eq!(zt, flipped);
    std::fs::remove_dir_all(&dir).ok();
}
