//! How the scene's lights move over the shutter: displacement keys of lights whose
//! instances move, composed with those of the geometry an object light takes its
//! triangles from, or, when those triangles change shape, the instances they come from
//! (made into moving triangles by `world::deforming_emitters`).

use glam::Affine3A;
use scene::Scene;

use super::affine;
use crate::motion::{lerp_keys, transform_keys, Shutter};

/// Keys over the shutter of each of the scene's lights (scene order) that moves: its world
/// → world displacement from where it is at motion time 0 (empty for a light that stays),
/// and, for an `object` light whose triangles change shape, the scene indices of the
/// instances they come from.
///
/// A light moves with its instance. An `object` area light's triangles are the geometry
/// instance's it names, placed by that instance: when they move rigidly (one instance,
/// or instances moving alike, without vertex motion vectors) its displacement is the
/// light instance's composed with the geometry instance's; otherwise the displacement is
/// the light instance's alone and the triangles are taken at each time from the moving
/// geometry (`world::deforming_emitters`).
pub(super) fn light_keys(shutter: &Shutter, scene: &Scene, warnings: &mut Vec<String>) -> LightKeys {
    let limit = scene::sanity::WORLD_LIMIT as f32;
    let steps = scene.options.motion_steps as usize;
    // The displacement keys of a transform that is `start` at motion time 0 and `end` at
    // motion time 1 (both something → world); empty when it does not move.
    let displacement = |start: Affine3A, end: Affine3A| -> Vec<Affine3A> {
        if start == end {
            return Vec::new();
        }
        let back = start.inverse();
        transform_keys(start, end, shutter, steps).into_iter().map(|k| k * back).collect()
    };
    scene
        .lights
        .iter()
        .map(|light| {
            let own = match light.motion_light_to_world {
                Some(end) => displacement(affine(light.light_to_world), affine(end)),
                None => Vec::new(),
            };
            let (emitter, deforming) = match &light.area {
                Some(scene::light::AreaLight { shape: scene::AreaShape::Object { instance }, .. }) => {
                    match emitter_motion(scene, instance, &displacement) {
                        EmitterMotion::Rigid(keys) => (keys, None),
                        EmitterMotion::Deforming(picked) => (Vec::new(), Some(picked)),
                    }
                }
                _ => (Vec::new(), None),
            };
            let keys = compose_keys(&own, &emitter);
            if !keys.iter().all(|k| k.is_finite() && k.translation.abs().max_element() <= limit) {
                warnings.push(format!("light '{}' moves beyond single precision: it is kept still", light.instance));
                return (Vec::new(), deforming);
            }
            (keys, deforming)
        })
        .unzip()
}

/// Per light (scene order): displacement keys, and the instances of a deforming object
/// light (see [`light_keys`]).
pub(super) type LightKeys = (Vec<Vec<Affine3A>>, Vec<Option<Vec<u32>>>);

/// How an object light's triangles move over the shutter.
enum EmitterMotion {
    /// Rigidly, by these world → world displacement keys (empty: they stay).
    Rigid(Vec<Affine3A>),
    /// Changing shape: they are these scene instances' triangles (scene indices).
    Deforming(Vec<u32>),
}

/// How the triangles of the geometry instance `name` an object light takes its triangles
/// from move (picked as [`shader::light::MeshShape::of_instance`] picks them: the
/// instance of that name, else every instance of the object of that name): rigidly when
/// every picked instance moves alike and no picked object has vertex motion vectors.
fn emitter_motion(
    scene: &Scene,
    name: &str,
    displacement: &dyn Fn(Affine3A, Affine3A) -> Vec<Affine3A>,
) -> EmitterMotion {
    let mut picked: Vec<(usize, &scene::Instance)> =
        scene.instances.iter().enumerate().filter(|(_, i)| i.name == name).collect();
    if picked.is_empty() {
        picked = scene
            .instances
            .iter()
            .enumerate()
            .filter(|(_, i)| scene.objects.get(i.object as usize).is_some_and(|o| o.name == name))
            .collect();
    }
    let moves: Vec<Vec<Affine3A>> = picked
        .iter()
        .map(|(_, i)| match i.motion_world_to_object {
            Some(end) => displacement(affine(i.object_to_world), affine(end).inverse()),
            None => Vec::new(),
        })
        .collect();
    let vertices_move = picked
        .iter()
        .any(|(_, i)| scene.objects.get(i.object as usize).is_some_and(|o| !o.geometry.mesh.motion.is_empty()));
    match moves.split_first() {
        Some((first, rest)) if !vertices_move && rest.iter().all(|k| k == first) => EmitterMotion::Rigid(first.clone()),
        Some(_) => EmitterMotion::Deforming(picked.iter().map(|(index, _)| *index as u32).collect()),
        None => EmitterMotion::Rigid(Vec::new()),
    }
}

/// Keys of `outer ∘ inner` (two displacements' keys spread evenly over the shutter;
/// empty: no displacement) at the more keys of the two.
fn compose_keys(outer: &[Affine3A], inner: &[Affine3A]) -> Vec<Affine3A> {
    match (outer.is_empty(), inner.is_empty()) {
        (true, _) => inner.to_vec(),
        (_, true) => outer.to_vec(),
        _ => {
            let count = outer.len().max(inner.len());
            (0..count)
                .map(|j| {
                    let s = j as f32 / (count - 1) as f32;
                    lerp_keys(outer, s) * lerp_keys(inner, s)
                })
                .collect()
        }
    }
}
