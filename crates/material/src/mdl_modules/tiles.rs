//! The tile pattern of `base::tile_texture` and `base::tile_bump_texture`, with what varies
//! tile by tile: missing tiles, brightness variation, rough grout edges, random row
//! offsets, and special rows and columns of other sizes.
//!
//! The steps follow the published behaviour of the MDL SDK's `base.mdl`: the coordinate
//! repeats over [0, 1)²; every `special_row_index`-th row and `special_column_index`-th
//! column (counted from 1) is rescaled; odd rows shift by `odd_row_offset` tiles, every row
//! by `random_row_offset` times a noise of its index; a tile is missing where its noise
//! (folded to [0, 1)) is below `missing_tile_amount`; grout lies within `grout_width` /
//! `grout_height` (texture units) of each tile's edges, widened by `grout_roughness` times
//! a noise stretched along the edges; a tile's brightness varies by
//! `tile_brightness_variation` times its own noise. The noise is mira's gradient noise
//! ([`perlin4`]), so which tiles are missing or brighter is not NVIDIA's tile for tile.

use glam::{Vec3A, Vec4};

use super::procedural::perlin4;

/// The parameters of the tile pattern (texture units; counts of tiles in [0, 1)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tiling {
    /// `number_of_rows`.
    pub rows: f32,
    /// `number_of_columns`.
    pub columns: f32,
    /// `grout_width`.
    pub grout_width: f32,
    /// `grout_height`.
    pub grout_height: f32,
    /// `grout_roughness`.
    pub grout_roughness: f32,
    /// `missing_tile_amount` (a fraction of the tiles).
    pub missing_tile_amount: f32,
    /// `tile_brightness_variation`.
    pub brightness_variation: f32,
    /// `seed`.
    pub seed: f32,
    /// `special_row_index` (1: every row).
    pub special_row_index: i32,
    /// `special_row_width_factor`.
    pub special_row_width_factor: f32,
    /// `special_column_index`.
    pub special_column_index: i32,
    /// `special_column_height_factor`.
    pub special_column_height_factor: f32,
    /// `odd_row_offset` (a fraction of a tile).
    pub odd_row_offset: f32,
    /// `random_row_offset`.
    pub random_row_offset: f32,
}

/// Where a point lies in the pattern.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TileSample {
    /// On a tile (else in the grout or a missing tile).
    pub in_tile: bool,
    /// The tile's relative brightness change (`tile_brightness_variation` times its
    /// noise, in [−variation, variation]; 0 in the grout).
    pub variation: f32,
}

fn noise2(x: f32, y: f32) -> f32 {
    perlin4([x, y, 0.0, 0.0])
}

impl Tiling {
    /// The pattern at texture coordinate (u, v).
    pub fn sample(&self, u: f32, v: f32) -> TileSample {
        let grout = TileSample { in_tile: false, variation: 0.0 };
        let (rows0, columns0) = (self.rows.max(1e-6), self.columns.max(1e-6));
        let (mut rows, mut columns) = (rows0, columns0);
        let mut x = (u - u.floor()) * columns;
        let mut y = (v - v.floor()) * rows;
        let mut row = y.floor() as i64;
        let column = x.floor() as i64;
        // Special rows and columns (an index of 0 or less reads as 1: every one).
        let every = |k: i64, n: i32| k.wrapping_add(1).rem_euclid(i64::from(n.max(1))) == 0;
        if every(row, self.special_row_index) && every(column, self.special_column_index) {
            columns *= self.special_column_height_factor;
            x *= self.special_column_height_factor;
            rows *= self.special_row_width_factor;
            y *= self.special_row_width_factor;
            row = y.floor() as i64;
        }
        let row_f = y.floor();
        if row & 1 != 0 {
            x += self.odd_row_offset;
        }
        if self.random_row_offset > 0.0 {
            x += self.random_row_offset * noise2(row_f * self.seed, 0.0);
        }
        let column_f = x.floor();
        let (fx, fy) = (x - column_f, y - row_f);
        if self.missing_tile_amount > 0.0 {
            let n = noise2(column_f * self.seed, row_f * self.seed);
            if self.missing_tile_amount > if n >= 0.0 { n } else { n + 1.0 } {
                return grout;
            }
        }
        // The grout in tile units, roughened by noise compressed along the edges.
        let mut gw = self.grout_width * columns;
        let mut gh = self.grout_height * rows;
        if self.grout_roughness > 0.0 {
            let scale_v = 10.0 * (rows + columns);
            let scale_u = columns / rows * scale_v;
            gw += columns / columns0 * self.grout_roughness * noise2(u * scale_u, v * scale_v);
            gh += rows * rows / (columns * rows0) * self.grout_roughness * noise2(u * scale_v, v * scale_u);
        }
        if fx < gw || fx > 1.0 - gw || fy < gh || fy > 1.0 - gh {
            return grout;
        }
        let variation = if self.brightness_variation > 0.0 {
            self.brightness_variation * noise2(column_f * self.seed * 0.5, row_f * self.seed * 0.5)
        } else {
            0.0
        };
        TileSample { in_tile: true, variation }
    }

    /// The pattern as the hit expressions read it at texture-space position `p`: x the bump
    /// height (1 on a tile scaled by its brightness, 1 + variation clamped to [0, 1]; 0 in
    /// the grout), y 1 on a tile, z the tile's variation.
    pub fn eval(&self, p: Vec3A) -> Vec4 {
        let s = self.sample(p.x, p.y);
        let on = if s.in_tile { 1.0 } else { 0.0 };
        Vec4::new(on * (1.0 + s.variation).clamp(0.0, 1.0), on, s.variation, 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plain() -> Tiling {
        Tiling {
            rows: 4.0,
            columns: 4.0,
            grout_width: 0.02,
            grout_height: 0.02,
            grout_roughness: 0.0,
            missing_tile_amount: 0.0,
            brightness_variation: 0.0,
            seed: 2.284,
            special_row_index: 1,
            special_row_width_factor: 1.0,
            special_column_index: 1,
            special_column_height_factor: 1.0,
            odd_row_offset: 0.5,
            random_row_offset: 0.0,
        }
    }

    /// Tile centres (of the running bond) over a 16 × 16 grid of tiles.
    fn centres() -> Vec<(f32, f32)> {
        let n = 16.0;
        let mut out = Vec::new();
        for r in 0..16 {
            for c in 0..16 {
                let shift = if r % 2 == 1 { 0.5 } else { 0.0 };
                out.push((((c as f32 + 0.5 - shift) / n).rem_euclid(1.0), (r as f32 + 0.5) / n));
            }
        }
        out
    }

    #[test]
    fn grout_lies_along_both_edges_of_each_tile() {
        let t = plain();
        // Column edges at u = 0.25 k; grout 0.02 on both sides.
        for (u, on) in [(0.125, true), (0.228, true), (0.235, false), (0.26, false), (0.275, true)] {
            assert_eq!(t.sample(u, 0.125).in_tile, on, "u {u}");
        }
        // Odd rows shift by half a tile: an edge at u = 0.125.
        assert!(!t.sample(0.125, 0.375).in_tile);
        assert!(t.sample(0.25, 0.375).in_tile);
        // The coordinate repeats over [0, 1).
        assert_eq!(t.sample(1.125, -0.875), t.sample(0.125, 0.125));
    }

    #[test]
    fn missing_tiles_and_brightness_vary_tile_by_tile() {
        let mut t = Tiling { rows: 16.0, columns: 16.0, ..plain() };
        t.missing_tile_amount = 0.5;
        let all = centres();
        let missing = all.iter().filter(|(u, v)| !t.sample(*u, *v).in_tile).count();
        // About half of 256 tiles (noise folded to [0, 1) is not uniform: a wide band).
        assert!((50..=206).contains(&missing), "{missing} of 256 missing");
        // A whole tile is missing or not: a point off its centre agrees with the centre.
        for &(u, v) in &all {
            let near = t.sample(u + 0.006, v + 0.006).in_tile;
            assert_eq!(t.sample(u, v).in_tile, near, "({u}, {v})");
        }
        t.missing_tile_amount = 0.0;
        t.brightness_variation = 0.4;
        let vs: Vec<f32> = all.iter().map(|(u, v)| t.sample(*u, *v).variation).collect();
        assert!(vs.iter().all(|v| v.abs() <= 0.4));
        let distinct = vs.iter().filter(|v| (**v - vs[0]).abs() > 1e-3).count();
        assert!(distinct > 100, "brightness varies between tiles: {distinct}");
        // Constant over one tile.
        let (u, v) = all[37];
        assert_eq!(t.sample(u, v).variation, t.sample(u + 0.006, v - 0.006).variation);
    }

    #[test]
    fn special_rows_and_rough_grout_change_the_layout() {
        // Every second row and column (from 1) doubled in width: a tile of column 1, row 1
        // (0-based) is then half as wide, so u = 0.25 + 0.125 · 0.5 lands in its grout.
        let mut t = Tiling { odd_row_offset: 0.0, ..plain() };
        assert!(t.sample(0.3125 + 0.001, 0.375).in_tile);
        t.special_row_index = 2;
        t.special_column_index = 2;
        t.special_column_height_factor = 2.0;
        t.special_row_width_factor = 1.0;
        // x = 1.25 · 2 = 2.5 + 0.004·2: the middle of a new tile, grout at its edges 2.0/3.0.
        assert!(t.sample(0.3125 + 0.001, 0.375).in_tile);
        assert!(!t.sample(0.376, 0.375).in_tile, "an edge of the doubled columns at u = 0.375");
        assert!(t.sample(0.376, 0.125).in_tile, "row 0 is not special");
        // Rough grout moves the grout's edge along the edge, not across whole tiles.
        let mut r = plain();
        r.grout_roughness = 0.2;
        let changed = (0..2000).filter(|k| {
            let (u, v) = (0.251 + 0.02 * (*k % 10) as f32 / 10.0, 0.01 + 0.23 * (*k / 10) as f32 / 200.0);
            r.sample(u, v).in_tile != plain().sample(u, v).in_tile
        });
        assert!(changed.count() > 20);
        assert!(r.sample(0.125, 0.125).in_tile, "tile centres stay tiles");
    }

    /// Hostile numbers (huge or non-finite counts and coordinates) give an answer, never a
    /// panic (indices saturate).
    #[test]
    fn extreme_parameters_do_not_panic() {
        for (rows, u) in [(1e30f32, 0.5f32), (f32::INFINITY, 0.3), (f32::NAN, f32::NAN), (4.0, f32::INFINITY)] {
            let t = Tiling { rows, columns: rows, special_row_index: 2, special_column_index: 2, ..plain() };
            let _ = t.sample(u, 0.999_999);
        }
    }

    #[test]
    fn a_random_row_offset_shifts_rows_differently() {
        let mut t = Tiling { rows: 16.0, columns: 16.0, odd_row_offset: 0.0, ..plain() };
        t.random_row_offset = 0.5;
        // Where each row has grout along u: row 0's noise is 0 (the lattice), others shift.
        let layout = |v: f32| (0..400).map(|k| t.sample(k as f32 / 400.0, v).in_tile).collect::<Vec<bool>>();
        let rows: Vec<Vec<bool>> = (0..16).map(|r| layout((r as f32 + 0.5) / 16.0)).collect();
        let shifted = rows.iter().filter(|r| **r != rows[0]).count();
        assert!(shifted >= 8, "{shifted} of 15 rows shifted");
        let plain_rows = Tiling { random_row_offset: 0.0, ..t };
        assert!((0..400).all(|k| plain_rows.sample(k as f32 / 400.0, 0.5 / 16.0).in_tile == rows[0][k]));
    }
}
