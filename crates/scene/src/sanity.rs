//! Values no renderer can use, reported at the statement that writes them before the
//! world reaches shaders or the renderer.
//!
//! - A number that is not finite (`1e999` reads as infinity; binary data may hold NaN) in
//!   an options, light or camera statement or in any shader parameter is an error: there is
//!   no meaningful fallback for an infinite light colour or filter width.
//! - A pixel filter wider than [`MAX_FILTER_SIZE`] pixels is narrowed with a warning.
//! - An area light without area (zero edges, radius ≤ 0) becomes the point, spot or
//!   directional light it would be without its shape, with a warning.
//!
//! Camera values (focal length, aperture, resolution, …) are checked by
//! [`crate::camera::Camera::from_blocks`]; vertex data by the tessellators.

/// Largest world-space coordinate of a placed object or the camera: beyond it, the
/// renderer's single-precision positions and ray arithmetic overflow to infinity.
pub const WORLD_LIMIT: f64 = 1e30;

use mi::ast::{Arg, Block, KwStmt, Param, ShaderItem, ShaderList, Stmt, Value};
use mi::Diagnostic;

use glam::Vec3;
use rayon::prelude::*;

use crate::light::{AreaShape, Light};
use crate::names::{Def, Table};
use crate::options::Options;
use crate::tessellate::ObjectGeometry;
use crate::values::last;

/// Widest pixel filter footprint, in pixels (mental ray's filters are a few pixels wide).
pub const MAX_FILTER_SIZE: f64 = 64.0;

/// Camera statements whose values the camera reader checks itself.
const CAMERA_CHECKED: &[&str] = &["focal", "aperture", "aspect", "offset", "clip", "resolution"];

/// Reports every non-finite number written in options, lights, cameras and shader
/// parameters of the elements of `table`.
pub fn check_numbers(table: &Table, diags: &mut Vec<Diagnostic>) {
    let mut elements: Vec<_> = table.elements.values().collect();
    elements.sort_by_key(|e| (e.span.file, e.span.lo));
    for e in elements {
        match &e.def {
            Def::Options(blocks) | Def::Light(blocks) => blocks.iter().for_each(|b| stmts(&b.stmts, &[], diags)),
            Def::Camera(blocks) => blocks.iter().for_each(|b| stmts(&b.stmts, CAMERA_CHECKED, diags)),
            Def::Shader(defs) => defs.iter().for_each(|d| list(&d.list, diags)),
            Def::Material(defs) => {
                for m in defs {
                    if let Some(l) = &m.shaders {
                        list(l, diags);
                    }
                    stmts(&m.stmts, &[], diags);
                }
            }
            _ => {}
        }
    }
}

fn stmts(stmts: &[Stmt], skip: &[&str], diags: &mut Vec<Diagnostic>) {
    for s in stmts {
        match s {
            Stmt::Kw(k) if !skip.contains(&k.key) => kw(k, diags),
            Stmt::Shaders(l) => list(l, diags),
            _ => {}
        }
    }
}

fn kw(k: &KwStmt, diags: &mut Vec<Diagnostic>) {
    let mut bad = None;
    for a in &k.args {
        match a {
            Arg::Float(v) if !v.is_finite() => bad = bad.or(Some(*v)),
            Arg::Floats(vs) => bad = bad.or(vs.iter().copied().find(|v| !v.is_finite())),
            Arg::Num(n) if !n.as_f64().is_finite() => bad = bad.or(Some(n.as_f64())),
            Arg::Shaders(l) | Arg::ShaderArray(l) => list(l, diags),
            _ => {}
        }
    }
    if let Some(v) = bad {
        diags.push(Diagnostic::error(k.span, format!("'{}' has a number that is not finite ({})", k.key, word(v))));
    }
}

fn list(l: &ShaderList, diags: &mut Vec<Diagnostic>) {
    for item in &l.0 {
        match item {
            ShaderItem::Call { params, .. } => params.iter().for_each(|p| param(p, diags)),
            ShaderItem::Define { list: inner, .. } => list(inner, diags),
            ShaderItem::Ref(_) => {}
        }
    }
}

fn param(p: &Param, diags: &mut Vec<Diagnostic>) {
    if let Some(v) = non_finite(&p.value, diags) {
        diags.push(Diagnostic::error(
            p.span,
            format!("shader parameter '{}' has a number that is not finite ({})", p.name.text, word(v)),
        ));
    }
}

/// The first non-finite number directly in `v` (struct fields are reported as parameters
/// of their own). Recursion follows one value's nesting, which the parser bounds.
fn non_finite(v: &Value, diags: &mut Vec<Diagnostic>) -> Option<f64> {
    match v {
        Value::Num(n) => Some(n.as_f64()).filter(|x| !x.is_finite()),
        Value::Tuple(ns) => ns.iter().map(|n| n.as_f64()).find(|x| !x.is_finite()),
        Value::Struct(fields) => {
            fields.iter().for_each(|f| param(f, diags));
            None
        }
        Value::Array(vs) | Value::Seq(vs) => vs.iter().find_map(|v| non_finite(v, diags)),
        Value::Define(item) => {
            list(&ShaderList(vec![(**item).clone()]), diags);
            None
        }
        _ => None,
    }
}

fn word(v: f64) -> &'static str {
    if v.is_nan() {
        "NaN"
    } else if v > 0.0 {
        "infinity"
    } else {
        "-infinity"
    }
}

/// Highest `samples` level the classic engine takes (4^5 = 1024 samples per pixel).
pub const MAX_SAMPLES_LEVEL: i64 = 5;

/// Deepest trace depth the options keep (`trace depth`, `finalgather trace depth`).
pub const MAX_TRACE_DEPTH: i64 = 1 << 16;

/// Deepest `photon trace depth` the options keep.
pub const MAX_PHOTON_TRACE_DEPTH: i64 = 1 << 10;

/// Warns where the options ask for more than mira takes: `samples` levels above
/// [`MAX_SAMPLES_LEVEL`], trace depths above [`MAX_TRACE_DEPTH`] (both read capped), and
/// narrows a filter wider than [`MAX_FILTER_SIZE`].
pub fn options(o: &mut Options, blocks: &[&Block], diags: &mut Vec<Diagnostic>) {
    let stmts: Vec<&Stmt> = blocks.iter().flat_map(|b| b.stmts.iter()).collect();
    if let Some(k) = last(&stmts, "samples") {
        let levels: Vec<i64> = (0..k.args.len()).filter_map(|i| crate::values::int_arg(k, i)).collect();
        if levels.iter().any(|l| *l > MAX_SAMPLES_LEVEL) {
            diags.push(Diagnostic::warning(
                k.span,
                format!(
                    "samples level {} asks for more than the {} samples per pixel mira takes: level \
                     {MAX_SAMPLES_LEVEL} is used",
                    levels.iter().max().copied().unwrap_or_default(),
                    4u32.pow(MAX_SAMPLES_LEVEL as u32)
                ),
            ));
        }
    }
    for s in &stmts {
        let Stmt::Kw(k) = s else { continue };
        let max = match k.key {
            "trace depth" | "finalgather trace depth" => MAX_TRACE_DEPTH,
            "photon trace depth" => MAX_PHOTON_TRACE_DEPTH,
            _ => continue,
        };
        let deepest = (0..k.args.len()).filter_map(|i| crate::values::int_arg(k, i)).max().unwrap_or(0);
        if deepest > max {
            diags.push(Diagnostic::warning(
                k.span,
                format!("{} {deepest} is deeper than mira traces: {max} is used", k.key),
            ));
        }
    }
    capped(&stmts, diags);
    environment_lighting_mode(&stmts, diags);
    environment_lighting_settings(&stmts, diags);
    gi_rays(&stmts, diags);
    let f = &mut o.filter;
    let (o_w, o_h) = (f.width, f.height);
    if f.width > MAX_FILTER_SIZE || f.height > MAX_FILTER_SIZE || !(f.width > 0.0 && f.height > 0.0) {
        let span =
            last(&stmts, "filter").map_or_else(|| blocks.first().map(|b| b.span).unwrap_or_default(), |k| k.span);
        let fix = |v: f64| if v > 0.0 { v.min(MAX_FILTER_SIZE) } else { 1.0 };
        let (w, h) = (fix(f.width), fix(f.height));
        let finite = f.width.is_finite() && f.height.is_finite(); // else already an error
        f.width = w;
        f.height = h;
        if !finite {
            return;
        }
        diags.push(Diagnostic::warning(
            span,
            format!("filter {} x {} pixels is outside (0, {MAX_FILTER_SIZE}]: {w} x {h} is used", o_w, o_h),
        ));
    }
}

/// Warns where an options statement, string option or attribute asks for more (or less)
/// than the options keep: the value read is clamped (`crate::options`), and the warning says
/// to what.
fn capped(stmts: &[&Stmt], diags: &mut Vec<Diagnostic>) {
    use crate::options::{MAX_ACCURACY, MAX_BUFFER_OR_POINTS, MAX_MOTION_STEPS, MAX_PROGRESSIVE_SAMPLES};
    // `shutter delay close` with close before delay: mira, as mental ray, takes it as a
    // closed shutter (no motion blur); said, since the file asked for blur.
    for s in stmts {
        if let Stmt::Kw(k) = s {
            let (delay, close) = (crate::values::f64_arg(k, 0), crate::values::f64_arg(k, 1));
            if let ("shutter", Some(d), Some(c)) = (k.key, delay, close) {
                if c < d {
                    diags.push(Diagnostic::warning(
                        k.span,
                        format!("shutter closes at {c} before it opens at {d}: no motion blur is rendered"),
                    ));
                }
            }
        }
    }
    let mut warn = |span: mi::Span, what: &str, v: f64, (lo, hi): (f64, f64)| {
        if v > hi {
            diags.push(Diagnostic::warning(span, format!("{what} {v} is more than mira takes: {hi} is used")));
        } else if v < lo {
            diags.push(Diagnostic::warning(span, format!("{what} {v} is less than {lo}: {lo} is used")));
        }
    };
    for s in stmts {
        match s {
            Stmt::Kw(k) => {
                let (index, range) = match k.key {
                    "caustic accuracy" | "globillum accuracy" => (0, (1, MAX_ACCURACY)),
                    "finalgather accuracy" => {
                        (usize::from(crate::values::str_arg(k, 0) == Some("view")), (1, MAX_ACCURACY))
                    }
                    "motion steps" => (0, (1, MAX_MOTION_STEPS)),
                    "frame buffer" | "finalgather points" => (0, (0, MAX_BUFFER_OR_POINTS)),
                    _ => continue,
                };
                if let Some(v) = crate::values::int_arg(k, index) {
                    warn(k.span, &format!("'{}'", k.key), v as f64, (range.0 as f64, range.1 as f64));
                }
            }
            Stmt::StringOption { name, value } => {
                let range = match name.text.as_str() {
                    "progressive max samples" | "progressive min samples" => (1.0, MAX_PROGRESSIVE_SAMPLES),
                    "finalgather points" => (0.0, MAX_BUFFER_OR_POINTS as f64),
                    _ => continue,
                };
                if let Some(v) = crate::values::AttrValue::from_value(value).and_then(|v| v.as_f64()) {
                    warn(name.span, &format!("\"{}\"", name.text), v, range);
                }
            }
            Stmt::Attribute(mi::ast::Attribute { name: Some(name), value: Some(value), .. }) => {
                if !matches!(
                    name.text.as_str(),
                    "progressive_rendering_max_samples" | "progressive_rendering_min_samples"
                ) {
                    continue;
                }
                if let Some(v) = crate::values::AttrValue::from_value(value).and_then(|v| v.as_f64()) {
                    warn(name.span, &format!("attribute '{}'", name.text), v, (1.0, MAX_PROGRESSIVE_SAMPLES));
                }
            }
            _ => {}
        }
    }
}

/// Warns where `"environment lighting mode"` is neither `"off"` nor `"light"`: mira reads
/// any other value as `"light"` (`crate::options::EnvironmentLighting`).
fn environment_lighting_mode(stmts: &[&Stmt], diags: &mut Vec<Diagnostic>) {
    for s in stmts {
        let Stmt::StringOption { name, value } = s else { continue };
        if name.text != "environment lighting mode" {
            continue;
        }
        let known = match crate::values::AttrValue::from_value(value) {
            Some(crate::values::AttrValue::Str(v)) => v.eq_ignore_ascii_case("off") || v.eq_ignore_ascii_case("light"),
            Some(crate::values::AttrValue::Bool(false)) => true,
            _ => false,
        };
        if !known {
            diags.push(Diagnostic::warning(
                name.span,
                "\"environment lighting mode\" is neither \"off\" nor \"light\": mira reads it as \"light\" (the environment lights the scene)",
            ));
        }
    }
}

/// Warns where `"environment lighting shadow"`, `"quality"` or `"scale"` has a value mira
/// does not read as written (`crate::options::modes`): a shadow mode other than
/// `"transparent"`, `"solid"` or `"off"` (read as `"transparent"`), a quality that is no
/// finite number (one sample), a scale that is negative or no number (1) or a colour (the
/// mean of its channels).
fn environment_lighting_settings(stmts: &[&Stmt], diags: &mut Vec<Diagnostic>) {
    use crate::values::AttrValue;
    for s in stmts {
        let Stmt::StringOption { name, value } = s else { continue };
        let v = AttrValue::from_value(value);
        let what = match name.text.as_str() {
            "environment lighting shadow" => match v.as_ref().and_then(crate::options::EnvironmentShadow::parse) {
                Some(_) => continue,
                None => "is none of \"transparent\", \"solid\" and \"off\": mira reads it as \"transparent\"",
            },
            "environment lighting quality" => match v.as_ref().and_then(AttrValue::as_f64) {
                Some(q) if q.is_finite() => continue,
                _ => "is no number: mira takes one environment sample per estimate",
            },
            "environment lighting scale" => match v {
                Some(AttrValue::Floats(f)) if f.len() > 1 => {
                    "is a colour: mira scales the environment's light by the mean of its channels"
                }
                Some(v) if v.as_f64().is_some_and(|x| x.is_finite() && x >= 0.0) => continue,
                _ => "is no number of at least 0: mira reads it as 1",
            },
            _ => continue,
        };
        diags.push(Diagnostic::warning(name.span, format!("\"{}\" {what}", name.text)));
    }
}

/// Notes at `"gi rays"` (GI "Next"'s rays per shading sample) that mira reads it but its
/// path engine has no counterpart (`crate::options::modes`): it does not change the image.
fn gi_rays(stmts: &[&Stmt], diags: &mut Vec<Diagnostic>) {
    for s in stmts {
        let Stmt::StringOption { name, .. } = s else { continue };
        if name.text == "gi rays" {
            diags.push(Diagnostic::warning(
                name.span,
                "\"gi rays\" does not change mira's path engine: it follows one ray per bounce and averages over the pixel's samples (raise the samples for less noise)",
            ));
        }
    }
}

/// Turns an area light without area into the light it is without its shape.
pub fn light(l: &mut Light, blocks: &[&Block], diags: &mut Vec<Diagnostic>) {
    let Some(area) = &l.area else { return };
    let usable = |r: f64| r > 0.0 && r.is_finite();
    let has_area = match &area.shape {
        AreaShape::Rectangle { edge_u, edge_v, .. } => usable(edge_u.cross(*edge_v).length()),
        AreaShape::Disc { radius, .. } | AreaShape::Sphere { radius } => usable(*radius),
        AreaShape::Cylinder { axis, radius } => usable(*radius) && usable(axis.length()),
        AreaShape::Object { .. } | AreaShape::User => true,
    };
    if has_area {
        return;
    }
    let stmts: Vec<&Stmt> = blocks.iter().flat_map(|b| b.stmts.iter()).collect();
    let span = stmts
        .iter()
        .rev()
        .find_map(|s| match s {
            Stmt::Kw(k) if matches!(k.key, "rectangle" | "disc" | "sphere" | "cylinder") => Some(k.span),
            _ => None,
        })
        .unwrap_or_else(|| blocks.first().map(|b| b.span).unwrap_or_default());
    diags.push(Diagnostic::warning(
        span,
        format!("area light '{}' has no area: it is used without its shape", l.instance),
    ));
    l.area = None;
}

/// Vertex data no renderer can use: a position that is not finite or lies beyond
/// ±[`WORLD_LIMIT`] leaves out the triangles that use it (the position is set
/// to the origin, unused); non-finite normals, texture, user, motion and derivative values
/// become zero. One warning per object, at its definition.
pub fn mesh(geometry: &mut ObjectGeometry, object: &str, span: mi::Span, diags: &mut Vec<Diagnostic>) {
    let mesh = &mut geometry.mesh;
    let limit = WORLD_LIMIT as f32;
    // Checked on all threads first (a large mesh usually has nothing to mend).
    let finite = |v: &Vec3| v.is_finite();
    if mesh.positions.par_iter().all(|p| p.is_finite() && p.abs().max_element() <= limit)
        && mesh.normals.par_iter().all(finite)
        && mesh.motion.par_iter().all(finite)
        && mesh.motion_more.iter().all(|m| m.par_iter().all(finite))
        && mesh.textures.iter().chain(&mesh.user).all(|space| space.coords.par_iter().all(finite))
        && mesh.derivatives.iter().chain(&mesh.bump_basis).flatten().all(finite)
    {
        return;
    }
    let bad: Vec<bool> = mesh.positions.iter().map(|p| !(p.is_finite() && p.abs().max_element() <= limit)).collect();
    let bad_positions = bad.iter().filter(|b| **b).count();
    let mut bad_values = 0usize;
    let mut zero = |v: &mut Vec3| {
        if !v.is_finite() {
            *v = Vec3::ZERO;
            bad_values += 1;
        }
    };
    mesh.normals.iter_mut().for_each(&mut zero);
    mesh.motion.iter_mut().for_each(&mut zero);
    mesh.motion_more.iter_mut().flatten().for_each(&mut zero);
    for space in mesh.textures.iter_mut().chain(mesh.user.iter_mut()) {
        space.coords.iter_mut().for_each(&mut zero);
    }
    for pair in mesh.derivatives.iter_mut().chain(mesh.bump_basis.iter_mut()) {
        pair.iter_mut().for_each(&mut zero);
    }
    if bad_positions == 0 && bad_values == 0 {
        return;
    }
    let mut dropped = 0usize;
    if bad_positions > 0 {
        for (p, b) in mesh.positions.iter_mut().zip(&bad) {
            if *b {
                *p = Vec3::ZERO;
            }
        }
        let keep: Vec<bool> =
            mesh.triangles.iter().map(|t| t.iter().all(|&v| !bad.get(v as usize).copied().unwrap_or(true))).collect();
        dropped = keep.iter().filter(|k| !**k).count();
        if dropped > 0 {
            // Lone triangles' face ids follow their index: kept with the triangles.
            mesh.materialize_ptex_triangles();
        }
        let mut i = 0;
        mesh.triangles.retain(|_| {
            i += 1;
            keep[i - 1]
        });
        if mesh.triangle_slots.len() == keep.len() {
            let mut i = 0;
            mesh.triangle_slots.retain(|_| {
                i += 1;
                keep[i - 1]
            });
        }
        if mesh.ptex_quads.len() == keep.len() {
            let mut i = 0;
            mesh.ptex_quads.retain(|_| {
                i += 1;
                keep[i - 1]
            });
        }
    }
    diags.push(Diagnostic::warning(
        span,
        format!(
            "object '{object}': {bad_positions} vertex positions are not finite or lie beyond ±{:e} ({dropped} \
             triangles using them are left out) and {bad_values} other vertex values are not finite (zero is used)",
            WORLD_LIMIT
        ),
    ));
}
