//! Balls, and the exact area of a convex polygon inside a ball (polygon ∩ disc in its plane).

use glam::Vec3;

/// A solid ball.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// Centre.
    pub center: Vec3,
    /// Radius (≥ 0).
    pub radius: f32,
}

impl Ball {
    /// A ball from centre and radius.
    pub const fn new(center: Vec3, radius: f32) -> Self {
        Ball { center, radius }
    }
}
