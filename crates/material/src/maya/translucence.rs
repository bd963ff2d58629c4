//! The lambert family's translucence in the path engine: `translucence` t, its focus and
//! its depth (rampShader's too: `translate_ramp`; a layeredShader's layers':
//! `super::layered_shader`).
//!
//! - `translucence` t: a transmission lobe of albedo c · t ⊙ the diffuse part's fade,
//!   concentrated by `translucenceFocus` ([`bsdf::maya_highlight::translucence`], the
//!   classic shader's lobe). A connected `color` c makes it follow each hit's diffuse
//!   colour c·d as t/d of it, or with `diffuse` d = 0 each hit's c itself (a
//!   [`Target::TranslucenceColor`] binding); a connected t is read at each hit (a
//!   [`Target::Translucence`] binding: the lobe is built with t = [`CONNECTED_STAND_IN`]
//!   and scaled per hit by t / that). The classic engine reads a colour-valued connection
//!   by its red, as this binding does.
//! - `translucenceDepth` D (world units): the classic engine's reading (`maya::material`)
//!   — a shadow ray from a point of the object that leaves the object's own geometry from
//!   inside after a stretch s passes T + (1 − T)·max(1 − s/D, 0), T the transparency,
//!   where the surface it leaves through is translucent — is
//!   [`SurfaceMaterial::translucence_depth`], which the path engine's shadow rays read
//!   through [`translucent_passage`].

use super::{connection, Reader};
use crate::{Binding, HitMaterial, SurfaceMaterial, SurfaceModel, Target};
use bsdf::maya_highlight::{table_at, VIEW_RAMP_STEPS};
use bsdf::Rgb;

/// The translucence a connected `translucence` stands in with in the material's constant
/// model (what the lobe is built with; each hit scales it by its own t over this).
pub const CONNECTED_STAND_IN: f32 = 0.5;

/// Gives `surface` the lambert family's translucence (see the module doc), `fade` the
/// diffuse part's fade per channel.
pub(super) fn translate(r: &mut Reader, surface: &mut SurfaceMaterial, fade: Rgb) {
    let connected = connection(r.graph, r.node, "translucence");
    let t = if connected.is_some() { CONNECTED_STAND_IN } else { r.scalar("translucence", 0.0) };
    if t <= 0.0 {
        return;
    }
    let d = r.scalar("diffuse", 0.8);
    let albedo = r.color("color", Rgb::splat(0.5)) * t * fade;
    let focus = bsdf::maya_highlight::translucence::focus_exponent(r.scalar("translucenceFocus", 0.5));
    let mut glossy = with_lobe(surface, albedo, focus);
    match connection(r.graph, r.node, "color") {
        // Each hit's diffuse colour is c·d (times the fade's mean): the translucence c·t
        // follows it as t/d of it.
        Some(_) if d > 0.0 => glossy = glossy.with_translucence_per_diffuse(t / d),
        // No diffuse colour to follow: the connected colour itself, c·t ⊙ the fade's mean.
        Some((node, member)) => {
            let mean = (fade.x + fade.y + fade.z) / 3.0;
            r.bindings.push(Binding { node, member, target: Target::TranslucenceColor, scale: t * mean });
        }
        None => {}
    }
    if let Some((node, member)) = connected {
        // After the colour's binding: it scales what that one sets.
        r.bindings.push(Binding { node, member, target: Target::Translucence, scale: 1.0 / CONNECTED_STAND_IN });
    }
    surface.translucence_depth = r.scalar("translucenceDepth", 0.0).max(0.0);
    surface.model = SurfaceModel::Maya(Box::new(glossy));
}

/// The material's Maya model (a highlight-less one when it has none) with a translucence
/// of albedo `albedo` and forward-lobe exponent `focus` ([`bsdf::MayaGlossy::translucence`]).
fn with_lobe(surface: &SurfaceMaterial, albedo: Rgb, focus: f32) -> bsdf::MayaGlossy {
    let glossy = match &surface.model {
        SurfaceModel::Maya(g) => **g,
        _ => bsdf::MayaGlossy::new(bsdf::maya_highlight::Shape::Phong { power: 1.0 }, Rgb::ZERO),
    };
    glossy.with_translucence(albedo, focus)
}

/// Gives the rampShader `surface` its translucence: a transmission lobe (focus 0: the
/// classic rampShader reads no `translucenceFocus`) of albedo `albedo` (see
/// `super::ramp_shader`: ⊙ the fade) shaped over the light's angle by `light_angle`
/// ([`bsdf::MayaGlossy::light_angle`]; `None`: diffuse), and the reader's
/// `translucenceDepth` for shadow rays, as the lambert family's (see the module doc).
pub(super) fn translate_ramp(
    r: &mut Reader,
    surface: &mut SurfaceMaterial,
    albedo: Rgb,
    light_angle: Option<bsdf::maya_highlight::translucence::LightAngle>,
) {
    if albedo == Rgb::ZERO {
        return;
    }
    let mut lobe = with_lobe(surface, albedo, 0.0);
    lobe.light_angle = light_angle;
    surface.model = SurfaceModel::Maya(Box::new(lobe));
    surface.translucence_depth = r.scalar("translucenceDepth", 0.5).max(0.0);
}

/// One layer of a layeredShader stack as its shadow rays pass it
/// ([`SurfaceMaterial::translucence_layers`]): its transparency and its translucence depth.
#[derive(Clone, Debug, PartialEq)]
pub struct TranslucentLayer {
    /// The layer's transparency T_i per channel, clamped to [0, 1] (a rampShader's ramp at
    /// facing ratio 1 when it does not follow the view).
    pub transparency: Rgb,
    /// A rampShader layer whose transparency ramp follows the view: T_i at the facing ratios
    /// k/32 (clamped to [0, 1]), read at the shadow ray's facing ratio as the classic
    /// rampShader reads its ramp in shadow rays; `None`: `transparency` everywhere.
    pub by_view: Option<Box<[Rgb; VIEW_RAMP_STEPS]>>,
    /// The layer's `translucenceDepth` D_i (world units; 0: none or not translucent).
    pub depth: f32,
}

impl TranslucentLayer {
    /// The layer's transparency T_i at facing ratio `facing` (|N·D| of the shadow ray).
    pub fn transparency_at(&self, facing: f32) -> Rgb {
        self.by_view.as_deref().map_or(self.transparency, |t| table_at(t, facing))
    }
}

/// What a shadow ray passes, per channel, where it leaves the receiving point's own
/// object through a surface of `material` (`hit`: that material at the point, met at
/// facing ratio `facing` = |N·D| of the ray) after going `inside` world units through it:
/// T + (1 − T)·max(1 − inside/D, 0), T the
/// transparency the surface lets shadow rays through by (its cut-out's, (1 − coverage) ·
/// tint) and D its [`SurfaceMaterial::translucence_depth`], where D > 0 and the surface is
/// translucent there; `None` otherwise (the surface filters the ray as any other). For a
/// layeredShader stack ([`SurfaceMaterial::translucence_layers`] not empty) it is
/// T + Π_i (T_i + (1 − T_i)·max(1 − inside/D_i, 0)) − Π_i T_i over its layers'
/// transparencies T_i at `facing` ([`TranslucentLayer::transparency_at`]: a rampShader
/// layer's ramp where it follows the view, as the classic rampShader reads it at the
/// shadow ray's facing ratio) and depths D_i (a layer without a depth: T_i) — the classic
/// stack's product of its layers' passages where T is their product.
pub fn translucent_passage(material: &SurfaceMaterial, hit: &HitMaterial, inside: f32, facing: f32) -> Option<Rgb> {
    let depth = material.translucence_depth;
    if depth <= 0.0 {
        return None;
    }
    let translucent = match &*hit.model {
        SurfaceModel::Maya(g) => {
            g.translucence_stack.is_some()
                || g.translucence_per_diffuse.map_or(g.translucence != Rgb::ZERO, |k| k > 0.0)
        }
        _ => false,
    };
    // (A stack's layers say themselves which are translucent: a layer that does not show
    // still passes shadow rays by its depth.)
    if !translucent && material.translucence_layers.is_empty() {
        return None;
    }
    let t =
        if hit.opacity < 1.0 { (hit.cutout_tint * (1.0 - hit.opacity)).clamp(Rgb::ZERO, Rgb::ONE) } else { Rgb::ZERO };
    let kept = |depth: f32| if depth > 0.0 { (1.0 - inside / depth).max(0.0) } else { 0.0 };
    if material.translucence_layers.is_empty() {
        return Some(t + (Rgb::ONE - t) * kept(depth));
    }
    let (passed, filtered) = material.translucence_layers.iter().fold((Rgb::ONE, Rgb::ONE), |(p, f), layer| {
        let t = layer.transparency_at(facing);
        (p * (t + (Rgb::ONE - t) * kept(layer.depth)), f * t)
    });
    Some((t + passed - filtered).clamp(Rgb::ZERO, Rgb::ONE))
}
