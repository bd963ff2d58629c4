//! MDL's `texture_cube` resources: six square faces read from a DDS cube map, an image of
//! a horizontal or vertical cross ([`CubeMap::from_cross`]) or six face images
//! ([`CubeMap::from_faces`]), looked up by direction (`tex::lookup_*(texture_cube, float3)`).
//!
//! Faces and orientation follow the cube-map convention of DirectX and OpenGL, which DDS
//! files store and the MDL SDK's texture runtime looks up: the direction's component of
//! largest magnitude picks the face (+x, −x, +y, −y, +z, −z, the file's order), and the
//! other two components divided by its magnitude m give the face coordinates
//! s = (sc/m + 1)/2 (0 at the face's left column) and t = (tc/m + 1)/2 (0 at its first,
//! top row) with (sc, tc) = (−z, −y) on +x, (z, −y) on −x, (x, z) on +y, (x, −z) on −y,
//! (x, −y) on +z, (−x, −y) on −z. Within a face values are interpolated bilinearly between
//! texel centres, clamped at the face's edges (no filtering across faces). The direction
//! need not be unit; the zero vector gives black.

use glam::{Vec3A, Vec4};

/// The six faces of a `texture_cube`.
#[derive(Clone, Debug, PartialEq)]
pub struct CubeMap {
    /// Texels on a face's side.
    pub size: usize,
    /// RGBA texels per face (+x, −x, +y, −y, +z, −z), rows top to bottom.
    faces: Vec<Vec<Vec4>>,
}

impl CubeMap {
    /// A cube map of six `size` × `size` faces, each's texels rows top to bottom; `None`
    /// when the counts do not match.
    pub fn new(size: usize, faces: Vec<Vec<Vec4>>) -> Option<CubeMap> {
        (size > 0 && faces.len() == 6 && faces.iter().all(|f| f.len() == size * size))
            .then_some(CubeMap { size, faces })
    }

    /// A cube map from an image of a cross, `None` unless the image is 4n × 3n or 3n × 4n
    /// texels (n ≥ 1):
    ///
    /// - a horizontal cross (4n × 3n): the middle row −x, +z, +x, −z from the left, +y
    ///   above +z and −y below it, each face as the convention orients it (the cross folds
    ///   into the cube without turning a face);
    /// - a vertical cross (3n × 4n): +y on top, the middle row −x, +z, +x from the left,
    ///   −y below +z and −z below −y, each face as the convention orients it except −z,
    ///   which is stored turned by 180° (as the cross folds: its top row in the picture
    ///   is the convention's bottom row, towards −y, and its left column the convention's
    ///   right one, towards −x), the common vertical-cross layout.
    pub fn from_cross(image: &shader::texture::MipMap) -> Option<CubeMap> {
        let (w, h) = image.size();
        // (column, row from the top) of each face's cell, +x, −x, +y, −y, +z, −z, and
        // whether −z is stored turned by 180°.
        let (n, cells, turned) = if w % 4 == 0 && h * 4 == w * 3 {
            (w / 4, [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (3, 1)], false)
        } else if w % 3 == 0 && h * 3 == w * 4 {
            (w / 3, [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (1, 3)], true)
        } else {
            return None;
        };
        if n == 0 {
            return None;
        }
        let faces = cells
            .iter()
            .enumerate()
            .map(|(face, &(cx, cy))| {
                let mut texels = Vec::with_capacity(n * n);
                for row in 0..n {
                    let row = if turned && face == 5 { n - 1 - row } else { row };
                    // The pyramid's rows count from the bottom of the picture.
                    let y = h - 1 - (cy * n + row);
                    texels.extend((0..n).map(|col| {
                        let col = if turned && face == 5 { n - 1 - col } else { col };
                        rgba(image, cx * n + col, y)
                    }));
                }
                texels
            })
            .collect();
        CubeMap::new(n, faces)
    }

    /// A cube map from six images of the same square size, +x, −x, +y, −y, +z, −z, each
    /// as the convention orients its face (first row the face's top, t = 0); `None` when
    /// they are not six, not square or not all the same size.
    pub fn from_faces(images: &[&shader::texture::MipMap]) -> Option<CubeMap> {
        let n = images.first()?.size().0;
        if images.len() != 6 || images.iter().any(|i| i.size() != (n, n)) {
            return None;
        }
        let faces = images
            .iter()
            .map(|image| (0..n).flat_map(|row| (0..n).map(move |col| rgba(image, col, n - 1 - row))).collect())
            .collect();
        CubeMap::new(n, faces)
    }

    /// The face a direction points at (0 to 5: +x, −x, +y, −y, +z, −z) and its face
    /// coordinates (s, t) in [0, 1]; `None` for the zero vector (or not a number).
    pub fn face_coordinates(dir: Vec3A) -> Option<(usize, f32, f32)> {
        let a = dir.abs();
        let (face, m, sc, tc) = if a.x >= a.y && a.x >= a.z {
            if dir.x >= 0.0 {
                (0, a.x, -dir.z, -dir.y)
            } else {
                (1, a.x, dir.z, -dir.y)
            }
        } else if a.y >= a.z {
            if dir.y >= 0.0 {
                (2, a.y, dir.x, dir.z)
            } else {
                (3, a.y, dir.x, -dir.z)
            }
        } else if dir.z >= 0.0 {
            (4, a.z, dir.x, -dir.y)
        } else {
            (5, a.z, -dir.x, -dir.y)
        };
        (m > 0.0 && m.is_finite()).then(|| (face, 0.5 * (sc / m + 1.0), 0.5 * (tc / m + 1.0)))
    }

    /// The value towards `dir` (any length; black for the zero vector).
    pub fn lookup(&self, dir: Vec3A) -> Vec4 {
        let Some((face, s, t)) = CubeMap::face_coordinates(dir) else { return Vec4::ZERO };
        let texels = &self.faces[face];
        let n = self.size;
        let last = n as i64 - 1;
        let (x, y) = (s * n as f32 - 0.5, t * n as f32 - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let texel =
            |i: f32, j: f32| texels[(j as i64).clamp(0, last) as usize * n + (i as i64).clamp(0, last) as usize];
        let top = texel(x0, y0) * (1.0 - fx) + texel(x0 + 1.0, y0) * fx;
        let bottom = texel(x0, y0 + 1.0) * (1.0 - fx) + texel(x0 + 1.0, y0 + 1.0) * fx;
        top * (1.0 - fy) + bottom * fy
    }
}

/// Texel (x, y) of `image` (y from the bottom) as RGBA: grey (and alpha) spread to RGB.
fn rgba(image: &shader::texture::MipMap, x: usize, y: usize) -> Vec4 {
    let c = image.texel(x, y);
    if image.channels < 3 {
        Vec4::new(c.x, c.x, c.x, if image.channels == 2 { c.y } else { 1.0 })
    } else {
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The face coordinates invert the convention's face directions: the centre of each
    /// face's top-left texel region maps back to its face and corner.
    #[test]
    fn face_coordinates_follow_the_cube_map_convention() {
        // (face, direction towards the face's top-left corner, slightly inside).
        let corners = [
            (0, Vec3A::new(1.0, 0.9, 0.9)),
            (1, Vec3A::new(-1.0, 0.9, -0.9)),
            (2, Vec3A::new(-0.9, 1.0, -0.9)),
            (3, Vec3A::new(-0.9, -1.0, 0.9)),
            (4, Vec3A::new(-0.9, 0.9, 1.0)),
            (5, Vec3A::new(0.9, 0.9, -1.0)),
        ];
        for (face, dir) in corners {
            let (f, s, t) = CubeMap::face_coordinates(dir).unwrap();
            assert_eq!(f, face);
            assert!((s - 0.05).abs() < 1e-6 && (t - 0.05).abs() < 1e-6, "face {face}: {s} {t}");
        }
        assert_eq!(CubeMap::face_coordinates(Vec3A::ZERO), None);
    }
}
