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
//! [`material::SurfaceModel::index_matched`]) lets shadow rays through, tinted where they
//! enter, and a
//! path crossing it keeps the sampling density of its last scattering vertex for MIS (the
//! crossing bends nothing, so a light found behind it is weighed against the light
//! sampling done before it). Any other boundary blocks shadow rays as surfaces do.
//!
//! Lights with `shadow off` are blocked and tinted by no surface, but the media along the
//! way still attenuate their light ([`light_transmittance`]). A cutout lets rays through
//! where it is cut out, and there it is no boundary: the media stay as they were.
//!
//! Camera paths start in the media around the camera's position at the shutter's opening
//! ([`media_at`], found once per render): a camera inside a closed object with a medium sees
//! through that medium. A camera that moves while the shutter is open follows its way from
//! there to where it is at each sample's time ([`camera_media_at`]). An orthographic
//! camera's rays start across its image plane: each in the media around its own origin
//! ([`camera_ray_media`]).
//!
//! Scenes without media take none of these branches (`World::has_media` is false): their
//! paths are the same, sample for sample.

use bsdf::medium::Flight;
use bsdf::{Medium, Rgb};
use glam::Vec3A;
use shader::state::RayType;
use shader::{Shading, State};

use super::own_stretch::{passage, OwnStretch};
use super::{
    cutout_number, light_radiance, material_at, power_heuristic, shadow_passed, surface, through_portal, Surface,
    MAX_CUTOUT_CROSSINGS,
};
use crate::accel::{Accel, Hit};
use crate::environment::Environment;
use crate::ray::{mask, Ray, RayCounts};
use crate::sampler::Sampler;
use crate::world::World;

/// How many media a path keeps inline; a path nested deeper moves its stack to the heap
/// (nothing is forgotten).
const INLINE_NESTING: usize = 8;

/// The media a path is in: the materials (indices into `World::materials`) whose
/// surfaces it entered and has not left, innermost last, each with the medium evaluated
/// where the path entered when the material's medium varies over its surface
/// ([`material::SurfaceMaterial::medium_at`]). Any depth: the first [`INLINE_NESTING`]
/// materials of constant media inline; deeper nesting, or a medium of its own, moves the
/// stack to the heap.
#[derive(Clone, Debug)]
pub struct MediumStack(Entries);

/// A [`MediumStack`]'s materials, inline or spilled.
#[derive(Clone, Debug)]
enum Entries {
    /// Up to [`INLINE_NESTING`] materials of constant media, the first `len` in use.
    Inline { materials: [u32; INLINE_NESTING], len: u8 },
    /// A deeper stack, or one holding a medium evaluated where the path entered.
    Spilled(Vec<Entered>),
}

/// A medium a path entered: its material, and the medium at the entry point where that
/// varies over the surface (`None`: the material's constant medium).
#[derive(Clone, Debug)]
struct Entered {
    material: u32,
    own: Option<Medium>,
}

impl Default for MediumStack {
    /// Outside every medium.
    fn default() -> MediumStack {
        MediumStack(Entries::Inline { materials: [0; INLINE_NESTING], len: 0 })
    }
}

impl PartialEq for MediumStack {
    /// The same materials in the same order (media evaluated at entry points not compared).
    fn eq(&self, other: &MediumStack) -> bool {
        self.materials().eq(other.materials())
    }
}

impl Eq for MediumStack {}

impl MediumStack {
    /// The materials of the media, outermost first.
    pub fn materials(&self) -> impl Iterator<Item = u32> + '_ {
        let (inline, spilled): (&[u32], &[Entered]) = match &self.0 {
            Entries::Inline { materials, len } => (&materials[..usize::from(*len)], &[]),
            Entries::Spilled(v) => (&[], v),
        };
        inline.iter().copied().chain(spilled.iter().map(|e| e.material))
    }

    /// The materials of the media, outermost first, each with its medium where that was
    /// evaluated at the entry point (it varies over the surface).
    pub fn entries(&self) -> impl Iterator<Item = (u32, Option<&Medium>)> + '_ {
        let (inline, spilled): (&[u32], &[Entered]) = match &self.0 {
            Entries::Inline { materials, len } => (&materials[..usize::from(*len)], &[]),
            Entries::Spilled(v) => (&[], v),
        };
        inline.iter().map(|&m| (m, None)).chain(spilled.iter().map(|e| (e.material, e.own.as_ref())))
    }

    /// Whether the path is in no medium.
    pub fn is_empty(&self) -> bool {
        match &self.0 {
            Entries::Inline { len, .. } => *len == 0,
            Entries::Spilled(v) => v.is_empty(),
        }
    }

    /// The medium the path travels in: the innermost one entered (as evaluated where the
    /// path entered it, when it varies).
    pub(super) fn current<'s>(&'s self, world: &'s World) -> Option<&'s Medium> {
        match self.top()? {
            (_, Some(own)) => Some(own),
            (material, None) => world.materials[material as usize].medium.as_ref(),
        }
    }

    /// The innermost entry: its material and, when it was evaluated where the path
    /// entered, its medium.
    fn top(&self) -> Option<(u32, Option<&Medium>)> {
        match &self.0 {
            Entries::Inline { materials, len } => materials[..usize::from(*len)].last().map(|&m| (m, None)),
            Entries::Spilled(v) => v.last().map(|e| (e.material, e.own.as_ref())),
        }
    }

    /// Enters the medium of `material` (innermost now), `own` its medium at the entry
    /// point when that varies.
    fn enter(&mut self, material: u32, own: Option<Medium>) {
        match &mut self.0 {
            Entries::Inline { materials, len } if usize::from(*len) < INLINE_NESTING && own.is_none() => {
                materials[usize::from(*len)] = material;
                *len += 1;
            }
            Entries::Inline { materials, len } => {
                let mut v = Vec::with_capacity(2 * INLINE_NESTING);
                v.extend(materials[..usize::from(*len)].iter().map(|&material| Entered { material, own: None }));
                v.push(Entered { material, own });
                self.0 = Entries::Spilled(v);
            }
            Entries::Spilled(v) => v.push(Entered { material, own }),
        }
    }

    /// Leaves the innermost medium of `material` (nothing when the path is not in it).
    fn leave(&mut self, material: u32) {
        match &mut self.0 {
            Entries::Inline { materials, len } => {
                let n = usize::from(*len);
                let Some(i) = materials[..n].iter().rposition(|&m| m == material) else { return };
                materials.copy_within(i + 1..n, i);
                *len -= 1;
            }
            Entries::Spilled(v) => {
                if let Some(i) = v.iter().rposition(|e| e.material == material) {
                    v.remove(i);
                }
            }
        }
    }

    /// The stack after a ray travelling along `dir_in` goes on along `dir_out` at a
    /// surface of `material` with geometric normal `ng` (world space, the surface's front):
    /// a transmission through a surface with a medium enters (front face) or leaves (back
    /// face) it; `at`, the ray and hit there, is where a medium that varies over the
    /// surface is evaluated (without it, its value at the material's default point).
    /// `None` when nothing changes.
    fn after(
        &self,
        world: &World,
        material: u32,
        ng: Vec3A,
        (dir_in, dir_out): (Vec3A, Vec3A),
        at: Option<(&Ray, &Hit)>,
    ) -> Option<MediumStack> {
        let m = &world.materials[material as usize];
        let front = dir_in.dot(ng) < 0.0;
        let transmitted = front == (dir_out.dot(ng) < 0.0);
        if !transmitted || m.medium.is_none() || !m.has_inside() {
            return None;
        }
        let mut next = self.clone();
        if front {
            next.enter(material, at.and_then(|(ray, hit)| medium_entered(world, material, ray, hit)));
        } else {
            next.leave(material);
        }
        Some(next)
    }

    /// Follows a path scattered at a surface (see [`MediumStack::after`]; `at` the ray and
    /// its hit there); true when the surface is an index-matched boundary it went straight
    /// through (then no bounce for MIS).
    pub(super) fn follow(&mut self, world: &World, material: u32, ng: Vec3A, dir_out: Vec3A, at: (&Ray, &Hit)) -> bool {
        let Some(next) = self.after(world, material, ng, (at.0.dir, dir_out), Some(at)) else { return false };
        *self = next;
        world.materials[material as usize].model.index_matched().is_some()
    }
}

/// The medium of `material` where a path along `ray` enters its object at `hit`, when
/// that medium varies over the surface (`None`: the material's constant medium is it).
/// Evaluated once per entry: the path keeps it until it leaves.
fn medium_entered(world: &World, material: u32, ray: &Ray, hit: &Hit) -> Option<Medium> {
    let varying = world.materials[material as usize].varying_medium.as_ref()?;
    let mut state = State {
        ray_type: RayType::Eye,
        org: ray.origin,
        dir: ray.dir,
        time: ray.time,
        child_dist: f32::INFINITY,
        ..State::default()
    };
    crate::tracer::fill_state(world, hit, &mut state);
    Some(varying.0.medium(&state))
}

/// Where a shadow ray leaves from: the media the path is in and, for a surface vertex, the
/// surface, which the shadow ray crosses when it goes to the other side.
#[derive(Clone, Copy)]
pub(super) struct Departure<'a> {
    /// The media of the path arriving.
    pub media: &'a MediumStack,
    /// The surface's material, geometric normal (front), and the ray that arrived with its
    /// hit; `None` in a medium.
    pub surface: Option<(u32, Vec3A, &'a Ray, &'a Hit)>,
}

impl Departure<'_> {
    /// The instance of the surface the ray leaves (`None` in a medium).
    fn instance(&self) -> Option<u32> {
        self.surface.map(|(_, _, _, hit)| hit.instance)
    }

    /// The media a shadow ray along `dir` starts in.
    fn media_towards(&self, world: &World, dir: Vec3A) -> MediumStack {
        self.surface
            .and_then(|(material, ng, ray, hit)| {
                self.media.after(world, material, ng, (ray.dir, dir), Some((ray, hit)))
            })
            .unwrap_or_else(|| self.media.clone())
    }
}

/// The fraction of light (per channel) that travels the shadow ray from `from` to its end:
/// without media in the scene 1 or 0 (blocked); with media, their Beer–Lambert
/// transmittance along it, through index-matched boundaries of materials with media (times
/// their tint where the ray enters), 0 at any other surface. A cutout lets the ray through by its opacity,
/// and where it does the surface is no boundary: the media stay as they are (as for the
/// path's own rays).
///
/// Scenes without media or cutouts (the common case) take one occlusion query, inlined
/// where it is asked; the rest is out of line ([`shadow_transmittance_through`]).
#[inline]
pub(super) fn shadow_transmittance(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    from: &Departure,
    shadow: &Ray,
    seed: u32,
) -> Rgb {
    if !world.has_media && !world.has_cutouts {
        return if accel.occluded(shadow) { Rgb::ZERO } else { Rgb::ONE };
    }
    shadow_transmittance_through(world, accel, shading, from, shadow, seed)
}

/// [`shadow_transmittance`] in scenes with media or cutouts.
#[inline(never)]
fn shadow_transmittance_through(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    from: &Departure,
    shadow: &Ray,
    seed: u32,
) -> Rgb {
    if !world.has_media {
        return shadow_passed(world, accel, shading, shadow, seed, from.instance());
    }
    media_shadow_walk(world, accel, shading, (from, shadow), seed, None)
}

/// The walk of [`shadow_transmittance_through`] in a scene with media, for light `light`
/// (an index into [`World::lights`]) when its shadow links apply ([`World::casts_shadow_for`]):
/// a surface of an instance that casts no shadow for that light blocks and tints nothing
/// but is still a medium boundary, as it is for a light with `shadow off`
/// ([`media_transmittance`]); surfaces passed for the link count against the limit twice
/// over, as in `linked_shadow_passed`. `None`: every surface casts shadows.
fn media_shadow_walk(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    (from, shadow): (&Departure, &Ray),
    seed: u32,
    light: Option<usize>,
) -> Rgb {
    let limit = if light.is_some() { 2 * MAX_CUTOUT_CROSSINGS } else { MAX_CUTOUT_CROSSINGS };
    let mut stretch = OwnStretch::new(from.instance());
    let walk = walk_media(world, accel, from, shadow, limit, |media, ray, s, crossing| {
        let inside = stretch.step(&s.hit, &s.surface, ray.dir);
        if light.is_some_and(|k| !world.casts_shadow_for(k, s.hit.instance)) {
            return match media.after(world, s.surface.material, s.surface.ng, (ray.dir, ray.dir), Some((ray, &s.hit))) {
                Some(next) => Crossing::Into(next, Rgb::ONE),
                None => Crossing::Through,
            };
        }
        if world.blocks_shadows(s.surface.material) {
            // Marked `opaque`: no cutout, no boundary.
            return Crossing::Blocked;
        }
        let cut_out = world.has_cutouts.then(|| {
            let m = material_at(world, accel, shading, ray, &s.hit, s.surface.material);
            // Leaving the receiving point's own object: its translucent passage, if any.
            passage(world, &m, &s.surface, ray.dir, inside).or_else(|| {
                (m.opacity < 1.0 && cutout_number(seed, s.surface.p, crossing + 100) >= m.opacity)
                    .then_some(m.cutout_tint)
            })
        });
        if let Some(Some(tint)) = cut_out {
            return Crossing::Filtered(tint);
        }
        let matched = world.materials[s.surface.material as usize].model.index_matched();
        match (media.after(world, s.surface.material, s.surface.ng, (ray.dir, ray.dir), Some((ray, &s.hit))), matched) {
            // The boundary tints what enters through it, once per object crossed, as it
            // does the path's own rays (`bsdf::Unified` tints light going in, not out).
            (Some(next), Some(tint)) => {
                Crossing::Into(next, if ray.dir.dot(s.surface.ng) < 0.0 { tint } else { Rgb::ONE })
            }
            _ => Crossing::Blocked,
        }
    });
    // Past that many surfaces the ray counts as blocked.
    walk.unwrap_or(Rgb::ZERO)
}

/// The fraction of a light's light that reaches the point the ray `shadow` leaves from
/// `from`: [`shadow_transmittance`] for a light that casts shadows; for one that does not
/// (`shadow off`), the transmittance of the media along the ray alone ([`media_transmittance`]).
///
/// Our reading of `shadow off`: mental ray then traces no shadow rays for the light, so no
/// surface blocks or filters it, but its light rays still pass through the volume shaders
/// of the media they cross (the classic engine does the same, `shader::lights`' light
/// volume); a participating medium is such a volume, so its Beer–Lambert transmittance
/// still applies. Without media this is 1: scenes without media are unchanged.
///
/// `linked`: the light's index in [`World::lights`] when the instances' shadow light
/// lists apply to it (Maya's shadow links, [`World::casts_shadow_for`]); in a scene with
/// media and such lists, objects that cast no shadow for it let its light through
/// untouched (the media inside them still attenuate it). Scenes without shadow lists, or
/// without media (the caller walks those with `linked_shadow_passed`), are unchanged.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(super) fn light_transmittance(
    world: &World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    from: &Departure,
    shadow: &Ray,
    seed: u32,
    casts_shadows: bool,
    linked: Option<usize>,
) -> Rgb {
    if casts_shadows {
        match linked {
            Some(k) if world.has_media && !world.shadow_unlinked.is_empty() => {
                media_shadow_walk(world, accel, shading, (from, shadow), seed, Some(k))
            }
            _ => shadow_transmittance(world, accel, shading, from, shadow, seed),
        }
    } else if world.has_media {
        media_transmittance(world, accel, from, shadow)
    } else {
        Rgb::ONE
    }
}

/// The Beer–Lambert transmittance of the media along `ray` (leaving `from`), through every
/// surface: each crossing of a medium's boundary enters or leaves it, nothing blocks or
/// tints. 1 in scenes without media.
#[inline(never)]
fn media_transmittance(world: &World, accel: &dyn Accel, from: &Departure, ray: &Ray) -> Rgb {
    if !world.has_media {
        return Rgb::ONE;
    }
    let walk = walk_media(world, accel, from, ray, MAX_BOUNDARY_CROSSINGS, |media, ray, s, _| {
        match media.after(world, s.surface.material, s.surface.ng, (ray.dir, ray.dir), Some((ray, &s.hit))) {
            Some(next) => Crossing::Into(next, Rgb::ONE),
            None => Crossing::Through,
        }
    });
    // Past that many surfaces the rest of the way is taken as clear.
    walk.unwrap_or_else(|tr| tr)
}

/// What a ray walking through the media ([`walk_media`]) does at a surface it meets.
enum Crossing {
    /// Passes with the media unchanged (no medium boundary).
    Through,
    /// Passes a cut-out with the media unchanged, its light multiplied by the cut-out's
    /// tint.
    Filtered(Rgb),
    /// Crosses into the media given, its light multiplied by the tint.
    Into(MediumStack, Rgb),
    /// Stops: no light gets through.
    Blocked,
}

/// A surface met by a walk: the hit and its surface.
struct Met {
    hit: Hit,
    surface: Surface,
}

/// Walks `ray` (leaving `from`) surface by surface, keeping the Beer–Lambert transmittance
/// of the media it is in along each segment and asking `at_surface` (the media so far, the
/// ray, the surface, the crossing's number) what happens at each surface: `Ok` with the
/// transmittance where the ray ends or is blocked (zero), `Err` with the transmittance so
/// far after `max_crossings` surfaces.
fn walk_media(
    world: &World,
    accel: &dyn Accel,
    from: &Departure,
    ray: &Ray,
    max_crossings: u32,
    mut at_surface: impl FnMut(&MediumStack, &Ray, &Met, u32) -> Crossing,
) -> Result<Rgb, Rgb> {
    let mut media = from.media_towards(world, ray.dir);
    let mut ray = *ray;
    let mut tr = Rgb::ONE;
    for crossing in 0..max_crossings {
        let hit = accel.intersect(&ray);
        let segment = hit.map_or(ray.tmax, |h| h.t);
        if let Some(medium) = media.current(world) {
            tr *= medium.transmittance(segment);
        }
        let Some(hit) = hit else { return Ok(tr) };
        if tr == Rgb::ZERO {
            return Ok(tr);
        }
        let met = Met { surface: surface(world, &ray, &hit), hit };
        match at_surface(&media, &ray, &met, crossing) {
            Crossing::Through => {}
            Crossing::Filtered(tint) => tr *= tint,
            Crossing::Into(next, tint) => {
                tr *= tint;
                media = next;
            }
            Crossing::Blocked => return Ok(Rgb::ZERO),
        }
        ray.origin = met.surface.leave(met.surface.ng, ray.dir);
        ray.tmax = (ray.tmax - segment).max(0.0);
    }
    Err(tr)
}

/// Most surfaces a ray walking through every surface crosses ([`media_transmittance`],
/// [`media_at`]).
const MAX_BOUNDARY_CROSSINGS: u32 = 1024;

/// Directions (world space, unit length after normalising) of the rays that find the media
/// around a point: away from the axes and from each other, so that a ray rarely grazes an
/// edge of a modelled box.
const PROBE_DIRECTIONS: [[f32; 3]; 3] =
    [[0.5377, 0.7226, 0.4344], [-0.6512, 0.2693, -0.7094], [0.3141, -0.8329, 0.4557]];

/// The media enclosing the point `p` (world space) at shutter time `time`: where a path
/// starting there is, e.g. a camera's, innermost last. Found along a ray from `p` to
/// infinity: a medium's surface met from behind (its back face) before any front face of
/// the same material is one `p` is inside (an object entered along the ray and left again
/// encloses nothing). Three rays in different directions vote; when all three disagree
/// (a ray through a crack, or an object that is not closed), the first ray's answer.
/// Outside every medium when the scene has none.
pub fn media_at(world: &World, accel: &dyn Accel, p: Vec3A, time: f32) -> MediumStack {
    if !world.has_media {
        return MediumStack::default();
    }
    let answers = PROBE_DIRECTIONS.map(|d| media_along(world, accel, p, Vec3A::from(d).normalize(), time));
    if answers[1] == answers[2] && answers[0] != answers[1] {
        return answers[1].clone();
    }
    let [first, ..] = answers;
    first
}

/// The media around the camera at shutter time `time` for a camera that moves while the
/// shutter is open: `start` (the media where it is when the shutter opens, [`media_at`])
/// followed along the camera's way from there to where it is at `time`, straight between
/// its motion keys: a medium whose surface the camera crosses from the front is entered,
/// one it crosses from behind is left (the surfaces taken where they are at `time`).
/// `None` when the camera does not move, at the shutter's opening, or in scenes without
/// media: the camera is in `start`.
pub fn camera_media_at(world: &World, accel: &dyn Accel, start: &MediumStack, time: f32) -> Option<MediumStack> {
    let cam = &world.camera;
    if !world.has_media || cam.keys.len() < 2 || time <= 0.0 {
        return None;
    }
    let steps = cam.keys.len() - 1;
    let mut media = start.clone();
    let mut from = cam.camera_to_world_at(0.0).translation;
    for j in 1..=steps {
        let key_time = j as f32 / steps as f32;
        let to = cam.camera_to_world_at(key_time.min(time)).translation;
        cross_between(world, accel, &mut media, (from, to), time);
        if key_time >= time {
            break;
        }
        from = to;
    }
    Some(media)
}

/// The media at the origin of camera ray `ray` when it is not the camera's centre: an
/// orthographic camera's rays start across its image plane, each in the media around its
/// own origin — `at_centre` (the media around the camera's centre at the ray's shutter
/// time, [`media_at`] and [`camera_media_at`]) followed from the centre to the origin, in
/// the plane of the image, entering the media whose surfaces it crosses from the front and
/// leaving those it crosses from behind. `None` for perspective cameras (their rays start
/// at the centre) and in scenes without media: the ray starts in `at_centre`.
pub fn camera_ray_media(world: &World, accel: &dyn Accel, at_centre: &MediumStack, ray: &Ray) -> Option<MediumStack> {
    if !world.has_media || !world.camera.orthographic {
        return None;
    }
    let centre = world.camera.camera_to_world_at(ray.time).translation;
    let mut media = at_centre.clone();
    cross_between(world, accel, &mut media, (centre, ray.origin), ray.time);
    Some(media)
}

/// Follows `media` along the straight way from `ends.0` to `ends.1` (world space) at
/// shutter time `time`: enters the media of surfaces crossed from the front, leaves those
/// crossed from behind.
fn cross_between(world: &World, accel: &dyn Accel, media: &mut MediumStack, ends: (Vec3A, Vec3A), time: f32) {
    let (from, to) = ends;
    let length = (to - from).length();
    if !(length > 0.0 && length.is_finite()) {
        return;
    }
    let dir = (to - from) / length;
    let mut ray = Ray { mask: mask::CAMERA | mask::SECONDARY, origin: from, dir, tmin: 0.0, tmax: length, time };
    for _ in 0..MAX_BOUNDARY_CROSSINGS {
        let Some(hit) = accel.intersect(&ray) else { break };
        let s = surface(world, &ray, &hit);
        let m = &world.materials[s.material as usize];
        if m.medium.is_some() && m.has_inside() {
            if dir.dot(s.ng) < 0.0 {
                media.enter(s.material, medium_entered(world, s.material, &ray, &hit));
            } else {
                media.leave(s.material);
            }
        }
        ray.origin = s.leave(s.ng, dir);
        ray.tmax = (ray.tmax - hit.t).max(0.0);
    }
}

/// The media enclosing `p` as the surfaces along one ray from it in unit direction `dir`
/// tell ([`media_at`]).
fn media_along(world: &World, accel: &dyn Accel, p: Vec3A, dir: Vec3A, time: f32) -> MediumStack {
    let mut ray = Ray { mask: mask::CAMERA | mask::SECONDARY, origin: p, dir, tmin: 0.0, tmax: f32::INFINITY, time };
    // Objects entered along the ray and not yet left; objects left without being entered
    // (those enclosing `p`, each with its medium where the ray leaves it when that varies),
    // innermost first.
    let mut entered: Vec<u32> = Vec::new();
    let mut enclosing: Vec<(u32, Option<Medium>)> = Vec::new();
    for _ in 0..MAX_BOUNDARY_CROSSINGS {
        let Some(hit) = accel.intersect(&ray) else { break };
        let s = surface(world, &ray, &hit);
        let m = &world.materials[s.material as usize];
        if m.medium.is_some() && m.has_inside() {
            if dir.dot(s.ng) < 0.0 {
                entered.push(s.material);
            } else if let Some(i) = entered.iter().rposition(|&e| e == s.material) {
                entered.remove(i);
            } else {
                enclosing.push((s.material, medium_entered(world, s.material, &ray, &hit)));
            }
        }
        ray.origin = s.leave(s.ng, dir);
    }
    let mut stack = MediumStack::default();
    for (m, own) in enclosing.into_iter().rev() {
        stack.enter(m, own);
    }
    stack
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

/// The free flight of a ray in the medium the path (of throughput `by`) is in, up to
/// distance `t_end` (two sample numbers); `None` outside media.
pub(super) fn fly(world: &World, media: &MediumStack, t_end: f32, by: Rgb, sampler: &mut Sampler) -> Option<Flight> {
    let medium = media.current(world)?;
    Some(medium.sample_flight(t_end, sampler.next_2d(), by))
}

/// The light scattered towards the path at point `p` of `medium` that arrived along unit
/// `dir`, for a path of throughput `by` there: next-event estimation to one light or the
/// environment (transmittance along the shadow ray), MIS against the phase function
/// (sampled as that path samples it: see [`bsdf::phase`]). Uses three sample numbers.
#[allow(clippy::too_many_arguments)]
pub(super) fn direct_light(
    scene: &Lighting,
    medium: &Medium,
    media: &MediumStack,
    (p, by): (Vec3A, Rgb),
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
        let (phase, colour) = phase_towards(medium, dir, es.dir, by);
        counts.shadow_rays += 1;
        let tr = super::env_light::environment_transmittance(
            world,
            scene.accel,
            scene.shading,
            &from,
            &shadow_ray(es.dir, f32::INFINITY),
            scene.seed,
            env.shadow,
        );
        if tr == Rgb::ZERO {
            return Rgb::ZERO;
        }
        let weight = if scene.mis && !env.nee_only() { power_heuristic(scene.pick * es.pdf, phase) } else { 1.0 };
        return tr * es.radiance * colour * (env.lighting_scale * phase * weight / (scene.pick * es.pdf));
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
    let (phase, colour) = phase_towards(medium, dir, ls.wi, by);
    let tmax = if ls.dist.is_finite() { ls.dist * (1.0 - 1e-4) } else { f32::INFINITY };
    if light.shadow || world.has_media {
        counts.shadow_rays += 1;
    }
    let shadow = shadow_ray(ls.wi, tmax);
    let tr = light_transmittance(world, scene.accel, scene.shading, &from, &shadow, scene.seed, light.shadow, Some(k));
    if tr == Rgb::ZERO {
        return Rgb::ZERO;
    }
    let weight = if ls.delta || !scene.mis { 1.0 } else { power_heuristic(scene.pick * ls.pdf, phase) };
    tr * ls.radiance * colour * (phase * weight / (scene.pick * ls.pdf))
}

/// The phase function of `medium` for light arriving along unit `dir` and leaving along
/// unit `towards` (world space, directions of travel) as light sampling uses it on a path
/// of throughput `by`: its sampling density (what MIS weighs against) and the colour that
/// turns the density into the phase function's value per channel — 1 for a grey phase
/// function (its density is its value), value / density for a chromatic one.
#[inline]
fn phase_towards(medium: &Medium, dir: Vec3A, towards: Vec3A, by: Rgb) -> (f32, Rgb) {
    let pdf = medium.phase.pdf(dir, towards, by);
    if !medium.phase.is_chromatic() {
        return (pdf, Rgb::ONE);
    }
    let value = medium.phase.value(dir, towards);
    (pdf, if pdf > 0.0 { value / pdf } else { Rgb::ZERO })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Entering pushes, leaving removes the innermost entry of that material (also out of
    /// order, for overlapping objects).
    #[test]
    fn the_stack_nests_and_overlaps() {
        let mut s = MediumStack::default();
        assert!(s.is_empty());
        s.enter(3, None);
        s.enter(5, None);
        s.enter(3, None);
        s.leave(5);
        assert_eq!(s.materials().collect::<Vec<_>>(), [3, 3]);
        s.leave(7);
        assert_eq!(s.materials().count(), 2);
        s.leave(3);
        s.leave(3);
        assert!(s.is_empty());
    }

    /// Nesting deeper than the inline stack spills to the heap and forgets nothing; leaving
    /// out of order works there too, and a spilled stack equals an inline one of the same
    /// media.
    #[test]
    fn deep_nesting_forgets_no_medium() {
        let mut s = MediumStack::default();
        let depth = 3 * INLINE_NESTING as u32 + 1;
        for m in 1..=depth {
            s.enter(m, None);
        }
        assert_eq!(s.materials().collect::<Vec<_>>(), (1..=depth).collect::<Vec<_>>());
        s.leave(2);
        for m in (3..=depth).rev() {
            assert_eq!(s.materials().last(), Some(m));
            s.leave(m);
        }
        assert_eq!(s.materials().collect::<Vec<_>>(), [1]);
        let mut inline = MediumStack::default();
        inline.enter(1, None);
        assert_eq!(s, inline);
        s.leave(1);
        assert!(s.is_empty());
    }

    /// A medium evaluated where the path entered is the one the path travels in until it
    /// leaves that object, also under and over constant media; leaving it uncovers the
    /// medium entered before.
    #[test]
    fn a_medium_entered_with_its_own_value_is_the_current_one() {
        let own = Medium::new(Rgb::splat(0.25), Rgb::splat(0.5), 0.3);
        let mut s = MediumStack::default();
        s.enter(1, None);
        assert_eq!(s.top(), Some((1, None)));
        s.enter(1, Some(own));
        assert_eq!(s.top(), Some((1, Some(&own))));
        s.enter(2, None);
        assert_eq!(s.top(), Some((2, None)));
        s.leave(2);
        assert_eq!(s.top(), Some((1, Some(&own))));
        s.leave(1);
        assert_eq!(s.top(), Some((1, None)));
        s.leave(1);
        assert!(s.is_empty() && s.top().is_none());
    }
}
