//! Object area lights over displaced geometry: an `object` light takes its triangles
//! from geometry instances (the instance of that name, else every instance of the object
//! of that name, as [`shader::light::MeshShape::of_instance`] picks them); when the
//! displacement stage moved any of them, the light's shape is rebuilt from the world's
//! displaced triangles (world space at motion time 0; the emitting side the one the
//! displaced triangles' winding gives, kept under a mirroring placement), in both
//! engines: the path engine's light ([`World::lights`], its output per area recomputed
//! for the new area, its motion kept), the classic engine's ([`Shading::lights`]), and
//! the triangles over the shutter of a light whose geometry changes shape while the
//! shutter is open ([`World::light_meshes`]). Emission given for a whole surface (MDL
//! `lumen`, `candela`) is spread anew over the displaced area ([`respread_emission`]).

use std::collections::HashSet;
use std::sync::Arc;

use mi::Diagnostic;
use scene::{AreaShape, Scene};
use shader::light::{MeshShape, Shape};
use shader::Shading;

use crate::light::LightSource;
use crate::world::{deforming_emitters, World};

/// The scene instances (scene indices) an object light naming `name` takes its triangles
/// from.
fn picked_instances(scene: &Scene, name: &str) -> Vec<u32> {
    let named: Vec<u32> =
        scene.instances.iter().enumerate().filter(|(_, i)| i.name == name).map(|(k, _)| k as u32).collect();
    if !named.is_empty() {
        return named;
    }
    scene
        .instances
        .iter()
        .enumerate()
        .filter(|(_, i)| scene.objects.get(i.object as usize).is_some_and(|o| o.name == name))
        .map(|(k, _)| k as u32)
        .collect()
}

/// The world-space triangles (motion time 0) of the world's instances of the scene
/// instances `picked`.
fn world_triangles(world: &World, picked: &[u32]) -> Option<MeshShape> {
    let mut triangles = Vec::new();
    for inst in world.instances.iter().filter(|i| picked.contains(&i.scene_index)) {
        let Some(mesh) = world.meshes.get(inst.mesh as usize).filter(|m| m.hair.is_none()) else { continue };
        let flip = inst.object_to_world.matrix3.determinant() < 0.0;
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| inst.object_to_world.transform_point3a(mesh.position(i)));
            triangles.push(if flip { [a, c, b] } else { [a, b, c] });
        }
    }
    MeshShape::new(triangles)
}

/// Rebuilds the shapes of the object lights whose geometry instances include one of
/// `displaced` (scene instance indices whose meshes the displacement stage replaced).
pub fn reshape_object_lights(
    world: &mut World,
    scene: &Scene,
    shading: &mut Shading,
    displaced: &HashSet<u32>,
    diagnostics: &mut Vec<Diagnostic>,
) {
    if displaced.is_empty() {
        return;
    }
    for (l, light) in scene.lights.iter().enumerate() {
        let Some(AreaShape::Object { instance }) = light.area.as_ref().map(|a| &a.shape) else { continue };
        let picked = picked_instances(scene, instance);
        if !picked.iter().any(|i| displaced.contains(i)) {
            continue;
        }
        // Messages point at the displaced geometry (lights carry no position in the file).
        let span = picked
            .iter()
            .filter(|i| displaced.contains(i))
            .find_map(|&i| scene.instances.get(i as usize).and_then(|i| scene.objects.get(i.object as usize)))
            .map(|o| o.span)
            .unwrap_or_default();
        let Some(still) = world_triangles(world, &picked) else {
            diagnostics.push(Diagnostic::warning(
                span,
                format!(
                    "object light '{}': its displaced triangles have no area; it keeps its undisplaced ones",
                    light.instance
                ),
            ));
            continue;
        };
        if let Some(s) = shading.lights.get_mut(l) {
            s.shape = Some(Shape::Mesh(Arc::new(still.clone())));
        }
        let deforming = match world.light_meshes.get(l) {
            Some(Some(_)) => deforming_emitters::deforming_mesh(&picked, &world.meshes, &world.instances).map(Arc::new),
            _ => None,
        };
        if let Some(keys) = &deforming {
            world.light_meshes[l] = Some(Arc::clone(keys));
        }
        let shape = match deforming {
            Some(keys) => still.deforming(keys),
            None => still,
        };
        for k in 0..world.lights.len() {
            if world.light_scene_indices.get(k) != Some(&l) {
                continue;
            }
            let shading: &Shading = shading;
            match LightSource::in_scene_with_shape(light, scene, Some(shading), Shape::Mesh(Arc::new(shape.clone()))) {
                Ok(mut source) => {
                    let old = &world.lights[k];
                    source.motion = old.motion.clone();
                    world.lights[k] = source;
                }
                Err(e) => diagnostics.push(Diagnostic::warning(span, e)),
            }
        }
    }
}

/// Spreads the emission of materials given for their whole surface (MDL `lumen`,
/// `candela`; [`World::spread_areas`]) over the area of the triangles that carry them
/// after displacement, where an instance in `displaced` (scene indices) carries them.
pub fn respread_emission(world: &mut World, displaced: &HashSet<u32>) {
    if displaced.is_empty() || world.spread_areas.iter().all(|a| *a <= 0.0) {
        return;
    }
    let mut picked: Vec<bool> = world.spread_areas.iter().map(|a| *a > 0.0).collect();
    // Only materials a displaced instance carries change.
    let carried: HashSet<u32> = world
        .instances
        .iter()
        .filter(|i| displaced.contains(&i.scene_index))
        .flat_map(|i| i.materials.iter().copied())
        .collect();
    for (m, p) in picked.iter_mut().enumerate() {
        *p &= carried.contains(&(m as u32));
    }
    let areas = crate::world::areas_of(&picked, &world.meshes, &world.instances);
    for (m, area) in areas.into_iter().enumerate() {
        let old = world.spread_areas[m];
        if !picked[m] || area <= 0.0 || area == old {
            continue;
        }
        // The emission is E / old; E / area is it spread once more over area / old.
        let material = &mut world.materials[m];
        material.emission_over_area = true;
        material.spread_emission_over(area / old);
        world.spread_areas[m] = area;
    }
}
