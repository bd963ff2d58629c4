//! `::base` procedural and bump textures, colour layering, projections and `::tex` texel
//! reads, crops and sizes called inside module materials (tests/mdl/base_functions.mdl): each
//! material, evaluated per hit, against the pattern's own implementation
//! (`material::mdl_modules::procedural`, `mdl::texture`) or a value worked out by hand.

use crate::mdl_support;

use bsdf::Rgb;
use glam::Vec3A;
use material::mdl_modules::procedural;
use material::{SurfaceMaterial, Varying};
use mdl_support::{close, compile_text, get};
use shader::State;

/// A shading point with texture coordinate (u, v), world position (u, v, 0), normal +z.
fn uv(u: f32, v: f32) -> State {
    let mut s = State {
        tex_count: 1,
        normal: Vec3A::Z,
        normal_geom: Vec3A::Z,
        dir: -Vec3A::Z,
        point: Vec3A::new(u, v, 0.0),
        ..State::default()
    };
    s.tex_list[0] = Vec3A::new(u, v, 0.0);
    s
}

/// The material's diffuse colour and shading normal at `state`.
fn at(m: &SurfaceMaterial, state: &State) -> (Rgb, Option<Vec3A>) {
    let Varying::Evaluated(hit) = &m.varying else { panic!("{} is not evaluated per hit: {:?}", m.name, m.varying) };
    let mut h = m.constant();
    hit.0.apply(state, &mut h);
    (h.diffuse, h.normal)
}

/// Compiles one instance of `base_functions::<material>` with `params`, expecting no message.
fn one(material: &str, params: &str) -> (material::mdl_modules::MdlMaterials, scene::Library) {
    let (mdl, lib, diags) = compile_text(&format!(r#"shader "m" "mdl::base_functions::{material}" ({params})"#));
    assert!(diags.is_empty(), "{material}: {diags:#?}");
    (mdl, lib)
}

#[test]
fn checker_cells_and_blur_per_hit() {
    let (mdl, lib) = one("checkered", "");
    let m = get(&mdl, &lib, "m");
    let (red, blue) = (Rgb::new(1.0, 0.0, 0.0), Rgb::new(0.0, 0.0, 1.0));
    // z = 0 lies below the split in z, so one more axis below it flips the cell.
    for (u, v, want) in
        [(0.75, 0.75, red), (0.25, 0.25, red), (0.25, 0.75, blue), (1.25, -0.25, blue), (1.75, -0.25, red)]
    {
        let (c, _) = at(m, &uv(u, v));
        assert!(close(c, want, 1e-6), "({u}, {v}): {c:?}");
    }
    // Blurred by 0.1 along u and v: 0.05 from the edge at u = 0.5 (inside red's cell) is
    // half the blur, so the blend is 0.5 + 0.5 · 0.5 towards red.
    let (mdl, lib) = one("checkered", r#""blur" 0.1"#);
    let (c, _) = at(get(&mdl, &lib, "m"), &uv(0.55, 0.75));
    assert!(close(c, Rgb::new(0.75, 0.0, 0.25), 1e-6), "{c:?}");
}

#[test]
fn perlin_noise_is_the_patterns_value_and_half_way_on_the_lattice() {
    let (mdl, lib) = one("perlin", r#""levels" 3"#);
    let m = get(&mdl, &lib, "m");
    let top = Rgb::new(1.0, 0.5, 0.25);
    // Gradient noise is 0 at every octave's lattice points: the colours' mean.
    let (c, _) = at(m, &uv(2.0, -1.0));
    assert!(close(c, top * 0.5, 1e-6), "{c:?}");
    let mut spread = (1.0f32, 0.0f32);
    for k in 0..50 {
        let (u, v) = (0.137 * k as f32, 0.071 * k as f32 + 0.3);
        let t = procedural::summed_perlin(Vec3A::new(u, v, 0.0), 0.0, 3, Vec3A::ZERO, false, false);
        let (c, _) = at(m, &uv(u, v));
        assert!(close(c, top * t, 1e-6), "({u}, {v}): {c:?} vs {t}");
        assert!((0.0..=1.0).contains(&t));
        spread = (spread.0.min(t), spread.1.max(t));
    }
    assert!(spread.1 - spread.0 > 0.2, "the noise varies: {spread:?}");
    // Marble: cos(x + 5·n) with n the summed noise (the scaled position's x the phase),
    // the blend of the colours; the tint is clamped to [0, 1] where the cosine is negative.
    let (mdl, lib) = one("perlin", r#""marble" on, "size" 2"#);
    let m = get(&mdl, &lib, "m");
    let mut inside = 0;
    for k in 0..20 {
        let (u, v) = (0.29 * k as f32, 0.13 * k as f32);
        let (c, _) = at(m, &uv(u, v));
        let q = Vec3A::new(u, v, 0.0) / 2.0;
        let t = (q.x + 5.0 * procedural::summed_perlin(q, 0.0, 1, Vec3A::ZERO, false, false)).cos();
        assert!(close(c, top * t.clamp(0.0, 1.0), 1e-5), "({u}, {v}): {c:?} vs {t}");
        inside += usize::from(t > 0.05 && t < 0.95);
    }
    assert!(inside > 3, "the marble's values were mostly clamped");
}

#[test]
fn worley_flow_and_flakes_are_their_patterns_values() {
    for mode in [0, 4, 7] {
        let (mdl, lib) = one("worley", &format!(r#""mode" {mode}"#));
        let m = get(&mdl, &lib, "m");
        for k in 0..20 {
            let p = Vec3A::new(0.31 * k as f32, 0.17 * k as f32, 0.0);
            // The tint is clamped to [0, 1] (F1 + F2 passes 1).
            let want = procedural::worley_mode(&procedural::worley(p, 0), mode, 0.2).clamp(0.0, 1.0);
            let (c, _) = at(m, &uv(p.x, p.y));
            assert!(close(c, Rgb::splat(want), 1e-6), "mode {mode} at {p}: {c:?} vs {want}");
        }
    }
    let (mdl, lib) = one("flow", "");
    let m = get(&mdl, &lib, "m");
    for k in 0..20 {
        let (u, v) = (0.23 * k as f32, 0.41 * k as f32);
        let want = procedural::flow(u, v, 0.3, 2, false, 0.5, 2.0, 1.0, 0.0);
        let (c, _) = at(m, &uv(u, v));
        assert!(close(c, Rgb::splat(want), 1e-6) && (0.0..=1.0).contains(&want), "({u}, {v}): {c:?} vs {want}");
    }
    // Flakes of Worley cells, 0.25 across: one value per flake.
    let (mdl, lib) = one("flakes", "");
    let m = get(&mdl, &lib, "m");
    for k in 0..20 {
        let p = Vec3A::new(0.093 * k as f32, 0.051 * k as f32, 0.0);
        let want = procedural::flake(p / 0.25, 1.0, 1.0, true, 10.0, 0);
        let (c, _) = at(m, &uv(p.x, p.y));
        assert!(close(c, Rgb::splat(want), 1e-6), "{p}: {c:?} vs {want}");
    }
}

#[test]
fn gradient_and_colour_layers() {
    let (mdl, lib) = one("gradient", "");
    let m = get(&mdl, &lib, "m");
    // Linear along u: red at 0, green at 0.5, blue at 1; a quarter is half red, half green.
    let (c, _) = at(m, &uv(0.25, 0.6));
    assert!(close(c, Rgb::new(0.5, 0.5, 0.0), 1e-6), "{c:?}");
    let (c, _) = at(m, &uv(1.625, 0.1));
    assert!(close(c, Rgb::new(0.0, 0.75, 0.25), 1e-6), "{c:?}");
    // Constant layers fold to a constant: 0.5 + 0.25 in red, then half way to ×0.5.
    let (mdl, lib) = one("layered", "");
    let m = get(&mdl, &lib, "m");
    assert_eq!(m.varying, Varying::Constant);
    let want = Rgb::new(0.75 * 0.75, 0.5 * 0.75, 0.5 * 0.75);
    assert!(close(m.diffuse, want, 1e-6), "{:?}", m.diffuse);
    let native = mdl::texture::blend_layer(
        "color_layer_multiply",
        mdl::texture::blend_layer("color_layer_add", Vec3A::splat(0.5), Vec3A::new(0.25, 0.0, 0.0), 1.0),
        Vec3A::splat(0.5),
        0.5,
    );
    assert!(close(m.diffuse, Rgb::new(native.x, native.y, native.z), 1e-6));
    // A texel layered at weight 0.5 over black: half the texel, per hit.
    let (mdl, lib) = one("layered_texture", "");
    let (c, _) = at(get(&mdl, &lib, "m"), &uv(0.25, 0.75));
    assert!(close(c, Rgb::new(0.5, 0.0, 0.0), 1e-6), "{c:?}");
}

#[test]
fn a_file_bump_leans_the_normal_as_the_shader_graphs_node_does() {
    let (mdl, lib) = one("file_bumped", r#""factor" 0.5"#);
    let m = get(&mdl, &lib, "m");
    // Heights (mono_average): red, green, blue 1/3, white 1. At the blue texel the height
    // rises by 2/3 one texel along u (white) and not along v (red): the node's formula
    // n − factor · (Δu · t_u + Δv · t_v), normalized.
    let s = uv(0.25, 0.25);
    let (tu, _) = mdl::texture::surface_tangents(&s);
    let want = (Vec3A::Z - tu * (0.5 * 2.0 / 3.0)).normalize();
    let (_, n) = at(m, &s);
    let n = n.expect("a bent normal");
    assert!((n - want).length() < 1e-5, "{n:?} vs {want:?}");
}

#[test]
fn bump_textures_keep_flat_regions_and_bend_at_edges() {
    // Tiles: 4 × 4, grout 0.05 wide (u in [0.25, 0.30) is grout). The middle of a tile is
    // flat; in the grout within half a grout (the step) of the tile, the rise bends it.
    let (mdl, lib) = one("tile_bumped", "");
    let m = get(&mdl, &lib, "m");
    let (_, flat) = at(m, &uv(0.125, 0.125));
    assert!((flat.expect("a normal") - Vec3A::Z).length() < 1e-6);
    let (_, edge) = at(m, &uv(0.29, 0.125));
    let edge = edge.expect("a normal");
    assert!(edge.z < 0.99 && (edge.length() - 1.0).abs() < 1e-5, "{edge:?}");
    // Checker: flat inside a cell, bent across an edge.
    let (mdl, lib) = one("checker_bumped", "");
    let m = get(&mdl, &lib, "m");
    let (_, inside) = at(m, &uv(0.7, 0.7));
    assert!((inside.expect("a normal") - Vec3A::Z).length() < 1e-6);
    let (_, edge) = at(m, &uv(0.49, 0.7));
    assert!(edge.expect("a normal").z < 0.99);
    // Noise and flakes: unit normals on the normal's side; flakes tilt at most by their
    // strength (|tangential part| ≤ 0.5 before normalizing: angle ≤ atan 0.5).
    for name in ["noise_bumped", "flake_bumped"] {
        let (mdl, lib) = one(name, "");
        let m = get(&mdl, &lib, "m");
        let mut bent = 0;
        for k in 0..30 {
            let (_, n) = at(m, &uv(0.173 * k as f32, 0.097 * k as f32));
            let n = n.expect("a normal");
            assert!((n.length() - 1.0).abs() < 1e-5 && n.z > 0.0, "{name}: {n:?}");
            if name == "flake_bumped" {
                assert!(n.z >= 1.0 / 1.25f32.sqrt() - 1e-5, "{n:?}");
            }
            bent += usize::from(n.z < 0.9999);
        }
        assert!(bent > 10, "{name}: only {bent} of 30 normals bent");
    }
}

#[test]
fn a_planar_projection_of_world_space_drives_the_checker() {
    let (mdl, lib) = one("projected", "");
    let m = get(&mdl, &lib, "m");
    // Scaled by 1/2: world (1.5, 1.5) is (0.75, 0.75), a colour-1 cell; (0.5, 1.5) is not.
    let (c, _) = at(m, &uv(1.5, 1.5));
    assert!(close(c, Rgb::ONE, 1e-6), "{c:?}");
    let (c, _) = at(m, &uv(0.5, 1.5));
    assert!(close(c, Rgb::ZERO, 1e-6), "{c:?}");
}

/// A shading point at `p` with shading and geometric normal `n` (world = object space).
fn on_surface(p: Vec3A, n: Vec3A) -> State {
    State { normal: n, normal_geom: n, dir: -n, point: p, ..State::default() }
}

/// The colour the `*_uv` materials show for coordinate (u, v) and u tangent x.
fn uv_colour(u: f32, v: f32, tangent_x: f32) -> Rgb {
    Rgb::new(0.5 + 0.1 * u, 0.5 + 0.1 * v, 0.5 + 0.5 * tangent_x)
}

#[test]
fn spherical_cylindrical_and_cubic_projections_at_known_points() {
    use std::f32::consts::{FRAC_PI_4, FRAC_PI_6};
    // A sphere of radius 2 at longitude π/4, latitude π/6: u = 2·π/4, v = 2·π/6 (arc
    // lengths), the u tangent east, (−sin φ, cos φ, 0).
    let (mdl, lib) = one("spherical_uv", "");
    let (phi, theta) = (FRAC_PI_4, FRAC_PI_6);
    let n = Vec3A::new(theta.cos() * phi.cos(), theta.cos() * phi.sin(), theta.sin());
    let (c, _) = at(get(&mdl, &lib, "m"), &on_surface(2.0 * n, n));
    assert!(close(c, uv_colour(2.0 * phi, 2.0 * theta, -phi.sin()), 1e-5), "{c:?}");
    // A cylinder of radius 1.5 (object space) at angle 1 rad, height 0.7: u = 1.5, v = 0.7;
    // its top cap at (0.3, −0.4, 1) projects planar, (0.3, −0.4), u tangent +x.
    let (mdl, lib) = one("cylindrical_uv", "");
    let m = get(&mdl, &lib, "m");
    let n = Vec3A::new(1.0f32.cos(), 1.0f32.sin(), 0.0);
    let (c, _) = at(m, &on_surface(1.5 * n, n));
    assert!(close(c, uv_colour(1.5, 0.0, -(1.0f32).sin()), 1e-5), "side at z = 0: {c:?}");
    let (c, _) = at(m, &on_surface(1.5 * n + Vec3A::new(0.0, 0.0, 0.7), n));
    assert!(close(c, uv_colour(1.5, 0.7, -(1.0f32).sin()), 1e-5), "side at z = 0.7: {c:?}");
    let (c, _) = at(m, &on_surface(Vec3A::new(0.3, -0.4, 1.0), Vec3A::Z));
    assert!(close(c, uv_colour(0.3, -0.4, 1.0), 1e-5), "cap: {c:?}");
    // A box of half size 1 projected cubic through a scale of 1/2: on the −y face the
    // plane is xz, (0.4, −1, −0.6) → (0.2, −0.3), u tangent +x; seen from inside (the
    // normal facing the origin) the same.
    let (mdl, lib) = one("cubic_uv", "");
    let m = get(&mdl, &lib, "m");
    let p = Vec3A::new(0.4, -1.0, -0.6);
    for n in [-Vec3A::Y, Vec3A::Y] {
        let (c, _) = at(m, &on_surface(p, n));
        assert!(close(c, uv_colour(0.2, -0.3, 1.0), 1e-5), "normal {n}: {c:?}");
    }
    // The +x face: plane yz, (1, 0.4, −0.6) → (0.2, −0.3), u tangent +y (x = 0).
    let (c, _) = at(m, &on_surface(Vec3A::new(1.0, 0.4, -0.6), Vec3A::X));
    assert!(close(c, uv_colour(0.2, -0.3, 0.0), 1e-5), "+x face: {c:?}");
}

#[test]
fn texel_reads_sizes_and_crops() {
    let (mdl, lib) = one("texel", "");
    let m = get(&mdl, &lib, "m");
    // (0, 0) is the lower left texel (blue); outside the image is black.
    for (u, v, want) in [
        (0.25, 0.25, Rgb::new(0.0, 0.0, 1.0)),
        (0.75, 0.25, Rgb::ONE),
        (0.25, 0.75, Rgb::new(1.0, 0.0, 0.0)),
        (0.75, 0.75, Rgb::new(0.0, 1.0, 0.0)),
        (1.25, 0.25, Rgb::ZERO),
    ] {
        let (c, _) = at(m, &uv(u, v));
        assert!(close(c, want, 1e-6), "({u}, {v}): {c:?}");
    }
    // texel_float4 (1, 0) is white (x = 1), texel_float2 (1, 1) green (y = 1), and the size
    // 2 × 2 gives (2·10 + 2)/100: a constant material.
    let (mdl, lib) = one("texel_float", "");
    let m = get(&mdl, &lib, "m");
    assert_eq!(m.varying, Varying::Constant);
    assert!(close(m.diffuse, Rgb::new(1.0, 1.0, 0.22), 1e-6), "{:?}", m.diffuse);
    // Cropped to the bottom-right quarter: [0, 1)² covers (0.5…1, 0…0.5) of the image, so
    // the middle is the white texel's centre and u = 0 the edge between blue and white.
    let (mdl, lib) = one("cropped", "");
    let m = get(&mdl, &lib, "m");
    for (u, v, want) in [(0.5, 0.5, Rgb::ONE), (0.0, 0.5, Rgb::new(0.5, 0.5, 1.0))] {
        let (c, _) = at(m, &uv(u, v));
        assert!(close(c, want, 1e-6), "({u}, {v}): {c:?}");
    }
    // file_texture cropped to the left column: u = 0.5 is the red texel's centre.
    let (mdl, lib) = one("file_cropped", "");
    let m = get(&mdl, &lib, "m");
    let (c, _) = at(m, &uv(0.5, 0.75));
    assert!(close(c, Rgb::new(1.0, 0.0, 0.0), 1e-6), "{c:?}");
}

#[test]
fn a_missing_3d_texture_is_a_warning_at_its_module_line() {
    let (_, _, diags) = compile_text(r#"shader "m" "mdl::base_functions::volume_texture" ()"#);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let d = &diags[0];
    assert!(d.contains("base_functions.mdl:97:") && d.contains("3D texture file './cloud.vdb' not found"), "{d}");
}

#[test]
fn a_module_texture_with_nan_texels_warns_once_naming_the_file() {
    let dir = std::env::temp_dir().join(format!("mira_mdl_nan_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut bad = image::Rgb32FImage::new(2, 1);
    bad.put_pixel(0, 0, image::Rgb([f32::NAN, f32::INFINITY, 0.5]));
    bad.put_pixel(1, 0, image::Rgb([0.25, 0.5, 0.75]));
    let file = dir.join("nan.exr");
    bad.save(&file).unwrap();
    let (mdl, lib, diags) = compile_text(&format!(
        r#"shader "a" "mdl::base_functions::non_finite" ("tex" "{0}")
shader "b" "mdl::base_functions::non_finite" ("tex" "{0}")"#,
        file.display()
    ));
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(diags.len(), 1, "one warning for the two instances: {diags:#?}");
    assert!(diags[0].contains("nan.exr") && diags[0].contains("2 texel components") && diags[0].contains("t.mi:1:"));
    // The NaN and infinity read as 0.
    let (c, _) = at(get(&mdl, &lib, "b"), &uv(0.25, 0.5));
    assert!(close(c, Rgb::new(0.0, 0.0, 0.5), 1e-6), "{c:?}");
}

#[test]
fn an_ior_that_varies_over_the_surface_is_read_per_hit() {
    let (mdl, lib, diags) = compile_text(
        r#"shader "graded" "mdl::base_functions::graded_glass" ()
shader "g15" "mdl::base_functions::glass" ("ior" 1.5)
shader "g175" "mdl::base_functions::glass" ("ior" 1.75)"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let graded = get(&mdl, &lib, "graded");
    let Varying::Evaluated(hit) = &graded.varying else { panic!("{:?}", graded.varying) };
    // At u = 0.5 and 0.75 the graded glass is the constant glass of ior 1.5 and 1.75.
    for (u, name) in [(0.5, "g15"), (0.75, "g175")] {
        let mut h = graded.constant();
        hit.0.apply(&uv(u, 0.5), &mut h);
        let want = get(&mdl, &lib, name);
        assert_eq!(*h.model, want.model, "u = {u}");
    }
    let (mut a, mut b) = (graded.constant(), graded.constant());
    hit.0.apply(&uv(0.5, 0.5), &mut a);
    hit.0.apply(&uv(0.75, 0.5), &mut b);
    assert_ne!(a.model, b.model, "the ior changes the model");
}

/// `tile_texture`: the tile colour on a tile, the grout colour in the grout (the first
/// 0.05 of each of the 4 columns and rows), odd rows shifted half a tile; its variations
/// other than the defaults are an error naming the parameter. `gradient3_recolor`: a
/// number that varies (here v) through the gradient, linear between the stops and clamped
/// beyond them.
#[test]
fn tile_colours_and_recoloured_numbers() {
    let (mdl, lib) = one("tiled_colors", "");
    let m = get(&mdl, &lib, "m");
    let (tile, grout) = (Rgb::new(0.8, 0.2, 0.1), Rgb::splat(0.9));
    for (u, v, want) in [
        (0.125, 0.125, tile),
        (0.27, 0.125, grout),
        (0.125, 0.26, grout),
        // Row 1 (odd) is shifted by half a tile: u = 0.14 is 0.015 into a column there.
        (0.14, 0.4, grout),
        (0.14, 0.125, tile),
    ] {
        let (c, _) = at(m, &uv(u, v));
        assert!(close(c, want, 1e-6), "({u}, {v}): {c:?} vs {want:?}");
    }
    let (mdl, lib) = one("recolored", "");
    let m = get(&mdl, &lib, "m");
    for (v, want) in [
        (0.25, Rgb::new(0.5, 0.5, 0.0)),
        (0.75, Rgb::new(0.0, 0.5, 0.5)),
        (0.6, Rgb::new(0.0, 0.8, 0.2)),
        (1.3, Rgb::new(0.0, 0.0, 1.0)),
        (-0.2, Rgb::new(1.0, 0.0, 0.0)),
    ] {
        let (c, _) = at(m, &uv(0.3, v));
        assert!(close(c, want, 1e-5), "v {v}: {c:?} vs {want:?}");
    }
}

/// A `df::measured_edf` whose light profile file does not exist: a diagnostic at the `.mi`
/// instance naming the module line of the profile and the file, and no emission.
#[test]
fn a_missing_light_profile_is_an_error_at_its_module_line() {
    let (mdl, lib, diags) = mdl_support::compile_text(r#"shader "m" "mdl::base_functions::measured_emitter" ()"#);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let d = &diags[0];
    assert!(d.contains("t.mi:1:") && d.contains("base_functions.mdl:122:") && d.contains("no_such.ies"), "{d}");
    assert_eq!(get(&mdl, &lib, "m").emission, Rgb::ZERO);
}
