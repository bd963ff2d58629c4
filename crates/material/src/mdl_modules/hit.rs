//! Expressions of a module material that depend on the shading point, compiled once per
//! material instance into a small tree ([`HitExpr`]) that the path engine evaluates at
//! every hit without parsing or allocating.
//!
//! Values are four lanes of `f32` (`Vec4`): a colour or `float3` uses x, y, z; a scalar
//! (`float`, `int`, `bool` as 0/1) is the same number in all four lanes, so that scalars
//! and vectors combine lane by lane without conversions. Every node whose operands are
//! constants is folded when it is built ([`fold`]): what does not depend on the hit is
//! computed once, and a material without hit-dependent parts compiles to constants.
//!
//! Hostile modules: a tree is refused before it is first evaluated ([`too_costly`]) when
//! one evaluation would visit more than [`MAX_HIT_NODES`] nodes (a `let` used twice is
//! shared, not copied, but evaluated twice: forty chained lets each used twice took 2^40
//! visits a hit) or recurse deeper than [`MAX_HIT_DEPTH`]; and values that come out NaN
//! or infinite (a division by zero, `sqrt` or `log` of a negative number) are read as 0
//! where the material uses them ([`HitExpr::eval_finite`]), as non-finite texels are.

use std::collections::HashMap;
use std::sync::Arc;

use glam::{Mat4, Vec4};
use shader::texture::Texture;
use shader::State;

use super::hit_loop::{HitLoop, MAX_LOOP_STEPS};
use super::procedural::Pattern;
use super::ptex::Ptex;
use super::sky_model::SkyCall;
use super::texture_3d::Volume;
use super::texture_cube::CubeMap;

mod eval;

/// A value of the shading state (MDL's `::state` functions; world space, scene units).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StateFn {
    /// `state::position()`: the hit point.
    Position,
    /// `state::normal()`: the shading normal, facing the ray.
    Normal,
    /// `state::geometry_normal()`: the geometric normal, facing the ray.
    GeometryNormal,
    /// `state::direction()`: the direction of the ray that hit (towards the point).
    Direction,
    /// `state::motion()`.
    Motion,
    /// `state::texture_coordinate(i)`.
    TextureCoordinate(u8),
    /// `state::texture_tangent_u(i)` (the surface tangents of the first texture space).
    TangentU,
    /// `state::texture_tangent_v(i)`.
    TangentV,
    /// The hit point in object space (`base::coordinate_source` object coordinates).
    ObjectPosition,
    /// The object's x axis in world space, unit.
    ObjectAxisX,
    /// The object's y axis in world space, unit.
    ObjectAxisY,
    /// The object's z axis in world space, unit.
    ObjectAxisZ,
    /// Column `i` of the hit instance's object-to-world matrix at the ray's time (0–2 the
    /// images of the object's axes, not normalized; 3 the translation; world units).
    ObjectToWorld(u8),
    /// Column `i` of its world-to-object matrix (object units).
    WorldToObject(u8),
    /// `state::animation_time()`: the ray's shutter time.
    Time,
    /// `state::object_id()`: the hit instance's label (mental ray's `tag`).
    ObjectId,
}

/// A unary operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnOp {
    /// `-x`.
    Neg,
    /// `!x` (0 → 1, else 0).
    Not,
}

/// A binary operator, lane by lane (comparisons and logic give 0 or 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `*`.
    Mul,
    /// `/`.
    Div,
    /// `%` (sign of the dividend, as C's `fmod`).
    Rem,
    /// `<`.
    Lt,
    /// `<=`.
    Le,
    /// `>`.
    Gt,
    /// `>=`.
    Ge,
    /// `==` (all lanes).
    Eq,
    /// `!=` (any lane).
    Ne,
    /// `&&`.
    And,
    /// `||`.
    Or,
}

/// A `::math` function (or a helper of the `::base` and `::tex` lowerings). Functions of a
/// vector's lanes carry how many lanes the vector has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MathFn {
    /// `min(a, b)`.
    Min,
    /// `max(a, b)`.
    Max,
    /// `clamp(a, lo, hi)`.
    Clamp,
    /// `saturate(a)`.
    Saturate,
    /// `lerp(a, b, t)`.
    Lerp,
    /// `step(edge, x)`.
    Step,
    /// `smoothstep(a, b, x)`.
    Smoothstep,
    /// `sqrt`.
    Sqrt,
    /// `exp`.
    Exp,
    /// `exp2`.
    Exp2,
    /// `log` (natural).
    Log,
    /// `log2`.
    Log2,
    /// `log10`.
    Log10,
    /// `pow(a, b)`.
    Pow,
    /// `abs`.
    Abs,
    /// `sign`.
    Sign,
    /// `floor`.
    Floor,
    /// `ceil`.
    Ceil,
    /// `round`.
    Round,
    /// Towards zero (integer division).
    Trunc,
    /// `frac` (x − floor x).
    Frac,
    /// `fmod(a, b)`.
    Fmod,
    /// `sin`.
    Sin,
    /// `cos`.
    Cos,
    /// `tan`.
    Tan,
    /// `asin`.
    Asin,
    /// `acos`.
    Acos,
    /// `atan`.
    Atan,
    /// `atan2(y, x)`.
    Atan2,
    /// `radians`.
    Radians,
    /// `degrees`.
    Degrees,
    /// `dot(a, b)` of n lanes.
    Dot(u8),
    /// `length` of n lanes.
    Length(u8),
    /// `distance(a, b)` of n lanes.
    Distance(u8),
    /// `normalize` of n lanes.
    Normalize(u8),
    /// `cross` of two `float3`.
    Cross,
    /// `luminance` of a colour (Rec. 709 weights).
    Luminance,
    /// `blackbody` of a temperature in kelvin (lane x): the colour of luminance 1
    /// ([`super::spectral::blackbody_rgb`]).
    Blackbody,
    /// `average` of n lanes.
    Average(u8),
    /// `max_value` of n lanes.
    MaxValue(u8),
    /// `min_value` of n lanes.
    MinValue(u8),
    /// `base::mono_mode` of a texel (RGBA): `mono_alpha`, `_average`, `_luminance`,
    /// `_maximum`, by the enumerator's name.
    Mono(&'static str),
    /// `base::blend_color_layers`' blend of a layer (b) over the colour so far (a) with
    /// weight c (clamped to [0, 1]), by `color_layer_mode`'s enumerator name
    /// ([`mdl::texture::blend_layer`]).
    Blend(&'static str),
    /// `base::coordinate_projection`'s coordinate (u, v, 0) by projection mode of a point
    /// (a), shading normal (b) and geometric normal (c) in the projector's space
    /// ([`super::projection::coordinate`]).
    Project(u8),
    /// The direction in the projector's space along which a projection's u (lane 0) or v
    /// (1) grows, of the same operands ([`super::projection::axis`]).
    ProjectAxis(u8, u8),
    /// The surface tangent u (0) or v (1) from the directions of u (a) and v (b) growth
    /// and the normal (c) ([`super::projection::surface_tangent`]).
    SurfaceTangent(u8),
}

/// A texture image as the expressions hold it (compared by identity).
#[derive(Clone, Debug)]
pub struct Image(pub Arc<Texture>);

impl PartialEq for Image {
    fn eq(&self, other: &Image) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl Image {
    /// The texel at integer position (x, y), y up; black outside the image. Grey images
    /// give their grey in all three colour channels, as lookups do.
    pub fn texel(&self, x: f32, y: f32) -> Vec4 {
        let Texture::Image { image, .. } = &*self.0 else { return Vec4::ZERO };
        let (w, h) = image.size();
        if !(x >= 0.0 && y >= 0.0 && (x as usize) < w && (y as usize) < h) {
            return Vec4::ZERO;
        }
        let c = image.texel(x as usize, y as usize);
        if image.channels < 3 {
            let a = if image.channels == 2 { c.y } else { 1.0 };
            return Vec4::new(c.x, c.x, c.x, a);
        }
        c
    }

    /// Width and height in texels (0 × 0 for a texture that could not be read).
    pub fn size(&self) -> (usize, usize) {
        match &*self.0 {
            Texture::Image { image, .. } => image.size(),
            _ => (0, 0),
        }
    }
}

/// An expression over the shading point. Two expressions are equal (`==`) when they
/// compute the same thing node for node; shared subexpressions are compared once
/// ([`super::hit_eq`]).
#[derive(Clone, Debug)]
pub enum HitExpr {
    /// A constant.
    Const(Vec4),
    /// A value of the state.
    State(StateFn),
    /// A unary operator.
    Unary(UnOp, Arc<HitExpr>),
    /// A binary operator.
    Binary(BinOp, Arc<HitExpr>, Arc<HitExpr>),
    /// `c ? a : b` (c's x lane).
    Select(Arc<HitExpr>, Arc<HitExpr>, Arc<HitExpr>),
    /// A function of the operands.
    Math(MathFn, Box<[Arc<HitExpr>]>),
    /// Lane `i` of a vector, as a scalar.
    Lane(Arc<HitExpr>, u8),
    /// A vector built from parts: each part gives its first `width` lanes, in order.
    Compose(Box<[(Arc<HitExpr>, u8)]>),
    /// A point (w = 1, divided by the result's w) or direction (3×3 part, normalized)
    /// through a 4×4 matrix.
    Transform {
        /// The matrix (MDL's column-vector convention).
        matrix: Mat4,
        /// What is transformed.
        of: Arc<HitExpr>,
        /// A point, else a direction.
        point: bool,
    },
    /// The RGBA texel of a 2D texture at a coordinate's x and y, with MDL's wrap modes
    /// (by enumerator name) per axis; black outside [0, 1)² when `clip`.
    Lookup {
        /// The texture.
        image: Image,
        /// The coordinate.
        coord: Arc<HitExpr>,
        /// `wrap_u`, `wrap_v`.
        wrap: [&'static str; 2],
        /// `clip`.
        clip: bool,
        /// `crop_u` and `crop_v`: the part of the image [0, 1)² maps to (u0, u1, v0, v1).
        crop: [f32; 4],
    },
    /// The RGBA texel at the integer position of a coordinate's x and y (`tex::texel_*`;
    /// (0, 0) the lower left texel; black outside the image).
    Texel {
        /// The texture.
        image: Image,
        /// The texel position (lanes x and y, rounded down).
        coord: Arc<HitExpr>,
    },
    /// The RGBA value of a `texture_3d` at a coordinate's x, y, z with MDL's wrap modes (by
    /// enumerator name) and crops per axis ([`Volume::lookup`]).
    Lookup3d {
        /// The volume.
        volume: Arc<Volume>,
        /// The coordinate.
        coord: Arc<HitExpr>,
        /// `wrap_u`, `wrap_v`, `wrap_w`.
        wrap: [&'static str; 3],
        /// `crop_u`, `crop_v`, `crop_w`.
        crop: [[f32; 2]; 3],
    },
    /// The voxel of a `texture_3d` at the integer position of a coordinate's x, y, z (black
    /// outside the volume).
    Texel3d {
        /// The volume.
        volume: Arc<Volume>,
        /// The voxel position (rounded down).
        coord: Arc<HitExpr>,
    },
    /// The RGBA value of a `texture_cube` towards a direction's x, y, z ([`CubeMap::lookup`]).
    LookupCube {
        /// The cube map.
        cube: Arc<CubeMap>,
        /// The direction.
        dir: Arc<HitExpr>,
    },
    /// The RGBA value of a `texture_ptex` at the hit's Ptex face (its triangle's index
    /// within its object) and barycentric coordinates, channels `channel` on
    /// ([`Ptex::lookup`]).
    LookupPtex {
        /// The texture.
        ptex: Arc<Ptex>,
        /// The first channel read.
        channel: usize,
    },
    /// A procedural pattern of `::base` at a texture-space position.
    Pattern(Arc<Pattern>, Arc<HitExpr>),
    /// A `::base` daylight environment's radiance towards a world direction (output units,
    /// lanes x, y, z; [`SkyCall::radiance`]): the operands are the direction, then the
    /// values of the call's varying parameters.
    Sky(Arc<SkyCall>, Box<[Arc<HitExpr>]>),
    /// A normal bent by the slope of a pattern's height (`::base` bump textures): the
    /// height (lane x) is differenced over `delta` along the coordinate's u and v, and
    /// the normal leans against the rise along the tangents by `factor` times those
    /// differences, then is normalized (world space).
    Bump {
        /// The height.
        height: Arc<Pattern>,
        /// Texture-space position.
        position: Arc<HitExpr>,
        /// The coordinate's u tangent (world space).
        tangent_u: Arc<HitExpr>,
        /// Its v tangent.
        tangent_v: Arc<HitExpr>,
        /// The normal bent.
        normal: Arc<HitExpr>,
        /// `factor`.
        factor: f32,
        /// The steps in u and v.
        delta: [f32; 2],
    },
    /// Slot `k` of the per-hit loops the expression is inside: a value a loop carries
    /// ([`super::hit_loop`]).
    Slot(u8),
    /// Slot `k` after the loop has run (a variable the loop assigned).
    LoopOut(Arc<HitLoop>, u8),
}

/// Builds `e`, folded to a constant when it does not depend on the hit.
pub fn fold(e: HitExpr) -> Arc<HitExpr> {
    let constant = |x: &Arc<HitExpr>| matches!(**x, HitExpr::Const(_));
    let foldable = match &e {
        HitExpr::Const(_) | HitExpr::State(_) | HitExpr::Lookup { .. } => false,
        HitExpr::Slot(_) | HitExpr::LoopOut(..) => false,
        HitExpr::Lookup3d { .. } | HitExpr::LookupCube { .. } | HitExpr::LookupPtex { .. } => false,
        HitExpr::Texel { coord, .. } | HitExpr::Texel3d { coord, .. } => constant(coord),
        HitExpr::Pattern(_, p) => constant(p),
        HitExpr::Sky(_, args) => args.iter().all(constant),
        HitExpr::Bump { position, tangent_u, tangent_v, normal, .. } => {
            constant(position) && constant(tangent_u) && constant(tangent_v) && constant(normal)
        }
        HitExpr::Unary(_, a) | HitExpr::Lane(a, _) => constant(a),
        HitExpr::Transform { of, .. } => constant(of),
        HitExpr::Binary(_, a, b) => constant(a) && constant(b),
        HitExpr::Select(c, a, b) => {
            // A constant condition picks its branch whatever the branches are.
            if let HitExpr::Const(v) = **c {
                return if v.x != 0.0 { a.clone() } else { b.clone() };
            }
            false
        }
        HitExpr::Math(_, args) => args.iter().all(constant),
        HitExpr::Compose(parts) => parts.iter().all(|(p, _)| constant(p)),
    };
    if foldable {
        Arc::new(HitExpr::Const(e.eval(&State::default())))
    } else {
        Arc::new(e)
    }
}

/// Most nodes one evaluation of a material's hit expression may visit (a shared
/// subexpression counts each time it is reached).
pub const MAX_HIT_NODES: u64 = 1 << 16;

/// Deepest hit expression evaluated ([`HitExpr::eval`] recurses once per level, on a render
/// thread's stack).
pub const MAX_HIT_DEPTH: usize = 1024;

/// Why `e` is too costly to evaluate at every hit, if it is: more than [`MAX_HIT_NODES`]
/// visits or deeper than [`MAX_HIT_DEPTH`] (see [`cost`]).
pub fn too_costly(e: &Arc<HitExpr>) -> Option<String> {
    let (visits, depth) = cost(e);
    if visits > MAX_HIT_NODES {
        Some(format!(
            "an expression that depends on the hit takes {visits} steps to evaluate, more than mira takes \
             ({MAX_HIT_NODES}; shared values count each time they are used)"
        ))
    } else if depth > MAX_HIT_DEPTH {
        Some(format!(
            "an expression that depends on the hit nests {depth} operations deep, more than mira evaluates \
             ({MAX_HIT_DEPTH})"
        ))
    } else {
        None
    }
}

/// The nodes one evaluation of `e` visits (a shared subexpression counted each time it is
/// reached; saturating) and its depth, computed without recursion, once per shared node. A
/// loop of the hit no loop is around runs once per evaluation however often its values are
/// read: each distinct one counts as its start plus [`MAX_LOOP_STEPS`] (all it may take)
/// once, and each read of it as one node.
pub fn cost(e: &Arc<HitExpr>) -> (u64, usize) {
    cost_with(e, true)
}

/// [`cost`], with loops inside others counted as their start and one turn when not
/// `budgeted` (the cost of one turn of a loop around them, whose steps count theirs as they
/// run).
pub(super) fn cost_with(e: &Arc<HitExpr>, budgeted: bool) -> (u64, usize) {
    let mut done: HashMap<*const HitExpr, (u64, usize)> = HashMap::new();
    // The loops no loop is around that the evaluation runs (once each).
    let mut once: HashMap<*const HitLoop, &HitLoop> = HashMap::new();
    let mut stack: Vec<(&HitExpr, bool)> = vec![(&**e, false)];
    while let Some((node, ready)) = stack.pop() {
        let key = std::ptr::from_ref(node);
        if done.contains_key(&key) {
            continue;
        }
        let operands = node.operands();
        if ready {
            let (mut visits, mut depth) = (1u64, 0usize);
            let counted = match node {
                HitExpr::LoopOut(l, _) if l.base == 0 => {
                    once.insert(Arc::as_ptr(l), l);
                    0
                }
                HitExpr::LoopOut(l, _) if budgeted => {
                    visits = visits.saturating_add(MAX_LOOP_STEPS);
                    l.init.len()
                }
                _ => operands.len(),
            };
            for (i, o) in operands.into_iter().enumerate() {
                let (v, d) = done.get(&Arc::as_ptr(o)).copied().unwrap_or((1, 1));
                if i < counted {
                    visits = visits.saturating_add(v);
                }
                depth = depth.max(d);
            }
            done.insert(key, (visits, depth + 1));
        } else {
            stack.push((node, true));
            stack.extend(operands.into_iter().filter(|o| !done.contains_key(&Arc::as_ptr(o))).map(|o| (&**o, false)));
        }
    }
    let (mut visits, depth) = done.get(&Arc::as_ptr(e)).copied().unwrap_or((1, 1));
    if budgeted {
        for l in once.values() {
            visits = visits.saturating_add(MAX_LOOP_STEPS);
            for i in l.init.iter() {
                visits = visits.saturating_add(done.get(&Arc::as_ptr(i)).map_or(1, |c| c.0));
            }
        }
    }
    (visits, depth)
}

impl HitExpr {
    /// The constant, if it is one.
    pub fn constant(&self) -> Option<Vec4> {
        match self {
            HitExpr::Const(v) => Some(*v),
            _ => None,
        }
    }

    /// The subexpressions this node evaluates (both branches of a `?:`).
    pub(super) fn operands(&self) -> Vec<&Arc<HitExpr>> {
        match self {
            HitExpr::Const(_) | HitExpr::State(_) | HitExpr::Slot(_) | HitExpr::LookupPtex { .. } => Vec::new(),
            HitExpr::LoopOut(l, _) => l.operands().collect(),
            HitExpr::Unary(_, a) | HitExpr::Lane(a, _) => vec![a],
            HitExpr::Transform { of, .. } => vec![of],
            HitExpr::Lookup { coord, .. } | HitExpr::Texel { coord, .. } => vec![coord],
            HitExpr::Lookup3d { coord, .. } | HitExpr::Texel3d { coord, .. } => vec![coord],
            HitExpr::LookupCube { dir, .. } => vec![dir],
            HitExpr::Pattern(_, at) => vec![at],
            HitExpr::Sky(_, args) => args.iter().collect(),
            HitExpr::Bump { position, tangent_u, tangent_v, normal, .. } => {
                vec![position, tangent_u, tangent_v, normal]
            }
            HitExpr::Binary(_, a, b) => vec![a, b],
            HitExpr::Select(c, a, b) => vec![c, a, b],
            HitExpr::Math(_, args) => args.iter().collect(),
            HitExpr::Compose(parts) => parts.iter().map(|(p, _)| p).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::eval::{math, splat};
    use super::*;
    use glam::Vec3A;

    fn c(v: f32) -> Arc<HitExpr> {
        Arc::new(HitExpr::Const(splat(v)))
    }

    #[test]
    fn constants_fold_and_hit_values_do_not() {
        let sum = fold(HitExpr::Binary(BinOp::Add, c(1.0), c(2.0)));
        assert_eq!(sum.constant(), Some(splat(3.0)));
        let uv = fold(HitExpr::State(StateFn::TextureCoordinate(0)));
        let scaled = fold(HitExpr::Binary(BinOp::Mul, uv.clone(), c(2.0)));
        assert!(scaled.constant().is_none());
        let mut s = State { tex_count: 1, ..State::default() };
        s.tex_list[0] = Vec3A::new(0.25, 0.5, 0.0);
        assert_eq!(scaled.eval(&s), Vec4::new(0.5, 1.0, 0.0, 0.0));
        // A constant condition picks its branch, even a hit-dependent one.
        assert_eq!(fold(HitExpr::Select(c(1.0), uv.clone(), c(0.0))), uv);
    }

    /// Divisions by zero, square roots and logarithms of negative numbers and overflows
    /// come out NaN or infinite from `eval` and 0 from `eval_finite`, lane by lane.
    #[test]
    fn nonfinite_results_are_read_as_zero() {
        let u = fold(HitExpr::State(StateFn::TextureCoordinate(0)));
        let mut s = State { tex_count: 1, ..State::default() };
        s.tex_list[0] = Vec3A::new(0.0, 2.0, 0.0);
        let inv = fold(HitExpr::Binary(BinOp::Div, c(1.0), u.clone()));
        assert!(inv.eval(&s).x.is_infinite());
        assert_eq!(inv.eval_finite(&s), Vec4::new(0.0, 0.5, 0.0, 0.0));
        let zero_by_zero = fold(HitExpr::Binary(BinOp::Div, u.clone(), u.clone()));
        assert!(zero_by_zero.eval(&s).x.is_nan());
        assert_eq!(zero_by_zero.eval_finite(&s).x, 0.0);
        let neg = fold(HitExpr::Unary(UnOp::Neg, u.clone()));
        for f in [MathFn::Sqrt, MathFn::Log] {
            let e = fold(HitExpr::Math(f, Box::new([fold(HitExpr::Binary(BinOp::Sub, neg.clone(), c(1.0)))])));
            assert!(!e.eval(&s).x.is_finite(), "{f:?}");
            assert_eq!(e.eval_finite(&s).x, 0.0, "{f:?}");
        }
        let huge = fold(HitExpr::Math(MathFn::Exp, Box::new([fold(HitExpr::Binary(BinOp::Mul, u, c(1000.0)))])));
        s.tex_list[0] = Vec3A::new(1.0, 0.0, 0.0);
        assert_eq!(huge.eval_finite(&s).x, 0.0);
        assert_eq!(huge.eval_finite(&s).y, 1.0);
    }

    /// Forty chained values each used twice (`b = a·a`, `c = b·b`, …) share their nodes,
    /// but an evaluation visits 2^41 − 1 of them: refused, with the count, after a walk
    /// that meets each shared node once. A deep chain is refused by its depth; a modest
    /// tree passes.
    #[test]
    fn shared_and_deep_trees_are_measured_without_recursion() {
        let mut e = fold(HitExpr::State(StateFn::Position));
        for _ in 0..40 {
            e = fold(HitExpr::Binary(BinOp::Mul, e.clone(), e));
        }
        assert_eq!(cost(&e), ((1u64 << 41) - 1, 41));
        let why = too_costly(&e).unwrap();
        assert!(why.contains("takes 2199023255551 steps to evaluate, more than mira takes (65536"), "{why}");
        let mut deep = fold(HitExpr::State(StateFn::Position));
        for _ in 0..100_000 {
            deep = Arc::new(HitExpr::Unary(UnOp::Neg, deep));
        }
        assert_eq!(cost(&deep), (100_001, 100_001));
        assert!(too_costly(&deep).is_some());
        // Dropping a tree this deep recurses too: let it go on a thread with room.
        std::thread::Builder::new().stack_size(256 << 20).spawn(move || drop(deep)).unwrap().join().unwrap();
        let mut modest = fold(HitExpr::State(StateFn::Position));
        for _ in 0..10 {
            modest = fold(HitExpr::Binary(BinOp::Mul, modest.clone(), modest));
        }
        assert_eq!(too_costly(&modest), None);
    }

    /// A loop no loop is around runs once per evaluation: ten of its values read (and a
    /// second loop starting from one of them) count its start and [`MAX_LOOP_STEPS`] once,
    /// each read as one node; a loop inside another counts its start at each read.
    #[test]
    fn a_loop_counts_once_however_many_of_its_values_are_read() {
        let u = fold(HitExpr::State(StateFn::TextureCoordinate(0)));
        let slot = |k| Arc::new(HitExpr::Slot(k));
        let make = |base: u8, init: Arc<HitExpr>| {
            Arc::new(HitLoop {
                base,
                init: vec![init; 10].into(),
                cond: fold(HitExpr::Binary(BinOp::Lt, slot(base), u.clone())),
                next: (0..10).map(|k| fold(HitExpr::Binary(BinOp::Add, slot(base + k), c(1.0)))).collect(),
                exit: c(0.0),
                test_first: true,
                turn_cost: 40,
                top: base + 10,
            })
        };
        let sum = |l: &Arc<HitLoop>| {
            let mut e = c(0.0);
            for k in 0..10 {
                e = Arc::new(HitExpr::Binary(BinOp::Add, e, Arc::new(HitExpr::LoopOut(l.clone(), l.base + k))));
            }
            e
        };
        let first = make(0, u.clone());
        // Ten reads and ten additions, the constant 0, the loop once (start: u, ten times).
        assert_eq!(cost(&sum(&first)), (21 + MAX_LOOP_STEPS + 10, 13));
        assert_eq!(too_costly(&sum(&first)), None);
        // A second loop starting from the first one's values: each loop once.
        let second = make(0, Arc::new(HitExpr::LoopOut(first.clone(), 3)));
        let both = Arc::new(HitExpr::Binary(BinOp::Add, sum(&first), sum(&second)));
        assert_eq!(cost(&both).0, 1 + 2 * 21 + 2 * MAX_LOOP_STEPS + 10 + 10);
        // A loop inside another (base 10) reads slots around it: run at each read.
        let inner = make(10, slot(0));
        assert_eq!(cost(&sum(&inner)).0, 21 + 10 * (MAX_LOOP_STEPS + 10));
        assert!(too_costly(&sum(&inner)).is_some());
    }

    #[test]
    fn vector_functions_use_their_lanes() {
        let v = Vec4::new(3.0, 4.0, 0.0, 9.0);
        assert_eq!(math(MathFn::Length(3), v, Vec4::ZERO, Vec4::ZERO), splat(5.0));
        assert_eq!(math(MathFn::Dot(2), v, Vec4::ONE, Vec4::ZERO), splat(7.0));
        assert_eq!(math(MathFn::MaxValue(3), v, Vec4::ZERO, Vec4::ZERO), splat(4.0));
        let n = math(MathFn::Normalize(3), v, Vec4::ZERO, Vec4::ZERO);
        assert!((n - Vec4::new(0.6, 0.8, 0.0, 0.0)).length() < 1e-6);
        let s = math(MathFn::Smoothstep, splat(0.0), splat(1.0), splat(0.5));
        assert_eq!(s, splat(0.5));
    }
}
