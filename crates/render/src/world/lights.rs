//! The world's lights from the scene's: the lights the path engine samples, Maya's
//! ambient lights it adds at each hit instead, and light linking (which lights light
//! which instance).

use scene::Scene;
use shader::Shading;

use super::InstanceData;
use crate::light::LightSource;

/// The scene's lights that translate, each with its index in the scene's list, and the
/// warnings of those that do not.
pub(super) type SceneLights = (Vec<(LightSource, usize)>, Vec<String>);

/// [`World::unlinked_lights`](super::World::unlinked_lights) of `instances` (the world's, from `scene`'s) and of lights
/// whose indices in the scene's list are `lights` (or the same for [`World::ambient`](super::World::ambient)): an
/// `exclusive` list names the lights that do not light the instance, another list the only
/// ones that do.
pub(super) fn unlinked_lights(scene: &Scene, instances: &[InstanceData], lights: &[usize]) -> Vec<Vec<u32>> {
    unlinked_by(scene, instances, lights, |i| i.lights.as_ref())
}

/// As [`unlinked_lights`] for the instances' shadow light lists (`light shadow
/// ["exclusive"] [ … ]`): for each instance, the lights it casts no shadow for
/// ([`World::shadow_unlinked`](super::World::shadow_unlinked)).
pub(super) fn shadow_unlinked_lights(scene: &Scene, instances: &[InstanceData], lights: &[usize]) -> Vec<Vec<u32>> {
    unlinked_by(scene, instances, lights, |i| i.shadow_lights.as_ref())
}

/// For each of `instances`, the indices into `lights` its list (`list` of its scene
/// instance) leaves out; empty when no instance has a list.
fn unlinked_by(
    scene: &Scene,
    instances: &[InstanceData],
    lights: &[usize],
    list: impl Fn(&scene::instance::Instance) -> Option<&scene::instance::LightLink>,
) -> Vec<Vec<u32>> {
    let links: Vec<Option<&scene::instance::LightLink>> =
        instances.iter().map(|i| scene.instances.get(i.scene_index as usize).and_then(&list)).collect();
    if links.iter().all(Option::is_none) {
        return Vec::new();
    }
    links
        .iter()
        .map(|link| {
            let Some(link) = link else { return Vec::new() };
            (0..lights.len() as u32)
                .filter(|&w| link.lights.contains(&(lights[w as usize] as u32)) == link.exclusive)
                .collect()
        })
        .collect()
}

/// The lights of `scene` (object area lights read its meshes).
pub(super) fn scene_lights(scene: &Scene, shading: Option<&Shading>) -> SceneLights {
    let mut lights = Vec::new();
    let mut warnings = Vec::new();
    for (index, l) in scene.lights.iter().enumerate() {
        if material::emission::ambient::maya_ambient(l, &scene.library).is_some() {
            // Not a light the path engine samples: see `World::ambient`.
            continue;
        }
        match LightSource::in_scene_shaded(l, scene, shading) {
            Ok(src) => lights.push((src, index)),
            Err(w) => warnings.push(w),
        }
    }
    (lights, warnings)
}

/// Maya's ambient lights among the scene's lights (see [`World::ambient`](super::World::ambient)),
/// each with its index in the scene's list.
pub(super) fn ambient_lights(scene: &Scene) -> (Vec<material::emission::ambient::AmbientLight>, Vec<usize>) {
    let mut ambient = Vec::new();
    let mut ambient_indices = Vec::new();
    for (index, l) in scene.lights.iter().enumerate() {
        if let Some(light) = material::emission::ambient::maya_ambient(l, &scene.library) {
            ambient.push(light);
            ambient_indices.push(index);
        }
    }
    (ambient, ambient_indices)
}
