//! Evaluation of a compiled [`HitExpr`] at a shading point. Interface:
//! [`HitExpr::eval`] (the value at a hit), [`HitExpr::eval_finite`] (the same with NaN and
//! infinite lanes read as 0, what materials use; [`HitExpr::eval_finite_with`] for several
//! expressions of one [`Evaluation`]) and [`HitExpr::eval_in`] (inside the per-hit loops
//! whose slots a [`Slots`] holds); [`fold`](super::fold) uses `eval` to fold
//! constant nodes. The lane helpers, [`splat`] and [`math`] are `pub(super)` for the tests.

use glam::{Vec3A, Vec4};
use shader::State;

use super::super::hit_loop::{Evaluation, Slots, Top};
use super::super::sky_model::SkyParam;
use super::{BinOp, HitExpr, MathFn, StateFn, UnOp};

/// A scalar in all four lanes.
pub(super) fn splat(x: f32) -> Vec4 {
    Vec4::splat(x)
}

fn truth(b: bool) -> Vec4 {
    splat(if b { 1.0 } else { 0.0 })
}

fn lanes(v: Vec4, n: u8) -> Vec4 {
    match n {
        1 => Vec4::new(v.x, 0.0, 0.0, 0.0),
        2 => Vec4::new(v.x, v.y, 0.0, 0.0),
        3 => v.truncate().extend(0.0),
        _ => v,
    }
}

fn map(v: Vec4, f: impl Fn(f32) -> f32) -> Vec4 {
    Vec4::new(f(v.x), f(v.y), f(v.z), f(v.w))
}

fn map2(a: Vec4, b: Vec4, f: impl Fn(f32, f32) -> f32) -> Vec4 {
    Vec4::new(f(a.x, b.x), f(a.y, b.y), f(a.z, b.z), f(a.w, b.w))
}

impl HitExpr {
    /// [`HitExpr::eval`] with every lane that is NaN or infinite read as 0: what a material
    /// uses (a colour, a weight, a roughness), so that no division by zero in a module
    /// reaches the film.
    #[inline]
    pub fn eval_finite(&self, s: &State) -> Vec4 {
        self.eval_finite_with(s, &Evaluation::new())
    }

    /// [`HitExpr::eval_finite`] as part of evaluation `ev`, whose other expressions share
    /// the results of its loops of the hit (each runs once in it).
    #[inline]
    pub fn eval_finite_with(&self, s: &State, ev: &Evaluation) -> Vec4 {
        let v = self.eval_in(s, Top(ev));
        if v.is_finite() {
            v
        } else {
            map(v, |x| if x.is_finite() { x } else { 0.0 })
        }
    }

    /// The value at the shading point `s`.
    #[inline]
    pub fn eval(&self, s: &State) -> Vec4 {
        self.eval_in(s, Top(&Evaluation::new()))
    }

    /// The value at the shading point `s` inside the per-hit loops whose slots `f` holds.
    pub fn eval_in<F: Slots>(&self, s: &State, f: F) -> Vec4 {
        match self {
            HitExpr::Slot(k) => f.slot(*k),
            HitExpr::LoopOut(l, k) => l.value(s, f, *k),
            HitExpr::Const(v) => *v,
            HitExpr::State(what) => state_value(*what, s),
            HitExpr::Unary(op, a) => {
                let a = a.eval_in(s, f);
                match op {
                    UnOp::Neg => -a,
                    UnOp::Not => truth(a.x == 0.0),
                }
            }
            HitExpr::Binary(op, a, b) => binary(*op, a.eval_in(s, f), b.eval_in(s, f)),
            HitExpr::Select(c, a, b) => {
                if c.eval_in(s, f).x != 0.0 {
                    a.eval_in(s, f)
                } else {
                    b.eval_in(s, f)
                }
            }
            HitExpr::Math(func, args) => {
                let arg = |i: usize| args.get(i).map_or(Vec4::ZERO, |a| a.eval_in(s, f));
                let (a, b, c) = (arg(0), arg(1), arg(2));
                math(*func, a, b, c)
            }
            HitExpr::Lane(a, i) => splat(a.eval_in(s, f)[(*i as usize).min(3)]),
            HitExpr::Compose(parts) => {
                let mut out = [0.0f32; 4];
                let mut at = 0;
                for (p, width) in parts.iter() {
                    let v = p.eval_in(s, f);
                    for k in 0..*width as usize {
                        if at < 4 {
                            out[at] = v[k.min(3)];
                            at += 1;
                        }
                    }
                }
                Vec4::from_array(out)
            }
            HitExpr::Transform { matrix, of, point } => {
                let v = of.eval_in(s, f).truncate();
                if *point {
                    let p = *matrix * v.extend(1.0);
                    let p3 = if p.w != 0.0 && p.w != 1.0 { p.truncate() / p.w } else { p.truncate() };
                    p3.extend(0.0)
                } else {
                    let d = matrix.transform_vector3(v);
                    d.normalize_or(v).extend(0.0)
                }
            }
            HitExpr::Lookup { image, coord, wrap, clip, crop } => {
                let c = coord.eval_in(s, f);
                if *clip && !((0.0..1.0).contains(&c.x) && (0.0..1.0).contains(&c.y)) {
                    return Vec4::ZERO;
                }
                let (Some(u), Some(v)) = (mdl::texture::wrap(c.x, wrap[0]), mdl::texture::wrap(c.y, wrap[1])) else {
                    return Vec4::ZERO;
                };
                // The wrapped coordinate covers the crop window of the image.
                let u = crop[0] + u * (crop[1] - crop[0]);
                let v = crop[2] + v * (crop[3] - crop[2]);
                image.0.lookup(Vec3A::new(u, v, 0.0), 0.0).unwrap_or(Vec4::ZERO)
            }
            HitExpr::Texel { image, coord } => {
                let c = coord.eval_in(s, f);
                image.texel(c.x.floor(), c.y.floor())
            }
            HitExpr::Lookup3d { volume, coord, wrap, crop } => {
                volume.lookup(coord.eval_in(s, f).truncate().into(), *wrap, *crop)
            }
            HitExpr::Texel3d { volume, coord } => {
                let c = coord.eval_in(s, f).floor();
                volume.texel(c.x as i64, c.y as i64, c.z as i64)
            }
            HitExpr::LookupCube { cube, dir } => cube.lookup(dir.eval_in(s, f).truncate().into()),
            HitExpr::LookupPtex { ptex, channel } => ptex.lookup_at(s, *channel),
            HitExpr::Pattern(p, at) => p.eval(at.eval_in(s, f).truncate().into()),
            HitExpr::Sky(sky, args) => {
                let dir =
                    args.first().map_or(Vec3A::Z, |d| Vec3A::from(d.eval_in(s, f).truncate()).normalize_or(Vec3A::Z));
                let mut values = [Vec4::ZERO; SkyParam::ALL.len()];
                for (v, a) in values.iter_mut().zip(args.iter().skip(1)) {
                    *v = a.eval_in(s, f);
                }
                sky.radiance(dir, &values).extend(0.0)
            }
            HitExpr::Bump { height, position, tangent_u, tangent_v, normal, factor, delta } => {
                let p = Vec3A::from(position.eval_in(s, f).truncate());
                let n = Vec3A::from(normal.eval_in(s, f).truncate());
                let h0 = height.eval(p).x;
                let hu = height.eval(p + Vec3A::X * delta[0]).x;
                let hv = height.eval(p + Vec3A::Y * delta[1]).x;
                let (tu, tv) =
                    (Vec3A::from(tangent_u.eval_in(s, f).truncate()), Vec3A::from(tangent_v.eval_in(s, f).truncate()));
                let bent = n - (tu * (hu - h0) + tv * (hv - h0)) * *factor;
                bent.normalize_or(n).extend(0.0)
            }
        }
    }
}

fn state_value(f: StateFn, s: &State) -> Vec4 {
    let v = match f {
        StateFn::Position => s.point,
        StateFn::Normal => s.normal,
        StateFn::GeometryNormal => s.normal_geom,
        StateFn::Direction => s.dir,
        StateFn::Motion => s.motion,
        StateFn::TextureCoordinate(i) => s.tex(i as usize),
        StateFn::TangentU => mdl::texture::surface_tangents(s).0,
        StateFn::TangentV => mdl::texture::surface_tangents(s).1,
        StateFn::ObjectPosition => s.world_to_object.transform_point3a(s.point),
        StateFn::ObjectAxisX => s.object_to_world.transform_vector3a(Vec3A::X).normalize_or(Vec3A::X),
        StateFn::ObjectAxisY => s.object_to_world.transform_vector3a(Vec3A::Y).normalize_or(Vec3A::Y),
        StateFn::ObjectAxisZ => s.object_to_world.transform_vector3a(Vec3A::Z).normalize_or(Vec3A::Z),
        StateFn::ObjectToWorld(i) => affine_column(&s.object_to_world, i),
        StateFn::WorldToObject(i) => affine_column(&s.world_to_object, i),
        StateFn::Time => return splat(s.time),
        StateFn::ObjectId => return splat(s.label as f32),
    };
    v.extend(0.0)
}

/// Column `i` of an affine map (3: the translation).
fn affine_column(m: &glam::Affine3A, i: u8) -> Vec3A {
    match i {
        0 => m.matrix3.x_axis,
        1 => m.matrix3.y_axis,
        2 => m.matrix3.z_axis,
        _ => m.translation,
    }
}

fn binary(op: BinOp, a: Vec4, b: Vec4) -> Vec4 {
    match op {
        BinOp::Add => a + b,
        BinOp::Sub => a - b,
        BinOp::Mul => a * b,
        BinOp::Div => a / b,
        BinOp::Rem => map2(a, b, |x, y| x % y),
        BinOp::Lt => truth(a.x < b.x),
        BinOp::Le => truth(a.x <= b.x),
        BinOp::Gt => truth(a.x > b.x),
        BinOp::Ge => truth(a.x >= b.x),
        BinOp::Eq => truth(a == b),
        BinOp::Ne => truth(a != b),
        BinOp::And => truth(a.x != 0.0 && b.x != 0.0),
        BinOp::Or => truth(a.x != 0.0 || b.x != 0.0),
    }
}

pub(super) fn math(f: MathFn, a: Vec4, b: Vec4, c: Vec4) -> Vec4 {
    use MathFn::*;
    match f {
        Min => a.min(b),
        Max => a.max(b),
        Clamp => a.max(b).min(c),
        Saturate => a.clamp(Vec4::ZERO, Vec4::ONE),
        Lerp => a + (b - a) * c,
        Step => map2(a, b, |edge, x| if x < edge { 0.0 } else { 1.0 }),
        Smoothstep => {
            let t = ((c - a) / (b - a)).clamp(Vec4::ZERO, Vec4::ONE);
            t * t * (Vec4::splat(3.0) - 2.0 * t)
        }
        Sqrt => map(a, f32::sqrt),
        Exp => map(a, f32::exp),
        Exp2 => map(a, f32::exp2),
        Log => map(a, f32::ln),
        Log2 => map(a, f32::log2),
        Log10 => map(a, f32::log10),
        Pow => map2(a, b, f32::powf),
        Abs => a.abs(),
        Sign => map(a, |x| {
            if x > 0.0 {
                1.0
            } else if x < 0.0 {
                -1.0
            } else {
                0.0
            }
        }),
        Floor => a.floor(),
        Ceil => a.ceil(),
        Round => a.round(),
        Trunc => a.trunc(),
        Frac => a - a.floor(),
        Fmod => map2(a, b, |x, y| x % y),
        Sin => map(a, f32::sin),
        Cos => map(a, f32::cos),
        Tan => map(a, f32::tan),
        Asin => map(a, f32::asin),
        Acos => map(a, f32::acos),
        Atan => map(a, f32::atan),
        Atan2 => map2(a, b, f32::atan2),
        Radians => a * (std::f32::consts::PI / 180.0),
        Degrees => a * (180.0 / std::f32::consts::PI),
        Dot(n) => splat(lanes(a, n).dot(lanes(b, n))),
        Length(n) => splat(lanes(a, n).length()),
        Distance(n) => splat(lanes(a - b, n).length()),
        Normalize(n) => lanes(a, n).normalize_or_zero(),
        Cross => a.truncate().cross(b.truncate()).extend(0.0),
        Luminance => splat(bsdf::color::luminance(bsdf::Rgb::new(a.x, a.y, a.z))),
        Blackbody => super::super::spectral::blackbody_rgb(a.x).extend(0.0),
        Average(n) => splat(lanes(a, n).element_sum() / f32::from(n.max(1))),
        MaxValue(n) => splat(a.to_array()[..n.clamp(1, 4) as usize].iter().copied().fold(f32::MIN, f32::max)),
        MinValue(n) => splat(a.to_array()[..n.clamp(1, 4) as usize].iter().copied().fold(f32::MAX, f32::min)),
        Mono(mode) => splat(mdl::texture::mono(a, mode)),
        Blend(mode) => {
            let below = Vec3A::from(a.truncate());
            mdl::texture::blend_layer(mode, below, Vec3A::from(b.truncate()), c.x.clamp(0.0, 1.0)).extend(0.0)
        }
        Project(mode) => {
            super::super::projection::coordinate(mode, a.truncate(), b.truncate(), c.truncate()).extend(0.0)
        }
        ProjectAxis(mode, i) => {
            super::super::projection::axis(mode, a.truncate(), b.truncate(), c.truncate(), i).extend(0.0)
        }
        SurfaceTangent(i) => {
            super::super::projection::surface_tangent(a.truncate(), b.truncate(), c.truncate(), i).extend(0.0)
        }
    }
}
