//! `mia_physicalsun`: the sun of the Architectural library's daylight system, a light shader
//! for a directional light, and the sun's colour shared with `mia_physicalsky`.
//!
//! The sun is what the manual describes: a 5900 K black body giving 127 500 lux outside the
//! atmosphere, attenuated on its way down by the atmosphere of Preetham, Shirley and Smits,
//! "A Practical Analytic Model for Daylight" (SIGGRAPH 1999, appendix A.2): Rayleigh
//! scattering `exp(−0.008735 λ^−4.08 m)`, aerosols after Ångström `exp(−β λ^−α m)` with
//! α = 1.3 and β = 0.04608 T − 0.04586 (T the turbidity), and ozone `exp(−k_o(λ) l m)`
//! with l = 0.35 cm; m is the relative optical air mass of Kasten (1966), as in the paper.
//! The product is integrated over the visible spectrum (380–780 nm, 5 nm steps) against
//! the CIE 1931 colour-matching functions and turned into linear Rec.709 RGB, so that the
//! luminance of the result is the sun's illuminance in lux on a plane facing it.
//!
//! mira's choices where the sources stop: ozone's Chappuis band, tabulated in the paper, is
//! a Gaussian here (peak 0.12 cm⁻¹ at 600 nm, σ 55 nm: within 0.01 cm⁻¹ of the table across
//! the visible); the water-vapour and mixed-gas bands of the paper lie mostly beyond 690 nm,
//! where the eye's response is small, and are left out; the colour-matching functions are
//! the multi-lobe Gaussian fit of Wyman, Sloan and Shirley (JCGT 2013).

use shader::{rgb, rgba, Color, Ctx, NodeId, ShaderImpl, Value};
pub use sky::sun::*;

/// `mia_physicalsun` as a light shader on a directional light: the sun's colour for its
/// elevation and the haze (see [`PhysicalSun::color`]), shadowed. With `samples` > 1 and
/// `shadow_softness` > 0 the shadow is the mean of `samples` shadow rays spread over the
/// sun's disk ([`PhysicalSun::shadow_cone`]), stratified: soft shadows from one light
/// sample. Photon emission (`photon_bbox_*`, `automatic_photon_energy`) is not used: mira's
/// classic engine has no photon map.
pub static MIA_PHYSICALSUN: ShaderImpl = ShaderImpl {
    name: "mia_physicalsun",
    params: &[
        "on",
        "multiplier",
        "rgb_unit_conversion",
        "haze",
        "redblueshift",
        "saturation",
        "horizon_height",
        "shadow_softness",
        "samples",
        "y_is_up",
        "illuminance_mode",
        "direct_normal_illuminance",
    ],
    run: physicalsun,
    ..ShaderImpl::PLAIN
};

/// The sun parameters of node `n`.
pub fn sun_of(ctx: &mut Ctx, n: NodeId) -> PhysicalSun {
    PhysicalSun {
        on: ctx.bool(n, 0),
        multiplier: ctx.scalar(n, 1),
        rgb_unit_conversion: rgb(ctx.color(n, 2)),
        haze: ctx.scalar(n, 3),
        redblueshift: ctx.scalar(n, 4),
        saturation: ctx.scalar(n, 5),
        horizon_height: ctx.scalar(n, 6),
        shadow_softness: ctx.scalar(n, 7),
        samples: ctx.int(n, 8),
        y_is_up: ctx.bool(n, 9),
        illuminance_mode: ctx.int(n, 10),
        direct_normal_illuminance: ctx.scalar(n, 11),
    }
}

fn physicalsun(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let sun = sun_of(ctx, n);
    let to_sun = -ctx.state.dir;
    let Some(c) = sun.color(to_sun) else { return false };
    let color: Color = rgba(c, 1.0);
    let radius = sun.shadow_cone();
    let shadowed = if sun.samples > 1 && radius > 0.0 {
        let count = sun.samples as u32;
        let site = ctx.next_site();
        let saved = ctx.state.dir;
        let mut sum = Color::ZERO;
        for i in 0..count {
            let j = ctx.sample2(site, i, count);
            ctx.state.dir = -cone_direction(to_sun, radius, j.x, j.y);
            let mut filter = color;
            ctx.trace_shadow(&mut filter);
            sum += filter;
        }
        ctx.state.dir = saved;
        sum / count as f32
    } else {
        let mut filter = color;
        ctx.trace_shadow(&mut filter);
        filter
    };
    *out = Value::Color(Color::new(shadowed.x, shadowed.y, shadowed.z, 1.0));
    shadowed.x > 0.0 || shadowed.y > 0.0 || shadowed.z > 0.0
}
