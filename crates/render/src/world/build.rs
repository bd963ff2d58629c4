//! Building the world from a scene: its meshes (moved or copied), materials, instances,
//! hair, lights, frame buffers and, when things move while the shutter is open, their keys.

use std::sync::Arc;

use material::SurfaceMaterial;
use scene::Scene;
use shader::Shading;

use super::lights::{ambient_lights, scene_lights, shadow_unlinked_lights, unlinked_lights, SceneLights};
use super::meshes::{copy_of_rendered_arrays, mesh_data};
use super::{deforming_emitters, hair, instance, light_motion, motion_keys, InstanceData, World};
use crate::camera::CameraModel;
use crate::mesh::MeshData;
use crate::motion::Shutter;

/// Divides the emission of materials given for their whole surface (MDL `lumen`,
/// `candela`) by the world-space area of the triangles that carry them: the area each
/// material's emission was divided by (0: none), see [`World::spread_areas`].
fn spread_emission(materials: &mut [SurfaceMaterial], meshes: &[MeshData], instances: &[InstanceData]) -> Vec<f32> {
    if !materials.iter().any(|m| m.emission_over_area) {
        return Vec::new();
    }
    let spread: Vec<bool> = materials.iter().map(|m| m.emission_over_area).collect();
    let area = areas_of(&spread, meshes, instances);
    for (m, a) in materials.iter_mut().zip(&area) {
        m.spread_emission_over(*a);
    }
    spread.iter().zip(area).map(|(s, a)| if *s { a } else { 0.0 }).collect()
}

/// The world-space area of the triangles of each material `m` with `picked[m]` (0 for
/// the others).
pub fn areas_of(picked: &[bool], meshes: &[MeshData], instances: &[InstanceData]) -> Vec<f32> {
    let mut area = vec![0.0f64; picked.len()];
    for inst in instances {
        let mesh = &meshes[inst.mesh as usize];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let slot = mesh.slots.get(t).copied().unwrap_or(0) as usize;
            let m = inst.materials.get(slot).copied().unwrap_or(0) as usize;
            if !picked.get(m).copied().unwrap_or(false) {
                continue;
            }
            let [a, b, c] = tri.map(|i| inst.object_to_world.transform_point3a(mesh.position(i)));
            area[m] += 0.5 * f64::from((b - a).cross(c - a).length());
        }
    }
    area.into_iter().map(|a| a as f32).collect()
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
        let meshes = scene
            .objects
            .iter()
            .map(|o| mesh_data(&mut copy_of_rendered_arrays(&o.geometry.mesh, mdl.quad_ptex), mdl.quad_ptex))
            .collect();
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
        let meshes = scene.objects.iter_mut().map(|o| mesh_data(&mut o.geometry.mesh, mdl.quad_ptex)).collect();
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
        let (ambient, ambient_indices) = ambient_lights(scene);
        let mut materials = vec![SurfaceMaterial::grey("(no material)")];
        for (i, m) in scene.materials.iter().enumerate() {
            let (mat, w) = material::translate_with(m, &scene.library, shading.map(|s| (s, i)), Some(mdl));
            warnings.extend(w);
            materials.push(mat);
        }
        // (Maya's `translucenceDepth` lets shadow rays through the object's own surfaces.)
        let has_cutouts =
            materials.iter().any(|m| m.may_cut_out(shading.map(|s| &s.graph)) || m.translucence_depth > 0.0);
        let mut shadow_opaque: Vec<bool> =
            std::iter::once(false).chain(scene.materials.iter().map(marked_opaque)).collect();
        if !shadow_opaque.contains(&true) {
            shadow_opaque = Vec::new();
        }
        let has_media = materials.iter().any(|m| m.medium.is_some() && m.has_inside());
        let object_has_triangles: Vec<bool> = meshes.iter().map(|m| !m.triangles.is_empty()).collect();
        let mut meshes = meshes;
        // Hair: one ribbon mesh per object with hair, after the objects' meshes.
        let hair_mesh = hair::crossed_meshes(scene, &mut meshes);
        let mut instances = instance::object_instances(scene, &object_has_triangles);
        let facing_hair = hair::place_hair(scene, &hair_mesh, &mut meshes, &mut instances);
        let spread_areas = spread_emission(&mut materials, &meshes, &instances);
        let mut lights = lights;
        warnings.extend(light_warnings);
        let mut user_buffers = user_buffers(scene);
        let glow_buffer = crate::output_shaders::glow_buffer(scene, &mut user_buffers);
        let mut camera = CameraModel::new(&scene.camera);
        let mut light_motion = Vec::new();
        let mut light_meshes = Vec::new();
        let weights = shading.and_then(|s| s.shutter_weights.as_deref());
        let shutter = Shutter::from_options(&scene.options, weights).filter(|shutter| {
            let deforming;
            (light_motion, deforming) = light_motion::light_keys(shutter, scene, &mut warnings);
            let lights_move = light_motion.iter().any(|k| !k.is_empty());
            let moving =
                motion_keys::set_motion_keys(shutter, scene, &mut meshes, &mut instances, &mut camera, &mut warnings);
            light_meshes = deforming_emitters::deforming_meshes(&deforming, &meshes, &instances);
            for (light, index) in &mut lights {
                light.motion = light_motion[*index].clone();
                if let (Some(keys), shader::light::Shape::Mesh(mesh)) = (&light_meshes[*index], &light.shape) {
                    light.shape = shader::light::Shape::Mesh(Arc::new((**mesh).clone().deforming(Arc::clone(keys))));
                }
            }
            hair::turn_facing_meshes(&facing_hair, scene, &mut meshes, &instances, &camera);
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
        let shadow_unlinked = shadow_unlinked_lights(scene, &instances, &light_indices);
        let lights = lights.into_iter().map(|(l, _)| l).collect();
        // Large still meshes as quads for the acceleration structure (their triangles
        // reordered, so before anything below reads them by index) — unless a Ptex file
        // names faces by triangle index and corner.
        if !mdl.reads_ptex {
            for mesh in &mut meshes {
                mesh.pair_into_quads();
            }
        }
        let faces = super::FaceCache::build(&meshes, &instances);
        World {
            meshes,
            instances,
            materials,
            lights,
            ambient,
            unlinked_lights,
            unlinked_ambient,
            shadow_unlinked,
            camera,
            options: scene.options.clone(),
            user_buffers,
            glow_buffer,
            warnings,
            has_cutouts,
            shadow_opaque,
            has_media,
            shutter,
            light_motion,
            light_meshes,
            light_scene_indices: light_indices,
            spread_areas,
            faces,
        }
    }
}

/// The user frame buffers `scene` declares, (name, data type): the options' numbered
/// buffers (`fbN`) in order, then the camera's named user buffers not among them.
fn user_buffers(scene: &Scene) -> Vec<(String, String)> {
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
    user_buffers
}

/// Whether the scene material `m` carries mental ray's `opaque` flag (in its last
/// definition: an incremental redefinition replaces the material as a whole).
fn marked_opaque(m: &scene::Material) -> bool {
    match &m.kind {
        scene::MaterialKind::Material(defs) => {
            defs.last().is_some_and(|d| d.stmts.iter().any(|s| matches!(s, mi::ast::Stmt::Kw(k) if k.key == "opaque")))
        }
        _ => false,
    }
}
