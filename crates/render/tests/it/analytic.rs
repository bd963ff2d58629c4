//! Analytic cases the path integrator must get right in absolute terms: a white furnace, a
//! Lambertian plane under a point light, an area light seen directly, and MIS on/off
//! agreeing. Each compares against a closed-form value with a tolerance set by the Monte
//! Carlo error of the sample count used.

use std::sync::atomic::AtomicBool;

use bsdf::Rgb;
use glam::{Affine3A, Mat3A, Vec3, Vec3A};
use material::SurfaceMaterial;
use render::camera::CameraModel;
use render::integrator::PathSettings;
use render::light::{LightSource, Output, RectFrame, Shape};
use render::mesh::MeshData;
use render::world::{InstanceData, World};
use render::{accel, Backend, Settings};
use scene::options::{Filter, FilterKind, Options};
use scene::LightKind;

/// A UV sphere of radius `r` around the origin.
fn sphere(r: f32, rings: u32, segments: u32) -> MeshData {
    let mut m = MeshData::default();
    for i in 0..=rings {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = std::f32::consts::TAU * j as f32 / segments as f32;
            m.positions.push(Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()) * r);
        }
    }
    for i in 0..rings {
        for j in 0..segments {
            let a = i * segments + j;
            let b = i * segments + (j + 1) % segments;
            let (c, d) = (a + segments, b + segments);
            m.triangles.push([a, c, b]);
            m.triangles.push([b, c, d]);
        }
    }
    m.slots = vec![0; m.triangles.len()];
    m
}

/// A square of side `s` in the z = 0 plane, facing +Z.
fn plane(s: f32) -> MeshData {
    let h = s / 2.0;
    MeshData {
        positions: vec![Vec3::new(-h, -h, 0.0), Vec3::new(h, -h, 0.0), Vec3::new(h, h, 0.0), Vec3::new(-h, h, 0.0)],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        slots: vec![0, 0],
        ..MeshData::default()
    }
}

fn instance(mesh: u32, material: u32) -> InstanceData {
    InstanceData {
        mesh,
        object_to_world: Affine3A::IDENTITY,
        world_to_object: Affine3A::IDENTITY,
        normal_to_world: Mat3A::IDENTITY,
        materials: vec![material],
        flags: scene::Flags::default(),
        tag: 0,
        scene_index: 0,
        motion_to_world: None,
        keys: Vec::new(),
    }
}

/// A camera at `eye` looking along −Z of `camera_to_world` (orthographic when `ortho`).
fn camera(camera_to_world: Affine3A, size: u32, aperture: f32, ortho: bool) -> CameraModel {
    CameraModel {
        width: size,
        height: size,
        camera_to_world,
        world_to_camera: camera_to_world.inverse(),
        focal: 1.0,
        aperture,
        aspect: 1.0,
        orthographic: ortho,
        offset: (0.0, 0.0),
        clip: (0.0, f32::INFINITY),
        window: (0, 0, size, size),
        keys: Vec::new(),
    }
}

fn options() -> Options {
    Options { filter: Filter { kind: FilterKind::Box, width: 1.0, height: 1.0, clip: false }, ..Options::default() }
}

fn world(
    meshes: Vec<MeshData>,
    instances: Vec<InstanceData>,
    materials: Vec<SurfaceMaterial>,
    lights: Vec<LightSource>,
    camera: CameraModel,
) -> World {
    World {
        has_cutouts: false,
        shadow_opaque: Vec::new(),
        has_media: false,
        meshes,
        instances,
        materials,
        lights,
        ambient: Vec::new(),
        unlinked_lights: Vec::new(),
        unlinked_ambient: Vec::new(),
        shadow_unlinked: Vec::new(),
        camera,
        options: options(),
        user_buffers: Vec::new(),
        glow_buffer: None,
        warnings: Vec::new(),
        shutter: None,
        light_motion: Vec::new(),
        light_meshes: Vec::new(),
        light_scene_indices: Vec::new(),
        spread_areas: Vec::new(),
        faces: render::world::FaceCache::default(),
    }
}

fn run(world: &World, spp: u32, path: PathSettings) -> Vec<[f32; 4]> {
    let accel = accel::build(world, Backend::Rust);
    let settings = Settings { spp: Some(spp), path, ..Settings::default() };
    let (film, _) = render::render(world, accel.as_ref(), None, &settings, &AtomicBool::new(false), &|_| {});
    film.rgba()
}

fn mean(pixels: &[[f32; 4]]) -> Rgb {
    pixels.iter().map(|p| Rgb::new(p[0], p[1], p[2])).sum::<Rgb>() / pixels.len() as f32
}

fn material(diffuse: f32, emission: f32) -> SurfaceMaterial {
    SurfaceMaterial { emission: Rgb::splat(emission), ..SurfaceMaterial::lambert("m", Rgb::splat(diffuse)) }
}

#[test]
fn white_furnace_closed_sphere() {
    // Inside a closed sphere of albedo a emitting Le everywhere, radiance is Le / (1 − a)
    // in every direction.
    for a in [0.0f32, 0.5, 0.8] {
        let le = 0.3;
        let w = world(
            vec![sphere(1.0, 24, 48)],
            vec![instance(0, 1)],
            vec![SurfaceMaterial::grey("default"), material(a, le)],
            Vec::new(),
            camera(Affine3A::IDENTITY, 8, 2.0, false),
        );
        let path = PathSettings { max_depth: 200, ..PathSettings::default() };
        let m = mean(&run(&w, 128, path));
        let expect = le / (1.0 - a);
        eprintln!("furnace albedo {a}: {} (expected {expect})", m.x);
        assert!((m.x - expect).abs() < 0.01 * expect, "albedo {a}: {} vs {expect}", m.x);
        assert!((m.x - m.y).abs() < 1e-6 && (m.x - m.z).abs() < 1e-6);
    }
}

/// `mia_material` in the path engine, inside the furnace: a white Lambert diffuse of 0.6
/// and a reflection of weight 0.5 at every angle (R0 = R90 = 1) conserve to the weights
/// 0.3 + 0.5 = 0.8. A mirror reflects exactly its weight, so the radiance is Le/(1 − 0.8);
/// glossy reflections lose a little to masking and never gain: at most that.
#[test]
fn mia_material_in_the_furnace_conserves_energy() {
    use material::SurfaceModel;
    use mia::params::Mia;
    for gloss in [1.0f32, 0.5] {
        let mia = Mia {
            diffuse: Rgb::splat(0.6),
            roughness: 0.0,
            reflectivity: 0.5,
            refl_color: Rgb::ONE,
            refl_gloss: gloss,
            metal: false,
            transparency: 0.0,
            refr_color: Rgb::ONE,
            ior: 1.4,
            transl: Rgb::ZERO,
            anisotropy: 1.0,
            rotation: 0.0,
            fresnel: false,
            curve: (1.0, 1.0, 5.0),
            conserve: true,
            hl_balance: 1.0,
            thin_walled: false,
        };
        let le = 0.2;
        let m = SurfaceMaterial {
            emission: Rgb::splat(le),
            model: SurfaceModel::Mia(Box::new((mia, 1.0))),
            ..SurfaceMaterial::lambert("mia", Rgb::splat(0.6))
        };
        let w = world(
            vec![sphere(1.0, 24, 48)],
            vec![instance(0, 1)],
            vec![SurfaceMaterial::grey("default"), m],
            Vec::new(),
            camera(Affine3A::IDENTITY, 8, 2.0, false),
        );
        let path = PathSettings { max_depth: 200, ..PathSettings::default() };
        let got = mean(&run(&w, 128, path)).x;
        let bound = le / (1.0 - 0.8);
        eprintln!("mia furnace, gloss {gloss}: {got} (bound {bound})");
        assert!(got <= bound * 1.01, "gloss {gloss}: {got} over {bound}");
        if gloss >= 1.0 {
            assert!((got - bound).abs() < 0.01 * bound, "mirror: {got} vs {bound}");
        } else {
            assert!(got > 0.9 * bound, "gloss {gloss}: {got} loses too much against {bound}");
        }
    }
}

#[test]
fn lambertian_plane_under_a_point_light() {
    // Plane z = 0 of albedo ρ, point light of intensity I at height h above (0, 0): the
    // radiance at (x, y) is ρ/π · I · h / d³ with d² = x² + y² + h².
    let (rho, intensity, h) = (0.6f32, 10.0f32, 2.0f32);
    let light = LightSource {
        name: "point".into(),
        kind: LightKind::Point,
        position: Vec3A::new(0.0, 0.0, h),
        direction: -Vec3A::Z,
        shape: Shape::Point,
        rect_frame: None,
        output: Output::Intensity(Rgb::splat(intensity)),
        spread: 0.0,
        cone: None,
        spot_exponent: None,
        maya_spot: None,
        visible: false,
        shadow: true,
        shadow_color: Rgb::ZERO,
        soft_shadow: None,
        motion: Vec::new(),
        lobes: Default::default(),
    };
    // An orthographic camera 5 units up looking down, 4 units wide, 32×32 pixels.
    let cam = camera(Affine3A::from_translation(glam::Vec3::new(0.0, 0.0, 5.0)), 32, 4.0, true);
    let w = world(
        vec![plane(10.0)],
        vec![instance(0, 1)],
        vec![SurfaceMaterial::grey("d"), material(rho, 0.0)],
        vec![light],
        cam,
    );
    let px = run(&w, 16, PathSettings::default());
    let mut worst = 0.0f32;
    for j in 0..32 {
        for i in 0..32 {
            // Pixel centre: x right, y up (row 0 at the top).
            let x = (i as f32 + 0.5) / 32.0 * 4.0 - 2.0;
            let y = 2.0 - (j as f32 + 0.5) / 32.0 * 4.0;
            let d = (x * x + y * y + h * h).sqrt();
            let expect = rho / std::f32::consts::PI * intensity * h / (d * d * d);
            let got = px[j * 32 + i][0];
            worst = worst.max((got - expect).abs() / expect);
        }
    }
    // The only error left is the pixel footprint's averaging (the function is smooth).
    assert!(worst < 5e-3, "worst relative error {worst}");
}

#[test]
fn area_light_seen_directly_and_mis_on_off_agree() {
    // A 2×2 rectangle light of exitance E faces down onto a diffuse plane.
    let e = 3.0f32;
    let light = LightSource {
        name: "rect".into(),
        kind: LightKind::Point,
        position: Vec3A::new(0.0, 0.0, 1.0),
        direction: -Vec3A::Z,
        shape: Shape::rect(Vec3A::new(2.0, 0.0, 0.0), Vec3A::new(0.0, 2.0, 0.0), -Vec3A::Z),
        rect_frame: RectFrame::of(&Shape::rect(Vec3A::new(2.0, 0.0, 0.0), Vec3A::new(0.0, 2.0, 0.0), -Vec3A::Z)),
        output: Output::Radiance { l: Rgb::splat(e / std::f32::consts::PI), two_sided: false },
        spread: 0.0,
        cone: None,
        spot_exponent: None,
        maya_spot: None,
        visible: true,
        shadow: true,
        shadow_color: Rgb::ZERO,
        soft_shadow: None,
        motion: Vec::new(),
        lobes: Default::default(),
    };
    // Seen from below, through its middle: radiance E/π exactly.
    let from_below = Affine3A::from_rotation_x(std::f32::consts::PI) * Affine3A::IDENTITY;
    let cam = camera(Affine3A::from_translation(glam::Vec3::new(0.0, 0.0, 0.5)) * from_below, 8, 1.0, true);
    let w = world(vec![], vec![], vec![SurfaceMaterial::grey("d")], vec![light.clone()], cam);
    for p in run(&w, 4, PathSettings::default()) {
        assert!((p[0] - e / std::f32::consts::PI).abs() < 1e-6 && p[3] == 1.0, "{p:?}");
    }
    // Looking down at the lit plane (the light's back is not seen): MIS on and off are two
    // unbiased estimators of the same image.
    let cam = camera(Affine3A::from_translation(glam::Vec3::new(0.0, 0.0, 0.9)), 16, 3.0, true);
    let w = world(
        vec![plane(6.0)],
        vec![instance(0, 1)],
        vec![SurfaceMaterial::grey("d"), material(0.5, 0.0)],
        vec![light],
        cam,
    );
    let on = mean(&run(&w, 256, PathSettings { mis: true, ..PathSettings::default() }));
    let off = mean(&run(&w, 256, PathSettings { mis: false, ..PathSettings::default() }));
    assert!((on.x - off.x).abs() < 0.01 * on.x, "MIS on {} vs off {}", on.x, off.x);
    // Both match ρ/π times the irradiance from the square, integrated numerically over the
    // light and averaged over the 3×3 patch of plane the camera sees.
    let (n_plane, n_light) = (48, 96);
    let mut sum = 0.0f64;
    for a in 0..n_plane {
        for b in 0..n_plane {
            let (x, y) =
                (-1.5 + 3.0 * (a as f64 + 0.5) / n_plane as f64, -1.5 + 3.0 * (b as f64 + 0.5) / n_plane as f64);
            let mut irradiance = 0.0;
            for c in 0..n_light {
                for d in 0..n_light {
                    let (lx, ly) = (
                        -1.0 + 2.0 * (c as f64 + 0.5) / n_light as f64,
                        -1.0 + 2.0 * (d as f64 + 0.5) / n_light as f64,
                    );
                    let r2 = (lx - x).powi(2) + (ly - y).powi(2) + 1.0;
                    // cos at both ends = 1 / r; dA = (2 / n)².
                    irradiance += 1.0 / (r2 * r2) * (2.0 / n_light as f64).powi(2);
                }
            }
            sum += irradiance * f64::from(e) / std::f64::consts::PI;
        }
    }
    let expect = 0.5 / std::f64::consts::PI * sum / (n_plane * n_plane) as f64;
    assert!((f64::from(on.x) - expect).abs() < 0.01 * expect, "{} vs {expect}", on.x);
}

#[test]
fn same_image_for_any_thread_count() {
    let scene = include_str!("../../../../scenes/iray_cornell_box.mi");
    let parsed = mi::parse_str("cb.mi", scene);
    let mut diags = Vec::new();
    let mut sc = scene::Scene::build(&parsed, 0, &mut diags).unwrap();
    sc.camera.resolution = (24, 24);
    let world = World::from_scene(&sc);
    let accel = accel::build(&world, Backend::Rust);
    let settings = Settings { spp: Some(4), seed: 7, ..Settings::default() };
    let image = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            render::render(&world, accel.as_ref(), None, &settings, &AtomicBool::new(false), &|_| {}).0.rgba()
        })
    };
    let one = image(1);
    let two = image(2);
    let bits = |v: &Vec<[f32; 4]>| v.iter().flat_map(|p| p.map(f32::to_bits)).collect::<Vec<_>>();
    assert_eq!(bits(&one), bits(&two));
    // A Cornell box: the left wall is red, the right wall green.
    let column = |i: usize| mean(&(0..24).map(|j| one[j * 24 + i]).collect::<Vec<_>>());
    let (left, right) = (column(1), column(22));
    assert!(left.x > 1.5 * left.y && right.y > 1.5 * right.x, "left {left}, right {right}");
}
