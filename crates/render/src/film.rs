//! The film: per-pixel sample accumulators and the frame buffers made from them.
//!
//! Colour buffers store the filter-weighted mean of a pixel's samples (straight RGB, alpha =
//! coverage). A sample whose colour is NaN or infinite is stored as 1.0 in those channels
//! (mental ray's rule) and counted. `z` (depth along −Z in camera space, 0 where nothing was
//! hit), `n` (world-space shading normal), `tag` (the instance's label) and `m` (raster-space
//! motion, both engines) come from each pixel's first sample.

use bsdf::Rgb;

/// One pixel's accumulators.
#[derive(Clone, Copy, Debug, Default)]
pub struct Pixel {
    /// Σ w·rgba.
    pub sum: [f64; 4],
    /// Σ w.
    pub weight: f64,
    /// Σ w·rgb of the odd-numbered samples (for the error estimate).
    pub odd_sum: [f32; 3],
    /// Σ w of the odd-numbered samples.
    pub odd_weight: f32,
    /// Samples taken.
    pub samples: u32,
    /// Depth of the first sample's hit (0: none).
    pub depth: f32,
    /// World-space shading normal of the first sample's hit.
    pub normal: [f32; 3],
    /// Label of the first sample's hit.
    pub tag: u32,
    /// Raster-space motion of the first sample's hit over the shutter interval (pixels, x
    /// right, y up as mental ray's raster space; 0 where nothing moves or was hit).
    pub motion: [f32; 2],
    /// Whether the pixel has converged.
    pub converged: bool,
    /// Smallest value of each channel (RGBA) over the samples (for the contrast test).
    pub lo: [f32; 4],
    /// Largest value of each channel over the samples.
    pub hi: [f32; 4],
}

impl Pixel {
    /// Adds one sample: colour, alpha and filter weight. Returns the number of channels
    /// that were NaN or infinite (stored as 1.0).
    pub fn add(&mut self, c: Rgb, alpha: f32, w: f32, index: u32) -> u32 {
        let mut bad = 0;
        let mut fix = |v: f32| {
            if v.is_finite() {
                v
            } else {
                bad += 1;
                1.0
            }
        };
        let c = Rgb::new(fix(c.x), fix(c.y), fix(c.z));
        let w64 = f64::from(w);
        self.sum[0] += f64::from(c.x) * w64;
        self.sum[1] += f64::from(c.y) * w64;
        self.sum[2] += f64::from(c.z) * w64;
        self.sum[3] += f64::from(alpha) * w64;
        self.weight += w64;
        let v = [c.x, c.y, c.z, alpha];
        if self.samples == 0 {
            self.lo = v;
            self.hi = v;
        } else {
            for ((lo, hi), x) in self.lo.iter_mut().zip(&mut self.hi).zip(v) {
                *lo = lo.min(x);
                *hi = hi.max(x);
            }
        }
        if index % 2 == 1 {
            self.odd_sum[0] += c.x * w;
            self.odd_sum[1] += c.y * w;
            self.odd_sum[2] += c.z * w;
            self.odd_weight += w;
        }
        self.samples += 1;
        bad
    }

    /// The pixel's colour and alpha.
    pub fn rgba(&self) -> [f32; 4] {
        if self.weight == 0.0 {
            return [0.0; 4];
        }
        let inv = 1.0 / self.weight;
        [(self.sum[0] * inv) as f32, (self.sum[1] * inv) as f32, (self.sum[2] * inv) as f32, (self.sum[3] * inv) as f32]
    }

    /// Relative difference between the odd samples' mean and the whole mean, in luminance:
    /// an estimate of the pixel's remaining error.
    pub fn error(&self) -> f32 {
        if self.samples < 4 || self.odd_weight == 0.0 || self.weight == 0.0 {
            return f32::INFINITY;
        }
        let all = self.rgba();
        let lum = |r: f32, g: f32, b: f32| 0.2126 * r + 0.7152 * g + 0.0722 * b;
        let l_all = lum(all[0], all[1], all[2]);
        let o = self.odd_sum;
        let l_odd = lum(o[0], o[1], o[2]) / self.odd_weight;
        // Absolute below a luminance of 0.1, relative above (dark pixels converge too).
        (l_all - l_odd).abs() / l_all.max(0.1)
    }
}

/// A user frame buffer declared by the scene (`frame buffer n "type"` in the options, or a
/// camera `framebuffer` with `user on`): four channels per pixel that shaders write with
/// `fb_put` (zero where nothing was written).
#[derive(Clone, Debug)]
pub struct UserBuffer {
    /// Name: `fb<n>` for numbered buffers, else the framebuffer's name.
    pub name: String,
    /// Declared data type (`rgba`, `rgba_fp`, `s`, `z`, …).
    pub datatype: String,
    /// Values, row by row from the top: the mean of what the samples wrote.
    pub data: Vec<[f32; 4]>,
    /// Writes per pixel.
    pub writes: Vec<u32>,
}

impl UserBuffer {
    /// Adds a value written by a sample of pixel `i` (the buffer keeps the mean).
    pub fn put(&mut self, i: usize, v: [f32; 4]) {
        self.writes[i] += 1;
        let n = self.writes[i] as f32;
        let d = &mut self.data[i];
        for k in 0..4 {
            let x = if v[k].is_finite() { v[k] } else { 1.0 };
            d[k] += (x - d[k]) / n;
        }
    }
}

/// The accumulated image.
#[derive(Clone, Debug)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The image row of this film's first row: 0, unless the film holds a strip of a larger
    /// image's rows (see [`crate::render::Settings::rows`]).
    pub y0: u32,
    /// Pixels, row by row from the top.
    pub pixels: Vec<Pixel>,
    /// User frame buffers.
    pub user: Vec<UserBuffer>,
    /// Filter-weighted sums of splatted samples (Σ w·rgba, Σ w) per pixel, when the engine
    /// splats (see [`crate::filter`]); empty otherwise.
    pub splat: Vec<[f64; 5]>,
}

impl Film {
    /// An empty film.
    pub fn new(width: u32, height: u32) -> Film {
        Film {
            width,
            height,
            y0: 0,
            pixels: vec![Pixel::default(); width as usize * height as usize],
            user: Vec::new(),
            splat: Vec::new(),
        }
    }

    /// Adds a user frame buffer.
    pub fn add_user_buffer(&mut self, name: &str, datatype: &str) {
        let n = self.width as usize * self.height as usize;
        self.user.push(UserBuffer {
            name: name.to_string(),
            datatype: datatype.to_string(),
            data: vec![[0.0; 4]; n],
            writes: vec![0; n],
        });
    }

    /// The pixels of image rows `rows` (within this film's; see [`Film::y0`]) as a film of
    /// their own: what a strip keeps (see [`crate::strips`]).
    pub fn rows(&self, rows: std::ops::Range<u32>) -> Film {
        let w = self.width as usize;
        let start = (rows.start.clamp(self.y0, self.y0 + self.height) - self.y0) as usize;
        let end = (rows.end.clamp(self.y0, self.y0 + self.height) - self.y0) as usize;
        let end = end.max(start);
        let cut = |i: usize| i * w;
        Film {
            width: self.width,
            height: (end - start) as u32,
            y0: self.y0 + start as u32,
            pixels: self.pixels[cut(start)..cut(end)].to_vec(),
            user: self
                .user
                .iter()
                .map(|b| UserBuffer {
                    name: b.name.clone(),
                    datatype: b.datatype.clone(),
                    data: b.data[cut(start)..cut(end)].to_vec(),
                    writes: b.writes[cut(start)..cut(end)].to_vec(),
                })
                .collect(),
            splat: if self.splat.is_empty() { Vec::new() } else { self.splat[cut(start)..cut(end)].to_vec() },
        }
    }

    /// Replaces the colour buffer by `rgba` (RGBA per pixel, rows from the top: a post
    /// pass's result); each pixel then resolves to its new value, with its sample weight
    /// kept (1 for a pixel no sample reached).
    pub fn set_rgba(&mut self, rgba: &[[f32; 4]]) {
        self.splat.clear();
        for (p, c) in self.pixels.iter_mut().zip(rgba) {
            if p.weight <= 0.0 {
                p.weight = 1.0;
            }
            p.sum = c.map(|v| f64::from(v) * p.weight);
        }
    }

    /// The colour buffer, RGBA per pixel, row by row from the top.
    pub fn rgba(&self) -> Vec<[f32; 4]> {
        if self.splat.is_empty() {
            return self.pixels.iter().map(Pixel::rgba).collect();
        }
        self.pixels
            .iter()
            .zip(&self.splat)
            .map(|(p, s)| {
                if s[4] > 1e-9 {
                    let inv = 1.0 / s[4];
                    [(s[0] * inv) as f32, (s[1] * inv) as f32, (s[2] * inv) as f32, (s[3] * inv) as f32]
                } else {
                    p.rgba()
                }
            })
            .collect()
    }

    /// The depth buffer.
    pub fn depth(&self) -> Vec<f32> {
        self.pixels.iter().map(|p| p.depth).collect()
    }

    /// The normal buffer.
    pub fn normals(&self) -> Vec<[f32; 3]> {
        self.pixels.iter().map(|p| p.normal).collect()
    }

    /// The label buffer.
    pub fn tags(&self) -> Vec<u32> {
        self.pixels.iter().map(|p| p.tag).collect()
    }

    /// The motion buffer (`m`): raster-space motion of each pixel's first hit over the
    /// shutter interval, pixels (x right, y up).
    pub fn motion(&self) -> Vec<[f32; 2]> {
        self.pixels.iter().map(|p| p.motion).collect()
    }
}
