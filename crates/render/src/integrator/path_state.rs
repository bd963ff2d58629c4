//! A camera path's state between two bounces, as the compact kernel for plain hits
//! ([`super::plain_path`]) hands it to the general loop: everything the general loop keeps
//! from one bounce to the next that a plain bounce can change.

use bsdf::Rgb;

use super::CameraRay;
use crate::accel::Hit;
use crate::ray::{FirstHit, Ray};

/// A path's radiance, summed term by term twice while the first bounce's shadow ray is
/// left to the caller: `lit` with that ray's light, `shadowed` without it. Every other
/// term goes into both in the same order, so each is, bit for bit, the sum the path makes
/// when the ray is (or is not) blocked.
#[derive(Clone, Copy)]
pub(super) struct RadianceSum {
    pub(super) lit: Rgb,
    pub(super) shadowed: Rgb,
}

impl RadianceSum {
    /// Nothing yet.
    pub(super) const ZERO: RadianceSum = RadianceSum { lit: Rgb::ZERO, shadowed: Rgb::ZERO };
}

impl std::ops::AddAssign<Rgb> for RadianceSum {
    #[inline(always)]
    fn add_assign(&mut self, term: Rgb) {
        self.lit += term;
        self.shadowed += term;
    }
}

/// Where the general path loop starts: at the camera ([`Resume::camera`]), or where the
/// plain kernel stopped, before bounce `depth` (its ray traced, its hit in `known`).
/// The state a plain bounce never changes (reflection and refraction levels, media, fogs,
/// the glossy share, a material's own environment) is the camera's.
pub(super) struct Resume {
    /// The bounce to go on with (0: the camera ray's).
    pub(super) depth: u32,
    /// The ray of that bounce (world space).
    pub(super) ray: Ray,
    /// Its closest hit when found already (as `Accel::intersect` gives it).
    pub(super) known: Option<Option<Hit>>,
    /// The path's throughput so far.
    pub(super) throughput: Rgb,
    /// Its radiance so far.
    pub(super) radiance: RadianceSum,
    /// The first bounce's shadow ray when it was left to the caller.
    pub(super) pending: Option<Ray>,
    /// The camera ray's hit, once found.
    pub(super) first: Option<FirstHit>,
    /// The glow of the surface the camera ray stopped at.
    pub(super) glow: Option<Rgb>,
    /// 1 once the path hit something.
    pub(super) alpha: f32,
    /// The density of the last bounce's BSDF sample (for MIS on lights found).
    pub(super) last_pdf: f32,
    /// Whether the last bounce was a delta one (the camera's counts as one).
    pub(super) last_delta: bool,
    /// The instance the path last scattered at (light linking; none at the camera).
    pub(super) from_instance: Option<u32>,
}

impl Resume {
    /// A path's start: the camera ray, nothing found or summed yet.
    #[inline(always)]
    pub(super) fn camera(camera: &CameraRay) -> Resume {
        Resume {
            depth: 0,
            ray: camera.ray,
            known: camera.hit,
            throughput: Rgb::ONE,
            radiance: RadianceSum::ZERO,
            pending: None,
            first: None,
            glow: None,
            alpha: 0.0,
            last_pdf: 0.0,
            last_delta: true,
            from_instance: None,
        }
    }
}
