//! What Maya exports put around the image: the `maya_colormgt` / `adskMayaColorMgt`
//! output shader's view transform.
//!
//! An output shader works on the finished image, outside the shader model; the renderer
//! reads the shader call's parameters with [`colormgt_view`] and encodes display images
//! with the [`ViewTransform`] (linear outputs such as EXR stay linear). Parameters read:
//! `enable` (off: no transform, the raw values) and `viewTransform` (a name as Maya's
//! colour-management preferences spell it: "sRGB gamma", "Rec 709 gamma", "Raw",
//! "Gamma 2.2" …). `frameBuffer` names the buffer it applies to; the integer
//! `inputSpace` / `outputSpace` of older exports are not interpreted (their numbering is
//! not documented), so they leave the default, sRGB.

use mi::ast::{Param, Value};

/// A display encoding of linear values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ViewTransform {
    /// No encoding: the linear values ("Raw", "Linear").
    Raw,
    /// The sRGB transfer function (IEC 61966-2-1).
    Srgb,
    /// The Rec. 709 (ITU-R BT.709) camera transfer function.
    Rec709,
    /// A pure power law v^(1/γ).
    Gamma(f32),
}

impl ViewTransform {
    /// The transform a view name denotes (case and punctuation ignored), if known.
    pub fn from_name(name: &str) -> Option<ViewTransform> {
        let key: String = name.chars().filter(char::is_ascii_alphanumeric).collect::<String>().to_ascii_lowercase();
        match key.as_str() {
            "raw" | "linear" | "none" => Some(ViewTransform::Raw),
            "srgb" | "srgbgamma" => Some(ViewTransform::Srgb),
            "rec709" | "rec709gamma" | "bt709" => Some(ViewTransform::Rec709),
            _ => {
                let g = key.strip_prefix("gamma")?;
                // "gamma22" → 2.2, "gamma18" → 1.8 (the point is lost with punctuation).
                let g = name
                    .split_whitespace()
                    .find_map(|w| w.parse::<f32>().ok())
                    .or_else(|| g.parse::<f32>().ok().map(|v| if v >= 10.0 { v / 10.0 } else { v }))?;
                (g > 0.0).then_some(ViewTransform::Gamma(g))
            }
        }
    }

    /// The display value of a linear value (negative values give 0).
    pub fn encode(self, v: f32) -> f32 {
        let v = v.max(0.0);
        match self {
            ViewTransform::Raw => v,
            ViewTransform::Srgb => {
                if v <= 0.003_130_8 {
                    12.92 * v
                } else {
                    1.055 * v.powf(1.0 / 2.4) - 0.055
                }
            }
            ViewTransform::Rec709 => {
                if v < 0.018 {
                    4.5 * v
                } else {
                    1.099 * v.powf(0.45) - 0.099
                }
            }
            ViewTransform::Gamma(g) => v.powf(1.0 / g),
        }
    }
}

/// The view transform of a `maya_colormgt` call's parameters: `Raw` when `enable` is off,
/// the named `viewTransform`, sRGB when none is named. An unknown name is an error
/// message for the caller to report (with the call's position).
pub fn colormgt_view(params: &[Param]) -> Result<ViewTransform, String> {
    let last = |name: &str| params.iter().rev().find(|p| p.name.text == name).map(|p| &p.value);
    if let Some(Value::Bool(false)) = last("enable") {
        return Ok(ViewTransform::Raw);
    }
    match last("viewTransform") {
        Some(Value::Str(n)) => ViewTransform::from_name(&n.text)
            .ok_or_else(|| format!("maya_colormgt: unknown view transform '{}'; sRGB is used instead", n.text)),
        _ => Ok(ViewTransform::Srgb),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn view_names_and_encodings() {
        assert_eq!(ViewTransform::from_name("sRGB gamma"), Some(ViewTransform::Srgb));
        assert_eq!(ViewTransform::from_name("Rec 709 gamma"), Some(ViewTransform::Rec709));
        assert_eq!(ViewTransform::from_name("Raw"), Some(ViewTransform::Raw));
        assert_eq!(ViewTransform::from_name("Gamma 2.2"), Some(ViewTransform::Gamma(2.2)));
        assert_eq!(ViewTransform::from_name("Gamma 1.8"), Some(ViewTransform::Gamma(1.8)));
        assert_eq!(ViewTransform::from_name("Log"), None);
        // Published values: 18 % grey is 0.4614 in sRGB and 0.409 in Rec. 709.
        assert!((ViewTransform::Srgb.encode(0.18) - 0.461_356).abs() < 1e-5);
        assert!((ViewTransform::Rec709.encode(0.18) - 0.409).abs() < 1e-3);
        // Both curves are continuous at their breakpoints and map 1 to 1.
        for t in [ViewTransform::Srgb, ViewTransform::Rec709] {
            assert!((t.encode(1.0) - 1.0).abs() < 1e-3);
        }
        let b = 0.003_130_8f32;
        assert!((ViewTransform::Srgb.encode(b) - ViewTransform::Srgb.encode(b + 1e-7)).abs() < 1e-4);
        assert!((ViewTransform::Rec709.encode(0.018) - 0.081).abs() < 1e-3);
        assert!((ViewTransform::Gamma(2.0).encode(0.25) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn colormgt_parameters() {
        // The parameters of a call written like the camera's output statement.
        let params = |text: &str| -> Vec<Param> {
            let call = mi::parse_str("t.mi", &format!("shader \"s\" \"maya_colormgt\" ({text})"));
            for item in call.items {
                if let mi::ast::Item::Shader(def) = item {
                    if let Some(mi::ast::ShaderItem::Call { params, .. }) = def.list.0.into_iter().next() {
                        return params;
                    }
                }
            }
            panic!("no call in {text}");
        };
        assert_eq!(colormgt_view(&params(r#""frameBuffer" "mayaColor""#)), Ok(ViewTransform::Srgb));
        assert_eq!(
            colormgt_view(&params(r#""frameBuffer" "mayaColor", "viewTransform" "Rec 709 gamma""#)),
            Ok(ViewTransform::Rec709)
        );
        assert_eq!(colormgt_view(&params(r#""enable" off, "viewTransform" "sRGB gamma""#)), Ok(ViewTransform::Raw));
        assert!(colormgt_view(&params(r#""viewTransform" "ACES RRT""#)).unwrap_err().contains("ACES RRT"));
    }
}
