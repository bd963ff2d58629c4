//! envFog's physical fog (Maya's `physicalFog` on): air and water vapour (fog) that absorb
//! and scatter light along a ray, thinning with height, lit by a sun (or, for the uniform
//! type, by the fog's lights).
//!
//! What Maya's envFog node reference states, and what mira takes from it (attribute
//! defaults are the reference's):
//! - `fogType`: 0 Uniform (the same density everywhere), 1 Atmospheric (thickest at the
//!   bottom, thinning exponentially upwards), 2 Sky (a layer with a top, its edge meeting
//!   the horizon over a curved planet), 3–6 the Water types: 3 Water alone, 4 Water/Fog,
//!   5 Water/Atmos, 6 Water/Sky the uniform, atmospheric and sky types above a body of
//!   water (below).
//! - Two media, fog (`fogDensity` 0.4, `fogColor` white, `fogOpacity` 0.5, `fogMinHeight`
//!   0, `fogMaxHeight` 1, `fogDecay` 0.2, `fogLightScatter` 1) and air (`airDensity` 0,
//!   `airColor` 0.6 0.8 1, `airOpacity` 0.37 0.47 0.9, `airMinHeight` 0, `airMaxHeight`
//!   50, `airDecay` 0.1, `airLightScatter` 1). The reference calls the colour the light a
//!   medium scatters and the opacity the light it absorbs; mira's reading, per channel and
//!   per scene unit: scattering coefficient σs = density · colour, absorption σa =
//!   density · opacity, extinction σt = σs + σa (so a medium's single-scattering albedo
//!   colour / (colour + opacity) is at most 1), each times the medium's height profile ρ.
//! - Height h above the planet: `planetRadius` R (1000) is the radius of a sphere whose
//!   top touches the world origin, its centre R below it along the up axis a (`fogAxis`),
//!   and h(p) = |p + R·a| − R (the plane height p·a near the origin; rays towards the
//!   horizon rise out of the layers, which is how the reference's curvature "pushes the
//!   horizon further away"). The reference names the axis choices (±X, ±Y, ±Z) but not
//!   their order: mira reads 0 +Y (Maya's up, the default), 1 −Y, 2 +X, 3 −X, 4 +Z, 5 −Z.
//! - Profiles (x = (h − min)/(max − min) with the medium's min and max heights; ρ = 1
//!   below min): Atmospheric ρ = 2^(−x) (the reference: max is the height at which the
//!   density is half that at the base; the decay is not used, as the half-life already
//!   sets the thinning), 0 above 24 half-lives; Sky ρ = 1 − x^k on [0, 1], 0 above the
//!   top, k = ln ½ / ln decay (mira's curve for the reference's words: decay ½ thins
//!   linearly, above ½ the layer stays even and drops near its top, below ½ it thins
//!   quickly near the base); Uniform ρ = 1 everywhere.
//! - Light: for Atmospheric and Sky a sun of `sunIntensity` (1) × `sunColor` (white) from
//!   the direction `sunElevation` (45°) above the horizon plane and `sunAzimuth` (0°)
//!   around the axis (degrees: the reference's attributes are plain numbers with
//!   default 45, not angles, which Maya would store in radians; azimuth 0 along the first axis after a in the cycle X → Y → Z, e.g.
//!   +Z for +Y up, turning towards the third; mira's choice). Light scattered towards the
//!   eye: σs · S · P(θ), P the Henyey–Greenstein phase normalised to 1 for isotropic
//!   scattering, g = 1 − lightScatter (1: uniform, as the reference says; lower values
//!   brighter towards the sun), θ between the ray and the sun direction. The sunlight is
//!   not dimmed by the fog on its way in (single scattering of the unattenuated sun). The
//!   Uniform type has no sun (the reference makes the sun attributes unavailable there):
//!   it scatters, isotropically, the light E its lights deliver at the segment's middle
//!   (`lightList`, every light when empty, as lightFog and Maya's envFogLight do).
//!
//! - Water (mira's reading of the attributes `waterDensity` 0, `waterColor` 0.6 0.8 1,
//!   `waterOpacity` 0.37 0.47 0.9, `waterLevel` 0, `waterDepth` 50, `waterLightDecay` 2,
//!   `waterLightScatter` 1; the reference names them without formulas): a medium like the
//!   others (σs = density · colour, σa = density · opacity, Henyey–Greenstein of g = 1 −
//!   `waterLightScatter`) filling everything below the height `waterLevel` (the ball of
//!   radius R + level around the planet's centre); the air and the fog lie above it only.
//!   The light the water scatters is the sun's (the lights' for Water/Fog, as its fog's)
//!   dimmed with the
//!   depth z below the surface as exp(−`waterLightDecay` · z / `waterDepth`) (e^−2 at the
//!   water depth by default). Water alone has no air or fog.
//!
//! Over a segment of length L the fog keeps T = exp(−∫σt) of what lies behind and adds
//! ∫ T(t)·Σ σs(t)·S·P dt; for one medium that is (1 − T) ⊙ colour / (colour + opacity) ⊙
//! S·P exactly. The integral runs over the part of the segment inside the layers (the ball
//! of radius R + top), in [`STEPS`] steps, each exact for the density at its middle.

use glam::Vec3A;
use shader::volume::VolumeTerms;

/// Steps of the integration along the part of a segment inside the layers.
pub const STEPS: usize = 128;

/// Half-lives above the base where an atmospheric layer is taken to end (2^−24 of the
/// base's density).
const ATMOSPHERIC_TOP: f32 = 24.0;

/// How the density varies with height ([`PhysicalFog`]'s `fogType`, water left out).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Profile {
    /// The same density everywhere.
    Uniform,
    /// 2^−x above the base: `max` is the half-life height.
    Atmospheric,
    /// 1 − x^k up to the top `max`.
    Sky,
}

/// One medium of the physical fog (the air or the water vapour): per channel and per
/// scene unit at full density.
#[derive(Clone, Copy, Debug)]
pub struct Medium {
    /// Scattering coefficient (density × colour).
    pub scatter: Vec3A,
    /// Absorption coefficient (density × opacity).
    pub absorb: Vec3A,
    /// Base height (world units above the planet).
    pub min: f32,
    /// Half-life height (Atmospheric) or top (Sky).
    pub max: f32,
    /// The decay attribute (Sky's profile).
    pub decay: f32,
    /// The light scatter attribute (1 uniform; g = 1 − it).
    pub light_scatter: f32,
}

impl Medium {
    /// The medium of `density`, `color`, `opacity` and the rest of its attributes.
    pub fn new(density: f32, color: Vec3A, opacity: Vec3A, min: f32, max: f32, decay: f32, light_scatter: f32) -> Self {
        let density = density.max(0.0);
        Medium {
            scatter: density * color.max(Vec3A::ZERO),
            absorb: density * opacity.max(Vec3A::ZERO),
            min,
            max,
            decay,
            light_scatter,
        }
    }

    /// Whether it scatters or absorbs anything.
    fn is_empty(&self) -> bool {
        self.scatter.max_element() <= 0.0 && self.absorb.max_element() <= 0.0
    }

    /// The height above which it has no density under `profile` (infinite: none).
    fn top(&self, profile: Profile) -> f32 {
        let span = self.max - self.min;
        match profile {
            Profile::Uniform => f32::INFINITY,
            _ if span <= 0.0 => self.min,
            Profile::Atmospheric => self.min + ATMOSPHERIC_TOP * span,
            Profile::Sky => self.max,
        }
    }

    /// The relative density ρ at height `h` under `profile` (see the module doc).
    pub fn density(&self, profile: Profile, h: f32) -> f32 {
        if profile == Profile::Uniform || h <= self.min {
            return 1.0;
        }
        let span = self.max - self.min;
        if span <= 0.0 {
            return 0.0;
        }
        let x = (h - self.min) / span;
        match profile {
            Profile::Uniform => 1.0,
            Profile::Atmospheric if x >= ATMOSPHERIC_TOP => 0.0,
            Profile::Atmospheric => (-x).exp2(),
            Profile::Sky if x >= 1.0 => 0.0,
            Profile::Sky => 1.0 - x.powf(sky_exponent(self.decay)),
        }
    }
}

/// Sky's profile exponent k = ln ½ / ln decay (decay kept inside (0, 1)).
pub fn sky_exponent(decay: f32) -> f32 {
    let d = decay.clamp(1e-4, 1.0 - 1e-4);
    0.5f32.ln() / d.ln()
}

/// The Henyey–Greenstein phase function normalised to 1 for isotropic scattering, with
/// g = 1 − `light_scatter` (clamped to [0, 0.99]), at the cosine `cos` between the ray's
/// direction and the direction towards the light.
pub fn phase(light_scatter: f32, cos: f32) -> f32 {
    let g = (1.0 - light_scatter).clamp(0.0, 0.99);
    let denom = 1.0 + g * g - 2.0 * g * cos.clamp(-1.0, 1.0);
    (1.0 - g * g) / (denom * denom.sqrt())
}

/// The unit up axis of `fogAxis` (see the module doc; out-of-range values give +Y).
pub fn axis(fog_axis: i32) -> Vec3A {
    match fog_axis {
        1 => Vec3A::NEG_Y,
        2 => Vec3A::X,
        3 => Vec3A::NEG_X,
        4 => Vec3A::Z,
        5 => Vec3A::NEG_Z,
        _ => Vec3A::Y,
    }
}

/// The unit direction towards the sun at `elevation_deg` above the plane normal to unit
/// `up` and `azimuth_deg` around it (see the module doc).
pub fn sun_direction(up: Vec3A, elevation_deg: f32, azimuth_deg: f32) -> Vec3A {
    // The next axis in the cycle X → Y → Z after the up axis, and the one after it.
    let a = up.abs();
    let (first, second) = if a.y > 0.5 {
        (Vec3A::Z, Vec3A::X)
    } else if a.x > 0.5 {
        (Vec3A::Y, Vec3A::Z)
    } else {
        (Vec3A::X, Vec3A::Y)
    };
    let (e, z) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    (e.cos() * (z.cos() * first + z.sin() * second) + e.sin() * up).normalize_or(up)
}

/// The body of water of physical fog's Water types (see the module doc).
#[derive(Clone, Copy, Debug)]
pub struct Water {
    /// The water as a medium (its profile is uniform below the level).
    pub medium: Medium,
    /// The height of the water's surface (`waterLevel`).
    pub level: f32,
    /// The depth scale of the light's decay (`waterDepth`).
    pub depth: f32,
    /// `waterLightDecay`.
    pub light_decay: f32,
}

impl Water {
    /// The water of `density`, `color`, `opacity`, `level`, `depth`, `light_decay` and
    /// `light_scatter`.
    pub fn new(
        density: f32,
        color: Vec3A,
        opacity: Vec3A,
        level: f32,
        depth: f32,
        light_decay: f32,
        light_scatter: f32,
    ) -> Self {
        Water {
            medium: Medium::new(density, color, opacity, level, level, 0.5, light_scatter),
            level,
            depth,
            light_decay,
        }
    }

    /// The share of the light from above that reaches depth `z` below the surface.
    pub fn light_at_depth(&self, z: f32) -> f32 {
        if self.depth <= 0.0 {
            return if z <= 0.0 { 1.0 } else { 0.0 };
        }
        (-self.light_decay.max(0.0) * z.max(0.0) / self.depth).exp()
    }
}

/// envFog's physical fog, its attributes read (see the module doc).
#[derive(Clone, Copy, Debug)]
pub struct PhysicalFog {
    /// The height profile of both media.
    pub profile: Profile,
    /// The water vapour and the air.
    pub media: [Medium; 2],
    /// The unit up axis.
    pub up: Vec3A,
    /// The planet's radius (scene units).
    pub planet_radius: f32,
    /// The unit direction towards the sun.
    pub sun_dir: Vec3A,
    /// The sun's light (intensity × colour; unused by the uniform type).
    pub sun: Vec3A,
    /// The body of water of the Water types (its air and fog lie above it).
    pub water: Option<Water>,
    /// Whether there is air and fog at all (not for the Water type alone).
    pub air: bool,
}

impl PhysicalFog {
    /// The height of `p` above the planet.
    pub fn height(&self, p: Vec3A) -> f32 {
        let r = self.planet_radius.max(1e-3);
        (p + r * self.up).length() - r
    }

    /// The part [t0, t1] of the ray from `org` along unit `dir` over `length` (infinite
    /// allowed) where some medium has density; `None` when there is none.
    fn interval(&self, org: Vec3A, dir: Vec3A, length: f32) -> Option<(f32, f32)> {
        let top =
            self.media.iter().filter(|m| !m.is_empty()).map(|m| m.top(self.profile)).fold(f32::NEG_INFINITY, f32::max);
        if top == f32::NEG_INFINITY {
            return None;
        }
        if top == f32::INFINITY {
            return Some((0.0, length));
        }
        // The ball of radius R + top around the planet's centre.
        let r = self.planet_radius.max(1e-3);
        let radius = r + top;
        if radius <= 0.0 {
            return None;
        }
        let oc = org + r * self.up;
        let b = oc.dot(dir);
        let c = oc.length_squared() - radius * radius;
        let disc = b * b - c;
        if disc <= 0.0 {
            return None;
        }
        let s = disc.sqrt();
        let (t0, t1) = ((-b - s).max(0.0), (-b + s).min(length));
        (t1 > t0).then_some((t0, t1))
    }

    /// The fog's terms over the segment from `org` along unit `dir` of `length` (infinite:
    /// a ray that left the scene), the water's included: the stretches above the water
    /// take the air and fog ([`PhysicalFog::air_terms`]), the one inside it the water's;
    /// `lit` is the light the uniform type scatters (see the module doc).
    pub fn terms(&self, org: Vec3A, dir: Vec3A, length: f32, lit: Vec3A) -> VolumeTerms {
        let Some(water) = self.water else { return self.air_terms(org, dir, length, lit) };
        let r = self.planet_radius.max(1e-3);
        let inside = ball_interval(org + r * self.up, dir, r + water.level, length);
        let above = |t0: f32, t1: f32| {
            if t1 > t0 && self.air {
                self.air_terms(org + dir * t0, dir, t1 - t0, lit)
            } else {
                VolumeTerms::NONE
            }
        };
        let Some((w0, w1)) = inside else { return above(0.0, length) };
        let lit_water = if self.profile == Profile::Uniform && self.air {
            lit
        } else {
            self.sun * phase(water.medium.light_scatter, dir.dot(self.sun_dir))
        };
        let mut acc = above(0.0, w0);
        let dt = (w1 - w0) / STEPS as f32;
        for i in 0..STEPS {
            let h = self.height(org + dir * (w0 + (i as f32 + 0.5) * dt));
            let shown = lit_water * water.light_at_depth(water.level - h);
            acc = step(&[water.medium], [1.0], [shown], dt, acc);
        }
        acc.after(above(w1, length))
    }

    /// The air and fog's terms over the segment from `org` along unit `dir` of `length`
    /// (see [`PhysicalFog::terms`]).
    fn air_terms(&self, org: Vec3A, dir: Vec3A, length: f32, lit: Vec3A) -> VolumeTerms {
        let Some((t0, t1)) = self.interval(org, dir, length) else { return VolumeTerms::NONE };
        // The light each medium scatters towards the ray's origin, per unit σs.
        let shown = self.media.map(|m| match self.profile {
            Profile::Uniform => lit,
            _ => self.sun * phase(m.light_scatter, dir.dot(self.sun_dir)),
        });
        if !t1.is_finite() || self.profile == Profile::Uniform {
            // Constant density: one step is exact (and saturates an infinite segment).
            return step(&self.media, [1.0, 1.0], shown, t1 - t0, VolumeTerms::NONE);
        }
        let dt = (t1 - t0) / STEPS as f32;
        let rho_at = |t: f32| {
            let h = self.height(org + dir * t);
            self.media.map(|m| m.density(self.profile, h))
        };
        let mut acc = VolumeTerms::NONE;
        let mut before = rho_at(t0);
        for i in 0..STEPS {
            let after = rho_at(t0 + (i + 1) as f32 * dt);
            let mean = [0, 1].map(|k| log_mean(before[k], after[k]));
            acc = step(&self.media, mean, shown, dt, acc);
            before = after;
        }
        acc
    }
}

/// The mean over a step of a density that is `a` at its start and `b` at its end, taken
/// as exponential in between (exact for the atmospheric profile): (a − b) / ln(a / b); the
/// arithmetic mean where either is 0 or they are nearly equal.
fn log_mean(a: f32, b: f32) -> f32 {
    if a <= 0.0 || b <= 0.0 || (a - b).abs() <= 1e-4 * a.max(b) {
        return 0.5 * (a + b);
    }
    (a - b) / (a / b).ln()
}

/// The part [t0, t1] of the ray from `oc` (relative to a ball's centre) along unit `dir`
/// over `length` (infinite allowed) inside the ball of `radius`; `None` when none is.
fn ball_interval(oc: Vec3A, dir: Vec3A, radius: f32, length: f32) -> Option<(f32, f32)> {
    if radius <= 0.0 {
        return None;
    }
    let b = oc.dot(dir);
    let c = oc.length_squared() - radius * radius;
    let disc = b * b - c;
    if disc <= 0.0 {
        return None;
    }
    let s = disc.sqrt();
    let (t0, t1) = ((-b - s).max(0.0), (-b + s).min(length));
    (t1 > t0).then_some((t0, t1))
}

/// `acc` (the terms from the origin to this step) followed by a step of length `dt` of
/// constant relative densities `rho` of `media`, each showing `shown` per unit of σs:
/// keep ← keep·exp(−σt·dt), add ← add + keep·σs/σt·(1 − exp(−σt·dt))·shown (σs·dt·shown
/// where nothing absorbs).
fn step<const N: usize>(
    media: &[Medium; N],
    rho: [f32; N],
    shown: [Vec3A; N],
    dt: f32,
    acc: VolumeTerms,
) -> VolumeTerms {
    let mut sigma_t = Vec3A::ZERO;
    let mut emitted = Vec3A::ZERO;
    for k in 0..N {
        sigma_t += rho[k] * (media[k].scatter + media[k].absorb);
        emitted += rho[k] * media[k].scatter * shown[k];
    }
    let mut keep = Vec3A::ONE;
    let mut add = Vec3A::ZERO;
    for c in 0..3 {
        let (st, e) = (sigma_t[c], emitted[c]);
        if st > 0.0 {
            let through = if dt.is_finite() { (-st * dt).exp() } else { 0.0 };
            keep[c] = through;
            add[c] = e / st * (1.0 - through);
        } else if e > 0.0 {
            add[c] = e * dt;
        }
    }
    VolumeTerms { keep: acc.keep * keep, add: acc.add + acc.keep * add }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fog(profile: Profile, fog: Medium) -> PhysicalFog {
        let none = Medium::new(0.0, Vec3A::ONE, Vec3A::ONE, 0.0, 1.0, 0.5, 1.0);
        PhysicalFog {
            profile,
            media: [fog, none],
            up: Vec3A::Y,
            planet_radius: 1000.0,
            sun_dir: Vec3A::Y,
            sun: Vec3A::splat(2.0),
            water: None,
            air: true,
        }
    }

    /// A vertical ray from height 1 down 3 units (to −2) into water below level 0, with no
    /// air or fog: it crosses 2 units of water, keeping exp(−2σt), and adds the sun's light
    /// (2, straight overhead, the ray going down; uniform scattering) dimmed with depth as
    /// exp(−k z / D): ∫₀² e^(−σt z) σs 2 e^(−k z/D) dz = 2σs (1 − e^(−2(σt + k/D))) / (σt +
    /// k/D) (1e-4 relative). Above the water the segment is untouched.
    #[test]
    fn water_keeps_and_adds_the_light_dimmed_with_depth() {
        let none = Medium::new(0.0, Vec3A::ONE, Vec3A::ONE, 0.0, 1.0, 0.5, 1.0);
        let water = Water::new(0.2, Vec3A::new(1.0, 0.5, 0.25), Vec3A::splat(0.5), 0.0, 4.0, 2.0, 1.0);
        let f = PhysicalFog {
            profile: Profile::Atmospheric,
            media: [none, none],
            up: Vec3A::Y,
            planet_radius: 1000.0,
            sun_dir: Vec3A::Y,
            sun: Vec3A::splat(2.0),
            water: Some(water),
            air: false,
        };
        let t = f.terms(Vec3A::new(0.0, 1.0, 0.0), Vec3A::NEG_Y, 3.0, Vec3A::ZERO);
        let k = 2.0 / 4.0;
        for (c, colour) in [1.0f32, 0.5, 0.25].into_iter().enumerate() {
            let (ss, st) = (0.2 * colour, 0.2 * (colour + 0.5));
            let keep = (-2.0 * st).exp();
            let add = 2.0 * ss * (1.0 - (-2.0 * (st + k)).exp()) / (st + k);
            assert!((t.keep[c] / keep - 1.0).abs() < 1e-4, "{c}: {t:?} vs {keep}");
            assert!((t.add[c] / add - 1.0).abs() < 1e-4, "{c}: {t:?} vs {add}");
        }
        let above = f.terms(Vec3A::new(0.0, 5.0, 0.0), Vec3A::NEG_Y, 3.0, Vec3A::ZERO);
        assert_eq!(above, VolumeTerms::NONE);
        assert!((water.light_at_depth(4.0) - (-2.0f32).exp()).abs() < 1e-7);
    }

    /// Uniform fog over L: T = exp(−σt·L), add = (1 − T)·σs/σt·E; infinite: saturated.
    #[test]
    fn uniform_fog_is_beer_lambert_with_scattered_light() {
        let m = Medium::new(0.4, Vec3A::new(1.0, 0.5, 0.2), Vec3A::splat(0.5), 0.0, 1.0, 0.2, 1.0);
        let f = fog(Profile::Uniform, m);
        let lit = Vec3A::new(3.0, 2.0, 1.0);
        let t = f.terms(Vec3A::ZERO, Vec3A::X, 2.5, lit);
        for c in 0..3 {
            let st = m.scatter[c] + m.absorb[c];
            let keep = (-st * 2.5).exp();
            assert!((t.keep[c] - keep).abs() < 1e-6, "{t:?}");
            assert!((t.add[c] - (1.0 - keep) * m.scatter[c] / st * lit[c]).abs() < 1e-5, "{t:?}");
        }
        let t = f.terms(Vec3A::ZERO, Vec3A::X, f32::INFINITY, lit);
        assert_eq!(t.keep, Vec3A::ZERO);
        assert!((t.add.x - 0.4 / 0.6 * 3.0).abs() < 1e-5, "{t:?}");
    }

    /// A vertical ray through atmospheric fog: optical depth σt·H/ln 2·(1 − 2^(−L/H)) from
    /// the base, within 1e-4 relative.
    #[test]
    fn atmospheric_fog_thins_by_half_lives() {
        let m = Medium::new(0.5, Vec3A::ONE, Vec3A::splat(0.5), 0.0, 2.0, 0.2, 1.0);
        let f = fog(Profile::Atmospheric, m);
        for length in [1.0f32, 4.0, 30.0] {
            let t = f.terms(Vec3A::ZERO, Vec3A::Y, length, Vec3A::ZERO);
            // σt = 0.5·(1 + 0.5), σs = 0.5.
            let depth = 0.75 * 2.0 / std::f32::consts::LN_2 * (1.0 - (-length / 2.0).exp2());
            let keep = (-depth).exp();
            assert!((t.keep.x / keep - 1.0).abs() < 1e-4, "{length}: {} vs {keep}", t.keep.x);
            // One medium: add = (1 − T)·σs/σt·S·P, the sun straight up along the ray.
            let want = (1.0 - keep) * (0.5 / 0.75) * 2.0 * phase(1.0, 1.0);
            assert!((t.add.x - want).abs() < 1e-4, "{length}: {} vs {want}", t.add.x);
        }
    }

    /// Sky's profile is linear at decay ½ and ends at its top; above the top nothing.
    #[test]
    fn sky_layers_end_at_their_top() {
        let m = Medium::new(1.0, Vec3A::ONE, Vec3A::ZERO, 0.0, 3.0, 0.5, 1.0);
        assert!((sky_exponent(0.5) - 1.0).abs() < 1e-6);
        assert!((m.density(Profile::Sky, 1.5) - 0.5).abs() < 1e-6);
        assert_eq!(m.density(Profile::Sky, 3.5), 0.0);
        assert!(sky_exponent(0.8) > 1.0 && sky_exponent(0.2) < 1.0);
        let f = fog(Profile::Sky, m);
        let t = f.terms(Vec3A::ZERO, Vec3A::Y, 100.0, Vec3A::ZERO);
        assert!((t.keep.x - (-1.5f32).exp()).abs() < 1e-4, "{t:?}");
        let above = f.terms(Vec3A::new(0.0, 5.0, 0.0), Vec3A::Y, 100.0, Vec3A::ZERO);
        assert_eq!(above, VolumeTerms::NONE);
    }

    /// The phase function is 1 when scattering is uniform, brighter towards the sun below
    /// 1, and averages to 1 over the sphere (midpoint rule in cos θ, 1e-3).
    #[test]
    fn phase_is_normalised_to_isotropic() {
        assert_eq!(phase(1.0, 0.3), 1.0);
        assert!(phase(0.5, 1.0) > 1.0 && phase(0.5, -1.0) < 1.0);
        let n = 20_000;
        let mean: f32 = (0..n).map(|i| phase(0.4, -1.0 + 2.0 * (i as f32 + 0.5) / n as f32)).sum::<f32>() / n as f32;
        assert!((mean - 1.0).abs() < 1e-3, "{mean}");
    }

    /// The sun stands at its elevation above the horizon plane and turns around the axis.
    #[test]
    fn sun_direction_follows_elevation_and_azimuth() {
        let s = sun_direction(Vec3A::Y, 30.0, 0.0);
        assert!((s.y - 0.5).abs() < 1e-6 && (s.z - 0.75f32.sqrt()).abs() < 1e-6, "{s:?}");
        let s = sun_direction(Vec3A::Y, 0.0, 90.0);
        assert!((s - Vec3A::X).length() < 1e-6, "{s:?}");
        assert!((sun_direction(Vec3A::Z, 90.0, 10.0) - Vec3A::Z).length() < 1e-6);
    }

    /// Heights over the planet: the plane height near the origin, rising towards the
    /// horizon (√(R² + d²) − R at distance d along the ground).
    #[test]
    fn heights_curve_with_the_planet() {
        let f = fog(Profile::Sky, Medium::new(1.0, Vec3A::ONE, Vec3A::ONE, 0.0, 1.0, 0.5, 1.0));
        assert!((f.height(Vec3A::new(0.0, 2.0, 0.0)) - 2.0).abs() < 1e-4);
        let h = f.height(Vec3A::new(100.0, 0.0, 0.0));
        assert!((h - ((1000.0f32 * 1000.0 + 100.0 * 100.0).sqrt() - 1000.0)).abs() < 1e-3, "{h}");
    }
}
