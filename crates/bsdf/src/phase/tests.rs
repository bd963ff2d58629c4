//! Unit tests of the phase functions: normalisation, mean cosine and chi-square checks of
//! their sampling against their densities.

use super::*;
use crate::testing::{chi_square_limit_99, pooled_chi_square, r2};
use std::f64::consts::PI;

/// ∫ 2π f(cos) dcos over [−1, 1] by the midpoint rule over `n` cells.
fn over_sphere(n: usize, f: impl Fn(f32) -> f64) -> f64 {
    (0..n)
        .map(|i| {
            let c = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
            2.0 * PI * f(c as f32) * 2.0 / n as f64
        })
        .sum()
}

/// The chi-square statistic and its 99 % limit of `samples` directions drawn by `draw`
/// (from the sample number) around `dir_in` against the density of cos θ `density`: 40
/// bins of cos θ (expected counts by the midpoint rule, 1000 points a bin) × 8 of φ.
fn chi_square(dir_in: Vec3A, samples: u32, draw: impl Fn(u32) -> Vec3A, density: impl Fn(f32) -> f32) -> (f64, f64) {
    let frame = Frame::from_normal(dir_in);
    let (nc, np) = (40usize, 8usize);
    let mut observed = vec![0f64; nc * np];
    for i in 0..samples {
        let dir = draw(i);
        assert!((dir.length() - 1.0).abs() < 1e-4, "{dir:?}");
        let local = frame.to_local(dir);
        let c = ((local.z.clamp(-1.0, 1.0) + 1.0) * 0.5 * nc as f32).min(nc as f32 - 1.0) as usize;
        let phi = local.y.atan2(local.x).rem_euclid(2.0 * std::f32::consts::PI);
        let p = ((phi / (2.0 * std::f32::consts::PI)) * np as f32).min(np as f32 - 1.0) as usize;
        observed[c * np + p] += 1.0;
    }
    let mut expected = vec![0f64; nc * np];
    for c in 0..nc {
        let (sub, width) = (1000, 2.0 / nc as f64);
        let mass: f64 = (0..sub)
            .map(|k| {
                let x = -1.0 + width * (c as f64 + (k as f64 + 0.5) / sub as f64);
                2.0 * PI * f64::from(density(x as f32)) * width / f64::from(sub)
            })
            .sum();
        for p in 0..np {
            expected[c * np + p] = mass / np as f64 * f64::from(samples);
        }
    }
    let test = pooled_chi_square(&observed, &expected);
    (test.chi2, chi_square_limit_99(test.dof))
}

/// ∫ p dω = 1 within 1e-4 (midpoint rule, 200 000 cells) for backward, isotropic,
/// forward and strongly forward lobes, and the mean cosine is g within 1e-3.
#[test]
fn henyey_greenstein_is_normalised_with_mean_cosine_g() {
    for g in [-0.7f32, 0.0, 0.3, 0.9] {
        let hg = HenyeyGreenstein::new(g);
        let sum = over_sphere(200_000, |c| f64::from(hg.eval_cos(c)));
        assert!((sum - 1.0).abs() < 1e-4, "g {g}: {sum}");
        let mean = over_sphere(200_000, |c| f64::from(c) * f64::from(hg.eval_cos(c)));
        assert!((mean - f64::from(g)).abs() < 1e-3, "g {g}: mean cosine {mean}");
    }
}

/// Sampled directions follow the density (chi-square, 200 000 samples, below the 99 %
/// quantile); the returned pdf equals `eval` within 1e-4 (relative).
#[test]
fn henyey_greenstein_sampling_matches_its_density() {
    let dir_in = Vec3A::new(0.3, -0.4, 0.866).normalize();
    for g in [-0.6f32, 0.0, 0.5, 0.85] {
        let hg = HenyeyGreenstein::new(g);
        let (chi2, limit) = chi_square(
            dir_in,
            200_000,
            |i| {
                let (dir, pdf) = hg.sample(dir_in, r2(i));
                let expect = hg.eval(dir_in, dir);
                assert!((pdf - expect).abs() <= 1e-4 * expect.max(1e-3), "g {g}: pdf {pdf} vs eval {expect}");
                dir
            },
            |c| hg.eval_cos(c),
        );
        assert!(chi2 < limit, "g {g}: chi-square {chi2} (limit {limit})");
    }
}

/// A grey mixture of a forward (0.8, weight 0.6) and a backward (−0.4) lobe: normalised
/// and of mean cosine 0.6·0.8 − 0.4·0.4 = 0.32 (1e-4 and 1e-3), its `g` that mean;
/// sampled directions follow its density (chi-square) with the mixture's pdf (1e-4) and
/// weight exactly 1; five lobes keep four, the lightest two merged (the mean cosine kept
/// within 1e-6).
#[test]
fn a_mixture_of_lobes_is_normalised_keeps_its_mean_cosine_and_samples_its_density() {
    let phase = Phase::mixture(&[(0.6, 0.8), (0.4, -0.4)]);
    assert_eq!(phase.lobes().len(), 2);
    assert!(!phase.is_chromatic());
    assert!((phase.g - 0.32).abs() < 1e-6, "{phase:?}");
    let sum = over_sphere(200_000, |c| f64::from(phase.pdf_cos(c)));
    let mean = over_sphere(200_000, |c| f64::from(c) * f64::from(phase.pdf_cos(c)));
    assert!((sum - 1.0).abs() < 1e-4 && (mean - 0.32).abs() < 1e-3, "∫ {sum}, mean cosine {mean}");
    let dir_in = Vec3A::new(0.3, -0.4, 0.866).normalize();
    let (chi2, limit) = chi_square(
        dir_in,
        200_000,
        |i| {
            let s = phase.sample(dir_in, r2(i), Rgb::ONE);
            let expect = phase.pdf(dir_in, s.dir, Rgb::ONE);
            assert!((s.pdf - expect).abs() <= 1e-4 * expect.max(1e-3), "pdf {} vs {expect}", s.pdf);
            assert_eq!(s.weight, Rgb::ONE);
            assert_eq!(phase.value(dir_in, s.dir), Rgb::splat(expect));
            s.dir
        },
        |c| phase.pdf_cos(c),
    );
    assert!(chi2 < limit, "chi-square {chi2} (limit {limit})");
    let five = Phase::mixture(&[(0.3, 0.5), (0.2, -0.2), (0.25, 0.9), (0.15, 0.0), (0.1, -0.7)]);
    let want = 0.3 * 0.5 - 0.2 * 0.2 + 0.25 * 0.9 - 0.1 * 0.7;
    assert_eq!(five.lobes().len(), MAX_PHASE_LOBES);
    assert!((five.g - want).abs() < 1e-6, "{five:?} vs {want}");
    let weights: f32 = five.lobes().map(|(w, _)| w.x).sum();
    assert!((weights - 1.0).abs() < 1e-6);
}

/// A chromatic mixture: red mostly forward (g 0.8), blue mostly backward (g −0.5), green
/// between; weights given unnormalised (the channels' totals 2, 1, 0.5).
fn chromatic() -> Phase {
    Phase::chromatic_mixture(&[(Rgb::new(1.8, 0.5, 0.05), 0.8), (Rgb::new(0.2, 0.5, 0.45), -0.5)])
}

/// Each channel of a chromatic mixture is its own normalised mixture: ∫ p_c dω = 1 and
/// its mean cosine Σₖ w_{c,k} gₖ (0.9·0.8 − 0.1·0.5 = 0.67, 0.15, 0.1·0.8 − 0.9·0.5 =
/// −0.37) within 1e-4 and 1e-3; the sampling density is the channels' mean, normalised
/// too; `g` is the channels' mean cosine averaged.
#[test]
fn a_chromatic_mixture_is_normalised_per_channel() {
    let phase = chromatic();
    assert!(phase.is_chromatic());
    let want = [0.67f64, 0.15, -0.37];
    for (c, want) in want.iter().enumerate() {
        let sum = over_sphere(200_000, |x| f64::from(phase.value_cos(x)[c]));
        let mean = over_sphere(200_000, |x| f64::from(x) * f64::from(phase.value_cos(x)[c]));
        assert!((sum - 1.0).abs() < 1e-4, "channel {c}: ∫ {sum}");
        assert!((mean - want).abs() < 1e-3, "channel {c}: mean cosine {mean} vs {want}");
    }
    let sum = over_sphere(200_000, |x| f64::from(phase.pdf_cos(x)));
    assert!((sum - 1.0).abs() < 1e-4, "the sampling density: ∫ {sum}");
    assert!((f64::from(phase.g) - want.iter().sum::<f64>() / 3.0).abs() < 1e-6, "{phase:?}");
}

/// Directions drawn from each channel's mixture follow that channel's density, and those
/// of [`Phase::sample`] the channels' densities mixed by the probabilities of picking
/// them — uniform for a white throughput, (1, 0.2, 0.05)/1.25 for a red one (chi-square,
/// 40 × 8 bins, 200 000 samples each, below the 99 % quantile); `sample`'s pdf is
/// [`Phase::pdf`] and its weight value / pdf (1e-4).
#[test]
fn a_chromatic_mixture_samples_each_channel_and_their_mixture() {
    let phase = chromatic();
    let dir_in = Vec3A::new(-0.2, 0.5, 0.843).normalize();
    for c in 0..3 {
        let (chi2, limit) =
            chi_square(dir_in, 200_000, |i| phase.sample_in_channel(c, dir_in, r2(i)), |x| phase.value_cos(x)[c]);
        assert!(chi2 < limit, "channel {c}: chi-square {chi2} (limit {limit})");
    }
    for by in [Rgb::ONE, Rgb::new(1.0, 0.2, 0.05)] {
        let picks = channel_probabilities(by);
        assert!((picks - by / by.element_sum()).abs().max_element() < 1e-6, "{picks:?}");
        let (chi2, limit) = chi_square(
            dir_in,
            200_000,
            |i| {
                let s = phase.sample(dir_in, r2(i), by);
                let (pdf, value) = (phase.pdf(dir_in, s.dir, by), phase.value(dir_in, s.dir));
                assert!((s.pdf - pdf).abs() <= 1e-4 * pdf, "pdf {} vs {pdf}", s.pdf);
                assert!((s.weight * s.pdf - value).abs().max_element() <= 1e-4 * value.max_element(), "{s:?}");
                s.dir
            },
            |x| phase.value_cos(x).dot(picks),
        );
        assert!(chi2 < limit, "throughput {by:?}: chi-square {chi2} (limit {limit})");
    }
    // Nothing left to weigh by: uniform.
    assert_eq!(channel_probabilities(Rgb::new(0.0, -1.0, f32::NAN)), Rgb::splat(1.0 / 3.0));
}

/// A white furnace for the phase function alone: scattering loses nothing in any channel,
/// so the mean weight of sampled directions is 1 per channel within 1 % (100 000 samples),
/// whatever throughput picks the channels, and the weighted mean cosine of the sampled
/// directions is each channel's own (0.67, 0.15, −0.37) within 0.01 — each channel
/// scatters by its own mixture. Picked by the throughput, each sample keeps the
/// throughput's sum over the channels (1e-4).
#[test]
fn chromatic_sampling_is_a_white_furnace_per_channel() {
    let phase = chromatic();
    let dir_in = Vec3A::new(0.6, 0.0, 0.8);
    let n = 100_000;
    for by in [Rgb::ONE, Rgb::new(0.05, 1.0, 0.3)] {
        let (mut weight, mut cosine) = (Rgb::ZERO, Rgb::ZERO);
        for i in 0..n {
            let s = phase.sample(dir_in, r2(i), by);
            weight += s.weight;
            cosine += s.weight * s.dir.dot(dir_in);
            let kept = (s.weight * by).element_sum();
            assert!((kept - by.element_sum()).abs() <= 1e-4 * by.element_sum(), "{by:?}: {s:?} keeps {kept}");
        }
        let (weight, cosine) = (weight / n as f32, cosine / n as f32);
        for (c, want) in [0.67f32, 0.15, -0.37].iter().enumerate() {
            assert!((weight[c] - 1.0).abs() < 0.01, "{by:?}, channel {c}: mean weight {}", weight[c]);
            assert!((cosine[c] - want).abs() < 0.01, "{by:?}, channel {c}: mean cosine {} vs {want}", cosine[c]);
        }
    }
}

/// Colour weights proportional in every channel give the grey mixture (not chromatic,
/// the same lobes); a channel without weight takes the other channels' mean; nothing
/// usable is isotropic; five lobes keep four.
#[test]
fn chromatic_mixtures_reduce_where_the_channels_agree() {
    let grey = Phase::chromatic_mixture(&[(Rgb::splat(0.6), 0.8), (Rgb::splat(0.4), -0.4)]);
    assert_eq!(grey, Phase::mixture(&[(0.6, 0.8), (0.4, -0.4)]));
    let scaled = Phase::chromatic_mixture(&[(Rgb::new(0.6, 1.2, 0.3), 0.8), (Rgb::new(0.4, 0.8, 0.2), -0.4)]);
    assert!(!scaled.is_chromatic() && (scaled.g - 0.32).abs() < 1e-6, "{scaled:?}");
    // Blue scatters nothing: it takes red and green's mean, (0.75, 0.25).
    let dark = Phase::chromatic_mixture(&[(Rgb::new(1.0, 0.5, 0.0), 0.8), (Rgb::new(0.0, 0.5, 0.0), -0.4)]);
    let weights: Vec<Rgb> = dark.lobes().map(|(w, _)| w).collect();
    assert!((weights[0] - Rgb::new(1.0, 0.5, 0.75)).abs().max_element() < 1e-6, "{weights:?}");
    assert!((weights[1] - Rgb::new(0.0, 0.5, 0.25)).abs().max_element() < 1e-6, "{weights:?}");
    assert_eq!(Phase::chromatic_mixture(&[(Rgb::new(-1.0, f32::NAN, 0.0), 0.5)]), Phase::henyey_greenstein(0.0));
    let five = Phase::chromatic_mixture(&[
        (Rgb::new(0.3, 0.1, 0.2), 0.5),
        (Rgb::new(0.2, 0.3, 0.1), -0.2),
        (Rgb::new(0.25, 0.2, 0.3), 0.9),
        (Rgb::new(0.15, 0.3, 0.2), 0.0),
        (Rgb::new(0.1, 0.1, 0.2), -0.7),
    ]);
    assert_eq!(five.lobes().len(), MAX_PHASE_LOBES);
    let sums = five.lobes().fold(Rgb::ZERO, |s, (w, _)| s + w);
    assert!((sums - Rgb::ONE).abs().max_element() < 1e-6, "{sums:?}");
}

/// Draine's lobe for (g, α) over Henyey–Greenstein's range and the shapes `fog_vdf` uses
/// (α up to 250): ∫ p dω = 1 within 1e-4, the mean cosine is the closed form
/// g(1 + α(3 + 2g²)/5)/(1 + α(1 + 2g²)/3) within 1e-3; α = 0 is Henyey–Greenstein exactly;
/// g = 0, α = 1 is Rayleigh's 3/(16π)(1 + cos²θ).
#[test]
fn draine_is_normalised_with_its_mean_cosine() {
    for (g, alpha) in [(0.0f32, 1.0f32), (0.5, 20.0), (-0.4, 3.0), (0.3, 250.0), (0.9, 30.0), (0.05, 250.0)] {
        let lobe = Draine::new(g, alpha);
        let sum = over_sphere(200_000, |c| f64::from(lobe.eval_cos(c)));
        assert!((sum - 1.0).abs() < 1e-4, "g {g} α {alpha}: ∫ {sum}");
        let mean = over_sphere(200_000, |c| f64::from(c) * f64::from(lobe.eval_cos(c)));
        let (g, a) = (f64::from(g), f64::from(alpha));
        let want = g * (1.0 + a * (3.0 + 2.0 * g * g) / 5.0) / (1.0 + a * (1.0 + 2.0 * g * g) / 3.0);
        assert!((mean - want).abs() < 1e-3, "g {g} α {a}: mean cosine {mean} vs {want}");
        assert!((f64::from(lobe.mean_cosine()) - want).abs() < 1e-5, "{lobe:?}");
    }
    let hg = HenyeyGreenstein::new(0.6);
    let as_draine = Draine::new(0.6, 0.0);
    for c in [-1.0f32, -0.3, 0.2, 0.99] {
        assert_eq!(as_draine.eval_cos(c), hg.eval_cos(c));
    }
    assert_eq!(as_draine.sample_cos(0.37), hg.sample_cos(0.37));
    let rayleigh = Draine::new(0.0, 1.0);
    for c in [-0.8f32, 0.0, 0.5] {
        let want = 3.0 / (16.0 * std::f32::consts::PI) * (1.0 + c * c);
        assert!((rayleigh.eval_cos(c) - want).abs() < 1e-6, "{c}");
    }
}

/// Draine's sampling follows its density (chi-square, 200 000 samples, 40 × 8 bins, below
/// the 99 % quantile) and reports it (1e-4 relative), for forward, backward and
/// Rayleigh-like shapes.
#[test]
fn draine_sampling_matches_its_density() {
    let dir_in = Vec3A::new(0.3, -0.4, 0.866).normalize();
    for (g, alpha) in [(0.55f32, 22.0f32), (-0.3, 5.0), (0.0, 250.0), (0.1, 250.0), (0.8, 1.0)] {
        let lobe = Draine::new(g, alpha);
        let (chi2, limit) = chi_square(
            dir_in,
            200_000,
            |i| {
                let (dir, pdf) = lobe.sample(dir_in, r2(i));
                let expect = lobe.eval(dir_in, dir);
                assert!((pdf - expect).abs() <= 1e-4 * expect.max(1e-3), "{lobe:?}: pdf {pdf} vs {expect}");
                dir
            },
            |c| lobe.eval_cos(c),
        );
        assert!(chi2 < limit, "{lobe:?}: chi-square {chi2} (limit {limit})");
    }
}

/// ∫ 2π f(cos) dcos over [−1, 1] by the midpoint rule, 200 000 cells over [−1, 0.99] and
/// 200 000 cells even in ln(1 − cos) over (0.99, 1]: for the sharp forward peaks of
/// large droplets.
fn over_sphere_graded(f: impl Fn(f32) -> f64) -> f64 {
    let n = 200_000;
    let body: f64 = (0..n)
        .map(|i| {
            let c = -1.0 + (i as f64 + 0.5) * 1.99 / n as f64;
            2.0 * PI * f(c as f32) * 1.99 / n as f64
        })
        .sum();
    // 1 − cos from 1e-2 down to 1e-12, cells even in its logarithm.
    let (top, bottom) = (1e-2f64.ln(), 1e-12f64.ln());
    let peak: f64 = (0..n)
        .map(|i| {
            let (a, b) = (top + (bottom - top) * i as f64 / n as f64, top + (bottom - top) * (i + 1) as f64 / n as f64);
            let (x0, x1) = (a.exp(), b.exp());
            let c = 1.0 - 0.5 * (x0 + x1);
            2.0 * PI * f(c as f32) * (x0 - x1)
        })
        .sum();
    body + peak
}

/// `df::fog_vdf`'s blend for droplets of 0.05 to 50 µm: normalised (1e-3: the f32
/// Henyey–Greenstein lobe of large droplets, g_HG up to 0.998, is a peak a few 1e-6 wide
/// in cos θ that f32 resolves only to a few 1e-3; 1e-4 at 3 µm and below), its mean
/// cosine (`Phase::g`) the blend's closed form and the integral's (1e-3), sampled by its
/// own density (chi-square as above up to 10 µm, pdf 1e-4, weight 1). Cloud and fog droplets of
/// 10–20 µm scatter with the asymmetry Mie theory gives them at visible wavelengths,
/// 0.85–0.89 (Hansen & Travis 1974, Space Sci. Rev. 16, fig. 13); particles far below the
/// wavelength scatter nearly symmetrically (|g| < 0.05 at 0.05 µm). The default diameter
/// is 8 µm.
#[test]
fn fog_vdf_is_a_normalised_mie_approximation_sampled_exactly() {
    assert_eq!(DEFAULT_PARTICLE_SIZE, 8.0);
    let dir_in = Vec3A::new(-0.2, 0.5, 0.843).normalize();
    for d in [0.05f32, 0.7, 3.0, 10.0, 20.0, 50.0] {
        let lobes = fog_lobes(d);
        assert!((lobes[0].0 + lobes[1].0 - 1.0).abs() < 1e-6);
        let phase = Phase::mixture_of(&lobes);
        let sum = over_sphere_graded(|c| f64::from(phase.pdf_cos(c)));
        eprintln!("d {d}: ∫ {sum}");
        assert!((sum - 1.0).abs() < 1e-3, "d {d}: ∫ {sum}");
        let mean = over_sphere_graded(|c| f64::from(c) * f64::from(phase.pdf_cos(c)));
        let want = lobes.iter().map(|(w, l)| f64::from(*w) * f64::from(l.mean_cosine())).sum::<f64>();
        assert!(
            (mean - want).abs() < 1e-3 && (f64::from(phase.g) - want).abs() < 1e-5,
            "d {d}: {mean} {want} {phase:?}"
        );
        if d > 10.0 {
            // The bins' expected counts come from a midpoint rule too coarse for the peak.
            continue;
        }
        let (chi2, limit) = chi_square(
            dir_in,
            200_000,
            |i| {
                let s = phase.sample(dir_in, r2(i), Rgb::ONE);
                let expect = phase.pdf(dir_in, s.dir, Rgb::ONE);
                assert!((s.pdf - expect).abs() <= 1e-4 * expect.max(1e-3), "d {d}: pdf {} vs {expect}", s.pdf);
                assert_eq!(s.weight, Rgb::ONE);
                s.dir
            },
            |c| phase.pdf_cos(c),
        );
        assert!(chi2 < limit, "d {d}: chi-square {chi2} (limit {limit})");
    }
    for d in [10.0f32, 20.0] {
        let g = Phase::mixture_of(&fog_lobes(d)).g;
        assert!((0.85..0.89).contains(&g), "d {d}: asymmetry {g}");
    }
    assert!(Phase::mixture_of(&fog_lobes(0.05)).g.abs() < 0.05);
    assert_eq!(fog_lobes(f32::NAN), fog_lobes(8.0));
    assert_eq!(fog_lobes(80.0), fog_lobes(50.0));
}
