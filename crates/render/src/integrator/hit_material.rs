//! The material at a hit, as the path loop and shadow rays read it: a material's constant
//! parameters ([`constant_materials`], built once per render), or its connected shaders
//! run at the point ([`material_at`]).

use material::HitMaterial;
use shader::{Ctx, RayType, Shading, State};

use super::surface;
use crate::accel::{Accel, Hit};
use crate::ray::Ray;
use crate::world::World;

/// Every material of `world` (as [`World::materials`]) with its constant parameters, as
/// [`material::SurfaceMaterial::constant`] gives them: built once per render, the path
/// loop reads a constant material's from here instead of building it at every hit.
pub fn constant_materials(world: &World) -> Vec<HitMaterial<'_>> {
    world.materials.iter().map(|m| m.constant()).collect()
}

/// The material at a hit: its constant parameters, or — for materials with connected
/// parameters, when the scene's shader graph is given — the connected shaders run at the
/// point.
#[inline]
pub(super) fn material_at<'w>(
    world: &'w World,
    accel: &dyn Accel,
    shading: Option<&Shading>,
    ray: &Ray,
    hit: &Hit,
    material: u32,
) -> HitMaterial<'w> {
    let m = &world.materials[material as usize];
    let mut at = match shading {
        Some(shading) if m.is_varying() => varying_material_at(world, accel, shading, ray, hit, m),
        _ => m.constant(),
    };
    if let Some(view) = &m.view_transparency {
        // The facing ratio of the (bumped) shading normal, as the classic shader's N·V.
        let n = at.normal.unwrap_or_else(|| surface(world, ray, hit).ns);
        view.apply(n.dot(ray.dir).abs(), &mut at);
    }
    at
}

/// [`material_at`] for a material with connected parameters (out of line: the constant
/// case is the common one).
#[inline(never)]
fn varying_material_at<'w>(
    world: &'w World,
    accel: &dyn Accel,
    shading: &Shading,
    ray: &Ray,
    hit: &Hit,
    m: &'w material::SurfaceMaterial,
) -> HitMaterial<'w> {
    let tracer = crate::tracer::SceneTracer::new(world, accel);
    let mut state = State {
        ray_type: RayType::Eye,
        org: ray.origin,
        dir: ray.dir,
        ior_in: 1.0,
        ior: 1.0,
        child_dist: f32::INFINITY,
        time: ray.time,
        ..State::default()
    };
    crate::tracer::fill_state(world, hit, &mut state);
    state.camera_footprint = world.camera.footprint_at(state.point);
    let mut ctx = Ctx::new(shading, &tracer, state);
    m.at(&mut ctx)
}
