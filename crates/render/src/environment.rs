//! The scene's environment for the path engine: the radiance arriving from infinitely far
//! away along a world-space direction, and how to sample directions by it.
//!
//! The environment is the camera's `environment` shader list (mental ray:
//! `mib_lookup_spherical`, `mib_lookup_background`, `mia_physicalsky`, …) or, in Iray
//! scenes, the shader named by the options attribute `environment_function` (which the
//! shading compiles as the camera's environment when the camera has none). It is run
//! through the shader graph for each direction asked for, as an environment ray of the
//! classic engine would run it. Iray's `environment_function_intensity` multiplies it;
//! `environment_lighting_scale` multiplies only the light it casts on surfaces (not what
//! the camera sees directly).
//!
//! At render start the environment is tabulated over a latitude–longitude grid
//! ([`MAP_WIDTH`] × [`MAP_HEIGHT`] texels, +Y the pole) of luminance × sin θ, and directions
//! are drawn from that piecewise-constant density. A texel's luminance is the largest found
//! at its centre and its four corners, so that lights smaller than a texel still get their
//! share of samples, and a floor (a thousandth of the mean) keeps the density positive
//! everywhere.
//! Constant environments skip the grid and are sampled uniformly over the sphere.
//!
//! An environment may show the camera more than the light it casts: `mia_physicalsky`
//! linked to a `mia_physicalsun` light hides its sun disk and glow from rays that gather
//! light (the sun light delivers the sun; see `mia::sky::linked_physical_sun`). Such an
//! environment is evaluated twice over: as seen ([`Environment::radiance`]: camera rays and
//! rays after mirror bounces) and as light ([`Environment::light_radiance`]: rays after
//! other bounces, environment samples, portals; run as a final gather ray would run it),
//! and its importance grid tabulates the light.
//!
//! A module's own MDL function as the environment (`material::mdl_modules::environment`)
//! is evaluated directly for each direction, exactly; only the sampling density comes
//! from the grid, so the estimate stays unbiased.
//!
//! A sun much smaller than a texel (Iray's `base::sun_and_sky` at its default disk size
//! covers a fifth of one) would still be found too rarely: when the environment is that
//! shader (or `base::perez_sun_and_sky`), or a module function that calls one, a share of
//! the samples goes uniformly into the cone that holds the sun's disk and glow
//! ([`SunLobe`]), combined with the grid as one mixture density.

use std::f32::consts::PI;

use bsdf::Rgb;
use glam::{Vec2, Vec3A};
use rayon::prelude::*;
use shader::{Color, Ctx, NodeId, RayType, Shading, State, Value};

use crate::accel::Accel;
use crate::tracer::SceneTracer;
use crate::world::World;

/// Texels of the importance grid around the pole axis.
pub const MAP_WIDTH: usize = 512;
/// Texels of the importance grid from pole to pole.
pub const MAP_HEIGHT: usize = 256;

/// Where the environment's radiance comes from.
pub enum Source<'a> {
    /// The same radiance from every direction.
    Constant(Rgb),
    /// A shader list of the scene's shader graph, run as an environment ray.
    Shader {
        /// The render world (for the tracer shaders get).
        world: &'a World,
        /// Its ray queries.
        accel: &'a dyn Accel,
        /// The compiled shading.
        shading: &'a Shading,
        /// The head of the shader list.
        node: NodeId,
    },
    /// A function of the world-space direction (tests, procedural skies).
    Function(Box<dyn Fn(Vec3A) -> Rgb + Send + Sync + 'a>),
}

impl Source<'_> {
    /// The unscaled radiance arriving along unit direction `dir` (travelling towards the
    /// scene: the environment is seen looking along `dir`). Non-finite values read as 0.
    fn eval(&self, dir: Vec3A) -> Rgb {
        self.eval_as(dir, false)
    }

    /// [`Source::eval`]; with `gather`, a shader runs as for a final gather ray (its
    /// `finalgather_level` 1): the light the environment casts rather than what is seen.
    pub fn eval_as(&self, dir: Vec3A, gather: bool) -> Rgb {
        let c = match self {
            Source::Constant(c) => *c,
            Source::Function(f) => f(dir),
            Source::Shader { world, accel, shading, node } => {
                let tracer = SceneTracer::new(world, *accel);
                let state = State {
                    ray_type: RayType::Environment,
                    org: Vec3A::ZERO,
                    point: Vec3A::ZERO,
                    dir,
                    dist: 0.0,
                    finalgather_level: u32::from(gather),
                    ..State::default()
                };
                let mut ctx = Ctx::new(shading, &tracer, state);
                let mut result = Value::Color(Color::ZERO);
                ctx.run_list(*node, &mut result);
                let c = result.color();
                Rgb::new(c.x, c.y, c.z)
            }
        };
        if c.is_finite() {
            c.max(Rgb::ZERO)
        } else {
            Rgb::ZERO
        }
    }
}

/// A direction drawn from the environment.
#[derive(Clone, Copy, Debug)]
pub struct EnvSample {
    /// Unit world-space direction towards the environment.
    pub dir: Vec3A,
    /// Radiance arriving from it (scaled by the intensity, not the lighting scale).
    pub radiance: Rgb,
    /// Solid-angle density of the choice.
    pub pdf: f32,
}

/// A piecewise-constant density on [0, 1) and its cumulative distribution.
#[derive(Clone, Debug)]
struct Distribution1D {
    func: Vec<f32>,
    cdf: Vec<f32>,
    integral: f32,
}

impl Distribution1D {
    fn new(func: Vec<f32>) -> Distribution1D {
        let n = func.len();
        let mut cdf = Vec::with_capacity(n + 1);
        cdf.push(0.0f32);
        let mut sum = 0.0f64;
        for f in &func {
            sum += f64::from(*f) / n as f64;
            cdf.push(sum as f32);
        }
        let integral = sum as f32;
        if integral > 0.0 {
            for c in &mut cdf {
                *c /= integral;
            }
        }
        Distribution1D { func, cdf, integral }
    }

    /// A point in [0, 1), its density and its cell.
    fn sample(&self, u: f32) -> (f32, f32, usize) {
        let n = self.func.len();
        let i = self.cdf.partition_point(|c| *c <= u).saturating_sub(1).min(n - 1);
        let width = self.cdf[i + 1] - self.cdf[i];
        let t = if width > 0.0 { ((u - self.cdf[i]) / width).clamp(0.0, 1.0) } else { 0.5 };
        let x = ((i as f32 + t) / n as f32).min(1.0 - f32::EPSILON);
        (x, self.func[i] / self.integral, i)
    }
}

/// The latitude–longitude importance grid.
#[derive(Clone, Debug)]
struct LatLongMap {
    rows: Vec<Distribution1D>,
    marginal: Distribution1D,
}

/// Direction of grid coordinates (u around the pole, v from +Y down), and sin θ.
fn direction(uv: Vec2) -> (Vec3A, f32) {
    let theta = uv.y * PI;
    let phi = uv.x * 2.0 * PI;
    let (s, c) = theta.sin_cos();
    (Vec3A::new(s * phi.cos(), c, s * phi.sin()), s.abs())
}

/// Grid coordinates of a unit direction.
fn coordinates(dir: Vec3A) -> Vec2 {
    let theta = dir.y.clamp(-1.0, 1.0).acos();
    let mut phi = dir.z.atan2(dir.x);
    if phi < 0.0 {
        phi += 2.0 * PI;
    }
    Vec2::new((phi / (2.0 * PI)).min(1.0 - f32::EPSILON), (theta / PI).min(1.0 - f32::EPSILON))
}

/// Luminance (Rec.709) of a colour.
fn luminance(c: Rgb) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// The scene environment of the path engine.
pub struct Environment<'a> {
    source: Source<'a>,
    /// Multiplies all of the environment (Iray `environment_function_intensity`).
    scale: f32,
    /// Multiplies the light it casts on surfaces (Iray `environment_lighting_scale`).
    pub lighting_scale: f32,
    /// Camera rays that miss everything see it.
    pub camera_visible: bool,
    /// Next-event estimation samples it (off: only scattered rays that leave the scene
    /// find it; mental ray's `"environment lighting mode" "off"`, and comparisons).
    pub sampled: bool,
    /// What its shadow rays do (mental ray's `"environment lighting shadow"`).
    pub shadow: scene::options::EnvironmentShadow,
    /// Directions one next-event estimate averages (mental ray's `"environment lighting
    /// quality"`; at least 1).
    pub samples: u32,
    /// The importance grid; `None` for constant environments (uniform sampling).
    map: Option<LatLongMap>,
    /// A small bright sun sampled on its own.
    sun: Option<SunLobe>,
    /// The light it casts differs from what is seen (evaluated as a final gather ray
    /// evaluates it; see the module comment).
    light_differs: bool,
}

/// The cone around a sun that gets its own share of the environment's samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunLobe {
    /// Unit world direction towards the sun's centre.
    pub direction: Vec3A,
    /// Cosine of the cone's half-angle.
    pub cos_max: f32,
    /// Probability of sampling the cone rather than the grid.
    pub share: f32,
}

impl SunLobe {
    /// A uniform direction in the cone for `u` in [0, 1)².
    fn sample(&self, u: Vec2) -> Vec3A {
        let cos = 1.0 - u.x * (1.0 - self.cos_max);
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        let frame = bsdf::Frame::from_normal(self.direction);
        frame.to_world(Vec3A::new(sin * phi.cos(), sin * phi.sin(), cos))
    }

    /// The cone's uniform solid-angle density at `dir`.
    fn pdf(&self, dir: Vec3A) -> f32 {
        if dir.dot(self.direction) >= self.cos_max {
            1.0 / (2.0 * PI * (1.0 - self.cos_max))
        } else {
            0.0
        }
    }
}

/// Whether the environment at `node` casts other light than it shows: `mia_physicalsky`
/// linked to a `mia_physicalsun` light ([`mia::sky::linked_physical_sun`]).
fn light_differs(world: &World, accel: &dyn Accel, shading: &Shading, node: NodeId) -> bool {
    let Some(imp) = shading.graph.nodes.get(node as usize).and_then(|n| n.imp) else { return false };
    if imp.name != "mia_physicalsky" {
        return false;
    }
    let tracer = SceneTracer::new(world, accel);
    let mut ctx = Ctx::new(shading, &tracer, State { ray_type: RayType::Environment, ..State::default() });
    mia::sky::linked_physical_sun(&mut ctx, node)
}

/// The sun's angular radius, radians (the MDL `::base` skies').
const MDL_SUN_RADIUS: f32 = 0.00465;

/// The sun of an Iray `base::sun_and_sky` or `base::perez_sun_and_sky` environment at
/// `node` — the `.mi` shader, or a module function that calls one (the first such call
/// with a sun; its varying parameters at their defaults) — as a lobe taking a share of
/// the samples equal to its part of the light on a plane facing it (between 0.1 and 0.9);
/// `None` for other shaders or without a sun.
fn sun_lobe(world: &World, accel: &dyn Accel, shading: &Shading, node: NodeId) -> Option<SunLobe> {
    if let Some(f) = material::mdl_modules::environment::of_node(shading, node) {
        use material::mdl_modules::sky_model::SkyModel;
        return f.sky_calls().iter().find_map(|call| match &call.model {
            SkyModel::SunAndSky(sky) => sun_and_sky_lobe(sky),
            SkyModel::Perez(sky) => perez_lobe(sky),
        });
    }
    let imp = shading.graph.nodes.get(node as usize)?.imp?;
    let tracer = SceneTracer::new(world, accel);
    let mut ctx = Ctx::new(shading, &tracer, State { ray_type: RayType::Environment, ..State::default() });
    match imp.name {
        "mdl::base::perez_sun_and_sky" => perez_lobe(&mdl::perez::sky_of(&mut ctx, node)),
        "mdl::base::sun_and_sky" => sun_and_sky_lobe(&mdl::sky::sun_and_sky_of(&mut ctx, node)),
        _ => None,
    }
}

/// The sun lobe of Perez's sky `sky`: its disk is drawn within 0.15 × 10 sun radii of the
/// sun and delivers about π × the direct illuminance (see `sky::perez`).
fn perez_lobe(sky: &sky::perez::PerezSky) -> Option<SunLobe> {
    let sun_light = luminance(sky.sun_color) * PI;
    if sun_light <= 0.0 {
        return None;
    }
    let share = sun_light / (sun_light + sky.sky_illuminance.max(0.0));
    let up = if sky.params.y_is_up { Vec3A::Y } else { Vec3A::Z };
    let direction = sky.params.sun_direction.normalize_or(up);
    let cos_max = (0.15 * 10.0 * MDL_SUN_RADIUS).cos();
    Some(SunLobe { direction, cos_max, share: share.clamp(0.1, 0.9) })
}

/// The sun lobe of `base::sun_and_sky` `sky`: the cone of its disk and glow.
fn sun_and_sky_lobe(sky: &mdl::sky::SunAndSky) -> Option<SunLobe> {
    let sun = sky.sun()?;
    let cos_max = sun.cone_radius.cos();
    if cos_max.is_nan() || cos_max >= 1.0 {
        return None;
    }
    // The sky's irradiance on the same plane, roughly: its zenith radiance × π.
    let sky_light = luminance(sky.sky_radiance(sun.direction)) * PI;
    let sun_light = luminance(sun.irradiance);
    let share = if sun_light + sky_light > 0.0 { sun_light / (sun_light + sky_light) } else { 0.5 };
    Some(SunLobe { direction: sun.direction.normalize_or(Vec3A::Y), cos_max, share: share.clamp(0.1, 0.9) })
}

/// The sun lobe the environment at `node` gets (for tests and diagnostics).
pub fn sun_lobe_of(world: &World, accel: &dyn Accel, shading: &Shading, node: NodeId) -> Option<SunLobe> {
    sun_lobe(world, accel, shading, node)
}

impl<'a> Environment<'a> {
    /// The environment of a scene whose compiled shading is `shading`, with the options'
    /// Iray attributes; `None` when the scene has none (or it is black everywhere).
    pub fn of_scene(world: &'a World, accel: &'a dyn Accel, shading: &'a Shading) -> Option<Environment<'a>> {
        let node = shading.environment?;
        let attr = |name: &str| world.options.attributes.get(name).and_then(|a| a.as_f64()).map(|v| v as f32);
        let source = match material::mdl_modules::environment::of_node(shading, node) {
            // A module's own function (alone in the list): evaluated directly.
            Some(f) if shading.graph.nodes[node as usize].next.is_none() => {
                Source::Function(Box::new(move |dir| f.radiance(dir)))
            }
            _ => Source::Shader { world, accel, shading, node },
        };
        let mut env = if light_differs(world, accel, shading, node) {
            let map = LatLongMap::build(&source, true);
            Environment { light_differs: true, map, ..Environment::new_untabulated(source) }
        } else {
            Environment::new(source)
        };
        env.sun = sun_lobe(world, accel, shading, node);
        env.scale = attr("environment_function_intensity").filter(|s| s.is_finite() && *s >= 0.0).unwrap_or(1.0);
        env.lighting_scale = attr("environment_lighting_scale").filter(|s| s.is_finite() && *s >= 0.0).unwrap_or(1.0);
        // mental ray's environment-light settings (`scene::options::modes`): its scale
        // multiplies Iray's, its quality sets the directions per estimate.
        env.lighting_scale *= world.options.environment_lighting_scale() as f32;
        env.shadow = world.options.environment_shadow();
        env.samples = world.options.environment_samples();
        // mental ray's `"environment lighting mode" "off"`: the environment is no light
        // source, only seen by the rays that leave the scene (`scene::options::modes`).
        env.sampled = world.options.environment_lighting() != Some(scene::options::EnvironmentLighting::Off);
        (!env.is_black()).then_some(env)
    }

    /// Whether its direct light is left to next-event estimation alone (no MIS): with
    /// solid shadows or none, scattered rays would find it where its shadow rays do not.
    pub fn nee_only(&self) -> bool {
        self.shadow != scene::options::EnvironmentShadow::Transparent
    }

    /// An environment of `source`, its importance grid tabulated now (intensity and
    /// lighting scale 1, seen by the camera).
    pub fn new(source: Source<'a>) -> Environment<'a> {
        let map = match source {
            Source::Constant(_) => None,
            _ => LatLongMap::build(&source, false),
        };
        Environment { map, ..Environment::new_untabulated(source) }
    }

    /// An environment of `source` without an importance grid (sampled uniformly).
    fn new_untabulated(source: Source<'a>) -> Environment<'a> {
        Environment {
            source,
            scale: 1.0,
            lighting_scale: 1.0,
            camera_visible: true,
            sampled: true,
            shadow: scene::options::EnvironmentShadow::Transparent,
            samples: 1,
            map: None,
            sun: None,
            light_differs: false,
        }
    }

    /// Whether it gives no light at all.
    fn is_black(&self) -> bool {
        match (&self.source, &self.map) {
            (Source::Constant(c), _) => c.max_element() <= 0.0,
            (_, Some(m)) => m.marginal.integral <= 0.0,
            // The grid was constant: one direction tells.
            (s, None) => s.eval(Vec3A::Y).max_element() <= 0.0,
        }
    }

    /// Radiance arriving along unit world direction `dir` (looking along `dir`) as seen:
    /// by camera rays and rays after mirror (delta) bounces.
    pub fn radiance(&self, dir: Vec3A) -> Rgb {
        self.source.eval(dir) * self.scale
    }

    /// Radiance arriving along unit world direction `dir` as light on surfaces: for rays
    /// after other bounces, environment samples and portals (see the module comment; the
    /// same as [`Environment::radiance`] for most environments). Not × the lighting scale.
    pub fn light_radiance(&self, dir: Vec3A) -> Rgb {
        if self.light_differs {
            self.source.eval_as(dir, true) * self.scale
        } else {
            self.radiance(dir)
        }
    }

    /// Draws a direction for the numbers `u` in [0, 1)².
    pub fn sample(&self, u: Vec2) -> Option<EnvSample> {
        let Some(sun) = self.sun else { return self.sample_grid(u) };
        // The mixture: the sun's cone with its share, else the grid; u.x is reused.
        let dir = if u.x < sun.share {
            sun.sample(Vec2::new(u.x / sun.share, u.y))
        } else {
            self.sample_grid(Vec2::new((u.x - sun.share) / (1.0 - sun.share), u.y))?.dir
        };
        let pdf = self.pdf(dir);
        (pdf > 0.0).then(|| EnvSample { dir, radiance: self.light_radiance(dir), pdf })
    }

    /// Sets the sun lobe (for tests; scenes get theirs from [`Environment::of_scene`]).
    pub fn with_sun(mut self, sun: Option<SunLobe>) -> Environment<'a> {
        self.sun = sun;
        self
    }

    /// Draws a direction from the grid (or uniformly) alone.
    fn sample_grid(&self, u: Vec2) -> Option<EnvSample> {
        let Some(map) = &self.map else {
            let z = 1.0 - 2.0 * u.x;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = 2.0 * PI * u.y;
            let dir = Vec3A::new(r * phi.cos(), r * phi.sin(), z);
            return Some(EnvSample { dir, radiance: self.light_radiance(dir), pdf: 1.0 / (4.0 * PI) });
        };
        let (v, pdf_v, row) = map.marginal.sample(u.y);
        let (x, pdf_u, _) = map.rows[row].sample(u.x);
        let (dir, sin_theta) = direction(Vec2::new(x, v));
        if sin_theta <= 0.0 || pdf_v * pdf_u <= 0.0 {
            return None;
        }
        let pdf = pdf_v * pdf_u / (2.0 * PI * PI * sin_theta);
        Some(EnvSample { dir, radiance: self.light_radiance(dir), pdf })
    }

    /// Solid-angle density with which [`Environment::sample`] draws unit direction `dir`.
    pub fn pdf(&self, dir: Vec3A) -> f32 {
        match self.sun {
            Some(sun) => sun.share * sun.pdf(dir) + (1.0 - sun.share) * self.pdf_grid(dir),
            None => self.pdf_grid(dir),
        }
    }

    /// The grid's (or the uniform) density at `dir`.
    fn pdf_grid(&self, dir: Vec3A) -> f32 {
        let Some(map) = &self.map else { return 1.0 / (4.0 * PI) };
        let uv = coordinates(dir);
        let (w, h) = (map.rows[0].func.len(), map.rows.len());
        let row = ((uv.y * h as f32) as usize).min(h - 1);
        let col = ((uv.x * w as f32) as usize).min(w - 1);
        let sin_theta = (1.0 - dir.y * dir.y).max(0.0).sqrt();
        if sin_theta <= 0.0 || map.marginal.integral <= 0.0 {
            return 0.0;
        }
        let pdf_uv = map.rows[row].func[col] / map.marginal.integral;
        pdf_uv / (2.0 * PI * PI * sin_theta)
    }
}

impl LatLongMap {
    /// Tabulates `source` (as light with `gather`: [`Source::eval_as`]); `None` when it is
    /// the same in every texel (then sampled uniformly).
    fn build(source: &Source, gather: bool) -> Option<LatLongMap> {
        let (w, h) = (MAP_WIDTH, MAP_HEIGHT);
        // Luminance at the texel corners, then each texel's largest of its centre and
        // corners: a light smaller than a texel still gets density where it is.
        let corners: Vec<f32> = (0..=h)
            .into_par_iter()
            .flat_map_iter(|row| {
                (0..=w).map(move |col| {
                    let uv = Vec2::new(col as f32 / w as f32, row as f32 / h as f32);
                    luminance(source.eval_as(direction(uv).0, gather))
                })
            })
            .collect();
        let texels: Vec<(f32, f32)> = (0..h)
            .into_par_iter()
            .flat_map_iter(|row| {
                let corners = &corners;
                (0..w).map(move |col| {
                    let uv = Vec2::new((col as f32 + 0.5) / w as f32, (row as f32 + 0.5) / h as f32);
                    let (dir, sin_theta) = direction(uv);
                    let at = |r: usize, c: usize| corners[r * (w + 1) + c];
                    let l = luminance(source.eval_as(dir, gather))
                        .max(at(row, col))
                        .max(at(row, col + 1))
                        .max(at(row + 1, col))
                        .max(at(row + 1, col + 1));
                    (l, sin_theta)
                })
            })
            .collect();
        let first = texels[0].0;
        if texels.iter().all(|(l, _)| *l == first) {
            return None;
        }
        let total: f64 = texels.iter().map(|(l, s)| f64::from(l * s)).sum();
        // The floor: a thousandth of the mean, so that no direction has zero density.
        let floor = (total / (w * h) as f64 * 1e-3).max(1e-12) as f32;
        let rows: Vec<Distribution1D> = texels
            .chunks(w)
            .map(|row| Distribution1D::new(row.iter().map(|(l, s)| (l + floor) * s).collect()))
            .collect();
        let marginal = Distribution1D::new(rows.iter().map(|r| r.integral).collect());
        Some(LatLongMap { rows, marginal })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn uniform(i: u32, n: u32) -> Vec2 {
        // A rank-1 lattice (Fibonacci): even coverage of the square.
        let g = 0.618_034f32;
        Vec2::new((i as f32 + 0.5) / n as f32, (i as f32 * g + 0.5 / n as f32).fract())
    }

    /// A dim sky with a bright disc around +X+Y.
    fn bright_spot() -> Environment<'static> {
        let centre = Vec3A::new(1.0, 1.0, 0.3).normalize();
        Environment::new(Source::Function(Box::new(move |d: Vec3A| {
            if d.dot(centre) > 0.99 {
                Rgb::splat(200.0)
            } else {
                Rgb::new(0.2, 0.3, 0.5)
            }
        })))
    }

    #[test]
    fn grid_coordinates_round_trip() {
        for i in 0..200 {
            let uv = uniform(i, 200) * 0.98 + Vec2::splat(0.01);
            let (d, _) = direction(uv);
            assert!((d.length() - 1.0).abs() < 1e-5);
            let back = coordinates(d);
            assert!((back - uv).abs().max_element() < 1e-4, "{uv} → {d} → {back}");
        }
    }

    #[test]
    fn density_integrates_to_one_and_matches_sampling() {
        let env = bright_spot();
        // ∫ pdf dω over the sphere by a fine midpoint rule in (cos θ, φ).
        let n = 800;
        let mut integral = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let z = -1.0 + 2.0 * (i as f32 + 0.5) / n as f32;
                let phi = 2.0 * PI * (j as f32 + 0.5) / n as f32;
                let r = (1.0 - z * z).sqrt();
                let d = Vec3A::new(r * phi.cos(), z, r * phi.sin());
                integral += f64::from(env.pdf(d)) * (4.0 * std::f64::consts::PI) / f64::from(n * n);
            }
        }
        assert!((integral - 1.0).abs() < 5e-3, "∫ pdf = {integral}");
        // The density sample() reports is pdf() of its direction (within a texel edge).
        for i in 0..500 {
            let s = env.sample(uniform(i, 500)).expect("a sample");
            let p = env.pdf(s.dir);
            assert!((s.pdf - p).abs() <= 1e-3 * p.max(s.pdf), "sample pdf {} vs pdf {p}", s.pdf);
        }
    }

    #[test]
    fn importance_sampling_lowers_the_variance_of_the_irradiance() {
        // E at a point facing +Y: ∫ L cos θ dω by environment sampling and by cosine
        // sampling, each with 256 samples, repeated 200 times.
        let env = bright_spot();
        let estimate = |k: u32, by_env: bool| {
            let n = 256u32;
            let mut sum = 0.0f64;
            for i in 0..n {
                // Independent pseudo-random numbers (plain Monte Carlo variance).
                let r = |j: u64| {
                    // SplitMix64 of the sample's index.
                    let mut z = (u64::from(k) << 32 | u64::from(i) << 1 | j).wrapping_mul(0x9E37_79B9_7F4A_7C15);
                    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                    ((z ^ (z >> 31)) >> 40) as f32 / (1u32 << 24) as f32
                };
                let u = Vec2::new(r(0), r(1));
                if by_env {
                    // (None only where sin θ = 0: a set of measure zero.)
                    if let Some(s) = env.sample(u).filter(|s| s.dir.y > 0.0) {
                        sum += f64::from(s.radiance.x * s.dir.y / s.pdf);
                    }
                } else {
                    let l = bsdf::cosine_hemisphere(u);
                    let d = Vec3A::new(l.x, l.z, l.y);
                    sum += f64::from(env.radiance(d).x * PI);
                }
            }
            sum / f64::from(n)
        };
        let stats = |by_env: bool| {
            let v: Vec<f64> = (0..200).map(|k| estimate(k, by_env)).collect();
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (v.len() - 1) as f64;
            (mean, var)
        };
        let (m_env, v_env) = stats(true);
        let (m_cos, v_cos) = stats(false);
        // Exactly: the dim sky over the hemisphere plus the cap's excess, ∫cap cos θ dω =
        // y_c · π (1 − 0.99²) for a cap wholly above the horizon.
        let cap = f64::from(Vec3A::new(1.0, 1.0, 0.3).normalize().y) * std::f64::consts::PI * (1.0 - 0.99 * 0.99);
        let exact = 0.2 * std::f64::consts::PI + (200.0 - 0.2) * cap;
        eprintln!(
            "irradiance {exact:.4}: environment sampling {m_env:.4} (variance {v_env:.4}), cosine {m_cos:.4} (variance {v_cos:.4})"
        );
        assert!((m_env - exact).abs() < 0.01 * exact, "{m_env} vs {exact}");
        // The cosine estimate is heavy-tailed: only its spread is compared.
        assert!((m_cos - exact).abs() < 6.0 * (v_cos / 200.0).sqrt(), "{m_cos} vs {exact}");
        assert!(v_env * 10.0 < v_cos, "variance {v_env} vs cosine {v_cos}");
    }

    #[test]
    fn constant_environments_are_sampled_uniformly() {
        let env = Environment::new(Source::Function(Box::new(|_| Rgb::splat(0.5))));
        assert!(env.map.is_none());
        let s = env.sample(Vec2::new(0.3, 0.8)).expect("a sample");
        assert!((s.pdf - 1.0 / (4.0 * PI)).abs() < 1e-7 && (s.radiance.x - 0.5).abs() < 1e-7);
        let black = Environment::new(Source::Constant(Rgb::ZERO));
        assert!(black.is_black());
    }
}
