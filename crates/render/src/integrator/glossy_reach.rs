//! `mib_glossy_reflection`'s `max_distance`, `falloff` and `environment_color`, and
//! `mib_glossy_refraction`'s `max_distance`, `falloff` and `deep_material`, in the path
//! engine. The classic shader weighs what its glossy rays find by `reflection_color`,
//! but the environment by `environment_color`; with `max_distance` > 0 a ray that finds a
//! surface at distance d fades towards the environment by t = (d / max_distance)^falloff,
//! and a ray that travels farther (or leaves the scene) sees only the environment.
//!
//! A path bounce at such a surface ([`material::SurfaceModel::MibGlossy`] whose lobe
//! [`reaches`](bsdf::MibGlossyLobe::reaches)) carries, per channel, the share of its
//! weight f·cos/pdf the glossy lobe gave (g) and the base's (b = 1 − g where f > 0; all
//! of it glossy for the mirror). The segment that follows is then split exactly: at a
//! surface or light at distance d, the environment along the ray weighed by
//! t·ratio⊙g (ratio: see below) is added and the path goes
//! on with b + (1 − t)·s⊙g; a ray that leaves the scene takes the environment by
//! b + ratio⊙g. In channels where `reflection_color` is 0 and `environment_color` is
//! not, the lobe carries `environment_color` ([`bsdf::MibGlossyLobe::carried`]): ratio is
//! 1 there and s (the share of what the rays find that is reflected,
//! [`bsdf::MibGlossyLobe::seen`]) 0; elsewhere s is 1 and ratio = `environment_color` /
//! `reflection_color`. Next-event estimation does not sample the scene's environment at such a
//! surface (its shadow rays know nothing of the split), so a ray that leaves takes all of
//! it (no MIS), as at a material with its own environment (`material_env`). The
//! environment is that one where the material has it (the shader's own `environment`
//! included), else the scene's. Not split: a segment through a participating medium that
//! scatters before its end (it goes on with the whole bounce). At every
//! `mib_glossy_reflection` surface (with a reach or not) next-event estimation leaves the
//! glossy lobe out ([`light_through`]) as for `mib_glossy_refraction` below.
//!
//! `mib_glossy_refraction` ([`material::SurfaceModel::MibGlossyRefraction`] whose lobe
//! [`reaches`](bsdf::MibGlossyRefractionLobe::reaches)) splits its segments the same way,
//! following mental ray's shader (not a physical medium): a glossy ray, refracted or
//! totally reflected, that finds a surface at d gives (1 − t)·what it finds + t·C, t =
//! (d / max_distance)^falloff (1 past the distance or leaving the scene), where C is the
//! deep material's shader run once at the entry point ([`super::deep_material`]). So the
//! segment after such a bounce adds t·g⊙C (g: the glossy share) and goes on with b + (1
//! − t)·g; a ray that leaves takes the environment by b alone. Next-event estimation
//! does not sample the environment at such a surface, as above. At every
//! `mib_glossy_refraction` surface (with `max_distance` or not) next-event estimation
//! leaves the glossy lobe out ([`light_through`]): the classic shader's glossy rays find
//! only lights that are geometry, and the path engine's take such a light whole through
//! the lobe ([`hit_weight`]).

use bsdf::{Bsdf, BsdfSample, Rgb};
use glam::Vec3A;
use material::SurfaceModel;
use shader::{NodeId, Shading};

use super::material_env;
use crate::accel::Accel;
use crate::environment::Environment;
use crate::world::World;

/// Whether a surface of `model` splits its glossy rays' view of the environment (or the
/// deep material) from its base's (and so is not lit by environment sampling).
#[inline]
pub(super) fn reaches(model: &SurfaceModel) -> bool {
    match model {
        SurfaceModel::MibGlossy(lobe) => lobe.reaches(),
        SurfaceModel::MibGlossyRefraction(lobe) => lobe.reaches(),
        _ => false,
    }
}

/// The glossy share of a bounce, to split the segment after it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Reach {
    /// The glossy lobe's share of the bounce's weight, per channel (the base has the rest).
    glossy: Rgb,
    /// The share of the glossy lobe's carried colour it reflects of what its rays find
    /// ([`bsdf::MibGlossyLobe::seen`]).
    seen: Rgb,
    /// The base's share.
    base: Rgb,
    /// `environment_color` / `reflection_color`, per channel; for a glossy refraction
    /// ([`Reach::into_deep`]) its deep material's colour at the bounce.
    ratio: Rgb,
    /// `max_distance` (0: none).
    max_distance: f32,
    /// `falloff`.
    falloff: f32,
    /// Whether the glossy share fades into `mib_glossy_refraction`'s deep material's
    /// colour (`ratio`) in place of the environment along the ray. (A flag beside the
    /// colour keeps the struct, copied at every bounce, as small as before.)
    into_deep: bool,
}

impl Reach {
    /// The split of the bounce `bs` sampled from `bsdf` seen from `wo` (local frame) at a
    /// surface of `model`; `None` where the surface does not split its rays. `deep` gives the deep material's colour at the bounce (run only where a
    /// `mib_glossy_refraction` fades and its glossy share is not 0). (Out of line: the
    /// path loop asks only where [`reaches`] says so.)
    #[inline(never)]
    pub(super) fn after(
        model: &SurfaceModel,
        bsdf: &Bsdf,
        wo: Vec3A,
        bs: &BsdfSample,
        deep: impl FnOnce() -> Rgb,
    ) -> Option<Reach> {
        match model {
            SurfaceModel::MibGlossy(_) => Reach::after_glossy(model, bsdf, wo, bs),
            SurfaceModel::MibGlossyRefraction(_) => Reach::after_refraction(model, bsdf, wo, bs, deep),
            _ => None,
        }
    }

    /// [`Reach::after`] for a glossy refraction's surface: the glossy share (refracted and
    /// totally reflected rays alike, as the classic shader fades them all) fades into
    /// the deep material, the top's or back's share goes on whole.
    #[inline]
    fn after_refraction(
        model: &SurfaceModel,
        bsdf: &Bsdf,
        wo: Vec3A,
        bs: &BsdfSample,
        deep: impl FnOnce() -> Rgb,
    ) -> Option<Reach> {
        let SurfaceModel::MibGlossyRefraction(lobe) = model else { return None };
        let Bsdf::MibGlossyRefraction(b) = bsdf else { return None };
        if !lobe.reaches() {
            return None;
        }
        let (base, glossy) = if bs.delta {
            // Only the glossy lobe has a delta.
            (Rgb::ZERO, Rgb::ONE)
        } else {
            shares(b.eval_split(wo, bs.wi))
        };
        let deep = if glossy == Rgb::ZERO { Rgb::ZERO } else { deep() };
        Some(Reach {
            glossy,
            seen: Rgb::ONE,
            base,
            ratio: deep,
            max_distance: lobe.max_distance,
            falloff: lobe.falloff,
            into_deep: true,
        })
    }

    /// [`Reach::after`] for a glossy lobe's surface.
    #[inline]
    fn after_glossy(model: &SurfaceModel, bsdf: &Bsdf, wo: Vec3A, bs: &BsdfSample) -> Option<Reach> {
        let SurfaceModel::MibGlossy(lobe) = model else { return None };
        let Bsdf::MibGlossy(b) = bsdf else { return None };
        if !lobe.reaches() {
            return None;
        }
        let (base, glossy) = if bs.delta {
            // Only the mirror has a delta.
            (Rgb::ZERO, Rgb::ONE)
        } else {
            shares(b.carried_split(wo, bs.wi))
        };
        Some(Reach {
            glossy,
            seen: lobe.seen(),
            base,
            ratio: lobe.environment_ratio(),
            max_distance: lobe.max_distance,
            falloff: lobe.falloff,
            into_deep: false,
        })
    }

    /// For a segment that found something at distance `d` (infinite: it left the scene;
    /// `left`: it found nothing): the factor the path's throughput keeps, the weight of
    /// the environment along it, and for a glossy refraction the deep material's colour
    /// its glossy share fades into (its base's share alone sees the environment). (Out of
    /// line: rare, and the path loop's inlining budget is tight.)
    #[inline(never)]
    pub(super) fn segment(&self, d: f32, left: bool) -> (Rgb, Rgb, Option<Rgb>) {
        let (keep, to_env) = self.split(d);
        match (self.into_deep, left) {
            // (`to_env` is then the glossy share's fade × the deep colour.)
            (true, _) => (keep, if left { keep } else { Rgb::ZERO }, Some(to_env)),
            (false, true) => (keep, keep + to_env, None),
            (false, false) => (keep, to_env, None),
        }
    }

    /// For a segment that found something at distance `d` (infinite: it left the scene):
    /// the factor the path's throughput keeps and the weight of the environment along it.
    pub(super) fn split(&self, d: f32) -> (Rgb, Rgb) {
        let t = if d.is_finite() { baselib::glossy::distance_fade(d, self.max_distance, self.falloff) } else { 1.0 };
        (self.base + self.glossy * self.seen * (1.0 - t), self.ratio * self.glossy * t)
    }
}

/// Whether next-event estimation at a surface of `model` leaves out its glossy lobe: a
/// `mib_glossy_refraction`'s or a `mib_glossy_reflection`'s (see [`light_through`]).
#[inline]
pub(super) fn unlit_lobe(model: &SurfaceModel) -> bool {
    matches!(model, SurfaceModel::MibGlossyRefraction(_) | SurfaceModel::MibGlossy(_))
}

/// f(ωo, ωi) = `f` towards a light that next-event estimation found at distance `dist`
/// from a surface of `model`: at a `mib_glossy_refraction` or `mib_glossy_reflection`
/// ([`unlit_lobe`]), without its glossy part (where the light lights the `specular`
/// lobes). mental ray's shaders (mental ray 3.6's base library) trace their glossy rays
/// (reflected; or refracted and totally reflected) and weigh what they find: they find a
/// light only where it is geometry (an area light they hit), never a point, spot or
/// directional light, and no light loop runs through the lobe (the classic shaders here,
/// `baselib::glossy`, do the same). So the path engine takes the lights through that
/// lobe only where its own rays find them (a light's geometry, the whole of the glossy
/// share: [`hit_weight`]), and within `max_distance` those rays keep 1 − t of it as any
/// segment does. `f` unchanged for any other surface. `dist` is unused (the glossy part
/// is left out at any distance).
#[inline(never)]
pub(super) fn light_through(
    model: &SurfaceModel,
    bsdf: &Bsdf,
    (wo, wi): (Vec3A, Vec3A),
    specular: bool,
    _dist: f32,
    f: Rgb,
) -> Rgb {
    if !specular {
        return f;
    }
    let glossy = match (model, bsdf) {
        (SurfaceModel::MibGlossyRefraction(_), Bsdf::MibGlossyRefraction(b)) => b.eval_split(wo, wi).1,
        (SurfaceModel::MibGlossy(_), Bsdf::MibGlossy(b)) => b.eval_split(wo, wi).1,
        _ => return f,
    };
    (f - glossy).max(Rgb::ZERO)
}

/// The glossy lobe's share of a bounce sampled from `bsdf` (a `mib_glossy_refraction`'s
/// or `mib_glossy_reflection`'s, [`unlit_lobe`]) seen from `wo`, per channel: all of a
/// delta sample, the glossy part of the sample's f in the whole for another (the whole
/// carried colour for `mib_glossy_reflection`: the weight its samples have); 0 for any
/// other surface. Light its ray finds is taken
/// whole there ([`hit_weight`]): next-event estimation left it out ([`light_through`]).
#[inline(never)]
pub(super) fn unlit_share(bsdf: &Bsdf, wo: Vec3A, bs: &BsdfSample) -> Rgb {
    match bsdf {
        Bsdf::MibGlossyRefraction(_) if bs.delta => Rgb::ONE,
        Bsdf::MibGlossyRefraction(b) => shares(b.eval_split(wo, bs.wi)).1,
        Bsdf::MibGlossy(_) if bs.delta => Rgb::ONE,
        Bsdf::MibGlossy(b) => shares(b.carried_split(wo, bs.wi)).1,
        _ => Rgb::ZERO,
    }
}

/// The weight of light a ray found, per channel: the MIS weight `mis` (what the bounce
/// before shares with next-event estimation) for the share of the path that next-event
/// estimation could have found it along, 1 for the share `unlit` it could not
/// ([`unlit_share`]): unlit + (1 − unlit)·mis.
#[inline]
pub(super) fn hit_weight(unlit: Rgb, mis: f32) -> Rgb {
    unlit + (Rgb::ONE - unlit) * mis
}

impl Reach {
    /// The share `unlit` of the bounce's weight that next-event estimation left out
    /// ([`unlit_share`]) after the segment to something at distance `d` kept
    /// [`Reach::split`]'s part of it: the glossy share faded by 1 − t (and weighed by what
    /// it reflects of what it finds, [`Reach::seen`]) over what was kept.
    pub(super) fn unlit_after(&self, unlit: Rgb, d: f32) -> Rgb {
        if unlit == Rgb::ZERO {
            return unlit;
        }
        let t = if d.is_finite() { baselib::glossy::distance_fade(d, self.max_distance, self.falloff) } else { 1.0 };
        let (kept, _) = self.split(d);
        let faded = unlit * self.seen * (1.0 - t);
        Rgb::new(
            if kept.x > 0.0 { (faded.x / kept.x).min(1.0) } else { 0.0 },
            if kept.y > 0.0 { (faded.y / kept.y).min(1.0) } else { 0.0 },
            if kept.z > 0.0 { (faded.z / kept.z).min(1.0) } else { 0.0 },
        )
    }
}

/// The shares of a bounce's two parts `(base, glossy)` of f in their sum, per channel (0
/// where the sum is).
fn shares((fb, fg): (Rgb, Rgb)) -> (Rgb, Rgb) {
    let sum = fb + fg;
    let share = |x: Rgb| {
        Rgb::new(
            if sum.x > 0.0 { x.x / sum.x } else { 0.0 },
            if sum.y > 0.0 { x.y / sum.y } else { 0.0 },
            if sum.z > 0.0 { x.z / sum.z } else { 0.0 },
        )
    };
    (share(fb), share(fg))
}

/// The environment along `dir` for a ray that left a surface (all of it, no MIS; as
/// light, or as seen after a `delta` bounce): `own` (the material's environment shader)
/// where given, else the scene's `env`, else black.
pub(super) fn environment(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    env: Option<&Environment>,
    own: Option<NodeId>,
    dir: Vec3A,
    delta: bool,
) -> Rgb {
    if let (Some(node), Some(shading)) = (own, shading) {
        return material_env::radiance(world, accel, shading, node, dir, !delta);
    }
    match env {
        Some(e) => (if delta { e.radiance(dir) } else { e.light_radiance(dir) }) * e.lighting_scale,
        None => Rgb::ZERO,
    }
}
