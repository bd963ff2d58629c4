//! The render world: the scene's meshes, instances, materials, lights and camera in the
//! compact `f32` form the integrators read.
//!
//! [`World`] and the questions asked of it are here; building it from a scene is
//! `build` (over `meshes`, `instance`, `hair`, `lights`), and the keys of what moves
//! while the shutter is open are `motion_keys` and `light_motion` (with
//! `deforming_emitters`).

mod build;
pub mod deforming_emitters;
mod faces;
mod hair;
mod instance;
mod light_motion;
mod lights;
mod meshes;
mod motion_keys;

use std::sync::Arc;

use glam::{Affine3A, Vec3A};
use material::SurfaceMaterial;

use crate::camera::CameraModel;
use crate::light::LightSource;
use crate::mesh::MeshData;
use crate::motion::Shutter;

pub use build::areas_of;
pub use faces::{face_normal, Face, FaceCache, FACE_CACHE_BUDGET, FACE_CACHE_TRIANGLES};
pub use instance::{InstanceData, Placement};
pub use motion_keys::{vertex_keys, world_key_positions, world_motion_bounds};

/// Everything an integrator needs.
pub struct World {
    /// Unique meshes.
    pub meshes: Vec<MeshData>,
    /// Their placements.
    pub instances: Vec<InstanceData>,
    /// Surface materials; index 0 is the grey default for faces without a material.
    pub materials: Vec<SurfaceMaterial>,
    /// Light sources.
    pub lights: Vec<LightSource>,
    /// Maya's ambient lights, which are not sampled: the path engine adds what they give
    /// at each hit of a material that takes ambient light (see [`World::ambient_lighting`]).
    pub ambient: Vec<material::emission::ambient::AmbientLight>,
    /// Light linking (instances' `light [exclusive] [ … ]` lists): for each instance (as
    /// [`World::instances`]), the indices into [`World::lights`] of the lights that do not
    /// light it; empty altogether when no instance has a list (see [`World::lights_instance`]).
    pub unlinked_lights: Vec<Vec<u32>>,
    /// The same for Maya's ambient lights: for each instance, the indices into
    /// [`World::ambient`] of those that do not light it (empty altogether when no
    /// instance has a list; see [`World::ambient_lighting`]).
    pub unlinked_ambient: Vec<Vec<u32>>,
    /// Shadow linking (instances' `light shadow ["exclusive"] [ … ]` lists, Maya's shadow
    /// links): for each instance, the indices into [`World::lights`] of the lights it casts
    /// no shadow for; empty altogether when no instance has a list (see
    /// [`World::casts_shadow_for`]).
    pub shadow_unlinked: Vec<Vec<u32>>,
    /// The camera.
    pub camera: CameraModel,
    /// The scene's options.
    pub options: scene::Options,
    /// User frame buffers the scene declares: (name, data type).
    pub user_buffers: Vec<(String, String)>,
    /// The user frame buffer (an index into `user_buffers`) Maya materials' glow goes to,
    /// when the camera runs a shader glow ([`crate::output_shaders::glow_buffer`]): both
    /// engines store there the glow of each surface a camera ray stops at.
    pub glow_buffer: Option<u32>,
    /// Things approximated or left out while translating, for the user.
    pub warnings: Vec<String>,
    /// Whether some material has cutouts (opacity below 1 somewhere) or a translucence
    /// depth (Maya's `translucenceDepth`: light through the object's own geometry):
    /// shadow rays then look at what they cross.
    pub has_cutouts: bool,
    /// For each material (as [`World::materials`]), whether the scene marks it `opaque`:
    /// mental ray's promise that it never transmits, so shadow rays stop at it without
    /// its transparency or shadow shader (both engines); empty when none is marked.
    pub shadow_opaque: Vec<bool>,
    /// Whether some material has a participating medium inside (the path engine then
    /// tracks the media its paths are in; see `integrator::media`).
    pub has_media: bool,
    /// The shutter, when the scene renders motion blur and something moves while it is
    /// open (`None`: every ray sees the scene at shutter time 0 and draws no time).
    pub shutter: Option<Shutter>,
    /// The scene's lights in scene order (the shading's `Tag::Light` numbers): the
    /// world → world displacement keys of each light whose instance moves while the
    /// shutter is open (as [`LightSource::motion`]), empty for a light that stays; empty
    /// altogether when no light moves. The classic engine's light loop reads it
    /// through [`shader::Tracer::light_motion`].
    pub light_motion: Vec<Vec<Affine3A>>,
    /// The scene's lights in scene order: the triangles over the shutter of each object
    /// light whose triangles change shape while it is open (vertex motion vectors,
    /// instances moving differently; `world::deforming_emitters`), `None` for the others;
    /// empty altogether when there is none. They are placed before `light_motion`'s
    /// displacement; the classic engine reads them through
    /// [`shader::Tracer::light_mesh`], the path engine in its lights' shapes.
    pub light_meshes: Vec<Option<Arc<shader::light::DeformingMesh>>>,
    /// The index in the scene's light list of each of [`World::lights`] (empty for a world
    /// not built from a scene).
    pub light_scene_indices: Vec<usize>,
    /// For each of [`World::materials`], the world-space area its emission given for the
    /// whole surface (MDL `lumen`, `candela`) was divided by; 0 for the others; empty when
    /// there is none (the displacement stage divides anew by the displaced area).
    pub spread_areas: Vec<f32>,
    /// The world-space geometric normals and hit-error bounds of the triangles of the
    /// instances that hold still (see [`FaceCache`]); to be built anew
    /// ([`World::cache_faces`]) after editing [`World::meshes`] or [`World::instances`].
    pub faces: FaceCache,
}

fn affine(m: glam::DMat4) -> Affine3A {
    Affine3A::from_mat4(m.as_mat4())
}

impl World {
    /// Whether shadow rays stop at material `material` whatever its opacity (it is marked
    /// `opaque`; see [`World::shadow_opaque`]).
    #[inline]
    pub fn blocks_shadows(&self, material: u32) -> bool {
        self.shadow_opaque.get(material as usize).copied().unwrap_or(false)
    }

    /// Whether light `light` (an index into [`World::lights`]) lights instance `instance`
    /// (an index into [`World::instances`]) by the instance's light list. (Inlined: every
    /// light sample of the path engine asks it.)
    #[inline]
    pub fn lights_instance(&self, light: usize, instance: u32) -> bool {
        self.unlinked_lights.get(instance as usize).is_none_or(|out| !out.contains(&(light as u32)))
    }

    /// Whether instance `instance` (an index into [`World::instances`]) casts shadows for
    /// light `light` (an index into [`World::lights`]) by its shadow light list.
    pub fn casts_shadow_for(&self, light: usize, instance: u32) -> bool {
        self.shadow_unlinked.get(instance as usize).is_none_or(|out| !out.contains(&(light as u32)))
    }

    /// The Maya ambient lights (of [`World::ambient`]) that instance `instance` (an index
    /// into [`World::instances`]) lets light it by its light list; each gives a surface
    /// there [`AmbientLight::shadowed_at`](material::emission::ambient::AmbientLight::shadowed_at)
    /// (× the material's diffuse colour × its [`SurfaceMaterial::ambient`]).
    pub fn ambient_lighting(&self, instance: u32) -> impl Iterator<Item = &material::emission::ambient::AmbientLight> {
        let out = self.unlinked_ambient.get(instance as usize);
        self.ambient
            .iter()
            .enumerate()
            .filter(move |(a, _)| out.is_none_or(|out| !out.contains(&(*a as u32))))
            .map(|(_, a)| a)
    }

    /// World-space bounds of all instances (over the whole shutter when things move).
    pub fn bounds(&self) -> (Vec3A, Vec3A) {
        let mut lo = Vec3A::splat(f32::INFINITY);
        let mut hi = Vec3A::splat(f32::NEG_INFINITY);
        for inst in &self.instances {
            let mesh = &self.meshes[inst.mesh as usize];
            if !inst.moves() && !mesh.moves() {
                for p in mesh.vertex_positions() {
                    let w = inst.object_to_world.transform_point3a(p.into());
                    lo = lo.min(w);
                    hi = hi.max(w);
                }
                continue;
            }
            let (l, h) = world_motion_bounds(inst, mesh);
            lo = lo.min(l);
            hi = hi.max(h);
        }
        (lo, hi)
    }

    /// Builds [`World::faces`] anew from the meshes and instances as they are now.
    pub fn cache_faces(&mut self) {
        self.faces = FaceCache::build(&self.meshes, &self.instances);
    }

    /// Number of triangles over all instances.
    pub fn instanced_triangles(&self) -> usize {
        self.instances.iter().map(|i| self.meshes[i.mesh as usize].triangles.len()).sum()
    }
}
