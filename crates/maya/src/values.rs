//! Small helpers shared by the modules: colour conversions, struct results and the
//! evaluation of a connected shader's whole result.

use std::sync::Arc;

use glam::{Vec3A, Vec4};
use shader::{Color, Ctx, NodeId, Slot, Value};

/// RGB of a colour.
#[inline]
pub(crate) fn rgb(c: Color) -> Vec3A {
    Vec3A::new(c.x, c.y, c.z)
}

/// A colour from RGB and alpha.
#[inline]
pub(crate) fn rgba(c: Vec3A, a: f32) -> Color {
    Vec4::new(c.x, c.y, c.z, a)
}

/// Writes a struct result: each named member takes its value; members of the declared
/// result not named keep theirs. A result that is not a struct becomes one.
pub(crate) fn write_struct(out: &mut Value, members: &[(&str, Value)]) {
    let existing: Vec<(Arc<str>, Value)> = match out {
        Value::Struct(m) => m.to_vec(),
        _ => Vec::new(),
    };
    let mut result = existing;
    for (name, v) in members {
        match result.iter_mut().find(|(n, _)| &**n == *name) {
            Some(slot) => slot.1 = v.clone(),
            None => result.push((Arc::from(*name), v.clone())),
        }
    }
    *out = Value::Struct(result.into());
}

/// The whole result of the shader parameter `i` of `node` is connected to (not only the
/// member the connection names), or `None` if the parameter is a constant.
pub(crate) fn connected_result(ctx: &mut Ctx, node: NodeId, i: usize) -> Option<Value> {
    match ctx.node(node).slots.get(i) {
        Some(Slot::Connect { node: source, .. }) => {
            let source = *source;
            Some(ctx.result(source))
        }
        _ => None,
    }
}

/// A member of a struct value as a colour (`None` if absent).
pub(crate) fn member_color(v: &Value, name: &str) -> Option<Color> {
    v.member(name).map(Value::color)
}

/// Rec. 601 luma weights, which Maya's luminance node and alphaIsLuminance use.
pub(crate) fn luma(c: Vec3A) -> f32 {
    0.3 * c.x + 0.59 * c.y + 0.11 * c.z
}
