//! Fuzz target for the scene layer: parse, then build the world as `mira check --scene`
//! does.
//!
//! Checks that building never panics, hangs or blows up in memory, that every diagnostic
//! renders, and that a world built without errors holds only what a renderer can use
//! (issue 15): a camera with a positive finite focal length, aperture and aspect ratio and
//! a resolution within 1 … 65536, finite transforms, finite vertex positions, finite light
//! positions and directions.
//!
//! A world built without errors is then rendered as `mira render` would, at 8 × 8 pixels
//! and 1 sample per pixel with mira's own BVH on one thread, stopped after
//! [`RENDER_SECONDS`] (the render's time limit and its cancel flag, which the pre-passes
//! honour too): compiling the shading (errors stop there, as in `mira render`), the
//! acceleration structure, the pre-passes (environment, photon maps, final gather points)
//! and the sample passes must not panic, and every pixel of the film must come out finite.
//!
//! As for the `parse` target, run it from an empty working directory (relative `$include`
//! of a `Memory` origin resolves against the current directory).

#![no_main]

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::Duration;

use libfuzzer_sys::fuzz_target;

/// Seconds an input may render before it is stopped (libFuzzer's `-timeout` catches what
/// does not stop).
const RENDER_SECONDS: f64 = 2.0;

/// One worker thread for every input: libFuzzer runs one input at a time, and one thread
/// keeps a run reproducible.
fn pool() -> &'static rayon::ThreadPool {
    static POOL: OnceLock<rayon::ThreadPool> = OnceLock::new();
    POOL.get_or_init(|| rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("one worker thread"))
}

/// Renders `scene` at 8 × 8, 1 spp, and checks the film.
fn render_small(mut scene: scene::Scene) {
    render::pipeline::set_resolution(&mut scene, 8, 8);
    let engine = render::pipeline::choose_engine(&scene, None);
    let options = shader::ShadingOptions {
        search: shader::texture::SearchPath { dirs: vec![] },
        seed: 0,
        finalgather_rays: Some(4),
    };
    let built = render::pipeline::build_world(&scene, &options, &[]);
    if built.diagnostics.iter().any(|d| d.is_error()) {
        return;
    }
    let settings = render::Settings {
        engine,
        spp: Some(1),
        max_time: Some(Duration::from_secs_f64(RENDER_SECONDS)),
        ..render::Settings::default()
    };
    let cancel = Arc::new(AtomicBool::new(false));
    let done = Arc::new(AtomicBool::new(false));
    let watchdog = {
        let (cancel, done) = (cancel.clone(), done.clone());
        std::thread::spawn(move || {
            let start = std::time::Instant::now();
            while !done.load(Ordering::Relaxed) && start.elapsed().as_secs_f64() < RENDER_SECONDS {
                std::thread::sleep(Duration::from_millis(10));
            }
            cancel.store(true, Ordering::Relaxed);
        })
    };
    let (world, shading) = (&built.world, &built.shading);
    let (film, _stats) = pool().install(|| {
        let accel = render::accel::build(world, render::accel::Backend::Rust);
        let prepared = render::prepare::prepare(world, accel.as_ref(), Some(shading), engine, &cancel);
        render::render_prepared(world, accel.as_ref(), Some(shading), &prepared, &settings, &cancel, &|_| {})
    });
    done.store(true, Ordering::Relaxed);
    let _ = watchdog.join();
    assert_eq!((film.width, film.height), (8, 8), "film size");
    for (i, p) in film.rgba().iter().enumerate() {
        assert!(p.iter().all(|v| v.is_finite()), "pixel {i} is not finite: {p:?}");
    }
}

fuzz_target!(|data: &[u8]| {
    let options = mi::ReadOptions { include_paths: vec![], builtin_declarations: true, max_errors: 50 };
    let parsed = mi::parse_source(mi::Origin::Memory("fuzz.mi".into()), data.to_vec(), &options);
    if parsed.diagnostics.has_errors() {
        return;
    }
    let mut diags = Vec::new();
    let world = scene::Scene::build(&parsed, 0, &mut diags);
    for d in &diags {
        let _ = d.render(&parsed.sources);
    }
    let Some(world) = world else { return };
    if diags.iter().any(|d| d.is_error()) {
        return;
    }
    let c = &world.camera;
    let positive = |v: f64| v > 0.0 && v.is_finite();
    assert!(c.focal.is_none_or(positive), "focal {:?}", c.focal);
    assert!(positive(c.aperture) && positive(c.aspect), "aperture {} aspect {}", c.aperture, c.aspect);
    let max = scene::camera::MAX_RESOLUTION;
    assert!((1..=max).contains(&c.resolution.0) && (1..=max).contains(&c.resolution.1), "{:?}", c.resolution);
    assert!(c.world_to_camera.is_finite() && c.camera_to_world.is_finite(), "camera transform");
    assert!(c.offset.0.is_finite() && c.offset.1.is_finite(), "offset {:?}", c.offset);
    for i in &world.instances {
        assert!(i.object_to_world.is_finite() && i.world_to_object.is_finite(), "instance '{}'", i.name);
    }
    for o in &world.objects {
        let mesh = &o.geometry.mesh;
        assert!(mesh.positions.iter().all(|p| p.is_finite()), "object '{}': non-finite vertex", o.name);
        let n = mesh.positions.len() as u64;
        assert!(mesh.triangles.iter().flatten().all(|&v| u64::from(v) < n), "object '{}': index out of range", o.name);
        for h in &o.geometry.hair {
            assert!(h.points.iter().all(|p| p.is_finite()), "object '{}': non-finite hair point", o.name);
        }
    }
    for l in &world.lights {
        assert!(l.position.is_finite() && l.direction.is_finite(), "light '{}'", l.instance);
    }
    render_small(world);
});
