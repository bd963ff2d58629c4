//! The light loop of mental ray shaders: light lists and their modes, sampling each
//! light (several points on area lights), calling its light shader, and shadow rays with
//! shadow shaders.
//!
//! A material shader's loop reads:
//!
//! ```text
//! for light in ctx.light_list(mode, &lights) {
//!     let mut l = ctx.light_loop(light);
//!     while let Some(s) = ctx.sample_light(&mut l) { sum += f(s.color, s.dir, s.dot_nl) }
//!     if l.samples > 0 { result += sum / l.samples }
//! }
//! ```
//!
//! Light shaders (`mib_light_point` …) see a light state: `org` the point on the light,
//! `point` the illuminated point, `dir` from the light to that point, `dist` between them.
//! They call [`Ctx::trace_shadow`], which walks the surfaces in between and runs their
//! shadow shaders on the light's colour; a surface without a shadow shader blocks it.
//! Where no material has a shadow shader, an area light's samples have their shadow rays
//! traced ahead in batches of eight (one packet), answered when the shader asks.
//! A base light shader with constant parameters ([`SimpleLight`]) is evaluated in place
//! of its call, with the same functions and the same bits.
//! The light's result then passes through the volume of the medium the point is seen in
//! ([`super::volume`]).

use std::borrow::Cow;

use glam::{Vec2, Vec3A, Vec4};
use scene::LightKind;

use super::ctx::Ctx;
use super::light::simple::{shadowed, SimpleLight};
use super::light::ShadingLight;
use super::light_list::LightList;
use super::site::SitePairs;
use super::state::{RayType, State};
use super::tracer::{ShadowHint, ShadowQuery};
use super::value::{Color, Tag, Value};

/// One sample of a light (what mental ray's `mi_sample_light` hands back).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// The light's colour arriving, after its shader (attenuation, shadows).
    pub color: Color,
    /// Unit direction from the shading point towards the light.
    pub dir: Vec3A,
    /// `dot(normal, dir)`.
    pub dot_nl: f32,
    /// Distance to the sampled point on the light (infinite for directional lights).
    pub dist: f32,
}

/// How many samples' shadow rays the light loop traces together (one packet).
const AHEAD: usize = 8;

/// Where one light sample lies, seen from the illuminated point.
#[derive(Clone, Copy, Debug, Default)]
struct SampleGeometry {
    /// Unit direction from the point to the sample.
    to_light: Vec3A,
    /// Distance to it (infinite for directional lights).
    dist: f32,
    /// The sample's point on the light.
    on_light: Vec3A,
    /// `dot(normal, to_light)`.
    dot_nl: f32,
}

/// What [`SimpleLight::unshadowed`] reads of `light` for a sample in direction `to_light`
/// (unit, from the point to the light): for a spot shader, the cosine between the light's
/// axis and the direction from the light to the point, as the shader finds it (the light
/// state's `dir` is −`to_light`), and the light's spread cosine; zeros for other shaders.
#[inline(always)]
fn spot_inputs(simple: &SimpleLight, light: &ShadingLight, to_light: Vec3A) -> (f32, f32) {
    match simple.cone {
        Some(_) => (light.direction.dot(-to_light), light.spread),
        None => (0.0, 0.0),
    }
}

/// The progress of sampling one light.
#[derive(Clone, Copy, Debug)]
pub struct LightLoop {
    /// The light.
    pub light: u32,
    /// Samples taken so far: divide the summed contributions by this.
    pub samples: u32,
    next: u32,
    grid: (u32, u32),
    site: u32,
    /// The numbers of the area samples (stratified in `grid`), made when the loop starts
    /// for lights with a shape.
    pairs: Option<SitePairs>,
    /// The light neither moves nor deforms at this point's time: its samples read the
    /// scene's light itself (no moved copy per sample).
    still: bool,
    /// The light's shader asked for an any-hit shadow ray: the shadow rays of the next
    /// samples are traced together ahead of their shader calls.
    batch: bool,
    /// The samples from `ahead_from` on whose points and shadow rays were found ahead:
    /// bit k of `ahead` is set when sample `ahead_from + k` was, of `ahead_reach` when it
    /// reaches the point (its geometry is in `ahead_samples`), of
    /// `ahead_blocked` when its shadow ray is blocked.
    ahead_from: u32,
    ahead: u8,
    ahead_reach: u8,
    ahead_blocked: u8,
    ahead_samples: [SampleGeometry; AHEAD],
    /// For a [`SimpleLight`]: bit k set when sample `ahead_from + k` arrives lit (its
    /// colour after the light and its shadow ray in `ahead_colors`, which holds the
    /// unshadowed colour until the batch's rays are answered).
    ahead_lit: u8,
    ahead_colors: [Color; AHEAD],
    /// What they were found for: the point, normal, shadow point, geometric normal and
    /// time of the shading state, and `both_sides` (a shader changing one between samples
    /// has them found again).
    ahead_for: ([Vec3A; 4], f32, bool),
    /// Accept points behind the surface (for translucency: the shader flips the normal).
    pub both_sides: bool,
    /// The light's shader is a [`SimpleLight`] the loop evaluates in place (no media to
    /// cross, no shadow shaders to run): see [`Ctx::simple_light_sample`].
    simple: Option<SimpleLight>,
    /// `simple`, with shadow rays, on a still area light: every sample is evaluated when
    /// its batch is found ahead ([`Ctx::simple_area_sample`]).
    simple_area: bool,
}

impl<'a> Ctx<'a> {
    /// Light `light` (index into `Shading::lights`) where it is at this point's shutter
    /// time (`state.time`): the scene's light itself when it does not move, else a copy
    /// moved there with its instance ([`ShadingLight::moved`]), its object triangles
    /// first placed where they are then when they deform ([`crate::Tracer::light_mesh`]).
    /// The light loop and light shaders read their light through this.
    pub fn light(&self, light: u32) -> Option<Cow<'a, ShadingLight>> {
        let l = self.shading().lights.get(light as usize)?;
        let mesh = self.tracer.light_mesh(light, self.state.time);
        Some(match (mesh, self.tracer.light_motion(light, self.state.time)) {
            (None, None) => Cow::Borrowed(l),
            (None, Some(by)) => Cow::Owned(l.moved(by)),
            (Some(mesh), by) => {
                let shaped = l.reshaped(mesh);
                Cow::Owned(match by {
                    Some(by) => shaped.moved(by),
                    None => shaped,
                })
            }
        })
    }

    /// The lights a shader with light `mode` (0 listed, 1 listed ∩ all, 2 all but listed,
    /// 3 all, 4 the instance's light list) and light array `lights` uses.
    pub fn light_list(&self, mode: i32, lights: &Value) -> LightList {
        let all = self.shading().lights.len() as u32;
        let listed = || {
            lights.array().iter().filter_map(move |v| match v.tag() {
                Some(Tag::Light(i)) if i < all => Some(i),
                _ => None,
            })
        };
        match mode {
            0 | 1 => {
                let mut l: LightList = listed().collect();
                l.dedup();
                l
            }
            2 => {
                let listed: LightList = listed().collect();
                (0..all).filter(|i| !listed.contains(i)).collect()
            }
            4 => self.instance_lights(),
            _ => (0..all).collect(),
        }
    }

    /// The light list of the instance being shaded (all lights when it has none).
    pub fn instance_lights(&self) -> LightList {
        let all = self.shading().lights.len() as u32;
        match self.shading().instance_lights.get(self.state.instance as usize).and_then(Option::as_ref) {
            None => (0..all).collect(),
            Some(link) if link.exclusive => (0..all).filter(|i| !link.lights.contains(i)).collect(),
            Some(link) => link.lights.iter().copied().filter(|&i| i < all).collect(),
        }
    }

    /// Starts sampling `light`.
    pub fn light_loop(&mut self, light: u32) -> LightLoop {
        let l = &self.shading().lights[light as usize];
        let level = self.state.reflection_level + self.state.refraction_level;
        let area = l.shape.is_some() || l.user;
        let grid = match l.low {
            _ if !area => (1, 1),
            Some((from, u, v)) if level >= from => (u.max(1), v.max(1)),
            _ => (l.samples.0.max(1), l.samples.1.max(1)),
        };
        let site = self.next_site();
        let pairs = l.shape.is_some().then(|| self.site_pairs(site, grid.0 * grid.1));
        let time = self.state.time;
        let still = self.tracer.light_motion(light, time).is_none() && self.tracer.light_mesh(light, time).is_none();
        let shading = self.shading();
        let simple = shading.simple_light(light).filter(|s| {
            // Media to cross or shadow shaders to run need the light state: the shader runs.
            let walks = s.casts_shadows() && shading.shadows && shading.has_shadow_shaders();
            !(shading.has_media() || walks)
        });
        let batch = simple.is_some_and(|s| s.casts_shadows() && shading.shadows);
        LightLoop {
            light,
            samples: 0,
            next: 0,
            grid,
            site,
            pairs,
            still,
            // A simple light that will ask for any-hit shadow rays has them traced ahead
            // from its first sample on.
            batch,
            ahead_from: 0,
            ahead: 0,
            ahead_reach: 0,
            ahead_blocked: 0,
            ahead_samples: [SampleGeometry::default(); AHEAD],
            ahead_lit: 0,
            ahead_colors: [Color::ZERO; AHEAD],
            ahead_for: ([Vec3A::ZERO; 4], 0.0, false),
            both_sides: false,
            simple,
            simple_area: batch && still && l.shape.is_some() && !l.user,
        }
    }

    /// The next sample of the light that reaches the point, or `None` when the light's
    /// samples are used up. Samples that do not reach (behind the surface, rejected by the
    /// light shader, fully shadowed) count in `samples` but are not returned.
    ///
    /// A `user` area light's shader is called again and again while it returns true, at
    /// most u·v times (its `samples`): each call sets the sample's point on the light
    /// (`org`, with `dir` and `dist` to match) itself and finds its number in the light
    /// loop in `sample_index`; it arrives with `org` at the light's origin. The call
    /// that returns false ends the loop and is no sample.
    pub fn sample_light(&mut self, lp: &mut LightLoop) -> Option<LightSample> {
        if lp.simple_area && self.volume_of(&self.state).is_none() {
            return self.simple_area_sample(lp);
        }
        let count = lp.grid.0 * lp.grid.1;
        let user = self.shading().lights[lp.light as usize].user;
        while lp.next < count {
            let i = lp.next;
            lp.next += 1;
            if user {
                match self.user_light_sample(lp, i) {
                    None => {
                        lp.next = count;
                        return None;
                    }
                    Some(s) => {
                        lp.samples += 1;
                        if s.is_some() {
                            return s;
                        }
                    }
                }
                continue;
            }
            lp.samples += 1;
            if let Some(s) = self.light_sample(lp, i) {
                return Some(s);
            }
        }
        None
    }

    /// One call of a user area light's shader: `None` when it returned false (the loop
    /// ends), else the sample if it reaches the point.
    fn user_light_sample(&mut self, lp: &LightLoop, i: u32) -> Option<Option<LightSample>> {
        let shading = self.shading();
        let light = self.light(lp.light)?;
        let shader = light.shader?;
        let p = self.state.point;
        let d = p - light.origin;
        let dist = d.length();
        let mut ls = self.state.child(RayType::Light, light.origin, d.normalize_or(-light.direction));
        ls.point = p;
        ls.shadow_point = self.state.shadow_point;
        ls.point_error = self.state.point_error;
        ls.dist = dist;
        ls.normal = self.state.normal;
        ls.normal_geom = self.state.normal_geom;
        ls.instance = self.state.instance;
        ls.light = Some(lp.light);
        ls.dot_nd = self.state.normal.dot(-ls.dir);
        ls.sample_index = i;
        let mut ctx = Ctx::new(shading, self.tracer, ls);
        let mut result = Value::Color(Color::ZERO);
        let ok = ctx.run_list(shader, &mut result);
        self.counts.calls += ctx.counts.calls;
        if !ok {
            return None;
        }
        // Where the shader put the sample.
        let to = ctx.state.org - p;
        let dist = to.length();
        if !(dist > 0.0 && dist.is_finite()) {
            return Some(None);
        }
        let dir = to / dist;
        let dot_nl = self.state.normal.dot(dir);
        let mut color = result.color();
        let unwalked = !ctx.media_walked && !crate::is_zero(color) && shading.has_media();
        if self.volume_of(&ctx.state).is_some() || unwalked {
            let mut light_ray = ctx.state.clone();
            (light_ray.dir, light_ray.point, light_ray.dist) = (-dir, p, dist);
            if unwalked {
                // No shadow ray: the media on the way still attenuate the light.
                color = self.light_media(&light_ray, color);
            }
            color = self.light_volume(&light_ray, color);
        }
        let reaches = (dot_nl > 0.0 || lp.both_sides) && (color.x != 0.0 || color.y != 0.0 || color.z != 0.0);
        Some(reaches.then_some(LightSample { color, dir, dot_nl, dist }))
    }

    fn light_sample(&mut self, lp: &mut LightLoop, i: u32) -> Option<LightSample> {
        let shading = self.shading();
        let moved;
        let light = if lp.still {
            shading.lights.get(lp.light as usize)?
        } else {
            moved = self.light(lp.light)?;
            &*moved
        };
        let p = self.state.point;
        let (geometry, hint) = if lp.batch && light.shape.is_some() {
            self.sample_ahead(lp, light, i)
        } else {
            (self.sample_geometry(lp, light, i), None)
        };
        let SampleGeometry { to_light, dist, on_light, dot_nl } = geometry?;
        let shader = light.shader?;
        if let Some(simple) = lp.simple {
            if self.volume_of(&self.state).is_none() {
                return self.simple_light_sample(lp, &simple, geometry?, hint, spot_inputs(&simple, light, to_light));
            }
        }
        let mut ls = self.state.child(RayType::Light, on_light, -to_light);
        ls.point = p;
        ls.shadow_point = self.state.shadow_point;
        ls.point_error = self.state.point_error;
        ls.dist = dist;
        ls.normal = self.state.normal;
        ls.normal_geom = self.state.normal_geom;
        ls.instance = self.state.instance;
        ls.light = Some(lp.light);
        ls.dot_nd = dot_nl;
        let mut ctx = Ctx::new(shading, self.tracer, ls);
        ctx.shadow_hint = hint;
        let mut result = Value::Color(Color::ZERO);
        let ok = ctx.run_list(shader, &mut result);
        self.counts.calls += ctx.counts.calls;
        // A shader that asked for an any-hit shadow ray will ask for the next samples'.
        lp.batch |= ctx.shadow_queried;
        if !ok {
            return None;
        }
        let mut color = result.color();
        if !ctx.media_walked {
            // No shadow ray: the media on the way still attenuate the light.
            color = self.light_media(&ctx.state, color);
        }
        let color = if crate::is_zero(color) { color } else { self.light_volume(&ctx.state, color) };
        (color.x != 0.0 || color.y != 0.0 || color.z != 0.0).then_some(LightSample {
            color,
            dir: to_light,
            dot_nl,
            dist,
        })
    }

    /// A light sample of a [`SimpleLight`] at `geometry`, evaluated in place of its shader
    /// call: the same colour bit for bit (the shader computes it with the same functions),
    /// without a light state. Its shadow ray is the one [`Ctx::trace_shadow`] would send
    /// from the light state (an any-hit query: the loop's `simple` excludes shadow shaders
    /// and media), answered ahead when `hint` holds it. `spot`: for a spot shader, the
    /// cosine between the light's axis and the direction from the light to the point, and
    /// the light's spread cosine ([`SimpleLight::unshadowed`]).
    #[inline(always)]
    fn simple_light_sample(
        &mut self,
        lp: &mut LightLoop,
        simple: &SimpleLight,
        geometry: SampleGeometry,
        hint: Option<ShadowHint>,
        spot: (f32, f32),
    ) -> Option<LightSample> {
        let SampleGeometry { to_light, dist, dot_nl, .. } = geometry;
        // The shader call this stands for.
        self.counts.calls += 1;
        let mut color = simple.unshadowed(dist, spot.0, spot.1)?;
        if simple.casts_shadows() {
            let through = !self.shading().shadows || {
                // Asked for an any-hit shadow ray: the next samples' are traced ahead.
                lp.batch = true;
                let blocked = match hint {
                    Some(hint) => hint.blocked,
                    None => {
                        let s = &self.state;
                        let org = crate::trace::leave_point(s.shadow_point, s.point_error, s.normal_geom, to_light);
                        let max_dist = if dist.is_finite() { dist * (1.0 - 1e-4) } else { f32::INFINITY };
                        self.tracer.shadow_blocked(org, to_light, max_dist, s.time)
                    }
                };
                !blocked
            };
            color = shadowed(color, simple.factor, through, Color::ONE)?;
        }
        (color.x != 0.0 || color.y != 0.0 || color.z != 0.0).then_some(LightSample {
            color,
            dir: to_light,
            dot_nl,
            dist,
        })
    }

    /// Where sample `i` of the light loop `lp` of `light` lies: the unit direction from
    /// this point to it, the distance, the point on the light and `dot(normal, dir)`;
    /// `None` when it does not reach the point (degenerate, or behind the surface).
    fn sample_geometry(&mut self, lp: &LightLoop, light: &ShadingLight, i: u32) -> Option<SampleGeometry> {
        self.sample_geometry_jittered(lp, light, i, None, None)
    }

    /// [`Ctx::sample_geometry`] with sample `i`'s two numbers `jitter` when they were
    /// made ahead (`lp.pairs`' `pair(i)`, bit for bit), and its cell `(i mod u, i div u)`
    /// of the light's u×v grid when the caller knows it.
    #[inline(always)]
    fn sample_geometry_jittered(
        &mut self,
        lp: &LightLoop,
        light: &ShadingLight,
        i: u32,
        jitter: Option<Vec2>,
        cell: Option<(u32, u32)>,
    ) -> Option<SampleGeometry> {
        let p = self.state.point;
        let (to_light, dist, on_light) = match (light.kind, &light.shape) {
            (LightKind::Directional, _) => (-light.direction, f32::INFINITY, p - light.direction * 1e30),
            (_, None) => {
                let d = light.origin - p;
                let dist = d.length();
                (d / dist, dist, light.origin)
            }
            (_, Some(shape)) => {
                // Stratified over the u×v grid, jittered.
                let j = match (jitter, lp.pairs) {
                    (Some(j), _) => j,
                    (None, Some(pairs)) => pairs.pair(i),
                    (None, None) => self.sample2(lp.site, i, lp.grid.0 * lp.grid.1),
                };
                let (gu, gv) = lp.grid;
                let (col, row) = cell.unwrap_or((i % gu, i / gu));
                let u = Vec2::new((col as f32 + j.x) / gu as f32, (row as f32 + j.y) / gv as f32);
                let (q, _) = shape.point_on(light.origin, u);
                let d = q - p;
                let dist = d.length();
                (d / dist, dist, q)
            }
        };
        if dist.is_nan() || dist <= 0.0 || !to_light.is_finite() {
            return None;
        }
        let dot_nl = self.state.normal.dot(to_light);
        if dot_nl <= 0.0 && !lp.both_sides {
            return None;
        }
        Some(SampleGeometry { to_light, dist, on_light, dot_nl })
    }

    /// [`Ctx::sample_light`] for a loop with `simple_area` set, where no volume shader
    /// changes the light (`volume_of` the state is none): the samples' colours are
    /// evaluated as their batch is found ahead ([`Ctx::find_ahead`]), and each sample
    /// reads its own — what [`Ctx::simple_light_sample`] gives, bit for bit.
    fn simple_area_sample(&mut self, lp: &mut LightLoop) -> Option<LightSample> {
        let count = lp.grid.0 * lp.grid.1;
        let light = &self.shading().lights[lp.light as usize];
        // No shader runs within this call: the state stays as it is.
        let s = &self.state;
        let at = ([s.point, s.normal, s.shadow_point, s.normal_geom], s.time, lp.both_sides);
        while lp.next < count {
            let i = lp.next;
            lp.next += 1;
            lp.samples += 1;
            let mut k = i.wrapping_sub(lp.ahead_from);
            if k >= AHEAD as u32 || lp.ahead & (1 << k) == 0 || lp.ahead_for != at {
                self.find_ahead(lp, light, i, at);
                k = 0;
            }
            if lp.ahead_reach & (1 << k) == 0 {
                continue;
            }
            // The shader call this stands for.
            self.counts.calls += 1;
            if lp.ahead_lit & (1 << k) != 0 {
                let g = &lp.ahead_samples[k as usize];
                return Some(LightSample {
                    color: lp.ahead_colors[k as usize],
                    dir: g.to_light,
                    dot_nl: g.dot_nl,
                    dist: g.dist,
                });
            }
        }
        None
    }

    /// Sample `i`'s geometry and the answer to its shadow query, found ahead together
    /// with the next samples' (up to [`AHEAD`] from `i`, their shadow rays traced as one
    /// batch) when sample `i` was not.
    fn sample_ahead(
        &mut self,
        lp: &mut LightLoop,
        light: &ShadingLight,
        i: u32,
    ) -> (Option<SampleGeometry>, Option<ShadowHint>) {
        let s = &self.state;
        let at = ([s.point, s.normal, s.shadow_point, s.normal_geom], s.time, lp.both_sides);
        let mut k = i.wrapping_sub(lp.ahead_from);
        if k >= AHEAD as u32 || lp.ahead & (1 << k) == 0 || lp.ahead_for != at {
            self.find_ahead(lp, light, i, at);
            k = 0;
        }
        if lp.ahead_reach & (1 << k) == 0 {
            return (None, None);
        }
        let geometry = lp.ahead_samples[k as usize];
        let blocked = lp.ahead_blocked & (1 << k) != 0;
        let s = &self.state;
        let from = shadow_inputs(s.shadow_point, s.point_error, s.normal_geom, geometry.to_light, geometry.dist);
        (Some(geometry), Some(ShadowHint { time: s.time, blocked, from }))
    }

    /// Finds samples `i` to `i + AHEAD − 1` (those the loop has) of `lp` for the state
    /// `at` ([`LightLoop::ahead_for`]): their geometry, their shadow rays traced as one
    /// batch, and for a [`SimpleLight`] their colours.
    fn find_ahead(&mut self, lp: &mut LightLoop, light: &ShadingLight, i: u32, at: ([Vec3A; 4], f32, bool)) {
        lp.ahead_for = at;
        let count = lp.grid.0 * lp.grid.1;
        let mut queries = [ShadowQuery { org: Vec3A::ZERO, dir: Vec3A::ZERO, max_dist: 0.0 }; AHEAD];
        let mut lanes = [0usize; AHEAD];
        let mut n = 0;
        (lp.ahead_from, lp.ahead, lp.ahead_reach, lp.ahead_blocked, lp.ahead_lit) = (i, 0, 0, 0, 0);
        // The samples' numbers: eight at a time, or four when no more are left.
        let jitter = lp.pairs.map(|pairs| {
            if count - i > 4 {
                pairs.pairs8(i)
            } else {
                let four = pairs.pairs4(i);
                std::array::from_fn(|k| four[k % 4])
            }
        });
        // Sample j's cell of the light's grid, kept from sample to sample.
        let gu = lp.grid.0.max(1);
        let mut cell = (i % gu, i / gu);
        for j in i..count.min(i + AHEAD as u32) {
            let lane = (j - i) as usize;
            lp.ahead |= 1 << lane;
            let at_cell = cell;
            cell = if cell.0 + 1 == gu { (0, cell.1 + 1) } else { (cell.0 + 1, cell.1) };
            let Some(g) =
                self.sample_geometry_jittered(lp, light, j, jitter.as_ref().map(|jit| jit[lane]), Some(at_cell))
            else {
                continue;
            };
            lp.ahead_reach |= 1 << lane;
            lp.ahead_samples[lane] = g;
            if let Some(simple) = lp.simple {
                let (axis_cos, spread) = spot_inputs(&simple, light, g.to_light);
                let Some(color) = simple.unshadowed(g.dist, axis_cos, spread) else {
                    // Past the ramp's stop or outside the spot's cone: neither the light
                    // loop nor the shader (no light there either) asks for this ray.
                    continue;
                };
                lp.ahead_colors[lane] = color;
                lp.ahead_lit |= 1 << lane;
            }
            // The ray `trace_shadow` casts from this sample's light state.
            let org = crate::trace::leave_point(
                self.state.shadow_point,
                self.state.point_error,
                self.state.normal_geom,
                g.to_light,
            );
            let max_dist = if g.dist.is_finite() { g.dist * (1.0 - 1e-4) } else { f32::INFINITY };
            (queries[n], lanes[n]) = (ShadowQuery { org, dir: g.to_light, max_dist }, lane);
            n += 1;
        }
        let mut blocked = [false; AHEAD];
        self.tracer.shadow_blocked_batch(&queries[..n], self.state.time, &mut blocked[..n]);
        for (&lane, &b) in lanes[..n].iter().zip(&blocked[..n]) {
            lp.ahead_blocked |= u8::from(b) << lane;
        }
        if let Some(simple) = lp.simple {
            // What `simple_light_sample` makes of each lit sample and its shadow ray.
            for lane in 0..AHEAD {
                if lp.ahead_lit & (1 << lane) == 0 {
                    continue;
                }
                let through = lp.ahead_blocked & (1 << lane) == 0;
                match shadowed(lp.ahead_colors[lane], simple.factor, through, Color::ONE) {
                    Some(c) if c.x != 0.0 || c.y != 0.0 || c.z != 0.0 => lp.ahead_colors[lane] = c,
                    _ => lp.ahead_lit &= !(1 << lane),
                }
            }
        }
    }

    /// For a light shader: sends a shadow ray from the illuminated point to the light and
    /// lets the surfaces in between filter `color` with their shadow shaders (mental ray's
    /// `mi_trace_shadow`). Returns false when nothing gets through.
    ///
    /// Without shadow shaders in the scene the ray is an any-hit query. Once a light's
    /// shader has asked for one, the light loop traces the next samples' rays together
    /// ahead of their shader calls ([`Tracer::shadow_blocked_batch`], packets of eight) and
    /// this takes the answer of the ray that is exactly the one traced ahead; any other ray
    /// is traced here.
    ///
    /// [`Tracer::shadow_blocked_batch`]: crate::Tracer::shadow_blocked_batch
    pub fn trace_shadow(&mut self, color: &mut Color) -> bool {
        let shading = self.shading();
        if !shading.shadows {
            return true;
        }
        let s = &self.state;
        let to_light = -s.dir;
        let max_dist = if s.dist.is_finite() { s.dist * (1.0 - 1e-4) } else { f32::INFINITY };
        let tracer = self.tracer;
        // Shadow links: the walk must know which instance each surface belongs to.
        let linked = shading.has_shadow_links();
        if !shading.has_shadow_shaders() && !linked {
            // Every surface stops the light (no material filters it): the first surface
            // found on the way decides, with no need for the nearest one or its state.
            self.shadow_queried = true;
            let blocked = match self.shadow_hint.take() {
                // Traced ahead by the light loop: the same inputs, so the same ray bit for bit.
                Some(hint)
                    if hint.time == s.time
                        && same_bits(
                            &hint.from,
                            &shadow_inputs(s.shadow_point, s.point_error, s.normal_geom, to_light, s.dist),
                        ) =>
                {
                    hint.blocked
                }
                _ => {
                    let org = crate::trace::leave_point(s.shadow_point, s.point_error, s.normal_geom, to_light);
                    tracer.shadow_blocked(org, to_light, max_dist, s.time)
                }
            };
            if blocked {
                *color = Color::ZERO;
                return false;
            }
            return true;
        }
        self.media_walked = true;
        let org = crate::trace::leave_point(s.shadow_point, s.point_error, s.normal_geom, to_light);
        let mut ray = s.child(RayType::Shadow, org, to_light);
        ray.light = s.light;
        let mut filter = *color;
        let mut blocked = false;
        let mut calls = 0;
        let mut media = crate::volume::ShadowMedia::new(&ray);
        if !shading.has_surface_shadow_shaders() && !shading.has_varying_media() && !linked {
            // Only media boundaries let the light through (tinted where it enters): the
            // walk needs each surface's distance and material, not its shading state
            // (unless a medium entered varies over its surface).
            tracer.boundary_hits(&ray, max_dist, &mut |dist, material| {
                media.advance(shading, dist, &mut filter);
                // A material marked `opaque` stops the ray (mental ray).
                let opaque = material.and_then(|m| shading.materials.get(m as usize)).is_some_and(|m| m.opaque);
                blocked = opaque || !media.cross_material(shading, material, &mut filter);
                !blocked
            });
            if blocked {
                *color = Color::ZERO;
                return false;
            }
            media.advance(shading, max_dist - media.walked(), &mut filter);
            *color = filter;
            return true;
        }
        let light = s.light;
        // The receiving instance, the distance walked along the ray, and where the ray
        // last entered the receiving instance (it starts on it): for `State::inside_own`.
        let own = s.instance;
        let mut walked = 0.0f32;
        let mut entered = 0.0f32;
        tracer.shadow_hits(&ray, max_dist, &mut |hit: &State| {
            media.advance(shading, hit.dist, &mut filter);
            walked += hit.dist;
            let mut inside_own = None;
            if hit.instance == own {
                if hit.inv_normal {
                    inside_own = Some(walked - entered);
                } else {
                    entered = walked;
                }
            }
            if !shading.casts_shadow_for(hit.instance, light) {
                // Shadow linking: this object casts no shadow for the light; the ray
                // passes it (entering or leaving its medium, if it has one).
                media.pass(shading, hit);
                return true;
            }
            let material = hit.material.and_then(|m| shading.materials.get(m as usize));
            if material.is_some_and(|m| m.opaque) {
                // Marked `opaque`: it stops the ray without its shadow shader (mental ray).
                blocked = true;
                return false;
            }
            let shader = material.and_then(|m| m.shadow);
            let Some(shader) = shader else {
                if media.cross(shading, hit, &mut filter) {
                    return true;
                }
                blocked = true;
                return false;
            };
            let mut at = hit.clone();
            at.inside_own = inside_own;
            let mut ctx = Ctx::new(shading, tracer, at);
            let mut result = Value::Color(filter);
            let ok = ctx.run_list(shader, &mut result);
            calls += ctx.counts.calls;
            filter = result.color();
            if !ok || (filter.x <= 0.0 && filter.y <= 0.0 && filter.z <= 0.0) {
                blocked = true;
                return false;
            }
            // Through: the ray enters or leaves the surface's medium, if it has one.
            media.pass(shading, hit);
            true
        });
        self.counts.calls += calls;
        if blocked {
            *color = Color::ZERO;
            return false;
        }
        // The last stretch, to the light.
        media.advance(shading, max_dist - media.walked(), &mut filter);
        *color = filter;
        true
    }
}

/// What a shadow ray's origin, direction and reach are made of (see
/// [`ShadowHint::from`]): the shading point's `shadow_point` and `point_error`, its
/// geometric normal and the distance, and the unit direction to the light.
#[inline(always)]
fn shadow_inputs(shadow_point: Vec3A, point_error: f32, normal_geom: Vec3A, to_light: Vec3A, dist: f32) -> [Vec4; 3] {
    [shadow_point.extend(point_error), normal_geom.extend(dist), to_light.extend(0.0)]
}

/// Whether `a` and `b` hold the same bits (unlike `==`, which takes -0 for 0).
#[inline(always)]
fn same_bits(a: &[Vec4; 3], b: &[Vec4; 3]) -> bool {
    let bits = |v: &[Vec4; 3]| v.map(|v| v.to_array().map(f32::to_bits));
    bits(a) == bits(b)
}
