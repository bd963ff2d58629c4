//! Test images with runs (for the run-length encoders) and noise, and a scratch directory.

#![allow(dead_code)]

use std::path::PathBuf;

use imageio::{ImageData, Pixels};

/// A scratch directory unique to this process and `tag`.
pub fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("imageio-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A hash of (x, y, k) to [0, 1).
pub fn noise(x: u32, y: u32, k: u32) -> f32 {
    let mut h = x.wrapping_mul(0x9E37_79B1) ^ y.wrapping_mul(0x85EB_CA77) ^ k.wrapping_mul(0xC2B2_AE3D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2C1B_3C6D);
    h ^= h >> 12;
    (h >> 8) as f32 / (1u32 << 24) as f32
}

/// Whether pixel (x, y) lies in a flat region (long runs) rather than noise.
fn flat(x: u32, y: u32) -> bool {
    x < 25 || (y / 7) % 3 == 0
}

/// A `w × h` colour image: display values in [0, 1] with exact 0s and 1s, runs and noise;
/// linear values in [0, 8) with runs and noise; alpha partly 0 and 1.
pub fn colour(w: u32, h: u32) -> ImageData {
    let mut linear = Vec::new();
    let mut display = Vec::new();
    for y in 0..h {
        for x in 0..w {
            if flat(x, y) {
                let band = (y / 5) as f32;
                display.push([(band * 0.13) % 1.0, 1.0, 0.0, if x < 10 { 0.0 } else { 1.0 }]);
                linear.push([band * 0.37, 2.5, 0.0, 1.0]);
            } else {
                display.push([noise(x, y, 0), noise(x, y, 1), noise(x, y, 2), noise(x, y, 3)]);
                linear.push([8.0 * noise(x, y, 4), noise(x, y, 5), 0.01 * noise(x, y, 6), noise(x, y, 7)]);
            }
        }
    }
    ImageData::new(w, h, Pixels::Color { linear, display })
}

/// A smooth colour image (for JPEG): display values vary slowly.
pub fn smooth(w: u32, h: u32) -> ImageData {
    let mut display = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let (u, v) = (x as f32 / w as f32, y as f32 / h as f32);
            display.push([u, v, 0.5 * (u + v), 1.0]);
        }
    }
    ImageData::new(w, h, Pixels::Color { linear: display.clone(), display })
}

/// A scalar image in [0, 1] with runs and noise.
pub fn scalar(w: u32, h: u32) -> Vec<f32> {
    (0..h).flat_map(|y| (0..w).map(move |x| if flat(x, y) { 0.25 } else { noise(x, y, 9) })).collect()
}

/// The 8-bit code of a display value: clamped, × 255, rounded to nearest.
pub fn code8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The 16-bit code of a display value.
pub fn code16(v: f32) -> u16 {
    (v.clamp(0.0, 1.0) * 65535.0).round() as u16
}

/// The display values of a colour image, `channels` (3 or 4) per pixel.
pub fn display(image: &ImageData, channels: usize) -> Vec<f32> {
    match &image.pixels {
        Pixels::Color { display, .. } => display.iter().flat_map(|p| p[..channels].to_vec()).collect(),
        _ => panic!("not a colour image"),
    }
}

/// The linear values of a colour image, `channels` per pixel.
pub fn linear(image: &ImageData, channels: usize) -> Vec<f32> {
    match &image.pixels {
        Pixels::Color { linear, .. } => linear.iter().flat_map(|p| p[..channels].to_vec()).collect(),
        _ => panic!("not a colour image"),
    }
}

/// Big-endian readers over a byte slice.
pub struct Be<'a> {
    pub data: &'a [u8],
    pub at: usize,
}

impl<'a> Be<'a> {
    pub fn new(data: &'a [u8]) -> Be<'a> {
        Be { data, at: 0 }
    }
    pub fn u8(&mut self) -> u8 {
        self.at += 1;
        self.data[self.at - 1]
    }
    pub fn u16(&mut self) -> u16 {
        self.at += 2;
        u16::from_be_bytes([self.data[self.at - 2], self.data[self.at - 1]])
    }
    pub fn u32(&mut self) -> u32 {
        self.at += 4;
        u32::from_be_bytes(self.data[self.at - 4..self.at].try_into().unwrap())
    }
    pub fn f32(&mut self) -> f32 {
        f32::from_bits(self.u32())
    }
    pub fn bytes(&mut self, n: usize) -> &'a [u8] {
        self.at += n;
        &self.data[self.at - n..self.at]
    }
}
