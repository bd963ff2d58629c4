//! Maya's layeredTexture: colours with alphas blended layer over layer.
//!
//! Parameters (see `mayabase.mi`): `inputs`, an array of {`color`, `alpha`, `blendMode`,
//! `isVisible`} whose element 0 is the top layer, and `alphaIsLuminance` (each layer's
//! alpha is its colour's luminance). Layers are blended from the bottom up: the bottom
//! visible layer over black of alpha 0, then each layer above with its `blendMode`, its
//! alpha a weighting the blend (fg the layer's colour, bg the result below):
//!
//! | mode | colour | | mode | colour |
//! |---|---|---|---|---|
//! | 0 none | fg | | 7 difference | bg + a (|fg − bg| − bg) |
//! | 1 over | bg + a (fg − bg) | | 8 lighten | bg + a (max(fg, bg) − bg) |
//! | 2 in | bg · a | | 9 darken | bg + a (min(fg, bg) − bg) |
//! | 3 out | bg · (1 − a) | | 10 saturate | bg · (1 + a fg) |
//! | 4 add | bg + a fg | | 11 desaturate | bg · (1 − a fg) |
//! | 5 subtract | bg − a fg | | 12 illuminate | bg · (1 + 2 a fg) |
//! | 6 multiply | bg · (1 + a (fg − 1)) | | | |
//!
//! The result's alpha: `none` takes the layer's, `in`/`out` scale the alpha below by a /
//! (1 − a), the others composite a over it (a + bg_α (1 − a)). Maya names the modes and
//! describes their effect; the formulas are mira's reading of that description.

use glam::Vec3A;
use shader::{Ctx, NodeId, Value};

use crate::maya_shader;
use crate::values::{luma, rgb, rgba, write_struct};

/// One layer: colour, alpha, blend mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer {
    /// The layer's colour.
    pub color: Vec3A,
    /// Its alpha (how much of it shows).
    pub alpha: f32,
    /// Maya's blend mode (see the module doc).
    pub mode: i32,
}

/// Blends `layer` onto the colour and alpha below it.
pub fn blend(below: (Vec3A, f32), layer: Layer) -> (Vec3A, f32) {
    let (bg, ba) = below;
    let (fg, a) = (layer.color, layer.alpha.clamp(0.0, 1.0));
    let over_alpha = a + ba * (1.0 - a);
    match layer.mode {
        0 => (fg, a),
        2 => (bg * a, ba * a),
        3 => (bg * (1.0 - a), ba * (1.0 - a)),
        4 => (bg + a * fg, over_alpha),
        5 => (bg - a * fg, over_alpha),
        6 => (bg * (Vec3A::ONE + a * (fg - Vec3A::ONE)), over_alpha),
        7 => (bg + a * ((fg - bg).abs() - bg), over_alpha),
        8 => (bg + a * (fg.max(bg) - bg), over_alpha),
        9 => (bg + a * (fg.min(bg) - bg), over_alpha),
        10 => (bg * (Vec3A::ONE + a * fg), over_alpha),
        11 => (bg * (Vec3A::ONE - a * fg), over_alpha),
        12 => (bg * (Vec3A::ONE + 2.0 * a * fg), over_alpha),
        _ => (bg + a * (fg - bg), over_alpha),
    }
}

/// The stack `layers` (top first) blended from the bottom up.
pub fn composite(layers: &[Layer]) -> (Vec3A, f32) {
    layers.iter().rev().fold((Vec3A::ZERO, 0.0), |below, &l| blend(below, l))
}

maya_shader!(
    /// Maya's layeredTexture (see the module doc).
    LAYEREDTEXTURE,
    ADSK_LAYEREDTEXTURE,
    "maya_layeredtexture",
    "adskMayaLayeredTexture",
    &["inputs", "alphaIsLuminance"],
    layered_texture
);

fn layered_texture(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let luminance_alpha = ctx.bool(n, 1);
    let inputs = ctx.array(n, 0);
    let layers: Vec<Layer> = inputs
        .array()
        .iter()
        .filter(|e| e.member("isVisible").is_none_or(Value::bool))
        .map(|e| {
            let color = e.member("color").map_or(Vec3A::ZERO, |c| rgb(c.color()));
            let alpha = if luminance_alpha { luma(color) } else { e.member("alpha").map_or(1.0, Value::scalar) };
            Layer { color, alpha, mode: e.member("blendMode").map_or(1, Value::int) }
        })
        .collect();
    let (c, a) = composite(&layers);
    write_struct(out, &[("outColor", Value::Color(rgba(c, a))), ("outAlpha", Value::Scalar(a))]);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: (Vec3A, f32), b: (Vec3A, f32)) {
        assert!((a.0 - b.0).length() < 1e-6 && (a.1 - b.1).abs() < 1e-6, "{a:?} vs {b:?}");
    }

    #[test]
    fn layers_blend_from_the_bottom_up() {
        let red = Vec3A::new(1.0, 0.0, 0.0);
        let grey = Vec3A::splat(0.5);
        // Half-transparent red over opaque grey: (0.75, 0.25, 0.25), alpha 1.
        let stack = [Layer { color: red, alpha: 0.5, mode: 1 }, Layer { color: grey, alpha: 1.0, mode: 1 }];
        close(composite(&stack), (Vec3A::new(0.75, 0.25, 0.25), 1.0));
        // Multiply at full alpha: grey · red.
        let m = [Layer { color: red, alpha: 1.0, mode: 6 }, Layer { color: grey, alpha: 1.0, mode: 1 }];
        close(composite(&m), (Vec3A::new(0.5, 0.0, 0.0), 1.0));
        // Add at alpha 0.5, subtract, lighten, darken, difference.
        let on = |mode: i32, alpha: f32| {
            composite(&[Layer { color: red, alpha, mode }, Layer { color: grey, alpha: 1.0, mode: 1 }])
        };
        close(on(4, 0.5), (Vec3A::new(1.0, 0.5, 0.5), 1.0));
        close(on(5, 1.0), (Vec3A::new(-0.5, 0.5, 0.5), 1.0));
        close(on(8, 1.0), (Vec3A::new(1.0, 0.5, 0.5), 1.0));
        close(on(9, 1.0), (Vec3A::new(0.5, 0.0, 0.0), 1.0));
        close(on(7, 1.0), (Vec3A::new(0.5, 0.5, 0.5), 1.0));
        // In / out keep the background where the layer's alpha is / is not.
        close(on(2, 0.25), (grey * 0.25, 0.25));
        close(on(3, 0.25), (grey * 0.75, 0.75));
        // None: the layer alone.
        close(on(0, 0.4), (red, 0.4));
        // Nothing: transparent black.
        close(composite(&[]), (Vec3A::ZERO, 0.0));
    }
}
