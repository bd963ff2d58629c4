//! IES LM-63 photometric profiles (mental ray's `lightprofile … format ies`, MDL's
//! `light_profile`): a lamp's measured luminous intensity (candela) over directions.
//!
//! Reads the 1986, 1991 (`IESNA91`), 1995 (`IESNA:LM-63-1995`) and 2002 (`IESNA:LM-63-2002`)
//! layouts: keyword lines up to `TILT=`, then whitespace- (or comma-) separated numbers that
//! may wrap over any number of lines. `TILT=INCLUDE` tables and `TILT=<file>` are skipped
//! with a warning (mira assumes the lamp burns in the position it was measured in). The
//! candela values are multiplied by the candela multiplier and the ballast and
//! ballast–lamp factors. Symmetric type C files (a single horizontal angle, 0–90°, 0–180°,
//! 90–270°) are expanded to the full 0–360°, and laterally symmetric type A and B files
//! (horizontal 0–90°) to −90–90°.
//!
//! **Axis convention** (the light's local frame, the space of its light instance): the
//! photometric axis — type C vertical angle 0, the nadir; type A and B angle (0, 0) — is the
//! light's local **−Z**, the direction mental ray exporters give lights (`direction 0 0 -1`)
//! and MDL's `light_ies` uses as its main axis. Type C horizontal angle 0 lies along local
//! +X and 90° along +Y (counter-clockwise seen from above, +Z, as LM-63 prescribes). Type B
//! files turn about the local X axis (their polar axis): a direction is (sin H,
//! cos H sin V, −cos H cos V) for horizontal angle H and vertical angle V; `flags 1` in the
//! `lightprofile` reads their horizontal angles clockwise (as mental ray does for type B
//! files that break the standard). Type A files (which mental ray does not read) turn
//! about local Y: (cos V sin H, sin V, −cos V cos H).
//!
//! Lookups interpolate bilinearly in the two angles (mental ray's `hermite 1`; a scene's
//! `hermite 3`, cubic smoothing, is read as linear). Directions outside the measured
//! angles get nothing.

use std::io::Read;
use std::path::Path;

use glam::Vec3A;

/// Largest profile file mira reads, in bytes.
pub const MAX_FILE_BYTES: u64 = 8 << 20;
/// Most angles on either axis of a profile.
pub const MAX_ANGLES: usize = 4096;
/// Most candela values in a profile (before symmetric expansion, which at most quadruples it).
pub const MAX_VALUES: usize = 1 << 20;

/// The photometric type of an IES file: how its two angles map to directions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Photometry {
    /// Type A (automotive): polar axis vertical to the aim (local Y).
    A,
    /// Type B (floodlights): polar axis lateral (local X).
    B,
    /// Type C (architectural, the common one): polar axis is the photometric axis (local −Z).
    C,
}

/// A photometric profile, ready for lookups; candela values with all multipliers applied.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    photometry: Photometry,
    /// Vertical angles, radians, strictly increasing.
    vertical: Vec<f32>,
    /// Horizontal angles, radians, strictly increasing, symmetric halves expanded.
    horizontal: Vec<f32>,
    /// Candela, horizontal-major: `values[h * vertical.len() + v]`.
    values: Vec<f32>,
    /// Type B horizontal angles read clockwise.
    clockwise: bool,
    peak: f32,
    flux: f32,
}

/// A parsed profile and what was approximated or ignored while reading it.
pub type Parsed = (Profile, Vec<String>);

/// Numbers after the `TILT=` line, read one at a time.
struct Numbers<'a> {
    tokens: Vec<&'a str>,
    next: usize,
}

impl Numbers<'_> {
    fn left(&self) -> usize {
        self.tokens.len() - self.next
    }

    fn num(&mut self, what: &str) -> Result<f64, String> {
        let Some(t) = self.tokens.get(self.next) else {
            return Err(format!("the file ends before the {what}"));
        };
        self.next += 1;
        match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(format!("'{t}' is not a number (reading the {what})")),
        }
    }

    fn count(&mut self, what: &str, max: usize) -> Result<usize, String> {
        let v = self.num(what)?;
        if v.fract() != 0.0 || v < 1.0 || v > max as f64 {
            return Err(format!("{what} {v} is not a whole number from 1 to {max}"));
        }
        Ok(v as usize)
    }

    /// `n` angles in degrees, strictly increasing.
    fn angles(&mut self, n: usize, what: &str) -> Result<Vec<f64>, String> {
        let mut out = Vec::with_capacity(n);
        for _ in 0..n {
            let a = self.num(what)?;
            if out.last().is_some_and(|&p| a <= p) {
                return Err(format!("the {what} do not increase ({a} after {})", out[out.len() - 1]));
            }
            out.push(a);
        }
        Ok(out)
    }
}

impl Profile {
    /// Reads an IES file (at most [`MAX_FILE_BYTES`]; non-UTF-8 bytes, as in Latin-1
    /// keyword lines, are tolerated).
    pub fn load(path: &Path, clockwise: bool) -> Result<Parsed, String> {
        let file = std::fs::File::open(path).map_err(|e| format!("cannot open: {e}"))?;
        let mut bytes = Vec::new();
        file.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes).map_err(|e| format!("cannot read: {e}"))?;
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(format!("larger than {MAX_FILE_BYTES} bytes; not a light profile mira reads"));
        }
        Profile::parse(&String::from_utf8_lossy(&bytes), clockwise)
    }

    /// Parses the text of an IES LM-63 file. `clockwise`: mental ray's `flags 1`, type B
    /// horizontal angles run clockwise.
    pub fn parse(text: &str, clockwise: bool) -> Result<Parsed, String> {
        let mut warnings = Vec::new();
        let mut lines = text.lines();
        let tilt = loop {
            let Some(line) = lines.next() else {
                return Err("no TILT= line: not an IES LM-63 file".into());
            };
            let t = line.trim_start();
            if t.len() >= 5 && t[..4].eq_ignore_ascii_case("TILT") {
                if let Some((_, v)) = t.split_once('=') {
                    break v.trim().to_string();
                }
            }
        };
        let rest: Vec<&str> = lines.collect();
        let tokens =
            rest.iter().flat_map(|l| l.split(|c: char| c.is_whitespace() || c == ',')).filter(|t| !t.is_empty());
        let mut nums = Numbers { tokens: tokens.collect(), next: 0 };
        if tilt.eq_ignore_ascii_case("INCLUDE") {
            nums.num("tilt lamp-to-luminaire geometry")?;
            let n = nums.count("number of tilt angles", MAX_ANGLES)?;
            if nums.left() < 2 * n {
                return Err("the file ends inside its tilt table".into());
            }
            nums.next += 2 * n;
            warnings.push("TILT=INCLUDE: the tilt table is ignored (the lamp is taken as measured)".into());
        } else if !tilt.eq_ignore_ascii_case("NONE") {
            warnings.push(format!("TILT={tilt}: tilt files are not read (the lamp is taken as measured)"));
        }
        nums.num("number of lamps")?;
        nums.num("lumens per lamp")?;
        let candela_multiplier = nums.num("candela multiplier")?;
        let nv = nums.count("number of vertical angles", MAX_ANGLES)?;
        let nh = nums.count("number of horizontal angles", MAX_ANGLES)?;
        let t = nums.num("photometric type")?;
        let photometry = if t == 1.0 {
            Photometry::C
        } else if t == 2.0 {
            Photometry::B
        } else if t == 3.0 {
            Photometry::A
        } else {
            return Err(format!("photometric type {t} is not 1 (C), 2 (B) or 3 (A)"));
        };
        for what in ["units type", "luminaire width", "luminaire length", "luminaire height"] {
            nums.num(what)?;
        }
        let ballast = nums.num("ballast factor")?;
        let ballast_lamp = nums.num("ballast-lamp photometric factor")?;
        nums.num("input watts")?;
        if candela_multiplier < 0.0 {
            return Err(format!("candela multiplier {candela_multiplier} is negative"));
        }
        let mut multiplier = candela_multiplier;
        for (f, what) in [(ballast, "ballast factor"), (ballast_lamp, "ballast-lamp photometric factor")] {
            if f > 0.0 {
                multiplier *= f;
            } else {
                warnings.push(format!("{what} {f} is not positive; taken as 1"));
            }
        }
        if nv * nh > MAX_VALUES {
            return Err(format!("{nv}×{nh} candela values are more than mira reads ({MAX_VALUES})"));
        }
        if nums.left() < nv + nh + nv * nh {
            return Err(format!(
                "the file ends early: {nv} vertical and {nh} horizontal angles and {} candela values announced, {} numbers left",
                nv * nh,
                nums.left()
            ));
        }
        if nv < 2 {
            return Err("a profile needs at least two vertical angles".into());
        }
        let vertical = nums.angles(nv, "vertical angles")?;
        let horizontal = nums.angles(nh, "horizontal angles")?;
        let mut values = Vec::with_capacity(nv * nh);
        let mut negative = false;
        for _ in 0..nv * nh {
            let c = nums.num("candela values")?;
            negative |= c < 0.0;
            values.push((c.max(0.0) * multiplier) as f32);
        }
        if negative {
            warnings.push("negative candela values are taken as 0".into());
        }
        if nums.left() > 0 {
            warnings.push(format!("{} numbers after the candela values are ignored", nums.left()));
        }
        let (v0, v1) = (vertical[0], vertical[nv - 1]);
        let (h0, h1) = (horizontal[0], horizontal[nh - 1]);
        let near = |a: f64, b: f64| (a - b).abs() < 1e-3;
        let (lo, hi) = if photometry == Photometry::C { (0.0, 180.0) } else { (-90.0, 90.0) };
        if v0 < lo - 1e-3 || v1 > hi + 1e-3 {
            return Err(format!("vertical angles {v0}..{v1} fall outside {lo}..{hi}"));
        }
        const FULL: (f64, f64) = (0.0, 360.0);
        let (horizontal, values) = match photometry {
            Photometry::C if nh == 1 => (vec![0.0, 360.0], [values.clone(), values].concat()),
            Photometry::C if near(h0, 0.0) && near(h1, 90.0) => expand(&horizontal, &values, nv, FULL, |h| {
                let m = h % 180.0;
                if m > 90.0 {
                    180.0 - m
                } else {
                    m
                }
            })?,
            Photometry::C if near(h0, 0.0) && near(h1, 180.0) => {
                expand(&horizontal, &values, nv, FULL, |h| if h > 180.0 { 360.0 - h } else { h })?
            }
            Photometry::C if near(h0, 90.0) && near(h1, 270.0) => expand(&horizontal, &values, nv, FULL, |h| {
                if h < 90.0 {
                    180.0 - h
                } else if h > 270.0 {
                    540.0 - h
                } else {
                    h
                }
            })?,
            Photometry::C if near(h0, 0.0) && h1 > 180.0 && h1 <= 360.0 + 1e-3 => {
                expand(&horizontal, &values, nv, FULL, |h| if h >= 360.0 - 1e-3 { 0.0 } else { h })?
            }
            Photometry::C => {
                return Err(format!("horizontal angles {h0}..{h1} are not a range LM-63 allows for type C"))
            }
            _ if nh < 2 => return Err("a type A or B profile needs at least two horizontal angles".into()),
            _ if near(h0, 0.0) && h1 <= 90.0 + 1e-3 => expand(&horizontal, &values, nv, (-90.0, 90.0), f64::abs)?,
            _ if h0 >= -180.0 - 1e-3 && h1 <= 180.0 + 1e-3 => (horizontal, values),
            _ => return Err(format!("horizontal angles {h0}..{h1} fall outside -180..180")),
        };
        let rad = |a: &[f64]| a.iter().map(|d| d.to_radians() as f32).collect::<Vec<f32>>();
        let mut p = Profile {
            photometry,
            vertical: rad(&vertical),
            horizontal: rad(&horizontal),
            values,
            clockwise: clockwise && photometry == Photometry::B,
            peak: 0.0,
            flux: 0.0,
        };
        p.peak = p.values.iter().copied().fold(0.0, f32::max);
        p.flux = p.integrate() as f32;
        Ok((p, warnings))
    }

    /// The photometric type.
    pub fn photometry(&self) -> Photometry {
        self.photometry
    }

    /// The largest intensity of the profile, candela.
    pub fn peak(&self) -> f32 {
        self.peak
    }

    /// Total luminous flux, lumens: the interpolated intensity integrated over the sphere.
    pub fn flux(&self) -> f32 {
        self.flux
    }

    /// Intensity towards `dir` (light's local frame, any length; see the module's axis
    /// convention), candela, interpolated bilinearly in the two angles; 0 outside the
    /// measured angles.
    pub fn candela(&self, dir: Vec3A) -> f32 {
        let d = dir.normalize_or_zero();
        if d == Vec3A::ZERO {
            return 0.0;
        }
        let (v, h) = match self.photometry {
            Photometry::C => ((-d.z).clamp(-1.0, 1.0).acos(), d.y.atan2(d.x).rem_euclid(std::f32::consts::TAU)),
            Photometry::B => {
                let h = d.x.clamp(-1.0, 1.0).asin();
                (d.y.atan2(-d.z), if self.clockwise { -h } else { h })
            }
            Photometry::A => (d.y.clamp(-1.0, 1.0).asin(), d.x.atan2(-d.z)),
        };
        self.lookup(v, h)
    }

    /// The intensity towards `dir` relative to the peak (0 to 1; 0 for an all-dark profile).
    pub fn normalized(&self, dir: Vec3A) -> f32 {
        if self.peak > 0.0 {
            self.candela(dir) / self.peak
        } else {
            0.0
        }
    }

    /// The interpolated intensity at vertical angle `v` and horizontal angle `h` (radians).
    fn lookup(&self, v: f32, h: f32) -> f32 {
        let (Some((i, s)), Some((j, t))) = (locate(&self.vertical, v), locate(&self.horizontal, h)) else {
            return 0.0;
        };
        let nv = self.vertical.len();
        let at = |h: usize, v: usize| self.values[h * nv + v];
        let i1 = (i + 1).min(nv - 1);
        let j1 = (j + 1).min(self.horizontal.len() - 1);
        let a = at(j, i) * (1.0 - s) + at(j, i1) * s;
        let b = at(j1, i) * (1.0 - s) + at(j1, i1) * s;
        a * (1.0 - t) + b * t
    }

    /// The exact integral of the bilinear interpolant over the sphere: per grid cell, the
    /// trapezoid rule along the longitude-like angle (exact for a linear function) and the
    /// closed form of ∫ (linear) · w along the latitude-like one, w = sin of the polar angle
    /// (type C) or cos of the elevation (types A, B).
    fn integrate(&self) -> f64 {
        let nv = self.vertical.len();
        let at = |h: usize, v: usize| f64::from(self.values[h * nv + v]);
        // ∫_{x0}^{x1} (f0 + (f1 − f0)(x − x0)/Δ) w(x) dx for w = sin (polar) or cos.
        let segment = |x0: f64, x1: f64, f0: f64, f1: f64, polar: bool| {
            let dx = x1 - x0;
            let (w0, w1) = if polar {
                (x0.cos() - x1.cos(), -dx * x1.cos() + x1.sin() - x0.sin())
            } else {
                (x1.sin() - x0.sin(), dx * x1.sin() + x1.cos() - x0.cos())
            };
            f0 * w0 + (f1 - f0) / dx * w1
        };
        let v: Vec<f64> = self.vertical.iter().map(|&a| f64::from(a)).collect();
        let h: Vec<f64> = self.horizontal.iter().map(|&a| f64::from(a)).collect();
        let mut sum = 0.0;
        for j in 0..h.len().saturating_sub(1) {
            let dh = h[j + 1] - h[j];
            for i in 0..nv - 1 {
                let dv = v[i + 1] - v[i];
                sum += match self.photometry {
                    // Latitude along the vertical angle: C (polar angle), A (elevation).
                    Photometry::C | Photometry::A => {
                        let f0 = 0.5 * (at(j, i) + at(j + 1, i)) * dh;
                        let f1 = 0.5 * (at(j, i + 1) + at(j + 1, i + 1)) * dh;
                        segment(v[i], v[i + 1], f0, f1, self.photometry == Photometry::C)
                    }
                    // Type B: the horizontal angle is the elevation from the polar plane.
                    Photometry::B => {
                        let f0 = 0.5 * (at(j, i) + at(j, i + 1)) * dv;
                        let f1 = 0.5 * (at(j + 1, i) + at(j + 1, i + 1)) * dv;
                        segment(h[j], h[j + 1], f0, f1, false)
                    }
                };
            }
        }
        sum
    }
}

/// Where `x` falls on `axis`: the cell's first index and the fraction across it; `None`
/// outside (a hair of rounding past either end counts as the end).
fn locate(axis: &[f32], x: f32) -> Option<(usize, f32)> {
    let (first, last) = (axis[0], axis[axis.len() - 1]);
    let eps = 1e-5;
    if !(x >= first - eps && x <= last + eps) {
        return None;
    }
    let x = x.clamp(first, last);
    let k = axis.partition_point(|&a| a <= x);
    if k >= axis.len() {
        return Some((axis.len() - 1, 0.0));
    }
    let i = k.saturating_sub(1);
    let span = axis[i + 1] - axis[i];
    Some((i, if span > 0.0 { (x - axis[i]) / span } else { 0.0 }))
}

/// Expands the measured horizontal angles (degrees) over the full range `lo..=hi`. The new
/// grid holds the range's ends and every reflection of a measured angle the LM-63
/// symmetries make; each gets the measured columns interpolated at its `fold` (the symmetry
/// back into the measured range; a measured angle itself where it lands on one). As the
/// grid holds every image of a measured angle, interpolating it reproduces the symmetric
/// extension of the measured table exactly.
fn expand(
    measured: &[f64],
    values: &[f32],
    nv: usize,
    (lo, hi): (f64, f64),
    fold: impl Fn(f64) -> f64,
) -> Result<(Vec<f64>, Vec<f32>), String> {
    let mut angles: Vec<f64> = measured
        .iter()
        .flat_map(|&a| [a, -a, 180.0 - a, 180.0 + a, 360.0 - a, 540.0 - a, 360.0 + a])
        .chain([lo, hi])
        .filter(|&a| (lo - 1e-6..=hi + 1e-6).contains(&a))
        .collect();
    angles.sort_by(f64::total_cmp);
    angles.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
    let (first, last) = (measured[0], measured[measured.len() - 1]);
    let mut out_angles = Vec::with_capacity(angles.len());
    let mut out = Vec::with_capacity(angles.len() * nv);
    for a in angles {
        let f = fold(a);
        if !(f >= first - 1e-6 && f <= last + 1e-6) {
            continue;
        }
        let k = measured.partition_point(|&m| m <= f).clamp(1, measured.len() - 1);
        let t = ((f - measured[k - 1]) / (measured[k] - measured[k - 1])).clamp(0.0, 1.0) as f32;
        let (c0, c1) = (&values[(k - 1) * nv..k * nv], &values[k * nv..(k + 1) * nv]);
        out_angles.push(a);
        out.extend(c0.iter().zip(c1).map(|(x, y)| x * (1.0 - t) + y * t));
    }
    if out_angles.len() < 2 {
        return Err("the horizontal angles do not cover a symmetric range".into());
    }
    Ok((out_angles, out))
}

#[cfg(test)]
mod tests {
    use std::f32::consts::PI;

    use super::*;

    /// A type C file with the given angles and values (candela multiplier `mult`).
    fn file(mult: f32, ty: u32, v: &[f32], h: &[f32], c: &[f32]) -> String {
        let list = |x: &[f32]| x.iter().map(|a| a.to_string()).collect::<Vec<_>>().join(" ");
        format!(
            "IESNA:LM-63-2002\n[TEST] mira\n[MANUFAC] none\nTILT=NONE\n1 -1 {mult} {} {} {ty} 2 0.1 0.1 0.0\n1.0 1.0 20\n{}\n{}\n{}\n",
            v.len(),
            h.len(),
            list(v),
            list(h),
            list(c)
        )
    }

    fn parse(text: &str) -> Profile {
        Profile::parse(text, false).unwrap().0
    }

    /// The direction of type C angles (degrees) in the light's frame.
    fn dir_c(v: f32, h: f32) -> Vec3A {
        let (v, h) = (v.to_radians(), h.to_radians());
        Vec3A::new(v.sin() * h.cos(), v.sin() * h.sin(), -v.cos())
    }

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    #[test]
    fn an_isotropic_profile_emits_four_pi_times_its_intensity() {
        let p = parse(&file(1.0, 1, &[0.0, 45.0, 90.0, 135.0, 180.0], &[0.0], &[100.0; 5]));
        assert!(close(p.flux(), 4.0 * PI * 100.0, 1e-5), "flux {}", p.flux());
        assert_eq!(p.peak(), 100.0);
        for d in [Vec3A::X, Vec3A::NEG_Z, Vec3A::Z, Vec3A::new(0.3, -0.4, 0.5)] {
            assert!(close(p.candela(d), 100.0, 1e-6));
            assert!(close(p.normalized(d), 1.0, 1e-6));
        }
        // A lower hemisphere only (0–90°): half the flux, nothing above.
        let p = parse(&file(1.0, 1, &[0.0, 30.0, 60.0, 90.0], &[0.0], &[50.0; 4]));
        assert!(close(p.flux(), 2.0 * PI * 50.0, 1e-5), "flux {}", p.flux());
        assert_eq!(p.candela(dir_c(120.0, 10.0)), 0.0);
    }

    /// A cosine distribution I = I0 cos v (lower hemisphere) emits π I0; the bilinear
    /// interpolant of a 1° table is within 1e-4 of that.
    #[test]
    fn a_cosine_profile_emits_pi_times_its_peak() {
        let v: Vec<f32> = (0..=90).map(|a| a as f32).collect();
        let c: Vec<f32> = v.iter().map(|a| 1000.0 * a.to_radians().cos()).collect();
        let p = parse(&file(1.0, 1, &v, &[0.0], &c));
        assert!(close(p.flux(), PI * 1000.0, 1e-4), "flux {}", p.flux());
    }

    const V: [f32; 4] = [0.0, 30.0, 60.0, 90.0];
    const H: [f32; 5] = [0.0, 90.0, 180.0, 270.0, 360.0];

    fn asymmetric() -> (Profile, Vec<f32>) {
        // Column h: 100 (h+1) + 10 v-index; the 360° column repeats the 0° one.
        let mut c = Vec::new();
        for j in 0..5 {
            for i in 0..4 {
                c.push(100.0 * ((j % 4) as f32 + 1.0) + 10.0 * i as f32);
            }
        }
        (parse(&file(1.0, 1, &V, &H, &c)), c)
    }

    #[test]
    fn table_angles_give_the_table_and_midway_the_bilinear_mean() {
        let (p, c) = asymmetric();
        for (j, &h) in H.iter().enumerate() {
            for (i, &v) in V.iter().enumerate() {
                let got = p.candela(dir_c(v, h));
                // At v = 0 every horizontal angle is the same direction (the nadir).
                let want = if v == 0.0 { got } else { c[j * 4 + i] };
                assert!(close(got, want, 1e-4), "v {v} h {h}: {got} vs {want}");
            }
        }
        for j in 0..4 {
            for i in 0..3 {
                let (v, h) = ((V[i] + V[i + 1]) / 2.0, (H[j] + H[j + 1]) / 2.0);
                let mean = (c[j * 4 + i] + c[j * 4 + i + 1] + c[(j + 1) * 4 + i] + c[(j + 1) * 4 + i + 1]) / 4.0;
                assert!(close(p.candela(dir_c(v, h)), mean, 1e-4), "v {v} h {h}");
            }
        }
        assert_eq!(p.peak(), 430.0);
        assert!(close(p.normalized(dir_c(90.0, 270.0)), 1.0, 1e-4));
        // Horizontal 90° is local +Y: the 90° column at v = 90°.
        assert!(close(p.candela(Vec3A::Y), 230.0, 1e-4));
    }

    #[test]
    fn symmetric_files_expand_to_the_full_circle() {
        let v = [0.0, 45.0, 90.0];
        // Quadrant symmetry (0–90°).
        let q = parse(&file(1.0, 1, &v, &[0.0, 45.0, 90.0], &[9.0, 1.0, 2.0, 9.0, 3.0, 4.0, 9.0, 5.0, 6.0]));
        for (h, want) in [(135.0, 3.0), (180.0, 1.0), (225.0, 3.0), (270.0, 5.0), (315.0, 3.0), (22.5, 2.0)] {
            assert!(close(q.candela(dir_c(45.0, h)), want, 1e-4), "quadrant h {h}");
        }
        assert!(close(q.candela(dir_c(90.0, 202.5)), 3.0, 1e-4));
        // Bilateral symmetry about the 0–180° plane.
        let b = parse(&file(1.0, 1, &v, &[0.0, 60.0, 180.0], &[9.0, 1.0, 1.0, 9.0, 2.0, 2.0, 9.0, 3.0, 3.0]));
        for (h, want) in [(300.0, 2.0), (180.0, 3.0), (240.0, 2.5)] {
            assert!(close(b.candela(dir_c(90.0, h)), want, 1e-4), "bilateral h {h}");
        }
        // Symmetry about the 90–270° plane.
        let m = parse(&file(1.0, 1, &v, &[90.0, 150.0, 270.0], &[9.0, 1.0, 1.0, 9.0, 2.0, 2.0, 9.0, 3.0, 3.0]));
        for (h, want) in [(30.0, 2.0), (0.0, 2.25), (330.0, 2.5), (150.0, 2.0)] {
            assert!(close(m.candela(dir_c(90.0, h)), want, 1e-4), "90-270 h {h}");
        }
        // Rotational symmetry: one horizontal angle.
        let r = parse(&file(1.0, 1, &v, &[0.0], &[10.0, 20.0, 30.0]));
        for h in [0.0, 77.0, 200.0, 359.0] {
            assert!(close(r.candela(dir_c(45.0, h)), 20.0, 1e-4));
        }
        // Symmetric and expanded files agree on the flux.
        let full: Vec<f32> = (0..8).flat_map(|_| [9.0, 4.0, 1.0]).collect();
        let h8: Vec<f32> = (0..=8).map(|k| k as f32 * 45.0).collect();
        let full = parse(&file(1.0, 1, &v, &h8, &[full.clone(), vec![9.0, 4.0, 1.0]].concat()));
        let quad = parse(&file(1.0, 1, &v, &[0.0, 45.0, 90.0], &[9.0, 4.0, 1.0, 9.0, 4.0, 1.0, 9.0, 4.0, 1.0]));
        assert!(close(full.flux(), quad.flux(), 1e-5));
    }

    #[test]
    fn multipliers_and_wrapped_number_lists_are_read() {
        let text = "IESNA91\nTILT=INCLUDE\n1\n3\n0 45\n90 1.0 0.9,\n0.8\n\
                    1 1000 2.0\n3 1 1 1 0 0 0\n0.5 1 100\n0\n90\n180\n0\n10 20\n30\n";
        let (p, w) = Profile::parse(text, false).unwrap();
        // Candela multiplier 2 × ballast factor 0.5: the table as written.
        assert!(close(p.candela(Vec3A::NEG_Z), 10.0, 1e-5));
        assert!(close(p.candela(Vec3A::X), 20.0, 1e-5));
        assert!(close(p.candela(Vec3A::Z), 30.0, 1e-5));
        assert!(w.iter().any(|w| w.contains("TILT=INCLUDE")), "{w:?}");
        // 1986 files have no version line; TILT= names a file.
        let (_, w) = Profile::parse("old lamp\nTILT=lamp.tlt\n1 1 1 2 1 1 1 0 0 0 1 1 1 0 180 0 5 5", false).unwrap();
        assert!(w.iter().any(|w| w.contains("lamp.tlt")));
    }

    #[test]
    fn type_b_turns_about_the_lateral_axis() {
        // Constant 7 cd over V −90..90, H 0..90 (mirrored): the front hemisphere, 2π · 7 lm.
        let v = [-90.0, 0.0, 90.0];
        let p = parse(&file(1.0, 2, &v, &[0.0, 90.0], &[7.0; 6]));
        assert_eq!(p.photometry(), Photometry::B);
        assert!(close(p.flux(), 2.0 * PI * 7.0, 1e-5), "flux {}", p.flux());
        assert_eq!(p.candela(Vec3A::Z), 0.0);
        // H grows towards +X: 1 at H 0, 3 at H ±90 (symmetric), 2 at H 45.
        let p = parse(&file(1.0, 2, &v, &[0.0, 90.0], &[1.0, 1.0, 1.0, 3.0, 3.0, 3.0]));
        assert!(close(p.candela(Vec3A::NEG_Z), 1.0, 1e-5));
        assert!(close(p.candela(Vec3A::new(1.0, 0.0, -1.0)), 2.0, 1e-4));
        assert!(close(p.candela(Vec3A::new(-1.0, 0.0, -1.0)), 2.0, 1e-4));
    }

    #[test]
    fn malformed_files_fail_with_a_message() {
        let good = file(1.0, 1, &V, &H, &[1.0; 20]);
        assert!(Profile::parse(&good, false).is_ok());
        let cases = [
            ("", "TILT"),
            ("TILT=NONE\n1 1 1 4 5 1 2 0 0 0 1 1 1 0 30 60 90 0 90 180 270 360 1 2 3", "ends early"),
            ("TILT=NONE\n1 1 1 1000000000 1000000000 1 2 0 0 0 1 1 1", "whole number"),
            ("TILT=NONE\n1 1 1 4000 4000 1 2 0 0 0 1 1 1", "more than"),
            ("TILT=NONE\n1 1 NaN 2 1 1 2 0 0 0 1 1 1 0 180 0 1 1", "not a number"),
            ("TILT=NONE\n1 1 1 2 1 1 2 0 0 0 1 1 1 0 180 0 1 inf", "not a number"),
            ("TILT=NONE\n1 1 1 2 1 7 2 0 0 0 1 1 1 0 180 0 1 1", "photometric type"),
            ("TILT=NONE\n1 1 1 2 1 1 2 0 0 0 1 1 1 90 10 0 1 1", "increase"),
            ("TILT=NONE\n1 1 1 2 1 1 2 0 0 0 1 1 1 0 200 0 1 1", "outside"),
            ("TILT=NONE\n1 1 1 2 2 1 2 0 0 0 1 1 1 0 180 0 45 1 1 1 1", "not a range"),
            ("TILT=NONE\n1 1 -1 2 1 1 2 0 0 0 1 1 1 0 180 0 1 1", "negative"),
            ("TILT=INCLUDE\n1 99999 1 2", "tilt"),
        ];
        for (text, needle) in cases {
            let e = Profile::parse(text, false).unwrap_err();
            assert!(e.contains(needle), "{text:?}: {e}");
        }
        // Every truncation of a good file fails or parses cleanly, never panics.
        for n in 0..good.len() {
            let _ = Profile::parse(&good[..n], false);
        }
        // Scrambled bytes (a fixed pseudo-random sequence) never panic either.
        let mut x: u32 = 12345;
        for _ in 0..2000 {
            let mut b = good.clone().into_bytes();
            for _ in 0..4 {
                x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                let k = (x >> 8) as usize % b.len();
                b[k] = b" -.e0123456789,\nNa"[(x >> 24) as usize % 18];
            }
            let _ = Profile::parse(&String::from_utf8_lossy(&b), false);
        }
        let missing = Profile::load(Path::new("/nonexistent/lamp.ies"), false).unwrap_err();
        assert!(missing.contains("cannot open"));
    }
}
