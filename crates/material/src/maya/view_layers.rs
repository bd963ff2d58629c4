//! A layeredShader whose rampShader layers have `transparency` or `incandescence` ramps
//! that follow the view, in the path engine: the classic rampShader reads them at each
//! ray's facing ratio f = N·V and the layered shader composites the layers by those
//! transparencies, so the path engine tabulates the whole stack over f — its
//! transparency Π T_i(f), its lit colour Σ w_i(f) d_i and its emission Σ w_i(f) e_i(f),
//! w_i(f) = T_0(f) ⊙ ⋯ ⊙ T_(i−1)(f) ⊙ (1 − T_i(f)) per channel, the rules of the constant stack
//! (see `crate::maya`'s module doc) at each f — and sets each hit from the table
//! ([`ViewTransparency::stack`]) instead of taking the ramps at f = 1. The layers'
//! translucence lobes are weighted by their shares w_i(f) at each hit too
//! ([`StackTranslucence`]: the stack's lobes held by the material, evaluated by the hit's
//! BSDF at f), as the classic stack composites its layers' light from behind at the
//! facing ratio of the ray that sees it.

use bsdf::maya_highlight::translucent_stack::{StackAt, StackLayer, StackLobe, TranslucentStack};
use bsdf::maya_highlight::VIEW_RAMP_STEPS;
use bsdf::{MayaGlossy, Rgb};
use shader::{Graph, NodeId};

use super::ramp_shader::ramp_of;
use super::{Reader, ViewTransparency};

/// A quantity at the facing ratios k/32, k = 0 … 32.
type Table = [Rgb; VIEW_RAMP_STEPS];

/// One layer of the stack at the facing ratios k/32.
pub(super) struct Layer {
    /// Its transparency.
    transparency: Table,
    /// A material layer's diffuse colour (its albedo, unfaded).
    diffuse: Rgb,
    /// A material layer's incandescence (unfaded).
    emission: Table,
    /// A plain colour layer's colour (`None` for a material).
    plain: Option<Rgb>,
    /// A material layer's translucence lobes before its share
    /// (`bsdf::MayaGlossy::translucence_parts`); empty: not translucent.
    lobes: Vec<StackLobe>,
}

impl Layer {
    /// A material layer of constant transparency `t`, diffuse colour and incandescence,
    /// or of the transparency and incandescence tables `ramps` ([`ramp_tables`]).
    pub(super) fn material(t: Rgb, diffuse: Rgb, emission: Rgb, ramps: Option<[Table; 2]>) -> Layer {
        let (transparency, emission) = match ramps {
            Some([t, e]) => (t, e),
            None => ([t; VIEW_RAMP_STEPS], [emission; VIEW_RAMP_STEPS]),
        };
        Layer { transparency, diffuse, emission, plain: None, lobes: Vec::new() }
    }

    /// The same layer with the translucence lobes of its material's model `g` (before its
    /// share; see [`Layer::lobes`]).
    pub(super) fn with_lobes(mut self, g: &MayaGlossy) -> Layer {
        self.lobes = g.translucence_parts();
        self
    }

    /// A plain colour layer `c` of transparency `t` (black for a layer the path engine
    /// leaves out).
    pub(super) fn plain(t: Rgb, c: Rgb) -> Layer {
        Layer {
            transparency: [t; VIEW_RAMP_STEPS],
            diffuse: Rgb::ZERO,
            emission: [Rgb::ZERO; VIEW_RAMP_STEPS],
            plain: Some(c),
            lobes: Vec::new(),
        }
    }
}

/// The transparency (clamped to [0, 1]) and incandescence ramps (the latter with the
/// ambient colour's C_ref ⊙ a added) of the rampShader `m` at the facing ratios k/32
/// when either varies with the view; `None` for other
/// materials and for ramps that are the same all along (a connected ramp takes its
/// default, as in the rampShader's own translation).
pub(super) fn ramp_tables(graph: &Graph, m: NodeId) -> Option<[Table; 2]> {
    let family = graph.nodes[m as usize].decl.name.trim_start_matches("maya_").trim_start_matches("adskMaya");
    if !family.eq_ignore_ascii_case("rampshader") {
        return None;
    }
    let mut r = Reader { graph, node: m, bindings: Vec::new(), warnings: Vec::new() };
    let table = |r: &mut Reader, name: &str| -> Table {
        let ramp = ramp_of(r, name, "Color", Rgb::ZERO);
        std::array::from_fn(|k| {
            ramp.as_ref().map_or(Rgb::ZERO, |ramp| {
                let c = ramp.at(k as f32 / (VIEW_RAMP_STEPS - 1) as f32);
                Rgb::new(c.x, c.y, c.z)
            })
        })
    };
    let transparency = table(&mut r, "transparency").map(|t| t.clamp(Rgb::ZERO, Rgb::ONE));
    // The ambient colour's C_ref ⊙ a joins the incandescence (both emitted, faded alike).
    let ambient = super::ramp_shader::Ambient::read(&mut r);
    let incandescence = table(&mut r, "incandescence");
    let incandescence: Table =
        std::array::from_fn(|k| incandescence[k] + ambient.at(k as f32 / (VIEW_RAMP_STEPS - 1) as f32));
    let varies = |t: &Table| t.iter().any(|x| (*x - t[VIEW_RAMP_STEPS - 1]).abs().max_element() > 1e-6);
    (varies(&transparency) || varies(&incandescence)).then_some([transparency, incandescence])
}

/// The stack `layers` (top first; `texture`: `compositingFlag` 1, plain colours weighted
/// by their opacity) tabulated over the facing ratio, each layer's share w_i per channel;
/// `below` is the transparency of the layers under the last of `layers` (those under a
/// refracting layer, which shadow rays still pass: white when there are none). The
/// stack's third table is the light `layers` let through, P_n(f): a refracting last
/// layer's refraction weight (see [`ViewTransparency::refracting`]).
pub(super) fn tabulate(layers: &[Layer], texture: bool, below: Rgb) -> ViewTransparency {
    let mut transparency = [Rgb::ZERO; VIEW_RAMP_STEPS];
    let mut lit = [Rgb::ZERO; VIEW_RAMP_STEPS];
    let mut emission = [Rgb::ZERO; VIEW_RAMP_STEPS];
    let mut passed = [Rgb::ZERO; VIEW_RAMP_STEPS];
    for k in 0..VIEW_RAMP_STEPS {
        let mut through = Rgb::ONE;
        for l in layers {
            let t = l.transparency[k].clamp(Rgb::ZERO, Rgb::ONE);
            let w = through * (Rgb::ONE - t);
            match l.plain {
                Some(c) => lit[k] += if texture { c * w } else { c * through },
                None => {
                    lit[k] += l.diffuse * w;
                    emission[k] += l.emission[k] * w;
                }
            }
            through *= t;
        }
        transparency[k] = through * below;
        passed[k] = through;
    }
    let view = ViewTransparency::stack(transparency, lit, emission, passed);
    if layers.iter().any(|l| !l.lobes.is_empty()) {
        let layers = layers
            .iter()
            .map(|l| StackLayer { transparency: l.transparency.to_vec(), lobes: l.lobes.clone() })
            .collect();
        view.with_stack_translucence(StackTranslucence { stack: TranslucentStack::interned(layers) })
    } else {
        view
    }
}

/// The translucence of a layeredShader stack whose layers' transparencies follow the
/// view: each layer's transparency T_i at the facing ratios k/32 and its translucence
/// lobes before its share, held for the material (`bsdf::maya_highlight::translucent_stack`).
/// At a hit of facing ratio f the stack's lobes are Σ_i w_i(f) ⊙ (layer i's lobes),
/// w_i(f) = T_0(f) ⊙ ⋯ ⊙ T_(i−1)(f) ⊙ (1 − T_i(f)) per channel — the shares the classic
/// stack composites its layers by at that ray — each T_i(f) read linearly between the
/// table's points (exact for a linear ramp whose knots lie on k/32) and the product taken
/// at f: the hit's BSDF evaluates them itself, exactly for any number of layers, foci and
/// ramps (no lobe merged, nothing allocated per hit).
#[derive(Clone, Debug, PartialEq)]
pub struct StackTranslucence {
    /// The stack's layers and lobes (interned).
    pub stack: &'static TranslucentStack,
}

impl StackTranslucence {
    /// `g` with its translucence replaced by the stack's at facing ratio `facing`, every
    /// lobe's albedo divided by `coverage` (the hit's, as its diffuse colour is; 1 for a
    /// refracting stack).
    pub fn apply(&self, facing: f32, coverage: f32, g: &MayaGlossy) -> MayaGlossy {
        let mut out = g.with_translucence_stack(self.stack);
        let scale = if coverage > 0.0 { 1.0 / coverage } else { 1.0 };
        out.translucence_stack = Some(StackAt { stack: self.stack, facing: facing.clamp(0.0, 1.0), scale });
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A layer whose transparency runs 1 − f over an opaque one of diffuse d and
    /// incandescence e: at f = 0.75 (a table point) the stack is opaque, its lit colour
    /// 0.75 · d_top + 0.25 · d and its emission 0.25 · e (within 1e-6).
    #[test]
    fn the_stack_follows_the_top_layers_transparency() {
        let top_t: Table = std::array::from_fn(|k| Rgb::splat(1.0 - k as f32 / 32.0));
        let top = Layer::material(Rgb::ZERO, Rgb::new(0.8, 0.0, 0.0), Rgb::ZERO, Some([top_t, [Rgb::ZERO; 33]]));
        let (d, e) = (Rgb::new(0.0, 0.5, 0.0), Rgb::new(0.0, 0.0, 2.0));
        let bottom = Layer::material(Rgb::ZERO, d, e, None);
        let v = tabulate(&[top, bottom], false, Rgb::ONE);
        let stack = v.stack.as_ref().expect("a stack");
        assert_eq!(v.transparency[24], Rgb::ZERO);
        assert!((stack[0][24] - (Rgb::new(0.8, 0.0, 0.0) * 0.75 + d * 0.25)).abs().max_element() < 1e-6);
        assert!((stack[1][24] - e * 0.25).abs().max_element() < 1e-6);
    }
}
