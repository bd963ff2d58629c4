//! Maya's highlight models as functions of the unit shading normal `n`, the unit
//! direction `v` towards the viewer and the unit direction `l` towards the light (all in
//! one space). Each returns the factor that multiplies `specularColor ⊙ light`; there is
//! no 1/π and no N·L factor beyond the formula's own (Maya's convention). The formulas
//! live in `bsdf::maya_highlight`, where the path engine's BSDF evaluates the same code.

use glam::Vec3A;

pub use bsdf::maya_highlight::{anisotropic, blinn, phong, phong_e, schlick};

/// The Ward-style slope widths (α_x, α_y) of Maya's anisotropic highlight: α = `roughness`
/// / √spread in each groove direction, so that a larger `spreadX`/`spreadY` (Maya: the
/// surface varies more smoothly that way) shrinks the highlight along it. mira's reading:
/// Maya documents the direction of the effect, not the formula.
pub fn anisotropic_widths(roughness: f32, spread_x: f32, spread_y: f32) -> (f32, f32) {
    let r = roughness.clamp(0.01, 1.0);
    (r / spread_x.max(0.1).sqrt(), r / spread_y.max(0.1).sqrt())
}

/// The groove direction of the anisotropic material: the surface's dP/du made
/// perpendicular to `n` and turned by `angle` (radians, counter-clockwise about `n`); any
/// tangent when dP/du is unknown or along `n`.
pub fn groove_direction(n: Vec3A, dpdu: Vec3A, angle: f32) -> Vec3A {
    let u = (dpdu - n * n.dot(dpdu)).try_normalize().unwrap_or_else(|| n.any_orthonormal_vector());
    let w = n.cross(u);
    u * angle.cos() + w * angle.sin()
}

/// Which highlight a Maya material adds, with its parameters (see `crate::material`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Highlight {
    /// lambert: none.
    None,
    /// blinn: [`blinn`] of `eccentricity` and `specularRollOff`; `reflectionRolloff`
    /// weights its reflections by Schlick's Fresnel of the roll-off.
    Blinn {
        /// `eccentricity`.
        eccentricity: f32,
        /// `specularRollOff`.
        rolloff: f32,
        /// `reflectionRolloff`.
        reflection_rolloff: bool,
    },
    /// phong: [`phong`] of `cosinePower`.
    Phong {
        /// `cosinePower`.
        power: f32,
    },
    /// phongE: [`phong_e`] of `roughness` and `highlightSize`, tinted by `whiteness`.
    PhongE {
        /// `roughness`.
        roughness: f32,
        /// `highlightSize`.
        size: f32,
        /// `whiteness` (linear RGB).
        whiteness: Vec3A,
    },
    /// anisotropic: [`anisotropic`] with grooves along the unit world direction `grooves`.
    Anisotropic {
        /// The grooves' direction (unit, world, in the surface).
        grooves: Vec3A,
        /// The highlight's width along the grooves.
        alpha_x: f32,
        /// The highlight's width across them.
        alpha_y: f32,
        /// `fresnelRefractiveIndex`.
        ior: f32,
    },
}

impl Highlight {
    /// The highlight (per unit of light and of `specularColor`) for the unit normal `n`,
    /// the unit direction towards the viewer `v` and towards the light `l` (world).
    pub fn value(self, n: Vec3A, v: Vec3A, l: Vec3A) -> Vec3A {
        match self {
            Highlight::None => Vec3A::ZERO,
            Highlight::Blinn { eccentricity, rolloff, .. } => Vec3A::splat(blinn(n, v, l, eccentricity, rolloff)),
            Highlight::Phong { power } => Vec3A::splat(phong(n, v, l, power)),
            Highlight::PhongE { roughness, size, whiteness } => whiteness * phong_e(n, v, l, roughness, size),
            Highlight::Anisotropic { grooves, alpha_x, alpha_y, ior } => {
                Vec3A::splat(anisotropic(n, v, l, grooves, alpha_x, alpha_y, ior))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blinn_peak_is_the_rolloff_and_falls_off_with_eccentricity() {
        let n = Vec3A::Z;
        assert!((blinn(n, n, n, 0.3, 0.7) - 0.7).abs() < 1e-6);
        // Off the peak: light 20° from the normal, viewer on the normal; H is 10° off.
        let t = 20f32.to_radians();
        let l = Vec3A::new(t.sin(), 0.0, t.cos());
        let h = (n + l).normalize();
        let (nh, vh) = (h.z, h.z);
        let e2 = 0.09f32;
        let d = (e2 / ((e2 - 1.0) * nh * nh + 1.0)).powi(2);
        let g = 1f32.min(2.0 * nh / vh).min(2.0 * nh * l.z / vh);
        let f = 0.7 + 0.3 * (1.0 - vh).powi(5);
        assert!((blinn(n, n, l, 0.3, 0.7) - d * g * f).abs() < 1e-6);
        // A smaller eccentricity gives a tighter highlight.
        assert!(blinn(n, n, l, 0.1, 0.7) < blinn(n, n, l, 0.3, 0.7));
    }

    #[test]
    fn phong_is_a_cosine_power_of_the_mirror_direction() {
        let n = Vec3A::Z;
        let t = 10f32.to_radians();
        let v = Vec3A::new(-t.sin(), 0.0, t.cos());
        let l = Vec3A::new(t.sin(), 0.0, t.cos());
        assert!((phong(n, v, l, 20.0) - 1.0).abs() < 1e-5);
        // Viewer on the normal, light at 10°: R·L = cos 10°.
        assert!((phong(n, n, l, 20.0) - t.cos().powf(20.0)).abs() < 1e-5);
        assert_eq!(phong(n, n, -l, 20.0), 0.0);
    }

    #[test]
    fn phong_e_peak_is_the_highlight_size() {
        let n = Vec3A::Z;
        assert!((phong_e(n, n, n, 0.4, 0.6) - 0.6).abs() < 1e-6);
        // Light 20° off the viewer on the normal: H is 10° off, (cos 10°)^(1/0.16).
        let t = 20f32.to_radians();
        let l = Vec3A::new(t.sin(), 0.0, t.cos());
        let want = 0.6 * 10f32.to_radians().cos().powf(1.0 / 0.16);
        assert!((phong_e(n, n, l, 0.4, 0.6) - want).abs() < 1e-5);
        // Rougher: a wider highlight, larger off the peak.
        assert!(phong_e(n, n, l, 0.8, 0.6) > phong_e(n, n, l, 0.4, 0.6));
    }
    #[test]
    fn anisotropic_peak_is_one_and_the_larger_spread_gives_the_narrower_highlight() {
        let n = Vec3A::Z;
        let x = groove_direction(n, Vec3A::X, 0.0);
        let (ax, ay) = anisotropic_widths(0.7, 13.0, 3.0);
        assert!((ax - 0.7 / 13f32.sqrt()).abs() < 1e-6 && (ay - 0.7 / 3f32.sqrt()).abs() < 1e-6);
        assert!((anisotropic(n, n, n, x, ax, ay, 6.0) - 1.0).abs() < 1e-5);
        // Light 20° off the normal, viewer on it: H is 10° off, tilted along x or along y.
        let t = 20f32.to_radians();
        let along_x = Vec3A::new(t.sin(), 0.0, t.cos());
        let along_y = Vec3A::new(0.0, t.sin(), t.cos());
        let (hx, hy) = (anisotropic(n, n, along_x, x, ax, ay, 6.0), anisotropic(n, n, along_y, x, ax, ay, 6.0));
        assert!(hx < hy, "spreadX 13 > spreadY 3: narrower along x ({hx} vs {hy})");
        // Against the formula: tan²(10°)/α_x² in the exponent, times the Fresnel ratio.
        let h = (n + along_x).normalize();
        let f = bsdf::dielectric::fresnel(h.z, 6.0) / bsdf::dielectric::fresnel(1.0, 6.0);
        let want = (-(10f32.to_radians().tan() / ax).powi(2)).exp() * f;
        assert!((hx - want).abs() < 1e-5, "{hx} vs {want}");
        // Turning the grooves by 90° swaps the two directions.
        let turned = groove_direction(n, Vec3A::X, std::f32::consts::FRAC_PI_2);
        assert!((turned - Vec3A::Y).length() < 1e-6);
        assert!((anisotropic(n, n, along_y, turned, ax, ay, 6.0) - hx).abs() < 1e-6);
    }
}
