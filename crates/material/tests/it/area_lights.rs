//! User area lights (the light shader places each sample), `mia_portal_light` and
//! `mia_light_surface` at hand-made shading points.

use crate::support;

use glam::Vec3A;
use shader::{Color, Ctx, NodeId, RayType, ShaderImpl, Value};
use support::{compile, compile_with, point, run, Compiled, Empty};

/// A user light shader: sample i sits at (i − 1, 5, 0) with colour (1, i, 0); the fourth
/// call says there are no more.
static THREE_POINTS: ShaderImpl =
    ShaderImpl { name: "test_three_points", params: &[], run: three_points, ..ShaderImpl::PLAIN };

fn three_points(ctx: &mut Ctx, _n: NodeId, out: &mut Value) -> bool {
    let i = ctx.state.sample_index;
    if i >= 3 {
        return false;
    }
    let org = Vec3A::new(i as f32 - 1.0, 5.0, 0.0);
    let d = ctx.state.point - org;
    ctx.state.org = org;
    ctx.state.dist = d.length();
    ctx.state.dir = d / ctx.state.dist;
    *out = Value::Color(Color::new(1.0, i as f32, 0.0, 1.0));
    true
}

/// A user light shader that never stops (the loop's cap must).
static ENDLESS: ShaderImpl = ShaderImpl { name: "test_endless", params: &[], run: endless, ..ShaderImpl::PLAIN };

fn endless(ctx: &mut Ctx, _n: NodeId, out: &mut Value) -> bool {
    ctx.state.org = Vec3A::new(0.0, 2.0, 0.0);
    *out = Value::Color(Color::ONE);
    true
}

/// The user light "u" (4 × 2 samples) with its shader replaced by `imp`, and its index.
fn user_light(imp: &'static ShaderImpl) -> (Compiled, u32) {
    let mut c = compile(
        r#"light "u" "mib_light_point" ("color" 1 1 1) origin 0 5 0 user 4 2 end light
instance "u_inst" "u" end instance"#,
        &[],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let li = c.shading.lights.iter().position(|l| l.name == "u_inst").expect("the light");
    let l = &c.shading.lights[li];
    assert!(l.user && l.shape.is_none());
    let shader = l.shader.expect("a light shader");
    c.shading.graph.nodes[shader as usize].imp = Some(imp);
    (c, li as u32)
}

#[test]
fn user_light_shader_is_called_until_it_returns_false() {
    let (c, li) = user_light(&THREE_POINTS);
    let tracer = Empty::default();
    let mut ctx = Ctx::new(&c.shading, &tracer, point(Vec3A::Y, -Vec3A::Y));
    let mut lp = ctx.light_loop(li);
    let mut got = Vec::new();
    while let Some(s) = ctx.sample_light(&mut lp) {
        got.push(s);
    }
    assert_eq!(lp.samples, 3, "three samples, the fourth call ends the loop");
    assert_eq!(got.len(), 3);
    for (i, s) in got.iter().enumerate() {
        let want = Vec3A::new(i as f32 - 1.0, 5.0, 0.0);
        assert!((s.dir - want.normalize()).length() < 1e-6, "sample {i}: {s:?}");
        assert!((s.dist - want.length()).abs() < 1e-5);
        assert!((s.dot_nl - 5.0 / want.length()).abs() < 1e-6);
        assert_eq!(s.color, Color::new(1.0, i as f32, 0.0, 1.0));
    }
}

#[test]
fn user_light_samples_are_capped_at_u_times_v() {
    let (c, li) = user_light(&ENDLESS);
    let tracer = Empty::default();
    let mut ctx = Ctx::new(&c.shading, &tracer, point(Vec3A::Y, -Vec3A::Y));
    let mut lp = ctx.light_loop(li);
    let mut n = 0;
    while let Some(s) = ctx.sample_light(&mut lp) {
        assert!((s.dir - Vec3A::Y).length() < 1e-6 && (s.dist - 2.0).abs() < 1e-6);
        n += 1;
    }
    assert_eq!((n, lp.samples), (8, 8));
}

/// Sum of colour × cos over a light's samples / their count, at the origin facing +Y.
fn irradiance(c: &Compiled, light: &str) -> Vec3A {
    let li = c.shading.lights.iter().position(|l| l.name == light).expect("the light") as u32;
    let tracer = Empty::default();
    let mut ctx = Ctx::new(&c.shading, &tracer, point(Vec3A::Y, -Vec3A::Y));
    let mut lp = ctx.light_loop(li);
    let mut sum = Vec3A::ZERO;
    while let Some(s) = ctx.sample_light(&mut lp) {
        sum += Vec3A::new(s.color.x, s.color.y, s.color.z) * s.dot_nl;
    }
    sum / lp.samples.max(1) as f32
}

const ENV: &str = r#"environment "mib_color_mix" ("num" 0, "color_base" 0.5 1 2 1)"#;

fn portal(params: &str) -> Compiled {
    let body = format!(
        r#"shader "white" "mib_color_mix" ("num" 0, "color_base" 1 1 1 1)
light "p" "mia_portal_light" ({params}) origin 0 1 0 rectangle 1 0 0 0 0 1 16 16 end light
instance "p_inst" "p" end instance"#
    );
    let c = compile_with("", ENV, &body, &[]);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    c
}

#[test]
fn portal_brings_in_the_environment_through_its_area() {
    // A 1×1 portal one unit above the point, facing it: the irradiance is the
    // environment's radiance × π × the square's form factor 0.23945.
    let ff = std::f32::consts::PI * 0.23945;
    let c = portal(r#""multiplier" 2, "tint_color" 1 1 0.5"#);
    let e = irradiance(&c, "p_inst");
    let want = Vec3A::new(0.5 * 2.0, 2.0, 2.0 * 2.0 * 0.5) * ff;
    assert!((e - want).abs().max_element() < 0.01 * want.max_element(), "{e} vs {want}");
    // Facing away (reverse), it gives nothing.
    let c = portal(r#""reverse" on"#);
    assert_eq!(irradiance(&c, "p_inst"), Vec3A::ZERO);
    // Off: nothing either.
    let c = portal(r#""on" off"#);
    assert_eq!(irradiance(&c, "p_inst"), Vec3A::ZERO);
    // A custom environment replaces the camera's.
    let c = portal(r#""use_custom_environment" on, "custom_environment" "white""#);
    let e = irradiance(&c, "p_inst");
    assert!((e - Vec3A::splat(ff)).abs().max_element() < 0.01 * ff, "{e} vs {ff}");
    // Below the cutoff, samples are dropped.
    let c = portal(r#""multiplier" 0.001, "cutoff_threshold" 0.01"#);
    assert_eq!(irradiance(&c, "p_inst"), Vec3A::ZERO);
}

#[test]
fn portal_blocks_final_gather_rays_that_meet_it() {
    let c = portal("");
    let blocks = |org: Vec3A, dir: Vec3A, tmax: f32| c.shading.blocks_gather(org, dir, tmax);
    assert!(blocks(Vec3A::ZERO, Vec3A::Y, f32::INFINITY));
    assert!(blocks(Vec3A::new(0.0, 3.0, 0.0), -Vec3A::Y, f32::INFINITY), "either side");
    assert!(!blocks(Vec3A::ZERO, Vec3A::Y, 0.5), "a surface before the portal");
    assert!(!blocks(Vec3A::ZERO, -Vec3A::Y, f32::INFINITY));
    assert!(!blocks(Vec3A::new(2.0, 0.0, 0.0), Vec3A::Y, f32::INFINITY));
    // A plain area light does not block.
    let c = compile("light \"a\" \"mib_light_point\" () origin 0 1 0 rectangle 1 0 0 0 0 1 end light\ninstance \"a_inst\" \"a\" end instance", &[]);
    assert!(!c.shading.blocks_gather(Vec3A::ZERO, Vec3A::Y, f32::INFINITY));
}

#[test]
fn light_surface_value_depends_on_the_ray_type() {
    let c = compile(
        r#"material "glow" "mia_light_surface" ("color" 0.5 1 2, "intensity" 2, "fg_contrib" 0.25, "refl_contrib" 0.5) end material
material "lit" "mia_light_surface" ("use_lights" on, "lights_multiplier" 2, "lights" ["key_inst"]) end material"#,
        &["glow", "lit"],
    );
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let tracer = Empty::default();
    let at = |node, ray_type| {
        let mut s = point(Vec3A::Y, -Vec3A::Y);
        s.ray_type = ray_type;
        let (v, _, _) = run(&c, &tracer, node, s);
        v.color()
    };
    let glow = c.material("glow");
    let base = [1.0, 2.0, 4.0];
    for (ray, w) in [
        (RayType::Eye, 1.0),
        (RayType::Refract, 1.0),
        (RayType::Transparent, 1.0),
        (RayType::Finalgather, 0.25),
        (RayType::Reflect, 0.5),
    ] {
        support::assert_color(at(glow, ray), [base[0] * w, base[1] * w, base[2] * w, 1.0], 1e-6);
    }
    // From the lights: key (0.8, 0.6, 0.4) below the point — both sides count — × 2.
    support::assert_color(at(c.material("lit"), RayType::Eye), [1.6, 1.2, 0.8, 1.0], 1e-6);
    support::assert_color(at(c.material("lit"), RayType::Finalgather), [0.0, 0.0, 0.0, 1.0], 1e-6);
}
