//! The stretches a shadow ray goes inside the receiving point's own object, for Maya's
//! `translucenceDepth` ([`material::maya::translucent_passage`]): the path engine's form
//! of the classic engine's `shader::State::inside_own`. The ray starts on the object
//! (inside it, for light from behind); each time it leaves the object (meets one of its
//! surfaces from behind) the stretch since it entered (met one from the front), or since
//! its start, is what it went through.

use bsdf::Rgb;
use material::HitMaterial;

use super::Surface;
use crate::accel::Hit;
use crate::world::World;

/// A shadow ray's walk through the receiving point's own instance.
pub(super) struct OwnStretch {
    /// The receiving point's instance (an index into [`World::instances`]); `None`: no
    /// receiving surface (a point in a medium), no stretch counts.
    own: Option<u32>,
    /// Distance walked along the ray so far (world units).
    walked: f32,
    /// Where along the ray it last entered the own instance (0: its start).
    entered: f32,
}

impl OwnStretch {
    /// The walk of a shadow ray leaving a point of instance `own`.
    pub(super) fn new(own: Option<u32>) -> OwnStretch {
        OwnStretch { own, walked: 0.0, entered: 0.0 }
    }

    /// Records the ray's next hit `hit` (its distance from the last) on `surface`, met
    /// along `dir`: the stretch inside the own instance when the ray leaves it there.
    pub(super) fn step(&mut self, hit: &Hit, surface: &Surface, dir: glam::Vec3A) -> Option<f32> {
        self.walked += hit.t;
        if self.own != Some(hit.instance) {
            return None;
        }
        if surface.ng.dot(dir) > 0.0 {
            Some(self.walked - self.entered)
        } else {
            self.entered = self.walked;
            None
        }
    }
}

/// What a shadow ray along `dir` passes at its hit on `surface` (material `m` there),
/// having gone `inside` through the receiving point's own object when it leaves it there:
/// the material's translucent passage ([`material::maya::translucent_passage`], at the
/// ray's facing ratio |N·D| of the (bumped) shading normal, as `material_at` reads the
/// view's ramps) when it has one, else `None` (the surface filters the ray as any other).
pub(super) fn passage(
    world: &World,
    m: &HitMaterial,
    surface: &Surface,
    dir: glam::Vec3A,
    inside: Option<f32>,
) -> Option<Rgb> {
    let inside = inside?;
    let facing = m.normal.unwrap_or(surface.ns).dot(dir).abs().min(1.0);
    material::maya::translucent_passage(&world.materials[surface.material as usize], m, inside, facing)
}
