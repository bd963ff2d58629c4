//! Measured BSDFs (`bsdf::measured_bsdf`): the MBSDF reader on written and hostile files,
//! the grid's interpolation and symmetry, and the measured lobe in a lobe sum (furnace,
//! reciprocity, χ² sampling). Each test states its tolerance.

use std::f32::consts::{FRAC_PI_2, PI};

use bsdf::measured_bsdf::reader::{encode, read, Block, MAX_VALUES};
use bsdf::measured_bsdf::{intern, MeasuredBsdf, MeasuredLobe, Part};
use bsdf::testing::{albedo, chi_square, incidences, standard_checks};
use bsdf::{Bsdf, Lobe, Lobes, Rgb};
use glam::Vec3A;

/// The lobe sum of one measured lobe of weight `w`.
fn lobe_of(m: MeasuredBsdf, reflect: bool, transmit: bool, w: f32) -> Bsdf {
    let mut l = Lobes::default();
    assert!(l.push(Rgb::splat(w), Lobe::Measured(MeasuredLobe::new(intern(m).unwrap(), reflect, transmit).unwrap())));
    Bsdf::Lobes(l)
}

/// A grid of `nt`² × `np` values of `f(θ_in, θ_out, Δφ)` at the sample positions.
fn grid(nt: usize, np: usize, f: impl Fn(f32, f32, f32) -> f32) -> Vec<f32> {
    let mut v = Vec::with_capacity(nt * nt * np);
    for a in 0..nt {
        for b in 0..nt {
            for k in 0..np {
                let t = |i: usize| i as f32 * FRAC_PI_2 / nt as f32;
                v.push(f(t(a), t(b), k as f32 * PI / np as f32));
            }
        }
    }
    v
}

/// A Phong-like peak about the mirror direction plus a floor: symmetric in θ_in, θ_out.
fn glossy(ti: f32, to: f32, dphi: f32) -> f32 {
    let cos_alpha = ti.cos() * to.cos() - ti.sin() * to.sin() * dphi.cos();
    0.04 + 0.5 * cos_alpha.max(0.0).powi(8)
}

/// Directions at `deg` degrees from the normal and azimuth `phi` (radians).
fn dir(deg: f32, phi: f32) -> Vec3A {
    let t = deg.to_radians();
    Vec3A::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
}

/// A constant grid c is a Lambertian of albedo π c: f = c at every pair of directions
/// (1e-6 relative), and its sampling is exactly the cosine distribution, so that every
/// sample's weight f cos/pdf is π c and the estimated albedo is π c within 1e-4 (relative)
/// at 0°, 37° and 72°; the same through the surface for a constant transmission part.
#[test]
fn a_constant_grid_is_a_lambertian_of_albedo_pi_c() {
    let c = 0.2;
    let values = vec![c; 5 * 5 * 7];
    let part = || Part::new(5, 7, 1, values.clone());
    let r = lobe_of(MeasuredBsdf { reflection: Some(part()), transmission: None }, true, false, 1.0);
    for (a, b, p) in [(0.0, 10.0, 0.3), (37.0, 80.0, 2.0), (89.0, 45.0, 3.1), (60.0, 60.0, 0.0)] {
        let (wo, wi) = (dir(a, 0.1), dir(b, 0.1 + p));
        assert!((r.eval(wo, wi) - Rgb::splat(c)).abs().max_element() < 1e-6 * c);
        assert_eq!(r.eval(wo, -wi), Rgb::ZERO, "nothing is transmitted");
    }
    for wo in incidences() {
        let a = albedo(&r, wo, 4096);
        assert!((a - Rgb::splat(PI * c)).abs().max_element() < 1e-4 * PI * c, "{wo:?}: {a:?}");
    }
    let t = lobe_of(MeasuredBsdf { reflection: None, transmission: Some(part()) }, false, true, 1.0);
    for wo in incidences() {
        let a = albedo(&t, wo, 4096);
        assert!((a - Rgb::splat(PI * c)).abs().max_element() < 1e-4 * PI * c, "{wo:?}: {a:?}");
        assert_eq!(t.eval(wo, Vec3A::new(wo.x, wo.y, wo.z)), Rgb::ZERO, "nothing is reflected");
    }
}

/// The grid is read at its samples exactly (a non-constant RGB grid, 1e-6) and linearly
/// between neighbouring samples along each axis (the midpoint of two Δφ samples is their
/// mean); past the last θ sample it is constant.
#[test]
fn the_grid_is_read_at_its_samples_and_trilinearly_between() {
    let (nt, np) = (4, 6);
    let f = |ti: f32, to: f32, dphi: f32| 0.1 + ti + to + 0.3 * dphi;
    let mut values = Vec::new();
    for v in grid(nt, np, f) {
        values.extend([v, 2.0 * v, 0.5 * v]);
    }
    let part = Part::new(nt, np, 3, values);
    let step = FRAC_PI_2 / nt as f32;
    let dstep = PI / np as f32;
    for (a, b, k) in [(0, 0, 0), (1, 3, 2), (3, 2, 5), (2, 2, 1)] {
        let want = f(a as f32 * step, b as f32 * step, k as f32 * dstep);
        let got = part.value(a as f32 * step, b as f32 * step, k as f32 * dstep);
        assert!((got - Rgb::new(want, 2.0 * want, 0.5 * want)).abs().max_element() < 1e-5, "{got:?} vs {want}");
    }
    let mid = part.value(step, 2.0 * step, 2.5 * dstep).x;
    let want = f(step, 2.0 * step, 2.5 * dstep);
    assert!((mid - want).abs() < 1e-5, "{mid} vs {want}");
    let last = part.value(3.0 * step, step, 0.0).x;
    assert!((part.value(FRAC_PI_2, step, 0.0).x - last).abs() < 1e-6);
}

/// A table that is not symmetric in θ_in, θ_out is made so (the mean of the two entries),
/// and the lobe is reciprocal.
#[test]
fn an_asymmetric_grid_is_made_reciprocal() {
    let values = grid(3, 4, |ti, _, _| 0.1 + ti);
    let part = Part::new(3, 4, 1, values);
    let step = FRAC_PI_2 / 3.0;
    let (x, y) = (part.value(0.0, 2.0 * step, 0.0).x, part.value(2.0 * step, 0.0, 0.0).x);
    assert!((x - y).abs() < 1e-7 && (x - (0.1 + step)).abs() < 1e-6, "{x} {y}");
}

/// A glossy grid (a peak about the mirror direction on a floor; 16² × 32 samples), alone
/// and with a transmission part, passes the standard checks: reciprocity (1e-4), albedo
/// below its bound, and χ² sampling of its density at 0°, 37° and 72°; a multiplier
/// scales f (1e-6).
#[test]
fn a_glossy_grid_is_reciprocal_and_samples_its_density() {
    let part = || Part::new(16, 32, 1, grid(16, 32, glossy));
    let r = lobe_of(MeasuredBsdf { reflection: Some(part()), transmission: None }, true, false, 1.0);
    standard_checks(&r, 1.0, "measured glossy");
    let both = MeasuredBsdf { reflection: Some(part()), transmission: Some(Part::new(8, 8, 1, vec![0.05; 8 * 8 * 8])) };
    let rt = lobe_of(both, true, true, 1.0);
    standard_checks(&rt, 1.0, "measured glossy and translucent");
    for wo in incidences() {
        chi_square(&rt, -wo);
    }
    let half = lobe_of(MeasuredBsdf { reflection: Some(part()), transmission: None }, true, false, 0.5);
    let (wo, wi) = (dir(30.0, 0.0), dir(40.0, 3.0));
    assert!((half.eval(wo, wi) - 0.5 * r.eval(wo, wi)).abs().max_element() < 1e-6);
}

/// A transmission part in a lobe that uses only reflection (`scatter_reflect`) scatters
/// nothing through, and the other way round.
#[test]
fn the_mode_chooses_the_parts() {
    let both = || MeasuredBsdf {
        reflection: Some(Part::new(4, 4, 1, vec![0.1; 64])),
        transmission: Some(Part::new(4, 4, 1, vec![0.2; 64])),
    };
    let (wo, wi) = (dir(20.0, 0.0), dir(50.0, 1.0));
    let r = lobe_of(both(), true, false, 1.0);
    let t = lobe_of(both(), false, true, 1.0);
    assert_eq!((r.eval(wo, wi).x, r.eval(wo, -wi).x), (0.1, 0.0));
    assert_eq!((t.eval(wo, wi).x, t.eval(wo, -wi).x), (0.0, 0.2));
    let a = albedo(&lobe_of(both(), true, true, 1.0), wo, 4096).x;
    assert!((a - 0.3 * PI).abs() < 1e-3, "{a}");
}

/// A file the test writes reads back: both parts, RGB and scalar, their grids as written
/// (symmetric ones unchanged), metadata lines skipped; negative values read as 0 with a
/// note.
#[test]
fn a_written_file_reads_back() {
    let refl = grid(3, 5, |ti, to, d| 0.1 + ti * to + d);
    let rgb: Vec<f32> = refl.iter().flat_map(|v| [*v, -0.5, 2.0 * v]).collect();
    let trans = vec![0.25f32; 2 * 2 * 3];
    let mut bytes = encode(
        Some(Block { channels: 3, res_theta: 3, res_phi: 5, values: &rgb }),
        Some(Block { channels: 1, res_theta: 2, res_phi: 3, values: &trans }),
    );
    // Metadata after the header line.
    let header = b"NVIDIA ARC MBSDF V1\n".len();
    bytes.splice(header..header, b"DATE=today\nCOMMENT=\"made by a test\"\n".iter().copied());
    let (m, notes) = read(&bytes).expect("a valid file");
    assert_eq!(notes, vec![format!("{} negative values read as 0", refl.len())]);
    let r = m.reflection.expect("reflection");
    let step = FRAC_PI_2 / 3.0;
    let got = r.value(step, 2.0 * step, PI / 5.0);
    let want = 0.1 + step * 2.0 * step + PI / 5.0;
    assert!((got - Rgb::new(want, 0.0, 2.0 * want)).abs().max_element() < 1e-5, "{got:?}");
    assert_eq!(m.transmission.expect("transmission").value(0.3, 1.0, 2.0), Rgb::splat(0.25));
}

/// Hostile files are errors at their byte offsets, never panics or huge allocations: every
/// truncation of a valid file past its header; a wrong header; an unknown type; zero
/// resolutions; grids larger than [`MAX_VALUES`] or whose size overflows; counts larger
/// than the bytes left; a NaN; stray bytes after the blocks.
#[test]
fn hostile_files_are_errors_at_their_offsets() {
    let values = vec![0.5f32; 2 * 2 * 3];
    let good = encode(Some(Block { channels: 1, res_theta: 2, res_phi: 3, values: &values }), None);
    let tag_end = b"NVIDIA ARC MBSDF V1\nMBSDF_DATA_REFLECTION=\n".len();
    for cut in tag_end..good.len() {
        let e = read(&good[..cut]).expect_err("a truncated file");
        assert!(e.offset <= cut && e.message.contains("ends inside"), "cut {cut}: {e}");
    }
    assert_eq!(read(b"NVIDIA ARC MBSDF V2\n").unwrap_err().offset, 0);
    let with = |kind: u32, rt: u32, rp: u32, tail: &[u8]| {
        let mut b = good[..tag_end].to_vec();
        for n in [kind, rt, rp] {
            b.extend_from_slice(&n.to_le_bytes());
        }
        b.extend_from_slice(tail);
        b
    };
    let cases: Vec<(Vec<u8>, &str, usize)> = vec![
        (with(7, 2, 3, &[]), "unknown value type 7", tag_end),
        (with(0, 0, 3, &[]), "resolution of 0", tag_end + 4),
        (with(1, 1 << 14, 1 << 14, &[]), "more than", tag_end + 4),
        (with(1, u32::MAX, u32::MAX, &[]), "more than", tag_end + 4),
        (with(0, 100, 100, &[0; 64]), "ends inside the block", tag_end + 12),
        (with(0, 1, 1, &f32::NAN.to_le_bytes()), "not a finite number", tag_end + 12),
        (with(0, 1, 1, &[0, 0, 0, 0, b'x']), "no `MBSDF_DATA_TRANSMISSION=`", tag_end + 16),
    ];
    for (bytes, says, at) in cases {
        let e = read(&bytes).expect_err(says);
        assert!(e.message.contains(says) && e.offset == at, "{says} at {at}: {e}");
    }
    const { assert!(MAX_VALUES < (1u64 << 14) * (1 << 14) * (1 << 14)) };
}
