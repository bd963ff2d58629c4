//! The classic engine's shadow rays where every surface stops light (no material has a
//! shadow shader): the any-hit query [`shader::Tracer::shadow_blocked`] answers what the
//! visit of the surfaces on the way ([`shader::Tracer::shadow_hits`]) would, and a render
//! through it is the same, bit for bit, as one through the visits.

use crate::support;

use glam::Vec3A;
use render::accel::{self, Backend};
use render::tracer::SceneTracer;
use render::{EngineKind, Settings};
use shader::{RayType, State, Tracer};

/// A 4×4 floor at z = −5 seen from above by an orthographic camera, lit by a 1×1
/// rectangle light (4×4 samples, hard shadows) at z = −3 over a 0.6×0.6 card at z = −4
/// whose shadow has a penumbra on the floor; `extra` adds statements (and its instance
/// "far_inst" to the scene, if it defines one).
fn scene(extra: &str) -> String {
    let instances = if extra.contains("far_inst") { " \"far_inst\"" } else { "" };
    format!(
        r#"
options "opt" filter box 1 1 samples 0 2 shadow on end options
camera "cam" focal infinity aperture 4 aspect 1 resolution 24 24 end camera
instance "cam_inst" "cam" end instance
light "L" "mib_light_point" ("color" 1 1 1, "shadow" on, "factor" 0)
    origin 0 0 -3 rectangle 1 0 0  0 1 0  4 4
end light
instance "L_inst" "L" end instance
material "floor_mtl" "mib_illum_lambert" ("ambient" 0 0 0 1, "diffuse" 0.5 0.5 0.5 1, "mode" 3) end material
{extra}
object "floor" group
    -2 -2 -5  2 -2 -5  2 2 -5  -2 2 -5
    -0.3 -0.3 -4  0.3 -0.3 -4  0.3 0.3 -4  -0.3 0.3 -4
    v 0 v 1 v 2 v 3 v 4 v 5 v 6 v 7
    c "floor_mtl" 0 1 2 3
    c "floor_mtl" 4 5 6 7
end group end object
instance "floor_inst" "floor" end instance
instgroup "root" "cam_inst" "L_inst" "floor_inst"{instances} end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// Shadow rays from a grid of floor points to a grid of points on the light: the any-hit
/// answer equals whether `shadow_hits` visits a surface, for every ray and each backend;
/// the card blocks some of them and not others.
#[test]
fn shadow_blocked_answers_what_shadow_hits_visits() {
    let support::Compiled { scene, .. } = support::compile(&scene(""));
    let world = render::World::from_scene(&scene);
    for backend in [Backend::Rust, Backend::Embree].into_iter().filter(|b| b.available()) {
        let accel = accel::build(&world, backend);
        let tracer = SceneTracer::new(&world, accel.as_ref());
        let (mut blocked, mut clear) = (0, 0);
        for i in 0..21 {
            for j in 0..21 {
                let p = Vec3A::new(-1.5 + 0.15 * i as f32, -1.5 + 0.15 * j as f32, -5.0 + 1e-3);
                for k in 0..9 {
                    let q = Vec3A::new(-0.4 + 0.1 * k as f32, 0.4 - 0.1 * k as f32, -3.0);
                    let dist = (q - p).length();
                    let dir = (q - p) / dist;
                    let ray = State { ray_type: RayType::Shadow, org: p, dir, ..State::default() };
                    let mut visited = false;
                    tracer.shadow_hits(&ray, dist, &mut |_| {
                        visited = true;
                        false
                    });
                    assert_eq!(tracer.shadow_blocked(p, dir, dist, 0.0), visited, "{backend:?}: {p} → {q}");
                    if visited {
                        blocked += 1;
                    } else {
                        clear += 1;
                    }
                }
            }
        }
        assert!(blocked > 100 && clear > 100, "{backend:?}: {blocked} blocked, {clear} clear");
    }
}

/// The same scene rendered through the any-hit query (no shadow shader anywhere) and
/// through the visits (a material with a shadow shader, on a triangle far outside the view
/// and every ray's way, turns the query off): the
/// pixels are bit-identical, and the floor shows a penumbra (values strictly between the
/// darkest and the brightest) so that partly blocked lights were compared too.
#[test]
fn renders_through_the_any_hit_query_equal_the_visits() {
    let far = r#"material "glass" "mib_illum_lambert" ("diffuse" 1 1 1 1)
    shadow "mib_shadow_transparency" ("color" 1 1 1 1, "transp" 0.5 0.5 0.5 0.5)
end material
object "far" group
    100 100 -5  101 100 -5  100 101 -5
    v 0 v 1 v 2
    c "glass" 0 1 2
end group end object
instance "far_inst" "far" end instance"#;
    let settings = Settings { engine: EngineKind::Classic, spp: Some(4), ..Settings::default() };
    let mut images = Vec::new();
    for (extra, shadow_shaders) in [("", false), (far, true)] {
        let support::Compiled { scene, shading, messages, .. } = support::compile(&scene(extra));
        assert_eq!(shading.has_shadow_shaders(), shadow_shaders, "{messages:?}");
        let world = render::World::from_scene(&scene);
        let (film, stats) = support::render_world(&world, &shading, &settings);
        assert!(stats.shadow_rays > 0);
        images.push(film.rgba());
    }
    let bits = |px: &[[f32; 4]]| px.iter().flat_map(|p| p.map(f32::to_bits)).collect::<Vec<_>>();
    assert_eq!(bits(&images[0]), bits(&images[1]));
    let red: Vec<f32> = images[0].iter().map(|p| p[0]).collect();
    let (lo, hi) = red.iter().fold((f32::MAX, f32::MIN), |(lo, hi), &r| (lo.min(r), hi.max(r)));
    let penumbra = red.iter().filter(|&&r| r > lo + 0.05 * (hi - lo) && r < hi - 0.05 * (hi - lo)).count();
    assert!(hi > 0.0 && penumbra >= 8, "lo {lo} hi {hi}: {penumbra} penumbra pixels");
}
