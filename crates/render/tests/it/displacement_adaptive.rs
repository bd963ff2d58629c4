//! Adaptive displacement approximations (`render::displace::adaptive`): `length`,
//! `distance` and `view length` refine the displaced triangles until they hold (or the
//! greatest level is reached), crack-free, with the shader's heights at the vertices; and
//! hostile values fail or are clamped at the statement's line.

use std::collections::HashMap;

use glam::Vec3;

use crate::displacement::{build, plane};
use crate::support;

/// The cosine wave h(u) = 0.1·cos 2πu of the first texture space (u = x on the plane) as
/// the displacement of material `m`.
const WAVE: &str = r#"shader "coord" "mib_texture_vector" ("select" 0, "selspace" 0)
shader "wave" "mib_texture_wave" ("coord" = "coord", "amplitude_x" 0.1, "amplitude_y" 0, "amplitude_z" 0, "offset" 0)
shader "lam" "mib_illum_lambert" ("diffuse" 1 1 1)
material "m" = "lam" displace = "wave" end material"#;

/// The triangles and positions of every displaced instance's mesh.
fn meshes(world: &render::World) -> Vec<(&[[u32; 3]], &[Vec3])> {
    world
        .instances
        .iter()
        .map(|i| {
            let m = &world.meshes[i.mesh as usize];
            (&m.triangles[..], &m.positions[..])
        })
        .collect()
}

/// How many triangles use each edge (by its sorted vertex indices).
fn edge_uses(triangles: &[[u32; 3]]) -> HashMap<(u32, u32), u32> {
    let mut uses = HashMap::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    uses
}

/// `approximate displace length 0.05 0 10` on the unit square displaced by the wave:
/// every displaced edge is at most 0.05 long (1e-6; the greatest level is not reached);
/// every vertex lies at the shader's height, z = 0.1·cos 2πx (1e-4), x and y on the square;
/// no T-junction: an edge used by one triangle only lies on the square's border (both ends
/// on one side), every other edge is used by exactly two. `distance 0.01 1 10` likewise
/// leaves no edge whose ends' heights differ by more than 0.01 (its least level 1 splits
/// once first: the square's corners all lie at height 0.1, so no criterion could tell).
#[test]
fn length_and_distance_refine_until_every_edge_holds() {
    for (approx, check_length) in
        [("approximate displace length 0.05 0 10", true), ("approximate displace distance 0.01 1 10", false)]
    {
        let b = build(&plane("", WAVE, approx, "m"));
        assert!(!b.messages.iter().any(|m| m.contains("error") || m.contains("warning")), "{:?}", b.messages);
        let [(triangles, positions)] = meshes(&b.built.world)[..] else { panic!("one instance") };
        assert!(triangles.len() > 64, "{approx}: {} triangles", triangles.len());
        for p in positions {
            let expect = 0.1 * (2.0 * std::f32::consts::PI * p.x).cos();
            assert!((p.z - expect).abs() < 1e-4, "{approx}: {p} vs {expect}");
            assert!((-1e-6..=1.0 + 1e-6).contains(&p.x) && (-1e-6..=1.0 + 1e-6).contains(&p.y), "{p}");
        }
        let on_side = |a: Vec3, b: Vec3| {
            let same = |u: f32, v: f32, s: f32| (u - s).abs() < 1e-6 && (v - s).abs() < 1e-6;
            same(a.x, b.x, 0.0) || same(a.x, b.x, 1.0) || same(a.y, b.y, 0.0) || same(a.y, b.y, 1.0)
        };
        for ((a, c), n) in edge_uses(triangles) {
            let (pa, pc) = (positions[a as usize], positions[c as usize]);
            match n {
                1 => assert!(on_side(pa, pc), "{approx}: an inner edge {pa} {pc} with one triangle"),
                2 => {}
                _ => panic!("{approx}: an edge used {n} times"),
            }
            if check_length {
                assert!((pa - pc).length() <= 0.05 + 1e-6, "{approx}: edge {}", (pa - pc).length());
            } else {
                assert!((pa.z - pc.z).abs() <= 0.01 + 1e-6, "{approx}: heights {} {}", pa.z, pc.z);
            }
        }
    }
}

/// The greatest level bounds the refinement: `length 0.001 0 3` splits every edge three
/// times (each triangle into 4³: 2·64 triangles) and stops, edges longer than 0.001 left.
#[test]
fn the_greatest_level_stops_the_refinement() {
    let b = build(&plane("", WAVE, "approximate displace length 0.001 0 3", "m"));
    let [(triangles, _)] = meshes(&b.built.world)[..] else { panic!("one instance") };
    assert_eq!(triangles.len(), 2 * 64);
}

/// `view length 1` (pixel diagonals) splits the nearer of two equal squares more finely:
/// squares 2.75 and 11.75 from a 64-pixel-wide 90° camera (displaced 0.25 towards it).
/// Every edge of the near square spans at most one pixel diagonal seen at its depth
/// (length · 32 / 2.75 / √2 ≤ 1, 1e-4), and it has more than 4× the far one's triangles
/// ((11.75/2.75)² ≈ 18 in the limit).
#[test]
fn view_length_splits_nearer_triangles_more_finely() {
    let square = |name: &str| {
        format!(
            "object \"{name}\"\n approximate displace view length 0.25 0 8\n group\n 0 0 0  1 0 0  1 1 0  0 1 0\n \
             v 0 v 1 v 2 v 3\n p 0 1 2 3\n end group end object\n"
        )
    };
    let text = format!(
        "options \"opt\" end options\n\
         camera \"cam\" focal 1 aperture 2 aspect 1 resolution 64 64 end camera\n\
         instance \"cam_inst\" \"cam\" transform 1 0 0 0 0 1 0 0 0 0 1 0 -0.5 -0.5 -3 1 end instance\n\
         {}\n{}{}\
         instance \"near_inst\" \"near\" material \"m\" end instance\n\
         instance \"far_inst\" \"far\" material \"m\" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 0 9 1 end instance\n\
         instgroup \"root\" \"cam_inst\" \"near_inst\" \"far_inst\" end instgroup\n\
         render \"root\" \"cam_inst\" \"opt\"\n",
        crate::displacement::constant_material(0.25),
        square("near"),
        square("far")
    );
    let b = support::build_parsed(&mi::parse_str("t.mi", &text), 64, &[]);
    assert!(!b.messages.iter().any(|m| m.contains("error") || m.contains("warning")), "{:?}", b.messages);
    let world = &b.built.world;
    let depth = |p: Vec3, inst: &render::world::InstanceData| {
        world.camera.depth(inst.object_to_world.transform_point3a(p.into()))
    };
    let mut counts = Vec::new();
    for inst in &world.instances {
        let m = &world.meshes[inst.mesh as usize];
        let d = depth(m.positions[0], inst);
        if d > 5.0 {
            counts.push((d, m.triangles.len()));
            continue;
        }
        for t in &m.triangles {
            for k in 0..3 {
                let (a, c) = (m.positions[t[k] as usize], m.positions[t[(k + 1) % 3] as usize]);
                let pixels = (a - c).length() * 32.0 / depth(a, inst) / std::f32::consts::SQRT_2;
                assert!(pixels <= 1.0 + 1e-4, "{pixels} pixel diagonals");
            }
        }
        counts.push((d, m.triangles.len()));
    }
    counts.sort_by(|x, y| x.0.total_cmp(&y.0));
    let [(near_depth, near), (far_depth, far)] = counts[..] else { panic!("two instances: {counts:?}") };
    assert!((near_depth - 2.75).abs() < 1e-4 && (far_depth - 11.75).abs() < 1e-4, "{counts:?}");
    assert!(near > 4 * far, "near {near}, far {far}");
}

/// Hostile values: a length of 0 or −1 and a negative level are errors at the statement's
/// line (t.mi:9); a greatest level of 99 is lowered to 16 with a warning there (the length
/// still ends the refinement); least levels of 13 (2·4^13 triangles, past the 2^23 limit)
/// are an error there, made before any triangle is.
#[test]
fn hostile_values_fail_or_are_clamped_at_the_statement() {
    let material = crate::displacement::constant_material(0.5);
    for (approx, what) in [
        ("approximate displace length 0 0 5", "positive"),
        ("approximate displace length -1 0 5", "positive"),
        ("approximate displace view length 0.5 -2 5", "level"),
        ("approximate displace length 0.5 13 13", "would make"),
    ] {
        let b = build(&plane("", &material, approx, "m"));
        let errors: Vec<&String> = b.messages.iter().filter(|m| m.contains("error")).collect();
        assert_eq!(errors.len(), 1, "{approx}: {:?}", b.messages);
        assert!(errors[0].contains("t.mi:9:") && errors[0].contains(what), "{approx}: {}", errors[0]);
    }
    let b = build(&plane("", &material, "approximate displace length 0.5 0 99", "m"));
    assert!(!b.messages.iter().any(|m| m.contains("error")), "{:?}", b.messages);
    let warning = b.messages.iter().find(|m| m.contains("lowered to 16")).expect("a warning");
    assert!(warning.contains("t.mi:9:"), "{warning}");
    let [(triangles, positions)] = meshes(&b.built.world)[..] else { panic!("one instance") };
    for t in triangles {
        for k in 0..3 {
            let l = (positions[t[k] as usize] - positions[t[(k + 1) % 3] as usize]).length();
            assert!(l <= 0.5 + 1e-6, "{l}");
        }
    }
}

/// `offscreen`, `grading`, `grid` and `delaunay` change no triangle (mental ray's
/// `grading` bounds the angles of its Delaunay meshing, which displacement here does not
/// do; `offscreen` has no documented meaning): under `view length 0.25` on a 19-unit-wide
/// strip 3 units from an 8-pixel 90° camera (which sees 6 units of it), each statement
/// makes the same triangles at the same positions, bit for bit, as `view length 0.25 0 8`
/// alone, with one warning per word at the statement's line (t.mi:10) naming it
/// (`grading` citing `miApprox`); `grading -5` and `grading 75` are also named as angles
/// no triangle can keep.
#[test]
fn offscreen_grading_and_styles_change_no_triangle() {
    let strip = |approx: &str| {
        plane("", WAVE, approx, "m")
            .replace("0 0 0  1 0 0  1 1 0  0 1 0\n    0 0 0", "-9 0 0  10 0 0  10 1 0  -9 1 0\n    0 0 0")
    };
    let base = build(&strip("approximate displace view length 0.25 0 8"));
    assert!(!base.messages.iter().any(|m| m.contains("warning")), "{:?}", base.messages);
    let [(triangles, positions)] = meshes(&base.built.world)[..] else { panic!("one instance") };
    assert!(positions.iter().any(|p| p.x < -8.0) && triangles.len() > 64, "{}", triangles.len());
    for (approx, words) in [
        ("approximate displace view offscreen length 0.25 0 8", &["'offscreen'"][..]),
        ("approximate displace delaunay view length 0.25 grading 30 0 8", &["'delaunay'", "'grading 30'"]),
        ("approximate displace grid view length 0.25 grading -5 0 8", &["'grid'", "'grading -5'"]),
        ("approximate displace view offscreen length 0.25 grading 75 0 8", &["'offscreen'", "'grading 75'"]),
    ] {
        let b = build(&strip(approx));
        let warnings: Vec<&String> = b.messages.iter().filter(|m| m.contains("warning")).collect();
        assert_eq!(warnings.len(), words.len(), "{approx}: {warnings:?}");
        for w in words {
            let said = warnings.iter().find(|m| m.contains(w)).unwrap_or_else(|| panic!("{approx}: {w} {warnings:?}"));
            assert!(said.contains("t.mi:10:") && said.contains("no effect"), "{said}");
            if w.starts_with("'grading") {
                assert!(said.contains("miApprox"), "{said}");
                let impossible = said.contains("no angle every triangle can keep");
                assert_eq!(impossible, !w.contains("30"), "{said}");
            }
        }
        let [(t, p)] = meshes(&b.built.world)[..] else { panic!("one instance") };
        assert_eq!(t, triangles, "{approx}");
        assert!(
            p.iter().zip(positions).all(|(a, b)| a.to_array() == b.to_array()) && p.len() == positions.len(),
            "{approx}"
        );
    }
}
