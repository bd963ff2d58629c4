//! `df::measured_factor` of float textures the tests write (EXR, beside a module they
//! write, in the target's temporary directory): its base scaled by the texture read at
//! u = θ′·2/π (θ′ between a direction and the half vector) and v = θ″·2/π (θ″ between the
//! normal and the half vector), bilinearly between texel centres. Each test states its
//! tolerance.

use std::path::PathBuf;

use bsdf::testing::{albedo, incidences, standard_checks};
use bsdf::Rgb;
use glam::Vec3A;

use crate::mdl_support::{compile_text_with, get};

/// The module the tests compile (`factor_test`), with its materials.
const MODULE: &str = r#"mdl 1.7;
import ::df::*;

export material constant_factor() = material(surface: material_surface(
    scattering: df::measured_factor(values: texture_2d("constant.exr"), base: df::normalized_mix(
        df::bsdf_component[](df::bsdf_component(0.5, df::diffuse_reflection_bsdf()),
            df::bsdf_component(0.5, df::microfacet_ggx_smith_bsdf(roughness_u: 0.3)))))));
export material constant_tint() = material(surface: material_surface(
    scattering: df::tint(color(0.8, 0.5, 0.25), df::normalized_mix(
        df::bsdf_component[](df::bsdf_component(0.5, df::diffuse_reflection_bsdf()),
            df::bsdf_component(0.5, df::microfacet_ggx_smith_bsdf(roughness_u: 0.3)))))));
export material u_mirror() = material(surface: material_surface(
    scattering: df::measured_factor(values: texture_2d("./u_ramp.exr"), base: df::specular_bsdf())));
export material v_lambert() = material(surface: material_surface(
    scattering: df::measured_factor(values: texture_2d("v_ramp.exr"), base: df::diffuse_reflection_bsdf())));
export material lambert() = material(surface: material_surface(scattering: df::diffuse_reflection_bsdf()));
export material rough() = material(surface: material_surface(
    scattering: df::measured_factor(values: texture_2d("varying.exr"),
        base: df::microfacet_ggx_smith_bsdf(roughness_u: 0.4, roughness_v: 0.2))));
export material chosen(uniform texture_2d values = texture_2d("constant.exr")) = material(surface: material_surface(
    scattering: df::measured_factor(values: values, base: df::specular_bsdf())));
export material constant_mirror() = material(surface: material_surface(
    scattering: df::measured_factor(values: texture_2d("constant.exr"), base: df::specular_bsdf())));
export material invalid() = material(surface: material_surface(
    scattering: df::measured_factor(values: texture_2d(), base: df::diffuse_reflection_bsdf())));
export material glass_factor() = material(ior: color(1.5), surface: material_surface(
    scattering: df::measured_factor(values: texture_2d("varying.exr"),
        base: df::microfacet_ggx_smith_bsdf(roughness_u: 0.3, mode: df::scatter_reflect_transmit))));
export material glass_ones() = material(ior: color(1.5), surface: material_surface(
    scattering: df::measured_factor(values: texture_2d("ones.exr"),
        base: df::microfacet_ggx_smith_bsdf(roughness_u: 0.3, mode: df::scatter_reflect_transmit))));
export material transl_factor() = material(thin_walled: true, surface: material_surface(
    scattering: df::measured_factor(values: texture_2d("varying.exr"), base: df::diffuse_transmission_bsdf())));
export material transl_ones() = material(thin_walled: true, surface: material_surface(
    scattering: df::measured_factor(values: texture_2d("ones.exr"), base: df::diffuse_transmission_bsdf())));
"#;

/// A module (`factor_by_hit`) choosing `values` by a condition of the hit: not MDL (the
/// parameter is uniform), in a module of its own as it fails to load.
const BY_HIT: &str = r#"mdl 1.7;
import ::df::*;
import ::state::*;

export material by_hit() = material(surface: material_surface(
    scattering: df::measured_factor(values: state::texture_coordinate(0).x > 0.5 ?
        texture_2d("u_ramp.exr") : texture_2d("constant.exr"), base: df::specular_bsdf())));
"#;

/// The constant texture's colour.
const CONSTANT: [f32; 3] = [0.8, 0.5, 0.25];
/// The u ramp's left (a) and right (b) texels; the v ramp's bottom (c) and top (d) ones.
const A: [f32; 3] = [0.9, 0.5, 0.3];
const B: [f32; 3] = [0.1, 0.7, 1.0];
const C: [f32; 3] = [1.0, 0.6, 0.2];
const D: [f32; 3] = [0.2, 0.3, 0.9];
/// The 3 × 3 texture of varying factors ≤ 1, rows as the file stores them (the top first).
const VARYING: [[[f32; 3]; 3]; 3] = [[A, B, [1.0; 3]], [C, D, [0.3; 3]], [[0.05; 3], B, C]];

/// The directory of the written module and textures (each test writes the same bytes).
fn written() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("mdl_measured_factor");
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, bytes: &[u8]| {
        // Written under a unique name and renamed: a test reading it never sees half a file.
        let tmp = dir.join(format!("{name}.{:?}", std::thread::current().id()));
        std::fs::write(&tmp, bytes).unwrap();
        std::fs::rename(&tmp, dir.join(name)).unwrap();
    };
    write("factor_test.mdl", MODULE.as_bytes());
    write("factor_by_hit.mdl", BY_HIT.as_bytes());
    // Rows as the file stores them: the top row first.
    let exr = |name: &str, rows: &[&[[f32; 3]]]| {
        let (w, h) = (rows[0].len() as u32, rows.len() as u32);
        let img = image::Rgb32FImage::from_fn(w, h, |x, y| image::Rgb(rows[y as usize][x as usize]));
        let tmp = dir.join(format!("{:?}.{name}", std::thread::current().id()));
        img.save(&tmp).unwrap();
        std::fs::rename(&tmp, dir.join(name)).unwrap();
    };
    exr("constant.exr", &[&[CONSTANT; 3], &[CONSTANT; 3]]);
    exr("u_ramp.exr", &[&[A, B]]);
    exr("v_ramp.exr", &[&[D], &[C]]);
    let varying: Vec<&[[f32; 3]]> = VARYING.iter().map(|row| &row[..]).collect();
    exr("varying.exr", &varying);
    exr("ones.exr", &[&[[1.0; 3]; 2], &[[1.0; 3]; 2]]);
    dir
}

/// Compiles `.mi` shaders of the written module.
fn compile(text: &str) -> (material::mdl_modules::MdlMaterials, scene::Library, Vec<String>) {
    compile_text_with(text, &[written()])
}

/// A direction at `deg` from the normal and azimuth `phi` (radians).
fn dir(deg: f32, phi: f32) -> Vec3A {
    let t = deg.to_radians();
    Vec3A::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
}

/// A constant texture of colour c is `df::tint(c)` of the same base (a Lambertian and GGX
/// mix): equal BSDF values at pairs of directions within 1e-5 of the larger.
#[test]
fn a_constant_texture_is_the_tint_of_its_colour() {
    let (mdl, lib, diags) = compile(
        r#"shader "f" "mdl::factor_test::constant_factor" ()
shader "t" "mdl::factor_test::constant_tint" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let (f, t) = (get(&mdl, &lib, "f"), get(&mdl, &lib, "t"));
    let pairs = [(0.0f32, 30.0f32, 1.0f32), (37.0, 72.0, 2.5), (80.0, 10.0, 0.2), (55.0, 55.0, 3.1), (20.0, 25.0, 3.0)];
    for (a, b, phi) in pairs {
        let (wo, wi) = (dir(a, 0.0), dir(b, phi));
        let (x, y) = (f.bsdf(wo).eval(wo, wi), t.bsdf(wo).eval(wo, wi));
        let scale = x.max_element().max(y.max_element());
        assert!(scale > 0.0 && (x - y).abs().max_element() <= 1e-5 * scale, "{a}°, {b}°: {x:?} vs {y:?}");
    }
}

/// A texture varying in u (two texels a, b) over a mirror (h = n, so u = θ·2/π, v = 0)
/// reflects a + (b − a) t, t = 2u − ½ clamped, at 30° and 60° (1e-4); one varying in v
/// (bottom c, top d) over a white Lambertian scales it by c + (d − c) t, t = 2v − ½, v the
/// half vector's angle to the normal ·2/π, at half-vector angles of 30° and 60° (1e-4).
#[test]
fn a_varying_texture_gives_the_factor_at_its_angles() {
    let (mdl, lib, diags) = compile(
        r#"shader "u" "mdl::factor_test::u_mirror" ()
shader "v" "mdl::factor_test::v_lambert" ()
shader "l" "mdl::factor_test::lambert" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let ramp = |lo: [f32; 3], hi: [f32; 3], deg: f32| {
        let t = (2.0 * deg / 90.0 - 0.5).clamp(0.0, 1.0);
        Rgb::from(lo) + (Rgb::from(hi) - Rgb::from(lo)) * t
    };
    let u = get(&mdl, &lib, "u");
    for deg in [30.0f32, 60.0] {
        let wo = dir(deg, 0.0);
        let got = albedo(&u.bsdf(wo), wo, 16);
        let want = ramp(A, B, deg);
        assert!((got - want).abs().max_element() <= 1e-4, "{deg}°: {got:?} vs {want:?}");
    }
    let (v, l) = (get(&mdl, &lib, "v"), get(&mdl, &lib, "l"));
    // (wo, wi) with the half vector at 30° (60° and 0°) and at 60° (80° and 40°) from n.
    for (a, b, half) in [(60.0f32, 0.0f32, 30.0f32), (80.0, 40.0, 60.0)] {
        let (wo, wi) = (dir(a, 0.0), dir(b, 0.0));
        let (fv, fl) = (v.bsdf(wo).eval(wo, wi), l.bsdf(wo).eval(wo, wi));
        let got = fv / fl;
        let want = ramp(C, D, half);
        assert!((got - want).abs().max_element() <= 1e-4, "h at {half}°: {got:?} vs {want:?}");
    }
}

/// A varying texture of factors ≤ 1 over an anisotropic GGX lobe reflects at most what it
/// receives (albedo ≤ 1 + 1 % at the standard incidences) and passes the standard checks
/// (reciprocity, χ² sampling); the invalid texture scatters nothing.
#[test]
fn measured_factors_pass_the_furnace_and_the_standard_checks() {
    let (mdl, lib, diags) = compile(
        r#"shader "r" "mdl::factor_test::rough" ()
shader "i" "mdl::factor_test::invalid" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let r = get(&mdl, &lib, "r");
    for wo in incidences() {
        let a = albedo(&r.bsdf(wo), wo, 20_000);
        assert!(a.max_element() <= 1.01, "albedo {a:?} at {wo:?}");
    }
    standard_checks(&r.bsdf(Vec3A::Z), 1.01, "measured_factor_rough");
    let i = get(&mdl, &lib, "i");
    let wo = Vec3A::Z;
    assert_eq!(i.bsdf(wo).eval(wo, dir(30.0, 0.0)), Rgb::ZERO);
}

/// The factor [`VARYING`] holds at u, v ∈ [0, 1], read independently of mira's table (in
/// f64): bilinear between texel centres (i + ½)/3, clamped at the edges, v from the bottom
/// row (the file's last).
fn varying_at(u: f64, v: f64) -> Rgb {
    let axis = |t: f64| {
        let at = (t * 3.0 - 0.5).clamp(0.0, 2.0);
        let i = (at.floor() as usize).min(1);
        (i, at - i as f64)
    };
    let ((x, tx), (y, ty)) = (axis(u), axis(v));
    let texel = |x: usize, y: usize| VARYING[2 - y][x].map(f64::from);
    let mut out = [0.0f32; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let bottom = texel(x, y)[k] * (1.0 - tx) + texel(x + 1, y)[k] * tx;
        let top = texel(x, y + 1)[k] * (1.0 - tx) + texel(x + 1, y + 1)[k] * tx;
        *o = (bottom * (1.0 - ty) + top * ty) as f32;
    }
    Rgb::from(out)
}

/// The index on `w`'s side of a solid of index 1.5 (inside below), or 1 for a thin sheet.
fn index(solid: bool, w: Vec3A) -> f32 {
    if solid && w.z < 0.0 {
        1.5
    } else {
        1.0
    }
}

/// On a transmitted pair the factor is read at the half vector of the pair with the
/// transmitted direction mirrored to ωo's side, h = (ωo + ω̃i)/|ωo + ω̃i| — what the MDL
/// SDK's libbsdf takes for every factor (`compute_half_vector` without refraction: "use
/// corresponding reflection direction"), `measured_factor` included — u = θ′·2/π with θ′
/// between ωo and h, v = θ″·2/π with θ″ between the normal and h: over rough solid glass
/// (GGX 0.3, index 1.5) and over a thin diffuse transmission, the BSDF over that of the
/// same base under a texture of ones equals the bilinear factor at those angles within
/// 1e-4 (relative) at five pairs each way through the surface (at least seven of the ten transmit). Both pass the white furnace
/// (n²-weighted radiance through the solid, ≤ 1 + 1 % from both sides at 0°, 37° and 72°)
/// and the generalised reciprocity f(ωo, ωi)/n(ωo)² = f(ωi, ωo)/n(ωi)² (1e-3 relative,
/// values under 0.01 within 1e-5 absolute) over 30 × 30 pairs.
#[test]
fn a_transmitted_pair_reads_the_factor_at_its_mirrored_half_vector() {
    let (mdl, lib, diags) = compile(
        r#"shader "gf" "mdl::factor_test::glass_factor" ()
shader "g1" "mdl::factor_test::glass_ones" ()
shader "tf" "mdl::factor_test::transl_factor" ()
shader "t1" "mdl::factor_test::transl_ones" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let pairs =
        [(10.0f32, 160.0f32, 1.0f32), (40.0, 130.0, 2.5), (65.0, 110.0, 0.3), (30.0, 170.0, 4.0), (75.0, 140.0, 3.1)];
    for (solid, with, ones) in [(true, "gf", "g1"), (false, "tf", "t1")] {
        let (f, one) = (get(&mdl, &lib, with), get(&mdl, &lib, ones));
        let mut checked = 0;
        for (a, b, phi) in pairs {
            for (wo, wi) in [(dir(a, 0.0), dir(b, phi)), (dir(180.0 - a, 0.0), dir(180.0 - b, phi))] {
                let (x, y) = (f.bsdf(wo).eval(wo, wi), one.bsdf(wo).eval(wo, wi));
                // From inside the solid some pairs are beyond the critical angle.
                if y.min_element() < 1e-4 {
                    continue;
                }
                checked += 1;
                let up = |w: Vec3A| Vec3A::new(w.x, w.y, w.z.abs());
                let h = (up(wo) + up(wi)).normalize();
                let angle = |c: f32| f64::from(c.clamp(-1.0, 1.0).acos()) * std::f64::consts::FRAC_2_PI;
                let want = varying_at(angle(up(wo).dot(h)), angle(h.z));
                let got = x / y;
                assert!(
                    (got - want).abs().max_element() <= 1e-4 * want.max_element(),
                    "{with} {a}°, {b}°: {got:?} vs {want:?}"
                );
            }
        }
        assert!(checked >= 7, "{with}: {checked} pairs transmit");
        for wo in incidences() {
            for wo in [wo, -wo] {
                let b = f.bsdf(wo);
                let n = 20_000;
                let mut sum = Rgb::ZERO;
                for k in 0..n {
                    let (u, c) = bsdf::testing::r3(k);
                    if let Some(s) = b.sample(wo, u, c) {
                        sum += s.weight() * (index(solid, s.wi) / index(solid, wo)).powi(2);
                    }
                }
                let e = sum / n as f32;
                assert!(e.max_element() <= 1.01 && e.min_element() >= 0.0, "{with} at {wo}: {e}");
            }
        }
        let sphere = |i: u32| {
            let u = bsdf::testing::r2(i);
            let z = 1.0 - 2.0 * u.x;
            let s = (1.0 - z * z).max(0.0).sqrt();
            Vec3A::new(s * (std::f32::consts::TAU * u.y).cos(), s * (std::f32::consts::TAU * u.y).sin(), z)
        };
        let b = f.bsdf(Vec3A::Z);
        for i in 0..30 {
            for j in 0..30 {
                let (a, c) = (sphere(i + 1), sphere(j + 301));
                let f1 = b.eval(a, c) / index(solid, a).powi(2);
                let f2 = b.eval(c, a) / index(solid, c).powi(2);
                let scale = f1.max_element().max(f2.max_element()).max(1e-2);
                assert!((f1 - f2).abs().max_element() <= 1e-3 * scale, "{with}: f({a}, {c}) {f1} vs {f2}");
            }
        }
    }
}

/// A `texture_2d` parameter of the material set from the `.mi` file is the constant texture
/// it names: `values` set to the u ramp over a mirror reflects exactly what the material
/// naming the ramp in its body reflects (albedo at 30° and 60°, 1e-6), and left at its
/// default (the constant texture) what the constant mirror reflects (1e-6). `values` is
/// a uniform parameter: a choice between textures by a condition of the hit is an error at
/// its line and column of the module.
#[test]
fn a_texture_set_from_the_mi_file_is_the_constant_case() {
    let (mdl, lib, diags) = compile(
        r#"shader "set" "mdl::factor_test::chosen" ("values" "u_ramp.exr")
shader "default" "mdl::factor_test::chosen" ()
shader "u" "mdl::factor_test::u_mirror" ()
shader "c" "mdl::factor_test::constant_mirror" ()"#,
    );
    assert!(diags.is_empty(), "{diags:#?}");
    let [set, default, u, c] = ["set", "default", "u", "c"].map(|n| get(&mdl, &lib, n));
    for deg in [30.0f32, 60.0] {
        let wo = dir(deg, 0.0);
        for (a, b, what) in [(set, u, "set"), (default, c, "default")] {
            let (x, y) = (albedo(&a.bsdf(wo), wo, 16), albedo(&b.bsdf(wo), wo, 16));
            assert!((x - y).abs().max_element() <= 1e-6, "{what} at {deg}°: {x:?} vs {y:?}");
        }
    }
    let (_, _, diags) = compile(r#"shader "h" "mdl::factor_by_hit::by_hit" ()"#);
    assert!(
        diags.iter().any(
            |d| d.contains("factor_by_hit.mdl:6:37: error: parameter `values` of `df::measured_factor` is uniform")
        ),
        "{diags:#?}"
    );
}
