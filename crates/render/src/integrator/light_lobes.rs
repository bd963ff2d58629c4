//! Maya's `emitDiffuse` and `emitSpecular` in the path engine: which of a material's
//! lobes a light lights ([`material::emission::maya::LightLobes`]).
//!
//! A light with both on (every light but Maya's with one of them off) lights the whole
//! BSDF. Otherwise a Maya material's BSDF is split as the classic shaders split the
//! light: its Lambertian lobe (albedo/π, [`bsdf::MayaBsdf::diffuse`]) is the diffuse
//! part and Maya's highlight the specular one; a unified BSDF (anisotropic, rampShader,
//! layeredShader) gives its reflection lobes ([`bsdf::Unified::eval_glossy`]) as the
//! specular part and the rest as the diffuse one; `mib_glossy_reflection`'s base is the
//! diffuse part and its glossy lobe the specular one; Lambertian and Oren–Nayar surfaces
//! are all diffuse. Any other BSDF is lit whole by a light with `emitDiffuse` on and
//! not at all by one with it off.

use bsdf::{Bsdf, Rgb};
use glam::Vec3A;
use material::emission::maya::LightLobes;

/// f(ωo, ωi) of the lobes of `bsdf` that a light of `lobes` lights (see the module doc).
#[inline]
pub(super) fn eval(bsdf: &Bsdf, wo: Vec3A, wi: Vec3A, lobes: LightLobes) -> Rgb {
    if lobes.diffuse && lobes.specular {
        return bsdf.eval(wo, wi);
    }
    split(bsdf, wo, wi, lobes)
}

/// [`eval`] for a light that lights only part of the lobes (out of line: rare).
#[inline(never)]
fn split(bsdf: &Bsdf, wo: Vec3A, wi: Vec3A, lobes: LightLobes) -> Rgb {
    let (diffuse, specular) = match bsdf {
        Bsdf::Maya(b) => {
            let all = b.eval(wo, wi);
            // The translucence is diffuse light too (the classic shaders' light from behind).
            let d =
                if wo.z * wi.z > 0.0 { b.diffuse * std::f32::consts::FRAC_1_PI } else { b.eval_translucence(wo, wi) };
            (d, (all - d).max(Rgb::ZERO))
        }
        Bsdf::Unified(u) => {
            let g = u.eval_glossy(wo, wi);
            ((u.eval(wo, wi) - g).max(Rgb::ZERO), g)
        }
        Bsdf::MibGlossy(g) => g.eval_split(wo, wi),
        Bsdf::MibGlossyRefraction(g) => g.eval_split(wo, wi),
        Bsdf::Lambert(_) | Bsdf::OrenNayar(_) => (bsdf.eval(wo, wi), Rgb::ZERO),
        _ => (bsdf.eval(wo, wi), Rgb::ZERO),
    };
    let pick = |on: bool, f: Rgb| if on { f } else { Rgb::ZERO };
    pick(lobes.diffuse, diffuse) + pick(lobes.specular, specular)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A blinn-like Maya BSDF split by the mask: the diffuse part alone is albedo/π, the
    /// specular part the rest, the two add up to the whole (within 1e-6), and a mask
    /// with neither gives zero.
    #[test]
    fn the_parts_of_a_maya_bsdf_add_up() {
        let shape = bsdf::maya_highlight::Shape::Phong { power: 20.0 };
        let glossy = bsdf::MayaGlossy::new(shape, Rgb::splat(0.5));
        let b = Bsdf::Maya(glossy.bsdf(Rgb::new(0.4, 0.3, 0.2), Vec3A::Z));
        let wo = Vec3A::new(0.1, 0.0, 1.0).normalize();
        let wi = Vec3A::new(-0.1, 0.0, 1.0).normalize();
        let both = eval(&b, wo, wi, LightLobes { diffuse: true, specular: true });
        let d = eval(&b, wo, wi, LightLobes { diffuse: true, specular: false });
        let s = eval(&b, wo, wi, LightLobes { diffuse: false, specular: true });
        assert!((d - Rgb::new(0.4, 0.3, 0.2) / std::f32::consts::PI).abs().max_element() < 1e-6, "{d:?}");
        assert!(s.min_element() > 0.0, "the highlight: {s:?}");
        assert!((d + s - both).abs().max_element() < 1e-6, "{d:?} + {s:?} vs {both:?}");
        assert_eq!(eval(&b, wo, wi, LightLobes { diffuse: false, specular: false }), Rgb::ZERO);
    }
}
