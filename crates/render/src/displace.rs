//! Stage 2b, **displace**: moves the surfaces of objects whose material has a
//! displacement shader (mental ray's `material … displace "shader" … end material`, a
//! Maya shading group's `displacementShader` through `maya_material_displace`), run by
//! [`crate::pipeline::build_world`] after the world is translated, so that both engines
//! trace the same displaced triangles.
//!
//! For each instance whose material has one, its object's triangles are subdivided by the
//! options' `approximate displace … all` where given (mental ray: the options'
//! approximations override the objects'), else the object's `approximate displace`
//! statement, read by [`plan`]: `[regular] parametric L` splits each triangle uniformly into
//! 4^L ([`subdivide`]); the criteria forms (`length`, `distance`, `angle`, `spatial`,
//! `curvature`, with `view`, `any`, `fine` and the least/greatest levels) refine edge by
//! edge until the displaced triangles meet them ([`adaptive`]); forms mira does not
//! implement (percentages, `fine` without a criterion) take [`DEFAULT_LEVEL`] with a
//! warning at their line, invalid values (a length of 0, a negative level) are an error
//! there; without any statement, the object's own vertices are displaced (level 0). The
//! shader runs at every vertex (the classic shader model, a state with the world-space
//! point and normal, the interpolated texture coordinates, their surface derivatives
//! dP/du, dP/dv as `state.derivs` ([`uv_derivs`]; on meshes without a bump basis), the
//! instance and material);
//! its scalar result (a colour result: its red component, as mental ray reads a scalar
//! there) is the distance the vertex moves along its unit object-space normal, clamped to
//! ±`max displace` (the object's, else the options') where given; a shader that moves
//! `state.point` or turns `state.normal` moves the vertex accordingly (vector
//! displacement, see [`offset`]). Normals are then recomputed from the displaced
//! triangles (area-weighted), and the approximation's `sharp` leans them towards the
//! triangles' faceted normals (see [`displace_mesh`]).
//!
//! Limits: at most [`MAX_DISPLACED_TRIANGLES`] triangles are made in all; an explicit level
//! or an adaptive refinement past that is an error at the `approximate` statement (the
//! object is not displaced), the default level is lowered with a warning. Hair is not
//! displaced. A mesh whose vertices move (motion vectors, `motion steps`) is displaced at
//! every motion step on the same finer triangles ([`moving`]); a moving instance's `view`
//! criteria hold over the whole shutter ([`adaptive::View::over_shutter`]). Object area lights whose
//! geometry is displaced emit from the displaced triangles, and emission given for a
//! whole surface (MDL `lumen`, `candela`) is spread over its displaced area ([`emitters`]).
//! Instances of one object with the same materials share one
//! displaced mesh, the shader evaluated where the first of them places it (world-space
//! lookups differ between such instances in mental ray).

pub mod adaptive;
pub mod emitters;
pub mod moving;
pub mod plan;
pub mod subdivide;
pub mod uv_derivs;

use std::collections::HashMap;

use glam::{Vec3, Vec3A};
use mi::Diagnostic;
use scene::Scene;
use shader::{Ctx, NoScene, NodeId, Shading, State, Value};

use crate::mesh::MeshData;
use crate::world::World;
use plan::{Plan, Reading};

/// The subdivision level of approximation forms mira does not implement (each triangle
/// into 4² = 16).
pub const DEFAULT_LEVEL: u32 = 2;

/// Most triangles the displacement stage makes, all displaced meshes together (about
/// 80 bytes each with their vertices).
pub const MAX_DISPLACED_TRIANGLES: usize = 1 << 23;

/// Displaces the instances of `world` whose materials have a displacement shader in
/// `shading` (`scene` gives the objects' and options' approximations). Scenes without
/// displacement shaders are left untouched. Messages go to `diagnostics`.
pub fn displace_world(world: &mut World, scene: &Scene, shading: &mut Shading, diagnostics: &mut Vec<Diagnostic>) {
    if !shading.materials.iter().any(|m| m.displace.is_some()) {
        return;
    }
    // World material m > 0 is scene material m − 1.
    let mut displaced = std::collections::HashSet::new();
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
            displaced.insert(world.instances[index].scene_index);
        }
    }
    emitters::reshape_object_lights(world, scene, shading, &displaced, diagnostics);
    emitters::respread_emission(world, &displaced);
    // The displaced meshes' faces, and no faces of the meshes they replaced.
    world.cache_faces();
}

/// The displaced mesh of instance `index` (`None`: left as it is, with a message), its
/// shading normals set by the approximation's `sharp` ([`plan::sharpness`]): 0 (or none)
/// keeps the smooth vertex normals, 1 drops them (every hit shades with its triangle's
/// geometric normal), a value between leans the interpolated normal towards the geometric
/// one at every hit ([`MeshData::sharpen`]).
fn displace_mesh(
    world: &World,
    scene: &Scene,
    shading: &Shading,
    index: usize,
    shader_of: &(dyn Fn(u32) -> Option<NodeId> + Sync),
    budget: &mut usize,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<MeshData> {
    let mut out = displace_vertices(world, scene, shading, index, shader_of, budget, diagnostics)?;
    let object = scene.objects.get(world.instances[index].mesh as usize)?;
    let approximation = scene.options.displace.approximation.as_ref().or(object.displace.approximation.as_ref());
    if let Some(a) = approximation {
        let name = &object.name;
        let (sharp, warning) = plan::sharpness(a);
        if let Some(w) = warning {
            diagnostics.push(Diagnostic::warning(a.span, format!("object '{name}': approximate displace: {w}")));
        }
        for said in plan::unused(a) {
            diagnostics.push(Diagnostic::warning(a.span, format!("object '{name}': approximate displace: {said}")));
        }
        match sharp {
            Some(s) if s >= 1.0 => {
                out.normals = Vec::new();
                out.normals_oct = Vec::new();
            }
            Some(s) if s > 0.0 => out.sharp = s,
            _ => {}
        }
    }
    Some(out)
}

/// The displaced vertices and triangles of instance `index`, with smooth normals
/// (`None`: left as it is, with a message).
fn displace_vertices(
    world: &World,
    scene: &Scene,
    shading: &Shading,
    index: usize,
    shader_of: &(dyn Fn(u32) -> Option<NodeId> + Sync),
    budget: &mut usize,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<MeshData> {
    let inst = &world.instances[index];
    let original = &world.meshes[inst.mesh as usize];
    // The subdivision reads the positions as a slice: an interleaved large mesh's copied out.
    let plain;
    let original = if original.is_interleaved() {
        plain = original.to_plain();
        &plain
    } else {
        original
    };
    let object = scene.objects.get(inst.mesh as usize).filter(|_| original.hair.is_none());
    let object = object?;
    let span = object.span;
    // The vertices' dP/du, dP/dv from the texture coordinates ride through the subdivision
    // in the bump basis's place (interpolated alike) when the mesh has no bump basis, and
    // reach the shaders as `state.derivs` (see `offset`); the displaced mesh keeps none.
    let with_derivs;
    let (base, uv_derivs) = match original.bump_basis.is_empty().then(|| uv_derivs::vertex_derivs(original)).flatten() {
        Some(derivs) => {
            with_derivs = MeshData { bump_basis: derivs, ..original.clone() };
            (&with_derivs, true)
        }
        None => (original, false),
    };
    // A mesh whose vertices move carries its motion steps through the subdivision.
    let steps = moving::steps_of(base);
    let carried;
    let mesh = if steps > 0 {
        carried = moving::carry_steps(base, steps);
        &carried
    } else {
        base
    };
    let first_carried = base.user.len();
    let settings = &object.displace;
    // mental ray: the options' approximation statements override the objects' (quick
    // previews at a lower tessellation quality).
    let approximation = scene.options.displace.approximation.as_ref().or(settings.approximation.as_ref());
    // `f32::clamp` panics on a negative or NaN bound: a hostile `max displace -1` bounds by 1.
    let max_displace =
        settings.max_displace.or(scene.options.displace.max_displace).map(|d| (d as f32).abs()).filter(|d| !d.is_nan());
    let triangles = mesh.triangles.len();
    let name = &object.name;
    let plan = match approximation {
        None => Plan::Uniform(0),
        Some(a) => match plan::read(a) {
            Reading::Plan(p, warnings) => {
                for w in warnings {
                    diagnostics
                        .push(Diagnostic::warning(a.span, format!("object '{name}': approximate displace: {w}")));
                }
                p
            }
            Reading::Invalid(why) => {
                diagnostics.push(Diagnostic::error(
                    a.span,
                    format!("object '{name}': approximate displace {}: {why}; it is not displaced", plan::words(a)),
                ));
                return None;
            }
            Reading::Unsupported(words) => {
                let mut level = DEFAULT_LEVEL;
                while level > 0 && triangles.saturating_mul(1 << (2 * level)) > *budget {
                    level -= 1;
                }
                diagnostics.push(Diagnostic::warning(
                    a.span,
                    format!(
                        "object '{name}': approximate displace {words} is not implemented; each triangle is split \
                         into {} (parametric {level})",
                        1u32 << (2 * level)
                    ),
                ));
                Plan::Uniform(level)
            }
        },
    };
    let material_of = |slot: u32| -> u32 { inst.materials.get(slot as usize).copied().unwrap_or(0) };
    let offset_with = |mesh: &MeshData, v: usize, p: Vec3, n: Vec3, slot: u32| -> Vec3 {
        let m = material_of(slot);
        match shader_of(m) {
            Some(node) => offset(shading, node, (mesh, v, uv_derivs), (p, n), m, inst, max_displace),
            None => Vec3::ZERO,
        }
    };
    let offset_at =
        |mesh: &MeshData, v: usize, slot: u32| offset_with(mesh, v, mesh.positions[v], mesh.normals[v], slot);
    // The moving mesh's every step displaced on the finer triangles, and its keys over the shutter.
    let finish_moving = |mut out: MeshData| -> MeshData {
        if steps > 0 {
            moving::displace_steps(&mut out, first_carried, steps, &offset_with);
            if let Some(Some(keys)) =
                world.shutter.as_ref().filter(|_| original.moves()).and_then(|s| crate::world::vertex_keys(s, &out))
            {
                out.position_keys = keys;
            }
        }
        if uv_derivs {
            out.bump_basis = Vec::new();
        }
        out
    };
    let level = match plan {
        Plan::Uniform(level) => level,
        Plan::Adaptive(criteria) => {
            let view = adaptive::View::over_shutter(inst, &world.camera);
            let carry = !original.ptex_quads.is_empty();
            return match adaptive::refine(mesh, &criteria, Some(&view), *budget, &offset_at, carry) {
                Ok((mut out, fine)) => {
                    *budget -= out.triangles.len();
                    out.ptex_split = ptex_split_of(original, 0, fine);
                    Some(finish_moving(out))
                }
                Err(made) => {
                    let a = approximation.map_or(span, |a| a.span);
                    diagnostics.push(Diagnostic::error(
                        a,
                        format!(
                            "object '{name}': approximate displace {} would make {made} triangles, more than the {} \
                             displacement may make",
                            approximation.map(plan::words).unwrap_or_default(),
                            *budget
                        ),
                    ));
                    None
                }
            };
        }
    };
    if let Some(a) = approximation.filter(|_| level > 0) {
        let made = triangles as f64 * 4f64.powf(level as f64);
        if made > *budget as f64 {
            diagnostics.push(Diagnostic::error(
                a.span,
                format!(
                    "object '{name}': approximate displace parametric {level} would make {made:.3e} triangles, \
                     more than the {} displacement may make",
                    *budget
                ),
            ));
            return None;
        }
    }
    let level = level.min(15);
    let made = triangles << (2 * level);
    if made > *budget {
        diagnostics.push(Diagnostic::error(
            span,
            format!("object '{name}': displacing it would make more triangles than displacement may make"),
        ));
        return None;
    }
    *budget -= made;
    let sub = subdivide::subdivide(mesh, 1 << level);
    let mut out = sub.mesh;
    out.ptex_split = ptex_split_of(original, 1 << level, Vec::new());
    if steps > 0 {
        return Some(finish_moving(out));
    }
    let slot_of = |t: u32| -> u32 { out.slots.get(t as usize).copied().unwrap_or(0) };
    let offsets: Vec<Vec3> = {
        use rayon::prelude::*;
        let out = &out;
        (0..out.positions.len())
            .into_par_iter()
            .map(|v| match sub.owner[v] {
                u32::MAX => Vec3::ZERO,
                owner => offset_at(out, v, slot_of(owner)),
            })
            .collect()
    };
    for (v, d) in offsets.iter().enumerate() {
        if *d != Vec3::ZERO {
            out.positions[v] += *d;
        }
    }
    out.normals = subdivide::vertex_normals(&out.positions, &out.triangles);
    if uv_derivs {
        out.bump_basis = Vec::new();
    }
    Some(out)
}

/// The quad-mesh Ptex faces of `original` for a mesh split from it (n × n, or unevenly
/// where `fine` says where each fine triangle lies), which each fine triangle keeps
/// ([`crate::mesh::ptex_split`]); `None` where it keeps none (the scene reads no
/// quad-mesh Ptex file, or the mesh has no polygons).
fn ptex_split_of(
    original: &MeshData,
    n: u32,
    fine: Vec<crate::mesh::ptex_split::FineOrigin>,
) -> Option<std::sync::Arc<crate::mesh::ptex_split::PtexSplit>> {
    if original.ptex_quads.is_empty() {
        return None;
    }
    Some(std::sync::Arc::new(crate::mesh::ptex_split::PtexSplit {
        n,
        fine,
        codes: original.ptex_quads.clone(),
        ngons: original.ptex_ngons.clone(),
        refined: original.ptex_refined.clone(),
        triangles: original.triangles.clone(),
        positions: original.positions.clone(),
    }))
}

/// Where the displacement shader list `node` moves vertex `v` of `mesh` (its texture
/// coordinates and bump basis; material `m` of the world, placed by `inst`) when it
/// stands at the object-space point `p` with the unit object-space normal `n`: the
/// object-space offset. `uv_derivs`: the mesh's bump basis holds the vertices' dP/du,
/// dP/dv from the texture coordinates ([`uv_derivs::vertex_derivs`]), given to the shader
/// as `state.derivs` (world space); else a bump basis is the state's bump basis. Its
/// scalar result d (clamped to
/// ±`max`) moves the vertex along its unit object-space normal; as mental ray allows, a
/// shader may also move `state.point` (the vertex, world space: the move is added) and
/// turn `state.normal` (the direction d moves along); then the offset's length is clamped
/// to `max`.
#[allow(clippy::too_many_arguments)]
fn offset(
    shading: &Shading,
    node: NodeId,
    (mesh, v, uv_derivs): (&MeshData, usize, bool),
    (p, n): (Vec3, Vec3),
    m: u32,
    inst: &crate::world::InstanceData,
    max: Option<f32>,
) -> Vec3 {
    let (p, n) = (Vec3A::from(p), Vec3A::from(n));
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
        let basis = [inst.object_to_world.transform_vector3a(*u), inst.object_to_world.transform_vector3a(*w)];
        if uv_derivs {
            state.derivs = basis;
        } else {
            state.bump_basis = Some(basis);
        }
    }
    let mut ctx = Ctx::new(shading, &NoScene, state);
    let mut result = Value::Scalar(0.0);
    if !ctx.run_list(node, &mut result) {
        return Vec3::ZERO;
    }
    let d = match result {
        Value::Scalar(s) => s,
        Value::Color(c) => c.x,
        Value::Int(i) => i as f32,
        _ => 0.0,
    };
    let d = if d.is_finite() { d } else { 0.0 };
    let d = match max {
        Some(max) => d.clamp(-max, max),
        None => d,
    };
    let (moved, turned) = (ctx.state.point - point, ctx.state.normal);
    if moved == Vec3A::ZERO && turned == normal {
        return Vec3::from(n * d);
    }
    let along =
        if turned == normal { n } else { (inst.object_to_world.matrix3.transpose() * turned).normalize_or_zero() };
    let moved = if moved.is_finite() { inst.world_to_object.transform_vector3a(moved) } else { Vec3A::ZERO };
    let off = along * d + moved;
    Vec3::from(match max {
        Some(max) if off.length() > max => off * (max / off.length()),
        _ => off,
    })
}
