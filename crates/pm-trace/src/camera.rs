//! The pinhole camera: position, look-at point, up vector and vertical field of view.

use crate::ray::Ray;
use glam::Vec3;

/// A pinhole camera. Image coordinates `(u, v) ∈ [0,1]²` run left to right and top to bottom.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    position: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    tan_half_fov: f32,
    /// The vertical field of view asked for, radians (checked by [`Camera::validate`]).
    vfov: f32,
    /// Why the view fell back to its default, for [`Camera::validate`].
    fallback: Option<&'static str>,
}

impl Camera {
    /// A camera at `position` looking at `look_at`, with `up` pointing up in the image and a
    /// vertical field of view of `vfov_radians`. An `up` parallel to the view direction falls
    /// back to +y (or +x); a look-at point equal to the position (or not finite) falls back to
    /// looking along +z, and [`Camera::validate`] (run by the scene builder) refuses it.
    pub fn new(position: Vec3, look_at: Vec3, up: Vec3, vfov_radians: f32) -> Self {
        let view = look_at - position;
        let fallback = if !(position.is_finite() && look_at.is_finite()) {
            Some("position or look-at point is not finite")
        } else if view.try_normalize().is_none() {
            Some("look-at point equals the position (no view direction)")
        } else {
            None
        };
        let forward = view.try_normalize().unwrap_or(Vec3::Z);
        let right = forward
            .cross(up)
            .try_normalize()
            .unwrap_or_else(|| forward.cross(Vec3::Y).try_normalize().unwrap_or(Vec3::X));
        let up = right.cross(forward);
        Camera {
            position,
            forward,
            right,
            up,
            tan_half_fov: (vfov_radians * 0.5).tan(),
            vfov: vfov_radians,
            fallback,
        }
    }

    /// Checks the camera: a finite position, a view direction (look-at point not the
    /// position) and a vertical field of view in (0, π) radians. The reason names the culprit.
    pub fn validate(&self) -> Result<(), String> {
        if let Some(reason) = self.fallback {
            return Err(reason.to_owned());
        }
        if !self.position.is_finite() {
            return Err(format!("position {} is not finite", self.position));
        }
        // Checked on the angle itself: tan(fov/2) of 2π comes out a tiny positive number.
        let in_range = self.vfov > 0.0 && self.vfov < std::f32::consts::PI;
        if !(in_range && self.tan_half_fov.is_finite() && self.tan_half_fov > 0.0) {
            let fov = self.vfov;
            return Err(format!("vertical field of view {fov} rad is not in (0, π)"));
        }
        if !(self.tan_half_fov.is_finite() && self.tan_half_fov > 0.0) {
            let fov = 2.0 * self.tan_half_fov.atan();
            return Err(format!(
                "vertical field of view {fov} rad is not in (0, π) (got tan(fov/2) = {})",
                self.tan_half_fov
            ));
        }
        Ok(())
    }

    /// How far from the centre of a box of `size` a camera looking along ±z must stand so
    /// that the box's near face fits a vertical field of view of `vfov_radians` (for square
    /// images), with a 10 % margin. Shared by the scene builder's default camera and glTF's
    /// framing camera.
    pub fn framing_distance(size: Vec3, vfov_radians: f32) -> f32 {
        let back = 0.5 * size.x.max(size.y) / (vfov_radians * 0.5).tan() + 0.5 * size.z;
        back * 1.1
    }

    /// Position of the pinhole.
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// Unit viewing direction (the image centre).
    pub fn forward(&self) -> Vec3 {
        self.forward
    }

    /// Unit up direction of the image (made orthogonal to [`Camera::forward`]).
    pub fn up(&self) -> Vec3 {
        self.up
    }

    /// The vertical field of view asked for, radians.
    pub fn vfov(&self) -> f32 {
        self.vfov
    }

    /// The angle (radians, small-angle) a pixel spans at the image centre for an image
    /// `height` pixels tall: how fast a camera ray's footprint grows with distance.
    pub fn pixel_angle(&self, height: u32) -> f32 {
        2.0 * self.tan_half_fov / height.max(1) as f32
    }

    /// The primary ray through image point `(u, v)` for an image of width/height `aspect`.
    pub fn ray(&self, u: f32, v: f32, aspect: f32) -> Ray {
        let x = (2.0 * u - 1.0) * self.tan_half_fov * aspect;
        let y = (1.0 - 2.0 * v) * self.tan_half_fov;
        Ray {
            origin: self.position,
            direction: (self.forward + self.right * x + self.up * y).normalize(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_ray_looks_at_target_and_top_edge_is_half_fov_up() {
        let fov = 40f32.to_radians();
        let cam = Camera::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(1.0, 2.0, 10.0), Vec3::Y, fov);
        let c = cam.ray(0.5, 0.5, 1.5);
        assert!((c.direction - Vec3::Z).length() < 1e-6);
        let top = cam.ray(0.5, 0.0, 1.5);
        assert!(top.direction.y > 0.0);
        assert!((top.direction.angle_between(Vec3::Z) - fov / 2.0).abs() < 1e-5);
        // Right-handed, +y up, looking along +z: image right is -x.
        assert!(cam.ray(1.0, 0.5, 1.0).direction.x < 0.0);
    }

    #[test]
    fn a_box_framed_at_the_framing_distance_fits_the_view_with_margin() {
        for (size, fov) in [
            (Vec3::new(2.0, 1.0, 0.5), 60f32),
            (Vec3::new(0.5, 3.0, 4.0), 40.0),
            (Vec3::splat(1.0), 90.0),
        ] {
            let fov = fov.to_radians();
            let d = Camera::framing_distance(size, fov);
            // Seen from the camera, the near face's edges sit at these angles off the axis.
            let near = d - 0.5 * size.z;
            let widest = (0.5 * size.x.max(size.y) / near).atan();
            assert!(widest < 0.5 * fov, "{size} at {fov}: {widest} > half fov");
            // …and the margin is about 10 %, not more.
            assert!(
                widest > 0.4 * fov,
                "{size} at {fov}: framed too loosely ({widest})"
            );
        }
    }
}
