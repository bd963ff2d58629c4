//! Procedural textures of the base library: checkerboard, polka dots (2-D and 3-D),
//! turbulence and waves, evaluated at a texture coordinate.

use std::f32::consts::PI;

use glam::{Vec3A, Vec4};

use shader::{Ctx, NodeId, ShaderImpl, Value};

/// `mib_texture_checkerboard (vector coord, scalar xsize, scalar ysize, scalar zsize,
/// color color000 … color111)`: space split along each axis at `xsize` (`ysize`,
/// `zsize`); colour `colorXYZ` covers the part where each digit is 0 at or below the split
/// and 1 above it. The coordinate is not wrapped: tiling comes from a `mib_texture_remap`
/// with `repeat` upstream, as in mental ray.
pub static CHECKERBOARD: ShaderImpl = ShaderImpl {
    name: "mib_texture_checkerboard",
    params: &[
        "coord", "xsize", "ysize", "zsize", "color000", "color001", "color010", "color011", "color100", "color101",
        "color110", "color111",
    ],
    run: checkerboard,
    ..ShaderImpl::PLAIN
};

/// Which of the eight colours (000 … 111 as 0 … 7) covers `coord`.
pub fn checker_cell(coord: Vec3A, size: Vec3A) -> usize {
    4 * usize::from(coord.x > size.x) + 2 * usize::from(coord.y > size.y) + usize::from(coord.z > size.z)
}

fn checkerboard(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let coord = ctx.vector(n, 0);
    let size = Vec3A::new(ctx.scalar(n, 1), ctx.scalar(n, 2), ctx.scalar(n, 3));
    let cell = checker_cell(coord, size);
    *out = Value::Color(ctx.color(n, 4 + cell));
    true
}

/// `mib_texture_polkadot (vector coord, scalar radius, color fgcolor, color bgcolor)`:
/// `fgcolor` within `radius` of the origin in (x, y), `bgcolor` elsewhere (one dot; tiling
/// comes from a remap upstream).
pub static POLKADOT: ShaderImpl = ShaderImpl {
    name: "mib_texture_polkadot",
    params: &["coord", "radius", "fgcolor", "bgcolor"],
    run: polkadot,
    ..ShaderImpl::PLAIN
};

fn polkadot(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let c = ctx.vector(n, 0);
    let r = ctx.scalar(n, 1);
    let inside = c.x.hypot(c.y) < r;
    *out = Value::Color(ctx.color(n, if inside { 2 } else { 3 }));
    true
}

/// `mib_texture_polkasphere (vector coord, scalar radius, color fgcolor, color bgcolor)`:
/// `fgcolor` within `radius` of the origin in 3-D.
pub static POLKASPHERE: ShaderImpl = ShaderImpl {
    name: "mib_texture_polkasphere",
    params: &["coord", "radius", "fgcolor", "bgcolor"],
    run: polkasphere,
    ..ShaderImpl::PLAIN
};

fn polkasphere(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let c = ctx.vector(n, 0);
    let r = ctx.scalar(n, 1);
    let inside = c.length() < r;
    *out = Value::Color(ctx.color(n, if inside { 2 } else { 3 }));
    true
}

/// The 1024 random values of the turbulence noise lattice: the 48-bit linear congruential
/// sequence of `erand48` (a = 0x5DEECE66D, c = 0xB) from the state 0x1_330E, as the base
/// shaders seed it.
fn noise_table() -> &'static [f32; 1024] {
    static TABLE: std::sync::OnceLock<[f32; 1024]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut x: u64 = 0x0000_0001_330e;
        let mut t = [0.0f32; 1024];
        for v in &mut t {
            x = (x.wrapping_mul(0x5_deec_e66d).wrapping_add(0xb)) & ((1 << 48) - 1);
            *v = (x as f64 / (1u64 << 48) as f64) as f32;
        }
        t
    })
}

/// The base shaders' lattice noise in [0, 1]: quadratic B-spline interpolation of random
/// lattice values (hash 1341 i + 719 j + 2031 k over a 1024-entry table).
pub fn lattice_noise(p: Vec3A) -> f32 {
    let table = noise_table();
    let axis = |x: f32| {
        let x = x + 39999.5;
        let i = x as i32;
        let f = x - i as f32;
        let w0 = 0.5 * (1.0 - f) * (1.0 - f);
        let w2 = 0.5 * f * f;
        (i, [w0, 1.0 - w0 - w2, w2])
    };
    let (ix, wx) = axis(p.x);
    let (iy, wy) = axis(p.y);
    let (iz, wz) = axis(p.z);
    let h = 1341i32.wrapping_mul(ix).wrapping_add(719i32.wrapping_mul(iy)).wrapping_add(2031i32.wrapping_mul(iz));
    let mut sum = 0.0;
    for (a, wa) in wx.iter().enumerate() {
        for (b, wb) in wy.iter().enumerate() {
            for (c, wc) in wz.iter().enumerate() {
                let k = h.wrapping_add(1341 * a as i32 + 719 * b as i32 + 2031 * c as i32) & 1023;
                sum += wa * wb * wc * table[k as usize];
            }
        }
    }
    sum
}

/// `mib_texture_turbulence (vector coord, scalar spacing, scalar strength, scalar power,
/// integer iteration, integer polar_dim)` → scalar: marble-like bands
/// ½ − ½ sin(2π spacing (r + strength S)), S a sum of `iteration` (0: 2, at most 8)
/// octaves of lattice noise with weights falling as frequency^−power (normalised to 1).
/// `polar_dim` 2 bands around the x axis (r = √(y² + z²)) on the plain noise sum; 1 bands
/// along x + y on the sum of |2 noise − 1|. Other values run, as in mental ray's source
/// (which falls through from its case 0 into case 1), the case-1 formula with
/// min(plain sum, 1) added to S.
pub static TURBULENCE: ShaderImpl = ShaderImpl {
    name: "mib_texture_turbulence",
    params: &["coord", "spacing", "strength", "power", "iteration", "polar_dim"],
    run: turbulence,
    ..ShaderImpl::PLAIN
};

/// The turbulence value at `p`.
pub fn turbulence_value(p: Vec3A, spacing: f32, strength: f32, power: f32, iteration: i32, polar_dim: i32) -> f32 {
    let power = if power != 0.0 { power } else { 1.0 };
    let terms = if iteration < 1 { 2 } else { iteration.min(8) } as usize;
    let mut scales = [0.0f32; 8];
    let mut weights = [0.0f32; 8];
    let mut s = 1.0f32;
    for i in 0..terms {
        if i > 0 {
            s *= 2.0;
        }
        scales[i] = s;
        weights[i] = if i == 0 { 0.5 } else { 0.5 * s.powf(-power) };
    }
    let total: f32 = weights[..terms].iter().sum();
    let spacing = if spacing != 0.0 { spacing } else { 1.0 };
    let strength = if strength != 0.0 { strength } else { 1.0 };
    let plain = || (0..terms).map(|i| weights[i] / total * lattice_noise(p * scales[i])).sum::<f32>();
    let folded =
        || (0..terms).map(|i| weights[i] / total * (2.0 * lattice_noise(p * scales[i]) - 1.0).abs()).sum::<f32>();
    let (r, sum) = match polar_dim {
        1 => (p.x + p.y, folded()),
        2 => ((p.y * p.y + p.z * p.z).sqrt(), plain()),
        _ => (p.x + p.y, plain().min(1.0) + folded()),
    };
    0.5 - 0.5 * (2.0 * PI * spacing * (r + strength * sum)).sin()
}

fn turbulence(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let p = ctx.vector(n, 0);
    let v = turbulence_value(p, ctx.scalar(n, 1), ctx.scalar(n, 2), ctx.scalar(n, 3), ctx.int(n, 4), ctx.int(n, 5));
    *out = Value::Scalar(v);
    true
}

/// `mib_texture_wave (vector coord, scalar amplitude_x, scalar amplitude_y, scalar
/// amplitude_z, scalar offset)`: `offset + Σ amplitude_i cos(2π coord_i)` in all four
/// channels.
pub static WAVE: ShaderImpl = ShaderImpl {
    name: "mib_texture_wave",
    params: &["coord", "amplitude_x", "amplitude_y", "amplitude_z", "offset"],
    run: wave,
    ..ShaderImpl::PLAIN
};

fn wave(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let c = ctx.vector(n, 0);
    let v = ctx.scalar(n, 4)
        + ctx.scalar(n, 1) * (2.0 * PI * c.x).cos()
        + ctx.scalar(n, 2) * (2.0 * PI * c.y).cos()
        + ctx.scalar(n, 3) * (2.0 * PI * c.z).cos();
    *out = Value::Color(Vec4::splat(v));
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_cells_follow_the_split_values() {
        let half = Vec3A::splat(0.5);
        assert_eq!(checker_cell(Vec3A::new(0.2, 0.2, 0.2), half), 0);
        assert_eq!(checker_cell(Vec3A::new(0.7, 0.2, 0.2), half), 4);
        assert_eq!(checker_cell(Vec3A::new(0.2, 0.7, 0.2), half), 2);
        assert_eq!(checker_cell(Vec3A::new(0.2, 0.2, 0.7), half), 1);
        assert_eq!(checker_cell(Vec3A::new(0.5, 0.2, 0.2), half), 0, "at the split: the first colour");
    }

    #[test]
    fn erand48_table_matches_the_c_library() {
        // srand48(1) leaves the state at 0x1330E, so the table is drand48()'s sequence
        // after srand48(1); its first values (glibc): 0.041630344771878, 0.454492444728629.
        let t = noise_table();
        assert!((t[0] - 0.041_630_34).abs() < 1e-6, "{}", t[0]);
        assert!((t[1] - 0.454_492_44).abs() < 1e-6, "{}", t[1]);
    }

    #[test]
    fn lattice_noise_is_a_smooth_weighted_mean() {
        let mut prev = lattice_noise(Vec3A::new(0.0, 0.37, 0.61));
        for i in 1..2000 {
            let v = lattice_noise(Vec3A::new(i as f32 * 0.01, 0.37, 0.61));
            assert!((0.0..=1.0).contains(&v));
            assert!((v - prev).abs() < 0.05, "jump at {i}");
            prev = v;
        }
        let t = turbulence_value(Vec3A::new(0.3, 0.4, 0.5), 0.0, 0.0, 0.0, 0, 1);
        assert!((0.0..=1.0).contains(&t));
    }
}
