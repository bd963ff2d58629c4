//! Stage 2b, **displace**: moves the surfaces of objects whose material has a
//! displacement shader (mental ray's `material … displace "shader" … end material`, a
//! Maya shading group's `displacementShader` through `maya_material_displace`), run by
//! [`crate::pipeline::build_world`] after the world is translated, so that both engines
//! trace the same displaced triangles.
//!
//! For each instance whose material has one, its object's triangles are split uniformly
//! ([`subdivide`]) by the object's `approximate displace` statement (else the options'
//! `approximate displace … all`): `[regular] parametric L` splits each triangle into 4^L
//! (each edge into 2^L parts); the other forms (`length`, `view length`, `fine`, `angle`,
//! `spatial`, …) are not implemented and take [`DEFAULT_LEVEL`] with a warning at their
//! line; without any, the object's own vertices are displaced (level 0). The shader runs
//! at every vertex (the classic shader model, a state with the world-space point and
//! normal, the interpolated texture coordinates, the instance and material); its scalar
//! result (a colour result: its red component, as mental ray reads a scalar there) is
//! the distance the vertex moves along its unit object-space normal, clamped to
//! ±`max displace` (the object's, else the options') where given. Normals are then
//! recomputed from the displaced triangles (area-weighted).
//!
//! Limits: at most [`MAX_DISPLACED_TRIANGLES`] triangles are made in all; an explicit level
//! past that is an error at the `approximate` statement (nothing is rendered), the default
//! level is lowered with a warning. Meshes whose vertices move over the shutter and hair
//! are not displaced (a warning). Object area lights and emission spread over the area
//! use the undisplaced surface. Instances of one object with the same materials share one
//! displaced mesh, the shader evaluated where the first of them places it (world-space
//! lookups differ between such instances in mental ray).

pub mod subdivide;

use std::collections::HashMap;

use glam::Vec3A;
use mi::ast::{ApproxTerm, Approximation};
use mi::Diagnostic;
use scene::Scene;
use shader::{Ctx, NoScene, NodeId, Shading, State, Value};

use crate::mesh::MeshData;
use crate::world::World;

/// The subdivision level of approximation forms mira does not implement (each triangle
/// into 4² = 16).
pub const DEFAULT_LEVEL: u32 = 2;

/// Most triangles the displacement stage makes, all displaced meshes together (about
/// 80 bytes each with their vertices).
pub const MAX_DISPLACED_TRIANGLES: usize = 1 << 23;

/// Displaces the instances of `world` whose materials have a displacement shader in
/// `shading` (`scene` gives the objects' and options' approximations). Scenes without
/// displacement shaders are left untouched. Messages go to `diagnostics`.
pub fn displace_world(world: &mut World, scene: &Scene, shading: &Shading, diagnostics: &mut Vec<Diagnostic>) {
    if !shading.materials.iter().any(|m| m.displace.is_some()) {
        return;
    }
    // World material m > 0 is scene material m − 1.
    let shader_of = |m: u32| m.checked_sub(1).and_then(|m| shading.materials.get(m as usize)).and_then(|m| m.displace);
    // Each (mesh, materials) pair is displaced once, whichever instances share it.
    let mut made: HashMap<(u32, Vec<u32>), Option<u32>> = HashMap::new();
    let mut budget = MAX_DISPLACED_TRIANGLES;
    // The material lists each mesh is placed with: a mesh placed with one list only is
    // replaced by its displaced form, not kept twice.
    let mut placements: HashMap<u32, Vec<&[u32]>> = HashMap::new();
    for inst in &world.instances {
        let lists = placements.entry(inst.mesh).or_default();
        if !lists.contains(&inst.materials.as_slice()) {
            lists.push(&inst.materials);
        }
    }
    let alone: std::collections::HashSet<u32> =
        placements.into_iter().filter(|(_, l)| l.len() == 1).map(|(m, _)| m).collect();
    for index in 0..world.instances.len() {
        let inst = &world.instances[index];
        let (mesh_index, materials) = (inst.mesh, inst.materials.clone());
        if !materials.iter().any(|&m| shader_of(m).is_some()) {
            continue;
        }
        let key = (mesh_index, materials.clone());
        let target = match made.get(&key) {
            Some(t) => *t,
            None => {
                let t = displace_mesh(world, scene, shading, index, &shader_of, &mut budget, diagnostics).map(|mesh| {
                    if alone.contains(&mesh_index) {
                        world.meshes[mesh_index as usize] = mesh;
                        mesh_index
                    } else {
                        world.meshes.push(mesh);
                        (world.meshes.len() - 1) as u32
                    }
                });
                made.insert(key, t);
                t
            }
        };
        if let Some(t) = target {
            world.instances[index].mesh = t;
        }
    }
}

/// The displaced mesh of instance `index` (`None`: left as it is, with a message).
fn displace_mesh(
    world: &World,
    scene: &Scene,
    shading: &Shading,
    index: usize,
    shader_of: &(dyn Fn(u32) -> Option<NodeId> + Sync),
    budget: &mut usize,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<MeshData> {
    let inst = &world.instances[index];
    let mesh = &world.meshes[inst.mesh as usize];
    let object = scene.objects.get(inst.mesh as usize).filter(|_| mesh.hair.is_none());
    let object = object?;
    let span = object.span;
    if mesh.moves() || !mesh.motion.is_empty() {
        diagnostics.push(Diagnostic::warning(
            span,
            format!("object '{}': its vertices move; it is not displaced (not implemented)", object.name),
        ));
        return None;
    }
    let settings = &object.displace;
    let approximation = settings.approximation.as_ref().or(scene.options.displace.approximation.as_ref());
    // `f32::clamp` panics on a negative or NaN bound: a hostile `max displace -1` bounds by 1.
    let max_displace =
        settings.max_displace.or(scene.options.displace.max_displace).map(|d| (d as f32).abs()).filter(|d| !d.is_nan());
    let triangles = mesh.triangles.len();
    let level = match approximation {
        None => 0,
        Some(a) => match parametric_level(a) {
            Some(level) => {
                let made = triangles as f64 * 4f64.powf(level);
                if made > *budget as f64 {
                    diagnostics.push(Diagnostic::error(
                        a.span,
                        format!(
                            "object '{}': approximate displace parametric {level} would make {made:.3e} triangles, \
                             more than the {} displacement may make",
                            object.name, *budget
                        ),
                    ));
                    return None;
                }
                level as u32
            }
            None => {
                let mut level = DEFAULT_LEVEL;
                while level > 0 && triangles.saturating_mul(1 << (2 * level)) > *budget {
                    level -= 1;
                }
                diagnostics.push(Diagnostic::warning(
                    a.span,
                    format!(
                        "object '{}': approximate displace {} is not implemented; each triangle is split into {} \
                         (parametric {level})",
                        object.name,
                        form(a),
                        1u32 << (2 * level)
                    ),
                ));
                level
            }
        },
    };
    let made = triangles << (2 * level);
    if made > *budget {
        diagnostics.push(Diagnostic::error(
            span,
            format!("object '{}': displacing it would make more triangles than displacement may make", object.name),
        ));
        return None;
    }
    *budget -= made;
    let sub = subdivide::subdivide(mesh, 1 << level);
    let mut out = sub.mesh;
    let material_of = |t: u32| -> u32 {
        let slot = out.slots.get(t as usize).copied().unwrap_or(0) as usize;
        inst.materials.get(slot).copied().unwrap_or(0)
    };
    let heights: Vec<f32> = {
        use rayon::prelude::*;
        let out = &out;
        (0..out.positions.len())
            .into_par_iter()
            .map(|v| {
                let owner = sub.owner[v];
                if owner == u32::MAX {
                    return 0.0;
                }
                let m = material_of(owner);
                let Some(node) = shader_of(m) else { return 0.0 };
                let d = height(shading, node, out, v, m, inst);
                match max_displace {
                    Some(max) => d.clamp(-max, max),
                    None => d,
                }
            })
            .collect()
    };
    for (v, d) in heights.iter().enumerate() {
        if *d != 0.0 {
            out.positions[v] += out.normals[v] * *d;
        }
    }
    out.normals = subdivide::vertex_normals(&out.positions, &out.triangles);
    Some(out)
}

/// What the displacement shader list `node` returns at vertex `v` of `mesh` (material
/// `m` of the world, placed by `inst`): object-space units along the normal.
fn height(
    shading: &Shading,
    node: NodeId,
    mesh: &MeshData,
    v: usize,
    m: u32,
    inst: &crate::world::InstanceData,
) -> f32 {
    let p = Vec3A::from(mesh.positions[v]);
    let n = Vec3A::from(mesh.normals[v]);
    let point = inst.object_to_world.transform_point3a(p);
    let normal = (inst.normal_to_world * n).normalize_or_zero();
    let mut state = State {
        point,
        shadow_point: point,
        normal,
        normal_geom: normal,
        dir: -normal,
        org: point + normal,
        dist: 1.0,
        dot_nd: -1.0,
        object_to_world: inst.object_to_world,
        world_to_object: inst.world_to_object,
        instance: inst.scene_index,
        label: inst.tag,
        material: m.checked_sub(1),
        ior_in: 1.0,
        ior: 1.0,
        ..State::default()
    };
    state.tex_count = mesh.textures.len().min(shader::state::MAX_TEXTURES);
    for (k, t) in mesh.textures.iter().take(shader::state::MAX_TEXTURES).enumerate() {
        state.tex_list[k] = t[v];
    }
    if let Some([u, w]) = mesh.bump_basis.get(v) {
        state.bump_basis =
            Some([inst.object_to_world.transform_vector3a(*u), inst.object_to_world.transform_vector3a(*w)]);
    }
    let mut ctx = Ctx::new(shading, &NoScene, state);
    let mut result = Value::Scalar(0.0);
    if !ctx.run_list(node, &mut result) {
        return 0.0;
    }
    let d = match result {
        Value::Scalar(s) => s,
        Value::Color(c) => c.x,
        Value::Int(i) => i as f32,
        _ => 0.0,
    };
    if d.is_finite() {
        d
    } else {
        0.0
    }
}

/// The subdivision level `parametric L` asks for (`regular parametric L …`; L below 0 is
/// 0, fractions are cut), `None` for other forms.
fn parametric_level(a: &Approximation) -> Option<f64> {
    let at = a.technique.iter().position(|t| *t == ApproxTerm::Word("parametric"))?;
    match a.technique.get(at + 1) {
        Some(ApproxTerm::Num(n)) => Some(n.as_f64().max(0.0).floor()),
        _ => None,
    }
}

/// The technique words of an approximation (`view length`, `fine`, …), for messages.
fn form(a: &Approximation) -> String {
    let words: Vec<&str> =
        a.technique.iter().filter_map(|t| if let ApproxTerm::Word(w) = t { Some(*w) } else { None }).collect();
    if words.is_empty() {
        "(no technique)".to_string()
    } else {
        words.join(" ")
    }
}
