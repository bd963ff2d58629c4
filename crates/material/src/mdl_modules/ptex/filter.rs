//! Filtered lookups of a [`Ptex`] texture: the nearest texel or an interpolation between
//! the texels around the point ([`Filter`]), at the level a filter width picks
//! ([`Ptex::level_for`]), across face edges through the file's adjacency.
//!
//! Face coordinates: quads (u, v) ∈ [0, 1]²; triangles barycentric (u, v), u, v ≥ 0,
//! u + v ≤ 1 (the module documentation of [`super`]). Widths are in the same units (a
//! face is 1 across).
//!
//! Quads (bilinear): between the texel centres around the point, weighted by the point's
//! fractions between them. In the half texel along a face edge the value goes linearly
//! from the face's texels (on the line of texel centres) to the edge's value (on the
//! edge): the mean of the two faces' rows of texels along it, each interpolated at its own
//! resolution ([`super::edges`]; with equal resolutions this is bilinear interpolation
//! with the texels across the edge). In the half-texel square at a face corner it is a
//! Coons patch: the two edges' values along the square's sides on the edges, plus the
//! corner texel, less the value at the vertex (the mean of the corner texels of every
//! face around it) weighted bilinearly. Every face computes the same values on a shared
//! edge and at a shared vertex, so the result is continuous across faces of any
//! resolutions, constant faces (one texel, blended with textured neighbours within it) and
//! mesh vertices of any valence. With no face across, an edge's value is the face's own
//! row (clamp to the edge).
//!
//! Triangles: Ptex has no bilinear filter of triangle texels (its triangle filter is an
//! elliptical Gaussian); mira interpolates linearly between texel centres on the dual
//! mesh of the small triangles. Each grid vertex of the face's lattice takes the mean of
//! the (up to six) texels around it; the small triangle holding the point is split into
//! six pieces, by its centroid, its corners and its edges' midpoints; the piece at corner
//! V next to the edge shared with small triangle N is interpolated in the triangle (V,
//! centroid of the point's texel, centroid of N) from (the mean at V, the texel, N's
//! texel). The result is continuous, exact at each texel's centroid, and reproduces
//! linear data away from unmatched borders. Along a face edge the pieces against it go
//! from the texel at their centroid straight toward the edge's value (the mean of both
//! faces' values along it, each at its own resolution, [`super::edges`]), and a lattice
//! vertex on a face edge takes the edge's value there; with equal resolutions this is the
//! interpolation with the texels across the edge. Texels past a face edge come from the
//! face across it, or are left out (a missing N counts as the texel itself).
//!
//! Across an edge: both faces see the shared edge counter-clockwise, so a point at
//! distance s past edge e of one face, at fraction t along it, lies at depth s inside the
//! adjacent face, at fraction 1 − t along its edge (two triangles unfold into a
//! parallelogram: t and s are barycentric weights, see `outside_edge`). Triangle values
//! agree on both sides of an edge whatever the faces' resolutions (a constant triangle
//! with neighbours is blended with them near its edges); at a face corner the lattice
//! vertex takes the vertex's value, shared by every face around it.
//!
//! A face of one texel with no neighbours has its value everywhere.

use super::{quad_texel, triangle_texel, FaceTexels, MeshType, Ptex};

/// How a lookup combines texels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    /// The texel the point lies in (Ptex's point filter).
    Nearest,
    /// Interpolation between the texels around the point (bilinear on quads, linear on
    /// the dual mesh of triangles; see the module documentation).
    Bilinear,
}

/// The six centroids of the small triangles around a grid vertex, in texels from it.
const AROUND_VERTEX: [(f32, f32); 6] = [
    (1.0 / 3.0, 1.0 / 3.0),
    (-2.0 / 3.0, 1.0 / 3.0),
    (1.0 / 3.0, -2.0 / 3.0),
    (-1.0 / 3.0, -1.0 / 3.0),
    (2.0 / 3.0, -1.0 / 3.0),
    (-1.0 / 3.0, 2.0 / 3.0),
];

/// Weighted texels (their first value's index in the texels) summed into a value.
pub(super) struct Taps<'a> {
    ptex: &'a Ptex,
    first: usize,
    out: &'a mut [f32],
    /// The last vertex whose value was asked for in this lookup (the corner rows and
    /// patches of one lookup ask for the same vertex up to five times).
    pub(super) vertex: Option<super::edges::Vertex>,
}

impl Taps<'_> {
    /// Adds `weight` × the texel whose first value is at `start`.
    pub(super) fn add(&mut self, weight: f32, start: usize) {
        let channels = self.ptex.channels;
        for (c, o) in self.out.iter_mut().enumerate() {
            let channel = self.first + c;
            if channel < channels {
                *o += weight * self.ptex.texels.get(start + channel).copied().unwrap_or(0.0);
            }
        }
    }
}

impl Ptex {
    /// Face `face`'s texels at level `level` (0 the highest resolution, k its k-th
    /// reduction); `None` past its levels or faces.
    pub fn level(&self, face: usize, level: usize) -> Option<&FaceTexels> {
        match level {
            0 => self.faces.get(face),
            k => self.reductions.get(face)?.get(k - 1),
        }
    }

    /// The level of face `face` a filter of width `width` (face units; `None`, 0 or not
    /// finite: level 0) reads: the coarsest the file has whose texels are no wider than
    /// the width (level 0's texels ≥ the width: level 0; the face's average when the width
    /// spans the face).
    pub fn level_for(&self, face: usize, width: Option<f32>) -> usize {
        let (Some(width), Some(top)) = (width.filter(|w| w.is_finite() && *w > 0.0), self.faces.get(face)) else {
            return 0;
        };
        let res = top.ulog2.max(top.vlog2);
        // How many halvings of level 0's texels the width allows.
        let wanted = (width.log2() + f32::from(res) + 1e-3).floor();
        if wanted < 1.0 {
            return 0;
        }
        let mut best = 0;
        for (k, level) in self.reductions.get(face).map_or(&[][..], Vec::as_slice).iter().enumerate() {
            if f32::from(res - level.ulog2.max(level.vlog2)) <= wanted {
                best = k + 1;
            }
        }
        best
    }

    /// The levels a [`Filter::Bilinear`] lookup of width `width` at face `face` blends:
    /// the finer (as [`Ptex::level_for`] picks it), and, where the file has a coarser one
    /// and the width lies within the octave below the coarser's texel width, the coarser's
    /// weight t ∈ (0, 1) — the width's place in that octave on a log₂ scale (between two
    /// consecutive levels: between their texel widths) — and the widths (face units, each
    /// exactly its level's texel) that pick each level.
    pub fn blend_for(&self, face: usize, width: Option<f32>) -> (usize, Option<(f32, f32, f32)>) {
        let fine = self.level_for(face, width);
        let blend = || {
            let width = width.filter(|w| w.is_finite() && *w > 0.0)?;
            let top = self.faces.get(face)?;
            let res = i32::from(top.ulog2.max(top.vlog2));
            let reductions = self.reductions.get(face)?;
            let coarse = reductions.get(fine)?;
            let halvings = |l: &FaceTexels| res - i32::from(l.ulog2.max(l.vlog2));
            let h0 = if fine == 0 { 0 } else { halvings(reductions.get(fine - 1)?) };
            let h1 = halvings(coarse);
            if h1 <= h0 {
                return None;
            }
            // Over the octave below the coarser level's texel (where the file has no
            // levels between the two, the finer is read alone until then).
            let t = width.log2() + res as f32 - (h1 - 1) as f32;
            let texel = |h: i32| (2.0f32).powi(h - res);
            (t > 0.0 && t < 1.0).then(|| (t, texel(h0), texel(h1)))
        };
        (fine, blend())
    }

    /// The filtered value at face `face`, face coordinates (`u`, `v`), for a filter of
    /// width `width` (face units): channels `first`, `first + 1`, … into `out` (0 past the
    /// last channel). [`Filter::Bilinear`] blends the two levels around the width
    /// ([`Ptex::blend_for`]: no step where the width crosses a level), [`Filter::Nearest`]
    /// reads the one [`Ptex::level_for`] picks. False for a face the file has not (`out`
    /// left at 0).
    #[allow(clippy::too_many_arguments)]
    pub fn sample(
        &self,
        face: u32,
        u: f32,
        v: f32,
        width: Option<f32>,
        filter: Filter,
        first: usize,
        out: &mut [f32],
    ) -> bool {
        if filter == Filter::Nearest || out.len() > 4 || width.is_none() {
            let level = self.level_for(face as usize, width);
            return self.sample_level(face, u, v, width, level, filter, first, out);
        }
        match self.blend_for(face as usize, width) {
            (level, None) => self.sample_level(face, u, v, width, level, filter, first, out),
            (level, Some((t, fine, coarse))) => {
                let mut lanes = [0.0f32; 4];
                let lanes = &mut lanes[..out.len()];
                if !self.sample_level(face, u, v, Some(coarse), level + 1, filter, first, lanes) {
                    out.fill(0.0);
                    return false;
                }
                self.sample_level(face, u, v, Some(fine), level, filter, first, out);
                for (o, c) in out.iter_mut().zip(lanes.iter()) {
                    *o += t * (c - *o);
                }
                true
            }
        }
    }

    /// [`Ptex::sample`] at level `level` of the face (what [`Ptex::level_for`] picks for
    /// `width`, which picks the neighbours' levels).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn sample_level(
        &self,
        face: u32,
        u: f32,
        v: f32,
        width: Option<f32>,
        level: usize,
        filter: Filter,
        first: usize,
        out: &mut [f32],
    ) -> bool {
        out.fill(0.0);
        let face = face as usize;
        let Some(texels) = self.level(face, level).copied() else { return false };
        let (u, v) = (finite(u), finite(v));
        let mut taps = Taps { ptex: self, first, out, vertex: None };
        let one_texel = texels.ulog2 + texels.vlog2 == 0;
        let alone = self.adjacency.get(face).is_none_or(|a| a.faces.iter().all(|&f| f < 0));
        // A face of one texel is blended with its neighbours (continuity with them).
        if filter == Filter::Nearest || (one_texel && alone) {
            taps.add(1.0, self.nearest(texels, u, v));
            return true;
        }
        match self.mesh {
            MeshType::Quad => self.bilinear_quad(face, texels, u, v, width, &mut taps),
            MeshType::Triangle => self.linear_triangle(face, texels, u, v, width, &mut taps),
        }
        true
    }

    /// Index of the first value of the texel of `texels` nearest to (`u`, `v`), clamped
    /// to the face.
    pub(super) fn nearest(&self, texels: FaceTexels, u: f32, v: f32) -> usize {
        let index = match self.mesh {
            MeshType::Quad => quad_texel(texels.ulog2, texels.vlog2, u, v),
            MeshType::Triangle => triangle_texel(texels.ulog2, u, v),
        };
        texels.start + index * self.channels
    }

    /// The texel nearest to (`u`, `v`) of face `face`, or past its edge of the face across
    /// it, each at the level `width` picks; `None` past an edge with no face across.
    fn texel_at(&self, face: usize, u: f32, v: f32, width: Option<f32>) -> Option<usize> {
        let Some((edge, t, s)) = outside_edge(self.mesh, u, v) else {
            return Some(self.nearest(*self.level(face, self.level_for(face, width))?, u, v));
        };
        let (other, other_edge) = self.adjacency.get(face)?.across(edge)?;
        let (u, v) = from_edge(self.mesh, other_edge, 1.0 - t, -s);
        let (u, v) = clamp_into(self.mesh, u, v);
        Some(self.nearest(*self.level(other, self.level_for(other, width))?, u, v))
    }

    /// Bilinear interpolation of the texel centres around (`u`, `v`); in the half texel
    /// along an edge, between the face's texels and the edge's value; in the half texel
    /// square at a corner, a Coons patch of the two edges' values, the corner texel and
    /// the vertex's value (the module documentation).
    fn bilinear_quad(&self, face: usize, texels: FaceTexels, u: f32, v: f32, width: Option<f32>, taps: &mut Taps) {
        let (w, h) = (1usize << texels.ulog2, 1usize << texels.vlog2);
        let (u, v) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
        let x = u * w as f32 - 0.5;
        let y = v * h as f32 - 0.5;
        // The edge a point within half a texel of lies along, and its depth fraction (0 on
        // the edge, 1 on the line of texel centres), with its fraction along the edge.
        let near = |p: f32, n: usize, low: usize, high: usize, t_low: f32, t_high: f32| {
            let last = (n - 1) as f32;
            if p < 0.0 {
                Some((low, 1.0 + 2.0 * p, t_low))
            } else if p > last {
                Some((high, 1.0 - 2.0 * (p - last), t_high))
            } else {
                None
            }
        };
        let along_u = near(x, w, 3, 1, 1.0 - v, v);
        let along_v = near(y, h, 0, 2, u, 1.0 - u);
        let texel = |i: usize, j: usize| texels.start + (j * w + i) * self.channels;
        // Interpolation between texel centres along one axis: the lower index, its fraction.
        let split = |p: f32, n: usize| {
            let k = (p.max(0.0).floor() as usize).min(n.saturating_sub(2));
            (k, (p - k as f32).clamp(0.0, 1.0))
        };
        match (along_u, along_v) {
            (None, None) => {
                let ((i, fx), (j, fy)) = (split(x, w), split(y, h));
                for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let weight = if di == 0 { 1.0 - fx } else { fx } * if dj == 0 { 1.0 - fy } else { fy };
                    if weight != 0.0 {
                        taps.add(weight, texel(i + di, j + dj));
                    }
                }
            }
            (Some((edge, depth, t)), None) => {
                let i = if edge == 3 { 0 } else { w - 1 };
                let (j, fy) = split(y, h);
                taps.add(depth * (1.0 - fy), texel(i, j));
                if fy > 0.0 {
                    taps.add(depth * fy, texel(i, j + 1));
                }
                self.add_edge(face, texels, (edge, t), width, 1.0 - depth, taps);
            }
            (None, Some((edge, depth, t))) => {
                let j = if edge == 0 { 0 } else { h - 1 };
                let (i, fx) = split(x, w);
                taps.add(depth * (1.0 - fx), texel(i, j));
                if fx > 0.0 {
                    taps.add(depth * fx, texel(i + 1, j));
                }
                self.add_edge(face, texels, (edge, t), width, 1.0 - depth, taps);
            }
            (Some((eu, au, tu)), Some((ev, av, tv))) => {
                // Coons patch over the corner square: both edges' values, plus the corner
                // texel, less the vertex's value (bilinear in the square's corners).
                let corner = match (eu, ev) {
                    (3, 0) => 0,
                    (1, 0) => 1,
                    (1, _) => 2,
                    _ => 3,
                };
                let (i, j) = (if eu == 3 { 0 } else { w - 1 }, if ev == 0 { 0 } else { h - 1 });
                self.add_edge(face, texels, (ev, tv), width, 1.0 - av, taps);
                self.add_edge(face, texels, (eu, tu), width, 1.0 - au, taps);
                if au * av != 0.0 {
                    taps.add(au * av, texel(i, j));
                }
                self.add_vertex(face, corner, width, -(1.0 - au) * (1.0 - av), taps);
            }
        }
    }

    /// Linear interpolation on the dual mesh of a triangle face's small triangles (the
    /// module documentation).
    fn linear_triangle(&self, face: usize, texels: FaceTexels, u: f32, v: f32, width: Option<f32>, taps: &mut Taps) {
        let n = (1u32 << texels.ulog2) as f32;
        let (u, v) = clamp_into(MeshType::Triangle, u, v);
        let (x, y) = (u * n, v * n);
        let (i, j) = ((x.floor()).min(n - 1.0), (y.floor()).min(n - 1.0));
        let (mut fx, mut fy) = (x - i, y - j);
        // The small triangle's corners (lattice units) and the point's weights on them.
        let corners: [((f32, f32), f32); 3] = if fx + fy <= 1.0 || i + j + 2.0 > n {
            if fx + fy > 1.0 {
                // Past the long edge by rounding: onto it.
                let sum = fx + fy;
                (fx, fy) = (fx / sum, fy / sum);
            }
            [((i, j), 1.0 - fx - fy), ((i + 1.0, j), fx), ((i, j + 1.0), fy)]
        } else {
            [((i + 1.0, j + 1.0), fx + fy - 1.0), ((i, j + 1.0), 1.0 - fx), ((i + 1.0, j), 1.0 - fy)]
        };
        let centroid = (
            (corners[0].0 .0 + corners[1].0 .0 + corners[2].0 .0) / 3.0,
            (corners[0].0 .1 + corners[1].0 .1 + corners[2].0 .1) / 3.0,
        );
        // The corner V nearest the point, and the other corner A on the side of the point.
        let k = (0..3).fold(0, |best, k| if corners[k].1 > corners[best].1 { k } else { best });
        let (b, c) = ((k + 1) % 3, (k + 2) % 3);
        let a = if corners[b].1 >= corners[c].1 { b } else { c };
        let vertex = corners[k].0;
        let across = (vertex.0 + corners[a].0 .0 - centroid.0, vertex.1 + corners[a].0 .1 - centroid.1);
        // The point's weights in the triangle (V, centroid, the centroid across V–A).
        let Some([wv, wt, wn]) = barycentric((x, y), vertex, centroid, across) else {
            taps.add(1.0, self.nearest(texels, u, v));
            return;
        };
        let own = self.nearest(texels, centroid.0 / n, centroid.1 / n);
        if let Some(edge) = face_edge_of(vertex, corners[a].0, n) {
            // The piece (V, M, C) against the face edge (M the middle of V–A): from the
            // texel at C straight toward the edge's value at the point of V–M in line.
            let (wc, wm) = (wt - wn, 2.0 * wn);
            taps.add(wc, own);
            if wv + wm > 0.0 {
                let mid = ((vertex.0 + corners[a].0 .0) / 2.0, (vertex.1 + corners[a].0 .1) / 2.0);
                let q = ((wv * vertex.0 + wm * mid.0) / (wv + wm), (wv * vertex.1 + wm * mid.1) / (wv + wm));
                self.add_edge(face, texels, (edge, edge_fraction(edge, q, n)), width, 1.0 - wc, taps);
            }
            return;
        }
        taps.add(wt, own);
        let neighbour = self.texel_at(face, across.0 / n, across.1 / n, width).unwrap_or(own);
        taps.add(wn, neighbour);
        // A face corner: the vertex's value, shared by every face around it.
        let corner = match (vertex.0 == 0.0, vertex.1 == 0.0) {
            (true, true) => Some(0),
            (false, true) if vertex.0 == n => Some(1),
            (true, false) if vertex.1 == n => Some(2),
            _ => None,
        };
        if let Some(corner) = corner {
            self.add_vertex(face, corner, width, wv, taps);
            return;
        }
        // A lattice vertex on a face edge: the edge's value there.
        let on_edge = [(0, vertex.1 == 0.0), (1, vertex.0 + vertex.1 == n), (2, vertex.0 == 0.0)];
        if let Some(&(edge, _)) = on_edge.iter().find(|(_, on)| *on) {
            self.add_edge(face, texels, (edge, edge_fraction(edge, vertex, n)), width, wv, taps);
            return;
        }
        // The mean of the texels around V.
        let mut around = [0usize; 6];
        let mut count = 0;
        for (dx, dy) in AROUND_VERTEX {
            if let Some(start) = self.texel_at(face, (vertex.0 + dx) / n, (vertex.1 + dy) / n, width) {
                around[count] = start;
                count += 1;
            }
        }
        for start in &around[..count] {
            taps.add(wv / count as f32, *start);
        }
    }
}

/// The triangle face edge (0 v = 0, 1 u + v = 1, 2 u = 0) both lattice points `a` and `b`
/// (lattice units of a face n texels a side) lie on, if any.
fn face_edge_of(a: (f32, f32), b: (f32, f32), n: f32) -> Option<usize> {
    if a.1 == 0.0 && b.1 == 0.0 {
        Some(0)
    } else if a.0 + a.1 == n && b.0 + b.1 == n {
        Some(1)
    } else if a.0 == 0.0 && b.0 == 0.0 {
        Some(2)
    } else {
        None
    }
}

/// The fraction along triangle face edge `edge` (counter-clockwise) of the point `q` on it
/// (lattice units of a face n texels a side).
fn edge_fraction(edge: usize, q: (f32, f32), n: f32) -> f32 {
    match edge {
        0 => q.0 / n,
        1 => q.1 / n,
        _ => 1.0 - q.1 / n,
    }
}

/// `x`, or 0 when not finite.
fn finite(x: f32) -> f32 {
    if x.is_finite() {
        x
    } else {
        0.0
    }
}

/// (`u`, `v`) moved onto the face: quads clamped to [0, 1]², triangles to u, v ≥ 0 and
/// scaled onto u + v ≤ 1.
fn clamp_into(mesh: MeshType, u: f32, v: f32) -> (f32, f32) {
    let (u, v) = (finite(u).max(0.0), finite(v).max(0.0));
    match mesh {
        MeshType::Quad => (u.min(1.0), v.min(1.0)),
        MeshType::Triangle if u + v > 1.0 => (u / (u + v), v / (u + v)),
        MeshType::Triangle => (u, v),
    }
}

/// The edge (quads: 0 v = 0, 1 u = 1, 2 v = 1, 3 u = 0; triangles: 0 v = 0, 1 u + v = 1,
/// 2 u = 0) a point past the face lies furthest past, with the point's fraction t along
/// the edge (counter-clockwise) and its depth s into the face (negative: past it); `None`
/// inside the face. On triangles t is the point's barycentric weight of the edge's end
/// vertex and s that of the vertex opposite the edge, so that t' = 1 − t, s' = −s is the
/// affine map onto the adjacent face (the two faces unfolded into a parallelogram).
pub(super) fn outside_edge(mesh: MeshType, u: f32, v: f32) -> Option<(usize, f32, f32)> {
    let past: &[f32] = match mesh {
        MeshType::Quad => &[-v, u - 1.0, v - 1.0, -u],
        MeshType::Triangle => &[-v, u + v - 1.0, -u],
    };
    let edge = (0..past.len()).fold(0, |best, k| if past[k] > past[best] { k } else { best });
    if past[edge] <= 0.0 {
        return None;
    }
    let (t, s) = edge_frame(mesh, edge, u, v);
    Some((edge, t, s))
}

/// The fraction t along edge `edge` (counter-clockwise) and the depth s into the face of
/// the point (`u`, `v`) (face coordinates; any point, inside the face or not): the frame
/// [`outside_edge`] gives, [`from_edge`]'s inverse.
pub(super) fn edge_frame(mesh: MeshType, edge: usize, u: f32, v: f32) -> (f32, f32) {
    match (mesh, edge) {
        (_, 0) => (u, v),
        (MeshType::Quad, 1) => (v, 1.0 - u),
        (MeshType::Quad, 2) => (1.0 - u, 1.0 - v),
        (MeshType::Quad, _) => (1.0 - v, u),
        (MeshType::Triangle, 1) => (v, 1.0 - u - v),
        (MeshType::Triangle, _) => (1.0 - u - v, u),
    }
}

/// The face coordinates of the point at fraction `t` along edge `edge` (counter-clockwise)
/// and depth `s` into the face ([`outside_edge`]'s inverse).
pub(super) fn from_edge(mesh: MeshType, edge: usize, t: f32, s: f32) -> (f32, f32) {
    match (mesh, edge) {
        (_, 0) => (t, s),
        (MeshType::Quad, 1) => (1.0 - s, t),
        (MeshType::Quad, 2) => (1.0 - t, 1.0 - s),
        (MeshType::Quad, _) => (s, 1.0 - t),
        (MeshType::Triangle, 1) => (1.0 - s - t, t),
        (MeshType::Triangle, _) => (s, 1.0 - s - t),
    }
}

/// The barycentric weights of `p` in the triangle (`a`, `b`, `c`); `None` if degenerate.
fn barycentric(p: (f32, f32), a: (f32, f32), b: (f32, f32), c: (f32, f32)) -> Option<[f32; 3]> {
    let (e1, e2, d) = ((b.0 - a.0, b.1 - a.1), (c.0 - a.0, c.1 - a.1), (p.0 - a.0, p.1 - a.1));
    let det = e1.0 * e2.1 - e1.1 * e2.0;
    if det.abs() < 1e-12 {
        return None;
    }
    let wb = (d.0 * e2.1 - d.1 * e2.0) / det;
    let wc = (e1.0 * d.1 - e1.1 * d.0) / det;
    Some([1.0 - wb - wc, wb, wc])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each edge's mapping and its inverse agree, and the point across an edge maps back
    /// onto the edge's other side (exact up to 1e-6).
    #[test]
    fn edge_frames_invert() {
        for mesh in [MeshType::Quad, MeshType::Triangle] {
            let edges = if mesh == MeshType::Quad { 4 } else { 3 };
            for edge in 0..edges {
                for (t, s) in [(0.25, -0.1), (0.7, -0.05), (0.5, -0.2)] {
                    let (u, v) = from_edge(mesh, edge, t, s);
                    let (e, t2, s2) = outside_edge(mesh, u, v).expect("past the face");
                    assert_eq!(e, edge, "{mesh:?}");
                    assert!((t2 - t).abs() < 1e-6 && (s2 - s).abs() < 1e-6, "{mesh:?} edge {edge}: {t2} {s2}");
                }
            }
            assert!(outside_edge(mesh, 0.2, 0.3).is_none());
        }
    }

    /// Barycentric weights reproduce the point (1e-6).
    #[test]
    fn barycentric_weights_reproduce_the_point() {
        let (a, b, c) = ((0.0, 0.0), (2.0, 0.5), (0.5, 1.5));
        let [x, y, z] = barycentric((0.7, 0.6), a, b, c).unwrap();
        assert!((x + y + z - 1.0).abs() < 1e-6);
        assert!((y * 2.0 + z * 0.5 - 0.7).abs() < 1e-6 && (y * 0.5 + z * 1.5 - 0.6).abs() < 1e-6);
        assert!(barycentric((0.1, 0.1), a, a, c).is_none());
    }
}
