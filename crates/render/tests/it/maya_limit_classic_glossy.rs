//! Maya's `reflectionLimit` and `refractionLimit` in the classic engine count the rays of
//! mental ray's glossy base shaders (`mib_glossy_reflection`, `mib_glossy_refraction`) as
//! they count mirror and refraction rays: those shaders cast their rays as reflection
//! (refraction) rays, which raise the state's reflection (refraction) level that the Maya
//! materials compare with their limits. (The path engine's count of
//! `mib_glossy_reflection` samples is tested in `mib_glossy_path`; its count of
//! `mib_glossy_refraction`'s transmissions here, with the classic engine's, and in
//! `mib_glossy_refraction_path`.)

use crate::support;
use crate::support::maya_view::pixels_warned;

use glam::Vec3A;
use render::EngineKind;

/// The image's side in pixels.
const SIDE: usize = 8;

/// A `mib_glossy_reflection` ground (base: a constant e, `reflection_color` 1, no
/// environment, weights 1, 16 samples spread by `spread` radians) under a Maya mirror
/// ceiling (phongE without a highlight, reflectivity r, incandescence e,
/// `reflectionLimit` `limit`) at y = 5, the camera between them looking down.
fn two_reflectors(limit: u32, spread: f32, e: f32, r: f32) -> String {
    let ground = format!(
        r#"shader "glow" "mib_color_mix" ("num" 0, "color_base" {e} {e} {e} 1)
material "g" opaque "mib_glossy_reflection" ("base_material" "glow", "reflection_color" 1 1 1,
    "environment_color" 0 0 0, "reflection_base_weight" 1, "reflection_edge_weight" 1,
    "samples" 16, "u_spread" {spread}, "v_spread" {spread}) end material"#
    );
    support::maya_view::under_a_mirror(SIDE, "trace depth 8 8 16", &ground, "g", 500, limit, e, r)
}

/// Two facing reflectors: the `mib_glossy_reflection` ground G (base e, reflection
/// colour 1) and the Maya mirror ceiling C (reflectivity r = 0.5, incandescence
/// e = 0.25, `reflectionLimit` L). At reflection level k the ground shows
/// G(k) = e + C(k + 1) and the ceiling C(k) = e + r·G(k + 1) while k < L, else e. The
/// glossy rays are reflection rays, so the camera's ground (level 0) sees the ceiling at
/// level 1: 2e for L = 0 and 1, then 2e·(1 + r) for L = 2 (the ceiling at level 3 no
/// longer reflects) and 2e·(1 + r + r²) for L = 4. The ceiling is uniform, so the glossy
/// spread (0 and 0.1 rad) does not change the value: every pixel within 1e-4. Were the
/// glossy rays not counted, the ceiling would sit at level 0 and reflect already for
/// L = 1.
#[test]
fn reflection_limit_counts_mib_glossy_reflection_rays_in_the_classic_engine() {
    let (r, e) = (0.5f32, 0.25f32);
    for spread in [0.0f32, 0.1] {
        for limit in [0u32, 1, 2, 4] {
            // G(0) = 2e·(1 + r + … + r^⌊L/2⌋).
            let want = 2.0 * e * (0..=limit / 2).map(|k| r.powi(k as i32)).sum::<f32>();
            let text = two_reflectors(limit, spread, e, r);
            for (i, p) in pixels_warned(&text, EngineKind::Classic, 1, "the path").iter().enumerate() {
                assert!(
                    (*p - Vec3A::splat(want)).abs().max_element() < 1e-4,
                    "spread {spread}, L = {limit}, pixel {i}: {p} vs {want}"
                );
            }
        }
    }
}

/// Maya's `refractionLimit` counts the rays of `mib_glossy_refraction` (index 1, sharp:
/// the straight ray it casts is a transparency ray of mental ray's refraction level;
/// `refraction_color` 1, weights 1, no top material) as it counts a transparent
/// lambert's: the same top plane over the refracting lambert over the strips as
/// `maya_refraction_path::the_refraction_limit_counts_other_materials_transparency_rays…`.
/// With `refractionLimit` 0 and 1 the lower plane is reached at refraction level 1 and
/// passes the ray straight, with 2 it bends it: at every pixel within one strip by the
/// formula the classic engine gives T ⊙ that strip's colour within 1e-3 per channel, and
/// ≥ 15 % of those pixels tell limits 1 and 2 apart; the path engine (which passes the
/// ray straight at `ior` 1 and counts the pass as a refraction) the same, 1e-3 per channel.
#[test]
fn refraction_limit_counts_mib_glossy_refraction_rays_in_the_classic_engine() {
    crate::maya_refraction_path::refraction_limit_past_the_top(Some(
        r#"material "m" "mib_glossy_refraction" ("refraction_color" 1 1 1, "refraction_base_weight" 1,
    "refraction_edge_weight" 1, "ior" 1, "samples" 4) end material"#,
    ));
}
