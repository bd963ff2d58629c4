//! Maya's useBackground as the path engine renders it: a shadow-catching matte.
//!
//! A path that reaches the matte (any ray but a shadow ray) sees the background — the
//! environment along the ray, what would show there without the matte — darkened by
//! `shadowMask` × the share of the lights' direct light that occluders block at the
//! point (each light in front of the point weighted by N·L, as the classic shader
//! `maya::matte` weighs them; Maya's `shadowColor` has no effect there), and a mirror of
//! weight `reflectivity` × `specularColor` while the path has made fewer than
//! `reflectionLimit` mirror reflections. The matte casts no shadow: its material is
//! fully transparent to shadow rays (coverage 0). `render`'s integrator shades it.

use bsdf::Rgb;

/// A useBackground material's parameters as the path engine reads them (see the module
/// doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MayaMatte {
    /// `shadowMask`, clamped to [0, 1]: the share of a fully blocked point's background
    /// taken away (and its alpha).
    pub shadow_mask: f32,
    /// `reflectivity` × `specularColor`: the mirror reflection's weight (linear RGB).
    pub mirror: Rgb,
    /// `reflectionLimit`: the matte reflects on paths of fewer mirror reflections.
    pub reflection_limit: u32,
}
