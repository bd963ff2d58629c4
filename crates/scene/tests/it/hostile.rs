//! Hostile input at the scene layer (issue 15): degenerate cameras, deep instgroup nesting,
//! values beyond single precision. Each case gives its diagnostic at the statement that
//! causes it, and what the scene then holds is finite.

use scene::Scene;

/// Builds `text`; returns the scene (if any) and the first line of every diagnostic.
fn build(text: &str) -> (Option<Scene>, Vec<String>) {
    let parsed = mi::parse_str("t.mi", text);
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let mut diags = Vec::new();
    let scene = Scene::build(&parsed, 0, &mut diags);
    let lines =
        diags.iter().map(|d| d.render(&parsed.sources).lines().next().unwrap_or_default().to_string()).collect();
    (scene, lines)
}

/// A one-triangle scene whose camera block holds `camera` (line 2 onwards).
fn with_camera(camera: &str) -> String {
    format!(
        "options \"o\" end options\ncamera \"c\"\n{camera}\nend camera\n\
         instance \"ci\" \"c\" transform 1 0 0 0 0 1 0 0 0 0 1 0 0 0 -5 1 end instance\n\
         object \"t\" group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 p 0 1 2 end group end object\n\
         instance \"ti\" \"t\" material \"m\" end instance\n\
         material \"m\" \"mib_illum_lambert\" () end material\n\
         instgroup \"root\" \"ci\" \"ti\" end instgroup\nrender \"root\" \"ci\" \"o\"\n"
    )
}

#[test]
fn degenerate_camera_is_an_error_at_its_statement() {
    let (scene, d) = build(&with_camera("focal 0\naperture 0\naspect 0\nresolution 8 8"));
    assert_eq!(
        d,
        [
            "t.mi:3:1: error: camera focal length 0 is not a positive finite number (or 'infinity' for an \
             orthographic camera)",
            "t.mi:4:1: error: camera aperture 0 is not a positive finite number",
            "t.mi:5:1: warning: camera aspect 0 is not a positive finite number: the resolution's ratio 1 is used",
        ]
    );
    // The camera is still built, from defaults, and has a finite field of view.
    let c = scene.expect("a scene").camera;
    assert_eq!((c.focal, c.aperture, c.aspect), (Some(1.0), 1.0, 1.0));
    assert!(c.fov_x().is_finite() && c.fov_y().is_finite());
}

#[test]
fn infinite_and_negative_camera_values() {
    // 1e999 reads as infinity.
    let (_, d) = build(&with_camera("focal 1e999\naperture -1"));
    assert_eq!(d[0], "t.mi:3:1: error: camera focal length infinity is not a positive finite number (or 'infinity' for an orthographic camera)");
    assert_eq!(d[1], "t.mi:4:1: error: camera aperture -1 is not a positive finite number");
    let (scene, d) = build(&with_camera("focal infinity\naperture 2\nclip 10 1\noffset 1e999 0"));
    assert_eq!(
        d,
        [
            "t.mi:6:1: warning: camera offset is not finite: no offset is used",
            "t.mi:5:1: warning: camera clip 10 1 is not a range from a near distance ≥ 0 to a farther one: \
             0.001 1e30 is used",
        ]
    );
    let c = scene.expect("a scene").camera;
    assert_eq!((c.focal, c.clip, c.offset), (None, (0.001, 1e30), (0.0, 0.0)));
}

#[test]
fn resolution_outside_the_supported_range_is_an_error() {
    for (text, shown) in [
        ("resolution 4000000000 4000000000", "4000000000 x 4000000000"),
        ("resolution 0 0", "0 x 0"),
        ("resolution -640 480", "-640 x 480"),
        ("resolution 65537 10", "65537 x 10"),
    ] {
        let (_, d) = build(&with_camera(text));
        assert_eq!(d, [format!("t.mi:3:1: error: camera resolution {shown} is outside 1 … 65536 pixels per side")]);
    }
    let (scene, d) = build(&with_camera("resolution 65536 1"));
    assert!(d.is_empty(), "{d:?}");
    let c = scene.expect("a scene").camera;
    assert_eq!(c.resolution, (65536, 1));
    // The statement's place is kept for later checks (memory).
    let (scene, _) = build(&with_camera("focal 1"));
    assert_eq!(scene.expect("a scene").camera.resolution, (768, 576), "mental ray's default");
}

/// `depth` instgroups, each holding the next; the innermost holds the triangle.
fn nested(depth: usize) -> String {
    let mut s = String::from(
        "options \"o\" end options\ncamera \"c\" end camera\ninstance \"ci\" \"c\" end instance\n\
         object \"t\" group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 p 0 1 2 end group end object\n\
         material \"m\" \"mib_illum_lambert\" () end material\n\
         instance \"ti\" \"t\" material \"m\" end instance\ninstgroup \"g0\" \"ti\" end instgroup\n",
    );
    for i in 1..depth {
        s += &format!("instgroup \"g{i}\" \"g{}\" end instgroup\n", i - 1);
    }
    s += &format!("instgroup \"root\" \"ci\" \"g{}\" end instgroup\nrender \"root\" \"ci\" \"o\"\n", depth - 1);
    s
}

#[test]
fn deep_instgroup_nesting_is_reported_as_depth_not_as_a_cycle() {
    // root + 255 groups: 256 levels, the most mira follows.
    let (scene, d) = build(&nested(255));
    assert!(d.is_empty(), "{d:?}");
    assert_eq!(scene.expect("a scene").instances.len(), 1);
    // Issue 15: 20 000 nested instgroups were reported as "contains itself".
    let (_, d) = build(&nested(20_000));
    assert_eq!(d.len(), 1, "{d:?}");
    assert!(
        d[0] == (
            "t.mi:19752:20: error: instgroup 'g19744' is nested 257 levels deep; mira follows at most 256 levels of \
             instgroups (through root -> g19999 -> g19998 -> … 250 more … -> g19747 -> g19746 -> g19745)"
        ),
        "{}",
        d[0]
    );
    assert!(!d[0].contains("contains itself"));
}

#[test]
fn objects_beyond_single_precision_are_left_out_with_a_warning() {
    let text = with_camera("resolution 8 8").replace(
        "instance \"ti\" \"t\" material",
        "instance \"ti\" \"t\" transform 1e-35 0 0 0 0 1e-35 0 0 0 0 1e-35 0 0 0 0 1 material",
    );
    let (scene, d) = build(&text);
    assert_eq!(
        d,
        ["t.mi:7:1: warning: instance 'ti': object 't' placed in world space reaches beyond single precision \
          (±1e30); the object is left out"]
    );
    assert!(scene.expect("a scene").instances.is_empty());
    let text = with_camera("resolution 8 8").replace("0 0 -5 1 end", "0 0 -1e31 1 end");
    let (scene, d) = build(&text);
    assert!(scene.is_none());
    assert_eq!(d, ["t.mi:5:1: error: the camera's position is beyond single precision (±1e30)"]);
}

/// Fuzz finding (scene target, on `crates/mira/tests/hostile/vertex_infinite.mi`): a vertex
/// at infinity stayed in the mesh after its polygon was skipped, and reached the world's
/// bounds. Positions that are not finite or lie beyond ±1e30 are now zeroed (triangles
/// using them left out), with one warning per object.
#[test]
fn non_finite_vertices_do_not_reach_the_world() {
    let text = with_camera("resolution 8 8").replace("group 0 0 0 1 0 0", "group 0 0 0 1e999 0 0");
    let (scene, d) = build(&text);
    assert_eq!(
        d.last().map(String::as_str),
        Some(
            "t.mi:6:1: warning: object 't': 1 vertex positions are not finite or lie beyond ±1e30 (0 triangles \
             using them are left out) and 0 other vertex values are not finite (zero is used)"
        ),
        "{d:?}"
    );
    let scene = scene.expect("a scene");
    assert!(scene.objects.iter().all(|o| o.geometry.mesh.positions.iter().all(|p| p.is_finite())));
    assert!(scene.bounds().is_none_or(|(lo, hi)| lo.is_finite() && hi.is_finite()));
}

/// Options values beyond what mira keeps are clamped with a warning at their statement
/// (they were clamped silently: two billion progressive samples became 10^9 unannounced).
#[test]
fn capped_options_warn_at_their_statement() {
    let text = with_camera("resolution 8 8").replace(
        "options \"o\" end options",
        "options \"o\"\n\"progressive max samples\" 2000000000\nmotion steps 100\nframe buffer 100000 \"rgba\"\n\
         finalgather accuracy view 5000000 1 0.1\ncaustic accuracy 0\nfinalgather points 70000\nend options",
    );
    let (scene, d) = build(&text);
    assert_eq!(
        d,
        [
            "t.mi:2:1: warning: \"progressive max samples\" 2000000000 is more than mira takes: 1000000000 is used",
            "t.mi:3:1: warning: 'motion steps' 100 is more than mira takes: 15 is used",
            "t.mi:4:1: warning: 'frame buffer' 100000 is more than mira takes: 65536 is used",
            "t.mi:5:1: warning: 'finalgather accuracy' 5000000 is more than mira takes: 1048576 is used",
            "t.mi:6:1: warning: 'caustic accuracy' 0 is less than 1: 1 is used",
            "t.mi:7:1: warning: 'finalgather points' 70000 is more than mira takes: 65536 is used",
        ]
    );
    let o = scene.expect("a scene").options;
    assert_eq!(o.progressive.max_samples, 1_000_000_000);
    assert_eq!(o.motion_steps, 15);
    assert_eq!(o.finalgather.rays, 1 << 20);
    assert_eq!(o.photons.caustic_accuracy.0, 1);
    assert_eq!(o.finalgather.points, 1 << 16);
}
