//! mental ray 3.7's `"shutter shape function"` string option: a shader the scene declares,
//! evaluated over the shutter interval, whose result is how far the shutter is open (its
//! transparency) at each time. The shading compiler finds the shader
//! (`Shading::shutter_shape`); [`tabulate_into`] evaluates it once over the interval into
//! `Shading::shutter_weights`, and the renderer draws sample times from that table.

use mi::Diagnostic;

use super::graph::NodeId;
use super::shading::Shading;
use super::state::State;
use super::tracer::NoScene;
use super::value::Value;
use super::Ctx;

/// The name of the string option.
pub const OPTION: &str = "shutter shape function";

/// Shutter times the shape shader is evaluated at.
pub const TABLE_SIZE: usize = 256;

/// Tabulates the scene's shutter shape shader (`shading.shutter_shape`, if any) into
/// `shading.shutter_weights` at [`TABLE_SIZE`] shutter times `(i + ½) / TABLE_SIZE` over
/// the interval (see [`tabulate`]); when it cannot be used, a warning at the string
/// option's statement says why and the weights stay unset.
pub fn tabulate_into(shading: &mut Shading, options: &scene::Options, diags: &mut Vec<Diagnostic>) {
    let Some(node) = shading.shutter_shape else { return };
    shading.shutter_weights = match tabulate(shading, node, TABLE_SIZE) {
        Ok(w) => Some(w),
        Err(why) => {
            let span = options.string_option_spans.get(OPTION).copied().unwrap_or_default();
            diags.push(Diagnostic::warning(
                span,
                format!(
                    "string option \"{OPTION}\": {why}; the shutter's shape is that of \"shutter full open\" and \
                     \"shutter full close\""
                ),
            ));
            None
        }
    };
}

/// The shader `node`'s result at `count` shutter times `(i + ½) / count` over the interval
/// (the shader sees `State::time` = that shutter time, 0 at the opening, 1 at the close,
/// and a scene it cannot trace into): a scalar result as it is, a colour's luminance
/// (Rec. 709 weights), negative values as 0. An error saying why when the shader fails
/// (returns false), gives a value that is not finite, or is 0 all along.
pub fn tabulate(shading: &Shading, node: NodeId, count: usize) -> Result<Vec<f32>, String> {
    let mut weights = Vec::with_capacity(count);
    for i in 0..count {
        let time = (i as f32 + 0.5) / count as f32;
        let state = State { time, ..State::default() };
        let mut ctx = Ctx::new(shading, &NoScene, state);
        let mut result = Value::Scalar(0.0);
        if !ctx.run_list(node, &mut result) {
            return Err(format!("its shader failed at shutter time {time}"));
        }
        let w = match result {
            Value::Color(c) => 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z,
            other => other.scalar(),
        };
        if !w.is_finite() {
            return Err(format!("its shader gave {w} at shutter time {time}"));
        }
        weights.push(w.max(0.0));
    }
    if weights.iter().all(|w| *w == 0.0) {
        return Err("its shader keeps the shutter closed all along (0 everywhere)".into());
    }
    Ok(weights)
}
