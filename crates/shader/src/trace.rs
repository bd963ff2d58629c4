//! Rays cast by shaders: reflection, refraction, transparency, environment lookups, final
//! gathering (mental ray's `mi_trace_*`, `mi_reflection_dir`, `mi_refraction_dir`,
//! `mi_compute_irradiance`), with the options' trace-depth limits.
//!
//! A traced ray that hits a surface runs that surface's material shader list in a fresh
//! context and returns its colour; a ray that hits nothing runs the environment shader (the
//! material's, else the camera's). Depth limits: reflection rays beyond `trace depth`'s
//! reflection limit, refraction and transparency rays beyond its refraction limit, and any
//! ray beyond the sum limit are not cast (the call returns `None`).

use glam::Vec3A;

use super::ctx::Ctx;
use super::state::{RayType, State};
use super::value::{Color, Value};
use bsdf::Frame;

/// Moves a surface point off the surface along its geometric normal `n` (towards the side
/// `dir` leaves to), by a few ulps of the coordinates: no fixed epsilon, so it works at
/// every scene scale (Wächter and Binder, "A fast and robust method for avoiding
/// self-intersection", Ray Tracing Gems, 2019).
#[inline]
pub fn offset_point(p: Vec3A, n: Vec3A, dir: Vec3A) -> Vec3A {
    let n = if n.dot(dir) < 0.0 { -n } else { n };
    #[cfg(target_arch = "x86_64")]
    if let Some(q) = offset_point_sse2(p, n) {
        return q;
    }
    offset_point_scalar(p, n)
}

/// [`offset_point`]'s parameters: points this close to the origin move by a fixed step
/// (`FLOAT_SCALE` × the normal), the others by `INT_SCALE` × the normal in ulps.
const ORIGIN: f32 = 1.0 / 32.0;
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
const INT_SCALE: f32 = 256.0;

/// [`offset_point`] for a normal `n` already facing the side the ray leaves to, one
/// coordinate at a time.
#[inline]
fn offset_point_scalar(p: Vec3A, n: Vec3A) -> Vec3A {
    let of_i = [(INT_SCALE * n.x) as i32, (INT_SCALE * n.y) as i32, (INT_SCALE * n.z) as i32];
    let step = |p: f32, o: i32| {
        let bits = p.to_bits() as i32;
        f32::from_bits(bits.wrapping_add(if p < 0.0 { -o } else { o }) as u32)
    };
    let p_i = Vec3A::new(step(p.x, of_i[0]), step(p.y, of_i[1]), step(p.z, of_i[2]));
    Vec3A::new(
        if p.x.abs() < ORIGIN { p.x + FLOAT_SCALE * n.x } else { p_i.x },
        if p.y.abs() < ORIGIN { p.y + FLOAT_SCALE * n.y } else { p_i.y },
        if p.z.abs() < ORIGIN { p.z + FLOAT_SCALE * n.z } else { p_i.z },
    )
}

/// [`offset_point_scalar`] with the three coordinates in one SSE2 vector (every x86-64 CPU
/// has SSE2): the same numbers bit for bit. `None` — the caller then goes coordinate by
/// coordinate — where a lane of `INT_SCALE · n` is NaN or outside the range of `i32`,
/// which the vector conversion does not saturate as Rust's `as` does (never for the unit
/// normals the renderers pass).
#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code)]
#[inline]
fn offset_point_sse2(p: Vec3A, n: Vec3A) -> Option<Vec3A> {
    use std::arch::x86_64::*;
    let (pv, nv): (__m128, __m128) = (p.into(), n.into());
    // SAFETY: these intrinsics need SSE and SSE2 only, part of every x86-64 CPU (the
    // target's baseline).
    unsafe {
        let scaled = _mm_mul_ps(_mm_set1_ps(INT_SCALE), nv);
        // |x| < 2^31 (false for NaN): the truncation is then exact where `as i32`'s is.
        let magnitude = _mm_andnot_ps(_mm_set1_ps(-0.0), scaled);
        let in_range = _mm_cmplt_ps(magnitude, _mm_set1_ps(2_147_483_648.0));
        if _mm_movemask_ps(in_range) & 0b111 != 0b111 {
            return None;
        }
        let of_i = _mm_cvttps_epi32(scaled);
        // −o where p < 0 (a lane mask of all ones: o ^ −1 − −1 = −o, wrapping), o elsewhere.
        let negative = _mm_castps_si128(_mm_cmplt_ps(pv, _mm_setzero_ps()));
        let signed = _mm_sub_epi32(_mm_xor_si128(of_i, negative), negative);
        let p_i = _mm_castsi128_ps(_mm_add_epi32(_mm_castps_si128(pv), signed));
        let near = _mm_cmplt_ps(_mm_andnot_ps(_mm_set1_ps(-0.0), pv), _mm_set1_ps(ORIGIN));
        let p_f = _mm_add_ps(pv, _mm_mul_ps(_mm_set1_ps(FLOAT_SCALE), nv));
        Some(Vec3A::from(_mm_or_ps(_mm_and_ps(near, p_f), _mm_andnot_ps(near, p_i))))
    }
}

/// [`offset_point`] of `p` after a step of `err` along `n`, towards the side `dir` leaves
/// to: past the hit point's rounding error (which the ulps of `p` alone do not bound; see
/// [`hit_error`]), so that the ray cannot find the surface it leaves again — neither the
/// triangle itself nor a neighbour across a shared edge. Both engines leave surfaces here.
#[inline]
pub fn leave_point(p: Vec3A, err: f32, n: Vec3A, dir: Vec3A) -> Vec3A {
    let n = if n.dot(dir) < 0.0 { -n } else { n };
    offset_point(p + n * err, n, dir)
}

/// A bound on how far a hit point on the triangle `p0 p1 p2` (object space), placed by
/// `to_world`, lies off the triangle and its neighbours as the ray–triangle test sees
/// them (world units): the test and the barycentric sum round in units of the vertices'
/// coordinates (and the placement's), not of the point's own, so on a large triangle the
/// point's ulps are far too small — a point near the origin on a 100-unit mirror split in
/// two lay behind its neighbour's plane, and the path engine's mirror ray found the
/// neighbour at t ≈ 1e-5; the classic engine's transparency rays through a 75° tilted
/// 150-unit plane found the same triangle again at t ≈ 3e-7 (from 1.4e-6 behind it).
/// [`HIT_ERROR_ULPS`] of the largest coordinate involved.
#[inline]
pub fn hit_error(p0: Vec3A, p1: Vec3A, p2: Vec3A, to_world: &glam::Affine3A) -> f32 {
    let reach = p0.abs().max(p1.abs()).max(p2.abs());
    let m = &to_world.matrix3;
    let world =
        m.x_axis.abs() * reach.x + m.y_axis.abs() * reach.y + m.z_axis.abs() * reach.z + to_world.translation.abs();
    HIT_ERROR_ULPS * f32::EPSILON * world.max_element()
}

/// The multiple of the largest coordinate's relative rounding (`f32::EPSILON`) a hit point
/// is taken to be off its surface by ([`hit_error`]): Möller–Trumbore's t rounds by a few
/// of them (measured: self-hits up to 2.5 ε × the coordinates along the ray).
pub const HIT_ERROR_ULPS: f32 = 16.0;

impl Ctx<'_> {
    /// Whether a ray of `kind` may leave this state under the depth limits.
    pub fn may_trace(&self, kind: RayType) -> bool {
        let d = self.shading().depth;
        let s = &self.state;
        let sum = s.reflection_level + s.refraction_level;
        if !self.shading().trace || sum >= d.sum {
            return false;
        }
        match kind {
            RayType::Reflect => s.reflection_level < d.reflect,
            RayType::Refract | RayType::Transparent => s.refraction_level < d.refract,
            _ => true,
        }
    }

    /// The mirror direction of the ray about the shading normal (mental ray's
    /// `mi_reflection_dir`).
    pub fn reflection_dir(&self) -> Vec3A {
        let d = self.state.dir;
        let n = self.state.normal;
        (d - 2.0 * d.dot(n) * n).normalize_or(n)
    }

    /// The refracted direction for indices `ior_in` (the side the ray comes from) and
    /// `ior_out`, or `None` under total internal reflection (mental ray's
    /// `mi_refraction_dir`).
    pub fn refraction_dir(&self, ior_in: f32, ior_out: f32) -> Option<Vec3A> {
        refract(self.state.dir, self.state.normal, ior_in / ior_out)
    }

    /// Traces a reflection ray along `dir` (unit). `None` if the depth limit forbids it.
    pub fn trace_reflection(&mut self, dir: Vec3A) -> Option<Color> {
        if !self.may_trace(RayType::Reflect) {
            return None;
        }
        Some(self.trace(RayType::Reflect, dir))
    }

    /// Traces a refraction ray along `dir` (unit); the ray enters (or leaves) the current
    /// material with index of refraction `state.ior`.
    pub fn trace_refraction(&mut self, dir: Vec3A) -> Option<Color> {
        if !self.may_trace(RayType::Refract) {
            return None;
        }
        Some(self.trace(RayType::Refract, dir))
    }

    /// Continues the ray straight through the surface.
    pub fn trace_transparent(&mut self) -> Option<Color> {
        if !self.may_trace(RayType::Transparent) {
            return None;
        }
        Some(self.trace(RayType::Transparent, self.state.dir))
    }

    /// Casts a ray of `kind` along `dir` no farther than `max_dist` (depth limits
    /// permitting; `None` if they forbid it): the colour found and the distance travelled,
    /// infinite when nothing was hit (the colour is then the environment's, or black when
    /// the distance is limited, since the ray stopped short of it).
    pub fn cast(&mut self, kind: RayType, dir: Vec3A, max_dist: f32) -> Option<(Color, f32)> {
        if !self.may_trace(kind) {
            return None;
        }
        let c = self.trace_limited(kind, dir, max_dist);
        Some((c, self.state.child_dist))
    }

    /// Casts a ray of `kind` and shades what it finds.
    fn trace(&mut self, kind: RayType, dir: Vec3A) -> Color {
        self.trace_limited(kind, dir, f32::INFINITY)
    }

    fn trace_limited(&mut self, kind: RayType, dir: Vec3A, max_dist: f32) -> Color {
        let s = &self.state;
        let org = leave_point(s.point, s.point_error, s.normal_geom, dir);
        let mut child = s.child(kind, org, dir);
        // Crossing the surface: enter or leave the material's medium.
        if matches!(kind, RayType::Refract | RayType::Transparent) {
            if let Some(m) = s.material {
                if s.inside(m) {
                    child.leave(m);
                } else {
                    let medium = super::state::Medium { material: m, ior: s.ior };
                    // A volume that varies over the surface: the one where the ray enters.
                    match self.shading().materials.get(m as usize).and_then(|x| x.varying_medium.as_ref()) {
                        Some(varying) => child.enter_evaluated(medium, varying.at(s)),
                        None => child.enter(medium),
                    }
                }
                child.ior_in = child.medium().map_or(1.0, |x| x.ior);
            }
        }
        let (color, dist) = self.shade_ray(child, max_dist);
        self.state.child_dist = dist;
        color
    }

    /// Shades the first surface along `ray` within `max_dist` (material shader) or, if
    /// none, the environment (transparent black when the distance is limited), then runs
    /// the volume shader of the medium the ray travelled in over the segment
    /// ([`super::volume`]). Returns the colour and the distance travelled (infinite on a
    /// miss).
    pub fn shade_ray(&mut self, mut ray: State, max_dist: f32) -> (Color, f32) {
        let shading = self.shading();
        if self.tracer.intersect(&mut ray, max_dist) {
            let dist = ray.dist;
            let shader = ray.material.and_then(|m| shading.materials.get(m as usize)).and_then(|m| m.surface);
            let Some(shader) = shader else { return (Color::new(0.0, 0.0, 0.0, 1.0), dist) };
            // The segment for the volume shader, if one applies.
            let segment = self.has_volume(&ray).then(|| ray.clone());
            let mut ctx = Ctx::new(shading, self.tracer, ray);
            let mut result = Value::Color(Color::ZERO);
            ctx.run_list(shader, &mut result);
            self.counts.calls += ctx.counts.calls;
            let c = result.color();
            (segment.map_or(c, |s| self.ray_volume(&s, true, c)), dist)
        } else if max_dist.is_finite() {
            (Color::ZERO, f32::INFINITY)
        } else {
            let segment = self.has_volume(&ray).then(|| ray.clone());
            let c = self.environment(ray);
            (segment.map_or(c, |s| self.ray_volume(&s, false, c)), f32::INFINITY)
        }
    }

    /// Casts an eye ray from `org` along unit `dir` (mental ray's `mi_trace_eye`): the next
    /// lens shader runs if there is one, else the ray is shaded. The distance the ray
    /// travelled (as the last lens shader saw it; infinite on a miss) is left in
    /// `state.child_dist`.
    pub fn trace_eye(&mut self, org: Vec3A, dir: Vec3A) -> Color {
        let shading = self.shading();
        let mut ray = self.state.child(RayType::Eye, org, dir);
        ray.reflection_level = self.state.reflection_level;
        if let Some(&lens) = shading.lens.get(self.state.lens_next as usize) {
            ray.lens_next = self.state.lens_next + 1;
            ray.point = org;
            let mut ctx = Ctx::new(shading, self.tracer, ray);
            let mut result = Value::Color(Color::ZERO);
            ctx.call(lens, &mut result);
            self.counts.calls += ctx.counts.calls;
            self.state.child_dist = ctx.state.child_dist;
            return result.color();
        }
        let (c, dist) = self.shade_ray(ray, f32::INFINITY);
        self.state.child_dist = dist;
        c
    }

    /// Runs the environment shader for direction `dir` (mental ray's
    /// `mi_trace_environment`): the current material's, else the camera's; black if none.
    pub fn trace_environment(&mut self, dir: Vec3A) -> Color {
        let ray = self.state.child(RayType::Environment, self.state.point, dir);
        self.environment(ray)
    }

    fn environment(&mut self, mut ray: State) -> Color {
        let shading = self.shading();
        let material_env =
            self.state.material.and_then(|m| shading.materials.get(m as usize)).and_then(|m| m.environment);
        let Some(shader) = material_env.or(shading.environment) else { return Color::ZERO };
        ray.ray_type = RayType::Environment;
        ray.point = ray.org;
        ray.dist = 0.0;
        ray.material = self.state.material;
        let mut ctx = Ctx::new(shading, self.tracer, ray);
        let mut result = Value::Color(Color::ZERO);
        ctx.run_list(shader, &mut result);
        self.counts.calls += ctx.counts.calls;
        result.color()
    }

    /// Indirect illumination at the point (mental ray's `mi_compute_irradiance`): the
    /// irradiance E = ∫ L cos θ dω over the hemisphere of the shading normal. At the first
    /// diffuse bounce it is interpolated from the render's final gather points where one is
    /// valid ([`super::fgcache`]); elsewhere it is estimated with cosine-distributed gather
    /// rays (π × their mean radiance). As in mental ray it is not divided by π: the base
    /// shaders' `diffuse ⊙ irradiance` is π times the physically correct Lambertian term,
    /// matching their direct term, which has no 1/π either. Zero when final gathering is
    /// off or its diffuse depth is used up. With photon maps, the caustic and global
    /// illumination estimates join in ([`Ctx::photon_irradiance`]).
    pub fn compute_irradiance(&mut self) -> Color {
        match self.shading().photons.get() {
            Some(maps) => self.photon_irradiance(maps),
            None => self.final_gather_irradiance(),
        }
    }

    /// The final gathering part of [`Ctx::compute_irradiance`]: zero when final gathering
    /// is off or its diffuse depth is used up.
    pub fn final_gather_irradiance(&mut self) -> Color {
        let fg = self.shading().finalgather;
        if !fg.enabled || self.state.finalgather_level > fg.diffuse_depth {
            return Color::ZERO;
        }
        let primary = self.state.finalgather_level == 0 && self.state.ray_type != RayType::Finalgather;
        let cached = if primary {
            self.tracer.fg_cache().and_then(|c| c.lookup(self.state.point, self.state.normal))
        } else {
            None
        };
        let e = match cached {
            Some(e) => e,
            None => self.gather(if primary { fg.rays } else { fg.secondary_rays }).0,
        };
        Color::new(e.x * fg.scale.x, e.y * fg.scale.y, e.z * fg.scale.z, 1.0)
    }

    /// Gathers irradiance at the point with `n` cosine-distributed rays about the shading
    /// normal: (π × their mean radiance, before `finalgather scale`; the harmonic mean
    /// distance to what the rays that hit something hit, infinite when every ray escaped).
    /// Final gather points of the interpolation cache are made with it.
    pub fn gather(&mut self, n: u32) -> (Color, f32) {
        let fg = self.shading().finalgather;
        let n = n.max(1);
        let frame = Frame::from_normal(self.state.normal);
        let site = self.next_site();
        let mut sum = Color::ZERO;
        let (mut inverse_dist, mut hits) = (0.0f64, 0u32);
        for i in 0..n {
            let u = self.sample2(site, i, n);
            let local = bsdf::cosine_hemisphere(u);
            let dir = frame.to_world(local);
            if dir.dot(self.state.normal_geom) <= 0.0 {
                continue;
            }
            let org = leave_point(self.state.point, self.state.point_error, self.state.normal_geom, dir);
            let ray = self.state.child(RayType::Finalgather, org, dir);
            let max = fg.max_dist.unwrap_or(f32::INFINITY);
            let (c, dist) = self.shade_ray(ray, max);
            if dist > 0.0 && dist.is_finite() {
                inverse_dist += 1.0 / f64::from(dist);
                hits += 1;
            }
            if self.shading().blocks_gather(org, dir, dist) {
                // A portal light brings this light in directly.
                continue;
            }
            let c = if dist.is_infinite() && fg.max_dist.is_some() {
                // Past the falloff distance: the environment.
                self.trace_environment(dir)
            } else {
                c
            };
            sum += c;
        }
        let mean_dist = if hits > 0 { (f64::from(hits) / inverse_dist) as f32 } else { f32::INFINITY };
        let e = sum * (std::f32::consts::PI / n as f32);
        (Color::new(e.x, e.y, e.z, 1.0), mean_dist)
    }

    /// A cosine-weighted direction about the shading normal (for shaders sampling the
    /// hemisphere themselves).
    pub fn cosine_dir(&mut self, site: u32, i: u32, n: u32) -> Vec3A {
        let u = self.sample2(site, i, n);
        Frame::from_normal(self.state.normal).to_world(bsdf::cosine_hemisphere(u))
    }
}

/// Refraction of unit direction `d` at unit normal `n` (facing against `d`) with relative
/// index `eta` = n_in / n_out; `None` under total internal reflection.
pub fn refract(d: Vec3A, n: Vec3A, eta: f32) -> Option<Vec3A> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((d * eta + n * (eta * cos_i - cos_t)).normalize())
}

impl Ctx<'_> {
    /// The distance to the first surface along `dir` from the point (any object, no
    /// shading), `None` if nothing is closer than `max_dist` (mental ray's `mi_trace_probe`).
    pub fn probe(&mut self, dir: Vec3A, max_dist: f32) -> Option<f32> {
        let org = leave_point(self.state.point, self.state.point_error, self.state.normal_geom, dir);
        let mut ray = self.state.child(RayType::Probe, org, dir);
        self.tracer.intersect(&mut ray, max_dist).then_some(ray.dist)
    }
}

impl Ctx<'_> {
    /// `compute_irradiance` with photon maps: the caustic estimate, plus indirect light from
    /// the global map where there is one and this point is not a final gather point (a
    /// final gather ray's hit, or any point when final gathering is off, looks the global
    /// map up instead of gathering further, as mental ray does); otherwise what final
    /// gathering finds.
    pub fn photon_irradiance(&mut self, maps: &crate::photonmap::PhotonMaps) -> Color {
        let (p, n) = (self.state.point, self.state.normal);
        let caustic = maps.caustic_irradiance(p, n);
        let fg = self.shading().finalgather;
        let at_gather_hit = self.state.ray_type == RayType::Finalgather || self.state.finalgather_level > 0;
        let indirect = match maps.global_irradiance(p, n) {
            Some(e) if !fg.enabled || at_gather_hit => e,
            _ => crate::rgb(self.final_gather_irradiance()),
        };
        let e = caustic + indirect;
        Color::new(e.x, e.y, e.z, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The vector [`offset_point`] gives the coordinate-by-coordinate numbers bit for bit:
    /// points near the origin and far, of both signs, zeros of both signs, subnormals,
    /// normals of every direction (NaN and huge lanes fall back to the scalar code).
    #[test]
    fn offset_point_equals_its_scalar_form() {
        let mut z = 0x0123_4567_89ab_cdefu64;
        let mut next = move || {
            z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut x = z;
            x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            x ^ (x >> 31)
        };
        let specials = [0.0, -0.0, 1e-40, -1e-40, 1.0 / 32.0, -1.0 / 32.0, 0.031, 1e30, -1e30, 278.0, -548.8];
        for i in 0..200_000 {
            let mut coordinate = |k: u64| {
                let r = next();
                if i % 7 == 0 {
                    specials[(r % specials.len() as u64) as usize]
                } else {
                    // Magnitudes from 1e-6 to 1e6, both signs.
                    let m = 10f32.powf((r >> 11) as f32 / (1u64 << 53) as f32 * 12.0 - 6.0);
                    if (r >> k) & 1 == 0 {
                        m
                    } else {
                        -m
                    }
                }
            };
            let p = Vec3A::new(coordinate(1), coordinate(2), coordinate(3));
            let n = Vec3A::new(coordinate(4), coordinate(5), coordinate(6)).normalize_or(Vec3A::Z);
            let n = if i % 11 == 0 { n * 1e6 } else { n };
            let dir = Vec3A::new(coordinate(7), coordinate(8), coordinate(9));
            let facing = if n.dot(dir) < 0.0 { -n } else { n };
            let want = offset_point_scalar(p, facing);
            let got = offset_point(p, n, dir);
            assert_eq!(got.to_array().map(f32::to_bits), want.to_array().map(f32::to_bits), "{p:?} {n:?} {dir:?}");
        }
        let nan = Vec3A::new(f32::NAN, 0.0, 1.0);
        assert_eq!(
            offset_point(Vec3A::ONE, nan, Vec3A::Z).y.to_bits(),
            offset_point_scalar(Vec3A::ONE, nan).y.to_bits()
        );
    }

    #[test]
    fn refraction_obeys_snell_and_total_internal_reflection() {
        let n = Vec3A::Z;
        let theta = 30f32.to_radians();
        let d = Vec3A::new(theta.sin(), 0.0, -theta.cos());
        let t = refract(d, n, 1.0 / 1.5).unwrap();
        assert!((t.x - theta.sin() / 1.5).abs() < 1e-6);
        assert!(t.z < 0.0);
        // From glass to air past the critical angle asin(1/1.5) = 41.8°.
        let steep = 42f32.to_radians();
        let d = Vec3A::new(steep.sin(), 0.0, -steep.cos());
        assert!(refract(d, n, 1.5).is_none());
        let shallow = 41f32.to_radians();
        let d = Vec3A::new(shallow.sin(), 0.0, -shallow.cos());
        assert!(refract(d, n, 1.5).is_some());
    }
}
