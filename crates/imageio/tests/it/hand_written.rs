//! The hand-written writers (SGI, Softimage pic, Alias pix, Maya IFF, mental images data
//! files) read back by readers written here from the formats' descriptions — they share no
//! code with the writers — and compared pixel for pixel: integer samples exactly, floats
//! bit for bit, half within half precision.

use crate::common;

use common::*;
use imageio::{write, Format, ImageData, Pixels};

const W: u32 = 70;
const H: u32 = 66;

fn format(name: &str, data_type: &str) -> Format {
    Format::from_name(name).unwrap().with_data_type(data_type)
}

fn written(tag: &str, name: &str, data_type: &str, image: &ImageData) -> Vec<u8> {
    let dir = scratch(tag);
    let path = dir.join(format!("x.{name}"));
    write(&path, format(name, data_type), image).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    bytes
}

/// Reads an SGI image file (magic 474; storage 0 verbatim or 1 RLE; 1 or 2 bytes per
/// channel; rows bottom first) into (width, height, channels, samples top row first).
fn read_sgi(data: &[u8]) -> (usize, usize, usize, Vec<u16>) {
    let mut r = Be::new(data);
    assert_eq!(r.u16(), 474, "magic");
    let storage = r.u8();
    let bpc = r.u8() as usize;
    let _dimension = r.u16();
    let (w, h, z) = (r.u16() as usize, r.u16() as usize, r.u16() as usize);
    let (pixmin, pixmax) = (r.u32(), r.u32());
    let value = |at: usize| -> u16 {
        if bpc == 1 {
            data[at] as u16
        } else {
            u16::from_be_bytes([data[at], data[at + 1]])
        }
    };
    let mut out = vec![0u16; w * h * z];
    for c in 0..z {
        for y in 0..h {
            let row_index = y + c * h;
            let mut at = if storage == 1 {
                let start = &data[512 + 4 * row_index..];
                u32::from_be_bytes(start[..4].try_into().unwrap()) as usize
            } else {
                512 + row_index * w * bpc
            };
            let dest_y = h - 1 - y;
            let mut x = 0;
            let mut put = |x: &mut usize, v: u16| {
                out[(dest_y * w + *x) * z + c] = v;
                *x += 1;
            };
            if storage == 0 {
                for _ in 0..w {
                    put(&mut x, value(at));
                    at += bpc;
                }
                continue;
            }
            loop {
                let packet = value(at);
                at += bpc;
                let count = (packet & 0x7f) as usize;
                if count == 0 {
                    break;
                }
                if packet & 0x80 != 0 {
                    for _ in 0..count {
                        put(&mut x, value(at));
                        at += bpc;
                    }
                } else {
                    let v = value(at);
                    at += bpc;
                    for _ in 0..count {
                        put(&mut x, v);
                    }
                }
            }
            assert_eq!(x, w, "row {y} channel {c} decodes to the width");
        }
    }
    assert_eq!(pixmin as u16, *out.iter().min().unwrap());
    assert_eq!(pixmax as u16, *out.iter().max().unwrap());
    (w, h, z, out)
}

#[test]
fn sgi_8_and_16_bit_rgb_rgba_and_grey() {
    let img = colour(W, H);
    for (data_type, channels, wide) in
        [("rgba", 4, false), ("rgb", 3, false), ("rgba_16", 4, true), ("rgb_16", 3, true)]
    {
        let bytes = written("sgi", "rgb", data_type, &img);
        assert_eq!(bytes[3] as usize, if wide { 2 } else { 1 }, "{data_type}: bytes per channel");
        let (w, h, z, got) = read_sgi(&bytes);
        assert_eq!((w, h, z), (W as usize, H as usize, channels), "{data_type}");
        let want: Vec<u16> =
            display(&img, channels).iter().map(|v| if wide { code16(*v) } else { code8(*v) as u16 }).collect();
        assert_eq!(got, want, "{data_type}");
    }
    let v = scalar(W, H);
    let (_, _, z, got) = read_sgi(&written("sgi", "rgb", "a", &ImageData::new(W, H, Pixels::Scalar(v.clone()))));
    assert_eq!(z, 1);
    assert_eq!(got, v.iter().map(|s| code8(*s) as u16).collect::<Vec<_>>());
}

/// Reads a Softimage picture (104-byte header, channel packets, scanlines top first in
/// uncompressed, pure or mixed run-length packets) into RGBA (alpha 255 if absent).
fn read_pic(data: &[u8]) -> (usize, usize, bool, Vec<u8>) {
    let mut r = Be::new(data);
    assert_eq!(r.u32(), 0x5380_F634, "magic");
    let _version = r.f32();
    r.bytes(80);
    assert_eq!(r.bytes(4), b"PICT");
    let (w, h) = (r.u16() as usize, r.u16() as usize);
    let _ratio = r.f32();
    assert_eq!(r.u16(), 3, "full frame");
    r.u16();
    let mut packets = Vec::new();
    loop {
        let (chained, size, kind, mask) = (r.u8(), r.u8(), r.u8(), r.u8());
        assert_eq!(size, 8);
        packets.push((kind, mask));
        if chained == 0 {
            break;
        }
    }
    let mut out = vec![255u8; w * h * 4];
    let mut has_alpha = false;
    for y in 0..h {
        for &(kind, mask) in &packets {
            let comps: Vec<usize> = [(0x80, 0), (0x40, 1), (0x20, 2), (0x10, 3)]
                .iter()
                .filter(|(bit, _)| mask & bit != 0)
                .map(|(_, k)| *k)
                .collect();
            has_alpha |= comps.contains(&3);
            let mut x = 0;
            while x < w {
                let pixel = |r: &mut Be| comps.iter().map(|_| r.u8()).collect::<Vec<u8>>();
                let (count, value): (usize, Option<Vec<u8>>) = match kind {
                    0 => (1, Some(pixel(&mut r))),
                    1 => {
                        let n = r.u8() as usize;
                        (n, Some(pixel(&mut r)))
                    }
                    2 => {
                        let c = r.u8() as usize;
                        if c < 128 {
                            for _ in 0..=c {
                                let p = pixel(&mut r);
                                for (i, k) in comps.iter().enumerate() {
                                    out[(y * w + x) * 4 + k] = p[i];
                                }
                                x += 1;
                            }
                            (0, None)
                        } else if c == 128 {
                            let n = r.u16() as usize;
                            (n, Some(pixel(&mut r)))
                        } else {
                            (c - 127, Some(pixel(&mut r)))
                        }
                    }
                    _ => panic!("packet type {kind}"),
                };
                if let Some(p) = value {
                    for _ in 0..count {
                        for (i, k) in comps.iter().enumerate() {
                            out[(y * w + x) * 4 + k] = p[i];
                        }
                        x += 1;
                    }
                }
            }
            assert_eq!(x, w, "row {y} decodes to the width");
        }
    }
    assert_eq!(r.at, data.len(), "no bytes left over");
    (w, h, has_alpha, out)
}

#[test]
fn softimage_pic_rgb_and_alpha() {
    // Wide enough for a run longer than 128 (the 16-bit count).
    let wide = colour(300, 20);
    for img in [colour(W, H), wide] {
        for (data_type, alpha) in [("rgba", true), ("rgb", false)] {
            let (w, h, has_alpha, got) = read_pic(&written("pic", "pic", data_type, &img));
            assert_eq!((w as u32, h as u32, has_alpha), (img.width, img.height, alpha));
            let mut want: Vec<u8> = display(&img, 4).iter().map(|v| code8(*v)).collect();
            if !alpha {
                want.iter_mut().skip(3).step_by(4).for_each(|a| *a = 255);
            }
            assert_eq!(got, want, "{data_type}");
        }
    }
}

#[test]
fn alias_pix_rgb() {
    let img = colour(300, 20);
    let data = written("pix", "alias", "", &img);
    let mut r = Be::new(&data);
    let (w, h) = (r.u16() as usize, r.u16() as usize);
    r.u16();
    r.u16();
    assert_eq!(r.u16(), 24);
    let mut got = Vec::new();
    for _ in 0..h {
        let mut x = 0;
        while x < w {
            let n = r.u8() as usize;
            assert!(n >= 1);
            let (b, g, red) = (r.u8(), r.u8(), r.u8());
            for _ in 0..n {
                got.extend_from_slice(&[red, g, b]);
            }
            x += n;
        }
        assert_eq!(x, w);
    }
    assert_eq!(r.at, data.len());
    assert_eq!(got, display(&img, 3).iter().map(|v| code8(*v)).collect::<Vec<_>>());
}

/// Reads a Maya IFF (`FOR4 CIMG`: `TBHD`, `FOR4 TBMP` of `RGBA` tiles) into samples, top row
/// first, RGBA or RGB order.
fn read_iff(data: &[u8]) -> (usize, usize, usize, bool, Vec<u16>) {
    let mut r = Be::new(data);
    assert_eq!(r.bytes(4), b"FOR4");
    assert_eq!(r.u32() as usize, data.len() - 8);
    assert_eq!(r.bytes(4), b"CIMG");
    assert_eq!(r.bytes(4), b"TBHD");
    assert_eq!(r.u32(), 32);
    let (w, h) = (r.u32() as usize, r.u32() as usize);
    let (_prnum, _prden) = (r.u16(), r.u16());
    let flags = r.u32();
    let bytes = r.u16() as usize + 1;
    let tiles = r.u16() as usize;
    let compressed = r.u32() == 1;
    r.bytes(8);
    let c = if flags & 2 != 0 { 4 } else { 3 };
    assert_eq!(r.bytes(4), b"FOR4");
    let tbmp_end = r.u32() as usize + r.at;
    assert_eq!(r.bytes(4), b"TBMP");
    let mut out = vec![0u16; w * h * c];
    let mut seen = 0;
    while r.at < tbmp_end {
        assert_eq!(r.bytes(4), b"RGBA");
        let size = r.u32() as usize;
        let next = r.at + size.div_ceil(4) * 4;
        let (x0, y0, x1, y1) = (r.u16() as usize, r.u16() as usize, r.u16() as usize, r.u16() as usize);
        let (tw, th) = (x1 - x0 + 1, y1 - y0 + 1);
        let body = r.bytes(size - 8);
        // Channels in file order A B G R (or B G R): component index in RGBA order.
        let comp = |i: usize| c - 1 - i;
        let mut set = |x: usize, y: usize, k: usize, v: u16| out[((h - 1 - (y0 + y)) * w + x0 + x) * c + k] = v;
        if compressed && body.len() < tw * th * c * bytes {
            let mut at = 0;
            for i in 0..c {
                let mut p = 0;
                while p < tw * th {
                    let head = body[at] as usize;
                    at += 1;
                    let n = (head & 0x7f) + 1;
                    for q in 0..n {
                        let v = if head & 0x80 != 0 { body[at] } else { body[at + q] };
                        set((p + q) % tw, (p + q) / tw, comp(i), v as u16);
                    }
                    at += if head & 0x80 != 0 { 1 } else { n };
                    p += n;
                }
                assert_eq!(p, tw * th);
            }
        } else {
            let mut at = 0;
            for y in 0..th {
                for x in 0..tw {
                    for i in 0..c {
                        let v = if bytes == 1 { body[at] as u16 } else { u16::from_be_bytes([body[at], body[at + 1]]) };
                        set(x, y, comp(i), v);
                        at += bytes;
                    }
                }
            }
        }
        seen += 1;
        r.at = next;
    }
    assert_eq!(seen, tiles);
    (w, h, c, bytes == 2, out)
}

#[test]
fn maya_iff_8_and_16_bit_in_tiles() {
    // 70 × 66: four tiles, three of them partial.
    let img = colour(W, H);
    for (data_type, channels, wide) in [("rgba", 4, false), ("rgb", 3, false), ("rgba_16", 4, true)] {
        let (w, h, c, is_wide, got) = read_iff(&written("iff", "iff", data_type, &img));
        assert_eq!((w, h, c, is_wide), (W as usize, H as usize, channels, wide), "{data_type}");
        let want: Vec<u16> =
            display(&img, channels).iter().map(|v| if wide { code16(*v) } else { code8(*v) as u16 }).collect();
        assert_eq!(got, want, "{data_type}");
    }
    // Pure noise does not run-length encode smaller: tiles are stored plain.
    let display: Vec<[f32; 4]> =
        (0..W * H).map(|i| [noise(i, 0, 0), noise(i, 1, 0), noise(i, 2, 0), noise(i, 3, 0)]).collect();
    let img = ImageData::new(W, H, Pixels::Color { linear: display.clone(), display: display.clone() });
    let (_, _, _, _, got) = read_iff(&written("iffnoise", "iff", "rgba", &img));
    assert_eq!(got, display.iter().flatten().map(|v| code8(*v) as u16).collect::<Vec<_>>());
}

/// Reads a mental images data file: type byte, zero, big-endian width and height, two zero
/// bytes, then big-endian samples, bottom row first. Returns the type and the rows top first.
fn read_mental(data: &[u8], bytes_per_pixel: usize) -> (u8, usize, usize, Vec<Vec<u8>>) {
    let mut r = Be::new(data);
    let kind = r.u8();
    assert_eq!(r.u8(), 0);
    let (w, h) = (r.u16() as usize, r.u16() as usize);
    assert_eq!(r.u16(), 0);
    assert_eq!(data.len(), 8 + w * h * bytes_per_pixel, "file size");
    let mut rows: Vec<Vec<u8>> = (0..h).map(|_| r.bytes(w * bytes_per_pixel).to_vec()).collect();
    rows.reverse();
    (kind, w, h, rows)
}

fn be_f32s(rows: &[Vec<u8>]) -> Vec<f32> {
    rows.concat().chunks(4).map(|b| f32::from_be_bytes(b.try_into().unwrap())).collect()
}

#[test]
fn mental_images_colour_in_four_depths() {
    let img = colour(W, H);
    let (kind, w, h, rows) = read_mental(&written("ct", "ct", "rgba", &img), 4);
    assert_eq!((kind, w, h), (0x0b, W as usize, H as usize));
    assert_eq!(rows.concat(), display(&img, 4).iter().map(|v| code8(*v)).collect::<Vec<_>>());

    let (_, _, _, rows) = read_mental(&written("ct16", "ct", "rgba_16", &img), 8);
    let got: Vec<u16> = rows.concat().chunks(2).map(|b| u16::from_be_bytes([b[0], b[1]])).collect();
    assert_eq!(got, display(&img, 4).iter().map(|v| code16(*v)).collect::<Vec<_>>());

    let (_, _, _, rows) = read_mental(&written("ctfp", "ctfp", "", &img), 16);
    assert_eq!(be_f32s(&rows), linear(&img, 4));

    let (_, _, _, rows) = read_mental(&written("cth", "cth", "", &img), 8);
    let halves: Vec<f32> = rows
        .concat()
        .chunks(2)
        .map(|b| exr::prelude::f16::from_bits(u16::from_be_bytes([b[0], b[1]])).to_f32())
        .collect();
    for (h, l) in halves.iter().zip(linear(&img, 4)) {
        assert!((h - l).abs() <= l.abs() * 2f32.powi(-11) + 1e-7, "{h} vs {l}");
    }
}

#[test]
fn mental_images_depth_normal_motion_tag_scalar_and_bit() {
    let n = (W * H) as usize;
    let depth: Vec<f32> = (0..n).map(|i| if i % 3 == 0 { 0.0 } else { 1.5 + i as f32 }).collect();
    let (kind, _, _, rows) =
        read_mental(&written("zt", "zt", "z", &ImageData::new(W, H, Pixels::Depth(depth.clone()))), 4);
    assert_eq!(kind, 0x08);
    assert_eq!(be_f32s(&rows), depth);

    let normals: Vec<[f32; 3]> = (0..n).map(|i| [i as f32, -0.5, 0.25]).collect();
    let (kind, _, _, rows) =
        read_mental(&written("nt", "nt", "n", &ImageData::new(W, H, Pixels::Normal(normals.clone()))), 12);
    assert_eq!(kind, 0x09);
    assert_eq!(be_f32s(&rows), normals.concat());

    let motion: Vec<[f32; 2]> = (0..n).map(|i| [0.5 * i as f32, -3.0]).collect();
    let (kind, _, _, rows) =
        read_mental(&written("mt", "mt", "m", &ImageData::new(W, H, Pixels::Motion(motion.clone()))), 12);
    assert_eq!(kind, 0x0c);
    assert_eq!(be_f32s(&rows), motion.iter().flat_map(|m| [m[0], m[1], 0.0]).collect::<Vec<_>>());

    let tags: Vec<u32> = (0..n as u32).map(|i| i.wrapping_mul(2_654_435_761)).collect();
    let (kind, _, _, rows) =
        read_mental(&written("tt", "tt", "tag", &ImageData::new(W, H, Pixels::Tag(tags.clone()))), 4);
    assert_eq!(kind, 0x0a);
    let got: Vec<u32> = rows.concat().chunks(4).map(|b| u32::from_be_bytes(b.try_into().unwrap())).collect();
    assert_eq!(got, tags);

    let v = scalar(W, H);
    let img = ImageData::new(W, H, Pixels::Scalar(v.clone()));
    let (kind, _, _, rows) = read_mental(&written("st", "st", "a", &img), 1);
    assert_eq!(kind, 0x04);
    assert_eq!(rows.concat(), v.iter().map(|s| code8(*s)).collect::<Vec<_>>());
    let (_, _, _, rows) = read_mental(&written("stfp", "st", "a_fp", &img), 4);
    assert_eq!(be_f32s(&rows), v);
    let (kind, _, _, rows) = read_mental(&written("bit", "bit", "", &img), 1);
    assert_eq!(kind, 0x0d);
    assert_eq!(rows.concat(), v.iter().map(|s| u8::from(*s >= 0.5)).collect::<Vec<_>>());
}

/// Softimage `Zpic` as its description gives it: no header, big-endian 32-bit floats, one
/// per pixel, rows top first (the size is the companion `pic`'s), depth as camera-space z
/// from 0 at the camera to −100000. Depths d come back as −d bit for bit, pixels with
/// nothing (0) and depths beyond the range as −100000.
#[test]
fn softimage_zpic_depth() {
    let n = (W * H) as usize;
    let depth: Vec<f32> = (0..n).map(|i| if i % 5 == 0 { 0.0 } else { 0.25 + i as f32 }).collect();
    let mut far = depth.clone();
    far[1] = 3.0e5;
    let bytes = written("zpic", "Zpic", "z", &ImageData::new(W, H, Pixels::Depth(far)));
    assert_eq!(bytes.len(), n * 4, "no header: four bytes a pixel");
    let read = be_f32s(&[bytes]);
    for (i, (z, d)) in read.iter().zip(&depth).enumerate() {
        let want = if i == 1 || *d == 0.0 { -100_000.0 } else { -d };
        assert_eq!(z.to_bits(), want.to_bits(), "pixel {i}");
    }
}
