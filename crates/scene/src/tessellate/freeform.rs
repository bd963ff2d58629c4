//! Free-form surfaces (`surface` statements of a group: Bézier, B-spline/NURBS, Taylor,
//! cardinal and basis-matrix patches, rational or not) tessellated into triangles.
//!
//! A surface is a tensor product of two [`basis::Direction`]s over its control points,
//! listed with u running fastest; rational surfaces weight each point (`i w weight`),
//! evaluated in homogeneous space so a weighted quadratic gives exact circles. The
//! triangles are cut on a grid of (u, v) values chosen by the surface's
//! `approximate surface …` statement ([`approx`]), counter-clockwise seen from the side
//! `∂P/∂u × ∂P/∂v` points to, with that normal per vertex, the derivatives `∂P/∂u`,
//! `∂P/∂v`, and one texture space per `texture` sub-surface (evaluated at the same
//! (u, v)); a surface without texture surfaces gets its (u, v) parameters as texture
//! space 0.
//!
//! Trimming ([`trim`]): grid cells away from every `trim`/`hole` loop are kept or dropped
//! whole by their centre; cells a loop passes through are cut into [`TRIM_REFINE`]²
//! sub-cells, each kept by its centre. Sub-cell positions are bilinear in the cell's
//! corners (so no crack opens against the neighbouring whole cells); their normals and
//! texture coordinates are the surface's own. The trimmed edge is therefore accurate to
//! about one sub-cell; trimmed surfaces get at least [`MIN_TRIMMED_PARTS`] parts per
//! direction.
//!
//! Not supported (reported once per group, then ignored): `special` points and curves,
//! `connect` statements and space curves, which only steer where mental ray places
//! vertices.

pub mod approx;
pub mod basis;
pub mod trim;

use std::collections::HashMap;

use glam::{DVec2, DVec3, DVec4, Vec3};
use mi::ast::{Approximation, Basis, FaceMaterial, Group, GroupItem, Surface, SurfaceDir, SurfaceExtra, VertexRef};
use mi::Diagnostic;

use crate::mesh::{MaterialSlot, Mesh, TexSpace};
use approx::Plan;
use basis::{Direction, Weights};
use trim::{Curve2, Trimming};

/// Sub-cells per side of a grid cell a trimming loop passes through.
pub const TRIM_REFINE: usize = 8;

/// Fewest grid parts per direction of a trimmed surface, so that its trimmed edges
/// (accurate to a [`TRIM_REFINE`]th of a part) stay smooth under coarse approximations.
pub const MIN_TRIMMED_PARTS: usize = 16;

/// Most grid vertices one surface may have; finer plans are reduced, with a warning.
pub const MAX_GRID_VERTICES: usize = 1 << 22;

/// A tensor-product patch: `u.count × v.count` homogeneous control points `(w·P, w)`,
/// u running fastest.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    /// The u direction.
    pub u: Direction,
    /// The v direction.
    pub v: Direction,
    points: Vec<DVec4>,
}

/// A point of a surface with its parameter derivatives (object space).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Position.
    pub p: DVec3,
    /// ∂P/∂u.
    pub du: DVec3,
    /// ∂P/∂v.
    pub dv: DVec3,
}

impl Patch {
    /// A patch over `points` (homogeneous, u fastest); the error says what does not fit.
    pub fn new(u: Direction, v: Direction, points: Vec<DVec4>) -> Result<Patch, String> {
        if points.len() != u.count * v.count {
            return Err(format!(
                "{} control points given, the bases need {} × {} = {}",
                points.len(),
                u.count,
                v.count,
                u.count * v.count
            ));
        }
        Ok(Patch { u, v, points })
    }

    /// The point at (u, v), clamped to the parameter ranges.
    pub fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        self.eval_weights(&self.u.eval(u), &self.v.eval(v))
    }

    /// The point for precomputed basis weights of its two directions.
    pub fn eval_weights(&self, wu: &Weights, wv: &Weights) -> SurfacePoint {
        let nu = self.u.count;
        let (mut s, mut su, mut sv) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        for (b, (&n, &dn)) in wv.w.iter().zip(&wv.dw).enumerate() {
            let row = (wv.first + b) * nu + wu.first;
            let (mut r, mut ru) = (DVec4::ZERO, DVec4::ZERO);
            for (c, (&m, &dm)) in self.points[row..row + wu.w.len()].iter().zip(wu.w.iter().zip(&wu.dw)) {
                r += m * *c;
                ru += dm * *c;
            }
            s += n * r;
            su += n * ru;
            sv += dn * r;
        }
        let w = if s.w.abs() > 1e-300 { s.w } else { 1.0 };
        let p = s.truncate() / w;
        SurfacePoint { p, du: (su.truncate() - p * su.w) / w, dv: (sv.truncate() - p * sv.w) / w }
    }

    /// The unit normal `∂P/∂u × ∂P/∂v` at (u, v); where it vanishes (a pole), the normal
    /// a little way into the patch.
    pub fn normal(&self, u: f64, v: f64, at: &SurfacePoint) -> DVec3 {
        let n = at.du.cross(at.dv);
        let scale = at.du.length() * at.dv.length();
        if n.length() > 1e-9 * scale && n.length() > 0.0 {
            return n.normalize();
        }
        for step in [1e-5, 1e-4, 1e-3, 1e-2] {
            let nudge = |x: f64, lo: f64, hi: f64| {
                let h = (hi - lo) * step;
                if x + h <= hi {
                    x + h
                } else {
                    x - h
                }
            };
            let (u2, v2) = (nudge(u, self.u.lo, self.u.hi), nudge(v, self.v.lo, self.v.hi));
            let q = self.eval(u2, v2);
            let n = q.du.cross(q.dv);
            if n.length() > 0.0 {
                return n.normalize();
            }
        }
        DVec3::ZERO
    }
}

/// A surface ready to tessellate.
#[derive(Clone, Debug, PartialEq)]
pub struct Freeform {
    /// The geometric patch.
    pub patch: Patch,
    /// Texture surfaces with the number of meaningful components (3 for `volume`).
    pub textures: Vec<(Patch, u8)>,
    /// Trim and hole loops in (u, v).
    pub trimming: Trimming,
}

/// What surfaces of one group are built from: the object's bases, the group's vectors
/// and curves.
pub struct Context<'a> {
    bases: HashMap<&'a str, &'a Basis>,
    group: &'a Group,
}

impl<'a> Context<'a> {
    /// The context of `group` in an object with `bases`.
    pub fn new(bases: &'a [Basis], group: &'a Group) -> Context<'a> {
        Context { bases: bases.iter().map(|b| (b.name.text.as_str(), b)).collect(), group }
    }

    fn direction(&self, dir: &SurfaceDir) -> Result<(Direction, bool), String> {
        let basis =
            self.bases.get(dir.basis.text.as_str()).ok_or_else(|| format!("unknown basis '{}'", dir.basis.text))?;
        let d = Direction::new(&basis.kind, dir).map_err(|e| format!("basis '{}': {e}", dir.basis.text))?;
        Ok((d, basis.rational || dir.rational))
    }

    fn vector(&self, r: &VertexRef) -> Result<DVec3, String> {
        let v =
            self.group.vertices.get(r.index as usize).ok_or_else(|| {
                format!("vertex {} does not exist ({} in the group)", r.index, self.group.vertices.len())
            })?;
        let p = self.group.vectors.get(v.pos as usize).ok_or_else(|| format!("vertex {} has no vector", r.index))?;
        Ok(DVec3::new(p[0].into(), p[1].into(), p[2].into()))
    }

    fn weight(r: &VertexRef, rational: bool) -> Result<f64, String> {
        let w = if rational { r.weight.map_or(1.0, |w| w.1) } else { 1.0 };
        if w.is_finite() && w > 0.0 {
            Ok(w)
        } else {
            Err(format!("vertex {} has the weight {w}; weights must be positive", r.index))
        }
    }

    fn patch(&self, u: &SurfaceDir, v: &SurfaceDir, refs: &[VertexRef]) -> Result<Patch, String> {
        let (du, ru) = self.direction(u)?;
        let (dv, rv) = self.direction(v)?;
        let points = refs
            .iter()
            .map(|r| {
                let w = Self::weight(r, ru || rv)?;
                Ok((self.vector(r)? * w).extend(w))
            })
            .collect::<Result<Vec<_>, String>>()?;
        Patch::new(du, dv, points)
    }

    fn curve(&self, name: &str) -> Result<Curve2, String> {
        let c = self
            .group
            .items
            .iter()
            .find_map(|i| match i {
                GroupItem::Curve(c) if c.name.text == name => Some(c),
                _ => None,
            })
            .ok_or_else(|| format!("unknown curve '{name}'"))?;
        let basis = self.bases.get(c.basis.text.as_str()).ok_or_else(|| format!("unknown basis '{}'", c.basis.text))?;
        let dir = Direction::from_parts(&basis.kind, &c.params, None).map_err(|e| format!("curve '{name}': {e}"))?;
        let rational = basis.rational || c.rational;
        if c.refs.len() != dir.count {
            return Err(format!("curve '{name}' has {} control points, its basis needs {}", c.refs.len(), dir.count));
        }
        let points = c
            .refs
            .iter()
            .map(|r| {
                let w = Self::weight(r, rational)?;
                let p = self.vector(r)?;
                Ok(DVec3::new(p.x * w, p.y * w, w))
            })
            .collect::<Result<Vec<_>, String>>()?;
        Ok(Curve2 { dir, points })
    }

    fn trim_loop(&self, segments: &[mi::ast::CurveSegment]) -> Result<Vec<DVec2>, String> {
        let mut points: Vec<DVec2> = Vec::new();
        for s in segments {
            let c = self.curve(&s.curve.text)?;
            let start = points.len();
            c.sample(s.t0, s.t1, &mut points);
            // Consecutive segments meet: drop the repeated joint.
            if start > 0 && points.len() > start && points[start].distance(points[start - 1]) < 1e-12 {
                points.remove(start);
            }
            if points.len() > trim::MAX_LOOP_POINTS {
                return Err(format!("a trimming loop has more than {} points", trim::MAX_LOOP_POINTS));
            }
        }
        if points.len() > 1 && points[0].distance(*points.last().expect("not empty")) < 1e-12 {
            points.pop();
        }
        if points.len() < 3 {
            return Err("a trimming loop has fewer than three points".into());
        }
        Ok(points)
    }

    /// Builds surface `s`; the error says what is wrong with it.
    pub fn surface(&self, s: &Surface) -> Result<Freeform, String> {
        let patch = self.patch(&s.u, &s.v, &s.refs)?;
        let mut textures = Vec::new();
        let mut trimming = Trimming::default();
        for extra in &s.extras {
            match extra {
                SurfaceExtra::Texture { volume, u, v, refs, .. } => {
                    let t = self.patch(u, v, refs).map_err(|e| format!("texture surface: {e}"))?;
                    textures.push((t, if *volume { 3 } else { 2 }));
                }
                SurfaceExtra::Trim(segs) => trimming.trims.push(self.trim_loop(segs)?),
                SurfaceExtra::Hole(segs) => trimming.holes.push(self.trim_loop(segs)?),
                SurfaceExtra::Derivative(_) | SurfaceExtra::Special(_) => {}
            }
        }
        Ok(Freeform { patch, textures, trimming })
    }
}

/// The material slot a surface's material or label becomes.
pub fn surface_slot(m: &FaceMaterial) -> MaterialSlot {
    match m {
        FaceMaterial::Named(n) if !n.text.is_empty() => MaterialSlot::Named(n.text.clone()),
        FaceMaterial::Label(l) => MaterialSlot::Label(*l),
        _ => MaterialSlot::Inherit,
    }
}

/// Tessellates the free-form surfaces of `group` and appends them to `mesh`. A surface
/// that cannot be built is reported and left out.
pub fn group_surfaces(
    group: &Group,
    bases: &[Basis],
    approximations: &[&Approximation],
    mesh: &mut Mesh,
    diags: &mut Vec<Diagnostic>,
) {
    let ctx = Context::new(bases, group);
    let mut ignored = None;
    for item in &group.items {
        let s = match item {
            GroupItem::Surface(s) => s,
            GroupItem::Connect(c) => {
                ignored.get_or_insert(c.span);
                continue;
            }
            GroupItem::SpaceCurve(c) => {
                ignored.get_or_insert(c.span);
                continue;
            }
            _ => continue,
        };
        if s.extras.iter().any(|e| matches!(e, SurfaceExtra::Special(_))) {
            ignored.get_or_insert(s.span);
        }
        let surface = match ctx.surface(s) {
            Ok(f) => f,
            Err(e) => {
                diags.push(Diagnostic::error(
                    s.span.start(),
                    format!("free-form surface '{}' of object '{}' is left out: {e}", s.name.text, mesh.name),
                ));
                continue;
            }
        };
        // The last approximation naming the surface that mira can follow.
        let plan = approximations
            .iter()
            .rev()
            .filter(|a| {
                a.target == Some("surface") && (a.names.is_empty() || a.names.iter().any(|n| n.text == s.name.text))
            })
            .find_map(|a| Plan::from_approximation(a))
            .unwrap_or_default();
        let (mut part, reduced) = surface.tessellate(&plan, &mesh.name);
        if reduced {
            diags.push(Diagnostic::warning(
                s.span.start(),
                format!(
                    "free-form surface '{}': its approximation asks for too many triangles; a coarser grid is used",
                    s.name.text
                ),
            ));
        }
        // The part's one slot (0, `Inherit`) becomes the surface's material.
        part.slots = vec![surface_slot(&s.material)];
        mesh.append(part);
    }
    if let Some(span) = ignored {
        diags.push(Diagnostic::warning(
            span.start(),
            format!(
                "object '{}': free-form 'special' points and curves, 'connect' statements and space curves are \
                 ignored; the surfaces are tessellated without them",
                mesh.name
            ),
        ));
    }
}

/// Evaluates a vertex of the output: its position (unless given) and everything else.
struct Emitter<'f> {
    f: &'f Freeform,
    mesh: Mesh,
}

impl Emitter<'_> {
    fn vertex(&mut self, u: f64, v: f64, at: SurfacePoint, position: Option<DVec3>) -> u32 {
        let patch = &self.f.patch;
        let n = patch.normal(u, v, &at);
        self.mesh.positions.push(position.unwrap_or(at.p).as_vec3());
        self.mesh.normals.push(n.as_vec3());
        self.mesh.derivatives.push([at.du.as_vec3(), at.dv.as_vec3()]);
        if self.f.textures.is_empty() {
            self.mesh.textures[0].coords.push(Vec3::new(u as f32, v as f32, 0.0));
        }
        for (k, (t, _)) in self.f.textures.iter().enumerate() {
            self.mesh.textures[k].coords.push(t.eval(u, v).p.as_vec3());
        }
        (self.mesh.positions.len() - 1) as u32
    }
}

impl Freeform {
    /// The grid of (u, v) values `plan` asks for, and whether it had to be reduced.
    pub fn grid(&self, plan: &Plan) -> (Vec<f64>, Vec<f64>, bool) {
        let (u, v) = (&self.patch.u, &self.patch.v);
        let (mut us, mut vs) = match plan {
            Plan::PerPatch(fu, fv) => {
                let parts =
                    |f: f64, d: &Direction| ((f * d.degree as f64).ceil().max(1.0) as usize).min(approx::MAX_PARTS);
                (
                    approx::per_patch_samples(&u.breaks, parts(*fu, u)),
                    approx::per_patch_samples(&v.breaks, parts(*fv, v)),
                )
            }
            Plan::Regular(nu, nv) => {
                (approx::uniform_samples(u.lo, u.hi, *nu), approx::uniform_samples(v.lo, v.hi, *nv))
            }
            Plan::Criteria(c) => {
                let (lu, tu, lv, tv) = self.measure();
                let pu = approx::criteria_parts(c, lu, tu, u.breaks.len() - 1);
                let pv = approx::criteria_parts(c, lv, tv, v.breaks.len() - 1);
                (approx::uniform_samples(u.lo, u.hi, pu), approx::uniform_samples(v.lo, v.hi, pv))
            }
        };
        if !self.trimming.is_empty() {
            if us.len() <= MIN_TRIMMED_PARTS {
                us = approx::uniform_samples(u.lo, u.hi, MIN_TRIMMED_PARTS);
            }
            if vs.len() <= MIN_TRIMMED_PARTS {
                vs = approx::uniform_samples(v.lo, v.hi, MIN_TRIMMED_PARTS);
            }
        }
        let mut reduced = false;
        let total = us.len() * vs.len();
        if total > MAX_GRID_VERTICES || us.len() > approx::MAX_PARTS + 1 || vs.len() > approx::MAX_PARTS + 1 {
            let k = (MAX_GRID_VERTICES as f64 / total as f64).sqrt().min(1.0);
            let pu = (((us.len() - 1) as f64 * k) as usize).clamp(1, approx::MAX_PARTS);
            let pv = (((vs.len() - 1) as f64 * k) as usize).clamp(1, approx::MAX_PARTS);
            us = approx::uniform_samples(u.lo, u.hi, pu);
            vs = approx::uniform_samples(v.lo, v.hi, pv);
            reduced = true;
        }
        (us, vs, reduced)
    }

    /// Longest iso-line (sum of chords) and largest total turn of the tangent (radians)
    /// along u, then along v, measured on a grid of 8 parts per patch (at most 256 per
    /// direction).
    fn measure(&self) -> (f64, f64, f64, f64) {
        let samples = |d: &Direction| {
            if (d.breaks.len() - 1) * 8 <= 256 {
                approx::per_patch_samples(&d.breaks, 8)
            } else {
                approx::uniform_samples(d.lo, d.hi, 256)
            }
        };
        let (us, vs) = (samples(&self.patch.u), samples(&self.patch.v));
        let wu: Vec<Weights> = us.iter().map(|&u| self.patch.u.eval(u)).collect();
        let wv: Vec<Weights> = vs.iter().map(|&v| self.patch.v.eval(v)).collect();
        let p: Vec<Vec<SurfacePoint>> =
            wv.iter().map(|b| wu.iter().map(|a| self.patch.eval_weights(a, b)).collect()).collect();
        // (position, tangent) along one iso-line.
        let line = |pts: &mut dyn Iterator<Item = (DVec3, DVec3)>| {
            let (pts, tangents): (Vec<DVec3>, Vec<DVec3>) = pts.unzip();
            let length: f64 = pts.windows(2).map(|w| w[0].distance(w[1])).sum();
            let tangents: Vec<DVec3> = tangents.into_iter().filter(|t| t.length() > 0.0).collect();
            let turn: f64 = tangents.windows(2).map(|w| w[0].angle_between(w[1])).sum();
            (length, turn)
        };
        let (mut lu, mut tu, mut lv, mut tv) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for row in &p {
            let (l, t) = line(&mut row.iter().map(|q| (q.p, q.du)));
            (lu, tu) = (lu.max(l), tu.max(t));
        }
        for i in 0..us.len() {
            let (l, t) = line(&mut p.iter().map(|row| (row[i].p, row[i].dv)));
            (lv, tv) = (lv.max(l), tv.max(t));
        }
        (lu, tu, lv, tv)
    }

    /// Triangles, normals, derivatives and texture spaces of the surface under `plan`
    /// (one material slot, `Inherit`, for the caller to replace), and whether the grid had
    /// to be reduced.
    pub fn tessellate(&self, plan: &Plan, name: &str) -> (Mesh, bool) {
        let (us, vs, reduced) = self.grid(plan);
        let mut mesh = Mesh::new(name);
        mesh.textures = if self.textures.is_empty() {
            vec![TexSpace { dim: 2, coords: Vec::new() }]
        } else {
            self.textures.iter().map(|(_, d)| TexSpace { dim: *d, coords: Vec::new() }).collect()
        };
        let mut out = Emitter { f: self, mesh };
        let patch = &self.patch;
        let wu: Vec<Weights> = us.iter().map(|&u| patch.u.eval(u)).collect();
        let wv: Vec<Weights> = vs.iter().map(|&v| patch.v.eval(v)).collect();
        let (cu, cv) = (us.len() - 1, vs.len() - 1);
        let mut grid = vec![u32::MAX; us.len() * vs.len()];
        let mut grid_pos = vec![None; us.len() * vs.len()];
        let mut grid_vertex = |out: &mut Emitter, i: usize, j: usize| -> (u32, DVec3) {
            let k = j * us.len() + i;
            if grid[k] == u32::MAX {
                let at = patch.eval_weights(&wu[i], &wv[j]);
                grid[k] = out.vertex(us[i], vs[j], at, None);
                grid_pos[k] = Some(at.p);
            }
            (grid[k], grid_pos[k].expect("set with the index"))
        };
        // Cells a trimming loop passes through (by the bounding box of each loop edge).
        let trimmed = !self.trimming.is_empty();
        let mut marked = vec![false; cu * cv];
        if trimmed {
            let cell = |xs: &[f64], x: f64| xs.partition_point(|&s| s <= x).saturating_sub(1).min(xs.len() - 2);
            for (a, b) in self.trimming.edges() {
                let (lo, hi) = (a.min(b), a.max(b));
                for j in cell(&vs, lo.y)..=cell(&vs, hi.y) {
                    for i in cell(&us, lo.x)..=cell(&us, hi.x) {
                        marked[j * cu + i] = true;
                    }
                }
            }
        }
        let r = TRIM_REFINE;
        for j in 0..cv {
            let centre = 0.5 * (vs[j] + vs[j + 1]);
            let row = trimmed.then(|| self.trimming.crossings(centre));
            let sub_rows: Vec<_> = if marked[j * cu..(j + 1) * cu].iter().any(|&m| m) {
                (0..r)
                    .map(|l| self.trimming.crossings(vs[j] + (vs[j + 1] - vs[j]) * (l as f64 + 0.5) / r as f64))
                    .collect()
            } else {
                Vec::new()
            };
            for i in 0..cu {
                let (a, pa) = grid_vertex(&mut out, i, j);
                let (b, pb) = grid_vertex(&mut out, i + 1, j);
                let (c, pc) = grid_vertex(&mut out, i + 1, j + 1);
                let (d, pd) = grid_vertex(&mut out, i, j + 1);
                if !marked[j * cu + i] {
                    if row.as_ref().is_none_or(|x| x.keeps(0.5 * (us[i] + us[i + 1]))) {
                        out.mesh.triangles.push([a, b, c]);
                        out.mesh.triangles.push([a, c, d]);
                    }
                    continue;
                }
                // A boundary cell: sub-cells kept by their centres.
                let mut local = vec![u32::MAX; (r + 1) * (r + 1)];
                local[0] = a;
                local[r] = b;
                local[(r + 1) * r + r] = c;
                local[(r + 1) * r] = d;
                for (l, sub_row) in sub_rows.iter().enumerate() {
                    for k in 0..r {
                        let uc = us[i] + (us[i + 1] - us[i]) * (k as f64 + 0.5) / r as f64;
                        if !sub_row.keeps(uc) {
                            continue;
                        }
                        let mut corner = |kk: usize, ll: usize| {
                            let at = ll * (r + 1) + kk;
                            if local[at] == u32::MAX {
                                let (s, t) = (kk as f64 / r as f64, ll as f64 / r as f64);
                                let u = us[i] + (us[i + 1] - us[i]) * s;
                                let v = vs[j] + (vs[j + 1] - vs[j]) * t;
                                let p = (pa * (1.0 - s) + pb * s) * (1.0 - t) + (pd * (1.0 - s) + pc * s) * t;
                                local[at] = out.vertex(u, v, patch.eval(u, v), Some(p));
                            }
                            local[at]
                        };
                        let (q0, q1, q2, q3) = (corner(k, l), corner(k + 1, l), corner(k + 1, l + 1), corner(k, l + 1));
                        out.mesh.triangles.push([q0, q1, q2]);
                        out.mesh.triangles.push([q0, q2, q3]);
                    }
                }
            }
        }
        let mut mesh = out.mesh;
        let slot = mesh.slot(MaterialSlot::Inherit);
        mesh.triangle_slots = vec![slot; mesh.triangles.len()];
        (mesh, reduced)
    }
}

/// `mib_geo_add_uv_texsurf`: appends to every surface of `object` a degree-1 Bézier
/// texture surface over the surface's own parameter range whose four texture vertices
/// are the range's corners `(u, v, 0)`, so the new last texture space holds each
/// vertex's (u, v) parameters. A basis `mira#uv_bezier1` is added to the object.
/// Returns how many surfaces got one.
pub fn add_uv_texture_surfaces(object: &mut mi::ast::Object) -> usize {
    let basis_name = "mira#uv_bezier1";
    let name = |span| mi::ast::Name { text: basis_name.to_string(), span };
    let mut count = 0;
    for g in &mut object.geometry {
        let mi::ast::Geometry::Group(group) = g else { continue };
        let mut added = Vec::new();
        for item in &group.items {
            let GroupItem::Surface(s) = item else { continue };
            let bases: HashMap<&str, &Basis> = object.bases.iter().map(|b| (b.name.text.as_str(), b)).collect();
            let range = |d: &SurfaceDir| {
                let basis = bases.get(d.basis.text.as_str())?;
                Direction::new(&basis.kind, d).ok().map(|x| (x.lo, x.hi))
            };
            let (Some(ru), Some(rv)) = (range(&s.u), range(&s.v)) else { continue };
            added.push((s.name.text.clone(), ru, rv));
        }
        for (surface, (u0, u1), (v0, v1)) in added {
            let first = group.vertices.len() as u32;
            for (u, v) in [(u0, v0), (u1, v0), (u0, v1), (u1, v1)] {
                group.vectors.push([u as f32, v as f32, 0.0]);
                let pos = (group.vectors.len() - 1) as u32;
                group.vertices.push(mi::ast::Vertex { pos, normal: None, attrs_end: group.vertex_attrs.len() as u32 });
            }
            let Some(GroupItem::Surface(s)) =
                group.items.iter_mut().find(|i| matches!(i, GroupItem::Surface(s) if s.name.text == surface))
            else {
                continue;
            };
            let span = s.span;
            let dir =
                |lo: f64, hi: f64| SurfaceDir { rational: false, basis: name(span), range: None, params: vec![lo, hi] };
            let refs = (first..first + 4).map(|index| VertexRef { index, weight: None }).collect();
            s.extras.push(SurfaceExtra::Texture { volume: false, vector: false, u: dir(u0, u1), v: dir(v0, v1), refs });
            count += 1;
        }
    }
    if count > 0 && !object.bases.iter().any(|b| b.name.text == basis_name) {
        let span = object.span;
        object.bases.push(Basis { name: name(span), rational: false, kind: mi::ast::BasisKind::Bezier(1), span });
    }
    count
}

#[cfg(test)]
mod tests;
