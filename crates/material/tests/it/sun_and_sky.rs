//! Iray's `base::sun_and_sky` through the shader graph: its declaration (with and without
//! the MDL signature), its defaults, and its agreement with `mia_physicalsky`; called
//! inside a module (and through a `.mi` connection) it is the same sky. `math::blackbody`
//! of a temperature that varies over the surface (the sky's module, tests/mdl/sky_heat.mdl).

use crate::support;

use glam::Vec3A;
use mdl::sky::SunAndSky;
use shader::{Color, Ctx, RayType, State, Value};
use support::{compile_with, Compiled, Empty};

/// The signature Iray gives the function's database name.
const SIGNATURE: &str = "mdl::base::sun_and_sky(bool,float,color,float,float,float,float,float,color,color,float3,float,float,float,bool,int,bool)";

/// Compiles a scene whose camera environment is `shader`.
fn environment(shader: &str) -> Compiled {
    let c = compile_with("", &format!("environment {shader}"), "", &[]);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    c
}

/// The camera environment's colour in world direction `dir`.
fn look(c: &Compiled, dir: Vec3A) -> Color {
    let env = c.shading.environment.expect("an environment");
    let state = State { ray_type: RayType::Environment, dir: dir.normalize(), ..State::default() };
    let tracer = Empty::default();
    let mut ctx = Ctx::new(&c.shading, &tracer, state);
    let mut out = Value::Color(Color::ZERO);
    ctx.run_list(env, &mut out);
    out.color()
}

/// The parameters both shaders share, in `.mi` syntax (Y up, the sun 35° up).
const PARAMS: &str = r#""multiplier" 0.5, "rgb_unit_conversion" 0.0002 0.0002 0.0002, "haze" 1.5,
    "redblueshift" 0.1, "saturation" 0.8, "horizon_height" 0.0, "horizon_blur" 0.2,
    "ground_color" 0.3 0.25 0.2, "night_color" 0 0 0, "sun_direction" 0.5 0.5735764 0.6,
    "sun_disk_intensity" 1, "sun_disk_scale" 2, "sun_glow_intensity" 1, "y_is_up" on,
    "physically_scaled_sun" on"#;

#[test]
fn zenith_and_horizon_are_pi_times_mia_physicalsky() {
    let mdl = environment(&format!("\"{SIGNATURE}\" ({PARAMS})"));
    let mia = environment(&format!("\"mia_physicalsky\" ({PARAMS})"));
    // The zenith, the horizon (in four azimuths and just above and below), the sun.
    let sun = Vec3A::new(0.5, 0.5735764, 0.6).normalize();
    let mut dirs = vec![Vec3A::Y, sun];
    for az in [0.0f32, 90.0, 180.0, 270.0] {
        let a = az.to_radians();
        for el in [0.0f32, 0.2, -0.2] {
            let e = el.to_radians();
            dirs.push(Vec3A::new(e.cos() * a.cos(), e.sin(), e.cos() * a.sin()));
        }
    }
    for d in dirs {
        let (a, b) = (look(&mdl, d), look(&mia, d) * std::f32::consts::PI);
        for k in 0..3 {
            // Within 1e-4 relative (float rounding of the same formulas).
            assert!((a[k] - b[k]).abs() <= 1e-4 * b[k].abs().max(1e-6), "{d}: {a} vs {b}");
        }
        assert_eq!(a.w, 1.0);
        assert!(a.x > 0.0 && a.z > 0.0, "{d}: {a}");
    }
}

#[test]
fn unset_parameters_take_the_mdl_defaults() {
    let c = environment("\"mdl::base::sun_and_sky\" ()");
    let want = SunAndSky::default();
    for d in [Vec3A::Y, Vec3A::new(1.0, 0.01, 0.0), Vec3A::new(0.0, 0.229271, 0.418882), Vec3A::NEG_Y] {
        let got = look(&c, d);
        let w = want.radiance(d.normalize());
        assert!((got.truncate() - glam::Vec3::from(w)).abs().max_element() <= 1e-6 * w.max_element(), "{d}: {got} {w}");
    }
    // The defaults' sky is Iray's dim default: the zenith about 1e-1 … 1 (2 000 … 10 000
    // cd/m² × π² × 0.025 / 1500), and the sun direction 28.7° up behind +Z gives a blue sky.
    let z = look(&c, Vec3A::Y);
    assert!(z.z > z.x && (0.02..2.0).contains(&z.y), "{z}");
    // Off: black.
    let off = environment("\"mdl::base::sun_and_sky\" (\"on\" false)");
    assert_eq!(look(&off, Vec3A::Y).truncate(), glam::Vec3::ZERO);
}

/// The emission of a module material at a shading point seen along `dir` (facing it):
/// radiance, output units.
fn module_emission(m: &material::SurfaceMaterial, dir: Vec3A, u: f32) -> glam::Vec3 {
    let material::Varying::Evaluated(hit) = &m.varying else { panic!("{} is not evaluated per hit", m.name) };
    let mut s = State { tex_count: 1, normal: -dir, normal_geom: -dir, dir, ..State::default() };
    s.tex_list[0] = Vec3A::new(u, 0.5, 0.0);
    let mut h = m.constant();
    hit.0.apply(&s, &mut h);
    glam::Vec3::from(h.emission)
}

/// `base::sun_and_sky` called inside a module (a function of tests/mdl/sky_heat.mdl that an
/// emitter's intensity calls) is the `.mi` shader's sky: a Lambertian emitter of that
/// exitance shows radiance exitance/π, so π × its radiance seen along a direction is the
/// environment's value looking along it, within 1e-5 relative, for the zenith, the sun, the
/// horizon and below it; the defaults match `SunAndSky::default()`.
#[test]
fn sun_and_sky_in_a_module_is_the_mi_shaders_sky() {
    use crate::mdl_support::{compile_text, get};
    let mi = environment(&format!("\"{SIGNATURE}\" ({PARAMS})"));
    let (mdl, lib, diags) = compile_text(
        r#"shader "glow" "mdl::sky_heat::sky_glow" ()
shader "plain" "mdl::sky_heat::default_sky" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let glow = get(&mdl, &lib, "glow");
    let sun = Vec3A::new(0.5, 0.5735764, 0.6).normalize();
    let dirs = [Vec3A::Y, sun, Vec3A::new(1.0, 0.05, 0.3), Vec3A::new(-0.3, 0.4, -1.0), Vec3A::new(0.2, -0.5, 1.0)];
    for d in dirs.map(Vec3A::normalize) {
        let want = look(&mi, d).truncate();
        let got = module_emission(glow, d, 0.0) * std::f32::consts::PI;
        assert!(want.max_element() > 0.0, "{d}: {want}");
        assert!((got - want).abs().max_element() <= 1e-5 * want.max_element(), "{d}: {got} vs {want}");
    }
    // A material parameter connected to the `.mi` function shader, as Iray exporters write
    // it, is the same sky.
    let (mdl2, lib2, diags) = compile_text(&format!(
        "shader \"sky\" \"mdl::base::sun_and_sky\" ({PARAMS})\nshader \"lit\" \"mdl::sky_heat::glow_of\" (\"c\" = \"sky\")"
    ));
    assert!(diags.is_empty(), "{diags:#?}");
    let lit = get(&mdl2, &lib2, "lit");
    for d in dirs.map(Vec3A::normalize) {
        let want = look(&mi, d).truncate();
        let got = module_emission(lit, d, 0.0) * std::f32::consts::PI;
        assert!((got - want).abs().max_element() <= 1e-5 * want.max_element(), "connected {d}: {got} vs {want}");
    }
    let plain = get(&mdl, &lib, "plain");
    for d in [Vec3A::Y, Vec3A::new(0.0, 0.229271, 0.418882).normalize(), Vec3A::new(1.0, 0.2, 0.0).normalize()] {
        let want = glam::Vec3::from(SunAndSky::default().radiance(d));
        let got = module_emission(plain, d, 0.0) * std::f32::consts::PI;
        assert!((got - want).abs().max_element() <= 1e-5 * want.max_element(), "{d}: {got} vs {want}");
    }
}

/// A parameter MDL declares varying (`haze`) that depends on the hit is evaluated at each
/// lookup: an emitter whose haze is its texture coordinate u shows, at u = 0, 0.7 and 2.5
/// and along three directions, the sky of that constant haze within 1e-5 relative (and the
/// three hazes differ). (A `uniform` parameter given a varying value is a type error of the
/// module, found when it is loaded.)
#[test]
fn a_varying_haze_is_evaluated_per_lookup() {
    use crate::mdl_support::{compile_text, get};
    let (mdl, lib, diags) = compile_text(r#"shader "h" "mdl::sky_heat::hazy" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let hazy = get(&mdl, &lib, "h");
    for d in [Vec3A::Y, Vec3A::new(1.0, 0.05, 0.3).normalize(), Vec3A::new(-0.3, 0.4, -1.0).normalize()] {
        let mut seen = Vec::new();
        for haze in [0.0f32, 0.7, 2.5] {
            let mut sky = SunAndSky::default();
            sky.sky.haze = haze;
            let want = glam::Vec3::from(sky.radiance(d));
            let got = module_emission(hazy, d, haze) * std::f32::consts::PI;
            assert!((got - want).abs().max_element() <= 1e-5 * want.max_element(), "haze {haze}, {d}: {got} vs {want}");
            seen.push(got);
        }
        assert!(seen[0] != seen[1] && seen[1] != seen[2], "the haze changes the sky: {seen:?}");
    }
}

/// `base::perez_sun_and_sky` in a module (its ground colour the texture coordinate u) and as
/// the `.mi` environment shader `mdl::base::perez_sun_and_sky` are the sky model's
/// radiance (`sky::perez::PerezSky`), within 1e-5 relative, above and below the horizon.
#[test]
fn perez_sun_and_sky_in_a_module_and_as_a_shader_is_the_models_sky() {
    use crate::mdl_support::{compile_text, get};
    use sky::perez::{PerezSky, PerezSunAndSky};
    let (mdl, lib, diags) = compile_text(r#"shader "p" "mdl::sky_heat::perez_glow" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let glow = get(&mdl, &lib, "p");
    let params = PerezSunAndSky {
        direct_normal_irradiance: 600.0,
        diffuse_horizontal_irradiance: 120.0,
        ..PerezSunAndSky::default()
    };
    let mi = environment(
        r#""mdl::base::perez_sun_and_sky" ("direct_normal_irradiance" 600, "diffuse_horizontal_irradiance" 120, "ground_color" 0.3 0.3 0.3)"#,
    );
    let dirs = [Vec3A::Y, Vec3A::new(1.0, 0.05, 0.3), Vec3A::new(-0.3, 0.4, -1.0), Vec3A::new(0.2, -0.5, 1.0)];
    for d in dirs.map(Vec3A::normalize) {
        for u in [0.1f32, 0.3, 0.8] {
            let sky = PerezSky::new(PerezSunAndSky { ground_color: Vec3A::splat(u), ..params });
            let want = glam::Vec3::from(sky.radiance(d));
            let got = module_emission(glow, d, u) * std::f32::consts::PI;
            assert!((got - want).abs().max_element() <= 1e-5 * want.max_element(), "u {u}, {d}: {got} vs {want}");
        }
        let sky = PerezSky::new(PerezSunAndSky { ground_color: Vec3A::splat(0.3), ..params });
        let want = sky.radiance(d);
        let got = look(&mi, d).truncate();
        assert!(
            (Vec3A::from(got) - want).abs().max_element() <= 1e-5 * want.max_element(),
            "shader {d}: {got} vs {want}"
        );
    }
}

/// `math::blackbody` of a temperature that varies over the surface (lerp of 1000 K to
/// 10 000 K by u) gives, at three points, the colour the constant form gives for that
/// temperature (the temperatures exact in f32), within 1e-6.
#[test]
fn blackbody_of_a_varying_temperature_is_the_constant_forms_colour() {
    use crate::mdl_support::{compile_text, get};
    let points = [(0.0f32, 1000.0f32), (0.25, 3250.0), (0.5, 5500.0), (1.0, 10000.0)];
    let mut text = String::from("shader \"heat\" \"mdl::sky_heat::heat\" ()\n");
    for (i, (_, t)) in points.iter().enumerate() {
        text += &format!("shader \"at{i}\" \"mdl::sky_heat::heat_at\" (\"t\" {t})\n");
    }
    let (mdl, lib, diags) = compile_text(&text);
    assert!(diags.is_empty(), "{diags:#?}");
    let heat = get(&mdl, &lib, "heat");
    let mut seen = Vec::new();
    for (i, (u, _)) in points.iter().enumerate() {
        let got = module_emission(heat, -Vec3A::Z, *u);
        let constant = get(&mdl, &lib, &format!("at{i}"));
        assert!(matches!(constant.varying, material::Varying::Constant), "a constant temperature is one colour");
        let want = glam::Vec3::from(constant.emission);
        assert!((got - want).abs().max_element() <= 1e-6 * want.max_element(), "u {u}: {got} vs {want}");
        seen.push(got);
    }
    // Cooler is redder: the red/blue ratio falls as the temperature rises.
    assert!(seen.windows(2).all(|w| w[0].x / w[0].z.max(1e-9) > w[1].x / w[1].z.max(1e-9)), "{seen:?}");
}

/// A haze that varies per lookup, over many lookups as a render makes them (hazes 0 to 1
/// as a texture coordinate gives them, 4000 lookups: a tenth within the sun's disk and
/// glow, half below the horizon, the rest in the sky): the sky of that haze, within 1e-5
/// relative in the sky and 1e-4 where the sun's and the ground's illuminance enter (the
/// disk and glow, the ground: there mira interpolates those two terms between hazes
/// 1/64 apart, see `sky::light_table`). Its cost, measured with
/// `valgrind --tool=callgrind target/debug/deps/it-… sun_and_sky::varying_haze_lookups
/// --exact --test-threads 1`, is in the commit that made it fast.
#[test]
fn varying_haze_lookups_match_the_exact_sky() {
    use crate::mdl_support::{compile_text, get};
    let (mdl, lib, diags) = compile_text(r#"shader "h" "mdl::sky_heat::hazy" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let hazy = get(&mdl, &lib, "h");
    let sun = SunAndSky::default().sun().expect("a sun");
    let frame = bsdf::Frame::from_normal(sun.direction);
    let mut worst = [0.0f32; 3];
    // Directions outer, hazes inner: a render's neighbouring lookups seldom share a haze.
    for j in 0..100 {
        for i in 0..40 {
            let haze = (i as f32 + 0.37) / 40.0;
            let mut sky = SunAndSky::default();
            sky.sky.haze = haze;
            let (a, b) = ((j as f32 * 0.618_034).fract(), (j as f32 * 0.414_214 + 0.1).fract());
            let phi = 2.0 * std::f32::consts::PI * a;
            let (kind, d) = if j % 10 == 0 {
                // Within the disk and glow's cone.
                let r = sun.cone_radius * b;
                (0, frame.to_world(Vec3A::new(r.sin() * phi.cos(), r.sin() * phi.sin(), r.cos())))
            } else if j % 2 == 0 {
                (1, Vec3A::new(phi.cos(), -b, phi.sin()).normalize())
            } else {
                (2, Vec3A::new(phi.cos(), b + 0.01, phi.sin()).normalize())
            };
            // The module's lookup first (the exact sky's costly terms are remembered for the
            // last few skies: the lookup should not find them there).
            let got = module_emission(hazy, d, haze) * std::f32::consts::PI;
            let want = glam::Vec3::from(sky.radiance(d));
            let error = (got - want).abs().max_element() / want.max_element().max(1e-12);
            worst[kind] = worst[kind].max(error);
        }
    }
    eprintln!("varying haze: worst relative error {worst:?} (sun cone, ground, sky)");
    assert!(worst[0] <= 1e-4 && worst[1] <= 1e-4 && worst[2] <= 1e-5, "{worst:?}");
}
