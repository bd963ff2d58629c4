//! Maya's displacementShader node (`maya_displace`, the name mental ray for Maya's
//! translator gives that node type; `adskMayaDisplacementShader`), connected to a shading
//! group's displacement through `maya_material_displace` (`"displacement" =
//! "<node>.displacement"`). It runs in the renderer's displacement stage, once per vertex.
//!
//! Parameters (Maya's node reference; defaults as there):
//! - `displacement` (scalar, 0) × `scale` (1): the output `displacement`, the distance the
//!   vertex moves along its normal (object-space units, see the renderer's stage);
//! - `vectorDisplacement` (vector, 0 0 0) × `scale`: a move in `vectorSpace` — 0 world,
//!   1 object (the default), 2 tangent (x along the tangent, y along the normal, z along
//!   the binormal N × T; with `yIsUp` off, y and z swap) — decoded by `vectorEncoding`:
//!   0 floating point absolute (as is), 1 signed encoding (v ↦ 2v − 1, fixed-point maps).
//!   It is used when connected or not zero (an unconnected zero vector with signed
//!   encoding would otherwise move every vertex by −1). The move is written to
//!   `state.point` (world space), which mental ray lets displacement shaders move;
//! - `displacementMode` (0) of older Maya versions: 1, 2, 3 select a vector displacement in
//!   tangent, object, world space (overriding `vectorSpace`);
//! - `tangent` (vector, object space): the tangent of tangent space where not zero; else
//!   the surface's bump basis u vector, else its dP/du — Maya's UV tangent, the direction
//!   of increasing u of the first texture space (the displacement stage gives each vertex
//!   the mean dP/du of its triangles, from their texture coordinates) — else, on a
//!   surface without texture coordinates, the world x axis (y where x is along the
//!   normal); each made perpendicular to the normal.
//!
//! Unverified: the order of `vectorSpace`'s values (taken from the order the node
//! reference lists them: world, object, tangent, with its default 1) and the `adskMaya*`
//! spelling.

use glam::Vec3A;
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::values::write_struct;

/// Parameter indices (the order of `params` below).
const DISPLACEMENT: usize = 0;
const MODE: usize = 1;
const SCALE: usize = 2;
const VECTOR: usize = 3;
const ENCODING: usize = 4;
const SPACE: usize = 5;
const TANGENT: usize = 6;
const Y_IS_UP: usize = 7;

maya_shader!(
    /// displacementShader: `displacement` × `scale` along the normal, plus
    /// `vectorDisplacement` × `scale` in `vectorSpace` (see the module).
    DISPLACE,
    ADSK_DISPLACE,
    "maya_displace",
    "adskMayaDisplacementShader",
    &["displacement", "displacementMode", "scale", "vectorDisplacement", "vectorEncoding", "vectorSpace", "tangent", "yIsUp"],
    displace
);

/// The space a vector displacement is written in.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Space {
    World,
    Object,
    Tangent,
}

fn displace(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let scale = ctx.scalar(n, SCALE);
    let d = ctx.scalar(n, DISPLACEMENT) * scale;
    let mode = ctx.int(n, MODE);
    let raw = ctx.vector(n, VECTOR);
    if mode != 0 || ctx.is_connected(n, VECTOR) || raw != Vec3A::ZERO {
        let v = match ctx.int(n, ENCODING) {
            1 => raw * 2.0 - Vec3A::ONE,
            _ => raw,
        };
        let space = match (mode, ctx.int(n, SPACE)) {
            (1, _) | (0, 2) => Space::Tangent,
            (2, _) | (0, 1) => Space::Object,
            _ => Space::World,
        };
        let world = match space {
            Space::World => v,
            Space::Object => ctx.state.object_to_world.transform_vector3a(v),
            Space::Tangent => {
                let normal = ctx.state.normal.normalize_or_zero();
                let t = tangent(ctx, n, normal);
                let b = normal.cross(t);
                let (along_n, along_b) = if ctx.bool(n, Y_IS_UP) { (v.y, v.z) } else { (v.z, v.y) };
                t * v.x + normal * along_n + b * along_b
            }
        };
        let moved = world * scale;
        if moved.is_finite() {
            ctx.state.point += moved;
        }
    }
    write_struct(out, &[("displacement", Value::Scalar(d))]);
    true
}

/// The unit tangent of tangent space at the shading point (world space, perpendicular to
/// the unit `normal`).
fn tangent(ctx: &mut Ctx, n: NodeId, normal: Vec3A) -> Vec3A {
    let given = ctx.vector(n, TANGENT);
    let candidates = [
        ctx.state.object_to_world.transform_vector3a(given),
        ctx.state.bump_basis.map_or(Vec3A::ZERO, |b| b[0]),
        ctx.state.derivs[0],
        Vec3A::X,
        Vec3A::Y,
    ];
    candidates
        .into_iter()
        .map(|t| (t - normal * t.dot(normal)).normalize_or_zero())
        .find(|t| *t != Vec3A::ZERO)
        .unwrap_or(Vec3A::X)
}
