//! The parameters of `mia_material` and `mia_material_x`, in their declaration order, and
//! their values at a shading point.

use glam::Vec3A;

use shader::rgb;
use shader::{Ctx, NodeId};

/// Parameter positions (the implementations list the names in this order); each variant
/// is the position of the parameter it names (the last four only in `mia_material_x`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(usize)]
pub enum P {
    /// `diffuse_weight`.
    DiffuseWeight,
    /// `diffuse`.
    Diffuse,
    /// `diffuse_roughness`.
    DiffuseRoughness,
    /// `reflectivity`.
    Reflectivity,
    /// `refl_color`.
    ReflColor,
    /// `refl_gloss`.
    ReflGloss,
    /// `refl_gloss_samples`.
    ReflGlossSamples,
    /// `refl_interpolate`.
    ReflInterpolate,
    /// `refl_hl_only`.
    ReflHlOnly,
    /// `refl_is_metal`.
    ReflIsMetal,
    /// `transparency`.
    Transparency,
    /// `refr_color`.
    RefrColor,
    /// `refr_gloss`.
    RefrGloss,
    /// `refr_ior`.
    RefrIor,
    /// `refr_gloss_samples`.
    RefrGlossSamples,
    /// `refr_interpolate`.
    RefrInterpolate,
    /// `refr_translucency`.
    RefrTranslucency,
    /// `refr_trans_color`.
    RefrTransColor,
    /// `refr_trans_weight`.
    RefrTransWeight,
    /// `anisotropy`.
    Anisotropy,
    /// `anisotropy_rotation`.
    AnisotropyRotation,
    /// `anisotropy_channel`.
    AnisotropyChannel,
    /// `brdf_fresnel`.
    BrdfFresnel,
    /// `brdf_0_degree_refl`.
    Brdf0DegreeRefl,
    /// `brdf_90_degree_refl`.
    Brdf90DegreeRefl,
    /// `brdf_curve`.
    BrdfCurve,
    /// `brdf_conserve_energy`.
    BrdfConserveEnergy,
    /// `refl_falloff_on`.
    ReflFalloffOn,
    /// `refl_falloff_dist`.
    ReflFalloffDist,
    /// `refl_falloff_color_on`.
    ReflFalloffColorOn,
    /// `refl_falloff_color`.
    ReflFalloffColor,
    /// `refl_depth`.
    ReflDepth,
    /// `refl_cutoff`.
    ReflCutoff,
    /// `refr_falloff_on`.
    RefrFalloffOn,
    /// `refr_falloff_dist`.
    RefrFalloffDist,
    /// `refr_falloff_color_on`.
    RefrFalloffColorOn,
    /// `refr_falloff_color`.
    RefrFalloffColor,
    /// `refr_depth`.
    RefrDepth,
    /// `refr_cutoff`.
    RefrCutoff,
    /// `indirect_multiplier`.
    IndirectMultiplier,
    /// `ao_on`.
    AoOn,
    /// `ao_samples`.
    AoSamples,
    /// `ao_distance`.
    AoDistance,
    /// `ao_dark`.
    AoDark,
    /// `ao_ambient`.
    AoAmbient,
    /// `ao_do_details`.
    AoDoDetails,
    /// `thin_walled`.
    ThinWalled,
    /// `no_visible_area_hl`.
    NoVisibleAreaHl,
    /// `skip_inside_refl`.
    SkipInsideRefl,
    /// `do_refractive_caustics`.
    DoRefractiveCaustics,
    /// `backface_cull`.
    BackfaceCull,
    /// `propagate_alpha`.
    PropagateAlpha,
    /// `hl_vs_refl_balance`.
    HlVsReflBalance,
    /// `cutout_opacity`.
    CutoutOpacity,
    /// `additional_color`.
    AdditionalColor,
    /// `bump`.
    Bump,
    /// `no_diffuse_bump`.
    NoDiffuseBump,
    /// `mode`.
    Mode,
    /// `lights`.
    Lights,
    /// `intr_grid_density`.
    IntrGridDensity,
    /// `bump_mode`.
    BumpMode,
    /// `overall_bump`.
    OverallBump,
    /// `standard_bump`.
    StandardBump,
}

/// The names, in the order of [`P`] (the last four only in `mia_material_x`).
pub const NAMES: &[&str] = &[
    "diffuse_weight",
    "diffuse",
    "diffuse_roughness",
    "reflectivity",
    "refl_color",
    "refl_gloss",
    "refl_gloss_samples",
    "refl_interpolate",
    "refl_hl_only",
    "refl_is_metal",
    "transparency",
    "refr_color",
    "refr_gloss",
    "refr_ior",
    "refr_gloss_samples",
    "refr_interpolate",
    "refr_translucency",
    "refr_trans_color",
    "refr_trans_weight",
    "anisotropy",
    "anisotropy_rotation",
    "anisotropy_channel",
    "brdf_fresnel",
    "brdf_0_degree_refl",
    "brdf_90_degree_refl",
    "brdf_curve",
    "brdf_conserve_energy",
    "refl_falloff_on",
    "refl_falloff_dist",
    "refl_falloff_color_on",
    "refl_falloff_color",
    "refl_depth",
    "refl_cutoff",
    "refr_falloff_on",
    "refr_falloff_dist",
    "refr_falloff_color_on",
    "refr_falloff_color",
    "refr_depth",
    "refr_cutoff",
    "indirect_multiplier",
    "ao_on",
    "ao_samples",
    "ao_distance",
    "ao_dark",
    "ao_ambient",
    "ao_do_details",
    "thin_walled",
    "no_visible_area_hl",
    "skip_inside_refl",
    "do_refractive_caustics",
    "backface_cull",
    "propagate_alpha",
    "hl_vs_refl_balance",
    "cutout_opacity",
    "additional_color",
    "bump",
    "no_diffuse_bump",
    "mode",
    "lights",
    "intr_grid_density",
    "bump_mode",
    "overall_bump",
    "standard_bump",
];

/// The names `mia_material` (the 3.5 interface) has.
pub const LEGACY_NAMES: &[&str] = NAMES.split_at(P::BumpMode as usize).0;

/// Parameter values at a shading point (the ones every shading needs; the rest are read
/// where they are used).
#[derive(Clone, Debug, PartialEq)]
pub struct Mia {
    /// `diffuse · diffuse_weight`.
    pub diffuse: Vec3A,
    /// `diffuse_roughness`.
    pub roughness: f32,
    /// `reflectivity`.
    pub reflectivity: f32,
    /// `refl_color`.
    pub refl_color: Vec3A,
    /// `refl_gloss`.
    pub refl_gloss: f32,
    /// `refl_is_metal`.
    pub metal: bool,
    /// `transparency`.
    pub transparency: f32,
    /// `refr_color`.
    pub refr_color: Vec3A,
    /// `refr_ior`.
    pub ior: f32,
    /// Translucency colour × weight when `refr_translucency` is on.
    pub transl: Vec3A,
    /// `anisotropy`.
    pub anisotropy: f32,
    /// `anisotropy_rotation` (full turns).
    pub rotation: f32,
    /// `brdf_fresnel`.
    pub fresnel: bool,
    /// R0, R90 and the curve exponent.
    pub curve: (f32, f32, f32),
    /// `brdf_conserve_energy`.
    pub conserve: bool,
    /// `hl_vs_refl_balance`.
    pub hl_balance: f32,
    /// `thin_walled`.
    pub thin_walled: bool,
}

impl Mia {
    /// Reads the parameters of node `n`.
    pub fn read(ctx: &mut Ctx, n: NodeId) -> Mia {
        let c = |ctx: &mut Ctx, p: P| rgb(ctx.color(n, p as usize));
        let s = |ctx: &mut Ctx, p: P| ctx.scalar(n, p as usize);
        let b = |ctx: &mut Ctx, p: P| ctx.bool(n, p as usize);
        let transl = if b(ctx, P::RefrTranslucency) {
            c(ctx, P::RefrTransColor) * s(ctx, P::RefrTransWeight)
        } else {
            Vec3A::ZERO
        };
        Mia {
            diffuse: c(ctx, P::Diffuse) * s(ctx, P::DiffuseWeight),
            roughness: s(ctx, P::DiffuseRoughness),
            reflectivity: s(ctx, P::Reflectivity),
            refl_color: c(ctx, P::ReflColor),
            refl_gloss: s(ctx, P::ReflGloss),
            metal: b(ctx, P::ReflIsMetal),
            transparency: s(ctx, P::Transparency),
            refr_color: c(ctx, P::RefrColor),
            ior: s(ctx, P::RefrIor),
            transl,
            anisotropy: s(ctx, P::Anisotropy),
            rotation: s(ctx, P::AnisotropyRotation),
            fresnel: b(ctx, P::BrdfFresnel),
            curve: (s(ctx, P::Brdf0DegreeRefl), s(ctx, P::Brdf90DegreeRefl), s(ctx, P::BrdfCurve)),
            conserve: b(ctx, P::BrdfConserveEnergy),
            hl_balance: s(ctx, P::HlVsReflBalance),
            thin_walled: b(ctx, P::ThinWalled),
        }
    }

    /// The layer weights seen from a direction at cosine `cos_nv` with the normal;
    /// `reflect` off takes the reflection layer away (`skip_inside_refl`).
    pub fn weights(&self, cos_nv: f32, reflect: bool) -> super::weights::LayerWeights {
        let (r0, r90, curve) = self.curve;
        let w = super::weights::brdf_curve(self.fresnel, self.ior, r0, r90, curve, cos_nv);
        let reflect = if reflect { self.refl_color * (self.reflectivity * w) } else { Vec3A::ZERO };
        super::weights::conserve(&super::weights::LayerInputs {
            diffuse: self.diffuse,
            reflect,
            refract: self.refr_color * self.transparency,
            transl: self.transl,
            metal_tint: self.metal.then_some(self.diffuse),
            conserve: self.conserve,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_the_enum_and_the_declarations() {
        assert_eq!(NAMES.len(), P::StandardBump as usize + 1);
        assert_eq!(NAMES[P::RefrIor as usize], "refr_ior");
        assert_eq!(NAMES[P::Lights as usize], "lights");
        let decls = shader::decl::Decls::default();
        for (decl, names) in [("mia_material", LEGACY_NAMES), ("mia_material_x", NAMES)] {
            let d = decls.get(decl).expect("declared");
            for name in names {
                assert!(d.param(name).is_some(), "{decl} has no {name}");
            }
        }
    }
}
