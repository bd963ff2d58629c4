//! Maya's anisotropic, rampShader and layeredShader in compiled scenes, in the classic
//! engine (against the formulas of their module docs, worked out here by hand) and
//! translated for the path engine (the same albedo). The shading point is the origin,
//! normal +y, seen from straight above, dP/du = +x (see `support::maya::point`).

use crate::support;

use material::SurfaceModel;
use support::maya::{assert_rgb, compile, point, run, Compiled};
use support::Empty;

const LIBS: &str = "$include \"mayabase.mi\"\n$include \"AdskShaderSDK.mi\"\n";

fn scene(body: &str) -> Compiled {
    let c = compile("", &format!("{LIBS}{body}"), &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    assert!(c.attached > 0);
    c
}

fn shade(c: &Compiled) -> glam::Vec4 {
    run(c, &Empty::default(), c.material("m"), point([0.0, 0.0])).color()
}

fn translate(c: &Compiled) -> (material::SurfaceMaterial, Vec<String>) {
    material::maya::surface_material("m", &c.shading.graph, c.material("m")).expect("a Maya shading engine")
}

/// A directional light of intensity `i` shining along `dir` (normalised here).
fn sun(i: f32, dir: [f32; 3]) -> String {
    let d = glam::Vec3::from_array(dir).normalize();
    format!(
        "light \"sun\" \"maya_directionallight\" (\"intensity\" {i}) direction {} {} {} end light\n\
         instance \"sun_inst\" \"sun\" end instance\n",
        d.x, d.y, d.z
    )
}

fn anisotropic_material(family: &str, engine: &str) -> String {
    format!(
        r#"shader "an" "{family}" ("color" 0.6 0.5 0.4, "diffuse" 0.7, "specularColor" 0.3 0.3 0.3,
            "reflectivity" 0, "spreadX" 13, "spreadY" 3, "roughness" 0.7, "fresnelRefractiveIndex" 6)
        material "m" opaque "{engine}" ("surfaceShader" = "an.outColor") end material"#
    )
}

#[test]
fn anisotropic_peak_and_groove_direction() {
    // Light and viewer on the normal: c·d·I + s·I (the highlight's peak is 1).
    let c = scene(&format!(
        "{}{}",
        sun(1.0, [0.0, -1.0, 0.0]),
        anisotropic_material("maya_anisotropic", "maya_shadingengine")
    ));
    assert_rgb(shade(&c), [0.6 * 0.7 + 0.3, 0.5 * 0.7 + 0.3, 0.4 * 0.7 + 0.3], 1e-5);
    // Light 20° off the normal towards +x (along the grooves, dP/du) or +z: lambert
    // c·d·cos 20° plus s times the highlight of the formula.
    let (ax, ay) = maya::specular::anisotropic_widths(0.7, 13.0, 3.0);
    let t = 20f32.to_radians();
    let mut peaks = Vec::new();
    for to_light in [glam::Vec3A::new(t.sin(), t.cos(), 0.0), glam::Vec3A::new(0.0, t.cos(), t.sin())] {
        let c = scene(&format!(
            "{}{}",
            sun(1.0, (-to_light).to_array()),
            anisotropic_material("adskMayaAnisotropic", "adskMayaShadingEngine")
        ));
        let h = maya::specular::anisotropic(glam::Vec3A::Y, glam::Vec3A::Y, to_light, glam::Vec3A::X, ax, ay, 6.0);
        let got = shade(&c);
        assert_rgb(
            got,
            [0.6 * 0.7 * t.cos() + 0.3 * h, 0.5 * 0.7 * t.cos() + 0.3 * h, 0.4 * 0.7 * t.cos() + 0.3 * h],
            1e-5,
        );
        peaks.push(got.x - 0.6 * 0.7 * t.cos());
    }
    assert!(peaks[0] < peaks[1], "spreadX 13 > spreadY 3: the highlight is narrower along the grooves {peaks:?}");
    // Path engine: Lambert of c·d beside the classic highlight itself, its grooves the
    // hit's tangent (dP/du turned by `angle`, 0 here): under the path engine's light of
    // π·I, f·π·cos θ is the classic colour for both light directions; no warning.
    let (s, warnings) = translate(&c);
    let SurfaceModel::Maya(g) = &s.model else { panic!("{:?}", s.model) };
    assert!((s.diffuse - bsdf::Rgb::new(0.42, 0.35, 0.28)).abs().max_element() < 1e-6);
    assert_eq!(s.tangent_angle, Some(0.0));
    assert!(warnings.is_empty(), "{warnings:?}");
    let n = glam::Vec3A::Y;
    let frame = bsdf::Frame::from_normal_and_tangent(n, maya::specular::groove_direction(n, glam::Vec3A::X, 0.0));
    for to_light in [glam::Vec3A::new(t.sin(), t.cos(), 0.0), glam::Vec3A::new(0.0, t.cos(), t.sin())] {
        let classic = shade(&scene(&format!(
            "{}{}",
            sun(1.0, (-to_light).to_array()),
            anisotropic_material("adskMayaAnisotropic", "adskMayaShadingEngine")
        )));
        let wo = frame.to_local(n);
        let path = g.bsdf(s.diffuse, wo).eval(wo, frame.to_local(to_light)) * (std::f32::consts::PI * t.cos());
        assert_rgb(glam::Vec4::new(path.x, path.y, path.z, 1.0), classic.truncate().to_array(), 1e-5);
    }
}

/// Maya's documented recipe: black at 0.5, the colour at 1, linear, diffuse 0,
/// translucence 1 — a lambert falloff — in both engines.
const RAMP_RECIPE: &str = r#"shader "rs" "maya_rampshader" ("colorInput" 0, "diffuse" 0, "translucence" 1,
    "color" [ { "color_Position" 0.5, "color_Color" 0 0 0, "color_Interp" 1 },
              { "color_Position" 1, "color_Color" 0.8 0.6 0.4, "color_Interp" 1 } ])
material "m" opaque "maya_shadingengine" ("surfaceShader" = "rs.outColor") end material
"#;

#[test]
fn ramp_shader_light_angle_recipe_is_lambert() {
    for deg in [0.0f32, 60.0, 120.0] {
        let t = deg.to_radians();
        let c = scene(&format!("{}{RAMP_RECIPE}", sun(2.0, [-t.sin(), -t.cos(), 0.0])));
        let k = 2.0 * t.cos().max(0.0);
        assert_rgb(shade(&c), [0.8 * k, 0.6 * k, 0.4 * k], 1e-5);
        // The path engine's Lambertian albedo is the colour at 1 · (d + t): the same c·I·cos θ.
        let (s, warnings) = translate(&c);
        assert!(warnings.is_empty(), "{warnings:?}");
        assert_eq!(s.model, SurfaceModel::Lambert);
        assert!((s.diffuse - bsdf::Rgb::new(0.8, 0.6, 0.4)).abs().max_element() < 1e-6, "{}", s.diffuse);
    }
}

#[test]
fn ramp_shader_facing_input_transparency_incandescence_and_highlight() {
    // Seen head-on (facing ratio 1): the ramps are read at 1. Colour 0.5 at 1, diffuse
    // 0.8, light 1 at 60°: 0.5·0.8·0.5 = 0.2; incandescence 0.1 red; transparency 0.25
    // scales both by 0.75 (nothing behind); alpha 0.75.
    let t = 60f32.to_radians();
    let c = scene(&format!(
        r#"{}shader "rs" "adskMayaRampShader" ("colorInput" 1, "diffuse" 0.8,
            "color" [ {{ "color_Position" 0, "color_Color" 1 0 0, "color_Interp" 1 }},
                      {{ "color_Position" 1, "color_Color" 0.5 0.5 0.5, "color_Interp" 1 }} ],
            "transparency" [ {{ "transparency_Position" 0, "transparency_Color" 0.25 0.25 0.25, "transparency_Interp" 1 }} ],
            "incandescence" [ {{ "incandescence_Position" 0, "incandescence_Color" 0.1 0 0, "incandescence_Interp" 1 }} ])
        material "m" opaque "adskMayaShadingEngine" ("surfaceShader" = "rs.outColor") end material"#,
        sun(1.0, [-t.sin(), -t.cos(), 0.0])
    ));
    let got = shade(&c);
    assert_rgb(got, [(0.2 + 0.1) * 0.75, 0.2 * 0.75, 0.2 * 0.75], 1e-5);
    assert!((got.w - 0.75).abs() < 1e-5, "alpha {}", got.w);
    let (s, warnings) = translate(&c);
    assert!((s.diffuse - bsdf::Rgb::splat(0.4)).abs().max_element() < 1e-6, "{}", s.diffuse);
    assert!((s.opacity - 0.75).abs() < 1e-6 && (s.emission.x - 0.1).abs() < 1e-6);
    assert!(warnings.iter().any(|w| w.contains("FacingAngle")), "{warnings:?}");

    // A highlight: light and viewer on the normal, specularity 0.5, specular colour ramp
    // 0.4 at the peak: 0.5 · 0.4 · I on top of the diffuse 0.5·0.8·I.
    let c = scene(&format!(
        r#"{}shader "rs" "maya_rampshader" ("colorInput" 1, "diffuse" 0.8, "specularity" 0.5, "eccentricity" 0.3,
            "specularColor" [ {{ "specularColor_Position" 1, "specularColor_Color" 0.4 0.4 0.4, "specularColor_Interp" 1 }} ])
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "rs.outColor") end material"#,
        sun(1.0, [0.0, -1.0, 0.0])
    ));
    assert_rgb(shade(&c), [0.4 + 0.2; 3], 1e-5);
}

#[test]
fn layered_shader_composites_materials_by_their_transparency() {
    // A red surfaceShader 25 % transparent over an opaque green lambert lit by 1 straight
    // above (0.5 green · 0.8): 0.75 red + 0.25 · (0, 0.4, 0), nothing behind.
    let c = scene(&format!(
        r#"{}shader "top" "maya_surfaceshader" ("outColor" 1 0 0, "outTransparency" 0.25 0.25 0.25)
        shader "bottom" "maya_lambert" ("color" 0 0.5 0, "diffuse" 0.8)
        shader "ls" "maya_layeredshader" ("inputs" [
            {{ "color" = "top.outColor", "transparency" = "top.outTransparency" }},
            {{ "color" = "bottom.outColor", "transparency" = "bottom.outTransparency" }} ])
        material "m" opaque "maya_shadingengine" ("surfaceShader" = "ls.outColor") end material"#,
        sun(1.0, [0.0, -1.0, 0.0])
    ));
    let got = shade(&c);
    assert_rgb(got, [0.75, 0.25 * 0.4, 0.0], 1e-5);
    assert!((got.w - 1.0).abs() < 1e-6);
    // Path engine: the visible shares 0.75 and 0.25 of the layers' albedos; the
    // surfaceShader's colour is emitted, the lambert's scatters.
    let (s, _) = translate(&c);
    assert!((s.diffuse - bsdf::Rgb::new(0.0, 0.1, 0.0)).abs().max_element() < 1e-6, "{}", s.diffuse);
    assert!((s.emission - bsdf::Rgb::new(0.75, 0.0, 0.0)).abs().max_element() < 1e-6, "{}", s.emission);
    assert!((s.opacity - 1.0).abs() < 1e-6);
}

#[test]
fn layered_shader_in_texture_mode_and_over_what_is_behind() {
    // Texture mode, constant colours: red at transparency 0.6 over grey 0.5 at 0.5, over
    // an empty background (black): 0.4 red + 0.6·0.5·grey; 0.3 of the background shows.
    let c = scene(
        r#"shader "ls" "adskMayaLayeredShader" ("compositingFlag" 1, "inputs" [
            { "color" 1 0 0, "transparency" 0.6 0.6 0.6 },
            { "color" 0.5 0.5 0.5, "transparency" 0.5 0.5 0.5 } ])
        material "m" opaque "adskMayaShadingEngine" ("surfaceShader" = "ls.outColor") end material"#,
    );
    let got = shade(&c);
    assert_rgb(got, [0.4 + 0.15, 0.15, 0.15], 1e-5);
    assert!((got.w - 0.7).abs() < 1e-5, "alpha {}", got.w);
    let (s, _) = translate(&c);
    assert!((s.opacity - 0.7).abs() < 1e-6);
    // The path engine's hits, 0.7 of the rays, carry the stack's colour / 0.7.
    assert!((s.diffuse * s.opacity - bsdf::Rgb::new(0.55, 0.15, 0.15)).abs().max_element() < 1e-6, "{}", s.diffuse);
}

#[test]
fn a_material_light_list_picks_its_lights() {
    // Two lights straight above, intensities 1 and 2: all lights give c·d·3; a lightList
    // naming the second gives c·d·2 (exports fill it in with lightMode 0).
    let lights = r#"light "one" "maya_directionallight" ("intensity" 1) direction 0 -1 0 end light
        instance "one_inst" "one" end instance
        light "two" "maya_directionallight" ("intensity" 2) direction 0 -1 0 end light
        instance "two_inst" "two" end instance
        "#;
    for (list, k) in [("", 3.0), (r#", "lightMode" 0, "lightList" ["two_inst"]"#, 2.0)] {
        let c = scene(&format!(
            r#"{lights}shader "lam" "maya_lambert" ("color" 0.5 0.5 0.5, "diffuse" 1{list})
            material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#
        ));
        assert_rgb(shade(&c), [0.5 * k; 3], 1e-5);
        let c = scene(&format!(
            r#"{lights}shader "rs" "adskMayaRampShader" ("colorInput" 1, "diffuse" 1{list})
            material "m" opaque "adskMayaShadingEngine" ("surfaceShader" = "rs.outColor") end material"#
        ));
        assert_rgb(shade(&c), [0.5 * k; 3], 1e-5);
    }
}

#[test]
fn a_volume_light_fills_its_shape_with_its_colour_range() {
    // A sphere volume light of radius 2 centred `h` above the point: inside (h = 1) the
    // point lies halfway to the boundary, so the colour range (black at the boundary,
    // white at the centre, linear) gives half of intensity 2: a lambert of colour 0.5 and
    // diffuse 1 shows 0.5. Outside (h = 3): no light.
    for (h, want) in [(1.0, 0.5), (3.0, 0.0)] {
        let c = scene(&format!(
            r#"light "vol" "maya_volumelight" ("intensity" 2, "lightShape" 1,
                "colorRange" [ {{ "colorRange_Position" 0, "colorRange_Color" 0 0 0, "colorRange_Interp" 1 }},
                               {{ "colorRange_Position" 1, "colorRange_Color" 1 1 1, "colorRange_Interp" 1 }} ])
                origin 0 0 0 end light
            instance "vol_inst" "vol" transform 0.5 0 0 0  0 0.5 0 0  0 0 0.5 0  0 {} 0 1 end instance
            shader "lam" "adskMayaLambert" ("color" 0.5 0.5 0.5, "diffuse" 1)
            material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#,
            -0.5 * h
        ));
        assert_rgb(shade(&c), [want; 3], 1e-5);
    }
}

#[test]
fn cylinder_and_cone_volume_lights_fall_off_from_their_axis_and_stop_at_their_shape() {
    // Volume lights of radius 2 (the instance scales the unit shape by 2) whose axis (the
    // light's y) lies along world x, 1 above the shading point (the origin), centred at
    // x = offset: the point is at distance 1 from the axis, halfway to a cylinder's
    // boundary, lit from the axis point straight above it (Maya: the light moves away from
    // the central axis), cos θ = 1 whatever the offset (from the light's centre it would
    // be 1/√(1 + offset²): 0.707 for the cone at offset 1); the linear
    // colour range (black at the boundary, white on the axis) gives half of intensity 2,
    // and a penumbra graph from 0.25 at the edge to 1 on the axis multiplies by 0.625.
    // The sharp cone narrows from radius 2 at local y = −1 to 0 at y = 1: at the point's
    // place along the axis (local y = −offset/2) its radius is 1 − y in local units of
    // which the point is ½ away: at offset 0 on the boundary (no light), at offset 1
    // (y = −½) at 2/3 of the radius. Beyond the ends (|y| > 1): none.
    let range = r#""colorRange" [ { "colorRange_Position" 0, "colorRange_Color" 0 0 0, "colorRange_Interp" 1 },
                       { "colorRange_Position" 1, "colorRange_Color" 1 1 1, "colorRange_Interp" 1 } ]"#;
    let penumbra = r#", "penumbra" [ { "penumbra_Position" 0, "penumbra_FloatValue" 0.25, "penumbra_Interp" 1 },
                       { "penumbra_Position" 1, "penumbra_FloatValue" 1, "penumbra_Interp" 1 } ]"#;
    // (shape, extra parameters, the light's centre's offset along x, expected value).
    let cases = [
        (2, "", 0.0f32, 0.5f32),
        (2, penumbra, 0.0, 0.5 * 0.625),
        (2, "", 2.5, 0.0),
        (3, "", 0.0, 0.0),
        (3, "", 1.0, 1.0 - 2.0 / 3.0),
        (3, "", -2.5, 0.0),
    ];
    for (shape, extra, offset, want) in cases {
        // World → light (rows): world x → light y, world y → light z, world z → light
        // x, all halved, the centre at (offset, 1, 0): the origin is at (0, −offset/2, −½).
        let c = scene(&format!(
            r#"light "vol" "maya_volumelight" ("intensity" 2, "lightShape" {shape}, {range}{extra})
                origin 0 0 0 end light
            instance "vol_inst" "vol" transform 0 0.5 0 0  0 0 0.5 0  0.5 0 0 0  0 {} -0.5 1 end instance
            shader "lam" "adskMayaLambert" ("color" 0.5 0.5 0.5, "diffuse" 1)
            material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#,
            -0.5 * offset,
        ));
        assert_rgb(shade(&c), [0.5 * 2.0 * want; 3], 1e-4);
    }
}

#[test]
fn volume_light_directions_and_emit_ambient_against_their_formulas() {
    // A sphere volume light of radius 2 (linear colour range, intensity 2) centred at c =
    // (0.6, −0.8, 0), 1 from the shading point (the origin, normal +y): halfway to the
    // boundary, so 1 arrives. A lambert of colour 0.5 and diffuse 0.8 shows
    // 0.5 · 0.8 · 1 · cos θ with the direction the light is shaded from: outward (towards
    // the centre) below the surface, 0; inward (away from the centre) cos θ = 0.8; down
    // the light's axis, its +y axis, turned by φ about z to (−sin φ, cos φ, 0): cos θ =
    // cos φ. With emitAmbient the light lights as Maya's ambient light does, not scaled
    // by diffuse: 0.5 · 1 · (½ + ½ max(cos θ, 0)) with emitDiffuse on, 0.5 · 1 with it off.
    let centre = glam::Vec3A::new(0.6, -0.8, 0.0);
    let cases: [(&str, f32, f32); 8] = [
        ("", 0.0, 0.0),
        (r#", "volumeLightDir" 0"#, 0.0, 0.0),
        (r#", "volumeLightDir" 1"#, 0.0, 0.5 * 0.8 * 0.8),
        (r#", "volumeLightDir" 2"#, 0.0, 0.5 * 0.8),
        (r#", "volumeLightDir" 2"#, 60.0, 0.5 * 0.8 * 0.5),
        (r#", "emitAmbient" on"#, 0.0, 0.5 * 0.5),
        (r#", "emitAmbient" on, "volumeLightDir" 1"#, 0.0, 0.5 * (0.5 + 0.5 * 0.8)),
        (r#", "emitAmbient" on, "emitDiffuse" off"#, 0.0, 0.5),
    ];
    for (extra, degrees, want) in cases {
        // m = ½ R, R turning about z by φ (the light's y axis to (−sin φ, cos φ, 0)).
        let (s, co) = f32::to_radians(degrees).sin_cos();
        let m = glam::Mat3A::from_cols(
            glam::Vec3A::new(co, s, 0.0) * 0.5,
            glam::Vec3A::new(-s, co, 0.0) * 0.5,
            glam::Vec3A::new(0.0, 0.0, 0.5),
        );
        // Row vectors: p_light = p_world · T, T's written rows (m's rows) and translation
        // row −(mᵀ c), so that the centre goes to the light's origin.
        let t = -(m.transpose() * centre);
        let (r0, r1, r2) = (m.x_axis, m.y_axis, m.z_axis);
        let c = scene(&format!(
            r#"light "vol" "maya_volumelight" ("intensity" 2, "lightShape" 1{extra},
                "colorRange" [ {{ "colorRange_Position" 0, "colorRange_Color" 0 0 0, "colorRange_Interp" 1 }},
                               {{ "colorRange_Position" 1, "colorRange_Color" 1 1 1, "colorRange_Interp" 1 }} ])
                origin 0 0 0 end light
            instance "vol_inst" "vol" transform {} {} {} 0  {} {} {} 0  {} {} {} 0  {} {} {} 1 end instance
            shader "lam" "adskMayaLambert" ("color" 0.5 0.5 0.5, "diffuse" 0.8)
            material "m" opaque "maya_shadingengine" ("surfaceShader" = "lam.outColor") end material"#,
            r0.x, r1.x, r2.x, r0.y, r1.y, r2.y, r0.z, r1.z, r2.z, t.x, t.y, t.z
        ));
        assert_rgb(shade(&c), [want; 3], 1e-5);
    }
}

/// A fog in a material's volume is applied by the path engine (no warning), as is a
/// volumeFog through the volume sampler; a fog in a volume list with a shader that is not
/// affine (`mib_volume`) is named for the path engine, which leaves it out; a physical fog
/// of a water type and a volumeFog with a cone dropoff are not named (both rendered).
#[test]
fn fogs_are_named_in_warnings_for_the_path_engine_and_physical_water() {
    let text = format!(
        "{LIBS}shader \"env\" \"maya_envfog\" (\"physicalFog\" on, \"fogType\" 4)\n\
         shader \"lit\" \"adskMayaLightFog\" (\"density\" 0.5)\n\
         shader \"lam\" \"maya_lambert\" ()\n\
         material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"lam.outColor\")\n\
         volume \"maya_volumesampler\" (\"volumeShader\" = \"env\") end material\n\
         shader \"mibv\" \"mib_volume\" (\"max\" 20)\n\
         material \"m2\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"lam.outColor\")\n\
         volume = \"lit\" = \"mibv\" end material"
    );
    let c = compile("", &text, &["m", "m2"], "");
    let warnings = maya::fog::fog_warnings(&c.shading);
    let messages: Vec<&str> = warnings.iter().map(|w| w.message.as_str()).collect();
    assert!(!messages.iter().any(|m| m.contains("maya_envfog") && m.contains("path engine")), "{messages:?}");
    assert!(!messages.iter().any(|m| m.contains("water")), "the water is rendered: {messages:?}");
    assert!(messages.iter().any(|m| m.contains("adskMayaLightFog") && m.contains("path engine")), "{messages:?}");
    assert!(!messages.iter().any(|m| m.contains("adskMayaLightFog") && m.contains("water")), "{messages:?}");
    // A volumeFog in a shading group's volume, with a cone dropoff: applied by the path
    // engine, no warning.
    let text = format!(
        "{LIBS}shader \"vf\" \"maya_volumefog\" (\"dropoffShape\" 3)\n\
         shader \"lam\" \"maya_lambert\" ()\n\
         material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"lam.outColor\")\n\
         volume \"maya_volumesampler\" (\"volumeShader\" = \"vf.outColor\") end material"
    );
    let c = compile("", &text, &["m"], "");
    assert!(c.messages.is_empty(), "{:#?}", c.messages);
    let warnings = maya::fog::fog_warnings(&c.shading);
    let messages: Vec<&str> = warnings.iter().map(|w| w.message.as_str()).collect();
    assert!(!messages.iter().any(|m| m.contains("maya_volumefog") && m.contains("path engine")), "{messages:?}");
    assert!(messages.is_empty(), "a cone dropoff is rendered: {messages:?}");
    // The same fog as the camera's volume: the path engine applies it.
    let body = format!(
        "{LIBS}shader \"envcam\" \"maya_envfog\" (\"saturationDistance\" 10)\n\
         shader \"lam\" \"maya_lambert\" ()\n\
         material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"lam.outColor\") end material"
    );
    let c = support::maya::compile_with_camera("volume = \"envcam\"", "", &body, &["m"], "");
    assert!(c.shading.volume.is_some(), "the camera has a volume");
    let warnings = maya::fog::fog_warnings(&c.shading);
    assert!(warnings.is_empty(), "{:?}", warnings.iter().map(|w| &w.message).collect::<Vec<_>>());
}

/// envFog's `useLayer`/`layer` (both name families): a constant layer of ½ halves the
/// fog's density (20 units of a 100-unit saturation: α = 0.1 instead of 0.2); a U ramp
/// (black at u = 0, white at 1, alpha its luminance) on `layer` scales it by the eye ray's
/// screen u — the centre of the image ½ (α = 0.1), its right edge 1 (α = 0.2), a quarter
/// in from the left ¼ (α = 0.05); `useLayer` off ignores the layer. The camera's volume
/// runs on an eye ray from the camera over 20 units with nothing behind (black), so the
/// result is α × the white fog (1e-5).
#[test]
fn env_fog_layer_scales_the_fog_across_the_view() {
    let ramp = r#"shader "ramp1" "maya_ramp" ("type" 1, "interpolation" 1, "alphaIsLuminance" on,
        "colorEntryList" [ { "position" 0, "color" 0 0 0 }, { "position" 1, "color" 1 1 1 } ])"#;
    for name in ["maya_envfog", "adskMayaEnvFog"] {
        let run_fog = |params: &str, screen_x: f32| -> glam::Vec4 {
            let body = format!(
                "{LIBS}{ramp}\nshader \"env\" \"{name}\" (\"saturationDistance\" 100{params})\n\
                 shader \"lam\" \"maya_lambert\" ()\n\
                 material \"m\" opaque \"maya_shadingengine\" (\"surfaceShader\" = \"lam.outColor\") end material"
            );
            let c = support::maya::compile_with_camera("volume = \"env\"", "", &body, &["m"], "");
            assert!(c.messages.is_empty(), "{:#?}", c.messages);
            // The eye ray through screen x (−1 left edge, 0 centre, 1 right edge) at
            // the image's middle height: camera space (x·half width, 0, −1).
            let to_world = c.shading.world_to_camera.inverse();
            let dir = to_world
                .transform_vector3a(glam::Vec3A::new(screen_x * c.shading.image_plane.x, 0.0, -1.0))
                .normalize();
            let org = to_world.transform_point3a(glam::Vec3A::ZERO);
            let state = shader::State {
                ray_type: shader::RayType::Eye,
                org,
                dir,
                dist: 20.0,
                point: org + dir * 20.0,
                ior_in: 1.0,
                ior: 1.0,
                child_dist: f32::INFINITY,
                ..shader::State::default()
            };
            support::maya::run_in(&c.shading, &Empty::default(), c.shading.volume.expect("camera volume"), state)
                .color()
        };
        assert_rgb(run_fog("", 0.3), [0.2; 3], 1e-5);
        assert_rgb(run_fog(", \"useLayer\" on, \"layer\" 0.5", 0.3), [0.1; 3], 1e-5);
        assert_rgb(run_fog(", \"useLayer\" off, \"layer\" 0.5", 0.3), [0.2; 3], 1e-5);
        assert_rgb(run_fog(", \"useLayer\" on, \"layer\" 0", 0.3), [0.0; 3], 1e-5);
        let layered = ", \"useLayer\" on, \"layer\" = \"ramp1.outAlpha\"";
        assert_rgb(run_fog(layered, 0.0), [0.1; 3], 1e-5);
        assert_rgb(run_fog(layered, 1.0), [0.2; 3], 1e-5);
        assert_rgb(run_fog(layered, -0.5), [0.05; 3], 1e-5);
    }
}
