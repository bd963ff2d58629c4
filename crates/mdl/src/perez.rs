//! MDL `::base::perez_sun_and_sky` as a `.mi` environment shader
//! (`mdl::base::perez_sun_and_sky`): Perez's all-weather sky from measured irradiances
//! ([`sky::perez::PerezSky`]; the model, its sources and units are documented there).
//!
//! The sky is set up once per node and render from its parameters (the MDL SDK's
//! `base.mdl` declares them `uniform`); `ground_color`, the one parameter MDL lets vary,
//! is read at each lookup.

use glam::Vec3A;

use shader::rgb;
use shader::{Color, Ctx, NodeId, ShaderImpl, Value};
use sky::perez::{PerezSky, PerezSunAndSky};

/// `mdl::base::perez_sun_and_sky (direct_normal_irradiance, diffuse_horizontal_irradiance,
/// sun_direction, ground_color, horizon_blur, y_is_up, julian_date, dew_point, haze)`: the
/// sky's radiance (cd/m², linear RGB) in the ray's direction, alpha 1.
pub static PEREZ_SUN_AND_SKY: ShaderImpl = ShaderImpl {
    name: "mdl::base::perez_sun_and_sky",
    params: &[
        "direct_normal_irradiance",
        "diffuse_horizontal_irradiance",
        "sun_direction",
        "ground_color",
        "horizon_blur",
        "y_is_up",
        "julian_date",
        "dew_point",
        "haze",
    ],
    run: perez_sun_and_sky,
    ..ShaderImpl::PLAIN
};

/// The parameters of `perez_sun_and_sky` node `n`.
pub fn perez_of(ctx: &mut Ctx, n: NodeId) -> PerezSunAndSky {
    PerezSunAndSky {
        direct_normal_irradiance: ctx.scalar(n, 0),
        diffuse_horizontal_irradiance: ctx.scalar(n, 1),
        sun_direction: ctx.vector(n, 2),
        ground_color: rgb(ctx.color(n, 3)),
        horizon_blur: ctx.scalar(n, 4),
        y_is_up: ctx.bool(n, 5),
        julian_date: ctx.scalar(n, 6),
        dew_point: ctx.scalar(n, 7),
        haze: ctx.scalar(n, 8),
    }
}

fn perez_sun_and_sky(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let params = perez_of(ctx, n);
    let shading = ctx.shading();
    let Some(base) = shading.precomputed.get_or_init(n, || PerezSky::new(params)) else { return false };
    let sky = base.with_ground(params.ground_color);
    let c = sky.radiance(ctx.state.dir.normalize_or(Vec3A::Z));
    *out = Value::Color(Color::new(c.x, c.y, c.z, 1.0));
    true
}

/// The sky of `perez_sun_and_sky` node `n` (set up from its parameters now).
pub fn sky_of(ctx: &mut Ctx, n: NodeId) -> PerezSky {
    PerezSky::new(perez_of(ctx, n))
}
