//! Lookups over an anisotropic footprint ([`Ptex::sample_ellipse`], and
//! [`Ptex::sample_rect`] for one along the face's axes): a footprint seen at a grazing
//! angle is long along one direction and short across it, and Ptex's own filters take the
//! two widths apart.
//!
//! The footprint is an ellipse in face coordinates (`footprint::FaceEllipse`: its major
//! axis' direction, its widths along and across it), read as the rectangle of those widths
//! turned along the major axis: n lookups of the minor width (blended levels,
//! [`Ptex::blend_for`]), spaced evenly over the major width along its direction, weighted
//! by Ptex's Gaussian of their distance from the centre ([`major_axis_weights`]). A thin
//! footprint diagonal to the face's axes so averages only texels along its major
//! axis (reading its bounding rectangle in face space would blur across it). Several
//! probes rather than an elliptical Gaussian over the texels of one level: each probe is
//! the filter's own interpolation, continuous across face edges of any resolutions
//! (`filter`, `edges`), so the ellipse needs no texel gather of its own across edges; its
//! cost is one lookup per probe, n at most [`MAX_PROBES`]. A round footprint (major =
//! minor) is one lookup at its width, exactly the isotropic lookup.
//!
//! The number of probes: n = ⌈major / max(minor, t)⌉ (at most [`MAX_PROBES`]), t the
//! distance along the major axis across one texel (the nearer of the next u and v texel
//! borders) of the level the minor width picks, the smallest over every face the major
//! axis crosses: walked from the centre to each end, face by face, the axis carried
//! across each edge it leaves by with its direction (the edge's orientation: the
//! unfolding of the two faces, `filter`'s `outside_edge`), t taken in each face at its
//! own resolution, so a footprint reaching or crossing a finer face is probed at that
//! face's texels. A footprint within a texel along its axis is one interpolated lookup of
//! its major width, as the isotropic one. Each probe reads a square as wide as the
//! spacing's larger extent along u or v in the face it lands in (the axis carried there;
//! the minor width where that is larger; past [`MAX_PROBES`] the squares widen with the
//! spacing, blurring across the axis by that much).
//!
//! A probe past a face edge reads the face across it ([`Ptex::across_edges`]: the point
//! carried over the edge as the bilinear filter carries texels, and on over further edges
//! up to [`MAX_CROSSINGS`] times) at the probe's width in face units, which picks that
//! face's level at its own resolution (Ptex's faces are all one unit across, sub-faces half a unit, below); where no
//! face is across, the probe clamps to the face's edge.
//!
//! Ptex's sub-faces (quad-mesh files: the n sub-quads of a face of n ≠ 4 vertices, each
//! half a quad face's size in parameter space, flagged 8 in the file): a quad face's edge
//! against a non-quad face is shared by two sub-faces, each along half of it. The quad
//! face's adjacency names the primary one, along the first half (fraction t < ½ along the
//! edge, counter-clockwise), which maps to 1 − 2 t along the primary's own edge at twice
//! the depth; the second half lands past the primary's previous edge and is carried on, as
//! any point, into the secondary sub-face across it. Back from a sub-face, fraction t
//! along its edge is (1 − t) / 2 along the quad face's (the primary, whose edge the quad
//! face's adjacency names) or 1 − t / 2 (the secondary), at half the depth. A width in
//! face units doubles into a sub-face and halves out of one (Ptex's filters build a
//! sub-face's kernel on its main face at half its coordinates and widths). Only these
//! probes are carried so; the bilinear lookup's blending across an edge (`edges`) still
//! pairs a sub-face's edge with the whole of a quad face's.

use std::sync::OnceLock;

use super::filter::{edge_frame, from_edge, outside_edge};
use super::footprint::FaceEllipse;
use super::{Filter, MeshType, Ptex};

/// The most face edges a probe is carried across.
pub const MAX_CROSSINGS: usize = 4;

/// The most lookups a footprint is averaged from (a longer footprint is read with squares
/// wider than its minor width: blurred across its axis by that much).
pub const MAX_PROBES: usize = 16;

/// The weights (summing to 1) of `probes` probes (1 to [`MAX_PROBES`]; entries past
/// `probes` 0) spaced evenly over an elliptical footprint's major width: Ptex's Gaussian
/// kernel exp(−2 x²), x the probe's distance from the footprint's centre in major widths
/// (probe k at x = (k + ½) / n − ½), normalised. Ptex's convention makes the filter
/// width w the Gaussian's 2σ (σ = w / 2) and lets the kernel run to ±2 w; mira keeps the
/// probes within the footprint's own major width (|x| ≤ ½, the ends weighing e^(−½) ≈
/// 0.61 of the centre) so the blur along the major axis stays that of the footprint,
/// matching the minor width's lookup across it. Symmetric about the centre.
pub fn major_axis_weights(probes: usize) -> [f32; MAX_PROBES] {
    static TABLE: OnceLock<[[f32; MAX_PROBES]; MAX_PROBES]> = OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|k| gaussian_weights(k + 1)))[probes.clamp(1, MAX_PROBES) - 1]
}

/// [`major_axis_weights`] computed.
fn gaussian_weights(probes: usize) -> [f32; MAX_PROBES] {
    let probes = probes.clamp(1, MAX_PROBES);
    let mut weights = [0.0f32; MAX_PROBES];
    let mut sum = 0.0f32;
    for (k, w) in weights[..probes].iter_mut().enumerate() {
        let x = (k as f32 + 0.5) / probes as f32 - 0.5;
        *w = (-2.0 * x * x).exp();
        sum += *w;
    }
    for w in &mut weights[..probes] {
        *w /= sum;
    }
    weights
}

/// How far past a face edge (face units along the axis) a walk along the major axis steps
/// to carry the axis into the face across it.
const EDGE_NUDGE: f32 = 1e-5;

/// The distance along `dir` (face coordinates per unit; any length) from (`u`, `v`) to the
/// edge of the face (a quad's unit square, a triangle's u, v ≥ 0, u + v ≤ 1) the ray
/// leaves by: 0 for a point already past an edge it moves away from, infinite for no
/// motion.
fn exit_distance(mesh: MeshType, (u, v): (f32, f32), (du, dv): (f32, f32)) -> f32 {
    let toward = |gap: f32, rate: f32| if rate > 0.0 { (gap / rate).max(0.0) } else { f32::INFINITY };
    match mesh {
        MeshType::Quad => toward(1.0 - u, du).min(toward(u, -du)).min(toward(1.0 - v, dv)).min(toward(v, -dv)),
        MeshType::Triangle => toward(u, -du).min(toward(v, -dv)).min(toward(1.0 - u - v, du + dv)),
    }
}

impl Ptex {
    /// The filtered value at face `face`, face coordinates (`u`, `v`), over a footprint
    /// `widths` wide along u and v (face units): [`Ptex::sample_ellipse`] with its major
    /// axis along the longer (u where they are equal). A width that is 0 or not finite
    /// counts as the other; both: level 0. False for a face the file has not.
    pub fn sample_rect(&self, face: u32, u: f32, v: f32, widths: (f32, f32), first: usize, out: &mut [f32]) -> bool {
        let ok = |w: f32| w.is_finite() && w > 0.0;
        let (wu, wv) = match widths {
            (a, b) if ok(a) && ok(b) => (a, b),
            (a, _) if ok(a) => (a, a),
            (_, b) if ok(b) => (b, b),
            _ => return self.sample(face, u, v, None, Filter::Bilinear, first, out),
        };
        self.sample_ellipse(face, u, v, FaceEllipse::along_axes((wu, wv)), first, out)
    }

    /// The filtered value at face `face`, face coordinates (`u`, `v`), over the footprint
    /// `ellipse` (face units; the module documentation): channels `first`, `first + 1`, …
    /// into `out` (at most 4 lanes; 0 past the last channel). A minor width that is 0 or
    /// not finite counts as the major; a major that is not positive and finite: level 0.
    /// False for a face the file has not.
    pub fn sample_ellipse(
        &self,
        face: u32,
        u: f32,
        v: f32,
        ellipse: FaceEllipse,
        first: usize,
        out: &mut [f32],
    ) -> bool {
        let FaceEllipse { axis, major, minor } = ellipse;
        if !(major.is_finite() && major > 0.0) {
            return self.sample(face, u, v, None, Filter::Bilinear, first, out);
        }
        let minor = if minor.is_finite() && minor > 0.0 { minor.min(major) } else { major };
        if minor == major {
            // Round: one lookup (n = 1 whatever the texels).
            return self.sample(face, u, v, Some(major), Filter::Bilinear, first, out);
        }
        let norm = (axis.0 * axis.0 + axis.1 * axis.1).sqrt();
        let (du, dv) = if norm.is_finite() && norm > 0.0 {
            if norm == 1.0 {
                axis
            } else {
                (axis.0 / norm, axis.1 / norm)
            }
        } else {
            (1.0, 0.0)
        };
        // One texel along the axis in every face the axis crosses (each at its own
        // resolution, the axis carried across edges).
        let texel = self.finest_texel_along(face, (u, v), (du, dv), major, minor);
        let probes = ((major / minor.max(texel)).ceil() as usize).clamp(1, MAX_PROBES);
        if probes == 1 || out.len() > 4 {
            return self.sample(face, u, v, Some(major), Filter::Bilinear, first, out);
        }
        // Squares as wide as the spacing's larger extent along u or v in the probe's face
        // (the minor width unless that is wider).
        let step = major / probes as f32;
        let weights = major_axis_weights(probes);
        out.fill(0.0);
        let mut lanes = [0.0f32; 4];
        let lanes = &mut lanes[..out.len()];
        for (k, weight) in weights[..probes].iter().enumerate() {
            let offset = (k as f32 + 0.5) * step - 0.5 * major;
            let (pface, pu, pv, pdir, scale) = self.carry_across(face, u + offset * du, v + offset * dv, (du, dv));
            let width = (minor * scale).max(step * pdir.0.abs().max(pdir.1.abs()));
            if !self.sample(pface, pu, pv, Some(width), Filter::Bilinear, first, lanes) {
                out.fill(0.0);
                return false;
            }
            for (o, l) in out.iter_mut().zip(lanes.iter()) {
                *o += *l * weight;
            }
        }
        true
    }

    /// The smallest distance (face units of face `face`, along its unit direction `dir`)
    /// across one texel ([`Ptex::texel_along`], at the level the minor width `minor`
    /// picks) in any face the major axis crosses: walked from the centre (`u`, `v`) to
    /// each end (`major` / 2 away), face by face, the axis carried across each edge it
    /// leaves by (up to [`MAX_CROSSINGS`] edges each way; ends where no face is across).
    fn finest_texel_along(&self, face: u32, (u, v): (f32, f32), (du, dv): (f32, f32), major: f32, minor: f32) -> f32 {
        let mut texel = self.texel_along(face, (du, dv), minor);
        for sign in [-1.0f32, 1.0] {
            let (mut f, mut pu, mut pv, mut dir) = (face, u, v, (sign * du, sign * dv));
            let (mut left, mut scale) = (0.5 * major, 1.0f32);
            for _ in 0..MAX_CROSSINGS {
                let exit = exit_distance(self.mesh, (pu, pv), dir);
                if exit.is_nan() || exit >= left {
                    break;
                }
                // Just past the edge the axis leaves by.
                let past = exit + EDGE_NUDGE;
                let (next, nu, nv, ndir, step) = self.carry_across(f, pu + past * dir.0, pv + past * dir.1, dir);
                if next == f {
                    break;
                }
                scale *= step;
                texel = texel.min(self.texel_along(next, ndir, minor * scale));
                (f, pu, pv, dir) = (next, nu, nv, ndir);
                left -= past;
            }
        }
        texel
    }

    /// The distance (face units) along direction `dir` (a unit vector of face coordinates)
    /// across one texel of the level of face `face` that width `width` picks: the texel's
    /// width along u over |du| or its height along v over |dv|, the smaller (triangles: the
    /// face's side over n along both); 0 for a face the file has not.
    fn texel_along(&self, face: u32, (du, dv): (f32, f32), width: f32) -> f32 {
        let Some(t) = self.level(face as usize, self.level_for(face as usize, Some(width))) else { return 0.0 };
        let vlog2 = if self.mesh == MeshType::Triangle { t.ulog2 } else { t.vlog2 };
        let across = |log2: u8, d: f32| if d == 0.0 { f32::INFINITY } else { (0.5f32).powi(i32::from(log2)) / d.abs() };
        across(t.ulog2, du).min(across(vlog2, dv))
    }

    /// The face and face coordinates of the point (`u`, `v`) of face `face`, carried across
    /// the edges it lies past into the faces there (at most [`MAX_CROSSINGS`] edges); the
    /// point as given (then clamped by the lookup) past an edge with no face across.
    pub fn across_edges(&self, face: u32, u: f32, v: f32) -> (u32, f32, f32) {
        let (face, u, v, _, _) = self.carry_across(face, u, v, (0.0, 0.0));
        (face, u, v)
    }

    /// [`Ptex::across_edges`], carrying the direction `dir` (face coordinates) along: each
    /// edge's unfolding is affine, its linear part turns `dir` into the face across
    /// (unnormalised: triangles' unfoldings shear it); and the scale of the landing face's
    /// units to the starting face's (1, but 2 into a sub-face from a quad face and ½ out of
    /// one: the module documentation).
    fn carry_across(&self, face: u32, u: f32, v: f32, dir: (f32, f32)) -> (u32, f32, f32, (f32, f32), f32) {
        let (mut face, mut u, mut v, mut dir, mut scale) = (face, u, v, dir, 1.0f32);
        for _ in 0..MAX_CROSSINGS {
            let Some((edge, t, s)) = outside_edge(self.mesh, u, v) else { break };
            let Some((other, other_edge)) = self.adjacency.get(face as usize).and_then(|a| a.across(edge)) else {
                break;
            };
            let Ok(other) = u32::try_from(other) else { break };
            if other as usize >= self.faces.len() {
                break;
            }
            // The point's fraction along the other face's edge and depth into it.
            let (from, to) = (self.is_subface(face), self.is_subface(other));
            let (along, deeper): (fn(f32) -> f32, f32) = match (from, to) {
                (false, true) => (|t| 1.0 - 2.0 * t, 2.0),
                (true, false) if self.primary_sub_face(other, other_edge, face) => (|t| 0.5 * (1.0 - t), 0.5),
                (true, false) => (|t| 1.0 - 0.5 * t, 0.5),
                _ => (|t| 1.0 - t, 1.0),
            };
            if dir != (0.0, 0.0) {
                let (t1, s1) = edge_frame(self.mesh, edge, u + dir.0, v + dir.1);
                let (au, av) = from_edge(self.mesh, other_edge, along(t), -s * deeper);
                let (bu, bv) = from_edge(self.mesh, other_edge, along(t1), -s1 * deeper);
                dir = (bu - au, bv - av);
            }
            (u, v) = from_edge(self.mesh, other_edge, along(t), -s * deeper);
            face = other;
            scale *= deeper;
        }
        (face, u, v, dir, scale)
    }

    /// Whether sub-face `sub` is the primary of the two sub-faces along edge `edge` of quad
    /// face `main` (the one `main`'s adjacency names: it covers the first half of the edge,
    /// counter-clockwise; the module documentation).
    fn primary_sub_face(&self, main: u32, edge: usize, sub: u32) -> bool {
        self.adjacency.get(main as usize).and_then(|a| a.across(edge)).is_some_and(|(f, _)| f == sub as usize)
    }
}
