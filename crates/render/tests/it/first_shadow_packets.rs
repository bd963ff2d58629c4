//! The first bounce's shadow ray left to the caller (the path engine traces those of a
//! packet's paths together): resolved by the caller's own occlusion query, a path's
//! radiance is bit for bit the one it makes tracing the ray itself, on both backends.

use render::accel::Backend;
use render::integrator::{constant_materials, plain_materials, trace_camera_path, CameraRay, PathScene, PathSettings};
use render::ray::RayCounts;
use render::sampler::{pixel_seed, Sampler};
use render::World;

/// The repository's Cornell box: a ceiling rectangle light, two blocks shadowing the floor.
fn cornell() -> World {
    let parsed = mi::parse_str("cb.mi", include_str!("../../../../scenes/iray_cornell_box.mi"));
    let mut diags = Vec::new();
    World::from_scene(&scene::Scene::build(&parsed, 0, &mut diags).expect("the Cornell box builds"))
}

/// 24 × 24 pixels over the image, 4 samples each: every path traced with its first shadow
/// ray left to the caller gives, once the caller's `occluded` answers it, the radiance,
/// alpha and ray counts of the same path tracing the ray itself; both outcomes (blocked
/// and not) occur hundreds of times.
#[test]
fn deferred_first_shadow_rays_give_the_paths_own_radiance() {
    let world = cornell();
    assert!(!world.lights.is_empty(), "the Cornell box has its light");
    let (w, h) = (world.camera.width, world.camera.height);
    let settings = PathSettings::default();
    for backend in [Backend::Rust, Backend::Embree].into_iter().filter(|b| b.available()) {
        let accel = render::accel::build(&world, backend);
        let constants = constant_materials(&world);
        let plain = plain_materials(&world, None);
        let scene = PathScene {
            world: &world,
            accel: accel.as_ref(),
            shading: None,
            env: None,
            constants: &constants,
            plain: &plain,
        };
        let (mut blocked, mut lit) = (0u32, 0u32);
        for y in 0..24u32 {
            for x in 0..24u32 {
                let raster = ((x as f32 + 0.5) * w as f32 / 24.0, (y as f32 + 0.5) * h as f32 / 24.0);
                for index in 0..4 {
                    let mut own_sampler = Sampler::new(pixel_seed(x, y, 3), index);
                    let _ = own_sampler.next_2d();
                    let mut left_sampler = own_sampler.clone();
                    let ray = world.camera.ray(raster.0, raster.1);
                    let (mut own_counts, mut left_counts) = (RayCounts::default(), RayCounts::default());
                    let path = |defer_shadow: bool, sampler: &mut Sampler, counts: &mut RayCounts| {
                        let camera = CameraRay { ray, hit: None, defer_shadow };
                        let media = Default::default();
                        trace_camera_path(&scene, camera, &media, sampler, &settings, counts)
                    };
                    let own = path(false, &mut own_sampler, &mut own_counts);
                    let left = path(true, &mut left_sampler, &mut left_counts);
                    assert!(own.pending.is_none(), "a path asked to trace its shadow ray left one");
                    let answered = match left.pending {
                        Some(p) => {
                            let b = accel.occluded(&p.ray);
                            if b {
                                blocked += 1;
                            } else {
                                lit += 1;
                            }
                            left.radiance_given(b)
                        }
                        None => left.radiance,
                    };
                    let bits = |c: bsdf::Rgb| c.to_array().map(f32::to_bits);
                    assert_eq!(bits(answered), bits(own.radiance), "{backend:?} pixel ({x}, {y}) sample {index}");
                    assert_eq!(left.alpha.to_bits(), own.alpha.to_bits());
                    assert_eq!((left_counts.rays, left_counts.shadow_rays), (own_counts.rays, own_counts.shadow_rays));
                }
            }
        }
        assert!(blocked > 100 && lit > 100, "{backend:?}: {blocked} blocked, {lit} lit");
    }
}
