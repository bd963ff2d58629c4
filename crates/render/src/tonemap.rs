//! Tone mapping for display images: the camera's `mia_exposure_photographic` (as Iray
//! camera attributes, an output shader, or a lens shader when the path engine ran, which
//! does not run lens shaders), `mia_exposure_simple`, or plain sRGB encoding. The curves
//! are `mia::exposure`'s. A Maya export's `maya_colormgt` / `adskMayaColorMgt` output
//! shader encodes the display image with its view transform (`maya::output`), after the
//! camera's `mia_exposure_simple` when there is one (Maya exports give it gamma 1 and
//! leave the display encoding to colour management).

use bsdf::Rgb;
use maya::output::ViewTransform;
use mi::ast::{Param, ShaderList};
use mia::exposure::{Photographic, Simple};
use scene::camera::Output;

/// Photographic tone mapping from the Iray camera attributes (`tm_tonemapper
/// "mia_exposure_photographic"` and `mip_*`), Iray's defaults where absent.
pub fn photographic_from_attributes(a: &scene::values::Attributes) -> Photographic {
    let f = |name: &str, default: f32| a.get(name).and_then(|v| v.as_f64()).map_or(default, |v| v as f32);
    let whitepoint = match a.get("mip_whitepoint") {
        Some(scene::values::AttrValue::Floats(v)) if v.len() >= 3 => Rgb::new(v[0] as f32, v[1] as f32, v[2] as f32),
        _ => Rgb::new(1.04287, 0.983863, 1.03358),
    };
    Photographic {
        cm2_factor: f("mip_cm2_factor", 1.0),
        whitepoint,
        film_iso: f("mip_film_iso", 100.0),
        camera_shutter: f("mip_camera_shutter", 0.125),
        f_number: f("mip_f_number", 8.0),
        vignetting: f("mip_vignetting", 0.0),
        burn_highlights: f("mip_burn_highlights", 0.0),
        crush_blacks: f("mip_crush_blacks", 0.25),
        saturation: f("mip_saturation", 1.0),
        gamma: f("mip_gamma", 2.2),
    }
}

/// A display transform.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ToneMapper {
    /// sRGB encoding of the clamped linear value.
    Srgb,
    /// `mia_exposure_simple`.
    Simple(Simple),
    /// `mia_exposure_photographic`, with the camera's half field of view tangents for
    /// vignetting.
    Photographic(Photographic, (f32, f32)),
    /// The pixels are display values already (a lens shader mapped every sample): clamp.
    Display,
    /// A Maya colour-management view transform of the (clamped) linear value, or of the
    /// values a lens shader already mapped.
    View(ViewTransform),
    /// `mia_exposure_simple`, then a Maya view transform.
    SimpleThenView(Simple, ViewTransform),
}

/// The view transform of a Maya colour-management output shader in `list`, if it holds
/// one (an unknown view name falls back to sRGB, `maya::output::colormgt_view`'s choice).
fn maya_view_in(list: &ShaderList, lib: &scene::Library) -> Option<ViewTransform> {
    list.0.iter().find_map(|item| {
        let (name, params) = material::first_call(std::slice::from_ref(item), lib)?;
        matches!(name, "maya_colormgt" | "adskMayaColorMgt")
            .then(|| maya::output::colormgt_view(params).unwrap_or(ViewTransform::Srgb))
    })
}

/// A value of a shader call's parameter, else the declaration's default, else 0.
fn param_f32(params: &[Param], decl: Option<&shader::decl::Decl>, name: &str) -> f32 {
    let given = params.iter().rev().find(|p| p.name.text == name).map(|p| &p.value);
    let default = decl.and_then(|d| d.param(name)).and_then(|i| decl?.params[i].default.as_ref());
    match given.or(default) {
        Some(mi::ast::Value::Num(n)) => n.as_f64() as f32,
        Some(mi::ast::Value::Tuple(t)) => t.first().map_or(0.0, |n| n.as_f64() as f32),
        Some(mi::ast::Value::Bool(b)) => f32::from(u8::from(*b)),
        _ => 0.0,
    }
}

fn param_rgb(params: &[Param], decl: Option<&shader::decl::Decl>, name: &str) -> Rgb {
    let given = params.iter().rev().find(|p| p.name.text == name).map(|p| &p.value);
    let default = decl.and_then(|d| d.param(name)).and_then(|i| decl?.params[i].default.as_ref());
    match given.or(default) {
        Some(mi::ast::Value::Tuple(t)) if t.len() >= 3 => {
            Rgb::new(t[0].as_f64() as f32, t[1].as_f64() as f32, t[2].as_f64() as f32)
        }
        Some(mi::ast::Value::Num(n)) => Rgb::splat(n.as_f64() as f32),
        _ => Rgb::ONE,
    }
}

/// The exposure shader a shader list holds, with constant parameters (connected ones read
/// as their defaults).
fn exposure_in(list: &ShaderList, lib: &scene::Library) -> Option<ToneMapper> {
    let decls = material::registry().decls(lib.declarations.values());
    list.0.iter().find_map(|item| {
        let (name, params) = material::first_call(std::slice::from_ref(item), lib)?;
        let decl = decls.get(name);
        let d = decl.as_deref();
        match name {
            "mia_exposure_simple" => Some(ToneMapper::Simple(Simple {
                pedestal: param_f32(params, d, "pedestal"),
                gain: param_f32(params, d, "gain"),
                knee: param_f32(params, d, "knee"),
                compression: param_f32(params, d, "compression"),
                gamma: param_f32(params, d, "gamma"),
            })),
            "mia_exposure_photographic" => Some(ToneMapper::Photographic(
                Photographic {
                    cm2_factor: param_f32(params, d, "cm2_factor"),
                    whitepoint: param_rgb(params, d, "whitepoint"),
                    film_iso: param_f32(params, d, "film_iso"),
                    camera_shutter: param_f32(params, d, "camera_shutter"),
                    f_number: param_f32(params, d, "f_number"),
                    vignetting: param_f32(params, d, "vignetting"),
                    burn_highlights: param_f32(params, d, "burn_highlights"),
                    crush_blacks: param_f32(params, d, "crush_blacks"),
                    saturation: param_f32(params, d, "saturation"),
                    gamma: param_f32(params, d, "gamma"),
                },
                (0.0, 0.0),
            )),
            _ => None,
        }
    })
}

impl ToneMapper {
    /// The display transform of a camera: its Iray tonemapper attributes, else an
    /// `mia_exposure_*` output shader, else an `mia_exposure_*` lens shader — which, when
    /// `lens_applied` (the classic engine ran it on every sample), leaves display values
    /// to clamp — else plain sRGB.
    pub fn for_camera(c: &scene::Camera, lib: &scene::Library, lens_applied: bool) -> ToneMapper {
        let tan = match c.focal {
            Some(f) if f > 0.0 => {
                ((c.aperture / (2.0 * f)) as f32, (c.aperture / (2.0 * f * c.aspect.max(1e-9))) as f32)
            }
            _ => (0.0, 0.0),
        };
        let with_tan = |t: ToneMapper| match t {
            ToneMapper::Photographic(p, _) => ToneMapper::Photographic(p, tan),
            other => other,
        };
        if c.attributes.get("tm_tonemapper").and_then(|v| v.as_str()) == Some("mia_exposure_photographic") {
            return ToneMapper::Photographic(photographic_from_attributes(&c.attributes), tan);
        }
        for out in &c.outputs {
            if let Output::Shader { shaders, .. } = out {
                if let Some(t) = exposure_in(shaders, lib) {
                    return with_tan(t);
                }
            }
        }
        let view = c.outputs.iter().find_map(|out| match out {
            Output::Shader { shaders, .. } => maya_view_in(shaders, lib),
            _ => None,
        });
        for lens in &c.lens {
            if let Some(t) = exposure_in(lens, lib) {
                return match (lens_applied, view, t) {
                    (true, Some(v), _) => ToneMapper::View(v),
                    (true, None, _) => ToneMapper::Display,
                    (false, Some(v), ToneMapper::Simple(s)) => ToneMapper::SimpleThenView(s, v),
                    (false, _, t) => with_tan(t),
                };
            }
        }
        view.map_or(ToneMapper::Srgb, ToneMapper::View)
    }

    /// Display value in [0, 1] of a linear colour at pixel (x, y) of a w × h image.
    pub fn map_at(&self, c: Rgb, x: u32, y: u32, w: u32, h: u32) -> Rgb {
        let out = match self {
            ToneMapper::Srgb => Rgb::new(srgb(c.x), srgb(c.y), srgb(c.z)),
            ToneMapper::Simple(s) => s.map(c),
            ToneMapper::Photographic(p, (tx, ty)) => {
                let u = (2.0 * (x as f32 + 0.5) / w.max(1) as f32 - 1.0) * tx;
                let v = (2.0 * (y as f32 + 0.5) / h.max(1) as f32 - 1.0) * ty;
                p.map(c, 1.0 / (1.0 + u * u + v * v).sqrt())
            }
            ToneMapper::Display => c,
            ToneMapper::View(v) => view(*v, c),
            ToneMapper::SimpleThenView(s, v) => view(*v, s.map(c)),
        };
        out.clamp(Rgb::ZERO, Rgb::ONE)
    }

    /// Display value of a linear colour at the image centre.
    pub fn map(&self, c: Rgb) -> Rgb {
        self.map_at(c, 0, 0, 1, 1)
    }
}

/// A view transform of a colour clamped to [0, 1].
fn view(v: ViewTransform, c: Rgb) -> Rgb {
    let c = c.clamp(Rgb::ZERO, Rgb::ONE);
    Rgb::new(v.encode(c.x), v.encode(c.y), v.encode(c.z))
}

/// The sRGB transfer function of a linear value, clamped to [0, 1].
pub fn srgb(v: f32) -> f32 {
    let v = v.clamp(0.0, 1.0);
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_known_values() {
        assert_eq!(srgb(0.0), 0.0);
        assert!((srgb(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb(0.18) - 0.461_356).abs() < 1e-5);
    }

    #[test]
    fn exposure_shaders_of_a_camera_are_found_with_their_defaults() {
        let text = r#"
options "o" end options
camera "c" focal 1 aperture 1 aspect 1 resolution 4 4
    output "+rgba" "mia_exposure_simple" ("gain" 0.2)
end camera
instance "ci" "c" end instance
instgroup "root" "ci" end instgroup
render "root" "ci" "o"
"#;
        let parsed = mi::parse_str("t.mi", text);
        let mut d = Vec::new();
        let sc = scene::Scene::build(&parsed, 0, &mut d).unwrap();
        let t = ToneMapper::for_camera(&sc.camera, &sc.library, false);
        assert_eq!(t, ToneMapper::Simple(Simple { pedestal: 0.0, gain: 0.2, knee: 0.5, compression: 2.0, gamma: 2.2 }));
        let lens = text.replace("output \"+rgba\"", "lens");
        let parsed = mi::parse_str("t.mi", &lens);
        let sc = scene::Scene::build(&parsed, 0, &mut d).unwrap();
        assert_eq!(ToneMapper::for_camera(&sc.camera, &sc.library, true), ToneMapper::Display);
        assert!(matches!(ToneMapper::for_camera(&sc.camera, &sc.library, false), ToneMapper::Simple(_)));
    }

    /// A Maya export's colour management: the view transform encodes the image, after
    /// the exposure lens shader (which Maya exports give gamma 1).
    #[test]
    fn maya_colormgt_encodes_after_the_exposure_lens_shader() {
        let text = r#"
$include "mayabase.mi"
options "o" end options
camera "c" focal 1 aperture 1 aspect 1 resolution 4 4
    output "maya_colormgt" ("frameBuffer" "mayaColor", "enable" on, "viewTransform" "Rec 709 gamma")
    LENS
end camera
instance "ci" "c" end instance
instgroup "root" "ci" end instgroup
render "root" "ci" "o"
"#;
        let camera = |lens: &str| {
            let parsed = mi::parse_str("t.mi", &text.replace("LENS", lens));
            let mut d = Vec::new();
            scene::Scene::build(&parsed, 0, &mut d).unwrap()
        };
        let sc = camera("");
        let t = ToneMapper::for_camera(&sc.camera, &sc.library, false);
        assert_eq!(t, ToneMapper::View(ViewTransform::Rec709));
        // 18 % grey is 0.409 in Rec. 709 (not sRGB's 0.4614).
        assert!((t.map(Rgb::splat(0.18)).x - 0.409).abs() < 1e-3);
        let sc = camera(r#"lens "mia_exposure_simple" ("gain" 0.5, "gamma" 1)"#);
        assert_eq!(ToneMapper::for_camera(&sc.camera, &sc.library, true), ToneMapper::View(ViewTransform::Rec709));
        let t = ToneMapper::for_camera(&sc.camera, &sc.library, false);
        let ToneMapper::SimpleThenView(s, ViewTransform::Rec709) = t else { panic!("{t:?}") };
        let c = Rgb::splat(0.3);
        let want = ViewTransform::Rec709.encode(s.map(c).x.clamp(0.0, 1.0));
        assert!((t.map(c).x - want).abs() < 1e-6);
        // Colour management off: the raw values.
        let parsed = mi::parse_str("t.mi", &text.replace("LENS", "").replace("\"enable\" on", "\"enable\" off"));
        let mut d = Vec::new();
        let sc = scene::Scene::build(&parsed, 0, &mut d).unwrap();
        let t = ToneMapper::for_camera(&sc.camera, &sc.library, false);
        assert_eq!(t, ToneMapper::View(ViewTransform::Raw));
        assert!((t.map(Rgb::splat(0.18)).x - 0.18).abs() < 1e-6);
    }
}
