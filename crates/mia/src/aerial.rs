//! Aerial perspective of `mia_physicalsky` (its `visibility_distance`): distant objects
//! fade into the haze of the sky.
//!
//! The manual: "Aerial Perspective is a term used by painters to convey how distant
//! objects are perceived as hazier"; a nonzero `visibility_distance` d₁₀ is the "10 %
//! distance", where 10 % of an object's original contrast is left. mira reads that as
//! Beer–Lambert extinction with in-scattering of the haze colour: an eye ray's colour c
//! at hit distance t becomes c·T + haze·(1 − T) with T = 0.1^(t / d₁₀) (90 % blended at
//! d₁₀, 99 % at 2 d₁₀), alpha likewise towards 1; rays that hit nothing see the sky as
//! it is.
//!
//! mira's choices where the manual stops: the haze colour is the sky's in the ray's
//! direction without the sun disk and glow, and rays at or below the horizon take the
//! horizon's colour in their azimuth (distant ground fades into the horizon, not into the
//! virtual ground below it); the manual says haze also strengthens the effect but not how,
//! so `visibility_distance` is used as given. mental ray runs it as a lens shader (eye
//! rays only) or a volume shader (every ray); mira does the lens shader, and as a volume
//! shader it does nothing (mira's classic engine runs no volume shaders).

use glam::Vec3A;

use ::sky::sky::PhysicalSky;
use shader::Color;

/// Up component (above the horizon's) at which the haze takes the horizon's colour.
const HORIZON_LIFT: f32 = 0.001;

/// The fraction of an object's light left after `dist` of air whose 10 % distance is
/// `visibility`: 0.1^(dist / visibility) (1 when `visibility` is not positive).
pub fn aerial_transmittance(dist: f32, visibility: f32) -> f32 {
    if visibility > 0.0 {
        (-std::f32::consts::LN_10 * dist.max(0.0) / visibility).exp()
    } else {
        1.0
    }
}

/// The haze colour of `sky` in world direction `dir` (unit), output units: the sky without
/// the sun disk and glow; at or below the horizon, the horizon's colour in that azimuth.
pub fn haze_color(sky: &PhysicalSky, dir: Vec3A) -> Vec3A {
    let plain = PhysicalSky { sun_disk_intensity: 0.0, sun_glow_intensity: 0.0, ..*sky };
    let up = if sky.y_is_up { Vec3A::Y } else { Vec3A::Z };
    // The sky frame lowers every up component by horizon_height / 10: that is where the
    // horizon lies in the world; just above it the sky is the horizon's.
    let horizon = (sky.horizon_height / 10.0 + HORIZON_LIFT).clamp(-0.999, 0.999);
    if dir.dot(up) > horizon {
        return plain.radiance(dir);
    }
    let flat = (dir - up * dir.dot(up)).normalize_or(up.any_orthonormal_vector());
    plain.radiance(flat * (1.0 - horizon * horizon).sqrt() + up * horizon)
}

/// Eye-ray colour `c` of a hit at distance `dist` along unit `dir`, seen through the air
/// of `sky` whose 10 % distance is `visibility` (see the module comment).
pub fn aerial_perspective(sky: &PhysicalSky, c: Color, dir: Vec3A, dist: f32, visibility: f32) -> Color {
    let t = aerial_transmittance(dist, visibility);
    if t >= 1.0 {
        return c;
    }
    let haze = haze_color(sky, dir);
    Color::new(
        c.x * t + haze.x * (1.0 - t),
        c.y * t + haze.y * (1.0 - t),
        c.z * t + haze.z * (1.0 - t),
        c.w * t + (1.0 - t),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ten_percent_left_at_the_visibility_distance() {
        assert!((aerial_transmittance(50.0, 50.0) - 0.1).abs() < 1e-6);
        assert!((aerial_transmittance(100.0, 50.0) - 0.01).abs() < 1e-6);
        assert_eq!(aerial_transmittance(0.0, 50.0), 1.0);
        assert_eq!(aerial_transmittance(10.0, 0.0), 1.0);
        // Halving: 0.1^(1/2) at half the distance.
        assert!((aerial_transmittance(25.0, 50.0) - 0.1f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn haze_is_the_sky_above_and_the_horizon_below() {
        let sky = PhysicalSky { sun_direction: Vec3A::new(0.3, 0.4, 0.5), ..PhysicalSky::default() };
        // Above the horizon: the sky itself (no sun disk in that direction).
        let d = Vec3A::new(-0.5, 0.2, 0.6).normalize();
        assert_eq!(haze_color(&sky, d), sky.radiance(d));
        // Below: the horizon's colour of that azimuth, not the ground's.
        let below = Vec3A::new(0.6, 0.8, -0.4).normalize();
        let horizon = Vec3A::new(0.6, 0.8, 0.001).normalize();
        let (h, want) = (haze_color(&sky, below), sky.radiance(horizon));
        assert!((h - want).abs().max_element() < 1e-3 * want.max_element(), "{h} {want}");
        assert!((h - sky.radiance(below)).abs().max_element() > 0.1 * want.max_element());
        // Towards the sun: the sky without the disk.
        let s = sky.sun_direction.normalize();
        assert!(haze_color(&sky, s).max_element() < 0.1 * sky.radiance(s).max_element());
    }

    #[test]
    fn blend_towards_the_haze() {
        let sky = PhysicalSky { sun_direction: Vec3A::new(0.3, 0.4, 0.5), ..PhysicalSky::default() };
        let d = Vec3A::new(0.0, 1.0, 0.2).normalize();
        let haze = haze_color(&sky, d);
        let c = Color::new(0.05, 0.1, 0.02, 0.5);
        let got = aerial_perspective(&sky, c, d, 30.0, 30.0);
        for k in 0..3 {
            let want = 0.1 * c[k] + 0.9 * haze[k];
            assert!((got[k] - want).abs() < 1e-5 * want.max(1.0), "{k}: {got} {want}");
        }
        assert!((got.w - 0.95).abs() < 1e-6);
        // No visibility distance: unchanged.
        assert_eq!(aerial_perspective(&sky, c, d, 30.0, 0.0), c);
    }
}
