//! Oriented planes `n·x = d`, used for clipping and for distances to a polygon's plane.

use glam::Vec3;

/// The plane of points `x` with `normal · x = offset`; `normal` is unit length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Unit normal; the positive side is where `signed_distance > 0`.
    pub normal: Vec3,
    /// `normal · x` for any point `x` on the plane.
    pub offset: f32,
}

impl Plane {
    /// The plane through `point` with unit `normal`.
    pub fn from_point_normal(point: Vec3, normal: Vec3) -> Self {
        Plane {
            normal,
            offset: normal.dot(point),
        }
    }

    /// Signed distance of `p` from the plane (positive on the normal's side).
    pub fn signed_distance(&self, p: Vec3) -> f32 {
        self.normal.dot(p) - self.offset
    }

    /// The orthogonal projection of `p` onto the plane.
    pub fn project(&self, p: Vec3) -> Vec3 {
        p - self.normal * self.signed_distance(p)
    }
}
