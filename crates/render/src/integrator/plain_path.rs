//! A compact path loop for the commonest paths: every surface they meet is *plain* — a
//! constant, opaque, Lambertian material without a bump or normal map or tangent, without
//! a matte, ambient light, cut-out or environment of its own ([`plain_materials`]) — in a
//! scene without media or fogs. Its state (throughput, ray, the last bounce's density,
//! depth) is a few values the compiler keeps in registers; the general loop
//! (`trace_camera_path_into`) keeps a far larger state in memory, and the rare branches
//! it carries cost every bounce.
//!
//! The kernel hands the path over to the general loop ([`Resume`]) the moment its ray
//! finds anything else (a surface that is not plain): the general loop
//! goes on from that bounce, with the hit already found, as if it had traced the path from
//! the camera. Every number is the general loop's for the same bounce, computed by the same
//! formulas in the same order (`lambert_hit` for the lobe), so images do not change.

use bsdf::{Bsdf, Frame, Rgb};
use shader::Shading;

use super::cutout::linked_shadow_passed;
use super::hit_surface::{surface_into, Surface};
use super::media::{self, Departure, MediumStack};
use super::path_state::{RadianceSum, Resume};
use super::{emitters::environment_seen, env_light, lambert_hit, light_radiance, power_heuristic, roulette_survival};
use super::{CameraRay, PathResult, PathScene, PathSettings, PendingShadow, Vertex};
use crate::accel::Hit;
use crate::light::LightSource;
use crate::ray::{mask, FirstHit, Ray, RayCounts};
use crate::sampler::Sampler;
use crate::world::World;

/// For each material of `world` (as [`World::materials`]), whether the plain kernel may
/// trace its hits with the scene's shader graph `shading`: constant (no connected
/// parameters read at the hit, no view-dependent transparency), opaque, one Lambertian
/// lobe without a bump or normal map or tangent, no Maya matte, no ambient light on it, no
/// environment of its own. Empty (no material is plain) when the scene has media or fogs.
pub fn plain_materials(world: &World, shading: Option<&Shading>) -> Vec<bool> {
    if world.has_media || shading.is_some_and(|s| s.has_affine_volumes()) {
        return Vec::new();
    }
    let plain = |(i, m): (usize, &material::SurfaceMaterial)| {
        let constant = !(shading.is_some() && m.is_varying()) && m.view_transparency.is_none();
        constant
            && m.opacity >= 1.0
            && !m.model.refracts()
            && m.maya_matte.is_none()
            && (world.ambient.is_empty() || m.ambient == Rgb::ZERO)
            && super::material_env::own(shading, i as u32).is_none()
            && lambert_hit::is_lambert(&m.constant())
    };
    world.materials.iter().enumerate().map(plain).collect()
}

/// Traces `camera`'s path while it meets only plain surfaces (see the module): `None`
/// when the path ends there (its result written to `out`); else the state to go on from
/// where it met anything else. The caller checks that the scene has plain materials and
/// that the camera is in no medium.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(super) fn trace(
    scene: &PathScene,
    camera: &CameraRay,
    camera_media: &MediumStack,
    sampler: &mut Sampler,
    settings: &PathSettings,
    counts: &mut RayCounts,
    out: &mut PathResult,
) -> Option<Resume> {
    let PathScene { world, accel, shading, env, constants, plain } = *scene;
    let mut ray = camera.ray;
    let mut throughput = Rgb::ONE;
    let mut radiance = RadianceSum::ZERO;
    let mut pending: Option<Ray> = None;
    let (mut first, mut glow, mut alpha) = (None, None, 0.0f32);
    let (mut last_pdf, mut last_delta) = (0.0f32, true);
    let mut from_instance: Option<u32> = None;
    let light_count = world.lights.len();
    let choices = light_count + usize::from(env.is_some_and(|e| e.sampled));
    let pick = if choices > 0 { 1.0 / choices as f32 } else { 0.0 };
    let seed = sampler.stream();
    let mut s = Surface::UNSET;
    let mut depth = 0;
    // The ray counts, added to `counts` when the kernel stops.
    let (mut rays, mut shadow_rays) = (0u64, 0u64);
    // What the current ray finds (traced at the end of the bounce before: no `Option` of
    // a known hit to take at every bounce).
    let mut h = match camera.hit {
        Some(found) => found,
        None if settings.max_depth > 0 => accel.intersect(&ray),
        None => None,
    };
    // `Some(found)`: handed over at `depth` with the ray's hit found; `None`: the path ended.
    let handed: Option<Option<Hit>> = loop {
        if depth >= settings.max_depth {
            break None;
        }
        // The distance to what the ray found (along it, as the general loop's cut-out loop
        // gives it): a plain surface, or nothing.
        let t = match &h {
            Some(h) => {
                surface_into(world, &ray, h, &mut s);
                if !plain.get(s.material as usize).copied().unwrap_or(false) {
                    break Some(Some(*h));
                }
                (s.p - ray.origin).dot(ray.dir)
            }
            None => ray.tmax,
        };
        rays += 1;
        if let Some((li, lt, le)) = nearest_light(&world.lights, &ray, t, depth == 0) {
            let le = light_radiance(&world.lights[li], le, env, ray.dir);
            if depth == 0 {
                alpha = 1.0;
            }
            let linked = from_instance.is_none_or(|i| world.lights_instance(li, i));
            let weight = if !linked {
                0.0
            } else if depth == 0 || last_delta {
                1.0
            } else if settings.mis {
                power_heuristic(last_pdf, pick * world.lights[li].pdf_at(ray.origin, ray.dir, lt, ray.time))
            } else {
                0.0
            };
            radiance += throughput * le * weight;
            break None;
        }
        let Some(found) = h else {
            // Left the scene: the environment.
            if let Some(env) = env {
                let le = environment_seen(env, &ray, depth, (last_pdf, last_delta), pick, settings.mis);
                if depth == 0 && le != Rgb::ZERO {
                    alpha = 1.0;
                }
                radiance += throughput * le;
            }
            break None;
        };
        let stop = Hit { t, ..found };
        let material = &constants[s.material as usize];
        if depth == 0 {
            alpha = 1.0;
            let motion = crate::tracer::hit_motion(world, &stop, s.p, ray.time);
            first = Some(FirstHit { point: s.p, normal: s.ns, tag: s.tag, motion });
            glow = Some(material.glow);
        }
        if material.emission != Rgb::ZERO {
            let spread =
                material.emission_shape.as_deref().map_or(Rgb::ONE, |e| e.factor(s.ns, material.tangent, -ray.dir));
            radiance += throughput * material.emission * spread;
        }
        let (ng, ns) = if s.ng.dot(ray.dir) <= 0.0 { (s.ng, s.ns) } else { (-s.ng, -s.ns) };
        let frame = Frame::from_normal(ns);
        let wo = frame.to_local(-ray.dir);
        let departure = || Departure { media: camera_media, surface: Some((s.material, s.ng, &ray, &stop)) };
        let choice = sampler.next_1d();
        let u_light = sampler.next_2d();
        let mis = settings.mis && depth + 1 < settings.max_depth;
        let k = if choices <= 1 { 0 } else { ((choice * choices as f32) as usize).min(choices - 1) };
        if let (Some(env), true) = (env, k == light_count && choices > light_count) {
            let bsdf = Bsdf::Lambert(bsdf::Lambert { albedo: material.diffuse });
            let v = Vertex {
                p: s.p,
                err: s.err,
                time: ray.time,
                ng,
                frame: &frame,
                wo,
                bsdf: &bsdf,
                departure: departure(),
            };
            radiance += throughput
                * env_light::environment_light(
                    world,
                    accel,
                    shading,
                    env,
                    &v,
                    pick,
                    (u_light, sampler),
                    seed,
                    mis,
                    counts,
                );
        } else if k < light_count && world.lights_instance(k, stop.instance) {
            let light = &world.lights[k];
            if let Some(ls) = light.sample_at(s.p, u_light, ray.time) {
                // (Kept apart from `ls`, which is not written to: the shadow ray reads
                // only its direction, distance and delta.)
                let l_radiance = light_radiance(light, ls.radiance, env, ls.wi);
                let wi = frame.to_local(ls.wi);
                let f = lambert_hit::eval(material.diffuse, wo, wi, light.lobes);
                if (ls.wi.dot(ng) > 0.0) == (wi.z > 0.0) && f != Rgb::ZERO && l_radiance != Rgb::ZERO {
                    let (dir, dist) = light.shadow_ray_at(s.p, &ls, u_light, ray.time);
                    let origin = s.leave(ng, dir);
                    let tmax = if dist.is_finite() { dist * (1.0 - 1e-4) } else { f32::INFINITY };
                    shadow_rays += 1;
                    let shadow = Ray { mask: mask::SHADOW, origin, dir, tmin: 0.0, tmax, time: ray.time };
                    let defer = depth == 0
                        && camera.defer_shadow
                        && light.shadow
                        && light.shadow_color == Rgb::ZERO
                        && !world.has_media
                        && !world.has_cutouts
                        && world.shadow_unlinked.is_empty();
                    let unshadowed = if defer {
                        pending = Some(shadow);
                        Rgb::ONE
                    } else if light.shadow && !world.shadow_unlinked.is_empty() && !world.has_media {
                        linked_shadow_passed(world, accel, shading, &shadow, seed, (k, Some(stop.instance)))
                    } else if light.shadow && !world.has_media && !world.has_cutouts {
                        // (What `light_transmittance` gives here, asked directly.)
                        if accel.occluded(&shadow) {
                            Rgb::ZERO
                        } else {
                            Rgb::ONE
                        }
                    } else {
                        media::light_transmittance(
                            world,
                            accel,
                            shading,
                            &departure(),
                            &shadow,
                            seed,
                            light.shadow,
                            Some(k),
                        )
                    };
                    let tr = if light.shadow && light.shadow_color != Rgb::ZERO {
                        unshadowed + (Rgb::ONE - unshadowed) * light.shadow_color
                    } else {
                        unshadowed
                    };
                    if tr != Rgb::ZERO {
                        let weight = if ls.delta || !mis {
                            1.0
                        } else {
                            power_heuristic(pick * ls.pdf, lambert_hit::pdf(wo, wi))
                        };
                        let term = throughput * f * l_radiance * tr * (wi.z.abs() * weight / (pick * ls.pdf));
                        if defer {
                            radiance.lit += term;
                        } else {
                            radiance += term;
                        }
                    }
                }
            }
        }
        // Scatter (the lobe's number is drawn, as the general loop draws it, and unused).
        let u_dir = sampler.next_2d();
        let _ = sampler.next_1d();
        let Some(bs) = lambert_hit::sample(material.diffuse, wo, u_dir) else { break None };
        let wi = frame.to_world(bs.wi);
        if (bs.wi.z > 0.0) != (wi.dot(ng) > 0.0) {
            break None;
        }
        let bounce_weight = bs.weight();
        throughput *= bounce_weight;
        from_instance = Some(stop.instance);
        last_pdf = bs.pdf;
        last_delta = bs.delta;
        let u_rr = sampler.next_1d();
        if depth + 1 >= settings.rr_depth {
            let q = roulette_survival(bounce_weight);
            if q.is_nan() || q <= 0.0 || u_rr >= q {
                break None;
            }
            throughput /= q;
        }
        ray = Ray {
            mask: mask::SECONDARY,
            origin: s.leave(ng, wi),
            dir: wi,
            tmin: 0.0,
            tmax: f32::INFINITY,
            time: ray.time,
        };
        depth += 1;
        if depth < settings.max_depth {
            h = accel.intersect(&ray);
        }
    };
    counts.rays += rays;
    counts.shadow_rays += shadow_rays;
    match handed {
        None => {
            // (No fog: the general loop's alpha, `alpha + (1 − alpha) · 0`, is `alpha`.)
            let pending = pending.map(|ray| PendingShadow { ray, blocked: radiance.shadowed });
            *out = PathResult { radiance: radiance.lit, alpha, first, glow, pending };
            None
        }
        Some(found) => Some(Resume {
            depth,
            ray,
            known: Some(found),
            throughput,
            radiance,
            pending,
            first,
            glow,
            alpha,
            last_pdf,
            last_delta,
            from_instance,
        }),
    }
}

/// The closest visible light `ray` finds before distance `tmax` (the general loop's
/// `hit_light`, the same lights compared in the same order; the best kept in three
/// values rather than an `Option` of a tuple, which the loop kept in memory).
#[inline(always)]
fn nearest_light(lights: &[LightSource], ray: &Ray, tmax: f32, camera: bool) -> Option<(usize, f32, Rgb)> {
    let (mut best, mut best_t, mut best_le) = (usize::MAX, 0.0f32, Rgb::ZERO);
    for (i, l) in lights.iter().enumerate() {
        if !l.visible || camera && l.is_portal() {
            continue;
        }
        if let Some((t, le)) = l.intersect_until(ray, tmax) {
            if best == usize::MAX || t < best_t {
                (best, best_t, best_le) = (i, t, le);
            }
        }
    }
    (best != usize::MAX).then_some((best, best_t, best_le))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::Backend;
    use crate::environment::{Environment, Source};
    use crate::integrator::{constant_materials, trace_camera_path_into};
    use crate::sampler::pixel_seed;

    /// The repository's Cornell box; with `mixed`, its tall block glossy (a flex material
    /// with reflectivity) and its short block a cut-out of opacity ½ (`mia_material`).
    fn cornell(mixed: bool) -> World {
        let mut text = include_str!("../../../../scenes/iray_cornell_box.mi").to_string();
        if mixed {
            let materials = r#"
shader "gloss" "mdl::nvidia::core_definitions::flex_material" (
        "base_color" 0.6 0.6 0.2, "reflectivity" 0.6, "roughness" 0.2
)
material "cut" "mia_material" ("diffuse" 0.2 0.3 0.7, "reflectivity" 0, "diffuse_roughness" 0,
    "cutout_opacity" 0.5) end material
"#;
            text = text.replacen("#\n# Light Definition", &format!("{materials}\n#\n# Light Definition"), 1);
            for (inst, material) in [("Tall_block_inst", "gloss"), ("Short_block_inst", "cut")] {
                let at = text.find(&format!("instance \"{inst}\"")).expect("the instance");
                let end = at + text[at..].find("material [ \"white\" ]").expect("its material");
                text.replace_range(end..end + 20, &format!("material [ \"{material}\" ]"));
            }
        }
        world_of(&text)
    }

    /// The world of the scene `text`.
    fn world_of(text: &str) -> World {
        let parsed = mi::parse_str("cb.mi", text);
        let mut diags = Vec::new();
        let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("the scene builds");
        assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}");
        World::from_scene(&scene)
    }

    /// The Cornell box with a second light, a point light, and light links: with `links`,
    /// the tall block is lit by the point light alone (`light "exclusive"`) and the short
    /// block casts shadows for the point light alone (`light shadow`).
    fn cornell_linked(links: bool) -> World {
        let mut text = include_str!("../../../../scenes/iray_cornell_box.mi").to_string();
        let point = r#"
shader "Point_def" "mdl::nvidia::core_definitions::light_omni" ("intensity" 20000)
light "Point_lgt" = "Point_def" origin 0 0 0 end light
instance "Point_inst" "Point_lgt" transform 1 0 0 0 0 1 0 0 0 0 1 0 -150 -420 -150 1 end instance
"#;
        text = text.replacen("#\n# Light Definition", &format!("{point}\n#\n# Light Definition"), 1);
        text = text.replacen("    \"Light_inst\"\n", "    \"Light_inst\"\n    \"Point_inst\"\n", 1);
        if links {
            for (inst, link) in [
                ("Tall_block_inst", r#"light "exclusive" ["Light_inst"]"#),
                ("Short_block_inst", r#"light shadow ["Point_inst"]"#),
            ] {
                let at = text.find(&format!("instance \"{inst}\"")).expect("the instance");
                let end = at + text[at..].find("material [ \"white\" ]").expect("its material");
                text.insert_str(end, &format!("{link}\n    "));
            }
        }
        world_of(&text)
    }

    /// How the kernel traced the paths it was given.
    #[derive(Default, Debug)]
    struct Tally {
        /// Paths the kernel traced to their end.
        whole: u32,
        /// Paths handed over at the camera ray's hit.
        at_camera: u32,
        /// Paths handed over after one or more plain bounces.
        mid_path: u32,
        /// The sum of the paths' radiance (lit), all channels: tells scenes apart.
        radiance: f64,
    }

    /// Traces 32 × 32 pixels × 4 samples over `world`'s image lit by `env` besides its
    /// light (first shadow rays left to the caller on odd samples) with the kernel and
    /// with the general loop alone (no plain materials), asserting that every path's radiance (lit and shadowed), alpha,
    /// first hit, glow, pending shadow ray and ray counts are the same bit for bit
    /// (tolerance: none); returns how the kernel traced them.
    fn kernel_against_general(world: &World, backend: Backend, env: Option<&Environment>) -> Tally {
        let accel = crate::accel::build(world, backend);
        let constants = constant_materials(world);
        let plain = plain_materials(world, None);
        assert!(plain.iter().any(|&p| p), "the scene has plain materials");
        let scene =
            PathScene { world, accel: accel.as_ref(), shading: None, env, constants: &constants, plain: &plain };
        let general = PathScene { plain: &[], ..scene };
        let settings = PathSettings::default();
        let (w, h) = (world.camera.width as f32, world.camera.height as f32);
        let media = MediumStack::default();
        let mut tally = Tally::default();
        let bits = |c: Rgb| c.to_array().map(f32::to_bits);
        for y in 0..32u32 {
            for x in 0..32u32 {
                let raster = ((x as f32 + 0.5) * w / 32.0, (y as f32 + 0.5) * h / 32.0);
                let ray = world.camera.ray(raster.0, raster.1);
                for index in 0..4 {
                    let camera = CameraRay { ray, hit: None, defer_shadow: index % 2 == 1 };
                    let mut start = Sampler::new(pixel_seed(x, y, 5), index);
                    let _ = start.next_2d();
                    let mut results = [PathResult::EMPTY; 2];
                    let mut counts = [RayCounts::default(); 2];
                    let mut samplers = [start.clone(), start.clone()];
                    for (i, sc) in [&scene, &general].into_iter().enumerate() {
                        let (sampler, c, out) = (&mut samplers[i], &mut counts[i], &mut results[i]);
                        trace_camera_path_into(sc, camera, &media, sampler, &settings, c, out);
                    }
                    let [fast, slow] = results;
                    tally.radiance += fast.radiance.to_array().iter().map(|&c| f64::from(c)).sum::<f64>();
                    let what = format!("{backend:?} pixel ({x}, {y}) sample {index}");
                    assert_eq!(bits(fast.radiance), bits(slow.radiance), "{what}");
                    assert_eq!(fast.alpha.to_bits(), slow.alpha.to_bits(), "{what}");
                    assert_eq!(format!("{:?}", fast.first), format!("{:?}", slow.first), "{what}");
                    assert_eq!(fast.glow.map(bits), slow.glow.map(bits), "{what}");
                    let pend = |r: &PathResult| r.pending.map(|p| (format!("{:?}", p.ray), bits(p.blocked)));
                    assert_eq!(pend(&fast), pend(&slow), "{what}");
                    assert_eq!(
                        (counts[0].rays, counts[0].shadow_rays),
                        (counts[1].rays, counts[1].shadow_rays),
                        "{what}"
                    );
                    // How the kernel alone fares with this path.
                    let (mut out, mut c) = (PathResult::EMPTY, RayCounts::default());
                    let mut sampler = start.clone();
                    match trace(&scene, &camera, &media, &mut sampler, &settings, &mut c, &mut out) {
                        None => tally.whole += 1,
                        Some(resume) if resume.depth == 0 => tally.at_camera += 1,
                        Some(_) => tally.mid_path += 1,
                    }
                }
            }
        }
        tally
    }

    /// The Cornell box, all Lambertian (its front open: many rays leave it): the kernel
    /// traces every path whole, and every path equals the general loop's bit for bit, on
    /// both backends.
    #[test]
    fn kernel_equals_the_general_loop_on_the_cornell_box() {
        let world = cornell(false);
        for backend in [Backend::Rust, Backend::Embree].into_iter().filter(|b| b.available()) {
            let tally = kernel_against_general(&world, backend, None);
            assert!(tally.whole == 4096, "{backend:?}: {tally:?}");
        }
    }

    /// The Cornell box with a glossy and a cut-out block: paths are handed over at the
    /// camera hit and after plain bounces, hundreds of times each, and every path equals
    /// the general loop's bit for bit (radiance, alpha, first hit, pending shadow ray,
    /// ray counts), on both backends.
    #[test]
    fn kernel_hands_over_to_the_general_loop_bit_for_bit() {
        let world = cornell(true);
        let plain = plain_materials(&world, None);
        let gloss = world.materials.iter().position(|m| !lambert_hit::is_lambert(&m.constant()));
        let cut = world.materials.iter().position(|m| m.opacity < 1.0);
        for m in [gloss, cut] {
            let m = m.expect("the mixed box has a glossy and a cut-out material");
            assert!(!plain[m], "material {m} is not plain");
        }
        for backend in [Backend::Rust, Backend::Embree].into_iter().filter(|b| b.available()) {
            let tally = kernel_against_general(&world, backend, None);
            assert!(tally.whole > 500 && tally.at_camera > 300 && tally.mid_path > 300, "{backend:?}: {tally:?}");
        }
    }

    /// The Cornell box lit by its area light and a point light, with and without light
    /// links (a block lit by one light only, a block shadowing one light only): every path
    /// equals the general loop's bit for bit, all traced whole by the kernel, on both
    /// backends; the links change the image (the radiance sums differ by more than 1 %).
    #[test]
    fn kernel_equals_the_general_loop_with_light_links() {
        let (free, linked) = (cornell_linked(false), cornell_linked(true));
        assert!(free.lights.len() >= 2, "two lights: {}", free.lights.len());
        for backend in [Backend::Rust, Backend::Embree].into_iter().filter(|b| b.available()) {
            let a = kernel_against_general(&free, backend, None);
            let b = kernel_against_general(&linked, backend, None);
            assert!(a.whole == 4096 && b.whole == 4096, "{backend:?}: {a:?} {b:?}");
            let change = (a.radiance - b.radiance).abs() / a.radiance;
            assert!(change > 0.01, "{backend:?}: the links change the image by {change}");
        }
    }

    /// The Cornell box under an environment (a sky brighter towards +y, sampled as one
    /// more light, seen by the rays that leave through the open front): every path equals
    /// the general loop's bit for bit, all of them traced whole by the kernel.
    #[test]
    fn kernel_equals_the_general_loop_under_an_environment() {
        let world = cornell(false);
        let sky = Environment::new(Source::Function(Box::new(|d: glam::Vec3A| {
            Rgb::new(0.4, 0.5, 0.7) * (1.5 + d.y) + Rgb::splat(0.1)
        })));
        assert!(sky.sampled);
        for backend in [Backend::Rust, Backend::Embree].into_iter().filter(|b| b.available()) {
            let tally = kernel_against_general(&world, backend, Some(&sky));
            assert!(tally.whole == 4096, "{backend:?}: {tally:?}");
        }
    }
}
