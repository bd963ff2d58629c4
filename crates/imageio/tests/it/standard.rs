//! PNG, JPEG, TIFF, Targa, BMP, PPM, Radiance HDR and OpenEXR files read back with the
//! `image` and `exr` crates' decoders: integer formats exactly, float exactly, half within
//! half precision, RGBE within its 8-bit mantissa, JPEG within a stated error.

use crate::common;

use std::path::Path;

use common::*;
use imageio::{write, Format, ImageData, Pixels};

const W: u32 = 70;
const H: u32 = 66;

fn format(name: &str, data_type: &str) -> Format {
    Format::from_name(name).unwrap().with_data_type(data_type)
}

fn read(path: &Path) -> image::DynamicImage {
    image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn eight_bit_formats_hold_the_quantized_display_values_exactly() {
    let dir = scratch("std8");
    let img = colour(W, H);
    for (name, data_type, channels) in [
        ("png", "rgba", 4),
        ("png", "rgb", 3),
        ("tif", "rgba", 4),
        ("tif", "rgb", 3),
        ("tga", "rgba", 4),
        ("tga", "rgb", 3),
        ("bmp", "rgba", 4),
        ("bmp", "rgb", 3),
        ("ppm", "rgb", 3),
        ("ppm", "rgba", 3),
    ] {
        let path = dir.join(format!("{name}-{data_type}.{name}"));
        write(&path, format(name, data_type), &img).unwrap();
        let back = read(&path);
        assert_eq!((back.width(), back.height()), (W, H), "{name} {data_type}");
        let got: Vec<u8> = if channels == 4 { back.to_rgba8().into_raw() } else { back.to_rgb8().into_raw() };
        assert_eq!(back.color().channel_count() as usize, channels, "{name} {data_type}: channels");
        let want: Vec<u8> = display(&img, channels).iter().map(|v| code8(*v)).collect();
        assert_eq!(got, want, "{name} {data_type}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn sixteen_bit_formats_hold_the_quantized_display_values_exactly() {
    let dir = scratch("std16");
    let img = colour(W, H);
    for (name, data_type, channels) in
        [("png", "rgba_16", 4), ("png", "rgb_16", 3), ("tif", "rgba_16", 4), ("tif16", "rgb", 3)]
    {
        let path = dir.join(format!("{name}-{data_type}.{}", &name[..3]));
        write(&path, format(name, data_type), &img).unwrap();
        let back = read(&path);
        assert_eq!(back.color().channel_count() as usize, channels, "{name} {data_type}");
        assert_eq!(back.color().bytes_per_pixel() as usize, 2 * channels, "{name} {data_type}: 16 bits");
        let got: Vec<u16> = if channels == 4 { back.to_rgba16().into_raw() } else { back.to_rgb16().into_raw() };
        let want: Vec<u16> = display(&img, channels).iter().map(|v| code16(*v)).collect();
        assert_eq!(got, want, "{name} {data_type}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn scalar_buffers_are_grey_in_png_and_tiff() {
    let dir = scratch("grey");
    let v = scalar(W, H);
    let img = ImageData::new(W, H, Pixels::Scalar(v.clone()));
    for (name, data_type) in [("png", "a"), ("tif", "a_16")] {
        let path = dir.join(format!("grey.{name}"));
        write(&path, format(name, data_type), &img).unwrap();
        let back = read(&path);
        assert_eq!(back.color().channel_count(), 1, "{name}");
        if data_type == "a" {
            assert_eq!(back.to_luma8().into_raw(), v.iter().map(|s| code8(*s)).collect::<Vec<_>>());
        } else {
            assert_eq!(back.to_luma16().into_raw(), v.iter().map(|s| code16(*s)).collect::<Vec<_>>());
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn float_tiff_holds_the_linear_values_bit_for_bit() {
    let dir = scratch("tiffp");
    let img = colour(W, H);
    for (data_type, channels) in [("rgba_fp", 4), ("rgb_fp", 3)] {
        let path = dir.join(format!("{data_type}.tif"));
        write(&path, format("tif", data_type), &img).unwrap();
        let back = read(&path);
        let got: Vec<f32> = if channels == 4 { back.to_rgba32f().into_raw() } else { back.to_rgb32f().into_raw() };
        assert!(matches!(back, image::DynamicImage::ImageRgba32F(_) | image::DynamicImage::ImageRgb32F(_)));
        assert_eq!(got, linear(&img, channels), "{data_type}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn jpeg_is_within_its_compression_error() {
    let dir = scratch("jpg");
    let img = smooth(W, H);
    let path = dir.join("x.jpg");
    write(&path, format("jpg", ""), &img).unwrap();
    let got = read(&path).to_rgb8().into_raw();
    let want: Vec<u8> = display(&img, 3).iter().map(|v| code8(*v)).collect();
    let errors: Vec<f64> = got.iter().zip(&want).map(|(a, b)| (*a as f64 - *b as f64).abs()).collect();
    let mean = errors.iter().sum::<f64>() / errors.len() as f64;
    let max = errors.iter().cloned().fold(0.0, f64::max);
    // Quality 75 on a smooth gradient: about one code on average.
    assert!(mean < 2.0 && max < 16.0, "mean {mean}, max {max}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn radiance_hdr_holds_linear_rgb_within_rgbe_precision() {
    let dir = scratch("hdr");
    let img = colour(W, H);
    let path = dir.join("x.hdr");
    write(&path, format("hdr", ""), &img).unwrap();
    let got = read(&path).to_rgb32f().into_raw();
    let want = linear(&img, 3);
    // RGBE: 8-bit mantissas sharing the exponent of the largest component, so each
    // component is within 1/128 of that largest component (truncation: within 2/256).
    for (p, (g, w)) in got.chunks(3).zip(want.chunks(3)).enumerate() {
        let largest = w.iter().cloned().fold(0.0f32, f32::max);
        for k in 0..3 {
            assert!((g[k] - w[k]).abs() <= largest / 128.0 + 1e-30, "pixel {p}: {g:?} vs {w:?}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Every channel of an EXR file by name.
fn exr_channels(path: &Path) -> Vec<(String, exr::prelude::FlatSamples)> {
    let image = exr::prelude::read_all_flat_layers_from_file(path).unwrap();
    image.layer_data[0].channel_data.list.iter().map(|c| (c.name.to_string(), c.sample_data.clone())).collect()
}

#[test]
fn exr_holds_every_buffer_as_float_half_and_uint_channels() {
    use exr::prelude::FlatSamples;
    let dir = scratch("exr");
    let img = colour(W, H);
    let n = (W * H) as usize;
    let depth: Vec<f32> = (0..n).map(|i| i as f32 * 0.25).collect();
    let normals: Vec<[f32; 3]> = (0..n).map(|i| [i as f32, -1.0, 0.5]).collect();
    let motion: Vec<[f32; 2]> = (0..n).map(|i| [0.5 * i as f32, -2.0]).collect();
    let tags: Vec<u32> = (0..n as u32).map(|i| i * 7 + 3_000_000_000).collect();
    let full = img
        .clone()
        .with_layer("", Pixels::Depth(depth.clone()))
        .with_layer("", Pixels::Normal(normals.clone()))
        .with_layer("", Pixels::Motion(motion.clone()))
        .with_layer("", Pixels::Tag(tags.clone()))
        .with_layer("fb0", img.pixels.clone());
    for data_type in ["rgba_fp", "rgba_h"] {
        let path = dir.join(format!("{data_type}.exr"));
        write(&path, format("exr", data_type), &full).unwrap();
        let channels = exr_channels(&path);
        let names: Vec<&str> = channels.iter().map(|(n, _)| n.as_str()).collect();
        for want in ["A", "B", "G", "R", "Z", "N.X", "N.Y", "N.Z", "M.X", "M.Y", "tag", "fb0.R", "fb0.A"] {
            assert!(names.contains(&want), "{data_type}: {want} in {names:?}");
        }
        let get = |name: &str| &channels.iter().find(|(n, _)| n == name).unwrap().1;
        let lin = linear(&img, 4);
        for (k, c) in ["R", "G", "B", "A"].iter().enumerate() {
            let want: Vec<f32> = lin.iter().skip(k).step_by(4).copied().collect();
            match (data_type, get(c)) {
                ("rgba_fp", FlatSamples::F32(v)) => assert_eq!(v, &want, "{c}"),
                ("rgba_h", FlatSamples::F16(v)) => {
                    // Half: 11 significant bits, relative error at most 2^-11 (normal range).
                    for (h, w) in v.iter().zip(&want) {
                        let tol = w.abs() * 2f32.powi(-11) + 6.1e-5 * 2f32.powi(-10);
                        assert!((h.to_f32() - w).abs() <= tol, "{c}: {} vs {w}", h.to_f32());
                    }
                }
                (_, other) => panic!("{data_type} {c}: sample type {other:?}"),
            }
        }
        assert_eq!(get("Z"), &FlatSamples::F32(depth.clone()));
        assert_eq!(get("N.Y"), &FlatSamples::F32(normals.iter().map(|v| v[1]).collect()));
        assert_eq!(get("M.X"), &FlatSamples::F32(motion.iter().map(|v| v[0]).collect()));
        assert_eq!(get("tag"), &FlatSamples::U32(tags.clone()));
    }
    // `rgb` leaves out alpha.
    let path = dir.join("rgb.exr");
    write(&path, format("exr", "rgb_h"), &img).unwrap();
    let names: Vec<String> = exr_channels(&path).into_iter().map(|(n, _)| n).collect();
    assert_eq!(names, ["B", "G", "R"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn formats_refuse_buffers_they_do_not_hold_with_a_clear_error() {
    let dir = scratch("refuse");
    let depth = ImageData::new(4, 4, Pixels::Depth(vec![1.0; 16]));
    let err = write(&dir.join("z.png"), format("png", ""), &depth).unwrap_err().to_string();
    assert!(err.contains("'png'") && err.contains("zt"), "{err}");
    let err = write(&dir.join("x.map"), format("map", ""), &colour(4, 4)).unwrap_err().to_string();
    assert!(err.contains("map"), "{err}");
    let short = ImageData::new(4, 4, Pixels::Depth(vec![1.0; 15]));
    assert!(write(&dir.join("z.zt"), format("zt", ""), &short).is_err());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn every_format_and_buffer_combination_writes_or_says_why() {
    let dir = scratch("all");
    let names = [
        "pic", "Zpic", "alias", "rgb", "jpg", "png", "exr", "tif", "tif16", "ppm", "tga", "bmp", "hdr", "iff", "ct",
        "ct16", "cth", "ctfp", "st", "st16", "stfp", "zt", "nt", "mt", "tt", "bit", "map", "rla", "qntpal",
    ];
    let types = ["", "rgb", "rgba", "rgba_16", "rgb_h", "rgba_fp", "a", "a_16", "z", "n", "m", "tag"];
    let (w, h) = (3, 2);
    let buffers = [
        colour(w, h).pixels,
        Pixels::Scalar(vec![0.5; 6]),
        Pixels::Depth(vec![2.0; 6]),
        Pixels::Normal(vec![[0.0, 1.0, 0.0]; 6]),
        Pixels::Motion(vec![[1.0, -1.0]; 6]),
        Pixels::Tag(vec![7; 6]),
    ];
    let (mut written, mut refused) = (0, 0);
    for name in names {
        for t in types {
            for (b, pixels) in buffers.iter().enumerate() {
                let f = format(name, t);
                let path = dir.join(format!("{name}-{t}-{b}.out"));
                let result = write(&path, f, &ImageData::new(w, h, pixels.clone()));
                assert_eq!(
                    result.is_ok(),
                    f.kind.holds(pixels.type_name()),
                    "{name} {t} {b}: holds() and write() agree"
                );
                match result {
                    Ok(()) => {
                        assert!(std::fs::metadata(&path).unwrap().len() > 0, "{name} {t} {b}");
                        written += 1;
                    }
                    Err(e) => {
                        assert!(e.to_string().contains(&format!("'{}'", f.kind)), "{name} {t} {b}: {e}");
                        // Colour goes into every writable colour format, whatever the type says.
                        let data_format =
                            ["st", "zt", "nt", "mt", "tt", "bit", "Zpic"].iter().any(|d| name.starts_with(d));
                        assert!(b != 0 || !f.kind.writable() || data_format, "{name} {t}: colour refused: {e}");
                        refused += 1;
                    }
                }
            }
        }
    }
    assert!(written > 300 && refused > 500, "{written} written, {refused} refused");
    // Sizes beyond a format's 16-bit fields are refused, not truncated.
    let wide = ImageData::new(65_536, 1, Pixels::Scalar(vec![0.0; 65_536]));
    for name in ["rgb", "pic", "iff", "st", "tga"] {
        let e = write(&dir.join(format!("wide.{name}")), format(name, "a"), &wide).unwrap_err().to_string();
        assert!(e.contains("65535") || e.contains("65536"), "{name}: {e}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
