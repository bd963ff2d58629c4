//! Prints mira's BSDF values for an outside check (`tools/compare/bsdf_mitsuba.py`).
//!
//! Reads whitespace-separated commands from stdin, one per line (`#` starts a comment):
//!
//! ```text
//! conductor AX AY ETA_R ETA_G ETA_B K_R K_G K_B   # selects a rough conductor
//! dielectric AX AY ETA                             # selects a rough dielectric (inside/outside)
//! eval WO_X WO_Y WO_Z WI_X WI_Y WI_Z               # f(ωo, ωi) of the selected BSDF
//! albedo WO_X WO_Y WO_Z N                          # mean sample weight over N samples
//! ```
//!
//! Directions are in the local frame (+Z = normal, x along AX), unit length, pointing away
//! from the surface. For each `eval` line it prints
//! `eval R G B  R_SEP G_SEP B_SEP  PDF`: f without the cosine; the same with Smith's
//! separable masking G1(ωo)·G1(ωi) in place of mira's height-correlated G2 (what Mitsuba 3
//! uses: the factor G1·G1/G2 is computed from mira's own Λ); and the sampling density per
//! solid angle. For each `albedo` line it prints `albedo R G B  R_SEP G_SEP B_SEP`: the
//! mean of f·|cos θi|/pdf over N samples of a 3-D Kronecker (R3) sequence, and the same with
//! each sample's weight given the separable-masking factor.

use std::io::{BufRead, Write};

use bsdf::microfacet::Ggx;
use bsdf::Rgb;
use bsdf::{Bsdf, Conductor, Dielectric};
use glam::{Vec2, Vec3A};

/// The i-th point of the R3 Kronecker sequence (generalised golden ratio), in [0, 1)³.
fn r3(i: u64) -> [f32; 3] {
    // φ₃ is the real root of x⁴ = x + 1.
    const PHI: f64 = 1.220_744_084_605_759_5;
    let a = [1.0 / PHI, 1.0 / (PHI * PHI), 1.0 / (PHI * PHI * PHI)];
    a.map(|a| (0.5 + a * i as f64).fract() as f32)
}

/// The masking factor that turns height-correlated masking–shadowing into the separable
/// form: G1(ωo) G1(ωi) / G2(ωo, ωi) (1 where G2 vanishes).
fn separable_factor(ggx: &Ggx, wo: Vec3A, wi: Vec3A) -> f32 {
    let g2 = ggx.g2(wo, wi);
    if g2 > 0.0 {
        ggx.g1(wo) * ggx.g1(wi) / g2
    } else {
        1.0
    }
}

fn numbers(fields: &[&str], n: usize, line: &str) -> Vec<f32> {
    assert!(fields.len() == n, "expected {n} numbers: {line}");
    fields.iter().map(|f| f.parse::<f32>().unwrap_or_else(|_| panic!("not a number {f:?}: {line}"))).collect()
}

fn main() {
    let stdin = std::io::stdin();
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    let mut current: Option<(Bsdf, Ggx)> = None;
    for line in stdin.lock().lines() {
        let line = line.expect("stdin");
        let line = line.split('#').next().unwrap_or("").trim().to_string();
        let fields: Vec<&str> = line.split_whitespace().collect();
        let Some((&cmd, rest)) = fields.split_first() else { continue };
        match cmd {
            "conductor" => {
                let v = numbers(rest, 8, &line);
                let ggx = Ggx { alpha_x: v[0], alpha_y: v[1] };
                let c = Conductor { ggx, eta: Rgb::new(v[2], v[3], v[4]), k: Rgb::new(v[5], v[6], v[7]) };
                current = Some((Bsdf::Conductor(c), ggx));
            }
            "dielectric" => {
                let v = numbers(rest, 3, &line);
                let ggx = Ggx { alpha_x: v[0], alpha_y: v[1] };
                let d = Dielectric::glass(v[2], ggx);
                current = Some((Bsdf::Dielectric(d), ggx));
            }
            "eval" => {
                let (bsdf, ggx) = current.as_ref().expect("eval before a BSDF");
                let v = numbers(rest, 6, &line);
                let (wo, wi) = (Vec3A::new(v[0], v[1], v[2]), Vec3A::new(v[3], v[4], v[5]));
                let f = bsdf.eval(wo, wi);
                let sep = f * separable_factor(ggx, wo, wi);
                let pdf = bsdf.pdf(wo, wi);
                writeln!(out, "eval {:e} {:e} {:e} {:e} {:e} {:e} {:e}", f.x, f.y, f.z, sep.x, sep.y, sep.z, pdf)
                    .expect("stdout");
            }
            "albedo" => {
                let (bsdf, ggx) = current.as_ref().expect("albedo before a BSDF");
                let v = numbers(&rest[..rest.len().min(3)], 3, &line);
                let wo = Vec3A::new(v[0], v[1], v[2]);
                let n: u64 = rest.get(3).and_then(|f| f.parse().ok()).unwrap_or_else(|| panic!("no count: {line}"));
                let (mut sum, mut sum_sep) = ([0f64; 3], [0f64; 3]);
                for i in 0..n {
                    let u = r3(i);
                    if let Some(s) = bsdf.sample(wo, Vec2::new(u[0], u[1]), u[2]) {
                        let w = s.weight();
                        let sep = if s.delta { 1.0 } else { separable_factor(ggx, wo, s.wi) };
                        for (c, x) in w.to_array().into_iter().enumerate() {
                            sum[c] += f64::from(x);
                            sum_sep[c] += f64::from(x * sep);
                        }
                    }
                }
                let (a, b) = (sum.map(|x| x / n as f64), sum_sep.map(|x| x / n as f64));
                writeln!(out, "albedo {:e} {:e} {:e} {:e} {:e} {:e}", a[0], a[1], a[2], b[0], b[1], b[2])
                    .expect("stdout");
            }
            other => panic!("unknown command {other:?}: {line}"),
        }
    }
}
