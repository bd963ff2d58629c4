//! Participating media in the path engine: homogeneous media inside closed surfaces whose
//! material has one (MDL's `material_volume`, [`material::SurfaceMaterial::medium`]).
//!
//! A path keeps the media it is in as a small stack of materials ([`MediumStack`]): a ray
//! transmitted through the front face of a surface whose material has a medium and an
//! inside enters it, one transmitted through the back face leaves it; nested and
//! overlapping objects stack (the innermost entered is the medium the ray travels in).
//! Along a segment in a medium a free-flight distance is drawn (chromatic, see
//! [`bsdf::medium`]); light scattered there is estimated by next-event estimation to a
//! light or the environment with the phase function, MIS against phase-function sampling,
//! and the path continues in a direction drawn from the phase function. Absorbing-only
//! media attenuate by Beer–Lambert and never scatter.
//!
//! Shadow rays through media carry their transmittance. An *index-matched* boundary of a
//! material with a medium (smooth transmission with index of refraction 1,
//! [`material::SurfaceModel::index_matched`]) lets shadow rays through with its tint, and a
//! path crossing it keeps the sampling density of its last scattering vertex for MIS (the
//! crossing bends nothing, so a light found behind it is weighed against the light
//! sampling done before it). Any other boundary blocks shadow rays as surfaces do.
//!
//! Scenes without media take none of these branches (`World::has_media` is false): their
//! paths are the same, sample for sample. The camera is assumed to be outside every
//! medium.

use bsdf::medium::Flight;
use bsdf::{Medium, Rgb};
use glam::Vec3A;
use shader::Shading;

use super::{
    cutout_number, light_radiance, material_at, power_heuristic, shadow_blocked, surface, through_portal,
    MAX_CUTOUT_CROSSINGS,
};
use crate::accel::Accel;
use crate::environment::Environment;
use crate::ray::{mask, offset_origin, Ray, RayCounts};
use crate::sampler::Sampler;
use crate::world::World;

/// How many media a path can be inside at once; entering more keeps the innermost four.
const MAX_NESTING: usize = 4;

/// The media a path is in: the materials (indices into `World::materials`) whose
/// surfaces it entered and has not left, innermost last.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct MediumStack {
    materials: [u32; MAX_NESTING],
    len: u8,
}

impl MediumStack {
    /// Whether the path is in no medium.
    pub(super) fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The medium the path travels in: the innermost one entered.
    pub(super) fn current<'w>(&self, world: &'w World) -> Option<&'w Medium> {
        let top = *self.materials[..usize::from(self.len)].last()?;
        world.materials[top as usize].medium.as_ref()
    }

    /// Enters the medium of `material`; when the stack is full its outermost is forgotten.
    fn enter(&mut self, material: u32) {
        if usize::from(self.len) == MAX_NESTING {
            self.materials.copy_within(1.., 0);
            self.len -= 1;
        }
        self.materials[usize::from(self.len)] = material;
        self.len += 1;
    }

    /// Leaves the innermost medium of `material` (nothing when the path is not in it).
    fn leave(&mut self, material: u32) {
        let len = usize::from(self.len);
        if let Some(i) = self.materials[..len].iter().rposition(|&m| m == material) {
            self.materials.copy_within(i + 1..len, i);
            self.len -= 1;
        }
    }

    /// The stack after a ray travelling along `dir_in` goes on along `dir_out` at a
    /// surface of `material` with geometric normal `ng` (world space, the surface's front):
    /// a transmission through a surface with a medium enters (front face) or leaves (back
    /// face) it. `None` when nothing changes.
    fn after(&self, world: &World, material: u32, ng: Vec3A, dir_in: Vec3A, dir_out: Vec3A) -> Option<MediumStack> {
        let m = &world.materials[material as usize];
        let front = dir_in.dot(ng) < 0.0;
        let transmitted = front == (dir_out.dot(ng) < 0.0);
        if !transmitted || m.medium.is_none() || !m.has_inside() {
            return None;
        }
        let mut next = *self;
        if front {
            next.enter(material);
        } else {
            next.leave(material);
        }
        Some(next)
    }

    /// Follows a path scattered at a surface (see [`MediumStack::after`]); true when the
    /// surface is an index-matched boundary it went straight through (then no bounce for
    /// MIS).
    pub(super) fn follow(&mut self, world: &World, material: u32, ng: Vec3A, dir_in: Vec3A, dir_out: Vec3A) -> bool {
        let Some(next) = self.after(world, material, ng, dir_in, dir_out) else { return false };
        *self = next;
        world.materials[material as usize].model.index_matched().is_some()
    }
}

/// Where a shadow ray leaves from: the media the path is in and, for a surface vertex, the
/// surface (its material, geometric front normal and the direction the path arrived along),
/// which the shadow ray crosses when it goes to the other side.
#[derive(Clone, Copy)]
pub(super) struct Departure<'a> {
    /// The media of the path arriving.
    pub media: &'a MediumStack,
    /// The surface's material, geometric normal (front) and the arriving direction; `None`
    /// in a medium.
    pub surface: Option<(u32, Vec3A, Vec3A)>,
}

impl Departure<'_> {
    /// The media a shadow ray along `dir` starts in.
    fn media_towards(&self, world: &World, dir: Vec3A) -> MediumStack {
        self.surface
            .and_then(|(material, ng, dir_in)| self.media.after(world, material, ng, dir_in, dir))
            .unwrap_or(*self.media)
    }
}

/// The fraction of light (per channel) that travels the shadow ray from `from` to its end:
/// without media in the scene 1 or 0 (blocked); with media, their Beer–Lambert
/// transmittance along it, through index-matched boundaries of materials with media (times
/// their tint), 0 at any other surface (cutouts by their opacity).
pub(super) fn shadow_transmittance(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    from: &Departure,
    shadow: &Ray,
    seed: u32,
) -> Rgb {
    if !world.has_media {
        return if shadow_blocked(world, accel, shading, shadow, seed) { Rgb::ZERO } else { Rgb::ONE };
    }
    let mut media = from.media_towards(world, shadow.dir);
    let mut ray = *shadow;
    let mut tr = Rgb::ONE;
    for crossing in 0..MAX_CUTOUT_CROSSINGS {
        let hit = accel.intersect(&ray);
        let segment = hit.map_or(ray.tmax, |h| h.t);
        if let Some(medium) = media.current(world) {
            tr *= medium.transmittance(segment);
        }
        let Some(hit) = hit else { return tr };
        if tr == Rgb::ZERO {
            return tr;
        }
        let s = surface(world, &ray, &hit);
        let matched = world.materials[s.material as usize].model.index_matched();
        match (media.after(world, s.material, s.ng, ray.dir, ray.dir), matched) {
            (Some(next), Some(tint)) => {
                media = next;
                tr *= tint;
            }
            _ => {
                if !world.has_cutouts {
                    return Rgb::ZERO;
                }
                let m = material_at(world, accel, shading, &ray, &hit, s.material);
                if m.opacity >= 1.0 || cutout_number(seed, s.p, crossing + 100) < m.opacity {
                    return Rgb::ZERO;
                }
            }
        }
        ray.origin = offset_origin(s.p, s.ng, ray.dir);
        ray.tmax = (ray.tmax - segment).max(0.0);
    }
    Rgb::ZERO
}

/// What a path samples lights with: the scene and how lights are chosen.
pub(super) struct Lighting<'a> {
    /// The scene.
    pub world: &'a World,
    /// Its acceleration structure.
    pub accel: &'a dyn Accel,
    /// Its compiled shader graph (materials with connected parameters).
    pub shading: Option<&'a Shading>,
    /// The environment, when it lights the scene.
    pub env: Option<&'a Environment<'a>>,
    /// The probability of choosing each light (and the environment, when sampled).
    pub pick: f32,
    /// How many lights can be chosen (the environment last).
    pub choices: usize,
    /// The path's stream number (for cutout decisions).
    pub seed: u32,
    /// Whether light sampling and phase sampling are combined by MIS.
    pub mis: bool,
}

/// The free flight of a ray in the medium the path is in, up to distance `t_end` (two
/// sample numbers); `None` outside media.
pub(super) fn fly(world: &World, media: &MediumStack, t_end: f32, sampler: &mut Sampler) -> Option<Flight> {
    let medium = media.current(world)?;
    Some(medium.sample_flight(t_end, sampler.next_2d()))
}

/// The light scattered towards the path at point `p` of `medium` that arrived along unit
/// `dir`: next-event estimation to one light or the environment (transmittance along the
/// shadow ray), MIS against the phase function. Uses three sample numbers.
#[allow(clippy::too_many_arguments)]
pub(super) fn direct_light(
    scene: &Lighting,
    medium: &Medium,
    media: &MediumStack,
    p: Vec3A,
    dir: Vec3A,
    time: f32,
    sampler: &mut Sampler,
    counts: &mut RayCounts,
) -> Rgb {
    let choice = sampler.next_1d();
    let u_light = sampler.next_2d();
    let world = scene.world;
    let light_count = world.lights.len();
    let k = ((choice * scene.choices as f32) as usize).min(scene.choices.saturating_sub(1));
    let from = Departure { media, surface: None };
    let shadow_ray = |dir: Vec3A, tmax: f32| Ray { mask: mask::SHADOW, origin: p, dir, tmin: 0.0, tmax, time };
    if k == light_count && scene.choices > light_count {
        let Some(env) = scene.env else { return Rgb::ZERO };
        let Some(es) = env.sample(u_light) else { return Rgb::ZERO };
        if es.pdf <= 0.0 || es.radiance == Rgb::ZERO || through_portal(&world.lights, p, es.dir) {
            return Rgb::ZERO;
        }
        let phase = medium.phase.eval(dir, es.dir);
        counts.shadow_rays += 1;
        let tr = shadow_transmittance(
            world,
            scene.accel,
            scene.shading,
            &from,
            &shadow_ray(es.dir, f32::INFINITY),
            scene.seed,
        );
        if tr == Rgb::ZERO {
            return Rgb::ZERO;
        }
        let weight = if scene.mis { power_heuristic(scene.pick * es.pdf, phase) } else { 1.0 };
        return tr * es.radiance * (env.lighting_scale * phase * weight / (scene.pick * es.pdf));
    }
    if k >= light_count {
        return Rgb::ZERO;
    }
    let light = &world.lights[k];
    let Some(mut ls) = light.sample_at(p, u_light, time) else { return Rgb::ZERO };
    ls.radiance = light_radiance(light, ls.radiance, scene.env, ls.wi);
    if ls.radiance == Rgb::ZERO || ls.pdf <= 0.0 {
        return Rgb::ZERO;
    }
    let phase = medium.phase.eval(dir, ls.wi);
    let tmax = if ls.dist.is_finite() { ls.dist * (1.0 - 1e-4) } else { f32::INFINITY };
    let tr = if light.shadow {
        counts.shadow_rays += 1;
        shadow_transmittance(world, scene.accel, scene.shading, &from, &shadow_ray(ls.wi, tmax), scene.seed)
    } else {
        Rgb::ONE
    };
    if tr == Rgb::ZERO {
        return Rgb::ZERO;
    }
    let weight = if ls.delta || !scene.mis { 1.0 } else { power_heuristic(scene.pick * ls.pdf, phase) };
    tr * ls.radiance * (phase * weight / (scene.pick * ls.pdf))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Entering pushes, leaving removes the innermost entry of that material (also out of
    /// order, for overlapping objects), a fifth medium forgets the outermost.
    #[test]
    fn the_stack_nests_and_overlaps() {
        let mut s = MediumStack::default();
        assert!(s.is_empty());
        s.enter(3);
        s.enter(5);
        s.enter(3);
        s.leave(5);
        assert_eq!(&s.materials[..usize::from(s.len)], &[3, 3]);
        s.leave(7);
        assert_eq!(s.len, 2);
        s.leave(3);
        s.leave(3);
        assert!(s.is_empty());
        for m in 1..=5 {
            s.enter(m);
        }
        assert_eq!(&s.materials[..usize::from(s.len)], &[2, 3, 4, 5]);
    }
}
