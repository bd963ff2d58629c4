//! Factor textures of MDL's `measured_factor`: an RGB table of `width × height` texels
//! (row 0 at the bottom, v = 0) read at u = θ′·2/π, v = θ″·2/π, θ′ the angle between a
//! direction and the half vector, θ″ the angle between the normal and the half vector
//! (the MDL SDK's coordinates), bilinearly between texel centres ((i + ½)/width), clamped
//! at the edges, each channel at least 0 (MDL allows factors above 1: the material's
//! author keeps the energy). Tables are interned ([`intern`]) so that layer curves holding
//! one stay `Copy`.

use std::sync::Mutex;

use crate::Rgb;

/// A factor texture: `width × height` RGB texels, row-major from the bottom row.
#[derive(Debug, PartialEq)]
pub struct FactorTable {
    /// Texels along u (the angle to the half vector).
    pub width: usize,
    /// Texels along v (the angle of the half vector to the normal).
    pub height: usize,
    /// `values[y * width + x]`, y from the bottom.
    pub values: Vec<Rgb>,
}

/// Every distinct table interned so far (kept for the life of the process).
static TABLES: Mutex<Vec<&'static FactorTable>> = Mutex::new(Vec::new());

/// The interned copy of a `width × height` table (`values` row-major from the bottom):
/// an equal table interned before, or a new one. `None` when the sizes do not match the
/// values or are zero.
pub fn intern(width: usize, height: usize, values: &[Rgb]) -> Option<&'static FactorTable> {
    if width == 0 || height == 0 || width.checked_mul(height) != Some(values.len()) {
        return None;
    }
    let table = FactorTable { width, height, values: values.to_vec() };
    let mut tables = TABLES.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(t) = tables.iter().find(|t| ***t == table) {
        return Some(t);
    }
    let table: &'static FactorTable = Box::leak(Box::new(table));
    tables.push(table);
    Some(table)
}

impl FactorTable {
    /// The factor for the cosine `cos_kh` of the angle between a direction and the half
    /// vector and the cosine `cos_nh` of the angle between the normal and the half vector
    /// (absolute values used).
    pub fn eval(&self, cos_kh: f32, cos_nh: f32) -> Rgb {
        let angle = |c: f32| c.abs().min(1.0).acos() * std::f32::consts::FRAC_2_PI;
        let (u, v) = (angle(cos_kh), angle(cos_nh));
        let axis = |t: f32, n: usize| {
            let at = (t * n as f32 - 0.5).clamp(0.0, (n - 1) as f32);
            let i = (at as usize).min(n - 1);
            (i, (i + 1).min(n - 1), at - i as f32)
        };
        let (x0, x1, tx) = axis(u, self.width);
        let (y0, y1, ty) = axis(v, self.height);
        let at = |x: usize, y: usize| self.values[y * self.width + x];
        let bottom = at(x0, y0) * (1.0 - tx) + at(x1, y0) * tx;
        let top = at(x0, y1) * (1.0 - tx) + at(x1, y1) * tx;
        (bottom * (1.0 - ty) + top * ty).max(Rgb::ZERO)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Texel centres read their texel, the point between four centres their mean, the
    /// edges clamp (1e-6); mismatched sizes are refused.
    #[test]
    fn a_table_is_read_bilinearly_between_texel_centres() {
        let v = [Rgb::new(0.1, 0.2, 0.3), Rgb::new(0.5, 0.2, 0.9), Rgb::new(1.0, 0.0, 0.6), Rgb::new(0.3, 0.3, 0.3)];
        let t = intern(2, 2, &v).unwrap();
        // u = ¼ ⇔ θ′ = 22.5°, u = ¾ ⇔ 67.5°; u = ½ ⇔ 45°.
        let cos = |deg: f32| deg.to_radians().cos();
        let cases = [
            (22.5, 22.5, v[0]),
            (67.5, 22.5, v[1]),
            (22.5, 67.5, v[2]),
            (67.5, 67.5, v[3]),
            (0.0, 90.0, v[2]),
            (45.0, 45.0, (v[0] + v[1] + v[2] + v[3]) / 4.0),
            (45.0, 0.0, (v[0] + v[1]) / 2.0),
        ];
        for (a, b, want) in cases {
            let got = t.eval(cos(a), cos(b));
            assert!((got - want).abs().max_element() < 1e-6, "{a}°, {b}°: {got:?} vs {want:?}");
        }
        assert!(intern(2, 2, &v[..3]).is_none() && intern(0, 0, &[]).is_none());
        assert!(std::ptr::eq(t, intern(2, 2, &v).unwrap()));
    }
}
