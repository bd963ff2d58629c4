//! How finely a displaced object is subdivided: its `approximate displace …` statement (or
//! the options' `… all`) read into a [`Plan`].
//!
//! mental ray's manual (approximations; displacement-mapped polygons): the `parametric`
//! technique splits each triangle a fixed number of times; every other technique takes
//! the displacement into account and subdivides "until the given criterion or combination
//! of them is satisfied or the maximum subdivision level is reached":
//!
//! - `length l`: no edge of the displaced triangles longer than `l` (object space; with
//!   `view`, in raster space, units of pixel diagonals); `spatial [view] l` is the same;
//! - `distance d`: the displacements of an edge's two vertices differ by less than `d`
//!   (with `view`: pixel diagonals);
//! - `angle a`: two displaced triangles meet at an edge under less than `a` degrees;
//! - `curvature d a`: `distance d angle a`;
//! - `any`: subdivision stops where any one criterion holds (else all must hold);
//! - `fine`: mental ray's fine approximation, length-based: the same criteria applied to
//!   the displaced micro-triangles, which mira's criteria always measure;
//! - the two numbers after the criteria are the least and greatest subdivision levels
//!   (each level halves the edges it splits; default 0 and [`DEFAULT_MAX_LEVEL`]);
//!   `max n` (the keyword) bounds the object's triangles: refinement stops before the
//!   level that would pass `n`.
//!
//! `sharp s` does not change which triangles are made: it sets how the displaced
//! surface's shading normals lean from the smooth interpolated vertex normals (0) to the
//! faceted geometric normals of the fine triangles (1), blending in between
//! ([`sharpness`], applied by [`crate::mesh::MeshData::sharpen`]). `nosmoothing` and
//! `tree` (the style mira's edge splitting is) are read as written, without effect.
//! `grid`, `delaunay`, `grading` and `offscreen` are read with a warning that says why
//! they change nothing here ([`unused`]):
//!
//! - `grading g` is the minimum-angle bound of mental ray's graded (Delaunay) meshing:
//!   mental ray's scene-database record of an approximation (`miApprox`, in the
//!   `shader.h` its shader SDK ships) keeps it as `grading`, "min angle bound for graded
//!   meshing", beside the style `miAPPROX_STYLE_DELAUNAY`; mira's displacement makes no
//!   Delaunay mesh (it splits edges, the `tree` style), so no bound on angles applies.
//!   A value no triangle can meet (negative, 60° or more: a triangle's angles sum to
//!   180°) is named in the warning.
//! - `offscreen`: the manual pages at hand list no meaning for it, and `miApprox` has no
//!   field for it (criteria, `sharp`, ray flags, `any`, `view`, method, style, levels,
//!   `max`, `grading`); `view` criteria measure every edge by its depth, inside the view
//!   or outside it, as mental ray's manual gives the measure ("as if the surface was
//!   parallel to the screen", so that a surface seen in a mirror stays well approximated).

use mi::ast::{ApproxTerm, Approximation};

/// The greatest subdivision level of the criteria techniques when the statement gives
/// none (3ds Max's mental ray displacement "Max. Level" default).
pub const DEFAULT_MAX_LEVEL: u32 = 6;

/// The greatest subdivision level mira accepts (each level can split every edge in two:
/// 4^16 triangles from one); higher levels are lowered with a warning.
pub const MAX_LEVEL: u32 = 16;

/// A subdivision plan.
#[derive(Clone, Debug, PartialEq)]
pub enum Plan {
    /// Each triangle split into 4^level (`parametric level`).
    Uniform(u32),
    /// Adaptive refinement under criteria.
    Adaptive(Criteria),
}

/// The refinement criteria of an adaptive plan.
#[derive(Clone, Debug, PartialEq)]
pub struct Criteria {
    /// Longest displaced edge (object space, or pixel diagonals with `view`).
    pub length: Option<f32>,
    /// Largest difference of the displacements of an edge's vertices (same units).
    pub distance: Option<f32>,
    /// Largest angle between the displaced triangles meeting at an edge, radians.
    pub angle: Option<f32>,
    /// `length` and `distance` are measured in raster space (pixel diagonals).
    pub view: bool,
    /// Refinement of an edge stops when any criterion holds (else when all hold).
    pub any: bool,
    /// Levels every edge is split for regardless of the criteria.
    pub min_level: u32,
    /// Most levels an edge is split for.
    pub max_level: u32,
    /// Most triangles the object may have (`max n`).
    pub max_triangles: Option<usize>,
}

/// What a statement asks for: the plan, or why there is none.
#[derive(Clone, Debug, PartialEq)]
pub enum Reading {
    /// A plan, with warnings about values mira changed.
    Plan(Plan, Vec<String>),
    /// A technique mira does not implement (its words, for the message).
    Unsupported(String),
    /// A value no plan can follow (the message).
    Invalid(String),
}

/// Reads the approximation `a`.
pub fn read(a: &Approximation) -> Reading {
    // `view` may stand between a word and its numbers (`spatial view 0.25`): read apart.
    let view = a.technique.contains(&ApproxTerm::Word("view"));
    let t: Vec<ApproxTerm> = a.technique.iter().copied().filter(|x| *x != ApproxTerm::Word("view")).collect();
    let word_at = |w: &str| t.iter().position(|x| matches!(x, ApproxTerm::Word(y) if *y == w));
    let num = |i: usize| match t.get(i) {
        Some(ApproxTerm::Num(n)) => Some(n.as_f64()),
        _ => None,
    };
    if t.contains(&ApproxTerm::Percent) {
        return Reading::Unsupported(words(a));
    }
    if let Some(p) = word_at("parametric") {
        return match num(p + 1) {
            Some(n) if n.is_finite() => {
                Reading::Plan(Plan::Uniform(n.max(0.0).floor().min(u32::MAX as f64) as u32), vec![])
            }
            _ => Reading::Unsupported(words(a)),
        };
    }
    // Numbers each word takes; numbers no word takes are the min and max levels.
    let arity = |w: &str| match w {
        "length" | "spatial" | "distance" | "angle" | "sharp" | "grading" | "samples" | "min" | "max" => 1,
        "curvature" => 2,
        _ => 0,
    };
    let mut values: Vec<(&str, f64)> = Vec::new();
    let mut levels: Vec<f64> = Vec::new();
    let mut i = 0;
    while i < t.len() {
        match t[i] {
            ApproxTerm::Word(w) => {
                let k = arity(w);
                for j in 0..k {
                    match num(i + 1 + j) {
                        Some(x) => values.push((if w == "curvature" && j == 1 { "curvature angle" } else { w }, x)),
                        None => return Reading::Invalid(format!("'{w}' needs {k} number(s)")),
                    }
                }
                i += 1 + k;
            }
            ApproxTerm::Num(n) => {
                levels.push(n.as_f64());
                i += 1;
            }
            ApproxTerm::Percent => i += 1,
        }
    }
    let mut c = Criteria {
        length: None,
        distance: None,
        angle: None,
        view,
        any: word_at("any").is_some(),
        min_level: 0,
        max_level: DEFAULT_MAX_LEVEL,
        max_triangles: None,
    };
    let mut warnings = Vec::new();
    for (w, x) in values {
        let positive = |what: &str| -> Result<f32, String> {
            if x.is_finite() && x > 0.0 {
                Ok(x as f32)
            } else {
                Err(format!("{what} {x} must be a positive number"))
            }
        };
        let r = match w {
            "length" | "spatial" => positive(w).map(|v| c.length = Some(v)),
            "distance" | "curvature" => positive("distance").map(|v| c.distance = Some(v)),
            "angle" | "curvature angle" => positive("angle").map(|v| c.angle = Some(v.to_radians())),
            "max" => positive("max").map(|v| c.max_triangles = Some(v.min(usize::MAX as f32) as usize)),
            _ => Ok(()),
        };
        if let Err(e) = r {
            return Reading::Invalid(e);
        }
    }
    if c.length.is_none() && c.distance.is_none() && c.angle.is_none() {
        return Reading::Unsupported(words(a));
    }
    if levels.len() > 2 {
        return Reading::Invalid(format!("{} numbers where the least and greatest level are expected", levels.len()));
    }
    if let [lo, hi] = levels[..] {
        for x in [lo, hi] {
            if !x.is_finite() || x < 0.0 {
                return Reading::Invalid(format!("subdivision level {x} must be 0 or more"));
            }
        }
        let clamp = |x: f64, warnings: &mut Vec<String>| {
            if x > MAX_LEVEL as f64 {
                warnings.push(format!("subdivision level {x} lowered to {MAX_LEVEL}"));
            }
            x.min(MAX_LEVEL as f64) as u32
        };
        c.min_level = clamp(lo, &mut warnings);
        c.max_level = clamp(hi, &mut warnings);
        if c.min_level > c.max_level {
            warnings
                .push(format!("least level {} above the greatest {}: the greatest is used", c.min_level, c.max_level));
            c.min_level = c.max_level;
        }
    } else if levels.len() == 1 {
        return Reading::Invalid("one level where the least and greatest are expected".to_string());
    }
    Reading::Plan(Plan::Adaptive(c), warnings)
}

/// The `sharp s` of an approximation: `None` where it gives none, else s clamped to 0…1,
/// with a warning where the value was outside (or not a number: then 0, smooth).
pub fn sharpness(a: &Approximation) -> (Option<f32>, Option<String>) {
    let Some(i) = a.technique.iter().position(|t| *t == ApproxTerm::Word("sharp")) else {
        return (None, None);
    };
    match a.technique.get(i + 1) {
        Some(ApproxTerm::Num(n)) => {
            let x = n.as_f64();
            if (0.0..=1.0).contains(&x) {
                (Some(x as f32), None)
            } else {
                let s = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
                (Some(s as f32), Some(format!("sharp {x} is outside 0…1; {s} is used")))
            }
        }
        _ => (None, None),
    }
}

/// What mira says about the words of `a` it reads without effect (`grid`, `delaunay`,
/// `grading g`, `offscreen`; see the module's documentation): one warning each, the
/// word first.
pub fn unused(a: &Approximation) -> Vec<String> {
    let t = &a.technique;
    let has = |w: &'static str| t.contains(&ApproxTerm::Word(w));
    let mut out = Vec::new();
    for style in ["grid", "delaunay"] {
        if has(style) {
            out.push(format!(
                "'{style}' has no effect: displaced triangles are refined by splitting their edges (the 'tree' style)"
            ));
        }
    }
    if let Some(i) = t.iter().position(|x| *x == ApproxTerm::Word("grading")) {
        let g = match t.get(i + 1) {
            Some(ApproxTerm::Num(n)) => n.as_f64(),
            _ => f64::NAN,
        };
        let bad = if (0.0..60.0).contains(&g) {
            String::new()
        } else {
            format!(" (and {g} is no angle every triangle can keep: 0 ≤ g < 60 degrees)")
        };
        out.push(format!(
            "'grading {g}' has no effect: it bounds the angles of mental ray's Delaunay meshing (miApprox.grading, \
             \"min angle bound for graded meshing\", mental ray's shader.h), and displaced triangles are refined by \
             splitting their edges{bad}"
        ));
    }
    if has("offscreen") {
        out.push(
            "'offscreen' has no effect: mental ray's approximation record (miApprox, shader.h) has no field for it and \
             the manual pages at hand do not describe it; 'view' criteria measure every edge by its depth, inside the \
             view or not"
                .to_string(),
        );
    }
    out
}

/// The technique words of an approximation (`view length`, `fine`, …), for messages.
pub fn words(a: &Approximation) -> String {
    let words: Vec<&str> =
        a.technique.iter().filter_map(|t| if let ApproxTerm::Word(w) = t { Some(*w) } else { None }).collect();
    if words.is_empty() {
        "(no technique)".to_string()
    } else {
        words.join(" ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plan of the technique `text` (words, numbers and `%` separated by blanks).
    fn reading(text: &str) -> Reading {
        read(&approximation(text))
    }

    /// The `approximate displace … all` statement of the technique `text`.
    fn approximation(text: &str) -> Approximation {
        let technique = text
            .split_whitespace()
            .map(|w| match w.trim_end_matches('%').parse::<f64>() {
                Ok(_) if w.ends_with('%') => ApproxTerm::Percent,
                Ok(x) => ApproxTerm::Num(mi::ast::Num::Float(x)),
                Err(_) => ApproxTerm::Word(Box::leak(w.to_string().into_boxed_str())),
            })
            .collect();
        Approximation {
            flags: vec![],
            target: Some("displace"),
            technique,
            names: vec![],
            all: true,
            span: Default::default(),
        }
    }

    /// Maya's forms read into their criteria: `fine view length 0.5 sharp 0.83 0 5`
    /// (view, length 0.5, levels 0…5, sharp 0.833333 read apart), `length 0.1 distance 0.01 angle 5 any
    /// 1 4`, `spatial view 0.25 0 4 max 500000`, `curvature 0.1 10`; parametric stays
    /// uniform; percentages and a missing criterion are unsupported; a zero or negative
    /// length, a negative level are invalid; a level of 40 is lowered to 16 with a warning.
    #[test]
    fn statements_read_into_plans() {
        let Reading::Plan(Plan::Adaptive(c), w) = reading("fine view length 0.5 sharp 0.833333 0 5") else { panic!() };
        assert!(w.is_empty());
        assert_eq!((c.length, c.view, c.min_level, c.max_level, c.any), (Some(0.5), true, 0, 5, false));
        let Reading::Plan(Plan::Adaptive(c), _) = reading("length 0.1 distance 0.01 angle 5 any 1 4") else { panic!() };
        assert_eq!((c.length, c.distance, c.any, c.min_level, c.max_level), (Some(0.1), Some(0.01), true, 1, 4));
        assert!((c.angle.unwrap() - 5f32.to_radians()).abs() < 1e-7);
        let Reading::Plan(Plan::Adaptive(c), _) = reading("spatial view 0.25 0 4 max 500000") else { panic!() };
        assert_eq!((c.length, c.view, c.max_level, c.max_triangles), (Some(0.25), true, 4, Some(500000)));
        let Reading::Plan(Plan::Adaptive(c), _) = reading("curvature 0.1 10") else { panic!() };
        assert_eq!((c.distance, c.max_level), (Some(0.1), DEFAULT_MAX_LEVEL));
        assert!(c.angle.is_some());
        assert_eq!(reading("regular parametric 3"), Reading::Plan(Plan::Uniform(3), vec![]));
        assert!(matches!(reading("regular parametric 50% 50%"), Reading::Unsupported(_)));
        assert!(matches!(reading("fine sharp 0.5 0 5"), Reading::Unsupported(_)));
        for bad in ["length 0 0 5", "length -1 0 5", "view length 0.5 -1 5", "angle -3"] {
            assert!(matches!(reading(bad), Reading::Invalid(_)), "{bad}");
        }
        let (sharp, w) = sharpness(&approximation("fine view length 0.5 sharp 0.833333 0 5"));
        assert_eq!((sharp, w), (Some(0.833333), None));
        assert_eq!(sharpness(&approximation("length 0.5 0 5")), (None, None));
        let (sharp, w) = sharpness(&approximation("fine length 0.5 sharp 3 0 5"));
        assert!(sharp == Some(1.0) && w.is_some());
        let said = unused(&approximation("fine view offscreen length 0.5 grading 2 0 5"));
        assert!(
            said.len() == 2 && said[0].starts_with("'grading 2'") && said[1].starts_with("'offscreen'"),
            "{said:?}"
        );
        for (g, bad) in [("30", false), ("0", false), ("-5", true), ("60", true), ("75", true)] {
            let said = unused(&approximation(&format!("delaunay length 0.5 grading {g} 0 5")));
            assert_eq!(said.len(), 2, "{said:?}");
            assert!(said[0].starts_with("'delaunay'"), "{said:?}");
            assert_eq!(said[1].contains("no angle every triangle can keep"), bad, "{g}: {said:?}");
        }
        let Reading::Plan(Plan::Adaptive(c), w) = reading("length 0.5 0 40") else { panic!() };
        assert_eq!(c.max_level, MAX_LEVEL);
        assert_eq!(w.len(), 1, "{w:?}");
    }
}
