//! How finely a free-form surface is tessellated: the `approximate surface …` statement
//! read into a [`Plan`], and the plan turned into the parameter values of a grid.
//!
//! - `parametric u v`: each patch (polynomial piece) is cut into `u·degree` × `v·degree`
//!   equal parts (rounded up, at least 1), as mental ray's manual describes.
//! - `regular parametric u v`: the whole surface into `u` × `v` equal parts.
//! - `length l`, `distance d`, `angle a` (also `spatial l`, `curvature d a`, `fine …`):
//!   mental ray refines recursively until every criterion holds; mira instead picks one
//!   uniform grid meant to meet them, measured on a sampled surface: along each
//!   iso-parameter line of length `L` whose chord directions turn by `Θ` in all, `N`
//!   equal parts give edges of about `L/N`, sags of about `L·Θ/(8N²)` (a circular arc)
//!   and turns of `Θ/N`, so `N = max(⌈L/l⌉, ⌈√(LΘ/8d)⌉, ⌈Θ/a⌉)` (with `any`: the
//!   smallest of those given), bounded by the `min`/`max` subdivision levels
//!   (`2^level` parts per patch; defaults 0 and [`DEFAULT_MAX_LEVEL`]).
//! - `view` (criteria in raster pixels): the camera is not known when objects are
//!   tessellated, so the length and distance criteria are dropped and the angle criterion
//!   (given, or [`VIEW_ANGLE_DEGREES`]) alone decides.
//! - anything else (`implicit`, percentages, `grid`/`tree`/`delaunay` alone): the
//!   default, `parametric` [`DEFAULT_PARAMETRIC`].

use mi::ast::{ApproxTerm, Approximation};

/// The `parametric` factor used without an approximation statement.
pub const DEFAULT_PARAMETRIC: f64 = 2.0;

/// Highest recursion level (`2^level` parts per patch) of the length/distance/angle
/// criteria when no `max` is given.
pub const DEFAULT_MAX_LEVEL: u32 = 6;

/// The angle criterion, degrees, of view-dependent approximations.
pub const VIEW_ANGLE_DEGREES: f64 = 10.0;

/// Most parts one direction may be cut into.
pub const MAX_PARTS: usize = 4096;

/// A tessellation plan.
#[derive(Clone, Debug, PartialEq)]
pub enum Plan {
    /// `parametric u v`: per patch, factor × degree parts.
    PerPatch(f64, f64),
    /// `regular parametric u v`: parts of the whole surface.
    Regular(usize, usize),
    /// Geometric criteria, object space.
    Criteria(Criteria),
}

/// The length / distance / angle criteria (object space; angle in radians).
#[derive(Clone, Debug, PartialEq)]
pub struct Criteria {
    /// Longest edge.
    pub length: Option<f64>,
    /// Largest distance of the surface from the triangles.
    pub distance: Option<f64>,
    /// Largest turn of the surface across one edge, radians.
    pub angle: Option<f64>,
    /// Stop when any criterion holds (`any`) rather than all.
    pub any: bool,
    /// Least subdivision level.
    pub min_level: u32,
    /// Greatest subdivision level.
    pub max_level: u32,
}

impl Default for Plan {
    fn default() -> Plan {
        Plan::PerPatch(DEFAULT_PARAMETRIC, DEFAULT_PARAMETRIC)
    }
}

impl Plan {
    /// The plan an approximation statement asks for; `None` when mira cannot follow it
    /// (the caller uses the default).
    pub fn from_approximation(a: &Approximation) -> Option<Plan> {
        let t = &a.technique;
        if t.contains(&ApproxTerm::Percent) {
            return None;
        }
        let word = |w: &str| t.iter().position(|x| *x == ApproxTerm::Word(leak(w)));
        let num_at = |i: usize| match t.get(i) {
            Some(ApproxTerm::Num(n)) => Some(n.as_f64()).filter(|x| x.is_finite()),
            _ => None,
        };
        let nums_after = |i: usize| {
            let mut v = Vec::new();
            let mut k = i + 1;
            while let Some(x) = num_at(k) {
                v.push(x);
                k += 1;
            }
            v
        };
        if let Some(p) = word("parametric") {
            let n = nums_after(p);
            let u = *n.first()?;
            let v = n.get(1).copied().unwrap_or(u);
            return Some(if word("regular").is_some() {
                let parts = |x: f64| (x.round().max(1.0) as usize).min(MAX_PARTS);
                Plan::Regular(parts(u), parts(v))
            } else {
                Plan::PerPatch(u.max(0.0), v.max(0.0))
            });
        }
        let view = word("view").is_some();
        let mut c = Criteria {
            length: None,
            distance: None,
            angle: None,
            any: word("any").is_some(),
            min_level: 0,
            max_level: DEFAULT_MAX_LEVEL,
        };
        let mut levels = Vec::new();
        for (key, is_length) in [("length", true), ("spatial", true)] {
            if let Some(i) = word(key) {
                let n = nums_after(i);
                c.length = n.first().copied().filter(|&x| x > 0.0 && is_length);
                levels.extend(n.into_iter().skip(1));
            }
        }
        if let Some(i) = word("distance") {
            let n = nums_after(i);
            c.distance = n.first().copied().filter(|&x| x > 0.0);
            levels.extend(n.into_iter().skip(1));
        }
        if let Some(i) = word("curvature") {
            let n = nums_after(i);
            c.distance = n.first().copied().filter(|&x| x > 0.0);
            c.angle = n.get(1).copied().filter(|&x| x > 0.0).map(f64::to_radians);
            levels.extend(n.into_iter().skip(2));
        }
        if let Some(i) = word("angle") {
            let n = nums_after(i);
            c.angle = n.first().copied().filter(|&x| x > 0.0).map(f64::to_radians);
            levels.extend(n.into_iter().skip(1));
        }
        if levels.len() >= 2 {
            c.min_level = levels[0].clamp(0.0, 12.0) as u32;
            c.max_level = levels[1].clamp(0.0, 12.0) as u32;
        }
        if let Some(x) = word("min").and_then(|i| num_at(i + 1)) {
            c.min_level = x.clamp(0.0, 12.0) as u32;
        }
        if let Some(x) = word("max").and_then(|i| num_at(i + 1)) {
            c.max_level = x.clamp(0.0, 12.0) as u32;
        }
        c.max_level = c.max_level.max(c.min_level);
        if view {
            c.length = None;
            c.distance = None;
            c.angle = c.angle.or(Some(VIEW_ANGLE_DEGREES.to_radians()));
        }
        (c.length.is_some() || c.distance.is_some() || c.angle.is_some()).then_some(Plan::Criteria(c))
    }
}

/// The technique words are `&'static str`s from the parser's table; comparing needs the
/// same type.
fn leak(w: &str) -> &'static str {
    match w {
        "parametric" => "parametric",
        "regular" => "regular",
        "view" => "view",
        "any" => "any",
        "length" => "length",
        "spatial" => "spatial",
        "distance" => "distance",
        "curvature" => "curvature",
        "angle" => "angle",
        "min" => "min",
        "max" => "max",
        _ => "",
    }
}

/// Parts for one direction under criteria, from the longest iso-line length `length` and
/// the largest total turn `turn` (radians) measured along that direction, and `patches`
/// pieces.
pub fn criteria_parts(c: &Criteria, length: f64, turn: f64, patches: usize) -> usize {
    let mut wanted: Vec<f64> = Vec::new();
    if let Some(l) = c.length {
        wanted.push((length / l).ceil());
    }
    if let Some(d) = c.distance {
        wanted.push((length * turn / (8.0 * d)).sqrt().ceil());
    }
    if let Some(a) = c.angle {
        wanted.push((turn / a).ceil());
    }
    let n = if c.any {
        wanted.iter().copied().fold(f64::INFINITY, f64::min)
    } else {
        wanted.iter().copied().fold(1.0, f64::max)
    };
    let lo = (patches << c.min_level.min(12)).max(1) as f64;
    let hi = (patches << c.max_level.min(12)) as f64;
    let n = if n.is_finite() { n } else { 1.0 };
    (n.clamp(lo, hi.max(lo)) as usize).min(MAX_PARTS)
}

/// Parameter values cutting each patch (`breaks` windows) into `per_patch` equal parts.
pub fn per_patch_samples(breaks: &[f64], per_patch: usize) -> Vec<f64> {
    let n = per_patch.max(1);
    let mut out = vec![breaks[0]];
    for w in breaks.windows(2) {
        out.extend((1..=n).map(|k| w[0] + (w[1] - w[0]) * k as f64 / n as f64));
    }
    out
}

/// `parts + 1` equally spaced values from `lo` to `hi`.
pub fn uniform_samples(lo: f64, hi: f64, parts: usize) -> Vec<f64> {
    let n = parts.max(1);
    (0..=n).map(|k| if k == n { hi } else { lo + (hi - lo) * k as f64 / n as f64 }).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(text: &str) -> Option<Plan> {
        let src = format!("object \"o\" group 0 0 0 v 0 {text} end group end object");
        let parsed = mi::parse_str("a.mi", &src);
        let mi::ast::Item::Object(o) = &parsed.items[0] else { panic!("an object") };
        let mi::ast::Geometry::Group(g) = &o.geometry[0] else { panic!("a group") };
        let Some(mi::ast::GroupItem::Approximate(a)) = g.items.last() else { panic!("{:?}", g.items) };
        Plan::from_approximation(a)
    }

    #[test]
    fn techniques_are_read() {
        assert_eq!(plan("approximate surface parametric 3 2 \"s\""), Some(Plan::PerPatch(3.0, 2.0)));
        assert_eq!(plan("approximate surface regular parametric 8 \"s\""), Some(Plan::Regular(8, 8)));
        let Some(Plan::Criteria(c)) = plan("approximate surface length 0.1 1 4 \"s\"") else { panic!() };
        assert_eq!((c.length, c.min_level, c.max_level), (Some(0.1), 1, 4));
        let Some(Plan::Criteria(c)) = plan("approximate surface view length 2 \"s\"") else { panic!() };
        assert_eq!(c.length, None);
        assert!((c.angle.unwrap() - VIEW_ANGLE_DEGREES.to_radians()).abs() < 1e-12);
        assert_eq!(plan("approximate surface regular parametric 50% 50% \"s\""), None);
    }

    #[test]
    fn criteria_meet_the_arc_formulas() {
        // A unit circle: L = 2π, Θ = 2π. Distance 0.01 → sag 1/(2N²)·π² ≤ 0.01 → N ≥ 22.2.
        let c = Criteria { length: None, distance: Some(0.01), angle: None, any: false, min_level: 0, max_level: 10 };
        let n = criteria_parts(&c, std::f64::consts::TAU, std::f64::consts::TAU, 4);
        assert_eq!(n, 23);
        let sag = 1.0 - (std::f64::consts::PI / n as f64).cos();
        assert!(sag <= 0.01, "sag {sag}");
        let c = Criteria { angle: Some(10f64.to_radians()), distance: None, ..c };
        assert_eq!(criteria_parts(&c, std::f64::consts::TAU, std::f64::consts::TAU, 4), 36);
    }
}
