//! `::base`'s functions of volume textures, called inside module materials:
//! `lookup_volume_coefficients` (a density `texture_3d` scaling uniform scattering and
//! absorption coefficients) and `volume_blackbody_emission` (a temperature `texture_3d` as
//! black body emission), built as [`HitExpr`] trees as the MDL SDK's `base.mdl` defines
//! them.
//!
//! Both read their textures at the shading point in object space (`state::position()`
//! through the instance's world-to-object matrix), through the `transform` argument (a
//! constant affine `float4x4`, column vectors), with `tex::wrap_clip` on every axis: a
//! volume texture fills the unit cube [0, 1]³ of that space and is 0 outside it.
//!
//! In the path engine a medium is homogeneous inside its object: coefficients from
//! `lookup_volume_coefficients` are evaluated where a path enters the object
//! ([`super::volume`]), so the density seen is the texture on the surface at the entry
//! point, not along the path. `volume_blackbody_emission` is rendered as a volume's
//! `emission_intensity` (the medium's emission, taken where the path enters) and as a
//! surface's emission intensity.

use std::sync::Arc;

use glam::{Mat4, Vec4};
use mdl_lang::Function;
use mi::Span;

use super::eval::{problem, Eval, Problem};
use super::hit::{fold, BinOp, HitExpr, MathFn, StateFn};
use super::hit_base::Args;
use super::value::{HitType, Value};

/// The volume functions' own readers of a `::base` call's arguments.
impl Args<'_> {
    /// A constant colour (`default` grey when absent).
    fn color(&self, p: &str, default: f32) -> Result<Arc<HitExpr>, Problem> {
        match self.get(p) {
            None => Ok(constant(Vec4::splat(default))),
            Some(v) => {
                let c = v.color().ok_or_else(|| self.not_constant(p, v))?;
                Ok(constant(c.extend(0.0)))
            }
        }
    }

    /// The `transform` argument: a constant affine matrix (identity when absent).
    fn transform(&self) -> Result<Mat4, Problem> {
        let m = match self.get("transform") {
            None => return Ok(Mat4::IDENTITY),
            Some(v) if super::matrix::mat4(v).is_some() => super::matrix::mat4(v).unwrap_or_default(),
            Some(v) => return Err(self.not_constant("transform", v)),
        };
        if m.row(3) != Vec4::W {
            return Err(problem(
                self.span,
                format!(
                    "`base::{}` with a projective `transform` (last row not 0 0 0 1) is not compiled",
                    self.def.name
                ),
            ));
        }
        Ok(m)
    }

    /// The value of `texture_3d` parameter `p` at the lookup position `uvw`, as a float3
    /// (lane x for a float lookup); `None` for the invalid texture.
    fn lookup(&self, p: &str, uvw: &Arc<HitExpr>) -> Result<Option<Arc<HitExpr>>, Problem> {
        match self.get(p) {
            Some(Value::Texture3d(Some(volume))) => Ok(Some(fold(HitExpr::Lookup3d {
                volume: volume.clone(),
                coord: uvw.clone(),
                wrap: ["wrap_clip"; 3],
                crop: [[0.0, 1.0]; 3],
            }))),
            Some(Value::Texture3d(None)) | None => Ok(None),
            Some(v) => Err(self.not_constant(p, v)),
        }
    }

    /// Where the textures are read: the object-space position through `transform`.
    fn object_uvw(&self) -> Result<Arc<HitExpr>, Problem> {
        let position = Arc::new(HitExpr::State(StateFn::ObjectPosition));
        Ok(fold(HitExpr::Transform { matrix: self.transform()?, of: position, point: true }))
    }
}

fn constant(v: Vec4) -> Arc<HitExpr> {
    Arc::new(HitExpr::Const(v))
}

fn num(x: f32) -> Arc<HitExpr> {
    constant(Vec4::splat(x))
}

fn bin(op: BinOp, a: Arc<HitExpr>, b: Arc<HitExpr>) -> Arc<HitExpr> {
    fold(HitExpr::Binary(op, a, b))
}

/// The first three lanes of `e` (a colour from a float3 lookup).
fn rgb(e: Arc<HitExpr>) -> Arc<HitExpr> {
    fold(HitExpr::Compose([(e, 3)].into()))
}

/// `base::lookup_volume_coefficients`: with d the density texture's float3 at the
/// shading point × `density_multiplier` (× the instance's scale, object to world, when
/// `density_relative_to_size`), the scattering coefficient is `scattering_multiplier` · d +
/// `scattering_offset` · `density_multiplier`, the absorption coefficient likewise.
pub fn lookup_volume_coefficients(def: &Function, args: &[Value], span: Span) -> Eval {
    let a = Args { def, args, span };
    let density_multiplier = a.num("density_multiplier", 1.0)?;
    let uvw = a.object_uvw()?;
    let texel = a.lookup("density", &uvw)?.unwrap_or_else(|| num(0.0));
    let mut density = bin(BinOp::Mul, rgb(texel), num(density_multiplier));
    match a.get("density_relative_to_size") {
        None | Some(Value::Bool(false)) => {}
        Some(Value::Bool(true)) => {
            let scale = super::state_space::transform(
                "transform_scale",
                &[Value::Int(1), Value::Int(2), Value::Float(1.0)],
                span,
            )?;
            let scale = scale.to_hit().ok_or_else(|| problem(span, "the instance's scale"))?;
            density = bin(BinOp::Mul, density, scale);
        }
        Some(v) => return Err(a.not_constant("density_relative_to_size", v)),
    }
    let coefficient = |multiplier: &str, offset: &str| -> Result<Value, Problem> {
        let scaled = bin(BinOp::Mul, a.color(multiplier, 0.0)?, density.clone());
        let offset = bin(BinOp::Mul, a.color(offset, 0.0)?, num(density_multiplier));
        Ok(Value::from_hit((*bin(BinOp::Add, scaled, offset)).clone(), HitType::Color))
    };
    Ok(Value::Struct(
        "volume_coefficients".into(),
        vec![
            ("scattering_coefficient".into(), coefficient("scattering_multiplier", "scattering_offset")?),
            ("absorption_coefficient".into(), coefficient("absorption_multiplier", "absorption_offset")?),
        ],
    ))
}

/// The coefficients of the MDL SDK's rational fit of the natural logarithm of a black
/// body's luminance per µm against its temperature t (kelvin): numerator and denominator
/// polynomials in t, lowest power first.
const LUMINANCE_FIT: ([f32; 5], [f32; 5]) = (
    [1.0, -8.814_886_5e2, -9.731_166_3e4, 1.299_717_4e2, 4.836_009_7e-4],
    [-3.839_857e-2, -4.604_076e3, 1.923_880_6e2, 4.005_696_1, 1.140_000_8e-5],
);

/// A polynomial of `t` with coefficients `c` (lowest power first), by Horner's rule.
fn polynomial(c: &[f32; 5], t: &Arc<HitExpr>) -> Arc<HitExpr> {
    let mut acc = num(c[4]);
    for k in (0..4).rev() {
        acc = bin(BinOp::Add, num(c[k]), bin(BinOp::Mul, t.clone(), acc));
    }
    acc
}

/// `base::volume_blackbody_emission`: with T = max(500, the temperature texture's value ×
/// `temperature_mult` + `temperature_offset`) kelvin at the shading point, the black body
/// colour of T (luminance 1) × exp(fit(T)) × `scale` / 1000 (× the density texture's value
/// when it is valid; at least 0) × `tint`.
pub fn volume_blackbody_emission(def: &Function, args: &[Value], span: Span) -> Eval {
    let a = Args { def, args, span };
    let uvw = a.object_uvw()?;
    let Some(temperature) = a.lookup("temperature", &uvw)? else {
        // The invalid texture reads 0: 500 K.
        let t = constant(Vec4::ZERO);
        return emission(&a, t, None);
    };
    let density = a.lookup("density", &uvw)?;
    emission(&a, fold(HitExpr::Lane(temperature, 0)), density)
}

/// The emission of [`volume_blackbody_emission`] for a raw temperature sample `sample`.
fn emission(a: &Args, sample: Arc<HitExpr>, density: Option<Arc<HitExpr>>) -> Eval {
    let scaled = bin(
        BinOp::Add,
        bin(BinOp::Mul, sample, num(a.num("temperature_mult", 1.0)?)),
        num(a.num("temperature_offset", 0.0)?),
    );
    let t = fold(HitExpr::Math(MathFn::Max, [num(500.0), scaled].into()));
    let log = bin(BinOp::Div, polynomial(&LUMINANCE_FIT.0, &t), polynomial(&LUMINANCE_FIT.1, &t));
    let mut intensity =
        bin(BinOp::Mul, fold(HitExpr::Math(MathFn::Exp, [log].into())), num(a.num("scale", 1.0)? / 1000.0));
    if let Some(d) = density {
        intensity = bin(BinOp::Mul, intensity, fold(HitExpr::Lane(d, 0)));
    }
    let intensity = fold(HitExpr::Math(MathFn::Max, [num(0.0), intensity].into()));
    let colour = fold(HitExpr::Math(MathFn::Blackbody, [t].into()));
    let tinted = bin(BinOp::Mul, bin(BinOp::Mul, colour, intensity), a.color("tint", 1.0)?);
    Ok(Value::from_hit((*tinted).clone(), HitType::Color))
}
