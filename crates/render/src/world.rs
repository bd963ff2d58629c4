//! The render world: the scene's meshes, instances, materials, lights and camera in the
//! compact `f32` form the integrators read.

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
    /// The camera.
    pub camera: CameraModel,
    /// The scene's options.
    pub options: scene::Options,
    /// User frame buffers the scene declares: (name, data type).
    pub user_buffers: Vec<(String, String)>,
    /// Things approximated or left out while translating, for the user.
    pub warnings: Vec<String>,
    /// Whether some material has cutouts (opacity below 1 somewhere): shadow rays then
    /// look at what they cross.
    pub has_cutouts: bool,
    /// The shutter, when the scene renders motion blur and something moves while it is
    /// open (`None`: every ray sees the scene at shutter time 0 and draws no time).
    pub shutter: Option<Shutter>,
    /// The scene's lights in scene order (the shading's `Tag::Light` numbers): the
    /// world → world displacement keys of each light whose instance moves while the
    /// shutter is open (as [`LightSource::motion`]), empty for a light that stays; empty
    /// altogether when no light moves. The classic engine's light loop reads it
    /// through [`shader::Tracer::light_motion`].
    pub light_motion: Vec<Vec<Affine3A>>,
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
            let [a, b, c] = tri.map(|i| inst.object_to_world.transform_point3a(mesh.positions[i as usize]));
            area[m] += 0.5 * f64::from((b - a).cross(c - a).length());
        }
    }
    for (m, a) in materials.iter_mut().zip(area) {
        m.spread_emission_over(a as f32);
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
    /// caller (who reports their diagnostics with the scene's sources).
    pub fn from_scene_with_mdl(
        scene: &Scene,
        shading: Option<&Shading>,
        mdl: &material::mdl_modules::MdlMaterials,
    ) -> World {
        let mut warnings = Vec::new();
        let mut materials = vec![SurfaceMaterial::grey("(no material)")];
        for (i, m) in scene.materials.iter().enumerate() {
            let (mat, w) = material::translate_with(m, &scene.library, shading.map(|s| (s, i)), Some(mdl));
            warnings.extend(w);
            materials.push(mat);
        }
        let has_cutouts = materials.iter().any(|m| m.may_cut_out(shading.map(|s| &s.graph)));
        let meshes: Vec<MeshData> = scene
            .objects
            .iter()
            .map(|o| {
                let m = &o.geometry.mesh;
                MeshData {
                    positions: m.positions.iter().map(|p| Vec3A::from(*p)).collect(),
                    normals: m.normals.iter().map(|n| Vec3A::from(*n)).collect(),
                    textures: m.textures.iter().map(|t| t.coords.iter().map(|c| Vec3A::from(*c)).collect()).collect(),
                    bump_basis: m.bump_basis.iter().map(|[u, v]| [Vec3A::from(*u), Vec3A::from(*v)]).collect(),
                    triangles: m.triangles.clone(),
                    // One slot for every triangle (the common case) is stored as none.
                    slots: if m.triangle_slots.iter().all(|&s| s == 0) { Vec::new() } else { m.triangle_slots.clone() },
                    hair: None,
                    motion: m.motion.iter().map(|v| Vec3A::from(*v)).collect(),
                    motion_more: m.motion_more.iter().map(|k| k.iter().map(|v| Vec3A::from(*v)).collect()).collect(),
                    position_keys: Vec::new(),
                }
            })
            .collect();
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
            .filter(|(_, i)| !scene.objects[i.object as usize].geometry.mesh.triangles.is_empty())
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
        let mut lights = Vec::new();
        for (index, l) in scene.lights.iter().enumerate() {
            match LightSource::in_scene_shaded(l, scene, shading) {
                Ok(src) => lights.push((src, index)),
                Err(w) => warnings.push(w),
            }
        }
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
        if crate::output_shaders::has_glow(&scene.camera, &scene.library)
            && !user_buffers.iter().any(|(n, _)| n == maya::glow::BUFFER)
        {
            // Maya materials' glow, which the shader glow's post pass spreads.
            user_buffers.push((maya::glow::BUFFER.to_string(), "rgba_fp".to_string()));
        }
        let mut camera = CameraModel::new(&scene.camera);
        let mut light_motion = Vec::new();
        let weights = shading.and_then(|s| s.shutter_weights.as_deref());
        let shutter = Shutter::from_options(&scene.options, weights).filter(|shutter| {
            light_motion = light_keys(shutter, scene, &mut warnings);
            for (light, index) in &mut lights {
                light.motion = light_motion[*index].clone();
            }
            let lights_move = light_motion.iter().any(|k| !k.is_empty());
            set_motion_keys(shutter, scene, &mut meshes, &mut instances, &mut camera, &mut warnings) | lights_move
        });
        if shutter.is_none() || light_motion.iter().all(Vec::is_empty) {
            light_motion = Vec::new();
        }
        let lights = lights.into_iter().map(|(l, _)| l).collect();
        World {
            meshes,
            instances,
            materials,
            lights,
            camera,
            options: scene.options.clone(),
            user_buffers,
            warnings,
            has_cutouts,
            shutter,
            light_motion,
        }
    }

    /// World-space bounds of all instances (over the whole shutter when things move).
    pub fn bounds(&self) -> (Vec3A, Vec3A) {
        let mut lo = Vec3A::splat(f32::INFINITY);
        let mut hi = Vec3A::splat(f32::NEG_INFINITY);
        for inst in &self.instances {
            let mesh = &self.meshes[inst.mesh as usize];
            if !inst.moves() && !mesh.moves() {
                for p in &mesh.positions {
                    let w = inst.object_to_world.transform_point3a(*p);
                    lo = lo.min(w);
                    hi = hi.max(w);
                }
                continue;
            }
            for key in world_key_positions(inst, mesh) {
                for w in key {
                    lo = lo.min(w);
                    hi = hi.max(w);
                }
            }
        }
        (lo, hi)
    }

    /// Number of triangles over all instances.
    pub fn instanced_triangles(&self) -> usize {
        self.instances.iter().map(|i| self.meshes[i.mesh as usize].triangles.len()).sum()
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
                    .map(|i| motion_path(mesh.positions[i], &mesh.motion_vectors(i, vectors), tau))
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

/// Keys over the shutter of each of the scene's lights (scene order) whose instance moves:
/// its world → world displacement from where it is at motion time 0 (empty for a light
/// that stays).
fn light_keys(shutter: &Shutter, scene: &Scene, warnings: &mut Vec<String>) -> Vec<Vec<Affine3A>> {
    let limit = scene::sanity::WORLD_LIMIT as f32;
    let steps = scene.options.motion_steps as usize;
    scene
        .lights
        .iter()
        .map(|light| {
            let Some(end) = light.motion_light_to_world else { return Vec::new() };
            let (start, end) = (affine(light.light_to_world), affine(end));
            if start == end {
                return Vec::new();
            }
            let back = start.inverse();
            let keys: Vec<Affine3A> =
                transform_keys(start, end, shutter, steps).into_iter().map(|k| k * back).collect();
            if !keys.iter().all(|k| k.is_finite() && k.translation.abs().max_element() <= limit) {
                warnings.push(format!("light '{}' moves beyond single precision: it is kept still", light.instance));
                return Vec::new();
            }
            if matches!(&light.area, Some(a) if matches!(a.shape, scene::AreaShape::Object { .. })) {
                warnings.push(format!(
                    "light '{}' moves while the shutter is open: the classic engine's light shaders see its object \
                     light's triangles where they are at the shutter's opening (its position and direction move)",
                    light.instance
                ));
            }
            keys
        })
        .collect()
}

/// World-space positions of an instance's mesh at each key of its motion (the more keys of
/// the instance's and the mesh's), for acceleration structures that store moving
/// triangles in world space.
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
