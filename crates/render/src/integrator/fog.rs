//! Volumes in the path engine: the camera's (mental ray's atmosphere, e.g. Maya's
//! environment and light fogs) and materials' (Maya's shading groups with a fog or a
//! volumeFog inside their objects).
//!
//! mental ray runs a volume shader on the colour each eye, reflection, refraction,
//! transparency and final gather ray brings back over its segment: the volume of the
//! innermost material the ray entered (through a refraction or transparency ray), else
//! the camera's. The path engine adds light forward instead (each contribution weighted by
//! the path's throughput), so it applies a volume whose effect is affine in the colour it
//! receives — c ↦ keep ⊙ c + add over the segment, as Maya's fogs and volume materials
//! are ([`shader::volume::VolumeTerms`]) — exactly: at every stretch of a path outside
//! the path engine's media it adds throughput ⊙ add (the fog's own light in front of what
//! lies behind) and multiplies the throughput by keep (what lies behind, the environment
//! and everything found later along the path). The terms come from the same shader code
//! the classic engine runs, on the same volume state (`org`, `dir`, `point`, `dist`, the
//! object space of the surface the stretch ends at; a ray that leaves the scene has an
//! infinite segment), so both engines give the same fog: a camera ray's composite is the
//! classic eye ray's, and rays after a bounce see it as the classic engine's reflection,
//! refraction and final gather rays do.
//!
//! A path enters a material with an affine volume where it passes through a cut-out
//! surface of it (Maya's transparency) or is transmitted through it, and leaves it the
//! same way ([`PathFog`]); the stretches of a ray between such surfaces take the volume
//! current on each. Next-event estimation at a surface sees the lights through the volume
//! the point is seen in, as mental ray's light rays do: Maya's fogs let them pass, a
//! volume material keeps its transparency of them ([`PathFog::light_keep`]).
//!
//! What differs: the classic engine leaves the atmosphere inside a closed object without
//! a volume that a ray refracted into (that material's volume, none, is current there);
//! the path engine keeps the volume current outside it (the camera's, or the fog
//! material's it is inside). A volume with any shader that tells no affine terms is not
//! applied (a warning at compile time names it).

use glam::{Affine3A, Vec3A};
use shader::volume::VolumeTerms;
use shader::{Ctx, NodeId, RayType, Shading, State};

use crate::accel::Accel;
use crate::ray::Ray;
use crate::world::World;

/// The affine volume (see [`shader::volume::is_affine`]) of world material `material`
/// (an index into `World::materials`, whose 0 is the default material), if it has one.
fn material_fog(shading: &Shading, material: u32) -> Option<NodeId> {
    let m = shading.materials.get(material.checked_sub(1)? as usize)?;
    m.volume.filter(|&v| shader::volume::is_affine(shading, v))
}

/// A surface of a fog material that a ray passed through where it is cut out (its
/// transparency), before the surface the ray stopped at.
#[derive(Clone, Copy, Debug)]
struct Crossing {
    /// Distance along the ray (world units).
    t: f32,
    /// The world material.
    material: u32,
    /// Its volume.
    volume: NodeId,
    /// The instance crossed.
    instance: u32,
}

/// The fogs along one path: the camera's volume when it is affine, the fog materials the
/// path entered and has not left (entered and left as mental ray's refraction and
/// transparency rays do: crossing a surface of a material not entered enters it, one
/// entered leaves it), and the fog surfaces the current ray passed through.
///
/// Nothing here allocates unless a path passes through a fog material's surface.
pub(super) struct PathFog<'s> {
    /// The compiled shading, when there is one.
    shading: Option<&'s Shading>,
    /// The camera's volume, when the path engine applies it.
    camera: Option<NodeId>,
    /// The fog materials entered (world material, its volume), innermost last.
    inside: Vec<(u32, NodeId)>,
    /// The current ray's fog surfaces passed through, nearest first.
    crossings: Vec<Crossing>,
}

impl<'s> PathFog<'s> {
    /// Outside every fog material, with the camera's volume of `shading`. (A scene without
    /// an affine volume keeps no shading: no fog can apply, [`PathFog::possible`].)
    pub(super) fn new(shading: Option<&'s Shading>) -> Self {
        let shading = shading.filter(|s| s.has_affine_volumes());
        PathFog { shading, camera: camera_fog(shading).map(|(_, v)| v), inside: Vec::new(), crossings: Vec::new() }
    }

    /// Whether any fog may apply to the path: the scene has an affine volume. When not,
    /// [`PathFog::is_active`] is false throughout and the other methods change nothing,
    /// so the path loop skips them.
    #[inline]
    pub(super) fn possible(&self) -> bool {
        self.shading.is_some()
    }

    /// Whether some fog applies to the path's current ray.
    #[inline]
    pub(super) fn is_active(&self) -> bool {
        self.camera.is_some() || !self.inside.is_empty() || !self.crossings.is_empty()
    }

    /// The volume the path's current segment travels in: the innermost fog material's,
    /// else the camera's.
    fn current(&self) -> Option<NodeId> {
        self.inside.last().map(|&(_, v)| v).or(self.camera)
    }

    /// Enters fog material `material` (volume `volume`), or leaves it when inside it.
    fn toggle(&mut self, material: u32, volume: NodeId) {
        match self.inside.iter().rposition(|&(m, _)| m == material) {
            Some(i) => {
                self.inside.remove(i);
            }
            None => self.inside.push((material, volume)),
        }
    }

    /// Records that the current ray passed, at distance `t`, through a cut-out surface of
    /// world material `material` of instance `instance` (nothing for a material without a
    /// fog volume).
    #[inline]
    pub(super) fn passed_through(&mut self, material: u32, t: f32, instance: u32) {
        let Some(shading) = self.shading else { return };
        if let Some(volume) = material_fog(shading, material) {
            self.crossings.push(Crossing { t, material, volume, instance });
        }
    }

    /// Follows a path scattered at a surface of world material `material` (geometric
    /// normal `ng`) from `dir_in` to `dir_out`: a transmission enters or leaves the
    /// material's fog.
    #[inline]
    pub(super) fn scattered(&mut self, material: u32, ng: Vec3A, dir_in: Vec3A, dir_out: Vec3A) {
        let transmitted = (dir_in.dot(ng) < 0.0) == (dir_out.dot(ng) < 0.0);
        let Some(shading) = self.shading.filter(|_| transmitted) else { return };
        if let Some(volume) = material_fog(shading, material) {
            self.toggle(material, volume);
        }
    }

    /// The fogs' terms over the current `ray` up to distance `t_end` (infinite: it left the
    /// scene), ending at a surface of instance `end` (`None`: none), a ray of type
    /// `ray_type` after `depth` bounces: the volume current on each stretch between the
    /// fog surfaces it passed through, front to back; those surfaces enter or leave their
    /// fogs. With `apply` false the fogs are followed and no terms are computed (a path in
    /// a participating medium).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn along(
        &mut self,
        world: &World,
        accel: &dyn Accel,
        ray: &Ray,
        t_end: f32,
        end: Option<u32>,
        ray_type: RayType,
        depth: u32,
        apply: bool,
    ) -> VolumeTerms {
        let crossings = std::mem::take(&mut self.crossings);
        let mut terms = VolumeTerms::NONE;
        let mut start = 0.0;
        let mut kind = ray_type;
        for c in crossings.iter().filter(|c| c.t < t_end) {
            if apply {
                terms = terms.after(self.stretch(world, accel, ray, (start, c.t), Some(c.instance), kind, depth));
            }
            self.toggle(c.material, c.volume);
            start = c.t;
            kind = RayType::Transparent;
        }
        if apply {
            terms = terms.after(self.stretch(world, accel, ray, (start, t_end), end, kind, depth));
        }
        self.crossings = crossings;
        self.crossings.clear();
        terms
    }

    /// The current volume's terms over the stretch `span` of `ray` (see [`PathFog::along`]).
    #[allow(clippy::too_many_arguments)]
    fn stretch(
        &self,
        world: &World,
        accel: &dyn Accel,
        ray: &Ray,
        span: (f32, f32),
        end: Option<u32>,
        ray_type: RayType,
        depth: u32,
    ) -> VolumeTerms {
        let (Some(shading), Some(volume)) = (self.shading, self.current()) else { return VolumeTerms::NONE };
        let org = ray.origin + ray.dir * span.0;
        // mental ray's volume state: a ray that hit nothing has `point` = `org`, `dist` 0.
        let (point, dist) =
            if span.1.is_finite() { (ray.origin + ray.dir * span.1, span.1 - span.0) } else { (org, 0.0) };
        // The object space of the surface the stretch ends at, as a volume shader's state
        // after intersection has it.
        let (world_to_object, object_to_world) = end.map_or((Affine3A::IDENTITY, Affine3A::IDENTITY), |i| {
            let placed = world.instances[i as usize].placement(ray.time);
            (placed.world_to_object, placed.object_to_world)
        });
        let state = State {
            ray_type,
            reflection_level: depth,
            org,
            dir: ray.dir,
            point,
            dist,
            ior_in: 1.0,
            ior: 1.0,
            child_dist: f32::INFINITY,
            time: ray.time,
            world_to_object,
            object_to_world,
            ..State::default()
        };
        volume_terms(world, accel, shading, volume, state)
    }

    /// What the volume the path is in lets through of a light's light arriving at `p`
    /// from unit direction `wi` over distance `dist` (infinite: a directional light), as
    /// mental ray's light rays pass through the volume of the medium the illuminated point
    /// is seen in (Maya's volume materials dim them by their transparency; the fogs let
    /// them pass). 1 outside every fog.
    pub(super) fn light_keep(
        &self,
        world: &World,
        accel: &dyn Accel,
        p: Vec3A,
        wi: Vec3A,
        dist: f32,
        time: f32,
    ) -> Vec3A {
        let (Some(shading), Some(volume)) = (self.shading, self.current()) else { return Vec3A::ONE };
        let finite = dist.is_finite();
        let state = State {
            ray_type: RayType::Light,
            org: if finite { p + wi * dist } else { p },
            dir: -wi,
            point: p,
            dist: if finite { dist } else { 0.0 },
            ior_in: 1.0,
            ior: 1.0,
            child_dist: f32::INFINITY,
            time,
            ..State::default()
        };
        volume_terms(world, accel, shading, volume, state).keep
    }
}

/// The terms of volume shader list `volume` over the segment `state` describes.
fn volume_terms(world: &World, accel: &dyn Accel, shading: &Shading, volume: NodeId, state: State) -> VolumeTerms {
    let tracer = crate::tracer::SceneTracer::new(world, accel);
    let mut ctx = Ctx::new(shading, &tracer, state);
    ctx.volume_terms(volume).unwrap_or(VolumeTerms::NONE)
}

/// The camera's volume shader list when the path engine applies it: every shader in it
/// tells its affine terms ([`shader::volume::is_affine`]).
fn camera_fog(shading: Option<&Shading>) -> Option<(&Shading, NodeId)> {
    let shading = shading?;
    let head = shading.volume?;
    shader::volume::is_affine(shading, head).then_some((shading, head))
}

/// The mental ray ray type of a path's segment after `depth` bounces: the camera's ray,
/// then a reflection or a refraction by the side the last bounce left `ng` (the surface's
/// normal facing the arriving ray) on along `dir`; `Finalgather` after a diffuse or glossy
/// bounce (`delta` false).
pub(super) fn segment_type(depth: u32, delta: bool, ng: Vec3A, dir: Vec3A) -> RayType {
    match (depth, delta) {
        (0, _) => RayType::Eye,
        (_, false) => RayType::Finalgather,
        _ if dir.dot(ng) >= 0.0 => RayType::Reflect,
        _ => RayType::Refract,
    }
}
