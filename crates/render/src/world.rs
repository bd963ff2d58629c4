//! The render world: the scene's meshes, instances, materials, lights and camera in the
//! compact `f32` form the integrators read.

mod deforming_emitters;

use std::sync::Arc;

use glam::{Affine3A, Mat3A, Vec3A};
use material::SurfaceMaterial;
use scene::Scene;
use shader::Shading;

use crate::camera::CameraModel;
use crate::light::LightSource;
use crate::mesh::MeshData;
use crate::motion::{lerp_keys, motion_path, transform_keys, Shutter};

/// An instance of a mesh.
#[derive(Clone, Debug)]
pub struct InstanceData {
    /// Index into [`World::meshes`].
    pub mesh: u32,
    /// Object → world.
    pub object_to_world: Affine3A,
    /// World → object.
    pub world_to_object: Affine3A,
    /// Object-space normals → world space (inverse transpose).
    pub normal_to_world: Mat3A,
    /// Material index (into [`World::materials`]) of each of the mesh's slots.
    pub materials: Vec<u32>,
    /// Render flags.
    pub flags: scene::Flags,
    /// The label written to the tag buffer.
    pub tag: u32,
    /// Index of the instance in the scene's instance list.
    pub scene_index: u32,
    /// Object → world at the end of the shutter interval, when the instance moves
    /// (`motion transform`).
    pub motion_to_world: Option<Affine3A>,
    /// Object → world at shutter times spread evenly over the shutter (see
    /// [`crate::motion`]), when the instance moves while the shutter is open; empty: it
    /// stays at `object_to_world`.
    pub keys: Vec<Affine3A>,
}

/// Where an instance is at one shutter time: its transforms then.
#[derive(Clone, Copy, Debug)]
pub struct Placement {
    /// Object → world.
    pub object_to_world: Affine3A,
    /// World → object.
    pub world_to_object: Affine3A,
    /// Object-space normals → world space (inverse transpose).
    pub normal_to_world: Mat3A,
}

impl InstanceData {
    /// Whether the instance moves while the shutter is open.
    #[inline]
    pub fn moves(&self) -> bool {
        !self.keys.is_empty()
    }

    /// Object → world at shutter time `time` (see [`crate::motion`]).
    #[inline]
    pub fn object_to_world_at(&self, time: f32) -> Affine3A {
        if self.keys.is_empty() {
            self.object_to_world
        } else {
            lerp_keys(&self.keys, time)
        }
    }

    /// The instance's transforms at shutter time `time` (the stored ones when it does not
    /// move).
    #[inline]
    pub fn placement(&self, time: f32) -> Placement {
        if self.keys.is_empty() {
            return Placement {
                object_to_world: self.object_to_world,
                world_to_object: self.world_to_object,
                normal_to_world: self.normal_to_world,
            };
        }
        let object_to_world = lerp_keys(&self.keys, time);
        Placement {
            object_to_world,
            world_to_object: object_to_world.inverse(),
            normal_to_world: object_to_world.matrix3.inverse().transpose(),
        }
    }
}

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
    /// Whether some material has cutouts (opacity below 1 somewhere): shadow rays then
    /// look at what they cross.
    pub has_cutouts: bool,
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
}

/// Divides the emission of materials given for their whole surface (MDL `lumen`,
/// `candela`) by the world-space area of the triangles that carry them.
fn spread_emission(materials: &mut [SurfaceMaterial], meshes: &[MeshData], instances: &[InstanceData]) {
    if !materials.iter().any(|m| m.emission_over_area) {
        return;
    }
    let mut area = vec![0.0f64; materials.len()];
    for inst in instances {
        let mesh = &meshes[inst.mesh as usize];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let slot = mesh.slots.get(t).copied().unwrap_or(0) as usize;
            let m = inst.materials.get(slot).copied().unwrap_or(0) as usize;
            if !materials.get(m).is_some_and(|m| m.emission_over_area) {
                continue;
            }
            let [a, b, c] = tri.map(|i| inst.object_to_world.transform_point3a(mesh.position(i)));
            area[m] += 0.5 * f64::from((b - a).cross(c - a).length());
        }
    }
    for (m, a) in materials.iter_mut().zip(area) {
        m.spread_emission_over(a as f32);
    }
}

/// The scene's lights that translate, each with its index in the scene's list, and the
/// warnings of those that do not.
type SceneLights = (Vec<(LightSource, usize)>, Vec<String>);

/// [`World::unlinked_lights`] of `instances` (the world's, from `scene`'s) and of lights
/// whose indices in the scene's list are `lights` (or the same for [`World::ambient`]): an
/// `exclusive` list names the lights that do not light the instance, another list the only
/// ones that do.
fn unlinked_lights(scene: &Scene, instances: &[InstanceData], lights: &[usize]) -> Vec<Vec<u32>> {
    let links: Vec<Option<&scene::instance::LightLink>> =
        instances.iter().map(|i| scene.instances.get(i.scene_index as usize).and_then(|s| s.lights.as_ref())).collect();
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
fn scene_lights(scene: &Scene, shading: Option<&Shading>) -> SceneLights {
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

/// A copy of the arrays of `m` that the renderer keeps (see [`mesh_data`]).
fn copy_of_rendered_arrays(m: &scene::Mesh) -> scene::Mesh {
    scene::Mesh {
        positions: m.positions.clone(),
        normals: m.normals.clone(),
        textures: m.textures.clone(),
        user: m.user.clone(),
        bump_basis: m.bump_basis.clone(),
        triangles: m.triangles.clone(),
        triangle_slots: m.triangle_slots.clone(),
        motion: m.motion.clone(),
        motion_more: m.motion_more.clone(),
        ..scene::Mesh::default()
    }
}

/// The renderer's form of a scene mesh: its position, normal, triangle and slot arrays are
/// moved out of `m`, not copied.
fn mesh_data(m: &mut scene::Mesh) -> MeshData {
    let mut positions = std::mem::take(&mut m.positions);
    // Room for one more vertex past the end: Embree reads the last vertex of a shared
    // 12-byte-stride buffer with a 16-byte load (a large vector grows in place).
    positions.reserve_exact(1);
    let slots = std::mem::take(&mut m.triangle_slots);
    MeshData {
        positions,
        normals: std::mem::take(&mut m.normals),
        textures: m.textures.iter().map(|t| t.coords.iter().map(|c| Vec3A::from(*c)).collect()).collect(),
        // Moved, not copied: the vectors keep the scene's packed form.
        user: m.user.iter_mut().map(|u| std::mem::take(&mut u.coords)).collect(),
        bump_basis: m.bump_basis.iter().map(|[u, v]| [Vec3A::from(*u), Vec3A::from(*v)]).collect(),
        triangles: std::mem::take(&mut m.triangles),
        // One slot for every triangle (the common case) is stored as none.
        slots: if slots.iter().all(|&s| s == 0) { Vec::new() } else { slots },
        hair: None,
        motion: m.motion.iter().map(|v| Vec3A::from(*v)).collect(),
        motion_more: m.motion_more.iter().map(|k| k.iter().map(|v| Vec3A::from(*v)).collect()).collect(),
        position_keys: Vec::new(),
    }
}

fn affine(m: glam::DMat4) -> Affine3A {
    Affine3A::from_mat4(m.as_mat4())
}

impl World {
    /// Translates a built scene; material parameters connected to shaders take their
    /// defaults (see [`World::from_scene_shaded`]).
    pub fn from_scene(scene: &Scene) -> World {
        World::from_scene_shaded(scene, None)
    }

    /// Translates a built scene whose compiled shading is `shading`: materials with
    /// connected parameters are evaluated through it at each hit (pass the same shading
    /// to the render).
    pub fn from_scene_shaded(scene: &Scene, shading: Option<&Shading>) -> World {
        let search = material::mdl_modules::search_path(&scene.library, &[]);
        let (mdl, diags) = material::mdl_modules::compile(&scene.library, search);
        let mut world = World::from_scene_with_mdl(scene, shading, &mdl);
        world.warnings.extend(diags.into_iter().map(|d| d.message));
        world
    }

    /// [`World::from_scene_shaded`] with the scene's MDL module materials compiled by the
    /// caller (who reports their diagnostics with the scene's sources). The scene's meshes
    /// are copied; [`World::from_scene_taking_meshes`] moves them instead.
    pub fn from_scene_with_mdl(
        scene: &Scene,
        shading: Option<&Shading>,
        mdl: &material::mdl_modules::MdlMaterials,
    ) -> World {
        let lights = scene_lights(scene, shading);
        let meshes = scene.objects.iter().map(|o| mesh_data(&mut copy_of_rendered_arrays(&o.geometry.mesh))).collect();
        World::assemble(scene, shading, mdl, meshes, lights)
    }

    /// [`World::from_scene_with_mdl`], moving the scene's vertex, normal and triangle arrays
    /// into the world instead of copying them (for a 4 M-triangle mesh, 96 MB neither copied
    /// nor held twice): the scene's object meshes are left empty (its hair and everything
    /// else stay).
    pub fn from_scene_taking_meshes(
        scene: &mut Scene,
        shading: Option<&Shading>,
        mdl: &material::mdl_modules::MdlMaterials,
    ) -> World {
        // Object area lights read the scene's meshes: they are made before the meshes move.
        let lights = scene_lights(scene, shading);
        let meshes = scene.objects.iter_mut().map(|o| mesh_data(&mut o.geometry.mesh)).collect();
        World::assemble(scene, shading, mdl, meshes, lights)
    }

    /// The world of `scene` whose object meshes (object order) are `meshes` and whose lights
    /// are `lights` (as [`scene_lights`] makes them).
    fn assemble(
        scene: &Scene,
        shading: Option<&Shading>,
        mdl: &material::mdl_modules::MdlMaterials,
        meshes: Vec<MeshData>,
        (lights, light_warnings): SceneLights,
    ) -> World {
        let mut warnings = Vec::new();
        let mut ambient = Vec::new();
        let mut ambient_indices = Vec::new();
        for (index, l) in scene.lights.iter().enumerate() {
            if let Some(light) = material::emission::ambient::maya_ambient(l, &scene.library) {
                ambient.push(light);
                ambient_indices.push(index);
            }
        }
        let mut materials = vec![SurfaceMaterial::grey("(no material)")];
        for (i, m) in scene.materials.iter().enumerate() {
            let (mat, w) = material::translate_with(m, &scene.library, shading.map(|s| (s, i)), Some(mdl));
            warnings.extend(w);
            materials.push(mat);
        }
        let has_cutouts = materials.iter().any(|m| m.may_cut_out(shading.map(|s| &s.graph)));
        let has_media = materials.iter().any(|m| m.medium.is_some() && m.has_inside());
        let object_has_triangles: Vec<bool> = meshes.iter().map(|m| !m.triangles.is_empty()).collect();
        let mut meshes = meshes;
        // Hair: one ribbon mesh per object with hair, after the objects' meshes.
        let hair_mesh: Vec<Option<u32>> = scene
            .objects
            .iter()
            .map(|o| {
                crate::hair::ribbons(&o.geometry.hair, crate::hair::Facing::Crossed).map(|(mut mesh, hair)| {
                    mesh.hair = Some(hair);
                    meshes.push(mesh);
                    (meshes.len() - 1) as u32
                })
            })
            .collect();
        let mut instances: Vec<InstanceData> = scene
            .instances
            .iter()
            .enumerate()
            .filter(|(_, i)| object_has_triangles.get(i.object as usize).copied().unwrap_or(false))
            .map(|(scene_index, i)| {
                let object_to_world = affine(i.object_to_world);
                InstanceData {
                    mesh: i.object,
                    object_to_world,
                    world_to_object: affine(i.world_to_object),
                    normal_to_world: object_to_world.matrix3.inverse().transpose(),
                    materials: i.materials.iter().map(|m| m.map_or(0, |m| m + 1)).collect(),
                    flags: i.flags,
                    tag: i.tag.unwrap_or(0).clamp(0, i64::from(u32::MAX)) as u32,
                    scene_index: scene_index as u32,
                    motion_to_world: i.motion_world_to_object.map(|m| affine(m).inverse()),
                    keys: Vec::new(),
                }
            })
            .collect();
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
        spread_emission(&mut materials, &meshes, &instances);
        let mut lights = lights;
        warnings.extend(light_warnings);
        let mut user_buffers: Vec<(String, String)> = scene
            .options
            .frame_buffers
            .iter()
            .map(|(n, ty)| (format!("fb{n}"), ty.trim_start_matches(['+', '-']).to_string()))
            .collect();
        for fb in &scene.camera.framebuffers {
            if fb.user && !user_buffers.iter().any(|(n, _)| *n == fb.name) {
                user_buffers.push((fb.name.clone(), fb.datatype.clone()));
            }
        }
        let glow_buffer = crate::output_shaders::glow_buffer(scene, &mut user_buffers);
        let mut camera = CameraModel::new(&scene.camera);
        let mut light_motion = Vec::new();
        let mut light_meshes = Vec::new();
        let weights = shading.and_then(|s| s.shutter_weights.as_deref());
        let shutter = Shutter::from_options(&scene.options, weights).filter(|shutter| {
            let deforming;
            (light_motion, deforming) = light_keys(shutter, scene, &mut warnings);
            let lights_move = light_motion.iter().any(|k| !k.is_empty());
            let moving = set_motion_keys(shutter, scene, &mut meshes, &mut instances, &mut camera, &mut warnings);
            light_meshes = deforming_emitters::deforming_meshes(&deforming, &meshes, &instances);
            for (light, index) in &mut lights {
                light.motion = light_motion[*index].clone();
                if let (Some(keys), shader::light::Shape::Mesh(mesh)) = (&light_meshes[*index], &light.shape) {
                    light.shape = shader::light::Shape::Mesh(Arc::new((**mesh).clone().deforming(Arc::clone(keys))));
                }
            }
            for hair in &facing_hair {
                turn_facing_ribbons(hair, scene, &mut meshes[hair.mesh as usize], &instances[hair.instance], &camera);
            }
            moving | lights_move
        });
        if shutter.is_none() || light_motion.iter().all(Vec::is_empty) {
            light_motion = Vec::new();
        }
        if shutter.is_none() || light_meshes.iter().all(Option::is_none) {
            light_meshes = Vec::new();
        }
        let light_indices: Vec<usize> = lights.iter().map(|(_, index)| *index).collect();
        let unlinked_ambient = unlinked_lights(scene, &instances, &ambient_indices);
        let unlinked_lights = unlinked_lights(scene, &instances, &light_indices);
        let lights = lights.into_iter().map(|(l, _)| l).collect();
        World {
            meshes,
            instances,
            materials,
            lights,
            ambient,
            unlinked_lights,
            unlinked_ambient,
            camera,
            options: scene.options.clone(),
            user_buffers,
            glow_buffer,
            warnings,
            has_cutouts,
            has_media,
            shutter,
            light_motion,
            light_meshes,
        }
    }

    /// Whether light `light` (an index into [`World::lights`]) lights instance `instance`
    /// (an index into [`World::instances`]) by the instance's light list.
    pub fn lights_instance(&self, light: usize, instance: u32) -> bool {
        self.unlinked_lights.get(instance as usize).is_none_or(|out| !out.contains(&(light as u32)))
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
                for &p in &mesh.positions {
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

    /// Number of triangles over all instances.
    pub fn instanced_triangles(&self) -> usize {
        self.instances.iter().map(|i| self.meshes[i.mesh as usize].triangles.len()).sum()
    }
}

/// A mesh of hair ribbons turned towards the camera (see [`crate::hair`]): its index, the
/// index of the instance placing it and of the object whose hair it is.
struct FacingHair {
    mesh: u32,
    instance: usize,
    object: u32,
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

/// Keys over the shutter of everything that moves while it is open: instances with a
/// `motion transform` (object → world moved over the motion interval as mental ray moves
/// instances: linearly, or as a rotation when it turns; see [`transform_keys`]), meshes with motion vectors (one key per motion step) and
/// the camera. Returns whether anything moves.
fn set_motion_keys(
    shutter: &Shutter,
    scene: &Scene,
    meshes: &mut [MeshData],
    instances: &mut [InstanceData],
    camera: &mut CameraModel,
    warnings: &mut Vec<String>,
) -> bool {
    let limit = scene::sanity::WORLD_LIMIT as f32;
    let steps = scene.options.motion_steps as usize;
    let placed_in_range = |m: &Affine3A| m.is_finite() && m.translation.abs().max_element() <= limit;
    let mut out_of_range = |what: String| {
        warnings.push(format!(
            "{what} moves beyond single precision (±{limit:e}) while the shutter is open: it is kept still"
        ))
    };
    let mut moving = false;
    for inst in instances.iter_mut() {
        if let Some(end) = inst.motion_to_world.filter(|m| *m != inst.object_to_world) {
            let keys = transform_keys(inst.object_to_world, end, shutter, steps);
            if keys.iter().all(|k| placed_in_range(k) && k.matrix3.determinant() != 0.0) {
                inst.keys = keys;
                moving = true;
            } else {
                out_of_range(format!("instance {}", inst.scene_index));
            }
        }
    }
    for mesh in meshes.iter_mut() {
        let still = |m: &[Vec3A]| m.iter().all(|v| *v == Vec3A::ZERO);
        if mesh.motion.is_empty()
            || mesh.hair.is_some()
            || still(&mesh.motion) && mesh.motion_more.iter().all(|m| still(m))
        {
            continue;
        }
        // One key per motion step (each vertex's `m` vectors are its motion path's corners).
        let vectors = mesh.motion_steps().min(crate::mesh::MAX_MOTION_STEPS);
        let keys = vectors;
        let position_keys: Vec<Vec<Vec3A>> = shutter
            .key_times(keys)
            .map(|tau| {
                (0..mesh.positions.len())
                    .map(|i| motion_path(mesh.position(i as u32), &mesh.motion_vectors(i, vectors), tau))
                    .collect()
            })
            .collect();
        if position_keys.iter().flatten().all(|p| p.is_finite() && p.abs().max_element() <= limit) {
            mesh.position_keys = position_keys;
            moving = true;
        } else {
            out_of_range("a mesh's motion vectors: the mesh".into());
        }
    }
    if let Some(end) = scene.camera.motion_world_to_camera {
        let end = affine(end).inverse();
        if end != camera.camera_to_world {
            let keys = transform_keys(camera.camera_to_world, end, shutter, steps);
            if keys.iter().all(|k| placed_in_range(k) && k.matrix3.determinant() != 0.0) {
                camera.keys = keys;
                moving = true;
            } else {
                out_of_range("the camera".into());
            }
        }
    }
    moving
}

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
fn light_keys(shutter: &Shutter, scene: &Scene, warnings: &mut Vec<String>) -> LightKeys {
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
type LightKeys = (Vec<Vec<Affine3A>>, Vec<Option<Vec<u32>>>);

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

/// World-space positions of an instance's mesh at each key of its motion (the more keys of
/// the instance's and the mesh's), for acceleration structures that store moving
/// triangles in world space. Exact between keys when only one of the two moves (the
/// instances [`crate::accel::flat_instances`] flattens); when both do, the world-space
/// path between keys is not linear (see [`world_motion_bounds`]).
pub fn world_key_positions(inst: &InstanceData, mesh: &MeshData) -> Vec<Vec<Vec3A>> {
    let keys = inst.keys.len().max(mesh.position_keys.len()).max(1);
    (0..keys)
        .map(|j| {
            let s = if keys == 1 { 0.0 } else { j as f32 / (keys - 1) as f32 };
            let to_world = inst.object_to_world_at(s);
            mesh.positions_at(s).into_iter().map(|p| to_world.transform_point3a(p)).collect()
        })
        .collect()
}

/// World-space bounds of an instance's mesh over the whole shutter, when the instance or
/// the mesh's vertices move. Between the times where either has a key both move linearly,
/// so a vertex at `A(t)·p(t)` follows a parabola: its chord between those times plus
/// `−f(1 − f)·ΔM·Δp` (`ΔM` the change of the instance's matrix, `Δp` the vertex's, `f` the
/// fraction of the interval), at most a quarter of `|ΔM·Δp|` off the chord in each axis.
/// The box holds every point at every time (the key boxes alone do when only one of
/// the two moves).
pub fn world_motion_bounds(inst: &InstanceData, mesh: &MeshData) -> (Vec3A, Vec3A) {
    let mut lo = Vec3A::splat(f32::INFINITY);
    let mut hi = Vec3A::splat(f32::NEG_INFINITY);
    let times = |keys: usize| (0..keys).map(move |j| j as f32 / (keys.max(2) - 1) as f32);
    let mut cuts: Vec<f32> = times(inst.keys.len()).chain(times(mesh.position_keys.len())).chain([0.0, 1.0]).collect();
    cuts.sort_by(f32::total_cmp);
    cuts.dedup();
    let at = |s: f32| (inst.object_to_world_at(s), mesh.positions_at(s));
    let (mut a0, mut p0) = at(cuts[0]);
    for &s in &cuts[1..] {
        let (a1, p1) = at(s);
        let dm = a1.matrix3 - a0.matrix3;
        for (q0, q1) in p0.iter().zip(&p1) {
            let (w0, w1) = (a0.transform_point3a(*q0), a1.transform_point3a(*q1));
            let bulge = (dm * (*q1 - *q0)).abs() * 0.25;
            lo = lo.min(w0.min(w1) - bulge);
            hi = hi.max(w0.max(w1) + bulge);
        }
        (a0, p0) = (a1, p1);
    }
    (lo, hi)
}
