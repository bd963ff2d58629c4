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
//!
//! A layer whose material refracts (`refractions` on, `refractiveIndex` not 1, its
//! transparency not black: the material traces a refraction ray, bent within its
//! `refractionLimit` and straight past it, see `crate::material::behind_with`) shows
//! through its transparency what that ray finds, and the layers below it do not show:
//! its colour is taken whole, as the last layer, `out = Σ_(i<k) P_i ⊙ c_i' + P_k ⊙ c_k`.
//! Maya's reference says nothing of refraction in a layered shader: this reading (the
//! refraction ray leaves the surface, so nothing below the refracting layer is crossed)
//! is mira's. Shadow rays still pass the whole stack by P_n.

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

/// For each element of the `inputs` array, the shader its `color` is connected to when
/// its result is a Maya material's (it has an `outTransparency` member).
fn material_layers(ctx: &Ctx, n: NodeId) -> Vec<Option<NodeId>> {
    let Some(Slot::Array(elements)) = ctx.node(n).slots.first() else { return Vec::new() };
    elements
        .iter()
        .map(|e| {
            let Slot::Struct(members) = e else { return None };
            members.iter().find_map(|(name, slot)| match slot {
                Slot::Connect { node, .. }
                    if &**name == "color"
                        && ctx.node(*node).decl.members().iter().any(|m| &**m == "outTransparency") =>
                {
                    Some(*node)
                }
                _ => None,
            })
        })
        .collect()
}

/// Whether the Maya material `m` traces a refraction ray where it is transparent:
/// `refractions` on and a positive `refractiveIndex` other than 1 (as
/// `crate::material::behind_with` decides; false for a node without them).
fn refracts(ctx: &mut Ctx, m: NodeId) -> bool {
    let index = |ctx: &Ctx, name: &str| {
        let node = ctx.node(m);
        match node.imp {
            Some(imp) => imp.params.iter().position(|p| *p == name),
            None => node.decl.param(name),
        }
    };
    let (Some(on), Some(ior)) = (index(ctx, "refractions"), index(ctx, "refractiveIndex")) else { return false };
    let ior = ctx.scalar(m, ior);
    ctx.bool(m, on) && ior > 0.0 && (ior - 1.0).abs() > 1e-6
}

fn layered_shader(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let texture = ctx.int(n, 1) == 1;
    let from_material = material_layers(ctx, n);
    let inputs = ctx.array(n, 0);
    let mut layers: Vec<ShaderLayer> = inputs
        .array()
        .iter()
        .enumerate()
        .map(|(i, e)| ShaderLayer {
            color: e.member("color").map_or(Vec3A::ZERO, |c| rgb(c.color())),
            transparency: e.member("transparency").map_or(Vec3A::ZERO, |c| rgb(c.color())),
            includes_behind: from_material.get(i).is_some_and(Option::is_some),
        })
        .collect();
    let (_, through) = composite_layers(&layers, texture, Vec3A::ZERO);
    if ctx.state.ray_type == RayType::Shadow {
        return crate::material::shadow_filter(out, through);
    }
    if !ctx.state.ray_type.is_visible() {
        return false;
    }
    // The first layer whose material refracts is the last that shows, whole (its
    // colour holds what its refraction ray found; see the module doc).
    let refracting = (0..layers.len()).find(|&i| {
        layers[i].transparency.clamp(Vec3A::ZERO, Vec3A::ONE) != Vec3A::ZERO
            && from_material.get(i).copied().flatten().is_some_and(|m| refracts(ctx, m))
    });
    if let Some(k) = refracting {
        layers.truncate(k + 1);
        layers[k] = ShaderLayer { color: layers[k].color, transparency: Vec3A::ZERO, includes_behind: false };
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
