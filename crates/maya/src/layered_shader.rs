//! Maya's layeredShader: materials (or colours) stacked with their transparencies.
//!
//! Parameters (`mayabase.mi`): `inputs`, an array of {`color`, `transparency`,
//! `glowColor`} whose element 0 is the top layer (exports connect `color` to a material's
//! `outColor` and `transparency` to its `outTransparency`), and `compositingFlag`:
//!
//! - 0, layer shader: each layer's colour is already weighted by its opacity, as a
//!   material's is; with P_i = T_0 ⊙ … ⊙ T_(i−1) the light that reaches layer i,
//!   `out = Σ P_i ⊙ c_i + P_n ⊙ behind`;
//! - 1, layer texture: colours are plain, `out = Σ P_i ⊙ (1 − T_i) ⊙ c_i + P_n ⊙ behind`.
//!
//! `outTransparency` is P_n (the product of all transparencies), `outGlowColor` is
//! Σ P_i ⊙ glow_i. Maya's materials (and mira's) add what lies behind them, T_i ⊙ behind,
//! to their own `outColor`; for a layer whose `color` is connected to such a material the
//! shader takes that share out again (c_i − T_i ⊙ behind, with what lies behind traced once
//! here), so that the stack shows what lies behind only through all of its layers. The
//! two formulas are Maya's documented meaning of the flag (shaders composite by their
//! transparency, textures as colours over one another) in mira's notation.

use glam::Vec3A;
use shader::{Color, Ctx, NodeId, RayType, Slot, Value};

use crate::maya_shader;
use crate::values::{rgb, rgba, write_struct};

/// One layer of the stack.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShaderLayer {
    /// Its colour (a material's `outColor`, which includes `transparency ⊙ behind` when
    /// `includes_behind`).
    pub color: Vec3A,
    /// Its transparency.
    pub transparency: Vec3A,
    /// Its colour already holds transparency ⊙ behind (a material's result).
    pub includes_behind: bool,
}

/// The stack `layers` (top first) over `behind`, for `compositingFlag` 0 (`texture`
/// false) or 1: the colour and the total transparency.
pub fn composite_layers(layers: &[ShaderLayer], texture: bool, behind: Vec3A) -> (Vec3A, Vec3A) {
    let mut through = Vec3A::ONE;
    let mut color = Vec3A::ZERO;
    for l in layers {
        let t = l.transparency.clamp(Vec3A::ZERO, Vec3A::ONE);
        let own = if texture {
            (Vec3A::ONE - t) * l.color
        } else if l.includes_behind {
            l.color - t * behind
        } else {
            l.color
        };
        color += through * own;
        through *= t;
    }
    (color + through * behind, through)
}

maya_shader!(
    /// Maya's layeredShader (see the module doc).
    LAYEREDSHADER,
    ADSK_LAYEREDSHADER,
    "maya_layeredshader",
    "adskMayaLayeredShader",
    &["inputs", "compositingFlag"],
    layered_shader
);

/// For each element of the `inputs` array, whether its `color` is connected to a shader
/// whose result is a Maya material's (it has an `outTransparency` member).
fn material_layers(ctx: &Ctx, n: NodeId) -> Vec<bool> {
    let Some(Slot::Array(elements)) = ctx.node(n).slots.first() else { return Vec::new() };
    elements
        .iter()
        .map(|e| {
            let Slot::Struct(members) = e else { return false };
            members.iter().any(|(name, slot)| {
                &**name == "color"
                    && matches!(slot, Slot::Connect { node, .. }
                        if ctx.node(*node).decl.members().iter().any(|m| &**m == "outTransparency"))
            })
        })
        .collect()
}

fn layered_shader(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let texture = ctx.int(n, 1) == 1;
    let from_material = material_layers(ctx, n);
    let inputs = ctx.array(n, 0);
    let layers: Vec<ShaderLayer> = inputs
        .array()
        .iter()
        .enumerate()
        .map(|(i, e)| ShaderLayer {
            color: e.member("color").map_or(Vec3A::ZERO, |c| rgb(c.color())),
            transparency: e.member("transparency").map_or(Vec3A::ZERO, |c| rgb(c.color())),
            includes_behind: from_material.get(i).copied().unwrap_or(false),
        })
        .collect();
    let (_, through) = composite_layers(&layers, texture, Vec3A::ZERO);
    if ctx.state.ray_type == RayType::Shadow {
        return crate::material::shadow_filter(out, through);
    }
    if !ctx.state.ray_type.is_visible() {
        return false;
    }
    let needs_behind =
        through != Vec3A::ZERO || layers.iter().any(|l| l.includes_behind && l.transparency != Vec3A::ZERO);
    let behind = if needs_behind { ctx.trace_transparent().unwrap_or(Color::ZERO) } else { Color::ZERO };
    let (color, through) = composite_layers(&layers, texture, rgb(behind));
    let mut glow = Vec3A::ZERO;
    let mut reach = Vec3A::ONE;
    for (e, l) in inputs.array().iter().zip(&layers) {
        glow += reach * e.member("glowColor").map_or(Vec3A::ZERO, |c| rgb(c.color()));
        reach *= l.transparency.clamp(Vec3A::ZERO, Vec3A::ONE);
    }
    let t_mean = (through.x + through.y + through.z) / 3.0;
    let alpha = 1.0 - t_mean + t_mean * behind.w;
    write_struct(
        out,
        &[
            ("outColor", Value::Color(rgba(color, alpha))),
            ("outTransparency", Value::Color(rgba(through, t_mean))),
            ("outGlowColor", Value::Color(rgba(glow, 1.0))),
            ("outMatteOpacity", Value::Color(Color::ONE)),
        ],
    );
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shaders_composite_by_their_transparency_and_show_what_is_behind_once() {
        let behind = Vec3A::new(0.0, 0.0, 1.0);
        let red = Vec3A::new(1.0, 0.0, 0.0);
        let green = Vec3A::new(0.0, 1.0, 0.0);
        // A 25 %-transparent red material over an opaque green one: as materials return
        // them, red·0.75 + 0.25·behind and green.
        let top =
            ShaderLayer { color: red * 0.75 + 0.25 * behind, transparency: Vec3A::splat(0.25), includes_behind: true };
        let bottom = ShaderLayer { color: green, transparency: Vec3A::ZERO, includes_behind: true };
        let (c, t) = composite_layers(&[top, bottom], false, behind);
        assert!((c - (red * 0.75 + green * 0.25)).abs().max_element() < 1e-6, "{c}");
        assert_eq!(t, Vec3A::ZERO);
        // Both half transparent: behind shows through a quarter.
        let half = |c: Vec3A| ShaderLayer {
            color: c * 0.5 + 0.5 * behind,
            transparency: Vec3A::splat(0.5),
            includes_behind: true,
        };
        let (c, t) = composite_layers(&[half(red), half(green)], false, behind);
        assert!((c - (red * 0.5 + green * 0.25 + behind * 0.25)).abs().max_element() < 1e-6, "{c}");
        assert!((t - Vec3A::splat(0.25)).abs().max_element() < 1e-6);
    }

    #[test]
    fn textures_composite_as_plain_colours() {
        let red = Vec3A::new(1.0, 0.0, 0.0);
        let grey = Vec3A::splat(0.5);
        let layers = [
            ShaderLayer { color: red, transparency: Vec3A::splat(0.6), includes_behind: false },
            ShaderLayer { color: grey, transparency: Vec3A::ZERO, includes_behind: false },
        ];
        let (c, t) = composite_layers(&layers, true, Vec3A::ONE);
        assert!((c - (red * 0.4 + grey * 0.6)).abs().max_element() < 1e-6, "{c}");
        assert_eq!(t, Vec3A::ZERO);
        // Constant colours in shader mode are taken as already weighted.
        let (c, _) = composite_layers(&layers, false, Vec3A::ONE);
        assert!((c - (red + grey * 0.6)).abs().max_element() < 1e-6, "{c}");
    }
}
