//! Colour utilities: mixing and layering, conversions to grey, ramps, fan-out, and the
//! colours of CIE daylight and black bodies.

use std::sync::Arc;

use glam::{Mat3A, Vec3A, Vec4};

use super::{rgb, rgba};
use shader::{Color, Ctx, NodeId, ShaderImpl, Value};

/// Weights of `mib_color_intensity` and of `mib_color_spread` mode 3 (NTSC luma).
pub const INTENSITY_WEIGHTS: Vec3A = Vec3A::new(0.299, 0.587, 0.114);

/// `mib_color_mix`: up to eight colours layered over `color_base` by per-layer modes
/// (0 over, 1 mix, 2 add, 3 bounded add, 4 multiply, 5 bounded multiply, 6 the layer's
/// alpha with the colour scaled by the weight; unknown modes act as 0) and weights. Alpha
/// is mixed like the colour channels.
pub static MIX: ShaderImpl = ShaderImpl {
    name: "mib_color_mix",
    params: &[
        "num",
        "mode_0",
        "mode_1",
        "mode_2",
        "mode_3",
        "mode_4",
        "mode_5",
        "mode_6",
        "mode_7",
        "weight_0",
        "weight_1",
        "weight_2",
        "weight_3",
        "weight_4",
        "weight_5",
        "weight_6",
        "weight_7",
        "color_0",
        "color_1",
        "color_2",
        "color_3",
        "color_4",
        "color_5",
        "color_6",
        "color_7",
        "color_base",
    ],
    run: mix,
    ..ShaderImpl::PLAIN
};

fn mix(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let num = ctx.int(n, 0).clamp(0, 8) as usize;
    let mut r = ctx.color(n, 25);
    for i in 0..num {
        let mode = ctx.int(n, 1 + i);
        let w = ctx.scalar(n, 9 + i);
        let b = ctx.color(n, 17 + i);
        r = match mode {
            0 => r * (1.0 - b.w) * w + b * w,
            1 => r * (1.0 - w) + b * w,
            2 => r + b * w,
            3 => (r + b * w).clamp(Vec4::ZERO, Vec4::ONE),
            4 => r * b * w,
            5 => (r * b * w).clamp(Vec4::ZERO, Vec4::ONE),
            6 => Vec4::new(r.x * w, r.y * w, r.z * w, b.w),
            _ => r * (1.0 - b.w) * w + b * w,
        };
    }
    *out = Value::Color(r);
    true
}

fn grey(ctx: &mut Ctx, n: NodeId, out: &mut Value, f: fn(Color) -> f32) -> bool {
    let factor = ctx.scalar(n, 1);
    if factor == 0.0 {
        *out = Value::Color(Vec4::ZERO);
        return true;
    }
    let v = f(ctx.color(n, 0)) * factor;
    *out = Value::Color(Vec4::splat(v));
    true
}

/// `mib_color_alpha (color input, scalar factor)`: alpha × factor in all four components.
pub static ALPHA: ShaderImpl = ShaderImpl {
    name: "mib_color_alpha",
    params: &["input", "factor"],
    run: |c, n, o| grey(c, n, o, |c| c.w),
    ..ShaderImpl::PLAIN
};

/// `mib_color_average (color input, scalar factor)`: (r+g+b)/3 × factor.
pub static AVERAGE: ShaderImpl = ShaderImpl {
    name: "mib_color_average",
    params: &["input", "factor"],
    run: |c, n, o| grey(c, n, o, |c| (c.x + c.y + c.z) / 3.0),
    ..ShaderImpl::PLAIN
};

/// `mib_color_intensity (color input, scalar factor)`: weighted intensity
/// 0.299 r + 0.587 g + 0.114 b, × factor.
pub static INTENSITY: ShaderImpl = ShaderImpl {
    name: "mib_color_intensity",
    params: &["input", "factor"],
    run: |c, n, o| grey(c, n, o, |c| rgb(c).dot(INTENSITY_WEIGHTS)),
    ..ShaderImpl::PLAIN
};

/// `mib_color_interpolate`: a piecewise-linear ramp of `num` colours over [0, 1], the
/// inner ones at `weight_1…` (ascending); only the two colours around `input` are
/// evaluated. `num` 0 gives transparent black.
pub static INTERPOLATE: ShaderImpl = ShaderImpl {
    name: "mib_color_interpolate",
    params: &[
        "input", "num", "weight_1", "weight_2", "weight_3", "weight_4", "weight_5", "weight_6", "color_0", "color_1",
        "color_2", "color_3", "color_4", "color_5", "color_6", "color_7",
    ],
    run: interpolate,
    ..ShaderImpl::PLAIN
};

fn interpolate(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let x = ctx.scalar(n, 0);
    let num = ctx.int(n, 1).min(8);
    if num < 1 {
        *out = Value::Color(Vec4::ZERO);
        return true;
    }
    let num = num as usize;
    let color = |ctx: &mut Ctx, i: usize| ctx.color(n, 8 + i);
    if num == 1 || x <= 0.0 {
        *out = Value::Color(color(ctx, 0));
        return true;
    }
    if x >= 1.0 {
        *out = Value::Color(color(ctx, num - 1));
        return true;
    }
    // Knot positions: 0, weight_1 … weight_{num-2}, 1; the first knot at or past the
    // input closes the segment.
    let mut lo = (0usize, 0.0f32);
    for i in 1..num {
        let at = if i == num - 1 { 1.0 } else { ctx.scalar(n, 1 + i) };
        if x == at {
            *out = Value::Color(color(ctx, i));
            return true;
        }
        if x <= at {
            let t = if at > lo.1 { (x - lo.1) / (at - lo.1) } else { 0.0 };
            let a = color(ctx, lo.0);
            let b = color(ctx, i);
            *out = Value::Color(a * (1.0 - t) + b * t);
            return true;
        }
        lo = (i, at);
    }
    *out = Value::Color(color(ctx, num - 1));
    true
}

/// `mib_color_spread`: fans `input` out to `num` outputs `out_i = w_i · f_i(input)` with f
/// by mode (0 colour, 1 alpha, 2 "average" — which mental ray's code computes as
/// (r + g + a)/3, 3 intensity, 4 red; unknown modes act as 0).
///
/// `base.mi` declares the weights as colours while the shader reads eight packed scalars:
/// mental ray's w_i is the i-th number of the packed colours (w_0…w_3 the RGBA of
/// `weight_0`, w_4… those of `weight_1`). mira reads them the same way.
pub static SPREAD: ShaderImpl = ShaderImpl {
    name: "mib_color_spread",
    params: &[
        "input", "num", "mode_0", "mode_1", "mode_2", "mode_3", "mode_4", "mode_5", "mode_6", "mode_7", "weight_0",
        "weight_1", "weight_2", "weight_3", "weight_4", "weight_5", "weight_6", "weight_7",
    ],
    run: spread,
    ..ShaderImpl::PLAIN
};

fn spread(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let input = ctx.color(n, 0);
    let num = ctx.int(n, 1).clamp(0, 8) as usize;
    let mut members = Vec::with_capacity(8);
    for i in 0..8 {
        let v = if i < num {
            let f = match ctx.int(n, 2 + i) {
                1 => Vec4::splat(input.w),
                2 => Vec4::splat((input.x + input.y + input.w) / 3.0),
                3 => Vec4::splat(rgb(input).dot(INTENSITY_WEIGHTS)),
                4 => Vec4::splat(input.x),
                _ => input,
            };
            let packed = ctx.color(n, 10 + i / 4);
            f * packed[i % 4]
        } else {
            Vec4::ZERO
        };
        members.push((Arc::from(format!("out_{i}").as_str()), Value::Color(v)));
    }
    *out = Value::Struct(members.into());
    true
}

/// XYZ (D65 white) → linear Rec.709 RGB.
pub const XYZ_TO_RGB: Mat3A = Mat3A::from_cols(
    Vec3A::new(3.240_97, -0.969_243_6, 0.055_630_08),
    Vec3A::new(-1.537_383_2, 1.875_967_5, -0.203_977),
    Vec3A::new(-0.498_610_76, 0.041_555_06, 1.056_971_5),
);

/// `mib_cie_d (scalar temperature, scalar intensity)`: the colour of CIE daylight
/// illuminant D at `temperature` kelvin (4000–25000; values below 4000 are read as
/// hundreds, 65 → 6500), with luminance Y = `intensity` (0 → 1).
pub static CIE_D: ShaderImpl =
    ShaderImpl { name: "mib_cie_d", params: &["temperature", "intensity"], run: cie_d, ..ShaderImpl::PLAIN };

/// Chromaticity (x, y) of CIE daylight at `t` kelvin.
pub fn daylight_xy(t: f32) -> (f32, f32) {
    let t = if t < 4000.0 { (t * 100.0).max(4000.0) } else { t }.min(25000.0);
    let s = 1000.0 / t;
    let x = if t <= 7000.0 {
        ((-4.6070 * s + 2.9678) * s + 0.0991) * s + 0.244063
    } else {
        ((-2.0064 * s + 1.9018) * s + 0.24748) * s + 0.237040
    };
    let y = -3.0 * x * x + 2.87 * x - 0.275;
    (x, y)
}

fn xyy_to_rgb(x: f32, y: f32, luminance: f32) -> Color {
    let xyz = Vec3A::new(x * luminance / y, luminance, (1.0 - x - y) * luminance / y);
    rgba(XYZ_TO_RGB * xyz, 1.0)
}

fn cie_d(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let t = ctx.scalar(n, 0);
    let i = ctx.scalar(n, 1);
    let (x, y) = daylight_xy(if t > 0.0 { t } else { 6500.0 });
    *out = Value::Color(xyy_to_rgb(x, y, if i != 0.0 { i } else { 1.0 }));
    true
}

/// CIE 1931 2° colour-matching functions x̄, ȳ, z̄ at 380, 390, … 780 nm.
const CMF: [[f64; 3]; 41] = [
    [0.001368, 0.000039, 0.006450],
    [0.004243, 0.000120, 0.020050],
    [0.014310, 0.000396, 0.067850],
    [0.043510, 0.001210, 0.207400],
    [0.134380, 0.004000, 0.645600],
    [0.283900, 0.011600, 1.385600],
    [0.348280, 0.023000, 1.747060],
    [0.336200, 0.038000, 1.772110],
    [0.290800, 0.060000, 1.669200],
    [0.195360, 0.090980, 1.287640],
    [0.095640, 0.139020, 0.812950],
    [0.032010, 0.208020, 0.465180],
    [0.004900, 0.323000, 0.272000],
    [0.009300, 0.503000, 0.158200],
    [0.063270, 0.710000, 0.078250],
    [0.165500, 0.862000, 0.042160],
    [0.290400, 0.954000, 0.020300],
    [0.433450, 0.994950, 0.008750],
    [0.594500, 0.995000, 0.003900],
    [0.762100, 0.952000, 0.002100],
    [0.916300, 0.870000, 0.001650],
    [1.026300, 0.757000, 0.001100],
    [1.062200, 0.631000, 0.000800],
    [1.002600, 0.503000, 0.000340],
    [0.854450, 0.381000, 0.000190],
    [0.642400, 0.265000, 0.000050],
    [0.447900, 0.175000, 0.000020],
    [0.283500, 0.107000, 0.000000],
    [0.164900, 0.061000, 0.000000],
    [0.087400, 0.032000, 0.000000],
    [0.046770, 0.017000, 0.000000],
    [0.022700, 0.008210, 0.000000],
    [0.011359, 0.004102, 0.000000],
    [0.005790, 0.002091, 0.000000],
    [0.002899, 0.001047, 0.000000],
    [0.001440, 0.000520, 0.000000],
    [0.000690, 0.000249, 0.000000],
    [0.000332, 0.000120, 0.000000],
    [0.000166, 0.000060, 0.000000],
    [0.000083, 0.000030, 0.000000],
    [0.000042, 0.000015, 0.000000],
];

/// XYZ of a black body at `t` kelvin (trapezoidal rule over the table, relative units:
/// the constant factor of Planck's law is dropped).
pub fn blackbody_xyz(t: f32) -> Vec3A {
    const HC_K: f64 = 1.438_786e7; // nm·K
    let mut sum = [0.0f64; 3];
    for (i, cmf) in CMF.iter().enumerate() {
        let lambda = 380.0 + 10.0 * i as f64;
        let planck = lambda.powi(-5) / ((HC_K / (lambda * f64::from(t))).exp() - 1.0);
        let w = if i == 0 || i == CMF.len() - 1 { 0.5 } else { 1.0 };
        for k in 0..3 {
            sum[k] += w * planck * cmf[k];
        }
    }
    Vec3A::new(sum[0] as f32, sum[1] as f32, sum[2] as f32)
}

/// `mib_blackbody (scalar temperature, scalar intensity)`: the colour of a black body at
/// `temperature` kelvin (0 → 6500) with luminance Y = `intensity` (0 → 1).
pub static BLACKBODY: ShaderImpl =
    ShaderImpl { name: "mib_blackbody", params: &["temperature", "intensity"], run: blackbody, ..ShaderImpl::PLAIN };

fn blackbody(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let t = ctx.scalar(n, 0);
    let i = ctx.scalar(n, 1);
    let xyz = blackbody_xyz(if t > 0.0 { t } else { 6500.0 });
    let sum = xyz.x + xyz.y + xyz.z;
    *out = Value::Color(xyy_to_rgb(xyz.x / sum, xyz.y / sum, if i != 0.0 { i } else { 1.0 }));
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_matching_table_is_balanced() {
        // Equal energy white has x = y = 1/3: the three functions have (nearly) equal sums.
        let s: Vec<f64> = (0..3).map(|k| CMF.iter().map(|c| c[k]).sum()).collect();
        assert!((s[0] / s[1] - 1.0).abs() < 2e-3 && (s[2] / s[1] - 1.0).abs() < 2e-3, "{s:?}");
    }

    #[test]
    fn blackbody_chromaticity_follows_the_planckian_locus() {
        // Published Planckian locus points (CIE 1931): 2856 K (illuminant A) and 6500 K.
        for (t, x, y) in [(2856.0, 0.4476, 0.4074), (6500.0, 0.3135, 0.3236), (4000.0, 0.3805, 0.3768)] {
            let xyz = blackbody_xyz(t);
            let s = xyz.x + xyz.y + xyz.z;
            assert!((xyz.x / s - x).abs() < 2e-3 && (xyz.y / s - y).abs() < 2e-3, "{t} K: {:?}", xyz / s);
        }
    }

    #[test]
    fn daylight_d65_is_rec709_white() {
        let (x, y) = daylight_xy(6504.0);
        assert!((x - 0.3127).abs() < 1e-3 && (y - 0.3290).abs() < 1e-3, "({x}, {y})");
        let c = xyy_to_rgb(x, y, 1.0);
        assert!((c.x - 1.0).abs() < 0.01 && (c.y - 1.0).abs() < 0.01 && (c.z - 1.0).abs() < 0.01, "{c}");
        // The shorthand: 65 means 6500 K.
        assert_eq!(daylight_xy(65.0), daylight_xy(6500.0));
    }
}
