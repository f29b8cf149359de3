//! Sutherland–Hodgman clipping of a convex polygon against an axis-aligned box, into a
//! caller-owned scratch buffer so that the hot path allocates nothing once warm.

use crate::Aabb;
use glam::Vec3;

/// Reusable buffers for clipping; keep one per thread.
#[derive(Clone, Debug, Default)]
pub struct ClipScratch {
    a: Vec<Vec3>,
    b: Vec<Vec3>,
}

impl ClipScratch {
    /// Empty scratch; grows on first use.
    pub fn new() -> Self {
        Self::default()
    }
}

/// Clips the convex `polygon` to the closed `aabb` and returns the clipped polygon, which
/// borrows `scratch`. Degenerate results (fewer than 3 vertices) are empty.
pub fn clip_polygon_to_aabb<'s>(polygon: &[Vec3], aabb: &Aabb, scratch: &'s mut ClipScratch) -> &'s [Vec3] {
    let _ = (polygon, aabb, &mut scratch.b);
    todo!("pm-geom issue")
}
