//! `mib_texture_filter_lookup`: elliptical filtering of an image texture over the pixel
//! footprint the state's differentials describe, and its `remap` shader.

use crate::support;

use glam::{Vec2, Vec3A};
use shader::State;
use support::{compile, point, run, Empty};

/// 16×16 texels, vertical stripes two texels wide (white at x = 0, 1), rows bottom up.
fn stripes() -> String {
    let row: String = (0..16).map(|x| if (x / 2) % 2 == 0 { " 'ffffff'" } else { " '000000'" }).collect();
    format!("color texture \"stripes\" [ 16 16 ]{}", row.repeat(16))
}

/// A shading point with texture coordinate (u, v) and a grazing footprint: a quarter
/// texel per pixel across (u), eight texels along (v).
fn grazing(u: f32, v: f32) -> State {
    let mut s = point(Vec3A::Z, -Vec3A::Z);
    s.tex_count = 1;
    s.tex_list[0] = Vec3A::new(u, v, 0.0);
    s.point_derivs = [Vec3A::X * 0.01, Vec3A::Y * 0.01];
    s.tex_derivs = [Vec2::new(0.25 / 16.0, 0.0), Vec2::new(0.0, 8.0 / 16.0)];
    s
}

fn lookup(remap: &str, state: State) -> f32 {
    let body = format!(
        r#"{}
shader "rm" "mib_texture_remap" ("input" 0.9 0.9 0, "repeat" 8 0 0)
material "m" "mib_texture_filter_lookup" ("tex" "stripes", "coord" 0.3125 0.5 0, "disc_r" 1{remap}) end material"#,
        stripes()
    );
    let c = compile(&body, &["m"]);
    assert!(c.messages.is_empty(), "{:?}", c.messages);
    let (v, _, _) = run(&c, &Empty::default(), c.material("m"), state);
    v.color().x
}

#[test]
fn grazing_footprints_keep_stripes_across_them_sharp() {
    // Centred on a white stripe: the footprint's minor axis is across the stripes.
    let sharp = lookup("", grazing(0.3125, 0.5));
    assert!(sharp > 0.95, "{sharp}");
    // Along the stripes the long axis averages nothing away; turned across them, it does.
    let mut s = grazing(0.3125, 0.5);
    s.tex_derivs = [Vec2::new(8.0 / 16.0, 0.0), Vec2::new(0.0, 0.25 / 16.0)];
    let across = lookup("", s);
    assert!((across - 0.5).abs() < 0.02, "{across}");
}

#[test]
fn the_remap_shader_maps_the_projected_points() {
    // mib_texture_remap takes the handed-over coordinates (not its constant input) and
    // repeats u eight times: the footprint is eight times wider across the stripes.
    let blurred = lookup(r#", "remap" "rm""#, grazing(0.3125, 0.5));
    assert!(blurred < 0.75 && blurred > 0.5, "{blurred}");
}

#[test]
fn without_differentials_the_lookup_is_unfiltered() {
    let mut s = grazing(0.3125, 0.5);
    s.point_derivs = [Vec3A::ZERO; 2];
    s.tex_derivs = [Vec2::new(8.0 / 16.0, 0.0), Vec2::ZERO];
    assert_eq!(lookup("", s), 1.0);
}
