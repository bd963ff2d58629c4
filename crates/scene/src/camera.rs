//! The render camera: the mental ray pinhole (or orthographic) camera placed by its
//! instance, its outputs and frame buffers.
//!
//! Camera space looks down −Z with +Y up. The image plane at distance `focal` is `aperture`
//! wide and `aperture / aspect` high; only the ratios matter, so the horizontal field of
//! view is `2·atan(aperture / (2·focal))`.

use glam::{DMat4, DVec3};
use mi::ast::{Arg, Block, KwStmt, OutputKind, ShaderList, Stmt};
use mi::Diagnostic;

use crate::values::{attributes, f64_arg, int_arg, last, str_arg, Attributes};

/// An image file or output shader the camera asks for.
#[derive(Clone, Debug, PartialEq)]
pub enum Output {
    /// Write frame buffers to a file.
    File {
        /// Frame buffer types (`+rgba`, `z`, `fb0`, …); empty for the default colour buffer.
        types: Vec<String>,
        /// File format (`exr`, `png`, …).
        format: String,
        /// File name.
        file: String,
    },
    /// Run output shaders.
    Shader {
        /// Frame buffer types it reads.
        types: Vec<String>,
        /// The shaders.
        shaders: ShaderList,
    },
}

/// A named frame buffer of a mental ray 3.10+ camera (`framebuffer "name" …`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Framebuffer {
    /// Its name.
    pub name: String,
    /// `datatype` (`rgba`, `rgba_fp`, `z`, `n`, …).
    pub datatype: String,
    /// `filtering`: samples filtered (true) or the frontmost taken.
    pub filtering: Option<bool>,
    /// `filename`, which also marks it for output.
    pub filename: Option<String>,
    /// `filetype`.
    pub filetype: Option<String>,
    /// `primary`: the main colour buffer.
    pub primary: bool,
    /// `user`: written by shaders.
    pub user: bool,
}

/// The camera used for rendering.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// The camera element's name.
    pub name: String,
    /// The camera instance's name.
    pub instance: String,
    /// Distance to the image plane; `None` for an orthographic camera (`focal infinity`).
    pub focal: Option<f64>,
    /// Width of the image plane (for orthographic cameras, of the view).
    pub aperture: f64,
    /// Image plane width / height.
    pub aspect: f64,
    /// Pixels (width, height).
    pub resolution: (u32, u32),
    /// Where the resolution is written: the `resolution` statement, or the camera element
    /// when it has none (the default 768 × 576 applies).
    pub resolution_span: mi::Span,
    /// Image centre shift in pixels.
    pub offset: (f64, f64),
    /// `window xl yl xh yh`: the pixel rectangle to render.
    pub window: Option<[i64; 4]>,
    /// Near and far clipping distances along −Z.
    pub clip: (f64, f64),
    /// `frame n [time]`.
    pub frame: (i64, f64),
    /// World → camera space.
    pub world_to_camera: DMat4,
    /// Camera → world space.
    pub camera_to_world: DMat4,
    /// World → camera space at the end of the motion interval, when the camera's instance
    /// path moves (`motion transform`, see [`crate::Instance::motion_world_to_object`]).
    pub motion_world_to_camera: Option<DMat4>,
    /// `lens` shaders, in order.
    pub lens: Vec<ShaderList>,
    /// `environment` shaders.
    pub environment: Option<ShaderList>,
    /// `volume` shaders.
    pub volume: Option<ShaderList>,
    /// `output` statements, in order.
    pub outputs: Vec<Output>,
    /// `framebuffer` statements.
    pub framebuffers: Vec<Framebuffer>,
    /// Attributes (Iray tone mapping: `tm_tonemapper`, `mip_*`).
    pub attributes: Attributes,
}

/// The largest image mira renders, in pixels per side.
pub const MAX_RESOLUTION: u32 = 1 << 16;

impl Camera {
    /// Reads the camera's definitions; `world_to_camera` comes from its instance path.
    ///
    /// Values no camera model can use are reported at their statement: a focal length or
    /// aperture that is not a positive finite number and a resolution outside 1 …
    /// [`MAX_RESOLUTION`] are errors (the values read are then replaced by the defaults, so
    /// that the returned camera is still finite); a non-positive or non-finite aspect ratio,
    /// image offset or clipping range is a warning and the default is used.
    pub fn from_blocks(
        blocks: &[&Block],
        instance: &str,
        world_to_camera: DMat4,
        camera_to_world: DMat4,
        diags: &mut Vec<Diagnostic>,
    ) -> Camera {
        let stmts: Vec<&Stmt> = blocks.iter().flat_map(|b| b.stmts.iter()).collect();
        let element_span = blocks.first().map(|b| b.span).unwrap_or_default();
        let positive = |v: f64| v > 0.0 && v.is_finite();
        let focal = match last(&stmts, "focal") {
            Some(k) if str_arg(k, 0) == Some("infinity") => None,
            Some(k) => match f64_arg(k, 0) {
                Some(f) if positive(f) => Some(f),
                f => {
                    diags.push(Diagnostic::error(
                        k.span,
                        format!(
                            "camera focal length {} is not a positive finite number (or 'infinity' for an \
                             orthographic camera)",
                            number(f)
                        ),
                    ));
                    Some(1.0)
                }
            },
            None => Some(1.0),
        };
        let aperture = match last(&stmts, "aperture") {
            Some(k) => match f64_arg(k, 0) {
                Some(a) if positive(a) => a,
                a => {
                    diags.push(Diagnostic::error(
                        k.span,
                        format!("camera aperture {} is not a positive finite number", number(a)),
                    ));
                    1.0
                }
            },
            None => 1.0,
        };
        let (resolution, resolution_span) = match last(&stmts, "resolution") {
            Some(k) => (read_resolution(k, diags), k.span),
            None => ((768, 576), element_span),
        };
        let default_aspect = resolution.0 as f64 / resolution.1 as f64;
        let aspect = match last(&stmts, "aspect") {
            Some(k) => match f64_arg(k, 0) {
                Some(a) if positive(a) => a,
                a => {
                    diags.push(Diagnostic::warning(
                        k.span,
                        format!(
                            "camera aspect {} is not a positive finite number: the resolution's ratio {} is used",
                            number(a),
                            number(Some(default_aspect))
                        ),
                    ));
                    default_aspect
                }
            },
            None => default_aspect,
        };
        let offset = match last(&stmts, "offset") {
            Some(k) => {
                let o = (f64_arg(k, 0).unwrap_or(0.0), f64_arg(k, 1).unwrap_or(0.0));
                if o.0.is_finite() && o.1.is_finite() {
                    o
                } else {
                    diags.push(Diagnostic::warning(k.span, "camera offset is not finite: no offset is used"));
                    (0.0, 0.0)
                }
            }
            None => (0.0, 0.0),
        };
        let default_clip = (0.001, 1e30);
        let clip = match last(&stmts, "clip") {
            Some(k) => {
                let c = (f64_arg(k, 0).unwrap_or(default_clip.0), f64_arg(k, 1).unwrap_or(default_clip.1));
                if c.0 >= 0.0 && c.0 < c.1 && !c.0.is_nan() && !c.1.is_nan() {
                    c
                } else {
                    diags.push(Diagnostic::warning(
                        k.span,
                        format!(
                            "camera clip {} {} is not a range from a near distance ≥ 0 to a farther one: \
                             0.001 1e30 is used",
                            number(Some(c.0)),
                            number(Some(c.1))
                        ),
                    ));
                    default_clip
                }
            }
            None => default_clip,
        };
        let mut cam = Camera {
            name: blocks.first().map(|b| b.name.text.clone()).unwrap_or_default(),
            instance: instance.to_string(),
            focal,
            aperture,
            aspect,
            resolution,
            resolution_span,
            offset,
            window: last(&stmts, "window").map(|k| [0, 1, 2, 3].map(|i| int_arg(k, i).unwrap_or(0))),
            clip,
            frame: last(&stmts, "frame")
                .map(|k| (int_arg(k, 0).unwrap_or(1), f64_arg(k, 1).unwrap_or(0.0)))
                .unwrap_or((1, 0.0)),
            world_to_camera,
            motion_world_to_camera: None,
            camera_to_world,
            lens: Vec::new(),
            environment: None,
            volume: None,
            outputs: Vec::new(),
            framebuffers: Vec::new(),
            attributes: attributes(&stmts),
        };
        for s in &stmts {
            match s {
                Stmt::Kw(k) => {
                    let shaders = match k.args.first() {
                        Some(Arg::Shaders(l)) => Some(l.clone()),
                        _ => None,
                    };
                    match k.key {
                        // A bare `lens`/`environment`/`volume` clears the slot.
                        "lens" => match shaders {
                            Some(l) => cam.lens.push(l),
                            None => cam.lens.clear(),
                        },
                        "environment" => cam.environment = shaders,
                        "volume" => cam.volume = shaders,
                        _ => {}
                    }
                }
                Stmt::Output(o) => {
                    let types: Vec<String> = o
                        .types
                        .as_ref()
                        .map(|t| t.text.split(',').map(|s| s.trim().to_string()).filter(|s| !s.is_empty()).collect())
                        .unwrap_or_default();
                    match &o.kind {
                        OutputKind::File { format, file, .. } => cam.outputs.push(Output::File {
                            types,
                            format: format.text.clone(),
                            file: file.text.clone(),
                        }),
                        OutputKind::Shader(l) => cam.outputs.push(Output::Shader { types, shaders: l.clone() }),
                        OutputKind::Clear => {
                            cam.outputs.clear();
                            cam.framebuffers.clear();
                        }
                    }
                }
                Stmt::Framebuffer(fb) => {
                    let at = match cam.framebuffers.iter().position(|f| f.name == fb.name.text) {
                        Some(i) => i,
                        None => {
                            cam.framebuffers.push(Framebuffer {
                                name: fb.name.text.clone(),
                                datatype: "rgba".into(),
                                ..Framebuffer::default()
                            });
                            cam.framebuffers.len() - 1
                        }
                    };
                    let f = &mut cam.framebuffers[at];
                    for field in &fb.fields {
                        if let Stmt::Kw(k) = field {
                            let b = || matches!(k.args.first(), Some(Arg::Bool(true)));
                            match k.key {
                                "datatype" => f.datatype = str_arg(k, 0).unwrap_or("rgba").to_string(),
                                "filtering" => f.filtering = Some(b()),
                                "filename" => f.filename = str_arg(k, 0).map(String::from),
                                "filetype" => f.filetype = str_arg(k, 0).map(String::from),
                                "primary" => f.primary = b(),
                                "user" => f.user = b(),
                                _ => {}
                            }
                        }
                    }
                }
                _ => {}
            }
        }
        cam
    }

    /// Horizontal field of view in radians (0 for orthographic cameras).
    pub fn fov_x(&self) -> f64 {
        self.focal.map_or(0.0, |f| 2.0 * (self.aperture / (2.0 * f)).atan())
    }

    /// Vertical field of view in radians.
    pub fn fov_y(&self) -> f64 {
        self.focal.map_or(0.0, |f| 2.0 * (self.aperture / (2.0 * self.aspect * f)).atan())
    }

    /// The eye position, world space.
    pub fn position(&self) -> DVec3 {
        self.camera_to_world.transform_point3(DVec3::ZERO)
    }

    /// The viewing direction (camera −Z), world space, unit length.
    pub fn forward(&self) -> DVec3 {
        self.camera_to_world.transform_vector3(DVec3::NEG_Z).normalize_or_zero()
    }

    /// The up direction (camera +Y), world space, unit length.
    pub fn up(&self) -> DVec3 {
        self.camera_to_world.transform_vector3(DVec3::Y).normalize_or_zero()
    }
}

/// `resolution x y`, each side checked against 1 … [`MAX_RESOLUTION`]; an error (and
/// 768 × 576) when either side is outside.
fn read_resolution(k: &KwStmt, diags: &mut Vec<Diagnostic>) -> (u32, u32) {
    let (x, y) = (int_arg(k, 0), int_arg(k, 1));
    let fits = |v: Option<i64>| v.is_some_and(|v| (1..=i64::from(MAX_RESOLUTION)).contains(&v));
    if fits(x) && fits(y) {
        return (x.unwrap_or(1) as u32, y.unwrap_or(1) as u32);
    }
    let side = |v: Option<i64>| v.map_or("?".to_string(), |v| v.to_string());
    diags.push(Diagnostic::error(
        k.span,
        format!("camera resolution {} x {} is outside 1 … {MAX_RESOLUTION} pixels per side", side(x), side(y)),
    ));
    (768, 576)
}

/// A number for a message (`?` when absent or not a number).
fn number(v: Option<f64>) -> String {
    match v {
        Some(v) if v.is_finite() => format!("{v}"),
        Some(v) if v.is_nan() => "NaN".into(),
        Some(v) if v > 0.0 => "infinity".into(),
        Some(_) => "-infinity".into(),
        None => "?".into(),
    }
}
