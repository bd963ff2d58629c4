//! Hair in the world: each object's hair as ribbons crossed for secondary rays and, per
//! instance, ribbons facing the camera for eye rays (see [`crate::hair`]), turned towards
//! a moving camera over the shutter.

use glam::Vec3A;
use scene::Scene;

use super::{affine, InstanceData};
use crate::camera::CameraModel;
use crate::mesh::MeshData;

/// One mesh of crossed hair ribbons per scene object with hair, pushed after `meshes`:
/// for each object (object order), the index of its hair mesh.
pub(super) fn crossed_meshes(scene: &Scene, meshes: &mut Vec<MeshData>) -> Vec<Option<u32>> {
    scene
        .objects
        .iter()
        .map(|o| {
            crate::hair::ribbons(&o.geometry.hair, crate::hair::Facing::Crossed).map(|(mut mesh, hair)| {
                mesh.hair = Some(hair);
                meshes.push(mesh);
                (meshes.len() - 1) as u32
            })
        })
        .collect()
}

/// Places the hair of every scene instance whose object has some (`hair_mesh`, as
/// [`crossed_meshes`] gives it): an instance of the crossed ribbons and, when eye or
/// transparency rays see it, one of ribbons facing the camera (a mesh pushed onto
/// `meshes`). Returns the camera-facing meshes, for [`turn_facing_ribbons`].
pub(super) fn place_hair(
    scene: &Scene,
    hair_mesh: &[Option<u32>],
    meshes: &mut Vec<MeshData>,
    instances: &mut Vec<InstanceData>,
) -> Vec<FacingHair> {
    let mut facing_hair = Vec::new();
    for (scene_index, i) in scene.instances.iter().enumerate() {
        let Some(mesh) = hair_mesh[i.object as usize] else { continue };
        let object_to_world = affine(i.object_to_world);
        let world_to_object = affine(i.world_to_object);
        // Crossed ribbons for shadow, reflection, refraction and final gather rays;
        // ribbons facing the camera for eye and transparency rays (see `crate::hair`).
        let mut crossed_flags = i.flags;
        crossed_flags.visible = false;
        crossed_flags.transparency.cast = false;
        let mut facing_flags = i.flags;
        for m in [&mut facing_flags.shadow, &mut facing_flags.reflection, &mut facing_flags.refraction] {
            m.cast = false;
        }
        facing_flags.finalgather.cast = false;
        let cam = &scene.camera;
        let cam_to_object = world_to_object * affine(cam.camera_to_world);
        let facing = if cam.focal.is_none() {
            crate::hair::Facing::Direction(cam_to_object.transform_vector3a(Vec3A::Z))
        } else {
            crate::hair::Facing::Point(cam_to_object.transform_point3a(Vec3A::ZERO))
        };
        let facing_mesh = (i.flags.visible || i.flags.transparency.cast)
            .then(|| crate::hair::ribbons(&scene.objects[i.object as usize].geometry.hair, facing))
            .flatten()
            .map(|(mut m, hair)| {
                m.hair = Some(hair);
                meshes.push(m);
                (meshes.len() - 1) as u32
            });
        if let Some(facing_mesh) = facing_mesh {
            facing_hair.push(FacingHair { mesh: facing_mesh, instance: instances.len() + 1, object: i.object });
        }
        let placed = |mesh: u32, flags: scene::Flags| InstanceData {
            mesh,
            object_to_world,
            world_to_object,
            normal_to_world: object_to_world.matrix3.inverse().transpose(),
            materials: i.hair_materials.iter().map(|m| m.map_or(0, |m| m + 1)).collect(),
            flags,
            tag: i.tag.unwrap_or(0).clamp(0, i64::from(u32::MAX)) as u32,
            scene_index: scene_index as u32,
            motion_to_world: i.motion_world_to_object.map(|m| affine(m).inverse()),
            keys: Vec::new(),
        };
        instances.push(placed(mesh, crossed_flags));
        if let Some(facing_mesh) = facing_mesh {
            instances.push(placed(facing_mesh, facing_flags));
        }
    }
    facing_hair
}

/// A mesh of hair ribbons turned towards the camera (see [`crate::hair`]): its index, the
/// index of the instance placing it and of the object whose hair it is.
pub(super) struct FacingHair {
    mesh: u32,
    instance: usize,
    object: u32,
}

/// Turns every camera-facing hair mesh of `facing_hair` (as [`place_hair`] placed them
/// in `meshes` and `instances`) towards the camera over the shutter (see
/// [`turn_facing_ribbons`]).
pub(super) fn turn_facing_meshes(
    facing_hair: &[FacingHair],
    scene: &Scene,
    meshes: &mut [MeshData],
    instances: &[InstanceData],
    camera: &CameraModel,
) {
    for hair in facing_hair {
        turn_facing_ribbons(hair, scene, &mut meshes[hair.mesh as usize], &instances[hair.instance], camera);
    }
}

/// Turns camera-facing hair ribbons towards the camera at every time while the shutter is
/// open, when the camera or the hair's instance moves: the ribbons are rebuilt facing the
/// camera as seen from the instance at each key of the two (the more keys of the two),
/// as the mesh's position keys. (mental ray turns each ribbon towards each ray; between
/// keys the ribbons' corners move linearly.) Nothing changes when neither moves.
fn turn_facing_ribbons(
    hair: &FacingHair,
    scene: &Scene,
    mesh: &mut MeshData,
    inst: &InstanceData,
    camera: &CameraModel,
) {
    let keys = inst.keys.len().max(camera.keys.len());
    if keys < 2 {
        return;
    }
    let blocks = &scene.objects[hair.object as usize].geometry.hair;
    let position_keys: Option<Vec<Vec<Vec3A>>> = (0..keys)
        .map(|j| {
            let s = j as f32 / (keys - 1) as f32;
            let cam_to_object = inst.object_to_world_at(s).inverse() * camera.camera_to_world_at(s);
            let facing = if camera.orthographic {
                crate::hair::Facing::Direction(cam_to_object.transform_vector3a(Vec3A::Z))
            } else {
                crate::hair::Facing::Point(cam_to_object.transform_point3a(Vec3A::ZERO))
            };
            crate::hair::ribbons(blocks, facing)
                .map(|(m, _)| m.positions.into_iter().map(Vec3A::from).collect::<Vec<_>>())
                .filter(|p| p.len() == mesh.positions.len() && p.iter().all(|v| v.is_finite()))
        })
        .collect();
    if let Some(position_keys) = position_keys {
        mesh.position_keys = position_keys;
    }
}
