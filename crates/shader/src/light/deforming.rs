//! Object-light triangles that change shape while the shutter is open: an emitting
//! object whose vertices carry motion vectors, or several instances of one emitting
//! object that move differently. They cannot be carried by one displacement
//! ([`super::MeshShape::displaced`]); instead their world-space vertices are kept at
//! keys over the shutter and the triangles are rebuilt at each ray's time.

use glam::Vec3A;

use super::MeshShape;

/// An object light's world-space triangles at keys spread evenly over shutter times
/// 0…1 (the same vertex order, counter-clockwise seen from the emitting side, at every
/// key), linear between keys, as the renderer moves the emitting geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct DeformingMesh {
    /// `keys[j][i]`: triangle `i` at shutter time `j / (keys.len() − 1)`.
    keys: Vec<Vec<[Vec3A; 3]>>,
}

impl DeformingMesh {
    /// Triangles at `keys` spread evenly over the shutter (at least two keys, every key
    /// with the same number of triangles); `None` otherwise.
    pub fn new(keys: Vec<Vec<[Vec3A; 3]>>) -> Option<DeformingMesh> {
        let count = keys.first()?.len();
        (keys.len() >= 2 && count > 0 && keys.iter().all(|k| k.len() == count)).then_some(DeformingMesh { keys })
    }

    /// Number of keys.
    pub fn key_count(&self) -> usize {
        self.keys.len()
    }

    /// The triangles at key `j` (shutter time `j / (key_count − 1)`), world space.
    pub fn key(&self, j: usize) -> &[[Vec3A; 3]] {
        &self.keys[j]
    }

    /// The triangles at shutter time `s` (0 at the opening, 1 at the closing; clamped),
    /// interpolated linearly between the two keys around it and sampled uniformly by
    /// their area there. `None` when none of them has area at that time.
    pub fn at(&self, s: f32) -> Option<MeshShape> {
        let segments = self.keys.len() - 1;
        let x = (if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) }) * segments as f32;
        let j = (x as usize).min(segments - 1);
        let f = x - j as f32;
        let (a, b) = (&self.keys[j], &self.keys[j + 1]);
        MeshShape::new(a.iter().zip(b).map(|(a, b)| [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * f)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangles_between_keys_are_interpolated() {
        // A right triangle of area 1/2 sliding 2 in x while growing to twice its size.
        let small = vec![[Vec3A::ZERO, Vec3A::X, Vec3A::Y]];
        let big = vec![[Vec3A::new(2.0, 0.0, 0.0), Vec3A::new(4.0, 0.0, 0.0), Vec3A::new(2.0, 2.0, 0.0)]];
        let m = DeformingMesh::new(vec![small, big]).expect("two keys");
        let half = m.at(0.5).expect("triangles");
        // At s = 1/2: corner (1, 0), legs 1.5: area 1.125.
        assert!((half.area() - 1.125).abs() < 1e-6, "{}", half.area());
        let hit = half.intersect(Vec3A::new(1.2, 0.2, 1.0), -Vec3A::Z, 0.0, 10.0);
        assert_eq!(hit.map(|(t, front)| ((t - 1.0).abs() < 1e-6, front)), Some((true, true)));
        assert!(half.intersect(Vec3A::new(0.8, 0.2, 1.0), -Vec3A::Z, 0.0, 10.0).is_none());
        // Clamped outside the shutter; NaN is the opening.
        assert!((m.at(7.0).expect("triangles").area() - 2.0).abs() < 1e-6);
        assert!((m.at(f32::NAN).expect("triangles").area() - 0.5).abs() < 1e-6);
        assert!(DeformingMesh::new(vec![vec![[Vec3A::ZERO; 3]]]).is_none());
    }
}
