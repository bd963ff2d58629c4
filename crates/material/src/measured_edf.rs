//! MDL's `df::measured_edf`: emission distributed over directions as a measured light
//! profile (an IES file read by [`shader::light::ies`]) says. The radiance leaving towards
//! a direction is the emission intensity times `multiplier` times the profile's intensity
//! (candela) towards it — the profile's values are not normalised, as MDL's specification
//! (section 21.2: `multiplier` scales "the light distribution intensity") and the MDL SDK's
//! evaluation (`multiplier · light_profile_evaluate(θ, φ)`) have it — and nothing behind
//! the surface.
//!
//! **Frames.** The distribution's frame has its main axis (the profile's vertical angle
//! 0, an IES type C file's nadir) along +z; the horizontal angle φ runs from its x axis
//! towards its y axis. Without `global_distribution` the frame is the surface's: z the
//! shading normal, x the `tangent_u` laid into the tangent plane, y = x × normal (as the MDL
//! SDK orients it, so that φ runs counter-clockwise seen from behind the emitter, as LM-63
//! counts it seen from above a lamp hanging down); with it, the columns of `global_frame`
//! (world space, mira's object space being the world's for module materials, as for
//! `spot_edf`). A frame direction (x, y, z) is the profile reader's light-local direction
//! (x, y, −z) (its photometric axis is −Z): `::nvidia::core_definitions::light_ies`'s
//! frame diag(1, 1, −1) is then exactly the light-local frame of a mental ray light.

use std::sync::Arc;

use glam::{Mat3A, Vec3A};
use shader::light::ies::Profile;

/// A measured emission distribution.
#[derive(Clone, Debug, PartialEq)]
pub struct MeasuredEdf {
    /// The light profile (candela over directions).
    pub profile: Arc<Profile>,
    /// `multiplier` (non-negative).
    pub multiplier: f32,
    /// The distribution's frame in world space (columns x, y, z; z the main axis) with
    /// `global_distribution`, or `None`: the surface's own frame.
    pub global_frame: Option<Mat3A>,
}

impl MeasuredEdf {
    /// The distribution of `profile` scaled by `multiplier` (negative and non-finite read
    /// as 0), in the world frame `global_frame` (columns; `None`: the surface's frame).
    pub fn new(profile: Arc<Profile>, multiplier: f32, global_frame: Option<Mat3A>) -> MeasuredEdf {
        let multiplier = if multiplier.is_finite() { multiplier.max(0.0) } else { 0.0 };
        MeasuredEdf { profile, multiplier, global_frame }
    }

    /// multiplier × the profile's candela towards `frame_dir`, a unit direction in the
    /// distribution's frame (z its main axis).
    pub fn in_frame(&self, frame_dir: Vec3A) -> f32 {
        self.multiplier * self.profile.candela(Vec3A::new(frame_dir.x, frame_dir.y, -frame_dir.z))
    }

    /// The radiance towards `dir_out` (world space, unit) per unit of emission intensity,
    /// from a surface of shading normal `normal` (world space, unit) whose `tangent_u` is
    /// `tangent` (world space; `None` or parallel to the normal: a tangent of the normal
    /// picked by [`bsdf::Frame::from_normal`]); 0 behind the surface.
    pub fn factor(&self, normal: Vec3A, tangent: Option<Vec3A>, dir_out: Vec3A) -> f32 {
        if normal.dot(dir_out) <= 0.0 {
            return 0.0;
        }
        let local = match self.global_frame {
            Some(frame) => frame.transpose() * dir_out,
            None => {
                let (x, y) = surface_axes(normal, tangent);
                Vec3A::new(dir_out.dot(x), dir_out.dot(y), dir_out.dot(normal))
            }
        };
        self.in_frame(local)
    }

    /// ∫ over the hemisphere about the main axis of the distribution times the cosine to
    /// that axis (W per unit area per unit of intensity for the surface's own frame): what
    /// a `intensity_power` emission divides by (with the area) to emit its power.
    pub fn hemisphere_power(&self) -> f32 {
        // Midpoint rule, 256 × 512 cells in (θ, φ).
        const NT: usize = 256;
        const NP: usize = 512;
        let (dt, dp) = (std::f64::consts::FRAC_PI_2 / NT as f64, std::f64::consts::TAU / NP as f64);
        let mut sum = 0.0f64;
        for i in 0..NT {
            let t = (i as f64 + 0.5) * dt;
            let (st, ct) = t.sin_cos();
            for j in 0..NP {
                let (sp, cp) = ((j as f64 + 0.5) * dp).sin_cos();
                let d = Vec3A::new((st * cp) as f32, (st * sp) as f32, ct as f32);
                sum += f64::from(self.in_frame(d)) * ct * st;
            }
        }
        (sum * dt * dp) as f32
    }
}

/// The surface frame's x (`tangent` laid into the tangent plane) and y = x × normal axes.
fn surface_axes(normal: Vec3A, tangent: Option<Vec3A>) -> (Vec3A, Vec3A) {
    let x = tangent
        .and_then(|t| (t - normal * normal.dot(t)).try_normalize())
        .unwrap_or_else(|| bsdf::Frame::from_normal(normal).tangent);
    (x, x.cross(normal))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A type C profile with a horizontal dependence: 0°: 100/50/10 cd at V 0/45/90°,
    /// 90°: 100/80/20, 180° and 270° as 0° and 90°.
    fn profile() -> Arc<Profile> {
        let text = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 5 1 1 0.1 0.1 0\n1 1 10\n0 45 90\n0 90 180 270 360\n\
                    100 50 10\n100 80 20\n100 50 10\n100 80 20\n100 50 10\n";
        Arc::new(Profile::parse(text, false).expect("profile").0)
    }

    /// In the surface's frame: along the normal the vertical angle 0; 45° from it towards
    /// the tangent horizontal 0°, towards x × normal 90° (× multiplier 2); nothing behind.
    #[test]
    fn the_surface_frame_follows_the_normal_and_tangent() {
        let e = MeasuredEdf::new(profile(), 2.0, None);
        let (n, t) = (Vec3A::Z, Vec3A::X);
        assert!((e.factor(n, Some(t), n) - 200.0).abs() < 1e-3);
        let at_45 = |d: Vec3A| (d + n).normalize();
        assert!((e.factor(n, Some(t), at_45(Vec3A::X)) - 100.0).abs() < 1e-3);
        assert!((e.factor(n, Some(t), at_45(Vec3A::NEG_Y)) - 160.0).abs() < 1e-3);
        assert_eq!(e.factor(n, Some(t), -n), 0.0);
    }
}
