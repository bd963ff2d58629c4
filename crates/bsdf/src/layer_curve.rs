//! Reflectance curves of layers: how much of the light a layer takes as a function of the
//! cosine of the angle of incidence, per RGB channel. MDL's `custom_curve_layer` and
//! `directional_factor` (a Schlick-style curve from a normal to a grazing value),
//! `fresnel_layer` (the unpolarised dielectric Fresnel reflectance), `thin_film` over a
//! Fresnel layer (the interference of a film between the air and the layer, per
//! wavelength), the directional albedo of a sheen lobe (what a sheen layer takes from
//! its base), a tabulated curve (`measured_curve_layer`) and a conductor's Fresnel
//! reflectance (`fresnel_factor`). Used by [`crate::lobes::Lobes`] to weigh a layer and its base.

use crate::measured_factor::FactorTable;
use crate::{conductor, dielectric, measured_curve, sheen_albedo, Rgb};

/// A reflectance curve R(cos θ) ∈ [0, 1] per channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CurveKind {
    /// normal + (grazing − normal)(1 − cos θ)^exponent.
    Schlick {
        /// Reflectance at normal incidence.
        normal: Rgb,
        /// Reflectance at grazing incidence.
        grazing: Rgb,
        /// The exponent (MDL's default 5).
        exponent: f32,
    },
    /// The dielectric Fresnel reflectance of relative index `ior` (unpolarised).
    Fresnel {
        /// Index of refraction of the layer relative to the outside.
        ior: f32,
    },
    /// The dielectric Fresnel reflectance of each channel's own relative index
    /// (`color_fresnel_layer`): channel k is the reflectance of index `ior[k]`.
    ColorFresnel {
        /// Index of refraction of the layer relative to the outside, per channel.
        ior: Rgb,
    },
    /// A film of `film_ior` (per channel) and `thickness_nm` nanometres between the outside
    /// (index 1) and a medium of index `ior`: the Airy reflectance of the film, averaged
    /// over three wavelengths in each channel's band.
    ThinFilm {
        /// Index of refraction under the film.
        ior: f32,
        /// Index of refraction of the film, per channel.
        film_ior: Rgb,
        /// Thickness of the film in nanometres.
        thickness_nm: f32,
    },
    /// The directional albedo of a unit-tint sheen lobe of this roughness.
    SheenAlbedo {
        /// The sheen's roughness.
        roughness: f32,
    },
    /// A tabulated curve (`measured_curve_layer`): samples at uniform steps of the angle
    /// from 0 to π/2, linear between them (see [`crate::measured_curve`]).
    Measured(&'static [Rgb]),
    /// A tabulated curve as [`CurveKind::Measured`] whose samples the lobe sum keeps itself
    /// (`len` samples from `start` of its table, [`crate::lobes::LobeSum::add_table`]): the
    /// per-hit curves of `measured_curve_layer`; read with [`CurveKind::eval_in`].
    Tabulated {
        /// The first sample's index in the sum's table.
        start: u8,
        /// How many samples.
        len: u8,
    },
    /// The unpolarised Fresnel reflectance of a conductor of complex index `eta` + i`k`
    /// per channel, relative to the outside (`fresnel_factor`).
    Conductor {
        /// Real part of the index, per channel.
        eta: Rgb,
        /// Extinction coefficient, per channel.
        k: Rgb,
    },
    /// A factor texture (`measured_factor`) read at the angles of the half vector to a
    /// direction and to the normal (see [`crate::measured_factor`]); as a curve of one
    /// cosine (a layer's), the texture at the normal's half vector (v = 0).
    MeasuredFactor(&'static FactorTable),
}

/// Wavelengths (nm) averaged in each of the red, green and blue channels of a thin film.
const BANDS_NM: [[f32; 3]; 3] = [[600.0, 630.0, 660.0], [510.0, 540.0, 570.0], [420.0, 450.0, 480.0]];

impl CurveKind {
    /// R(cos θ), `cos` the cosine of the angle of incidence (its absolute value is used);
    /// a [`CurveKind::Tabulated`] curve reads an empty table here (0): see
    /// [`CurveKind::eval_in`].
    pub fn eval(&self, cos: f32) -> Rgb {
        self.eval_in(cos, &[])
    }

    /// R(cos θ) as [`CurveKind::eval`], a [`CurveKind::Tabulated`] curve reading its samples
    /// from `table` (its lobe sum's; samples past its end read as none).
    pub fn eval_in(&self, cos: f32, table: &[Rgb]) -> Rgb {
        let c = cos.abs().min(1.0);
        match *self {
            CurveKind::Schlick { normal, grazing, exponent } => {
                let t = (1.0 - c).max(0.0).powf(exponent.max(0.0));
                (normal + (grazing - normal) * t).clamp(Rgb::ZERO, Rgb::ONE)
            }
            CurveKind::Fresnel { ior } => Rgb::splat(dielectric::fresnel(c, ior)),
            CurveKind::ColorFresnel { ior } => {
                Rgb::new(dielectric::fresnel(c, ior.x), dielectric::fresnel(c, ior.y), dielectric::fresnel(c, ior.z))
            }
            CurveKind::ThinFilm { ior, film_ior, thickness_nm } => {
                let film = film_ior.to_array();
                let mut out = [0.0f32; 3];
                for (k, band) in BANDS_NM.iter().enumerate() {
                    out[k] =
                        band.iter().map(|&l| airy_reflectance(c, film[k], ior, thickness_nm, l)).sum::<f32>() / 3.0;
                }
                Rgb::from_array(out)
            }
            CurveKind::SheenAlbedo { roughness } => Rgb::splat(sheen_albedo::albedo(c, roughness)),
            CurveKind::Measured(values) => measured_curve::eval(values, c),
            CurveKind::Tabulated { start, len } => {
                let (start, end) = (usize::from(start), usize::from(start) + usize::from(len));
                measured_curve::eval(table.get(start..end).unwrap_or(&[]), c)
            }
            CurveKind::Conductor { eta, k } => conductor::fresnel_conductor_rgb(c, eta, k),
            CurveKind::MeasuredFactor(table) => table.eval(c, 1.0),
        }
    }

    /// The curve as a directional factor at a half vector h: `cos_kh` the cosine of the
    /// angle between a direction and h, `cos_nh` that of the angle between the normal and
    /// h. Every curve but a factor texture depends on `cos_kh` alone.
    pub fn factor(&self, cos_kh: f32, cos_nh: f32) -> Rgb {
        self.factor_in(cos_kh, cos_nh, &[])
    }

    /// The factor as [`CurveKind::factor`], a [`CurveKind::Tabulated`] curve reading its
    /// samples from `table` (its lobe sum's).
    pub fn factor_in(&self, cos_kh: f32, cos_nh: f32, table: &[Rgb]) -> Rgb {
        match *self {
            CurveKind::MeasuredFactor(factors) => factors.eval(cos_kh, cos_nh),
            _ => self.eval_in(cos_kh, table),
        }
    }

    /// The cosine-weighted hemispherical mean 2 ∫₀¹ R(μ) μ dμ (Schlick: exact; the others
    /// by a 64-point midpoint rule).
    pub fn mean(&self) -> Rgb {
        self.mean_in(&[])
    }

    /// The mean as [`CurveKind::mean`], a [`CurveKind::Tabulated`] curve reading `table`.
    pub fn mean_in(&self, table: &[Rgb]) -> Rgb {
        match *self {
            CurveKind::Schlick { normal, grazing, exponent } => {
                let e = exponent.max(0.0);
                let t = 2.0 / ((e + 1.0) * (e + 2.0));
                (normal + (grazing - normal) * t).clamp(Rgb::ZERO, Rgb::ONE)
            }
            _ => {
                const N: usize = 64;
                let mut sum = Rgb::ZERO;
                for i in 0..N {
                    let mu = (i as f32 + 0.5) / N as f32;
                    sum += self.eval_in(mu, table) * mu;
                }
                sum * (2.0 / N as f32)
            }
        }
    }
}

/// The reflectance of a dielectric film of index `n1` and thickness `d_nm` between air
/// (index 1) and a medium of index `n2`, at wavelength `lambda_nm` and incidence cosine
/// `cos0`: the Airy sum of the film's multiple reflections, s and p averaged. Total
/// internal reflection at the film's lower face reflects everything.
pub fn airy_reflectance(cos0: f32, n1: f32, n2: f32, d_nm: f32, lambda_nm: f32) -> f32 {
    let (n0, n1, n2) = (1.0f64, f64::from(n1.max(1e-3)), f64::from(n2.max(1e-3)));
    let c0 = f64::from(cos0.clamp(0.0, 1.0));
    let s0_sq = 1.0 - c0 * c0;
    let s1_sq = s0_sq * (n0 / n1).powi(2);
    let s2_sq = s0_sq * (n0 / n2).powi(2);
    if s1_sq >= 1.0 || s2_sq >= 1.0 {
        return 1.0;
    }
    let (c1, c2) = ((1.0 - s1_sq).sqrt(), (1.0 - s2_sq).sqrt());
    let rs = |na: f64, ca: f64, nb: f64, cb: f64| (na * ca - nb * cb) / (na * ca + nb * cb);
    let rp = |na: f64, ca: f64, nb: f64, cb: f64| (nb * ca - na * cb) / (nb * ca + na * cb);
    let delta = 4.0 * std::f64::consts::PI * n1 * f64::from(d_nm.max(0.0)) * c1 / f64::from(lambda_nm);
    let cos_d = delta.cos();
    let airy = |a: f64, b: f64| {
        let num = a * a + b * b + 2.0 * a * b * cos_d;
        let den = 1.0 + a * a * b * b + 2.0 * a * b * cos_d;
        num / den
    };
    let r_s = airy(rs(n0, c0, n1, c1), rs(n1, c1, n2, c2));
    let r_p = airy(rp(n0, c0, n1, c1), rp(n1, c1, n2, c2));
    (0.5 * (r_s + r_p)).clamp(0.0, 1.0) as f32
}

/// A layer's curve and weight as [`crate::lobes::Lobes`] applies them: the layer's lobes
/// are scaled by `weight · min(R(cos θo), R(cos θi))` (for a sheen, by nothing: its lobe
/// has its albedo), its base's by `(1 − weight·R(cos θo)) (1 − weight·R(cos θi)) ·
/// compensation`. Both factors are symmetric in the two directions (reciprocal); the
/// layer's share at ωo is at most weight·R(cos θo), what the base loses (energy ≤ 1).
/// `compensation` is 1 / (1 − weight·R̄) (R̄ the hemispherical mean) when the base is
/// Lambertian, which makes a white Lambertian base under any curve lossless, else 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayerCurve {
    /// The curve.
    pub kind: CurveKind,
    /// The layer's weight per channel, in [0, 1].
    pub weight: Rgb,
    /// The base's normalization (see above).
    pub compensation: Rgb,
}

impl LayerCurve {
    /// A curve of `weight` (clamped to [0, 1]); `lambertian_base` asks for the
    /// compensation that makes a Lambertian base lossless.
    pub fn new(kind: CurveKind, weight: Rgb, lambertian_base: bool) -> LayerCurve {
        LayerCurve::new_in(kind, weight, lambertian_base, &[])
    }

    /// A curve as [`LayerCurve::new`], a [`CurveKind::Tabulated`] one reading `table` (the
    /// table of the lobe sum it is added to).
    pub fn new_in(kind: CurveKind, weight: Rgb, lambertian_base: bool, table: &[Rgb]) -> LayerCurve {
        let weight = weight.clamp(Rgb::ZERO, Rgb::ONE);
        let compensation = if lambertian_base {
            let left = Rgb::ONE - weight * kind.mean_in(table);
            Rgb::new(inv_or_one(left.x), inv_or_one(left.y), inv_or_one(left.z))
        } else {
            Rgb::ONE
        };
        LayerCurve { kind, weight, compensation }
    }

    /// The layer's factor for directions of cosines `co`, `ci`.
    pub fn over(&self, co: f32, ci: f32) -> Rgb {
        self.over_in(co, ci, &[])
    }

    /// The layer's factor as [`LayerCurve::over`], a tabulated curve reading `table`.
    pub fn over_in(&self, co: f32, ci: f32, table: &[Rgb]) -> Rgb {
        if matches!(self.kind, CurveKind::SheenAlbedo { .. }) {
            return Rgb::ONE;
        }
        self.weight * self.kind.eval_in(co, table).min(self.kind.eval_in(ci, table))
    }

    /// The base's factor for directions of cosines `co`, `ci`.
    pub fn under(&self, co: f32, ci: f32) -> Rgb {
        self.under_in(co, ci, &[])
    }

    /// The base's factor as [`LayerCurve::under`], a tabulated curve reading `table`.
    pub fn under_in(&self, co: f32, ci: f32, table: &[Rgb]) -> Rgb {
        (Rgb::ONE - self.weight * self.kind.eval_in(co, table))
            * (Rgb::ONE - self.weight * self.kind.eval_in(ci, table))
            * self.compensation
    }
}

fn inv_or_one(x: f32) -> f32 {
    if x > 1e-4 {
        1.0 / x
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A film of no thickness is the bare interface: the Airy sum reduces to the Fresnel
    /// reflectance of the medium under it (within 1e-5 at every angle).
    #[test]
    fn a_film_of_zero_thickness_is_the_bare_interface() {
        for i in 0..=20 {
            let c = i as f32 / 20.0;
            let r = airy_reflectance(c, 1.33, 1.5, 0.0, 550.0);
            let f = dielectric::fresnel(c, 1.5);
            assert!((r - f).abs() < 1e-5, "cos {c}: film {r}, Fresnel {f}");
        }
    }

    /// A quarter-wave film of index √n₂ on a medium of index n₂ cancels the reflection at
    /// normal incidence (an anti-reflection coating): R < 1e-6 at its design wavelength;
    /// a half-wave film reflects like the bare interface.
    #[test]
    fn a_quarter_wave_film_cancels_reflection_and_a_half_wave_one_is_absent() {
        let n2: f32 = 1.69;
        let n1 = n2.sqrt();
        let lambda = 550.0;
        let quarter = lambda / (4.0 * n1);
        assert!(airy_reflectance(1.0, n1, n2, quarter, lambda) < 1e-6);
        let half = airy_reflectance(1.0, n1, n2, 2.0 * quarter, lambda);
        assert!((half - dielectric::fresnel(1.0, n2)).abs() < 1e-5, "{half}");
        // Normal incidence of the bare interface: ((n − 1)/(n + 1))².
        let f0 = ((n2 - 1.0) / (n2 + 1.0)).powi(2);
        assert!((half - f0).abs() < 1e-5);
    }

    /// A curve kept in a wide sum's own table reads as the interned curve of the same
    /// samples (values and mean equal exactly); a table takes at most its `WIDE_TABLE`
    /// samples in all, and a compact sum none.
    #[test]
    fn a_tabulated_curve_reads_as_the_measured_one() {
        use crate::lobes::{Lobes, WideLobes, WIDE_TABLE};
        let v = [Rgb::new(0.1, 0.2, 0.3), Rgb::new(0.5, 0.2, 0.9), Rgb::new(1.0, 0.0, 0.6)];
        let mut sum = WideLobes::default();
        assert!(sum.add_table(&[Rgb::splat(0.7)]).is_some());
        let kind = sum.add_table(&v).unwrap();
        assert_eq!(kind, CurveKind::Tabulated { start: 1, len: 3 });
        let measured = CurveKind::Measured(measured_curve::intern(&v));
        for i in 0..=16 {
            let c = i as f32 / 16.0;
            assert_eq!(kind.eval_in(c, sum.table()), measured.eval(c), "cos {c}");
        }
        assert_eq!(kind.mean_in(sum.table()), measured.mean());
        assert_eq!(sum.add_table(&[Rgb::ONE; WIDE_TABLE - 3]), None, "one sample too many");
        assert!(sum.add_table(&[Rgb::ONE; WIDE_TABLE - 4]).is_some());
        assert_eq!(Lobes::default().add_table(&v), None);
    }

    /// The Schlick curve's mean is exact: compared with a 4000-point midpoint rule (1e-4).
    #[test]
    fn the_schlick_mean_is_the_integral() {
        let kind =
            CurveKind::Schlick { normal: Rgb::new(0.04, 0.2, 0.5), grazing: Rgb::new(1.0, 0.8, 0.5), exponent: 3.0 };
        let n = 4000;
        let mut sum = Rgb::ZERO;
        for i in 0..n {
            let mu = (i as f32 + 0.5) / n as f32;
            sum += kind.eval(mu) * mu;
        }
        let numeric = sum * (2.0 / n as f32);
        assert!((numeric - kind.mean()).abs().max_element() < 1e-4, "{numeric:?} vs {:?}", kind.mean());
    }
}
