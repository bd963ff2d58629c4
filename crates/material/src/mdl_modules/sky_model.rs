//! The daylight environments of `::base` called in modules, as a hit expression evaluates
//! them ([`super::hit::HitExpr::Sky`]): the model set up once per call from its constant
//! parameters, and the parameters MDL declares varying that depend on the hit or the
//! direction, whose values the expression hands over at each lookup ([`SkyCall::radiance`]).
//!
//! What `base::sun_and_sky`'s radiance takes from its parameters alone is computed once per
//! call ([`sky::sky::SkySetup`] and its light terms), so a lookup only evaluates the
//! direction's part. A varying `multiplier`, `redblueshift`, `horizon_blur`, `ground_color`
//! or `night_color` leaves that part as it is (exactly the sky of those values); a
//! varying `haze` or `horizon_height` changes it: the cheap part is set up per lookup, and
//! the two costly light terms (the sun's and the sky's illuminance, which only the sun's
//! disk and the ground need) are asked for only there — for a varying haze interpolated
//! on a grid of hazes ([`sky::light_table`]) instead of integrated at each lookup (a
//! varying horizon height computes them exactly).

use glam::{Vec3A, Vec4};
use mdl::sky::SunAndSky;
use sky::perez::PerezSky;
use sky::sky::{SkyLight, SkySetup};

/// A parameter of `base::sun_and_sky` that MDL's `base.mdl` declares varying (the others
/// are `uniform`), given per lookup when it depends on the hit or the direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SkyParam {
    /// `multiplier`.
    Multiplier,
    /// `haze`.
    Haze,
    /// `redblueshift`.
    RedBlueShift,
    /// `horizon_height`.
    HorizonHeight,
    /// `horizon_blur`.
    HorizonBlur,
    /// `ground_color`.
    GroundColor,
    /// `night_color`.
    NightColor,
}

impl SkyParam {
    /// Every one, with its MDL name.
    pub const ALL: [(SkyParam, &'static str); 7] = [
        (SkyParam::Multiplier, "multiplier"),
        (SkyParam::Haze, "haze"),
        (SkyParam::RedBlueShift, "redblueshift"),
        (SkyParam::HorizonHeight, "horizon_height"),
        (SkyParam::HorizonBlur, "horizon_blur"),
        (SkyParam::GroundColor, "ground_color"),
        (SkyParam::NightColor, "night_color"),
    ];
}

/// The daylight model of a call.
#[derive(Clone, Debug, PartialEq)]
pub enum SkyModel {
    /// `base::sun_and_sky`.
    SunAndSky(SunAndSky),
    /// `base::perez_sun_and_sky` (its sky set up once; only `ground_color` may vary).
    Perez(Box<PerezSky>),
}

/// A call of a `::base` daylight environment: its model with the constant parameters, and
/// which parameters the expression gives per lookup (in order, after the direction).
#[derive(Clone, Debug, PartialEq)]
pub struct SkyCall {
    /// The model, its varying parameters at their defaults.
    pub model: SkyModel,
    /// The varying parameters given per lookup, in the order of their values.
    pub varying: Box<[SkyParam]>,
    /// `sun_and_sky`'s setup and light terms for the model's parameters.
    prepared: Option<(SkySetup, SkyLight)>,
}

impl SkyCall {
    /// A call of `model` whose parameters `varying` are given per lookup.
    pub fn new(model: SkyModel, varying: Box<[SkyParam]>) -> SkyCall {
        let prepared = match &model {
            SkyModel::SunAndSky(s) => {
                let setup = s.sky.setup();
                Some((setup, setup.light()))
            }
            SkyModel::Perez(_) => None,
        };
        SkyCall { model, varying, prepared }
    }

    /// A call whose parameters are all constant.
    pub fn constant(model: SkyModel) -> SkyCall {
        SkyCall::new(model, Box::new([]))
    }

    /// The radiance looking along unit world direction `dir` (output units, linear RGB),
    /// the varying parameters taking `values` (lane x for numbers, x, y, z for colours).
    pub fn radiance(&self, dir: Vec3A, values: &[Vec4]) -> Vec3A {
        match &self.model {
            SkyModel::SunAndSky(base) => {
                let Some((setup, light)) = &self.prepared else { return base.radiance(dir) };
                if !base.on {
                    return Vec3A::ZERO;
                }
                if self.varying.is_empty() {
                    return base.sky.radiance_in(setup, dir, &mut || *light) * std::f32::consts::PI;
                }
                let mut sky = *base;
                for (p, v) in self.varying.iter().zip(values) {
                    let s = &mut sky.sky;
                    match p {
                        SkyParam::Multiplier => s.multiplier = v.x,
                        SkyParam::Haze => s.haze = v.x,
                        SkyParam::RedBlueShift => s.redblueshift = v.x,
                        SkyParam::HorizonHeight => s.horizon_height = v.x,
                        SkyParam::HorizonBlur => s.horizon_blur = v.x,
                        SkyParam::GroundColor => s.ground_color = v.truncate().into(),
                        SkyParam::NightColor => s.night_color = v.truncate().into(),
                    }
                }
                let sky = sky.sky;
                let moves = |p: &SkyParam| matches!(p, SkyParam::Haze | SkyParam::HorizonHeight);
                let radiance = if !self.varying.iter().any(moves) {
                    // The setup does not depend on what varies.
                    sky.radiance_in(setup, dir, &mut || *light)
                } else {
                    let own = sky.setup_like(setup);
                    let height_varies = self.varying.contains(&SkyParam::HorizonHeight);
                    if sky.is_plain_daylight() && !height_varies {
                        let (t, z) = (own.turbidity, own.sun.z);
                        sky.radiance_in(&own, dir, &mut || sky::light_table::interpolated(t, z))
                    } else {
                        sky.radiance_in(&own, dir, &mut || own.light())
                    }
                };
                radiance * std::f32::consts::PI
            }
            SkyModel::Perez(base) => {
                let ground = self.varying.iter().zip(values).find(|(p, _)| **p == SkyParam::GroundColor);
                match ground {
                    None => base.radiance(dir),
                    Some((_, v)) => base.with_ground(v.truncate().into()).radiance(dir),
                }
            }
        }
    }
}
