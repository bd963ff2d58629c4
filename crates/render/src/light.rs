//! Light sources in world space: their shapes, what they emit and how to sample them.
//!
//! Physical lights (MDL light materials) emit radiance from their surface (one-sided for
//! rectangles and discs, facing their normal); point lights have an intensity falling off
//! with 1/r². mental ray's base light shaders are not physical: a lit point receives the
//! shader's colour, with no distance falloff unless `atten` asks for a linear one, and area
//! lights average that colour over points of their surface; they are sampled like point
//! lights at those points. Photometric lights (MDL `light_ies`, `mib_light_photometric`,
//! `mia_photometric_light`) are point lights whose intensity follows a [`Distribution`]
//! (an IES profile or a cosine power) over directions in the light's local frame.

use std::f32::consts::PI;
use std::sync::Arc;

use bsdf::{Frame, Rgb};
use glam::{Mat3A, Vec2, Vec3A};
use material::emission::maya::SoftShadow;
use material::emission::{Distribution, Emission, Power};
use scene::{Library, Light, LightKind};
pub use shader::light::Shape;

use crate::ray::Ray;

pub mod rect_solid_angle;
pub use rect_solid_angle::RectFrame;

/// A distribution over directions and the frame it is given in.
#[derive(Clone, Debug, PartialEq)]
pub struct LocalDistribution {
    /// The distribution (light-local directions).
    pub distribution: Distribution,
    /// World → light-local rotation of directions.
    pub to_local: Mat3A,
}

impl LocalDistribution {
    /// The factor towards world direction `out` (from the light).
    pub fn factor(&self, out: Vec3A) -> f32 {
        self.distribution.factor(self.to_local * out)
    }
}

/// What a light gives a lit point, resolved for its shape.
#[derive(Clone, Debug, PartialEq)]
pub enum Output {
    /// Surface radiance (area lights); `two_sided` surfaces emit on both sides.
    Radiance {
        /// Radiance.
        l: Rgb,
        /// Emits on both sides.
        two_sided: bool,
    },
    /// Radiant intensity (point and spot lights), falling off with 1/r².
    Intensity(Rgb),
    /// Irradiance perpendicular to the beam (directional lights).
    Irradiance(Rgb),
    /// mental ray base light shaders: the colour itself, optionally with a linear falloff.
    Constant {
        /// Colour received.
        color: Rgb,
        /// Linear falloff `(start, stop)`.
        falloff: Option<(f32, f32)>,
    },
    /// Photometric lights: `color` × the distribution towards the point × d^−exponent
    /// (only between `range`'s start and stop when given; none for exponent 0). With
    /// exponent 2 and no range, `color` × distribution is a radiant intensity.
    Photometric {
        /// Colour (intensity) along the distribution's unit direction.
        color: Rgb,
        /// Distance falloff exponent.
        exponent: f32,
        /// Where the falloff applies.
        range: Option<(f32, f32)>,
        /// How it varies with direction (`None`: uniform).
        distribution: Option<Arc<LocalDistribution>>,
    },
    /// Maya volume lights: the colour a lit point receives from the light's origin
    /// depends on where the point lies in the light's volume (see
    /// [`material::emission::maya::VolumeEmission`]); nothing outside it.
    Volume(Box<material::emission::maya::VolumeEmission>),
    /// `mia_physicalsun`: a distant light of this irradiance (on a plane facing it) from
    /// directions spread uniformly over the cone of half-angle `angular_radius` (radians)
    /// around the direction opposite the light's; soft shadows, as the classic shader's
    /// shadow rays over the sun's disk. Not seen by rays (the sky shows the disk).
    Sun {
        /// Irradiance on a plane facing the sun.
        irradiance: Rgb,
        /// Half-angle of the cone, radians (0: one direction).
        angular_radius: f32,
    },
    /// `mia_portal_light`: a window bringing the environment in. Its surface radiance
    /// along a direction is `scale` × the environment's radiance along it (the integrator
    /// multiplies the two), towards the shape's normal side (the other with `reverse`).
    /// Sampled by area like [`Output::Radiance`].
    Portal {
        /// Tint × multiplier.
        scale: Rgb,
        /// Emits to the side opposite the shape's normal.
        reverse: bool,
    },
}

/// A light in the render world.
#[derive(Clone, Debug)]
pub struct LightSource {
    /// The light instance's name.
    pub name: String,
    /// Point, spot or directional.
    pub kind: LightKind,
    /// Position (centre of the shape), world space.
    pub position: Vec3A,
    /// Direction light travels (spot, directional), unit.
    pub direction: Vec3A,
    /// The shape.
    pub shape: Shape,
    /// A rectangle's frame for sampling it in solid angle, worked out from `shape` when the
    /// light is built: [`RectFrame::of`] of it (a light whose `shape` changes needs it anew;
    /// `None`: a rectangle sampled by area, or another shape).
    pub rect_frame: Option<RectFrame>,
    /// What it emits.
    pub output: Output,
    /// Cosine of the spot's outer half-angle.
    pub spread: f32,
    /// Cosine of the spot's inner (full-intensity) half-angle (mental ray spots).
    pub cone: Option<f32>,
    /// MDL spot exponent.
    pub spot_exponent: Option<f32>,
    /// A Maya spot's cone: its spot factor is the classic light's
    /// ([`::maya::light::SpotCone::factor`]), whatever `spread`, `cone` and `spot_exponent`.
    pub maya_spot: Option<::maya::light::SpotCone>,
    /// Seen by rays.
    pub visible: bool,
    /// Casts shadows.
    pub shadow: bool,
    /// The fraction of the light a fully shadowed point still receives (Maya's
    /// `shadowColor`; black for every other light): received = light ⊙ (f + (1 − f) ⊙
    /// this), f the fraction let through.
    pub shadow_color: Rgb,
    /// Maya's point, spot and directional lights with `lightRadius` or `lightAngle`:
    /// where their shadow rays spread ([`LightSource::shadow_ray_at`]; what arrives is
    /// still the light's from its point or direction, as in the classic engine); `None`:
    /// hard shadows.
    pub soft_shadow: Option<SoftShadow>,
    /// World → world displacement of the light at shutter times spread evenly over the
    /// shutter (see [`crate::motion`]) when its instance moves while the shutter is open
    /// (the light is taken to move rigidly); empty: it stays where it is. (An object
    /// light's triangles that change shape over the shutter carry their own keys in
    /// their [`Shape::Mesh`].)
    pub motion: Vec<glam::Affine3A>,
    /// Which lobes of the materials it lights (Maya's `emitDiffuse`, `emitSpecular`;
    /// both for every other light).
    pub lobes: material::emission::maya::LightLobes,
}

/// A sampled light contribution towards a shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit direction from the shading point to the light.
    pub wi: Vec3A,
    /// Distance to the sampled point (`f32::INFINITY` for directional lights).
    pub dist: f32,
    /// Radiance arriving (for `delta` samples, the contribution with the pdf divided out).
    pub radiance: Rgb,
    /// Solid-angle density of the sample (1 for delta samples).
    pub pdf: f32,
    /// Whether the sample cannot be found by a BSDF ray (points, directions, non-physical
    /// lights).
    pub delta: bool,
}

impl LightSource {
    /// Translates a scene light (its emission read by `shade`); `object` area lights need
    /// the scene's geometry: [`LightSource::in_scene`].
    pub fn from_scene(light: &Light, lib: &Library) -> Result<LightSource, String> {
        let shape = match (&light.area, light.kind) {
            (Some(a), LightKind::Point | LightKind::Spot) => Shape::from_area(&a.shape).ok_or_else(|| {
                format!(
                    "light '{}': object area lights need the scene's geometry; user area lights have no shape",
                    light.instance
                )
            })?,
            _ => Shape::Point,
        };
        Self::with_shape(light, lib, shape, &|_| None)
    }

    /// Translates a light of `scene`, `object` area lights included (their instance's
    /// triangles, world space). User area lights have no shape the path engine could
    /// sample (their light shader places the points; the classic engine runs it): an error.
    pub fn in_scene(light: &Light, scene: &scene::Scene) -> Result<LightSource, String> {
        Self::in_scene_shaded(light, scene, None)
    }

    /// [`LightSource::in_scene`] with the scene's compiled shading, which holds the light
    /// profiles photometric lights use (without it they shine uniformly).
    pub fn in_scene_shaded(
        light: &Light,
        scene: &scene::Scene,
        shading: Option<&shader::Shading>,
    ) -> Result<LightSource, String> {
        let shape = match (&light.area, light.kind) {
            (Some(a), LightKind::Point | LightKind::Spot) => Shape::of_area(&a.shape, scene)
                .map_err(|e| format!("light '{}': {e}; the path engine leaves it out", light.instance))?,
            _ => Shape::Point,
        };
        Self::in_scene_with_shape(light, scene, shading, shape)
    }

    /// [`LightSource::in_scene_shaded`] with the light's shape given (world space): an
    /// object light whose triangles the displacement stage moved.
    pub fn in_scene_with_shape(
        light: &Light,
        scene: &scene::Scene,
        shading: Option<&shader::Shading>,
        shape: Shape,
    ) -> Result<LightSource, String> {
        Self::with_shape(light, &scene.library, shape, &|name| shading.and_then(|s| s.lightprofile(name)))
    }

    /// Translates a scene light given its shape, world space, and its light profiles.
    fn with_shape(
        light: &Light,
        lib: &Library,
        shape: Shape,
        profiles: &dyn Fn(&str) -> Option<Arc<shader::light::ies::Profile>>,
    ) -> Result<LightSource, String> {
        let emission: Emission = material::emission::emission_with(light, lib, profiles)?;
        let to_local = shader::light::profiles::to_local(light.light_to_world);
        let distribution =
            emission.distribution.clone().map(|distribution| Arc::new(LocalDistribution { distribution, to_local }));
        let a = shape.area();
        let is_area = !matches!(shape, Shape::Point);
        let output = match (emission.power, light.kind, is_area) {
            (Power::Portal { scale, reverse }, _, true) => Output::Portal { scale, reverse },
            (Power::Portal { .. }, _, false) => {
                return Err(format!("light '{}': mia_portal_light needs an area light shape", light.instance))
            }
            (Power::Constant { color, falloff }, _, _) => Output::Constant { color, falloff },
            (Power::Volume(volume), _, _) => Output::Volume(volume),
            (Power::Sun { irradiance, angular_radius }, _, _) => Output::Sun { irradiance, angular_radius },
            (p, LightKind::Directional, _) => Output::Irradiance(match p {
                Power::Exitance(c) | Power::Radiance(c) | Power::Flux(c) | Power::Intensity(c) => c,
                Power::Constant { color, .. } | Power::Photometric { color, .. } => color,
                Power::Portal { scale, .. } => scale,
                Power::Volume(volume) => volume.color,
                Power::Sun { irradiance, .. } => irradiance,
            }),
            (Power::Photometric { color, exponent, range }, _, _) => {
                Output::Photometric { color, exponent, range, distribution }
            }
            (Power::Exitance(e), _, true) => Output::Radiance { l: e / PI, two_sided: false },
            (Power::Radiance(l), _, true) => Output::Radiance { l, two_sided: false },
            (Power::Flux(f), _, true) => Output::Radiance { l: f / (PI * a), two_sided: false },
            (Power::Intensity(i), _, true) => Output::Radiance { l: i / a, two_sided: false },
            (Power::Flux(f), _, false) => Output::Intensity(f / (4.0 * PI)),
            (Power::Exitance(c) | Power::Radiance(c) | Power::Intensity(c), _, false) => Output::Intensity(c),
        };
        let radiant = matches!(output, Output::Radiance { .. });
        // Portals are always found by scattered rays (the integrator's rule that the
        // environment is not counted twice needs it); camera rays pass through them.
        let portal = matches!(output, Output::Portal { .. });
        // Maya's lights: raytraced shadows only with `useRayTraceShadows`, tinted.
        let (casts, shadow_color) = material::emission::maya::shadowing(light, lib).unwrap_or((true, Rgb::ZERO));
        Ok(LightSource {
            name: light.instance.clone(),
            kind: light.kind,
            position: light.position.as_vec3a(),
            direction: light.direction.as_vec3a(),
            rect_frame: RectFrame::of(&shape),
            shape,
            output,
            spread: light.spread as f32,
            cone: emission.cone,
            spot_exponent: emission.spot_exponent,
            maya_spot: emission.maya_spot,
            visible: (light.visible && radiant || portal) && is_area,
            shadow: light.shadow && casts,
            shadow_color,
            soft_shadow: material::emission::maya::soft_shadow(light, lib).filter(|_| !is_area),
            motion: Vec::new(),
            lobes: material::emission::maya::light_lobes(light, lib).unwrap_or_default(),
        })
    }

    /// Whether it is a `mia_portal_light` window.
    pub fn is_portal(&self) -> bool {
        matches!(self.output, Output::Portal { .. })
    }

    /// Spot attenuation of light leaving in unit direction `out`.
    fn spot(&self, out: Vec3A) -> f32 {
        if self.kind != LightKind::Spot {
            return 1.0;
        }
        let c = out.dot(self.direction);
        if let Some(maya) = self.maya_spot {
            // Maya's spot: the classic light's factor of the angle from the axis.
            return maya.factor(c.clamp(-1.0, 1.0).acos());
        }
        let power = self.spot_exponent.map_or(1.0, |e| c.max(0.0).powf(e));
        if self.spot_exponent.is_some() && self.cone.is_none() {
            // MDL's spot: the cosine power alone.
            return power;
        }
        if c < self.spread {
            return 0.0;
        }
        // mental ray's spots: the cone, its edge fading linearly in the cosine.
        power
            * match self.cone {
                Some(inner) if inner > self.spread && c < inner => (c - self.spread) / (inner - self.spread),
                _ => 1.0,
            }
    }

    /// A point on the shape (uniform by area) and its normal.
    fn point_on(&self, u: Vec2) -> (Vec3A, Vec3A) {
        self.shape.point_on(self.position, u)
    }

    /// Samples the light as seen from `p`.
    pub fn sample(&self, p: Vec3A, u: Vec2) -> Option<LightSample> {
        match &self.output {
            Output::Photometric { color, exponent, range, distribution } => {
                let (q, _) = self.point_on(u);
                let d = q - p;
                let dist = d.length();
                if dist <= 0.0 || !dist.is_finite() {
                    return None;
                }
                let wi = d / dist;
                let mut f = distribution.as_ref().map_or(1.0, |dist| dist.factor(-wi));
                if self.cone.is_some() {
                    // A spot with a cone (Maya's spots with a decay): its cone too.
                    f *= self.spot(-wi);
                }
                let in_range = range.is_none_or(|(start, stop)| dist > start && dist < stop);
                if *exponent > 0.0 && in_range {
                    f *= dist.powf(-exponent);
                }
                (f > 0.0).then_some(LightSample { wi, dist, radiance: *color * f, pdf: 1.0, delta: true })
            }
            Output::Irradiance(e) => {
                Some(LightSample { wi: -self.direction, dist: f32::INFINITY, radiance: *e, pdf: 1.0, delta: true })
            }
            Output::Sun { irradiance, angular_radius } => {
                // One direction in the cone, uniform in solid angle: the cone's irradiance
                // is the given one, shadowed by the share of the cone that is blocked (the
                // cosine varies by less than 1e-4 across the sun's cone).
                let to_sun = -self.direction;
                let wi = if *angular_radius > 0.0 {
                    mia::sun::cone_direction(to_sun, *angular_radius, u.x, u.y)
                } else {
                    to_sun
                };
                Some(LightSample { wi, dist: f32::INFINITY, radiance: *irradiance, pdf: 1.0, delta: true })
            }
            Output::Intensity(i) => {
                let d = self.position - p;
                let dist2 = d.length_squared();
                let dist = dist2.sqrt();
                let wi = d / dist;
                let radiance = *i * self.spot(-wi) / dist2;
                (dist > 0.0).then_some(LightSample { wi, dist, radiance, pdf: 1.0, delta: true })
            }
            Output::Constant { color, falloff } => {
                let (q, _) = self.point_on(u);
                let (wi, dist) = if self.kind == LightKind::Directional {
                    (-self.direction, f32::INFINITY)
                } else {
                    let d = q - p;
                    let dist = d.length();
                    (d / dist, dist)
                };
                let atten = match *falloff {
                    Some((start, stop)) if stop > start && self.kind != LightKind::Directional => {
                        ((stop - dist) / (stop - start)).clamp(0.0, 1.0)
                    }
                    _ => 1.0,
                };
                let radiance = *color * atten * self.spot(-wi);
                (dist > 0.0).then_some(LightSample { wi, dist, radiance, pdf: 1.0, delta: true })
            }
            Output::Volume(volume) => {
                // From the centre, or a cylinder's or cone's axis.
                let d = volume.source(self.position, p) - p;
                let dist = d.length();
                let radiance = volume.at(p - self.position);
                // `volumeLightDir`: shaded from the turned direction (the shadow ray goes
                // to the origin: `shadow_ray_at`).
                let wi = match volume.turn {
                    None => d / dist,
                    Some(::maya::light::Turn::Inward) => -d / dist,
                    Some(::maya::light::Turn::DownAxis(axis)) => axis,
                };
                (dist > 0.0 && radiance.max_element() > 0.0).then_some(LightSample {
                    wi,
                    dist,
                    radiance,
                    pdf: 1.0,
                    delta: true,
                })
            }
            Output::Portal { scale, reverse } => {
                if let Shape::Rect { u: eu, v: ev, normal, area, .. } = self.shape {
                    let normal = if *reverse { -normal } else { normal };
                    let frame = self.rect_frame.as_ref();
                    return rect_sample(self.position, eu, ev, normal, area, frame, *scale, false, p, u);
                }
                let (q, n) = self.point_on(u);
                let n = if *reverse { -n } else { n };
                let d = q - p;
                let dist2 = d.length_squared();
                let dist = dist2.sqrt();
                let wi = d / dist;
                let cos_l = -wi.dot(n);
                if dist == 0.0 || cos_l <= 0.0 {
                    return None;
                }
                let pdf = dist2 / (cos_l * self.shape.area());
                Some(LightSample { wi, dist, radiance: *scale, pdf, delta: false })
            }
            Output::Radiance { l, two_sided } => {
                if let Shape::Sphere { radius } = self.shape {
                    return self.sample_sphere_cone(p, radius, *l, u);
                }
                if let Shape::Rect { u: eu, v: ev, normal, area, .. } = self.shape {
                    let frame = self.rect_frame.as_ref();
                    return rect_sample(self.position, eu, ev, normal, area, frame, *l, *two_sided, p, u);
                }
                let (q, n) = self.point_on(u);
                let d = q - p;
                let dist2 = d.length_squared();
                let dist = dist2.sqrt();
                if dist == 0.0 {
                    return None;
                }
                let wi = d / dist;
                let cos_l = -wi.dot(n);
                if cos_l <= 0.0 && !*two_sided || cos_l == 0.0 {
                    return None;
                }
                let pdf = dist2 / (cos_l.abs() * self.shape.area());
                Some(LightSample { wi, dist, radiance: *l, pdf, delta: false })
            }
        }
    }

    /// Samples the cone of directions a sphere subtends from `p` (uniform in solid angle).
    fn sample_sphere_cone(&self, p: Vec3A, radius: f32, l: Rgb, u: Vec2) -> Option<LightSample> {
        let d = self.position - p;
        let dist2 = d.length_squared();
        if dist2 <= radius * radius {
            return None;
        }
        let dist_c = dist2.sqrt();
        let cos_max = (1.0 - radius * radius / dist2).max(0.0).sqrt();
        let cos_t = 1.0 - u.x * (1.0 - cos_max);
        let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        let f = Frame::from_normal(d / dist_c);
        let wi = f.to_world(Vec3A::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t));
        let (t, _) = self.intersect(&Ray::new(p, wi))?;
        let pdf = 1.0 / (2.0 * PI * (1.0 - cos_max));
        Some(LightSample { wi, dist: t, radiance: l, pdf, delta: false })
    }

    /// Solid-angle density with which [`LightSource::sample`] picks direction `wi` (unit)
    /// from `p` towards the point at distance `t` on the light.
    pub fn pdf(&self, p: Vec3A, wi: Vec3A, t: f32) -> f32 {
        match (&self.output, &self.shape) {
            (Output::Radiance { .. }, &Shape::Sphere { radius }) => {
                let dist2 = (self.position - p).length_squared();
                let cos_max = (1.0 - radius * radius / dist2).max(0.0).sqrt();
                1.0 / (2.0 * PI * (1.0 - cos_max))
            }
            (Output::Radiance { .. } | Output::Portal { .. }, shape) => {
                if let (Shape::Rect { .. }, Some(frame)) = (shape, &self.rect_frame) {
                    if let Some(rect) = frame.view(self.position, p) {
                        return rect.pdf();
                    }
                }
                let n = shape.normal_at(self.position, p + wi * t);
                let cos_l = wi.dot(n).abs();
                if cos_l == 0.0 {
                    return 0.0;
                }
                t * t / (cos_l * shape.area())
            }
            _ => 0.0,
        }
    }

    /// Where `ray` hits the light's surface: (t, radiance towards the ray's origin).
    ///
    /// Every ray of the path engine asks every visible light this, so the common case — a
    /// rectangle that emits radiance and does not move — is inlined at the caller; the
    /// rest is `intersect_any`, out of line.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<(f32, Rgb)> {
        self.intersect_until(ray, ray.tmax)
    }

    /// [`LightSource::intersect`] for `ray` cut at distance `tmax` instead of its own
    /// `tmax` (the path engine asks it of every ray up to the surface the ray found,
    /// without copying the ray for each light).
    #[inline]
    pub fn intersect_until(&self, ray: &Ray, tmax: f32) -> Option<(f32, Rgb)> {
        if let (Output::Radiance { l, two_sided }, Shape::Rect { normal, .. }, true) =
            (&self.output, &self.shape, self.motion.is_empty())
        {
            // (A one-sided rectangle met from behind, or edge on, gives nothing: its
            // plane's distance is not worked out.)
            if !*two_sided && ray.dir.dot(*normal) >= 0.0 {
                return None;
            }
            let (t, facing) = self.shape.intersect(self.position, ray.origin, ray.dir, ray.tmin, tmax)?;
            return (facing || *two_sided).then_some((t, *l));
        }
        self.intersect_any(&Ray { tmax, ..*ray })
    }

    /// [`LightSource::intersect`] for any light.
    #[inline(never)]
    fn intersect_any(&self, ray: &Ray) -> Option<(f32, Rgb)> {
        if let Some(shaped) = self.shaped_at(ray.time) {
            return shaped.intersect(ray);
        }
        if !self.motion.is_empty() {
            // Where the light is at the ray's time: the ray carried back to where it is at
            // the shutter's opening (a rigid motion keeps distances along it).
            let back = crate::motion::lerp_keys(&self.motion, ray.time).inverse();
            let still =
                Ray { origin: back.transform_point3a(ray.origin), dir: back.transform_vector3a(ray.dir), ..*ray };
            return self.intersect_still(&still);
        }
        self.intersect_still(ray)
    }

    /// This light with its object triangles where they are at shutter time `time`, when
    /// they change shape while the shutter is open ([`shader::light::MeshShape::at_time`];
    /// the copy's triangles then hold still, its own `motion` still applies); `None` when
    /// its shape holds at every time.
    #[inline]
    fn shaped_at(&self, time: f32) -> Option<LightSource> {
        // The test inlined into every ray's light query; the rare copy out of line.
        let Shape::Mesh(mesh) = &self.shape else { return None };
        self.mesh_shaped_at(mesh, time)
    }

    /// [`LightSource::shaped_at`] for a light made of triangles `mesh`.
    #[inline(never)]
    fn mesh_shaped_at(&self, mesh: &shader::light::MeshShape, time: f32) -> Option<LightSource> {
        let at = mesh.at_time(time)?;
        Some(LightSource { shape: Shape::Mesh(Arc::new(at)), ..self.clone() })
    }

    /// [`LightSource::intersect`] with the light where it is at the shutter's opening.
    fn intersect_still(&self, ray: &Ray) -> Option<(f32, Rgb)> {
        let (l, two_sided, reverse) = match self.output {
            Output::Radiance { l, two_sided } => (l, two_sided, false),
            // A portal's radiance is its scale (× the environment, which the caller adds).
            Output::Portal { scale, reverse } => (scale, false, reverse),
            _ => return None,
        };
        let (t, facing) = self.shape.intersect(self.position, ray.origin, ray.dir, ray.tmin, ray.tmax)?;
        (facing != reverse || two_sided).then_some((t, l))
    }

    /// [`LightSource::sample`] with the light where it is at shutter time `time`.
    ///
    /// The common case — a rectangle that emits radiance and does not move, sampled by
    /// area — is inlined at the caller (the same arithmetic as [`LightSource::sample`]'s);
    /// the rest, a rectangle that looks large from `p` included, is `sample_any_at`, out of
    /// line.
    #[inline]
    pub fn sample_at(&self, p: Vec3A, u: Vec2, time: f32) -> Option<LightSample> {
        if let (Output::Radiance { l, two_sided }, &Shape::Rect { u: eu, v: ev, normal, area, .. }, true) =
            (&self.output, &self.shape, self.motion.is_empty())
        {
            // By area unless the light looks large from `p`; then `sample_any_at` (out of
            // line: the one call here, so the caller's loop keeps its registers) asks again
            // and samples it in solid angle.
            if !self.rect_frame.as_ref().is_some_and(|frame| frame.looks_large(self.position, p)) {
                return rect_sample_by_area(self.position, eu, ev, normal, area, *l, *two_sided, p, u);
            }
        }
        self.sample_any_at(p, u, time)
    }

    /// [`LightSource::sample_at`] for any light.
    #[inline(never)]
    fn sample_any_at(&self, p: Vec3A, u: Vec2, time: f32) -> Option<LightSample> {
        if let Some(shaped) = self.shaped_at(time) {
            return shaped.sample_at(p, u, time);
        }
        if self.motion.is_empty() {
            return self.sample(p, u);
        }
        let moved = crate::motion::lerp_keys(&self.motion, time);
        let back = moved.inverse();
        let mut ls = self.sample(back.transform_point3a(p), u)?;
        ls.wi = moved.transform_vector3a(ls.wi).normalize_or(ls.wi);
        Some(ls)
    }

    /// The direction (unit) and length of the shadow ray that tests sample `ls` of this
    /// light from `p` at shutter time `time`: the sample's own, or for a light with
    /// [`LightSource::soft_shadow`] one of its soft shadow rays, picked by `u` (uniform in
    /// [0, 1)²) — towards a point uniform over the surface of the sphere of `lightRadius`
    /// around the light, or along a direction uniform in solid angle over the cone of half
    /// `lightAngle` around the sample's direction. The classic Maya light's shadow rays:
    /// the unshadowed light is unchanged, the share of such rays let through shadows it.
    /// A Maya volume light whose `volumeLightDir` turns the sample's direction: towards
    /// the point it shines from (its origin, or the nearest point of a cylinder's or
    /// cone's axis). (Always inlined: its common case is one test.)
    #[inline(always)]
    pub fn shadow_ray_at(&self, p: Vec3A, ls: &LightSample, u: Vec2, time: f32) -> (Vec3A, f32) {
        // Most lights: the sample's own ray (tested inline; the others out of line).
        if self.soft_shadow.is_none() && !matches!(self.output, Output::Volume(_)) {
            return (ls.wi, ls.dist);
        }
        self.spread_shadow_ray_at(p, ls, u, time)
    }

    /// [`LightSource::shadow_ray_at`] for lights with soft shadows or a turned volume light.
    #[inline(never)]
    fn spread_shadow_ray_at(&self, p: Vec3A, ls: &LightSample, u: Vec2, time: f32) -> (Vec3A, f32) {
        let centre = || {
            if self.motion.is_empty() {
                self.position
            } else {
                crate::motion::lerp_keys(&self.motion, time).transform_point3a(self.position)
            }
        };
        if let Output::Volume(volume) = &self.output {
            if volume.turn.is_some() {
                // The point the light shines from: found where the light is at `time`.
                let source = if self.motion.is_empty() {
                    volume.source(self.position, p)
                } else {
                    let moved = crate::motion::lerp_keys(&self.motion, time);
                    moved.transform_point3a(volume.source(self.position, moved.inverse().transform_point3a(p)))
                };
                let d = source - p;
                let dist = d.length();
                return if dist > 0.0 && dist.is_finite() { (d / dist, dist) } else { (ls.wi, ls.dist) };
            }
        }
        match self.soft_shadow {
            Some(SoftShadow::Radius(r)) if ls.delta => {
                let z = 1.0 - 2.0 * u.x;
                let s = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * PI * u.y;
                let d = centre() + r * Vec3A::new(s * phi.cos(), s * phi.sin(), z) - p;
                let dist = d.length();
                // A point of the sphere at `p` itself keeps the sample's ray.
                if dist > 0.0 && dist.is_finite() {
                    (d / dist, dist)
                } else {
                    (ls.wi, ls.dist)
                }
            }
            Some(SoftShadow::Angle(half)) if ls.delta => (mia::sun::cone_direction(ls.wi, half, u.x, u.y), ls.dist),
            _ => (ls.wi, ls.dist),
        }
    }

    /// [`LightSource::pdf`] with the light where it is at shutter time `time`.
    pub fn pdf_at(&self, p: Vec3A, wi: Vec3A, t: f32, time: f32) -> f32 {
        if let Some(shaped) = self.shaped_at(time) {
            return shaped.pdf_at(p, wi, t, time);
        }
        if self.motion.is_empty() {
            return self.pdf(p, wi, t);
        }
        let back = crate::motion::lerp_keys(&self.motion, time).inverse();
        self.pdf(back.transform_point3a(p), back.transform_vector3a(wi).normalize_or(wi), t)
    }
}

/// A sample of a rectangle of radiance `l` centred at `centre` (full edges `eu`, `ev`, unit
/// normal `normal` on its emitting side, area `area`, frame `frame` when it has one; both
/// sides when `two_sided`) seen from `p`: the point picked by `u` uniformly in the solid
/// angle the rectangle subtends where [`RectFrame::view`] allows it, else uniformly by area;
/// its density per solid angle. `None` when that point is `p` itself or faces away.
///
/// Inlined at every caller: the test whether the light looks large from `p` is a few
/// multiplications; the solid-angle sampler behind it is out of line.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn rect_sample(
    centre: Vec3A,
    eu: Vec3A,
    ev: Vec3A,
    normal: Vec3A,
    area: f32,
    frame: Option<&RectFrame>,
    l: Rgb,
    two_sided: bool,
    p: Vec3A,
    u: Vec2,
) -> Option<LightSample> {
    if let Some(frame) = frame {
        if frame.looks_large(centre, p) {
            return rect_sample_large(centre, eu, ev, normal, area, frame, l, two_sided, p, u);
        }
    }
    rect_sample_by_area(centre, eu, ev, normal, area, l, two_sided, p, u)
}

/// [`rect_sample`] where the rectangle [`RectFrame::looks_large`] from `p` (out of line):
/// in solid angle when [`RectFrame::view_large`] allows it, else by area.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
#[cold]
fn rect_sample_large(
    centre: Vec3A,
    eu: Vec3A,
    ev: Vec3A,
    normal: Vec3A,
    area: f32,
    frame: &RectFrame,
    l: Rgb,
    two_sided: bool,
    p: Vec3A,
    u: Vec2,
) -> Option<LightSample> {
    let Some(rect) = frame.view_large(centre, p) else {
        return rect_sample_by_area(centre, eu, ev, normal, area, l, two_sided, p, u);
    };
    // (`looks_large` declines points in the plane: p is strictly on one side.)
    if !two_sided && (p - centre).dot(normal) <= 0.0 {
        return None;
    }
    let d = rect.point(u) - p;
    let dist = d.length();
    if dist.is_nan() || dist <= 0.0 {
        return None;
    }
    Some(LightSample { wi: d / dist, dist, radiance: l, pdf: rect.pdf(), delta: false })
}

/// [`rect_sample`]'s point picked uniformly by area (the parametrisation's fallback).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn rect_sample_by_area(
    centre: Vec3A,
    eu: Vec3A,
    ev: Vec3A,
    normal: Vec3A,
    area: f32,
    l: Rgb,
    two_sided: bool,
    p: Vec3A,
    u: Vec2,
) -> Option<LightSample> {
    // The arithmetic of `Shape::point_on` and `Shape::area` for rectangles, step
    // by step: the same numbers bit for bit as the general path.
    let q = centre + eu * (u.x - 0.5) + ev * (u.y - 0.5);
    let d = q - p;
    let dist2 = d.length_squared();
    let dist = dist2.sqrt();
    if dist == 0.0 {
        return None;
    }
    let wi = d / dist;
    let cos_l = -wi.dot(normal);
    if cos_l <= 0.0 && !two_sided || cos_l == 0.0 {
        return None;
    }
    let pdf = dist2 / (cos_l.abs() * area);
    Some(LightSample { wi, dist, radiance: l, pdf, delta: false })
}
