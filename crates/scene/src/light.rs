//! Lights in world space.
//!
//! A light's geometry is given in its instance's space and carried to world space by the
//! instance path. Which of `origin`, `direction` and `spread` are given decides the type:
//! a direction alone makes a directional (infinite) light, origin, direction and spread a
//! spot, anything else a point light; an area shape turns a point or spot light into an
//! area light of that shape.

use glam::{DMat4, DVec3};
use mi::ast::{Arg, Block, ShaderList, Stmt};

use crate::values::{attributes, bool_arg, f64_arg, floats_arg, int_arg, last, str_arg, Attributes};

/// The shape of an area light, world space.
#[derive(Clone, Debug, PartialEq)]
pub enum AreaShape {
    /// A parallelogram centred on the light's position, spanned by two full edge vectors;
    /// it faces `normal` (`edge_u × edge_v` in light space, carried to world space as a
    /// normal, so that a mirroring instance transform does not turn the light around).
    Rectangle {
        /// First edge.
        edge_u: DVec3,
        /// Second edge.
        edge_v: DVec3,
        /// Unit normal of the emitting side.
        normal: DVec3,
    },
    /// A disc centred on the position, facing `normal`.
    Disc {
        /// Unit normal.
        normal: DVec3,
        /// Radius.
        radius: f64,
    },
    /// A sphere around the position.
    Sphere {
        /// Radius.
        radius: f64,
    },
    /// A cylinder centred on the position along `axis` (full length).
    Cylinder {
        /// Axis, full length.
        axis: DVec3,
        /// Radius.
        radius: f64,
    },
    /// An object instance used as the light's surface.
    Object {
        /// The instance's name.
        instance: String,
    },
    /// A user-defined shape (the light shader samples it).
    User,
}

/// An area light's shape and sampling.
#[derive(Clone, Debug, PartialEq)]
pub struct AreaLight {
    /// The shape.
    pub shape: AreaShape,
    /// Samples in u and v (mental ray's `u v`; a single number means u×1).
    pub samples: (u32, u32),
    /// From this ray level on, the low sample counts are used: (level, u, v).
    pub low: Option<(u32, u32, u32)>,
}

/// The type of a light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightKind {
    /// Emits in all directions from a point (or area).
    Point,
    /// A cone of light.
    Spot,
    /// Parallel light from infinitely far away.
    Directional,
}

/// One light instance, world space.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// The light element's name.
    pub name: String,
    /// The light instance's name.
    pub instance: String,
    /// The light shader list (mental ray), or the MDL emissive material (Iray, `= "def"`).
    pub shader: Option<ShaderList>,
    /// The photon emitter shader.
    pub emitter: Option<ShaderList>,
    /// Point, spot or directional.
    pub kind: LightKind,
    /// Position, world space.
    pub position: DVec3,
    /// Direction the light travels, world space, unit length (spot and directional).
    pub direction: DVec3,
    /// Cosine of the spot cone's outer half-angle.
    pub spread: f64,
    /// The area shape, if it is an area light.
    pub area: Option<AreaLight>,
    /// The light's surface is seen by rays.
    pub visible: bool,
    /// Casts shadows.
    pub shadow: bool,
    /// `energy r g b`: photon energy.
    pub energy: Option<[f64; 3]>,
    /// `exponent`: photon falloff exponent.
    pub exponent: f64,
    /// `caustic photons store [emit]`: caustic photons to store, and the most to emit.
    pub caustic_photons: Option<(u32, Option<u32>)>,
    /// `globillum photons store [emit]`: global illumination photons to store, and the
    /// most to emit.
    pub globillum_photons: Option<(u32, Option<u32>)>,
    /// `shadowmap`.
    pub shadowmap: bool,
    /// `lightprofile "name"`.
    pub lightprofile: Option<String>,
    /// Light space → world space.
    pub light_to_world: DMat4,
    /// Light space → world space at the end of the motion interval, when the light's
    /// instance path moves (`motion transform`).
    pub motion_light_to_world: Option<DMat4>,
    /// Attributes.
    pub attributes: Attributes,
}

/// Low-level sampling of an area light: (ray level, u, v).
type LowSamples = Option<(u32, u32, u32)>;

fn samples(args: &[Arg], from: usize) -> ((u32, u32), LowSamples) {
    let ints: Vec<u32> = args[from.min(args.len())..]
        .iter()
        .filter_map(|a| if let Arg::Int(i) = a { Some((*i).clamp(1, 1 << 16) as u32) } else { None })
        .collect();
    let main = match ints[..] {
        [] => (1, 1),
        [u] => (u, 1),
        [u, v, ..] => (u, v),
    };
    let low = match ints[..] {
        [_, _, level, lu, lv] => Some((level, lu, lv)),
        [_, _, level] => Some((level, 1, 1)),
        _ => None,
    };
    (main, low)
}

impl Light {
    /// Reads a light's definitions, placed by `light_to_world`.
    pub fn from_blocks(
        blocks: &[&Block],
        instance: &str,
        light_to_world: DMat4,
        instance_visible: Option<bool>,
    ) -> Light {
        let stmts: Vec<&Stmt> = blocks.iter().flat_map(|b| b.stmts.iter()).collect();
        let origin = last(&stmts, "origin").and_then(|k| floats_arg(k, 0)).map(|v| DVec3::new(v[0], v[1], v[2]));
        let dir = last(&stmts, "direction").and_then(|k| floats_arg(k, 0)).map(|v| DVec3::new(v[0], v[1], v[2]));
        let spread = last(&stmts, "spread").and_then(|k| f64_arg(k, 0));
        let kind = match (origin, dir, spread) {
            (_, Some(_), Some(_)) if origin.is_some() => LightKind::Spot,
            (None, Some(_), _) => LightKind::Directional,
            (Some(_), Some(_), None) => LightKind::Directional,
            _ => LightKind::Point,
        };
        let position = light_to_world.transform_point3(origin.unwrap_or(DVec3::ZERO));
        let direction = light_to_world.transform_vector3(dir.unwrap_or(DVec3::NEG_Z)).normalize_or(DVec3::NEG_Z);
        let vec = |v: &[f64]| DVec3::new(v[0], v[1], v[2]);
        // The area shape: the last shape statement wins; a bare keyword turns it off.
        let mut area = None;
        for s in &stmts {
            let Stmt::Kw(k) = s else { continue };
            let shape = match k.key {
                "rectangle" | "disc" | "sphere" | "cylinder" if k.args.is_empty() => {
                    area = None;
                    continue;
                }
                "rectangle" => {
                    let (Some(u), Some(v)) = (floats_arg(k, 0), floats_arg(k, 1)) else { continue };
                    let normal_matrix = light_to_world.inverse().transpose();
                    let shape = AreaShape::Rectangle {
                        edge_u: light_to_world.transform_vector3(vec(u)),
                        edge_v: light_to_world.transform_vector3(vec(v)),
                        normal: normal_matrix.transform_vector3(vec(u).cross(vec(v))).normalize_or(DVec3::Z),
                    };
                    (shape, 2)
                }
                "disc" => {
                    let Some(n) = floats_arg(k, 0) else { continue };
                    let r = f64_arg(k, 1).unwrap_or(1.0);
                    let normal_matrix = light_to_world.inverse().transpose();
                    let normal = normal_matrix.transform_vector3(vec(n)).normalize_or(DVec3::Z);
                    (AreaShape::Disc { normal, radius: r * scale(light_to_world) }, 2)
                }
                "sphere" => (AreaShape::Sphere { radius: f64_arg(k, 0).unwrap_or(1.0) * scale(light_to_world) }, 1),
                "cylinder" => {
                    let Some(a) = floats_arg(k, 0) else { continue };
                    let shape = AreaShape::Cylinder {
                        axis: light_to_world.transform_vector3(vec(a)),
                        radius: f64_arg(k, 1).unwrap_or(1.0) * scale(light_to_world),
                    };
                    (shape, 2)
                }
                "object" => (AreaShape::Object { instance: str_arg(k, 0).unwrap_or("").to_string() }, 1),
                "user" => (AreaShape::User, 0),
                _ => continue,
            };
            let (samples, low) = samples(&k.args, shape.1);
            area = Some(AreaLight { shape: shape.0, samples, low });
        }
        let shader = stmts.iter().rev().find_map(|s| if let Stmt::Shaders(l) = s { Some(l.clone()) } else { None });
        let emitter = last(&stmts, "emitter").and_then(|k| {
            if let Some(Arg::Shaders(l)) = k.args.first() {
                Some(l.clone())
            } else {
                None
            }
        });
        let visible = last(&stmts, "visible").map(|k| bool_arg(k, 0)).or(instance_visible).unwrap_or(false);
        Light {
            name: blocks.first().map(|b| b.name.text.clone()).unwrap_or_default(),
            instance: instance.to_string(),
            shader,
            emitter,
            kind,
            position,
            direction,
            spread: spread.unwrap_or(0.0),
            area,
            visible: instance_visible.unwrap_or(visible),
            shadow: last(&stmts, "shadow").map(|k| bool_arg(k, 0)).unwrap_or(true),
            energy: last(&stmts, "energy").and_then(|k| {
                k.args.iter().find_map(|a| if let Arg::Floats(v) = a { Some([v[0], v[1], v[2]]) } else { None })
            }),
            exponent: last(&stmts, "exponent").and_then(|k| f64_arg(k, 0)).unwrap_or(2.0),
            caustic_photons: last(&stmts, "caustic photons").and_then(photon_counts),
            globillum_photons: last(&stmts, "globillum photons").and_then(photon_counts),
            shadowmap: last(&stmts, "shadowmap").map(|k| bool_arg(k, 0)).unwrap_or(false),
            lightprofile: last(&stmts, "lightprofile").and_then(|k| str_arg(k, 0)).map(String::from),
            light_to_world,
            motion_light_to_world: None,
            attributes: attributes(&stmts),
        }
    }

    /// The area light's surface area, world space (`None` for non-area lights and shapes
    /// without a closed form).
    pub fn area_size(&self) -> Option<f64> {
        Some(match &self.area.as_ref()?.shape {
            AreaShape::Rectangle { edge_u, edge_v, .. } => edge_u.cross(*edge_v).length(),
            AreaShape::Disc { radius, .. } => std::f64::consts::PI * radius * radius,
            AreaShape::Sphere { radius } => 4.0 * std::f64::consts::PI * radius * radius,
            AreaShape::Cylinder { axis, radius } => std::f64::consts::TAU * radius * axis.length(),
            _ => return None,
        })
    }

    /// The emitting side's normal of a rectangle or disc light, world space.
    pub fn area_normal(&self) -> Option<DVec3> {
        match &self.area.as_ref()?.shape {
            AreaShape::Rectangle { normal, .. } => Some(*normal),
            AreaShape::Disc { normal, .. } => Some(*normal),
            _ => None,
        }
    }
}

/// Most photons a light stores (or emits) per map: 16.7 M, about 1 GiB of photons; a
/// larger count in a file would only exhaust memory.
pub const MAX_PHOTONS: i64 = 1 << 24;

/// `store [emit]` of a `caustic photons` or `globillum photons` statement (negative
/// counts read as 0, counts above [`MAX_PHOTONS`] as it).
fn photon_counts(k: &mi::ast::KwStmt) -> Option<(u32, Option<u32>)> {
    let count = |i| int_arg(k, i).map(|n| n.clamp(0, MAX_PHOTONS) as u32);
    Some((count(0)?, count(1)))
}

/// The mean linear scale of a transform (for radii).
fn scale(m: DMat4) -> f64 {
    let d = m.determinant().abs();
    if d > 0.0 {
        d.cbrt()
    } else {
        1.0
    }
}
