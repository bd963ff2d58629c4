//! MDL's `texture_ptex` resources: per-face textures read from Ptex files (`.ptx`,
//! [`reader`]) and looked up by `tex::lookup_*` at the hit's face and position on it.
//!
//! A Ptex file holds one small image per face of the mesh it was painted on. mira reads
//! every face's highest resolution (the file's level 0), its reduced levels (each half
//! the one before along u and v, as the file stores them) and its average (the file's
//! constant value of the face), and the faces' adjacency; not the meta data. Texels are
//! `f32` (8- and 16-bit integers scaled to [0, 1], half floats widened, NaN and infinite
//! texels read as 0).
//!
//! Looking up at a hit ([`Ptex::lookup`] at the face and coordinates [`quad::face_at`]
//! finds): in a triangle-mesh file the Ptex face id is the hit triangle's index within its
//! object (mira's meshes are triangles, numbered in the order the object's polygons give
//! them), and the position on the face is the hit's barycentric coordinates, Ptex's
//! triangle convention: u weights the triangle's second vertex, v its third (the first at
//! (0, 0), the second at (1, 0), the third at (0, 1)). In a quad-mesh file the face id is
//! the quad polygon's (Ptex's numbering: a quad one face, another polygon one per vertex)
//! and the position the hit's place on the quad (origin at its vertex 0, u along the edge
//! 0 → 1, v along 0 → 3). The lookup interpolates between texels and across face edges
//! ([`filter`]); [`Ptex::texel`] and [`Filter::Nearest`] give the nearest texel (Ptex's
//! point filter).
//!
//! Triangle textures (Ptex's layout): a face of resolution 2^n is cut into 4^n small
//! triangles of side 1/2^n; the upright one with its right angle at grid corner (i, j)
//! (i + j < 2^n) is texel (i, j) of a square image of 2^n × 2^n texels, the inverted one
//! with its right angle at corner (i + 1, j + 1) (i + j < 2^n − 1) is texel
//! (2^n − 1 − j, 2^n − 1 − i), the image's upper right half. Quad textures: texel
//! (⌊u w⌋, ⌊v h⌋) of the face's w × h image (row v = 0 first).

use glam::Vec4;

pub mod anisotropic;
mod edges;
pub mod filter;
pub mod footprint;
pub mod quad;
pub mod reader;

pub use filter::Filter;
use footprint::FaceEllipse;

/// The mesh type a Ptex file's faces are textures of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshType {
    /// Triangles (barycentric face coordinates).
    Triangle,
    /// Quads (bilinear face coordinates).
    Quad,
}

/// The texels of one face: `start` of its first texel's first channel in [`Ptex`]'s
/// texels, its resolution (log2 along u and v; a constant face is 1 × 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceTexels {
    /// Index of its first value in the texture's texels.
    pub start: usize,
    /// log2 of its width (texels along u).
    pub ulog2: u8,
    /// log2 of its height (texels along v).
    pub vlog2: u8,
}

/// A face's neighbours as the file records them: per edge (quads: 0 v = 0, 1 u = 1, 2
/// v = 1, 3 u = 0; triangles: 0 v = 0, 1 u + v = 1, 2 u = 0; counter-clockwise) the
/// adjacent face (−1: none) and which of its edges is shared (2 bits per edge).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Adjacency {
    /// Adjacent face per edge, −1 where there is none.
    pub faces: [i32; 4],
    /// The adjacent face's edge per edge, 2 bits each (edge 0 in the lowest).
    pub edges: u8,
}

impl Adjacency {
    /// The face and edge across edge `edge`, if any.
    pub fn across(&self, edge: usize) -> Option<(usize, usize)> {
        let face = usize::try_from(*self.faces.get(edge)?).ok()?;
        Some((face, usize::from((self.edges >> (2 * edge)) & 3)))
    }
}

/// A Ptex texture: every face's texels at its highest resolution and its reduced levels,
/// as `f32` texels, and how the faces adjoin.
#[derive(Clone, Debug, PartialEq)]
pub struct Ptex {
    /// The faces' mesh type.
    pub mesh: MeshType,
    /// Channels per texel.
    pub channels: usize,
    /// The alpha channel, if the file names one.
    pub alpha: Option<usize>,
    /// Per face (by Ptex face id): where its texels are (level 0, the highest resolution).
    pub faces: Vec<FaceTexels>,
    /// Per face: its reduced levels in turn (each half the one before along u and v, as
    /// the file stores them), the last the face's average (1 × 1); none for a constant
    /// face.
    pub reductions: Vec<Vec<FaceTexels>>,
    /// Per face: its neighbours.
    pub adjacency: Vec<Adjacency>,
    /// Per face: whether the file flags it a sub-face (Ptex's flag 8: one of the sub-quads
    /// of a quad-mesh file's non-quad face, half a quad face's size in parameter space:
    /// its edge against a quad face is half of that face's edge); empty: none is.
    pub subfaces: Vec<bool>,
    /// Every face's texels, row by row (v = 0 first, u fastest), channels interleaved.
    pub texels: Vec<f32>,
}

impl Ptex {
    /// The channels of the texel of face `face` nearest to face coordinates (`u`, `v`)
    /// (clamped to the face); `None` for a face id the file has not.
    pub fn texel(&self, face: u32, u: f32, v: f32) -> Option<&[f32]> {
        let f = self.faces.get(face as usize)?;
        let index = match self.mesh {
            MeshType::Quad => quad_texel(f.ulog2, f.vlog2, u, v),
            MeshType::Triangle => triangle_texel(f.ulog2, u, v),
        };
        let at = f.start + index * self.channels;
        self.texels.get(at..at + self.channels)
    }

    /// The value `tex::lookup_*` gives at face `face`, coordinates (`u`, `v`), for a filter
    /// of width `width` (face units; `None`: the highest resolution): channels `channel`,
    /// `channel + 1`, … interpolated between texels ([`Filter::Bilinear`]) in lanes x, y,
    /// z, w (lanes past the last channel 0; a texture with one channel from `channel` on
    /// gives it in every lane, a grey colour). Black for a face the file has not or a
    /// channel past the last.
    pub fn lookup(&self, face: u32, u: f32, v: f32, width: Option<f32>, channel: usize) -> Vec4 {
        let mut lanes = [0.0f32; 4];
        if channel >= self.channels || !self.sample(face, u, v, width, Filter::Bilinear, channel, &mut lanes) {
            return Vec4::ZERO;
        }
        self.lanes_from(lanes, channel)
    }

    /// [`Ptex::lookup`] over a footprint `widths` wide along u and v (face units;
    /// [`Ptex::sample_rect`], which reads equal widths exactly as [`Ptex::lookup`] reads
    /// one of them; `None`: the highest resolution).
    pub fn lookup_rect(&self, face: u32, u: f32, v: f32, widths: Option<(f32, f32)>, channel: usize) -> Vec4 {
        let mut lanes = [0.0f32; 4];
        let found = match widths {
            _ if channel >= self.channels => false,
            Some(widths) => self.sample_rect(face, u, v, widths, channel, &mut lanes),
            None => self.sample(face, u, v, None, Filter::Bilinear, channel, &mut lanes),
        };
        if !found {
            return Vec4::ZERO;
        }
        self.lanes_from(lanes, channel)
    }

    /// [`Ptex::lookup`] over the footprint `ellipse` (face units; [`Ptex::sample_ellipse`],
    /// which reads a round one exactly as [`Ptex::lookup`] reads its width; `None`: the
    /// highest resolution).
    pub fn lookup_ellipse(&self, face: u32, u: f32, v: f32, ellipse: Option<FaceEllipse>, channel: usize) -> Vec4 {
        let mut lanes = [0.0f32; 4];
        let found = match ellipse {
            _ if channel >= self.channels => false,
            Some(ellipse) => self.sample_ellipse(face, u, v, ellipse, channel, &mut lanes),
            None => self.sample(face, u, v, None, Filter::Bilinear, channel, &mut lanes),
        };
        if !found {
            return Vec4::ZERO;
        }
        self.lanes_from(lanes, channel)
    }

    /// The value `tex::lookup_*` gives at hit `s` (the engines' Ptex lookup): at the face
    /// and coordinates [`quad::face_at`] finds, over the footprint's ellipse in face
    /// coordinates ([`footprint::filter_ellipse`], [`Ptex::lookup_ellipse`]); black where
    /// the hit has no face of this file.
    #[inline]
    pub fn lookup_at(&self, s: &shader::State, channel: usize) -> Vec4 {
        match quad::face_at(self.mesh, s) {
            Some((face, u, v)) => self.lookup_ellipse(face, u, v, footprint::filter_ellipse(self.mesh, s), channel),
            None => Vec4::ZERO,
        }
    }

    /// Whether face `face` is a sub-face ([`Ptex::subfaces`]).
    #[inline]
    pub fn is_subface(&self, face: u32) -> bool {
        self.subfaces.get(face as usize).copied().unwrap_or(false)
    }

    /// A lookup's lanes from channel `channel` on: one channel left is a grey colour.
    fn lanes_from(&self, lanes: [f32; 4], channel: usize) -> Vec4 {
        if self.channels - channel == 1 {
            return Vec4::splat(lanes[0]);
        }
        Vec4::from_array(lanes)
    }
}

/// Texel index (row-major, row v = 0 first) of a quad face of 2^`ulog2` × 2^`vlog2` texels
/// nearest to (`u`, `v`), clamped to the face.
fn quad_texel(ulog2: u8, vlog2: u8, u: f32, v: f32) -> usize {
    let (w, h) = (1usize << ulog2, 1usize << vlog2);
    let cell = |x: f32, n: usize| ((x.clamp(0.0, 1.0) * n as f32) as usize).min(n - 1);
    cell(v, h) * w + cell(u, w)
}

/// Texel index of a triangle face of resolution 2^`log2` (Ptex's layout, see the module
/// documentation) of the small triangle holding barycentric (`u`, `v`), clamped to the
/// face (u, v ≥ 0, u + v ≤ 1).
fn triangle_texel(log2: u8, u: f32, v: f32) -> usize {
    let n = 1usize << log2;
    let (mut u, mut v) = (if u.is_finite() { u.max(0.0) } else { 0.0 }, if v.is_finite() { v.max(0.0) } else { 0.0 });
    if u + v > 1.0 {
        let sum = u + v;
        (u, v) = (u / sum, v / sum);
    }
    let (x, y) = (u * n as f32, v * n as f32);
    let i = (x as usize).min(n - 1);
    let j = (y as usize).min(n - 1);
    let inverted = (x - i as f32) + (y - j as f32) >= 1.0;
    if inverted && i + j + 2 <= n {
        // The inverted small triangle with its right angle at corner (i + 1, j + 1).
        (n - 1 - i) * n + (n - 1 - j)
    } else {
        // The upright one at corner (i, j); on the face's long side, the last of its row.
        let i = i.min(n - 1 - j.min(n - 1));
        j * n + i
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every small triangle of a resolution-4 face, at its centroid, maps to its own texel
    /// and the 16 texels are all used once (exact).
    #[test]
    fn triangle_texels_cover_the_square_image_once() {
        let n = 4usize;
        let mut seen = vec![0; n * n];
        for j in 0..n {
            for i in 0..n - j {
                let up = triangle_texel(2, (i as f32 + 1.0 / 3.0) / n as f32, (j as f32 + 1.0 / 3.0) / n as f32);
                assert_eq!(up, j * n + i);
                seen[up] += 1;
                if i + j + 2 <= n {
                    let c = |k: usize| (k as f32 + 2.0 / 3.0) / n as f32;
                    let down = triangle_texel(2, c(i), c(j));
                    assert_eq!(down, (n - 1 - i) * n + (n - 1 - j));
                    seen[down] += 1;
                }
            }
        }
        assert!(seen.iter().all(|&k| k == 1), "{seen:?}");
        // The corners and outside points clamp onto the face.
        assert_eq!(triangle_texel(2, 1.0, 0.0), 3);
        assert_eq!(triangle_texel(2, 0.0, 1.0), 12);
        assert_eq!(triangle_texel(2, 2.0, 2.0), triangle_texel(2, 0.5, 0.5));
        assert_eq!(triangle_texel(0, 0.3, 0.3), 0);
    }

    /// Quad texels: ⌊u w⌋, ⌊v h⌋, clamped (exact).
    #[test]
    fn quad_texels_are_row_major_from_v_zero() {
        assert_eq!(quad_texel(2, 1, 0.0, 0.0), 0);
        assert_eq!(quad_texel(2, 1, 0.99, 0.0), 3);
        assert_eq!(quad_texel(2, 1, 0.3, 0.7), 4 + 1);
        assert_eq!(quad_texel(2, 1, 1.0, 1.0), 7);
        assert_eq!(quad_texel(2, 1, -1.0, f32::NAN), 0);
    }
}
