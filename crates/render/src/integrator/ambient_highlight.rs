//! The highlight of Maya volume lights with `emitAmbient` and `emitSpecular` in the path
//! engine.
//!
//! Such a light lights the classic Maya materials in two parts: as Maya's ambient light
//! (no BSDF; added at each hit, see `material::emission::ambient`), and on the highlight
//! alone, as a light from its (turned) direction lights it. The path engine adds the
//! second part as the classic material does: `specularColor` ⊙ light ⊙ the material's
//! highlight formula ([`material::maya::MayaHighlight`]; blinn, phong, phongE). For the
//! other Maya materials (anisotropic, rampShader, layeredShader) it is the material's
//! reflection lobes without the diffuse one ([`bsdf::Unified::eval_glossy`]) under the
//! light's irradiance, as every other Maya light's highlight is given by the BSDF; a
//! lambert has none, as in the classic engine.

use bsdf::{Bsdf, Frame, Rgb};
use glam::Vec3A;
use material::emission::ambient::AmbientLight;
use material::maya::MayaHighlight;

/// Where the highlight is seen from: the shading point and its frame.
pub struct Viewpoint<'a> {
    /// The shading point (world).
    pub p: Vec3A,
    /// The unit shading normal (world), on the viewer's side.
    pub ns: Vec3A,
    /// The unit geometric normal (world), on the viewer's side.
    pub ng: Vec3A,
    /// The shading frame.
    pub frame: &'a Frame,
    /// The unit direction towards the viewer, local to `frame`.
    pub wo: Vec3A,
}

/// The radiance towards the viewer that `light`'s highlight adds at `at` on a material of
/// classic highlight `classic` and BSDF `bsdf`, with the fraction `through` of the light's
/// shadow rays let through: zero for other lights, for a light below the surface and for
/// materials without a highlight.
pub fn radiance(
    light: &AmbientLight,
    at: &Viewpoint,
    through: Rgb,
    classic: Option<&MayaHighlight>,
    bsdf: &Bsdf,
) -> Rgb {
    let Some((towards, irradiance)) = light.highlight_at(at.p, through) else { return Rgb::ZERO };
    if towards.dot(at.ns) <= 0.0 || towards.dot(at.ng) <= 0.0 {
        return Rgb::ZERO;
    }
    if let Some(h) = classic {
        // The classic light's colour is the irradiance without π; a connected
        // `specularColor` is the hit's (the factor the BSDF's tint was multiplied by).
        let v = at.frame.to_world(at.wo);
        let value = h.model.value(at.ns, v, towards);
        let per_hit = match bsdf {
            Bsdf::Maya(b) => b.tinted_by,
            _ => Rgb::ONE,
        };
        return h.color * per_hit * irradiance * value / std::f32::consts::PI;
    }
    let wi = at.frame.to_local(towards);
    let f = match bsdf {
        Bsdf::Unified(u) => u.eval_glossy(at.wo, wi),
        _ => Rgb::ZERO,
    };
    f * irradiance * wi.z
}
