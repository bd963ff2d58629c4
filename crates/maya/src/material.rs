//! Maya's surface materials: lambert, blinn, phong, phongE, anisotropic and surfaceShader.
//!
//! Parameters read (Maya's attribute names; defaults in `mayabase.mi`):
//! - `color` c (0.5 grey), `diffuse` d (0.8), `ambientColor` a (black), `incandescence`
//!   (black), `translucence` t (0), `transparency` T (black), `normalCamera` (the
//!   shading normal when connected, e.g. to bump2d's `outNormal`: mira passes normals in
//!   world space), `refractions`, `refractiveIndex`, `refractionLimit`,
//!   `matteOpacityMode`, `matteOpacity`, `glowIntensity`, `irradianceColor` g (white),
//!   `irradiance` M (black);
//! - the reflective ones add `specularColor` s (0.5 grey), `reflectivity` r (0.5),
//!   `reflectedColor` (black), `reflectionLimit` (1), `reflectionSpecularity`; then blinn
//!   `eccentricity`, `specularRollOff`, `reflectionRolloff`; phong `cosinePower`; phongE
//!   `roughness`, `highlightSize`, `whiteness`; anisotropic `angle` (radians, 0),
//!   `spreadX` (13), `spreadY` (3), `roughness` (0.7), `fresnelRefractiveIndex` (6)
//!   ([`specular::anisotropic`]: grooves along dP/du turned by `angle`).
//!
//! The colour (Maya's lambert model, which mental ray for Maya reproduces; no 1/π):
//!
//! ```text
//! D   = Σ_lights light · cos θ            (emitDiffuse lights, in front)
//! A   = Σ_ambient lights light · ((1 − ambientShade) + ambientShade · cos θ)
//! B   = Σ_lights behind light · |cos θ| · K(n, −v·l)   (translucence; K: `translucenceFocus`)
//! out = (c ⊙ (a + A + d·(D + g ⊙ (E_fg/π + M)) + t·B) + incandescence) ⊙ (1 − T)
//!       + s ⊙ Σ_lights light · highlight   (emitSpecular lights)
//!       + r · s ⊙ (reflectedColor + traced reflection) [· Fresnel for blinn's rolloff]
//!       + T ⊙ behind                     (a transparency or refraction ray)
//! ```
//!
//! K is the forward lobe of `translucenceFocus` φ ([`bsdf::maya_highlight::translucence`]:
//! K = (n + 2)/2 · max(−v·l, 0)^n, n = 2φ/(1 − φ), 1 for φ = 0; mira's reading, Maya
//! publishes no formula).
//!
//! `translucenceDepth` D (world units): Maya's node reference describes it as how far
//! past the point where the object is in shadow light still penetrates it (0: no light
//! shows through; seen with raytraced shadows). mental ray for Maya hands it to the
//! shading group's shadow shader (its translator writes `maya_shadow` with the material's
//! `outTransparency`, `shadowAttenuation` and `translucenceDepth`: the open-source
//! exporter github.com/ggarra13/mrliquid, `mrLiquid/src/mrShaderMayaShadow.cpp`), whose
//! formula is not published. mira's reading, in the material's shadow mode: a shadow ray
//! from a point of the object that leaves the object's own geometry (from inside) after
//! a stretch of length s through it passes a fraction max(1 − s/D, 0) of what its
//! transparency T stops, T + (1 − T)·max(1 − s/D, 0), when the material's `translucence`
//! is above 0 — a linear fall-off to nothing at s = D, so light from behind (the
//! translucence term B) reaches a slab of thickness s as B·(1 − s/D). Each stretch
//! inside counts on its own; other objects, and the object's own surfaces met from
//! outside, shadow as before. D = 0 (or no translucence) is the plain filter by T.
//!
//! E_fg is final gathering's irradiance (`mi_compute_irradiance`, the energy over the
//! hemisphere). Unlike the base library's materials, which add diffuse ⊙ E_fg as the
//! manual's example shader does, mental ray for Maya's materials divide it by π since Maya 6
//! (Maya 5 left the 1/π to the user through `irradianceColor`; the Los Angeles mental ray
//! user group's "Maya 5 Final Gathering Tips", lamrug.org/resources/mayafgtips.html), so a
//! lambert under a uniform sky of radiance L shows c·d·L, as the path engine gives.
//!
//! M, the `irradiance` input, is an illumination map: Maya's reference (the materials'
//! mental ray attributes, Maya 2013) has it take an incoming illumination map such as
//! mental ray's Batch Bake writes, scaled by `irradianceColor`, the colour of the bounced
//! light. mira's reading: M is light arriving at the point in Maya's
//! light units — what a lambert of colour 1 and diffuse 1 shows, as an illumination-only
//! bake records it — added to final gathering's E_fg/π (a baked map usually replaces
//! final gathering, which is then off), lit whether or not any light reaches the point.
//! As in Maya,
//! transparency fades the diffuse part, not the highlights and reflections. Raytraced
//! reflections stop at `reflectionLimit` (and at the scene's trace depth). The lights are
//! the material's `lightList` or the instance's light list (see below). In a shadow ray
//! the material filters the light by T (exports make the shading engine the material's
//! shadow shader too; see [`crate::engine`]).
//!
//! Where mental ray for Maya and Maya's own renderer differ, mira follows mental ray for
//! Maya: final gathering and the `irradiance` map (both scaled by `irradianceColor`) supply
//! indirect light, and reflections are raytraced up to `reflectionLimit`
//! (no reflection maps).
//!
//! Lights: the material's `lightList` (exports fill it in with `lightMode` 0) when it is
//! not empty, else the instance's light list. `lightMode` itself is not read (its other
//! values are not documented).
//!
//! Not read: `shadowAttenuation` (Maya brightens the middle of transparent objects'
//! shadows with it), `chromaticAberration`, `lightAbsorbance`, `surfaceThickness`,
//! `matteOpacityMode`, `hideSource`,
//! `reflectionSpecularity`; anisotropic's `anisotropicReflectivity` (Maya then derives the
//! reflectivity from the roughness by an unpublished rule; mira uses `reflectivity`).

use glam::Vec3A;
use shader::{Color, Ctx, NodeId, RayType, Value};

use crate::light::light_role;
use crate::maya_shader;
use crate::specular;
use crate::specular::Highlight;
use crate::values::{rgb, rgba, write_struct};

const COLOR: usize = 0;
const TRANSPARENCY: usize = 1;
const AMBIENT_COLOR: usize = 2;
const INCANDESCENCE: usize = 3;
const NORMAL_CAMERA: usize = 4;
const DIFFUSE: usize = 5;
const TRANSLUCENCE: usize = 6;
const REFRACTIONS: usize = 7;
const REFRACTIVE_INDEX: usize = 8;
const REFRACTION_LIMIT: usize = 9;
const MATTE_OPACITY: usize = 10;
const GLOW_INTENSITY: usize = 11;
const LIGHT_LIST: usize = 12;
const IRRADIANCE_COLOR: usize = 13;
const IRRADIANCE: usize = 14;
const TRANSLUCENCE_FOCUS: usize = 15;
const TRANSLUCENCE_DEPTH: usize = 16;
const SPECULAR_COLOR: usize = 17;
const REFLECTIVITY: usize = 18;
const REFLECTED_COLOR: usize = 19;
const REFLECTION_LIMIT: usize = 20;
/// The first parameter a reflective material adds to the shared ones.
const EXTRA: usize = REFLECTION_LIMIT + 1;

/// Parameters of lambert, in the order the code reads them.
const LAMBERT_PARAMS: &[&str] = &[
    "color",
    "transparency",
    "ambientColor",
    "incandescence",
    "normalCamera",
    "diffuse",
    "translucence",
    "refractions",
    "refractiveIndex",
    "refractionLimit",
    "matteOpacity",
    "glowIntensity",
    "lightList",
    "irradianceColor",
    "irradiance",
    "translucenceFocus",
    "translucenceDepth",
];

macro_rules! reflective_params {
    ($($extra:literal),*) => {
        &[
            "color", "transparency", "ambientColor", "incandescence", "normalCamera", "diffuse",
            "translucence", "refractions", "refractiveIndex", "refractionLimit", "matteOpacity",
            "glowIntensity", "lightList", "irradianceColor", "irradiance", "translucenceFocus", "translucenceDepth", "specularColor", "reflectivity", "reflectedColor", "reflectionLimit",
            $($extra),*
        ]
    };
}

maya_shader!(
    /// Maya's lambert: the diffuse model above without highlights.
    LAMBERT,
    ADSK_LAMBERT,
    "maya_lambert",
    "adskMayaLambert",
    LAMBERT_PARAMS,
    lambert
);

fn lambert(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    surface(ctx, n, out, |_, _| Highlight::None)
}

maya_shader!(
    /// Maya's blinn: lambert plus Blinn's highlight ([`specular::blinn`]) of
    /// `eccentricity` (0.3) and `specularRollOff` (0.7); with `reflectionRolloff` the
    /// reflections fade by the same Fresnel factor at N·V.
    BLINN,
    ADSK_BLINN,
    "maya_blinn",
    "adskMayaBlinn",
    reflective_params!("eccentricity", "specularRollOff", "reflectionRolloff"),
    blinn
);

fn blinn(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    surface(ctx, n, out, |ctx, n| Highlight::Blinn {
        eccentricity: ctx.scalar(n, EXTRA),
        rolloff: ctx.scalar(n, EXTRA + 1),
        reflection_rolloff: ctx.bool(n, EXTRA + 2),
    })
}

maya_shader!(
    /// Maya's phong: lambert plus (R·L)^`cosinePower` (20).
    PHONG,
    ADSK_PHONG,
    "maya_phong",
    "adskMayaPhong",
    reflective_params!("cosinePower"),
    phong
);

fn phong(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    surface(ctx, n, out, |ctx, n| Highlight::Phong { power: ctx.scalar(n, EXTRA) })
}

maya_shader!(
    /// Maya's phongE: lambert plus [`specular::phong_e`] of `roughness` (0.5) and
    /// `highlightSize` (0.5), tinted by `whiteness` (0.5 grey).
    PHONGE,
    ADSK_PHONGE,
    "maya_phongE",
    "adskMayaPhongE",
    reflective_params!("roughness", "highlightSize", "whiteness"),
    phong_e
);

fn phong_e(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    surface(ctx, n, out, |ctx, n| Highlight::PhongE {
        roughness: ctx.scalar(n, EXTRA),
        size: ctx.scalar(n, EXTRA + 1),
        whiteness: rgb(ctx.color(n, EXTRA + 2)),
    })
}

maya_shader!(
    /// Maya's anisotropic: lambert plus [`specular::anisotropic`], grooves along dP/du
    /// turned by `angle`, widths from `roughness`, `spreadX` and `spreadY`
    /// ([`specular::anisotropic_widths`]), Fresnel of `fresnelRefractiveIndex`.
    ANISOTROPIC,
    ADSK_ANISOTROPIC,
    "maya_anisotropic",
    "adskMayaAnisotropic",
    reflective_params!("angle", "spreadX", "spreadY", "roughness", "fresnelRefractiveIndex"),
    anisotropic
);

fn anisotropic(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    surface(ctx, n, out, |ctx, n| {
        let angle = ctx.scalar(n, EXTRA);
        let (alpha_x, alpha_y) =
            specular::anisotropic_widths(ctx.scalar(n, EXTRA + 3), ctx.scalar(n, EXTRA + 1), ctx.scalar(n, EXTRA + 2));
        let grooves = specular::groove_direction(ctx.state.normal, ctx.state.derivs[0], angle);
        Highlight::Anisotropic { grooves, alpha_x, alpha_y, ior: ctx.scalar(n, EXTRA + 4) }
    })
}

/// A shadow ray through a Maya material: called as a shadow shader (the arriving light
/// in `out`), the light is filtered by the transparency; called through a shading engine
/// (`out` holds the output struct), the transparency is reported in `outTransparency`
/// for the engine to filter with.
pub(crate) fn shadow_filter(out: &mut Value, transparency: Vec3A) -> bool {
    if let Value::Struct(_) = out {
        write_struct(out, &[("outTransparency", Value::Color(rgba(transparency, 1.0)))]);
        return true;
    }
    let c = out.color();
    let f = rgb(c) * transparency;
    *out = Value::Color(rgba(f, c.w));
    f != Vec3A::ZERO
}

/// What a shadow ray passes where it leaves the receiving point's own object after going
/// `inside` world units through it (see the module doc): with `translucence` > 0 and
/// `translucenceDepth` D > 0, the transparency T raised to T + (1 − T)·max(1 − inside/D, 0)
/// (mira's reading of Maya's reference); else T unchanged.
fn translucent_passage(ctx: &mut Ctx, n: NodeId, transparency: Vec3A, inside: f32) -> Vec3A {
    let (translucence, depth) = (ctx.scalar(n, TRANSLUCENCE), ctx.scalar(n, TRANSLUCENCE_DEPTH));
    passage(transparency, translucence, depth, inside)
}

/// The shadow passage of a material of `translucence` t and `translucenceDepth` D where a
/// shadow ray leaves its own object after `inside` world units (see the module doc):
/// T + (1 − T)·max(1 − inside/D, 0) when t > 0 and D > 0, else T (`transparency`).
/// rampShader reads it too (`crate::ramp_shader`).
pub(crate) fn passage(transparency: Vec3A, translucence: f32, depth: f32, inside: f32) -> Vec3A {
    if depth <= 0.0 || translucence <= 0.0 {
        return transparency;
    }
    let kept = (1.0 - inside / depth).max(0.0);
    transparency + (Vec3A::ONE - transparency) * kept
}

/// The lights a Maya material shades with: its `lightList` (parameter `i` of `node`) when
/// the export filled it in, else the instance's light list (`light "exclusive"` links).
pub(crate) fn material_lights(ctx: &mut Ctx, node: NodeId, i: usize) -> shader::light_list::LightList {
    let listed = ctx.array(node, i);
    if listed.array().is_empty() {
        ctx.instance_lights()
    } else {
        ctx.light_list(0, &listed)
    }
}

/// The light arriving at the point, split by how the material uses it.
#[derive(Default)]
struct Received {
    diffuse: Vec3A,
    ambient: Vec3A,
    behind: Vec3A,
    specular: Vec3A,
}

/// The light arriving at the point for the material `node` of `highlight`; `focus`, the
/// forward lobe's exponent of a translucent material (`None`: not translucent), weights
/// the light from behind ([`bsdf::maya_highlight::translucence`]).
fn gather_lights(ctx: &mut Ctx, node: NodeId, highlight: Highlight, focus: Option<f32>) -> Received {
    let mut r = Received::default();
    let (n, v) = (ctx.state.normal, -ctx.state.dir);
    for light in material_lights(ctx, node, LIGHT_LIST) {
        let role = light_role(ctx, light);
        let mut lp = ctx.light_loop(light);
        lp.both_sides = role.needs_both_sides() || focus.is_some();
        let mut sum = Received::default();
        while let Some(s) = ctx.sample_light(&mut lp) {
            let c = rgb(s.color);
            // The direction the light is shaded with (a volume light may turn it).
            let (dir, dot_nl) = role.shading_direction(ctx.state.point, n, s.dir);
            if let Some(shade) = role.ambient_shade {
                sum.ambient += c * ((1.0 - shade) + shade * dot_nl.max(0.0));
                if role.ambient_specular && dot_nl > 0.0 {
                    sum.specular += c * highlight.value(n, v, dir);
                }
            } else if dot_nl > 0.0 {
                if role.diffuse {
                    sum.diffuse += c * dot_nl;
                }
                if role.specular {
                    sum.specular += c * highlight.value(n, v, dir);
                }
            } else if role.diffuse {
                let lobe = focus.map_or(1.0, |n| bsdf::maya_highlight::translucence::forward_lobe(n, -v.dot(dir)));
                sum.behind += c * (-dot_nl * lobe);
            }
        }
        if lp.samples > 0 {
            let k = 1.0 / lp.samples as f32;
            r.diffuse += sum.diffuse * k;
            r.ambient += sum.ambient * k;
            r.behind += sum.behind * k;
            r.specular += sum.specular * k;
        }
    }
    r
}

/// What lies behind a transparent point: a refraction ray when `refractions` is on and
/// the index is not 1 (within `refractionLimit`), else a transparency ray.
fn behind(ctx: &mut Ctx, n: NodeId) -> Color {
    let refract = ctx.bool(n, REFRACTIONS);
    let ior = ctx.scalar(n, REFRACTIVE_INDEX);
    let limit = ctx.int(n, REFRACTION_LIMIT).max(0) as u32;
    behind_with(ctx, refract, ior, limit)
}

/// [`behind`] with the refraction parameters given: `refract` (`refractions`), the
/// index `ior` and `limit` (`refractionLimit`).
pub(crate) fn behind_with(ctx: &mut Ctx, refract: bool, ior: f32, limit: u32) -> Color {
    let traced = if refract && ior > 0.0 && (ior - 1.0).abs() > 1e-6 && ctx.state.refraction_level < limit {
        let (from, to) = if ctx.state.inv_normal { (ior, 1.0) } else { (1.0, ior) };
        match ctx.refraction_dir(from, to) {
            Some(d) => ctx.trace_refraction(d),
            None => ctx.trace_reflection(ctx.reflection_dir()),
        }
    } else {
        ctx.trace_transparent()
    };
    traced.unwrap_or(Color::ZERO)
}

/// The shading of every Maya material but surfaceShader (see the module doc).
fn surface(ctx: &mut Ctx, n: NodeId, out: &mut Value, highlight: fn(&mut Ctx, NodeId) -> Highlight) -> bool {
    let transparency = rgb(ctx.color(n, TRANSPARENCY)).clamp(Vec3A::ZERO, Vec3A::ONE);
    if ctx.state.ray_type == RayType::Shadow {
        let transparency = match ctx.state.inside_own {
            Some(inside) => translucent_passage(ctx, n, transparency, inside),
            None => transparency,
        };
        return shadow_filter(out, transparency);
    }
    if !ctx.state.ray_type.is_visible() {
        return false;
    }
    let saved_normal = ctx.state.normal;
    if ctx.is_connected(n, NORMAL_CAMERA) {
        if let Some(bumped) = ctx.vector(n, NORMAL_CAMERA).try_normalize() {
            ctx.state.normal = if bumped.dot(ctx.state.dir) > 0.0 { -bumped } else { bumped };
        }
    }
    let color = rgb(ctx.color(n, COLOR));
    let diffuse = ctx.scalar(n, DIFFUSE);
    let translucence = ctx.scalar(n, TRANSLUCENCE);
    let highlight = highlight(ctx, n);
    let reflective = !matches!(highlight, Highlight::None);
    let focus = (translucence > 0.0)
        .then(|| bsdf::maya_highlight::translucence::focus_exponent(ctx.scalar(n, TRANSLUCENCE_FOCUS)));
    let received = gather_lights(ctx, n, highlight, focus);
    let fg = if diffuse > 0.0 && color != Vec3A::ZERO {
        let map = rgb(ctx.color(n, IRRADIANCE));
        rgb(ctx.color(n, IRRADIANCE_COLOR)) * (rgb(ctx.compute_irradiance()) * std::f32::consts::FRAC_1_PI + map)
    } else {
        Vec3A::ZERO
    };
    let ambient = rgb(ctx.color(n, AMBIENT_COLOR)) + received.ambient;
    let lit = color * (ambient + diffuse * (received.diffuse + fg) + translucence * received.behind)
        + rgb(ctx.color(n, INCANDESCENCE));
    let mut result = lit * (Vec3A::ONE - transparency);
    if reflective {
        let spec_color = rgb(ctx.color(n, SPECULAR_COLOR));
        result += spec_color * received.specular;
        let r = ctx.scalar(n, REFLECTIVITY);
        let limit = ctx.int(n, REFLECTION_LIMIT).max(0) as u32;
        if r > 0.0 {
            let mut reflected = rgb(ctx.color(n, REFLECTED_COLOR));
            if ctx.state.reflection_level < limit {
                if let Some(t) = ctx.trace_reflection(ctx.reflection_dir()) {
                    reflected += rgb(t);
                }
            }
            let fresnel = match highlight {
                Highlight::Blinn { rolloff, reflection_rolloff: true, .. } => {
                    specular::schlick(rolloff, ctx.state.normal.dot(-ctx.state.dir))
                }
                _ => 1.0,
            };
            result += r * fresnel * spec_color * reflected;
        }
    }
    let t_mean = (transparency.x + transparency.y + transparency.z) / 3.0;
    let mut alpha = 1.0;
    if transparency != Vec3A::ZERO {
        let b = behind(ctx, n);
        result += transparency * rgb(b);
        alpha = 1.0 - t_mean + t_mean * b.w;
    }
    ctx.state.normal = saved_normal;
    let glow = color * ctx.scalar(n, GLOW_INTENSITY);
    let matte = ctx.scalar(n, MATTE_OPACITY);
    write_struct(
        out,
        &[
            ("outColor", Value::Color(rgba(result, alpha))),
            ("outTransparency", Value::Color(rgba(transparency, t_mean))),
            ("outGlowColor", Value::Color(rgba(glow, 1.0))),
            ("outMatteOpacity", Value::Color(Color::new(matte, matte, matte, 1.0))),
        ],
    );
    true
}

maya_shader!(
    /// Maya's surfaceShader: returns its `outColor` unlit, composited over what lies
    /// behind by its `outTransparency`; its glow and matte pass through.
    SURFACESHADER,
    ADSK_SURFACESHADER,
    "maya_surfaceshader",
    "adskMayaSurfaceShader",
    &["outColor", "outTransparency", "outGlowColor", "outMatteOpacity"],
    surface_shader
);

fn surface_shader(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let transparency = rgb(ctx.color(n, 1)).clamp(Vec3A::ZERO, Vec3A::ONE);
    if ctx.state.ray_type == RayType::Shadow {
        return shadow_filter(out, transparency);
    }
    if !ctx.state.ray_type.is_visible() {
        return false;
    }
    let mut result = rgb(ctx.color(n, 0)) * (Vec3A::ONE - transparency);
    let t_mean = (transparency.x + transparency.y + transparency.z) / 3.0;
    let mut alpha = 1.0;
    if transparency != Vec3A::ZERO {
        let b = ctx.trace_transparent().unwrap_or(Color::ZERO);
        result += transparency * rgb(b);
        alpha = 1.0 - t_mean + t_mean * b.w;
    }
    let glow = ctx.color(n, 2);
    let matte = ctx.color(n, 3);
    write_struct(
        out,
        &[
            ("outColor", Value::Color(rgba(result, alpha))),
            ("outTransparency", Value::Color(rgba(transparency, t_mean))),
            ("outGlowColor", Value::Color(glow)),
            ("outMatteOpacity", Value::Color(matte)),
        ],
    );
    true
}
