//! Instances of objects in the world: their transforms, flags and material bindings.

use glam::DMat4;
use mi::ast::{Arg, KwStmt, Stmt};

use crate::options::Face;
use crate::values::{bool_arg, int_arg, str_arg};

#[cfg(test)]
mod tests;

/// A cast/receive pair of an object or instance mode (`shadow`, `reflection`, …).
///
/// For shadows: cast = the object casts shadows, receive = it is shadowed. For reflection,
/// refraction, transparency and final gathering: cast = the object is seen by those rays,
/// receive = the object itself reflects, refracts, lets light through or is lit by final
/// gathering. For caustic and global illumination photons: cast = photons are sent
/// towards it, receive = photons are stored on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mode {
    /// The "cast" bit (1).
    pub cast: bool,
    /// The "receive" bit (2).
    pub receive: bool,
}

impl Mode {
    /// Both bits on.
    pub const BOTH: Mode = Mode { cast: true, receive: true };
}

/// Render flags of an instance, after inheritance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Flags {
    /// Seen by primary (eye) rays.
    pub visible: bool,
    /// Shadows.
    pub shadow: Mode,
    /// Reflection rays.
    pub reflection: Mode,
    /// Refraction rays.
    pub refraction: Mode,
    /// Transparency rays.
    pub transparency: Mode,
    /// Final gather rays.
    pub finalgather: Mode,
    /// Caustic photons.
    pub caustic: Mode,
    /// Global illumination photons.
    pub globillum: Mode,
    /// Which faces exist for rays.
    pub face: Face,
    /// Drawn into shadow maps.
    pub shadowmap: bool,
}

impl Default for Flags {
    /// Everything on, both faces: what exporters write for ordinary geometry. (mental ray
    /// 1 and 2 treated an absent `visible`, `shadow` or `trace` as off; mira does not.)
    fn default() -> Flags {
        Flags {
            visible: true,
            shadow: Mode::BOTH,
            reflection: Mode::BOTH,
            refraction: Mode::BOTH,
            transparency: Mode::BOTH,
            finalgather: Mode::BOTH,
            caustic: Mode::BOTH,
            globillum: Mode::BOTH,
            face: Face::Both,
            shadowmap: true,
        }
    }
}

/// A cast/receive pair as written: each bit set on, set off, or not set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ModeSet {
    /// The cast bit, if set.
    pub cast: Option<bool>,
    /// The receive bit, if set.
    pub receive: Option<bool>,
}

impl ModeSet {
    fn both(v: bool) -> ModeSet {
        ModeSet { cast: Some(v), receive: Some(v) }
    }

    /// An object's mode value: bit 1 cast, bit 2 receive, both always set.
    fn object(v: i64) -> ModeSet {
        ModeSet { cast: Some(v & 1 != 0), receive: Some(v & 2 != 0) }
    }

    /// An instance's mode value: bits 1/2 force cast/receive on, 4/8 force them off,
    /// unset bits inherit.
    fn instance(v: i64) -> ModeSet {
        let bit = |on: i64, off: i64| {
            if v & on != 0 {
                Some(true)
            } else if v & off != 0 {
                Some(false)
            } else {
                None
            }
        };
        ModeSet { cast: bit(1, 4), receive: bit(2, 8) }
    }

    fn or(self, below: ModeSet) -> ModeSet {
        ModeSet { cast: self.cast.or(below.cast), receive: self.receive.or(below.receive) }
    }

    fn resolve(self, default: Mode) -> Mode {
        Mode { cast: self.cast.unwrap_or(default.cast), receive: self.receive.unwrap_or(default.receive) }
    }
}

/// Flags written on one element (object or instance); unset ones are inherited.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FlagSet {
    /// `visible`
    pub visible: Option<bool>,
    /// `shadow`
    pub shadow: ModeSet,
    /// `reflection` (and `trace`)
    pub reflection: ModeSet,
    /// `refraction` (and `trace`)
    pub refraction: ModeSet,
    /// `transparency`
    pub transparency: ModeSet,
    /// `finalgather` (and `trace`)
    pub finalgather: ModeSet,
    /// `caustic`
    pub caustic: ModeSet,
    /// `globillum`
    pub globillum: ModeSet,
    /// `face`
    pub face: Option<Face>,
    /// `shadowmap`
    pub shadowmap: Option<bool>,
    /// `hide`
    pub hide: Option<bool>,
}

/// Whether the flags are written on an object or an instance (integer modes differ).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FlagOwner {
    /// Object flags: modes are cast/receive bits.
    Object,
    /// Instance flags: modes force bits on or off.
    Instance,
}

impl FlagSet {
    /// Reads the flag statements among `stmts` (later statements win).
    pub fn read<'a>(stmts: impl IntoIterator<Item = &'a Stmt>, owner: FlagOwner) -> FlagSet {
        let mut f = FlagSet::default();
        let int = |v: i64| match owner {
            FlagOwner::Object => ModeSet::object(v),
            FlagOwner::Instance => ModeSet::instance(v),
        };
        // `on`/`off` and integer modes; `shadow off` keeps receiving, as mental ray does.
        let mode = |k: &KwStmt, off: ModeSet| match k.args.first() {
            Some(Arg::Bool(false)) => off,
            Some(Arg::Int(v)) => int(*v),
            _ => ModeSet::both(true),
        };
        for s in stmts {
            let Stmt::Kw(k) = s else { continue };
            match k.key {
                "visible" => f.visible = Some(bool_arg(k, 0)),
                "shadow" => f.shadow = mode(k, ModeSet { cast: Some(false), receive: Some(true) }),
                "trace" => {
                    let m = if bool_arg(k, 0) {
                        ModeSet::both(true)
                    } else if owner == FlagOwner::Object {
                        ModeSet { cast: Some(false), receive: Some(true) }
                    } else {
                        ModeSet::both(false)
                    };
                    f.reflection = m;
                    f.refraction = m;
                    f.finalgather = m;
                }
                "reflection" => f.reflection = int_arg(k, 0).map_or(f.reflection, int),
                "refraction" => f.refraction = int_arg(k, 0).map_or(f.refraction, int),
                "transparency" => f.transparency = int_arg(k, 0).map_or(f.transparency, int),
                "caustic" => f.caustic = mode(k, ModeSet::both(false)),
                "globillum" => f.globillum = mode(k, ModeSet::both(false)),
                "finalgather" => f.finalgather = mode(k, ModeSet::both(false)),
                "face" => f.face = str_arg(k, 0).map(Face::from_word),
                "shadowmap" => f.shadowmap = Some(bool_arg(k, 0)),
                "hide" => f.hide = Some(bool_arg(k, 0)),
                _ => {}
            }
        }
        f
    }

    /// `self` (closer to the object) with its unset flags taken from `other`.
    pub fn or(self, other: FlagSet) -> FlagSet {
        FlagSet {
            visible: self.visible.or(other.visible),
            shadow: self.shadow.or(other.shadow),
            reflection: self.reflection.or(other.reflection),
            refraction: self.refraction.or(other.refraction),
            transparency: self.transparency.or(other.transparency),
            finalgather: self.finalgather.or(other.finalgather),
            caustic: self.caustic.or(other.caustic),
            globillum: self.globillum.or(other.globillum),
            face: self.face.or(other.face),
            shadowmap: self.shadowmap.or(other.shadowmap),
            hide: self.hide.or(other.hide),
        }
    }

    /// The final flags: unset flags take the defaults (`face` from the options).
    pub fn resolve(self, face: Face) -> Flags {
        let d = Flags::default();
        Flags {
            visible: self.visible.unwrap_or(d.visible),
            shadow: self.shadow.resolve(d.shadow),
            reflection: self.reflection.resolve(d.reflection),
            refraction: self.refraction.resolve(d.refraction),
            transparency: self.transparency.resolve(d.transparency),
            finalgather: self.finalgather.resolve(d.finalgather),
            caustic: self.caustic.resolve(d.caustic),
            globillum: self.globillum.resolve(d.globillum),
            face: self.face.unwrap_or(face),
            shadowmap: self.shadowmap.unwrap_or(d.shadowmap),
        }
    }
}

/// An instance's light list (`light ["exclusive"] [ … ]`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LightLink {
    /// The listed lights are excluded (all others apply) rather than the only ones.
    pub exclusive: bool,
    /// Indices into the scene's lights.
    pub lights: Vec<u32>,
}

/// An object placed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// The (leaf) instance's full name.
    pub name: String,
    /// Index of the object in [`crate::Scene::objects`].
    pub object: u32,
    /// Object space → world space.
    pub object_to_world: DMat4,
    /// World space → object space (mental ray's instance transform, composed).
    pub world_to_object: DMat4,
    /// World → object at the other end of the shutter interval, when the instance moves.
    pub motion_world_to_object: Option<DMat4>,
    /// Render flags.
    pub flags: Flags,
    /// For each material slot of the object's mesh, the material index in
    /// [`crate::Scene::materials`] (`None`: no material found).
    pub materials: Vec<Option<u32>>,
    /// For each hair block of the object, its material.
    pub hair_materials: Vec<Option<u32>>,
    /// The instance's light list, if it has one.
    pub lights: Option<LightLink>,
    /// The instance's shadow light list, if it has one.
    pub shadow_lights: Option<LightLink>,
    /// `tag`: the label written to the tag frame buffer.
    pub tag: Option<i64>,
}
