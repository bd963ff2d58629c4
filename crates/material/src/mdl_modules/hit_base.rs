//! The `::base` procedural textures, bump textures, colour layering and projections called
//! inside module materials, built as [`HitExpr`] trees over [`Pattern`]s (folded to
//! constants where the coordinate is): `checker_texture`, `perlin_noise_texture`,
//! `worley_noise_texture`, `flow_noise_texture`, `flake_noise_texture`,
//! `gradient3_texture`, their `_bump_` forms, `tile_bump_texture`, `file_bump_texture`,
//! `blend_color_layers` and `coordinate_projection` (every projection mode); it hands
//! `sun_and_sky` and `perez_sun_and_sky` to [`super::sky`], `lookup_volume_coefficients`
//! and `volume_blackbody_emission` to [`super::base_volume`].
//!
//! The parameters MDL declares `uniform` (sizes, levels, modes…) must be constants; the
//! colours may vary over the surface. What is not compiled is an error naming the function
//! and its parameter, which the compiler reports at the module line.

use std::sync::Arc;

use glam::{Vec3A, Vec4};
use mdl_lang::Function;
use mi::Span;

use super::eval::{kind, problem, Eval, Problem};
use super::hit::{fold, BinOp, HitExpr, MathFn, StateFn};
use super::hit_natives::{coordinate_info, enum_arg, mono_name, state_value, wrap_name};
use super::procedural::{NoiseShaping, Pattern};
use super::projection;
use super::tiles::Tiling;
use super::value::{HitType, Value};

/// The arguments of one `::base` call, read by parameter name (shared with the volume
/// functions of [`super::base_volume`], which add their own readers).
pub(super) struct Args<'a> {
    pub(super) def: &'a Function,
    pub(super) args: &'a [Value],
    pub(super) span: Span,
}

impl Args<'_> {
    /// The argument of parameter `p`, if the call has it.
    pub(super) fn get(&self, p: &str) -> Option<&Value> {
        self.def.param(p).and_then(|(i, _)| self.args.get(i))
    }

    /// The error for parameter `p` given a value `v` that is not a constant.
    pub(super) fn not_constant(&self, p: &str, v: &Value) -> Problem {
        problem(
            self.span,
            format!("`base::{}`'s `{p}` is {}; mira compiles it only as a constant", self.def.name, kind(v)),
        )
    }

    /// A constant number (`default` when absent).
    pub(super) fn num(&self, p: &str, default: f32) -> Result<f32, Problem> {
        match self.get(p) {
            None => Ok(default),
            Some(v) => v.float().map(|f| f as f32).ok_or_else(|| self.not_constant(p, v)),
        }
    }

    fn int(&self, p: &str, default: i32) -> Result<i32, Problem> {
        match self.get(p) {
            None => Ok(default),
            Some(Value::Enum(_, i)) | Some(Value::Int(i)) => Ok(*i as i32),
            Some(v) => Err(self.not_constant(p, v)),
        }
    }

    fn flag(&self, p: &str) -> Result<bool, Problem> {
        match self.get(p) {
            None => Ok(false),
            Some(Value::Bool(b)) => Ok(*b),
            Some(v) => Err(self.not_constant(p, v)),
        }
    }

    fn vec3(&self, p: &str) -> Result<Vec3A, Problem> {
        match self.get(p) {
            None => Ok(Vec3A::ZERO),
            Some(Value::Vector(v)) if v.len() == 3 => Ok(Vec3A::new(v[0] as f32, v[1] as f32, v[2] as f32)),
            Some(v) => Err(self.not_constant(p, v)),
        }
    }

    /// A hit expression of the argument (`default` in all lanes when absent).
    fn hit(&self, p: &str, default: f32) -> Result<Arc<HitExpr>, Problem> {
        match self.get(p) {
            None => Ok(Arc::new(HitExpr::Const(Vec4::splat(default)))),
            Some(v) => v.to_hit().ok_or_else(|| self.not_constant(p, v)),
        }
    }

    /// A part (`position`, `tangent_u`, `tangent_v`) of the `uvw` coordinate.
    fn uvw(&self, part: &str) -> Result<Arc<HitExpr>, Problem> {
        let v = self
            .get("uvw")
            .and_then(|c| c.field(part))
            .ok_or_else(|| problem(self.span, format!("`base::{}` of a coordinate without `{part}`", self.def.name)))?;
        v.to_hit().ok_or_else(|| self.not_constant(&format!("uvw.{part}"), v))
    }

    /// The shared noise modifications.
    fn shaping(&self) -> Result<NoiseShaping, Problem> {
        Ok(NoiseShaping {
            marble: self.flag("apply_marble")?,
            dent: self.flag("apply_dent")?,
            bands: self.num("noise_bands", 1.0)?,
            low: self.num("noise_threshold_low", 0.0)?,
            high: self.num("noise_threshold_high", 1.0)?,
        })
    }

    /// A positive constant size (`size`, `scale`): zero or negative sizes are errors.
    fn size(&self, p: &str) -> Result<f32, Problem> {
        let s = self.num(p, 1.0)?;
        if s > 0.0 && s.is_finite() {
            Ok(s)
        } else {
            Err(problem(self.span, format!("`base::{}`'s `{p}` is {s}; it must be positive", self.def.name)))
        }
    }
}

/// A `texture_return` of `tint` and `mono`.
fn texture_return(tint: Arc<HitExpr>, mono: Arc<HitExpr>) -> Value {
    Value::Struct(
        "texture_return".into(),
        vec![
            ("tint".into(), Value::from_hit((*tint).clone(), HitType::Color)),
            ("mono".into(), Value::from_hit((*mono).clone(), HitType::Float)),
        ],
    )
}

fn constant(x: f32) -> Arc<HitExpr> {
    Arc::new(HitExpr::Const(Vec4::splat(x)))
}

/// `pattern` at the coordinate's position.
fn at(pattern: Pattern, a: &Args) -> Result<Arc<HitExpr>, Problem> {
    Ok(fold(HitExpr::Pattern(Arc::new(pattern), a.uvw("position")?)))
}

/// The texture of a blend pattern: tint = lerp(`from`, `to`, t); mono as given.
fn blended(t: Arc<HitExpr>, from: Arc<HitExpr>, to: Arc<HitExpr>, mono_average: bool) -> Value {
    let tint = fold(HitExpr::Math(MathFn::Lerp, [from, to, t].into()));
    let mono =
        if mono_average { fold(HitExpr::Math(MathFn::Average(3), [tint.clone()].into())) } else { constant(0.0) };
    texture_return(tint, mono)
}

/// A bump texture: `normal` bent by the slope of `height` over `delta`.
fn bump(height: Pattern, factor: f32, delta: [f32; 2], a: &Args) -> Eval {
    let normal = match a.get("normal") {
        Some(v) => v.to_hit().ok_or_else(|| a.not_constant("normal", v))?,
        None => Arc::new(HitExpr::State(StateFn::Normal)),
    };
    let e = HitExpr::Bump {
        height: Arc::new(height),
        position: a.uvw("position")?,
        tangent_u: a.uvw("tangent_u")?,
        tangent_v: a.uvw("tangent_v")?,
        normal,
        factor,
        delta,
    };
    Ok(Value::from_hit((*fold(e)).clone(), HitType::Vector(3)))
}

fn perlin(a: &Args) -> Result<Pattern, Problem> {
    Ok(Pattern::Perlin {
        size: a.size("size")?,
        phase: a.num("noise_phase", 0.0)?,
        levels: a.int("noise_levels", 1)?.clamp(0, 32) as u32,
        absolute: a.flag("absolute_noise")?,
        ridged: a.flag("ridged_noise")?,
        distortion: a.vec3("noise_distortion")?,
        shaping: a.shaping()?,
    })
}

fn worley(a: &Args) -> Result<Pattern, Problem> {
    Ok(Pattern::Worley {
        size: a.size("size")?,
        mode: a.int("mode", 0)?,
        metric: a.int("metric", 0)?,
        distortion: a.vec3("noise_distortion")?,
        step_threshold: a.num("step_threshold", 0.2)?,
        shaping: a.shaping()?,
    })
}

fn flow(a: &Args) -> Result<Pattern, Problem> {
    Ok(Pattern::Flow {
        size: a.size("size")?,
        phase: a.num("phase", 0.0)?,
        levels: a.int("levels", 1)?.clamp(1, 32) as u32,
        absolute: a.flag("absolute_noise")?,
        gain: a.num("level_gain", 0.5)?,
        scale: a.num("level_scale", 2.0)?,
        u_scale: a.num("level_progressive_u_scale", 1.0)?,
        v_motion: a.num("level_progressive_v_motion", 0.0)?,
    })
}

fn checker(a: &Args) -> Result<Pattern, Problem> {
    Ok(Pattern::Checker { blur: a.num("blur", 0.0)?, position: a.num("checker_position", 0.5)? })
}

fn tiles(a: &Args) -> Result<Tiling, Problem> {
    Ok(Tiling {
        rows: a.size("number_of_rows")?,
        columns: a.size("number_of_columns")?,
        grout_width: a.num("grout_width", 0.02)?,
        grout_height: a.num("grout_height", 0.02)?,
        grout_roughness: a.num("grout_roughness", 0.0)?,
        missing_tile_amount: a.num("missing_tile_amount", 0.0)?,
        brightness_variation: a.num("tile_brightness_variation", 0.0)?,
        seed: a.num("seed", 2.284)?,
        special_row_index: a.int("special_row_index", 1)?,
        special_row_width_factor: a.num("special_row_width_factor", 1.0)?,
        special_column_index: a.int("special_column_index", 1)?,
        special_column_height_factor: a.num("special_column_height_factor", 1.0)?,
        odd_row_offset: a.num("odd_row_offset", 0.5)?,
        random_row_offset: a.num("random_row_offset", 0.0)?,
    })
}

/// `tile_texture`: the tile colour (brightened or darkened tile by tile, clamped to
/// [0, 1]) on a tile, the grout colour elsewhere; mono 1 on a tile, 0 elsewhere.
fn tile_texture(a: &Args) -> Eval {
    let p = at(Pattern::Tiles(tiles(a)?), a)?;
    let on = fold(HitExpr::Lane(p.clone(), 1));
    let variation = fold(HitExpr::Lane(p, 2));
    let tile = a.hit("tile_color", 0.0)?;
    let varied = fold(HitExpr::Binary(BinOp::Add, tile.clone(), fold(HitExpr::Binary(BinOp::Mul, tile, variation))));
    let varied = fold(HitExpr::Math(MathFn::Saturate, [varied].into()));
    let tint = fold(HitExpr::Math(MathFn::Lerp, [a.hit("grout_color", 1.0)?, varied, on.clone()].into()));
    Ok(texture_return(tint, on))
}

/// Three constant numbers of an array argument.
fn three(a: &Args, p: &str, f: impl Fn(&Value) -> Option<Vec3A>) -> Result<[Vec3A; 3], Problem> {
    match a.get(p) {
        Some(Value::Array(items)) if items.len() == 3 => {
            let mut out = [Vec3A::ZERO; 3];
            for (o, v) in out.iter_mut().zip(items) {
                *o = f(v).ok_or_else(|| a.not_constant(p, v))?;
            }
            Ok(out)
        }
        Some(v) => Err(a.not_constant(p, v)),
        None => Err(problem(a.span, format!("`base::{}` without `{p}`", a.def.name))),
    }
}

/// The three stops of a gradient: positions, colours, interpolation modes (constants).
type Stops = ([f32; 3], [Vec3A; 3], [i32; 3]);

fn stops(a: &Args) -> Result<Stops, Problem> {
    let positions = three(a, "gradient_positions", |v| v.float().map(|f| Vec3A::splat(f as f32)))?;
    let colors = three(a, "gradient_colors", |v| v.color().map(|c| Vec3A::new(c.x, c.y, c.z)))?;
    let modes = three(a, "interpolation_modes", |v| match v {
        Value::Enum(_, i) | Value::Int(i) => Some(Vec3A::splat(*i as f32)),
        _ => None,
    })?;
    Ok((positions.map(|v| v.x), colors, modes.map(|v| v.x as i32)))
}

/// `gradient3_recolor`: `position` + `distortion` (which may vary) through the gradient;
/// mono by `mono_source` of the colour with alpha 1.
fn gradient_recolor(a: &Args) -> Eval {
    let (positions, colors, interpolation) = stops(a)?;
    let at = fold(HitExpr::Binary(BinOp::Add, a.hit("position", 0.0)?, a.hit("distortion", 0.0)?));
    let tint = fold(HitExpr::Pattern(Arc::new(Pattern::Recolor { positions, colors, interpolation }), at));
    let rgba = fold(HitExpr::Compose([(tint.clone(), 3), (constant(1.0), 1)].into()));
    let mono = fold(HitExpr::Math(MathFn::Mono(mono_name(enum_arg(a.get("mono_source"), 0))), [rgba].into()));
    Ok(texture_return(tint, mono))
}

fn gradient(a: &Args) -> Result<Pattern, Problem> {
    let (positions, colors, interpolation) = stops(a)?;
    if let Some(d) = a.get("distortion").filter(|d| d.float().is_none()) {
        return Err(a.not_constant("distortion", d));
    }
    Ok(Pattern::Gradient {
        mode: a.int("mode", 0)?,
        positions,
        colors,
        interpolation,
        distortion: a.num("distortion", 0.0)?,
    })
}

/// `color_layer_mode`'s enumerator names mira blends (by value), as
/// [`mdl::texture::blend_layer`] knows them.
fn layer_mode(v: i64) -> Option<&'static str> {
    Some(match v {
        0 => "color_layer_blend",
        1 => "color_layer_add",
        2 => "color_layer_multiply",
        3 => "color_layer_screen",
        4 => "color_layer_overlay",
        8 => "color_layer_average",
        9 => "color_layer_lighten",
        10 => "color_layer_darken",
        11 => "color_layer_subtract",
        13 => "color_layer_difference",
        _ => return None,
    })
}

/// `blend_color_layers`: each layer blended in order over the colour so far, starting at
/// `base`; mono of the result by `mono_source` (alpha 1).
fn blend_color_layers(a: &Args) -> Eval {
    let Some(Value::Array(layers)) = a.get("layers") else {
        return Err(problem(a.span, "`base::blend_color_layers` without an array of layers"));
    };
    let mut c = a.hit("base", 0.0)?;
    for layer in layers {
        let field = |f: &str| layer.field(f).ok_or_else(|| problem(a.span, format!("a colour layer without `{f}`")));
        let mode = match field("mode")? {
            Value::Enum(_, i) | Value::Int(i) => layer_mode(*i).ok_or_else(|| {
                problem(a.span, format!("`base::blend_color_layers` with colour layer mode {i} is not compiled yet"))
            })?,
            v => return Err(a.not_constant("layers.mode", v)),
        };
        let top = field("layer_color")?.to_hit().ok_or_else(|| a.not_constant("layers.layer_color", layer))?;
        let w = field("weight")?.to_hit().ok_or_else(|| a.not_constant("layers.weight", layer))?;
        c = fold(HitExpr::Math(MathFn::Blend(mode), [c, top, w].into()));
    }
    let rgba = fold(HitExpr::Compose([(c.clone(), 3), (constant(1.0), 1)].into()));
    let mono = fold(HitExpr::Math(MathFn::Mono(mono_name(enum_arg(a.get("mono_source"), 1))), [rgba].into()));
    Ok(texture_return(c, mono))
}

/// `coordinate_projection`: the point, shading and geometric normals in the chosen space
/// (object, world, or a texture space with object-space normals) through
/// `projection_transform`, projected by `projection_type` ([`super::projection`]); the
/// tangents are the directions of u and v growth brought back to world space and laid
/// into the surface. Object-space normals and directions go through the object's unit
/// axes (exact for rotations and uniform scales).
fn coordinate_projection(a: &Args) -> Eval {
    let projection = a.int("projection_type", i32::from(projection::PLANAR))?;
    let Some(mode) = u8::try_from(projection).ok().filter(|m| projection::known(*m)) else {
        return Err(problem(a.span, format!("`base::coordinate_projection` of unknown projection mode {projection}")));
    };
    let m = match a.get("projection_transform") {
        None => glam::Mat4::IDENTITY,
        Some(v) if super::matrix::mat4(v).is_some() => super::matrix::mat4(v).unwrap_or_default(),
        Some(v) => return Err(a.not_constant("projection_transform", v)),
    };
    let state = |f: StateFn| Arc::new(HitExpr::State(f));
    let axes_world = [Vec4::X, Vec4::Y, Vec4::Z].map(|v| Arc::new(HitExpr::Const(v)));
    let axes_object = [StateFn::ObjectAxisX, StateFn::ObjectAxisY, StateFn::ObjectAxisZ].map(state);
    // A world-space direction in the space of `axes` (their dot products), and back.
    let into = |axes: &[Arc<HitExpr>; 3], v: Arc<HitExpr>| {
        let lanes = axes.clone().map(|ax| (fold(HitExpr::Math(MathFn::Dot(3), [v.clone(), ax].into())), 1u8));
        fold(HitExpr::Compose(Box::new(lanes)))
    };
    let out_of = |axes: &[Arc<HitExpr>; 3], v: Arc<HitExpr>| {
        let part =
            |i: usize| fold(HitExpr::Binary(BinOp::Mul, fold(HitExpr::Lane(v.clone(), i as u8)), axes[i].clone()));
        let sum = fold(HitExpr::Binary(BinOp::Add, fold(HitExpr::Binary(BinOp::Add, part(0), part(1))), part(2)));
        fold(HitExpr::Math(MathFn::Normalize(3), [sum].into()))
    };
    let (position, axes) = match a.int("coordinate_system", 2)? {
        0 => {
            let space = u8::try_from(a.int("texture_space", 0)?).unwrap_or(u8::MAX);
            (state(StateFn::TextureCoordinate(space)), &axes_object)
        }
        1 => (state(StateFn::Position), &axes_world),
        2 => (state(StateFn::ObjectPosition), &axes_object),
        c => return Err(problem(a.span, format!("`base::coordinate_projection` of coordinate system {c}"))),
    };
    let normal = into(axes, state(StateFn::Normal));
    let geometric = into(axes, state(StateFn::GeometryNormal));
    let through = |of: Arc<HitExpr>, point: bool| fold(HitExpr::Transform { matrix: m, of, point });
    let operands: Box<[Arc<HitExpr>]> =
        [through(position, true), through(normal, false), through(geometric, false)].into();
    let uv = fold(HitExpr::Math(MathFn::Project(mode), operands.clone()));
    // The rows of the projection's linear part: the directions of u and v growth in the
    // chosen space (the projector's direction through the transpose of its matrix).
    let growth = |i: u8| {
        let r = fold(HitExpr::Math(MathFn::ProjectAxis(mode, i), operands.clone()));
        out_of(axes, fold(HitExpr::Transform { matrix: m.transpose(), of: r, point: false }))
    };
    let (du, dv) = (growth(0), growth(1));
    let tangent = |i: u8| {
        let t = HitExpr::Math(MathFn::SurfaceTangent(i), [du.clone(), dv.clone(), state(StateFn::Normal)].into());
        Value::from_hit(t, HitType::Vector(3))
    };
    Ok(coordinate_info(Value::from_hit((*uv).clone(), HitType::Vector(3)), tangent(0), tangent(1)))
}

/// The `::base` function `def` with `args` (those [`super::hit_natives::base`] does not
/// build itself).
pub fn base(def: &Function, args: &[Value], span: Span) -> Eval {
    let a = Args { def, args, span };
    let name = def.name.as_str();
    let factor = || a.num("factor", 1.0);
    match name {
        "checker_texture" => Ok(blended(at(checker(&a)?, &a)?, a.hit("color2", 1.0)?, a.hit("color1", 0.0)?, false)),
        "checker_bump_texture" => bump(checker(&a)?, factor()?, [0.025; 2], &a),
        "perlin_noise_texture" => Ok(blended(at(perlin(&a)?, &a)?, a.hit("color1", 0.0)?, a.hit("color2", 1.0)?, true)),
        "perlin_noise_bump_texture" => {
            let d = 0.1 * a.size("size")? / a.num("noise_bands", 1.0)?.max(1e-3);
            bump(perlin(&a)?, factor()?, [d; 2], &a)
        }
        "worley_noise_texture" => Ok(blended(at(worley(&a)?, &a)?, a.hit("color1", 0.0)?, a.hit("color2", 1.0)?, true)),
        "worley_noise_bump_texture" => {
            let d = 0.1 * a.size("size")? / a.num("noise_bands", 1.0)?.max(1e-3);
            bump(worley(&a)?, factor()?, [d; 2], &a)
        }
        "flow_noise_texture" => Ok(blended(at(flow(&a)?, &a)?, a.hit("color1", 0.0)?, a.hit("color2", 1.0)?, false)),
        "flow_noise_bump_texture" => {
            let d = 0.1 * a.size("size")?;
            bump(flow(&a)?, factor()?, [d; 2], &a)
        }
        "flake_noise_texture" => {
            let r = at(
                Pattern::Flake {
                    intensity: a.num("intensity", 1.0)?,
                    scale: a.size("scale")?,
                    density: a.num("density", 1.0)?,
                    cells: a.int("noise_type", 0)? == 1,
                    maximum_size: a.num("maximum_size", 1.0)?,
                    metric: a.int("metric", 0)?,
                },
                &a,
            )?;
            Ok(texture_return(r.clone(), r))
        }
        "flake_noise_bump_texture" => {
            // The normal tilted towards the flake's own random direction by `strength`.
            let r = at(
                Pattern::FlakeDirection {
                    scale: a.size("scale")?,
                    cells: a.int("noise_type", 0)? == 1,
                    metric: a.int("metric", 0)?,
                },
                &a,
            )?;
            let n = a.hit("normal", 0.0)?;
            let n = if a.get("normal").is_none() { Arc::new(HitExpr::State(StateFn::Normal)) } else { n };
            let dot = fold(HitExpr::Math(MathFn::Dot(3), [r.clone(), n.clone()].into()));
            let along = fold(HitExpr::Binary(BinOp::Mul, n.clone(), dot));
            let tangential = fold(HitExpr::Binary(BinOp::Sub, r, along));
            let tilt = fold(HitExpr::Binary(BinOp::Mul, tangential, constant(a.num("strength", 1.0)?)));
            let sum = fold(HitExpr::Binary(BinOp::Add, n, tilt));
            Ok(Value::from_hit(HitExpr::Math(MathFn::Normalize(3), [sum].into()), HitType::Vector(3)))
        }
        "gradient3_texture" => {
            let tint = at(gradient(&a)?, &a)?;
            Ok(texture_return(tint, constant(0.0)))
        }
        "gradient3_recolor" => gradient_recolor(&a),
        "gradient3_bump_texture" => {
            // The mean of the gradient's colour differenced over 0.0025 in u and v, the
            // normal leaning towards the rise by `scale` / 0.0025 (the MDL SDK's step and
            // direction).
            const DELTA: f32 = 0.0025;
            let scale = a.num("scale", 1.0)?;
            bump(Pattern::Mean(Box::new(gradient(&a)?)), -scale / DELTA, [DELTA; 2], &a)
        }
        "tile_texture" => tile_texture(&a),
        "tile_bump_texture" => {
            // The height (1 on a tile times its brightness) differenced over half the two
            // grout sizes, as the MDL SDK steps it.
            let t = tiles(&a)?;
            let d = (0.5 * (t.grout_width + t.grout_height)).max(1e-4);
            bump(Pattern::Tiles(t), factor()?, [d; 2], &a)
        }
        "file_bump_texture" => file_bump(&a),
        "blend_color_layers" => blend_color_layers(&a),
        "coordinate_projection" => coordinate_projection(&a),
        "sun_and_sky" => super::sky::sun_and_sky(def, args, span),
        "perez_sun_and_sky" => super::sky::perez_sun_and_sky(def, args, span),
        "lookup_volume_coefficients" => super::base_volume::lookup_volume_coefficients(def, args, span),
        "volume_blackbody_emission" => super::base_volume::volume_blackbody_emission(def, args, span),
        _ => Err(problem(span, format!("`base::{name}` is not compiled in module materials yet"))),
    }
}

/// `file_bump_texture`: the height is the texel by `bump_source`, differenced over one
/// texel in u and v — the same formula as the shader-graph node
/// (`mdl::texture::FILE_BUMP`).
fn file_bump(a: &Args) -> Eval {
    let crop = super::hit_natives::crops(a.get("crop_u"), a.get("crop_v"), a.span)?;
    if crop != [0.0, 1.0, 0.0, 1.0] {
        return Err(problem(a.span, "`base::file_bump_texture` with a crop is not compiled yet"));
    }
    let normal = || match a.get("normal") {
        Some(v) => v.clone(),
        None => state_value(StateFn::Normal),
    };
    let image = match a.get("texture") {
        Some(Value::Texture(Some(image))) => image.clone(),
        // No image: no slope, the normal as it is.
        Some(Value::Texture(None)) => return Ok(normal()),
        Some(v) => return Err(a.not_constant("texture", v)),
        None => return Err(problem(a.span, "`base::file_bump_texture` without a texture")),
    };
    let (w, h) = image.size();
    let delta = [1.0 / w.max(1) as f32, 1.0 / h.max(1) as f32];
    let height = Pattern::ImageHeight {
        image,
        wrap: [wrap_name(enum_arg(a.get("wrap_u"), 1)), wrap_name(enum_arg(a.get("wrap_v"), 1))],
        clip: a.flag("clip")?,
        mono: mono_name(enum_arg(a.get("bump_source"), 1)),
    };
    bump(height, a.num("factor", 1.0)?, delta, a)
}
