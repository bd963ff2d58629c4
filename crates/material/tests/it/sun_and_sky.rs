//! Iray's `base::sun_and_sky` through the shader graph: its declaration (with and without
//! the MDL signature), its defaults, and its agreement with `mia_physicalsky`.

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
