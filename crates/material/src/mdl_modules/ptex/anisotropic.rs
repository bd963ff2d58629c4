//! Lookups with separate filter widths along a face's u and v ([`Ptex::sample_rect`]): a
//! footprint seen at a grazing angle is long along one face axis and short along the
//! other, and Ptex's own filters take the two widths apart.
//!
//! The short width picks the levels (blended, [`Ptex::blend_for`]); along the long axis
//! the lookup averages n = ⌈long / max(short, t)⌉ such lookups (t the width of a texel
//! along the long axis of the level the short width picks: a footprint within a texel is
//! one interpolated lookup, as the isotropic one; at most [`MAX_PROBES`]) spaced
//! evenly over the long width, the footprint's rectangle covered by n squares of the
//! short width — the rectangle's average of the face, where an isotropic width (the
//! footprint's area as a square) would blur the short axis as much as the long one.
//!
//! A probe past a face edge reads the face across it ([`Ptex::across_edges`]: the point
//! carried over the edge as the bilinear filter carries texels, `filter`'s `outside_edge`
//! mapping, and on over further edges up to [`MAX_CROSSINGS`] times), with the same widths
//! (the neighbour taken to be as large as the face); where no face is across, the probe
//! clamps to the face's edge.

use super::filter::{from_edge, outside_edge};
use super::{Filter, MeshType, Ptex};

/// The most face edges a probe is carried across.
pub const MAX_CROSSINGS: usize = 4;

/// The most lookups a rectangle is averaged from (a longer footprint is read with squares
/// wider than its short width: blurred along the short axis by that much).
pub const MAX_PROBES: usize = 16;

impl Ptex {
    /// The filtered value at face `face`, face coordinates (`u`, `v`), over a footprint
    /// `widths` wide along u and v (face units): channels `first`, `first + 1`, … into
    /// `out` (at most 4 lanes; 0 past the last channel). A width that is 0 or not finite
    /// counts as the other; both: level 0. False for a face the file has not.
    pub fn sample_rect(&self, face: u32, u: f32, v: f32, widths: (f32, f32), first: usize, out: &mut [f32]) -> bool {
        let ok = |w: f32| w.is_finite() && w > 0.0;
        let (wu, wv) = match widths {
            (a, b) if ok(a) && ok(b) => (a, b),
            (a, _) if ok(a) => (a, a),
            (_, b) if ok(b) => (b, b),
            _ => return self.sample(face, u, v, None, Filter::Bilinear, first, out),
        };
        let (short, long) = (wu.min(wv), wu.max(wv));
        let along_u = wu >= wv;
        // A footprint no longer than a texel of the level the short width picks (along the
        // long axis) is covered by one interpolated lookup.
        let texel = self.level(face as usize, self.level_for(face as usize, Some(short))).map_or(0.0, |t| {
            let log2 = if along_u || self.mesh == MeshType::Triangle { t.ulog2 } else { t.vlog2 };
            (0.5f32).powi(i32::from(log2))
        });
        let probes = ((long / short.max(texel)).ceil() as usize).clamp(1, MAX_PROBES);
        if probes == 1 || out.len() > 4 {
            return self.sample(face, u, v, Some(long), Filter::Bilinear, first, out);
        }
        // Squares of the spacing's width (the short width unless the probes ran out).
        let step = long / probes as f32;
        let width = short.max(step);
        out.fill(0.0);
        let mut lanes = [0.0f32; 4];
        let lanes = &mut lanes[..out.len()];
        for k in 0..probes {
            let offset = (k as f32 + 0.5) * step - 0.5 * long;
            let (pu, pv) = if along_u { (u + offset, v) } else { (u, v + offset) };
            let (pface, pu, pv) = self.across_edges(face, pu, pv);
            if !self.sample(pface, pu, pv, Some(width), Filter::Bilinear, first, lanes) {
                out.fill(0.0);
                return false;
            }
            for (o, l) in out.iter_mut().zip(lanes.iter()) {
                *o += *l / probes as f32;
            }
        }
        true
    }

    /// The face and face coordinates of the point (`u`, `v`) of face `face`, carried across
    /// the edges it lies past into the faces there (at most [`MAX_CROSSINGS`] edges); the
    /// point as given (then clamped by the lookup) past an edge with no face across.
    pub fn across_edges(&self, face: u32, u: f32, v: f32) -> (u32, f32, f32) {
        let (mut face, mut u, mut v) = (face, u, v);
        for _ in 0..MAX_CROSSINGS {
            let Some((edge, t, s)) = outside_edge(self.mesh, u, v) else { break };
            let Some((other, other_edge)) = self.adjacency.get(face as usize).and_then(|a| a.across(edge)) else {
                break;
            };
            let Ok(other) = u32::try_from(other) else { break };
            if other as usize >= self.faces.len() {
                break;
            }
            (u, v) = from_edge(self.mesh, other_edge, 1.0 - t, -s);
            face = other;
        }
        (face, u, v)
    }
}
