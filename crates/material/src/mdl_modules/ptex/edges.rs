//! What neighbouring faces of a Ptex texture share, so that a filter is continuous across
//! them: a value at each mesh vertex ([`Ptex::add_vertex`]) and a value along each edge
//! (`add_edge`).
//!
//! A vertex's value is the mean of the corner texels of every face around it (each at the
//! level the filter width picks for it), the faces found by walking the adjacency around
//! the vertex both ways from the face that asks, so every face around it finds the same
//! faces. (Ptex's own separable filters apply the corner part of a kernel to the
//! diagonal face at a vertex of four faces and equally to every corner face at one of
//! five or more; mira averages all of them at any valence, the same for every face.)
//!
//! An edge's value at fraction t along it is the mean of the two faces' texel rows along
//! it, each interpolated at its own resolution (knots at its texel centres, the last half
//! texel at either end toward the vertex's value); with no face across, the face's own
//! row. Both faces compute the same function whatever their resolutions (a constant face
//! is a row of one texel), which is what makes the filter continuous. A triangle's row
//! has knots at its edge texels' middles and, between them, at the lattice vertices on
//! the edge (the mean of the face's three texels there), so that with equal resolutions
//! the edge's value is that of the dual-mesh interpolation across the edge.

use super::filter::Taps;
use super::{FaceTexels, MeshType, Ptex};

/// Most faces a walk around one vertex visits (a vertex of more faces averages the
/// first ones found; adjacency that loops without returning stops there too).
const MAX_VALENCE: usize = 32;

/// A vertex as one lookup found it: the faces around it with their corners there, and
/// the corner texels' first values.
pub(super) struct Vertex {
    around: [(usize, usize); MAX_VALENCE],
    count: usize,
    starts: [usize; MAX_VALENCE],
    found: usize,
}

impl Ptex {
    /// Edges (and corners) per face.
    fn sides(&self) -> usize {
        match self.mesh {
            MeshType::Quad => 4,
            MeshType::Triangle => 3,
        }
    }

    /// The faces around the vertex at corner `corner` of face `face` (corner k starts edge
    /// k: quads 0 (0, 0), 1 (1, 0), 2 (1, 1), 3 (0, 1); triangles 0 (0, 0), 1 (1, 0), 2
    /// (0, 1)), each with its corner there, into `out`; how many. Across edge k (from the
    /// vertex) the face across runs that edge the other way, so the vertex is the corner
    /// after its edge; across edge k − 1 (to the vertex) its edge's first corner.
    fn faces_around(&self, face: usize, corner: usize, out: &mut [(usize, usize); MAX_VALENCE]) -> usize {
        let n = self.sides();
        out[0] = (face, corner);
        let mut count = 1;
        let mut at = (face, corner);
        let mut closed = false;
        while count < MAX_VALENCE {
            let Some((g, edge)) = self.adjacency.get(at.0).and_then(|a| a.across(at.1)) else { break };
            let next = (g, (edge + 1) % n);
            if out[..count].contains(&next) {
                closed = true;
                break;
            }
            out[count] = next;
            count += 1;
            at = next;
        }
        at = (face, corner);
        while !closed && count < MAX_VALENCE {
            let Some((g, edge)) = self.adjacency.get(at.0).and_then(|a| a.across((at.1 + n - 1) % n)) else { break };
            let next = (g, edge);
            if out[..count].contains(&next) {
                break;
            }
            out[count] = next;
            count += 1;
            at = next;
        }
        count
    }

    /// Index of the first value of face `face`'s texel at corner `corner`, at the level
    /// `width` picks (quads: the corner texel of its image; triangles: the upright small
    /// triangle at the corner).
    fn corner_texel(&self, face: usize, corner: usize, width: Option<f32>) -> Option<usize> {
        let t = self.level(face, self.level_for(face, width))?;
        let (w, h) = (1usize << t.ulog2, 1usize << t.vlog2);
        let index = match (self.mesh, corner) {
            (_, 0) => 0,
            (_, 1) => w - 1,
            (MeshType::Quad, 2) => h * w - 1,
            (MeshType::Quad, _) => (h - 1) * w,
            (MeshType::Triangle, _) => (w - 1) * w,
        };
        Some(t.start + index * self.channels)
    }

    /// Adds `weight` × the value of the vertex at corner `corner` of face `face` (the
    /// module documentation).
    pub(super) fn add_vertex(&self, face: usize, corner: usize, width: Option<f32>, weight: f32, taps: &mut Taps) {
        if weight == 0.0 {
            return;
        }
        // Every face around a vertex finds the same faces: one walk per vertex a lookup.
        let known = taps.vertex.as_ref().is_some_and(|v| v.around[..v.count].contains(&(face, corner)));
        if !known {
            let mut v = Vertex { around: [(0, 0); MAX_VALENCE], count: 0, starts: [0; MAX_VALENCE], found: 0 };
            v.count = self.faces_around(face, corner, &mut v.around);
            for &(f, c) in &v.around[..v.count] {
                if let Some(start) = self.corner_texel(f, c, width) {
                    v.starts[v.found] = start;
                    v.found += 1;
                }
            }
            taps.vertex = Some(v);
        }
        let found = taps.vertex.as_ref().map_or(0, |v| v.found);
        for k in 0..found {
            let start = taps.vertex.as_ref().map_or(0, |v| v.starts[k]);
            taps.add(weight / found as f32, start);
        }
    }

    /// Adds `weight` × face `face`'s row of texels along its edge `edge` (quads: 0 v = 0,
    /// 1 u = 1, 2 v = 1, 3 u = 0, each counter-clockwise) at fraction `t` along it
    /// (`(edge, t)` = `along`),
    /// interpolated linearly between texel centres, toward the vertex's value in the half
    /// texel at either end. `texels` is the face's level.
    fn add_row(
        &self,
        face: usize,
        texels: FaceTexels,
        (edge, t): (usize, f32),
        width: Option<f32>,
        weight: f32,
        taps: &mut Taps,
    ) {
        if self.mesh == MeshType::Triangle {
            return self.add_triangle_row(face, texels, (edge, t), width, weight, taps);
        }
        let (w, h) = (1usize << texels.ulog2, 1usize << texels.vlog2);
        let n = if edge % 2 == 0 { w } else { h };
        let texel = |k: usize| {
            let index = match edge {
                0 => k,
                1 => k * w + w - 1,
                2 => (h - 1) * w + w - 1 - k,
                _ => (h - 1 - k) * w,
            };
            texels.start + index * self.channels
        };
        let p = t.clamp(0.0, 1.0) * n as f32 - 0.5;
        let last = (n - 1) as f32;
        if p < 0.0 {
            let f = 2.0 * p + 1.0;
            taps.add(weight * f, texel(0));
            self.add_vertex(face, edge, width, weight * (1.0 - f), taps);
        } else if p > last {
            let f = 2.0 * (p - last);
            taps.add(weight * (1.0 - f), texel(n - 1));
            self.add_vertex(face, (edge + 1) % 4, width, weight * f, taps);
        } else {
            let k = (p.floor() as usize).min(n.saturating_sub(2));
            let f = p - k as f32;
            taps.add(weight * (1.0 - f), texel(k));
            if f > 0.0 && k + 1 < n {
                taps.add(weight * f, texel(k + 1));
            }
        }
    }

    /// Adds `weight` × triangle face `face`'s own values along its edge `edge` (0 v = 0, 1
    /// u + v = 1, 2 u = 0, each counter-clockwise) at fraction `t` along it: piecewise
    /// linear through the face's corner vertices' values (t = 0, 1), its edge texels (one
    /// per 1/n of the edge, at their middles) and, at the lattice vertices between them,
    /// the mean of the three texels of the face around each (the two edge texels and the
    /// inverted one between them). `texels` is the face's level (n × n).
    fn add_triangle_row(
        &self,
        face: usize,
        texels: FaceTexels,
        (edge, t): (usize, f32),
        width: Option<f32>,
        weight: f32,
        taps: &mut Taps,
    ) {
        let n = 1usize << texels.ulog2;
        let nf = n as f32;
        // Texels by their centroids in the edge's frame (fraction along it, depth into the
        // face): the k-th edge texel at ((k + 1/3)/n, 1/(3n)), the inverted texel at
        // lattice vertex k at ((k − 1/3)/n, 2/(3n)), the same for each edge.
        let at = |t: f32, s: f32| {
            let (u, v) = super::filter::from_edge(MeshType::Triangle, edge, t, s);
            self.nearest(texels, u, v)
        };
        let edge_texel = |k: usize| at((k as f32 + 1.0 / 3.0) / nf, 1.0 / (3.0 * nf));
        let p = if t.is_finite() { t.clamp(0.0, 1.0) * nf } else { 0.0 };
        if p < 0.5 {
            let f = 2.0 * p;
            taps.add(weight * f, edge_texel(0));
            self.add_vertex(face, edge, width, weight * (1.0 - f), taps);
            return;
        }
        if p > nf - 0.5 {
            let f = 2.0 * (p - (nf - 0.5));
            taps.add(weight * (1.0 - f), edge_texel(n - 1));
            self.add_vertex(face, (edge + 1) % 3, width, weight * f, taps);
            return;
        }
        // Between edge texel k (g = 0), lattice vertex k + 1 (g = 1/2) and edge texel k + 1.
        let q = p - 0.5;
        let k = (q.floor() as usize).min(n - 1);
        let g = q - k as f32;
        let (w_left, w_vertex, w_right) =
            if g <= 0.5 { (1.0 - 2.0 * g, 2.0 * g, 0.0) } else { (0.0, 2.0 - 2.0 * g, 2.0 * g - 1.0) };
        if w_left != 0.0 {
            taps.add(weight * w_left, edge_texel(k));
        }
        if w_vertex != 0.0 && k + 1 < n {
            let inverted = at((k as f32 + 1.0 - 1.0 / 3.0) / nf, 2.0 / (3.0 * nf));
            for start in [edge_texel(k), edge_texel(k + 1), inverted] {
                taps.add(weight * w_vertex / 3.0, start);
            }
        }
        if w_right != 0.0 && k + 1 < n {
            taps.add(weight * w_right, edge_texel(k + 1));
        }
    }

    /// Adds `weight` × the value of face `face`'s edge `edge` at fraction `t` along it
    /// (`(edge, t)` = `along`):
    /// the mean of its row and the row of the face across (at the fraction 1 − t along that
    /// face's edge), or its own row where no face is across.
    pub(super) fn add_edge(
        &self,
        face: usize,
        texels: FaceTexels,
        (edge, t): (usize, f32),
        width: Option<f32>,
        weight: f32,
        taps: &mut Taps,
    ) {
        if weight == 0.0 {
            return;
        }
        let across = self.adjacency.get(face).and_then(|a| a.across(edge));
        let other = across.and_then(|(g, e)| Some((g, e, *self.level(g, self.level_for(g, width))?)));
        match other {
            Some((g, e, g_texels)) => {
                self.add_row(face, texels, (edge, t), width, 0.5 * weight, taps);
                self.add_row(g, g_texels, (e, 1.0 - t), width, 0.5 * weight, taps);
            }
            None => self.add_row(face, texels, (edge, t), width, weight, taps),
        }
    }
}
