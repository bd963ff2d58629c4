//! `state::` object-space transforms, `object_id` and `animation_time` in module materials
//! (tests/mdl/object_space.mdl), evaluated per hit against the same transforms computed
//! with glam from the shading state's matrices (within 1e-5).

use crate::mdl_support;

use bsdf::Rgb;
use glam::{Affine3A, Mat4, Quat, Vec3, Vec3A};
use material::{SurfaceMaterial, Varying};
use mdl_support::{close, compile_text, get};
use shader::State;

/// Object → world: scaled (2, 1, 0.5), turned 30° about (1, 2, 3), moved by (4, −1, 2).
fn placement() -> Affine3A {
    Affine3A::from_scale_rotation_translation(
        Vec3::new(2.0, 1.0, 0.5),
        Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 30f32.to_radians()),
        Vec3::new(4.0, -1.0, 2.0),
    )
}

/// A hit at world point `p` of an instance placed by `to_world`.
fn hit(p: Vec3A, to_world: Affine3A) -> State {
    State {
        point: p,
        normal: Vec3A::Z,
        normal_geom: Vec3A::Z,
        dir: -Vec3A::Z,
        object_to_world: to_world,
        world_to_object: to_world.inverse(),
        ..State::default()
    }
}

/// The radiance the material emits at `state`.
fn emitted(m: &SurfaceMaterial, state: &State) -> Rgb {
    let Varying::Evaluated(e) = &m.varying else { panic!("{} is not evaluated per hit: {:?}", m.name, m.varying) };
    let mut h = m.constant();
    e.0.apply(state, &mut h);
    h.emission
}

fn rgb(v: Vec3) -> Rgb {
    Rgb::new(v.x, v.y, v.z)
}

fn compiled(params: &str) -> (material::mdl_modules::MdlMaterials, scene::Library) {
    let (mdl, lib, diags) = compile_text(&format!(r#"shader "m" "mdl::object_space::transformed" ({params})"#));
    assert!(diags.is_empty(), "{params}: {diags:#?}");
    (mdl, lib)
}

#[test]
fn points_vectors_normals_scales_and_matrices_follow_the_instance() {
    let m = placement();
    let inv = m.inverse();
    let v = Vec3::new(1.0, 2.0, 3.0);
    let state = hit(Vec3A::new(0.3, -0.2, 0.7), m);
    let world_normal = Mat4::from(m).inverse().transpose();
    let scale = (m.matrix3.x_axis.length() + m.matrix3.y_axis.length() + m.matrix3.z_axis.length()) / 3.0;
    let inv_scale = (inv.matrix3.x_axis.length() + inv.matrix3.y_axis.length() + inv.matrix3.z_axis.length()) / 3.0;
    assert!((scale - 7.0 / 6.0).abs() < 1e-5);
    let cases = [
        (0, rgb(inv.transform_point3(v))),
        (1, rgb(inv.transform_vector3(v))),
        // Normals go by the inverse transpose of the object-to-world's inverse: mᵀ.
        (2, rgb(Mat4::from(m).transpose().transform_vector3(v))),
        (3, rgb(m.transform_point3(v))),
        (4, Rgb::splat(inv_scale)),
        (5, rgb((Mat4::from(m) * v.extend(1.0)).truncate())),
    ];
    for (which, want) in cases {
        let (mdl, lib) = compiled(&format!(r#""which" {which}"#));
        let got = emitted(get(&mdl, &lib, "m"), &state);
        assert!(close(got, want, 1e-5), "which {which}: {got:?} vs {want:?}");
    }
    // A normal to world space and back is where it started (inverse transposes compose).
    let n = world_normal.transform_vector3(Mat4::from(m).transpose().transform_vector3(v));
    assert!((n - v).length() < 1e-5);
}

/// Between spaces that are the same (internal is world in mira) the value is unchanged
/// and constant: nothing is evaluated per hit.
#[test]
fn a_transform_within_one_space_is_the_identity() {
    let text = r#"shader "m" "mdl::object_space::cell" ("object" false, "offset" 0)"#;
    let (mdl, lib, diags) = compile_text(text);
    assert!(diags.is_empty(), "{diags:#?}");
    let m = get(&mdl, &lib, "m");
    let got = emitted(m, &hit(Vec3A::new(1.3, -0.2, 0.6), placement()));
    assert!(close(got, Rgb::new(2.0, -1.0, 1.0), 1e-6), "{got:?}");
}

/// The same object point of two instances placed apart gives the same object-space cell
/// and different world-space ones.
#[test]
fn object_space_is_the_same_for_two_instances_placed_apart() {
    let object_point = Vec3A::new(0.3, 0.6, -0.1);
    let (a, b) = (placement(), Affine3A::from_translation(Vec3::new(-5.0, 3.0, 1.0)) * placement());
    for (object, same) in [(true, true), (false, false)] {
        let text = format!(r#"shader "m" "mdl::object_space::cell" ("object" {object})"#);
        let (mdl, lib, diags) = compile_text(&text);
        assert!(diags.is_empty(), "{diags:#?}");
        let m = get(&mdl, &lib, "m");
        let ca = emitted(m, &hit(a.transform_point3a(object_point), a));
        let cb = emitted(m, &hit(b.transform_point3a(object_point), b));
        assert_eq!(close(ca, cb, 1e-5), same, "object {object}: {ca:?} {cb:?}");
        if object {
            assert!(close(ca, Rgb::new(4.0, 5.0, 3.0), 1e-5), "{ca:?}");
        }
    }
}

#[test]
fn object_id_is_the_instance_label_and_animation_time_the_ray_time() {
    let (mdl, lib, diags) = compile_text(r#"shader "m" "mdl::object_space::ids" ()"#);
    assert!(diags.is_empty(), "{diags:#?}");
    let mut s = hit(Vec3A::ZERO, Affine3A::IDENTITY);
    s.label = 17;
    s.time = 0.375;
    let got = emitted(get(&mdl, &lib, "m"), &s);
    assert!(close(got, Rgb::new(17.0, 0.375, 0.0), 1e-6), "{got:?}");
    // Black where nothing is set: these values are read at the hit, not folded.
    assert!(close(emitted(get(&mdl, &lib, "m"), &State::default()), Rgb::ZERO, 0.0));
}

/// `state::transform`'s matrix of an instance used other than times a vector — indexed,
/// squared, transposed, times a row vector, times its inverse, times a constant matrix and
/// a scalar and added — against the same products computed with glam from the instance's
/// placement (within 1e-4; the values reach about 30).
#[test]
fn a_matrix_of_the_hit_is_indexed_multiplied_and_transposed() {
    let placed = placement();
    let m = Mat4::from(placed);
    let v = Vec3::new(1.0, 2.0, 3.0);
    let p = v.extend(1.0);
    let c = Mat4::from_cols(
        glam::Vec4::new(2.0, 0.0, 0.0, 0.0),
        glam::Vec4::new(0.0, 3.0, 0.0, 0.0),
        glam::Vec4::new(0.0, 0.0, 4.0, 0.0),
        glam::Vec4::new(1.0, 1.0, 1.0, 1.0),
    );
    let row = |j: usize| m.row(j);
    let cases = [
        (0, m.w_axis.truncate()),
        (1, (m * m * p).truncate()),
        (2, row(0).truncate()),
        (3, Vec3::new(p.dot(m.x_axis), p.dot(m.y_axis), p.dot(m.z_axis))),
        (4, v),
        (5, ((c * m + m * 0.5) * p).truncate()),
        (6, Vec3::new(m.x_axis.y, m.y_axis.z, m.z_axis.x)),
    ];
    let state = hit(Vec3A::new(0.3, -0.2, 0.7), placed);
    for (which, want) in cases {
        let text = format!(r#"shader "m" "mdl::object_space::matrices" ("which" {which})"#);
        let (mdl, lib, diags) = compile_text(&text);
        assert!(diags.is_empty(), "which {which}: {diags:#?}");
        let got = emitted(get(&mdl, &lib, "m"), &state);
        assert!(close(got, rgb(want), 1e-4), "which {which}: {got:?} vs {want:?}");
    }
}
