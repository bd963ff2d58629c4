//! A scene's light profiles (`lightprofile "name" format ies file "f.ies" [flags n]
//! [hermite n] [resolution x y] end lightprofile`), read once each, in the order of the
//! library's names (the index a `Tag::Lightprofile` carries).
//!
//! Files are looked for as texture files are: absolute, then beside the scene file and in
//! the `-I` include directories (see [`SearchPath`]). Eulumdat files are not read yet: such
//! a profile is missing (lights using it shine uniformly), with a warning.

use std::sync::Arc;

use glam::{Mat3A, Vec3A};
use mi::ast::{Arg, Block, Stmt};
use mi::Diagnostic;

use super::ies::Profile;
use crate::texture::SearchPath;

/// Reads every light profile of `lib`, in name order; one that cannot be read is `None`
/// and has a warning.
pub fn load_all(lib: &scene::Library, search: &SearchPath) -> (Vec<Option<Arc<Profile>>>, Vec<Diagnostic>) {
    let mut diags = Vec::new();
    let profiles = lib
        .lightprofiles
        .iter()
        .map(|(name, blocks)| {
            let block = blocks.last()?;
            match load_block(block, search) {
                Ok((p, warnings)) => {
                    for w in warnings {
                        diags.push(Diagnostic::warning(block.span, format!("lightprofile '{name}': {w}")));
                    }
                    Some(Arc::new(p))
                }
                Err(e) => {
                    diags.push(Diagnostic::warning(
                        block.span,
                        format!("lightprofile '{name}': {e}; lights using it shine uniformly"),
                    ));
                    None
                }
            }
        })
        .collect();
    (profiles, diags)
}

/// The last statement `key` of a block, its arguments.
fn statement<'a>(block: &'a Block, key: &str) -> Option<&'a [Arg]> {
    block.stmts.iter().rev().find_map(|s| match s {
        Stmt::Kw(k) if k.key == key => Some(k.args.as_slice()),
        _ => None,
    })
}

/// The file a `lightprofile` block reads (its last `file` statement), as written.
pub fn file_name(block: &Block) -> Option<String> {
    statement(block, "file").and_then(|a| match a.first()? {
        Arg::Word(w) => Some(w.to_string()),
        Arg::Name(n) => Some(n.text.clone()),
        _ => None,
    })
}

/// Reads one `lightprofile` block's file (found on `search`): the profile and what reading
/// it approximated; `Err` says why it could not be read.
pub fn load_block(block: &Block, search: &SearchPath) -> Result<(Profile, Vec<String>), String> {
    let word = |a: &Arg| match a {
        Arg::Word(w) => Some(w.to_string()),
        Arg::Name(n) => Some(n.text.clone()),
        _ => None,
    };
    let int = |a: &Arg| match a {
        Arg::Int(i) => Some(*i),
        Arg::Num(n) => Some(n.as_f64() as i64),
        _ => None,
    };
    let format = statement(block, "format").and_then(|a| a.first().and_then(word)).unwrap_or_default();
    if !format.eq_ignore_ascii_case("ies") {
        return Err(if format.is_empty() {
            "no `format` statement".into()
        } else {
            format!("format {format} is not read yet (only ies)")
        });
    }
    let Some(file) = file_name(block) else {
        return Err("no `file` statement".into());
    };
    let Some(path) = search.resolve(&file) else {
        return Err(format!("file '{file}' not found"));
    };
    let clockwise = statement(block, "flags").and_then(|a| a.first().and_then(int)) == Some(1);
    let (p, mut warnings) = Profile::load(&path, clockwise).map_err(|e| format!("{}: {e}", path.display()))?;
    if statement(block, "hermite").and_then(|a| a.first().and_then(int)).is_some_and(|h| h > 1) {
        warnings.push("hermite smoothing is read as linear interpolation".into());
    }
    Ok((p, warnings))
}

/// World → light-local rotation of directions, for profile lookups: the inverse of the
/// linear part of `light_to_world` (identity if that is singular).
pub fn to_local(light_to_world: glam::DMat4) -> Mat3A {
    let m = Mat3A::from_mat4(light_to_world.as_mat4());
    let inv = m.inverse();
    if m.determinant().abs() > 1e-12 && inv.is_finite() {
        inv
    } else {
        Mat3A::IDENTITY
    }
}

/// A light's photometric distribution over directions (point lights).
#[derive(Clone, Debug, PartialEq)]
pub enum Distribution {
    /// cos^e of the angle from the light's local −Z (its photometric axis), nothing behind.
    Cosine(f32),
    /// A measured profile: its candela value (light-local direction) times `scale`.
    Profile {
        /// The profile.
        profile: Arc<Profile>,
        /// Multiplies the profile's candela: 1 for measured intensities, 1/peak for the
        /// normalised shape.
        scale: f32,
    },
}

impl Distribution {
    /// The factor towards `local`, a direction from the light in its local frame.
    pub fn factor(&self, local: Vec3A) -> f32 {
        match self {
            Distribution::Cosine(e) => {
                let c = -local.normalize_or_zero().z;
                if c <= 0.0 {
                    0.0
                } else {
                    c.powf(e.max(0.0))
                }
            }
            Distribution::Profile { profile, scale } => profile.candela(local) * scale,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distributions_follow_the_local_minus_z_axis() {
        let c = Distribution::Cosine(2.0);
        assert!((c.factor(Vec3A::NEG_Z) - 1.0).abs() < 1e-6);
        assert!((c.factor(Vec3A::new(1.0, 0.0, -1.0)) - 0.5).abs() < 1e-6);
        assert_eq!(c.factor(Vec3A::Z), 0.0);
        // A light turned by 90° about X: its local −Z is world +Y.
        let m = glam::DMat4::from_rotation_x(std::f64::consts::FRAC_PI_2);
        let local = to_local(m) * Vec3A::Y;
        assert!((local - Vec3A::NEG_Z).length() < 1e-6, "{local}");
        assert_eq!(to_local(glam::DMat4::ZERO), Mat3A::IDENTITY);
    }
}
