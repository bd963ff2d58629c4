//! The mental ray camera as a ray generator.
//!
//! Raster coordinates here have their origin at the top-left corner of the image, y down,
//! pixel (i, j) covering `[i, i+1) × [j, j+1)`; mental ray's raster space has y up, so
//! `raster_y_mr = height − y`. A camera-space point (x, y, z) projects to
//! `raster_x = x/(−z) · focal·w/aperture + w/2 − offset_x` and
//! `raster_y_mr = y/(−z) · focal·aspect·h/aperture + h/2 − offset_y`; orthographic cameras
//! drop the division by −z.

use glam::{Affine3A, Vec3A};

use crate::ray::Ray;

/// The camera in the form the renderer needs.
#[derive(Clone, Debug)]
pub struct CameraModel {
    /// Image size in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Camera → world.
    pub camera_to_world: Affine3A,
    /// World → camera.
    pub world_to_camera: Affine3A,
    /// Focal distance (1 for orthographic cameras).
    pub focal: f32,
    /// Image plane width.
    pub aperture: f32,
    /// Image plane width / height.
    pub aspect: f32,
    /// Orthographic projection.
    pub orthographic: bool,
    /// Offset in pixels.
    pub offset: (f32, f32),
    /// Near and far clip distances along −Z.
    pub clip: (f32, f32),
    /// Pixel rectangle to render, top-left origin: x0, y0 inclusive, x1, y1 exclusive.
    pub window: (u32, u32, u32, u32),
    /// Camera → world at shutter times spread evenly over the shutter (see
    /// [`crate::motion`]), when the camera moves while it is open; empty: it stays at
    /// `camera_to_world`.
    pub keys: Vec<Affine3A>,
}

impl CameraModel {
    /// From the scene's camera.
    pub fn new(c: &scene::Camera) -> CameraModel {
        let (w, h) = c.resolution;
        let window = match c.window {
            Some([xl, yl, xh, yh]) => {
                // mental ray's window is in its lower-left raster space, xh/yh inclusive.
                let cl = |v: i64, max: u32| v.clamp(0, i64::from(max)) as u32;
                let (x0, x1) = (cl(xl, w), cl(xh + 1, w));
                let (y0, y1) = (cl(i64::from(h) - (yh + 1), h), cl(i64::from(h) - yl, h));
                (x0.min(x1), y0.min(y1), x1.max(x0), y1.max(y0))
            }
            None => (0, 0, w, h),
        };
        CameraModel {
            width: w,
            height: h,
            camera_to_world: Affine3A::from_mat4(c.camera_to_world.as_mat4()),
            world_to_camera: Affine3A::from_mat4(c.world_to_camera.as_mat4()),
            focal: c.focal.unwrap_or(1.0) as f32,
            aperture: c.aperture as f32,
            aspect: c.aspect as f32,
            orthographic: c.focal.is_none(),
            offset: (c.offset.0 as f32, c.offset.1 as f32),
            clip: (c.clip.0.max(0.0) as f32, c.clip.1 as f32),
            window,
            keys: Vec::new(),
        }
    }

    /// Sets a new resolution, keeping the field of view (and scaling the offset).
    pub fn resize(&mut self, width: u32, height: u32) {
        let (sx, sy) = (width as f32 / self.width as f32, height as f32 / self.height as f32);
        self.offset = (self.offset.0 * sx, self.offset.1 * sy);
        let (x0, y0, x1, y1) = self.window;
        self.window = (
            (x0 as f32 * sx) as u32,
            (y0 as f32 * sy) as u32,
            ((x1 as f32 * sx).ceil() as u32).min(width),
            ((y1 as f32 * sy).ceil() as u32).min(height),
        );
        self.width = width;
        self.height = height;
    }

    /// The primary ray through raster position (x, y), top-left origin; the direction has
    /// unit length and the range is limited by the clip planes.
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        self.ray_at(x, y, 0.0)
    }

    /// Camera → world at shutter time `time`.
    #[inline]
    pub fn camera_to_world_at(&self, time: f32) -> Affine3A {
        if self.keys.is_empty() {
            self.camera_to_world
        } else {
            crate::motion::lerp_keys(&self.keys, time)
        }
    }

    /// [`CameraModel::ray`] from where the camera is at shutter time `time` (the ray
    /// carries the time).
    pub fn ray_at(&self, x: f32, y: f32, time: f32) -> Ray {
        self.raster_rays().ray_at(x, y, time)
    }

    /// The constants of [`CameraModel::ray_at`] that do not depend on the raster position,
    /// computed once for the many rays of a band of pixels.
    #[inline]
    pub fn raster_rays(&self) -> RasterRays<'_> {
        let (w, h) = (self.width as f32, self.height as f32);
        RasterRays {
            camera: self,
            half_width: w * 0.5,
            height: h,
            half_height: h * 0.5,
            sx: self.aperture / (self.focal * w),
            sy: self.aperture / (self.focal * self.aspect * h),
        }
    }

    /// A ray from `origin` along unit `dir` (world space) limited by the clip planes, which
    /// are distances along −Z in camera space (for lens shaders that bend eye rays).
    pub fn clip_ray(&self, origin: Vec3A, dir: Vec3A) -> Ray {
        let cos = -self.world_to_camera.transform_vector3a(dir).z;
        let (tmin, tmax) = if cos > 0.0 { (self.clip.0 / cos, self.clip.1 / cos) } else { (0.0, f32::INFINITY) };
        Ray { mask: crate::ray::mask::CAMERA, origin, dir, tmin, tmax, time: 0.0 }
    }

    /// The angle one pixel subtends at the centre of the image (radians; 0 for orthographic
    /// cameras, whose rays do not spread).
    pub fn pixel_angle(&self) -> f32 {
        if self.orthographic {
            0.0
        } else {
            self.aperture / (self.focal * self.width.max(1) as f32)
        }
    }

    /// The width of a pixel's footprint at the camera (scene units; orthographic cameras).
    pub fn pixel_width(&self) -> f32 {
        if self.orthographic {
            self.aperture / self.width.max(1) as f32
        } else {
            0.0
        }
    }

    /// The width of a pixel's footprint at world point `p` seen from the camera (scene
    /// units): the pixel width at the camera plus the pixel angle times the distance
    /// from the camera's origin (pbrt-v4's camera-ray approximation of ray differentials,
    /// used by the path engine at every bounce).
    pub fn footprint_at(&self, p: Vec3A) -> f32 {
        let origin = self.camera_to_world.translation;
        self.pixel_width() + self.pixel_angle() * (p - origin).length()
    }

    /// Depth (−z in camera space) of a world point: what the `z` frame buffer stores.
    pub fn depth(&self, p: Vec3A) -> f32 {
        -self.world_to_camera.transform_point3a(p).z
    }
}

/// A camera's primary rays with the per-image constants of [`CameraModel::ray_at`] worked
/// out ([`CameraModel::raster_rays`]): the same rays bit for bit, a division pair less each.
#[derive(Clone, Copy, Debug)]
pub struct RasterRays<'a> {
    camera: &'a CameraModel,
    /// Half the image width, pixels.
    half_width: f32,
    /// The image height, pixels.
    height: f32,
    /// Half the image height, pixels.
    half_height: f32,
    /// Image-plane units (at focal distance 1) per pixel, horizontally.
    sx: f32,
    /// The same vertically.
    sy: f32,
}

impl RasterRays<'_> {
    /// [`CameraModel::ray_at`]: the primary ray through raster position (x, y), top-left
    /// origin, at shutter time `time`.
    #[inline]
    pub fn ray_at(&self, x: f32, y: f32, time: f32) -> Ray {
        let c = self.camera;
        let rx = x - self.half_width + c.offset.0;
        let ry = (self.height - y) - self.half_height + c.offset.1;
        let (sx, sy) = (self.sx, self.sy);
        let (origin_cam, dir_cam) = if c.orthographic {
            (Vec3A::new(rx * sx, ry * sy, 0.0), Vec3A::NEG_Z)
        } else {
            (Vec3A::ZERO, Vec3A::new(rx * sx, ry * sy, -1.0).normalize())
        };
        let camera_to_world = c.camera_to_world_at(time);
        let origin = camera_to_world.transform_point3a(origin_cam);
        let dir = camera_to_world.transform_vector3a(dir_cam);
        let len = dir.length();
        // Clip distances are along −Z; along the ray they grow by 1/cos.
        let cos = -dir_cam.z;
        Ray {
            mask: crate::ray::mask::CAMERA,
            origin,
            dir: dir / len,
            tmin: c.clip.0 / cos * len,
            tmax: c.clip.1 / cos * len,
            time,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam(offset: (f32, f32)) -> CameraModel {
        CameraModel {
            width: 200,
            height: 100,
            camera_to_world: Affine3A::IDENTITY,
            world_to_camera: Affine3A::IDENTITY,
            focal: 1.0,
            aperture: 2.0,
            aspect: 2.0,
            orthographic: false,
            offset,
            clip: (0.0, f32::INFINITY),
            window: (0, 0, 200, 100),
            keys: Vec::new(),
        }
    }

    /// [`RasterRays::ray_at`] gives, bit for bit, the rays of `ray_at`'s formula written out
    /// whole (the per-image constants recomputed for every ray), for a perspective and an
    /// orthographic camera with an offset and clip planes, across the image.
    #[test]
    fn raster_rays_equal_the_formula() {
        let turned = Affine3A::from_rotation_translation(
            glam::Quat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 0.2),
            glam::Vec3::new(1.0, -2.0, 5.0),
        );
        for orthographic in [false, true] {
            let mut c = cam((3.5, -2.25));
            c.camera_to_world = turned;
            c.clip = (0.1, 1000.0);
            c.focal = 1.7;
            c.orthographic = orthographic;
            let rays = c.raster_rays();
            for (x, y) in [(0.0, 0.0), (17.3, 91.25), (199.99, 99.99), (100.0, 50.0), (3.0, 77.7)] {
                let (w, h) = (c.width as f32, c.height as f32);
                let (rx, ry) = (x - w * 0.5 + c.offset.0, (h - y) - h * 0.5 + c.offset.1);
                let sx = c.aperture / (c.focal * w);
                let sy = c.aperture / (c.focal * c.aspect * h);
                let (o, d) = if orthographic {
                    (Vec3A::new(rx * sx, ry * sy, 0.0), Vec3A::NEG_Z)
                } else {
                    (Vec3A::ZERO, Vec3A::new(rx * sx, ry * sy, -1.0).normalize())
                };
                let (origin, dir) = (turned.transform_point3a(o), turned.transform_vector3a(d));
                let len = dir.length();
                let want = (origin, dir / len, c.clip.0 / -d.z * len, c.clip.1 / -d.z * len);
                for r in [rays.ray_at(x, y, 0.0), c.ray_at(x, y, 0.0)] {
                    assert_eq!(r.origin.to_array().map(f32::to_bits), want.0.to_array().map(f32::to_bits));
                    assert_eq!(r.dir.to_array().map(f32::to_bits), want.1.to_array().map(f32::to_bits));
                    assert_eq!((r.tmin.to_bits(), r.tmax.to_bits()), (want.2.to_bits(), want.3.to_bits()));
                }
            }
        }
    }

    #[test]
    fn centre_and_corners() {
        let c = cam((0.0, 0.0));
        let r = c.ray(100.0, 50.0);
        assert!((r.dir - Vec3A::NEG_Z).length() < 1e-6);
        // Top-left corner: x = −aperture/2, y = +aperture/(2·aspect).
        let r = c.ray(0.0, 0.0);
        let expect = Vec3A::new(-1.0, 0.5, -1.0).normalize();
        assert!((r.dir - expect).length() < 1e-6, "{}", r.dir);
    }

    #[test]
    fn positive_offset_moves_the_picture_left() {
        // A point seen at the centre without offset appears 10 pixels to the left with
        // offset_x = 10: the pixel 10 to the left now looks straight ahead.
        let c = cam((10.0, 0.0));
        let r = c.ray(90.0, 50.0);
        assert!((r.dir - Vec3A::NEG_Z).length() < 1e-6, "{}", r.dir);
    }
}
