//! Volume shaders: what happens to light along a ray segment (mental ray's volume shader
//! calls).
//!
//! After a ray's colour is known (the surface shader at its hit, or the environment on a
//! miss), the volume shader of the medium the ray travelled in modifies it: the material
//! volume of the innermost medium the ray is inside (entered through a refraction or
//! transparency ray, see [`super::state::State::enter`]), else the camera's volume (the
//! atmosphere). A material without a volume shader has none inside it: the camera's does
//! not apply there, as in mental ray, where entering a surface makes its material's volume
//! (possibly none) the current one.
//!
//! The volume shader's state is mental ray's: `org` and `dir` the ray's, `point` its hit
//! and `dist` the distance travelled, or, on a miss, `point` = `org` and `dist` = 0 (an
//! infinite segment); `ray_type` the ray's own. Its result arrives holding the ray's
//! colour. Light rays (a light shader's result on its way from the light to the
//! illuminated point: `org` on the light, `point` the illuminated point, `dir` from the
//! light, `dist` between them, `ray_type` [`RayType::Light`]) pass through the volume of
//! the medium the illuminated point is seen in, over their whole length (mental ray's
//! `shadow segments` mode, which splits them at every surface, is not followed).
//!
//! A material without a volume shader but with a participating medium
//! ([`super::shading::MaterialShaders::medium`], MDL's `material_volume`) acts as a volume
//! shader of a homogeneous medium: a ray segment of length d inside it keeps exp(−σt·d)
//! of its colour per channel (σt = σa + σs) and gains the light the medium scatters into
//! it from the scene's lights, single scattering ([`super::inscatter`]). Shadow rays
//! through such media are attenuated alike ([`ShadowMedia`]): they cross the medium's
//! index-matched boundary (tinted by its colour where they enter) and keep exp(−σt·d) over
//! each stretch d inside, the innermost medium counting, as for eye rays; a boundary that
//! refracts (glass) still stops them, and a surface with a shadow shader filters them by
//! that shader and is entered or left like any boundary. The light of a light that traces
//! no shadow ray (its shader's shadows off, or `shadow off` in the options) is still
//! attenuated by the media between it and the point: the walk then crosses every surface
//! ([`Ctx::light_media`]).
//!
//! A volume shader whose effect on a segment is affine in the colour it receives — c ↦
//! keep ⊙ c + add per channel, the same keep and add whatever c is (Maya's fogs) — also
//! tells those terms ([`crate::ShaderImpl::volume_terms`], [`VolumeTerms`]). The path
//! engine, which runs no shader on the colour a path brings back (it adds light forward,
//! weighted by the path's throughput), applies such a volume exactly: it adds
//! throughput ⊙ add and multiplies the throughput by keep ([`Ctx::volume_terms`]), on
//! the camera's volume and, inside the objects of a material, on that material's. A
//! shader whose effect is affine only for some of its connections (Maya's volume sampler)
//! says for which ([`crate::ShaderImpl::volume_affine`], asked by [`is_affine`]).

use glam::Vec3A;

use super::ctx::Ctx;
use super::graph::NodeId;
use super::shading::Shading;
use super::state::{RayType, State};
use super::value::{Color, Value};

/// A volume's effect on a segment as an affine map of the colour c arriving from behind
/// it: keep ⊙ c + add (per channel, RGB).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeTerms {
    /// The share of what lies behind that reaches the segment's origin.
    pub keep: Vec3A,
    /// What the volume itself adds along the segment.
    pub add: Vec3A,
}

impl VolumeTerms {
    /// No effect: keep everything, add nothing.
    pub const NONE: VolumeTerms = VolumeTerms { keep: Vec3A::ONE, add: Vec3A::ZERO };

    /// `self` applied to what `behind` (the next volume along the list, which receives the
    /// colour first) leaves: c ↦ keep ⊙ (behind.keep ⊙ c + behind.add) + add.
    pub fn after(self, behind: VolumeTerms) -> VolumeTerms {
        VolumeTerms { keep: self.keep * behind.keep, add: self.keep * behind.add + self.add }
    }

    /// The terms applied to colour `c` (RGB).
    pub fn apply(self, c: Vec3A) -> Vec3A {
        self.keep * c + self.add
    }
}

/// Whether every shader of the volume shader list at `head` tells its affine terms
/// ([`crate::ShaderImpl::volume_terms`]), so that [`Ctx::volume_terms`] describes the list.
pub fn is_affine(shading: &Shading, head: NodeId) -> bool {
    let mut node = Some(head);
    let mut guard = 0;
    while let Some(n) = node {
        let Some(x) = shading.graph.nodes.get(n as usize) else { return false };
        let Some(imp) = x.imp.filter(|i| i.volume_terms.is_some()) else { return false };
        if imp.volume_affine.is_some_and(|affine| !affine(shading, n)) {
            return false;
        }
        node = x.next;
        guard += 1;
        if guard > 1024 {
            return false;
        }
    }
    true
}

impl Shading {
    /// Whether the camera's volume shader list or some material's is affine
    /// ([`is_affine`]: the fogs the path engine applies). Found once, on the
    /// first question (after the renderer handed over what affinity depends on).
    pub fn has_affine_volumes(&self) -> bool {
        *self.affine_volumes.get_or_init(|| {
            self.volume.into_iter().chain(self.materials.iter().filter_map(|m| m.volume)).any(|v| is_affine(self, v))
        })
    }
}

impl Ctx<'_> {
    /// The affine terms of the volume shader list at `head` over the segment of the
    /// context's state (mental ray's volume state, see the module documentation): each
    /// shader's terms in list order (a list's shaders run in turn on one result, so the
    /// first receives the colour first); `None` when one of them tells none (see
    /// [`is_affine`]).
    pub fn volume_terms(&mut self, head: NodeId) -> Option<VolumeTerms> {
        let mut terms = VolumeTerms::NONE;
        let mut node = Some(head);
        let mut guard = 0;
        while let Some(n) = node {
            let run = self.node(n).imp.and_then(|i| i.volume_terms)?;
            self.counts.calls += 1;
            terms = run(self, n).after(terms);
            node = self.node(n).next;
            guard += 1;
            if guard > 1024 {
                return None;
            }
        }
        Some(terms)
    }

    /// The volume shader list of the medium a ray with state `s` travels in: the innermost
    /// entered material's volume (`None` if it has none), else the camera's.
    pub fn volume_of(&self, s: &State) -> Option<NodeId> {
        let shading = self.shading();
        match s.medium() {
            Some(m) => shading.materials.get(m.material as usize).and_then(|m| m.volume),
            None => shading.volume,
        }
    }

    /// The participating medium a ray with state `s` travels in: the innermost entered
    /// material's, where that material has no volume shader (as evaluated where the ray
    /// entered it, when it varies over the surface).
    pub fn medium_of(&self, s: &State) -> Option<bsdf::Medium> {
        let m = self.shading().materials.get(s.medium()?.material as usize)?;
        let own = s.media.innermost_evaluated().copied();
        own.or(m.medium).filter(|_| m.volume.is_none())
    }

    /// Whether a volume (a shader or a medium) changes the colour of a ray with state `s`.
    pub fn has_volume(&self, s: &State) -> bool {
        self.volume_of(s).is_some() || self.medium_of(s).is_some()
    }

    /// Runs volume shader list `volume` on `color` for the segment `state` describes
    /// (see the module documentation) and returns the modified colour.
    pub fn run_volume(&mut self, volume: NodeId, state: State, color: Color) -> Color {
        let mut ctx = Ctx::new(self.shading(), self.tracer, state);
        let mut result = Value::Color(color);
        ctx.run_list(volume, &mut result);
        self.counts.calls += ctx.counts.calls;
        result.color()
    }

    /// Applies the volume of the medium `ray` travelled in to the colour it brought back:
    /// `ray` is the traced ray's state after intersection (`hit`: it found a surface at
    /// `ray.dist`; else it escaped to infinity). Rays that are not eye, reflection,
    /// refraction, transparency or final gather rays are left alone.
    pub fn ray_volume(&mut self, ray: &State, hit: bool, color: Color) -> Color {
        let kinds = matches!(
            ray.ray_type,
            RayType::Eye | RayType::Reflect | RayType::Refract | RayType::Transparent | RayType::Finalgather
        );
        if !kinds {
            return color;
        }
        if let Some(medium) = self.medium_of(ray) {
            // Beer–Lambert over the segment; a ray that escaped crossed an infinite one.
            let length = if hit { ray.dist } else { f32::INFINITY };
            let t = medium.transmittance(length);
            // In-scattered light, and what the medium emits along the segment.
            let s = self.in_scattered(&medium, ray, length) + medium.emitted(length);
            return Color::new(color.x * t.x + s.x, color.y * t.y + s.y, color.z * t.z + s.z, color.w);
        }
        let Some(volume) = self.volume_of(ray) else { return color };
        let mut s = ray.clone();
        if !hit {
            s.point = s.org;
            s.dist = 0.0;
        }
        self.run_volume(volume, s, color)
    }

    /// Attenuates a light shader's result `color` on light ray `light` (a light state, see
    /// [`Ctx::light_volume`]) by the participating media between the illuminated point and
    /// the light, for a light whose shader traced no shadow ray: the walk towards the light
    /// crosses every surface, entering and leaving the media of those that have one, and
    /// keeps the innermost medium's transmittance over each stretch (no surface blocks or
    /// tints). Unchanged in scenes without media.
    pub fn light_media(&mut self, light: &State, color: Color) -> Color {
        let shading = self.shading();
        if !shading.has_media() || crate::is_zero(color) {
            return color;
        }
        let to_light = -light.dir;
        let org = crate::trace::leave_point(light.shadow_point, light.point_error, light.normal_geom, to_light);
        let max_dist = if light.dist.is_finite() { light.dist * (1.0 - 1e-4) } else { f32::INFINITY };
        let mut ray = light.child(RayType::Shadow, org, to_light);
        ray.light = light.light;
        let mut filter = color;
        let mut media = ShadowMedia::new(&ray);
        if shading.has_varying_media() {
            // Where a medium entered varies over its surface, the walk needs each surface's
            // shading state to evaluate it.
            self.tracer.shadow_hits(&ray, max_dist, &mut |hit: &State| {
                media.advance(shading, hit.dist, &mut filter);
                media.pass(shading, hit);
                !crate::is_zero(filter)
            });
        } else {
            self.tracer.boundary_hits(&ray, max_dist, &mut |dist, material| {
                media.advance(shading, dist, &mut filter);
                media.pass_material(shading, material);
                !crate::is_zero(filter)
            });
        }
        media.advance(shading, max_dist - media.walked(), &mut filter);
        filter
    }

    /// Applies the volume to a light shader's result on light ray `light` (a light state:
    /// `org` on the light, `point` the illuminated point, `dist` between them, infinite for
    /// directional lights, where the volume sees 0, an infinite segment).
    pub fn light_volume(&mut self, light: &State, color: Color) -> Color {
        let Some(volume) = self.volume_of(light) else { return color };
        let mut s = light.clone();
        s.ray_type = RayType::Light;
        if !s.dist.is_finite() {
            s.dist = 0.0;
        }
        self.run_volume(volume, s, color)
    }
}

/// The length of a volume shader's segment: `state.dist`, or infinite where mental ray
/// gives 0 (a ray that hit nothing, a directional light's ray).
pub fn segment_length(state: &State) -> f32 {
    if state.dist > 0.0 {
        state.dist
    } else {
        f32::INFINITY
    }
}

/// The media a shadow ray is inside as it walks from the illuminated point towards the
/// light (the classic engine's Beer–Lambert media, see the module documentation): the
/// materials it entered, innermost last, starting with those the illuminated point's ray
/// was inside. A medium that varies over its object's surface is the one evaluated where
/// the illuminated point's ray entered it, or where the shadow ray enters it
/// ([`ShadowMedia::cross`], [`ShadowMedia::pass`]; walks that know only the material,
/// [`ShadowMedia::cross_material`] and [`ShadowMedia::pass_material`], take its value at
/// the material's default point).
pub struct ShadowMedia {
    /// The scene materials entered, innermost last, each with its medium where that was
    /// evaluated at the entry point.
    inside: Vec<(u32, Option<bsdf::Medium>)>,
    /// Distance walked from the illuminated point (scene units).
    walked: f32,
}

impl ShadowMedia {
    /// The media at the start of shadow ray `ray` (a state whose media chain is the
    /// illuminated point's).
    pub fn new(ray: &State) -> Self {
        Self { inside: ray.media.evaluated().map(|(m, own)| (m.material, own)).collect(), walked: 0.0 }
    }

    /// Walks `dist` further (to the next surface, or to the light): `filter` keeps the
    /// innermost medium's transmittance over that stretch.
    pub fn advance(&mut self, shading: &Shading, dist: f32, filter: &mut Color) {
        self.walked += dist;
        let Some(&(innermost, own)) = self.inside.last() else { return };
        let Some(m) = shading.materials.get(innermost as usize) else { return };
        if let Some(medium) = own.or(m.medium).filter(|_| m.volume.is_none()) {
            let t = medium.transmittance(dist.max(0.0));
            *filter = Color::new(filter.x * t.x, filter.y * t.y, filter.z * t.z, filter.w);
        }
    }

    /// Crosses `hit`'s surface, one without a shadow shader: an index-matched boundary of a
    /// medium is entered (tinting `filter` by its colour) or left; returns false for any
    /// other surface, which stops the shadow ray.
    pub fn cross(&mut self, shading: &Shading, hit: &State, filter: &mut Color) -> bool {
        self.cross_at(shading, hit.material, Some(hit), filter)
    }

    /// [`ShadowMedia::cross`] of a surface of scene material `material` (`None`: none).
    pub fn cross_material(&mut self, shading: &Shading, material: Option<u32>, filter: &mut Color) -> bool {
        self.cross_at(shading, material, None, filter)
    }

    /// Crosses a surface of `material`, `hit` its state when known (where a varying
    /// medium entered is evaluated).
    fn cross_at(&mut self, shading: &Shading, material: Option<u32>, hit: Option<&State>, filter: &mut Color) -> bool {
        let Some(m) = material else { return false };
        let Some(tint) = shading.materials.get(m as usize).and_then(|x| x.boundary_tint) else { return false };
        if !self.leave(m) {
            self.inside.push((m, evaluated(shading, m, hit)));
            *filter = Color::new(filter.x * tint.x, filter.y * tint.y, filter.z * tint.z, filter.w);
        }
        true
    }

    /// Leaves the innermost medium of material `m`; false when the walk is not inside it.
    fn leave(&mut self, m: u32) -> bool {
        let Some(i) = self.inside.iter().rposition(|&(x, _)| x == m) else { return false };
        self.inside.remove(i);
        true
    }

    /// Passes `hit`'s surface, whatever it is (a light without shadows, or a surface whose
    /// shadow shader filtered the ray): a surface whose material has a medium is entered or
    /// left, untinted.
    pub fn pass(&mut self, shading: &Shading, hit: &State) {
        self.pass_at(shading, hit.material, Some(hit));
    }

    /// [`ShadowMedia::pass`] of a surface of scene material `material` (`None`: none).
    pub fn pass_material(&mut self, shading: &Shading, material: Option<u32>) {
        self.pass_at(shading, material, None);
    }

    /// Passes a surface of `material`, `hit` its state when known.
    fn pass_at(&mut self, shading: &Shading, material: Option<u32>, hit: Option<&State>) {
        let Some(m) = material else { return };
        if shading.materials.get(m as usize).is_none_or(|x| x.medium.is_none()) {
            return;
        }
        if !self.leave(m) {
            self.inside.push((m, evaluated(shading, m, hit)));
        }
    }

    /// The distance walked so far.
    pub fn walked(&self) -> f32 {
        self.walked
    }
}

/// The medium of material `m` evaluated at surface state `hit`, where it varies over the
/// surface and the state is known (`None`: the material's constant medium applies).
fn evaluated(shading: &Shading, m: u32, hit: Option<&State>) -> Option<bsdf::Medium> {
    let varying = shading.materials.get(m as usize)?.varying_medium.as_ref()?;
    Some(varying.at(hit?))
}
