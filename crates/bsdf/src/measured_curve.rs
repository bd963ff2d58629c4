//! Tabulated reflectance curves (MDL's `measured_curve_layer` and its colour form): colour
//! values sampled at uniform steps of the angle of incidence θ from 0 (normal incidence) to
//! π/2 (grazing), read between the samples by linear interpolation in θ, each channel
//! clamped to [0, 1]. Constant tables are interned ([`intern`]): a layer curve holds a
//! `'static` slice, so that the lobe sums that weigh lobes by it stay `Copy` and of fixed
//! size; tables that vary per hit are kept in the lobe sum's own table instead
//! ([`crate::layer_curve::CurveKind::Tabulated`], [`crate::lobes::LobeSum::add_table`]).

use std::sync::Mutex;

use crate::Rgb;

/// Every distinct table interned so far (kept for the life of the process: one per
/// distinct curve a scene's materials use).
static TABLES: Mutex<Vec<&'static [Rgb]>> = Mutex::new(Vec::new());

/// The interned copy of `values`: an equal table interned before, or a new one.
pub fn intern(values: &[Rgb]) -> &'static [Rgb] {
    let mut tables = TABLES.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(t) = tables.iter().find(|t| **t == values) {
        return t;
    }
    let table: &'static [Rgb] = Box::leak(values.to_vec().into_boxed_slice());
    tables.push(table);
    table
}

/// The curve `values` at the cosine `cos` of the angle of incidence (its absolute value is
/// used): θ = acos |cos| mapped onto the samples, the two nearest interpolated linearly,
/// clamped to [0, 1]; an empty table is 0.
pub fn eval(values: &[Rgb], cos: f32) -> Rgb {
    let Some(last) = values.len().checked_sub(1) else { return Rgb::ZERO };
    let theta = cos.abs().min(1.0).acos();
    let at = (theta * std::f32::consts::FRAC_2_PI * last as f32).clamp(0.0, last as f32);
    let i = (at as usize).min(last);
    let j = (i + 1).min(last);
    let t = at - i as f32;
    (values[i] * (1.0 - t) + values[j] * t).clamp(Rgb::ZERO, Rgb::ONE)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The samples are the curve at their angles, the midpoints the mean of their
    /// neighbours (1e-6); a table of one value is constant and an empty one 0.
    #[test]
    fn a_table_is_read_at_its_angles_and_linearly_between_them() {
        let v = [Rgb::new(0.1, 0.2, 0.3), Rgb::new(0.5, 0.2, 0.9), Rgb::new(1.0, 0.0, 0.6)];
        let cos = |deg: f32| deg.to_radians().cos();
        for (deg, want) in [(0.0, v[0]), (45.0, v[1]), (90.0, v[2]), (22.5, (v[0] + v[1]) / 2.0)] {
            let got = eval(&v, cos(deg));
            assert!((got - want).abs().max_element() < 1e-6, "{deg}°: {got:?} vs {want:?}");
        }
        assert_eq!(eval(&v[..1], 0.3), v[0]);
        assert_eq!(eval(&[], 0.3), Rgb::ZERO);
    }

    /// Equal tables intern to one slice; different ones do not.
    #[test]
    fn equal_tables_are_interned_once() {
        let a = intern(&[Rgb::splat(0.25), Rgb::splat(0.75)]);
        let b = intern(&[Rgb::splat(0.25), Rgb::splat(0.75)]);
        let c = intern(&[Rgb::splat(0.25), Rgb::splat(0.5)]);
        assert!(std::ptr::eq(a, b) && !std::ptr::eq(a, c));
    }
}
