//! Maya's utility nodes that exports connect between textures and materials.
//!
//! Each returns Maya's output attribute as the member of a struct (`output`, `outValue`,
//! `outColor` …, see `mayabase.mi`); Maya's float3 attributes are vectors, colours where
//! Maya makes them colours.

use glam::Vec3A;
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::values::{luma, rgb, rgba, write_struct};

fn vector_out(out: &mut Value, name: &str, v: Vec3A) -> bool {
    write_struct(out, &[(name, Value::Vector(v))]);
    true
}

maya_shader!(
    /// multiplyDivide: `operation` 0 passes `input1`, 1 multiplies, 2 divides (a zero
    /// divisor gives 0 in that channel rather than infinity), 3 raises `input1` to
    /// `input2`, per channel, into `output`.
    MULTIPLYDIVIDE,
    ADSK_MULTIPLYDIVIDE,
    "maya_multiplydivide",
    "adskMayaMultiplyDivide",
    &["operation", "input1", "input2"],
    multiply_divide
);

/// multiplyDivide's operation on two vectors.
pub fn multiply_divide_op(op: i32, a: Vec3A, b: Vec3A) -> Vec3A {
    match op {
        1 => a * b,
        2 => Vec3A::from_array(std::array::from_fn(|i| if b[i] == 0.0 { 0.0 } else { a[i] / b[i] })),
        3 => Vec3A::from_array(std::array::from_fn(|i| a[i].powf(b[i]))),
        _ => a,
    }
}

fn multiply_divide(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let v = multiply_divide_op(ctx.int(n, 0), ctx.vector(n, 1), ctx.vector(n, 2));
    vector_out(out, "output", v)
}

maya_shader!(
    /// plusMinusAverage: over the arrays `input1D` (scalars) and `input3D` (vectors),
    /// `operation` 1 sums, 2 subtracts the rest from the first, 3 averages, 0 passes the
    /// first; into `output1D` and `output3D`.
    PLUSMINUSAVERAGE,
    ADSK_PLUSMINUSAVERAGE,
    "maya_plusminusaverage",
    "adskMayaPlusMinusAverage",
    &["operation", "input1D", "input3D"],
    plus_minus_average
);

/// plusMinusAverage's operation over `items`.
pub fn plus_minus_average_op<T>(op: i32, items: &[T]) -> T
where
    T: Copy + Default + std::ops::Add<Output = T> + std::ops::Sub<Output = T> + std::ops::Mul<f32, Output = T>,
{
    let Some(&first) = items.first() else { return T::default() };
    match op {
        1 => items.iter().fold(T::default(), |s, &x| s + x),
        2 => items[1..].iter().fold(first, |s, &x| s - x),
        3 => items.iter().fold(T::default(), |s, &x| s + x) * (1.0 / items.len() as f32),
        _ => first,
    }
}

fn plus_minus_average(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let op = ctx.int(n, 0);
    let one: Vec<f32> = ctx.array(n, 1).array().iter().map(Value::scalar).collect();
    let three: Vec<Vec3A> = ctx.array(n, 2).array().iter().map(Value::vector).collect();
    write_struct(
        out,
        &[
            ("output1D", Value::Scalar(plus_minus_average_op(op, &one))),
            ("output3D", Value::Vector(plus_minus_average_op(op, &three))),
        ],
    );
    true
}

maya_shader!(
    /// reverse: `output` = 1 − `input`.
    REVERSE,
    ADSK_REVERSE,
    "maya_reverse",
    "adskMayaReverse",
    &["input"],
    reverse
);

fn reverse(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let v = Vec3A::ONE - ctx.vector(n, 0);
    vector_out(out, "output", v)
}

maya_shader!(
    /// blendColors: `output` = `color1` · `blender` + `color2` · (1 − `blender`).
    BLENDCOLORS,
    ADSK_BLENDCOLORS,
    "maya_blendcolors",
    "adskMayaBlendColors",
    &["color1", "color2", "blender"],
    blend_colors
);

fn blend_colors(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let b = ctx.scalar(n, 2);
    let c = rgb(ctx.color(n, 0)) * b + rgb(ctx.color(n, 1)) * (1.0 - b);
    write_struct(out, &[("output", Value::Color(rgba(c, 1.0)))]);
    true
}

maya_shader!(
    /// condition: compares `firstTerm` with `secondTerm` by `operation` (0 equal, 1 not
    /// equal, 2 greater, 3 greater or equal, 4 less, 5 less or equal) and returns
    /// `colorIfTrue` or `colorIfFalse` as `outColor`.
    CONDITION,
    ADSK_CONDITION,
    "maya_condition",
    "adskMayaCondition",
    &["operation", "firstTerm", "secondTerm", "colorIfTrue", "colorIfFalse"],
    condition
);

/// condition's comparison.
pub fn condition_holds(op: i32, a: f32, b: f32) -> bool {
    match op {
        0 => a == b,
        1 => a != b,
        2 => a > b,
        3 => a >= b,
        4 => a < b,
        _ => a <= b,
    }
}

fn condition(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let holds = condition_holds(ctx.int(n, 0), ctx.scalar(n, 1), ctx.scalar(n, 2));
    // Only the chosen branch is evaluated.
    let c = if holds { ctx.color(n, 3) } else { ctx.color(n, 4) };
    write_struct(out, &[("outColor", Value::Color(rgba(rgb(c), 1.0)))]);
    true
}

maya_shader!(
    /// clamp: `output` = `input` limited to [`min`, `max`] per channel (Maya's clamp
    /// leaves a channel whose min exceeds its max unclamped).
    CLAMP,
    ADSK_CLAMP,
    "maya_clamp",
    "adskMayaClamp",
    &["min", "max", "input"],
    clamp
);

/// clamp's per-channel operation.
pub fn clamp_op(input: Vec3A, min: Vec3A, max: Vec3A) -> Vec3A {
    Vec3A::from_array(std::array::from_fn(|i| if min[i] > max[i] { input[i] } else { input[i].clamp(min[i], max[i]) }))
}

fn clamp(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let v = clamp_op(ctx.vector(n, 2), ctx.vector(n, 0), ctx.vector(n, 1));
    vector_out(out, "output", v)
}

maya_shader!(
    /// setRange: `outValue` = `min` + (`value` − `oldMin`) / (`oldMax` − `oldMin`) ·
    /// (`max` − `min`) per channel, clamped to [min, max] as Maya does; an empty old
    /// range gives `min`.
    SETRANGE,
    ADSK_SETRANGE,
    "maya_setrange",
    "adskMayaSetRange",
    &["value", "min", "max", "oldMin", "oldMax"],
    set_range
);

/// setRange's per-channel mapping.
pub fn set_range_op(value: Vec3A, min: Vec3A, max: Vec3A, old_min: Vec3A, old_max: Vec3A) -> Vec3A {
    Vec3A::from_array(std::array::from_fn(|i| {
        let span = old_max[i] - old_min[i];
        if span == 0.0 {
            return min[i];
        }
        let t = ((value[i] - old_min[i]) / span).clamp(0.0, 1.0);
        min[i] + t * (max[i] - min[i])
    }))
}

fn set_range(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let v = set_range_op(ctx.vector(n, 0), ctx.vector(n, 1), ctx.vector(n, 2), ctx.vector(n, 3), ctx.vector(n, 4));
    vector_out(out, "outValue", v)
}

maya_shader!(
    /// remapValue: `inputValue` normalised by [`inputMin`, `inputMax`] is looked up in the
    /// scalar curve `value` (array of {position, value, interp}) → `outValue` scaled into
    /// [`outputMin`, `outputMax`], and in the gradient `color` → `outColor`. An empty curve
    /// is the identity; an empty gradient gives the normalised input as grey.
    REMAPVALUE,
    ADSK_REMAPVALUE,
    "maya_remapvalue",
    "adskMayaRemapValue",
    &["inputValue", "inputMin", "inputMax", "outputMin", "outputMax", "value", "color"],
    remap_value
);

/// The value of sorted curve points (position, value, Maya interpolation: 0 none, 1
/// linear, 2 smooth, 3 spline) at `t`, as `bsdf::maya_highlight::ramp_curve` documents
/// the interpolations (the path engine reads ramps there too); no points: `t` as grey.
pub fn curve_at(points: &[(f32, Vec3A, i32)], t: f32) -> Vec3A {
    if points.is_empty() {
        return Vec3A::splat(t);
    }
    bsdf::maya_highlight::ramp_curve::ramp_value(points, t)
}

/// The points of a ramp array of structs {`<p>_Position`, `<p>_<value>`,
/// `<p>_Interp`}, sorted by position.
pub(crate) fn ramp_points(v: &Value, prefix: &str, value: &str) -> Vec<(f32, Vec3A, i32)> {
    let (pos, val, interp) = (format!("{prefix}_Position"), format!("{prefix}_{value}"), format!("{prefix}_Interp"));
    let mut pts: Vec<(f32, Vec3A, i32)> = v
        .array()
        .iter()
        .map(|e| {
            let p = e.member(&pos).map_or(0.0, Value::scalar);
            let value = e.member(&val).map_or(Vec3A::ZERO, |m| match m {
                Value::Color(c) => rgb(*c),
                other => Vec3A::splat(other.scalar()),
            });
            (p, value, e.member(&interp).map_or(1, Value::int))
        })
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts
}

/// A ramp read from its array: sorted points and the value of an empty ramp.
pub struct Ramp {
    points: Vec<(f32, Vec3A, i32)>,
    empty: Vec3A,
}

impl Ramp {
    /// A ramp of sorted `points` (position, value, Maya interpolation), `empty` when
    /// there are none.
    pub fn new(points: Vec<(f32, Vec3A, i32)>, empty: Vec3A) -> Ramp {
        Ramp { points, empty }
    }

    /// The ramp of array `value` whose members are `<prefix>_Position`,
    /// `<prefix>_<member>` and `<prefix>_Interp`; `empty` when it has no points.
    pub fn read(value: &Value, prefix: &str, member: &str, empty: Vec3A) -> Ramp {
        Ramp { points: ramp_points(value, prefix, member), empty }
    }

    /// The ramp's points (position, value, Maya interpolation), sorted by position.
    pub fn points(&self) -> &[(f32, Vec3A, i32)] {
        &self.points
    }

    /// Whether the ramp has no points (it is its `empty` value everywhere).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The ramp at `x` (the first point's value before it, the last one's after it).
    pub fn at(&self, x: f32) -> Vec3A {
        if self.points.is_empty() {
            self.empty
        } else {
            curve_at(&self.points, x)
        }
    }
}

/// `x` normalised by [`lo`, `hi`] and clamped to [0, 1] (0 for an empty range).
fn normalised(x: f32, lo: f32, hi: f32) -> f32 {
    if hi != lo {
        ((x - lo) / (hi - lo)).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

fn remap_value(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let tc = normalised(ctx.scalar(n, 0), ctx.scalar(n, 1), ctx.scalar(n, 2));
    let curve = ramp_points(&ctx.array(n, 5), "value", "FloatValue");
    let gradient = ramp_points(&ctx.array(n, 6), "color", "Color");
    let v = if curve.is_empty() { tc } else { curve_at(&curve, tc).x };
    let (omin, omax) = (ctx.scalar(n, 3), ctx.scalar(n, 4));
    let c = curve_at(&gradient, tc);
    write_struct(
        out,
        &[("outValue", Value::Scalar(omin + v * (omax - omin))), ("outColor", Value::Color(rgba(c, 1.0)))],
    );
    true
}

maya_shader!(
    /// remapColor: each channel of `color`, normalised by [`inputMin`, `inputMax`], is
    /// looked up in its own curve (`red`, `green`, `blue`: arrays of {position, value,
    /// interp}; empty: the identity) and scaled into [`outputMin`, `outputMax`].
    REMAPCOLOR,
    ADSK_REMAPCOLOR,
    "maya_remapcolor",
    "adskMayaRemapColor",
    &["color", "inputMin", "inputMax", "outputMin", "outputMax", "red", "green", "blue"],
    remap_color
);

fn remap_color(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let c = rgb(ctx.color(n, 0));
    let (lo, hi, omin, omax) = (ctx.scalar(n, 1), ctx.scalar(n, 2), ctx.scalar(n, 3), ctx.scalar(n, 4));
    let mut o = Vec3A::ZERO;
    for (i, name) in ["red", "green", "blue"].into_iter().enumerate() {
        let curve = ramp_points(&ctx.array(n, 5 + i), name, "FloatValue");
        let t = normalised(c[i], lo, hi);
        let v = if curve.is_empty() { t } else { curve_at(&curve, t).x };
        o[i] = omin + v * (omax - omin);
    }
    write_struct(out, &[("outColor", Value::Color(rgba(o, 1.0)))]);
    true
}

maya_shader!(
    /// luminance: `outValue` = 0.3 R + 0.59 G + 0.11 B of `value`.
    LUMINANCE,
    ADSK_LUMINANCE,
    "maya_luminance",
    "adskMayaLuminance",
    &["value"],
    luminance
);

fn luminance(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let l = luma(rgb(ctx.color(n, 0)));
    write_struct(out, &[("outValue", Value::Scalar(l))]);
    true
}

maya_shader!(
    /// gammaCorrect: `outValue` = `value`^(1/`gamma`) per channel (a gamma of 0 leaves the
    /// channel unchanged; negative values stay 0).
    GAMMACORRECT,
    ADSK_GAMMACORRECT,
    "maya_gammacorrect",
    "adskMayaGammaCorrect",
    &["value", "gamma"],
    gamma_correct
);

fn gamma_correct(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let (v, g) = (ctx.vector(n, 0), ctx.vector(n, 1));
    let o = Vec3A::from_array(std::array::from_fn(|i| if g[i] <= 0.0 { v[i] } else { v[i].max(0.0).powf(1.0 / g[i]) }));
    vector_out(out, "outValue", o)
}

maya_shader!(
    /// contrast: per channel, `value` pushed away from `bias` by `contrast` ([`contrast_op`])
    /// into `outValue`.
    CONTRAST,
    ADSK_CONTRAST,
    "maya_contrast",
    "adskMayaContrast",
    &["value", "contrast", "bias"],
    contrast
);

/// One channel of Maya's contrast node: x (clamped to [0, 1]) is mapped so that `bias`
/// becomes ½ (Perlin's bias curve, t = x^(ln ½ / ln b)), steepened about ½ by the power
/// `contrast` (t < ½: ½·(2t)^c, else 1 − ½·(2 − 2t)^c) and mapped back (t^(ln b / ln ½)).
/// So 0, 1 and `bias` stay where they are, values above the bias get lighter and those
/// below darker for c > 1, contrast 1 changes nothing and contrast 0 gives the bias
/// everywhere ("decrease Contrast to make everything grey"; a higher bias makes more of
/// the texture dark — Maya's node reference). The curve is mira's reading: the reference
/// describes the behaviour, not the formula. A bias outside (0, 1) is clamped into it.
pub fn contrast_op(x: f32, contrast: f32, bias: f32) -> f32 {
    let x = x.clamp(0.0, 1.0);
    let b = bias.clamp(1e-4, 1.0 - 1e-4);
    let c = contrast.max(0.0);
    let to_half = std::f32::consts::LN_2.recip() * -b.ln(); // log2(1/b): b^(1/k) = ½
    let t = x.powf(1.0 / to_half);
    let t = if t < 0.5 { 0.5 * (2.0 * t).powf(c) } else { 1.0 - 0.5 * (2.0 - 2.0 * t).powf(c) };
    t.powf(to_half)
}

fn contrast(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let (v, c, b) = (ctx.vector(n, 0), ctx.vector(n, 1), ctx.vector(n, 2));
    let o = Vec3A::from_array(std::array::from_fn(|i| contrast_op(v[i], c[i], b[i])));
    vector_out(out, "outValue", o)
}

/// RGB to (hue in degrees [0, 360), saturation, value), as Maya's rgbToHsv.
pub fn rgb_to_hsv(c: Vec3A) -> Vec3A {
    let max = c.max_element();
    let min = c.min_element();
    let d = max - min;
    let s = if max > 0.0 { d / max } else { 0.0 };
    let h = if d <= 0.0 {
        0.0
    } else if max == c.x {
        60.0 * ((c.y - c.z) / d).rem_euclid(6.0)
    } else if max == c.y {
        60.0 * ((c.z - c.x) / d + 2.0)
    } else {
        60.0 * ((c.x - c.y) / d + 4.0)
    };
    Vec3A::new(h, s, max)
}

/// (hue in degrees, saturation, value) to RGB, as Maya's hsvToRgb.
pub fn hsv_to_rgb(hsv: Vec3A) -> Vec3A {
    let (h, s, v) = (hsv.x.rem_euclid(360.0) / 60.0, hsv.y, hsv.z);
    let c = v * s;
    let x = c * (1.0 - (h.rem_euclid(2.0) - 1.0).abs());
    let (r, g, b) = match h as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    Vec3A::new(r, g, b) + Vec3A::splat(v - c)
}

maya_shader!(
    /// rgbToHsv: `outHsv` of `inRgb` (hue in degrees).
    RGBTOHSV,
    ADSK_RGBTOHSV,
    "maya_rgbtohsv",
    "adskMayaRgbToHsv",
    &["inRgb"],
    rgb_to_hsv_node
);

fn rgb_to_hsv_node(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let v = rgb_to_hsv(ctx.vector(n, 0));
    vector_out(out, "outHsv", v)
}

maya_shader!(
    /// hsvToRgb: `outRgb` of `inHsv` (hue in degrees).
    HSVTORGB,
    ADSK_HSVTORGB,
    "maya_hsvtorgb",
    "adskMayaHsvToRgb",
    &["inHsv"],
    hsv_to_rgb_node
);

fn hsv_to_rgb_node(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let v = hsv_to_rgb(ctx.vector(n, 0));
    vector_out(out, "outRgb", v)
}

maya_shader!(
    /// vectorProduct: `operation` 1 dot product (in all three channels), 2 cross product,
    /// 3 `input1` as a direction through `matrix`, 4 as a point through it, 0 passes
    /// `input1`; `normalizeOutput` makes the result unit length.
    VECTORPRODUCT,
    ADSK_VECTORPRODUCT,
    "maya_vectorproduct",
    "adskMayaVectorProduct",
    &["operation", "input1", "input2", "matrix", "normalizeOutput"],
    vector_product
);

fn vector_product(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let (a, b) = (ctx.vector(n, 1), ctx.vector(n, 2));
    let m = ctx.eval(n, 3).transform();
    let v = match ctx.int(n, 0) {
        1 => Vec3A::splat(a.dot(b)),
        2 => a.cross(b),
        3 => m.transform_vector3a(a),
        4 => m.transform_point3a(a),
        _ => a,
    };
    let v = if ctx.bool(n, 4) { v.normalize_or_zero() } else { v };
    vector_out(out, "output", v)
}

maya_shader!(
    /// samplerInfo: facts of the shading point — `pointWorld`, `pointObj`, `pointCamera`
    /// and `normalCamera` (the camera space of mira's camera, which looks down −z),
    /// `rayDirection` (world), `uvCoord` (first texture space), `facingRatio` (|N·V|, 1
    /// facing the viewer) and `flippedNormal` (seen from the back).
    SAMPLERINFO,
    ADSK_SAMPLERINFO,
    "maya_samplerinfo",
    "adskMayaSamplerInfo",
    &[],
    sampler_info
);

fn sampler_info(ctx: &mut Ctx, _n: NodeId, out: &mut Value) -> bool {
    let s = &ctx.state;
    let to_camera = ctx.shading().world_to_camera;
    let facing = s.normal.dot(-s.dir).abs().min(1.0);
    let uv = s.tex(0);
    let members = [
        ("pointWorld", Value::Vector(s.point)),
        ("pointObj", Value::Vector(s.world_to_object.transform_point3a(s.point))),
        ("pointCamera", Value::Vector(to_camera.transform_point3a(s.point))),
        ("normalCamera", Value::Vector(to_camera.transform_vector3a(s.normal).normalize_or_zero())),
        ("rayDirection", Value::Vector(s.dir)),
        ("uvCoord", Value::Vector(Vec3A::new(uv.x, uv.y, 0.0))),
        ("facingRatio", Value::Scalar(facing)),
        ("flippedNormal", Value::Bool(s.inv_normal)),
    ];
    write_struct(out, &members);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3A, b: Vec3A) {
        assert!((a - b).length() < 1e-5, "{a} vs {b}");
    }

    #[test]
    fn multiply_divide_operations() {
        let (a, b) = (Vec3A::new(2.0, 3.0, 4.0), Vec3A::new(4.0, 0.0, 0.5));
        close(multiply_divide_op(1, a, b), Vec3A::new(8.0, 0.0, 2.0));
        close(multiply_divide_op(2, a, b), Vec3A::new(0.5, 0.0, 8.0));
        close(multiply_divide_op(3, a, b), Vec3A::new(16.0, 1.0, 2.0));
        close(multiply_divide_op(0, a, b), a);
    }

    #[test]
    fn plus_minus_average_operations() {
        let xs = [1.0f32, 2.0, 6.0];
        assert_eq!(plus_minus_average_op(1, &xs), 9.0);
        assert_eq!(plus_minus_average_op(2, &xs), -7.0);
        assert_eq!(plus_minus_average_op(3, &xs), 3.0);
        assert_eq!(plus_minus_average_op::<f32>(1, &[]), 0.0);
    }

    #[test]
    fn condition_clamp_and_set_range() {
        assert!(condition_holds(2, 0.6, 0.5) && !condition_holds(4, 0.6, 0.5) && condition_holds(5, 0.5, 0.5));
        close(clamp_op(Vec3A::new(-1.0, 0.5, 2.0), Vec3A::ZERO, Vec3A::ONE), Vec3A::new(0.0, 0.5, 1.0));
        // min > max: unclamped.
        close(clamp_op(Vec3A::splat(5.0), Vec3A::splat(2.0), Vec3A::splat(1.0)), Vec3A::splat(5.0));
        // 5 in [0, 10] → [100, 200]: 150.
        let v =
            set_range_op(Vec3A::splat(5.0), Vec3A::splat(100.0), Vec3A::splat(200.0), Vec3A::ZERO, Vec3A::splat(10.0));
        close(v, Vec3A::splat(150.0));
    }

    #[test]
    fn contrast_keeps_its_ends_and_bias_and_steepens_about_the_bias() {
        for b in [0.5, 0.3, 0.8] {
            for c in [0.0, 0.5, 1.0, 2.0, 5.0] {
                assert!((contrast_op(b, c, b) - b).abs() < 1e-5, "bias {b} contrast {c}");
                assert!(contrast_op(1.0, c, b) > 1.0 - 1e-5 || c == 0.0);
            }
            assert!(contrast_op(0.0, 2.0, b) < 1e-6 && contrast_op(1.0, 2.0, b) > 1.0 - 1e-6);
            // Contrast 1 is the identity; 0 gives the bias everywhere.
            for x in [0.0, 0.1, 0.45, 0.9] {
                assert!((contrast_op(x, 1.0, b) - x).abs() < 1e-5, "{x}");
                assert!((contrast_op(x, 0.0, b) - b).abs() < 1e-5, "{x}");
            }
            // Contrast 2: darker below the bias, lighter above; ½ contrast the reverse.
            assert!(
                contrast_op(0.9 * b, 2.0, b) < 0.9 * b
                    && contrast_op(b + 0.1 * (1.0 - b), 2.0, b) > b + 0.1 * (1.0 - b)
            );
            assert!(contrast_op(0.9 * b, 0.5, b) > 0.9 * b);
        }
        // Bias ½ by hand: 0.25 → ½·(0.5)² = 0.125, 0.75 → 1 − 0.125.
        assert!((contrast_op(0.25, 2.0, 0.5) - 0.125).abs() < 1e-6);
        assert!((contrast_op(0.75, 2.0, 0.5) - 0.875).abs() < 1e-6);
        // A higher bias darkens more of the texture.
        assert!(contrast_op(0.5, 2.0, 0.7) < contrast_op(0.5, 2.0, 0.3));
    }

    #[test]
    fn remap_curve_and_hsv_round_trip() {
        let pts = [(0.0, Vec3A::ZERO, 1), (1.0, Vec3A::splat(2.0), 1)];
        close(curve_at(&pts, 0.25), Vec3A::splat(0.5));
        close(curve_at(&[], 0.3), Vec3A::splat(0.3));
        close(rgb_to_hsv(Vec3A::new(1.0, 0.0, 0.0)), Vec3A::new(0.0, 1.0, 1.0));
        close(rgb_to_hsv(Vec3A::new(0.0, 0.5, 0.5)), Vec3A::new(180.0, 1.0, 0.5));
        for c in [Vec3A::new(0.2, 0.7, 0.4), Vec3A::new(0.9, 0.1, 0.6), Vec3A::new(0.3, 0.3, 0.8)] {
            close(hsv_to_rgb(rgb_to_hsv(c)), c);
        }
    }
}
