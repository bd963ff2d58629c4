//! Fuzz target for the scene layer: parse, then build the world as `mira check --scene`
//! does.
//!
//! Checks that building never panics, hangs or blows up in memory, that every diagnostic
//! renders, and that a world built without errors holds only what a renderer can use
//! (issue 15): a camera with a positive finite focal length, aperture and aspect ratio and
//! a resolution within 1 … 65536, finite transforms, finite vertex positions, finite light
//! positions and directions.
//!
//! As for the `parse` target, run it from an empty working directory (relative `$include`
//! of a `Memory` origin resolves against the current directory).

#![no_main]

use libfuzzer_sys::fuzz_target;

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
});
