//! The world's kept faces (`render::world::FaceCache`): the unit world-space geometric
//! normals and hit-error bounds of the triangles of instances that hold still, the same
//! bits as computed at a hit, rebuilt after displacement, and changing no path's radiance.

use glam::Vec3A;
use render::integrator::{constant_materials, trace_camera_path, CameraRay, PathScene, PathSettings};
use render::ray::RayCounts;
use render::sampler::{pixel_seed, Sampler};
use render::world::{face_normal, FaceCache};
use render::World;

use crate::displacement::{build, constant_material, plane};

/// Two quads: one placed by a rotation, a non-uniform scale and a mirror (x → −x), one
/// that moves while the shutter is open.
const SCENE: &str = r#"
options "opt" shutter 0 1 motion on end options
camera "cam" focal 1 aperture 2 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 0 -5 1 end instance
material "m" "mib_illum_lambert" ("diffuse" 1 1 1) end material
object "quad" group
    -1 -1 0.2  1 -1 0  1 1 0.3  -1 1 0
    v 0 v 1 v 2 v 3
    c "m" 0 1 2 3
end group end object
instance "still_inst" "quad"
    transform -0.8 0.6 0 0  0.6 0.8 0 0  0 0 0.5 0  0.3 -0.2 0.1 1
end instance
instance "moving_inst" "quad" motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1 end instance
instgroup "root" "cam_inst" "still_inst" "moving_inst" end instgroup
render "root" "cam_inst" "opt"
"#;

/// The world of `text` (no shading).
fn world_of(text: &str) -> World {
    let parsed = mi::parse_str("t.mi", text);
    assert!(parsed.diagnostics.list.is_empty(), "parse diagnostics");
    let mut diags = Vec::new();
    World::from_scene(&scene::Scene::build(&parsed, 0, &mut diags).expect("a scene"))
}

/// The still instance's faces are kept, bit for bit the normal and bound computed at a
/// hit; each normal is unit (1e-6), perpendicular to its world-space triangle's edges
/// (1e-5 of their length) and on the side the mirror turns the counter-clockwise one to
/// (its dot with the world-space edges' cross product is negative: det < 0). The moving
/// instance's faces are computed at each hit: none kept.
#[test]
fn still_instances_keep_their_unit_world_normals_and_error_bounds() {
    let world = world_of(SCENE);
    assert_eq!(world.instances.len(), 2);
    let still = world.instances.iter().position(|i| !i.moves()).expect("a still instance") as u32;
    let moving = world.instances.iter().position(|i| i.moves()).expect("a moving instance") as u32;
    let inst = &world.instances[still as usize];
    assert!(inst.object_to_world.matrix3.determinant() < 0.0, "the placement mirrors");
    let mesh = &world.meshes[inst.mesh as usize];
    assert_eq!(mesh.triangles.len(), 2);
    for (prim, &tri) in mesh.triangles.iter().enumerate() {
        let (ng, err) = world.faces.get(still, prim as u32).expect("kept");
        let [p0, p1, p2] = mesh.triangle_at(tri, 0.0);
        let want = face_normal(&inst.normal_to_world, p0, p1, p2);
        assert_eq!(ng.to_array().map(f32::to_bits), want.to_array().map(f32::to_bits));
        let want_err = shader::trace::hit_error(p0, p1, p2, &inst.object_to_world);
        assert_eq!(err.to_bits(), want_err.to_bits());
        assert!(err > 0.0);
        let [w0, w1, w2] = [p0, p1, p2].map(|p| inst.object_to_world.transform_point3a(p));
        assert!((ng.length() - 1.0).abs() < 1e-6, "{ng}");
        for e in [w1 - w0, w2 - w1, w0 - w2] {
            assert!(ng.dot(e).abs() <= 1e-5 * e.length(), "{ng} against edge {e}");
        }
        assert!(ng.dot((w1 - w0).cross(w2 - w0)) < 0.0, "the mirror keeps the counter-clockwise side as the front");
        assert!(world.faces.get(moving, prim as u32).is_none(), "a moving instance keeps no faces");
    }
    assert_eq!(world.faces.len(), 2);
    assert!(world.faces.get(still, 2).is_none() && world.faces.get(9, 0).is_none());
}

/// After displacement (a plane split into 32 triangles and lifted by 0.375) the kept faces
/// are the displaced mesh's: 32 of them, each bit for bit the one computed from the
/// displaced triangle, pointing up (+z within 1e-6).
#[test]
fn displaced_meshes_keep_their_own_faces() {
    let b = build(&plane("", &constant_material(0.375), "approximate displace regular parametric 2", "m"));
    let world = &b.built.world;
    assert_eq!(world.faces.len(), 32);
    for (i, inst) in world.instances.iter().enumerate() {
        let mesh = &world.meshes[inst.mesh as usize];
        for (prim, &tri) in mesh.triangles.iter().enumerate() {
            let (ng, err) = world.faces.get(i as u32, prim as u32).expect("kept");
            let [p0, p1, p2] = mesh.triangle_at(tri, 0.0);
            let want = face_normal(&inst.normal_to_world, p0, p1, p2);
            assert_eq!(ng.to_array().map(f32::to_bits), want.to_array().map(f32::to_bits));
            assert_eq!(err.to_bits(), shader::trace::hit_error(p0, p1, p2, &inst.object_to_world).to_bits());
            assert!((ng - Vec3A::Z).length() < 1e-6, "{ng}");
        }
    }
}

/// The repository's Cornell box traced with its faces kept and without (every face then
/// computed at each hit): 16 × 16 pixels, 4 samples each, the same radiance and alpha bit
/// for bit.
#[test]
fn kept_faces_change_no_path() {
    let parsed = mi::parse_str("cb.mi", include_str!("../../../../scenes/iray_cornell_box.mi"));
    let mut diags = Vec::new();
    let kept = World::from_scene(&scene::Scene::build(&parsed, 0, &mut diags).expect("the Cornell box builds"));
    assert!(!kept.faces.is_empty());
    let mut computed = World::from_scene(&scene::Scene::build(&parsed, 0, &mut diags).expect("builds"));
    computed.faces = FaceCache::default();
    let backend = render::Backend::default_available();
    let (accel_kept, accel_computed) = (render::accel::build(&kept, backend), render::accel::build(&computed, backend));
    let (w, h) = (kept.camera.width, kept.camera.height);
    let settings = PathSettings::default();
    let (constants_kept, constants_computed) = (constant_materials(&kept), constant_materials(&computed));
    let scene = |world, accel, constants| PathScene { world, accel, shading: None, env: None, constants, plain: &[] };
    let scene_kept = scene(&kept, accel_kept.as_ref(), &constants_kept);
    let scene_computed = scene(&computed, accel_computed.as_ref(), &constants_computed);
    let mut lit = 0;
    for y in 0..16u32 {
        for x in 0..16u32 {
            let raster = ((x as f32 + 0.5) * w as f32 / 16.0, (y as f32 + 0.5) * h as f32 / 16.0);
            for index in 0..4 {
                let trace = |scene: &PathScene| {
                    let mut sampler = Sampler::new(pixel_seed(x, y, 5), index);
                    let _ = sampler.next_2d();
                    let camera =
                        CameraRay { ray: scene.world.camera.ray(raster.0, raster.1), hit: None, defer_shadow: false };
                    let media = Default::default();
                    let mut counts = RayCounts::default();
                    let r = trace_camera_path(scene, camera, &media, &mut sampler, &settings, &mut counts);
                    (r.radiance.to_array().map(f32::to_bits), r.alpha.to_bits(), counts.rays)
                };
                let a = trace(&scene_kept);
                assert_eq!(a, trace(&scene_computed), "pixel ({x}, {y}) sample {index}");
                lit += u32::from(a.0 != [0; 3]);
            }
        }
    }
    assert!(lit > 500, "{lit} lit samples");
}
