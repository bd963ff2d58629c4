//! The classic engine's pre-passes see moving things at shutter times of their own: each
//! photon leaves its light at a time drawn from the shutter's shape, and each final gather
//! point is found at a time of its own, so indirect light blurs like the image.

use std::sync::atomic::AtomicBool;

use crate::support;

use support::build_clean as build;

/// A point light of energy 100 at height 1 over a 10 × 10 floor (reflectance 0.5) under a
/// dark ceiling at height 2, placed by `placement`; `options` in the options block.
fn photon_scene(options: &str, placement: &str) -> String {
    format!(
        r#"
options "opt" filter box 1 1 globillum on globillum accuracy 100 1 {options} end options
camera "cam" focal 1 aperture 1 aspect 1 resolution 8 8 end camera
instance "cam_inst" "cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -8 1 end instance
material "white" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1) end material
material "dark" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.001 0.001 0.001 1) end material
object "floor" group
    -5 -5 0  5 -5 0  5 5 0  -5 5 0
    v 0 v 1 v 2 v 3
    c "white" 0 1 2 3
end group end object
object "ceiling" group
    -5 -5 2  5 -5 2  5 5 2  -5 5 2
    v 0 v 1 v 2 v 3
    c "dark" 0 3 2 1
end group end object
instance "floor_inst" "floor" end instance
instance "ceiling_inst" "ceiling" end instance
light "pt" "mib_light_point" ("color" 1 1 1) origin 0 0 1 energy 100 100 100 exponent 2
    globillum photons 20000 end light
instance "pt_inst" "pt" {placement} end instance
instgroup "root" "cam_inst" "floor_inst" "ceiling_inst" "pt_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The global photon map's photons (positions) of `text`.
fn global_photons(text: &str) -> Vec<glam::Vec3A> {
    let (scene, shading) = build(text);
    let world = render::World::from_scene(&scene);
    let accel = render::accel::build(&world, render::Backend::default_available());
    render::photons::build(&world, accel.as_ref(), &shading, &AtomicBool::new(false)).expect("photons");
    let maps = shading.photons.get().expect("maps");
    maps.global.as_ref().expect("a global map").0.photons().iter().map(|p| p.position).collect()
}

/// The light slides from x = −1 to x = 1 while the shutter is open: the global photons
/// (stored on the ceiling after a floor bounce, symmetric about the light's x) average
/// x ≈ 0 over the shutter, |mean x| < 0.05; where the light stands at x = −1 (what the
/// pre-pass saw before: the light at the shutter's opening) they average x < −0.5. A still
/// scene's photons are the same bit for bit with and without `motion on`.
#[test]
fn photons_leave_the_light_where_it_is_at_their_time() {
    let mean_x = |p: &[glam::Vec3A]| p.iter().map(|p| f64::from(p.x)).sum::<f64>() / p.len() as f64;
    let sliding = "transform 1 0 0 0  0 1 0 0  0 0 1 0  1 0 0 1  motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0 0 1";
    let moving = global_photons(&photon_scene("motion on shutter 0 1", sliding));
    let at_start = global_photons(&photon_scene("", "transform 1 0 0 0  0 1 0 0  0 0 1 0  1 0 0 1"));
    let (m, s) = (mean_x(&moving), mean_x(&at_start));
    eprintln!("global photons: sliding light mean x {m:.4} ({} photons), light at x = -1: {s:.4}", moving.len());
    assert!(moving.len() > 1000 && at_start.len() > 1000);
    assert!(m.abs() < 0.05, "{m}");
    assert!(s < -0.5, "{s}");
    let still = global_photons(&photon_scene("", ""));
    let still_motion_on = global_photons(&photon_scene("motion on shutter 0 1", ""));
    assert_eq!(still, still_motion_on);
}

/// An orthographic view down onto a floor at z = −5 and a black card at z = −4 over
/// x ∈ [−10, 0] that moves +2 in x while the shutter is open (`card` placement).
fn fg_scene(options: &str, card: &str) -> String {
    format!(
        r#"
options "opt" filter box 1 1 finalgather on finalgather accuracy 16 0.2 0.05 {options} end options
camera "cam" focal infinity aperture 8 aspect 1 resolution 32 32
    environment "mib_color_mix" ("num" 0, "color_base" 1 1 1 1)
end camera
instance "cam_inst" "cam" end instance
material "floor_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 1 1 1 1) end material
material "black" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0 0 0 1) end material
object "floor" group
    -20 -20 -5  20 -20 -5  20 20 -5  -20 20 -5
    v 0 v 1 v 2 v 3
    c "floor_mtl" 0 1 2 3
end group end object
object "card" group
    -10 -20 -4  0 -20 -4  0 20 -4  -10 20 -4
    v 0 v 1 v 2 v 3
    c "black" 0 1 2 3
end group end object
instance "floor_inst" "floor" end instance
instance "card_inst" "card" {card} end instance
instgroup "root" "cam_inst" "floor_inst" "card_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Final gather points on the card lie where the card is at each point's own time: with
/// the card moving +2 over the shutter they reach past x = 1 (at most x = 2), where the
/// card at the shutter's opening (what the pre-pass saw before) ends at x = 0.
#[test]
fn final_gather_points_are_found_at_times_of_their_own() {
    let card_points_max_x = |text: &str| {
        let (scene, shading) = build(text);
        let world = render::World::from_scene(&scene);
        let accel = render::accel::build(&world, render::Backend::default_available());
        let pre = render::fgcache::prepass(&world, accel.as_ref(), &shading, &AtomicBool::new(false)).expect("points");
        let on_card: Vec<f32> =
            pre.cache.points().iter().filter(|p| (p.position.z + 4.0).abs() < 1e-3).map(|p| p.position.x).collect();
        eprintln!("{} points on the card", on_card.len());
        assert!(on_card.len() > 10, "{} points on the card", on_card.len());
        on_card.iter().copied().fold(f32::NEG_INFINITY, f32::max)
    };
    let moving =
        card_points_max_x(&fg_scene("motion on shutter 0 1", "motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -2 0 0 1"));
    let still = card_points_max_x(&fg_scene("", ""));
    eprintln!("final gather points on the card reach x = {moving} (moving), {still} (still)");
    assert!(moving > 1.0 && moving <= 2.0 + 1e-3, "{moving}");
    assert!(still <= 1e-3, "{still}");
}
