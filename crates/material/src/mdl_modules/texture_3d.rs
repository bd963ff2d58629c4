//! MDL's `texture_3d` resources: a block of voxels read from a DDS volume file, looked up
//! by `tex::lookup_*` with trilinear interpolation and MDL's wrap modes and crops per axis,
//! and read texel by texel by `tex::texel_*`.
//!
//! Texture space: u along x (the file's columns, left to right), v along y with v = 0 at
//! the bottom of each slice (the file's last row, as 2D textures are read), w along z (the
//! file's first slice at w = 0); [0, 1)³ covers the volume once, voxel (i, j, k) centred at
//! ((i + ½)/width, (j + ½)/height, (k + ½)/depth). Between voxel centres values are
//! interpolated linearly along each axis; the neighbours of a voxel at the volume's side
//! follow the axis's wrap mode (`wrap_repeat`: the far side; `wrap_mirrored_repeat`: the
//! mirror image; `wrap_clamp` and `wrap_clip`: the side voxel itself), and `wrap_clip`
//! gives black outside [0, 1). A crop (`crop_u` …, the part of [0, 1) the volume's
//! coordinate range covers) restricts the voxels and the wrapping to that part.

use glam::{Vec3A, Vec4};

/// Voxels of a `texture_3d`.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume {
    /// Voxels along x, y, z.
    pub size: [usize; 3],
    /// RGBA per voxel, x fastest, then y (bottom row first), then z.
    voxels: Vec<Vec4>,
}

impl Volume {
    /// A volume of `size` voxels from texels in a DDS file's order (slices, each slice's rows
    /// top to bottom, each row left to right); `None` when the counts do not match.
    pub fn from_file_order(size: [usize; 3], texels: &[Vec4]) -> Option<Volume> {
        let [w, h, d] = size;
        if w == 0 || h == 0 || d == 0 || texels.len() != w * h * d {
            return None;
        }
        let mut voxels = Vec::with_capacity(texels.len());
        for z in 0..d {
            for y in 0..h {
                let row = (z * h + (h - 1 - y)) * w;
                voxels.extend_from_slice(&texels[row..row + w]);
            }
        }
        Some(Volume { size, voxels })
    }

    /// The voxel at integer position (x, y, z) (y up); black outside the volume.
    pub fn texel(&self, x: i64, y: i64, z: i64) -> Vec4 {
        let [w, h, d] = self.size.map(|n| n as i64);
        if !(0..w).contains(&x) || !(0..h).contains(&y) || !(0..d).contains(&z) {
            return Vec4::ZERO;
        }
        self.voxels[((z * h + y) * w + x) as usize]
    }

    /// The interpolated value at texture coordinate `coord` with the wrap modes
    /// (`tex::wrap_mode` enumerator names) and crops (per axis the part [0, 1) maps to).
    pub fn lookup(&self, coord: Vec3A, wrap: [&str; 3], crop: [[f32; 2]; 3]) -> Vec4 {
        let mut axes = [(0i64, 0i64, 0.0f32); 3];
        for a in 0..3 {
            match self.axis(coord[a], wrap[a], crop[a], self.size[a]) {
                Some(x) => axes[a] = x,
                None => return Vec4::ZERO,
            }
        }
        let [(x0, x1, fx), (y0, y1, fy), (z0, z1, fz)] = axes;
        let lerp = |a: Vec4, b: Vec4, t: f32| a + (b - a) * t;
        let plane = |z: i64| {
            let low = lerp(self.texel(x0, y0, z), self.texel(x1, y0, z), fx);
            let high = lerp(self.texel(x0, y1, z), self.texel(x1, y1, z), fx);
            lerp(low, high, fy)
        };
        lerp(plane(z0), plane(z1), fz)
    }

    /// Along one axis of `n` voxels: the two voxels a coordinate `c` falls between and the
    /// weight of the second; `None` when clipped (or not a number).
    fn axis(&self, c: f32, mode: &str, crop: [f32; 2], n: usize) -> Option<(i64, i64, f32)> {
        if !c.is_finite() || (mode == "wrap_clip" && !(0.0..1.0).contains(&c)) {
            return None;
        }
        // The voxels of the crop window: [lo, hi).
        let lo = ((crop[0] * n as f32).floor() as i64).clamp(0, n as i64 - 1);
        let hi = ((crop[1] * n as f32).ceil() as i64).clamp(lo + 1, n as i64);
        let span = hi - lo;
        // The coordinate in voxels of the window, centres at k + ½.
        let x = c * span as f32 - 0.5;
        let i = x.floor();
        let t = x - i;
        let i = i as i64;
        let place = |k: i64| -> i64 {
            let k = if mode == "wrap_repeat" {
                k.rem_euclid(span)
            } else if mode == "wrap_mirrored_repeat" {
                let m = k.rem_euclid(2 * span);
                if m < span {
                    m
                } else {
                    2 * span - 1 - m
                }
            } else {
                k.clamp(0, span - 1)
            };
            lo + k
        };
        Some((place(i), place(i + 1), t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2×1×1 volume: 0 and 1 at the voxel centres, ½ between them; the side's neighbour
    /// by each wrap mode.
    #[test]
    fn interpolates_between_centres_and_wraps_per_mode() {
        let v = Volume::from_file_order([2, 1, 1], &[Vec4::ZERO, Vec4::ONE]).unwrap();
        let at = |u: f32, mode: &str| {
            v.lookup(Vec3A::new(u, 0.5, 0.5), [mode, "wrap_clamp", "wrap_clamp"], [[0.0, 1.0]; 3]).x
        };
        for mode in ["wrap_repeat", "wrap_clamp", "wrap_mirrored_repeat", "wrap_clip"] {
            assert_eq!(at(0.25, mode), 0.0, "{mode}");
            assert_eq!(at(0.75, mode), 1.0, "{mode}");
            assert!((at(0.5, mode) - 0.5).abs() < 1e-6, "{mode}");
        }
        // u = 0: half way between voxel 0 and its left neighbour.
        assert!((at(0.0, "wrap_repeat") - 0.5).abs() < 1e-6);
        assert_eq!(at(0.0, "wrap_clamp"), 0.0);
        assert_eq!(at(0.0, "wrap_mirrored_repeat"), 0.0);
        assert_eq!(at(-0.1, "wrap_clip"), 0.0);
        assert!((at(1.25, "wrap_repeat") - 0.0).abs() < 1e-6);
    }
}
